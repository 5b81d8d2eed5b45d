//! A `bsdf` figure: a rough dielectric boundary ([`crate::shading::rough_dielectric`]) as the
//! BRDF above the surface plus the BTDF below it, beside the smooth glass: its lobes in the
//! plane of incidence over the whole circle, and how it splits a beam's energy between
//! reflection and transmission against the angle of incidence.

use super::plot::{Chart, font, format_number, legend, render_generic, with_note};
use crate::lesson::i18n::Lang;
use crate::shading::microfacet::fresnel::dielectric;
use crate::shading::rough_dielectric::RoughDielectric;
use glam::Vec3;
use plotters::coord::Shift;
use plotters::prelude::*;
use rayon::prelude::*;

/// Line colours, one per roughness (Okabe & Ito 2008, as the other charts).
const COLOURS: [RGBColor; 4] = [RGBColor(0, 114, 178), RGBColor(213, 94, 0), RGBColor(0, 158, 115), RGBColor(204, 121, 167)];
/// The smooth glass's lines.
const GREY: RGBColor = RGBColor(110, 110, 110);
/// Visible-normal grid per side for each energy split.
const SPLIT_GRID: u32 = 128;

/// Both charts of a `bsdf` figure.
pub struct BsdfCharts {
    /// f_s |cos θₒ| in the plane of incidence, the whole circle.
    pub lobes: Chart,
    /// Reflected and transmitted shares against the angle of incidence.
    pub split: Chart,
}

/// The light's direction at `deg` from the normal, from the left (as the lobe charts).
fn light(deg: f64) -> Vec3 {
    let t = deg.to_radians();
    Vec3::new(-t.sin() as f32, 0.0, t.cos() as f32)
}

/// Draws a `bsdf` figure's charts for index `ior`, the roughnesses and the angle of incidence.
///
/// # Errors
/// A message from the chart backend.
pub fn bsdf_charts(ior: f64, roughness: &[f64], incidence: f64, lang: Lang) -> Result<BsdfCharts, String> {
    let models: Vec<RoughDielectric> = roughness.iter().map(|r| RoughDielectric::new(ior as f32, *r as f32)).collect();
    let i = light(incidence);
    // Per roughness: (θₒ, f·|cos θₒ|) over the circle, scaled so the transmitted peak is 1.
    let raw: Vec<Vec<(f64, f64)>> = models
        .iter()
        .map(|m| {
            (0..=1440)
                .map(|k| (-180.0 + k as f64 * 0.25).to_radians())
                .map(|t| {
                    let o = Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
                    (t, (m.eval(i, o) * o.z.abs()) as f64)
                })
                .collect()
        })
        .collect();
    let peak = |c: &[(f64, f64)], above: bool| c.iter().filter(|(t, _)| (t.cos() > 0.0) == above).map(|p| p.1).fold(0.0, f64::max);
    let scaled: Vec<Vec<(f64, f64)>> = raw
        .iter()
        .map(|c| {
            let s = 1.0 / peak(c, false).max(1e-30);
            c.iter().map(|&(t, r)| (t, r * s)).collect()
        })
        .collect();
    // The reflections are far smaller than the transmissions: magnified by one factor (1, 2
    // or 5 × 10ᵏ) so the largest reaches about 0.6.
    let upper = scaled.iter().map(|c| peak(c, true)).fold(0.0, f64::max);
    let magnify = nice_floor(0.6 / upper.max(1e-30)).max(1.0);
    let curves: Vec<Vec<(f64, f64)>> = scaled
        .iter()
        .map(|c| {
            c.iter()
                .map(|&(t, r)| {
                    let r = if t.cos() > 0.0 { r * magnify } else { r };
                    (r * t.sin(), r * t.cos())
                })
                .collect()
        })
        .collect();
    let at_incidence: Vec<_> = models.iter().map(|m| m.split(i, SPLIT_GRID)).collect();
    let labels: Vec<String> = roughness
        .iter()
        .zip(&at_incidence)
        .map(|(r, s)| format!("roughness {}: R = {:.3}, T = {:.3}", format_number(*r), s.reflected, s.transmitted))
        .collect();
    let f = dielectric(incidence.to_radians().cos() as f32, ior as f32) as f64;
    let lobes = LobeChart {
        magnify,
        curves: &curves,
        labels: &labels,
        incidence,
        ior,
        note: format!(
            "θᵢ = {}°, η = {}; each roughness scaled to its peak; smooth glass (dashed): F = {f:.3}, 1 − F = {:.3}",
            format_number(incidence),
            format_number(ior),
            1.0 - f
        ),
    };
    let lobes = render_generic((700, 600), lang, |a, k| lobes.draw(a, k), |a, k| lobes.draw(a, k))?;
    let angles: Vec<f64> = (0..=44).map(|k| 2.0 * k as f64).collect();
    let splits: Vec<Vec<(f64, f64, f64)>> = models
        .iter()
        .map(|m| {
            angles
                .par_iter()
                .map(|a| {
                    let s = m.split(light(a.min(89.5)), SPLIT_GRID);
                    (*a, s.reflected, s.transmitted)
                })
                .collect()
        })
        .collect();
    let smooth: Vec<(f64, f64)> = angles.iter().map(|a| (*a, dielectric(a.to_radians().cos() as f32, ior as f32) as f64)).collect();
    let names: Vec<String> = roughness.iter().map(|r| format!("roughness {}", format_number(*r))).collect();
    let split = SplitChart { splits: &splits, names: &names, smooth: &smooth };
    let split = render_generic((700, 600), lang, |a, k| split.draw(a, k), |a, k| split.draw(a, k))?;
    Ok(BsdfCharts { lobes, split })
}

/// The largest 1, 2 or 5 × 10ᵏ at most `x` (> 0).
fn nice_floor(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0].into_iter().map(|m| m * p).find(|v| *v <= x).unwrap_or(p)
}

/// What the lobe chart draws.
struct LobeChart<'a> {
    /// The factor the reflections (above the surface) are drawn larger by.
    magnify: f64,
    curves: &'a [Vec<(f64, f64)>],
    labels: &'a [String],
    incidence: f64,
    ior: f64,
    note: String,
}

impl LobeChart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let area = with_note(root, Some(&self.note), k)?;
        let top = self.curves.iter().flatten().map(|(x, y)| x.hypot(*y)).fold(1e-9, f64::max) * 1.08;
        let mut chart = ChartBuilder::on(&area)
            .caption("BSDF = BRDF (above) + BTDF (below): f·|cos θₒ|", (font(), 22 * k))
            .margin(14 * k)
            .margin_top(8 * k)
            .build_cartesian_2d(-top..top, -top..top)
            .map_err(err)?;
        // Only the shapes are read (each roughness is scaled to its own peak): no tick numbers.
        chart.configure_mesh().disable_x_mesh().disable_y_mesh().disable_axes().draw().map_err(err)?;
        // The surface, the incident ray (drawn arriving from the light), and the smooth
        // glass's mirror and Snell directions.
        let ti = self.incidence.to_radians();
        let sin_t = ti.sin() / self.ior;
        let grey = GREY.stroke_width(k);
        chart.draw_series(LineSeries::new([(-top, 0.0), (top, 0.0)], RGBColor(60, 60, 60).stroke_width(2 * k))).map_err(err)?;
        chart.draw_series(LineSeries::new([(-top * ti.sin(), top * ti.cos()), (0.0, 0.0)], grey)).map_err(err)?;
        let mirror = [(0.0, 0.0), (top * ti.sin(), top * ti.cos())];
        chart.draw_series(DashedLineSeries::new(mirror, 6 * k, 5 * k, grey)).map_err(err)?;
        if sin_t < 1.0 {
            let tt = sin_t.asin();
            let snell = [(0.0, 0.0), (top * tt.sin(), -top * tt.cos())];
            chart.draw_series(DashedLineSeries::new(snell, 6 * k, 5 * k, grey)).map_err(err)?;
        }
        let style = (font(), 14 * k).into_font().color(&RGBColor(70, 70, 70));
        let plot = chart.plotting_area();
        plot.draw(&Text::new("outside (air)", (-0.95 * top, 0.06 * top), style.clone())).map_err(err)?;
        plot.draw(&Text::new("inside (glass)", (-0.95 * top, -0.1 * top), style.clone())).map_err(err)?;
        let above = format!("above the surface: × {}", format_number(self.magnify));
        plot.draw(&Text::new(above, (0.25 * top, 0.95 * top), style.clone())).map_err(err)?;
        plot.draw(&Text::new("light", (-top * ti.sin() * 0.92, top * ti.cos() * 0.92), style)).map_err(err)?;
        for (n, (c, label)) in self.curves.iter().zip(self.labels).enumerate() {
            let colour = COLOURS[n % COLOURS.len()];
            let len = 18 * k as i32;
            chart
                .draw_series(LineSeries::new(c.iter().copied(), colour.stroke_width(2 * k)))
                .map_err(err)?
                .label(label.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + len, y)], colour.stroke_width(2 * k)));
        }
        // The transmitted lobes point down and right: the upper right holds the reflections,
        // small; the lower left is clear.
        legend(&mut chart, k, SeriesLabelPosition::LowerLeft)?;
        area.present().map_err(err)
    }
}

/// What the energy chart draws.
struct SplitChart<'a> {
    /// Per roughness: (angle, R, T).
    splits: &'a [Vec<(f64, f64, f64)>],
    names: &'a [String],
    /// The smooth glass's F against the angle.
    smooth: &'a [(f64, f64)],
}

impl SplitChart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let note = "solid: transmitted T; dashed: reflected R; 1 − R − T: light that would meet a second microfacet";
        let area = with_note(root, Some(note), k)?;
        let mut chart = ChartBuilder::on(&area)
            .caption("Where a beam's energy goes", (font(), 22 * k))
            .margin(14 * k)
            .margin_right(24 * k)
            .x_label_area_size(40 * k)
            .y_label_area_size(56 * k)
            .build_cartesian_2d(0.0..90.0, 0.0..1.05)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("angle of incidence θᵢ (degrees)")
            .y_desc("share of the incident energy")
            .x_label_formatter(&|v| format_number(*v))
            .y_label_formatter(&|v| format_number(*v))
            .label_style((font(), 13 * k))
            .axis_desc_style((font(), 15 * k))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(220, 220, 220).stroke_width(k))
            .axis_style(RGBColor(0, 0, 0).stroke_width(k))
            .draw()
            .map_err(err)?;
        let len = 18 * k as i32;
        let grey = GREY.stroke_width(2 * k);
        chart
            .draw_series(LineSeries::new(self.smooth.iter().map(|&(a, f)| (a, 1.0 - f)), grey))
            .map_err(err)?
            .label("smooth glass: 1 − F and F")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + len, y)], grey));
        chart.draw_series(DashedLineSeries::new(self.smooth.iter().copied(), 7 * k, 5 * k, grey)).map_err(err)?;
        for (n, (s, name)) in self.splits.iter().zip(self.names).enumerate() {
            let c = COLOURS[n % COLOURS.len()].stroke_width(2 * k);
            chart
                .draw_series(LineSeries::new(s.iter().map(|&(a, _, t)| (a, t)), c))
                .map_err(err)?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + len, y)], c));
            chart.draw_series(DashedLineSeries::new(s.iter().map(|&(a, r, _)| (a, r)), 7 * k, 5 * k, c)).map_err(err)?;
        }
        // T falls and R rises only near grazing: the middle left is clear.
        legend(&mut chart, k, SeriesLabelPosition::MiddleLeft)?;
        area.present().map_err(err)
    }
}
