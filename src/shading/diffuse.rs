//! Lambert's diffuse BRDF in physical units.
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `diffuse` ρ | [0, 1] RGB (or a scalar for grey) | 0.5 here (Mitsuba's); a lesson's default is 0.8 | albedo: the fraction of incident light scattered back |
//!
//! f(l, v) = ρ / π   (1/sr), so that ∫ f cos θ_l dω_l = ρ for every viewing direction.
//!
//! Source: Lambert 1760 (the cosine law); the 1/π normalization follows from ∫ cos θ dω = π
//! (pbrt-v4 `DiffuseBxDF`, Mitsuba 3 `diffuse`). The course's classic term K_diff max(N·L, 0)
//! ([`lambert`](super::lambert)) is this BRDF times π times the cosine. One-sided: f = 0 when
//! n·l ≤ 0 or n·v ≤ 0. No clamps.
//!
//! **Lobes and sampling** ([`super::lobe`]): one diffuse lobe of weight ρ, the whole f in the
//! diffuse part. Sampled by the cosine-weighted hemisphere (Malley's method, pbrt-v4
//! `SampleCosineHemisphere`), pdf cos θ_l/π, so f cos θ_l / pdf = ρ exactly.

use super::lobe::{Lobe, LobeKind, LobeSet};
use glam::Vec3;
use std::f32::consts::FRAC_1_PI;

/// The Lambert BRDF ρ/π.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Diffuse {
    /// Albedo ρ per channel.
    pub albedo: Vec3,
}

impl Default for Diffuse {
    /// ρ = 0.5 (grey), as Mitsuba 3's default `reflectance`.
    fn default() -> Self {
        Diffuse { albedo: Vec3::splat(0.5) }
    }
}

impl Diffuse {
    /// f(l, v) = ρ/π for unit `l`, `v` above the surface (local frame, z = normal), else 0.
    #[inline]
    pub fn eval(&self, l: Vec3, v: Vec3) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        lambert_brdf(self.albedo)
    }

    /// One diffuse lobe of weight ρ.
    pub fn lobes(&self) -> LobeSet {
        LobeSet::new(&[Lobe::new(LobeKind::Diffuse, self.albedo)])
    }
}

/// ρ/π: the value of the Lambert BRDF for albedo `rho`.
#[inline]
pub fn lambert_brdf(rho: Vec3) -> Vec3 {
    rho * FRAC_1_PI
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_above_zero_below() {
        let d = Diffuse { albedo: Vec3::new(0.8, 0.4, 0.2) };
        let up = Vec3::new(0.1, 0.2, 0.9).normalize();
        assert_eq!(d.eval(up, Vec3::Z), d.albedo * FRAC_1_PI);
        assert_eq!(d.eval(Vec3::new(1.0, 0.0, 0.0), Vec3::Z), Vec3::ZERO);
        assert_eq!(d.eval(up, -up), Vec3::ZERO);
    }
}
