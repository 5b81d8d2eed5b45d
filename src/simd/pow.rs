//! A deterministic x^k for the classic lobes and the spot cone, written once for one value
//! or for lanes, and the log₂ inside it on its own ([`log2`], for AgX's log encoding in
//! `render::develop`).
//!
//! **Why not `f32::powf`.** It is a call into the C library on every sample (16% of a
//! per-pixel Blinn-Phong render), and glibc picks its implementation at run time
//! (`__powf_fma` on CPUs with FMA), so its last bit is not guaranteed to be the same on
//! every x86-64 machine. This one uses only IEEE-754 add, multiply, divide and exact bit
//! manipulation in f32/f64, which give the same bits everywhere, and inlines into the
//! shading loops (a loop over lanes vectorizes).
//!
//! **Method.** Both paths work in f64 and round once to f32 at the end:
//! - integer k ≤ [`INTEGER_MAX`] (K_shi = 32 and most lesson exponents): binary powering,
//!   x^k by ⌊log₂ k⌋ squarings and popcount(k) products (Knuth, TAOCP vol. 2, §4.6.3);
//!   relative error before the final rounding ≤ k·2⁻⁵³ ≤ 2⁻⁴³;
//! - otherwise 2^(k·log₂ x): x = m·2^e with m ∈ [√½, √2) taken exactly from the bits;
//!   ln m = 2 atanh(s), s = (m − 1)/(m + 1), |s| ≤ 0.172, by its series to s¹⁷ (truncation
//!   < 1.1e-15 relative); 2^t = 2^n · 2^f with n = round(t) (exact, by the 1.5·2⁵² trick)
//!   and 2^f, |f| ≤ ½, by its Taylor series to degree 11 (truncation < 7e-15). The error of
//!   t = k·log₂ x is ≤ 2.3e-15·|t| and only |t| ≤ 152 matters (below that the result
//!   underflows to 0), so the f64 result is within 2⁻⁴¹ relative of x^k.
//!
//! **Error bound.** After the one rounding to f32: ≤ 0.5 + 2⁻¹⁷ ULP of the exact x^k
//! (correctly rounded except when x^k lies within 2⁻¹⁷ ULP of a rounding midpoint); tested
//! against f64 `powf` over bases 0, denormals, 1 − 2⁻²⁴, 1 and random values, with
//! exponents 0, 1e-6, ½, integers, 1e4, 1e6 and random ones.
//!
//! **Domain.** x ≥ 0 (shading passes a clamped cosine in [0, 1]) or NaN, k ≥ 0 finite.
//! Special values follow `powf`: x⁰ = 1 for every x (NaN included), 0^k = 0 for k > 0,
//! 1^k = 1, NaN^k = NaN for k > 0, +∞^k = +∞ for k > 0; a negative x gives NaN unless k is
//! an integer ≤ [`INTEGER_MAX`] (then the signed power, as `powf`).

/// Integer exponents up to this use binary powering (error ≤ k·2⁻⁵³ before rounding).
pub const INTEGER_MAX: f32 = 1024.0;

/// x^k, deterministic and within 0.5 + 2⁻¹⁷ ULP (see the module docs for the domain).
#[inline]
pub fn pow(x: f32, k: f32) -> f32 {
    pow_lanes([x], k)[0]
}

/// x^k for every lane of `x` with one exponent (the same formula as [`pow`], lane by lane;
/// branches and loops depend only on `k`, so every step is a loop over lanes that vectorizes).
#[inline(always)]
pub fn pow_lanes<const N: usize>(x: [f32; N], k: f32) -> [f32; N] {
    if k == 0.0 {
        // x⁰ = 1 for every x, as powf (0⁰ = 1, NaN⁰ = 1).
        return [1.0; N];
    }
    let mut out = [0f32; N];
    if k <= INTEGER_MAX && (k as u32) as f32 == k {
        // Binary powering, right to left: x^n = Π x^(2^j) over the set bits j of n, each
        // product and square rounded once in f64.
        let mut n = k as u32;
        let mut b = [0f64; N];
        for (b, &x) in b.iter_mut().zip(&x) {
            *b = x as f64;
        }
        let mut r = [1f64; N];
        loop {
            if n & 1 == 1 {
                for (r, b) in r.iter_mut().zip(&b) {
                    *r *= b;
                }
            }
            n >>= 1;
            if n == 0 {
                break;
            }
            for b in b.iter_mut() {
                *b *= *b;
            }
        }
        for (o, r) in out.iter_mut().zip(&r) {
            *o = *r as f32;
        }
        return out;
    }
    for (o, &x) in out.iter_mut().zip(&x) {
        *o = exp2_log2(x, k);
    }
    out
}

/// Bits of √½ in f32: x's mantissa is reduced to [√½, √2).
const SQRT_HALF_BITS: u32 = 0x3f35_04f3;
/// 2/ln 2 divided by 1, 3, 5, ..., 17: log₂ m = s · Σ C[j] s^(2j) (the atanh series).
const LOG2_SERIES: [f64; 9] = {
    let c = 2.0 * std::f64::consts::LOG2_E;
    [c, c / 3.0, c / 5.0, c / 7.0, c / 9.0, c / 11.0, c / 13.0, c / 15.0, c / 17.0]
};
/// (ln 2)^j / j! for j = 0..=11: 2^f = Σ E[j] f^j (the Taylor series of e^(f ln 2)).
const EXP2_SERIES: [f64; 12] = {
    let ln2 = std::f64::consts::LN_2;
    let mut e = [1.0f64; 12];
    let mut j = 1;
    while j < 12 {
        e[j] = e[j - 1] * ln2 / j as f64;
        j += 1;
    }
    e
};
/// Adding and subtracting 1.5·2⁵² rounds an f64 of magnitude < 2⁵¹ to the nearest integer.
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;

/// log₂ x in f64 for a positive finite x (the atanh series of the module docs, relative
/// error below 1.1e-15 plus the rounding of e + s·series); branch-free in x.
#[inline(always)]
fn log2_f64(x: f32) -> f64 {
    // Subnormal x: scale by 2²³ (exact) so the exponent field is meaningful.
    let subnormal = x < f32::MIN_POSITIVE;
    let xs = if subnormal { x * 8_388_608.0 } else { x };
    let bits = xs.to_bits();
    // x = m · 2^e with m ∈ [√½, √2): the offset from √½ carries into the exponent field.
    let e = (bits.wrapping_sub(SQRT_HALF_BITS) as i32) >> 23;
    let m = f32::from_bits(bits.wrapping_sub((e as u32) << 23)) as f64;
    let e = e as f64 - if subnormal { 23.0 } else { 0.0 };
    // log₂ m = (2/ln 2) atanh(s), s = (m − 1)/(m + 1); m ± 1 are exact in f64.
    let s = (m - 1.0) / (m + 1.0);
    let z = s * s;
    let mut series = LOG2_SERIES[8];
    for c in LOG2_SERIES[..8].iter().rev() {
        series = series * z + c;
    }
    e + s * series
}

/// log₂ x, deterministic (IEEE add, multiply, divide and bit manipulation only, as [`pow`]):
/// the f64 value rounded once, within 0.5 + 2⁻¹⁷ ULP of the exact log₂ (tested).
/// Special values follow `f32::log2`: log₂ 0 = −∞, log₂ +∞ = +∞, NaN for NaN and x < 0.
#[inline]
pub fn log2(x: f32) -> f32 {
    let y = log2_f64(x) as f32;
    if x == 0.0 {
        f32::NEG_INFINITY
    } else if x == f32::INFINITY {
        x
    } else if x.is_nan() || x < 0.0 {
        f32::NAN
    } else {
        y
    }
}

/// 2^(k · log₂ x) in f64, rounded once to f32; branch-free in x.
#[inline(always)]
fn exp2_log2(x: f32, k: f32) -> f32 {
    // t = k log₂ x, kept where the result is neither 0 nor ∞ in f32.
    let t = (k as f64 * log2_f64(x)).clamp(-160.0, 160.0);
    // 2^t = 2^n · 2^f, n = round(t), f ∈ [−½, ½]; n's bits sit in the low bits of t + magic.
    let shifted = t + ROUND_MAGIC;
    let n = shifted.to_bits().wrapping_sub(ROUND_MAGIC.to_bits()) as i64;
    let f = t - (shifted - ROUND_MAGIC);
    let mut p = EXP2_SERIES[11];
    for c in EXP2_SERIES[..11].iter().rev() {
        p = p * f + c;
    }
    let scale = f64::from_bits(((n + 1023) as u64) << 52);
    let y = (p * scale) as f32;
    // 0^k = 0 and ∞^k = ∞ (k > 0); NaN and negative bases have no real power here.
    if x == 0.0 || x == f32::INFINITY {
        x
    } else if x.is_nan() || x < 0.0 {
        f32::NAN
    } else {
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// |got − x^k| in units of the f32 spacing at x^k (subnormal spacing below 2⁻¹²⁶).
    fn ulp_error(got: f32, x: f32, k: f32) -> f64 {
        let exact = (x as f64).powf(k as f64);
        if exact == 0.0 || got as f64 == exact {
            return (got as f64 - exact).abs() / f64::from(f32::from_bits(1));
        }
        let r = exact as f32;
        let ulp = if r.abs() < f32::MIN_POSITIVE { f64::from(f32::from_bits(1)) } else { (r.next_up() - r) as f64 };
        (got as f64 - exact).abs() / ulp
    }

    /// A small deterministic generator (xorshift64*), so the test sees the same values every run.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
        }
        fn unit(&mut self) -> f32 {
            (self.next() >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    const BOUND: f64 = 0.5 + 1.0 / 131_072.0;

    #[test]
    fn within_half_an_ulp_and_a_bit_over_the_whole_range() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut bases =
            vec![0.0, f32::from_bits(1), f32::from_bits(0x0040_0000), 1e-40, f32::MIN_POSITIVE, 1e-30, 0.5, 1.0 - f32::EPSILON / 2.0, 1.0];
        // Random bases, uniform and log-uniform down to the smallest denormal.
        for _ in 0..4000 {
            bases.push(rng.unit());
            bases.push(f32::from_bits((rng.next() % 0x3f80_0000) as u32));
        }
        let mut exponents = vec![1e-6, 0.5, 1.0, 2.0, 3.0, 2.4, 1.0 / 2.4, 16.0, 32.0, 100.5, 1024.0, 1025.0, 1e4, 1e6];
        for _ in 0..40 {
            exponents.push(rng.unit() * 64.0);
            exponents.push((rng.unit() * 13.8).exp());
        }
        let (mut worst, mut misrounded, mut n) = (0f64, 0u32, 0u32);
        for &k in &exponents {
            for &x in &bases {
                let got = pow(x, k);
                let e = ulp_error(got, x, k);
                assert!(e <= BOUND, "pow({x:e}, {k}) = {got:e}, exact {:e}: {e} ulp", (x as f64).powf(k as f64));
                worst = worst.max(e);
                misrounded += (got != (x as f64).powf(k as f64) as f32) as u32;
                n += 1;
            }
        }
        // Correct rounding fails only within 2⁻¹⁷ ULP of a midpoint: practically never.
        assert!(misrounded <= n / 100_000, "{misrounded} of {n} not correctly rounded (worst {worst} ulp)");
    }

    #[test]
    fn special_values_follow_powf() {
        for x in [0.0, 0.3, 1.0, f32::NAN, f32::INFINITY, f32::from_bits(1)] {
            assert_eq!(pow(x, 0.0), 1.0, "{x}^0");
        }
        for k in [1e-6, 0.5, 1.0, 32.0, 1e6] {
            assert_eq!(pow(0.0, k), 0.0);
            assert_eq!(pow(1.0, k), 1.0);
            assert!(pow(f32::NAN, k).is_nan());
            assert_eq!(pow(f32::INFINITY, k), f32::INFINITY);
        }
        assert!(pow(-0.5, 0.5).is_nan());
        assert_eq!(pow(-0.5, 3.0), -0.125);
        // Long exponents of values near 1: x = 1 − 2⁻²⁴, k = 1e6 → e^(−1e6 · 5.96e-8) ≈ 0.9421.
        let x = 1.0 - f32::EPSILON / 2.0;
        assert!(ulp_error(pow(x, 1e6), x, 1e6) <= BOUND);
        // Underflow to the smallest denormal and to 0.
        assert_eq!(pow(0.5, 149.0), f32::from_bits(1));
        assert_eq!(pow(0.5, 151.0), 0.0);
        assert_eq!(pow(0.5, 149.5), f32::from_bits(1));
    }

    #[test]
    fn log2_is_the_f64_log2_rounded_and_its_special_values_follow_f32() {
        let mut rng = Rng(0x51_7cc1_b727_220a);
        let mut values = vec![f32::from_bits(1), 1e-40, f32::MIN_POSITIVE, 1e-30, 0.25, 0.5, 2.0, 1.5, 3.0e38, f32::MAX];
        for _ in 0..20_000 {
            values.push(f32::from_bits((rng.next() % 0x7f80_0000) as u32));
        }
        let mut misrounded = 0;
        for &x in &values {
            let (got, exact) = (log2(x), (x as f64).log2());
            let r = exact as f32;
            let ulp = (r.abs().next_up() - r.abs()) as f64;
            assert!((got as f64 - exact).abs() <= BOUND * ulp, "log2({x:e}) = {got:e}, exact {exact:e}");
            misrounded += (got != r) as u32;
        }
        assert!(misrounded <= 2, "{misrounded} not correctly rounded");
        assert_eq!(log2(1.0), 0.0);
        assert_eq!(log2(0.0), f32::NEG_INFINITY);
        assert_eq!(log2(f32::INFINITY), f32::INFINITY);
        assert!(log2(-1.0).is_nan() && log2(f32::NAN).is_nan());
    }

    #[test]
    fn lanes_give_the_same_bits_as_one_value() {
        let mut rng = Rng(7);
        for k in [0.0, 1e-6, 5.0, 32.0, 37.3, 1e4] {
            let x: [f32; 8] = std::array::from_fn(|_| rng.unit());
            let lanes = pow_lanes(x, k);
            for i in 0..8 {
                assert_eq!(lanes[i].to_bits(), pow(x[i], k).to_bits());
            }
        }
    }
}
