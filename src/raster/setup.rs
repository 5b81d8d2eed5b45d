//! Triangle setup: vertices projected to fixed point, triangles clipped, culled, oriented and
//! binned into strips, and each strip rasterized from its bins.

use super::edge::{SetupTri, UNCLIPPED};
#[cfg(test)]
use super::project::round_half_away;
use super::project::{Projected, project_one, project_vertex};
use super::strip::{BaryMap, StripTri, StripVis};
use super::tiles::{DEPTH_TILE, DepthLayout};
use super::walk::{WalkWidth, walk};
use super::walk_depth::walk_depth;
use super::{CullMode, HALF, ONE, RasterStats, SUBPIXEL_BITS, clip};
use glam::{Vec3, Vec4};
use rayon::prelude::*;

/// Screen coordinates stay within ±2^19 samples (guard band), so edge-function products fit in i64.
const GUARD_SAMPLES: f32 = (1 << 19) as f32;

/// Triangles per setup chunk (set up in parallel, concatenated in order); the output does
/// not depend on it (ids and bin order are the submission order). 1024 was tried (the
/// sphere's 16k triangles in 16 jobs instead of 4): alternating medians within 1.5% of
/// 4096 on `sphere` and `dense`, so it stays 4096.
const CHUNK: usize = 4096;

/// How many triangles ahead setup prefetches vertices, and strips set-up triangles.
const PREFETCH_AHEAD: usize = 8;

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
    setup_with(clip.len(), |i| clip[i], triangles, width, height, strip_rows, cull)
}

/// [`setup`] of `vertices` vertices whose clip-space positions `clip(i)` gives (a pure
/// function, called again for the triangles that take the clipping path): a renderer passes
/// its world positions and transform, and each vertex goes to clip space and onto the sample
/// grid in one pass. A stored clip-space copy was a pass of its own, writing 16 bytes a
/// vertex that setup then read back (8 MB for the `dense` bench's sphere).
#[allow(clippy::too_many_arguments)]
pub fn setup_with(
    vertices: usize,
    clip: impl Fn(usize) -> Vec4 + Sync,
    triangles: &[[u32; 3]],
    width: u32,
    height: u32,
    strip_rows: u32,
    cull: CullMode,
) -> Setup {
    let g = GUARD_SAMPLES / width.max(height) as f32;
    let strips = height.div_ceil(strip_rows) as usize;
    let projected = project_all(vertices, &clip, width, height, g);
    let chunks: Vec<(Chunk, RasterStats)> = triangles
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, chunk)| {
            let mut out = Chunk { tris: Vec::with_capacity(chunk.len()), clipped: Vec::new(), bin_start: Vec::new(), bins: Vec::new() };
            let mut stats = RasterStats::default();
            for (i, t) in chunk.iter().enumerate() {
                // A mesh's triangles reach their vertices in strides (a uv sphere's column
                // goes down the rings, a ring apart): fetch a later triangle's now.
                if let Some(ahead) = chunk.get(i + PREFETCH_AHEAD) {
                    for &v in ahead {
                        crate::simd::prefetch(projected.as_ptr().wrapping_add(v as usize));
                    }
                }
                let id = (c * CHUNK + i) as u32;
                let p = [projected[t[0] as usize], projected[t[1] as usize], projected[t[2] as usize]];
                if p.iter().all(|p| p.x != Projected::CLIP.x) {
                    assemble(p, None, id, width, height, cull, &mut out, &mut stats);
                } else {
                    let v = t.map(|i| clip(i as usize));
                    setup_triangle(v, id, width, height, g, cull, &mut out, &mut stats);
                }
            }
            out.bin_by_strip(strips, StripOf::new(strip_rows));
            (out, stats)
        })
        .collect();
    let mut stats = RasterStats { triangles_in: triangles.len() as u64, ..Default::default() };
    for (_, s) in &chunks {
        stats += *s;
    }
    Setup { chunks: chunks.into_iter().map(|(c, _)| c).collect(), width, height, strip_rows, strips, stats }
}

/// Vertices projected per job of [`project_all`].
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))] // only the x86 paths use it
const PROJECT_CHUNK: usize = 4096;

/// Each vertex on the sample grid, or [`Projected::CLIP`] when its triangles need the
/// clipping path ([`project_one`]): sixteen at a time with AVX-512F.
fn project_all(n: usize, clip: &(impl Fn(usize) -> Vec4 + Sync), width: u32, height: u32, g: f32) -> Vec<Projected> {
    #[cfg(target_arch = "x86_64")]
    if let Some(t) = crate::simd::Cpu::get().avx512() {
        let mut out = Vec::with_capacity(n);
        out.spare_capacity_mut()[..n].par_chunks_mut(PROJECT_CHUNK).enumerate().for_each(|(c, run)| {
            super::project_avx512::project_run(t, clip, c * PROJECT_CHUNK, run, (width, height, g));
        });
        // SAFETY: the jobs cover `..n` and `project_run` writes every element of its run; a
        // job that panicked unwinds through `for_each` before this line.
        unsafe { out.set_len(n) };
        return out;
    }
    (0..n).into_par_iter().map(|i| project_one(clip(i), width, height, g)).collect()
}

/// The strip of a sample row, `row / strip_rows`, by a multiplication: four divisions a
/// triangle were 6% of `dense`'s set-up time (perf).
#[derive(Debug, Clone, Copy)]
struct StripOf {
    /// ⌈2⁶⁴ / strip_rows⌉ (`u64::MAX / strip_rows + 1`), or 0 for one row a strip.
    magic: u64,
}

impl StripOf {
    /// Precondition: `strip_rows` ≥ 1.
    fn new(strip_rows: u32) -> StripOf {
        StripOf { magic: if strip_rows == 1 { 0 } else { u64::MAX / strip_rows as u64 + 1 } }
    }

    /// `row / strip_rows`, exact for every u32 row: with M = ⌈2⁶⁴/d⌉, ⌊M·n / 2⁶⁴⌋ = ⌊n/d⌋
    /// for all 32-bit n and 2 ≤ d < 2³² (Lemire, Kaser and Kurz 2019, "Faster remainder by
    /// direct computation", Theorem 1 with N = 32, F = 64).
    #[inline(always)]
    fn row(self, row: u32) -> usize {
        if self.magic == 0 { row as usize } else { ((self.magic as u128 * row as u128) >> 64) as usize }
    }
}

impl Chunk {
    /// Bins the chunk's triangles by strip (a counting sort: counts, offsets, fill).
    fn bin_by_strip(&mut self, strips: usize, strip_of: StripOf) {
        let span = |t: &SetupTri| strip_of.row(t.bbox[1] as u32)..=strip_of.row(t.bbox[3] as u32);
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

impl Setup {
    /// Number of strips.
    pub fn strip_count(&self) -> usize {
        self.strips
    }

    /// Rows per strip (the last strip may be shorter).
    pub fn strip_rows(&self) -> u32 {
        self.strip_rows
    }

    /// Depth only: rasterizes strip `s` into `depth` (its samples laid out as `layout` says,
    /// rows counted from the strip's first; reversed depth, 0 where uncovered) with the same
    /// coverage as [`Setup::rasterize_strip`], for the shadow-map pass. The strip's part of
    /// `depth` is cleared first. Precondition for [`DepthLayout::Tiles`]: the strip's rows are
    /// a multiple of [`DEPTH_TILE`] (but for the last strip) and `depth` holds its rows of tiles.
    pub fn depth_strip(&self, s: usize, layout: DepthLayout, depth: &mut [f32]) -> RasterStats {
        let y0 = s as u32 * self.strip_rows;
        let rows = self.strip_rows.min(self.height - y0);
        let len = match layout {
            DepthLayout::Rows { width } => rows as usize * width,
            DepthLayout::Tiles { tiles } => (rows as usize).div_ceil(DEPTH_TILE) * tiles * DEPTH_TILE * DEPTH_TILE,
        };
        let depth = &mut depth[..len];
        depth.fill(0.0);
        let mut stats = RasterStats::default();
        let width = WalkWidth::detect();
        for chunk in &self.chunks {
            for &ti in chunk.bin(s) {
                stats.samples_rasterized += walk_depth(&chunk.tris[ti as usize], y0, rows, layout, depth, width);
            }
        }
        stats
    }

    /// Rasterizes strip `s` into `out` (resized as needed) and returns its stats.
    pub fn rasterize_strip(&self, s: usize, out: &mut StripVis) -> RasterStats {
        let y0 = s as u32 * self.strip_rows;
        out.reset(y0, self.strip_rows.min(self.height - y0), self.width);
        let mut stats = RasterStats::default();
        let width = WalkWidth::detect();
        for chunk in &self.chunks {
            let bin = chunk.bin(s);
            for (k, &ti) in bin.iter().enumerate() {
                // A strip's triangles lie scattered over the chunk (a mesh's order crosses
                // every strip): fetch a later one now.
                if let Some(ahead) = bin.get(k + PREFETCH_AHEAD).and_then(|&a| chunk.tris.get(a as usize)) {
                    // 80 bytes: both ends, which may lie in two cache lines.
                    crate::simd::prefetch(ahead);
                    crate::simd::prefetch(&ahead.swapped);
                }
                let t = &chunk.tris[ti as usize];
                let start = out.listed as u32;
                stats.samples_rasterized += walk(t, out, width);
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
        // (A branch-free sum: `filter().count()` here was a branch per sample.)
        if out.listed > out.depth().iter().map(|&d| (d > 0.0) as u32).sum::<u32>() as usize {
            out.drop_overwritten();
        }
        out.pad();
        stats
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Camera;
    use crate::raster::tests::{H, W, camera, ray_plane};
    use crate::raster::{NO_TRIANGLE, VisBuffer, rasterize};

    #[test]
    fn strip_of_a_row_is_the_division() {
        // Every divisor a renderer uses (16 rows times 1..=16 samples a pixel, the shadow map's
        // strips) and others, at rows near each multiple and across the u32 range.
        for d in (1..=300u32).chain([1 << 16, 65_537, u32::MAX / 3, u32::MAX]) {
            let s = StripOf::new(d);
            let mut rows: Vec<u32> = (0..2000).collect();
            rows.extend(
                (1..=400u32).flat_map(|k| [k.wrapping_mul(d).wrapping_sub(1), k.wrapping_mul(d), k.wrapping_mul(d).wrapping_add(1)]),
            );
            rows.extend([u32::MAX, u32::MAX - 1, u32::MAX / d * d, (u32::MAX / d * d).wrapping_sub(1)]);
            let mut x = 0x9e37_79b9u32;
            for _ in 0..2000 {
                x ^= x << 13;
                x ^= x >> 17;
                x ^= x << 5;
                rows.push(x);
            }
            for r in rows {
                assert_eq!(s.row(r), (r / d) as usize, "{r} / {d}");
            }
        }
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
}
