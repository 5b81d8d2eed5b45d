//! Importance sampling of microfacet normals h and of cosine-power lobes, with the solid-angle
//! pdf of the reflected direction l = 2(v·h)h − v.
//!
//! | strategy | h drawn with pdf | used by | source |
//! | --- | --- | --- | --- |
//! | [`HalfVector::VisibleGgx`] | D_v(h) = G1(v) max(0, v·h) D(h) / (n·v) | GGX with Smith masking (Cook-Torrance), principled specular (anisotropic) | Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), Listing 1 |
//! | [`HalfVector::NormalCos`] GGX | D(h) cos θ_h, tan θ_h = α √(ξ/(1 − ξ)) | GGX with V-cavity masking | Walter et al. 2007, eqs. 35–36 |
//! | [`HalfVector::NormalCos`] Beckmann | D(h) cos θ_h, tan²θ_h = −α² ln(1 − ξ) | Beckmann | Walter et al. 2007, eqs. 28–29 |
//! | [`HalfVector::NormalCos`] Blinn | D(h) cos θ_h = (k + 2)/(2π) cos^{k+1} θ_h, cos θ_h = (1 − ξ)^{1/(k+2)} | Blinn NDF (k = 2/α² − 2) | Walter et al. 2007, eqs. 30 and 14 (inverting the cos^{k+1} CDF) |
//! | [`HalfVector::NormalCos`] Gaussian | q(h) = θ e^{−θ²/α²} / (π α² Z sin θ), a truncated Rayleigh law in θ_h, Z = 1 − e^{−π²/(4α²)} | Gaussian NDF | a proposal (see below) |
//! | [`HalfVector::Gtr1`] | D_GTR1(h) cos θ_h, cos²θ_h = (1 − α^{2(1−ξ)})/(1 − α²) | principled clearcoat | Burley 2012, Appendix B, eq. 2 |
//! | [`HalfVector::CosPower`] | (k + 1)/(2π) cos^k θ_h | normalized Blinn-Phong (k = n + 1); [`cos_power_direction`] about the mirror direction for normalized Phong (k = n) | as Blinn above |
//!
//! The pdf of l follows from the Jacobian of the reflection, dω_h/dω_l = 1/(4 v·h) (Walter et
//! al. 2007, eq. 14): p(l) = p(h)/(4 v·h) (eq. 38). For the visible normals it simplifies to
//! p(l) = G1(v) D(h)/(4 n·v) = D(h)/(4 (n·v + Λ(v) n·v)), which needs no division by a cosine
//! and stays finite at grazing v. v·h is taken as |l + v|/2 ([`half_vector_and_cos`]).
//!
//! **Gaussian.** The Torrance-Sparrow D ∝ e^{−θ²/α²} has no invertible D·cos CDF. Its
//! half vectors are drawn from the proposal q above, whose θ density (2θ/α²) e^{−θ²/α²}/Z on
//! [0, π/2] is the small-angle form of D cos θ sin θ; the pdf reported is q's, exactly, so
//! estimators stay unbiased. q/(D cos) = (θ/sin θ)(1/cos θ) N(α)/(π α² Z) ≥ N(α)/(π α² Z), which is
//! ≥ 0.89 for α ≤ 0.4 (the series of N) and ≥ 0.40 for α ≤ 3 (test `gaussian_proposal_covers_d_cos`):
//! q covers D·cos everywhere, so the weights f cos/p stay bounded.
//!
//! A sampled h can reflect v below the surface (l.z ≤ 0): the sample is lost (`None`); the
//! pdf of l then integrates to less than 1 over the upper hemisphere (measured in the tests).
//! Samples u are clamped to [0, 1 − 2⁻²⁴] so u = 1 cannot reach a logarithm of 0.

use super::ndf::{Ndf, blinn_exponent, cos_pow, gaussian, ggx_aniso, ggx_lambda_cos, gtr1};
use super::{clamp_alpha, half_vector_and_cos};
use crate::geometry::sampling::sin_cos;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, PI, TAU};

/// The largest f32 below 1: sample coordinates are clamped to it.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// How the half vectors of a microfacet or cosine-power lobe are drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HalfVector {
    /// GGX visible normals (Heitz 2018), anisotropic widths α_x (along local x) and α_y.
    VisibleGgx {
        /// Width along the tangent.
        alpha_x: f32,
        /// Width along the bitangent.
        alpha_y: f32,
    },
    /// D(h) cos θ_h for an isotropic distribution (the Gaussian through its proposal).
    NormalCos {
        /// The distribution.
        ndf: Ndf,
        /// Its width α (clamped to [`ALPHA_MIN`](super::ALPHA_MIN) here).
        alpha: f32,
    },
    /// D_GTR1(h) cos θ_h (principled clearcoat).
    Gtr1 {
        /// The clearcoat width α.
        alpha: f32,
    },
    /// (k + 1)/(2π) cos^k θ_h.
    CosPower {
        /// The exponent k ≥ 0.
        k: f32,
    },
}

impl HalfVector {
    /// A direction l = 2(v·h)h − v (local frame, unit) for u in [0, 1)²; `None` when it falls
    /// below the surface or h is degenerate. Precondition: `v` unit with v.z > 0.
    #[inline]
    pub fn sample(&self, v: Vec3, u: Vec2) -> Option<Vec3> {
        let u = u.clamp(Vec2::ZERO, Vec2::splat(ONE_MINUS_EPSILON));
        let h = match *self {
            HalfVector::VisibleGgx { alpha_x, alpha_y } => ggx_visible_normal(v, clamp_alpha(alpha_x), clamp_alpha(alpha_y), u)?,
            HalfVector::NormalCos { ndf, alpha } => normal_cos(ndf, clamp_alpha(alpha), u),
            HalfVector::Gtr1 { alpha } => gtr1_normal(clamp_alpha(alpha), u),
            HalfVector::CosPower { k } => cos_power_direction(u, k),
        };
        let l = reflect_about(v, h)?;
        (l.z > 0.0).then_some(l)
    }

    /// The solid-angle pdf (1/sr) of [`sample`](Self::sample) returning `l`; 0 when l.z ≤ 0
    /// or v.z ≤ 0.
    #[inline]
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return 0.0;
        }
        let (h, v_dot_h) = half_vector_and_cos(l, v);
        let p = match *self {
            // Heitz 2018, eq. 3 with the Jacobian 1/(4 v·h): G1(v) D(h) / (4 n·v), and G1(v)/n·v = 1/(n·v + Λ n·v).
            HalfVector::VisibleGgx { alpha_x, alpha_y } => {
                let (ax, ay) = (clamp_alpha(alpha_x), clamp_alpha(alpha_y));
                ggx_aniso(h, ax, ay) / (4.0 * (v.z + ggx_lambda_cos(v, ax, ay)))
            }
            HalfVector::NormalCos { ndf, alpha } => normal_cos_pdf(ndf, clamp_alpha(alpha), h) / (4.0 * v_dot_h),
            HalfVector::Gtr1 { alpha } => gtr1(h, clamp_alpha(alpha)) * h.z / (4.0 * v_dot_h),
            HalfVector::CosPower { k } => cos_power_pdf(h.z, h.x * h.x + h.y * h.y, k) / (4.0 * v_dot_h),
        };
        // p ≤ f32::MAX: near a needle lobe's peak at grazing v the true value can exceed f32.
        p.min(f32::MAX)
    }
}

/// The mirror image of `v` about the unit normal `h`, 2(v·h)h − v, renormalized; `None` when
/// v·h ≤ 0 (no facet with normal h reflects towards v).
#[inline]
pub fn reflect_about(v: Vec3, h: Vec3) -> Option<Vec3> {
    let vh = v.dot(h);
    if vh <= 0.0 {
        return None;
    }
    normalize_scaled(2.0 * vh * h - v)
}

/// `w` / |w|, dividing by the largest component first so that tiny vectors normalize too;
/// `None` for the zero vector or a non-finite one.
#[inline]
fn normalize_scaled(w: Vec3) -> Option<Vec3> {
    let m = w.abs().max_element();
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let s = w / m;
    Some(s / s.length())
}

/// A unit direction about +z from cos θ and sin θ and the azimuth sample `u_phi`.
#[inline]
fn spherical(cos_theta: f32, sin_theta: f32, u_phi: f32) -> Vec3 {
    let (sin_phi, cos_phi) = sin_cos(TAU * u_phi);
    Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta)
}

/// A visible GGX normal seen from `v` (Heitz 2018, Listing 1), for u in [0, 1)².
///
/// pdf D_v(h) = G1(v) max(0, v·h) D(h)/v.z. `None` only when the stretched vectors vanish
/// (not for unit v with v.z > 0 and α ≥ `ALPHA_MIN`).
#[inline]
pub fn ggx_visible_normal(v: Vec3, alpha_x: f32, alpha_y: f32, u: Vec2) -> Option<Vec3> {
    // Section 3.2: the view direction in the configuration where the ellipsoid is a hemisphere.
    let vh = normalize_scaled(Vec3::new(alpha_x * v.x, alpha_y * v.y, v.z))?;
    // Section 4.1: a basis about vh (any tangent when vh is the pole).
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 { Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt() } else { Vec3::X };
    let t2 = vh.cross(t1);
    // Section 4.2: a uniform point on the projected area, the disk with its lower half squeezed.
    let r = u.x.sqrt();
    let (sin_phi, cos_phi) = sin_cos(TAU * u.y);
    let p1 = r * cos_phi;
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * ((1.0 - p1) * (1.0 + p1)).max(0.0).sqrt() + s * (r * sin_phi);
    // Section 4.3: lifted onto the hemisphere; Section 3.4: back to the ellipsoid.
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    normalize_scaled(Vec3::new(alpha_x * nh.x, alpha_y * nh.y, nh.z.max(0.0)))
}

/// A microfacet normal with pdf D(h) cos θ_h (Gaussian: the proposal of the module docs).
/// Precondition: `alpha` ≥ `ALPHA_MIN`, u in [0, 1)².
#[inline]
pub fn normal_cos(ndf: Ndf, alpha: f32, u: Vec2) -> Vec3 {
    let xi = u.x;
    match ndf {
        Ndf::Ggx => {
            // Walter et al. 2007, eq. 35 as cos² = (1 − ξ)/(1 − ξ + α²ξ), sin² = α²ξ/(1 − ξ + α²ξ):
            // no tangent, so ξ → 1 and α → 0 stay finite and exact.
            let a2 = alpha * alpha;
            let den = (1.0 - xi) + a2 * xi;
            spherical(((1.0 - xi) / den).sqrt(), (a2 * xi / den).sqrt(), u.y)
        }
        Ndf::Beckmann => {
            // Walter et al. 2007, eq. 28: tan²θ = −α² ln(1 − ξ) (finite: ξ ≤ 1 − 2⁻²⁴).
            let t2 = -(alpha * alpha) * (-xi).ln_1p();
            let c2 = 1.0 / (1.0 + t2);
            spherical(c2.sqrt(), (t2 * c2).sqrt(), u.y)
        }
        Ndf::Blinn => cos_power_direction(u, blinn_exponent(alpha) + 1.0),
        Ndf::Gaussian => {
            // The truncated Rayleigh proposal: θ = α √(−ln(1 − ξ Z)), θ ≤ π/2.
            let z = gaussian_proposal_mass(alpha);
            let theta = (alpha * (-(-(xi * z)).ln_1p()).sqrt()).min(FRAC_PI_2);
            let (s, c) = sin_cos(theta);
            spherical(c, s, u.y)
        }
    }
}

/// Z = 1 − e^{−π²/(4α²)}: the mass of the untruncated Rayleigh law inside θ ≤ π/2.
#[inline]
fn gaussian_proposal_mass(alpha: f32) -> f32 {
    let x = FRAC_PI_2 / alpha;
    -(-(x * x)).exp_m1()
}

/// The pdf (1/sr) of [`normal_cos`] at the unit normal `h`: D(h) cos θ_h, or the
/// Gaussian's proposal q(h).
#[inline]
pub fn normal_cos_pdf(ndf: Ndf, alpha: f32, h: Vec3) -> f32 {
    if h.z <= 0.0 {
        return 0.0;
    }
    match ndf {
        Ndf::Ggx | Ndf::Beckmann | Ndf::Blinn => ndf.d(h, alpha) * h.z,
        Ndf::Gaussian => {
            let sin_theta = (h.x * h.x + h.y * h.y).sqrt();
            let theta = sin_theta.atan2(h.z);
            // θ / sin θ → 1 at the pole (0/0 there).
            let ratio = if sin_theta > 0.0 { theta / sin_theta } else { 1.0 };
            let e = (-(theta / alpha).powi(2)).exp();
            ratio * e / (PI * alpha * alpha * gaussian_proposal_mass(alpha))
        }
    }
    .min(f32::MAX)
}

/// The Gaussian's D(h) cos θ_h, for comparing with its proposal in tests.
#[inline]
pub fn gaussian_d_cos(h: Vec3, alpha: f32) -> f32 {
    gaussian(h, alpha) * h.z.max(0.0)
}

/// A clearcoat normal with pdf D_GTR1(h) cos θ_h (Burley 2012, Appendix B):
/// cos²θ = (1 − α^{2(1−ξ)})/(1 − α²); for α ≥ 1 (D = 1/π) the cosine-weighted cos²θ = 1 − ξ.
#[inline]
pub fn gtr1_normal(alpha: f32, u: Vec2) -> Vec3 {
    if alpha >= 1.0 {
        let c2 = 1.0 - u.x;
        return spherical(c2.sqrt(), u.x.sqrt(), u.y);
    }
    let a2 = alpha * alpha;
    let p = ((1.0 - u.x) * a2.ln()).exp(); // α^{2(1−ξ)} ∈ [α², 1]
    // sin²θ = (α^{2(1−ξ)} − α²)/(1 − α²) written directly: exact near the pole.
    let s2 = ((p - a2) / (1.0 - a2)).clamp(0.0, 1.0);
    let c2 = ((1.0 - p) / (1.0 - a2)).clamp(0.0, 1.0);
    spherical(c2.sqrt(), s2.sqrt(), u.y)
}

/// A direction about +z with pdf (k + 1)/(2π) cos^k θ: cos θ = (1 − ξ)^{1/(k+1)}, with
/// sin²θ = −expm1(2 ln(1 − ξ)/(k + 1)) so lobes of k = 1e6 and beyond keep their width.
/// Precondition: k ≥ 0 (negative k is taken as 0), u in [0, 1)².
#[inline]
pub fn cos_power_direction(u: Vec2, k: f32) -> Vec3 {
    let e = (-u.x).ln_1p() / (k.max(0.0) + 1.0);
    spherical(e.exp(), (-(2.0 * e).exp_m1()).max(0.0).sqrt(), u.y)
}

/// The pdf (k + 1)/(2π) cos^k θ of [`cos_power_direction`], from cos θ and sin²θ
/// ([`cos_pow`]: 0 for cos θ ≤ 0).
#[inline]
pub fn cos_power_pdf(cos_theta: f32, sin2_theta: f32, k: f32) -> f32 {
    let k = k.max(0.0);
    (k + 1.0) * (0.5 * FRAC_1_PI) * cos_pow(cos_theta, sin2_theta, k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A normal sampler integrates to 1 over the hemisphere of h: ∫ p(h) dω_h by a midpoint rule
    /// in (cos θ, φ) refined near the pole, where the narrow lobes live.
    fn integral_over_h(p: impl Fn(Vec3) -> f32) -> f64 {
        let mut sum = 0.0f64;
        // θ panels graded towards 0: [0, 1e-4], [1e-4, 2e-4], ..., up to π/2.
        let mut edges = vec![0.0f64];
        let mut w = 1e-4;
        while edges.last().unwrap() + w < std::f64::consts::FRAC_PI_2 {
            edges.push(edges.last().unwrap() + w);
            w *= 1.25;
        }
        edges.push(std::f64::consts::FRAC_PI_2);
        for e in edges.windows(2) {
            let nt = 16;
            for i in 0..nt {
                let t = e[0] + (e[1] - e[0]) * (i as f64 + 0.5) / nt as f64;
                let dt = (e[1] - e[0]) / nt as f64;
                let np = 8;
                for j in 0..np {
                    let phi = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
                    let h = Vec3::new((t.sin() * phi.cos()) as f32, (t.sin() * phi.sin()) as f32, t.cos() as f32);
                    sum += p(h) as f64 * t.sin() * dt * std::f64::consts::TAU / np as f64;
                }
            }
        }
        sum
    }

    #[test]
    fn normal_pdfs_integrate_to_one() {
        for alpha in [0.01f32, 0.2, 0.7, 1.0, 1.5] {
            for ndf in Ndf::ALL {
                if ndf == Ndf::Blinn && alpha > 1.0 {
                    continue; // Blinn caps α at 1: the same law as α = 1.
                }
                let i = integral_over_h(|h| normal_cos_pdf(ndf, alpha, h));
                assert!((i - 1.0).abs() < 2e-3, "{ndf:?} α={alpha}: {i}");
            }
        }
        for alpha in [0.001f32, 0.05, 0.1] {
            let i = integral_over_h(|h| gtr1(h, alpha) * h.z);
            assert!((i - 1.0).abs() < 2e-3, "GTR1 α={alpha}: {i}");
        }
        for k in [0.0f32, 3.0, 300.0] {
            let i = integral_over_h(|h| cos_power_pdf(h.z, h.x * h.x + h.y * h.y, k));
            assert!((i - 1.0).abs() < 2e-3, "k={k}: {i}");
        }
    }

    #[test]
    fn gaussian_proposal_covers_d_cos() {
        // q/(D cos) bounded below (the proposal is never much narrower than the target).
        for alpha in [0.01f32, 0.3, 1.0, 3.0] {
            let mut min_ratio = f32::INFINITY;
            for i in 0..200 {
                let t = (i as f32 + 0.5) / 200.0 * FRAC_PI_2;
                let h = Vec3::new(t.sin(), 0.0, t.cos());
                let d = gaussian_d_cos(h, alpha);
                if d > 1e-30 {
                    min_ratio = min_ratio.min(normal_cos_pdf(Ndf::Gaussian, alpha, h) / d);
                }
            }
            assert!(min_ratio > if alpha <= 0.4 { 0.89 } else { 0.4 }, "α={alpha}: {min_ratio}");
        }
    }

    #[test]
    fn visible_normals_face_the_viewer_and_stay_finite() {
        let v = Vec3::new(85f32.to_radians().sin(), 0.0, 85f32.to_radians().cos());
        for (ax, ay) in [(1e-12f32, 1e-12f32), (0.01, 0.01), (0.5, 0.05), (1.0, 1.0)] {
            for k in 0..400 {
                let u = crate::geometry::sampling::sample_2d(k, 7).clamp(Vec2::ZERO, Vec2::splat(ONE_MINUS_EPSILON));
                let h = ggx_visible_normal(v, ax, ay, u).expect("unit v above the surface");
                assert!(h.is_finite() && (h.length() - 1.0).abs() < 1e-5 && h.z >= 0.0, "{h}");
                assert!(v.dot(h) >= -1e-6, "a visible normal faces v: {h}");
            }
        }
        // Degenerate corners of the unit square.
        for u in [Vec2::ZERO, Vec2::new(ONE_MINUS_EPSILON, 0.0), Vec2::splat(ONE_MINUS_EPSILON), Vec2::new(0.0, ONE_MINUS_EPSILON)] {
            for ndf in Ndf::ALL {
                for alpha in [1e-12f32, 0.3, 2.0] {
                    let h = normal_cos(ndf, alpha, u);
                    assert!(h.is_finite() && (h.length() - 1.0).abs() < 1e-5 && h.z >= 0.0, "{ndf:?} α={alpha} u={u}: {h}");
                }
            }
            assert!(gtr1_normal(0.001, u).is_finite() && cos_power_direction(u, 1e9).is_finite());
        }
    }

    #[test]
    fn cos_power_keeps_narrow_lobes() {
        // k = 1e8: θ ≈ √(−ln(1 − ξ)/k)·… ~ 1e-4, far below where cos θ rounds to 1.
        let d = cos_power_direction(Vec2::new(0.5, 0.0), 1e8);
        let want = (2.0 * (2f64.ln()) / (1e8 + 1.0)).sqrt();
        assert!((d.x as f64 / want - 1.0).abs() < 1e-4, "{} vs {want}", d.x);
    }
}
