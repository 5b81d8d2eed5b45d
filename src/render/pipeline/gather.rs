//! The last samples of each triangle (fewer than a bundle) gathered across triangles into
//! full bundles, for Phong with a classic material.
//!
//! A bundle costs the same whether one lane or all of them hold a sample. The `dense` bench's
//! triangles own one or two samples each, so shading each triangle's samples in a bundle of
//! its own ran the whole lighting formula for three or more empty lanes per sample. Here a
//! triangle's rest is interpolated in lanes (position and vertex normal, cheap), its lanes
//! stored in [`Gathered`], and the lighting runs once sixteen have gathered, each lane with
//! its own position, normal, face normal, triangle and object (its shadow rays skip its own
//! triangle, [`LaneIds`]). Each lane's bits depend only on its inputs, so
//! a sample gets the bits the per-triangle bundles give it (tested:
//! `gathered_rests_give_the_bits_of_per_triangle_bundles`). Measured in docs/performance.md.

use super::bundle::{bundle, splat3, surface_lanes};
use super::dispatch::Renderer;
use super::strip::Totals;
use crate::raster::{Owned, StripTri};
use crate::scene::Model;
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::simd::lanes::{Lanes, MAX_WIDTH, V3};
use crate::transport::lighting::LaneIds;
use glam::Vec3;

/// Room for a bundle short of full plus a rest pushed after it (each under `MAX_WIDTH`).
const CAP: usize = 2 * MAX_WIDTH;

/// Surface points waiting to be shaded with one classic material, a lane each, by channel.
pub(super) struct Gathered {
    /// Positions.
    p: [[f32; CAP]; 3],
    /// Interpolated vertex normals, not yet renormalized.
    n: [[f32; CAP]; 3],
    /// Face normals.
    face: [[f32; CAP]; 3],
    /// Sample indices in the strip.
    index: [u32; CAP],
    /// Triangles (indices into the scene's geometry).
    tri: [u32; CAP],
    /// Objects.
    object: [u32; CAP],
    /// Points waiting.
    len: usize,
    /// Their material (an index into the scene's materials).
    material: usize,
    /// Whether `tri` and `object` are kept (shadow rays need them; plain lighting does not,
    /// and filling them cost `dense` 10%).
    keep_ids: bool,
}

impl Gathered {
    /// Nothing waiting; each point's triangle and object kept when `keep_ids`.
    pub(super) fn new(keep_ids: bool) -> Gathered {
        let zero = [[0f32; CAP]; 3];
        Gathered { p: zero, n: zero, face: zero, index: [0; CAP], tri: [0; CAP], object: [0; CAP], len: 0, material: 0, keep_ids }
    }

    /// Appends the first `index.len()` lanes of `p`, `n` and `face` (samples `index` of
    /// triangle `tri` of `object`).
    #[inline(always)]
    fn push<G: Lanes>(&mut self, p: V3<G>, n: V3<G>, face: V3<G>, index: &[u32], (tri, object): (u32, u32)) {
        let (at, end) = (self.len, self.len + index.len());
        store3(p, &mut self.p, at);
        store3(n, &mut self.n, at);
        store3(face, &mut self.face, at);
        self.index[at..end].copy_from_slice(index);
        if self.keep_ids {
            self.tri[at..end].fill(tri);
            self.object[at..end].fill(object);
        }
        self.len = end;
    }

    /// The triangle and object of each of the first `MAX_WIDTH` points.
    #[inline(always)]
    fn ids(&self) -> LaneIds {
        let first = |a: &[u32; CAP]| -> [u32; MAX_WIDTH] { a[..MAX_WIDTH].try_into().expect("CAP holds MAX_WIDTH") };
        LaneIds { tri: first(&self.tri), object: first(&self.object) }
    }

    /// The first `F::WIDTH` waiting points as lanes (lanes past `len` repeat the first, so
    /// they compute valid values that nobody reads), and their sample indices.
    #[inline(always)]
    fn lanes<F: Lanes>(&self) -> (F::Mask, [V3<F>; 3], &[u32]) {
        let n = self.len.min(F::WIDTH);
        let active = F::first(n);
        let lanes = [load3(&self.p, active), load3(&self.n, active), load3(&self.face, active)];
        (active, lanes, &self.index[..n])
    }

    /// Drops the first `F::WIDTH` points (shaded), moving the others to the front.
    #[inline(always)]
    fn shift<F: Lanes>(&mut self) {
        let w = F::WIDTH;
        for a in self.p.iter_mut().chain(&mut self.n).chain(&mut self.face) {
            a.copy_within(w..2 * w, 0);
        }
        self.index.copy_within(w..2 * w, 0);
        if self.keep_ids {
            self.tri.copy_within(w..2 * w, 0);
            self.object.copy_within(w..2 * w, 0);
        }
        self.len -= w;
    }
}

/// Stores the lanes of `v` from entry `at` of each channel.
#[inline(always)]
fn store3<G: Lanes>(v: V3<G>, out: &mut [[f32; CAP]; 3], at: usize) {
    v.x.store(&mut out[0][at..]);
    v.y.store(&mut out[1][at..]);
    v.z.store(&mut out[2][at..]);
}

/// The first `F::WIDTH` entries of each channel, the inactive lanes repeating the first.
#[inline(always)]
fn load3<F: Lanes>(a: &[[f32; CAP]; 3], active: F::Mask) -> V3<F> {
    V3 { x: load1(&a[0], active), y: load1(&a[1], active), z: load1(&a[2], active) }
}

/// [`load3`] of one channel.
#[inline(always)]
fn load1<F: Lanes>(a: &[f32; CAP], active: F::Mask) -> F {
    F::select(active, F::load(a), F::splat(a[0]))
}

/// Whether triangles' rests may be gathered across triangles (a test on this thread may
/// switch it off, to compare with per-triangle bundles).
pub(super) fn gather_allowed() -> bool {
    #[cfg(test)]
    return super::tests::GATHER.with(|g| g.get());
    #[cfg(not(test))]
    true
}

impl Renderer<'_> {
    /// Phong with classic material `mi` for the samples `run` of triangle `t` (fewer than
    /// `W::WIDTH`, the rest after its full bundles): their positions and normals interpolated
    /// in `H` lanes (or `W` when more than `H::WIDTH`) and added to `queue`, which shades a
    /// bundle of `W` once that many wait.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn phong_gather<W: Lanes, H: Lanes>(
        &self,
        t: &StripTri,
        clipped: &[[Vec3; 3]],
        owned: &Owned,
        run: std::ops::Range<usize>,
        mi: usize,
        queue: &mut Gathered,
        totals: &mut (impl Totals + ?Sized),
        mut terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        debug_assert!(run.len() < W::WIDTH);
        if run.is_empty() {
            return;
        }
        if queue.material != mi {
            self.phong_flush::<W>(queue, totals, terms.as_deref_mut(), k);
            queue.material = mi;
        }
        if run.len() <= H::WIDTH {
            self.push_rest::<H>(t, clipped, owned, run, queue);
        } else {
            self.push_rest::<W>(t, clipped, owned, run, queue);
        }
        if queue.len >= W::WIDTH {
            self.shade_gathered::<W>(queue, totals, terms, k);
            queue.shift::<W>();
        }
    }

    /// Shades the points still waiting in `queue` (one partial bundle of `W`).
    #[inline(always)]
    pub(super) fn phong_flush<W: Lanes>(
        &self,
        queue: &mut Gathered,
        totals: &mut (impl Totals + ?Sized),
        terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        if queue.len > 0 {
            self.shade_gathered::<W>(queue, totals, terms, k);
            queue.len = 0;
        }
    }

    /// The samples `run` of triangle `t` interpolated in `G` lanes and added to `queue`.
    #[inline(always)]
    fn push_rest<G: Lanes>(&self, t: &StripTri, clipped: &[[Vec3; 3]], owned: &Owned, run: std::ops::Range<usize>, queue: &mut Gathered) {
        let g = self.g;
        let orig = t.orig as usize;
        let v = g.triangles[orig].map(|i| i as usize);
        let (p, n) = (splat3::<G>(&g.positions, v), splat3::<G>(&g.normals, v));
        let (_, b1, b2) = bundle::<G>(t, clipped, owned, run.start, run.end);
        let (pos, normal) = surface_lanes(&p, &n, b1, b2);
        // (Finding the object is a search: only when kept.)
        let ids = if queue.keep_ids { (t.orig, g.object_of_triangle(orig)) } else { (u32::MAX, u32::MAX) };
        queue.push(pos, normal, V3::splat(g.face_normals[orig]), &owned.index[run], ids);
    }

    /// Shades the first `W::WIDTH` points waiting in `queue` (fewer when fewer wait).
    #[inline(always)]
    fn shade_gathered<W: Lanes>(
        &self,
        queue: &Gathered,
        totals: &mut (impl Totals + ?Sized),
        terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        let m = &self.scene.materials[queue.material];
        let Model::Classic(c) = &m.model else { unreachable!("only classic materials are gathered") };
        let (active, [pos, n, face], index) = queue.lanes::<W>();
        // Plain lighting casts no shadow ray: it needs no triangle or object.
        let ids = queue.keep_ids.then(|| queue.ids());
        self.phong_surface((m, c), active, pos, n, (face, u32::MAX, u32::MAX, ids), index, totals, terms, k);
    }
}
