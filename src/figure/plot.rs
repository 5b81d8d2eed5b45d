//! Charts: BRDF lobes in polar form and curves (albedo, cost), as PNG and SVG.
//!
//! Drawn with plotters on the embedded DejaVu Sans, so the bytes do not depend on the
//! fonts installed on the machine.

use plotters::coord::Shift;
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

fn font() -> &'static str {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The bytes are the embedded font; registering cannot fail for them.
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

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, s: &Spec) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let area = match s.note {
        Some(note) => {
            let (top, bottom) = root.split_vertically(root.dim_in_pixel().1.saturating_sub(28));
            bottom.draw_text(note, &(font(), 14).into_font().color(&RGBColor(80, 80, 80)), (16, 6)).map_err(err)?;
            top
        }
        None => root,
    };
    let mut chart = ChartBuilder::on(&area)
        .caption(s.title, (font(), 22))
        .margin(14)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d(s.x.0..s.x.1, s.y.0..s.y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(s.x_label)
        .y_desc(s.y_label)
        .label_style((font(), 13))
        .axis_desc_style((font(), 15))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(err)?;
    for (a, b) in s.guides {
        chart.draw_series(LineSeries::new([*a, *b], RGBColor(150, 150, 150).stroke_width(1))).map_err(err)?;
    }
    for (i, series) in s.series.iter().enumerate() {
        let c = PALETTE[i % PALETTE.len()];
        chart
            .draw_series(LineSeries::new(series.points.iter().copied(), c.stroke_width(2)))
            .map_err(err)?
            .label(series.label.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], c.stroke_width(2)));
    }
    if s.series.len() > 1 || s.series.first().is_some_and(|x| !x.label.is_empty()) {
        chart
            .configure_series_labels()
            .label_font((font(), 14))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(200, 200, 200))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(err)?;
    }
    area.present().map_err(err)
}

fn render(size: (u32, u32), s: &Spec) -> Result<Chart, String> {
    let mut buf = vec![255u8; (size.0 * size.1 * 3) as usize];
    draw(BitMapBackend::with_buffer(&mut buf, size).into_drawing_area(), s)?;
    let mut svg = String::new();
    draw(SVGBackend::with_string(&mut svg, size).into_drawing_area(), s)?;
    let png = image::RgbImage::from_raw(size.0, size.1, buf).ok_or("buffer size")?;
    Ok(Chart { png, svg })
}

/// BRDF lobes in the plane of incidence: each series holds points (x, y) = r (sin θ_o, cos θ_o)
/// with r = f·cos θ_o; the light comes from the left, and each incident direction is drawn
/// from the origin at its angle in `incidence_deg`.
///
/// # Errors
/// A message when plotters fails (it does not for in-memory backends in practice).
pub fn polar_lobe(series: &[Series], incidence_deg: &[f64], title: &str, size: (u32, u32)) -> Result<Chart, String> {
    let r = series.iter().flat_map(|s| s.points.iter()).map(|(x, y)| x.hypot(*y)).fold(0.0f64, f64::max).max(1e-6) * 1.1;
    let mut guides = vec![((0.0, 0.0), (0.0, r)), ((-r, 0.0), (r, 0.0))];
    for i in incidence_deg.iter().map(|d| d.to_radians()) {
        guides.push(((0.0, 0.0), (-r * i.sin(), r * i.cos())));
    }
    let spec = Spec {
        title,
        x_label: "f·cos θ_o  (towards the mirror side →)",
        y_label: "along the normal",
        x: (-r, r),
        y: (0.0, r),
        series,
        guides: &guides,
        note: Some("grey: the surface, the normal, and the direction towards the light"),
    };
    render(size, &spec)
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
) -> Result<Chart, String> {
    render(size, &Spec { title, x_label, y_label, x, y, series, guides: &[], note })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lobe_chart_draws_and_is_deterministic() {
        let pts: Vec<(f64, f64)> = (0..=90).map(|d| (d as f64).to_radians()).map(|t| (t.sin() * t.cos(), t.cos() * t.cos())).collect();
        let s = [Series { label: "test".into(), points: pts }];
        let a = polar_lobe(&s, &[30.0], "lobe", (400, 300)).unwrap();
        let b = polar_lobe(&s, &[30.0], "lobe", (400, 300)).unwrap();
        assert_eq!(a.png.as_raw(), b.png.as_raw());
        assert!(a.svg.contains("<svg") && a.svg.contains("lobe"));
        // Something coloured (the curve) was drawn.
        assert!(a.png.pixels().any(|p| p[2] > 150 && p[0] < 60));
    }
}
