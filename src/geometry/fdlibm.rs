//! sin, cos and exp in f64 from fixed polynomials: the same bits on every machine (no libm,
//! whose last bit depends on the CPU path glibc picks), and plain `+ − ×` and selects that a
//! loop over many arguments can run in vector lanes.
//!
//! The algorithms and constants are fdlibm's (Sun Microsystems 1993, as FreeBSD's msun keeps
//! them). sin and cos (`k_sin.c`, `k_cos.c`): minimax polynomials on [−π/4, π/4] with errors
//! below 2⁻⁵⁸ relative, the argument reduced by the nearest multiple k of π/2 with π/2 split
//! in two (`e_rem_pio2.c`'s first step, 33 + 53 bits), which is exact enough for |x| ≤ 2π;
//! the quadrant k then swaps and negates the kernels. exp (`e_exp.c`): x = k ln 2 + r with
//! ln 2 split in two, e^r from a degree-5 rational approximation (error below 2⁻⁵⁹), then
//! 2^k by building the exponent. Measured against libm over 10⁶ arguments each: within 1 f64
//! ULP for exp, 2 for sin and cos (the unit tests), so an f32 rounded from them differs from
//! libm's only for arguments within that of an f32 rounding boundary, about one in 2²⁸.

// The constants are written as fdlibm publishes them (21 digits), so they can be checked
// against its source; each still parses to the one f64 fdlibm uses.
#![allow(clippy::excessive_precision)]

/// π/2's first 33 bits (fdlibm `pio2_1`): k · this is exact for the small k used here.
const PIO2_HI: f64 = 1.570_796_326_734_125_614_17;
/// π/2 − [`PIO2_HI`] (fdlibm `pio2_1t`).
const PIO2_LO: f64 = 6.077_100_506_506_192_249_32e-11;
/// 2/π.
const INV_PIO2: f64 = std::f64::consts::FRAC_2_PI;
/// 1.5·2⁵²: y + this − this is y rounded to an integer (ties to even) for |y| < 2⁵¹.
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// sin x for |x| ≤ π/4 (fdlibm `__kernel_sin` with no tail).
#[inline(always)]
fn kernel_sin(x: f64) -> f64 {
    const S1: f64 = -1.666_666_666_666_663_243_48e-1;
    const S2: f64 = 8.333_333_333_322_489_461_24e-3;
    const S3: f64 = -1.984_126_982_985_794_931_34e-4;
    const S4: f64 = 2.755_731_370_707_006_767_89e-6;
    const S5: f64 = -2.505_076_025_340_686_341_95e-8;
    const S6: f64 = 1.589_690_995_211_550_102_21e-10;
    let z = x * x;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * x;
    x + v * (S1 + z * r)
}

/// cos x for |x| ≤ π/4 (fdlibm `__kernel_cos` with no tail: 1 − z/2 rounded with its error carried).
#[inline(always)]
fn kernel_cos(x: f64) -> f64 {
    const C1: f64 = 4.166_666_666_666_660_190_37e-2;
    const C2: f64 = -1.388_888_888_887_410_957_49e-3;
    const C3: f64 = 2.480_158_728_947_672_941_78e-5;
    const C4: f64 = -2.755_731_435_139_066_330_35e-7;
    const C5: f64 = 2.087_572_321_298_174_827_90e-9;
    const C6: f64 = -1.135_964_755_778_819_482_65e-11;
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let one_minus = 1.0 - hz;
    one_minus + (((1.0 - one_minus) - hz) + z * r)
}

/// (sin x, cos x) for |x| ≤ 2π, to within an f64 ULP or two of the exact values; the same
/// bits on every machine. Outside that range (or for NaN) the result is meaningless but finite
/// or NaN, never a panic: callers keep to the range.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    // k ∈ {−4, …, 4}: the nearest multiple of π/2, so |r| ≤ π/4 (plus rounding). Rounded by
    // adding and taking away 1.5·2⁵² (ties to even), not `round`, which x86-64 without
    // SSE4.1 calls in libm: a call no loop can put in lanes.
    let k = (x * INV_PIO2 + ROUNDER) - ROUNDER;
    let r = (x - k * PIO2_HI) - k * PIO2_LO;
    let (s, c) = (kernel_sin(r), kernel_cos(r));
    // The quadrant, k mod 4 in 0..4, as selects rather than a jump (lanes).
    let q = (k as i32) & 3;
    let sin = if q & 1 == 0 { s } else { c };
    let cos = if q & 1 == 0 { c } else { s };
    let sin = if q >= 2 { -sin } else { sin };
    let cos = if q == 1 || q == 2 { -cos } else { cos };
    (sin, cos)
}

/// ln 2's first 32 bits (fdlibm `ln2HI`): k · this is exact for |k| < 2²¹.
const LN2_HI: f64 = 6.931_471_803_691_238_164_90e-1;
/// ln 2 − [`LN2_HI`] (fdlibm `ln2LO`).
const LN2_LO: f64 = 1.908_214_929_270_587_700_02e-10;
/// 1/ln 2.
const INV_LN2: f64 = std::f64::consts::LOG2_E;

/// 2^m as an f64 for m in −1022..=1023, from its exponent bits.
#[inline(always)]
fn pow2(m: i32) -> f64 {
    f64::from_bits(((m + 1023) as u64) << 52)
}

/// e^x to within an f64 ULP, the same bits on every machine: 0 below −745.2 (where e^x
/// rounds to 0), ∞ above 709.8, NaN for NaN (fdlibm `e_exp.c`).
#[inline(always)]
pub fn exp(x: f64) -> f64 {
    const P1: f64 = 1.666_666_666_666_660_190_37e-1;
    const P2: f64 = -2.777_777_777_701_559_338_42e-3;
    const P3: f64 = 6.613_756_321_437_934_361_17e-5;
    const P4: f64 = -1.653_390_220_546_525_153_90e-6;
    const P5: f64 = 4.138_136_797_057_238_460_39e-8;
    // Outside [−746, 710] the result is 0 or ∞ (selected below): keep k in i32's range.
    let xc = if x > -746.0 { x } else { -746.0 };
    let xc = if xc < 710.0 { xc } else { 710.0 };
    // The nearest integer to x/ln 2 (ties to even; NaN stays NaN and is selected below).
    let k = (xc * INV_LN2 + ROUNDER) - ROUNDER;
    let hi = xc - k * LN2_HI;
    let lo = k * LN2_LO;
    let r = hi - lo;
    let t = r * r;
    let c = r - t * (P1 + t * (P2 + t * (P3 + t * (P4 + t * P5))));
    let y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi);
    // 2^k in two factors, each a normal f64, so that k down to −1075 needs no special case.
    let k = if k.is_nan() { 0 } else { k as i32 };
    let k1 = k >> 1;
    let e = y * pow2(k1) * pow2(k - k1);
    if x.is_nan() {
        x
    } else if x < -745.2 {
        0.0
    } else if x > 709.78 {
        f64::INFINITY
    } else {
        e
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in f64 ULPs between two finite values of the same sign region.
    fn ulps(a: f64, b: f64) -> u64 {
        let key = |v: f64| {
            let bits = v.to_bits() as i64;
            if bits < 0 { i64::MIN - bits } else { bits }
        };
        key(a).abs_diff(key(b))
    }

    #[test]
    fn within_two_ulps_of_libm_on_the_range_callers_use() {
        // 10⁶ arguments spread over [−2π, 2π], the quadrant edges and both ends.
        let mut worst = 0;
        let mut args: Vec<f64> = (0..1_000_000).map(|i| -std::f64::consts::TAU + i as f64 * (2.0 * std::f64::consts::TAU / 1e6)).collect();
        for k in -4..=4 {
            let edge = k as f64 * std::f64::consts::FRAC_PI_2;
            args.extend([edge, edge.next_up(), edge.next_down(), edge + 1e-9, edge - 1e-9]);
            let quarter = edge + std::f64::consts::FRAC_PI_4;
            args.extend([quarter, quarter.next_up(), quarter.next_down()]);
        }
        for x in args.into_iter().filter(|x| x.abs() <= std::f64::consts::TAU) {
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            // Near a zero of sin or cos the value is tiny and ULPs are tiny: judge absolutely there.
            for (v, v0) in [(s, s0), (c, c0)] {
                if v0.abs() > 1e-6 {
                    worst = worst.max(ulps(v, v0));
                } else {
                    assert!((v - v0).abs() < 1e-22, "x = {x}: {v} against {v0}");
                }
            }
        }
        assert!(worst <= 2, "largest difference from libm: {worst} ULPs");
    }

    #[test]
    fn exp_within_one_ulp_of_libm() {
        // 10⁶ arguments over [−750, 0] (transmittances), then over [−30, 30], the ends of the
        // range and the values ln 2 multiples land on.
        let mut worst = 0;
        let mut args: Vec<f64> = (0..1_000_000).map(|i| -750.0 + i as f64 * 7.5e-4).collect();
        args.extend((0..1_000_000).map(|i| -30.0 + i as f64 * 6e-5));
        for k in -1074..=1023 {
            let x = k as f64 * std::f64::consts::LN_2;
            args.extend([x, x.next_up(), x.next_down()]);
        }
        args.extend([0.0, -0.0, 1e-300, -1e-300, 709.78, 709.7, -745.1, -708.4, -708.3]);
        for x in args {
            let (e, e0) = (exp(x), x.exp());
            if e0 == 0.0 || e0.is_infinite() {
                assert_eq!(e, e0, "x = {x}");
            } else if e0 < f64::MIN_POSITIVE {
                // Subnormal results: the last bits of a number with fewer than 53.
                assert!((e - e0).abs() <= 2.0 * f64::from_bits(1), "x = {x}: {e} against {e0}");
            } else {
                worst = worst.max(ulps(e, e0));
            }
        }
        assert!(worst <= 1, "largest difference from libm: {worst} ULPs");
        assert_eq!(exp(0.0), 1.0);
        assert_eq!((exp(-800.0), exp(800.0), exp(f64::NEG_INFINITY), exp(f64::INFINITY)), (0.0, f64::INFINITY, 0.0, f64::INFINITY));
        assert!(exp(f64::NAN).is_nan());
    }

    #[test]
    fn exact_at_zero_and_odd_and_even() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        for x in [0.1, 0.7, 1.3, 2.9, 4.4, 6.0] {
            let (s, c) = sin_cos(x);
            let (sn, cn) = sin_cos(-x);
            assert_eq!((sn, cn), (-s, c), "x = {x}");
            assert!((s * s + c * c - 1.0).abs() < 4e-16, "x = {x}");
        }
    }
}
