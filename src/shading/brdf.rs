//! The physically based BRDFs as one closed set, the local shading frame, and directional
//! albedo by deterministic quadrature.
//!
//! Every model is a pure function f(l, v) in 1/sr of two unit vectors in the **local frame**
//! (z = surface normal, x = tangent, y = bitangent), with `l` towards the light and `v` towards
//! the viewer, both pointing away from the surface. f excludes the cosine: the renderer forms
//! L_o = Σ f(l, v) E_l (n·l). All models are one-sided: f = 0 when n·l ≤ 0 or n·v ≤ 0.
//!
//! | variant | model | file |
//! | --- | --- | --- |
//! | [`Brdf::Diffuse`] | Lambert ρ/π | `diffuse.rs` |
//! | [`Brdf::CookTorrance`] | microfacet D·G·F/(4 (n·l)(n·v)) + ρ/π | `cook_torrance.rs`, `microfacet/` |
//! | [`Brdf::OrenNayar`] | rough diffuse (full and qualitative) | `oren_nayar.rs` |
//! | [`Brdf::Principled`] | Disney 2012 | `principled.rs` |
//! | [`Brdf::NormalizedPhong`] | k_d/π + k_s (n+2)/(2π) cos^n α_r | `normalized_phong.rs` |
//! | [`Brdf::NormalizedBlinnPhong`] | k_d/π + k_s (n+8)/(8π) cos^n θ_h | `normalized_phong.rs` |
//!
//! **Reciprocity.** Every model is reciprocal, f(l, v) = f(v, l): Lambert trivially;
//! Cook-Torrance because h, v·h = l·h and every G are symmetric; Oren-Nayar because it depends
//! on (max θ, min θ, cos Δφ); principled because each lobe is symmetric (F_L F_V, l·h = v·h);
//! normalized Phong because R(l)·v = R(v)·l, and Blinn-Phong because h is symmetric. Tested
//! for every model in the stability suite (`reciprocity*`).
//!
//! **Lobes and sampling** (pbrt-v4's BxDF interface, in `lobe.rs`): [`Brdf::lobes`] lists each
//! model's lobes with a kind and an albedo estimate (the one diffuse/specular split for
//! radiosity, the split sum and sampling), [`Brdf::eval_parts`] / [`Brdf::eval_part`] evaluate
//! the diffuse and specular parts the frame's layers show, [`Brdf::sample`] draws l with the
//! mixture pdf [`Brdf::pdf`]. Each model's file documents its parts, weights and strategies;
//! `sampling_tests.rs` checks them against each other (χ²) and against [`directional_albedo`].
//!
//! **Local frame.** [`local_frame`] builds a tangent and bitangent for any unit normal with the
//! branch-free construction of Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 6(1),
//! 2017, Listing 3); [`to_local`] projects a world vector onto it. The tangent it picks is
//! arbitrary (and flips where n.z changes sign), which only matters for the anisotropic principled
//! lobe; a mesh tangent can be passed to [`to_local`] instead.
//!
//! **Directional albedo.** ρ(v) = ∫ f(l, v) cos θ_l dω_l over the hemisphere, by [`directional_albedo`]:
//! a product Gauss-Legendre rule on panels in θ_l ∈ [0, π/2] and φ_l ∈ [0, 2π), graded
//! geometrically (widths 1e-6·2^k rad) towards the mirror direction of `v`, where every lobe of
//! these models peaks, and split at the horizon so each panel's integrand is smooth. The estimate
//! uses 2·`samples` nodes per panel and dimension; the reported error bound is the larger of
//! |A(2·samples) − A(samples)| (the change from halving the resolution) and the change when the
//! grid is displaced by a fraction of its finest panel (which exposes the f32 rounding of the
//! integration directions: at grazing incidence a needle lobe is narrower than the rounding
//! moves its half vector). It is an estimate, not a guarantee, and is reported as ∞ when the
//! lobe, [`Brdf::lobe_width`] × n·v across the plane of incidence, is narrower than 1e-5 rad
//! (e.g. α < 5e-6 at normal incidence, α < 1e-4 at n·v = 0.05, shininess > 2e10).

use super::cook_torrance::CookTorrance;
use super::diffuse::Diffuse;
use super::microfacet::clamp_alpha;
use super::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use super::oren_nayar::OrenNayar;
use super::principled::Principled;
use glam::{DVec3, Vec3};
use std::f32::consts::FRAC_PI_2;

/// A physically based BRDF (closed set, dispatched with `match`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Brdf {
    /// Lambert ρ/π.
    Diffuse(Diffuse),
    /// Cook-Torrance microfacet lobe with optional Lambert base.
    CookTorrance(CookTorrance),
    /// Oren-Nayar rough diffuse.
    OrenNayar(OrenNayar),
    /// Disney principled (Burley 2012).
    Principled(Principled),
    /// Normalized Phong.
    NormalizedPhong(NormalizedPhong),
    /// Normalized Blinn-Phong.
    NormalizedBlinnPhong(NormalizedBlinnPhong),
}

impl Brdf {
    /// The reflectance the ambient light sees when a lesson gives no `ambient`: the weight of
    /// the diffuse part (`Brdf::lobes`), e.g. the albedo, or the base colour × (1 − metallic).
    pub fn ambient_albedo(&self) -> glam::Vec3 {
        self.lobes().weight(super::lobe::Part::Diffuse)
    }

    /// f(l, v) in 1/sr (cosine excluded) for unit `l`, `v` in the local frame (z = normal).
    #[inline]
    pub fn eval(&self, l: Vec3, v: Vec3) -> Vec3 {
        match self {
            Brdf::Diffuse(m) => m.eval(l, v),
            Brdf::CookTorrance(m) => m.eval(l, v),
            Brdf::OrenNayar(m) => m.eval(l, v),
            Brdf::Principled(m) => m.eval(l, v),
            Brdf::NormalizedPhong(m) => m.eval(l, v),
            Brdf::NormalizedBlinnPhong(m) => m.eval(l, v),
        }
    }

    /// f for world-space unit vectors: `n` the shading normal, `l` and `v` away from the surface.
    #[inline]
    pub fn eval_world(&self, n: Vec3, l: Vec3, v: Vec3) -> Vec3 {
        let (t, b) = local_frame(n);
        self.eval(to_local(l, t, b, n), to_local(v, t, b, n))
    }

    /// Approximate angular width (radians) of the narrowest lobe of f as a function of `l`:
    /// 2α for microfacet lobes (h deviates by α, l by twice that), √(2/n) for a Phong lobe,
    /// 2√(2/n) for a Blinn-Phong lobe, π/2 for diffuse models.
    pub fn lobe_width(&self) -> f32 {
        let phong = |n: f32| if n > 0.0 { (2.0 / n).sqrt().min(FRAC_PI_2) } else { FRAC_PI_2 };
        match self {
            Brdf::Diffuse(_) | Brdf::OrenNayar(_) => FRAC_PI_2,
            Brdf::CookTorrance(m) => {
                if m.specular == Vec3::ZERO {
                    FRAC_PI_2
                } else {
                    (2.0 * clamp_alpha(m.alpha)).min(FRAC_PI_2)
                }
            }
            Brdf::Principled(m) => {
                let (ax, ay) = m.alphas();
                let cc = if m.clearcoat > 0.0 { m.clearcoat_alpha() } else { 1.0 };
                (2.0 * ax.min(ay).min(cc)).min(FRAC_PI_2)
            }
            Brdf::NormalizedPhong(m) => phong(m.shininess),
            Brdf::NormalizedBlinnPhong(m) => (2.0 * phong(m.shininess)).min(FRAC_PI_2),
        }
    }
}

impl Brdf {
    /// The perceptual roughness (√α) of the specular lobe, what a prefiltered environment is
    /// looked up with: √α of a microfacet lobe (√(α_x α_y) for the anisotropic principled
    /// one), √(half the lobe width) for a Phong lobe, 1 for the diffuse models.
    pub fn specular_roughness(&self) -> f32 {
        match self {
            Brdf::Diffuse(_) | Brdf::OrenNayar(_) => 1.0,
            Brdf::CookTorrance(c) => c.alpha.max(0.0).sqrt(),
            Brdf::Principled(p) => {
                let (ax, ay) = p.alphas();
                (ax * ay).sqrt().sqrt()
            }
            Brdf::NormalizedPhong(_) | Brdf::NormalizedBlinnPhong(_) => (0.5 * self.lobe_width()).clamp(0.0, 1.0).sqrt(),
        }
    }
}

/// Tangent and bitangent (t, b) completing the unit normal `n` to a right-handed orthonormal
/// basis (t × b = n), by Duff et al. 2017, Listing 3 (no branch near n = ±z, no division by
/// a small number).
///
/// Precondition: `n` is normalized.
#[inline]
pub fn local_frame(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bt = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    (t, bt)
}

/// `w` expressed in the frame (t, b, n): (w·t, w·b, w·n).
#[inline]
pub fn to_local(w: Vec3, t: Vec3, b: Vec3, n: Vec3) -> Vec3 {
    Vec3::new(w.dot(t), w.dot(b), w.dot(n))
}

/// `w` given in the local frame (t, b, n) back in world space: w_x t + w_y b + w_z n.
#[inline]
pub fn from_local(w: Vec3, t: Vec3, b: Vec3, n: Vec3) -> Vec3 {
    w.x * t + w.y * b + w.z * n
}

/// Smallest panel width (radians) of the graded quadrature.
const FINEST_PANEL: f64 = 1e-6;
/// Narrowest lobe (radians, as seen from the viewer) for which the quadrature is trusted.
const NARROWEST_RESOLVED_LOBE: f32 = 1e-5;

/// Directional albedo ρ(v) = ∫ f(l, v) cos θ_l dω_l of the largest channel, and its error bound.
///
/// `cos_theta_v` is n·v (the viewer sits in the xz-plane at azimuth 0); `samples` (≥ 1) is the
/// number of Gauss-Legendre nodes per panel and dimension of the coarse rule. Returns the fine
/// estimate A(2·samples) and the bound max(|A(2·samples) − A(samples)|, |A(2·samples) − A'(2·samples)|),
/// where A' uses the panel grid displaced by 0.37 of the finest panel (it exposes the f32
/// rounding of the integration directions, which matters for needle lobes at grazing
/// incidence). The bound is ∞ when the lobe is too narrow to resolve (module docs). Returns
/// (0, 0) for `cos_theta_v` ≤ 0.
pub fn directional_albedo(brdf: &Brdf, cos_theta_v: f64, samples: usize) -> (f64, f64) {
    let (albedo, error) = directional_albedo_rgb(brdf, cos_theta_v, samples);
    (albedo.max_element(), error.max_element())
}

/// Per-channel directional albedo A(2·`samples`) and per-channel error bound (see
/// [`directional_albedo`]).
pub fn directional_albedo_rgb(brdf: &Brdf, cos_theta_v: f64, samples: usize) -> (DVec3, DVec3) {
    if cos_theta_v <= 0.0 {
        return (DVec3::ZERO, DVec3::ZERO);
    }
    let c = cos_theta_v.min(1.0);
    let theta_v = c.acos();
    let v = Vec3::new((1.0 - c * c).max(0.0).sqrt() as f32, 0.0, c as f32);
    let samples = samples.max(1);
    let (coarse_rule, fine_rule) = (gauss_legendre(samples), gauss_legendre(2 * samples));
    // The mirror direction of v is at θ = θ_v, φ = π; every lobe here peaks at or near it.
    let grid = |shift: f64| {
        let theta = graded_breaks(0.0, std::f64::consts::FRAC_PI_2, theta_v + shift);
        // With v in the xz-plane the integrand is even in φ: an isotropic BRDF sees the
        // same n·l, n·v and l·v for l and its mirror image in that plane, and the
        // principled model's anisotropy has its axes along x and y (it reads h_y² and
        // l_y²). So the half φ ∈ [0, π] is integrated and doubled, with the same panels as
        // that half of [0, 2π] graded towards π.
        let phi = graded_breaks(0.0, std::f64::consts::PI, std::f64::consts::PI + shift);
        (theta, phi)
    };
    let (theta, phi) = grid(0.0);
    let fine = 2.0 * integrate(brdf, v, &theta, &phi, &fine_rule);
    let coarse = 2.0 * integrate(brdf, v, &theta, &phi, &coarse_rule);
    let (theta_s, phi_s) = grid(0.37 * FINEST_PANEL);
    let shifted = 2.0 * integrate(brdf, v, &theta_s, &phi_s, &fine_rule);
    let mut error = (fine - coarse).abs().max((fine - shifted).abs());
    // A specular lobe of width w seen at n·v = c is only w·c wide across the plane of incidence.
    let width = brdf.lobe_width();
    if width < FRAC_PI_2 && width * (c as f32) < NARROWEST_RESOLVED_LOBE {
        error = DVec3::INFINITY;
    }
    (fine, error)
}

/// Panel boundaries in [lo, hi] graded geometrically towards `center`: center ± 1e-6·2^k.
fn graded_breaks(lo: f64, hi: f64, center: f64) -> Vec<f64> {
    let mut breaks = vec![lo, hi];
    if center > lo && center < hi {
        breaks.push(center);
    }
    let mut w = FINEST_PANEL;
    while w < hi - lo {
        for x in [center - w, center + w] {
            if x > lo && x < hi {
                breaks.push(x);
            }
        }
        w *= 2.0;
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    breaks
}

/// ∫∫ f(l(θ, φ), v) cos θ sin θ dθ dφ over the panels, with the node set `rule` on [−1, 1].
fn integrate(brdf: &Brdf, v: Vec3, theta_breaks: &[f64], phi_breaks: &[f64], rule: &[(f64, f64)]) -> DVec3 {
    // The φ nodes are the same for every θ: their sin, cos and weight once (this halved
    // the time of an albedo chart; the sums are the same, term by term).
    let phi_nodes: Vec<(f64, f64, f64)> = phi_breaks
        .windows(2)
        .flat_map(|pw| {
            let (p0, p1) = (pw[0], pw[1]);
            rule.iter().map(move |&(xp, wp)| {
                let phi = 0.5 * (p1 - p0) * xp + 0.5 * (p1 + p0);
                let (sp, cp) = phi.sin_cos();
                (sp, cp, 0.5 * (p1 - p0) * wp)
            })
        })
        .collect();
    let mut total = DVec3::ZERO;
    for tw in theta_breaks.windows(2) {
        let (t0, t1) = (tw[0], tw[1]);
        for &(xt, wt) in rule {
            let theta = 0.5 * (t1 - t0) * xt + 0.5 * (t1 + t0);
            let (st, ct) = theta.sin_cos();
            let weight_theta = 0.5 * (t1 - t0) * wt * ct * st;
            let mut row = DVec3::ZERO;
            for &(sp, cp, w) in &phi_nodes {
                let l = Vec3::new((st * cp) as f32, (st * sp) as f32, ct as f32);
                row += w * brdf.eval(l, v).as_dvec3();
            }
            total += weight_theta * row;
        }
    }
    total
}

/// Gauss-Legendre nodes and weights on [−1, 1] (Newton iteration on the Legendre polynomial P_n).
pub(crate) fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut rule = Vec::with_capacity(n);
    for i in 0..n {
        // Chebyshev-like initial guess, then Newton on the Legendre recurrence.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            // p1 = P_n(x), p0 = P_{n−1}(x); P_n'(x) = n (x P_n − P_{n−1}) / (x² − 1).
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        rule.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    rule
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_right_handed() {
        for n in [Vec3::Z, -Vec3::Z, Vec3::X, Vec3::new(0.3, -0.4, 0.5).normalize(), Vec3::new(1e-8, 0.0, -1.0).normalize()] {
            let (t, b) = local_frame(n);
            assert!((t.length() - 1.0).abs() < 1e-6 && (b.length() - 1.0).abs() < 1e-6);
            assert!(t.dot(b).abs() < 1e-6 && t.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6);
            assert!((t.cross(b) - n).length() < 1e-6, "{n}");
            let w = Vec3::new(0.2, 0.5, -0.3);
            assert!((from_local(to_local(w, t, b, n), t, b, n) - w).length() < 1e-6);
        }
    }

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        for n in [1usize, 2, 5, 16] {
            let rule = gauss_legendre(n);
            let sum_w: f64 = rule.iter().map(|&(_, w)| w).sum();
            assert!((sum_w - 2.0).abs() < 1e-13);
            // x^(2n−2) integrates to 2/(2n−1).
            let k = 2 * n as i32 - 2;
            let integral: f64 = rule.iter().map(|&(x, w)| w * x.powi(k)).sum();
            assert!((integral - 2.0 / (k + 1) as f64).abs() < 1e-12, "n={n}");
        }
    }

    #[test]
    fn lambert_albedo_is_rho() {
        let brdf = Brdf::Diffuse(Diffuse { albedo: Vec3::new(0.25, 0.5, 0.75) });
        for c in [1.0, 0.5, 1e-3] {
            let (a, e) = directional_albedo(&brdf, c, 4);
            assert!((a - 0.75).abs() < 1e-6 && e < 1e-6, "cos={c}: {a} ± {e}");
        }
    }

    #[test]
    fn world_eval_matches_local() {
        let brdf = Brdf::CookTorrance(CookTorrance::default());
        let n = Vec3::new(0.2, 0.9, -0.1).normalize();
        let (t, b) = local_frame(n);
        let l = from_local(Vec3::new(0.3, 0.1, 0.9).normalize(), t, b, n);
        let v = from_local(Vec3::new(-0.5, 0.2, 0.7).normalize(), t, b, n);
        let a = brdf.eval_world(n, l, v);
        let c = brdf.eval(Vec3::new(0.3, 0.1, 0.9).normalize(), Vec3::new(-0.5, 0.2, 0.7).normalize());
        assert!((a - c).abs().max_element() < 1e-5 * c.max_element());
    }
}
