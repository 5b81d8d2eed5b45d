//! A disk light: a one-sided disk emitting radiance L_e towards its `direction`.
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `position` | centre |
//! | `direction` | unit normal of the emitting side |
//! | `radius` | > 0 |
//!
//! Sampled uniformly by area with the concentric map (Shirley & Chiu 1997), dω = A cos θ_l /
//! (r² N). Shadows: by ray only.

use super::sample::{AreaSample, towards};
use crate::geometry::sampling::{basis, concentric_disk};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A disk light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disk {
    /// Centre.
    pub position: Vec3,
    /// Unit normal of the emitting side.
    pub direction: Vec3,
    /// Radius (> 0).
    pub radius: f32,
}

impl Disk {
    /// The sample at u ∈ [0, 1)² seen from `p`, carrying `per` of the solid angle.
    #[inline]
    pub fn sample(&self, p: Vec3, u: Vec2, per: f32, le: Vec3) -> AreaSample {
        let d = concentric_disk(u);
        let (t, b) = basis(self.direction);
        let q = self.position + (t * d.x + b * d.y) * self.radius;
        towards(p, q, Some(self.direction), PI * self.radius * self.radius * per, le)
    }
}
