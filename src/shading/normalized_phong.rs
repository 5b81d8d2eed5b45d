//! Normalized Phong and Blinn-Phong: the course's classic lobes made into BRDFs, the bridge
//! from classic to physically based shading.
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `diffuse` k_d | [0, 1] RGB | 0.5 | albedo of the Lambert term k_d/π |
//! | `specular` k_s | [0, 1] RGB | 0.5 | albedo of the specular lobe at its best incidence |
//! | `shininess` n | [0, 1e6] | 32 | lobe exponent K_shi |
//!
//! Normalized Phong (modified Phong of Lewis 1994 and Lafortune & Willems 1994):
//! f = k_d/π + k_s (n + 2)/(2π) cos^n α_r,   cos α_r = R·V,  R = 2(N·L)N − L.
//! (n + 2)/(2π) makes ∫ lobe · cos θ_l dω = 1 at normal incidence, so k_d + k_s ≤ 1 conserves
//! energy for every incidence (the lobe loses energy below the horizon elsewhere). Reciprocal:
//! R(l)·v = R(v)·l.
//!
//! Normalized Blinn-Phong (Akenine-Möller, Haines & Hoffman, *Real-Time Rendering* 3rd ed. 2008,
//! §7.6; derivation in F. Giesen, "Derivation of Phong and Blinn-Phong BRDF normalization
//! factors", 2009): f = k_d/π + k_s (n + 8)/(8π) cos^n θ_h. (n + 8)/(8π) is an approximation of
//! the exact factor (n + 2)(n + 4)/(8π (2^{−n/2} + n)); it is exact at n = 0 and a few percent
//! too large for small n, so k_s = 1 gives an albedo slightly above 1 at normal incidence
//! (measured and printed by the stability suite's `energy_measured_for_the_rest`).
//!
//! Compare the classic terms (course equation, no π): max(R·V, 0)^K_shi grows the reflected energy
//! as K_shi falls and is unnormalized; these BRDFs keep the total constant while the lobe narrows.
//!
//! **Numerics and conventions.** The lobe is clipped to the front half-space: cos^n is 0 where
//! cos ≤ 0 for every n ≥ 0, including n = 0 (the n → 0⁺ limit; the classic `powf` gives
//! 0⁰ = 1 instead), so f is continuous in n. cos^n = exp(n/2 · ln(1 − sin²)), with sin² computed
//! directly (|R × V|² in f64 for Phong; h_x² + h_y² for Blinn-Phong) so that n = 1e6 lobes, whose
//! width is 1e-3 rad, keep f32 relative precision where cos rounds to 1. The shininess is taken
//! as max(n, 0) (a negative exponent is infinite at the lobe's edge). One-sided.
//!
//! **Lobes, parts and sampling** ([`super::lobe`]). Two lobes each, in this order: 0, the
//! Lambert term k_d/π (diffuse, weight k_d, diffuse part), sampled by the cosine-weighted
//! hemisphere, pdf cos θ_l/π; 1, the k_s lobe (glossy, weight k_s, specular part; k_s is its
//! albedo at its best incidence), chosen with probability ∝ the mean of its weight:
//!
//! - Phong: l about the mirror direction r = 2(n·v)n − v with pdf (n + 1)/(2π) cos^n α
//!   (cos α = l·r = R(l)·v), cos α = (1 − ξ)^{1/(n+1)} (Lafortune & Willems 1994, "Using the
//!   modified Phong reflectance model for physically based rendering", §4); the pdf is
//!   (n + 1)/(n + 2) times the lobe, so the lobe alone is sampled in proportion to f.
//! - Blinn-Phong: h with pdf (n + 2)/(2π) cos^{n+1} θ_h (the Blinn NDF times cos θ_h, Walter
//!   et al. 2007, eq. 30), cos θ_h = (1 − ξ)^{1/(n+2)}, l = 2(v·h)h − v, p(l) = p(h)/(4 v·h).
//!
//! Either can reflect l below the surface (lost samples), more so at grazing v.

use super::lobe::{Lobe, LobeKind, LobeSet, cosine_pdf, sample_cosine};
use super::microfacet::ndf::cos_pow;
use super::microfacet::sample::{HalfVector, ONE_MINUS_EPSILON, cos_power_direction};
use glam::{DVec3, Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Normalized Phong BRDF: Lambert plus (n + 2)/(2π) cos^n α_r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalizedPhong {
    /// Diffuse albedo k_d.
    pub diffuse: Vec3,
    /// Specular albedo k_s.
    pub specular: Vec3,
    /// Exponent n.
    pub shininess: f32,
}

/// Normalized Blinn-Phong BRDF: Lambert plus (n + 8)/(8π) cos^n θ_h.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalizedBlinnPhong {
    /// Diffuse albedo k_d.
    pub diffuse: Vec3,
    /// Specular albedo k_s.
    pub specular: Vec3,
    /// Exponent n.
    pub shininess: f32,
}

impl Default for NormalizedPhong {
    /// k_d = k_s = 0.5, n = 32.
    fn default() -> Self {
        NormalizedPhong { diffuse: Vec3::splat(0.5), specular: Vec3::splat(0.5), shininess: 32.0 }
    }
}

impl Default for NormalizedBlinnPhong {
    /// k_d = k_s = 0.5, n = 32.
    fn default() -> Self {
        NormalizedBlinnPhong { diffuse: Vec3::splat(0.5), specular: Vec3::splat(0.5), shininess: 32.0 }
    }
}

impl NormalizedPhong {
    /// f(l, v) in 1/sr for unit `l`, `v` in the local frame (z = normal); 0 below the horizon.
    #[inline]
    pub fn eval(&self, l: Vec3, v: Vec3) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.diffuse * FRAC_1_PI + self.specular * phong_lobe(l, v, self.shininess)
    }

    /// The Lambert term (diffuse, weight k_d) and the Phong lobe (glossy, weight k_s).
    pub fn lobes(&self) -> LobeSet {
        LobeSet::new(&[Lobe::new(LobeKind::Diffuse, self.diffuse), Lobe::new(LobeKind::Glossy, self.specular)])
    }

    /// l drawn from lobe `lobe` (0: cosine, 1: cos^n about the mirror direction of v) for u in
    /// [0, 1)²; `None` below the surface. Precondition: v unit, v.z > 0.
    #[inline]
    pub fn sample_lobe(&self, lobe: usize, v: Vec3, u: Vec2) -> Option<Vec3> {
        if lobe == 0 {
            return sample_cosine(u);
        }
        let r = Vec3::new(-v.x, -v.y, v.z); // 2(n·v)n − v, exact in the local frame
        let d = cos_power_direction(u.clamp(Vec2::ZERO, Vec2::splat(ONE_MINUS_EPSILON)), self.shininess);
        let (t, b) = crate::geometry::sampling::basis(r);
        let l = (d.x * t + d.y * b + d.z * r).normalize();
        (l.z > 0.0).then_some(l)
    }

    /// The pdf (1/sr) of lobe `lobe`'s strategy at l seen from v.
    #[inline]
    pub fn lobe_pdf(&self, lobe: usize, v: Vec3, l: Vec3) -> f32 {
        if lobe == 0 { cosine_pdf(l) } else { phong_lobe_pdf(l, v, self.shininess) }
    }
}

impl NormalizedBlinnPhong {
    /// f(l, v) in 1/sr for unit `l`, `v` in the local frame (z = normal); 0 below the horizon.
    #[inline]
    pub fn eval(&self, l: Vec3, v: Vec3) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.diffuse * FRAC_1_PI + self.specular * blinn_phong_lobe(l, v, self.shininess)
    }

    /// The Lambert term (diffuse, weight k_d) and the Blinn-Phong lobe (glossy, weight k_s).
    pub fn lobes(&self) -> LobeSet {
        LobeSet::new(&[Lobe::new(LobeKind::Diffuse, self.diffuse), Lobe::new(LobeKind::Glossy, self.specular)])
    }

    /// The Blinn-Phong lobe's half vectors: pdf (n + 2)/(2π) cos^{n+1} θ_h.
    #[inline]
    fn half_vector_sampling(&self) -> HalfVector {
        HalfVector::CosPower { k: self.shininess.max(0.0) + 1.0 }
    }

    /// l drawn from lobe `lobe` (0: cosine, 1: h from cos^{n+1} θ_h) for u in [0, 1)²; `None`
    /// below the surface.
    #[inline]
    pub fn sample_lobe(&self, lobe: usize, v: Vec3, u: Vec2) -> Option<Vec3> {
        if lobe == 0 { sample_cosine(u) } else { self.half_vector_sampling().sample(v, u) }
    }

    /// The pdf (1/sr) of lobe `lobe`'s strategy at l seen from v.
    #[inline]
    pub fn lobe_pdf(&self, lobe: usize, v: Vec3, l: Vec3) -> f32 {
        if lobe == 0 { cosine_pdf(l) } else { self.half_vector_sampling().pdf(v, l) }
    }
}

/// The pdf (n + 1)/(2π) max(cos α, 0)^n of the Phong lobe's directions about the mirror
/// direction of v: (n + 1)/(n + 2) times [`phong_lobe`]. 0 for l.z ≤ 0 is left to the caller.
#[inline]
pub fn phong_lobe_pdf(l: Vec3, v: Vec3, shininess: f32) -> f32 {
    let n = shininess.max(0.0);
    phong_lobe(l, v, n) * ((n + 1.0) / (n + 2.0))
}

/// (n + 2)/(2π) max(cos α_r, 0)^n with cos α_r the cosine between R = (−l_x, −l_y, l_z) and v.
///
/// Scale-invariant in `l` and `v` (the angle, not the raw dot product, is used).
#[inline]
pub fn phong_lobe(l: Vec3, v: Vec3, shininess: f32) -> f32 {
    let n = shininess.max(0.0); // n ≥ 0: a negative exponent is infinite at cos = 0
    // R = 2(N·L)N − L is exact in the local frame; products of f32 are exact in f64.
    let r = DVec3::new(-(l.x as f64), -(l.y as f64), l.z as f64);
    let w = v.as_dvec3();
    let norm2 = r.length_squared() * w.length_squared();
    let cos = r.dot(w) / norm2.sqrt();
    let sin2 = r.cross(w).length_squared() / norm2;
    (n + 2.0) / (2.0 * PI) * cos_pow(cos as f32, sin2 as f32, n)
}

/// (n + 8)/(8π) cos^n θ_h with h = normalize(l + v); 0 when h.z ≤ 0.
#[inline]
pub fn blinn_phong_lobe(l: Vec3, v: Vec3, shininess: f32) -> f32 {
    let n = shininess.max(0.0); // n ≥ 0: a negative exponent is infinite at cos = 0
    let s = l + v;
    let m = s.abs().max_element();
    if m == 0.0 {
        return 0.0; // l = −v: no half vector (not reached by eval, which needs l.z, v.z > 0)
    }
    let h = s / m; // rescaled so |h|² cannot underflow when l ≈ −v near the horizon
    let len2 = h.length_squared();
    let sin2 = (h.x * h.x + h.y * h.y) / len2;
    (n + 8.0) / (8.0 * PI) * cos_pow(h.z / len2.sqrt(), sin2, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::vector::reflect;

    #[test]
    fn peak_values() {
        let l = Vec3::new(0.6, 0.0, 0.8);
        let r = reflect(l, Vec3::Z);
        for n in [0.5f32, 10.0, 1e6] {
            assert!((phong_lobe(l, r, n) - (n + 2.0) / (2.0 * PI)).abs() <= 1e-6 * (n + 2.0));
            // Blinn-Phong peak: h = n when v is the mirror of l.
            assert!((blinn_phong_lobe(l, r, n) - (n + 8.0) / (8.0 * PI)).abs() <= 1e-6 * (n + 8.0));
        }
    }

    #[test]
    fn agrees_with_the_classic_lobe_shape() {
        // Up to the normalization factor, the lobe is the course's max(R·V, 0)^K_shi.
        let n = Vec3::Z;
        let l = Vec3::new(0.3, -0.2, 0.9).normalize();
        let v = Vec3::new(-0.2, 0.25, 0.95).normalize();
        let classic = crate::shading::phong::phong(n, l, v, 20.0);
        let ours = phong_lobe(l, v, 20.0) / (22.0 / (2.0 * PI));
        assert!((classic - ours).abs() < 1e-5, "{classic} vs {ours}");
        let classic_b = crate::shading::blinn_phong::blinn_phong(n, l, v, 20.0);
        let ours_b = blinn_phong_lobe(l, v, 20.0) / (28.0 / (8.0 * PI));
        assert!((classic_b - ours_b).abs() < 1e-5);
    }

    #[test]
    fn shininess_zero_is_the_clipped_constant() {
        let p = NormalizedPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess: 0.0 };
        let l = Vec3::new(0.8, 0.0, 0.6);
        // Forward of the mirror plane: 1/π; behind it (R·V < 0): 0, as the n → 0⁺ limit.
        assert!((p.eval(l, Vec3::new(-0.6, 0.0, 0.8)).x - FRAC_1_PI).abs() < 1e-7);
        assert_eq!(p.eval(l, Vec3::new(0.8, 0.0, 0.6)).x, 0.0);
    }

    #[test]
    fn reciprocal() {
        let (l, v) = (Vec3::new(0.3, -0.5, 0.4).normalize(), Vec3::new(-0.2, 0.6, 0.5).normalize());
        let p = NormalizedPhong::default();
        let b = NormalizedBlinnPhong::default();
        assert!((p.eval(l, v) - p.eval(v, l)).abs().max_element() < 1e-6);
        assert!((b.eval(l, v) - b.eval(v, l)).abs().max_element() < 1e-6);
    }
}
