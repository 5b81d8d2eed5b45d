//! A bounding volume hierarchy over a triangle soup: closest-hit and any-hit (shadow) rays.
//!
//! **Build.** Binned SAH (Wald, "On fast construction of SAH-based bounding volume
//! hierarchies", IEEE RT 2007): at each node the triangle centroids fall into 16 bins along
//! each axis, and the split between bins that minimises the surface area heuristic
//! C = C_trav + (A_l N_l + A_r N_r) / A (MacDonald and Booth 1990; C_trav = C_isect = 1) wins.
//! A node of at most 4 triangles becomes a leaf when that is no dearer than splitting; past
//! depth 32 the split is the object median, so the depth (and the traversal stack) stays
//! below 64 whatever the input. Triangles with a non-finite vertex, an index out of range or
//! zero area are left out. The tree is flattened depth first into 32-byte nodes (the first
//! child follows its parent; pbrt's `LinearBVHNode` layout), and each leaf's triangles are
//! copied next to each other in leaf order with their original index. The build is
//! deterministic: the two halves of large nodes are built in parallel (rayon), but the tree
//! does not depend on that.
//!
//! **Traversal.** Iterative, with a fixed stack of 64; a node's near child by the sign of the
//! ray direction on its split axis is visited first. The slab test uses 1/dir (±∞ for a zero
//! component, whose NaN cases are dropped by the order of the min/max) and enlarges the far
//! distance by 2 ulps, which makes it conservative in f32 (Ize, "Robust BVH Ray Traversal",
//! JCGT 2(2), 2013). Triangles use the watertight test of [`super::triangle`], so a ray
//! through a shared edge of a closed mesh cannot leak through the BVH either.
//!
//! **Measured** on the `dense` bench mesh (the uv sphere 1024×512 of `shadelab bench`,
//! 1,046,528 triangles, built by `scene::build`), 2-core x86-64, by a scratch binary that uses
//! the library as a path dependency (`cargo build --release`, then the binary; rayon
//! `par_iter` over the rays, best of 3): 1M closest-hit rays from random points on the plane
//! y = −1.5 (x, z in [−3, 3]) in uniform random upward directions (83,240 hit), and 1M shadow
//! rays from a 1000×1000 grid on that plane to a point light at (2, 4, 3), t_max = 1
//! (234,973 occluded). Against `obvhs` 0.4.0 (feature `parallel`: PLOC build, 8-wide
//! compressed BVH, SIMD node tests, Möller–Trumbore triangles reordered to leaf order):
//!
//! | | threads | build ms | closest Mrays/s | any-hit Mrays/s |
//! | --- | --- | --- | --- | --- |
//! | this BVH | 2 | 470 | 11.5 | 15.0 |
//! | this BVH | 1 | 795 | 5.9 | 7.3 |
//! | obvhs `fast_build` | 2 | 557 | 12.8 | 14.0 |
//! | obvhs `fast_build` | 1 | 623 | 6.2 | 7.4 |
//! | obvhs `medium_build` | 2 | 626 | 12.2 | 14.2 |
//!
//! The machine was shared with other builds: runs differ by ±10 %, and under load the
//! 2-thread figures fall to the 1-thread ones. Within that noise the two are equal (obvhs ~5 %
//! faster on closest hits, this one on shadow rays), so the crate is not worth its
//! dependencies here. Testing both children at the parent and visiting the nearer first
//! measured the same as the sign order (1 thread: 6.3 vs 6.45 Mrays/s closest, 8.0 vs 8.2
//! any-hit), so the simpler order stays. The `sphere` mesh (16,128 triangles) builds in
//! 9 ms on 1 thread, 5 ms on 2 (15,855 nodes, depth 17); the dense one is 24 deep.

use super::triangle::{RayPrecomp, intersect};
use glam::Vec3;
use std::ops::Range;

/// Bins per axis in the binned SAH build (Wald 2007 uses 16 or 32).
const BINS: usize = 16;
/// Most triangles in a leaf.
const MAX_LEAF: usize = 4;
/// Depth from which object-median splits replace SAH splits (bounding the depth).
const SAH_DEPTH: usize = 32;
/// Traversal stack entries: more than the deepest tree the build can make (32 + log2(2³²/4)).
const STACK: usize = 64;
/// Nodes with at least this many triangles build their two halves in parallel.
const PARALLEL_MIN: usize = 4096;

/// One node, 32 bytes: its box, and either its second child or its triangles.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C)]
struct Node {
    /// Low corner of the box.
    min: Vec3,
    /// Interior: the second child's index (the first is the next node). Leaf: its first
    /// triangle in leaf order.
    index: u32,
    /// High corner of the box.
    max: Vec3,
    /// Leaf: its number of triangles (≥ 1). Interior: 0.
    count: u16,
    /// Interior: the split axis (0, 1, 2).
    axis: u16,
}

const _: () = assert!(std::mem::size_of::<Node>() == 32);

/// A BVH over triangles (the default is empty and hits nothing).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Bvh {
    /// Depth-first nodes; the root is node 0.
    nodes: Vec<Node>,
    /// Each kept triangle's vertices, in leaf order.
    tris: Vec<[Vec3; 3]>,
    /// Each kept triangle's index in the input, in leaf order.
    ids: Vec<u32>,
    /// Nodes on the longest root-to-leaf path.
    depth: usize,
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

/// A triangle during the build: its box and its index.
#[derive(Debug, Clone, Copy)]
struct Prim {
    /// Low corner.
    lo: Vec3,
    /// High corner.
    hi: Vec3,
    /// Index in the input.
    id: u32,
}

impl Prim {
    /// Twice the box centre (the halving changes no comparison).
    #[inline]
    fn centroid2(&self) -> Vec3 {
        self.lo + self.hi
    }
}

/// An axis-aligned box being grown.
#[derive(Debug, Clone, Copy)]
struct Aabb {
    /// Low corner.
    lo: Vec3,
    /// High corner.
    hi: Vec3,
}

impl Aabb {
    /// The empty box.
    const EMPTY: Aabb = Aabb { lo: Vec3::INFINITY, hi: Vec3::NEG_INFINITY };

    /// Grows the box to hold `lo..hi`.
    #[inline]
    fn grow(&mut self, lo: Vec3, hi: Vec3) {
        self.lo = self.lo.min(lo);
        self.hi = self.hi.max(hi);
    }

    /// Half the surface area (0 for the empty box).
    #[inline]
    fn half_area(&self) -> f32 {
        let d = (self.hi - self.lo).max(Vec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

impl Bvh {
    /// A BVH over `triangles` (indices into `positions`). Triangles with a non-finite vertex,
    /// an index out of range or zero area are left out (they could not be hit anyway).
    pub fn build(positions: &[Vec3], triangles: &[[u32; 3]]) -> Bvh {
        let mut prims: Vec<Prim> = triangles
            .iter()
            .enumerate()
            .filter_map(|(id, t)| {
                let [a, b, c] = vertices(positions, t)?;
                let finite = a.is_finite() && b.is_finite() && c.is_finite();
                if !finite || (b - a).cross(c - a) == Vec3::ZERO {
                    return None;
                }
                Some(Prim { lo: a.min(b).min(c), hi: a.max(b).max(c), id: id as u32 })
            })
            .collect();
        if prims.is_empty() {
            return Bvh::default();
        }
        let mut nodes = Vec::with_capacity(prims.len() / 2 * 2 + 1);
        let depth = build_node(&mut prims, 0, 1, &mut nodes);
        debug_assert!(depth <= STACK);
        let tris = prims.iter().map(|p| vertices(positions, &triangles[p.id as usize]).expect("kept")).collect();
        let ids = prims.iter().map(|p| p.id).collect();
        Bvh { nodes, tris, ids, depth }
    }

    /// Nearest hit with t in (0, t_max), ignoring triangles whose index is in `skip` (an object's own triangles).
    pub fn closest_hit(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
        self.traverse::<false>(origin, dir, t_max, skip)
    }

    /// Any hit with t in (0, t_max), ignoring `skip`: the shadow-ray query (early exit).
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> bool {
        self.traverse::<true>(origin, dir, t_max, skip).is_some()
    }

    /// The one traversal: front to back by the direction's sign on each split axis; with
    /// `ANY` it returns the first hit found, else it keeps the nearest, shrinking t_max.
    #[inline(always)]
    fn traverse<const ANY: bool>(&self, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
        if self.nodes.is_empty() {
            return None;
        }
        let ray = SlabRay::new(origin, dir);
        let pre = RayPrecomp::new(dir);
        let mut best: Option<TriHit> = None;
        let mut t_best = t_max;
        let mut stack = [0u32; STACK];
        let mut sp = 0;
        let mut i = 0usize;
        loop {
            let node = &self.nodes[i];
            if ray.hits(node, t_best) {
                if node.count > 0 {
                    let first = node.index as usize;
                    for k in first..first + node.count as usize {
                        let id = self.ids[k];
                        if skip.contains(&id) {
                            continue;
                        }
                        let [a, b, c] = self.tris[k];
                        if let Some((t, b1, b2)) = intersect(&pre, origin, a, b, c, t_best) {
                            if ANY {
                                return Some(TriHit { t, tri: id, b1, b2 });
                            }
                            t_best = t;
                            best = Some(TriHit { t, tri: id, b1, b2 });
                        }
                    }
                } else {
                    let (near, far) = if ray.neg[node.axis as usize] { (node.index, i as u32 + 1) } else { (i as u32 + 1, node.index) };
                    stack[sp] = far;
                    sp += 1;
                    i = near as usize;
                    continue;
                }
            }
            if sp == 0 {
                return best;
            }
            sp -= 1;
            i = stack[sp] as usize;
        }
    }

    /// Number of nodes (0 when empty).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of triangles kept (the input less the degenerate ones).
    pub fn triangle_count(&self) -> usize {
        self.ids.len()
    }

    /// Nodes on the longest root-to-leaf path (0 when empty, 1 for a single leaf).
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// The box around every kept triangle, (low, high); the empty box (+∞, −∞) when empty.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.nodes.first().map_or((Vec3::INFINITY, Vec3::NEG_INFINITY), |n| (n.min, n.max))
    }
}

/// The three vertices of `t`, or `None` when an index is out of range.
#[inline]
fn vertices(positions: &[Vec3], t: &[u32; 3]) -> Option<[Vec3; 3]> {
    Some([*positions.get(t[0] as usize)?, *positions.get(t[1] as usize)?, *positions.get(t[2] as usize)?])
}

/// Builds the subtree over `prims` (which start at `first` in leaf order) at depth `depth`,
/// appending its nodes to `nodes` depth first; returns the subtree's depth below its parent.
fn build_node(prims: &mut [Prim], first: u32, depth: usize, nodes: &mut Vec<Node>) -> usize {
    let mut bounds = Aabb::EMPTY;
    let mut centroids = Aabb::EMPTY;
    for p in prims.iter() {
        bounds.grow(p.lo, p.hi);
        let c = p.centroid2();
        centroids.grow(c, c);
    }
    let n = prims.len();
    let me = nodes.len();
    let leaf = Node { min: bounds.lo, max: bounds.hi, index: first, count: n as u16, axis: 0 };
    let extent = centroids.hi - centroids.lo;
    let mid = if n <= 1 {
        return leaf_node(nodes, leaf);
    } else if extent.max_element() <= 0.0 {
        // Every centroid coincides: no plane separates them, so halve the list.
        if n <= MAX_LEAF {
            return leaf_node(nodes, leaf);
        }
        (n / 2, extent_axis(extent))
    } else if depth >= SAH_DEPTH {
        if n <= MAX_LEAF {
            return leaf_node(nodes, leaf);
        }
        median_split(prims, extent_axis(extent))
    } else {
        match sah_split(prims, &bounds, &centroids) {
            Some(split) => split,
            None if n <= MAX_LEAF => return leaf_node(nodes, leaf),
            None => median_split(prims, extent_axis(extent)),
        }
    };
    let (mid, axis) = mid;
    nodes.push(Node { axis: axis as u16, count: 0, ..leaf });
    let (left, right) = prims.split_at_mut(mid);
    let right_first = first + mid as u32;
    let (dl, dr) = if n >= PARALLEL_MIN {
        // The right half goes into its own list, moved behind the left half afterwards; the
        // nodes and their order are those of the sequential build.
        let (dl, (dr, right_nodes)) = rayon::join(
            || build_node(left, first, depth + 1, nodes),
            || {
                let mut right_nodes = Vec::with_capacity(right.len() / 2 * 2);
                let dr = build_node(right, right_first, depth + 1, &mut right_nodes);
                (dr, right_nodes)
            },
        );
        let base = nodes.len() as u32;
        nodes[me].index = base;
        nodes.extend(right_nodes.into_iter().map(|mut c| {
            if c.count == 0 {
                c.index += base;
            }
            c
        }));
        (dl, dr)
    } else {
        let dl = build_node(left, first, depth + 1, nodes);
        nodes[me].index = nodes.len() as u32;
        let dr = build_node(right, right_first, depth + 1, nodes);
        (dl, dr)
    };
    1 + dl.max(dr)
}

/// Appends a leaf; its depth below its parent is 1.
fn leaf_node(nodes: &mut Vec<Node>, leaf: Node) -> usize {
    nodes.push(leaf);
    1
}

/// The axis where `extent` is largest.
fn extent_axis(extent: Vec3) -> usize {
    if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    }
}

/// Splits at the median centroid on `axis`: (left count, axis).
fn median_split(prims: &mut [Prim], axis: usize) -> (usize, usize) {
    let mid = prims.len() / 2;
    // Ties broken by index, so the result is the same for any input order.
    prims.select_nth_unstable_by(mid, |a, b| a.centroid2()[axis].total_cmp(&b.centroid2()[axis]).then(a.id.cmp(&b.id)));
    (mid, axis)
}

/// The binned SAH split (Wald 2007, §3): partitions `prims` and returns (left count, axis),
/// or `None` when a leaf of them is cheaper (only offered for at most [`MAX_LEAF`]).
fn sah_split(prims: &mut [Prim], bounds: &Aabb, centroids: &Aabb) -> Option<(usize, usize)> {
    let n = prims.len();
    let extent = centroids.hi - centroids.lo;
    // The bin of a centroid on each axis: k = ⌊BINS·(1 − ε)·(c − lo)/extent⌋ (Wald eq. 1).
    let scale = Vec3::select(extent.cmpgt(Vec3::ZERO), BINS as f32 * (1.0 - 1e-6) / extent, Vec3::ZERO);
    let bin_of = |p: &Prim| -> [usize; 3] {
        let k = ((p.centroid2() - centroids.lo) * scale).to_array();
        k.map(|k| (k as usize).min(BINS - 1))
    };
    let mut boxes = [[Aabb::EMPTY; BINS]; 3];
    let mut counts = [[0u32; BINS]; 3];
    for p in prims.iter() {
        let k = bin_of(p);
        for axis in 0..3 {
            boxes[axis][k[axis]].grow(p.lo, p.hi);
            counts[axis][k[axis]] += 1;
        }
    }
    // Sweep from the right for the right-hand areas and counts, then from the left.
    let mut best = (f32::INFINITY, 0, 0);
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [0u32; BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for k in (1..BINS).rev() {
            acc.grow(boxes[axis][k].lo, boxes[axis][k].hi);
            cnt += counts[axis][k];
            right_area[k] = acc.half_area();
            right_count[k] = cnt;
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for k in 1..BINS {
            acc.grow(boxes[axis][k - 1].lo, boxes[axis][k - 1].hi);
            cnt += counts[axis][k - 1];
            if cnt == 0 || right_count[k] == 0 {
                continue;
            }
            let cost = acc.half_area() * cnt as f32 + right_area[k] * right_count[k] as f32;
            if cost < best.0 {
                best = (cost, axis, k);
            }
        }
    }
    let (cost, axis, split) = best;
    if !cost.is_finite() {
        return None;
    }
    // SAH with C_trav = C_isect = 1, both in units of the node's area.
    let area = bounds.half_area();
    if n <= MAX_LEAF && (area <= 0.0 || n as f32 <= 1.0 + cost / area) {
        return None;
    }
    // In-place partition by bin (same arithmetic as the binning, so the counts agree).
    let mut mid = 0;
    for j in 0..n {
        if bin_of(&prims[j])[axis] < split {
            prims.swap(mid, j);
            mid += 1;
        }
    }
    Some((mid, axis))
}

/// A ray prepared for slab tests.
struct SlabRay {
    /// Origin.
    o: Vec3,
    /// 1/dir per component (±∞ for a zero component).
    inv: Vec3,
    /// Whether each component of dir is negative (then a slab is entered at its max).
    neg: [bool; 3],
}

impl SlabRay {
    /// Prepares `origin + t·dir`.
    #[inline]
    fn new(origin: Vec3, dir: Vec3) -> SlabRay {
        let inv = dir.recip();
        SlabRay { o: origin, inv, neg: [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0] }
    }

    /// Whether the ray meets `node`'s box for some t in [0, t_max] (conservatively).
    #[inline(always)]
    fn hits(&self, node: &Node, t_max: f32) -> bool {
        // max/min with the accumulated value second: a NaN slab distance (0·∞, a ray in the
        // plane of a face) then leaves the interval as it was (Ize 2013, §3).
        #[inline(always)]
        fn max_keep(x: f32, acc: f32) -> f32 {
            if x > acc { x } else { acc }
        }
        #[inline(always)]
        fn min_keep(x: f32, acc: f32) -> f32 {
            if x < acc { x } else { acc }
        }
        let pick = |neg: bool, lo: f32, hi: f32| if neg { (hi, lo) } else { (lo, hi) };
        let (nx, fx) = pick(self.neg[0], node.min.x, node.max.x);
        let (ny, fy) = pick(self.neg[1], node.min.y, node.max.y);
        let (nz, fz) = pick(self.neg[2], node.min.z, node.max.z);
        let t_near =
            max_keep((nz - self.o.z) * self.inv.z, max_keep((ny - self.o.y) * self.inv.y, max_keep((nx - self.o.x) * self.inv.x, 0.0)));
        let t_far =
            min_keep((fz - self.o.z) * self.inv.z, min_keep((fy - self.o.y) * self.inv.y, min_keep((fx - self.o.x) * self.inv.x, t_max)));
        // Ize 2013, §3: enlarging the far distance by 2 ulps covers the rounding of all three
        // slabs. A t_near of +∞ (a zero direction component outside its slab) is a miss even
        // when t_max is +∞.
        t_near <= t_far * (1.0 + 2.0 * f32::EPSILON) && t_near < f32::INFINITY
    }
}

#[cfg(test)]
mod tests;
