//! The depth-only walk of shadow maps: each row's covered span solved from the edge
//! functions (the listing walk's samples and top-left rule) and its depths filled as one
//! linear ramp, in rows or in tiles of [`DEPTH_TILE`]² texels.

use super::edge::{Edges, SetupTri, edges, row_span};
use super::tiles::{DEPTH_TILE, DepthLayout, tiled};
use super::walk::WalkWidth;

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
    if let DepthLayout::Tiles { tiles } = layout {
        let (bx0, by0, bx1, by1) = (t.bbox[0], t.bbox[1].max(y0 as i32), t.bbox[2], t.bbox[3].min((y0 + rows) as i32 - 1));
        if by0 > by1 || bx0 > bx1 {
            return 0;
        }
        // Most of a sphere's triangles in a 2048² map: no division, no branch on the span.
        if let Some(avx512) = width.avx512
            && bx1 - bx0 < super::walk_depth_avx512::LANES
            && let Some(e) = super::edge::small_edges(t, bx0, by0)
        {
            return super::walk_depth_avx512::walk_depth_small16(avx512, t, y0, [bx0, by0, bx1, by1], e, tiles, depth);
        }
        if let Some(avx2) = width.avx2 {
            return super::walk_depth_avx2::walk_depth_tiles8(avx2, t, y0, rows, tiles, depth);
        }
    }
    let _ = width;
    walk_depth_rows(t, y0, rows, layout, depth)
}

/// [`walk_depth`] one row span at a time (each span solved by [`row_span`]), for any layout
/// and CPU: the reference the AVX2 walk of tiles matches bit for bit (tested by
/// `depth_walk_widths_agree_bit_for_bit`).
fn walk_depth_rows(t: &SetupTri, y0: u32, rows: u32, layout: DepthLayout, depth: &mut [f32]) -> u64 {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::edge::RowSpans;

    /// A deterministic integer in [−range, range] (SplitMix64 of `i`).
    fn any(i: u64, range: i64) -> i64 {
        let mut z = i.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) % (2 * range as u64 + 1)) as i64 - range
    }

    #[test]
    fn stepped_spans_are_the_divided_spans() {
        let mut nonempty = 0;
        for k in 0..4000u64 {
            // Small and large steps, zero steps (flat edges) and both signs of everything.
            let range = if k % 2 == 0 { 40 } else { 1 << 36 };
            let step = |j: u64| if any(k * 31 + j, 5) == 0 { 0 } else { any(k * 37 + j, range) };
            let e = Edges {
                e_row: [0, 1, 2].map(|i| any(k * 7 + i, range * 40)),
                step_x: [0, 1, 2].map(step),
                step_y: [3, 4, 5].map(step),
                bias: [0, 1, 2].map(|i| -(any(k * 11 + i, 1).abs())),
            };
            let last = any(k, 60).abs();
            let mut spans = RowSpans::new(&e, last);
            let mut e_row = e.e_row;
            for row in 0..50 {
                let want = row_span(&e_row, &e.step_x, &e.bias, last);
                let got = spans.next();
                assert!(got == want || (got.0 > got.1 && want.0 > want.1), "case {k}, row {row}: {got:?} ≠ {want:?}");
                nonempty += (want.0 <= want.1) as u32;
                for (v, s) in e_row.iter_mut().zip(e.step_y) {
                    *v += s;
                }
            }
        }
        assert!(nonempty > 10_000, "{nonempty} non-empty spans");
    }
}
