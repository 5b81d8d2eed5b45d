//! [`walk_lanes`](super::walk) sixteen samples of a row at a time in AVX-512 registers, for
//! CPUs with AVX-512BW (chosen at run time through the [`Avx512Bw`] token).
//!
//! The same samples, depths, barycentrics and owned-sample entries in the same order as the
//! narrower walks: each lane's edge values are the exact i32 they compute, `vcvtdq2ps`
//! rounds an i32 to f32 as `cvtdq2ps` does, and the depth is `(z0 + l1·dz1) + l2·dz2` with
//! separate multiplies and adds (nothing is fused), so the bits match (tested:
//! `every_walk_width_gives_the_one_sample_walk`).
//!
//! **How it differs.** A row's groups of sixteen start at the box's left edge, without the
//! narrower walks' realignment at the row's span: the inside lanes of a group are a mask,
//! the nearer ones are compressed (`vpcompressd`) to the front of a register and stored
//! whole, so a span may begin anywhere in a group. A box up to sixteen samples wide (most
//! of the `sphere` bench's) takes one group a row.

use super::edge::SetupTri;
use super::edge::{Edges, row_span};
use super::strip::StripVis;
use crate::simd::avx512::Avx512Bw;
use std::arch::x86_64::*;

/// Samples of a row the AVX-512 walk tests at once.
pub(super) const LANES: usize = 16;

// A group's stores reach fifteen entries past the last listed one and fifteen depths past
// the box: the list and depth padding must hold them.
const _: () = assert!(super::strip::LIST_PAD >= LANES && super::edge::MAX_WALK_LANES >= LANES);

/// [`walk_lanes16_avx512`] for a CPU that has AVX-512BW (the token proves it).
#[allow(clippy::too_many_arguments)]
#[inline]
pub(super) fn walk_lanes16(
    _: Avx512Bw,
    t: &SetupTri,
    out: &mut StripVis,
    bbox: [i32; 4],
    e_row: [i32; 3],
    step_x: [i32; 3],
    step_y: [i32; 3],
    bias: [i32; 3],
) -> u64 {
    // SAFETY: an `Avx512Bw` token exists only when detection found every feature enabled below.
    unsafe { walk_lanes16_avx512(t, out, bbox, e_row, step_x, step_y, bias) }
}

/// The walk in sixteen lanes; see [`walk_lanes`](super::walk) for the per-sample arithmetic.
#[allow(clippy::too_many_arguments)]
#[target_feature(enable = "avx512bw,popcnt")]
fn walk_lanes16_avx512(
    t: &SetupTri,
    out: &mut StripVis,
    [bx0, by0, bx1, by1]: [i32; 4],
    mut e_row: [i32; 3],
    step_x: [i32; 3],
    step_y: [i32; 3],
    bias: [i32; 3],
) -> u64 {
    let sample = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    let off = step_x.map(|s| _mm512_mullo_epi32(sample, _mm512_set1_epi32(s)));
    let step16 = step_x.map(|s| _mm512_set1_epi32(LANES as i32 * s));
    let bias = bias.map(|b| _mm512_set1_epi32(b));
    let inv_area = _mm512_set1_ps(t.inv_area);
    let (z0, dz1, dz2) = (_mm512_set1_ps(t.z[0]), _mm512_set1_ps(t.z[1] - t.z[0]), _mm512_set1_ps(t.z[2] - t.z[0]));
    let mut n = out.listed;
    let width = out.width as usize;
    let sy0 = out.y0 as i32;
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    for y in by0..=by1 {
        let mut e = [0, 1, 2].map(|i| _mm512_add_epi32(_mm512_set1_epi32(e_row[i]), off[i]));
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
        let row = (y - sy0) as usize * width;
        let mut x = bx0;
        let mut seen = false;
        while x <= bx1 {
            // Lanes inside every edge (biased edge values ≥ 0) and inside the box.
            let in_box = u16::MAX >> (15 - (bx1 - x).min(15));
            let any = _mm512_or_si512(
                _mm512_or_si512(_mm512_add_epi32(e[0], bias[0]), _mm512_add_epi32(e[1], bias[1])),
                _mm512_add_epi32(e[2], bias[2]),
            );
            let inside = _mm512_mask_cmpge_epi32_mask(in_box, any, _mm512_setzero_si512());
            if inside == 0 {
                // The inside samples of a row are contiguous: past them, the row is done.
                if seen {
                    break;
                }
            } else {
                seen = true;
                covered += inside.count_ones() as u64;
                let l1 = _mm512_mul_ps(_mm512_cvtepi32_ps(e[1]), inv_area);
                let l2 = _mm512_mul_ps(_mm512_cvtepi32_ps(e[2]), inv_area);
                let z = _mm512_add_ps(_mm512_add_ps(z0, _mm512_mul_ps(l1, dz1)), _mm512_mul_ps(l2, dz2));
                let i = row + x as usize;
                let cell = &mut depth[i..i + LANES];
                // SAFETY: `cell` holds sixteen f32 (unaligned masked loads and stores are allowed).
                let d = unsafe { _mm512_maskz_loadu_ps(inside, cell.as_ptr()) };
                // Reversed z: the nearer samples become this triangle's.
                let nearer = _mm512_mask_cmp_ps_mask::<_CMP_GT_OQ>(inside, z, d);
                if nearer != 0 {
                    let entries = _mm512_add_epi32(_mm512_set1_epi32(i as i32), sample);
                    let (ix, a, b) = (&mut index[n..n + LANES], &mut list_l1[n..n + LANES], &mut list_l2[n..n + LANES]);
                    // SAFETY: `cell` and each list slice hold sixteen 4-byte values. The
                    // nearer lanes go to the front of the list's next sixteen entries in
                    // lane order; the entries past them are overwritten later or are room.
                    unsafe {
                        _mm512_mask_storeu_ps(cell.as_mut_ptr(), nearer, z);
                        _mm512_storeu_si512(ix.as_mut_ptr().cast(), _mm512_maskz_compress_epi32(nearer, entries));
                        _mm512_storeu_ps(a.as_mut_ptr(), _mm512_maskz_compress_ps(nearer, l1));
                        _mm512_storeu_ps(b.as_mut_ptr(), _mm512_maskz_compress_ps(nearer, l2));
                    }
                    n += nearer.count_ones() as usize;
                }
                // The span ended inside this group.
                if inside >> 15 == 0 {
                    break;
                }
            }
            for i in 0..3 {
                e[i] = _mm512_add_epi32(e[i], step16[i]);
            }
            x += LANES as i32;
        }
    }
    out.listed = n;
    covered
}

/// The one-sample walk of a triangle whose edge values exceed i32 (a floor spanning the
/// image), sixteen samples of each row's span at a time, for a CPU with AVX-512BW and DQ (the
/// token proves it). `edges` are [`walk`](super::walk::walk)'s, at the box's first sample.
#[inline]
pub(super) fn walk_spans16(_: Avx512Bw, t: &SetupTri, out: &mut StripVis, bbox: [i32; 4], edges: Edges) -> u64 {
    // SAFETY: an `Avx512Bw` token exists only when detection found every feature enabled below.
    unsafe { walk_spans16_avx512(t, out, bbox, edges) }
}

/// [`walk_spans16`]: each row's span solved exactly (`row_span`, as the one-sample walk), then
/// its samples in groups of sixteen with no edge test. The edge values of barycentrics 1 and
/// 2 are stepped in i64 lanes and rounded to f32 once (`vcvtqq2ps`, as `i64 as f32` rounds),
/// so every lane computes the one-sample walk's bits (tested:
/// `every_walk_width_gives_the_one_sample_walk`, whose floor takes this walk).
#[target_feature(enable = "avx512bw,avx512dq,popcnt")]
fn walk_spans16_avx512(t: &SetupTri, out: &mut StripVis, [bx0, by0, bx1, by1]: [i32; 4], edges: Edges) -> u64 {
    let Edges { mut e_row, step_x, step_y, bias } = edges;
    let sample = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    // Lanes 0..8 and 8..16 of the two edges as multiples of their step.
    let k = [_mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7), _mm512_setr_epi64(8, 9, 10, 11, 12, 13, 14, 15)];
    let off = [1, 2].map(|i| k.map(|k| _mm512_mullo_epi64(k, _mm512_set1_epi64(step_x[i]))));
    let inv_area = _mm512_set1_ps(t.inv_area);
    let (z0, dz1, dz2) = (_mm512_set1_ps(t.z[0]), _mm512_set1_ps(t.z[1] - t.z[0]), _mm512_set1_ps(t.z[2] - t.z[0]));
    let mut n = out.listed;
    let width = out.width as usize;
    let sy0 = out.y0 as i32;
    let last = (bx1 - bx0) as i64;
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    for y in by0..=by1 {
        let (lo, hi) = row_span(&e_row, &step_x, &bias, last);
        let row = (y - sy0) as usize * width;
        let mut x = lo;
        while x <= hi {
            let inside: __mmask16 = u16::MAX >> (15 - (hi - x).min(15));
            let count = inside.count_ones() as usize;
            covered += count as u64;
            // The lanes' edge values, exact in i64, each rounded to f32 once.
            let to_f32 = |i: usize| {
                let e = _mm512_set1_epi64(e_row[i] + step_x[i] * x);
                let [a, b] = off[i - 1].map(|o| _mm512_cvtepi64_ps(_mm512_add_epi64(e, o)));
                _mm512_insertf32x8::<1>(_mm512_castps256_ps512(a), b)
            };
            let l1 = _mm512_mul_ps(to_f32(1), inv_area);
            let l2 = _mm512_mul_ps(to_f32(2), inv_area);
            let z = _mm512_add_ps(_mm512_add_ps(z0, _mm512_mul_ps(l1, dz1)), _mm512_mul_ps(l2, dz2));
            let i = row + (bx0 as i64 + x) as usize;
            assert!(i + count <= depth.len());
            // SAFETY: the inside lanes are samples of this row (asserted inside `depth`);
            // masked loads and stores touch only them.
            let cell = unsafe { depth.as_mut_ptr().add(i) };
            let d = unsafe { _mm512_maskz_loadu_ps(inside, cell) };
            // Reversed z: the nearer samples become this triangle's.
            let nearer = _mm512_mask_cmp_ps_mask::<_CMP_GT_OQ>(inside, z, d);
            if nearer != 0 {
                let entries = _mm512_add_epi32(_mm512_set1_epi32(i as i32), sample);
                let (ix, a, b) = (&mut index[n..n + LANES], &mut list_l1[n..n + LANES], &mut list_l2[n..n + LANES]);
                // SAFETY: each list slice holds sixteen 4-byte values; the nearer lanes go to
                // the front in lane order, the entries past them are overwritten later or room.
                unsafe {
                    _mm512_mask_storeu_ps(cell, nearer, z);
                    _mm512_storeu_si512(ix.as_mut_ptr().cast(), _mm512_maskz_compress_epi32(nearer, entries));
                    _mm512_storeu_ps(a.as_mut_ptr(), _mm512_maskz_compress_ps(nearer, l1));
                    _mm512_storeu_ps(b.as_mut_ptr(), _mm512_maskz_compress_ps(nearer, l2));
                }
                n += nearer.count_ones() as usize;
            }
            x += LANES as i64;
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    out.listed = n;
    covered
}
