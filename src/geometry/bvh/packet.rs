//! Packets: up to sixteen rays through the wide tree together, one ray per SIMD lane
//! ([`crate::simd::lanes::Lanes`]: four SSE lanes everywhere, sixteen with AVX-512F or
//! AVX through their detection tokens), with each ray's single-ray answer bit for bit.
//!
//! **Why the answers are the single ray's.** The lanes are split into groups that share the
//! direction octant and the watertight test's axis permutation (a coherent packet, such as
//! a bundle's shadow rays toward one light, is one group). A group walks the tree depth
//! first in its octant's child order ([`super::wide`]), the order a single ray of that
//! octant walks it; a ray is active in a subtree only where its own box tests passed, with
//! its own t_max (its best hit so far for closest hits, exactly as the single ray's stack
//! does when it pops). So each ray meets the same boxes in the same order, with the same
//! IEEE operations per lane as [`super::traverse`] (and [`intersect`] for a lane whose
//! edge function came out exactly 0), and ties go to the smallest triangle index there and
//! here. Any-hit answers do not depend on the order at all.

use super::TriHit;
use super::traverse::SHALLOW;
use super::wide::{Block, LANES, LEAF, Node8, WIDTH, Wide};
use crate::geometry::triangle::{RayPrecomp, intersect};
use crate::simd::lanes::{LaneTask, Lanes, MAX_WIDTH};
use glam::Vec3;
use std::ops::Range;

/// 1 + 2 ulps: Ize's enlargement of the far distance (as `SlabRay::hits`).
const ULPS2: f32 = 1.0 + 2.0 * f32::EPSILON;

/// Up to sixteen rays, each `origin + t·dir` for t in (0, t_max), each ignoring the
/// triangles whose indices are in its `skip` range (the shaded point's own triangle).
/// Stored by component (`origin[axis][lane]`), as the lanes load them.
///
/// A lane left as [`RayPacket::default`] has a zero direction and t_max 0 and hits nothing.
#[derive(Debug, Clone)]
pub struct RayPacket {
    /// Origins, by axis then lane.
    pub origin: [[f32; MAX_WIDTH]; 3],
    /// Directions (any length, as for [`super::Bvh::occluded`]), by axis then lane.
    pub dir: [[f32; MAX_WIDTH]; 3],
    /// Each ray's open upper bound on t.
    pub t_max: [f32; MAX_WIDTH],
    /// Each ray's ignored triangle indices.
    pub skip: [Range<u32>; MAX_WIDTH],
}

impl Default for RayPacket {
    fn default() -> RayPacket {
        RayPacket {
            origin: [[0.0; MAX_WIDTH]; 3],
            dir: [[0.0; MAX_WIDTH]; 3],
            t_max: [0.0; MAX_WIDTH],
            skip: std::array::from_fn(|_| 0..0),
        }
    }
}

impl RayPacket {
    /// Most rays in a packet.
    pub const MAX: usize = MAX_WIDTH;

    /// Sets lane `i` (precondition: `i < RayPacket::MAX`) to the ray `origin + t·dir`, t in
    /// (0, t_max), ignoring the triangles in `skip`.
    pub fn set(&mut self, i: usize, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) {
        for a in 0..3 {
            self.origin[a][i] = origin[a];
            self.dir[a][i] = dir[a];
        }
        self.t_max[i] = t_max;
        self.skip[i] = skip;
    }

    /// Lane `i`'s origin.
    pub fn origin(&self, i: usize) -> Vec3 {
        Vec3::new(self.origin[0][i], self.origin[1][i], self.origin[2][i])
    }

    /// Lane `i`'s direction.
    pub fn dir(&self, i: usize) -> Vec3 {
        Vec3::new(self.dir[0][i], self.dir[1][i], self.dir[2][i])
    }
}

/// A packet query as a lane task: `ANY` for occlusion, else closest hits.
#[derive(Clone, Copy)]
pub(super) struct Query<'a, const ANY: bool> {
    /// The tree.
    pub tree: &'a Wide,
    /// The rays.
    pub packet: &'a RayPacket,
    /// The rays to trace (bit i for lane i).
    pub active: u16,
}

impl<const ANY: bool> LaneTask for Query<'_, ANY> {
    type Output = [Option<TriHit>; MAX_WIDTH];

    // Inlined into the token's `#[target_feature]` function, as the lanes are.
    #[inline(always)]
    fn run<W: Lanes, H: Lanes>(self) -> [Option<TriHit>; MAX_WIDTH] {
        let mut out = [None; MAX_WIDTH];
        if self.tree.blocks.is_empty() {
            return out;
        }
        for first in (0..MAX_WIDTH).step_by(W::WIDTH) {
            if self.active >> first & ((1u32 << W::WIDTH) - 1) as u16 != 0 {
                trace_group::<W, ANY>(self.tree, self.packet, self.active, first, &mut out);
            }
        }
        out
    }
}

/// `x > acc ? x : acc` per lane (the scalar `max_keep`).
#[inline(always)]
fn max_keep<L: Lanes>(x: L, acc: L) -> L {
    L::select(x.gt(acc), x, acc)
}

/// `x < acc ? x : acc` per lane (the scalar `min_keep`).
#[inline(always)]
fn min_keep<L: Lanes>(x: L, acc: L) -> L {
    L::select(x.lt(acc), x, acc)
}

/// Each lane of `m` as a bool.
#[inline(always)]
fn bools<L: Lanes>(m: L::Mask) -> [bool; MAX_WIDTH] {
    let mut v = [0.0; MAX_WIDTH];
    L::select(m, L::splat(1.0), L::splat(0.0)).store(&mut v);
    v.map(|x| x != 0.0)
}

/// A mask from bools.
#[inline(always)]
fn mask<L: Lanes>(b: &[bool; MAX_WIDTH]) -> L::Mask {
    let v = b.map(|x| if x { 1.0 } else { 0.0 });
    L::load(&v).gt(L::splat(0.0))
}

/// The rays of one group of lanes, prepared as `SlabRay` and [`RayPrecomp`] prepare one.
struct Rays<L: Lanes> {
    /// Origin per lane.
    o: [L; 3],
    /// 1/dir per lane.
    inv: [L; 3],
    /// The shear sx, sy, sz per lane.
    s: [L; 3],
    /// t_max per lane.
    t_max: L,
}

/// Traces the packet's lanes `first..first + W::WIDTH` that are in `active` into `out`.
#[inline(always)]
fn trace_group<L: Lanes, const ANY: bool>(
    tree: &Wide,
    packet: &RayPacket,
    active: u16,
    first: usize,
    out: &mut [Option<TriHit>; MAX_WIDTH],
) {
    let n = L::WIDTH;
    let at = |v: &[f32; MAX_WIDTH]| L::load(&v[first..]);
    let (o, d, t_max) = (packet.origin.each_ref().map(at), packet.dir.each_ref().map(at), at(&packet.t_max));
    // SlabRay::new per lane: the correctly rounded 1/dir; a lane is negative on an axis
    // where 1/dir < 0.
    let inv = d.map(|x| L::splat(1.0) / x);
    let zero = L::splat(0.0);
    let neg = inv.map(|x| x.lt(zero));
    let on: [bool; MAX_WIDTH] = std::array::from_fn(|j| j < n && active >> (first + j) & 1 == 1);
    // The root box first (as a single ray tests it), each lane in its own octant: most rays
    // of a packet that misses an object's box stop here.
    let (lo, hi) = tree.bounds;
    let slab = |a: usize, near: bool| {
        let (p, q) = if near { (hi[a], lo[a]) } else { (lo[a], hi[a]) };
        (L::select(neg[a], L::splat(p), L::splat(q)) - o[a]) * inv[a]
    };
    let t_near = max_keep(slab(2, true), max_keep(slab(1, true), max_keep(slab(0, true), zero)));
    let t_far = min_keep(slab(2, false), min_keep(slab(1, false), min_keep(slab(0, false), t_max)));
    let root = mask::<L>(&on) & t_near.le(t_far * L::splat(ULPS2)) & t_near.lt(L::splat(f32::INFINITY));
    if !L::any(root) {
        return;
    }
    // RayPrecomp::new per lane: kz where |dir| is largest, kx and ky after it (swapped when
    // dir[kz] < 0), and the shear.
    let abs = d.map(|x| L::select(x.lt(zero), -x, x));
    let z0 = abs[1].le(abs[0]) & abs[2].le(abs[0]);
    let z1 = !z0 & abs[2].le(abs[1]);
    let pick = |m0: L::Mask, m1: L::Mask, v: &[L; 3]| L::select(m0, v[0], L::select(m1, v[1], v[2]));
    let d_z = pick(z0, z1, &d);
    let swap = d_z.lt(zero);
    // kx = kz + 1 and ky = kz + 2 (mod 3), or the other way round when swapped.
    let (d_1, d_2) = (pick(z0, z1, &[d[1], d[2], d[0]]), pick(z0, z1, &[d[2], d[0], d[1]]));
    let (d_x, d_y) = (L::select(swap, d_2, d_1), L::select(swap, d_1, d_2));
    let rays = Rays { o, inv, s: [d_x / d_z, d_y / d_z, L::splat(1.0) / d_z], t_max };
    // Each lane's class: its octant, kz and the swap; a group walks one class at a time.
    let one = L::splat(1.0);
    let bit = |m: L::Mask, v: f32| L::select(m, L::splat(v), zero);
    let class = bit(neg[0], 1.0) + bit(neg[1], 2.0) + bit(neg[2], 4.0) + bit(z1, 8.0) + bit(!z0 & !z1, 16.0) + bit(swap, 32.0) + one;
    let mut classes = [0.0; MAX_WIDTH];
    L::select(root, class, zero).store(&mut classes);
    let mut done = [false; MAX_WIDTH];
    for j in 0..n {
        if classes[j] == 0.0 || done[j] {
            continue;
        }
        let c = classes[j];
        let lanes: [bool; MAX_WIDTH] = std::array::from_fn(|l| l >= j && l < n && classes[l] == c);
        for (l, &x) in lanes.iter().enumerate() {
            done[l] |= x;
        }
        let c = c as usize - 1;
        let octant = c & 7;
        let kz = (c >> 3 & 1) + 2 * (c >> 4 & 1);
        let (kx, ky) = if c >> 5 & 1 == 1 { ((kz + 2) % 3, (kz + 1) % 3) } else { ((kz + 1) % 3, (kz + 2) % 3) };
        let live = mask::<L>(&lanes);
        if tree.depth <= SHALLOW {
            walk::<L, ANY, STACK_SHALLOW>(tree, packet, &rays, live, octant, [kx, ky, kz], first, out);
        } else {
            walk::<L, ANY, STACK_DEEP>(tree, packet, &rays, live, octant, [kx, ky, kz], first, out);
        }
    }
}

/// One entry of a group's traversal stack: a child, where its box is (for the test repeated
/// when a closer hit was found since), and the lanes that entered it.
#[derive(Clone, Copy)]
struct Entry<M> {
    /// The child's reference.
    child: u32,
    /// Its parent node and slot (`u32::MAX` for the root).
    parent: u32,
    /// Its slot in the parent.
    slot: u32,
    /// The lanes whose box test passed.
    lanes: M,
}

/// The lanes (of `live`) whose ray meets the box of slot `slot` of `node` for t in
/// [0, t_cap], in octant `octant`: `SlabRay::hits` per lane, with its entry distance.
#[inline(always)]
fn box_lanes<L: Lanes>(rays: &Rays<L>, lo: [f32; 3], hi: [f32; 3], octant: usize, t_cap: L) -> (L::Mask, L) {
    let slab = |p: f32, a: usize| (L::splat(p) - rays.o[a]) * rays.inv[a];
    let near = |a: usize| if octant >> a & 1 == 1 { hi[a] } else { lo[a] };
    let far = |a: usize| if octant >> a & 1 == 1 { lo[a] } else { hi[a] };
    let zero = L::splat(0.0);
    let t_near = max_keep(slab(near(2), 2), max_keep(slab(near(1), 1), max_keep(slab(near(0), 0), zero)));
    let t_far = min_keep(slab(far(2), 2), min_keep(slab(far(1), 1), min_keep(slab(far(0), 0), t_cap)));
    (t_near.le(t_far * L::splat(ULPS2)) & t_near.lt(L::splat(f32::INFINITY)), t_near)
}

/// Slot `slot`'s box in `node`: (low, high).
#[inline(always)]
fn slot_box(node: &Node8, slot: usize) -> ([f32; 3], [f32; 3]) {
    let p = &node.planes;
    ([p[0][slot], p[2][slot], p[4][slot]], [p[1][slot], p[3][slot], p[5][slot]])
}

/// Traversal stack entries for trees up to [`SHALLOW`] deep: up to seven siblings per
/// level, plus a node's eight children before one is popped.
const STACK_SHALLOW: usize = (WIDTH - 1) * SHALLOW + WIDTH;
/// Traversal stack entries for any tree the build makes (below 64 deep).
const STACK_DEEP: usize = (WIDTH - 1) * 64 + WIDTH;

/// The depth-first walk of one class of lanes `live` (octant `octant`, axes `k`), with a
/// stack of `N` entries.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn walk<L: Lanes, const ANY: bool, const N: usize>(
    tree: &Wide,
    packet: &RayPacket,
    rays: &Rays<L>,
    live: L::Mask,
    octant: usize,
    k: [usize; 3],
    first: usize,
    out: &mut [Option<TriHit>; MAX_WIDTH],
) {
    let n = L::WIDTH;
    let none = L::mask(false);
    // `live` met the root box.
    let mut cur = Entry { child: tree.root, parent: u32::MAX, slot: 0, lanes: live };
    let has_skip = (0..n).any(|j| !packet.skip[first + j].is_empty());
    // Closest hits so far: t (t_max where none), the triangle's index bits, b1, b2.
    let mut best_t = rays.t_max;
    let mut best_id = L::splat(f32::from_bits(u32::MAX));
    let mut best_b1 = L::splat(0.0);
    let mut best_b2 = L::splat(0.0);
    // Any-hit: the lanes that found one.
    let mut hit_any = none;
    let mut stack = [Entry { child: 0, parent: 0, slot: 0, lanes: none }; N];
    let mut sp = 0;
    loop {
        let lanes = cur.lanes;
        if cur.child & LEAF == 0 {
            let node = &tree.nodes[cur.child as usize];
            let order = node.order[octant];
            let valid = Node8::valid(order);
            // Children in reverse visiting order, so they pop in order.
            for kk in (0..WIDTH).rev() {
                let slot = Node8::slot(order, kk);
                if valid >> slot & 1 == 0 {
                    continue;
                }
                let (lo, hi) = slot_box(node, slot);
                let (m, _) = box_lanes(rays, lo, hi, octant, best_t);
                let m = m & lanes;
                if L::any(m) {
                    stack[sp] = Entry { child: node.child[slot], parent: cur.child, slot: slot as u32, lanes: m };
                    sp += 1;
                }
            }
        } else {
            let block = &tree.blocks[(cur.child & !LEAF) as usize];
            for lane in 0..LANES {
                let id = block.ids[lane];
                if id == u32::MAX {
                    continue;
                }
                let (mut hit, t, b1, b2) = triangle(rays, block, lane, k, lanes, first, packet);
                if has_skip {
                    let skipped: [bool; MAX_WIDTH] = std::array::from_fn(|j| j < n && packet.skip[first + j].contains(&id));
                    hit = hit & !mask::<L>(&skipped);
                }
                if !L::any(hit) {
                    continue;
                }
                if ANY {
                    hit_any = hit_any | hit;
                    continue;
                }
                // The smaller (t, index) wins; a tie in t (rare) compares indices lane by lane.
                let mut better = hit & t.lt(best_t);
                let tie = hit & !t.ne(best_t);
                if L::any(tie) {
                    let mut ids = [0.0; MAX_WIDTH];
                    best_id.store(&mut ids);
                    let tie = bools::<L>(tie);
                    let smaller: [bool; MAX_WIDTH] = std::array::from_fn(|j| tie[j] && id < ids[j].to_bits());
                    better = better | mask::<L>(&smaller);
                }
                best_t = L::select(better, t, best_t);
                best_id = L::select(better, L::splat(f32::from_bits(id)), best_id);
                best_b1 = L::select(better, b1, best_b1);
                best_b2 = L::select(better, b2, best_b2);
            }
            if ANY && !L::any(live & !hit_any) {
                break;
            }
        }
        // Pop the next child with lanes left: lanes that found a hit are done (any hit), and
        // a box is tested again with each lane's best hit (closest hit), which is the single
        // ray's test of the entry distance it stored against its smaller t_max.
        let mut next = None;
        while sp > 0 {
            sp -= 1;
            let e = stack[sp];
            let m = if ANY {
                e.lanes & !hit_any
            } else {
                let node = &tree.nodes[e.parent as usize];
                let (lo, hi) = slot_box(node, e.slot as usize);
                e.lanes & box_lanes(rays, lo, hi, octant, best_t).0
            };
            if L::any(m) {
                next = Some(Entry { lanes: m, ..e });
                break;
            }
        }
        match next {
            Some(e) => cur = e,
            None => break,
        }
    }
    let lanes = bools::<L>(live);
    if ANY {
        let hit = bools::<L>(hit_any);
        for j in 0..n {
            if lanes[j] && hit[j] {
                out[first + j] = Some(TriHit { t: 0.0, tri: 0, b1: 0.0, b2: 0.0 });
            }
        }
        return;
    }
    let (mut t, mut id, mut b1, mut b2) = ([0.0; MAX_WIDTH], [0.0; MAX_WIDTH], [0.0; MAX_WIDTH], [0.0; MAX_WIDTH]);
    best_t.store(&mut t);
    best_id.store(&mut id);
    best_b1.store(&mut b1);
    best_b2.store(&mut b2);
    for j in 0..n {
        if lanes[j] && id[j].to_bits() != u32::MAX {
            out[first + j] = Some(TriHit { t: t[j], tri: id[j].to_bits(), b1: b1[j], b2: b2[j] });
        }
    }
}

/// The lanes (of `lanes`) whose ray hits triangle `lane` of `block` for t in (0, t_max),
/// with (t, b1, b2): [`intersect`]'s arithmetic per lane, with the axes `k` every lane shares.
#[inline(always)]
fn triangle<L: Lanes>(
    rays: &Rays<L>,
    block: &Block,
    lane: usize,
    k: [usize; 3],
    lanes: L::Mask,
    first: usize,
    packet: &RayPacket,
) -> (L::Mask, L, L, L) {
    let [kx, ky, kz] = k;
    let [sx, sy, sz] = rays.s;
    let rel = |v: usize, axis: usize| L::splat(block.v[v][axis][lane]) - rays.o[axis];
    let (a_x, a_y, a_z) = (rel(0, kx), rel(0, ky), rel(0, kz));
    let (b_x, b_y, b_z) = (rel(1, kx), rel(1, ky), rel(1, kz));
    let (c_x, c_y, c_z) = (rel(2, kx), rel(2, ky), rel(2, kz));
    let (ax, ay) = (a_x - sx * a_z, a_y - sy * a_z);
    let (bx, by) = (b_x - sx * b_z, b_y - sy * b_z);
    let (cx, cy) = (c_x - sx * c_z, c_y - sy * c_z);
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    let zero = L::splat(0.0);
    // Exactly 0: not (x ≠ 0), false for NaN as `==` is.
    let exact_zero = lanes & (!u.ne(zero) | !v.ne(zero) | !w.ne(zero));
    let inside = (zero.le(u) & zero.le(v) & zero.le(w)) | (u.le(zero) & v.le(zero) & w.le(zero));
    let det = u + v + w;
    let t_scaled = u * (sz * a_z) + v * (sz * b_z) + w * (sz * c_z);
    let neg = det.lt(zero);
    let (t_abs, det_abs) = (L::select(neg, -t_scaled, t_scaled), L::select(neg, -det, det));
    let rcp = L::splat(1.0) / det;
    let t = t_scaled * rcp;
    let ok = lanes & !exact_zero & inside & det.ne(zero) & zero.lt(t_abs) & t_abs.lt(rays.t_max * det_abs) & zero.lt(t) & t.lt(rays.t_max);
    let (mut b1, mut b2) = (v * rcp, w * rcp);
    if !L::any(exact_zero) {
        return (ok, t, b1, b2);
    }
    // Lanes with an edge function of exactly 0: the scalar test, with its f64 fallback.
    let zeros = bools::<L>(exact_zero);
    let mut ok_b = bools::<L>(ok);
    let (mut tv, mut b1v, mut b2v) = ([0.0; MAX_WIDTH], [0.0; MAX_WIDTH], [0.0; MAX_WIDTH]);
    t.store(&mut tv);
    b1.store(&mut b1v);
    b2.store(&mut b2v);
    let vertex = |i: usize| Vec3::new(block.v[i][0][lane], block.v[i][1][lane], block.v[i][2][lane]);
    for j in 0..L::WIDTH {
        if !zeros[j] {
            continue;
        }
        let i = first + j;
        match intersect(&RayPrecomp::new(packet.dir(i)), packet.origin(i), vertex(0), vertex(1), vertex(2), packet.t_max[i]) {
            Some((tl, b1l, b2l)) => {
                (tv[j], b1v[j], b2v[j]) = (tl, b1l, b2l);
                ok_b[j] = true;
            }
            None => ok_b[j] = false,
        }
    }
    b1 = L::load(&b1v);
    b2 = L::load(&b2v);
    (mask::<L>(&ok_b), L::load(&tv), b1, b2)
}
