//! The Henyey-Greenstein phase function (Henyey & Greenstein 1941, "Diffuse radiation in
//! the galaxy", ApJ 93, eq. 1), in 1/sr.
//!
//! p(cos θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^(3/2)), θ the scattering angle between the
//! direction light travels before and after scattering; g = ⟨cos θ⟩ in (−1, 1): 0 isotropic
//! (p = 1/4π), g > 0 forward, g < 0 backward. pbrt-v4 (`HenyeyGreenstein` in
//! `util/scattering.h`) writes the same function of cos = wo·wi with both directions
//! pointing away from the point, hence its `+ 2g cos`; here `cos_theta` = l·d, with l the
//! unit vector towards the light and d the eye ray's direction (away from the eye), which is
//! the cosine of θ: g > 0 makes a light seen behind the fog glow.

/// p(cos θ) in 1/sr for asymmetry `g` (precondition: |g| < 1, so the denominator is at least
/// (1 − |g|)³ > 0: finite for |g| = 0.99, where the peak is 1.99/(4π·10⁻⁴) ≈ 1584/sr).
#[inline]
pub fn henyey_greenstein(cos_theta: f32, g: f32) -> f32 {
    let c = cos_theta.clamp(-1.0, 1.0) as f64;
    let g = g as f64;
    let denom = 1.0 + g * g - 2.0 * g * c;
    // denom ≥ (1 − |g|)² > 0 for |c| ≤ 1; the max guards rounding at c = ±1.
    let denom = denom.max((1.0 - g.abs()).powi(2));
    ((1.0 - g * g) / (4.0 * std::f64::consts::PI * denom * denom.sqrt())) as f32
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// ∫ p dω over the sphere = 2π ∫_{−1}^{1} p(μ) dμ, by composite Gauss-Legendre in μ on
    /// panels that are fine where the peak is (μ = ±1 for |g| near 1).
    fn integral(g: f32) -> f64 {
        let (x, w) = gauss_legendre_8();
        let mut sum = 0.0;
        // Geometric panels towards both ends: the peak is 1 − |g| wide.
        let mut edges = vec![0.0f64];
        let mut h = 1e-6;
        while h < 1.0 {
            edges.push(h);
            h *= 1.25;
        }
        edges.push(1.0);
        for side in [-1.0f64, 1.0] {
            for pair in edges.windows(2) {
                // μ from side·(1 − e) : panels measured from the end μ = side.
                let (a, b) = (side * (1.0 - pair[1]), side * (1.0 - pair[0]));
                let (mid, half) = ((a + b) / 2.0, (b - a) / 2.0);
                for k in 0..8 {
                    sum += w[k] * half.abs() * henyey_greenstein((mid + half * x[k]) as f32, g) as f64;
                }
            }
        }
        2.0 * std::f64::consts::PI * sum
    }

    pub(crate) fn gauss_legendre_8() -> ([f64; 8], [f64; 8]) {
        (
            [
                -0.960_289_856_497_536_3,
                -0.796_666_477_413_626_7,
                -0.525_532_409_916_329,
                -0.183_434_642_495_649_8,
                0.183_434_642_495_649_8,
                0.525_532_409_916_329,
                0.796_666_477_413_626_7,
                0.960_289_856_497_536_3,
            ],
            [
                0.101_228_536_290_376_26,
                0.222_381_034_453_374_47,
                0.313_706_645_877_887_3,
                0.362_683_783_378_362,
                0.362_683_783_378_362,
                0.313_706_645_877_887_3,
                0.222_381_034_453_374_47,
                0.101_228_536_290_376_26,
            ],
        )
    }

    #[test]
    fn integrates_to_one_over_the_sphere_even_at_g_099() {
        for g in [-0.99f32, -0.5, 0.0, 0.3, 0.9, 0.99] {
            let i = integral(g);
            eprintln!("g = {g}: ∫p dω − 1 = {:.1e}", i - 1.0);
            assert!((i - 1.0).abs() < 1e-4, "g = {g}: ∫p dω = {i}");
        }
    }

    #[test]
    fn isotropic_is_one_over_four_pi_and_forward_peaks_at_cos_one() {
        for c in [-1.0f32, -0.3, 0.0, 0.7, 1.0] {
            assert!((henyey_greenstein(c, 0.0) - 1.0 / (4.0 * std::f32::consts::PI)).abs() < 1e-7);
        }
        // g > 0 peaks forward (cos θ = 1): (1 + g)/(4π (1 − g)²).
        let g = 0.99f32;
        let peak = (1.0 + 0.99f64) / (4.0 * std::f64::consts::PI * 0.01f64.powi(2));
        assert!((henyey_greenstein(1.0, g) as f64 / peak - 1.0).abs() < 1e-5);
        assert!(henyey_greenstein(-1.0, g) < henyey_greenstein(0.0, g));
        // pbrt's convention: p_pbrt(wo·wi) with both away from the point is p(−wo·wi) here.
        assert_eq!(henyey_greenstein(0.4, -0.6), henyey_greenstein(-0.4, 0.6));
        // Finite and positive everywhere at the extremes of g.
        for g in [-0.99f32, 0.99] {
            for k in 0..=200 {
                let p = henyey_greenstein(-1.0 + k as f32 / 100.0, g);
                assert!(p.is_finite() && p > 0.0, "g {g}: {p}");
            }
        }
    }
}
