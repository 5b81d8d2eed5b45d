//! The Disney "principled" BRDF of Burley 2012: a few artist-friendly parameters in [0, 1]
//! drive a diffuse lobe with retro-reflection, a sheen lobe, an anisotropic GGX specular lobe
//! and a clearcoat lobe.
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `base_color` C | [0, 1] linear RGB | (0.646, 0.414, 0.018) here (the Explorer's); a lesson's default is 0.8 | diffuse albedo, or specular colour of metals |
//! | `metallic` | [0, 1] | 0 | blends dielectric (diffuse + tinted-white specular) to metal (coloured specular, no diffuse) |
//! | `roughness` r | [0, 1] | 0.5 | specular α = r² (≥ 0.001) and diffuse retro-reflection |
//! | `specular` | [0, 1] | 0.5 | dielectric F0 = 0.08 · specular (0.5 → F0 = 0.04, η = 1.5) |
//! | `specular_tint` | [0, 1] | 0 | tints the dielectric F0 towards the base colour's hue |
//! | `sheen` | [0, 1] | 0 | grazing-angle sheen lobe for cloth |
//! | `sheen_tint` | [0, 1] | 0.5 | tints the sheen towards the base colour's hue |
//! | `clearcoat` | [0, 1] | 0 | strength of a second, white GTR1 lobe (F0 = 0.04) |
//! | `clearcoat_gloss` | [0, 1] | 1 | clearcoat α from 0.1 (0) to 0.001 (1) |
//! | `subsurface` | [0, 1] | 0 | blends the diffuse lobe to a Hanrahan-Krueger-like flattened lobe |
//! | `anisotropic` | [0, 1] | 0 | aspect = √(1 − 0.9 anisotropic): α_x = r²/aspect along the tangent (local x), α_y = r²·aspect |
//! | `specular_transmission` | [0, 1] | 0 | share of the dielectric that is a rough glass boundary (path tracer; [`super::principled_transmission`]) |
//! | `ior` | [1, 3] | 1.5 | index of refraction of that boundary |
//! | `transmittance_color`, `transmittance_distance` | [0, 1], > 0 | 1, ∞ | the colour light keeps after that distance inside (Beer-Lambert) |
//! | `diffuse_transmission` | [0, 1] | 0 | share of the diffuse lobe that leaves through the other side (thin surfaces); scales this BRDF's diffuse lobe by 1 − it |
//! | `subsurface_radius` | ≥ 0 per channel, world units × scale | 0 (not given) | the mean free path per channel of the path tracer's random walk under the surface (`transport::path::subsurface`); not read by [`Principled::eval`] |
//! | `subsurface_scale` | ≥ 0 | 1 | multiplies `subsurface_radius` (Blender's "Subsurface Scale") |
//!
//! With θ_d the angle between l and h, F_S(x) = (1 − x)⁵ (Schlick weight), F_L = F_S(n·l),
//! F_V = F_S(n·v), F_H = F_S(l·h), C_tint = C / lum(C) with lum = 0.3R + 0.6G + 0.1B:
//!
//! - diffuse: (1 − metallic) C/π · mix(f_d, f_ss, subsurface),
//!   f_d = (1 + (F_D90 − 1)F_L)(1 + (F_D90 − 1)F_V), F_D90 = 0.5 + 2 r cos²θ_d (Burley 2012, section "Diffuse model details");
//!   f_ss = 1.25 (F_ss (1/(n·l + n·v) − 0.5) + 0.5), F_ss = (1 + (F_ss90 − 1)F_L)(1 + (F_ss90 − 1)F_V), F_ss90 = r cos²θ_d;
//! - sheen: (1 − metallic) · sheen · mix(1, C_tint, sheen_tint) · F_H;
//! - specular: D_GTR2aniso(h; α_x, α_y) · F · G1(l) G1(v) / (4 (n·l)(n·v)), F = mix(C_spec0, 1, F_H),
//!   C_spec0 = mix(0.08 · specular · mix(1, C_tint, specular_tint), C, metallic);
//! - clearcoat: 0.25 · clearcoat · D_GTR1(h; mix(0.1, 0.001, gloss)) · mix(0.04, 1, F_H) · G1(l) G1(v) / (4 (n·l)(n·v)) with the GGX G1 at α = 0.25.
//!
//! Sources: B. Burley, *Physically-Based Shading at Disney*, SIGGRAPH 2012 course notes
//! (revised Aug 31 2012) and its Appendix B; the reference implementation `disney.brdf` in
//! Disney's BRDF Explorer (github.com/wdas/brdf, src/brdfs/disney.brdf), which this follows line
//! by line. Deliberate differences: `base_color` is linear RGB here (the Explorer converts a
//! display-referred colour with a 2.2 power, `mon2lin`; the default above is its default
//! (0.82, 0.67, 0.16) so converted), and f = 0 when n·l = 0 or n·v = 0 exactly (the Explorer
//! evaluates those). Reciprocal: every term is symmetric in l and v.
//!
//! Not energy conserving by design: the retro-reflective diffuse (F_D90 up to 2.5) and the
//! sheen add energy at grazing angles; the specular lobe is single-scattering GGX.
//!
//! Clamps: α_x, α_y ≥ 0.001 (from the reference code); n·l + n·v ≥ [`COS_FLOOR`] in the
//! subsurface term 1/(n·l + n·v) (a Lommel-Seeliger-like pole at grazing; f·cos stays bounded).
//! Mitsuba 3's `principled` follows Burley 2015; its diffuse lobe is algebraically the same,
//! but its dielectric specular uses the exact Fresnel and its clearcoat omits the
//! 1/(4 (n·l)(n·v)) factor (see docs/models.md).
//!
//! **Lobes, parts and sampling** ([`super::lobe`]). The four sub-lobes of [`PrincipledLobes`]
//! go to the two parts as [`Brdf::eval_parts`](super::brdf::Brdf::eval_parts) has always put them:
//! **diffuse part = diffuse (with its subsurface blend) + sheen**, **specular part = specular
//! + clearcoat**. For sampling they form three lobes, in this order (m = metallic):
//!
//! | lobe | sub-lobes | kind | weight | strategy, pdf p(l) |
//! | --- | --- | --- | --- | --- |
//! | 0 | diffuse, subsurface, sheen | diffuse | (1 − m)(C + sheen · C_sheen · s̄), s̄ = [`SHEEN_ALBEDO`] | cosine-weighted hemisphere, cos θ_l/π |
//! | 1 | specular | glossy | C_spec0 + (1 − C_spec0)/21 (Schlick's average of mix(C_spec0, 1, F_H)) | anisotropic GGX visible normals (Heitz 2018, JCGT 7(4)), p = G1(v) D(h)/(4 n·v) |
//! | 2 | clearcoat | glossy | 0.25 · clearcoat · (0.04 + 0.96/21) | GTR1 D(h) cos θ_h (Burley 2012, Appendix B), p = D cos θ_h/(4 v·h) |
//!
//! The lobes are chosen with probability ∝ the mean of their weights. The diffuse weight C(1 − m)
//! is the Lambert albedo of the base colour (the Disney diffuse's directional albedo departs from
//! it with roughness and angle, the retro-reflection); the sheen's s̄ is its hemispherical average.

use super::lobe::{Lobe, LobeKind, LobeSet, SHEEN_ALBEDO, cosine_pdf, sample_cosine};
use super::microfacet::fresnel::schlick_weight;
use super::microfacet::masking::separable_visibility;
use super::microfacet::ndf::{ggx_aniso, ggx_lambda_cos, gtr1};
use super::microfacet::sample::HalfVector;
use super::microfacet::{COS_FLOOR, half_vector_and_cos};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A Disney principled material (Burley 2012).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Principled {
    /// Base colour C, linear RGB.
    pub base_color: Vec3,
    /// Metalness in [0, 1].
    pub metallic: f32,
    /// Roughness r in [0, 1]; α = r².
    pub roughness: f32,
    /// Dielectric specular amount: F0 = 0.08 · specular.
    pub specular: f32,
    /// Tint of the dielectric specular towards the base colour's hue.
    pub specular_tint: f32,
    /// Sheen amount.
    pub sheen: f32,
    /// Tint of the sheen towards the base colour's hue.
    pub sheen_tint: f32,
    /// Clearcoat amount.
    pub clearcoat: f32,
    /// Clearcoat glossiness: α_cc = mix(0.1, 0.001, clearcoat_gloss).
    pub clearcoat_gloss: f32,
    /// Blend from the diffuse lobe to the subsurface approximation.
    pub subsurface: f32,
    /// Anisotropy: aspect = √(1 − 0.9 anisotropic), tangent = local x.
    pub anisotropic: f32,
    /// Share of the dielectric that is a rough glass boundary (Burley 2015's specTrans).
    pub specular_transmission: f32,
    /// Index of refraction of the transmitting boundary.
    pub ior: f32,
    /// The colour light keeps after `transmittance_distance` inside the object.
    pub transmittance_color: Vec3,
    /// The distance at which light inside has `transmittance_color` (∞: no absorption).
    pub transmittance_distance: f32,
    /// Share of the diffuse lobe sent through to the other side (Burley 2015's diffTrans).
    pub diffuse_transmission: f32,
    /// Mean free path per channel under the surface (Blender's "Subsurface Radius"); zero when
    /// not given. Only the path tracer's random walk reads it; the BRDF keeps the flattening.
    pub subsurface_radius: Vec3,
    /// World-unit multiplier of `subsurface_radius` (Blender's "Subsurface Scale").
    pub subsurface_scale: f32,
}

impl Default for Principled {
    /// The BRDF Explorer defaults (base colour converted to linear RGB).
    fn default() -> Self {
        Principled {
            base_color: Vec3::new(0.82f32.powf(2.2), 0.67f32.powf(2.2), 0.16f32.powf(2.2)),
            metallic: 0.0,
            roughness: 0.5,
            specular: 0.5,
            specular_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.5,
            clearcoat: 0.0,
            clearcoat_gloss: 1.0,
            subsurface: 0.0,
            anisotropic: 0.0,
            specular_transmission: 0.0,
            ior: 1.5,
            transmittance_color: Vec3::ONE,
            transmittance_distance: f32::INFINITY,
            diffuse_transmission: 0.0,
            subsurface_radius: Vec3::ZERO,
            subsurface_scale: 1.0,
        }
    }
}

/// The four lobes of the principled BRDF, each in 1/sr (their sum is f).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PrincipledLobes {
    /// Diffuse (with retro-reflection and the subsurface blend), × (1 − metallic).
    pub diffuse: Vec3,
    /// Sheen, × (1 − metallic).
    pub sheen: Vec3,
    /// Anisotropic GGX specular.
    pub specular: Vec3,
    /// Clearcoat (white).
    pub clearcoat: Vec3,
}

impl PrincipledLobes {
    /// The BRDF value: the sum of the lobes.
    #[inline]
    pub fn total(&self) -> Vec3 {
        self.diffuse + self.sheen + self.specular + self.clearcoat
    }
}

/// GLSL `mix`: x(1 − a) + y a.
#[inline]
fn mix(x: f32, y: f32, a: f32) -> f32 {
    x * (1.0 - a) + y * a
}

/// GLSL `mix` per channel.
#[inline]
fn mix3(x: Vec3, y: Vec3, a: f32) -> Vec3 {
    x * (1.0 - a) + y * a
}

impl Principled {
    /// Whether the path tracer walks under this surface: subsurface > 0 and a radius given.
    pub fn walks(&self) -> bool {
        self.subsurface > 0.0 && self.subsurface_radius != Vec3::ZERO
    }

    /// The specular widths (α_x, α_y) = (max(0.001, r²/aspect), max(0.001, r²·aspect)).
    #[inline]
    pub fn alphas(&self) -> (f32, f32) {
        let aspect = (1.0 - 0.9 * self.anisotropic).sqrt();
        let r2 = self.roughness * self.roughness;
        ((r2 / aspect).max(0.001), (r2 * aspect).max(0.001))
    }

    /// C_tint = C / lum(C), lum = 0.3R + 0.6G + 0.1B (white for a black C), and the specular
    /// colour at normal incidence C_spec0 = mix(0.08 specular mix(1, C_tint, specular_tint), C, metallic).
    #[inline]
    pub fn tint_and_spec0(&self) -> (Vec3, Vec3) {
        let c = self.base_color;
        let lum = 0.3 * c.x + 0.6 * c.y + 0.1 * c.z;
        let tint = if lum > 0.0 { c / lum } else { Vec3::ONE };
        (tint, mix3(self.specular * 0.08 * mix3(Vec3::ONE, tint, self.specular_tint), c, self.metallic))
    }

    /// The clearcoat width α_cc = mix(0.1, 0.001, clearcoat_gloss).
    #[inline]
    pub fn clearcoat_alpha(&self) -> f32 {
        mix(0.1, 0.001, self.clearcoat_gloss)
    }

    /// f(l, v) in 1/sr for unit `l`, `v` in the local frame (z = normal, x = tangent).
    #[inline]
    pub fn eval(&self, l: Vec3, v: Vec3) -> Vec3 {
        self.eval_lobes(l, v).total()
    }

    /// Diffuse (with sheen), specular and clearcoat lobes with their weights (module docs).
    pub fn lobes(&self) -> LobeSet {
        let (tint, spec0) = self.tint_and_spec0();
        let sheen_color = mix3(Vec3::ONE, tint, self.sheen_tint);
        let diffuse =
            (self.base_color * (1.0 - self.diffuse_transmission) + self.sheen * SHEEN_ALBEDO * sheen_color) * (1.0 - self.metallic);
        let specular = spec0 + (Vec3::ONE - spec0) * (1.0 / 21.0);
        // eval adds no clearcoat for clearcoat ≤ 0: its weight is 0 there too.
        let clearcoat = if self.clearcoat > 0.0 { Vec3::splat(0.25 * self.clearcoat * (0.04 + 0.96 / 21.0)) } else { Vec3::ZERO };
        LobeSet::new(&[
            Lobe::new(LobeKind::Diffuse, diffuse),
            Lobe::new(LobeKind::Glossy, specular),
            Lobe::new(LobeKind::Glossy, clearcoat),
        ])
    }

    /// The strategy of lobe `lobe` ≥ 1: anisotropic GGX visible normals, or GTR1 D·cos.
    #[inline]
    fn half_vector_sampling(&self, lobe: usize) -> HalfVector {
        if lobe == 1 {
            let (alpha_x, alpha_y) = self.alphas();
            HalfVector::VisibleGgx { alpha_x, alpha_y }
        } else {
            HalfVector::Gtr1 { alpha: self.clearcoat_alpha() }
        }
    }

    /// l drawn from lobe `lobe` (0: cosine, 1: specular, 2: clearcoat) for u in [0, 1)²;
    /// `None` below the surface.
    #[inline]
    pub fn sample_lobe(&self, lobe: usize, v: Vec3, u: Vec2) -> Option<Vec3> {
        if lobe == 0 { sample_cosine(u) } else { self.half_vector_sampling(lobe).sample(v, u) }
    }

    /// The pdf (1/sr) of lobe `lobe`'s strategy at l seen from v.
    #[inline]
    pub fn lobe_pdf(&self, lobe: usize, v: Vec3, l: Vec3) -> f32 {
        if lobe == 0 { cosine_pdf(l) } else { self.half_vector_sampling(lobe).pdf(v, l) }
    }

    /// The four lobes separately; all zero when n·l ≤ 0 or n·v ≤ 0.
    pub fn eval_lobes(&self, l: Vec3, v: Vec3) -> PrincipledLobes {
        if l.z <= 0.0 || v.z <= 0.0 {
            return PrincipledLobes::default();
        }
        let (n_dot_l, n_dot_v) = (l.z, v.z);
        let (h, l_dot_h) = half_vector_and_cos(l, v); // l·h = |l + v|/2: no cancellation

        let c = self.base_color;
        let (tint, spec0) = self.tint_and_spec0();
        let sheen_color = mix3(Vec3::ONE, tint, self.sheen_tint);

        // Diffuse: Schlick-like retro-reflection, 1 at normal incidence to F_D90 at grazing.
        let (fl, fv) = (schlick_weight(n_dot_l), schlick_weight(n_dot_v));
        let rough_cos2 = l_dot_h * l_dot_h * self.roughness;
        let fd90 = 0.5 + 2.0 * rough_cos2;
        let fd = mix(1.0, fd90, fl) * mix(1.0, fd90, fv);
        // Hanrahan-Krueger-like subsurface: n·l + n·v ≥ COS_FLOOR keeps 1/(n·l + n·v) finite.
        let fss = mix(1.0, rough_cos2, fl) * mix(1.0, rough_cos2, fv);
        let ss = 1.25 * (fss * (1.0 / (n_dot_l + n_dot_v).max(COS_FLOOR) - 0.5) + 0.5);
        // The share sent through the surface (`diffuse_transmission`) is not reflected.
        let diffuse = FRAC_1_PI * mix(fd, ss, self.subsurface) * c * ((1.0 - self.metallic) * (1.0 - self.diffuse_transmission));

        // Anisotropic GGX specular with separable Smith masking (visibility form).
        let (ax, ay) = self.alphas();
        let fh = schlick_weight(l_dot_h);
        let ds = ggx_aniso(h, ax, ay);
        let gs = separable_visibility(n_dot_l, n_dot_v, ggx_lambda_cos(l, ax, ay), ggx_lambda_cos(v, ax, ay));
        let specular = ds * gs * mix3(spec0, Vec3::ONE, fh);

        let sheen = fh * self.sheen * sheen_color * (1.0 - self.metallic);

        // Clearcoat: GTR1, F0 = 0.04 (η = 1.5), GGX masking at α = 0.25.
        let clearcoat = if self.clearcoat > 0.0 {
            let dr = gtr1(h, self.clearcoat_alpha());
            let fr = mix(0.04, 1.0, fh);
            let gr = separable_visibility(n_dot_l, n_dot_v, ggx_lambda_cos(l, 0.25, 0.25), ggx_lambda_cos(v, 0.25, 0.25));
            Vec3::splat(0.25 * self.clearcoat * gr * fr * dr)
        } else {
            Vec3::ZERO
        };
        PrincipledLobes { diffuse, sheen, specular, clearcoat }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    #[test]
    fn normal_incidence_diffuse_is_lambert() {
        // l = v = n: F_L = F_V = 0, so f_d = 1 and the diffuse lobe is C/π.
        let p = Principled { base_color: Vec3::new(0.5, 0.2, 0.1), ..Principled::default() };
        let lobes = p.eval_lobes(Vec3::Z, Vec3::Z);
        assert!((lobes.diffuse - p.base_color * FRAC_1_PI).length() < 1e-7);
    }

    #[test]
    fn metal_has_no_diffuse_and_coloured_f0() {
        let p = Principled { metallic: 1.0, base_color: Vec3::new(0.9, 0.6, 0.2), roughness: 0.4, ..Principled::default() };
        let lobes = p.eval_lobes(Vec3::Z, Vec3::Z);
        assert_eq!(lobes.diffuse, Vec3::ZERO);
        // h = n: D = 1/(π α²), V = 1/4, F = C.
        let a = 0.16f32;
        let expect = p.base_color / (4.0 * std::f32::consts::PI * a * a);
        assert!((lobes.specular - expect).abs().max_element() < 1e-4 * expect.max_element());
    }

    #[test]
    fn anisotropy_stretches_along_the_tangent() {
        let p = Principled { metallic: 1.0, roughness: 0.5, anisotropic: 1.0, ..Principled::default() };
        let (ax, ay) = p.alphas();
        assert!(ax > ay);
        let v = Vec3::Z;
        // A light tilted along x (tangent) keeps more highlight than one tilted along y.
        let along_x = p.eval(dir(0.3, 0.0), v).x;
        let along_y = p.eval(dir(0.3, std::f32::consts::FRAC_PI_2), v).x;
        assert!(along_x > along_y);
    }

    #[test]
    fn reciprocal() {
        let p = Principled { subsurface: 0.5, sheen: 1.0, clearcoat: 1.0, anisotropic: 0.7, ..Principled::default() };
        let (l, v) = (dir(0.4, 0.3), dir(1.2, 2.5));
        let (a, b) = (p.eval(l, v), p.eval(v, l));
        assert!((a - b).abs().max_element() <= 1e-6 * a.max_element());
    }
}
