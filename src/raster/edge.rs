//! The edge functions of a set-up triangle: the 80-byte record the walks read, its three
//! edge functions at a sample with their steps and the top-left rule, each row's exact
//! covered span, and the depth at a sample. Every walk (one sample, lanes of four, eight or
//! sixteen, the depth-only walk of shadow maps) computes from these, so they agree to the bit.

use super::{HALF, ONE};

/// A triangle ready for the edge walk (after clipping, snapping and orientation): 80 bytes
/// (144 before the clipped barycentrics moved to a side table and x, y to i32; the dense
/// bench sets up ~520k of them per frame).
#[derive(Debug, Clone, Copy)]
pub(super) struct SetupTri {
    /// Fixed-point sample coordinates (within ±2^27: the guard band), wound so that the
    /// signed area is positive.
    pub(super) x: [i32; 3],
    pub(super) y: [i32; 3],
    /// Reversed depth z/w and 1/w per vertex.
    pub(super) z: [f32; 3],
    pub(super) q: [f32; 3],
    /// Inclusive sample bounding box: x0, y0, x1, y1.
    pub(super) bbox: [i32; 4],
    /// 1 / (twice the signed area), the area in fixed point (> 0).
    pub(super) inv_area: f32,
    /// Index of the original triangle.
    pub(super) orig: u32,
    /// For clipped pieces, the index in [`Chunk::clipped`] of each vertex's barycentrics in
    /// the original triangle; [`UNCLIPPED`] otherwise.
    pub(super) clipped: u32,
    /// Vertices 1 and 2 were swapped to make the area positive (unclipped triangles only).
    pub(super) swapped: bool,
}

/// [`SetupTri::clipped`] of a triangle that was not clipped.
pub(super) const UNCLIPPED: u32 = u32::MAX;

/// The widest lane walk: lanes past a box's right end still compute edge values, so the
/// i32 bound and the depth buffer's padding allow this many.
pub(super) const MAX_WALK_LANES: usize = 16;

/// The three edge functions of a set-up triangle at a sample, their steps per sample along
/// x and y, and the top-left rule as a bias.
pub(super) struct Edges {
    pub(super) e_row: [i64; 3],
    pub(super) step_x: [i64; 3],
    pub(super) step_y: [i64; 3],
    pub(super) bias: [i64; 3],
}

/// [`Edges`] of `t` at sample (x0, y0).
#[inline(always)]
pub(super) fn edges(t: &SetupTri, x0: i32, y0: i32) -> Edges {
    let (tx, ty) = (t.x.map(|v| v as i64), t.y.map(|v| v as i64));
    let (px, py) = (x0 as i64 * ONE + HALF, y0 as i64 * ONE + HALF);
    let mut e = Edges { e_row: [0; 3], step_x: [0; 3], step_y: [0; 3], bias: [0; 3] };
    for i in 0..3 {
        // Edge i is opposite vertex i: from vertex i+1 to vertex i+2.
        // E(p) = (b.x − a.x)(p.y − a.y) − (b.y − a.y)(p.x − a.x), positive inside.
        let (a, b) = ((i + 1) % 3, (i + 2) % 3);
        let (dx, dy) = (tx[b] - tx[a], ty[b] - ty[a]);
        e.e_row[i] = dx * (py - ty[a]) - dy * (px - tx[a]);
        e.step_x[i] = -dy * ONE;
        e.step_y[i] = dx * ONE;
        // Top-left rule: a sample exactly on an edge belongs to the triangle only if the
        // edge is a top edge (horizontal, interior below) or a left edge (going up).
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        e.bias[i] = if top_left { 0 } else { -1 };
    }
    e
}

/// Vertices closer than this (in subpixels, 32 samples) in x and in y give edge values under
/// 2^28 over their box and the lanes past it (|dx|, |dy| < 2^13 times offsets under 2^13 +
/// 17 samples), so i32 holds them: [`small_edges`] computes them without the corner check.
const SMALL_EXTENT: i32 = 1 << 13;

/// [`edges`] in i32 (`[e_row, step_x, step_y, bias]`, the same integers) for a triangle whose
/// vertices are within [`SMALL_EXTENT`] of each other (the `dense` bench's: its i64 edges,
/// corner check and conversions were a third of its walk); `None` for a larger one.
#[inline(always)]
pub(super) fn small_edges(t: &SetupTri, x0: i32, y0: i32) -> Option<[[i32; 3]; 4]> {
    let (tx, ty) = (t.x, t.y);
    let extent = |v: [i32; 3]| v[0].max(v[1]).max(v[2]) - v[0].min(v[1]).min(v[2]);
    if extent(tx) >= SMALL_EXTENT || extent(ty) >= SMALL_EXTENT {
        return None;
    }
    // The box's samples lie within a sample of the vertices (the box is theirs, clipped to
    // the screen), so each offset below is under 2^13 + 17 samples.
    let (px, py) = (x0 * ONE as i32 + HALF as i32, y0 * ONE as i32 + HALF as i32);
    let (mut e_row, mut step_x, mut step_y, mut bias) = ([0i32; 3], [0i32; 3], [0i32; 3], [0i32; 3]);
    for i in 0..3 {
        let (a, b) = ((i + 1) % 3, (i + 2) % 3);
        let (dx, dy) = (tx[b] - tx[a], ty[b] - ty[a]);
        e_row[i] = dx * (py - ty[a]) - dy * (px - tx[a]);
        step_x[i] = -dy * ONE as i32;
        step_y[i] = dx * ONE as i32;
        bias[i] = if dy < 0 || (dy == 0 && dx > 0) { 0 } else { -1 };
    }
    Some([e_row, step_x, step_y, bias])
}

/// The samples k in 0..=`last` of a box row where every biased edge function
/// `e_row[i] + bias[i] + step_x[i]·k` is ≥ 0 (the walk's inside test, the top-left rule in
/// the bias), as `(lo, hi)`; empty when lo > hi. Exact, in integers.
#[inline(always)]
pub(super) fn row_span(e_row: &[i64; 3], step_x: &[i64; 3], bias: &[i64; 3], last: i64) -> (i64, i64) {
    let (mut lo, mut hi) = (0i64, last);
    for i in 0..3 {
        let (e, s) = (e_row[i] + bias[i], step_x[i]);
        if s > 0 {
            // k ≥ ceil(−e / s) = −floor(e / s)
            lo = lo.max(-e.div_euclid(s));
        } else if s < 0 {
            // k ≤ floor(e / −s)
            hi = hi.min(e.div_euclid(-s));
        } else if e < 0 {
            hi = -1;
        }
    }
    (lo, hi)
}

/// What bounds a row's span from one edge: its step along x decides.
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))] // only the x86 paths use it
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Bound {
    /// Step > 0: the edge gives the span's first sample.
    Lo,
    /// Step < 0: the edge gives the span's last sample.
    Hi,
    /// Step 0 (a horizontal edge): the whole row is in or out.
    Flat,
}

/// [`row_span`] of row after row, exact in integers with no division per row: for each
/// sloped edge ⌊E/|s|⌋ is kept as a quotient and remainder and stepped by ⌊s_y/|s|⌋ and
/// s_y mod |s| (a carry when the remainder reaches |s|), the integer form of a DDA.
/// A division per edge and row was a fifth of the depth-only walk's time (perf, `shadow`).
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))] // only the x86 paths use it
pub(super) struct RowSpans {
    bound: [Bound; 3],
    /// ⌊E/|s|⌋ and E mod |s| of the biased edge value E (E itself for a flat edge).
    q: [i64; 3],
    r: [i64; 3],
    /// |s|, and ⌊s_y/|s|⌋, s_y mod |s| (s_y for a flat edge).
    m: [i64; 3],
    dq: [i64; 3],
    dr: [i64; 3],
    last: i64,
}

#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))] // only the x86 paths use it
impl RowSpans {
    /// The spans of the box rows whose first row has edge values `e_row`.
    pub(super) fn new(e: &Edges, last: i64) -> RowSpans {
        let mut s = RowSpans { bound: [Bound::Flat; 3], q: [0; 3], r: [0; 3], m: [1; 3], dq: [0; 3], dr: [0; 3], last };
        for i in 0..3 {
            let (biased, sx, sy) = (e.e_row[i] + e.bias[i], e.step_x[i], e.step_y[i]);
            if sx == 0 {
                (s.q[i], s.dq[i]) = (biased, sy);
                continue;
            }
            let m = sx.abs();
            s.bound[i] = if sx > 0 { Bound::Lo } else { Bound::Hi };
            (s.m[i], s.q[i], s.r[i], s.dq[i], s.dr[i]) =
                (m, biased.div_euclid(m), biased.rem_euclid(m), sy.div_euclid(m), sy.rem_euclid(m));
        }
        s
    }

    /// This row's span `(lo, hi)` (empty when lo > hi), then a step to the next row.
    #[inline(always)]
    pub(super) fn next(&mut self) -> (i64, i64) {
        let (mut lo, mut hi) = (0i64, self.last);
        for i in 0..3 {
            match self.bound[i] {
                // k ≥ ceil(−E/s) = −⌊E/s⌋
                Bound::Lo => lo = lo.max(-self.q[i]),
                // k ≤ ⌊E/−s⌋
                Bound::Hi => hi = hi.min(self.q[i]),
                Bound::Flat if self.q[i] < 0 => hi = -1,
                Bound::Flat => {}
            }
            self.q[i] += self.dq[i];
            if self.bound[i] != Bound::Flat {
                self.r[i] += self.dr[i];
                if self.r[i] >= self.m[i] {
                    self.r[i] -= self.m[i];
                    self.q[i] += 1;
                }
            }
        }
        (lo, hi)
    }
}

/// Reversed depth z/w at screen-space barycentrics (l1, l2) of a set-up triangle with vertex
/// depths `z`: the walk's depth test, and the owner test after overdraw (the same bits).
#[inline(always)]
pub(super) fn depth_at(z: &[f32; 3], l1: f32, l2: f32) -> f32 {
    z[0] + l1 * (z[1] - z[0]) + l2 * (z[2] - z[0])
}
