//! A rect light: a one-sided rectangle emitting radiance L_e towards its `direction`.
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `position` | centre |
//! | `direction` | unit normal of the emitting side (the way the light travels) |
//! | `half_w`, `half_h` | half of each side, as perpendicular vectors in its plane |
//!
//! Sampled uniformly by area (dω = A cos θ_l / (r² N), `sample.rs`); its exact unoccluded
//! light on a Lambertian receiver is Lambert's polygon formula ([`Rect::projected_solid_angle`]),
//! the reference of the `area_samples` ladder. Shadows: by ray only (a map sees from one point).

use super::sample::{AreaSample, towards};
use crate::geometry::polygon::polygon_form_factor;
use glam::{Vec2, Vec3};

/// A rect light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Centre.
    pub position: Vec3,
    /// Unit normal of the emitting side (the way the light travels).
    pub direction: Vec3,
    /// Half the `w` side, as a vector in the rectangle's plane.
    pub half_w: Vec3,
    /// Half the `h` side, as a vector in the rectangle's plane (⊥ `half_w`).
    pub half_h: Vec3,
}

impl Rect {
    /// The sample at u ∈ [0, 1)² seen from `p`, carrying `per` of the solid angle.
    #[inline]
    pub fn sample(&self, p: Vec3, u: Vec2, per: f32, le: Vec3) -> AreaSample {
        let q = self.position + self.half_w * (2.0 * u.x - 1.0) + self.half_h * (2.0 * u.y - 1.0);
        let area = 4.0 * self.half_w.length() * self.half_h.length();
        towards(p, q, Some(self.direction), area * per, le)
    }

    /// The corners, counter-clockwise seen from the emitting side.
    pub fn corners(&self) -> [Vec3; 4] {
        let (c, w, h) = (self.position, self.half_w, self.half_h);
        [c - w - h, c + w - h, c + w + h, c - w + h]
    }

    /// The projected solid angle A′ = π F of the rectangle seen from `p` with unit normal `n`
    /// (Lambert 1760: the polygon form factor F), 0 behind the emitting side.
    #[inline]
    pub fn projected_solid_angle(&self, p: Vec3, n: Vec3, corners: &[Vec3; 4]) -> f32 {
        // One-sided: a point behind the emitting side gets nothing.
        if (p - self.position).dot(self.direction) > 0.0 { std::f32::consts::PI * polygon_form_factor(p, n, corners) } else { 0.0 }
    }
}
