//! Cook-Torrance microfacet BRDF: a specular lobe from facet mirrors, with an optional Lambert
//! base beneath it.
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `ndf` | `blinn`, `beckmann`, `ggx`, `gaussian` | `ggx` | distribution of facet normals D ([`Ndf`]) |
//! | `masking` | `cook_torrance`, `smith`, `smith_correlated` | `smith` | masking-shadowing G ([`Masking`]) |
//! | `fresnel` | `schlick`, `dielectric`, `conductor`, `none` | `schlick`, F0 = 0.04 | facet reflectance F ([`Fresnel`]) |
//! | `alpha` α | [0, 1] | 0.25 | lobe width; `roughness` r gives α = r² (lessons accept one of the two) |
//! | `specular` k_s | [0, 1] RGB | 1 | tint of the specular lobe |
//! | `diffuse` ρ | [0, 1] RGB | 0 | albedo of a Lambert term ρ/π added beneath the lobe |
//!
//! f(l, v) = k_s ⊗ D(h) G(l, v, h) F(v·h) / (4 (n·l)(n·v)) + ρ/π,   h = normalize(l + v)
//!
//! Sources: Cook & Torrance 1982 (the model), Walter et al. 2007, eq. 20 (the 4 (n·l)(n·v)
//! normalization and the GGX/Beckmann conventions also used by Mitsuba 3 `roughconductor` and
//! `roughplastic`). One-sided: f = 0 when n·l ≤ 0 or n·v ≤ 0.
//!
//! The diffuse term is simply added (as the issue asks); it does not take the energy the lobe
//! reflects away, so ρ + the lobe's albedo can exceed 1. Single scattering also loses energy at
//! high α (no multiple bounces between facets): a white GGX lobe with α = 1 has albedo < 1.
//!
//! Clamps (one line each in the code): α ≥ [`ALPHA_MIN`](super::microfacet::ALPHA_MIN);
//! cosines in V ≥ [`COS_FLOOR`](super::microfacet::COS_FLOOR); D·V ≤ f32::MAX (near the
//! mirror direction with both cosines below 1e-7 the true value can exceed f32). The Fresnel
//! cosine v·h is evaluated as |l + v|/2 (exact for unit vectors, symmetric, no cancellation).
//!
//! **Lobes, parts and sampling** ([`super::lobe`]). Two lobes, in this order:
//!
//! | lobe | kind, part | weight | strategy, pdf p(l) |
//! | --- | --- | --- | --- |
//! | 0, Lambert base ρ/π | diffuse | ρ | cosine-weighted hemisphere, cos θ_l/π |
//! | 1, microfacet lobe | glossy, specular part | k_s ⊗ F̄, F̄ = F(1) + (1 − F(1))/21 ([`Fresnel::average`]) | GGX with `smith` or `smith_correlated`: visible normals (Heitz 2018, JCGT 7(4)), p = G1(v) D(h)/(4 n·v); otherwise D(h) cos θ_h (Walter et al. 2007, eqs. 28–29 Beckmann, 35–36 GGX; Blinn cos^{k+1}; Gaussian by a truncated Rayleigh proposal with its own exact pdf), p = p(h)/(4 v·h) (eqs. 14, 38) |
//!
//! The lobe is chosen with probability ∝ the mean of its weight. Visible normals are not used
//! with the V-cavity G, whose masking is not the Smith G1 that D_v assumes, nor with Beckmann
//! (no closed-form inversion; its D·cos sampling is exact). The strategies are in
//! [`microfacet::sample`](super::microfacet::sample). With α clamped to `ALPHA_MIN` a roughness
//! of 0 is a needle lobe with a finite pdf (≤ f32::MAX), not a delta.

use super::lobe::{Lobe, LobeKind, LobeSet, cosine_pdf, sample_cosine};
use super::microfacet::sample::HalfVector;
use super::microfacet::{Fresnel, Masking, Ndf, clamp_alpha, half_vector_and_cos};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A Cook-Torrance material: specular microfacet lobe plus optional Lambert base.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CookTorrance {
    /// Distribution of microfacet normals D.
    pub ndf: Ndf,
    /// Masking-shadowing G.
    pub masking: Masking,
    /// Facet reflectance F.
    pub fresnel: Fresnel,
    /// Width α of the distribution (α = roughness²).
    pub alpha: f32,
    /// Tint k_s of the specular lobe.
    pub specular: Vec3,
    /// Albedo ρ of the Lambert term ρ/π beneath the lobe.
    pub diffuse: Vec3,
}

impl Default for CookTorrance {
    /// GGX, separable Smith, Schlick with F0 = 0.04, roughness 0.5 (α = 0.25), white lobe, no diffuse.
    fn default() -> Self {
        CookTorrance {
            ndf: Ndf::Ggx,
            masking: Masking::Smith,
            fresnel: Fresnel::default(),
            alpha: 0.25,
            specular: Vec3::ONE,
            diffuse: Vec3::ZERO,
        }
    }
}

impl CookTorrance {
    /// f(l, v) in 1/sr (cosine not included) for unit `l`, `v` in the local frame (z = normal).
    #[inline]
    pub fn eval(&self, l: Vec3, v: Vec3) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.specular_lobe(l, v) + self.diffuse * FRAC_1_PI
    }

    /// The specular lobe alone, k_s D G F / (4 (n·l)(n·v)); zero below the horizon.
    #[inline]
    pub fn eval_specular(&self, l: Vec3, v: Vec3) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.specular_lobe(l, v)
    }

    /// The Lambert term alone, ρ/π; zero below the horizon.
    #[inline]
    pub fn eval_diffuse(&self, l: Vec3, v: Vec3) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.diffuse * FRAC_1_PI
    }

    /// The Lambert base (diffuse, weight ρ) and the microfacet lobe (glossy, weight k_s ⊗ F̄).
    pub fn lobes(&self) -> LobeSet {
        LobeSet::new(&[Lobe::new(LobeKind::Diffuse, self.diffuse), Lobe::new(LobeKind::Glossy, self.specular * self.fresnel.average())])
    }

    /// How the microfacet lobe's half vectors are drawn: GGX visible normals with a Smith G,
    /// else D(h) cos θ_h.
    pub fn half_vector_sampling(&self) -> HalfVector {
        let alpha = clamp_alpha(self.alpha);
        match (self.ndf, self.masking) {
            (Ndf::Ggx, Masking::Smith | Masking::SmithCorrelated) => HalfVector::VisibleGgx { alpha_x: alpha, alpha_y: alpha },
            (ndf, _) => HalfVector::NormalCos { ndf, alpha },
        }
    }

    /// l drawn from lobe `lobe` (0: cosine, 1: microfacet) for u in [0, 1)²; `None` below the surface.
    #[inline]
    pub fn sample_lobe(&self, lobe: usize, v: Vec3, u: Vec2) -> Option<Vec3> {
        if lobe == 0 { sample_cosine(u) } else { self.half_vector_sampling().sample(v, u) }
    }

    /// The pdf (1/sr) of lobe `lobe`'s strategy at l seen from v.
    #[inline]
    pub fn lobe_pdf(&self, lobe: usize, v: Vec3, l: Vec3) -> f32 {
        if lobe == 0 { cosine_pdf(l) } else { self.half_vector_sampling().pdf(v, l) }
    }

    /// A partial product of the specular lobe, for lobe charts only (shading never calls it):
    /// k_s D [G] [F] / (4 (n·l)(n·v)), with G and F left out (taken as 1) as `terms` says;
    /// [`Terms::Dgf`] is [`eval_specular`](Self::eval_specular). No diffuse term; zero below
    /// the horizon.
    pub fn eval_terms(&self, l: Vec3, v: Vec3, terms: Terms) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        if terms == Terms::Dgf {
            return self.specular_lobe(l, v);
        }
        let alpha = clamp_alpha(self.alpha);
        let (h, _) = half_vector_and_cos(l, v);
        let d = self.ndf.d(h, alpha);
        let g = if terms == Terms::Dg { self.masking.g(self.ndf, l, v, h, alpha) } else { 1.0 };
        (d * g / (4.0 * l.z * v.z)).min(f32::MAX) * self.specular
    }

    /// Precondition: l.z > 0, v.z > 0.
    #[inline]
    fn specular_lobe(&self, l: Vec3, v: Vec3) -> Vec3 {
        let alpha = clamp_alpha(self.alpha); // α ≥ ALPHA_MIN: α = 0 is a Dirac delta
        let (h, v_dot_h) = half_vector_and_cos(l, v); // v·h = |l + v|/2: no cancellation
        let d = self.ndf.d(h, alpha);
        let vis = self.masking.visibility(self.ndf, l, v, h, alpha);
        // D·V ≤ f32::MAX: reached only for cosines below 1e-7 near the mirror direction.
        let dv = (d * vis).min(f32::MAX);
        dv * self.fresnel.eval(v_dot_h) * self.specular
    }
}

/// Which factors of the specular numerator D G F a lobe chart keeps (the rest are taken as 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Terms {
    /// D alone: where the facets point.
    D,
    /// D·G: the facets that are neither masked nor shadowed.
    Dg,
    /// D·G·F: the whole specular lobe.
    Dgf,
}

impl Terms {
    /// Every choice, in the order of the course.
    pub const ALL: [Terms; 3] = [Terms::D, Terms::Dg, Terms::Dgf];

    /// The name used in lesson files and on the command line: `D`, `DG`, `DGF`.
    pub fn name(self) -> &'static str {
        match self {
            Terms::D => "D",
            Terms::Dg => "DG",
            Terms::Dgf => "DGF",
        }
    }

    /// The product as a chart label writes it: `D`, `D·G`, `D·G·F`.
    pub fn product(self) -> &'static str {
        match self {
            Terms::D => "D",
            Terms::Dg => "D·G",
            Terms::Dgf => "D·G·F",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    #[test]
    fn normal_incidence_matches_hand_computation() {
        // l = v = n: h = n, D = 1/(πα²), G = 1, F = F0, f = F0 / (4πα²).
        let ct = CookTorrance { alpha: 0.3, ..CookTorrance::default() };
        let f = ct.eval(Vec3::Z, Vec3::Z);
        let expect = 0.04 / (4.0 * PI * 0.09);
        assert!((f.x / expect - 1.0).abs() < 1e-5, "{f} vs {expect}");
    }

    #[test]
    fn one_sided_and_diffuse_only() {
        let ct = CookTorrance { diffuse: Vec3::new(0.5, 0.25, 1.0), specular: Vec3::ZERO, ..CookTorrance::default() };
        assert_eq!(ct.eval(Vec3::Z, -Vec3::Z), Vec3::ZERO);
        assert_eq!(ct.eval(Vec3::X, Vec3::Z), Vec3::ZERO);
        assert!((ct.eval(Vec3::Z, Vec3::new(0.6, 0.0, 0.8)) - ct.diffuse / PI).length() < 1e-7);
    }

    #[test]
    fn reciprocal() {
        let l = Vec3::new(0.3, -0.5, 0.4).normalize();
        let v = Vec3::new(-0.7, 0.1, 0.2).normalize();
        for ndf in Ndf::ALL {
            for masking in Masking::ALL {
                let ct = CookTorrance { ndf, masking, fresnel: Fresnel::Dielectric { eta: 1.5 }, ..CookTorrance::default() };
                let (a, b) = (ct.eval(l, v), ct.eval(v, l));
                assert!((a - b).abs().max_element() <= 1e-6 * a.max_element(), "{ndf:?} {masking:?}");
            }
        }
    }

    #[test]
    fn partial_products_shrink_as_factors_are_added() {
        // G ≤ 1 and F ≤ 1: D·G ≤ D and D·G·F ≤ D·G at every pair, for every masking.
        let l = Vec3::new(-(75f32.to_radians().sin()), 0.0, 75f32.to_radians().cos());
        for masking in Masking::ALL {
            let ct = CookTorrance { masking, ..CookTorrance::default() };
            for k in 0..=180 {
                let t = (-90.0 + k as f32).to_radians();
                let v = Vec3::new(t.sin(), 0.0, t.cos());
                let (d, dg, dgf) = (ct.eval_terms(l, v, Terms::D), ct.eval_terms(l, v, Terms::Dg), ct.eval_terms(l, v, Terms::Dgf));
                assert!(dg.x <= d.x * (1.0 + 1e-6) && dgf.x <= dg.x * (1.0 + 1e-5), "{masking:?} {k}: {d} {dg} {dgf}");
                assert_eq!(dgf, ct.eval_specular(l, v));
            }
        }
    }

    #[test]
    fn roughness_zero_and_grazing_stay_finite() {
        let ct = CookTorrance { alpha: 0.0, masking: Masking::CookTorrance, ..CookTorrance::default() };
        let l = Vec3::new(1.0, 0.0, 1e-7).normalize();
        let v = Vec3::new(-1.0, 0.0, 1e-7).normalize();
        let f = ct.eval(l, v);
        assert!(f.is_finite() && f.min_element() >= 0.0, "{f}");
    }
}
