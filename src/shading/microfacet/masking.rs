//! Masking-shadowing G(l, v, h): the fraction of the facets with normal h that are visible
//! from both the light and the viewer.
//!
//! | parameter | values | default | meaning |
//! | --- | --- | --- | --- |
//! | `masking` | `cook_torrance`, `smith`, `smith_correlated` | `smith` | which G |
//!
//! | name | G(l, v, h) | source |
//! | --- | --- | --- |
//! | `cook_torrance` (V-cavity) | min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)) | Cook & Torrance 1982, the geometrical attenuation factor G (after Blinn 1977) |
//! | `smith` (separable) | G1(l, h) · G1(v, h), G1 = χ⁺(w·h)/(1 + Λ(w)) | Smith 1967; Walter et al. 2007, eq. 23 |
//! | `smith_correlated` (height-correlated) | χ⁺(l·h) χ⁺(v·h) / (1 + Λ(l) + Λ(v)) | Heitz 2014, eq. 99 |
//!
//! Λ comes from the distribution ([`Ndf::lambda`]). `smith` is what Mitsuba 3 and Walter et al.
//! use; `smith_correlated` is the more accurate form recommended by Heitz 2014 (it is larger
//! than the separable product because masking and shadowing are correlated through height).
//!
//! **Visibility form.** Renderers need V = G / (4 (n·l)(n·v)). Dividing G by two tiny cosines
//! loses precision and overflows, so V is built from Λ(w)·cos θ (finite everywhere):
//!
//! - separable: V = 1 / (4 (n·l + Λ_l n·l)(n·v + Λ_v n·v));
//! - correlated: V = 1 / (4 ((n·l)(n·v) + (n·v) Λ_l n·l + (n·l) Λ_v n·v));
//! - V-cavity: V = G / (4 (n·l)(n·v)).
//!
//! Clamp: every cosine in a V denominator is at least [`COS_FLOOR`] = 1e-19, so V ≤ 2.5e37 stays
//! finite (the V-cavity and correlated forms grow like 1/cos² and 1/cos at grazing).

use super::ndf::Ndf;
use super::{COS_FLOOR, half_vector_and_cos};
use glam::Vec3;

/// The masking-shadowing functions (a closed set, dispatched with `match`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Masking {
    /// Cook-Torrance V-cavity: min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)).
    CookTorrance,
    /// Separable Smith: G1(l) G1(v) (Mitsuba 3, Walter et al. 2007).
    #[default]
    Smith,
    /// Height-correlated Smith: 1 / (1 + Λ(l) + Λ(v)) (Heitz 2014).
    SmithCorrelated,
}

impl Masking {
    /// All masking functions, for tests and figures.
    pub const ALL: [Masking; 3] = [Masking::CookTorrance, Masking::Smith, Masking::SmithCorrelated];

    /// The lesson-file name (`cook_torrance`, `smith`, `smith_correlated`).
    pub fn name(self) -> &'static str {
        match self {
            Masking::CookTorrance => "cook_torrance",
            Masking::Smith => "smith",
            Masking::SmithCorrelated => "smith_correlated",
        }
    }

    /// G(l, v, h) in [0, 1] for unit `l`, `v` and microfacet normal `h` (local frame).
    #[inline]
    pub fn g(self, ndf: Ndf, l: Vec3, v: Vec3, h: Vec3, alpha: f32) -> f32 {
        match self {
            Masking::CookTorrance => v_cavity(l, v, h),
            Masking::Smith => smith_separable(ndf, l, v, h, alpha),
            Masking::SmithCorrelated => smith_correlated(ndf, l, v, h, alpha),
        }
    }

    /// V = G / (4 (n·l)(n·v)) in 1/sr-free units, computed without dividing by tiny cosines.
    ///
    /// Preconditions: `l.z > 0`, `v.z > 0`, `h` = normalize(l + v).
    #[inline]
    pub fn visibility(self, ndf: Ndf, l: Vec3, v: Vec3, h: Vec3, alpha: f32) -> f32 {
        match self {
            Masking::CookTorrance => v_cavity_visibility(l, v, h),
            Masking::Smith => separable_visibility(l.z, v.z, ndf.lambda_cos(l, alpha), ndf.lambda_cos(v, alpha)),
            Masking::SmithCorrelated => correlated_visibility(l.z, v.z, ndf.lambda_cos(l, alpha), ndf.lambda_cos(v, alpha)),
        }
    }
}

/// Cook-Torrance V-cavity G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)), clamped at 0.
///
/// 0 when v·h ≤ 0 (then l = −v and no facet reflects l into v).
#[inline]
pub fn v_cavity(l: Vec3, v: Vec3, h: Vec3) -> f32 {
    let vh = v.dot(h);
    if vh <= 0.0 {
        return 0.0;
    }
    (2.0 * h.z * l.z.min(v.z) / vh).clamp(0.0, 1.0)
}

/// V-cavity visibility G / (4 (n·l)(n·v)) with both cosines at least [`COS_FLOOR`].
///
/// Precondition: `h` = normalize(l + v); v·h is then evaluated as |l + v|/2
/// ([`half_vector_and_cos`]), which is exact, symmetric in l and v and free of cancellation.
#[inline]
pub fn v_cavity_visibility(l: Vec3, v: Vec3, h: Vec3) -> f32 {
    let (_, vh) = half_vector_and_cos(l, v);
    let g = (2.0 * h.z * l.z.min(v.z) / vh).clamp(0.0, 1.0);
    g / (4.0 * l.z.max(COS_FLOOR) * v.z.max(COS_FLOOR))
}

/// Separable Smith G = G1(l, h) G1(v, h).
#[inline]
pub fn smith_separable(ndf: Ndf, l: Vec3, v: Vec3, h: Vec3, alpha: f32) -> f32 {
    ndf.g1(l, h, alpha) * ndf.g1(v, h, alpha)
}

/// Height-correlated Smith G = χ⁺(l·h) χ⁺(v·h) / (1 + Λ(l) + Λ(v)) (Heitz 2014, eq. 99).
#[inline]
pub fn smith_correlated(ndf: Ndf, l: Vec3, v: Vec3, h: Vec3, alpha: f32) -> f32 {
    if l.dot(h) * l.z <= 0.0 || v.dot(h) * v.z <= 0.0 {
        return 0.0;
    }
    1.0 / (1.0 + ndf.lambda(l, alpha) + ndf.lambda(v, alpha))
}

/// Separable Smith visibility 1 / (4 (n·l + Λ_l n·l)(n·v + Λ_v n·v)) from the cosines
/// `n_dot_l`, `n_dot_v` and Λ·cos of each direction; each factor is at least [`COS_FLOOR`].
#[inline]
pub fn separable_visibility(n_dot_l: f32, n_dot_v: f32, lambda_cos_l: f32, lambda_cos_v: f32) -> f32 {
    let a = (n_dot_l + lambda_cos_l).max(COS_FLOOR);
    let b = (n_dot_v + lambda_cos_v).max(COS_FLOOR);
    1.0 / (4.0 * a * b)
}

/// Height-correlated visibility 1 / (4 ((n·l)(n·v) + (n·v) Λ_l n·l + (n·l) Λ_v n·v)), with
/// both cosines at least [`COS_FLOOR`].
#[inline]
pub fn correlated_visibility(n_dot_l: f32, n_dot_v: f32, lambda_cos_l: f32, lambda_cos_v: f32) -> f32 {
    let nl = n_dot_l.max(COS_FLOOR);
    let nv = n_dot_v.max(COS_FLOOR);
    1.0 / (4.0 * (nl * nv + nv * lambda_cos_l + nl * lambda_cos_v))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    #[test]
    fn visibility_equals_g_over_four_cosines() {
        let l = dir(0.7, 0.2);
        let v = dir(1.1, 2.9);
        let h = (l + v).normalize();
        for ndf in Ndf::ALL {
            for m in Masking::ALL {
                let g = m.g(ndf, l, v, h, 0.4);
                let vis = m.visibility(ndf, l, v, h, 0.4);
                assert!((vis / (g / (4.0 * l.z * v.z)) - 1.0).abs() < 1e-5, "{ndf:?} {m:?}");
            }
        }
    }

    #[test]
    fn correlated_is_at_least_separable() {
        let l = dir(1.3, 0.0);
        let v = dir(1.2, 2.0);
        let h = (l + v).normalize();
        let sep = smith_separable(Ndf::Ggx, l, v, h, 0.8);
        let cor = smith_correlated(Ndf::Ggx, l, v, h, 0.8);
        assert!(cor >= sep && cor <= 1.0);
    }

    #[test]
    fn no_masking_at_normal_incidence() {
        let h = Vec3::Z;
        for m in Masking::ALL {
            assert_eq!(m.g(Ndf::Ggx, Vec3::Z, Vec3::Z, h, 1.0), 1.0, "{m:?}");
        }
    }

    #[test]
    fn grazing_visibility_is_finite() {
        let l = Vec3::new(1.0, 0.0, 1e-30).normalize();
        let v = Vec3::new(-1.0, 0.0, 1e-30).normalize();
        let h = super::super::half_vector(l, v);
        assert_eq!(h, Vec3::Z);
        for ndf in Ndf::ALL {
            for m in Masking::ALL {
                let vis = m.visibility(ndf, l, v, h, 1e-4);
                assert!(vis.is_finite() && vis >= 0.0, "{ndf:?} {m:?} {vis}");
            }
        }
    }
}
