//! The 8-bit sRGB encode sixteen pixels at a time in AVX-512 registers, for CPUs with
//! AVX-512BW (chosen at run time through the [`Avx512Bw`] token): the guess of
//! `encode_avx2` in one register of sixteen lanes, its codes scattered as 4-byte pixels into
//! a strip buffer, and the strip packed to 3-byte pixels once its shading is done.
//!
//! **Why 4-byte pixels.** A shaded batch lists pixels in triangle order: short row runs and
//! scattered pixels. Written to 3-byte pixels they take two or three stores each behind a
//! run test; a 4-byte pixel is one lane of one scatter (no branch), and the pack of the strip
//! is sixteen pixels a load, a shuffle and a store. Measured: docs/performance.md.
//!
//! **Exact.** The guess is the AVX2 guess operation for operation (the same multiplies and
//! adds in the same order, the same 16-entry scale picked by one permute instead of two and
//! a blend), so the bytes are the table's: `every_f32_in_0_1_encodes_as_the_table`.

use super::develop::{LINEAR_END, encode_u8};
use super::encode_avx2::{EPS, P, SCALE};
use crate::simd::avx512::Avx512Bw;
use std::arch::x86_64::*;
use std::mem::MaybeUninit;

/// Writes the 8-bit sRGB codes of pixel `index[l]`'s channels `c[0][l]`, `c[1][l]`,
/// `c[2][l]` (each in [0, 1]: the encode's clamp is done) to `px[index[l]]` as R | G << 8 |
/// B << 16: the bytes [`encode_u8`] gives, channel by channel.
#[inline]
pub(super) fn encode_rgb(_: Avx512Bw, c: [&[f32]; 3], index: &[u32], px: &mut [u32]) {
    assert!(c.iter().all(|c| c.len() >= index.len()));
    // SAFETY: an `Avx512Bw` token exists only when detection found every feature enabled below.
    unsafe { encode_rgb_avx512(c, index, px) }
}

/// [`encode_rgb`], compiled with AVX-512BW.
#[target_feature(enable = "avx512bw")]
fn encode_rgb_avx512(c: [&[f32]; 3], index: &[u32], px: &mut [u32]) {
    let n = index.len();
    let len = _mm512_set1_epi32(px.len().min(i32::MAX as usize) as i32);
    let mut j = 0;
    while j < n {
        let lanes: __mmask16 = if n - j >= 16 { u16::MAX } else { (1u16 << (n - j)) - 1 };
        let mut packed = _mm512_setzero_si512();
        let mut fails = [0u16; 3];
        for (k, ch) in c.iter().enumerate() {
            // SAFETY: a masked load of the lanes below n (≤ the slice's length, asserted).
            let x = unsafe { _mm512_maskz_loadu_ps(lanes, ch.as_ptr().add(j)) };
            let (code, fail) = guess(x);
            packed = _mm512_or_si512(packed, _mm512_sll_epi32(code, _mm_cvtsi32_si128(8 * k as i32)));
            fails[k] = fail & lanes;
        }
        if fails != [0; 3] {
            // Near a half-code (about 0.4% of lanes): the table's code for that channel.
            let mut rgb = [0u32; 16];
            // SAFETY: a store of 16 u32 into an array of 16, and its load back.
            unsafe { _mm512_storeu_si512(rgb.as_mut_ptr().cast(), packed) };
            for (k, &fail) in fails.iter().enumerate() {
                let mut f = fail;
                while f != 0 {
                    let l = f.trailing_zeros() as usize;
                    f &= f - 1;
                    rgb[l] = (rgb[l] & !(0xff << (8 * k))) | (encode_u8(c[k][j + l]) as u32) << (8 * k);
                }
            }
            packed = unsafe { _mm512_loadu_si512(rgb.as_ptr().cast()) };
        }
        // SAFETY: a masked load of the lanes below n; the scatter writes only lanes whose
        // index is below px.len(), checked here (an index past it panics, as a slice would).
        unsafe {
            let idx = _mm512_maskz_loadu_epi32(lanes, index.as_ptr().add(j).cast());
            assert_eq!(_mm512_mask_cmpge_epu32_mask(lanes, idx, len), 0, "pixel index out of the strip");
            _mm512_mask_i32scatter_epi32::<4>(px.as_mut_ptr().cast(), lanes, idx, packed);
        }
        j += 16;
    }
}

/// The codes of sixteen values in [0, 1] as rounded guesses, and the lanes (bit l for lane l)
/// whose guess is within [`EPS`] of a half-integer, whose code must come from the table: the
/// AVX2 `guess` in sixteen lanes.
#[inline]
#[target_feature(enable = "avx512bw")]
fn guess(x: __m512) -> (__m512i, u16) {
    let y = guess_y(x);
    let r = _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(y);
    let off = _mm512_abs_ps(_mm512_sub_ps(y, r));
    let fail = _mm512_cmp_ps_mask::<_CMP_GT_OQ>(off, _mm512_set1_ps(0.5 - EPS));
    (_mm512_cvtps_epi32(r), fail)
}

/// 255 · encode(x) for sixteen values in [0, 1], as the AVX2 `guess_y` computes it.
#[inline]
#[target_feature(enable = "avx512bw")]
fn guess_y(x: __m512) -> __m512 {
    let bits = _mm512_castps_si512(x);
    // The table index e + 15; the permute reads its low four bits (other lanes are blended away).
    let i = _mm512_sub_epi32(_mm512_srli_epi32::<23>(bits), _mm512_set1_epi32(127 - 15));
    let m = _mm512_castsi512_ps(_mm512_or_si512(_mm512_and_si512(bits, _mm512_set1_epi32(0x007f_ffff)), _mm512_set1_epi32(0x3f80_0000)));
    let mut p = _mm512_set1_ps(P[5]);
    for &k in P[..5].iter().rev() {
        p = _mm512_add_ps(_mm512_mul_ps(p, m), _mm512_set1_ps(k));
    }
    // SAFETY: a load of 16 f32 from a 16-entry array.
    let s = _mm512_permutexvar_ps(i, unsafe { _mm512_loadu_ps(SCALE.as_ptr()) });
    let power = _mm512_sub_ps(_mm512_mul_ps(s, p), _mm512_set1_ps(255.0 * 0.055));
    let linear = _mm512_mul_ps(x, _mm512_set1_ps(255.0 * 12.92));
    _mm512_mask_blend_ps(_mm512_cmp_ps_mask::<_CMP_LE_OQ>(x, _mm512_set1_ps(LINEAR_END)), power, linear)
}

/// Writes the 4-byte pixels `px` (R | G << 8 | B << 16) to `out` as 3-byte RGB: every byte
/// of `out`.
#[inline]
pub(super) fn pack_rgb(_: Avx512Bw, px: &[u32], out: &mut [MaybeUninit<u8>]) {
    assert_eq!(out.len(), 3 * px.len(), "three bytes a pixel");
    // SAFETY: as for `encode_rgb`.
    unsafe { pack_rgb_avx512(px, out) }
}

/// [`pack_rgb`], compiled with AVX-512BW.
#[target_feature(enable = "avx512bw")]
fn pack_rgb_avx512(px: &[u32], out: &mut [MaybeUninit<u8>]) {
    // Each 16-byte quarter's four pixels to its first 12 bytes, then the quarters' 12-byte
    // heads side by side: 48 bytes.
    let keep: [i8; 16] = [0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1];
    // SAFETY: a load of 16 bytes from an array of 16.
    let keep = _mm512_broadcast_i32x4(unsafe { _mm_loadu_si128(keep.as_ptr().cast()) });
    let heads = _mm512_setr_epi32(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 0, 0, 0, 0);
    let mut groups = px.chunks_exact(16);
    let mut o = 0;
    for g in &mut groups {
        // SAFETY: a load of 16 u32 from a chunk of 16; the masked store writes 12 u32 (48
        // bytes) at out[o..o + 48], inside `out` (3 bytes a pixel, asserted).
        unsafe {
            let v = _mm512_shuffle_epi8(_mm512_loadu_si512(g.as_ptr().cast()), keep);
            _mm512_mask_storeu_epi32(out.as_mut_ptr().add(o).cast(), 0x0fff, _mm512_permutexvar_epi32(heads, v));
        }
        o += 48;
    }
    for (p, o) in groups.remainder().iter().zip(out[o..].chunks_exact_mut(3)) {
        for (o, b) in o.iter_mut().zip(p.to_le_bytes()) {
            o.write(b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `f` with the token, or says why it is skipped.
    fn with_avx512bw(f: impl FnOnce(Avx512Bw)) {
        match Avx512Bw::detect() {
            Some(t) => f(t),
            None => eprintln!("skipped: no AVX-512BW"),
        }
    }

    #[test]
    fn every_f32_in_0_1_encodes_as_the_table() {
        // Every f32 in [0, 1] (a stride in debug builds), sixteen at a time in three channels.
        with_avx512bw(|t| {
            let step = if cfg!(debug_assertions) { 9973 } else { 1 };
            let top = 1.0f32.to_bits();
            let index: Vec<u32> = (0..16).collect();
            let mut px = [0u32; 16];
            let mut bits = 0u32;
            while bits <= top {
                let x: [f32; 16] = std::array::from_fn(|l| f32::from_bits((bits + l as u32 * step).min(top)));
                encode_rgb(t, [&x, &x, &x], &index, &mut px);
                for (l, &v) in x.iter().enumerate() {
                    let e = encode_u8(v) as u32;
                    assert_eq!(px[l], e | e << 8 | e << 16, "x = {v:e}");
                }
                bits += 16 * step;
            }
        });
    }

    #[test]
    fn scattered_pixels_and_a_partial_group_land_on_their_pixels() {
        // Runs, scattered lanes and a last group of five; untouched pixels keep their value,
        // and the pack gives each pixel's three bytes (a rest of seven past the groups of 16).
        with_avx512bw(|t| {
            let index: Vec<u32> = (0..16)
                .chain([70, 3 + 16, 9 + 40, 40, 41, 42, 43, 44, 17, 18, 19, 20, 21, 22, 23, 24])
                .chain([60, 61, 62, 78, 1 + 64])
                .collect();
            let c: [Vec<f32>; 3] = std::array::from_fn(|k| (0..index.len()).map(|l| ((l * 37 + k * 11) % 101) as f32 / 100.0).collect());
            let mut px = vec![0x00ab_cdefu32; 87];
            encode_rgb(t, [&c[0], &c[1], &c[2]], &index, &mut px);
            let mut want = vec![[0xef, 0xcd, 0xab]; 87];
            for (l, &i) in index.iter().enumerate() {
                want[i as usize] = [0, 1, 2].map(|k| encode_u8(c[k][l]));
            }
            let mut out = Vec::with_capacity(87 * 3);
            pack_rgb(t, &px, &mut out.spare_capacity_mut()[..87 * 3]);
            // SAFETY: `pack_rgb` wrote all 87 · 3 bytes.
            unsafe { out.set_len(87 * 3) };
            assert_eq!(out, want.concat());
        });
    }

    #[test]
    #[should_panic(expected = "pixel index out of the strip")]
    fn an_index_past_the_strip_panics() {
        let Some(t) = Avx512Bw::detect() else { panic!("pixel index out of the strip (skipped: no AVX-512BW)") };
        encode_rgb(t, [&[0.5; 3], &[0.5; 3], &[0.5; 3]], &[0, 1, 3], &mut [0; 3]);
    }
}
