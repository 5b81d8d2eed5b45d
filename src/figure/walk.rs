//! A `walk` figure: light walked through a slab of isotropic scatterers
//! ([`crate::transport::slab`]), as two charts: where the light leaves (radiance against
//! the exit angle, relative to Lambert's law) and which light leaves (each channel's
//! reflected energy against the scatterings it took, with the reflected colour).

use super::plot::{Chart, Series, font, format_number, legend, line_chart, log_ticks, render_generic, with_note};
use crate::lesson::i18n::Lang;
use crate::transport::slab::{BINS, EVENTS, GROUPS, Slab, SlabWalk, half_space_albedo};
use plotters::coord::Shift;
use plotters::prelude::*;

/// The walks' seed: fixed, so a figure is the same on every run.
const SEED: u32 = 0x5eed_51ab;

/// Each chart's size in pixels.
const SIZE: (u32, u32) = (800, 520);

/// The walk a figure shows, and its two charts.
pub struct WalkCharts {
    /// What the walks measured.
    pub walk: SlabWalk,
    /// Radiance against the exit angle, per group of scatterings.
    pub directions: Chart,
    /// Reflected energy per channel against the scatterings, with the reflected colour.
    pub colour: Chart,
}

/// Walks `slab` `walks` times and draws both charts.
///
/// # Errors
/// A message from the chart backend.
pub fn walk_charts(slab: &Slab, walks: u32, lang: Lang) -> Result<WalkCharts, String> {
    let walk = crate::transport::slab::walk(slab, walks, SEED);
    let directions = directions_chart(&walk, slab, lang)?;
    let colour = colour_chart(&walk, slab, lang)?;
    Ok(WalkCharts { walk, directions, colour })
}

/// The group's legend name.
fn group_name(g: usize) -> String {
    match GROUPS[g] {
        (1, 1) => "1 scattering".into(),
        (lo, u32::MAX) => format!("{lo} or more scatterings"),
        (lo, hi) => format!("{lo}–{hi} scatterings"),
    }
}

/// Radiance of the reflected light against the exit angle, relative to a Lambertian exit of
/// the same power (1 everywhere), per group of scatterings and in all.
fn directions_chart(walk: &SlabWalk, slab: &Slab, lang: Lang) -> Result<Chart, String> {
    let curve = |bins: [f64; BINS]| (0..BINS).map(|k| (SlabWalk::bin_angle(k), bins[k])).collect::<Vec<_>>();
    let shares = walk.group_shares();
    let mut series: Vec<Series> = (0..GROUPS.len())
        .map(|g| Series { label: format!("{} ({:.0}%)", group_name(g), 100.0 * shares[g]), points: curve(walk.relative_radiance(Some(g))) })
        .collect();
    series.push(Series { label: "all reflected light".into(), points: curve(walk.relative_radiance(None)) });
    series.push(Series { label: "Lambert: the same in every direction".into(), points: vec![(0.0, 1.0), (90.0, 1.0)] });
    let top = series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).fold(1.0, f64::max);
    let note = format!(
        "{} walks in at θ₀ = {}°; bins of equal projected solid angle; share of the reflected light in brackets",
        walk.walks,
        format_number(slab.cos_incidence.clamp(-1.0, 1.0).acos().to_degrees().round())
    );
    line_chart(
        &series,
        "Where the light leaves: radiance against the exit angle",
        "exit angle θ from the normal (degrees)",
        "radiance relative to Lambert",
        (0.0, 90.0),
        (0.0, (top * 1.25).max(1.6)),
        Some(&note),
        SIZE,
        lang,
    )
}

/// The channels' line colours (red, green, blue as themselves, dark enough for text).
const CHANNELS: [(RGBColor, &str); 3] = [(RGBColor(200, 30, 30), "red"), (RGBColor(20, 140, 50), "green"), (RGBColor(30, 70, 200), "blue")];

/// The events at which the cumulative curves are sampled: every one to 100, then 2% apart.
fn sample_events() -> Vec<usize> {
    let mut out: Vec<usize> = (1..=100).collect();
    let mut n = 100.0f64;
    while (n as usize) < EVENTS {
        n *= 1.02;
        let k = (n as usize).min(EVENTS);
        if out.last() != Some(&k) {
            out.push(k);
        }
    }
    out
}

/// Each channel's energy reflected within n scatterings against n (log scale), and a swatch
/// of the reflected colour under white light.
fn colour_chart(walk: &SlabWalk, slab: &Slab, lang: Lang) -> Result<Chart, String> {
    let mut cumulative = vec![[0.0f64; 3]; EVENTS];
    let mut sum = [0.0f64; 3];
    for (n, e) in walk.by_events.iter().enumerate() {
        (0..3).for_each(|c| sum[c] += e[c]);
        cumulative[n] = sum;
    }
    let events = sample_events();
    let series: Vec<Series> = (0..3)
        .map(|c| Series {
            label: format!("{}: R = {:.3}", CHANNELS[c].1, walk.reflected[c]),
            points: events.iter().map(|&n| (n as f64, cumulative[n - 1][c])).collect(),
        })
        .collect();
    let albedo = [slab.albedo.x, slab.albedo.y, slab.albedo.z].map(|a| a as f64);
    let note = match slab.thickness {
        None => {
            let exact = albedo.map(|a| half_space_albedo(a, slab.cos_incidence));
            format!("ω = {}; exact R (Chandrasekhar) = {:.3}, {:.3}, {:.3}", triple(albedo), exact[0], exact[1], exact[2])
        }
        Some(t) => format!(
            "ω = {}; optical thickness {}; transmitted T = {:.3}, {:.3}, {:.3}",
            triple(albedo),
            format_number(t),
            walk.transmitted[0],
            walk.transmitted[1],
            walk.transmitted[2]
        ),
    };
    let reflected = walk.reflected.map(|r| (crate::render::srgb::srgb_encode(r.clamp(0.0, 1.0) as f32) * 255.0).round() as u8);
    let chart = ColourChart { series: &series, note: &note, swatch: RGBColor(reflected[0], reflected[1], reflected[2]) };
    render_generic(SIZE, lang, |a, k| chart.draw(a, k), |a, k| chart.draw(a, k))
}

/// `0.999, 0.98, 0.9`.
fn triple(v: [f64; 3]) -> String {
    v.map(format_number).join(", ")
}

/// What [`colour_chart`] draws.
struct ColourChart<'a> {
    series: &'a [Series],
    note: &'a str,
    swatch: RGBColor,
}

impl ColourChart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let area = with_note(root, Some(self.note), k)?;
        let x = (1.0, EVENTS as f64);
        let mut chart = ChartBuilder::on(&area)
            .caption("Which light leaves: the absorption colours the long walks", (font(), 22 * k))
            .margin(14 * k)
            .margin_right(30 * k)
            .x_label_area_size(40 * k)
            .y_label_area_size(56 * k)
            .build_cartesian_2d((x.0..x.1).log_scale().with_key_points(log_ticks(x, &[1.0])), 0.0..1.05)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("scatterings before leaving, n (log scale)")
            .y_desc("energy reflected within n scatterings")
            .x_label_formatter(&|v| format_number(*v))
            .y_label_formatter(&|v| format_number(*v))
            .label_style((font(), 13 * k))
            .axis_desc_style((font(), 15 * k))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(200, 200, 200).stroke_width(k))
            .axis_style(RGBColor(0, 0, 0).stroke_width(k))
            .set_all_tick_mark_size(5 * k)
            .draw()
            .map_err(err)?;
        for (s, (c, _)) in self.series.iter().zip(CHANNELS) {
            let legend_len = 18 * k as i32;
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), c.stroke_width(2 * k)))
                .map_err(err)?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + legend_len, y)], c.stroke_width(2 * k)));
        }
        // The reflected colour, upper left, where the curves have not risen yet.
        let plot = chart.plotting_area();
        plot.draw(&Rectangle::new([(1.25, 1.0), (3.2, 0.78)], self.swatch.filled())).map_err(err)?;
        plot.draw(&Rectangle::new([(1.25, 1.0), (3.2, 0.78)], RGBColor(120, 120, 120).stroke_width(k))).map_err(err)?;
        let style = (font(), 15 * k).into_font().color(&RGBColor(40, 40, 40));
        plot.draw(&Text::new("the reflected colour (white light in)", (3.6, 0.93), style)).map_err(err)?;
        // The curves end high on the right: the lower right stays clear.
        legend(&mut chart, k, SeriesLabelPosition::LowerRight)?;
        area.present().map_err(err)
    }
}
