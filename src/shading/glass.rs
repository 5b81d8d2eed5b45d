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
//!
//! **Lobes and sampling** ([`super::lobe`]): a delta-reflection lobe of weight F̄ and a
//! delta-transmission lobe of weight tint ⊗ (1 − F̄), F̄ = F0 + (1 − F0)/21 per channel with
//! F0 = ((η − 1)/(η + 1))² (an estimate: no diffuse or specular part). [`Glass::sample`] is the
//! path tracer's version of render's split (`render/glass.rs`): in the local frame with z the
//! **outward** normal, v.z ≥ 0 is outside (η = ior) and v.z < 0 inside (η = 1/ior; a `thin`
//! surface keeps η = ior from both sides, as render does). It reflects with probability F
//! (F = 1 under total internal reflection, where `refract` fails) and refracts otherwise, so
//! the weights are F/F = 1 for the reflection and (1 − F) tint/(1 − F) = tint for the
//! refraction: the expected value is render's F L(r) + (1 − F) tint L(t). The radiance
//! factor 1/η² of pbrt-v4's `DielectricBxDF` (radiance mode) is left out, as render leaves it
//! out (see above): a path tracer using this sample matches render's pictures.

use super::lobe::{DeltaSample, Lobe, LobeKind, LobeSet};
use super::microfacet::fresnel::{dielectric, f0_from_ior};
use crate::geometry::vector::refract;
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
    /// 0 for the smooth interface; above, GGX microfacets that reflect and refract (Walter et
    /// al. 2007, [`super::rough_dielectric`]), which only the path tracer draws.
    pub roughness: f32,
}

impl Glass {
    /// True when the channels refract differently (dispersion): render traces each channel.
    pub fn disperses(&self) -> bool {
        self.ior.x != self.ior.y || self.ior.y != self.ior.z
    }

    /// The reflection (weight F̄) and transmission (weight tint ⊗ (1 − F̄)) lobes, F̄ per channel.
    pub fn lobes(&self) -> LobeSet {
        let f0 = Vec3::new(f0_from_ior(self.ior.x), f0_from_ior(self.ior.y), f0_from_ior(self.ior.z));
        let f = f0 + (Vec3::ONE - f0) * (1.0 / 21.0);
        LobeSet::new(&[Lobe::new(LobeKind::DeltaReflection, f), Lobe::new(LobeKind::DeltaTransmission, self.tint * (Vec3::ONE - f))])
    }

    /// Reflection with probability F, else refraction, for unit `v` in the local frame (z the
    /// outward normal; module docs), `u_lobe` in [0, 1) choosing. `channel` picks the index of
    /// that colour channel (dispersion: the caller follows one channel per path and keeps only
    /// its component); `None` uses the first, as render does without dispersion. The weight is
    /// 1 (reflection) or `tint` (refraction), for every channel. `None` for a non-finite v.
    #[inline]
    pub fn sample(&self, v: Vec3, u_lobe: f32, channel: Option<usize>) -> Option<DeltaSample> {
        if !v.is_finite() {
            return None;
        }
        let ior = self.ior[channel.unwrap_or(0).min(2)];
        // The normal on v's side and the relative index η = η_t/η_i seen from there.
        let (n, eta) = if v.z >= 0.0 {
            (Vec3::Z, ior)
        } else if self.thin {
            (-Vec3::Z, ior)
        } else {
            (-Vec3::Z, 1.0 / ior)
        };
        let (mut r, _) = fresnel_split(n.dot(v), eta);
        let refracted = refract(v, n, eta);
        if refracted.is_none() {
            r = 1.0; // total internal reflection (refract and Fresnel agree up to rounding at θ_c)
        }
        match refracted {
            Some(t) if u_lobe >= r => {
                Some(DeltaSample { l: t, weight: self.tint, probability: 1.0 - r, kind: LobeKind::DeltaTransmission })
            }
            _ => Some(DeltaSample { l: Vec3::new(-v.x, -v.y, v.z), weight: Vec3::ONE, probability: r, kind: LobeKind::DeltaReflection }),
        }
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

    /// Sampling reproduces render's split: P(reflect) = F, weights 1 and tint, so the mean of
    /// the weighted radiance is F L_r + (1 − F) tint L_t; refraction follows Snell's law; total
    /// internal reflection inside always reflects with weight 1; no 1/η² factor.
    #[test]
    fn sample_matches_the_fresnel_split() {
        let g = Glass { ior: Vec3::splat(1.5), thin: false, tint: Vec3::new(0.9, 0.8, 0.7), roughness: 0.0 };
        let (l_r, l_t) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(5.0, 7.0, 11.0));
        for theta in [0.0f32, 0.4, 1.0, 1.5] {
            for inside in [false, true] {
                let v = Vec3::new(theta.sin(), 0.0, if inside { -theta.cos() } else { theta.cos() });
                let eta = if inside { 1.0 / 1.5 } else { 1.5 };
                let (f, _) = fresnel_split(theta.cos(), eta);
                let tir = crate::geometry::vector::refract(v, if inside { -Vec3::Z } else { Vec3::Z }, eta).is_none();
                let f = if tir { 1.0 } else { f };
                let n = 100_000;
                let mut mean = glam::DVec3::ZERO;
                for k in 0..n {
                    let s = g.sample(v, (k as f32 + 0.5) / n as f32, None).unwrap();
                    let radiance = if s.kind == LobeKind::DeltaReflection {
                        assert_eq!((s.l, s.weight, s.probability), (Vec3::new(-v.x, -v.y, v.z), Vec3::ONE, f));
                        l_r
                    } else {
                        // Snell: η_i sin θ_i = η_t sin θ_t, on the far side.
                        let sin_t = (s.l.x * s.l.x + s.l.y * s.l.y).sqrt();
                        assert!((sin_t * eta - theta.sin()).abs() < 1e-5 && s.l.z * v.z < 0.0, "θ={theta} inside={inside}: {}", s.l);
                        assert_eq!((s.weight, s.probability), (g.tint, 1.0 - f));
                        l_t
                    };
                    mean += (s.weight * radiance).as_dvec3() / n as f64;
                }
                let want = (f * l_r + (1.0 - f) * g.tint * l_t).as_dvec3();
                // Stratified u: the reflected share is F to within 1/n.
                assert!((mean - want).abs().max_element() < 2e-4 * want.max_element(), "θ={theta} inside={inside}: {mean} vs {want}");
                assert_eq!(tir, inside && theta > (1.0f32 / 1.5).asin(), "θ={theta}");
            }
        }
        // Thin: the same η from both sides; dispersion: the channel's index.
        let thin = Glass { thin: true, ..g };
        let v = Vec3::new(0.6, 0.0, -0.8);
        assert_eq!(thin.sample(v, 0.99, None).unwrap().l, crate::geometry::vector::refract(v, -Vec3::Z, 1.5).unwrap());
        let prism = Glass { ior: Vec3::new(1.4, 1.5, 1.6), ..g };
        let (t0, t2) = (prism.sample(v, 0.99, Some(0)).unwrap().l, prism.sample(v, 0.99, Some(2)).unwrap().l);
        assert!(t0 != t2 && prism.sample(v, 0.99, None).unwrap().l == t0);
        assert!(g.sample(Vec3::NAN, 0.5, None).is_none());
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
