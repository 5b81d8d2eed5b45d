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
//! The measurements behind these choices are in `docs/performance.md` (Rasterizer).

pub mod clip;
mod edge;
mod project;
#[cfg(target_arch = "x86_64")]
mod project_avx512;
mod setup;
mod strip;
mod tiles;
mod walk;
#[cfg(target_arch = "x86_64")]
mod walk_avx2;
#[cfg(target_arch = "x86_64")]
mod walk_avx512;
mod walk_depth;
#[cfg(target_arch = "x86_64")]
mod walk_depth_avx2;
#[cfg(target_arch = "x86_64")]
mod walk_depth_avx512;

pub use setup::{Setup, setup, setup_with};
pub use strip::{BaryMap, LIST_PAD, Owned, StripTri, StripVis};
pub use tiles::{DEPTH_TILE, DepthLayout, tiled};

use glam::{Vec3, Vec4};
use rayon::prelude::*;

/// Marks a sample that no triangle covers.
pub const NO_TRIANGLE: u32 = u32::MAX;
/// Fixed-point subsample precision: 8 bits (1/256 of a sample).
const SUBPIXEL_BITS: u32 = 8;
const ONE: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = ONE / 2;

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
    rasterize_in(clip, triangles, width, height, cull, false)
}

/// [`rasterize`], with screen-space (affine) barycentrics in the buffer when `screen_space`
/// ([`StripVis::interpolate_in_screen_space`]), else perspective-correct ones.
pub fn rasterize_in(clip: &[Vec4], triangles: &[[u32; 3]], width: u32, height: u32, cull: CullMode, screen_space: bool) -> VisBuffer {
    let setup = setup(clip, triangles, width, height, 16, cull);
    let rows = setup.strip_rows() as usize * width as usize;
    let mut samples = vec![VisSample::EMPTY; width as usize * height as usize];
    let stats: Vec<RasterStats> = samples
        .par_chunks_mut(rows)
        .enumerate()
        .map_init(StripVis::default, |strip, (s, chunk)| {
            let st = setup.rasterize_strip(s, strip);
            if screen_space {
                strip.interpolate_in_screen_space();
            }
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

/// The nearest triangle of each sample in rows `0..rows` (row-major, [`NO_TRIANGLE`] where
/// none covers it): [`rasterize`]'s `tri` there, without resolving barycentrics and without
/// rasterizing the strips below (a hemicube's side face reads its upper half only). The
/// strips run one after another in `strip` (scratch, reused): a caller runs many of these
/// in parallel.
pub fn nearest_triangles(
    clip: &[Vec4],
    triangles: &[[u32; 3]],
    width: u32,
    height: u32,
    rows: u32,
    cull: CullMode,
    strip: &mut StripVis,
) -> Vec<u32> {
    let setup = setup(clip, triangles, width, height, 16, cull);
    let rows = rows.min(height);
    let mut out = vec![NO_TRIANGLE; rows as usize * width as usize];
    for s in 0..rows.div_ceil(setup.strip_rows()) as usize {
        setup.rasterize_strip(s, strip);
        let first = s * (setup.strip_rows() * width) as usize;
        // The order `StripVis::write_resolved` writes in, so a sample gets the same triangle.
        for t in strip.tris() {
            let o = strip.owned(t);
            for &i in &o.index[..o.len] {
                if let Some(id) = out.get_mut(first + i as usize) {
                    *id = t.orig;
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Camera;

    /// A unit latitude-longitude sphere (`segments` around, `rings` pole to pole) as
    /// positions and counter-clockwise triangles: raster tests need triangles, not a scene.
    pub(super) struct TestMesh {
        pub(super) positions: Vec<Vec3>,
        pub(super) triangles: Vec<[u32; 3]>,
    }

    pub(super) fn uv_sphere(segments: u32, rings: u32) -> TestMesh {
        let mut positions = Vec::new();
        for r in 0..=rings {
            let theta = std::f32::consts::PI * r as f32 / rings as f32;
            for s in 0..=segments {
                let phi = std::f32::consts::TAU * s as f32 / segments as f32;
                positions.push(Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin()));
            }
        }
        let row = segments + 1;
        let mut triangles = Vec::new();
        for r in 0..rings {
            for s in 0..segments {
                let (a, b) = (r * row + s, (r + 1) * row + s);
                triangles.push([a, b, b + 1]);
                triangles.push([a, b + 1, a + 1]);
            }
        }
        TestMesh { positions, triangles }
    }

    // The grid, camera and floor ray are shared with the tests of `setup`, `strip` and `walk`.
    pub(super) const W: u32 = 64;
    pub(super) const H: u32 = 48;

    pub(super) fn camera() -> Camera {
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
    pub(super) fn ray_plane(cam: &Camera, x: u32, y: u32) -> Option<Vec3> {
        let ndc = Vec4::new(2.0 * (x as f32 + 0.5) / W as f32 - 1.0, 1.0 - 2.0 * (y as f32 + 0.5) / H as f32, 0.5, 1.0);
        let inv = cam.view_projection().inverse();
        let p = inv * ndc;
        let dir = (p.truncate() / p.w - cam.position).normalize();
        let t = -cam.position.y / dir.y;
        (t > 0.0).then(|| cam.position + t * dir)
    }

    #[test]
    fn nearest_triangles_are_the_visibility_buffers_rows() {
        // Overlapping spheres (overdraw), clipped by the near plane, at sizes whose rows end
        // inside a strip and on its edge; every row count from none to past the height.
        let cam = camera();
        let mesh = uv_sphere(24, 12);
        let mut strip = StripVis::default();
        for (w, h, at) in [(W, H, -2.0), (37, 29, -0.6), (64, 64, -1.0), (8, 8, -3.0)] {
            let mut positions = mesh.positions.clone();
            let mut triangles = mesh.triangles.clone();
            let n = positions.len() as u32;
            positions.extend(mesh.positions.iter().map(|p| *p * 0.7 + Vec3::new(0.4, 0.2, 0.5)));
            triangles.extend(mesh.triangles.iter().map(|t| t.map(|i| i + n)));
            let vp = cam.view_projection() * glam::Mat4::from_translation(Vec3::new(0.0, 0.5, at));
            let clip: Vec<Vec4> = positions.iter().map(|p| vp * p.extend(1.0)).collect();
            for cull in [CullMode::None, CullMode::Back] {
                let vis = rasterize(&clip, &triangles, w, h, cull);
                assert!(vis.samples.iter().any(|s| s.tri != NO_TRIANGLE));
                for rows in [0, 1, h / 2, 15, 16, 17, h - 1, h, h + 5] {
                    let ids = nearest_triangles(&clip, &triangles, w, h, rows, cull, &mut strip);
                    let want: Vec<u32> = vis.samples[..(rows.min(h) * w) as usize].iter().map(|s| s.tri).collect();
                    assert_eq!(ids, want, "{w}×{h}, {rows} rows, {cull:?}");
                }
            }
        }
    }

    #[test]
    fn same_bytes_for_one_thread_and_many() {
        let cam = camera();
        let mesh = uv_sphere(24, 12);
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
