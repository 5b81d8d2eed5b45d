//! A line light: a thin tube from `start` to `end` emitting radiance L_e all round (a
//! fluorescent lamp).
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `start`, `end` | the ends of its axis (distinct) |
//! | `radius` | tube radius, > 0 |
//!
//! Sampled uniformly along the axis: a length element dx seen from distance r has the
//! projected area 2R·sin φ·dx (φ between the axis and l), so its solid angle is
//! 2R sin φ dx / r². Shadows: by ray only.

use super::sample::AreaSample;
use glam::{Vec2, Vec3};

/// A line light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// One end of the axis.
    pub start: Vec3,
    /// The other end.
    pub end: Vec3,
    /// Tube radius (> 0).
    pub radius: f32,
}

impl Line {
    /// The sample at u ∈ [0, 1)² seen from `p`, carrying `per` of the solid angle.
    pub fn sample(&self, p: Vec3, u: Vec2, per: f32, le: Vec3) -> AreaSample {
        let axis = self.end - self.start;
        let len = axis.length();
        let q = self.start + axis * u.x;
        let to = q - p;
        // Inside the tube the point sees it at its radius.
        let r = to.length().max(self.radius);
        let l = (to / r).normalize_or_zero();
        if l == Vec3::ZERO {
            return AreaSample::NONE;
        }
        let sin = l.cross(axis / len).length();
        AreaSample { l, distance: to.length(), weight: 2.0 * self.radius * len * sin / (r * r) * per, radiance: le }
    }
}
