//! A rect light: a one-sided rectangle emitting radiance L_e towards its `direction`.
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `position` | centre |
//! | `direction` | unit normal of the emitting side (the way the light travels) |
//! | `half_w`, `half_h` | half of each side, as perpendicular vectors in its plane |
//!
//! | `sampling` | `solid_angle` (default): uniform over the spherical rectangle it subtends (Ureña, Fajardo & King 2013), leaned towards the receiver's cosine (Hart et al. 2020); `area`: uniform over its area, dω = A cos θ_l / (r² N) |
//!
//! Its exact unoccluded light on a Lambertian receiver is Lambert's polygon formula
//! ([`Rect::projected_solid_angle`]), the reference of the `area_samples` ladder. Shadows: by
//! ray only (a map sees from one point).

use super::sample::{AreaSample, LightSampling, by_solid_angle, towards};
use crate::geometry::polygon::polygon_form_factor;
use crate::geometry::spherical_rect::{CosineWeighted, SphericalRect};
use crate::lesson::light::LightSpec;
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
    /// How its samples are placed.
    pub sampling: LightSampling,
}

/// A rect light seen from one point: what its samples there share.
// Unboxed: one lives on the stack per shaded point; a box would allocate at every point.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy)]
pub enum RectFrom {
    /// The point is behind the emitting side (or in its plane): no light.
    Behind,
    /// By area, from this point.
    Area(Vec3),
    /// By solid angle: the spherical rectangle with its warp towards the receiver's normal.
    SolidAngle(CosineWeighted),
}

impl Rect {
    /// The rect a validated `[[light]]` describes: its size along its frame.
    pub fn from_spec(l: &LightSpec) -> Rect {
        let [w, h] = l.size;
        Rect {
            position: l.position,
            direction: l.direction,
            half_w: l.frame[0] * (w * 0.5),
            half_h: l.frame[1] * (h * 0.5),
            sampling: l.sampling,
        }
    }

    /// The rect seen from `p` (unit normal `n`), ready for its samples.
    pub fn from(&self, p: Vec3, n: Vec3) -> RectFrom {
        if (p - self.position).dot(self.direction).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return RectFrom::Behind;
        }
        match self.sampling {
            LightSampling::Area => RectFrom::Area(p),
            LightSampling::SolidAngle => {
                let corner = self.position - self.half_w - self.half_h;
                RectFrom::SolidAngle(SphericalRect::new(p, corner, 2.0 * self.half_w, 2.0 * self.half_h).cosine_weighted(n))
            }
        }
    }

    /// The sample at u ∈ [0, 1)² from `from`, carrying `per` of the solid angle.
    #[inline]
    pub fn sample(&self, from: &RectFrom, u: Vec2, per: f32, le: Vec3) -> AreaSample {
        match from {
            RectFrom::Behind => AreaSample::NONE,
            RectFrom::Area(p) => {
                let q = self.position + self.half_w * (2.0 * u.x - 1.0) + self.half_h * (2.0 * u.y - 1.0);
                let area = 4.0 * self.half_w.length() * self.half_h.length();
                towards(*p, q, Some(self.direction), area * per, le)
            }
            RectFrom::SolidAngle(rect) => by_solid_angle(rect.sample(u), per, le),
        }
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
