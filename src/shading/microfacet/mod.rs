//! Microfacet theory: the one home for the normal distribution D, the masking-shadowing G
//! (with Smith's Λ) and the Fresnel factor F shared by every physically based model.
//!
//! A rough surface is a field of tiny mirrors (microfacets) with normals `m` distributed by
//! D(m). Light from `l` reaches the viewer at `v` only through facets with `m = h`, the half
//! vector, so the single-scattering BRDF is (Walter et al. 2007, eq. 20)
//!
//! f(l, v) = D(h) · G(l, v, h) · F(v·h) / (4 (n·l)(n·v)),  h = normalize(l + v)
//!
//! All functions work in the local shading frame: z is the surface normal `n`, so `n·w = w.z`.
//! Directions are unit vectors pointing away from the surface (docs/conventions.md).
//!
//! | file | contents |
//! | --- | --- |
//! | [`ndf`] | D: normalized Blinn, Beckmann, GGX (isotropic and anisotropic), Gaussian, GTR1; Smith Λ |
//! | [`masking`] | G: Cook-Torrance V-cavity, separable Smith, height-correlated Smith |
//! | [`fresnel`] | F: Schlick, exact dielectric, exact conductor (complex η + ik) |
//! | [`sample`] | importance sampling of h (GGX visible normals, D·cos θ_h per NDF, GTR1, cosine powers) and the pdf of l |
//!
//! Roughness: `alpha` (α) is the width parameter of Walter et al. 2007; when a lesson gives
//! `roughness`, α = roughness² ([`alpha_from_roughness`]), as in Mitsuba 3 and pbrt-v4.

pub mod fresnel;
pub mod masking;
pub mod ndf;
pub mod sample;

pub use fresnel::Fresnel;
pub use masking::Masking;
pub use ndf::Ndf;

/// Smallest α used by the distributions (α = 0, a perfect mirror, is a Dirac delta that no
/// finite function can represent); below it α is raised to this value.
///
/// Measured in f32 (tests/integration/stability/finite.rs, `clamp_thresholds_are_measured`): in the
/// hard case n·l = n·v = 1e-7 at the mirror configuration, the V-cavity lobe
/// D/(4 (n·l)(n·v)) = 1/(4π α² 10⁻¹⁴) exceeds f32::MAX (3.4e38) for α < 1.5e-13 (the
/// distributions alone would survive down to α ≈ 1e-19, where α² turns subnormal). 1e-12 keeps
/// every hard case finite with a 40× margin; the lobe is then 2e-12 rad wide, far below what
/// f32 directions resolve (6e-8 rad), so it is invisible in a render, as a delta would be.
pub const ALPHA_MIN: f32 = 1e-12;

/// Smallest cosine used in the denominators of the visibility terms V = G / (4 (n·l)(n·v)).
///
/// 1/(4 cos²) stays below f32::MAX (3.4e38) for cos ≥ 2.7e-20; the floor keeps V finite so
/// that a zero D or F can never meet an infinite V (0·∞ = NaN). It changes V only for
/// directions within 1e-19 rad of the horizon, where f·cos θ is negligible anyway.
pub const COS_FLOOR: f32 = 1e-19;

/// α = roughness² (Walter et al. 2007 parameterization as used by Mitsuba 3 and pbrt-v4).
#[inline]
pub fn alpha_from_roughness(roughness: f32) -> f32 {
    roughness * roughness
}

/// α raised to [`ALPHA_MIN`] (α = 0 would be a Dirac delta).
#[inline]
pub fn clamp_alpha(alpha: f32) -> f32 {
    alpha.max(ALPHA_MIN)
}

/// The half vector h = normalize(l + v) of two directions in the upper hemisphere.
///
/// Preconditions: `l.z > 0` and `v.z > 0`, so |l + v| ≥ l.z + v.z > 0 and h.z > 0.
#[inline]
pub fn half_vector(l: glam::Vec3, v: glam::Vec3) -> glam::Vec3 {
    half_vector_and_cos(l, v).0
}

/// The half vector h = normalize(l + v) and cos θ_d = v·h = l·h, evaluated as |l + v|/2.
///
/// For unit vectors v·h = (1 + l·v)/|l + v| = |l + v|/2 exactly; the second form has no
/// cancellation when l ≈ −v (near the horizon the dot product v·h loses all its digits, and
/// l·h and v·h then differ, breaking reciprocity). l + v is divided by its largest component
/// first, so it normalizes even when its squared length underflows (l + v = (0, 0, 2e-30)).
/// Preconditions: `l.z > 0` and `v.z > 0`.
#[inline]
pub fn half_vector_and_cos(l: glam::Vec3, v: glam::Vec3) -> (glam::Vec3, f32) {
    let s = l + v;
    let m = s.abs().max_element();
    let scaled = s / m;
    let len = scaled.length();
    (scaled / len, 0.5 * len * m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn half_vector_cosine_is_exact_and_symmetric() {
        let l = Vec3::new(0.3, -0.4, 0.5).normalize();
        let v = Vec3::new(-0.6, 0.1, 0.2).normalize();
        let (h, c) = half_vector_and_cos(l, v);
        assert!((h.length() - 1.0).abs() < 1e-6);
        assert!((c - v.dot(h)).abs() < 1e-6 && (c - l.dot(h)).abs() < 1e-6);
        assert_eq!(half_vector_and_cos(v, l), (h, c));
        // l ≈ −v just above the horizon: |l + v|² underflows, h is still the normal.
        let l = Vec3::new(1.0, 0.0, 1e-30);
        let v = Vec3::new(-1.0, 0.0, 1e-30);
        let (h, c) = half_vector_and_cos(l, v);
        assert_eq!(h, Vec3::Z);
        assert!((c / 1e-30 - 1.0).abs() < 1e-6);
    }

    #[test]
    fn alpha_from_roughness_and_floor() {
        assert_eq!(alpha_from_roughness(0.5), 0.25);
        assert_eq!(clamp_alpha(0.0), ALPHA_MIN);
        assert_eq!(clamp_alpha(0.3), 0.3);
    }
}
