//! A line light: a thin tube from `start` to `end` emitting radiance L_e all round (a
//! fluorescent lamp).
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `start`, `end` | the ends of its axis (distinct) |
//! | `radius` | tube radius, > 0 |
//! | `sampling` | `solid_angle` (default): uniform in the solid angle of the thin tube (Gamito 2016's thin-tube limit, `geometry::tube`), every sample the same dω = 2R (sin θ_b − sin θ_a)/(d N); `area`: uniform along the axis |
//!
//! A length element dx seen from distance r has the projected area 2R·sin φ·dx (φ between
//! the axis and l), so its solid angle is 2R sin φ dx / r². Shadows: by ray only.

use super::sample::{AreaSample, LightSampling, by_solid_angle};
use crate::geometry::tube::ThinTube;
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
    /// How its samples are placed.
    pub sampling: LightSampling,
}

/// A line light seen from one point: what its samples there share.
#[derive(Debug, Clone, Copy)]
pub enum LineFrom {
    /// By length, from this point.
    Area(Vec3),
    /// By solid angle: the thin tube seen from the point.
    SolidAngle(ThinTube),
}

impl Line {
    /// The line seen from `p`, ready for its samples.
    pub fn from(&self, p: Vec3) -> LineFrom {
        match self.sampling {
            LightSampling::Area => LineFrom::Area(p),
            LightSampling::SolidAngle => LineFrom::SolidAngle(ThinTube::new(p, self.start, self.end, self.radius)),
        }
    }

    /// The sample at u ∈ [0, 1)² from `from`, carrying `per` of the solid angle.
    pub fn sample(&self, from: &LineFrom, u: Vec2, per: f32, le: Vec3) -> AreaSample {
        match from {
            LineFrom::Area(p) => self.sample_area(*p, u, per, le),
            LineFrom::SolidAngle(tube) => by_solid_angle(tube.sample(u.x), per, le),
        }
    }

    /// A sample uniform along the axis.
    fn sample_area(&self, p: Vec3, u: Vec2, per: f32, le: Vec3) -> AreaSample {
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
