//! The depth-only walk of shadow maps: each row's covered span solved from the edge
//! functions (the listing walk's samples and top-left rule) and its depths filled as one
//! linear ramp, in rows or in tiles of [`DEPTH_TILE`]² texels.

use super::setup::SetupTri;
use super::walk::{Edges, WalkWidth, edges, row_span};

/// How a depth-only strip is laid out in memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthLayout {
    /// Row-major, `width` samples a row.
    Rows {
        /// Samples per row.
        width: usize,
    },
    /// Tiles of [`DEPTH_TILE`]² samples, `tiles` tiles a row of tiles (see [`tiled`]).
    Tiles {
        /// Tiles per row of tiles.
        tiles: usize,
    },
}

/// Samples per side of a [`DepthLayout::Tiles`] tile.
pub const DEPTH_TILE: usize = 8;

/// Index of sample (x, y) in a buffer of rows of `tiles` tiles of [`DEPTH_TILE`]² samples,
/// each tile row-major: the lookups of neighbouring points fall in a few cache lines
/// whatever the direction they move in.
#[inline(always)]
pub fn tiled(x: usize, y: usize, tiles: usize) -> usize {
    ((y / DEPTH_TILE) * tiles + x / DEPTH_TILE) * (DEPTH_TILE * DEPTH_TILE) + (y % DEPTH_TILE) * DEPTH_TILE + x % DEPTH_TILE
}

/// Depth-only walk of one triangle within the strip of `rows` sample rows from row `y0`
/// (laid out as `layout` says, rows counted from the strip's first): every covered sample
/// keeps the nearer (larger, reversed) depth. Returns the covered samples.
///
/// The shadow-map pass needs no barycentrics, so each row's covered span is solved from
/// the three edge functions at once (exactly, in integers, with the same top-left rule as
/// [`walk`]: the same samples) and its depths are filled as one linear ramp, a loop the
/// compiler vectorizes. Measured on the `shadow` bench (2048² map, floor + sphere): the
/// listing walk took the map pass to about 40 ms, this one to a few ms (docs/performance.md).
pub(super) fn walk_depth(t: &SetupTri, y0: u32, rows: u32, layout: DepthLayout, depth: &mut [f32], width: WalkWidth) -> u64 {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx2) = width.avx2 {
        return super::walk_avx2::walk_depth8(avx2, t, y0, rows, layout, depth);
    }
    let _ = width;
    walk_depth_rows(t, y0, rows, layout, depth)
}

/// [`walk_depth`]'s body, inlined into each entry point: compiled for baseline x86-64 its
/// span fills vectorize to four lanes, inside the AVX2 entry to eight (the same per-texel
/// operations, so the same bits: tested by `depth_walk_widths_agree_bit_for_bit`).
#[inline(always)]
pub(super) fn walk_depth_rows(t: &SetupTri, y0: u32, rows: u32, layout: DepthLayout, depth: &mut [f32]) -> u64 {
    let (sy0, sy1) = (y0 as i32, (y0 + rows) as i32 - 1);
    let (bx0, by0, bx1, by1) = (t.bbox[0], t.bbox[1].max(sy0), t.bbox[2], t.bbox[3].min(sy1));
    if by0 > by1 || bx0 > bx1 {
        return 0;
    }
    let Edges { mut e_row, step_x, step_y, bias } = edges(t, bx0, by0);
    // Depth is linear in the screen-space barycentrics l_i = E_i / (2 area): along a row,
    // z(k) = z(0) + k·dz/dx. Row starts in f64, so long rows keep their precision.
    let inv = t.inv_area as f64;
    let (z0, dz1, dz2) = (t.z[0] as f64, (t.z[1] - t.z[0]) as f64, (t.z[2] - t.z[0]) as f64);
    let dzx = (step_x[1] as f64 * dz1 + step_x[2] as f64 * dz2) * inv;
    let last = (bx1 - bx0) as i64;
    let mut covered = 0u64;
    for y in by0..=by1 {
        let (lo, hi) = row_span(&e_row, &step_x, &bias, last);
        if lo <= hi {
            let zs = (z0 + (e_row[1] as f64 * dz1 + e_row[2] as f64 * dz2) * inv + lo as f64 * dzx) as f32;
            let dz = dzx as f32;
            let (yl, x_lo, x_hi) = ((y - sy0) as usize, (bx0 as i64 + lo) as usize, (bx0 as i64 + hi) as usize);
            // The span in runs that are contiguous in memory: the whole row, or each tile's part.
            let mut x = x_lo;
            while x <= x_hi {
                let (at, run_end) = match layout {
                    DepthLayout::Rows { width } => (yl * width + x, x_hi),
                    DepthLayout::Tiles { tiles } => (tiled(x, yl, tiles), x_hi.min(x | (DEPTH_TILE - 1))),
                };
                let base = (x - x_lo) as f32;
                let run = &mut depth[at..=at + (run_end - x)];
                if let Ok(run) = <&mut [f32; DEPTH_TILE]>::try_from(&mut *run) {
                    // A whole tile row: a fixed-length loop the compiler turns into vector ops.
                    for (k, d) in run.iter_mut().enumerate() {
                        let z = zs + (base + k as f32) * dz;
                        *d = if z > *d { z } else { *d };
                    }
                } else {
                    for (k, d) in run.iter_mut().enumerate() {
                        let z = zs + (base + k as f32) * dz;
                        *d = if z > *d { z } else { *d };
                    }
                }
                x = run_end + 1;
            }
            covered += (hi - lo + 1) as u64;
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    covered
}
