//! A rough dielectric interface, GGX microfacets that reflect and refract: the BSDF as a
//! BRDF plus a BTDF (Walter, Marschner, Li & Torrance 2007, "Microfacet Models for
//! Refraction through Rough Surfaces"). It is drawn in charts (`bsdf` figures, lesson 31) and
//! by the path tracer (`glass` with `roughness` > 0): [`RoughDielectric::sample`] picks a
//! visible GGX normal (Heitz 2018) and reflects or refracts about it as Fresnel says (Walter
//! et al. 2007, §5.3), with the pdf of eq. 38 (reflection) and eq. 17's Jacobian (refraction).
//!
//! Local frame: z is the outward normal, the outside has index 1 and the inside `ior`.
//! i (towards the light) and o (outgoing) are unit vectors pointing away from the surface.
//! * reflection (i, o on one side): h_r = ±normalize(i + o) (eq. 13),
//!   f_r = F(i·h) G D / (4 |i·n| |o·n|) (eq. 20);
//! * transmission: h_t = −normalize(η_i i + η_o o) (eq. 16), turned to the outside,
//!   f_t = |i·h| |o·h| / (|i·n| |o·n|) · η_o² (1 − F(i·h)) G D / (η_i (i·h) + η_o (o·h))² (eq. 21),
//!
//! with D the GGX distribution, G = G1(i, h) G1(o, h) Smith's separable masking and F the
//! exact dielectric Fresnel. f_t obeys the generalized reciprocity f_t(i, o)/η_o² =
//! f_t(o, i)/η_i² (eq. 22's consequence), and ∫ f_s |o·n| dω_o is the share of a beam from
//! i that leaves in the hemisphere of o: [`RoughDielectric::split`] integrates it over the
//! visible normals (Heitz 2018), where the smooth glass's split is F and 1 − F.

use super::microfacet::fresnel::dielectric;
use super::microfacet::ndf::Ndf;
use super::microfacet::sample::{ggx_visible_normal, reflect_about};
use super::microfacet::{alpha_from_roughness, clamp_alpha};
use crate::geometry::vector::refract;
use glam::{Vec2, Vec3};

/// A rough dielectric boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughDielectric {
    /// Index of the inside relative to the outside (η ≠ 1).
    pub ior: f32,
    /// GGX width α = roughness².
    pub alpha: f32,
}

/// Where a beam goes: the shares reflected and transmitted (the rest is the energy single
/// scattering loses: light that would hit a second microfacet).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Split {
    /// Reflected share.
    pub reflected: f64,
    /// Transmitted share.
    pub transmitted: f64,
}

/// A direction chosen by [`RoughDielectric::sample`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughSample {
    /// The direction, in the local frame.
    pub l: Vec3,
    /// Its pdf (1/sr).
    pub pdf: f32,
    /// f_s(l, v).
    pub value: f32,
    /// True when it crossed the interface.
    pub transmitted: bool,
}

impl RoughDielectric {
    /// The boundary of roughness `roughness` (α = roughness², clamped above 0).
    pub fn new(ior: f32, roughness: f32) -> RoughDielectric {
        RoughDielectric { ior, alpha: clamp_alpha(alpha_from_roughness(roughness)) }
    }

    /// The indices (η_i, η_o) of the sides of `i` and `o`.
    fn indices(&self, i: Vec3, o: Vec3) -> (f32, f32) {
        let side = |w: Vec3| if w.z >= 0.0 { 1.0 } else { self.ior };
        (side(i), side(o))
    }

    /// f_s(i, o): f_r when i and o are on one side, f_t across (0 for grazing directions
    /// and for the configurations no microfacet connects). Never NaN.
    pub fn eval(&self, i: Vec3, o: Vec3) -> f32 {
        if i.z == 0.0 || o.z == 0.0 {
            return 0.0;
        }
        let ggx = Ndf::Ggx;
        let (eta_i, eta_o) = self.indices(i, o);
        let reflect = i.z * o.z > 0.0;
        let h = if reflect { i + o } else { -(eta_i * i + eta_o * o) };
        let len = h.length();
        if len.is_nan() || len <= 1e-7 {
            return 0.0;
        }
        let h = h / len;
        let h = if h.z < 0.0 { -h } else { h };
        let g = ggx.g1(i, h, self.alpha) * ggx.g1(o, h, self.alpha);
        if g == 0.0 {
            return 0.0;
        }
        let d = ggx.d(h, self.alpha);
        let (ih, oh) = (i.dot(h), o.dot(h));
        // Fresnel from i's side: η_t/η_i as the interface meets the light.
        let eta = if i.z > 0.0 { self.ior } else { 1.0 / self.ior };
        let f = dielectric(ih.abs(), eta);
        let f = if reflect {
            f * g * d / (4.0 * i.z.abs() * o.z.abs())
        } else {
            let denom = eta_i * ih + eta_o * oh;
            if denom == 0.0 {
                return 0.0;
            }
            (ih * oh).abs() / (i.z * o.z).abs() * eta_o * eta_o * (1.0 - f) * g * d / (denom * denom)
        };
        if f.is_finite() { f } else { 0.0 }
    }

    /// A direction `l` for the unit `v` (towards the viewer, on either side; `u_lobe` picks
    /// the lobe, `u` the normal): a normal h visible from v on v's side, then reflection about
    /// h with probability F(v·h), else refraction (F = 1 under total internal reflection).
    /// `None` when v is grazing or the direction leaves on the wrong side (that mass is the
    /// energy single scattering loses).
    pub fn sample(&self, v: Vec3, u_lobe: f32, u: Vec2) -> Option<RoughSample> {
        if !v.is_finite() || v.z == 0.0 {
            return None;
        }
        let up = Vec3::new(v.x, v.y, v.z.abs());
        let hu = ggx_visible_normal(up, self.alpha, self.alpha, u)?;
        let h = Vec3::new(hu.x, hu.y, hu.z.copysign(v.z));
        let eta = if v.z > 0.0 { self.ior } else { 1.0 / self.ior };
        let refracted = refract(v, h, eta);
        let f = if refracted.is_some() { dielectric(v.dot(h).max(0.0), eta) } else { 1.0 };
        let (l, refracting) = match refracted {
            Some(t) if u_lobe >= f => (t, true),
            _ => (reflect_about(v, h)?, false),
        };
        let transmitted = l.z * v.z < 0.0;
        if l.z == 0.0 || transmitted != refracting {
            return None;
        }
        let pdf = self.pdf(v, l);
        let value = self.eval(l, v);
        (pdf > 0.0 && pdf.is_finite() && value > 0.0).then_some(RoughSample { l, pdf, value, transmitted })
    }

    /// The pdf (1/sr) with which [`RoughDielectric::sample`] picks `l` for `v`.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        if v.z == 0.0 || l.z == 0.0 {
            return 0.0;
        }
        let ggx = Ndf::Ggx;
        let reflect = v.z * l.z > 0.0;
        let (eta_v, eta_l) = self.indices(v, l);
        let h = if reflect { v + l } else { -(eta_v * v + eta_l * l) };
        let len = h.length();
        if len.is_nan() || len <= 1e-7 {
            return 0.0;
        }
        let h = h / len;
        let h = if h.z * v.z < 0.0 { -h } else { h };
        let (vh, lh) = (v.dot(h), l.dot(h));
        if vh <= 0.0 || (reflect && lh <= 0.0) || (!reflect && lh >= 0.0) {
            return 0.0;
        }
        // The visible-normal density in the frame where v is above: G1(v) (v·h) D(h) / v.z.
        let (up, hu) = (Vec3::new(v.x, v.y, v.z.abs()), Vec3::new(h.x, h.y, h.z.abs()));
        let visible = ggx.g1(up, hu, self.alpha) * vh * ggx.d(hu, self.alpha) / up.z;
        let eta = if v.z > 0.0 { self.ior } else { 1.0 / self.ior };
        let f = if refract(v, h, eta).is_some() { dielectric(vh, eta) } else { 1.0 };
        let p = if reflect {
            f * visible / (4.0 * vh)
        } else {
            let denom = eta_v * vh + eta_l * lh;
            (1.0 - f) * visible * eta_l * eta_l * lh.abs() / (denom * denom)
        };
        if p.is_finite() { p.max(0.0) } else { 0.0 }
    }

    /// The shares of a beam from `i` (outside, i.z > 0) reflected and transmitted:
    /// E[F G1(o_r)] and E[(1 − F) G1(o_t)] over the normals visible from i (Heitz 2018's
    /// sampling on a `n` × `n` grid of cell centres), o_r and o_t the mirror and Snell
    /// directions about each normal.
    pub fn split(&self, i: Vec3, n: u32) -> Split {
        let ggx = Ndf::Ggx;
        let (mut r, mut t) = (0.0f64, 0.0f64);
        for a in 0..n {
            for b in 0..n {
                let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
                let Some(h) = ggx_visible_normal(i, self.alpha, self.alpha, u) else { continue };
                let f = dielectric(i.dot(h).max(0.0), self.ior) as f64;
                if let Some(o) = reflect_about(i, h).filter(|o| o.z > 0.0) {
                    r += f * ggx.g1(o, h, self.alpha) as f64;
                }
                if let Some(o) = refract(i, h, self.ior).filter(|o| o.z < 0.0) {
                    t += (1.0 - f) * ggx.g1(o, h, self.alpha) as f64;
                }
            }
        }
        let cells = (n * n) as f64;
        Split { reflected: r / cells, transmitted: t / cells }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    /// ∫ f_s |o·n| dω_o over one hemisphere, by the midpoint rule in (θ, φ): the transmitted
    /// lobe is narrow (refraction into glass narrows it about threefold), so steps even in θ.
    fn brute_force(m: &RoughDielectric, i: Vec3, below: bool, steps: u32) -> f64 {
        hemisphere(below, steps, |o| m.eval(i, o))
    }

    /// ∫ f(w) |w·n| dω over the upper (or lower) hemisphere by the midpoint rule in (θ, φ).
    fn hemisphere(below: bool, steps: u32, f: impl Fn(Vec3) -> f32) -> f64 {
        let mut sum = 0.0f64;
        let dt = std::f64::consts::FRAC_PI_2 / steps as f64;
        let dp = std::f64::consts::PI / steps as f64;
        for a in 0..steps {
            let t = (a as f64 + 0.5) * dt;
            let (s, c) = (t.sin(), t.cos());
            for b in 0..2 * steps {
                let phi = (b as f64 + 0.5) * dp;
                let w = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, (if below { -c } else { c }) as f32);
                sum += f(w) as f64 * c * s;
            }
        }
        sum * dt * dp
    }

    #[test]
    fn the_split_is_the_integral_of_the_bsdf() {
        let m = RoughDielectric::new(1.5, 0.6);
        for theta in [0.0, 40.0, 75.0] {
            let i = dir(theta, 0.0);
            let s = m.split(i, 256);
            let (r, t) = (brute_force(&m, i, false, 600), brute_force(&m, i, true, 600));
            assert!((s.reflected - r).abs() < 2e-3, "θ = {theta}: R {} vs {r}", s.reflected);
            assert!((s.transmitted - t).abs() < 4e-3, "θ = {theta}: T {} vs {t}", s.transmitted);
            assert!(s.reflected + s.transmitted <= 1.0 + 1e-6);
        }
    }

    #[test]
    fn a_smooth_boundary_splits_as_fresnel() {
        let m = RoughDielectric::new(1.5, 0.02);
        for theta in [0.0f32, 30.0, 60.0, 80.0] {
            let s = m.split(dir(theta, 0.0), 64);
            let f = dielectric(theta.to_radians().cos(), 1.5) as f64;
            assert!((s.reflected - f).abs() < 2e-3, "θ = {theta}: R {} vs F {f}", s.reflected);
            assert!((s.transmitted - (1.0 - f)).abs() < 3e-3, "θ = {theta}: T {} vs {}", s.transmitted, 1.0 - f);
        }
    }

    #[test]
    fn transmission_obeys_the_generalized_reciprocity() {
        let m = RoughDielectric::new(1.5, 0.4);
        for (a, b) in [((30.0, 0.0), (160.0, 180.0)), ((60.0, 20.0), (140.0, 170.0)), ((10.0, 0.0), (175.0, 90.0))] {
            let (i, o) = (dir(a.0, a.1), dir(b.0, b.1));
            let (fwd, back) = (m.eval(i, o), m.eval(o, i));
            assert!(fwd > 0.0, "{a:?} → {b:?}");
            // f_t(i, o)/η_o² = f_t(o, i)/η_i²: η_o = 1.5 inside, η_i = 1 outside.
            assert!((fwd / 2.25 - back).abs() <= 1e-4 * back.max(1.0), "{fwd} / 2.25 vs {back}");
            // Reflection is symmetric.
            let o2 = dir(b.0 - 90.0, b.1);
            assert!((m.eval(i, o2) - m.eval(o2, i)).abs() <= 1e-5 * m.eval(i, o2).max(1.0));
        }
    }

    #[test]
    fn hard_cases_stay_finite() {
        for roughness in [0.0, 1e-4, 0.3, 1.0] {
            let m = RoughDielectric::new(1.5, roughness);
            for (a, b) in [(0.0, 180.0), (89.99, 90.01), (90.0, 0.0), (45.0, 45.0), (0.0, 0.0), (60.0, 120.0)] {
                for phi in [0.0, 90.0, 180.0] {
                    let v = m.eval(dir(a, 0.0), dir(b, phi));
                    assert!(v.is_finite() && v >= 0.0, "roughness {roughness}, {a} → {b} at {phi}: {v}");
                }
            }
            let s = m.split(dir(89.9, 0.0), 16);
            assert!(s.reflected.is_finite() && s.transmitted.is_finite());
        }
        // η = 1: nothing reflects, and no half vector exists straight through.
        let same = RoughDielectric::new(1.0, 0.3);
        assert_eq!(same.eval(dir(30.0, 0.0), dir(150.0, 180.0)), 0.0);
    }

    /// Sampling agrees with the BSDF: E[f |l·n| / pdf] over the samples is ∫ f_s(l, v) |l·n| dω_l
    /// by quadrature, reflected and transmitted apart, from outside and from inside; and the
    /// pdf a sample reports is `pdf`'s.
    #[test]
    fn sampling_agrees_with_the_bsdf_on_both_sides() {
        for (roughness, theta) in [(0.3f32, 30.0f32), (0.6, 60.0), (0.3, 160.0), (0.5, 130.0)] {
            let m = RoughDielectric::new(1.5, roughness);
            let v = dir(theta, 20.0);
            let (mut refl, mut trans) = (0.0f64, 0.0f64);
            let n = 400u32;
            for a in 0..n {
                for b in 0..n {
                    let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
                    let u_lobe = ((a * 7 + b * 13) % n) as f32 / n as f32 + 0.5 / n as f32;
                    let Some(s) = m.sample(v, u_lobe, u) else { continue };
                    assert!((s.pdf / m.pdf(v, s.l) - 1.0).abs() < 1e-4, "{s:?}");
                    let w = (s.value * s.l.z.abs() / s.pdf) as f64;
                    if s.transmitted { trans += w } else { refl += w }
                }
            }
            let cells = (n * n) as f64;
            let (refl, trans) = (refl / cells, trans / cells);
            // The same integrals over l by the midpoint rule.
            let quad = |below: bool| hemisphere(below, 600, |l| m.eval(l, v));
            let above = v.z > 0.0;
            let (q_refl, q_trans) = (quad(!above), quad(above));
            assert!((refl - q_refl).abs() < 0.01 * q_refl.max(0.05), "α {} θ {theta}: reflected {refl} against {q_refl}", m.alpha);
            assert!((trans - q_trans).abs() < 0.01 * q_trans.max(0.05), "α {} θ {theta}: transmitted {trans} against {q_trans}", m.alpha);
        }
    }
}
