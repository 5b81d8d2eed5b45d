//! A bounding volume hierarchy over a triangle soup: closest-hit and any-hit (shadow) rays,
//! one at a time or in packets of up to sixteen.
//!
//! **Build** (`build.rs`). Binned SAH (Wald, "On fast construction of SAH-based bounding
//! volume hierarchies", IEEE RT 2007): at each node the triangle centroids fall into bins
//! along each axis (16, or 8 below 256 triangles), and the split between bins that
//! minimises the surface area heuristic C = C_trav + (A_l N_l + A_r N_r) / A (MacDonald and
//! Booth 1990) wins. A node of at most 4 triangles is always a leaf (they are tested in one
//! block of SIMD lanes, about the cost of one); past depth 32 the split is the object
//! median, so the depth stays below 64 whatever the input. Triangles with a non-finite
//! vertex, an index out of range or zero area are left out. Each triangle is one 32-byte
//! box of two SIMD registers; a node gets its box and centroid box from its parent's
//! partition, so it reads its triangles twice (bin, partition), not three times. On more
//! than one thread the two halves of large nodes are built in parallel (rayon); the tree
//! does not depend on that.
//!
//! **Layout** (`wide.rs`). The binary tree is collapsed into an eight-wide one (Wald, Benthin
//! and Boulos 2008; Embree's BVH8): each node holds its children's eight boxes as six planes
//! of eight lanes, and each leaf's triangles sit in one block of four lanes (vertices by
//! axis, with their input indices). Each node also stores, per direction octant, the order
//! in which the binary tree's near-child-first walk visits its children.
//!
//! **Traversal** (`traverse.rs`). Iterative, depth first. A ray first checks, without a
//! division, whether it starts outside the root box and moves away from it on some axis
//! (most shadow rays of a scene with an object per BVH stop there), then the scalar slab
//! test of the root box, then each node's eight boxes in two four-lane halves (SSE on
//! x86-64, where every CPU has it; portable `wide` lanes elsewhere), children in the
//! octant's order, and each leaf's four triangles in one four-lane watertight test. The
//! slab test uses 1/dir (±∞ for a zero component, whose NaN cases are dropped by the order
//! of the min/max) and enlarges the far distance by 2 ulps, which makes it conservative in
//! f32 (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013). Triangles use the watertight test
//! of [`super::triangle`], so a ray through a shared edge of a closed mesh cannot leak
//! through the BVH either. Every lane does the scalar test's IEEE operations in the scalar
//! order (no FMA, no reciprocal approximation), so each box and triangle gets the scalar
//! answer bit for bit; a lane whose edge function came out exactly 0 runs the scalar test
//! with its f64 fallback.
//!
//! **Packets** ([`RayPacket`], [`Bvh::occluded_packet`], [`Bvh::closest_packet`]). Up to
//! sixteen rays, one per lane: sixteen AVX-512F lanes or two AVX registers where the CPU
//! has them (through the `simd` detection tokens), else four SSE lanes at a time. Rays
//! that share an octant and the watertight test's axis permutation walk together in that
//! octant's order, each active only where its own box tests passed, so each gets its
//! single-ray answer bit for bit (`packet.rs`).
//!
//! **Ties and determinism.** Each triangle is tested up to the ray's own t_max (boxes up to
//! the best hit so far), so its (t, b1, b2) do not depend on the order of the visits; the
//! closest hit is the smallest (t, triangle index). Single rays, packets, any node width
//! and any thread count of the build give the same answers; `occluded` is exactly
//! `closest_hit(..).is_some()`. The scalar reference the tests compare against bit for bit
//! is the binary tree walked one node and one triangle at a time (`reference`, test only).
//!
//! **Measured** by a scratch binary that includes these files by path (`cargo build
//! --release`, one thread, each figure the median of alternating rounds of the old and new
//! code, in thread CPU time): the `shadow-ray` bench's shadow rays rebuilt outside the
//! renderer (the uv sphere 128×64 on the ground square, 1024², a ray toward
//! normalize(1, 1, 1) per sample whose shading normal faces the light, origin offset along
//! the face normal; a ray from the sphere tests the ground's BVH and one from the ground
//! the sphere's: 736,200 rays, 54,632 occluded), and the build of the `dense` uv sphere
//! (1024×512, 1,046,528 triangles). 2-core x86-64 (AMD EPYC, AVX-512) shared with other
//! builds (load 7–11): ratios are steadier than the absolute figures.
//!
//! | one thread | before (binary, scalar) | this BVH | ratio |
//! | --- | --- | --- | --- |
//! | shadow rays one at a time, Mrays/s | 23.0 | 54.7 | 2.37× |
//! | the same rays as packets of 16 (in pixel order), Mrays/s | — | 72.4 | 3.15× |
//! | closest hits of the 1024² camera rays (both BVHs), one at a time, Mrays/s | 20.7 | 26.6 | 1.29× |
//! | the same in packets of 16 along a row, Mrays/s | — | 70.0 | 3.38× |
//! | `dense` build, ms of CPU time | 771 | 361 | 2.15× |
//!
//! Where the time went, and what was tried: a shadow ray that meets the sphere's root box
//! took 154 ns before and 76 ns now (4.2 wide nodes and 0.9 leaf blocks a ray); one that
//! misses took 15 ns and 3.5 ns (most stop at the division-free early exit). At an earlier
//! stage (early exits out of line), four-wide nodes took 95 ns where eight-wide took 87;
//! with four-wide nodes, writing every child to the stack without a branch (no fast path
//! for one hit) took 117 ns against 95, and prefetching the pushed children changed
//! nothing. The early exits out of line, or their components packed into lanes, cost 8–10
//! ns instead of 3 (the arguments' reload waited on the caller's stores); the walk compiled
//! with AVX-512 encodings (more registers) takes 76 instead of 78 ns. The builder was at half speed until the
//! triangle index in the boxes' w lane stopped being a denormal float; then one bounds
//! pass fewer, two bin sets, 8 bins for small nodes, leaves of up to 4 always, and one
//! vector conversion for the bin indices took it from 1.4× to 2.15× the old one.
//!
//! Before this, a binary tree of 32-byte nodes with a scalar slab test and one triangle at
//! a time; `obvhs` 0.4.0 (PLOC build, eight-wide compressed BVH) measured the same as that
//! tree on the dense mesh (within ±10 %), so it is not used.

mod build;
mod packet;
mod traverse;
mod wide;

#[cfg(test)]
mod reference;
#[cfg(test)]
mod tests;

pub use packet::RayPacket;

use glam::Vec3;
use std::ops::Range;

/// A BVH over triangles (the default is empty and hits nothing).
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    /// The eight-wide tree the queries walk.
    tree: wide::Wide,
    /// Triangles kept.
    triangles: usize,
    /// The instruction set the walks are compiled for on this CPU, found at build.
    isa: Isa,
}

impl PartialEq for Bvh {
    /// The same tree (the instruction set is the CPU's, not the tree's).
    fn eq(&self, o: &Bvh) -> bool {
        self.tree == o.tree && self.triangles == o.triangles
    }
}

/// The widest instruction set the walks use on this CPU: a detection token
/// (`crate::simd`), so code compiled for it runs only where the CPU has it.
#[derive(Debug, Clone, Copy, Default)]
enum Isa {
    /// Baseline: SSE2 on x86-64, portable lanes elsewhere.
    #[default]
    Base,
    /// AVX: packets in sixteen lanes as two registers; single rays VEX-encoded.
    #[cfg(target_arch = "x86_64")]
    Avx(crate::simd::avx::Avx),
    /// AVX-512F: packets in sixteen lanes; single rays with 32 registers.
    #[cfg(target_arch = "x86_64")]
    Avx512(crate::simd::avx512::Avx512),
}

impl Isa {
    /// The widest this CPU has.
    fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        {
            let cpu = crate::simd::Cpu::get();
            if let Some(t) = cpu.avx512() {
                return Isa::Avx512(t);
            }
            if let Some(t) = cpu.avx() {
                return Isa::Avx(t);
            }
        }
        Isa::Base
    }

    /// Runs `task` compiled for this instruction set, with its widest lanes.
    #[inline(always)]
    fn run<K: crate::simd::lanes::LaneTask>(self, task: K) -> K::Output {
        match self {
            Isa::Base => task.run::<crate::simd::lanes::F32x4, crate::simd::lanes::F32x4>(),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx(t) => t.run(task),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512(t) => t.run(task),
        }
    }
}

/// A closest hit: ray parameter, the original triangle index and its barycentrics (of vertices 1 and 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriHit {
    /// Ray parameter, in multiples of the ray's direction.
    pub t: f32,
    /// Index of the triangle in the slice given to [`Bvh::build`].
    pub tri: u32,
    /// Barycentric weight of the triangle's vertex 1.
    pub b1: f32,
    /// Barycentric weight of the triangle's vertex 2.
    pub b2: f32,
}

impl Bvh {
    /// A BVH over `triangles` (indices into `positions`). Triangles with a non-finite vertex,
    /// an index out of range or zero area are left out (they could not be hit anyway).
    pub fn build(positions: &[Vec3], triangles: &[[u32; 3]]) -> Bvh {
        let binary = build::build(positions, triangles);
        let tree = wide::collapse(&binary, positions, triangles);
        Bvh { tree, triangles: binary.ids.len(), isa: Isa::detect() }
    }

    /// Nearest hit with t in (0, t_max), ignoring triangles whose index is in `skip` (an
    /// object's own triangles). Of hits at equal t, the smallest triangle index wins.
    #[inline]
    pub fn closest_hit(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
        traverse::closest(&self.tree, self.isa, origin, dir, t_max, skip)
    }

    /// Any hit with t in (0, t_max), ignoring `skip`: the shadow-ray query (early exit).
    /// Always `closest_hit(..).is_some()`.
    #[inline]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> bool {
        traverse::occluded(&self.tree, self.isa, origin, dir, t_max, skip)
    }

    /// Which rays of `packet` (bit i for lane i, among those set in `active`) are occluded:
    /// each bit is [`Bvh::occluded`] of that lane's ray.
    pub fn occluded_packet(&self, packet: &RayPacket, active: u16) -> u16 {
        let hits = self.trace(packet::Query::<true> { tree: &self.tree, packet, active });
        (0..RayPacket::MAX).fold(0, |m, i| m | (hits[i].is_some() as u16) << i)
    }

    /// The closest hit of each ray of `packet` set in `active` (`None` for the others): each
    /// is [`Bvh::closest_hit`] of that lane's ray, bit for bit.
    pub fn closest_packet(&self, packet: &RayPacket, active: u16) -> [Option<TriHit>; RayPacket::MAX] {
        self.trace(packet::Query::<false> { tree: &self.tree, packet, active })
    }

    /// Runs a packet query with the widest lanes this CPU has: sixteen with AVX-512F, sixteen
    /// as two AVX registers, else four SSE (or portable) lanes.
    fn trace<const ANY: bool>(&self, q: packet::Query<'_, ANY>) -> [Option<TriHit>; RayPacket::MAX] {
        self.isa.run(q)
    }

    /// Number of nodes, interior and leaves (0 when empty).
    pub fn node_count(&self) -> usize {
        self.tree.nodes.len() + self.tree.blocks.len()
    }

    /// Number of triangles kept (the input less the degenerate ones).
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// Nodes on the longest root-to-leaf path (0 when empty, 1 for a single leaf).
    pub fn depth(&self) -> usize {
        self.tree.depth
    }

    /// The box around every kept triangle, (low, high); the empty box (+∞, −∞) when empty.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        if self.tree.blocks.is_empty() { (Vec3::INFINITY, Vec3::NEG_INFINITY) } else { self.tree.bounds }
    }
}
