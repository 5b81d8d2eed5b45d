//! The binary tree: binned SAH over triangle boxes (Wald 2007), built top down in place.
//!
//! Each triangle is one 32-byte [`Prim`] (two `Vec4` corners, the index in the low
//! corner's w), so a box grows by one SIMD min and one max. A node's box and the box of its
//! triangles' centroids arrive from its parent, which computed them while partitioning, so
//! each node reads its triangles twice: once to bin them on all three axes, once to
//! partition them (growing both children's boxes on the way). The builder before this one
//! read them three times (a bounds pass first) and grew boxes one component at a time; the
//! difference is in the module docs' table.

use glam::{Vec3, Vec4};

/// Bins per axis of large nodes (Wald 2007 uses 16 or 32).
const BINS: usize = 16;
/// Bins per axis of nodes of fewer than [`FEW`] triangles (emptying and sweeping 16 bins
/// on three axes cost more than binning a few triangles).
const FEW_BINS: usize = 8;
/// Below this many triangles a node uses [`FEW_BINS`] and one set of bins.
const FEW: usize = 256;
/// Most triangles in a leaf: one block of four SIMD lanes ([`super::wide::Block`]).
pub(super) const MAX_LEAF: usize = 4;
/// Depth from which object-median splits replace SAH splits (bounding the depth).
const SAH_DEPTH: usize = 32;
/// Nodes with at least this many triangles build their two halves in parallel.
const PARALLEL_MIN: usize = 4096;

/// A binary node, 32 bytes: its box, and either its second child or its triangles.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C)]
pub(super) struct Node {
    /// Low corner of the box.
    pub min: Vec3,
    /// Interior: the second child's index (the first is the next node). Leaf: its first
    /// triangle in leaf order.
    pub index: u32,
    /// High corner of the box.
    pub max: Vec3,
    /// Leaf: its number of triangles (≥ 1). Interior: 0.
    pub count: u16,
    /// Interior: the split axis (0, 1, 2).
    pub axis: u16,
}

const _: () = assert!(std::mem::size_of::<Node>() == 32);

/// The binary tree over the kept triangles.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Binary {
    /// Depth-first nodes; the root is node 0 (none when no triangle was kept).
    pub nodes: Vec<Node>,
    /// Each kept triangle's index in the input, in leaf order.
    pub ids: Vec<u32>,
    /// Nodes on the longest root-to-leaf path.
    pub depth: usize,
}

/// Added to a triangle index to give the bits of its low corner's w: a normal float (1.0 for
/// index 0), since SIMD arithmetic on the w lanes of denormals (the bare index) took a
/// microcode assist per operation (the builder ran at half speed).
const ID_BIAS: u32 = 0x3F80_0000;
/// Most triangles a BVH takes: the biased index stays a finite float.
const MAX_TRIANGLES: usize = (1 << 30) - 1;

/// A triangle during the build: its box, with its index in the low corner's w.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
struct Prim {
    /// Low corner; w holds the index's bits plus [`ID_BIAS`].
    lo: Vec4,
    /// High corner; w is 0.
    hi: Vec4,
}

impl Prim {
    /// Twice the box centre (the halving changes no comparison); w is meaningless.
    #[inline(always)]
    fn centroid2(&self) -> Vec4 {
        self.lo + self.hi
    }

    /// The triangle's index in the input.
    #[inline(always)]
    fn id(&self) -> u32 {
        self.lo.w.to_bits() - ID_BIAS
    }
}

/// An axis-aligned box being grown (x, y, z; w is meaningless).
#[derive(Debug, Clone, Copy)]
struct Aabb {
    /// Low corner.
    lo: Vec4,
    /// High corner.
    hi: Vec4,
}

impl Aabb {
    /// The empty box.
    const EMPTY: Aabb = Aabb { lo: Vec4::INFINITY, hi: Vec4::NEG_INFINITY };

    /// Grows the box to hold `lo..hi`.
    #[inline(always)]
    fn grow(&mut self, lo: Vec4, hi: Vec4) {
        self.lo = self.lo.min(lo);
        self.hi = self.hi.max(hi);
    }

    /// Grows the box to hold the point `p`.
    #[inline(always)]
    fn add(&mut self, p: Vec4) {
        self.grow(p, p);
    }

    /// Half the surface area (0 for the empty box).
    #[inline(always)]
    fn half_area(&self) -> f32 {
        let d = (self.hi - self.lo).truncate().max(Vec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// The binary tree over `triangles` (indices into `positions`), leaving out triangles with a
/// non-finite vertex, an index out of range or zero area. The tree depends on the input
/// only, not on the number of threads.
///
/// # Panics
/// With more than 2³⁰ − 1 triangles (32 GiB of them).
pub(super) fn build(positions: &[Vec3], triangles: &[[u32; 3]]) -> Binary {
    assert!(triangles.len() <= MAX_TRIANGLES, "a BVH takes at most 2^30 - 1 triangles");
    let mut bounds = Aabb::EMPTY;
    let mut centroids = Aabb::EMPTY;
    let mut prims = Vec::with_capacity(triangles.len());
    for (id, t) in triangles.iter().enumerate() {
        let Some([a, b, c]) = vertices(positions, t) else { continue };
        let finite = a.is_finite() && b.is_finite() && c.is_finite();
        if !finite || (b - a).cross(c - a) == Vec3::ZERO {
            continue;
        }
        let p = Prim { lo: a.min(b).min(c).extend(f32::from_bits(ID_BIAS + id as u32)), hi: a.max(b).max(c).extend(0.0) };
        bounds.grow(p.lo, p.hi);
        centroids.add(p.centroid2());
        prims.push(p);
    }
    if prims.is_empty() {
        return Binary::default();
    }
    let mut nodes = Vec::with_capacity(prims.len() / 2 * 2 + 1);
    let depth = build_node(&mut prims, 0, 1, bounds, centroids, &mut nodes);
    Binary { nodes, ids: prims.iter().map(Prim::id).collect(), depth }
}

/// The three vertices of `t`, or `None` when an index is out of range.
#[inline]
pub(super) fn vertices(positions: &[Vec3], t: &[u32; 3]) -> Option<[Vec3; 3]> {
    Some([*positions.get(t[0] as usize)?, *positions.get(t[1] as usize)?, *positions.get(t[2] as usize)?])
}

/// Builds the subtree over `prims` (which start at `first` in leaf order, lie in `bounds`
/// and have their doubled centroids in `centroids`) at depth `depth`, appending its nodes to
/// `nodes` depth first; returns the subtree's depth below its parent.
fn build_node(prims: &mut [Prim], first: u32, depth: usize, bounds: Aabb, centroids: Aabb, nodes: &mut Vec<Node>) -> usize {
    let n = prims.len();
    let me = nodes.len();
    let leaf = Node { min: bounds.lo.truncate(), max: bounds.hi.truncate(), index: first, count: n as u16, axis: 0 };
    let extent = (centroids.hi - centroids.lo).truncate();
    // A leaf's triangles are tested in one block of lanes, so up to MAX_LEAF of them cost
    // about one triangle: such a node is always a leaf.
    let split = if n <= MAX_LEAF {
        None
    } else if extent.max_element() <= 0.0 {
        // Every centroid coincides: no plane separates them, so halve the list.
        Some(halves(prims, n / 2, extent_axis(extent)))
    } else if depth >= SAH_DEPTH {
        Some(median_split(prims, extent_axis(extent)))
    } else {
        Some(sah_split(prims, &centroids).unwrap_or_else(|| median_split(prims, extent_axis(extent))))
    };
    let Some(split) = split else {
        nodes.push(leaf);
        return 1;
    };
    nodes.push(Node { axis: split.axis as u16, count: 0, ..leaf });
    let (left, right) = prims.split_at_mut(split.mid);
    let right_first = first + split.mid as u32;
    // On one thread the halves are built in place (no right-hand list to move).
    let (dl, dr) = if n >= PARALLEL_MIN && rayon::current_num_threads() > 1 {
        // The right half goes into its own list, moved behind the left half afterwards; the
        // nodes and their order are those of the sequential build.
        let (dl, (dr, right_nodes)) = rayon::join(
            || build_node(left, first, depth + 1, split.left.0, split.left.1, nodes),
            || {
                let mut right_nodes = Vec::with_capacity(right.len() / 2 * 2);
                let dr = build_node(right, right_first, depth + 1, split.right.0, split.right.1, &mut right_nodes);
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
        let dl = build_node(left, first, depth + 1, split.left.0, split.left.1, nodes);
        nodes[me].index = nodes.len() as u32;
        let dr = build_node(right, right_first, depth + 1, split.right.0, split.right.1, nodes);
        (dl, dr)
    };
    1 + dl.max(dr)
}

/// A chosen split: the left count, the axis, and each side's (box, centroid box).
struct Split {
    /// Triangles on the left (they come first).
    mid: usize,
    /// The split axis.
    axis: usize,
    /// The left side's box and centroid box.
    left: (Aabb, Aabb),
    /// The right side's box and centroid box.
    right: (Aabb, Aabb),
}

/// The boxes of the two sides of `prims` cut at `mid`.
fn halves(prims: &[Prim], mid: usize, axis: usize) -> Split {
    let side = |s: &[Prim]| {
        let (mut b, mut c) = (Aabb::EMPTY, Aabb::EMPTY);
        for p in s {
            b.grow(p.lo, p.hi);
            c.add(p.centroid2());
        }
        (b, c)
    };
    Split { mid, axis, left: side(&prims[..mid]), right: side(&prims[mid..]) }
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

/// Splits at the median centroid on `axis`.
fn median_split(prims: &mut [Prim], axis: usize) -> Split {
    let mid = prims.len() / 2;
    // Ties broken by index, so the result is the same for any input order.
    prims.select_nth_unstable_by(mid, |a, b| a.centroid2()[axis].total_cmp(&b.centroid2()[axis]).then(a.id().cmp(&b.id())));
    halves(prims, mid, axis)
}

/// The bins of `p`'s doubled centroid on each axis: k = ⌊(c − lo)·scale⌋, at most the last.
/// Binning and partitioning both ask here, so they always agree.
#[inline(always)]
fn bins_of<const B: usize>(p: &Prim, lo: Vec4, scale: Vec4) -> [usize; 3] {
    // One truncating conversion for the four lanes (cvttps2dq on x86-64; glam's `as_ivec4`
    // converts lane by lane with saturation, a tenth of the build). c ≥ lo, so k ≥ 0; an
    // out-of-range lane (i32::MIN) becomes the last bin.
    let k = wide::f32x4::new(((p.centroid2() - lo) * scale).to_array()).fast_trunc_int().to_array();
    [0, 1, 2].map(|a| (k[a] as u32).min(B as u32 - 1) as usize)
}

/// The binned SAH split (Wald 2007, §3): partitions `prims` and returns the split, or `None`
/// when no bin boundary separates them.
fn sah_split(prims: &mut [Prim], centroids: &Aabb) -> Option<Split> {
    if prims.len() < FEW { sah_split_with::<FEW_BINS, 1>(prims, centroids) } else { sah_split_with::<BINS, 2>(prims, centroids) }
}

/// [`sah_split`] with `B` bins per axis in `S` sets (one or two).
#[inline(always)]
fn sah_split_with<const B: usize, const S: usize>(prims: &mut [Prim], centroids: &Aabb) -> Option<Split> {
    let n = prims.len();
    let extent = centroids.hi - centroids.lo;
    // The bin of a centroid on each axis: k = ⌊B·(1 − ε)·(c − lo)/extent⌋ (Wald eq. 1),
    // computed by `bins_of`.
    let scale = Vec4::select(extent.cmpgt(Vec4::ZERO), B as f32 * (1.0 - 1e-6) / extent, Vec4::ZERO);
    let lo = centroids.lo;
    // Large nodes bin even and odd triangles in two sets: neighbours in a mesh often fall
    // into the same bin, and one set would chain each update on the last one's store.
    let mut boxes = [[[Aabb::EMPTY; B]; 3]; S];
    let mut counts = [[[0u32; B]; 3]; S];
    let mut pairs = prims.chunks_exact(S);
    for pair in &mut pairs {
        for (set, p) in pair.iter().enumerate() {
            let k = bins_of::<B>(p, lo, scale);
            for axis in 0..3 {
                boxes[set][axis][k[axis]].grow(p.lo, p.hi);
                counts[set][axis][k[axis]] += 1;
            }
        }
    }
    for p in pairs.remainder() {
        let k = bins_of::<B>(p, lo, scale);
        for axis in 0..3 {
            boxes[0][axis][k[axis]].grow(p.lo, p.hi);
            counts[0][axis][k[axis]] += 1;
        }
    }
    for set in 1..S {
        for axis in 0..3 {
            for k in 0..B {
                let odd = boxes[set][axis][k];
                boxes[0][axis][k].grow(odd.lo, odd.hi);
                counts[0][axis][k] += counts[set][axis][k];
            }
        }
    }
    let (boxes, counts) = (&boxes[0], &counts[0]);
    // Sweep from the right for the right-hand areas and counts, then from the left.
    let mut best = (f32::INFINITY, 0, 0);
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let mut right_area = [0.0f32; B];
        let mut right_count = [0u32; B];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for k in (1..B).rev() {
            acc.grow(boxes[axis][k].lo, boxes[axis][k].hi);
            cnt += counts[axis][k];
            right_area[k] = acc.half_area();
            right_count[k] = cnt;
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for k in 1..B {
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
    // In-place partition by bin (the binning's arithmetic, so the counts agree), growing
    // each side's boxes on the way.
    let left_of = |p: &Prim| bins_of::<B>(p, lo, scale)[axis] < split;
    let (mut left, mut right) = ((Aabb::EMPTY, Aabb::EMPTY), (Aabb::EMPTY, Aabb::EMPTY));
    let (mut i, mut j) = (0, n);
    loop {
        while i < j && left_of(&prims[i]) {
            left.0.grow(prims[i].lo, prims[i].hi);
            left.1.add(prims[i].centroid2());
            i += 1;
        }
        while i < j && !left_of(&prims[j - 1]) {
            right.0.grow(prims[j - 1].lo, prims[j - 1].hi);
            right.1.add(prims[j - 1].centroid2());
            j -= 1;
        }
        if i >= j {
            break;
        }
        // prims[i] belongs right and prims[j − 1] left: swap them into place.
        prims.swap(i, j - 1);
    }
    Some(Split { mid: i, axis, left, right })
}
