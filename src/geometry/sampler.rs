//! Where the N samples of a light (or a fog march) fall in [0, 1)^d: independent, stratified
//! or low-discrepancy, each a pure function of (sample index, N, stream seed) so a pixel gets
//! the same samples on every run and thread (DESIGN.md, Determinism).
//!
//! - [`Sampler::Independent`]: every coordinate its own hash — plain Monte Carlo, error
//!   ∝ N^(−1/2) and white-noise grain, the baseline the lesson `sampling` shows;
//! - [`Sampler::Stratified`]: correlated multi-jittered sampling (A. Kensler, "Correlated
//!   Multi-Jittered Sampling", Pixar Technical Memo 13-01, 2013, §3–4: `permute`,
//!   `randfloat`, `cmj`): one sample in each of N 1D strata per axis and in each cell of an
//!   m × ⌈N/m⌉ grid, for any N;
//! - [`Sampler::Sobol`]: shuffled, Owen-scrambled Sobol points (Burley 2020, [`super::sobol`]):
//!   a (0, m, 2)-net for every power of two, the default.
//!
//! The seed names the stream: a hash of the shaded point, the light and the purpose.

use super::sampling::hash;
use super::sobol::{sobol_1d, sobol_2d};
use glam::Vec2;

/// Whose light samples they are (`[render] sample_pattern`): each shaded point its own
/// scrambled pattern (grain where the estimate is off), or one pattern for every point, as a
/// rasterizer that renders the light as N fixed points does (Eevee's soft shadows): the
/// error then varies smoothly from point to point and shows as steps (a penumbra of N + 1
/// bands) instead of grain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SamplePattern {
    /// Each shaded point hashes its own pattern.
    #[default]
    PerPoint,
    /// Every shaded point uses the same N samples of a light.
    Shared,
}

impl SamplePattern {
    /// Every pattern with its name in lesson files.
    pub const NAMES: [(&'static str, SamplePattern); 2] = [("per_point", SamplePattern::PerPoint), ("shared", SamplePattern::Shared)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            SamplePattern::PerPoint => "per_point",
            SamplePattern::Shared => "shared",
        }
    }

    /// The stream seed of a point whose own seed is `point`: itself, or one for all points.
    #[inline]
    pub fn point(self, point: u32) -> u32 {
        match self {
            SamplePattern::PerPoint => point,
            SamplePattern::Shared => 0x5ba2_ed01,
        }
    }
}

/// How sample points are placed (`[render] sampler`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Sampler {
    /// Independent hashed uniforms: white noise.
    Independent,
    /// Correlated multi-jittered strata (Kensler 2013).
    Stratified,
    /// Shuffled Owen-scrambled Sobol points (Burley 2020).
    #[default]
    Sobol,
}

impl Sampler {
    /// Every sampler with its name in lesson files.
    pub const NAMES: [(&'static str, Sampler); 3] =
        [("independent", Sampler::Independent), ("stratified", Sampler::Stratified), ("sobol", Sampler::Sobol)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            Sampler::Independent => "independent",
            Sampler::Stratified => "stratified",
            Sampler::Sobol => "sobol",
        }
    }

    /// Sample `k` of `n` (k < n) in [0, 1)² of the stream `seed`.
    #[inline]
    pub fn u2(self, k: u32, n: u32, seed: u32) -> Vec2 {
        match self {
            Sampler::Independent => Vec2::new(unit(hash(hash(seed ^ 0x2545_f491) ^ k)), unit(hash(hash(seed ^ 0x9e37_79b9) ^ k))),
            Sampler::Stratified => cmj(k, n.max(1), seed),
            Sampler::Sobol => sobol_2d(k, seed),
        }
    }

    /// Sample `k` of `n` (k < n) in [0, 1) of the stream `seed`.
    #[inline]
    pub fn u1(self, k: u32, n: u32, seed: u32) -> f32 {
        match self {
            Sampler::Independent => unit(hash(hash(seed ^ 0x6a09_e667) ^ k)),
            Sampler::Stratified => {
                // One sample per stratum [j/n, (j+1)/n), the strata visited in a hashed order.
                let n = n.max(1);
                let j = permute(k % n, n, seed.wrapping_mul(0x51633e2d));
                ((j as f32 + randfloat(k, seed.wrapping_mul(0x967a889b))) / n as f32).min(ONE_BELOW)
            }
            Sampler::Sobol => sobol_1d(k, seed),
        }
    }
}

/// The largest f32 below 1.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

/// A u32 as a uniform in [0, 1): its top 24 bits, exact in f32.
#[inline]
fn unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// Kensler 2013, `permute`: a hashed permutation of 0..l applied to i (cycle-walking within
/// the next power of two).
#[inline]
fn permute(mut i: u32, l: u32, p: u32) -> u32 {
    let mut w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | p >> 27);
        i = i.wrapping_mul(0x6935fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dcb303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e501cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860a3df);
        i &= w;
        i ^= i >> 5;
        if i < l {
            break;
        }
    }
    (i.wrapping_add(p)) % l
}

/// Kensler 2013, `randfloat`: a hashed uniform in [0, 1).
#[inline]
fn randfloat(mut i: u32, p: u32) -> f32 {
    i ^= p;
    i ^= i >> 17;
    i ^= i >> 10;
    i = i.wrapping_mul(0xb36534e5);
    i ^= i >> 12;
    i ^= i >> 21;
    i = i.wrapping_mul(0x93fc4795);
    i ^= 0xdf6e307f;
    i ^= i >> 17;
    i = i.wrapping_mul(1 | p >> 18);
    // i·(1/4294967808) as the memo has it, rounded to f32 and kept below 1.
    ((i as f64 / 4_294_967_808.0) as f32).min(ONE_BELOW)
}

/// Kensler 2013, `cmj`: sample s of N, correlated multi-jittered on an m × ⌈N/m⌉ grid with
/// m = ⌊√N⌋, pattern `p`.
#[inline]
fn cmj(s: u32, n_total: u32, p: u32) -> Vec2 {
    let m = ((n_total as f32).sqrt() as u32).max(1);
    let n = n_total.div_ceil(m);
    let s = permute(s % n_total, n_total, p.wrapping_mul(0x51633e2d));
    let sx = permute(s % m, m, p.wrapping_mul(0x68bc21eb));
    let sy = permute(s / m, n, p.wrapping_mul(0x02e5be93));
    let jx = randfloat(s, p.wrapping_mul(0x967a889b));
    let jy = randfloat(s, p.wrapping_mul(0x368cc8b7));
    let x = (sx as f32 + (sy as f32 + jx) / n as f32) / m as f32;
    let y = (s as f32 + jy) / n_total as f32;
    Vec2::new(x.min(ONE_BELOW), y.min(ONE_BELOW))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every sampler stays in [0, 1)² and repeats itself bit for bit.
    #[test]
    fn samples_lie_in_the_unit_square_and_are_deterministic() {
        for sampler in [Sampler::Independent, Sampler::Stratified, Sampler::Sobol] {
            for n in [1u32, 2, 3, 7, 16, 17, 64, 100] {
                for seed in [0u32, 1, 0xdead_beef] {
                    for k in 0..n {
                        let u = sampler.u2(k, n, seed);
                        assert!(u.x >= 0.0 && u.x < 1.0 && u.y >= 0.0 && u.y < 1.0, "{sampler:?} {k}/{n}: {u}");
                        assert_eq!(u.to_array().map(f32::to_bits), sampler.u2(k, n, seed).to_array().map(f32::to_bits));
                        let v = sampler.u1(k, n, seed);
                        assert!((0.0..1.0).contains(&v));
                    }
                }
            }
        }
    }

    /// Correlated multi-jittering is a permutation of strata: N samples put exactly one in
    /// each of N rows (1D strata of y) and each of the m columns gets ⌈N/m⌉ or fewer, and
    /// its 1D stream one in each [j/N, (j+1)/N).
    #[test]
    fn stratified_samples_fill_every_stratum_once() {
        for n in [4u32, 9, 10, 16, 37, 64] {
            for seed in 0..20u32 {
                let mut rows = vec![0; n as usize];
                let mut strata = vec![0; n as usize];
                for k in 0..n {
                    let u = Sampler::Stratified.u2(k, n, seed);
                    rows[(u.y * n as f32) as usize] += 1;
                    strata[(Sampler::Stratified.u1(k, n, seed) * n as f32) as usize] += 1;
                }
                assert!(rows.iter().all(|&c| c == 1), "n {n} seed {seed}: {rows:?}");
                assert!(strata.iter().all(|&c| c == 1), "n {n} seed {seed}: {strata:?}");
            }
        }
        // A square count is a full jittered grid too: one sample per cell.
        let mut cells = [0; 16];
        for k in 0..16 {
            let u = Sampler::Stratified.u2(k, 16, 3);
            cells[(u.y * 4.0) as usize * 4 + (u.x * 4.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
    }

    /// The mean of a smooth integrand (∫∫ x y dx dy = 1/4) over many patterns: every sampler
    /// is unbiased, and at N = 16 the stratified and Sobol errors are far below independent
    /// ones (measured RMSE over 2000 streams: independent 0.055, stratified 0.014, Sobol 0.0069).
    #[test]
    fn stratified_and_sobol_estimates_are_unbiased_and_far_less_noisy() {
        let (n, streams) = (16u32, 2000u32);
        let rmse = |s: Sampler| {
            let (mut sum, mut sq) = (0.0f64, 0.0f64);
            for seed in 0..streams {
                let est: f64 = (0..n).map(|k| s.u2(k, n, hash(seed)).to_array().iter().product::<f32>() as f64).sum::<f64>() / n as f64;
                sum += est;
                sq += (est - 0.25) * (est - 0.25);
            }
            (sum / streams as f64, (sq / streams as f64).sqrt())
        };
        let (mi, ri) = rmse(Sampler::Independent);
        let (ms, rs) = rmse(Sampler::Stratified);
        let (mq, rq) = rmse(Sampler::Sobol);
        for (m, r) in [(mi, ri), (ms, rs), (mq, rq)] {
            // Within 4 standard errors of 1/4.
            assert!((m - 0.25).abs() < 4.0 * r / (streams as f64).sqrt(), "mean {m} rmse {r}");
        }
        assert!(rs < ri / 3.0 && rq < ri / 6.0, "independent {ri}, stratified {rs}, sobol {rq}");
    }
}
