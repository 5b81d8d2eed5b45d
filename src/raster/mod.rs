//! Triangles → covered samples. No graphics library, and no knowledge of light.
//!
//! Stages, each a short function:
//! 1. **setup**: clip-space triangles are clipped ([`clip`]), projected to the sample
//!    grid, snapped to fixed point (1/256 sample), culled by facing and binned into
//!    horizontal strips of rows;
//! 2. **strip raster**: for each triangle of a strip, walk its bounding box with
//!    integer edge functions (Pineda 1988) and the top-left fill rule, keeping the
//!    nearest sample (reversed depth: larger z/w is nearer);
//! 3. **resolve**: screen-space barycentrics become perspective-correct barycentrics of
//!    the *original* triangle (Heckbert & Moreton 1991), written to a visibility buffer.
//!
//! Strips are independent, so they run in parallel (rayon) with identical results for
//! any thread count; each strip processes its triangles in submission order.

pub mod clip;

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

/// A triangle ready for the edge walk (after clipping, snapping and orientation).
#[derive(Debug, Clone, Copy)]
struct SetupTri {
    /// Fixed-point sample coordinates, wound so that the signed area is positive.
    x: [i64; 3],
    y: [i64; 3],
    /// Reversed depth z/w and 1/w per vertex.
    z: [f32; 3],
    q: [f32; 3],
    /// For clipped pieces, each vertex's barycentrics in the original triangle.
    bary: Option<[Vec3; 3]>,
    /// Vertices 1 and 2 were swapped to make the area positive (unclipped triangles only).
    swapped: bool,
    /// Index of the original triangle.
    orig: u32,
    /// Inclusive sample bounding box: x0, y0, x1, y1.
    bbox: [i32; 4],
    /// Twice the signed area in fixed point (> 0).
    area2: i64,
}

/// Triangles set up and binned into strips: the input of [`Setup::rasterize_strip`].
pub struct Setup {
    tris: Vec<SetupTri>,
    bins: Vec<Vec<u32>>,
    width: u32,
    height: u32,
    strip_rows: u32,
    /// Counts from setup (samples_rasterized is added by the strips).
    pub stats: RasterStats,
}

/// Sets up `triangles` (indices into `clip`, clip-space positions) for a `width` × `height`
/// sample grid, binned into strips of `strip_rows` rows.
///
/// Preconditions: `width`, `height`, `strip_rows` ≥ 1; indices are in range.
pub fn setup(clip: &[Vec4], triangles: &[[u32; 3]], width: u32, height: u32, strip_rows: u32, cull: CullMode) -> Setup {
    let g = GUARD_SAMPLES / width.max(height) as f32;
    // Parallel setup in fixed-size chunks; concatenating in chunk order keeps submission order.
    let chunks: Vec<(Vec<SetupTri>, RasterStats)> = triangles
        .par_chunks(4096)
        .enumerate()
        .map(|(c, chunk)| {
            let mut out = Vec::with_capacity(chunk.len());
            let mut stats = RasterStats::default();
            for (i, t) in chunk.iter().enumerate() {
                let id = (c * 4096 + i) as u32;
                let v = [clip[t[0] as usize], clip[t[1] as usize], clip[t[2] as usize]];
                setup_triangle(v, id, width, height, g, cull, &mut out, &mut stats);
            }
            (out, stats)
        })
        .collect();
    let mut stats = RasterStats { triangles_in: triangles.len() as u64, ..Default::default() };
    let mut tris = Vec::with_capacity(triangles.len());
    for (chunk, s) in chunks {
        tris.extend(chunk);
        stats += s;
    }
    let strips = height.div_ceil(strip_rows) as usize;
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); strips];
    for (i, t) in tris.iter().enumerate() {
        for s in (t.bbox[1] as u32 / strip_rows)..=(t.bbox[3] as u32 / strip_rows) {
            bins[s as usize].push(i as u32);
        }
    }
    Setup { tris, bins, width, height, strip_rows, stats }
}

#[allow(clippy::too_many_arguments)]
fn setup_triangle(
    v: [Vec4; 3],
    id: u32,
    width: u32,
    height: u32,
    g: f32,
    cull: CullMode,
    out: &mut Vec<SetupTri>,
    stats: &mut RasterStats,
) {
    if !v.iter().all(|p| p.is_finite()) {
        stats.triangles_degenerate += 1;
        return;
    }
    let inside = v.iter().all(|p| clip::distances(*p, g).iter().all(|d| *d >= 0.0));
    if inside {
        project(v, None, id, width, height, cull, out, stats);
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
        project([a.pos, b.pos, c.pos], Some([a.bary, b.bary, c.bary]), id, width, height, cull, out, stats);
    }
}

#[allow(clippy::too_many_arguments)]
fn project(
    v: [Vec4; 3],
    bary: Option<[Vec3; 3]>,
    id: u32,
    width: u32,
    height: u32,
    cull: CullMode,
    out: &mut Vec<SetupTri>,
    stats: &mut RasterStats,
) {
    let mut x = [0i64; 3];
    let mut y = [0i64; 3];
    let mut z = [0f32; 3];
    let mut q = [0f32; 3];
    for i in 0..3 {
        q[i] = 1.0 / v[i].w;
        // NDC → sample grid: x right, y down (row 0 at the top).
        let sx = (v[i].x * q[i] + 1.0) * 0.5 * width as f32;
        let sy = (1.0 - v[i].y * q[i]) * 0.5 * height as f32;
        x[i] = (sx * ONE as f32).round() as i64;
        y[i] = (sy * ONE as f32).round() as i64;
        z[i] = v[i].z * q[i];
    }
    // Twice the signed area; with y down, counter-clockwise in NDC (front) is negative.
    let area2 = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
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
    // Samples sit at centres (s + 0.5); the box holds samples whose centre may be inside.
    let first = |lo: i64| ((lo - HALF) as f64 / ONE as f64).ceil() as i64;
    let last = |hi: i64| ((hi - HALF) as f64 / ONE as f64).floor() as i64;
    let x0 = first(*x.iter().min().unwrap()).max(0);
    let y0 = first(*y.iter().min().unwrap()).max(0);
    let x1 = last(*x.iter().max().unwrap()).min(width as i64 - 1);
    let y1 = last(*y.iter().max().unwrap()).min(height as i64 - 1);
    if x0 > x1 || y0 > y1 {
        stats.triangles_outside += 1;
        return;
    }
    out.push(SetupTri {
        x,
        y,
        z,
        q,
        bary,
        orig: id,
        bbox: [x0 as i32, y0 as i32, x1 as i32, y1 as i32],
        area2,
        swapped: swapped && bary.is_none(),
    });
}

/// The visibility samples of one strip of rows, reused across strips.
#[derive(Debug, Clone, Default)]
pub struct StripVis {
    /// First sample row of the strip.
    pub y0: u32,
    /// Rows in the strip.
    pub rows: u32,
    /// Samples per row.
    pub width: u32,
    /// `rows × width` samples, row-major.
    pub samples: Vec<VisSample>,
}

impl Setup {
    /// Number of strips.
    pub fn strip_count(&self) -> usize {
        self.bins.len()
    }

    /// Rows per strip (the last strip may be shorter).
    pub fn strip_rows(&self) -> u32 {
        self.strip_rows
    }

    /// Rasterizes strip `s` into `out` (resized as needed) and returns its stats.
    pub fn rasterize_strip(&self, s: usize, out: &mut StripVis) -> RasterStats {
        let y0 = s as u32 * self.strip_rows;
        let rows = self.strip_rows.min(self.height - y0);
        out.y0 = y0;
        out.rows = rows;
        out.width = self.width;
        out.samples.clear();
        out.samples.resize((rows * self.width) as usize, VisSample::EMPTY);
        let mut stats = RasterStats::default();
        for &ti in &self.bins[s] {
            stats.samples_rasterized += self.walk(&self.tris[ti as usize], ti, out);
        }
        self.resolve(out);
        stats
    }

    /// Edge walk of one triangle over its bounding box clipped to the strip.
    /// Stores the setup index and screen-space barycentrics; returns covered samples.
    fn walk(&self, t: &SetupTri, ti: u32, out: &mut StripVis) -> u64 {
        let (sy0, sy1) = (out.y0 as i32, (out.y0 + out.rows) as i32 - 1);
        let (bx0, by0, bx1, by1) = (t.bbox[0], t.bbox[1].max(sy0), t.bbox[2], t.bbox[3].min(sy1));
        // Edge i is opposite vertex i: from vertex i+1 to vertex i+2.
        // E(p) = (b.x − a.x)(p.y − a.y) − (b.y − a.y)(p.x − a.x), positive inside.
        let mut e_row = [0i64; 3];
        let mut step_x = [0i64; 3];
        let mut step_y = [0i64; 3];
        let mut bias = [0i64; 3];
        let (px, py) = (bx0 as i64 * ONE + HALF, by0 as i64 * ONE + HALF);
        for i in 0..3 {
            let (a, b) = ((i + 1) % 3, (i + 2) % 3);
            let (dx, dy) = (t.x[b] - t.x[a], t.y[b] - t.y[a]);
            e_row[i] = dx * (py - t.y[a]) - dy * (px - t.x[a]);
            step_x[i] = -dy * ONE;
            step_y[i] = dx * ONE;
            // Top-left rule: a sample exactly on an edge belongs to the triangle only if the
            // edge is a top edge (horizontal, interior below) or a left edge (going up).
            let top_left = dy < 0 || (dy == 0 && dx > 0);
            bias[i] = if top_left { 0 } else { -1 };
        }
        let inv_area = 1.0 / t.area2 as f32;
        let mut covered = 0u64;
        for y in by0..=by1 {
            let mut e = e_row;
            let row = ((y - sy0) as u32 * out.width) as usize;
            for x in bx0..=bx1 {
                if (e[0] + bias[0]) | (e[1] + bias[1]) | (e[2] + bias[2]) >= 0 {
                    covered += 1;
                    let l1 = e[1] as f32 * inv_area;
                    let l2 = e[2] as f32 * inv_area;
                    let z = t.z[0] + l1 * (t.z[1] - t.z[0]) + l2 * (t.z[2] - t.z[0]);
                    let s = &mut out.samples[row + x as usize];
                    if z > s.depth {
                        *s = VisSample { tri: ti, b1: l1, b2: l2, depth: z };
                    }
                }
                for i in 0..3 {
                    e[i] += step_x[i];
                }
            }
            for i in 0..3 {
                e_row[i] += step_y[i];
            }
        }
        covered
    }

    /// Setup index + screen-space barycentrics → original triangle + perspective-correct barycentrics.
    fn resolve(&self, out: &mut StripVis) {
        for s in out.samples.iter_mut().filter(|s| s.tri != NO_TRIANGLE) {
            let t = &self.tris[s.tri as usize];
            let l = [1.0 - s.b1 - s.b2, s.b1, s.b2];
            // Attributes are linear in 1/w: b_i = λ_i q_i / Σ λ_j q_j.
            let w = Vec3::new(l[0] * t.q[0], l[1] * t.q[1], l[2] * t.q[2]);
            let b = w / (w.x + w.y + w.z);
            let b = match &t.bary {
                Some(m) => m[0] * b.x + m[1] * b.y + m[2] * b.z,
                None if t.swapped => Vec3::new(b.x, b.z, b.y),
                None => b,
            };
            s.tri = t.orig;
            s.b1 = b.y;
            s.b2 = b.z;
        }
    }
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
            chunk.copy_from_slice(&strip.samples);
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
