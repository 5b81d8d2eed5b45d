//! The eight-wide tree the queries walk: the binary tree collapsed (Wald, Benthin and Boulos,
//! "Getting rid of packets", IEEE RT 2008; Embree's BVH8), each node's eight boxes laid out
//! for a SIMD slab test (two four-lane halves), and each leaf's triangles in one block of
//! four lanes.
//!
//! **Collapse.** A wide node starts as the two children of a binary node; while it has
//! fewer than eight, the interior child with the largest surface area is replaced by its
//! two children (in place, so the slots keep the binary tree's depth-first order). Every
//! binary leaf becomes one [`Block`].
//!
//! **Order.** A ray visits the binary tree's near child first by the sign of its direction
//! on the split axis. Each wide node stores that order for each of the eight direction
//! octants (`order`), so a single ray and a packet of rays in one octant visit the children
//! in the same order: the packet then does, ray by ray, exactly the single ray's tests.

use super::build::{Binary, MAX_LEAF, vertices};
use glam::Vec3;

/// Children of a wide node.
pub(super) const WIDTH: usize = 8;
/// Triangles in a leaf block (one four-lane register per coordinate).
pub(super) const LANES: usize = 4;
/// Bits of a slot number in [`Node8::order`].
const SLOT_BITS: u32 = 3;
/// A child reference with this bit set is a leaf: the rest is its block's index.
pub(super) const LEAF: u32 = 1 << 31;

/// Eight children's boxes as planes, each plane in eight lanes (one per child), and the
/// children's references. 256 bytes, four cache lines.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(super) struct Node8 {
    /// `planes[2·axis]` are the children's low bounds on `axis`, `planes[2·axis + 1]` the
    /// high ones. An empty slot has the empty box (+∞ low, −∞ high).
    pub planes: [[f32; WIDTH]; 6],
    /// Each child: an interior node's index, or [`LEAF`] | its block's index.
    pub child: [u32; WIDTH],
    /// Per octant (bit a set when the ray's direction is negative on axis a): the slots in
    /// visiting order, three bits each, first in the low bits (empty slots last); bits 24 to
    /// 31 have bit k set when slot k holds a child (the same in every octant's word).
    pub order: [u32; 8],
}

const _: () = assert!(std::mem::size_of::<Node8>() == 256);

impl Node8 {
    /// Slot `k` of octant `octant`'s visiting order.
    #[inline(always)]
    pub fn slot(order: u32, k: usize) -> usize {
        (order >> (SLOT_BITS as usize * k)) as usize & (WIDTH - 1)
    }

    /// The slots that hold a child, from an octant's word of [`Node8::order`].
    #[inline(always)]
    pub fn valid(order: u32) -> u32 {
        order >> 24
    }
}

/// Up to four triangles in lanes: vertex `v[k][axis][lane]`, and their input indices.
/// Unused lanes have NaN vertices (no ray hits them) and index `u32::MAX`.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(16))]
pub(super) struct Block {
    /// Vertex k (0, 1, 2) of each lane's triangle, by axis.
    pub v: [[[f32; LANES]; 3]; 3],
    /// Each lane's triangle index in the input.
    pub ids: [u32; LANES],
}

impl PartialEq for Block {
    /// Equal bits (the NaN of unused lanes equals itself).
    fn eq(&self, o: &Block) -> bool {
        self.ids == o.ids
            && self.v.as_flattened().as_flattened().iter().zip(o.v.as_flattened().as_flattened()).all(|(a, b)| a.to_bits() == b.to_bits())
    }
}

/// The wide tree.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Wide {
    /// Interior nodes, depth first (children after their parent).
    pub nodes: Vec<Node8>,
    /// Leaves, in leaf order.
    pub blocks: Vec<Block>,
    /// The root's reference (node 0, or block 0 when the whole tree is one leaf).
    pub root: u32,
    /// The root's box.
    pub bounds: (Vec3, Vec3),
    /// Wide nodes and leaves on the longest root-to-leaf path.
    pub depth: usize,
}

/// Half the surface area of a binary node's box.
fn half_area(n: &super::build::Node) -> f32 {
    let d = (n.max - n.min).max(Vec3::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// The wide tree of `bin`, with the kept triangles' vertices from `positions` and `triangles`.
pub(super) fn collapse(bin: &Binary, positions: &[Vec3], triangles: &[[u32; 3]]) -> Wide {
    if bin.nodes.is_empty() {
        return Wide::default();
    }
    // A wide node has two to eight children, most of them eight.
    let leaves = bin.nodes.iter().filter(|n| n.count > 0).count();
    let mut w = Wide {
        nodes: Vec::with_capacity(leaves / 4 + 1),
        blocks: Vec::with_capacity(leaves),
        root: 0,
        bounds: (bin.nodes[0].min, bin.nodes[0].max),
        depth: 0,
    };
    let (root, depth) = emit(bin, 0, positions, triangles, &mut w);
    w.root = root;
    w.depth = depth;
    w
}

/// Appends binary node `i`'s subtree; returns its reference and depth.
fn emit(bin: &Binary, i: usize, positions: &[Vec3], triangles: &[[u32; 3]], w: &mut Wide) -> (u32, usize) {
    let n = &bin.nodes[i];
    if n.count > 0 {
        const _: () = assert!(MAX_LEAF <= LANES);
        let mut block = Block { v: [[[f32::NAN; LANES]; 3]; 3], ids: [u32::MAX; LANES] };
        for lane in 0..n.count as usize {
            let id = bin.ids[n.index as usize + lane];
            let tri = vertices(positions, &triangles[id as usize]).expect("a kept triangle's indices are in range");
            for (k, p) in tri.iter().enumerate() {
                for axis in 0..3 {
                    block.v[k][axis][lane] = p[axis];
                }
            }
            block.ids[lane] = id;
        }
        w.blocks.push(block);
        return (LEAF | (w.blocks.len() - 1) as u32, 1);
    }
    // Open the node with the largest area until the slots are filled (ties: the first).
    let mut slots = [0; WIDTH];
    slots[..2].copy_from_slice(&[i + 1, n.index as usize]);
    let mut len = 2;
    while len < WIDTH {
        let mut widest: Option<usize> = None;
        for k in 0..len {
            let open = bin.nodes[slots[k]].count == 0;
            if open && widest.is_none_or(|b| half_area(&bin.nodes[slots[k]]) > half_area(&bin.nodes[slots[b]])) {
                widest = Some(k);
            }
        }
        let Some(k) = widest else { break };
        let s = slots[k];
        slots.copy_within(k + 1..len, k + 2);
        slots[k] = s + 1;
        slots[k + 1] = bin.nodes[s].index as usize;
        len += 1;
    }
    let slots = &slots[..len];
    let me = w.nodes.len();
    let mut node = Node8 {
        planes: [
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [0; WIDTH],
        order: [0; 8],
    };
    for octant in 0..8 {
        let mut seq = [0u8; WIDTH];
        let mut at = 0;
        visit_order(bin, i, slots, octant, &mut seq, &mut at);
        for (k, s) in (len..WIDTH).enumerate() {
            seq[at + k] = s as u8;
        }
        let valid = ((1u32 << len) - 1) << 24;
        node.order[octant] = seq.iter().enumerate().fold(valid, |acc, (k, &s)| acc | (s as u32) << (SLOT_BITS as usize * k));
    }
    w.nodes.push(node);
    let mut depth = 0;
    for (k, &s) in slots.iter().enumerate() {
        let c = &bin.nodes[s];
        for axis in 0..3 {
            w.nodes[me].planes[2 * axis][k] = c.min[axis];
            w.nodes[me].planes[2 * axis + 1][k] = c.max[axis];
        }
        let (r, d) = emit(bin, s, positions, triangles, w);
        w.nodes[me].child[k] = r;
        depth = depth.max(d);
    }
    (me as u32, 1 + depth)
}

/// Appends to `seq` the slots below binary node `i` in the order a ray of `octant` visits
/// them in the binary tree (the near child first by the sign on the split axis).
fn visit_order(bin: &Binary, i: usize, slots: &[usize], octant: usize, seq: &mut [u8; WIDTH], at: &mut usize) {
    if let Some(k) = slots.iter().position(|&s| s == i) {
        seq[*at] = k as u8;
        *at += 1;
        return;
    }
    let n = &bin.nodes[i];
    let (first, second) = (i + 1, n.index as usize);
    let (near, far) = if octant >> n.axis & 1 == 1 { (second, first) } else { (first, second) };
    visit_order(bin, near, slots, octant, seq, at);
    visit_order(bin, far, slots, octant, seq, at);
}
