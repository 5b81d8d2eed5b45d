//! The lights with a surface (rect, disk, sphere) as the path tracer sees them: sampled by
//! area for next-event estimation, and hit by BSDF-sampled rays, each strategy with the
//! solid-angle pdf the other needs for multiple importance sampling (Veach 1997, §9.2).
//!
//! The lights are not in the scene's BVH: they block nothing (as in the rasterizer, where a
//! light never shadows), and a ray that crosses one picks up its radiance and goes on. The
//! pdf of choosing a point uniformly on an emitter of area A, seen from distance r at angle
//! θ_e to its normal, is r²/(A cos θ_e) per steradian.

use crate::geometry::sampling::{concentric_disk, sin_cos};
use crate::light::{Light, LightKind};
use glam::{Vec2, Vec3};

/// A light's shape: where it is, its area, and which way it emits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A one-sided rectangle.
    Rect {
        /// Centre.
        centre: Vec3,
        /// Unit normal of the emitting side.
        normal: Vec3,
        /// Half of one side, in its plane.
        half_w: Vec3,
        /// Half of the other side, in its plane.
        half_h: Vec3,
    },
    /// A one-sided disk.
    Disk {
        /// Centre.
        centre: Vec3,
        /// Unit normal of the emitting side.
        normal: Vec3,
        /// Radius.
        radius: f32,
    },
    /// A sphere emitting all round.
    Sphere {
        /// Centre.
        centre: Vec3,
        /// Radius.
        radius: f32,
    },
}

/// A point of a light's shape reached along a ray: distance, radiance and the solid-angle pdf
/// with which sampling the shape by area would have chosen it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeHit {
    /// Distance along the (unit) ray, or from the sampled point.
    pub t: f32,
    /// Direction from the point towards the light (for a sample).
    pub l: Vec3,
    /// Radiance the light sends back along the ray.
    pub radiance: Vec3,
    /// r²/(A cos θ_e), 1/sr.
    pub pdf: f32,
}

impl Shape {
    /// The shape of `light`, for the kinds that have one.
    pub fn of(light: &Light) -> Option<Shape> {
        match light.kind {
            LightKind::Rect(r) => Some(Shape::Rect { centre: r.position, normal: r.direction, half_w: r.half_w, half_h: r.half_h }),
            LightKind::Disk(d) => Some(Shape::Disk { centre: d.position, normal: d.direction, radius: d.radius }),
            LightKind::Sphere(s) => Some(Shape::Sphere { centre: s.position, radius: s.radius }),
            _ => None,
        }
    }

    /// Its area.
    pub fn area(&self) -> f32 {
        match *self {
            Shape::Rect { half_w, half_h, .. } => 4.0 * half_w.length() * half_h.length(),
            Shape::Disk { radius, .. } => std::f32::consts::PI * radius * radius,
            Shape::Sphere { radius, .. } => 4.0 * std::f32::consts::PI * radius * radius,
        }
    }

    /// The point at u ∈ [0, 1)², uniform in area, and its outward normal.
    pub(super) fn point(&self, u: Vec2) -> (Vec3, Vec3) {
        match *self {
            Shape::Rect { centre, normal, half_w, half_h } => (centre + half_w * (2.0 * u.x - 1.0) + half_h * (2.0 * u.y - 1.0), normal),
            Shape::Disk { centre, normal, radius } => {
                let (t, b) = crate::geometry::sampling::basis(normal);
                let d = concentric_disk(u) * radius;
                (centre + t * d.x + b * d.y, normal)
            }
            Shape::Sphere { centre, radius } => {
                let z = 1.0 - 2.0 * u.x;
                let r = ((1.0 - z) * (1.0 + z)).max(0.0).sqrt();
                let (s, c) = sin_cos(std::f32::consts::TAU * u.y);
                let m = Vec3::new(r * c, r * s, z);
                (centre + m * radius, m)
            }
        }
    }

    /// A point chosen uniformly on the shape seen from `p`, carrying `radiance`; `None` when it
    /// faces away from `p` (the back of a one-sided light, the far side of a sphere).
    pub fn sample(&self, p: Vec3, u: Vec2, radiance: Vec3) -> Option<ShapeHit> {
        let (q, m) = self.point(u);
        let to = q - p;
        let r2 = to.length_squared();
        if !(r2 > 1e-20 && r2.is_finite()) {
            return None;
        }
        let t = r2.sqrt();
        let l = to / t;
        let cos_e = -l.dot(m);
        (cos_e > 0.0).then(|| ShapeHit { t, l, radiance, pdf: r2 / (self.area() * cos_e) })
    }

    /// Where the ray o + t d (unit d) first meets the shape's emitting side for t in (0, t_max),
    /// carrying `radiance`.
    pub fn hit(&self, o: Vec3, d: Vec3, t_max: f32, radiance: Vec3) -> Option<ShapeHit> {
        let (t, m) = match *self {
            Shape::Rect { centre, normal, half_w, half_h } => {
                let t = plane(o, d, centre, normal)?;
                let p = o + d * t - centre;
                let inside =
                    (p.dot(half_w) / half_w.length_squared()).abs() <= 1.0 && (p.dot(half_h) / half_h.length_squared()).abs() <= 1.0;
                (inside.then_some(t)?, normal)
            }
            Shape::Disk { centre, normal, radius } => {
                let t = plane(o, d, centre, normal)?;
                ((o + d * t - centre).length_squared() <= radius * radius).then_some(t).map(|t| (t, normal))?
            }
            Shape::Sphere { centre, radius } => {
                let oc = o - centre;
                let b = oc.dot(d);
                let disc = b * b - (oc.length_squared() - radius * radius);
                if disc.is_nan() || disc <= 0.0 {
                    return None;
                }
                let s = disc.sqrt();
                let t = if -b - s > 0.0 { -b - s } else { -b + s };
                (t > 0.0).then_some(t).map(|t| (t, (o + d * t - centre) / radius))?
            }
        };
        let cos_e = -d.dot(m);
        (t < t_max && cos_e > 0.0).then(|| ShapeHit { t, l: d, radiance, pdf: t * t / (self.area() * cos_e) })
    }
}

/// The distance along o + t d to the plane through `c` with unit normal `n`, when positive.
fn plane(o: Vec3, d: Vec3, c: Vec3, n: Vec3) -> Option<f32> {
    let denom = d.dot(n);
    if denom.abs() < 1e-12 {
        return None;
    }
    let t = (c - o).dot(n) / denom;
    (t > 1e-6 && t.is_finite()).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sobol::sobol_2d;

    /// The pdf a hit reports integrates, over the directions that reach the emitting side, to
    /// the share of the area seen from the point: ∫ r²/(A cos θ_e) dω = A_seen/A (1 for a rect
    /// or disk facing the point, (1 − r/d)/2 for a sphere at distance d), by uniform directions.
    #[test]
    fn the_hit_pdf_integrates_to_the_share_of_the_area_seen() {
        let shapes = [
            Shape::Rect { centre: Vec3::new(0.0, 2.0, 0.0), normal: -Vec3::Y, half_w: Vec3::X * 0.6, half_h: Vec3::Z * 0.3 },
            Shape::Disk { centre: Vec3::new(0.5, 1.5, 0.2), normal: Vec3::new(-0.3, -1.0, 0.0).normalize(), radius: 0.5 },
            Shape::Sphere { centre: Vec3::new(0.0, 1.2, 0.5), radius: 0.4 },
        ];
        let n = 400_000u32;
        for s in shapes {
            let mut sum = 0.0f64;
            for k in 0..n {
                let u = sobol_2d(k, 3);
                let z = 1.0 - 2.0 * u.x;
                let r = ((1.0 - z) * (1.0 + z)).max(0.0).sqrt();
                let d = Vec3::new(r * (std::f32::consts::TAU * u.y).cos(), r * (std::f32::consts::TAU * u.y).sin(), z);
                if let Some(h) = s.hit(Vec3::ZERO, d, f32::INFINITY, Vec3::ONE) {
                    sum += h.pdf as f64;
                }
            }
            let integral = sum * 4.0 * std::f64::consts::PI / n as f64;
            // The sphere: the cap seen from the origin, (1 − r/d)/2 of its area.
            let want = match s {
                Shape::Sphere { centre, radius } => (1.0 - radius as f64 / centre.length() as f64) / 2.0,
                _ => 1.0,
            };
            assert!((integral - want).abs() < 0.01, "{s:?}: ∫ pdf dω = {integral}, want {want}");
        }
    }

    /// A sample's direction hits the shape at the sampled point with the same pdf.
    #[test]
    fn a_samples_ray_hits_the_shape_where_it_was_sampled_with_its_pdf() {
        let shapes = [
            Shape::Rect { centre: Vec3::new(0.0, 2.0, 0.0), normal: -Vec3::Y, half_w: Vec3::X * 0.6, half_h: Vec3::Z * 0.3 },
            Shape::Disk { centre: Vec3::new(0.5, 1.5, 0.2), normal: Vec3::new(-0.3, -1.0, 0.0).normalize(), radius: 0.5 },
            Shape::Sphere { centre: Vec3::new(0.0, 1.2, 0.5), radius: 0.4 },
        ];
        for s in shapes {
            for k in 0..64 {
                let Some(smp) = s.sample(Vec3::ZERO, sobol_2d(k, 9), Vec3::ONE) else { continue };
                let h = s.hit(Vec3::ZERO, smp.l, f32::INFINITY, Vec3::ONE).expect("the sample's ray hits");
                assert!((h.t - smp.t).abs() < 1e-4 * smp.t && (h.pdf - smp.pdf).abs() < 1e-3 * smp.pdf, "{s:?}: {h:?} against {smp:?}");
            }
        }
    }
}
