//! The smooth dielectric (`glass`): Fresnel-weighted reflection plus refraction.
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `ior` η | 0.1 to 10, one number or `[r, g, b]` | 1.5 | index of the glass relative to the medium around it (air: 1); per channel for dispersion; η < 1 is a bubble of a thinner medium (total internal reflection from outside) |
//! | `thin` | bool | false | one interface only (the course's "surface only" panels): the refracted ray never meets the object again |
//! | `tint` | [0, 1]³ | 1 | multiplies the light at each refraction (Mitsuba's `specular_transmittance`) |
//!
//! At an interface with cos θ_i = n·v and relative index η = η_t/η_i, a share
//! F = F_dielectric(cos θ_i, η) (exact unpolarized Fresnel, Walter et al. 2007 eq. 22) leaves
//! along r = 2(n·v)n − v and 1 − F along the refracted t (Snell, n₁ sin θ₁ = n₂ sin θ₂);
//! under total internal reflection F = 1. The BSDF is a pair of Dirac deltas, so no point or
//! area light is seen through it: render traces both rays (the reflection and transmission
//! layers). The radiance factor 1/η² of a refraction is left out: on a path that enters and
//! leaves it cancels, and a `thin` surface is a teaching device, not a physical slab.

use super::microfacet::fresnel::dielectric;
use glam::Vec3;

/// A smooth dielectric interface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Glass {
    /// η per channel (all three equal without dispersion).
    pub ior: Vec3,
    /// One interface only: the refracted ray does not meet the object again.
    pub thin: bool,
    /// Multiplies the transmitted light at each refraction.
    pub tint: Vec3,
}

impl Glass {
    /// True when the channels refract differently (dispersion): render traces each channel.
    pub fn disperses(&self) -> bool {
        self.ior.x != self.ior.y || self.ior.y != self.ior.z
    }
}

/// The Fresnel split at an interface: (R, T) with R + T = 1, for cos θ_i (clamped to [0, 1])
/// and the relative index `eta` = η_t/η_i; R = 1 under total internal reflection.
#[inline]
pub fn fresnel_split(cos_theta_i: f32, eta: f32) -> (f32, f32) {
    let r = dielectric(cos_theta_i, eta);
    (r, 1.0 - r)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Energy: what is not reflected is transmitted, at every angle and index, and nothing is NaN.
    #[test]
    fn reflection_plus_transmission_is_one_and_finite() {
        for eta in [0.1f32, 1.0 / 1.5, 0.999, 1.0, 1.0001, 1.05, 1.2, 1.5, 2.4, 10.0] {
            for k in 0..=1000 {
                let c = k as f32 / 1000.0;
                let (r, t) = fresnel_split(c, eta);
                assert!(
                    r.is_finite() && t.is_finite() && (0.0..=1.0).contains(&r) && (0.0..=1.0).contains(&t),
                    "η {eta}, cos {c}: {r} {t}"
                );
                assert!((r + t - 1.0).abs() < 1e-6);
            }
            // Grazing incidence reflects everything; η = 1 reflects nothing.
            assert!((fresnel_split(0.0, eta).0 - if eta == 1.0 { 0.0 } else { 1.0 }).abs() < 1e-6, "η {eta}");
        }
        // Normal incidence: ((η − 1)/(η + 1))², 0.04 for η = 1.5 (Hecht, Optics §4.6).
        assert!((fresnel_split(1.0, 1.5).0 - 0.04).abs() < 1e-6);
        assert!((fresnel_split(1.0, 1.0 / 1.5).0 - 0.04).abs() < 1e-6);
    }

    /// From the denser side (η < 1) beyond the critical angle everything is reflected.
    #[test]
    fn total_internal_reflection_beyond_the_critical_angle() {
        let eta = 1.0 / 1.5;
        let critical = (1.0f32 / 1.5).asin(); // θ_c = arcsin(n₂/n₁)
        assert_eq!(fresnel_split((critical + 1e-3).cos(), eta), (1.0, 0.0));
        assert!(fresnel_split((critical - 1e-3).cos(), eta).0 < 1.0);
    }
}
