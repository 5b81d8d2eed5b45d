//! BRDF charts of a lesson's materials: lobes in the plane of incidence and albedo curves.

use super::plot::{Chart, Series, line_chart, polar_lobe};
use super::text::to_plain_text;
use crate::shading::brdf::{Brdf, directional_albedo};
use glam::Vec3;
use rayon::prelude::*;

/// Rec. 709 luminance, one curve per material.
fn luminance(c: Vec3) -> f64 {
    (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) as f64
}

/// The lobe of `brdf` lit from the left at `incidence` degrees: points r (sin θ_o, cos θ_o)
/// with r = f·cos θ_o (luminance), θ_o from −90° to 90° in 0.25° steps.
pub fn lobe_points(brdf: &Brdf, incidence: f64) -> Vec<(f64, f64)> {
    let i = incidence.to_radians() as f32;
    let l = Vec3::new(-i.sin(), 0.0, i.cos());
    (0..=720)
        .map(|k| (-90.0 + 180.0 * k as f64 / 720.0).to_radians())
        .map(|t| {
            let v = Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
            let r = luminance(brdf.eval(l, v)) * t.cos();
            (r * t.sin(), r * t.cos())
        })
        .collect()
}

/// Polar lobes of named BRDFs at the given angles of incidence (degrees, in [0, 90)).
///
/// # Errors
/// A message from the chart backend.
pub fn lobe_chart(brdfs: &[(String, Brdf)], incidence: &[f64], title: &str) -> Result<Chart, String> {
    let mut series = Vec::new();
    for (name, brdf) in brdfs {
        for i in incidence {
            let label = if incidence.len() > 1 { format!("{}, θᵢ = {i}°", to_plain_text(name)) } else { to_plain_text(name) };
            series.push(Series { label, points: lobe_points(brdf, *i) });
        }
    }
    polar_lobe(&series, incidence, &to_plain_text(title), (900, 520))
}

/// Directional albedo (largest channel) against the angle of incidence, 0° to 88° every 2°,
/// with the worst integration error bound in the note.
///
/// # Errors
/// A message from the chart backend.
pub fn albedo_chart(brdfs: &[(String, Brdf)], samples: usize, title: &str) -> Result<Chart, String> {
    let mut series = Vec::new();
    let (mut worst, mut top) = (0.0f64, 1.0f64);
    for (name, b) in brdfs {
        // Each angle is an independent quadrature: in parallel, collected in order.
        let values: Vec<(f64, f64, f64)> = (0..=44)
            .into_par_iter()
            .map(|i| {
                let deg = 2.0 * i as f64;
                let (a, e) = directional_albedo(b, deg.to_radians().cos(), samples);
                (deg, a, e)
            })
            .collect();
        for &(_, a, e) in &values {
            worst = worst.max(e);
            top = top.max(a);
        }
        series.push(Series { label: to_plain_text(name), points: values.iter().map(|&(d, a, _)| (d, a)).collect() });
    }
    let note =
        format!("largest channel; integration error bound ≤ {worst:.1e} (Gauss-Legendre, {samples} vs {} nodes per panel)", 2 * samples);
    line_chart(
        &series,
        &to_plain_text(title),
        "angle of incidence θᵢ (degrees)",
        "albedo",
        (0.0, 90.0),
        (0.0, top * 1.1),
        Some(&note),
        (900, 520),
    )
}
