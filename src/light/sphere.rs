//! A sphere light: a sphere emitting radiance L_e all round.
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `position` | centre |
//! | `radius` | > 0 |
//! | `sampling` | `solid_angle` (default): uniform directions in the cone it subtends (pbrt-v4 `SphereShape::Sample`), half-angle asin(R/d), dω = 2π(1 − cos θ_max)/N, from inside the whole sphere of directions; `area`: uniform points on its surface, dω = 4πR² cos θ_q / (r² N), 0 for the half facing away |
//!
//! Shadows: by ray only.

use super::sample::{AreaSample, LightSampling, towards};
use crate::geometry::sampling::{basis, uniform_cone};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A sphere light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Centre.
    pub position: Vec3,
    /// Radius (> 0).
    pub radius: f32,
    /// How its samples are placed.
    pub sampling: LightSampling,
}

impl Sphere {
    /// The sample at u ∈ [0, 1)² seen from `p`, carrying `per` of the solid angle.
    pub fn sample(&self, p: Vec3, u: Vec2, per: f32, le: Vec3) -> AreaSample {
        let (centre, radius) = (self.position, self.radius);
        if self.sampling == LightSampling::Area {
            // A uniform point on the whole surface; the half facing away sends nothing
            // (its cos θ_q < 0), which is what makes this the noisier strategy.
            let d = uniform_cone(u, -1.0);
            // From inside the sphere every point is seen from its inner side: the cone's answer.
            if (p - centre).length_squared() <= radius * radius {
                return AreaSample { l: d, distance: radius, weight: 4.0 * PI * per, radiance: le };
            }
            // Each surface point emits along its outward normal d.
            return towards(p, centre + d * radius, Some(d), 4.0 * PI * radius * radius * per, le);
        }
        let to = centre - p;
        let d2 = to.length_squared();
        let r2 = radius * radius;
        if d2 <= r2 {
            let l = uniform_cone(u, -1.0);
            return AreaSample { l, distance: radius, weight: 4.0 * PI * per, radiance: le };
        }
        let d = d2.sqrt();
        let sin2 = r2 / d2;
        let cos_max = (1.0 - sin2).max(0.0).sqrt();
        // 1 − cos θ_max without cancellation for small spheres: sin²/(1 + cos).
        let one_minus = sin2 / (1.0 + cos_max);
        let local = uniform_cone(u, cos_max);
        let w = to / d;
        let (t, b) = basis(w);
        let l = (t * local.x + b * local.y + w * local.z).normalize_or(w);
        // Nearest intersection with the sphere along l (b² − c clamped: l lies in the cone).
        let bl = l.dot(to);
        let disc = (bl * bl - (d2 - r2)).max(0.0);
        let distance = (bl - disc.sqrt()).max(0.0);
        AreaSample { l, distance, weight: 2.0 * PI * one_minus * per, radiance: le }
    }
}
