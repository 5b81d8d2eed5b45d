//! AgX, the tone map of Blender 4's default view: a per-pixel curve that keeps a saturated
//! colour's hue where per-channel curves slide it (gold towards olive). [`agx`] is the one
//! formula every develop path calls (`render::develop`).

use crate::simd::lanes::{Lanes, MAX_WIDTH, V3};

/// AgX's inset matrix (rows; Wrensch's `agx_mat` read column by column): each channel takes
/// a few percent of the other two, so a saturated colour starts nearer the grey axis and its
/// channels reach the curve's shoulder together. Rows sum to 1 within 1.4e-4: grey stays grey.
const AGX_INSET: [[f32; 3]; 3] = [
    [0.842_479_062_253_094_f64 as f32, 0.078_433_599_999_999_2_f64 as f32, 0.079_223_745_147_764_3_f64 as f32],
    [0.042_328_242_261_012_3_f64 as f32, 0.878_468_636_469_772_f64 as f32, 0.079_166_127_460_543_4_f64 as f32],
    [0.042_375_654_905_705_1_f64 as f32, 0.078_433_6_f64 as f32, 0.879_142_973_793_104_f64 as f32],
];
/// AgX's outset matrix: the inverse of the inset (Wrensch's `agx_mat_inv`), giving back the
/// chroma the inset took where the curve did not compress it.
const AGX_OUTSET: [[f32; 3]; 3] = [
    [1.196_879_005_120_17_f64 as f32, -0.098_020_881_140_136_8_f64 as f32, -0.099_029_744_079_720_5_f64 as f32],
    [-0.052_896_851_757_456_2_f64 as f32, 1.151_903_129_904_17_f64 as f32, -0.098_961_176_844_843_3_f64 as f32],
    [-0.052_971_635_514_443_8_f64 as f32, -0.098_043_450_117_124_1_f64 as f32, 1.151_073_672_641_16_f64 as f32],
];
/// The log encoding's range in stops: 2^−12.47393 (about 1.8e-4) to 2^4.026069 (about 16.3),
/// 16.5 stops with mid-grey 0.18 at 0.606 of the way.
const AGX_MIN_EV: f32 = -12.473_93;
/// See [`AGX_MIN_EV`].
const AGX_MAX_EV: f32 = 4.026_069;
/// 2^[`AGX_MIN_EV`] and 2^[`AGX_MAX_EV`] (written out: `f32::exp2` is the C library's).
const AGX_RANGE: (f32, f32) = (0.000_175_781_394_789_187_66_f64 as f32, 16.291_742_365_295_857_f64 as f32);

/// AgX (Troy Sobotka, 2022; Blender 4's default view transform, "AgX Base") in the analytic
/// form of Benjamin Wrensch's "Minimal AgX Implementation" (iolite engine blog, 2024), in our
/// own words: (1) mix the channels with [`AGX_INSET`]; (2) encode each as log₂ over
/// [[`AGX_MIN_EV`], [`AGX_MAX_EV`]] scaled to [0, 1]; (3) Wrensch's 6th-order polynomial fit of
/// AgX's sigmoid (mean squared error 3.7e-6 against the curve), which gives display values
/// for a 2.2-power display; (4) [`AGX_OUTSET`]; (5) back to linear with ^2.2, as his `agxEotf`,
/// so the sRGB encode that follows writes the display values (within the small difference
/// between the sRGB curve and a 2.2 power, largest in the deepest shadows).
///
/// Never NaN: negative and NaN channels count as 0, the encoding clamps to its range (so +∞
/// is the brightest and 0 the darkest stop), the output to [0, 1]. log₂ and ^2.2 are
/// `simd::pow`'s deterministic ones, lane by lane, so every lane width gives the same bits.
#[inline(always)]
pub(super) fn agx<F: Lanes>(c: V3<F>) -> V3<F> {
    let (zero, one) = (F::splat(0.0), F::splat(1.0));
    let clamp01 = |x: F| F::select(x.gt(zero), F::select(x.lt(one), x, one), zero);
    let c = V3 { x: F::select(c.x.gt(zero), c.x, zero), y: F::select(c.y.gt(zero), c.y, zero), z: F::select(c.z.gt(zero), c.z, zero) };
    let mix = |m: &[[f32; 3]; 3], v: V3<F>| {
        let row = |r: [f32; 3]| F::splat(r[0]) * v.x + F::splat(r[1]) * v.y + F::splat(r[2]) * v.z;
        V3 { x: row(m[0]), y: row(m[1]), z: row(m[2]) }
    };
    let (lo, hi) = (F::splat(AGX_RANGE.0), F::splat(AGX_RANGE.1));
    let curve = |x: F| {
        // The range's ends first, so log₂ sees a positive finite value (+∞ → the top).
        let x = F::select(x.gt(lo), F::select(x.lt(hi), x, hi), lo);
        let t = clamp01((log2_lanes(x) - F::splat(AGX_MIN_EV)) * F::splat(1.0 / (AGX_MAX_EV - AGX_MIN_EV)));
        // 15.5 t⁶ − 40.14 t⁵ + 31.96 t⁴ − 6.868 t³ + 0.4298 t² + 0.1191 t − 0.00232, by Horner.
        let mut p = F::splat(15.5);
        for k in [-40.14, 31.96, -6.868, 0.4298, 0.1191, -0.00232] {
            p = p * t + F::splat(k);
        }
        p
    };
    let inset = mix(&AGX_INSET, c);
    let display = mix(&AGX_OUTSET, V3 { x: curve(inset.x), y: curve(inset.y), z: curve(inset.z) });
    let linear = |x: F| clamp01(x).pow(2.2);
    V3 { x: linear(display.x), y: linear(display.y), z: linear(display.z) }
}

/// log₂ of each lane (`simd::pow::log2`, deterministic), through memory.
#[inline(always)]
fn log2_lanes<F: Lanes>(x: F) -> F {
    let mut a = [0f32; MAX_WIDTH];
    x.store(&mut a);
    for v in &mut a[..F::WIDTH] {
        *v = crate::simd::pow::log2(*v);
    }
    F::load(&a)
}
