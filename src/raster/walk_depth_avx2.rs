//! The depth-only walk of a shadow map's tiles eight texels at a time in AVX2 registers, for
//! CPUs with AVX2 (chosen at run time through the [`Avx2`] token).
//!
//! The same texels and bits as [`walk_depth_rows`](super::walk_depth): each row's span comes
//! from [`RowSpans`] (the exact spans of `row_span`, stepped without a division), its depth
//! ramp starts from the same f64 value, and each texel's depth is `zs + f32(x − x_lo)·dz` with
//! separate `vmulps`/`vaddps` (no FMA is enabled), as the scalar `zs + (base + k)·dz` whose
//! integer sum is exact. One tile row (eight texels, 32 bytes) is one load, compare, blend
//! and store, the texels outside the span stored back unchanged.

use super::edge::SetupTri;
use super::edge::{RowSpans, edges};
use super::tiles::DEPTH_TILE;
use crate::simd::avx2::Avx2;
use std::arch::x86_64::*;

/// Texels of a storage tile.
const TILE_LEN: usize = DEPTH_TILE * DEPTH_TILE;

/// [`walk_depth_tiles_avx2`] for a CPU that has AVX2 (the token proves it).
#[inline]
pub(super) fn walk_depth_tiles8(_: Avx2, t: &SetupTri, y0: u32, rows: u32, tiles: usize, depth: &mut [f32]) -> u64 {
    // SAFETY: an `Avx2` token exists only when detection found every feature enabled below.
    unsafe { walk_depth_tiles_avx2(t, y0, rows, tiles, depth) }
}

/// The walk of [`DepthLayout::Tiles`](super::DepthLayout): `tiles` tiles a row of tiles,
/// rows counted from the strip's first (`y0`, `rows` rows). Returns the covered texels.
#[target_feature(enable = "avx2")]
fn walk_depth_tiles_avx2(t: &SetupTri, y0: u32, rows: u32, tiles: usize, depth: &mut [f32]) -> u64 {
    const _: () = assert!(DEPTH_TILE == 8, "one tile row is one AVX2 register");
    let (sy0, sy1) = (y0 as i32, (y0 + rows) as i32 - 1);
    let (bx0, by0, bx1, by1) = (t.bbox[0], t.bbox[1].max(sy0), t.bbox[2], t.bbox[3].min(sy1));
    if by0 > by1 || bx0 > bx1 {
        return 0;
    }
    let e = edges(t, bx0, by0);
    let mut spans = RowSpans::new(&e, (bx1 - bx0) as i64);
    let (mut e_row, step_y) = (e.e_row, e.step_y);
    // As the reference: row starts in f64, the step along x rounded once to f32.
    let inv = t.inv_area as f64;
    let (z0, dz1, dz2) = (t.z[0] as f64, (t.z[1] - t.z[0]) as f64, (t.z[2] - t.z[0]) as f64);
    let dzx = (e.step_x[1] as f64 * dz1 + e.step_x[2] as f64 * dz2) * inv;
    let dz = _mm256_set1_ps(dzx as f32);
    let lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    let (eight, minus_one) = (_mm256_set1_epi32(DEPTH_TILE as i32), _mm256_set1_epi32(-1));
    let mut covered = 0u64;
    for y in by0..=by1 {
        let (lo, hi) = spans.next();
        if lo <= hi {
            let zs = (z0 + (e_row[1] as f64 * dz1 + e_row[2] as f64 * dz2) * inv + lo as f64 * dzx) as f32;
            let yl = (y - sy0) as usize;
            let (x_lo, x_hi) = ((bx0 as i64 + lo) as usize, (bx0 as i64 + hi) as usize);
            let (c0, c1) = (x_lo / DEPTH_TILE, x_hi / DEPTH_TILE);
            // The row's part of tile column c starts at `row + c·TILE_LEN` (see `tiled`).
            let row = (yl / DEPTH_TILE) * tiles * TILE_LEN + (yl % DEPTH_TILE) * DEPTH_TILE;
            let end = row + c1 * TILE_LEN + DEPTH_TILE;
            assert!(x_hi < tiles * DEPTH_TILE && end <= depth.len(), "the span lies in the strip's tiles");
            let zs = _mm256_set1_ps(zs);
            let n = _mm256_set1_epi32((hi - lo + 1) as i32);
            // x − x_lo of each lane of the first tile column.
            let mut off = _mm256_add_epi32(lane, _mm256_set1_epi32((c0 * DEPTH_TILE) as i32 - x_lo as i32));
            let mut p = depth[row + c0 * TILE_LEN..end].as_mut_ptr();
            for _ in c0..=c1 {
                // Lanes in the span: 0 ≤ x − x_lo < n.
                let inside = _mm256_and_si256(_mm256_cmpgt_epi32(off, minus_one), _mm256_cmpgt_epi32(n, off));
                let z = _mm256_add_ps(zs, _mm256_mul_ps(_mm256_cvtepi32_ps(off), dz));
                // SAFETY: p points into `depth` at a tile row of a column ≤ c1, whose eight
                // texels end by `end` ≤ depth.len() (asserted above).
                unsafe {
                    let d = _mm256_loadu_ps(p);
                    let keep = _mm256_and_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(z, d), _mm256_castsi256_ps(inside));
                    _mm256_storeu_ps(p, _mm256_blendv_ps(d, z, keep));
                }
                // Wrapping: past the last column it points beyond `depth`, never read.
                p = p.wrapping_add(TILE_LEN);
                off = _mm256_add_epi32(off, eight);
            }
            covered += (hi - lo + 1) as u64;
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    covered
}
