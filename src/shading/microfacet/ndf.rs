//! Microfacet normal distribution functions D(m) and Smith's Λ.
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `ndf` | `blinn`, `beckmann`, `ggx`, `gaussian` | `ggx` | which distribution of microfacet normals |
//! | `alpha` α | [0, 1] (GGX, Beckmann, Gaussian accept α > 1) | 0.25 | width of the distribution ≈ RMS slope; α = roughness² |
//!
//! Every D is normalized so that the projected microfacet area is the macro-surface area,
//! ∫ D(m) (n·m) dω_m = 1 (checked numerically in the stability suite), and is zero for m.z ≤ 0.
//! With θ the angle between m and n:
//!
//! | name | D(m) | source |
//! | --- | --- | --- |
//! | Blinn (normalized Phong NDF) | (k + 2)/(2π) cos^k θ, with k = 2/α² − 2 | Blinn 1977; normalization and the Beckmann-equivalent exponent k = 2α⁻² − 2: Walter et al. 2007, eq. 30 and §5.2 |
//! | Beckmann | exp(−tan²θ / α²) / (π α² cos⁴θ) | Beckmann & Spizzichino 1963; Walter et al. 2007, eq. 25 |
//! | GGX / Trowbridge-Reitz | α² / (π cos⁴θ (α² + tan²θ)²) = 1 / (π α² (cos²θ + sin²θ/α²)²) | Trowbridge & Reitz 1975; Walter et al. 2007, eq. 33 |
//! | GGX anisotropic | 1 / (π α_x α_y (m_x²/α_x² + m_y²/α_y² + m_z²)²) | Burley 2012, Appendix B (anisotropic GTR2) |
//! | Gaussian (Torrance-Sparrow) | exp(−θ²/α²) / N(α) | Torrance & Sparrow 1967, eq. 12; Cook & Torrance 1982 |
//! | GTR1 (Berry), clearcoat only | (α² − 1) / (π ln(α²) (1 + (α² − 1) cos²θ)) | Burley 2012, eq. 4 with γ = 1 (normalized in Appendix B) |
//!
//! **Gaussian normalization.** Torrance and Sparrow leave the constant free; here it is chosen
//! so that ∫ D cos θ dω = 1 over the hemisphere: N(α) = 2π ∫₀^{π/2} exp(−θ²/α²) sin θ cos θ dθ.
//! For α ≤ 0.4 the series N = π α² Σ_k (−2α²)^k / (2k+1)!! is used (it integrates to θ = ∞;
//! the part beyond π/2 is below 7e-9 relative); for α > 0.4 a 16-term Chebyshev expansion in
//! β = 1/α² on [0, 6.25], fitted to 400-point Gauss-Legendre quadrature (max relative error
//! 2.5e-9, verified by the unit test `gaussian_normalization_matches_quadrature`). As α → 0,
//! N → πα² and the Gaussian, Beckmann and GGX peaks coincide at 1/(πα²).
//!
//! **Smith Λ.** G1(w, m) = χ⁺(w·m) / (1 + Λ(w)). GGX: Λ = (√(1 + α² tan²θ) − 1)/2 (Heitz 2014,
//! eq. 72; anisotropic with α² tan²θ → (α_x² w_x² + α_y² w_y²)/w_z², eq. 86). Beckmann: the rational
//! approximation of Walter et al. 2007, eq. 27 (the one Mitsuba 3 and pbrt-v3 use; < 0.35 %
//! from the exact erf form), written as Λ = (1 − 1.259a + 0.396a²)/(3.535a + 2.181a²) for
//! a = 1/(α tan θ) < 1.6, else 0. Blinn and Gaussian have no closed-form Λ; they use the
//! Beckmann Λ at the same α, as Walter et al. 2007 (eq. 31 for Phong) recommend, so their weak
//! white furnace holds only approximately (tolerances in the stability suite).
//!
//! **Numerics.** Every D is written in terms of sin²θ = m_x² + m_y² and cos²θ = m_z², never
//! 1 − cos²θ, so narrow lobes (α = 1e-4) keep full f32 relative precision near their peak.
//! α is raised to [`ALPHA_MIN`] (a Dirac delta cannot be represented); Blinn also caps α at 1
//! (k ≥ 0).

use super::ALPHA_MIN;
use glam::Vec3;
use std::f32::consts::PI;

/// The distributions of microfacet normals (a closed set, dispatched with `match`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ndf {
    /// Normalized Blinn-Phong lobe (k + 2)/(2π) cos^k θ with k = 2/α² − 2.
    Blinn,
    /// Beckmann: a Gaussian distribution of slopes.
    Beckmann,
    /// GGX / Trowbridge-Reitz: long tails, the modern default.
    #[default]
    Ggx,
    /// Torrance-Sparrow Gaussian in the angle θ, normalized numerically.
    Gaussian,
}

impl Ndf {
    /// All distributions, for tests and figures.
    pub const ALL: [Ndf; 4] = [Ndf::Blinn, Ndf::Beckmann, Ndf::Ggx, Ndf::Gaussian];

    /// The lesson-file name (`blinn`, `beckmann`, `ggx`, `gaussian`).
    pub fn name(self) -> &'static str {
        match self {
            Ndf::Blinn => "blinn",
            Ndf::Beckmann => "beckmann",
            Ndf::Ggx => "ggx",
            Ndf::Gaussian => "gaussian",
        }
    }

    /// D(m) in 1/sr for the unit microfacet normal `m` (local frame); 0 when m.z ≤ 0.
    #[inline]
    pub fn d(self, m: Vec3, alpha: f32) -> f32 {
        match self {
            Ndf::Blinn => blinn(m, alpha),
            Ndf::Beckmann => beckmann(m, alpha),
            Ndf::Ggx => ggx(m, alpha),
            Ndf::Gaussian => gaussian(m, alpha),
        }
    }

    /// Smith's Λ(w) for the unit direction `w`; +∞ at the horizon (w.z = 0).
    #[inline]
    pub fn lambda(self, w: Vec3, alpha: f32) -> f32 {
        self.lambda_cos(w, alpha) / w.z.abs()
    }

    /// Λ(w)·|w.z|: finite everywhere, including the horizon, so G1 and V can be formed
    /// without dividing by a cosine.
    #[inline]
    pub fn lambda_cos(self, w: Vec3, alpha: f32) -> f32 {
        match self {
            Ndf::Ggx => ggx_lambda_cos(w, alpha, alpha),
            // No closed-form Λ: Beckmann's at the same α (Walter et al. 2007, eq. 31).
            Ndf::Beckmann | Ndf::Blinn | Ndf::Gaussian => beckmann_lambda_cos(w, alpha),
        }
    }

    /// Smith's masking G1(w, m) = χ⁺(w·m) / (1 + Λ(w)), in [0, 1].
    #[inline]
    pub fn g1(self, w: Vec3, m: Vec3, alpha: f32) -> f32 {
        if w.dot(m) * w.z <= 0.0 {
            return 0.0;
        }
        let z = w.z.abs();
        z / (z + self.lambda_cos(w, alpha))
    }

    /// True when Λ is the exact Smith Λ of this D (GGX), false when it is an approximation
    /// (Beckmann's rational fit, and the Beckmann Λ borrowed by Blinn and Gaussian).
    pub fn has_exact_lambda(self) -> bool {
        matches!(self, Ndf::Ggx)
    }
}

/// The Blinn exponent equivalent to Beckmann width α: k = 2/α² − 2 (Walter et al. 2007, §5.2).
#[inline]
pub fn blinn_exponent(alpha: f32) -> f32 {
    let a = alpha.clamp(ALPHA_MIN, 1.0);
    2.0 / (a * a) - 2.0
}

/// The inverse of [`blinn_exponent`]: α = √(2/(k + 2)).
#[inline]
pub fn alpha_from_blinn_exponent(k: f32) -> f32 {
    (2.0 / (k.max(0.0) + 2.0)).sqrt()
}

/// cos^k θ for a lobe clipped to the front half-space, from cos θ and sin²θ.
///
/// Returns 0 when `cos ≤ 0` (for every k ≥ 0, also k = 0: the k → 0⁺ limit, so the lobe is
/// continuous in k). For `sin2 < 0.5` the logarithm is ½·ln_1p(−sin²θ), exact to f32 precision
/// even when cos θ rounds to 1, so k = 1e6 lobes keep their shape; otherwise ln(cos θ).
/// Preconditions: `sin2` = sin²θ of the same angle, `k` ≥ 0 and finite.
#[inline]
pub fn cos_pow(cos: f32, sin2: f32, k: f32) -> f32 {
    if cos <= 0.0 {
        return 0.0;
    }
    if k == 0.0 {
        return 1.0;
    }
    let ln_cos = if sin2 < 0.5 { 0.5 * (-sin2).ln_1p() } else { cos.ln() };
    (k * ln_cos).exp()
}

/// Normalized Blinn D(m) = (k + 2)/(2π) cos^k θ = cos^k θ / (π α²), k = 2/α² − 2.
///
/// α is clamped to [`ALPHA_MIN`, 1]: for α > 1 the exponent is negative and D is infinite
/// at the horizon.
#[inline]
pub fn blinn(m: Vec3, alpha: f32) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a = alpha.clamp(ALPHA_MIN, 1.0);
    let a2 = a * a;
    let k = 2.0 / a2 - 2.0;
    cos_pow(m.z, m.x * m.x + m.y * m.y, k) / (PI * a2)
}

/// Beckmann D(m) = exp(−tan²θ/α²) / (π α² cos⁴θ) (Walter et al. 2007, eq. 25).
///
/// Returns 0 once exp(−tan²θ/α²) underflows: the limit there is 0 and it avoids 0/0 at the
/// horizon.
#[inline]
pub fn beckmann(m: Vec3, alpha: f32) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a2 = alpha.max(ALPHA_MIN).powi(2);
    let c2 = m.z * m.z;
    let s2 = m.x * m.x + m.y * m.y;
    let e = (-(s2 / (a2 * c2))).exp();
    if e == 0.0 {
        return 0.0;
    }
    e / (PI * a2 * c2 * c2)
}

/// Isotropic GGX D(m) = 1 / (π α² (cos²θ + sin²θ/α²)²) (Walter et al. 2007, eq. 33).
#[inline]
pub fn ggx(m: Vec3, alpha: f32) -> f32 {
    ggx_aniso(m, alpha, alpha)
}

/// Anisotropic GGX D(m) = 1 / (π α_x α_y (m_x²/α_x² + m_y²/α_y² + m_z²)²); α_x along the
/// tangent (local x), α_y along the bitangent (local y).
///
/// When the bracket squared overflows, D → 1/∞ = 0, the correct limit.
#[inline]
pub fn ggx_aniso(m: Vec3, alpha_x: f32, alpha_y: f32) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let ax = alpha_x.max(ALPHA_MIN);
    let ay = alpha_y.max(ALPHA_MIN);
    let q = (m.x / ax).powi(2) + (m.y / ay).powi(2) + m.z * m.z;
    1.0 / (PI * ax * ay * q * q)
}

/// Gaussian (Torrance-Sparrow) D(m) = exp(−θ²/α²) / N(α), normalized so ∫ D cos θ dω = 1.
#[inline]
pub fn gaussian(m: Vec3, alpha: f32) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a = alpha.max(ALPHA_MIN);
    let theta = (m.x * m.x + m.y * m.y).sqrt().atan2(m.z);
    let e = (-(theta / a).powi(2)).exp();
    if e == 0.0 {
        return 0.0;
    }
    e / gaussian_normalization(a)
}

/// Chebyshev coefficients of N(α) in t = 0.32/α² − 1 for α > 0.4 (see the module docs).
const GAUSSIAN_CHEBYSHEV: [f64; 17] = [
    1.2312221894139261,
    -1.1197604128896996,
    0.48145044877412807,
    -0.1951248855653698,
    0.07439438860260467,
    -0.0266564219989033,
    0.008975071538205944,
    -0.0028410867957223617,
    0.0008464442317951877,
    -0.00023767901709828551,
    6.300489088519981e-05,
    -1.5795022615901868e-05,
    3.751707090819901e-06,
    -8.458759494062316e-07,
    1.8136385577043056e-07,
    -3.704578413604304e-08,
    7.2214164707469704e-09,
];

/// N(α) = 2π ∫₀^{π/2} exp(−θ²/α²) sin θ cos θ dθ, the Gaussian NDF's normalization.
#[inline]
pub fn gaussian_normalization(alpha: f32) -> f32 {
    let a = alpha.max(ALPHA_MIN);
    if a <= 0.4 {
        // π α² Σ_k (−2α²)^k / (2k+1)!!: 8 terms reach 1e-10 for α ≤ 0.4.
        let x = -2.0 * a * a;
        let mut sum = 0.0;
        let mut term = 1.0;
        for k in 0..8 {
            sum += term;
            term *= x / (2 * k + 3) as f32;
        }
        PI * a * a * sum
    } else {
        // Clenshaw recurrence for Σ c_j T_j(t), t ∈ [−1, 1) for α ∈ (0.4, ∞).
        let t = (0.32 / (a as f64 * a as f64) - 1.0).clamp(-1.0, 1.0);
        let (mut b1, mut b2) = (0.0f64, 0.0f64);
        for &c in GAUSSIAN_CHEBYSHEV.iter().skip(1).rev() {
            let b0 = 2.0 * t * b1 - b2 + c;
            b2 = b1;
            b1 = b0;
        }
        (t * b1 - b2 + GAUSSIAN_CHEBYSHEV[0]) as f32
    }
}

/// Berry's GTR1 (γ = 1) used by the principled clearcoat:
/// D = (α² − 1) / (π ln(α²) (α² cos²θ + sin²θ)); 1/π for α ≥ 1 (its limit, as in Burley's code).
#[inline]
pub fn gtr1(m: Vec3, alpha: f32) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a = alpha.max(ALPHA_MIN);
    if a >= 1.0 {
        return 1.0 / PI;
    }
    let a2 = a * a;
    let t = a2 * m.z * m.z + (m.x * m.x + m.y * m.y);
    (a2 - 1.0) / (PI * a2.ln() * t)
}

/// GGX Λ(w)·|w.z| = (√(w_z² + α_x² w_x² + α_y² w_y²) − |w_z|)/2, written without cancellation.
#[inline]
pub fn ggx_lambda_cos(w: Vec3, alpha_x: f32, alpha_y: f32) -> f32 {
    let z = w.z.abs();
    let q = (alpha_x.max(ALPHA_MIN) * w.x).powi(2) + (alpha_y.max(ALPHA_MIN) * w.y).powi(2);
    q / (2.0 * ((z * z + q).sqrt() + z))
}

/// GGX Λ(w) (Heitz 2014, eqs. 72 and 86); +∞ at the horizon.
#[inline]
pub fn ggx_lambda(w: Vec3, alpha_x: f32, alpha_y: f32) -> f32 {
    ggx_lambda_cos(w, alpha_x, alpha_y) / w.z.abs()
}

/// Beckmann Λ(w)·|w.z| from Walter et al. 2007, eq. 27, finite at the horizon.
///
/// With r = α sin θ and a = |w.z|/r: Λ·|w.z| = r (1 − 1.259a + 0.396a²)/(3.535 + 2.181a) for
/// a < 1.6, else 0. The rational fit dips to −6e-5 for a ∈ (1.548, 1.6); it is clamped at 0,
/// which also makes it continuous at a = 1.6 (Mitsuba 3 has a 6e-5 step there).
#[inline]
pub fn beckmann_lambda_cos(w: Vec3, alpha: f32) -> f32 {
    let z = w.z.abs();
    let r = alpha.max(ALPHA_MIN) * (w.x * w.x + w.y * w.y).sqrt();
    if z >= 1.6 * r {
        return 0.0;
    }
    let a = z / r;
    (r * (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 + 2.181 * a)).max(0.0)
}

/// Beckmann Λ(w) (rational approximation, Walter et al. 2007, eq. 27); +∞ at the horizon.
#[inline]
pub fn beckmann_lambda(w: Vec3, alpha: f32) -> f32 {
    beckmann_lambda_cos(w, alpha) / w.z.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    #[test]
    fn peaks_are_one_over_pi_alpha_squared() {
        for a in [0.05f32, 0.3, 1.0] {
            let expect = 1.0 / (PI * a * a);
            for ndf in Ndf::ALL {
                let d = ndf.d(Vec3::Z, a);
                // The Gaussian's N(α) departs from πα² as α grows (N(1) = 1.7206).
                let expect = if ndf == Ndf::Gaussian { 1.0 / gaussian_normalization(a) } else { expect };
                assert!((d / expect - 1.0).abs() < 1e-5, "{ndf:?} α={a}: {d} vs {expect}");
            }
        }
    }

    #[test]
    fn ggx_closed_form_at_45_degrees() {
        // θ = 45°: tan²θ = 1, cos⁴θ = 1/4, D = α² / (π/4 (α² + 1)²).
        let a = 0.5f32;
        let d = ggx(dir(PI / 4.0, 0.3), a);
        let expect = a * a / (PI * 0.25 * (a * a + 1.0).powi(2));
        assert!((d / expect - 1.0).abs() < 1e-6);
    }

    #[test]
    fn beckmann_closed_form_at_30_degrees() {
        let a = 0.3f32;
        let t2 = (PI / 6.0).tan().powi(2);
        let c4 = (PI / 6.0).cos().powi(4);
        let expect = (-t2 / (a * a)).exp() / (PI * a * a * c4);
        assert!((beckmann(dir(PI / 6.0, 1.0), a) / expect - 1.0).abs() < 1e-5);
    }

    #[test]
    fn blinn_exponent_round_trip() {
        for a in [0.01f32, 0.2, 0.7, 1.0] {
            let k = blinn_exponent(a);
            assert!((alpha_from_blinn_exponent(k) - a).abs() < 1e-5);
        }
        assert_eq!(blinn_exponent(1.0), 0.0);
    }

    #[test]
    fn cos_pow_is_accurate_when_cos_rounds_to_one() {
        // θ = 1e-4: cos θ = 1 − 5e-9 rounds to 1.0 in f32, yet cos^1e6 θ = e^{−0.005}.
        let s = 1e-4f32;
        let c = (1.0 - s * s).sqrt();
        assert_eq!(c, 1.0);
        let v = cos_pow(c, s * s, 1e6);
        assert!((v - (-0.005f32).exp()).abs() < 1e-6, "{v}");
        assert_eq!(cos_pow(0.0, 1.0, 0.0), 0.0);
        assert_eq!(cos_pow(0.5, 0.75, 0.0), 1.0);
    }

    #[test]
    fn gaussian_normalization_matches_quadrature() {
        // Independent check: 2000-point midpoint rule in f64 against the series/Chebyshev form.
        for a in [1e-3f64, 0.05, 0.2, 0.39, 0.4, 0.41, 0.7, 1.0, 3.0, 30.0] {
            let n = 20000;
            let hi = (std::f64::consts::FRAC_PI_2).min(12.0 * a);
            let h = hi / n as f64;
            let q: f64 = (0..n)
                .map(|i| {
                    let t = (i as f64 + 0.5) * h;
                    (-(t / a).powi(2)).exp() * t.sin() * t.cos()
                })
                .sum::<f64>()
                * h
                * 2.0
                * std::f64::consts::PI;
            let got = gaussian_normalization(a as f32) as f64;
            assert!((got / q - 1.0).abs() < 2e-6, "α={a}: {got} vs {q}");
        }
    }

    #[test]
    fn ggx_lambda_matches_textbook_form() {
        let w = dir(1.2, 0.4);
        let a = 0.6f32;
        let t2 = 1.2f32.tan().powi(2);
        let expect = ((1.0 + a * a * t2).sqrt() - 1.0) / 2.0;
        assert!((ggx_lambda(w, a, a) / expect - 1.0).abs() < 1e-5);
        assert_eq!(ggx_lambda(Vec3::Z, a, a), 0.0);
        assert_eq!(Ndf::Ggx.g1(Vec3::X, Vec3::Z, a), 0.0);
    }

    #[test]
    fn beckmann_lambda_is_continuous_and_non_negative() {
        // Sweep a = 1/(α tan θ) through the end of the rational fit at 1.6.
        let alpha = 0.5f32;
        let mut prev = f32::NAN;
        for i in 0..2000 {
            let a = 1.4 + 0.3 * i as f32 / 2000.0;
            let theta = (1.0 / (alpha * a)).atan();
            let l = beckmann_lambda(dir(theta, 0.0), alpha);
            assert!(l >= 0.0);
            if prev.is_finite() {
                assert!((l - prev).abs() < 1e-4, "jump at a={a}");
            }
            prev = l;
        }
    }

    #[test]
    fn gtr1_limit_at_alpha_one() {
        let m = dir(0.7, 0.0);
        assert!((gtr1(m, 0.9999) - 1.0 / PI).abs() < 1e-3);
        assert_eq!(gtr1(m, 1.0), 1.0 / PI);
    }
}
