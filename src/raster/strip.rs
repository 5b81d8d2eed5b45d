//! The visibility of one strip of rows: nearest depth per sample, the samples each triangle
//! owns, and their resolve to perspective-correct barycentrics of the original triangle.

use super::edge::{MAX_WALK_LANES, depth_at};
use super::{NO_TRIANGLE, VisSample};
use crate::simd::lanes::Lanes;
use glam::Vec3;

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
    pub(super) depth: Vec<f32>,
    /// The walked triangles that own samples, in submission order.
    pub(super) tris: Vec<StripTri>,
    /// The owned-sample list, triangle after triangle: sample index and screen-space l1, l2,
    /// entries `..listed`, then [`LIST_PAD`] zero entries so bundles of lanes load past the
    /// end. The vectors only grow (entries are written by index), so a strip allocates and
    /// zero-fills nothing once the thread's buffers are large enough.
    pub(super) index: Vec<u32>,
    pub(super) l1: Vec<f32>,
    pub(super) l2: Vec<f32>,
    /// Entries in the owned-sample list.
    pub(super) listed: usize,
    /// Barycentric maps of clipped pieces ([`BaryMap::Clipped`]).
    pub(super) clipped: Vec<[Vec3; 3]>,
}

/// Zero entries after the owned-sample list: a bundle of up to sixteen lanes loads in bounds.
pub const LIST_PAD: usize = 16;

/// Depth entries after a strip's samples: the lane walk loads and stores up to sixteen samples at a time.
const DEPTH_PAD: usize = MAX_WALK_LANES;

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
    /// strip loaded from a [`VisBuffer`](super::VisBuffer)).
    Resolved,
}

/// A triangle that owns samples of a strip.
#[derive(Debug, Clone, Copy)]
pub struct StripTri {
    /// Reversed depth z/w at the set-up triangle's vertices.
    pub(super) z: [f32; 3],
    /// 1/w at the set-up triangle's vertices.
    pub(super) q: [f32; 3],
    /// Index of the original triangle.
    pub orig: u32,
    /// How its barycentrics map to the original triangle's.
    pub(super) map: BaryMap,
    /// Its entries in the owned-sample list: `start..end`.
    pub(super) start: u32,
    pub(super) end: u32,
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
    pub(super) fn reset(&mut self, y0: u32, rows: u32, width: u32) {
        (self.y0, self.rows, self.width) = (y0, rows, width);
        let n = (rows * width) as usize;
        // Only the depth is reset: it is the coverage, and the rest is read only where it is > 0.
        // The lane walk reads and writes back up to fifteen samples past a row's box.
        self.depth.clear();
        self.depth.resize(n + DEPTH_PAD, 0.0);
        self.tris.clear();
        self.clipped.clear();
        self.listed = 0;
    }

    /// Makes [`StripTri::resolve`] give screen-space (affine) barycentrics of the original
    /// triangle: with every 1/w set to 1 the perspective weights are the screen-space ones
    /// (their sum is 1 to rounding). A clipped piece's are affine across the piece, the
    /// attributes at its new vertices (on the near plane) perspective-correct, as a scanline
    /// renderer that clips first interpolates them. Run it after rasterizing, before resolving.
    pub fn interpolate_in_screen_space(&mut self) {
        for t in &mut self.tris {
            t.q = [1.0; 3];
        }
    }

    /// Makes room for `n` more entries in the owned-sample list (and its padding).
    pub(super) fn reserve(&mut self, n: usize) {
        let room = self.listed + n + LIST_PAD;
        if self.index.len() < room {
            let len = room.max(2 * self.index.len());
            self.index.resize(len, 0);
            self.l1.resize(len, 0.0);
            self.l2.resize(len, 0.0);
        }
    }

    /// Ends the owned-sample list with the padding entries bundles read past the end.
    pub(super) fn pad(&mut self) {
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
    pub(super) fn drop_overwritten(&mut self) {
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
    pub(super) fn write_resolved(&self, out: &mut [VisSample]) {
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

#[cfg(test)]
mod tests {
    use crate::raster::tests::{H, W, camera, ray_plane};
    use crate::raster::{CullMode, NO_TRIANGLE, rasterize};
    use glam::{Vec3, Vec4};

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
}
