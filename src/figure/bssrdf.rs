//! A `bssrdf` figure: where light leaves a flat, semi-infinite slab of a subsurface material
//! relative to where it entered, per channel: the path tracer's random walk
//! ([`crate::transport::path::subsurface::half_space_exits`], the same walk code) histogrammed,
//! against Christensen & Burley 2015's normalized diffusion and the classical dipole (Jensen et
//! al. 2001).

use super::plot::{Chart, font, format_number, legend, log_ticks, render_generic, with_note};
use crate::lesson::i18n::Lang;
use crate::transport::path::subsurface::{Interior, burley_profile, burley_scale, dipole_profile, half_space_exits};
use glam::Vec3;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Walks histogrammed: the figure's noise is below a line width at the peaks.
pub const WALKS: u32 = 200_000;
/// Histogram bins per decade of r.
const PER_DECADE: usize = 16;
/// The chart's size in pixels.
const SIZE: (u32, u32) = (900, 560);
/// The channels' line colours and names.
const CHANNELS: [(RGBColor, &str); 3] = [(RGBColor(200, 30, 30), "red"), (RGBColor(20, 140, 50), "green"), (RGBColor(30, 70, 200), "blue")];

/// The walk's radial exit profile per channel, on log-spaced bins of r.
#[derive(Debug, Clone)]
pub struct ExitProfile {
    /// The smallest r of the bins (world units).
    pub r_min: f64,
    /// The bins' width in ln r.
    pub step: f64,
    /// Per bin and channel: the energy that left within the bin over its width in ln r, the
    /// mean of 2π r² R(r) over the bin.
    pub bins: Vec<[f64; 3]>,
    /// All the energy that left, per channel (the walk's total albedo), whatever r.
    pub albedo: [f64; 3],
    /// The mean exit radius per channel (energy-weighted, exact r, not binned).
    pub mean_r: [f64; 3],
}

impl ExitProfile {
    /// The centre of bin `k` (geometric).
    pub fn r(&self, k: usize) -> f64 {
        self.r_min * ((k as f64 + 0.5) * self.step).exp()
    }
}

/// Walks `walks` light paths into the half-space of medium `m` and histograms where they
/// leave between `r_min` and `r_max` (world units).
pub fn exit_profile(m: &Interior, walks: u32, r_min: f64, r_max: f64) -> ExitProfile {
    let decades = (r_max / r_min).log10().max(0.1);
    let n = ((decades * PER_DECADE as f64).ceil() as usize).max(1);
    let step = (r_max / r_min).ln() / n as f64;
    let mut bins = vec![[0.0f64; 3]; n];
    let (mut albedo, mut moment) = ([0.0f64; 3], [0.0f64; 3]);
    half_space_exits(m, walks, |r, w| {
        let (r, w) = (f64::from(r), w.to_array().map(f64::from));
        for c in 0..3 {
            albedo[c] += w[c];
            moment[c] += w[c] * r;
        }
        // r = 0 (or below r_min) falls outside the chart but still counts in the albedo.
        if r >= r_min {
            let k = ((r / r_min).ln() / step) as usize;
            if let Some(b) = bins.get_mut(k) {
                (0..3).for_each(|c| b[c] += w[c]);
            }
        }
    });
    let scale = 1.0 / (f64::from(walks) * step);
    bins.iter_mut().for_each(|b| b.iter_mut().for_each(|v| *v *= scale));
    let mean_r = [0, 1, 2].map(|c| if albedo[c] > 0.0 { moment[c] / albedo[c] } else { 0.0 });
    ExitProfile { r_min, step, bins, albedo: albedo.map(|a| a / f64::from(walks)), mean_r }
}

/// The dipole's mean exit radius ∫ r R_d 2πr dr / ∫ R_d 2πr dr (midpoint rule in ln r, out
/// to 200 mean free paths, where R_d is below 1e-40 of its peak for α < 0.999).
pub fn dipole_mean_radius(alpha: f32, free_path: f32) -> f64 {
    let (lo, hi, n) = (1e-4 * f64::from(free_path), 200.0 * f64::from(free_path), 20_000);
    let step = (hi / lo).ln() / n as f64;
    let (mut e, mut m) = (0.0, 0.0);
    for k in 0..n {
        let r = lo * ((k as f64 + 0.5) * step).exp();
        let w = f64::from(dipole_profile(alpha, free_path, r as f32)) * r * r;
        e += w;
        m += w * r;
    }
    if e > 0.0 { m / e } else { 0.0 }
}

/// The chart of a subsurface material (the figure's title names it) of colour `color` (its multiple-scattering albedo A)
/// and mean free paths `free_path` (world units); returns the walk's profile too.
///
/// # Errors
/// A message from the chart backend.
pub fn bssrdf_chart(color: Vec3, free_path: Vec3, lang: Lang) -> Result<(Chart, ExitProfile), String> {
    let m = Interior::new(color, free_path);
    // From a fiftieth of the shortest mean free path to twenty of the longest (past the tails).
    let (lo, hi) = (0.02 * f64::from(free_path.min_element()), 20.0 * f64::from(free_path.max_element()));
    let profile = exit_profile(&m, WALKS, lo, hi);
    let curve = |f: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
        (0..=400).map(|k| lo * (hi / lo).powf(k as f64 / 400.0)).map(|r| (r, std::f64::consts::TAU * r * r * f(r))).collect()
    };
    let mut lines = Vec::new();
    let mut labels = Vec::new();
    for c in 0..3 {
        let (a, l, alpha) = (color[c], free_path[c], m.albedo[c]);
        let walk: Vec<(f64, f64)> = (0..profile.bins.len()).map(|k| (profile.r(k), profile.bins[k][c])).collect();
        let burley = curve(&|r| f64::from(burley_profile(a, l, r as f32)));
        let dipole = curve(&|r| f64::from(dipole_profile(alpha, l, r as f32)));
        lines.push([walk, burley, dipole]);
        labels.push(format!(
            "{} (ℓ = {}): mean r = {} walk, {} Burley, {} dipole",
            CHANNELS[c].1,
            format_number(f64::from(l)),
            round3(profile.mean_r[c]),
            round3(2.5 * f64::from(l) / f64::from(burley_scale(a))),
            round3(dipole_mean_radius(alpha, l)),
        ));
    }
    let top = lines.iter().flat_map(|l| l[0].iter().chain(l[1].iter()).map(|p| p.1)).fold(0.0, f64::max);
    let note = format!(
        "{} walks in by diffuse transmission at one point; A = {}, {}, {}; the walk returns {}, {}, {}",
        WALKS,
        format_number(f64::from(color.x)),
        format_number(f64::from(color.y)),
        format_number(f64::from(color.z)),
        round3(profile.albedo[0]),
        round3(profile.albedo[1]),
        round3(profile.albedo[2]),
    );
    let chart = ProfileChart { lines: &lines, labels: &labels, note: &note, x: (lo, hi), top: top * 1.35 };
    let drawn = render_generic(SIZE, lang, |a, k| chart.draw(a, k), |a, k| chart.draw(a, k))?;
    Ok((drawn, profile))
}

/// Three decimals, trailing zeros dropped.
fn round3(v: f64) -> String {
    format_number((v * 1000.0).round() / 1000.0)
}

/// A legend mark's three segments, (start, end) in pixels before the supersampling.
type Marks = [(i32, i32); 3];

/// What [`bssrdf_chart`] draws.
struct ProfileChart<'a> {
    /// Per channel: the walk, Burley's fit and the dipole.
    lines: &'a [[Vec<(f64, f64)>; 3]],
    labels: &'a [String],
    note: &'a str,
    x: (f64, f64),
    top: f64,
}

impl ProfileChart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, k: u32) -> Result<(), String> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let area = with_note(root, Some(self.note), k)?;
        let mut chart = ChartBuilder::on(&area)
            .caption("Where light leaves: the radial exit profile R(r)", (font(), 22 * k))
            .margin(14 * k)
            .margin_right(30 * k)
            .x_label_area_size(40 * k)
            .y_label_area_size(56 * k)
            .build_cartesian_2d((self.x.0..self.x.1).log_scale().with_key_points(log_ticks(self.x, &[1.0, 3.0])), 0.0..self.top)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("distance r from the entry point (world units, log scale)")
            .y_desc("2π r² R(r): light leaving per unit of ln r")
            .x_label_formatter(&|v| format_number(*v))
            .y_label_formatter(&|v| format_number((v * 100.0).round() / 100.0))
            .label_style((font(), 13 * k))
            .axis_desc_style((font(), 15 * k))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(200, 200, 200).stroke_width(k))
            .axis_style(RGBColor(0, 0, 0).stroke_width(k))
            .set_all_tick_mark_size(5 * k)
            .draw()
            .map_err(err)?;
        let len = 18 * k as i32;
        for (c, [walk, burley, dipole]) in self.lines.iter().enumerate() {
            let colour = CHANNELS[c].0;
            chart
                .draw_series(LineSeries::new(walk.iter().copied(), colour.stroke_width(3 * k)))
                .map_err(err)?
                .label(self.labels[c].as_str())
                .legend(move |(x, y)| PathElement::new([(x, y), (x + len, y)], colour.stroke_width(3 * k)));
            chart.draw_series(DashedLineSeries::new(burley.iter().copied(), 9 * k, 5 * k, colour.stroke_width(k))).map_err(err)?;
            chart.draw_series(DashedLineSeries::new(dipole.iter().copied(), 2 * k, 4 * k, colour.stroke_width(2 * k))).map_err(err)?;
        }
        // The line styles once, in grey: three segments each (solid, dashed, dotted).
        let grey = RGBColor(90, 90, 90);
        let key: [(&str, Marks, u32); 3] = [
            ("random walk (the path tracer's), histogram", [(0, 6), (6, 12), (12, 18)], 3),
            ("Burley 2015 normalized diffusion (dashed)", [(0, 5), (7, 12), (14, 18)], 1),
            ("dipole, Jensen et al. 2001 (dotted)", [(0, 2), (8, 10), (16, 18)], 2),
        ];
        for (label, segs, width) in key {
            let style = grey.stroke_width(width * k);
            let seg = move |i: usize| PathElement::new([(segs[i].0 * k as i32, 0), (segs[i].1 * k as i32, 0)], style);
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map_err(err)?
                .label(label)
                .legend(move |(x, y)| EmptyElement::at((x, y)) + seg(0) + seg(1) + seg(2));
        }
        legend(&mut chart, k, SeriesLabelPosition::UpperLeft)?;
        area.present().map_err(err)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Skin (lesson 46): the histogram holds the walk's whole albedo (nothing leaves outside
    /// 1e-6 to 2 world units), the walk returns the base colour
    /// within 5% and leaves within 10% of Burley's mean radius 2.5 ℓ/s (the half-space test's
    /// tolerances), and red leaves more than five times further out than blue (ℓ 0.1 against 0.01).
    #[test]
    fn the_skin_profile_holds_the_albedo_and_red_spreads_furthest() {
        let (color, path) = (Vec3::new(0.8, 0.45, 0.35), Vec3::new(0.1, 0.02, 0.01));
        let p = exit_profile(&Interior::new(color, path), 40_000, 1e-6, 2.0);
        for c in 0..3 {
            let binned: f64 = p.bins.iter().map(|b| b[c] * p.step).sum();
            let burley = 2.5 * f64::from(path[c]) / f64::from(burley_scale(color[c]));
            eprintln!("channel {c}: albedo {:.4}, binned {binned:.4}, mean r {:.4} against Burley's {burley:.4}", p.albedo[c], p.mean_r[c]);
            assert!((binned / p.albedo[c] - 1.0).abs() < 0.01, "channel {c}: {binned} of {}", p.albedo[c]);
            assert!((p.albedo[c] / f64::from(color[c]) - 1.0).abs() < 0.05, "channel {c}: {}", p.albedo[c]);
            assert!((p.mean_r[c] / burley - 1.0).abs() < 0.10, "channel {c}: {} against {burley}", p.mean_r[c]);
        }
        assert!(p.mean_r[0] > 5.0 * p.mean_r[2], "{:?}", p.mean_r);
    }

    /// The dipole's mean radius is finite and grows with α: less absorption, longer paths
    /// (σ_tr = √(3 σ_a σ_t) falls).
    #[test]
    fn the_dipole_mean_radius_is_finite_and_grows_with_the_albedo() {
        let a = [0.3f32, 0.6, 0.9, 0.99].map(|x| dipole_mean_radius(x, 1.0));
        assert!(a.windows(2).all(|w| w[1] > w[0]), "{a:?}");
        assert!(a.iter().all(|r| r.is_finite() && *r > 0.0));
    }
}
