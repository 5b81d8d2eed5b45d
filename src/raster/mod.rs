//! Triangles → covered samples. No graphics library, and no knowledge of light.
//!
//! Stages, each a short function:
//! 1. **setup**: vertices are projected once each to the sample grid and snapped to fixed
//!    point (1/256 sample); triangles with a vertex outside the guard band or the near plane
//!    are clipped ([`clip`]) and their pieces projected; triangles are culled by facing and
//!    binned into horizontal strips of rows;
//! 2. **strip raster**: for each triangle of a strip, walk its bounding box with
//!    integer edge functions (Pineda 1988) and the top-left fill rule, keeping the
//!    nearest sample (reversed depth: larger z/w is nearer) with its screen-space
//!    barycentrics, listed by the triangle that owns it ([`StripVis`]);
//! 3. **resolve** ([`StripTri::resolve`]): screen-space barycentrics become
//!    perspective-correct barycentrics of the *original* triangle (Heckbert & Moreton
//!    1991), for the renderer a bundle of one triangle's samples at a time, for
//!    [`rasterize`] one sample at a time into a whole-image [`VisBuffer`].
//!
//! Strips are independent, so they run in parallel (rayon) with identical results for
//! any thread count; each strip processes its triangles in submission order.
//!
//! Measured on the `dense` bench (1,046,528 triangles, 1024²; callgrind, `shadelab
//! --threads 1 bench --workload dense --frames 1 --warmup 0`, three frames): 3.90e9 →
//! 2.65e9 instructions for the whole run with these changes together: vertices projected
//! once instead of once per triangle corner, `f32::round` (a libm call on baseline x86-64)
//! and the f64 ceil/floor of the box replaced by exact integer arithmetic, an 80-byte setup
//! record (144 before), binning per chunk in parallel (a counting sort) instead of serially,
//! and the resolve pass folded into the walk. The resolve then left the walk for the
//! shading bundles (one divide per bundle of lanes; measured in `render/pipeline.rs`).

pub mod clip;

use crate::simd::lanes::Lanes;
use glam::{Vec3, Vec4};
use rayon::prelude::*;

/// Marks a sample that no triangle covers.
pub const NO_TRIANGLE: u32 = u32::MAX;
/// Fixed-point subsample precision: 8 bits (1/256 of a sample).
const SUBPIXEL_BITS: u32 = 8;
const ONE: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = ONE / 2;
/// Screen coordinates stay within ±2^19 samples (guard band), so edge-function products fit in i64.
const GUARD_SAMPLES: f32 = (1 << 19) as f32;

/// Which triangles are discarded by facing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CullMode {
    /// Drop triangles wound clockwise on screen (counter-clockwise is front).
    Back,
    /// Keep every triangle.
    None,
}

/// One sample of the visibility buffer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VisSample {
    /// Index of the original triangle, or [`NO_TRIANGLE`].
    pub tri: u32,
    /// Perspective-correct barycentric weight of the triangle's vertex 1.
    pub b1: f32,
    /// Perspective-correct barycentric weight of the triangle's vertex 2.
    pub b2: f32,
    /// Reversed depth z/w (1 at the near plane, 0 at infinity).
    pub depth: f32,
}

impl VisSample {
    /// An uncovered sample.
    pub const EMPTY: VisSample = VisSample { tri: NO_TRIANGLE, b1: 0.0, b2: 0.0, depth: 0.0 };

    /// Barycentric weights (b0, b1, b2).
    #[inline]
    pub fn bary(&self) -> Vec3 {
        Vec3::new(1.0 - self.b1 - self.b2, self.b1, self.b2)
    }
}

/// Counts from setup and rasterization.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RasterStats {
    /// Triangles submitted.
    pub triangles_in: u64,
    /// Triangles that had to be clipped (crossing the near plane or the guard band).
    pub triangles_clipped: u64,
    /// Triangles discarded: back-facing.
    pub triangles_culled: u64,
    /// Triangles discarded: wholly behind the camera or outside the image.
    pub triangles_outside: u64,
    /// Triangles with zero area on the sample grid (or non-finite vertices).
    pub triangles_degenerate: u64,
    /// Samples that passed the coverage test (before depth testing; counts overdraw).
    pub samples_rasterized: u64,
}

impl std::ops::AddAssign for RasterStats {
    fn add_assign(&mut self, o: RasterStats) {
        self.triangles_in += o.triangles_in;
        self.triangles_clipped += o.triangles_clipped;
        self.triangles_culled += o.triangles_culled;
        self.triangles_outside += o.triangles_outside;
        self.triangles_degenerate += o.triangles_degenerate;
        self.samples_rasterized += o.samples_rasterized;
    }
}

/// A triangle ready for the edge walk (after clipping, snapping and orientation): 80 bytes
/// (144 before the clipped barycentrics moved to a side table and x, y to i32; the dense
/// bench sets up ~520k of them per frame).
#[derive(Debug, Clone, Copy)]
struct SetupTri {
    /// Fixed-point sample coordinates (within ±2^27: the guard band), wound so that the
    /// signed area is positive.
    x: [i32; 3],
    y: [i32; 3],
    /// Reversed depth z/w and 1/w per vertex.
    z: [f32; 3],
    q: [f32; 3],
    /// Inclusive sample bounding box: x0, y0, x1, y1.
    bbox: [i32; 4],
    /// 1 / (twice the signed area), the area in fixed point (> 0).
    inv_area: f32,
    /// Index of the original triangle.
    orig: u32,
    /// For clipped pieces, the index in [`Chunk::clipped`] of each vertex's barycentrics in
    /// the original triangle; [`UNCLIPPED`] otherwise.
    clipped: u32,
    /// Vertices 1 and 2 were swapped to make the area positive (unclipped triangles only).
    swapped: bool,
}

/// [`SetupTri::clipped`] of a triangle that was not clipped.
const UNCLIPPED: u32 = u32::MAX;

/// Triangles per setup chunk (set up in parallel, concatenated in order).
const CHUNK: usize = 4096;

/// One chunk of consecutive input triangles, set up and binned by one worker.
struct Chunk {
    /// Its triangles in submission order.
    tris: Vec<SetupTri>,
    /// Barycentrics (in the original triangle) of clipped pieces' vertices.
    clipped: Vec<[Vec3; 3]>,
    /// `bins[bin_start[s]..bin_start[s + 1]]` are the indices into `tris` that touch strip `s`.
    bin_start: Vec<u32>,
    bins: Vec<u32>,
}

/// Triangles set up and binned into strips: the input of [`Setup::rasterize_strip`].
pub struct Setup {
    chunks: Vec<Chunk>,
    width: u32,
    height: u32,
    strip_rows: u32,
    strips: usize,
    /// Counts from setup (samples_rasterized is added by the strips).
    pub stats: RasterStats,
}

/// A vertex on the sample grid: fixed-point position, reversed depth z/w, 1/w
/// ([`Projected::CLIP`] when its triangles need the clipping path).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Projected {
    x: i32,
    y: i32,
    z: f32,
    q: f32,
}

/// Sets up `triangles` (indices into `clip`, clip-space positions) for a `width` × `height`
/// sample grid, binned into strips of `strip_rows` rows.
///
/// Vertices are projected once each (a vertex is shared by ~6 triangles of a mesh); a
/// triangle with a vertex outside the guard band or the near plane (or not finite) takes
/// the clipping path from its clip-space positions. Chunks of `CHUNK` (4096) triangles are set up
/// and binned in parallel; strips read the chunks in order, so submission order holds.
///
/// Preconditions: `width`, `height`, `strip_rows` ≥ 1; indices are in range.
pub fn setup(clip: &[Vec4], triangles: &[[u32; 3]], width: u32, height: u32, strip_rows: u32, cull: CullMode) -> Setup {
    let g = GUARD_SAMPLES / width.max(height) as f32;
    let strips = height.div_ceil(strip_rows) as usize;
    // Each vertex on the sample grid, or CLIP when its triangles need the clipping path.
    let projected: Vec<Projected> = clip
        .par_iter()
        .map(|p| {
            let inside = p.is_finite() && clip::distances(*p, g).iter().all(|d| *d >= 0.0);
            if inside { project_vertex(*p, width, height) } else { Projected::CLIP }
        })
        .collect();
    let chunks: Vec<(Chunk, RasterStats)> = triangles
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut out = Chunk { tris: Vec::with_capacity(chunk.len()), clipped: Vec::new(), bin_start: Vec::new(), bins: Vec::new() };
            let mut stats = RasterStats::default();
            for (i, t) in chunk.iter().enumerate() {
                let id = (c * CHUNK + i) as u32;
                let p = [projected[t[0] as usize], projected[t[1] as usize], projected[t[2] as usize]];
                if p.iter().all(|p| p.x != Projected::CLIP.x) {
                    assemble(p, None, id, width, height, cull, &mut out, &mut stats);
                } else {
                    let v = [clip[t[0] as usize], clip[t[1] as usize], clip[t[2] as usize]];
                    setup_triangle(v, id, width, height, g, cull, &mut out, &mut stats);
                }
            }
            out.bin_by_strip(strips, strip_rows);
            (out, stats)
        })
        .collect();
    let mut stats = RasterStats { triangles_in: triangles.len() as u64, ..Default::default() };
    for (_, s) in &chunks {
        stats += *s;
    }
    Setup { chunks: chunks.into_iter().map(|(c, _)| c).collect(), width, height, strip_rows, strips, stats }
}

impl Chunk {
    /// Bins the chunk's triangles by strip (a counting sort: counts, offsets, fill).
    fn bin_by_strip(&mut self, strips: usize, strip_rows: u32) {
        let span = |t: &SetupTri| (t.bbox[1] as u32 / strip_rows) as usize..=(t.bbox[3] as u32 / strip_rows) as usize;
        let mut start = vec![0u32; strips + 1];
        for t in &self.tris {
            for s in span(t) {
                start[s + 1] += 1;
            }
        }
        for s in 0..strips {
            start[s + 1] += start[s];
        }
        let mut fill = start.clone();
        let mut bins = vec![0u32; start[strips] as usize];
        for (i, t) in self.tris.iter().enumerate() {
            for s in span(t) {
                bins[fill[s] as usize] = i as u32;
                fill[s] += 1;
            }
        }
        self.bin_start = start;
        self.bins = bins;
    }

    /// Indices into `tris` of the triangles touching strip `s`, in submission order.
    fn bin(&self, s: usize) -> &[u32] {
        &self.bins[self.bin_start[s] as usize..self.bin_start[s + 1] as usize]
    }
}

#[allow(clippy::too_many_arguments)]
fn setup_triangle(v: [Vec4; 3], id: u32, width: u32, height: u32, g: f32, cull: CullMode, out: &mut Chunk, stats: &mut RasterStats) {
    if !v.iter().all(|p| p.is_finite()) {
        stats.triangles_degenerate += 1;
        return;
    }
    let inside = v.iter().all(|p| clip::distances(*p, g).iter().all(|d| *d >= 0.0));
    if inside {
        let p = v.map(|v| project_vertex(v, width, height));
        assemble(p, None, id, width, height, cull, out, stats);
        return;
    }
    stats.triangles_clipped += 1;
    let Some(poly) = clip::clip_triangle(v, g) else {
        stats.triangles_outside += 1;
        return;
    };
    // Fan-triangulate the convex polygon; every piece keeps the original's id.
    let p = &poly.verts[..poly.len];
    for i in 1..poly.len - 1 {
        let (a, b, c) = (p[0], p[i], p[i + 1]);
        let projected = [a.pos, b.pos, c.pos].map(|v| project_vertex(v, width, height));
        assemble(projected, Some([a.bary, b.bary, c.bary]), id, width, height, cull, out, stats);
    }
}

impl Projected {
    /// Marks a vertex outside the guard band or the near plane, or not finite (x is never
    /// i32::MIN on the grid: the guard band keeps |x| < 2^28).
    const CLIP: Projected = Projected { x: i32::MIN, y: 0, z: 0.0, q: 0.0 };
}

/// Clip space → sample grid: x right, y down (row 0 at the top), snapped to 1/256 sample.
///
/// Precondition: `v` is inside the guard band and in front of the near plane.
#[inline]
fn project_vertex(v: Vec4, width: u32, height: u32) -> Projected {
    let q = 1.0 / v.w;
    let sx = (v.x * q + 1.0) * 0.5 * width as f32;
    let sy = (1.0 - v.y * q) * 0.5 * height as f32;
    Projected { x: round_half_away(sx * ONE as f32), y: round_half_away(sy * ONE as f32), z: v.z * q, q }
}

/// `x.round() as i32` for |x| < 2^30 without the libm call `f32::round` is on baseline x86-64
/// (no SSE4.1 `roundss`): truncate, then step away from zero when the dropped fraction is at
/// least ½. Exact: for |x| < 2^23 the fraction x − trunc(x) is computed exactly, and above
/// that x is an integer (tested against `f32::round`). Measured: `roundf` was 5.7% of the
/// dense bench.
#[inline]
fn round_half_away(x: f32) -> i32 {
    let t = x as i32;
    let frac = x - t as f32;
    t + (frac >= 0.5) as i32 - (frac <= -0.5) as i32
}

/// Culls and orients a projected triangle, computes its box, and adds it to `out`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn assemble(
    p: [Projected; 3],
    bary: Option<[Vec3; 3]>,
    id: u32,
    width: u32,
    height: u32,
    cull: CullMode,
    out: &mut Chunk,
    stats: &mut RasterStats,
) {
    let mut x = p.map(|p| p.x);
    let mut y = p.map(|p| p.y);
    let mut z = p.map(|p| p.z);
    let mut q = p.map(|p| p.q);
    // Twice the signed area; with y down, counter-clockwise in NDC (front) is negative.
    let (dx1, dy1, dx2, dy2) = ((x[1] - x[0]) as i64, (y[1] - y[0]) as i64, (x[2] - x[0]) as i64, (y[2] - y[0]) as i64);
    let area2 = dx1 * dy2 - dy1 * dx2;
    if area2 == 0 {
        stats.triangles_degenerate += 1;
        return;
    }
    if area2 > 0 && cull == CullMode::Back {
        stats.triangles_culled += 1;
        return;
    }
    let mut bary = bary;
    let mut area2 = area2;
    let swapped = area2 < 0;
    if swapped {
        // Swap vertices 1 and 2 so the area is positive; barycentrics follow the swap.
        x.swap(1, 2);
        y.swap(1, 2);
        z.swap(1, 2);
        q.swap(1, 2);
        if let Some(m) = bary.as_mut() {
            m.swap(1, 2);
        }
        area2 = -area2;
    }
    // Samples sit at centres (s + 0.5); the box holds samples whose centre may be inside:
    // the first sample at or after (lo − ½) and the last at or before (hi − ½), in integer
    // arithmetic (ceil and floor of a division by 256 as shifts).
    let first = |lo: i32| (lo as i64 - HALF + ONE - 1) >> SUBPIXEL_BITS;
    let last = |hi: i32| (hi as i64 - HALF) >> SUBPIXEL_BITS;
    let x0 = first(x[0].min(x[1]).min(x[2])).max(0);
    let y0 = first(y[0].min(y[1]).min(y[2])).max(0);
    let x1 = last(x[0].max(x[1]).max(x[2])).min(width as i64 - 1);
    let y1 = last(y[0].max(y[1]).max(y[2])).min(height as i64 - 1);
    if x0 > x1 || y0 > y1 {
        stats.triangles_outside += 1;
        return;
    }
    let clipped = match bary {
        Some(m) => {
            out.clipped.push(m);
            (out.clipped.len() - 1) as u32
        }
        None => UNCLIPPED,
    };
    out.tris.push(SetupTri {
        x,
        y,
        z,
        q,
        bbox: [x0 as i32, y0 as i32, x1 as i32, y1 as i32],
        inv_area: 1.0 / area2 as f32,
        orig: id,
        clipped,
        swapped: swapped && clipped == UNCLIPPED,
    });
}

/// The visibility of one strip of rows, reused across strips (thread-local in the renderer).
///
/// Per sample: the nearest depth and which entry of the owned-sample list holds it. Per
/// walked triangle that owns samples ([`StripTri`]): a contiguous range of that list, each
/// entry a sample index with its *screen-space* barycentrics (l1, l2). The perspective
/// division is left to [`StripTri::resolve`], which the renderer runs four or eight samples
/// of one triangle at a time (one `divps` per lane bundle instead of a `divss` stall per
/// depth-test pass; the same formula, so the same bits as resolving at the depth test).
#[derive(Debug, Clone, Default)]
pub struct StripVis {
    /// First sample row of the strip.
    pub y0: u32,
    /// Rows in the strip.
    pub rows: u32,
    /// Samples per row.
    pub width: u32,
    /// Per sample (`rows × width`, row-major): reversed depth z/w of the nearest triangle,
    /// 0 where no triangle covers it (a written depth is > 0, so this is the coverage).
    depth: Vec<f32>,
    /// The walked triangles that own samples, in submission order.
    tris: Vec<StripTri>,
    /// The owned-sample list, triangle after triangle: sample index and screen-space l1, l2,
    /// entries `..listed`, then [`LIST_PAD`] zero entries so bundles of lanes load past the
    /// end. The vectors only grow (entries are written by index), so a strip allocates and
    /// zero-fills nothing once the thread's buffers are large enough.
    index: Vec<u32>,
    l1: Vec<f32>,
    l2: Vec<f32>,
    /// Entries in the owned-sample list.
    listed: usize,
    /// Barycentric maps of clipped pieces ([`BaryMap::Clipped`]).
    clipped: Vec<[Vec3; 3]>,
}

/// Zero entries after the owned-sample list: a bundle of up to sixteen lanes loads in bounds.
pub const LIST_PAD: usize = 16;

/// Depth entries after a strip's samples: the lane walk loads and stores four samples at a time.
const DEPTH_PAD: usize = WALK_LANES;

/// How a walked triangle's screen-space barycentrics map to the original triangle's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BaryMap {
    /// The set-up triangle is the original, vertex for vertex.
    Same,
    /// The set-up triangle is the original with vertices 1 and 2 swapped.
    Swapped,
    /// A clipped piece: `StripVis::clipped[i]` holds the barycentrics (in the original
    /// triangle) of its vertices.
    Clipped(u32),
    /// The barycentrics are already perspective-correct ones of the original triangle (a
    /// strip loaded from a [`VisBuffer`]).
    Resolved,
}

/// A triangle that owns samples of a strip.
#[derive(Debug, Clone, Copy)]
pub struct StripTri {
    /// Reversed depth z/w at the set-up triangle's vertices.
    z: [f32; 3],
    /// 1/w at the set-up triangle's vertices.
    q: [f32; 3],
    /// Index of the original triangle.
    pub orig: u32,
    /// How its barycentrics map to the original triangle's.
    map: BaryMap,
    /// Its entries in the owned-sample list: `start..end`.
    start: u32,
    end: u32,
}

/// The samples one [`StripTri`] owns: parallel slices, each padded with [`LIST_PAD`] entries
/// past `len` (readable, not owned).
#[derive(Debug, Clone, Copy)]
pub struct Owned<'a> {
    /// Number of owned samples.
    pub len: usize,
    /// Sample indices in the strip (row-major).
    pub index: &'a [u32],
    /// Screen-space barycentric weight of the set-up triangle's vertex 1.
    pub l1: &'a [f32],
    /// Screen-space barycentric weight of the set-up triangle's vertex 2.
    pub l2: &'a [f32],
}

impl StripTri {
    /// Its first entry in the strip's owned-sample list.
    pub fn start(&self) -> u32 {
        self.start
    }

    /// Screen-space barycentrics (l1, l2) of the set-up triangle → perspective-correct
    /// barycentrics (b1, b2) of the original triangle (Heckbert & Moreton 1991), for one
    /// sample (`f32`) or for lanes: one formula, lane-wise IEEE arithmetic, so the same bits.
    /// `clipped` is the strip's table ([`StripVis::clipped`]).
    #[inline(always)]
    pub fn resolve<F: Lanes>(&self, clipped: &[[Vec3; 3]], l1: F, l2: F) -> (F, F) {
        match self.map {
            BaryMap::Resolved => (l1, l2),
            BaryMap::Same => {
                let (_, w1, w2, sum) = self.weights(l1, l2);
                (w1 / sum, w2 / sum)
            }
            BaryMap::Swapped => {
                let (_, w1, w2, sum) = self.weights(l1, l2);
                (w2 / sum, w1 / sum)
            }
            BaryMap::Clipped(i) => {
                // b = m0 b0 + m1 b1 + m2 b2, the piece's vertices in the original triangle.
                let m = &clipped[i as usize];
                let (w0, w1, w2, sum) = self.weights(l1, l2);
                let (b0, b1, b2) = (w0 / sum, w1 / sum, w2 / sum);
                let y = F::splat(m[0].y) * b0 + F::splat(m[1].y) * b1 + F::splat(m[2].y) * b2;
                let z = F::splat(m[0].z) * b0 + F::splat(m[1].z) * b1 + F::splat(m[2].z) * b2;
                (y, z)
            }
        }
    }

    /// Attributes are linear in 1/w: b_i = λ_i q_i / Σ λ_j q_j with λ_0 = 1 − λ_1 − λ_2; the
    /// weights λ_i q_i and their sum.
    #[inline(always)]
    fn weights<F: Lanes>(&self, l1: F, l2: F) -> (F, F, F, F) {
        let l0 = F::splat(1.0) - l1 - l2;
        let (w0, w1, w2) = (l0 * F::splat(self.q[0]), l1 * F::splat(self.q[1]), l2 * F::splat(self.q[2]));
        (w0, w1, w2, w0 + w1 + w2)
    }
}

impl StripVis {
    /// True when a triangle covers sample `i` (row-major in the strip).
    #[inline]
    pub fn covered(&self, i: usize) -> bool {
        self.depth[i] > 0.0
    }

    /// Per sample: reversed depth, 0 where uncovered.
    pub fn depth(&self) -> &[f32] {
        &self.depth[..(self.rows * self.width) as usize]
    }

    /// Entries in the owned-sample list: the covered samples, each listed once (by the
    /// triangle that owns it).
    pub fn listed(&self) -> usize {
        self.listed
    }

    /// The triangles owning samples, in submission order.
    pub fn tris(&self) -> &[StripTri] {
        &self.tris
    }

    /// The barycentric maps of clipped pieces (the `clipped` argument of [`StripTri::resolve`]).
    pub fn clipped(&self) -> &[[Vec3; 3]] {
        &self.clipped
    }

    /// Sample index of entry `e` of the owned-sample list.
    #[inline]
    pub fn entry_index(&self, e: usize) -> u32 {
        self.index[e]
    }

    /// Screen-space l1 of entry `e` of the owned-sample list.
    #[inline]
    pub fn entry_l1(&self, e: usize) -> f32 {
        self.l1[e]
    }

    /// Screen-space l2 of entry `e` of the owned-sample list.
    #[inline]
    pub fn entry_l2(&self, e: usize) -> f32 {
        self.l2[e]
    }

    /// The samples triangle `t` owns.
    #[inline]
    pub fn owned(&self, t: &StripTri) -> Owned<'_> {
        let (a, b) = (t.start as usize, t.end as usize);
        Owned { len: b - a, index: &self.index[a..b + LIST_PAD], l1: &self.l1[a..b + LIST_PAD], l2: &self.l2[a..b + LIST_PAD] }
    }

    /// Empties the strip for rows `y0..y0 + rows` of `width` samples.
    fn reset(&mut self, y0: u32, rows: u32, width: u32) {
        (self.y0, self.rows, self.width) = (y0, rows, width);
        let n = (rows * width) as usize;
        // Only the depth is reset: it is the coverage, and the rest is read only where it is > 0.
        // The lane walk reads and writes back up to three samples past a row's box.
        self.depth.clear();
        self.depth.resize(n + DEPTH_PAD, 0.0);
        self.tris.clear();
        self.clipped.clear();
        self.listed = 0;
    }

    /// Makes room for `n` more entries in the owned-sample list (and its padding).
    fn reserve(&mut self, n: usize) {
        let room = self.listed + n + LIST_PAD;
        if self.index.len() < room {
            let len = room.max(2 * self.index.len());
            self.index.resize(len, 0);
            self.l1.resize(len, 0.0);
            self.l2.resize(len, 0.0);
        }
    }

    /// Ends the owned-sample list with the padding entries bundles read past the end.
    fn pad(&mut self) {
        self.reserve(0);
        let pad = self.listed..self.listed + LIST_PAD;
        self.index[pad.clone()].fill(0);
        self.l1[pad.clone()].fill(0.0);
        self.l2[pad].fill(0.0);
    }

    /// Drops the entries of samples a later, nearer triangle took (overdraw), keeping each
    /// triangle's entries contiguous and in order. An entry is its sample's owner when its
    /// depth, recomputed with the walk's formula (so the same bits), is the sample's depth:
    /// a triangle takes a sample only with a strictly nearer depth, so earlier owners' are
    /// smaller.
    fn drop_overwritten(&mut self) {
        let mut kept = 0usize;
        for t in self.tris.iter_mut() {
            let start = kept;
            for e in t.start as usize..t.end as usize {
                if depth_at(&t.z, self.l1[e], self.l2[e]) == self.depth[self.index[e] as usize] {
                    (self.index[kept], self.l1[kept], self.l2[kept]) = (self.index[e], self.l1[e], self.l2[e]);
                    kept += 1;
                }
            }
            (t.start, t.end) = (start as u32, kept as u32);
        }
        self.listed = kept;
    }

    /// Loads a strip of a whole-image visibility buffer (`samples`: its rows, row-major),
    /// grouping samples by original triangle, with [`BaryMap::Resolved`] barycentrics.
    pub fn load(&mut self, samples: &[VisSample], y0: u32, width: u32) {
        self.reset(y0, samples.len() as u32 / width, width);
        // Covered samples ordered by triangle (a stable sort keeps row order within one).
        let mut order: Vec<u32> = (0..samples.len() as u32).filter(|&i| samples[i as usize].tri != NO_TRIANGLE).collect();
        order.sort_by_key(|&i| samples[i as usize].tri);
        self.reserve(order.len());
        for (e, &i) in order.iter().enumerate() {
            let s = &samples[i as usize];
            if self.tris.last().is_none_or(|t| t.orig != s.tri) {
                let tri = StripTri { z: [0.0; 3], q: [1.0; 3], orig: s.tri, map: BaryMap::Resolved, start: e as u32, end: e as u32 };
                self.tris.push(tri);
            }
            self.tris.last_mut().expect("pushed above").end = e as u32 + 1;
            (self.index[e], self.l1[e], self.l2[e]) = (i, s.b1, s.b2);
            self.depth[i as usize] = s.depth;
        }
        self.listed = order.len();
        self.pad();
    }

    /// Writes the strip in the whole-image form ([`VisSample`] per sample, row-major): original
    /// triangle, perspective-correct barycentrics (resolved one sample at a time) and depth.
    fn write_resolved(&self, out: &mut [VisSample]) {
        out.fill(VisSample::EMPTY);
        for t in &self.tris {
            let o = self.owned(t);
            for k in 0..o.len {
                let (b1, b2) = t.resolve::<f32>(&self.clipped, o.l1[k], o.l2[k]);
                let i = o.index[k] as usize;
                out[i] = VisSample { tri: t.orig, b1, b2, depth: self.depth[i] };
            }
        }
    }
}

impl Setup {
    /// Number of strips.
    pub fn strip_count(&self) -> usize {
        self.strips
    }

    /// Rows per strip (the last strip may be shorter).
    pub fn strip_rows(&self) -> u32 {
        self.strip_rows
    }

    /// Rasterizes strip `s` into `out` (resized as needed) and returns its stats.
    pub fn rasterize_strip(&self, s: usize, out: &mut StripVis) -> RasterStats {
        let y0 = s as u32 * self.strip_rows;
        out.reset(y0, self.strip_rows.min(self.height - y0), self.width);
        let mut stats = RasterStats::default();
        for chunk in &self.chunks {
            for &ti in chunk.bin(s) {
                let t = &chunk.tris[ti as usize];
                let start = out.listed as u32;
                stats.samples_rasterized += walk(t, out);
                let end = out.listed as u32;
                if end > start {
                    let map = match (t.clipped, t.swapped) {
                        (UNCLIPPED, false) => BaryMap::Same,
                        (UNCLIPPED, true) => BaryMap::Swapped,
                        (i, _) => {
                            out.clipped.push(chunk.clipped[i as usize]);
                            BaryMap::Clipped(out.clipped.len() as u32 - 1)
                        }
                    };
                    out.tris.push(StripTri { z: t.z, q: t.q, orig: t.orig, map, start, end });
                }
            }
        }
        // More entries than covered samples: a nearer triangle took some (overdraw). Counting
        // the covered samples once per strip (a vectorized pass) instead of an overwrite
        // test per passing sample: sphere 0.610e9 → 0.599e9 instructions, dense 2.684e9 →
        // 2.665e9 (callgrind, three frames).
        if out.listed > out.depth().iter().filter(|&&d| d > 0.0).count() {
            out.drop_overwritten();
        }
        out.pad();
        stats
    }
}

/// Edge walk of one triangle over its bounding box clipped to the strip: each covered
/// sample nearer than what the strip holds takes the triangle's depth and a new entry in
/// the owned-sample list (its screen-space barycentrics). Returns the covered samples.
///
/// Triangles whose edge values fit i32 over their box (small ones: every triangle of the
/// `sphere` bench) are walked four samples at a time ([`walk_lanes`]); the others here.
///
/// Before, the walk resolved at the depth test: a `divss` on the path of every passing
/// sample (perf: a quarter of the walk's time stalled on it) and 16-byte samples cleared
/// per strip. Now it lists the screen-space barycentrics and the depth is the only per-sample
/// word cleared; the measurements are in the module docs of `render/pipeline.rs`.
fn walk(t: &SetupTri, out: &mut StripVis) -> u64 {
    let (sy0, sy1) = (out.y0 as i32, (out.y0 + out.rows) as i32 - 1);
    let (bx0, by0, bx1, by1) = (t.bbox[0], t.bbox[1].max(sy0), t.bbox[2], t.bbox[3].min(sy1));
    let (tx, ty) = (t.x.map(|v| v as i64), t.y.map(|v| v as i64));
    // Edge i is opposite vertex i: from vertex i+1 to vertex i+2.
    // E(p) = (b.x − a.x)(p.y − a.y) − (b.y − a.y)(p.x − a.x), positive inside.
    let mut e_row = [0i64; 3];
    let mut step_x = [0i64; 3];
    let mut step_y = [0i64; 3];
    let mut bias = [0i64; 3];
    let (px, py) = (bx0 as i64 * ONE + HALF, by0 as i64 * ONE + HALF);
    for i in 0..3 {
        let (a, b) = ((i + 1) % 3, (i + 2) % 3);
        let (dx, dy) = (tx[b] - tx[a], ty[b] - ty[a]);
        e_row[i] = dx * (py - ty[a]) - dy * (px - tx[a]);
        step_x[i] = -dy * ONE;
        step_y[i] = dx * ONE;
        // Top-left rule: a sample exactly on an edge belongs to the triangle only if the
        // edge is a top edge (horizontal, interior below) or a left edge (going up).
        let top_left = dy < 0 || (dy == 0 && dx > 0);
        bias[i] = if top_left { 0 } else { -1 };
    }
    // The owned-sample list grows by at most the box's samples: room made once, written by index.
    out.reserve(((bx1 - bx0 + 1).max(0) * (by1 - by0 + 1).max(0)) as usize);
    if by0 > by1 || bx0 > bx1 {
        return 0;
    }
    // Edge values at the corners of the box (widened by the lanes past its right end) bound
    // every value the walk computes (each is linear in x and y): within ±2^30, i32 lanes hold
    // them exactly.
    let (wide_x, tall_y) = ((bx1 - bx0) as i64 + 2 * WALK_LANES as i64, (by1 - by0) as i64 + 1);
    let fits = (0..3).all(|i| {
        let corners = [0, step_x[i] * wide_x].map(|dx| [0, step_y[i] * tall_y].map(|dy| e_row[i] + dx + dy));
        corners.as_flattened().iter().all(|e| e.abs() < 1 << 30)
    });
    #[cfg(test)]
    let fits = fits && !tests::ONE_SAMPLE_WALK.with(|f| f.get());
    if fits {
        return walk_lanes(
            t,
            out,
            [bx0, by0, bx1, by1],
            e_row.map(|e| e as i32),
            step_x.map(|s| s as i32),
            step_y.map(|s| s as i32),
            bias.map(|b| b as i32),
        );
    }
    // Inside when every biased edge function is ≥ 0 (one sign test for all three).
    let inside = |e: &[i64; 3]| (e[0] + bias[0]) | (e[1] + bias[1]) | (e[2] + bias[2]) >= 0;
    let mut n = out.listed;
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    for y in by0..=by1 {
        let mut e = e_row;
        let mut x = bx0;
        // Skip the samples left of the row's span.
        while x <= bx1 && !inside(&e) {
            for i in 0..3 {
                e[i] += step_x[i];
            }
            x += 1;
        }
        // The covered samples of a row are contiguous (each edge function is linear along the
        // row, so the inside set is an intersection of intervals): stop at the first sample
        // past the span instead of testing the rest of the box. Measured (one thread, best
        // of 4 alternating runs, image): sphere 23.4 → 22.1 ms, sphere-gouraud 15.2 → 13.8 ms.
        let row = ((y - sy0) as u32 * out.width) as usize;
        while x <= bx1 && inside(&e) {
            covered += 1;
            // Screen-space barycentrics of vertices 1 and 2, and the depth they interpolate.
            let l1 = e[1] as f32 * t.inv_area;
            let l2 = e[2] as f32 * t.inv_area;
            let z = depth_at(&t.z, l1, l2);
            // Reversed z: larger is nearer. The nearer sample becomes this triangle's.
            let i = row + x as usize;
            let d = &mut depth[i];
            if z > *d {
                *d = z;
                (index[n], list_l1[n], list_l2[n]) = (i as u32, l1, l2);
                n += 1;
            }
            for i in 0..3 {
                e[i] += step_x[i];
            }
            x += 1;
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    out.listed = n;
    covered
}

/// Samples of a row the lane walk tests at once.
const WALK_LANES: usize = 4;

/// [`walk`] four samples of a row at a time, for a triangle whose edge values fit i32 over its
/// box (`e_row`, `step_x`, `step_y` and `bias` as [`walk`] computes them, at the box's first
/// sample): the same samples, depths, barycentrics and entries in the same order. Each lane
/// computes what the one-sample walk computes for its sample (an i32 edge value converts to
/// the f32 an i64 one does: the same integer, rounded once), and lanes past the box are
/// masked off (their depths loaded and stored back unchanged).
#[allow(clippy::too_many_arguments)]
fn walk_lanes(
    t: &SetupTri,
    out: &mut StripVis,
    [bx0, by0, bx1, by1]: [i32; 4],
    e_row: [i32; 3],
    step_x: [i32; 3],
    step_y: [i32; 3],
    bias: [i32; 3],
) -> u64 {
    use wide::{f32x4, i32x4};
    let lane = |s: i32| i32x4::new([0, s, 2 * s, 3 * s]);
    let (off, step4) = (step_x.map(lane), step_x.map(|s| i32x4::splat(WALK_LANES as i32 * s)));
    let bias = bias.map(i32x4::splat);
    let inv_area = f32x4::splat(t.inv_area);
    let (z0, dz1, dz2) = (f32x4::splat(t.z[0]), f32x4::splat(t.z[1] - t.z[0]), f32x4::splat(t.z[2] - t.z[0]));
    let sample = i32x4::new([0, 1, 2, 3]);
    let mut n = out.listed;
    let width = out.width as usize;
    let sy0 = out.y0 as i32;
    let depth = &mut out.depth[..];
    let (index, list_l1, list_l2) = (&mut out.index[..], &mut out.l1[..], &mut out.l2[..]);
    let mut covered = 0u64;
    let mut e_row = e_row;
    for y in by0..=by1 {
        let mut e = [0, 1, 2].map(|i| i32x4::splat(e_row[i]) + off[i]);
        let row = (y - sy0) as usize * width;
        let (mut x, mut aligned) = (bx0, false);
        while x <= bx1 {
            // Lanes inside every edge (biased edge values ≥ 0: no sign bit) and inside the box.
            let outside = ((e[0] + bias[0]) | (e[1] + bias[1]) | (e[2] + bias[2])).to_bitmask();
            let in_box = 0b1111 >> (3 - (bx1 - x).min(3));
            let inside = !outside & in_box;
            if !aligned {
                if inside != 0 {
                    // The row's span starts at lane k: start the lanes there, so that its
                    // bundles are full but for the last and each one's inside lanes come first.
                    let k = inside.trailing_zeros() as i32;
                    aligned = true;
                    for i in 0..3 {
                        e[i] += i32x4::splat(k * step_x[i]);
                    }
                    x += k;
                    continue;
                }
            } else {
                // The covered samples of a row are contiguous from the span's start (lane 0 of
                // the first aligned bundle): the inside lanes are the first `m`.
                let m = (!inside).trailing_zeros() as usize;
                if m == 0 {
                    break;
                }
                covered += m as u64;
                // Screen-space barycentrics of vertices 1 and 2 and their depth, as `depth_at`.
                let l1 = e[1].round_float() * inv_area;
                let l2 = e[2].round_float() * inv_area;
                let z = z0 + l1 * dz1 + l2 * dz2;
                let i = row + x as usize;
                let d = f32x4::new(depth[i..i + WALK_LANES].try_into().expect("four samples"));
                // Reversed z: the nearer samples become this triangle's.
                let nearer = inside & z.simd_gt(d).to_bitmask();
                if nearer != 0 {
                    let keep: f32x4 = wide::bytemuck::cast(lane_mask(nearer));
                    depth[i..i + WALK_LANES].copy_from_slice(&keep.bitselect(z, d).to_array());
                    let entries = (i32x4::splat(i as i32) + sample).to_array().map(|v| v as u32);
                    let (l1, l2) = (l1.to_array(), l2.to_array());
                    if nearer & (nearer + 1) == 0 {
                        // The first lanes (no overdraw): all four written, the nearer ones kept.
                        index[n..n + WALK_LANES].copy_from_slice(&entries);
                        list_l1[n..n + WALK_LANES].copy_from_slice(&l1);
                        list_l2[n..n + WALK_LANES].copy_from_slice(&l2);
                        n += (!nearer).trailing_zeros() as usize;
                    } else {
                        for k in 0..WALK_LANES {
                            (index[n], list_l1[n], list_l2[n]) = (entries[k], l1[k], l2[k]);
                            n += (nearer >> k) as usize & 1;
                        }
                    }
                }
                if m < WALK_LANES {
                    break;
                }
            }
            for i in 0..3 {
                e[i] += step4[i];
            }
            x += WALK_LANES as i32;
        }
        for i in 0..3 {
            e_row[i] += step_y[i];
        }
    }
    out.listed = n;
    covered
}

/// Lanes of a four-bit set as an i32 mask (lane k all ones where bit k is set).
#[inline(always)]
fn lane_mask(bits: u32) -> wide::i32x4 {
    let bit = wide::i32x4::new([1, 2, 4, 8]);
    (wide::i32x4::splat(bits as i32) & bit).simd_eq(bit)
}

/// Reversed depth z/w at screen-space barycentrics (l1, l2) of a set-up triangle with vertex
/// depths `z`: the walk's depth test, and the owner test after overdraw (the same bits).
#[inline(always)]
fn depth_at(z: &[f32; 3], l1: f32, l2: f32) -> f32 {
    z[0] + l1 * (z[1] - z[0]) + l2 * (z[2] - z[0])
}

/// A whole-image visibility buffer (for tests and tools; the renderer works strip by strip).
#[derive(Debug, Clone)]
pub struct VisBuffer {
    /// Samples per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Row-major samples.
    pub samples: Vec<VisSample>,
    /// Counts.
    pub stats: RasterStats,
}

/// Rasterizes everything into one visibility buffer.
pub fn rasterize(clip: &[Vec4], triangles: &[[u32; 3]], width: u32, height: u32, cull: CullMode) -> VisBuffer {
    let setup = setup(clip, triangles, width, height, 16, cull);
    let rows = setup.strip_rows as usize * width as usize;
    let mut samples = vec![VisSample::EMPTY; width as usize * height as usize];
    let stats: Vec<RasterStats> = samples
        .par_chunks_mut(rows)
        .enumerate()
        .map_init(StripVis::default, |strip, (s, chunk)| {
            let st = setup.rasterize_strip(s, strip);
            strip.write_resolved(chunk);
            st
        })
        .collect();
    let mut total = setup.stats;
    for s in stats {
        total += s;
    }
    VisBuffer { width, height, samples, stats: total }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Camera;
    use glam::{Vec2, Vec3};

    const W: u32 = 64;
    const H: u32 = 48;

    thread_local! {
        /// Set by a test: strips rasterized on this thread walk one sample at a time.
        pub(super) static ONE_SAMPLE_WALK: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    }

    /// Clip-space vertex (w = 1) for a sample-grid position.
    fn at(sx: f32, sy: f32) -> Vec4 {
        Vec4::new(2.0 * sx / W as f32 - 1.0, 1.0 - 2.0 * sy / H as f32, 0.5, 1.0)
    }

    fn covered(v: &[Vec4], tris: &[[u32; 3]]) -> Vec<bool> {
        rasterize(v, tris, W, H, CullMode::None).samples.iter().map(|s| s.tri != NO_TRIANGLE).collect()
    }

    /// Counts, per sample, how many triangles of a mesh cover it (each rasterized alone).
    fn cover_counts(v: &[Vec4], tris: &[[u32; 3]]) -> Vec<u32> {
        let mut counts = vec![0u32; (W * H) as usize];
        for t in tris {
            for (c, hit) in counts.iter_mut().zip(covered(v, &[*t])) {
                *c += hit as u32;
            }
        }
        counts
    }

    #[test]
    fn round_half_away_is_f32_round() {
        // Halves, their neighbours, and a sweep of bit patterns up to 2^30.
        let mut values =
            vec![0.0f32, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0.49999997, -0.49999997, 8_388_607.5, -8_388_607.5, 8_388_608.0];
        let mut bits = 0u32;
        while bits < ((1u32 << 30) as f32).to_bits() {
            let x = f32::from_bits(bits);
            values.extend([x, -x, x + 0.5, -(x + 0.5), x.next_up(), x.next_down()]);
            bits += 4099;
        }
        for x in values.into_iter().filter(|x| x.abs() < (1u32 << 30) as f32) {
            assert_eq!(round_half_away(x), x.round() as i32, "{x}");
        }
    }

    #[test]
    fn fan_covers_every_sample_exactly_once() {
        // A fan around a centre that sits exactly on a sample centre, with rim vertices on
        // sample centres and half-way points, so many edges pass exactly through samples.
        let centre = Vec2::new(32.5, 24.5);
        let mut v = vec![at(centre.x, centre.y)];
        let rim = [(12.5, 24.5), (16.0, 8.5), (32.5, 4.5), (50.5, 10.0), (56.5, 24.5), (48.5, 40.5), (32.5, 44.5), (14.5, 38.5)];
        for (x, y) in rim {
            v.push(at(x, y));
        }
        let n = rim.len() as u32;
        // Counter-clockwise on screen with y down is clockwise in NDC; winding does not matter with CullMode::None.
        let tris: Vec<[u32; 3]> = (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
        let counts = cover_counts(&v, &tris);
        assert!(counts.iter().all(|&c| c <= 1), "a sample is covered twice");
        // No holes: every sample strictly inside the (convex) rim polygon is covered.
        let inside = |p: Vec2| {
            (0..rim.len()).all(|i| {
                let a = Vec2::from(rim[i]);
                let b = Vec2::from(rim[(i + 1) % rim.len()]);
                (b - a).perp_dot(p - a) > 1e-3
            })
        };
        let mut interior = 0;
        for y in 0..H {
            for x in 0..W {
                let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                if inside(p) {
                    interior += 1;
                    assert_eq!(counts[(y * W + x) as usize], 1, "hole at {x},{y}");
                }
            }
        }
        assert!(interior > 500);
    }

    #[test]
    fn quad_split_along_its_diagonal_covers_each_sample_once() {
        // Corners on sample centres: the top and left edges are in, bottom and right out.
        let v = [at(4.5, 4.5), at(20.5, 4.5), at(20.5, 12.5), at(4.5, 12.5)];
        let counts = cover_counts(&v, &[[0, 1, 2], [0, 2, 3]]);
        assert!(counts.iter().all(|&c| c <= 1));
        let total: u32 = counts.iter().sum();
        // Top-left rule: columns 4..20 (16) × rows 4..12 (8).
        assert_eq!(total, 16 * 8);
        assert_eq!(counts[(4 * W + 4) as usize], 1, "top-left corner sample belongs to the quad");
        assert_eq!(counts[(12 * W + 4) as usize], 0, "bottom edge is excluded");
        assert_eq!(counts[(4 * W + 20) as usize], 0, "right edge is excluded");
    }

    fn camera() -> Camera {
        Camera {
            position: Vec3::new(0.0, 1.0, 2.0),
            look_at: Vec3::new(0.0, 0.0, -3.0),
            up: Vec3::Y,
            fov_y_deg: 60.0,
            width: W,
            height: H,
            near: 0.1,
            background: Vec3::ZERO,
        }
    }

    /// The world point a sample sees on the plane y = 0 (ray cast from the camera).
    fn ray_plane(cam: &Camera, x: u32, y: u32) -> Option<Vec3> {
        let ndc = Vec4::new(2.0 * (x as f32 + 0.5) / W as f32 - 1.0, 1.0 - 2.0 * (y as f32 + 0.5) / H as f32, 0.5, 1.0);
        let inv = cam.view_projection().inverse();
        let p = inv * ndc;
        let dir = (p.truncate() / p.w - cam.position).normalize();
        let t = -cam.position.y / dir.y;
        (t > 0.0).then(|| cam.position + t * dir)
    }

    #[test]
    fn interpolation_is_perspective_correct_on_a_tilted_plane() {
        // A floor quad receding from the camera: screen-space (affine) interpolation would be
        // off by many units here; perspective-correct barycentrics hit the ray/plane point.
        let cam = camera();
        let world = [Vec3::new(-3.0, 0.0, 1.0), Vec3::new(3.0, 0.0, 1.0), Vec3::new(3.0, 0.0, -20.0), Vec3::new(-3.0, 0.0, -20.0)];
        let vp = cam.view_projection();
        let clip: Vec<Vec4> = world.iter().map(|p| vp * p.extend(1.0)).collect();
        let tris = [[0u32, 1, 2], [0, 2, 3]];
        let vis = rasterize(&clip, &tris, W, H, CullMode::None);
        let mut checked = 0;
        for y in 0..H {
            for x in 0..W {
                let s = vis.samples[(y * W + x) as usize];
                if s.tri == NO_TRIANGLE {
                    continue;
                }
                let t = tris[s.tri as usize];
                let b = s.bary();
                let p = world[t[0] as usize] * b.x + world[t[1] as usize] * b.y + world[t[2] as usize] * b.z;
                let exact = ray_plane(&cam, x, y).expect("a covered sample sees the floor");
                assert!((p - exact).length() < 1e-3 * (1.0 + (exact - cam.position).length()), "sample {x},{y}: {p} vs {exact}");
                checked += 1;
            }
        }
        assert!(checked > 500, "{checked}");
    }

    #[test]
    fn triangles_crossing_the_near_plane_are_clipped_not_lost() {
        // A floor that passes under and behind the camera: everything below the horizon is floor.
        let cam = Camera { look_at: Vec3::new(0.0, 1.0, -3.0), ..camera() };
        let world = [Vec3::new(-50.0, 0.0, 50.0), Vec3::new(50.0, 0.0, 50.0), Vec3::new(50.0, 0.0, -50.0), Vec3::new(-50.0, 0.0, -50.0)];
        let vp = cam.view_projection();
        let clip: Vec<Vec4> = world.iter().map(|p| vp * p.extend(1.0)).collect();
        let tris = [[0u32, 1, 2], [0, 2, 3]];
        let vis = rasterize(&clip, &tris, W, H, CullMode::None);
        assert!(vis.stats.triangles_clipped >= 1);
        for y in 0..H {
            for x in 0..W {
                let hit = vis.samples[(y * W + x) as usize].tri != NO_TRIANGLE;
                // The camera looks level, so the horizon is the middle row; allow the far edge.
                let sees_floor = ray_plane(&cam, x, y).is_some_and(|p| p.x.abs() < 50.0 && p.z.abs() < 50.0);
                if y > H / 2 {
                    assert!(sees_floor && hit, "row {y} col {x} should be floor");
                }
                if y < H / 2 {
                    assert!(!hit, "row {y} col {x} is above the horizon");
                }
            }
        }
        // And every covered sample's interpolated position is in front of the camera.
        for s in vis.samples.iter().filter(|s| s.tri != NO_TRIANGLE) {
            let t = tris[s.tri as usize];
            let b = s.bary();
            let p = world[t[0] as usize] * b.x + world[t[1] as usize] * b.y + world[t[2] as usize] * b.z;
            assert!((cam.view() * p.extend(1.0)).z < -0.09);
        }
    }

    #[test]
    fn back_faces_are_culled_only_when_asked() {
        // Counter-clockwise in NDC (x right, y up) is front-facing.
        let ccw = [Vec4::new(-0.5, -0.5, 0.5, 1.0), Vec4::new(0.5, -0.5, 0.5, 1.0), Vec4::new(0.0, 0.5, 0.5, 1.0)];
        let front = rasterize(&ccw, &[[0, 1, 2]], W, H, CullMode::Back);
        let back = rasterize(&ccw, &[[0, 2, 1]], W, H, CullMode::Back);
        let both = rasterize(&ccw, &[[0, 2, 1]], W, H, CullMode::None);
        let count = |v: &VisBuffer| v.samples.iter().filter(|s| s.tri != NO_TRIANGLE).count();
        assert!(count(&front) > 100);
        assert_eq!(count(&back), 0);
        assert_eq!(back.stats.triangles_culled, 1);
        assert_eq!(count(&both), count(&front));
    }

    #[test]
    fn nearer_triangle_wins_regardless_of_order() {
        let near = [Vec4::new(-1.0, -1.0, 0.5, 1.0), Vec4::new(1.0, -1.0, 0.5, 1.0), Vec4::new(0.0, 1.0, 0.5, 1.0)];
        let far = near.map(|v| Vec4::new(v.x, v.y, 0.2, 1.0));
        let v: Vec<Vec4> = near.iter().chain(far.iter()).copied().collect();
        for tris in [[[0u32, 1, 2], [3, 4, 5]], [[3, 4, 5], [0, 1, 2]]] {
            let vis = rasterize(&v, &tris, W, H, CullMode::Back);
            let centre = vis.samples[(H / 2 * W + W / 2) as usize];
            assert_eq!(tris[centre.tri as usize], [0, 1, 2]);
            assert!((centre.depth - 0.5).abs() < 1e-6);
        }
    }

    #[test]
    fn degenerate_and_non_finite_triangles_are_counted_and_skipped() {
        let v = [
            Vec4::new(0.0, 0.0, 0.5, 1.0),
            Vec4::new(0.5, 0.5, 0.5, 1.0),
            Vec4::new(1.0, 1.0, 0.5, 1.0),
            Vec4::new(f32::NAN, 0.0, 0.5, 1.0),
        ];
        let vis = rasterize(&v, &[[0, 1, 2], [0, 1, 3]], W, H, CullMode::None);
        assert_eq!(vis.stats.triangles_degenerate, 2);
        assert!(vis.samples.iter().all(|s| s.tri == NO_TRIANGLE));
    }

    #[test]
    fn four_lane_walk_gives_the_one_sample_walk() {
        // A fine sphere (small triangles: the lane walk) with its back faces (overdraw) over a
        // large floor quad (edge values past i32: the one-sample walk either way).
        let cam = camera();
        let mesh = crate::scene::shapes::uv_sphere(40, 20);
        let vp = cam.view_projection() * glam::Mat4::from_translation(Vec3::new(0.0, 0.5, -2.0));
        let mut clip: Vec<Vec4> = mesh.positions.iter().map(|p| vp * p.extend(1.0)).collect();
        let mut tris = mesh.triangles.clone();
        let floor = [Vec3::new(-9.0, 0.0, 1.0), Vec3::new(9.0, 0.0, 1.0), Vec3::new(9.0, 0.0, -30.0), Vec3::new(-9.0, 0.0, -30.0)];
        let base = clip.len() as u32;
        clip.extend(floor.iter().map(|p| cam.view_projection() * p.extend(1.0)));
        tris.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        let (w, h) = (W * 3, H * 3);
        let run = |one_sample: bool| {
            ONE_SAMPLE_WALK.with(|f| f.set(one_sample));
            let setup = setup(&clip, &tris, w, h, 16, CullMode::None);
            let mut samples = vec![VisSample::EMPTY; (w * h) as usize];
            let (mut strip, mut stats) = (StripVis::default(), setup.stats);
            for (s, chunk) in samples.chunks_mut(16 * w as usize).enumerate() {
                stats += setup.rasterize_strip(s, &mut strip);
                strip.write_resolved(chunk);
            }
            ONE_SAMPLE_WALK.with(|f| f.set(false));
            let bits: Vec<[u32; 4]> = samples.iter().map(|s| [s.tri, s.b1.to_bits(), s.b2.to_bits(), s.depth.to_bits()]).collect();
            (bits, stats)
        };
        let (lanes, one) = (run(false), run(true));
        assert!(lanes.1.samples_rasterized > lanes.0.iter().filter(|s| s[0] != NO_TRIANGLE).count() as u64, "overdraw");
        assert_eq!(lanes, one);
    }

    #[test]
    fn same_bytes_for_one_thread_and_many() {
        let cam = camera();
        let mesh = crate::scene::shapes::uv_sphere(24, 12);
        let vp = cam.view_projection() * glam::Mat4::from_translation(Vec3::new(0.0, 0.5, -2.0));
        let clip: Vec<Vec4> = mesh.positions.iter().map(|p| vp * p.extend(1.0)).collect();
        let run = |threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| rasterize(&clip, &mesh.triangles, W * 3, H * 3, CullMode::Back))
        };
        let (a, b) = (run(1), run(4));
        assert_eq!(a.stats, b.stats);
        assert!(
            a.samples
                .iter()
                .zip(&b.samples)
                .all(|(x, y)| x.tri == y.tri && x.b1.to_bits() == y.b1.to_bits() && x.b2.to_bits() == y.b2.to_bits())
        );
    }
}
