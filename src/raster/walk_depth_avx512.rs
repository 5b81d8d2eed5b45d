//! The depth-only walk of a small triangle (a box at most sixteen texels wide) into a shadow
//! map's tiles with AVX-512 (chosen at run time through the [`Avx512Bw`] token): no division,
//! no branch on the span.
//!
//! Each row's texels are tested against the three edges at once, in lanes from the left
//! edge of the box's first tile column (the i32 edge values of the lane walks); the span is
//! the inside mask, its first texel the mask's trailing zeros (`row_span`'s exact span: the
//! inside set of a row is an interval). Depths are the reference's `zs + f32(x − x_lo)·dz`
//! from the same f64 row start, so the bits match [`walk_depth_rows`](super::walk_depth)
//! (tested: `depth_walk_widths_agree_bit_for_bit`). A box sixteen texels wide reaches at most
//! three tile columns: each is one masked load, compare and masked store of its 32-byte tile
//! row. (Sixteen lanes stored from the box's left edge overlapped the next row's load, a
//! store the load could not forward from: a sixth of this walk's time, perf.)

use super::edge::SetupTri;
use super::tiles::DEPTH_TILE;
use crate::simd::avx512::Avx512Bw;
use std::arch::x86_64::*;

/// Texels of a row the walk tests at once: the widest box it takes.
pub(super) const LANES: i32 = 16;

/// Texels of a storage tile.
const TILE_LEN: usize = DEPTH_TILE * DEPTH_TILE;

/// [`walk_depth_small_avx512`] for a CPU that has AVX-512BW (the token proves it).
#[inline]
pub(super) fn walk_depth_small16(
    _: Avx512Bw,
    t: &SetupTri,
    y0: u32,
    bbox: [i32; 4],
    edges: [[i32; 3]; 4],
    tiles: usize,
    depth: &mut [f32],
) -> u64 {
    // SAFETY: an `Avx512Bw` token exists only when detection found every feature enabled below.
    unsafe { walk_depth_small_avx512(t, y0, bbox, edges, tiles, depth) }
}

/// The walk of box `bbox` (clipped to the strip from row `y0`, at most [`LANES`] wide) with
/// `[e_row, step_x, step_y, bias]` at its first texel, into a strip of `tiles` tiles a row.
/// Returns the covered texels.
#[target_feature(enable = "avx512bw,popcnt")]
fn walk_depth_small_avx512(
    t: &SetupTri,
    y0: u32,
    [bx0, by0, bx1, by1]: [i32; 4],
    [e_row, step_x, step_y, bias]: [[i32; 3]; 4],
    tiles: usize,
    depth: &mut [f32],
) -> u64 {
    const _: () = assert!(DEPTH_TILE == 8, "sixteen texels reach three tile columns");
    debug_assert!(bx1 - bx0 < LANES && bx0 <= bx1 && by0 <= by1);
    let (yl0, yl1) = ((by0 - y0 as i32) as usize, (by1 - y0 as i32) as usize);
    // The texel farthest into the strip is the last row's, in the box's last column.
    let row_at = |yl: usize| (yl / DEPTH_TILE) * tiles * TILE_LEN + (yl % DEPTH_TILE) * DEPTH_TILE;
    assert!(bx0 >= 0 && (bx1 as usize) < tiles * DEPTH_TILE, "the box lies in the strip's columns");
    assert!(row_at(yl1) + (bx1 as usize / DEPTH_TILE) * TILE_LEN + DEPTH_TILE <= depth.len(), "the box lies in the strip");
    // Lanes from the first column's left edge, r = bx0 mod 8 texels left of the box: lane j
    // (of 32, two registers) is texel x = bx0 − r + j. Their edge values stay within ±2^29
    // (`small_edges`' bound, with offsets of up to 40 samples instead of 17), so i32 holds them.
    let r = bx0 % DEPTH_TILE as i32;
    let lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    let at = |i: usize, from: i32| {
        _mm512_add_epi32(
            _mm512_set1_epi32(e_row[i] + bias[i] + (from - r) * step_x[i]),
            _mm512_mullo_epi32(lane, _mm512_set1_epi32(step_x[i])),
        )
    };
    let (mut lo16, mut hi16) = ([0, 1, 2].map(|i| at(i, 0)), [0, 1, 2].map(|i| at(i, LANES)));
    let step_y16 = step_y.map(|s| _mm512_set1_epi32(s));
    let in_box = ((1u32 << (bx1 - bx0 + 1)) - 1) << r;
    // The unbiased edges 1 and 2 at lane r (the box's first texel), for the row's depth start.
    let (mut e1, mut e2) = (e_row[1], e_row[2]);
    // As the reference: row starts in f64, the step along x rounded once to f32.
    let inv = t.inv_area as f64;
    let (z0, dz1, dz2) = (t.z[0] as f64, (t.z[1] - t.z[0]) as f64, (t.z[2] - t.z[0]) as f64);
    let dzx = (step_x[1] as f64 * dz1 + step_x[2] as f64 * dz2) * inv;
    let dz = _mm512_set1_ps(dzx as f32);
    // Lane j of column k is lane 8k + j of the 32.
    let column = [0, 1, 2].map(|k| _mm512_cvtepi32_ps(_mm512_add_epi32(lane, _mm512_set1_epi32(8 * k))));
    let first = bx0 as usize / DEPTH_TILE * TILE_LEN;
    let base = depth.as_mut_ptr();
    let mut covered = 0u64;
    for yl in yl0..=yl1 {
        let inside =
            |e: [__m512i; 3]| _mm512_cmpge_epi32_mask(_mm512_or_si512(_mm512_or_si512(e[0], e[1]), e[2]), _mm512_setzero_si512()) as u32;
        let inside = (inside(lo16) | inside(hi16) << LANES) & in_box;
        if inside != 0 {
            // The span's first texel: lane k0, sample k0 − r of the box's row.
            let k0 = inside.trailing_zeros();
            let zs = (z0 + (e1 as f64 * dz1 + e2 as f64 * dz2) * inv + (k0 as i32 - r) as f64 * dzx) as f32;
            let (zs, k0f) = (_mm512_set1_ps(zs), _mm512_set1_ps(k0 as f32));
            let row = row_at(yl) + first;
            for (k, lanes) in column.iter().enumerate() {
                let m = (inside >> (8 * k)) as u16 & 0xff;
                // f32(x − x_lo) = f32(8k + j − k0), exact, as the reference's (x − x_lo) as f32.
                let z = _mm512_add_ps(zs, _mm512_mul_ps(_mm512_sub_ps(*lanes, k0f), dz));
                // Wrapping: a column past the box's last may point beyond `depth` (none of
                // its lanes is in `m`).
                let p = base.wrapping_add(row + k * TILE_LEN);
                // SAFETY: the lanes in `m` are texels of the box's row in this tile column,
                // its row of eight in `depth` (asserted above); masked-off lanes are not
                // accessed. Each column is its own 32-byte tile row, so rows never overlap
                // partially (a store the next load could not forward from).
                unsafe {
                    let d = _mm512_maskz_loadu_ps(m, p);
                    _mm512_mask_storeu_ps(p, _mm512_mask_cmp_ps_mask::<_CMP_GT_OQ>(m, z, d), z);
                }
            }
            covered += inside.count_ones() as u64;
        }
        for i in 0..3 {
            lo16[i] = _mm512_add_epi32(lo16[i], step_y16[i]);
            hi16[i] = _mm512_add_epi32(hi16[i], step_y16[i]);
        }
        e1 += step_y[1];
        e2 += step_y[2];
    }
    covered
}
