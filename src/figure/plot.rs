//! Charts: BRDF lobes in polar form and curves (albedo, cost), as PNG and SVG.
//!
//! Drawn with plotters on the embedded DejaVu Sans, so the bytes do not depend on the
//! fonts installed on the machine. plotters' bitmap backend draws lines without
//! anti-aliasing (stair-stepped curves); the PNG is therefore drawn at [`SUPERSAMPLE`]×
//! the size, every length scaled with it, and box-filtered down.

use super::chart_text::Localized;
use crate::lesson::i18n::Lang;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;
use std::sync::Once;

/// One curve: a label and its points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Points in chart coordinates.
    pub points: Vec<(f64, f64)>,
}

/// A chart drawn twice: a bitmap and an SVG document.
#[derive(Debug, Clone)]
pub struct Chart {
    /// RGB pixels.
    pub png: image::RgbImage,
    /// The same chart as SVG.
    pub svg: String,
}

/// Line colours, distinguishable in print and for common colour-vision deficiencies (Okabe & Ito 2008).
const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// Bitmap charts are drawn this many times larger in each direction, then averaged down.
pub const SUPERSAMPLE: u32 = 3;

/// The family name charts draw with: the embedded DejaVu Sans, registered once.
pub(crate) fn font() -> &'static str {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The bytes are the embedded font; registering cannot fail for them. (plotters has no
        // font registry on wasm32, where the live lab draws no charts.)
        #[cfg(not(target_arch = "wasm32"))]
        let _ = plotters::style::register_font("shadelab", FontStyle::Normal, super::text::font_bytes());
    });
    "shadelab"
}

/// A straight segment between two chart points.
type Segment = ((f64, f64), (f64, f64));

/// What a chart shows, independent of the backend.
struct Spec<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    x: (f64, f64),
    y: (f64, f64),
    series: &'a [Series],
    /// Extra straight segments (e.g. the incident direction and the normal), drawn grey.
    guides: &'a [Segment],
    note: Option<&'a str>,
}

/// The area above the note line (if any), with the note drawn; `k` scales every length.
pub(super) fn with_note<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    note: Option<&str>,
    k: u32,
) -> Result<DrawingArea<DB, Shift>, String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    Ok(match note {
        Some(note) => {
            let (top, bottom) = root.split_vertically(root.dim_in_pixel().1.saturating_sub(28 * k));
            let style = (font(), 14 * k).into_font().color(&RGBColor(80, 80, 80));
            bottom.draw_text(note, &style, (16 * k as i32, 6 * k as i32)).map_err(err)?;
            top
        }
        None => root,
    })
}

/// A line chart or polar lobe; `k` scales every length (fonts, strokes, margins).
fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, s: &Spec, k: u32) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let area = with_note(root, s.note, k)?;
    let mut chart = ChartBuilder::on(&area)
        .caption(s.title, (font(), 22 * k))
        .margin(14 * k)
        .x_label_area_size(40 * k)
        .y_label_area_size(56 * k)
        .build_cartesian_2d(s.x.0..s.x.1, s.y.0..s.y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(s.x_label)
        .y_desc(s.y_label)
        .x_label_formatter(&|v| format_number(*v))
        .y_label_formatter(&|v| format_number(*v))
        .label_style((font(), 13 * k))
        .axis_desc_style((font(), 15 * k))
        .light_line_style(RGBColor(235, 235, 235).stroke_width(k))
        .bold_line_style(RGBColor(200, 200, 200).stroke_width(k))
        .axis_style(RGBColor(0, 0, 0).stroke_width(k))
        .set_all_tick_mark_size(5 * k)
        .draw()
        .map_err(err)?;
    for (a, b) in s.guides {
        chart.draw_series(LineSeries::new([*a, *b], RGBColor(150, 150, 150).stroke_width(k))).map_err(err)?;
    }
    for (i, series) in s.series.iter().enumerate() {
        let c = PALETTE[i % PALETTE.len()];
        let legend = 18 * k as i32;
        chart
            .draw_series(LineSeries::new(series.points.iter().copied(), c.stroke_width(2 * k)))
            .map_err(err)?
            .label(super::chart_text::legend_label(&series.label))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + legend, y)], c.stroke_width(2 * k)));
    }
    if s.series.len() > 1 || s.series.first().is_some_and(|x| !x.label.is_empty()) {
        legend(&mut chart, k, legend_corner(s))?;
    }
    area.present().map_err(err)
}

/// The corner whose legend-sized box the curves cross least (upper right on a tie, then upper
/// left, lower right, lower left), so the legend hides as little of them as it can.
fn legend_corner(s: &Spec) -> SeriesLabelPosition {
    // The box a legend of this many rows takes, as a share of the axes (about 40% wide, a
    // row ≈ 6% high at the chart sizes drawn here).
    let (w, h) = (0.42, 0.06 * s.series.len() as f64 + 0.04);
    let ((x0, x1), (y0, y1)) = (s.x, s.y);
    let unit = |p: (f64, f64)| ((p.0 - x0) / (x1 - x0), (p.1 - y0) / (y1 - y0));
    let corners = [
        (SeriesLabelPosition::UpperRight, (1.0 - w, 1.0), (1.0 - h, 1.0)),
        (SeriesLabelPosition::UpperLeft, (0.0, w), (1.0 - h, 1.0)),
        (SeriesLabelPosition::LowerRight, (1.0 - w, 1.0), (0.0, h)),
        (SeriesLabelPosition::LowerLeft, (0.0, w), (0.0, h)),
    ];
    let crossings = |(bx, by): ((f64, f64), (f64, f64))| -> usize {
        let inside = |(u, v): (f64, f64)| u >= bx.0 && u <= bx.1 && v >= by.0 && v <= by.1;
        // Points along every segment, so a long straight stretch through a box counts.
        s.series
            .iter()
            .flat_map(|c| c.points.windows(2))
            .flat_map(|ab| {
                (0..8).map(move |i| {
                    let t = i as f64 / 8.0;
                    (ab[0].0 + t * (ab[1].0 - ab[0].0), ab[0].1 + t * (ab[1].1 - ab[0].1))
                })
            })
            .filter(|&p| inside(unit(p)))
            .count()
    };
    let mut best = (usize::MAX, SeriesLabelPosition::UpperRight);
    for (pos, bx, by) in corners {
        let n = crossings((bx, by));
        if n < best.0 {
            best = (n, pos);
        }
    }
    best.1
}

/// The legend box at `position`, every length scaled by `k`.
pub(super) fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    k: u32,
    position: SeriesLabelPosition,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .label_font((font(), 14 * k))
        .margin(10 * k)
        .legend_area_size(30 * k)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(200, 200, 200).stroke_width(k))
        .position(position)
        .draw()
        .map_err(|e| e.to_string())
}

/// Box-filters an RGB image drawn at `k`× down to `size` (8-bit, sRGB-encoded values averaged).
fn downsample(big: &[u8], big_w: u32, size: (u32, u32), k: u32) -> image::RgbImage {
    let (w, h) = size;
    let big_w = big_w as usize;
    let n = k * k;
    image::RgbImage::from_fn(w, h, |x, y| {
        let mut sum = [0u32; 3];
        for dy in 0..k {
            let row = ((y * k + dy) as usize) * big_w;
            for dx in 0..k {
                let i = 3 * (row + (x * k + dx) as usize);
                for c in 0..3 {
                    sum[c] += big[i + c] as u32;
                }
            }
        }
        image::Rgb(sum.map(|s| ((s + n / 2) / n) as u8))
    })
}

/// Draws a chart twice: on a bitmap [`SUPERSAMPLE`]× larger (then box-filtered down to
/// `size`) and on an SVG document of `size`. The two closures are the same drawing code
/// for the two backends; the `u32` is the length scale.
/// Every string drawn is translated into `lang` on the way ([`Localized`]).
pub(super) fn render_generic(
    size: (u32, u32),
    lang: Lang,
    bitmap: impl FnOnce(DrawingArea<Localized<BitMapBackend>, Shift>, u32) -> Result<(), String>,
    svg: impl FnOnce(DrawingArea<Localized<SVGBackend>, Shift>, u32) -> Result<(), String>,
) -> Result<Chart, String> {
    render_zoomed(size, 1.0, lang, bitmap, svg)
}

/// [`render_generic`] with the bitmap `zoom`× larger, text and strokes included (rounded to
/// thirds: the drawing's length scale is a whole number of supersampled pixels). The SVG
/// keeps `size`: it scales without loss.
fn render_zoomed(
    size: (u32, u32),
    zoom: f32,
    lang: Lang,
    bitmap: impl FnOnce(DrawingArea<Localized<BitMapBackend>, Shift>, u32) -> Result<(), String>,
    svg: impl FnOnce(DrawingArea<Localized<SVGBackend>, Shift>, u32) -> Result<(), String>,
) -> Result<Chart, String> {
    let k = ((SUPERSAMPLE as f32 * zoom).ceil() as u32).clamp(SUPERSAMPLE, 8 * SUPERSAMPLE);
    let big = (size.0 * k, size.1 * k);
    let mut buf = vec![255u8; (big.0 * big.1 * 3) as usize];
    bitmap(Localized::new(BitMapBackend::with_buffer(&mut buf, big), lang, true).into_drawing_area(), k)?;
    let mut doc = String::new();
    svg(Localized::new(SVGBackend::with_string(&mut doc, size), lang, false).into_drawing_area(), 1)?;
    Ok(Chart { png: downsample(&buf, big.0, (big.0 / SUPERSAMPLE, big.1 / SUPERSAMPLE), SUPERSAMPLE), svg: doc })
}

fn render(size: (u32, u32), lang: Lang, s: &Spec) -> Result<Chart, String> {
    render_generic(size, lang, |a, k| draw(a, s, k), |a, k| draw(a, s, k))
}

/// BRDF lobes in the plane of incidence: each series holds points (x, y) = r (sin θ_o, cos θ_o)
/// with r = f·cos θ_o; the light comes from the left, and each incident direction is drawn
/// from the origin at its angle in `incidence_deg`.
///
/// # Errors
/// A message when plotters fails (it does not for in-memory backends in practice).
pub fn polar_lobe(series: &[Series], incidence_deg: &[f64], title: &str, size: (u32, u32), lang: Lang) -> Result<Chart, String> {
    polar_lobe_labelled(series, incidence_deg, title, "f·cos θₒ  (towards the mirror side →)", size, lang)
}

/// [`polar_lobe`] with another name for the radius on the horizontal axis (`I` for the
/// classic models).
///
/// # Errors
/// As [`polar_lobe`].
pub fn polar_lobe_labelled(
    series: &[Series],
    incidence_deg: &[f64],
    title: &str,
    x_label: &str,
    size: (u32, u32),
    lang: Lang,
) -> Result<Chart, String> {
    let r = series.iter().flat_map(|s| s.points.iter()).map(|(x, y)| x.hypot(*y)).fold(0.0f64, f64::max).max(1e-6) * 1.1;
    let mut guides = vec![((0.0, 0.0), (0.0, r)), ((-r, 0.0), (r, 0.0))];
    for i in incidence_deg.iter().map(|d| d.to_radians()) {
        guides.push(((0.0, 0.0), (-r * i.sin(), r * i.cos())));
    }
    let spec = Spec {
        title,
        x_label,
        y_label: "along the normal",
        x: (-r, r),
        y: (0.0, r),
        series,
        guides: &guides,
        note: Some("grey: the surface, the normal, and the direction towards the light"),
    };
    render(size, lang, &spec)
}

/// Spot lights' distributions I(θ) in polar form: each series holds points
/// (x, y) = I(θ) (sin θ, cos θ), the spot's axis drawn upwards.
///
/// # Errors
/// As [`polar_lobe`].
pub fn polar_distribution(series: &[Series], title: &str, size: (u32, u32), lang: Lang) -> Result<Chart, String> {
    let r = series.iter().flat_map(|s| s.points.iter()).map(|(x, y)| x.hypot(*y)).fold(0.0f64, f64::max).max(1e-6) * 1.1;
    let guides = vec![((0.0, 0.0), (0.0, r)), ((-r, 0.0), (r, 0.0))];
    let spec = Spec {
        title,
        x_label: "I(θ) sin θ",
        y_label: "along the spot's axis",
        x: (-r, r),
        y: (0.0, r),
        series,
        guides: &guides,
        note: Some("grey: the spot's axis; θ is measured from it"),
    };
    render(size, lang, &spec)
}

/// A line chart (e.g. albedo against the angle of incidence).
///
/// # Errors
/// As [`polar_lobe`].
#[allow(clippy::too_many_arguments)]
pub fn line_chart(
    series: &[Series],
    title: &str,
    x_label: &str,
    y_label: &str,
    x: (f64, f64),
    y: (f64, f64),
    note: Option<&str>,
    size: (u32, u32),
    lang: Lang,
) -> Result<Chart, String> {
    render(size, lang, &Spec { title, x_label, y_label, x, y, series, guides: &[], note })
}

/// One rung of a cost chart: where it stands in time and error.
#[derive(Debug, Clone, PartialEq)]
pub struct CostPoint {
    /// Label drawn next to the point.
    pub label: String,
    /// Time in ms (> 0).
    pub ms: f64,
    /// Error (≥ 0); zero is drawn on the bottom edge with an open triangle.
    pub error: f64,
    /// On the Pareto front: filled, and joined to the other front points.
    pub pareto: bool,
    /// The series it belongs to (its points are joined and share a colour); empty for one series.
    pub series: String,
}

/// Error against time on log–log axes, one labelled point per rung; the Pareto front
/// (rungs nothing else beats in both time and error) is joined by a line. The bitmap is
/// `zoom`× `size`, its text with it.
///
/// # Errors
/// A message when there is no point with a positive time, or from plotters.
pub fn cost_chart(
    points: &[CostPoint],
    title: &str,
    y_label: &str,
    note: Option<&str>,
    size: (u32, u32),
    zoom: f32,
    lang: Lang,
) -> Result<Chart, String> {
    let times: Vec<f64> = points.iter().map(|p| p.ms).filter(|t| *t > 0.0 && t.is_finite()).collect();
    if times.is_empty() {
        return Err("a cost chart needs at least one rung with a positive time".into());
    }
    let (t0, t1) = (times.iter().copied().fold(f64::INFINITY, f64::min), times.iter().copied().fold(0.0, f64::max));
    let errors: Vec<f64> = points.iter().map(|p| p.error).filter(|e| *e > 0.0 && e.is_finite()).collect();
    let (e0, e1) = match errors.is_empty() {
        true => (1e-4, 1.0),
        false => (errors.iter().copied().fold(f64::INFINITY, f64::min), errors.iter().copied().fold(0.0, f64::max)),
    };
    // Half a decade of room on each side (more across time, for the labels); zero errors sit on the floor.
    let x = (t0 / 2.0, t1 * 3.0);
    let y = (e0 / 4.0, e1 * 2.5);
    let c = CostChart { points, title, y_label, note, x, y };
    render_zoomed(size, zoom, lang, |a, k| c.draw(a, k), |a, k| c.draw(a, k))
}

/// What [`cost_chart`] draws, with its axis ranges decided.
struct CostChart<'a> {
    points: &'a [CostPoint],
    title: &'a str,
    y_label: &'a str,
    note: Option<&'a str>,
    x: (f64, f64),
    y: (f64, f64),
}

impl CostChart<'_> {
    fn at(&self, p: &CostPoint) -> (f64, f64) {
        (p.ms.clamp(self.x.0, self.x.1), if p.error > 0.0 { p.error.clamp(self.y.0, self.y.1) } else { self.y.0 })
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let area = with_note(root, self.note, k)?;
        let mut chart = ChartBuilder::on(&area)
            .caption(self.title, (font(), 22 * k))
            .margin(14 * k)
            .margin_right(40 * k)
            .x_label_area_size(40 * k)
            .y_label_area_size(70 * k)
            .build_cartesian_2d(
                (self.x.0..self.x.1).log_scale().with_key_points(log_ticks(self.x, &[1.0, 2.0, 5.0])),
                (self.y.0..self.y.1).log_scale().with_key_points(log_ticks(self.y, y_mantissas(self.y))),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("median render time (ms, log scale)")
            .y_desc(self.y_label)
            .x_label_formatter(&|v| format_tick(*v))
            .y_label_formatter(&|v| format_error_tick(*v))
            .label_style((font(), 13 * k))
            .axis_desc_style((font(), 15 * k))
            // Log axes put nine light lines in every decade: too busy behind labelled points.
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(200, 200, 200).stroke_width(k))
            .axis_style(RGBColor(0, 0, 0).stroke_width(k))
            .set_all_tick_mark_size(5 * k)
            .draw()
            .map_err(err)?;
        let ink = PALETTE[0];
        let mut front: Vec<&CostPoint> = self.points.iter().filter(|p| p.pareto).collect();
        front.sort_by(|a, b| a.ms.total_cmp(&b.ms));
        chart
            .draw_series(LineSeries::new(front.iter().map(|p| self.at(p)), PALETTE[1].stroke_width(2 * k)))
            .map_err(err)?
            .label("Pareto front: nothing is both faster and more accurate")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18 * k as i32, y)], PALETTE[1].stroke_width(2 * k)));
        // Each named series joined in its own colour, in time order, with its legend entry.
        let mut names: Vec<&str> = Vec::new();
        for p in self.points {
            if !p.series.is_empty() && !names.contains(&p.series.as_str()) {
                names.push(&p.series);
            }
        }
        let colour = |series: &str| names.iter().position(|n| *n == series).map_or(ink, |i| PALETTE[(i + 2) % PALETTE.len()]);
        for name in &names {
            let mut pts: Vec<&CostPoint> = self.points.iter().filter(|p| p.series == *name).collect();
            pts.sort_by(|a, b| a.ms.total_cmp(&b.ms));
            let c = colour(name);
            chart
                .draw_series(LineSeries::new(pts.iter().map(|p| self.at(p)), c.stroke_width(k)))
                .map_err(err)?
                .label(name.to_string())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18 * k as i32, y)], c.stroke_width(2 * k)));
        }
        let r = 5 * k;
        // Label boxes placed so far (pixels): a label that would overprint one moves down a line
        // (two rungs at one point, as `sh` and `prefiltered` on gold, read as a short list).
        let mut placed: Vec<(i32, i32, i32, i32)> = Vec::new();
        let line = 18 * k as i32;
        for p in self.points {
            let at = self.at(p);
            let ink = colour(&p.series);
            let style = if p.pareto { ink.filled() } else { ink.stroke_width(2 * k) };
            let label_style = (font(), 14 * k).into_font().color(&RGBColor(30, 30, 30));
            let text = if p.error > 0.0 { p.label.clone() } else { format!("{} (error 0)", p.label) };
            if p.error > 0.0 {
                chart.draw_series(std::iter::once(EmptyElement::at(at) + Circle::new((0, 0), r, style))).map_err(err)?;
            } else {
                let r = r as i32;
                let up = Polygon::new(vec![(-r, 0), (r, 0), (0, -2 * r)], style);
                chart.draw_series(std::iter::once(EmptyElement::at(at) + up)).map_err(err)?;
            }
            let (px, py) = chart.backend_coord(&at);
            let width = (text.chars().count() as f64 * 0.6 * 14.0 * k as f64) as i32;
            let (x0, mut y0) = (px + 8 * k as i32, py - line);
            while placed.iter().any(|&(a, b, c, d)| x0 < c && a < x0 + width && y0 < d && b < y0 + line) {
                y0 += line;
            }
            placed.push((x0, y0, x0 + width, y0 + line));
            let label = EmptyElement::at(at) + Text::new(text, (x0 - px, y0 - py), label_style);
            chart.draw_series(std::iter::once(label)).map_err(err)?;
        }
        // The front runs from upper left to lower right: the upper right stays clear.
        legend(&mut chart, k, SeriesLabelPosition::UpperRight)?;
        area.present().map_err(err)
    }
}

/// Residual against iteration for iterative solvers: a linear iteration axis, a log residual
/// axis, one line with a dot per iteration for each series (points (k, r_k)), and the
/// stopping tolerance as a grey line. Residuals of 0 are drawn on the bottom edge.
///
/// # Errors
/// A message when no series has a point, or from plotters.
pub fn convergence_chart(
    series: &[Series],
    tolerance: f64,
    title: &str,
    note: Option<&str>,
    size: (u32, u32),
    lang: Lang,
) -> Result<Chart, String> {
    let points: Vec<(f64, f64)> = series.iter().flat_map(|s| s.points.iter().copied()).collect();
    if points.is_empty() {
        return Err("a convergence chart needs at least one residual".into());
    }
    let last = points.iter().map(|p| p.0).fold(1.0, f64::max);
    let positive = || points.iter().map(|p| p.1).chain([tolerance]).filter(|r| *r > 0.0 && r.is_finite());
    let lo = positive().fold(f64::INFINITY, f64::min);
    let hi = positive().fold(0.0, f64::max);
    let (lo, hi) = if lo.is_finite() && hi > 0.0 { (lo / 3.0, hi * 3.0) } else { (1e-6, 1.0) };
    let c = ConvergenceChart { series, tolerance, title, note, x: (0.0, last), y: (lo, hi) };
    render_generic(size, lang, |a, k| c.draw(a, k), |a, k| c.draw(a, k))
}

/// What [`convergence_chart`] draws, with its axis ranges decided.
struct ConvergenceChart<'a> {
    series: &'a [Series],
    tolerance: f64,
    title: &'a str,
    note: Option<&'a str>,
    x: (f64, f64),
    y: (f64, f64),
}

impl ConvergenceChart<'_> {
    /// A point on the axes: zero (or non-finite) residuals sit on the floor.
    fn at(&self, (k, r): (f64, f64)) -> (f64, f64) {
        (k, if r > 0.0 && r.is_finite() { r.clamp(self.y.0, self.y.1) } else { self.y.0 })
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let area = with_note(root, self.note, k)?;
        let mut chart = ChartBuilder::on(&area)
            .caption(self.title, (font(), 22 * k))
            .margin(14 * k)
            .margin_right(30 * k)
            .x_label_area_size(40 * k)
            .y_label_area_size(70 * k)
            .build_cartesian_2d(
                self.x.0..self.x.1,
                (self.y.0..self.y.1).log_scale().with_key_points(log_ticks(self.y, y_mantissas(self.y))),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("iteration")
            .y_desc("relative residual (log scale)")
            .x_label_formatter(&|v| format_number(*v))
            .y_label_formatter(&|v| format_error_tick(*v))
            .label_style((font(), 13 * k))
            .axis_desc_style((font(), 15 * k))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(200, 200, 200).stroke_width(k))
            .axis_style(RGBColor(0, 0, 0).stroke_width(k))
            .set_all_tick_mark_size(5 * k)
            .draw()
            .map_err(err)?;
        if self.tolerance > 0.0 {
            let grey = RGBColor(120, 120, 120);
            let line = [(self.x.0, self.tolerance), (self.x.1, self.tolerance)].map(|p| self.at(p));
            let legend = 18 * k as i32;
            chart
                .draw_series(DashedLineSeries::new(line, 8 * k, 5 * k, grey.stroke_width(k)))
                .map_err(err)?
                .label(format!("tolerance {}", format_error_tick(self.tolerance)))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + legend, y)], grey.stroke_width(k)));
        }
        for (i, s) in self.series.iter().enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            let legend = 18 * k as i32;
            let pts: Vec<(f64, f64)> = s.points.iter().map(|&p| self.at(p)).collect();
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(2 * k)))
                .map_err(err)?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + legend, y)], c.stroke_width(2 * k)));
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3 * k, c.filled()))).map_err(err)?;
        }
        // Residuals fall from the upper left: the upper right stays clear.
        legend(&mut chart, k, SeriesLabelPosition::UpperRight)?;
        area.present().map_err(err)
    }
}

/// A linear-axis tick: at most six decimals, trailing zeros dropped (`10`, `0.15`, `-0.2`).
pub(super) fn format_number(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// An error tick label: `1e-3`, `2e-3`, `5e-2`.
fn format_error_tick(v: f64) -> String {
    format!("{v:.0e}")
}

/// Ticks m·10^k inside `range` for each mantissa m (e.g. 1, 2, 5), ascending.
pub(super) fn log_ticks(range: (f64, f64), mantissas: &[f64]) -> Vec<f64> {
    let (lo, hi) = range;
    if !(lo > 0.0 && hi > lo && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let mut out = Vec::new();
    for k in lo.log10().floor() as i32..=hi.log10().ceil() as i32 {
        for m in mantissas {
            let t = m * 10f64.powi(k);
            if t >= lo && t <= hi {
                out.push(t);
            }
        }
    }
    out
}

/// Error ticks: every decade when the range spans many, 1-2-5 within few.
fn y_mantissas(range: (f64, f64)) -> &'static [f64] {
    if (range.1 / range.0).log10() > 4.0 { &[1.0] } else { &[1.0, 2.0, 5.0] }
}

/// A time tick label: `0.5`, `2`, `40`, `1200`.
fn format_tick(v: f64) -> String {
    if v >= 10.0 {
        format!("{v:.0}")
    } else if v >= 1.0 {
        format!("{v:.1}").trim_end_matches(".0").to_string()
    } else {
        format!("{v:.2}").trim_end_matches('0').to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_legend_goes_to_the_corner_the_curves_leave_free() {
        let spec = |series: &[Series]| -> SeriesLabelPosition {
            let s = Spec { title: "", x_label: "", y_label: "", x: (0.0, 90.0), y: (0.0, 1.1), series, guides: &[], note: None };
            legend_corner(&s)
        };
        let line = |a: (f64, f64), b: (f64, f64)| Series { label: "c".into(), points: vec![a, b] };
        // Empty upper right: it is kept.
        assert!(matches!(spec(&[line((0.0, 0.1), (90.0, 0.2))]), SeriesLabelPosition::UpperRight));
        // Curves along the top and one rising at the left: the lower right is free.
        let curves = [line((0.0, 1.0), (90.0, 1.0)), line((0.0, 0.0), (30.0, 0.9)), line((0.0, 0.3), (90.0, 0.6))];
        assert!(matches!(spec(&curves), SeriesLabelPosition::LowerRight));
        // Falling curves that end low on the right: the lower left is free.
        let falling = [line((0.0, 1.0), (90.0, 0.0)), line((0.0, 1.0), (90.0, 1.0)), line((0.0, 0.6), (90.0, 0.1))];
        assert!(matches!(spec(&falling), SeriesLabelPosition::LowerLeft));
    }

    #[test]
    fn lobe_chart_draws_and_is_deterministic() {
        let pts: Vec<(f64, f64)> = (0..=90).map(|d| (d as f64).to_radians()).map(|t| (t.sin() * t.cos(), t.cos() * t.cos())).collect();
        let s = [Series { label: "test".into(), points: pts }];
        let a = polar_lobe(&s, &[30.0], "lobe", (400, 300), Lang::En).unwrap();
        let b = polar_lobe(&s, &[30.0], "lobe", (400, 300), Lang::En).unwrap();
        assert_eq!(a.png.as_raw(), b.png.as_raw());
        assert!(a.svg.contains("<svg") && a.svg.contains("lobe"));
        // Something coloured (the curve) was drawn.
        assert!(a.png.pixels().any(|p| p[2] > 150 && p[0] < 60));
        // Supersampled: the curve's edges are blended, not stair-stepped (grey levels between).
        assert!(a.png.pixels().any(|p| p[2] > 200 && p[0] > 100 && p[0] < 200));
    }

    #[test]
    fn convergence_chart_draws_each_solver_and_puts_zero_residuals_on_the_floor() {
        let s =
            |label: &str, r: &[f64]| Series { label: label.into(), points: r.iter().enumerate().map(|(k, &r)| (k as f64, r)).collect() };
        let series = [s("jacobi", &[1.0, 0.3, 0.1, 0.03]), s("gauss_seidel", &[1.0, 0.1, 0.0])];
        let chart = convergence_chart(&series, 0.05, "convergence", None, (600, 400), Lang::En).unwrap();
        assert!(chart.svg.contains("jacobi") && chart.svg.contains("gauss_seidel") && chart.svg.contains("tolerance 5e-2"));
        // The first two palette colours (blue, vermilion) are drawn.
        assert!(chart.png.pixels().any(|q| q[2] > 150 && q[0] < 60), "blue series");
        assert!(chart.png.pixels().any(|q| q[0] > 180 && q[1] < 130 && q[2] < 60), "vermilion series");
        let c = ConvergenceChart { series: &series, tolerance: 0.05, title: "", note: None, x: (0.0, 3.0), y: (0.01, 3.0) };
        assert_eq!(c.at((2.0, 0.0)), (2.0, 0.01));
        assert_eq!(c.at((1.0, 0.1)), (1.0, 0.1));
        assert!(convergence_chart(&[], 0.1, "t", None, (300, 200), Lang::En).is_err());
    }

    #[test]
    fn cost_chart_marks_the_front_and_puts_zero_errors_on_the_floor() {
        let p =
            |label: &str, ms: f64, error: f64, pareto: bool| CostPoint { label: label.into(), ms, error, pareto, series: String::new() };
        let points = [p("flat", 1.0, 0.1, true), p("gouraud", 3.0, 0.2, false), p("phong", 2.0, 0.01, true), p("exact", 9.0, 0.0, true)];
        let c = CostChart { points: &points, title: "t", y_label: "RMSE", note: None, x: (0.5, 27.0), y: (0.0025, 0.5) };
        assert_eq!(c.at(&points[3]), (9.0, 0.0025));
        assert_eq!(c.at(&points[0]), (1.0, 0.1));
        let chart = cost_chart(&points, "cost", "RMSE", Some("note"), (600, 400), 1.0, Lang::En).unwrap();
        assert!(chart.svg.contains("flat") && chart.svg.contains("exact (error 0)"));
        assert!(chart.png.pixels().any(|q| q[0] > 180 && q[1] < 130 && q[2] < 60), "the orange front is drawn");
        assert!(cost_chart(&[p("x", 0.0, 1.0, true)], "t", "e", None, (300, 200), 1.0, Lang::En).is_err());
        assert_eq!(log_ticks((1.5, 71.0), &[1.0, 2.0, 5.0]), vec![2.0, 5.0, 10.0, 20.0, 50.0]);
        assert_eq!(log_ticks((0.003, 0.2), &[1.0]), vec![0.01, 0.1]);
        assert!(log_ticks((0.0, 1.0), &[1.0]).is_empty());
        assert_eq!([10.0, 0.15000000000000002, -0.2, -0.0, 90.0].map(format_number), ["10", "0.15", "-0.2", "0", "90"]);
        assert_eq!(
            (format_tick(0.5), format_tick(2.0), format_tick(2.5), format_tick(40.0)),
            ("0.5".into(), "2".into(), "2.5".into(), "40".into())
        );
    }
}
