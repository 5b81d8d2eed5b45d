//! The 8-bit sRGB encode sixteen pixels at a time in AVX-512 registers, for CPUs with
//! AVX-512BW (chosen at run time through the [`Avx512Bw`] token): one gather a channel from a
//! table indexed by the f32's own bits, its codes scattered as 4-byte pixels into a strip
//! buffer, and the strip packed to 3-byte pixels once its shading is done.
//!
//! **The table.** The bits of x ≥ 2^−13 shifted right by 15 are its exponent and top eight
//! mantissa bits: a bucket 1/256 of a binade wide, narrow enough that at most one of the
//! encode's thresholds lies inside it (checked when the table is built). A bucket's entry
//! holds the code at its start and where in the bucket the next threshold lies, as the low
//! fifteen bits of the threshold's f32 (0x8000 when none does): x steps up one code when its
//! own low fifteen bits are at or above that. Below 2^−13 every x encodes as 0, the first
//! bucket's code. So a lane's code is the count of thresholds at or below x, the code
//! [`encode_u8`](super::srgb::encode_u8) gives, with no guess and no fallback: `every_f32_in_0_1_encodes_as_the_table`.
//! The table is 3,329 entries (13 KB) and stays in L1 beside a strip's shading. (The AVX2
//! encode guesses with a polynomial instead: the CPUs it serves micro-code gathers.)
//!
//! **Why 4-byte pixels.** A shaded batch lists pixels in triangle order: short row runs and
//! scattered pixels. Written to 3-byte pixels they take two or three stores each behind a
//! run test; a 4-byte pixel is one lane of one scatter (no branch), and the pack of the strip
//! is sixteen pixels a load, a shuffle and a store. Measured: docs/performance.md.

use super::srgb::srgb_thresholds;
use crate::simd::avx512::Avx512Bw;
use std::arch::x86_64::*;
use std::mem::MaybeUninit;
use std::sync::OnceLock;

/// The biased exponent of the table's first binade, 2^−13: every f32 below it encodes as 0
/// (the first threshold is (0.5/255)/12.92 ≈ 1.52e-4 > 2^−13 · (1 + 1/256)).
const FIRST_EXPONENT: u32 = 127 - 13;

/// Low bits of an f32 below its bucket: the bucket is the exponent and the top eight
/// mantissa bits.
const BUCKET_SHIFT: u32 = 15;

/// Buckets from 2^−13 up to 1.0 (whose bucket, the last, holds code 255 alone).
const ENTRIES: usize = 13 * 256 + 1;

/// In an entry's high half: no threshold inside the bucket (above any low fifteen bits).
const NO_STEP: u32 = 1 << BUCKET_SHIFT;

/// The bucket table: entry i = code at bucket i's start | (the next threshold's low fifteen
/// bits, or [`NO_STEP`]) << 16.
fn bucket_table() -> &'static [u32; ENTRIES] {
    static T: OnceLock<[u32; ENTRIES]> = OnceLock::new();
    T.get_or_init(|| {
        let t = srgb_thresholds();
        std::array::from_fn(|i| {
            let lo = (FIRST_EXPONENT << 23) + ((i as u32) << BUCKET_SHIFT);
            let hi = lo + NO_STEP;
            let code = t.iter().take_while(|&&th| f32::from_bits(lo) >= th).count();
            // Thresholds are positive, so their order is their bits' order.
            let inside = |k: usize| k < 255 && t[k].to_bits() < hi;
            assert!(!inside(code + 1), "two thresholds in bucket {i}");
            let step = if inside(code) { t[code].to_bits() - lo } else { NO_STEP };
            code as u32 | step << 16
        })
    })
}

/// Writes the 8-bit sRGB codes of pixel `index[l]`'s channels `c[0][l]`, `c[1][l]`,
/// `c[2][l]` (each in [0, 1]: the encode's clamp is done) to `px[index[l]]` as R | G << 8 |
/// B << 16: the bytes [`encode_u8`](super::srgb::encode_u8) gives, channel by channel.
#[inline]
pub(super) fn encode_rgb(_: Avx512Bw, c: [&[f32]; 3], index: &[u32], px: &mut [u32]) {
    assert!(c.iter().all(|c| c.len() >= index.len()));
    let table = bucket_table();
    // SAFETY: an `Avx512Bw` token exists only when detection found every feature enabled below.
    unsafe { encode_rgb_avx512(table, c, index, px) }
}

/// [`encode_rgb`], compiled with AVX-512BW.
#[target_feature(enable = "avx512bw")]
fn encode_rgb_avx512(table: &[u32; ENTRIES], c: [&[f32]; 3], index: &[u32], px: &mut [u32]) {
    let n = index.len();
    let len = _mm512_set1_epi32(px.len().min(i32::MAX as usize) as i32);
    let mut j = 0;
    while j < n {
        let lanes: __mmask16 = if n - j >= 16 { u16::MAX } else { (1u16 << (n - j)) - 1 };
        let mut packed = _mm512_setzero_si512();
        for (k, ch) in c.iter().enumerate() {
            // SAFETY: a masked load of the lanes below n (≤ the slice's length, asserted);
            // the gather reads entries 0..ENTRIES only (`bucket` clamps every f32 in [0, 1]).
            let (x, entry) = unsafe {
                let x = _mm512_castps_si512(_mm512_maskz_loadu_ps(lanes, ch.as_ptr().add(j)));
                (x, _mm512_i32gather_epi32::<4>(bucket(x), table.as_ptr().cast()))
            };
            // One code up where x's low bits reach the threshold inside its bucket.
            let low = _mm512_and_si512(x, _mm512_set1_epi32(NO_STEP as i32 - 1));
            let up = _mm512_cmpge_epu32_mask(low, _mm512_srli_epi32::<16>(entry));
            let code = _mm512_and_si512(entry, _mm512_set1_epi32(0xff));
            let code = _mm512_mask_add_epi32(code, up, code, _mm512_set1_epi32(1));
            packed = _mm512_or_si512(packed, _mm512_sll_epi32(code, _mm_cvtsi32_si128(8 * k as i32)));
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

/// The bucket of each lane's f32 bits `x` (x in [0, 1]): 0 below 2^−13, [`ENTRIES`] − 1 at 1.0.
#[inline]
#[target_feature(enable = "avx512bw")]
fn bucket(x: __m512i) -> __m512i {
    let i = _mm512_sub_epi32(_mm512_srli_epi32::<{ BUCKET_SHIFT }>(x), _mm512_set1_epi32((FIRST_EXPONENT << 8) as i32));
    let i = _mm512_max_epi32(i, _mm512_setzero_si512());
    _mm512_min_epi32(i, _mm512_set1_epi32(ENTRIES as i32 - 1))
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
    use crate::render::srgb::encode_u8;

    /// Runs `f` with the token, or says why it is skipped.
    fn with_avx512bw(f: impl FnOnce(Avx512Bw)) {
        match crate::simd::Cpu::get().avx512bw() {
            Some(t) => f(t),
            None => crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512BW"),
        }
    }

    #[test]
    fn a_bucket_entry_is_the_code_at_its_start_and_its_step() {
        // The entries against the thresholds directly: a bucket with a threshold inside
        // steps exactly there (the f32 just below stays), the first bucket is code 0 with no
        // step, and the last (1.0) is 255.
        let (table, t) = (bucket_table(), srgb_thresholds());
        assert_eq!(table[0], NO_STEP << 16);
        assert_eq!(table[ENTRIES - 1] & 0xff, 255);
        let mut steps = 0;
        for (i, &e) in table.iter().enumerate() {
            if e >> 16 != NO_STEP {
                steps += 1;
                let at = f32::from_bits((FIRST_EXPONENT << 23) + ((i as u32) << BUCKET_SHIFT) + (e >> 16));
                assert_eq!(at, t[(e & 0xff) as usize], "bucket {i}");
            }
        }
        // All 255 finite thresholds lie in [2^-13, 1): each is one bucket's step.
        assert_eq!(steps, 255);
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
        let Some(t) = crate::simd::Cpu::get().avx512bw() else { panic!("pixel index out of the strip (skipped: no AVX-512BW)") };
        encode_rgb(t, [&[0.5; 3], &[0.5; 3], &[0.5; 3]], &[0, 1, 3], &mut [0; 3]);
    }
}
