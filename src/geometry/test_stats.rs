//! Test helpers for the samplers: independent (white-noise) samples and Pearson's χ² test.
//!
//! χ² needs independent samples: stratified ones match a histogram better than chance, so a
//! test on them would pass a wrong pdf more easily. The critical value is the Wilson–Hilferty
//! approximation of the χ² quantile, χ²_{k,1−α} ≈ k (1 − 2/(9k) + z_α √(2/(9k)))³ (E. B. Wilson
//! and M. M. Hilferty, "The distribution of chi-square", PNAS 17, 1931), at most 1.2 % above
//! the exact quantile for k ≥ 10 at the α used here (checked below).

use super::sampling::hash3;
use glam::Vec2;

/// The standard normal quantile of 1 − α for α = 10⁻⁴: the significance of each χ² test.
/// (The tests are deterministic, so a correct sampler either always passes or always fails;
/// 10⁻⁴ keeps the chance that a correct one was unlucky at the one draw small.)
const Z: f64 = 3.719;

/// An independent uniform value in [0, 1) for sample `k` of stream `seed`.
pub(crate) fn independent_1d(k: u32, seed: u32) -> f32 {
    (hash3(k, seed, 0x1d) >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// An independent uniform point in [0, 1)² for sample `k` of stream `seed`.
pub(crate) fn independent_2d(k: u32, seed: u32) -> Vec2 {
    let c = |d: u32| (hash3(k, seed, d) >> 8) as f32 * (1.0 / (1u32 << 24) as f32);
    Vec2::new(c(0x2d0), c(0x2d1))
}

/// Pearson's χ² of `observed` counts against `expected` counts (same length), after pooling
/// bins whose expectation is below 5 with their neighbours (as pbrt-v4's `Chi2Test`); returns
/// (χ², degrees of freedom).
pub(crate) fn chi2(observed: &[f64], expected: &[f64]) -> (f64, usize) {
    assert_eq!(observed.len(), expected.len());
    let (mut stat, mut bins) = (0.0, 0usize);
    let (mut o_pool, mut e_pool) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        if e == 0.0 {
            assert!(o == 0.0, "a sample fell where the pdf is 0");
            continue;
        }
        o_pool += o;
        e_pool += e;
        if e_pool >= 5.0 {
            stat += (o_pool - e_pool) * (o_pool - e_pool) / e_pool;
            bins += 1;
            o_pool = 0.0;
            e_pool = 0.0;
        }
    }
    if e_pool > 0.0 {
        stat += (o_pool - e_pool) * (o_pool - e_pool) / e_pool;
        bins += 1;
    }
    (stat, bins.saturating_sub(1))
}

/// The χ² critical value at significance 10⁻⁴ for `dof` degrees of freedom (Wilson–Hilferty).
pub(crate) fn chi2_critical(dof: usize) -> f64 {
    let k = dof as f64;
    let a = 2.0 / (9.0 * k);
    k * (1.0 - a + Z * a.sqrt()).powi(3)
}

/// Asserts that `observed` fits `expected` by Pearson's χ² at significance 10⁻⁴.
pub(crate) fn chi2_test(name: &str, observed: &[f64], expected: &[f64]) {
    let total_o: f64 = observed.iter().sum();
    let total_e: f64 = expected.iter().sum();
    assert!(
        (total_o - total_e).abs() < 1e-6 * total_e + 1e-9,
        "{name}: {total_o} samples binned, {total_e} expected (pdf not normalized?)"
    );
    let (stat, dof) = chi2(observed, expected);
    let critical = chi2_critical(dof);
    assert!(dof >= 10, "{name}: only {dof} degrees of freedom");
    assert!(stat < critical, "{name}: χ² = {stat:.1} ≥ {critical:.1} ({dof} dof)");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_critical_values_match_tables() {
        // Exact χ² quantiles at 1 − 10⁻⁴ (by bisection on the regularized incomplete gamma
        // function): Wilson–Hilferty is 1.2 % high at 10 dof (slightly lenient), 0.1 % at 63.
        for (dof, want) in [(10, 35.564), (20, 52.386), (63, 113.505), (100, 161.319), (255, 347.654)] {
            let got = chi2_critical(dof);
            assert!(got >= want && got / want - 1.0 < 0.012, "{dof}: {got} vs {want}");
        }
    }

    #[test]
    fn chi2_rejects_a_wrong_histogram_and_accepts_a_fair_one() {
        // 64 bins of uniform independent samples pass; the same samples against a slanted pdf
        // (a 10 % tilt) fail.
        let n = 100_000;
        let mut observed = vec![0.0; 64];
        for k in 0..n {
            observed[(independent_1d(k, 3) * 64.0) as usize] += 1.0;
        }
        let fair = vec![n as f64 / 64.0; 64];
        let (stat, dof) = chi2(&observed, &fair);
        assert!(stat < chi2_critical(dof), "{stat}");
        let tilted: Vec<f64> = (0..64).map(|i| n as f64 / 64.0 * (0.95 + 0.1 * (i as f64 + 0.5) / 64.0)).collect();
        let (stat, dof) = chi2(&observed, &tilted);
        assert!(stat > chi2_critical(dof), "{stat}");
    }
}
