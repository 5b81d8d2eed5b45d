//! The 8-bit sRGB encode of developed pixels eight at a time in AVX2 registers, for CPUs with
//! AVX2 (chosen at run time through the [`Avx2`] token).
//!
//! **Exact.** A code is the correctly rounded 255·encode(x) that the bucket table of
//! [`encode_u8`] gives. In lanes, a polynomial guesses y = 255·encode(x) to within 3.9e-4 of
//! a code; where the guess lies within [`EPS`] of a half-integer, where rounding could go
//! either way, the lane takes the table instead (about 0.4% of lanes). Elsewhere the guess
//! rounds to the same code as the exact value. Tested for every f32 in [0, 1]:
//! `every_f32_in_0_1_encodes_as_the_table`.
//!
//! **Why not gathers.** The table step in lanes needs two gathers a channel, which this
//! kind of CPU micro-codes (measured slower than the scalar loop, docs/performance.md); the
//! guess is ~30 register operations for eight lanes and no memory.

use super::srgb::{LINEAR_END, encode_u8};
use crate::simd::avx2::Avx2;
use std::arch::x86_64::*;

/// Half-width of the band around a half-integer where a guess is not trusted: four times the
/// largest error of the guess (measured over every f32 in [0, 1] by
/// `the_guess_is_within_a_quarter_of_eps`).
pub(super) const EPS: f32 = 0.002;

/// P(m) ≈ m^(5/12) on [1, 2), lowest degree first: a degree-5 fit minimizing the largest
/// relative error (1.25e-6 with these f32 coefficients).
pub(super) const P: [f32; 6] = [0.376_330_35, 0.952_814_8, -0.491_73, 0.208_567_68, -0.051_416_98, 0.005_435_368];

/// 255 · 1.055 · 2^(5e/12) for the binary exponent e = i − 15 of x, i in 0..16: with
/// x = 2^e · m, x^(1/2.4) = 2^(5e/12) · m^(5/12) (IEC 61966-2-1's power segment).
pub(super) const SCALE: [f32; 16] = scales();

/// [`SCALE`] in f64, rounded once.
const fn scales() -> [f32; 16] {
    // 2^(−5/12), to f64 precision.
    const DOWN: f64 = 0.749_153_538_438_340_7;
    let mut s = [0f32; 16];
    let mut v = 255.0 * 1.055;
    let mut i = 16;
    while i > 0 {
        i -= 1;
        s[i] = v as f32;
        v *= DOWN;
    }
    s
}

/// Writes the 8-bit sRGB codes of pixel `index[l]`'s channels `c[0][l]`, `c[1][l]`,
/// `c[2][l]` (each in [0, 1]: the encode's clamp is done) to `out[3 index[l]..]`: the bytes
/// [`encode_u8`] gives, channel by channel.
#[inline]
pub(super) fn encode_rgb(_: Avx2, c: [&[f32]; 3], index: &[u32], out: &mut [u8]) {
    assert!(c.iter().all(|c| c.len() >= index.len()));
    // SAFETY: an `Avx2` token exists only when detection found every feature enabled below.
    unsafe { encode_rgb_avx2(c, index, out) }
}

/// [`encode_rgb`], compiled with AVX2.
#[target_feature(enable = "avx2")]
fn encode_rgb_avx2(c: [&[f32]; 3], index: &[u32], out: &mut [u8]) {
    let n = index.len();
    let mut j = 0;
    while j + 8 <= n {
        let mut rgb = [0u32; 8];
        let mut packed = _mm256_setzero_si256();
        let mut fails = [0u32; 3];
        for (k, ch) in c.iter().enumerate() {
            // SAFETY: an unaligned load of 8 f32 from a slice of 8.
            let x = unsafe { _mm256_loadu_ps(ch[j..j + 8].as_ptr()) };
            let (code, fail) = guess(x);
            packed = _mm256_or_si256(packed, _mm256_sllv_epi32(code, _mm256_set1_epi32(8 * k as i32)));
            fails[k] = fail;
        }
        // SAFETY: an unaligned store of 8 u32 into an array of 8.
        unsafe { _mm256_storeu_si256(rgb.as_mut_ptr().cast(), packed) };
        for (k, &fail) in fails.iter().enumerate() {
            let mut f = fail;
            while f != 0 {
                let l = f.trailing_zeros() as usize;
                f &= f - 1;
                let code = encode_u8(c[k][j + l]) as u32;
                rgb[l] = (rgb[l] & !(0xff << (8 * k))) | code << (8 * k);
            }
        }
        let i0 = index[j] as usize;
        let run = index[j..j + 8].iter().enumerate().all(|(l, &i)| i as usize == i0 + l);
        match out.get_mut(3 * i0..3 * i0 + 24).filter(|_| run) {
            // Eight neighbours (a walk's row run): 24 bytes from two 12-byte halves.
            Some(o) => {
                let mut bytes = [0u8; 32];
                // SAFETY: loads and stores of 32 bytes from and into arrays of 32.
                unsafe {
                    let v = _mm256_loadu_si256(rgb.as_ptr().cast());
                    let keep = _mm256_setr_epi8(
                        0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1, 0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,
                    );
                    _mm256_storeu_si256(bytes.as_mut_ptr().cast(), _mm256_shuffle_epi8(v, keep));
                }
                o[..12].copy_from_slice(&bytes[..12]);
                o[12..].copy_from_slice(&bytes[16..28]);
            }
            None => {
                for (l, &i) in index[j..j + 8].iter().enumerate() {
                    out[3 * i as usize..3 * i as usize + 3].copy_from_slice(&rgb[l].to_le_bytes()[..3]);
                }
            }
        }
        j += 8;
    }
    for (l, &i) in index.iter().enumerate().skip(j) {
        let o = &mut out[3 * i as usize..3 * i as usize + 3];
        (o[0], o[1], o[2]) = (encode_u8(c[0][l]), encode_u8(c[1][l]), encode_u8(c[2][l]));
    }
}

/// The codes of eight values in [0, 1] as rounded guesses, and the lanes (bit l for lane l)
/// whose guess is within [`EPS`] of a half-integer, whose code must come from the table.
#[inline]
#[target_feature(enable = "avx2")]
fn guess(x: __m256) -> (__m256i, u32) {
    let y = guess_y(x);
    let r = _mm256_round_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(y);
    let off = _mm256_andnot_ps(_mm256_set1_ps(-0.0), _mm256_sub_ps(y, r));
    let fail = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(off, _mm256_set1_ps(0.5 - EPS))) as u32;
    (_mm256_cvtps_epi32(r), fail)
}

/// 255 · encode(x) for eight values in [0, 1], to within 3.9e-4: 12.92 x on the linear
/// segment, else 1.055 · 2^(5e/12) · P(m) − 0.055 with x = 2^e · m (m in [1, 2)).
#[inline]
#[target_feature(enable = "avx2")]
fn guess_y(x: __m256) -> __m256 {
    let bits = _mm256_castps_si256(x);
    // The table index e + 15 (in 6..=15 on the power segment; other lanes are blended away).
    let i = _mm256_sub_epi32(_mm256_srli_epi32::<23>(bits), _mm256_set1_epi32(127 - 15));
    let m = _mm256_or_ps(_mm256_and_ps(x, _mm256_castsi256_ps(_mm256_set1_epi32(0x007f_ffff))), _mm256_set1_ps(1.0));
    let mut p = _mm256_set1_ps(P[5]);
    for &k in P[..5].iter().rev() {
        p = _mm256_add_ps(_mm256_mul_ps(p, m), _mm256_set1_ps(k));
    }
    // SAFETY: loads of 8 f32 from the halves of a 16-entry array.
    let (lo, hi) = unsafe { (_mm256_loadu_ps(SCALE.as_ptr()), _mm256_loadu_ps(SCALE.as_ptr().add(8))) };
    // Bit 3 of the index, moved to the sign bit, picks the upper half.
    let upper = _mm256_castsi256_ps(_mm256_slli_epi32::<28>(i));
    let s = _mm256_blendv_ps(_mm256_permutevar8x32_ps(lo, i), _mm256_permutevar8x32_ps(hi, i), upper);
    let power = _mm256_sub_ps(_mm256_mul_ps(s, p), _mm256_set1_ps(255.0 * 0.055));
    let linear = _mm256_mul_ps(x, _mm256_set1_ps(255.0 * 12.92));
    _mm256_blendv_ps(power, linear, _mm256_cmp_ps::<_CMP_LE_OQ>(x, _mm256_set1_ps(LINEAR_END)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `f` with the token, or says why it is skipped.
    fn with_avx2(f: impl FnOnce(Avx2)) {
        match crate::simd::Cpu::get().avx2() {
            Some(t) => f(t),
            None => crate::simd::cpu::missing(crate::simd::Level::Avx2, "AVX2"),
        }
    }

    /// Every f32 in [0, 1] (a stride in debug builds), eight at a time.
    fn every_f32_in_0_1(mut f: impl FnMut(&[f32; 8])) {
        let step = if cfg!(debug_assertions) { 9973 } else { 1 };
        let top = 1.0f32.to_bits();
        let mut bits = 0u32;
        while bits <= top {
            let x: [f32; 8] = std::array::from_fn(|l| f32::from_bits((bits + l as u32 * step).min(top)));
            f(&x);
            bits += 8 * step;
        }
    }

    #[test]
    fn every_f32_in_0_1_encodes_as_the_table() {
        with_avx2(|t| {
            let index: Vec<u32> = (0..8).collect();
            let mut out = [0u8; 24];
            every_f32_in_0_1(|x| {
                encode_rgb(t, [x, x, x], &index, &mut out);
                for (l, &v) in x.iter().enumerate() {
                    assert_eq!(out[3 * l..3 * l + 3], [encode_u8(v); 3], "x = {v:e}");
                }
            });
        });
    }

    #[test]
    fn the_guess_is_within_a_quarter_of_eps() {
        // The guess against 255 · encode(x) in f64 (the transfer function the table rounds).
        let exact = |x: f32| {
            let x = x as f64;
            255.0 * if x <= LINEAR_END as f64 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 }
        };
        with_avx2(|_| {
            let mut worst = 0f64;
            every_f32_in_0_1(|x| {
                // SAFETY: the token exists.
                let y = unsafe { guess_y(_mm256_loadu_ps(x.as_ptr())) };
                let mut a = [0f32; 8];
                // SAFETY: a store of 8 f32 into an array of 8.
                unsafe { _mm256_storeu_ps(a.as_mut_ptr(), y) };
                for (l, &v) in x.iter().enumerate() {
                    worst = worst.max((a[l] as f64 - exact(v)).abs());
                }
            });
            assert!(worst < EPS as f64 / 4.0, "largest error {worst:e} codes");
        });
    }

    #[test]
    fn scattered_runs_and_rests_land_on_their_pixels() {
        // Runs of eight neighbours, scattered lanes, a run at the end of the buffer and a rest
        // of three: every pixel's bytes are the table's codes of its own channels.
        with_avx2(|t| {
            let index: Vec<u32> = (0..8).chain([20, 3 + 8, 9 + 8, 40, 41, 42, 43, 44]).chain(72..80).chain([60, 61, 62]).collect();
            let c: [Vec<f32>; 3] = std::array::from_fn(|k| (0..index.len()).map(|l| ((l * 37 + k * 11) % 101) as f32 / 100.0).collect());
            let mut out = vec![7u8; 80 * 3];
            encode_rgb(t, [&c[0], &c[1], &c[2]], &index, &mut out);
            let mut want = vec![7u8; 80 * 3];
            for (l, &i) in index.iter().enumerate() {
                for k in 0..3 {
                    want[3 * i as usize + k] = encode_u8(c[k][l]);
                }
            }
            assert_eq!(out, want);
        });
    }
}
