//! Area, line and sky lights: what one sample of the emitter delivers at a shaded point.
//!
//! Which light paths it counts: direct light from the emitter, one-sided where the kind is
//! (rect, disk), visibility left to the caller. Each sample carries its share of the solid
//! angle, dω = A cos θ_l / (r² N) for a point q sampled uniformly on an emitter of area A
//! (θ_l between the emitter's normal and the way to the shaded point), so that
//! - physically based shading, L_o = Σ f L_e cos θ dω, estimates ∫ f L_e cos θ dω;
//! - the classic equation, K_diff ⊗ L_e Σ cos θ dω, estimates the course's K_diff ⊗ L_e·A′
//!   with A′ = ∫ cos θ dω the light's projected solid angle (no π), and its specular term
//!   the sampled sum Σ K_spec (R·V)^K_shi L_e dω.
//!
//! Samples are stratified and deterministic: sample k of N is the R2 sequence rotated by a
//! hash of the shaded point and the light ([`crate::geometry::sampling::sample_2d`]).
//! A sphere is sampled by the cone it subtends (pbrt-v4 `SphereShape::Sample`), the sky by
//! cosine-weighted directions about the normal (Malley's method).

use crate::geometry::sampling::{basis, concentric_disk, cosine_hemisphere, sample_2d, uniform_cone};
use crate::lesson::light::{Light, LightKind};
use glam::Vec3;
use std::f32::consts::PI;

/// One sample of a sampled light as seen from a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaSample {
    /// Unit direction from the point towards the sample.
    pub l: Vec3,
    /// Distance to the emitter along `l` (infinite for the sky).
    pub distance: f32,
    /// This sample's solid angle dω, already divided by the sample count; 0 when it sends
    /// no light to the point (the back of a one-sided emitter).
    pub weight: f32,
    /// Radiance L_e arriving along `l`.
    pub radiance: Vec3,
}

impl AreaSample {
    const NONE: AreaSample = AreaSample { l: Vec3::Z, distance: 0.0, weight: 0.0, radiance: Vec3::ZERO };
}

impl Light {
    /// Sample `k` of this light's `samples`, seen from point `p` with unit normal `n`, with
    /// the sample pattern `seed`. Precondition: the kind is sampled ([`LightKind::is_sampled`]).
    pub fn area_sample(&self, p: Vec3, n: Vec3, k: u32, seed: u32) -> AreaSample {
        let u = sample_2d(k, seed);
        let per = 1.0 / self.samples.max(1) as f32;
        let le = self.radiance;
        match self.kind {
            LightKind::Rect { position, direction, half_w, half_h } => {
                let q = position + half_w * (2.0 * u.x - 1.0) + half_h * (2.0 * u.y - 1.0);
                let area = 4.0 * half_w.length() * half_h.length();
                towards(p, q, Some(direction), area * per, le)
            }
            LightKind::Disk { position, direction, radius } => {
                let d = concentric_disk(u);
                let (t, b) = basis(direction);
                towards(p, position + (t * d.x + b * d.y) * radius, Some(direction), PI * radius * radius * per, le)
            }
            LightKind::Sphere { position, radius } => sphere(p, position, radius, u, per, le),
            LightKind::Line { start, end, radius } => {
                let axis = end - start;
                let len = axis.length();
                let q = start + axis * u.x;
                let to = q - p;
                // Inside the tube the point sees it at its radius.
                let r = to.length().max(radius);
                let l = (to / r).normalize_or_zero();
                if l == Vec3::ZERO {
                    return AreaSample::NONE;
                }
                // A thin tube's length element dx seen from r: projected area 2R·sin φ·dx
                // (φ between the axis and l), solid angle 2R sin φ dx / r².
                let sin = l.cross(axis / len).length();
                AreaSample { l, distance: to.length(), weight: 2.0 * radius * len * sin / (r * r) * per, radiance: le }
            }
            LightKind::Sky { ground } => {
                // Cosine-weighted about n (pdf cos θ/π): dω = π/(N cos θ), so a Lambertian
                // receiver under an unblocked sky of one colour gets exactly π L_e, no noise.
                let d = cosine_hemisphere(u);
                let (t, b) = basis(n);
                let l = (t * d.x + b * d.y + n * d.z).normalize_or(n);
                // A direction in the tangent plane carries nothing (its N·L is 0 in shading too).
                let weight = if d.z > 1e-6 { PI / d.z * per } else { 0.0 };
                AreaSample { l, distance: f32::INFINITY, weight, radiance: if l.y >= 0.0 { le } else { ground } }
            }
            LightKind::Directional { .. } | LightKind::Point { .. } | LightKind::Spot { .. } | LightKind::Ambient => AreaSample::NONE,
        }
    }

    /// The radiance a sky sample brings from below the horizon (`None` for other kinds).
    pub fn ground(&self) -> Option<Vec3> {
        match self.kind {
            LightKind::Sky { ground } => Some(ground),
            _ => None,
        }
    }
}

/// A point `q` of an emitter (facing `normal` when one-sided) seen from `p`: dω = A cos θ_l / r².
#[inline]
fn towards(p: Vec3, q: Vec3, normal: Option<Vec3>, area: f32, radiance: Vec3) -> AreaSample {
    let to = q - p;
    let r2 = to.length_squared();
    if r2 <= 1e-20 || !r2.is_finite() {
        return AreaSample::NONE;
    }
    let r = r2.sqrt();
    let l = to / r;
    // The emitter sends light towards `normal`: it reaches p when −l·normal > 0.
    let cos_l = normal.map_or(1.0, |nl| -l.dot(nl));
    let weight = if cos_l > 0.0 { area * cos_l / r2 } else { 0.0 };
    AreaSample { l, distance: r, weight, radiance }
}

/// A sphere light sampled by its cone: uniform directions within the half-angle
/// asin(R/d), dω = 2π(1 − cos θ_max)/N; from inside, the whole sphere of directions.
fn sphere(p: Vec3, centre: Vec3, radius: f32, u: glam::Vec2, per: f32, le: Vec3) -> AreaSample {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::settings::ShadowMethod;

    fn light(kind: LightKind, samples: u32) -> Light {
        Light { kind, radiance: Vec3::ONE, ambient: Vec3::ZERO, attenuation: Vec3::X, samples, shadows: None::<ShadowMethod> }
    }

    /// A sampled light's projected solid angle A′ = Σ cos θ dω at p (normal n), averaged over
    /// `seeds` patterns.
    fn projected(l: &Light, p: Vec3, n: Vec3, seeds: u32) -> f64 {
        let mut sum = 0.0;
        for seed in 0..seeds {
            for k in 0..l.samples {
                let s = l.area_sample(p, n, k, crate::geometry::sampling::hash(seed + 1));
                sum += (s.weight * s.l.dot(n).max(0.0)) as f64;
            }
        }
        sum / seeds as f64
    }

    /// On the axis of a disk of radius R at height h, facing it: A′ = π R²/(h² + R²).
    #[test]
    fn a_disk_gives_its_analytic_projected_solid_angle() {
        let (r, h) = (0.5f32, 2.0f32);
        let disk = light(LightKind::Disk { position: Vec3::new(0.0, h, 0.0), direction: -Vec3::Y, radius: r }, 64);
        let want = std::f64::consts::PI * (r * r / (h * h + r * r)) as f64;
        let got = projected(&disk, Vec3::ZERO, Vec3::Y, 64);
        assert!((got - want).abs() < 2e-3 * want, "{got} vs {want}");
        // One-sided: from above (behind the emitting side) nothing arrives.
        assert_eq!(projected(&disk, Vec3::new(0.0, 2.0 * h, 0.0), -Vec3::Y, 4), 0.0);
    }

    /// A sphere of radius r at distance d over a point facing it: A′ = π (r/d)² (E = πL(r/d)²),
    /// to rounding whatever the sample count (the cone is sampled, and cos is nearly 1 in it).
    #[test]
    fn a_sphere_gives_pi_r_over_d_squared() {
        for (r, d) in [(0.5f32, 2.0f32), (0.01, 10.0), (1.0, 1.001)] {
            let s = light(LightKind::Sphere { position: Vec3::new(0.0, d, 0.0), radius: r }, 256);
            let want = std::f64::consts::PI * (r as f64 / d as f64).powi(2);
            let got = projected(&s, Vec3::ZERO, Vec3::Y, 4);
            assert!((got - want).abs() < 3e-3 * want, "r {r} d {d}: {got} vs {want}");
        }
    }

    /// A sky of one colour over a surface facing up: A′ = π exactly (cosine-weighted samples).
    #[test]
    fn a_sky_over_a_floor_gives_pi() {
        let sky = light(LightKind::Sky { ground: Vec3::ONE }, 7);
        assert!((projected(&sky, Vec3::ZERO, Vec3::Y, 3) - std::f64::consts::PI).abs() < 1e-4);
    }

    /// Every kind gives finite, non-negative samples for points on, inside and far from the
    /// emitter and for degenerate normals.
    #[test]
    fn samples_are_finite_everywhere() {
        let kinds = [
            LightKind::Rect { position: Vec3::ZERO, direction: -Vec3::Y, half_w: Vec3::X * 0.5, half_h: Vec3::Z * 0.5 },
            LightKind::Disk { position: Vec3::ZERO, direction: -Vec3::Y, radius: 1e-6 },
            LightKind::Sphere { position: Vec3::ZERO, radius: 1.0 },
            LightKind::Line { start: Vec3::ZERO, end: Vec3::X, radius: 0.01 },
            LightKind::Sky { ground: Vec3::ZERO },
        ];
        let points = [Vec3::ZERO, Vec3::new(0.5, 0.0, 0.5), Vec3::new(0.2, 0.0, 0.0), Vec3::splat(1e6), Vec3::new(0.0, -1e-7, 0.0)];
        for kind in kinds {
            let l = light(kind, 8);
            for p in points {
                for n in [Vec3::Y, -Vec3::Y, Vec3::X] {
                    for k in 0..8 {
                        let s = l.area_sample(p, n, k, 12345);
                        assert!(
                            s.weight.is_finite() && s.weight >= 0.0 && s.l.is_finite() && !s.distance.is_nan(),
                            "{kind:?} at {p}: {s:?}"
                        );
                    }
                }
            }
        }
    }
}
