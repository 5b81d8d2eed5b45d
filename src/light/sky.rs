//! A sky light: radiance `color × intensity` from above the horizon (y ≥ 0) and `ground`
//! from below, all round the point.
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `ground` | radiance from below the horizon |
//!
//! Sampled by cosine-weighted directions about the shading normal (Malley's method, pdf
//! cos θ/π): dω = π/(N cos θ), so a Lambertian receiver under an unblocked sky of one colour
//! gets exactly π L_e, no noise. A sample below the horizon carries the ground's radiance
//! (the renderer delivers the two as separate incidents). Shadows: by ray only.

use super::sample::AreaSample;
use crate::geometry::sampling::{basis, cosine_hemisphere};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A sky light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sky {
    /// Radiance from below the horizon (y < 0).
    pub ground: Vec3,
}

impl Sky {
    /// The sample at u ∈ [0, 1)² about the unit normal `n`, carrying `per` of the solid angle.
    pub fn sample(&self, n: Vec3, u: Vec2, per: f32, le: Vec3) -> AreaSample {
        let d = cosine_hemisphere(u);
        let (t, b) = basis(n);
        let l = (t * d.x + b * d.y + n * d.z).normalize_or(n);
        // A direction in the tangent plane carries nothing (its N·L is 0 in shading too).
        let weight = if d.z > 1e-6 { PI / d.z * per } else { 0.0 };
        AreaSample { l, distance: f32::INFINITY, weight, radiance: if l.y >= 0.0 { le } else { self.ground } }
    }
}
