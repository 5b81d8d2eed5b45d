//! One ray through the wide tree: a node's eight boxes in two four-lane slab tests, a
//! leaf's four triangles in one four-lane watertight test.
//!
//! Both lane tests are the scalar tests' IEEE operations in the scalar order (no FMA, no
//! reciprocal approximation), lane by lane, so every box and triangle gets the bits the
//! scalar code gives it: the slab test is [`SlabRay::hits`] and the triangle test is
//! [`intersect`], which also runs a lane whose edge function came out exactly 0 (its f64
//! fallback). The lanes are `wide::f32x4`: SSE on x86-64, where every x86-64 CPU has it,
//! and a portable fallback elsewhere.

use super::wide::{Block, LANES, LEAF, Node8, WIDTH, Wide};
use super::{Isa, TriHit};
use crate::geometry::triangle::{RayPrecomp, intersect};
use crate::simd::lanes::{LaneTask, Lanes};
use glam::Vec3;
use std::cell::OnceCell;
use std::ops::Range;
use wide::f32x4;

/// The deepest wide tree the small stack serves (the common case: cheaper to set up).
pub(super) const SHALLOW: usize = 10;
/// Traversal stack entries for trees up to [`SHALLOW`] deep: each node on the path leaves at
/// most seven siblings, and the last writes all eight children before one is popped.
const STACK_SHALLOW: usize = (WIDTH - 1) * SHALLOW + WIDTH;
/// Traversal stack entries for any tree the build makes (the wide tree is no deeper than
/// the binary one, below 64).
const STACK_DEEP: usize = (WIDTH - 1) * 64 + WIDTH;

/// Calls `$f::<$n, OCT>($args)` for the octant `$oct` (a constant in the callee).
macro_rules! by_octant {
    ($oct:expr, $f:ident::<$n:ident>($($a:expr),*)) => {
        match $oct {
            0 => $f::<$n, 0>($($a),*),
            1 => $f::<$n, 1>($($a),*),
            2 => $f::<$n, 2>($($a),*),
            3 => $f::<$n, 3>($($a),*),
            4 => $f::<$n, 4>($($a),*),
            5 => $f::<$n, 5>($($a),*),
            6 => $f::<$n, 6>($($a),*),
            _ => $f::<$n, 7>($($a),*),
        }
    };
}

/// 1 + 2 ulps: Ize's enlargement of the far distance (`SlabRay::hits`).
const ULPS2: f32 = 1.0 + 2.0 * f32::EPSILON;

/// A ray prepared for slab tests (the scalar test of the root box, and the reference).
#[derive(Debug, Clone, Copy)]
pub(super) struct SlabRay {
    /// Origin.
    pub o: Vec3,
    /// 1/dir per component (±∞ for a zero component).
    pub inv: Vec3,
    /// Whether each component of 1/dir is negative (then a slab is entered at its max).
    pub neg: [bool; 3],
}

impl SlabRay {
    /// Prepares `origin + t·dir`.
    #[inline(always)]
    pub fn new(origin: Vec3, dir: Vec3) -> SlabRay {
        // The three divisions in one instruction (glam's `recip` is three in a row, and was
        // a fifth of a shadow ray's time); each lane is the correctly rounded 1/dir.
        let [x, y, z, _] = (f32x4::ONE / f32x4::new([dir.x, dir.y, dir.z, 1.0])).to_array();
        let inv = Vec3::new(x, y, z);
        SlabRay { o: origin, inv, neg: [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0] }
    }

    /// The octant: bit a set when the ray goes down axis a.
    #[inline(always)]
    pub fn octant(&self) -> usize {
        self.neg[0] as usize | (self.neg[1] as usize) << 1 | (self.neg[2] as usize) << 2
    }

    /// Whether the ray meets the box `min..max` for some t in [0, t_max] (conservatively).
    #[inline(always)]
    pub fn hits(&self, min: Vec3, max: Vec3, t_max: f32) -> bool {
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
        let (nx, fx) = pick(self.neg[0], min.x, max.x);
        let (ny, fy) = pick(self.neg[1], min.y, max.y);
        let (nz, fz) = pick(self.neg[2], min.z, max.z);
        let t_near =
            max_keep((nz - self.o.z) * self.inv.z, max_keep((ny - self.o.y) * self.inv.y, max_keep((nx - self.o.x) * self.inv.x, 0.0)));
        let t_far =
            min_keep((fz - self.o.z) * self.inv.z, min_keep((fy - self.o.y) * self.inv.y, min_keep((fx - self.o.x) * self.inv.x, t_max)));
        // Ize 2013, §3: enlarging the far distance by 2 ulps covers the rounding of all three
        // slabs. A t_near of +∞ (a zero direction component outside its slab) is a miss even
        // when t_max is +∞.
        t_near <= t_far * ULPS2 && t_near < f32::INFINITY
    }
}

/// Whether the ray `o + t·dir` starts outside the box `min..max` on some axis and does not
/// move towards it there: then [`SlabRay::hits`] is false, and this answers without the
/// division.
///
/// Past the max by at least 2⁻⁶⁰ with 0 ≤ dir ≤ 2⁶⁰: for dir = +0, 1/dir = +∞ and the far
/// slab distance is −∞; for dir = −0, 1/dir = −∞ and the near one is +∞; otherwise
/// 1/dir ≥ 2⁻⁶⁰ and the far distance (max − o)/dir ≤ −2⁻¹²⁰ cannot round to −0. A
/// negative far distance caps t_far below t_near ≥ 0. Below the min likewise. (Without the
/// bounds an infinite dir or an underflow gives a far distance of −0, which the slab test
/// takes as a hit at t = 0.) A NaN fails every comparison.
#[inline(always)]
pub(super) fn moves_away(o: Vec3, dir: Vec3, min: Vec3, max: Vec3) -> bool {
    const GAP: f32 = 1.0 / (1u64 << 60) as f32;
    const FAST: f32 = (1u64 << 60) as f32;
    // Component by component: loading the Vec3s as vectors measured 2.8 → 10 ns a ray.
    let axis = |o: f32, d: f32, lo: f32, hi: f32| {
        let past = o - hi >= GAP && (0.0..=FAST).contains(&d);
        let before = lo - o >= GAP && (-FAST..=0.0).contains(&d);
        past || before
    };
    axis(o.x, dir.x, min.x, max.x) || axis(o.y, dir.y, min.y, max.y) || axis(o.z, dir.z, min.z, max.z)
}

/// `x > acc ? x : acc` per lane: the scalar `max_keep` (a NaN `x` keeps `acc`).
#[inline(always)]
fn max_keep(x: f32x4, acc: f32x4) -> f32x4 {
    // SSE's maxps is exactly `x > acc ? x : acc`.
    #[cfg(target_arch = "x86_64")]
    return x.fast_max(acc);
    #[cfg(not(target_arch = "x86_64"))]
    return x.simd_gt(acc).bitselect(x, acc);
}

/// `x < acc ? x : acc` per lane: the scalar `min_keep`.
#[inline(always)]
fn min_keep(x: f32x4, acc: f32x4) -> f32x4 {
    // SSE's minps is exactly `x < acc ? x : acc`.
    #[cfg(target_arch = "x86_64")]
    return x.fast_min(acc);
    #[cfg(not(target_arch = "x86_64"))]
    return x.simd_lt(acc).bitselect(x, acc);
}

/// A ray prepared for the four-lane tests.
#[derive(Debug, Clone)]
pub(super) struct Ray4 {
    /// The scalar ray.
    pub slab: SlabRay,
    /// Origin, each component in every lane.
    o: [f32x4; 3],
    /// 1/dir, each component in every lane.
    inv: [f32x4; 3],
    /// The octant ([`SlabRay::octant`]).
    pub octant: usize,
    /// The direction.
    dir: Vec3,
    /// The watertight test's constants, made at the first leaf (many rays meet none).
    tri: OnceCell<Shear>,
}

/// The watertight test's constants of a ray.
#[derive(Debug, Clone, Copy)]
struct Shear {
    /// As [`intersect`] takes them.
    pre: RayPrecomp,
    /// The axes kx, ky, kz.
    k: [usize; 3],
    /// The shear sx, sy, sz in every lane.
    s: [f32x4; 3],
}

impl Ray4 {
    /// Prepares `slab`'s ray with direction `dir` for the lanes.
    #[inline(always)]
    pub fn new(slab: SlabRay, dir: Vec3) -> Ray4 {
        let splat3 = |v: [f32; 3]| v.map(f32x4::splat);
        Ray4 { slab, o: splat3(slab.o.to_array()), inv: splat3(slab.inv.to_array()), octant: slab.octant(), dir, tri: OnceCell::new() }
    }

    /// The watertight test's constants.
    #[inline(always)]
    fn shear(&self) -> &Shear {
        self.tri.get_or_init(|| {
            let pre = RayPrecomp::new(self.dir);
            let (k, s) = pre.parts();
            Shear { pre, k, s: s.map(f32x4::splat) }
        })
    }

    /// Which of `node`'s boxes the ray meets for t in [0, t_cap] (bit k for slot k), with
    /// each box's entry distance: [`SlabRay::hits`] in lanes, for a ray in octant `OCT`
    /// (a constant, so the near and far planes are fixed offsets). The two halves are
    /// independent, so they run side by side.
    #[inline(always)]
    pub fn boxes<const OCT: usize>(&self, node: &Node8, t_cap: f32x4) -> (u32, [f32x4; 2]) {
        debug_assert_eq!(OCT, self.octant);
        let half = |h: usize| {
            let plane = |i: usize| f32x4::new(node.planes[i].as_chunks::<4>().0[h]);
            let slab = |axis: usize, i: usize| (plane(i) - self.o[axis]) * self.inv[axis];
            let neg = |axis: usize| (OCT >> axis) & 1;
            let t_near = max_keep(slab(2, 4 + neg(2)), max_keep(slab(1, 2 + neg(1)), max_keep(slab(0, neg(0)), f32x4::ZERO)));
            let t_far = min_keep(slab(2, 5 - neg(2)), min_keep(slab(1, 3 - neg(1)), min_keep(slab(0, 1 - neg(0)), t_cap)));
            let hit = t_near.simd_le(t_far * f32x4::splat(ULPS2)) & t_near.simd_lt(f32x4::splat(f32::INFINITY));
            (hit.to_bitmask(), t_near)
        };
        let (lo, near_lo) = half(0);
        let (hi, near_hi) = half(1);
        ((lo | hi << 4) & Node8::valid(node.order[OCT]), [near_lo, near_hi])
    }

    /// The hits of the ray with `block`'s triangles for t in (0, t_max): a bit per lane and
    /// each lane's (t, b1, b2), as [`intersect`] gives them.
    #[inline(always)]
    pub fn triangles(&self, block: &Block, t_max: f32) -> (u32, [f32; LANES], [f32; LANES], [f32; LANES]) {
        let shear = self.shear();
        let [kx, ky, kz] = shear.k;
        let [sx, sy, sz] = shear.s;
        // Vertices relative to the origin, permuted (Woop et al. Fig. 2), then sheared.
        let rel = |v: usize, axis: usize| f32x4::new(block.v[v][axis]) - self.o[axis];
        let (a_x, a_y, a_z) = (rel(0, kx), rel(0, ky), rel(0, kz));
        let (b_x, b_y, b_z) = (rel(1, kx), rel(1, ky), rel(1, kz));
        let (c_x, c_y, c_z) = (rel(2, kx), rel(2, ky), rel(2, kz));
        let (ax, ay) = (a_x - sx * a_z, a_y - sy * a_z);
        let (bx, by) = (b_x - sx * b_z, b_y - sy * b_z);
        let (cx, cy) = (c_x - sx * c_z, c_y - sy * c_z);
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let zero = f32x4::ZERO;
        let exact_zero = (u.simd_eq(zero) | v.simd_eq(zero) | w.simd_eq(zero)).to_bitmask();
        let inside = (u.simd_ge(zero) & v.simd_ge(zero) & w.simd_ge(zero)) | (u.simd_le(zero) & v.simd_le(zero) & w.simd_le(zero));
        let mut t = [0.0; LANES];
        let mut b1 = [0.0; LANES];
        let mut b2 = [0.0; LANES];
        let mut hits = 0;
        if inside.to_bitmask() & !exact_zero != 0 {
            let det = u + v + w;
            let t_scaled = u * (sz * a_z) + v * (sz * b_z) + w * (sz * c_z);
            let neg = det.simd_lt(zero);
            let (t_abs, det_abs) = (neg.bitselect(-t_scaled, t_scaled), neg.bitselect(-det, det));
            let t_max4 = f32x4::splat(t_max);
            let rcp = f32x4::ONE / det;
            let tt = t_scaled * rcp;
            let ok =
                inside & det.simd_ne(zero) & t_abs.simd_gt(zero) & t_abs.simd_lt(t_max4 * det_abs) & tt.simd_gt(zero) & tt.simd_lt(t_max4);
            hits = ok.to_bitmask() & !exact_zero;
            if hits != 0 {
                t = tt.to_array();
                b1 = (v * rcp).to_array();
                b2 = (w * rcp).to_array();
            }
        }
        // A lane with an edge function of exactly 0: the scalar test, with its f64 fallback.
        let mut rest = exact_zero;
        while rest != 0 {
            let lane = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let vertex = |k: usize| Vec3::new(block.v[k][0][lane], block.v[k][1][lane], block.v[k][2][lane]);
            if let Some((tl, b1l, b2l)) = intersect(&shear.pre, self.slab.o, vertex(0), vertex(1), vertex(2), t_max) {
                (t[lane], b1[lane], b2[lane]) = (tl, b1l, b2l);
                hits |= 1 << lane;
            }
        }
        (hits, t, b1, b2)
    }
}

/// The lanes of `block` whose triangle is in `skip`.
#[inline(always)]
pub(super) fn skipped(block: &Block, skip: &Range<u32>) -> u32 {
    if skip.is_empty() {
        return 0;
    }
    (0..LANES).fold(0, |m, lane| m | (skip.contains(&block.ids[lane]) as u32) << lane)
}

/// The stack size for `tree`.
#[inline(always)]
fn shallow(tree: &Wide) -> bool {
    tree.depth <= SHALLOW
}

/// Whether a triangle not in `skip` lies along `origin + t·dir` for t in (0, t_max).
// Inlined into the caller, with the early exits: out of line, the arguments went through
// memory and their reload waited on the caller's stores (2.8 → 9 ns a ray that stops here).
#[inline]
pub(super) fn occluded(tree: &Wide, isa: Isa, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> bool {
    if tree.blocks.is_empty() || moves_away(origin, dir, tree.bounds.0, tree.bounds.1) {
        return false;
    }
    let slab = SlabRay::new(origin, dir);
    if !slab.hits(tree.bounds.0, tree.bounds.1, t_max) {
        return false;
    }
    let ray = Ray4::new(slab, dir);
    let hit = if shallow(tree) {
        by_octant!(ray.octant, run_walk::<STACK_SHALLOW>(isa, Walk { tree, ray: &ray, t_max, skip: &skip, any: true }))
    } else {
        by_octant!(ray.octant, run_walk::<STACK_DEEP>(isa, Walk { tree, ray: &ray, t_max, skip: &skip, any: true }))
    };
    hit.is_some()
}

/// [`occluded`] once the root box is met, for a ray in octant `OCT`.
#[inline(always)]
fn occluded_from<const N: usize, const OCT: usize>(tree: &Wide, ray: &Ray4, t_max: f32, skip: &Range<u32>) -> bool {
    let t_cap = f32x4::splat(t_max);
    let mut stack = [0u32; N];
    let mut sp = 0;
    let mut cur = tree.root;
    loop {
        if cur & LEAF == 0 {
            let node = &tree.nodes[cur as usize];
            let (hit, _) = ray.boxes::<OCT>(node, t_cap);
            if hit & hit.wrapping_sub(1) == 0 {
                // None or one box hit (the usual case): no order to follow.
                if hit != 0 {
                    cur = node.child[hit.trailing_zeros() as usize];
                    continue;
                }
            } else {
                // Every child is written, in reverse visiting order, and kept (sp moves on)
                // when its box is hit.
                let order = node.order[OCT];
                for k in (0..WIDTH).rev() {
                    let s = Node8::slot(order, k);
                    stack[sp] = node.child[s];
                    sp += (hit >> s) as usize & 1;
                }
            }
        } else {
            let block = &tree.blocks[(cur & !LEAF) as usize];
            let (hits, ..) = ray.triangles(block, t_max);
            if hits & !skipped(block, skip) != 0 {
                return true;
            }
        }
        if sp == 0 {
            return false;
        }
        sp -= 1;
        cur = stack[sp];
    }
}

/// One ray's walk below the root, as a lane task: a CPU-feature token runs it compiled for
/// its instruction set (VEX or EVEX encodings: three-operand instructions and, with
/// AVX-512, sixteen more registers, so fewer copies and spills). It uses no lane type; its
/// arithmetic is the same SSE-width IEEE operations whatever the encoding.
#[derive(Clone, Copy)]
pub(super) struct Walk<'a, const N: usize, const OCT: usize> {
    /// The tree.
    tree: &'a Wide,
    /// The ray.
    ray: &'a Ray4,
    /// Its t_max.
    t_max: f32,
    /// Its skipped triangles.
    skip: &'a Range<u32>,
    /// Any hit (`occluded`), else the closest.
    any: bool,
}

impl<const N: usize, const OCT: usize> LaneTask for Walk<'_, N, OCT> {
    type Output = Option<TriHit>;

    // Inlined into the token's `#[target_feature]` function.
    #[inline(always)]
    fn run<W: Lanes, H: Lanes>(self) -> Option<TriHit> {
        if self.any {
            // `occluded` needs only whether: any hit stands for it.
            occluded_from::<N, OCT>(self.tree, self.ray, self.t_max, self.skip).then_some(TriHit { t: 0.0, tri: 0, b1: 0.0, b2: 0.0 })
        } else {
            closest_from::<N, OCT>(self.tree, self.ray, self.t_max, self.skip)
        }
    }
}

/// Runs `walk` (octant `OCT`, a stack of `N`) with `isa`, out of line.
#[inline(never)]
fn run_walk<const N: usize, const OCT: usize>(isa: Isa, walk: Walk<'_, N, OCT>) -> Option<TriHit> {
    isa.run(walk)
}

/// The nearest hit not in `skip` along `origin + t·dir` for t in (0, t_max): the smallest
/// (t, triangle index).
#[inline]
pub(super) fn closest(tree: &Wide, isa: Isa, origin: Vec3, dir: Vec3, t_max: f32, skip: Range<u32>) -> Option<TriHit> {
    if tree.blocks.is_empty() || moves_away(origin, dir, tree.bounds.0, tree.bounds.1) {
        return None;
    }
    let slab = SlabRay::new(origin, dir);
    if !slab.hits(tree.bounds.0, tree.bounds.1, t_max) {
        return None;
    }
    let ray = Ray4::new(slab, dir);
    if shallow(tree) {
        by_octant!(ray.octant, run_walk::<STACK_SHALLOW>(isa, Walk { tree, ray: &ray, t_max, skip: &skip, any: false }))
    } else {
        by_octant!(ray.octant, run_walk::<STACK_DEEP>(isa, Walk { tree, ray: &ray, t_max, skip: &skip, any: false }))
    }
}

/// Keeps in `best` the smaller of it and lane hits `hits` of `block` by (t, index).
#[inline(always)]
pub(super) fn keep_nearest(best: &mut Option<TriHit>, block: &Block, hits: u32, t: &[f32; LANES], b1: &[f32; LANES], b2: &[f32; LANES]) {
    let mut rest = hits;
    while rest != 0 {
        let lane = rest.trailing_zeros() as usize;
        rest &= rest - 1;
        let (tl, id) = (t[lane], block.ids[lane]);
        if best.is_none_or(|b| tl < b.t || (tl == b.t && id < b.tri)) {
            *best = Some(TriHit { t: tl, tri: id, b1: b1[lane], b2: b2[lane] });
        }
    }
}

/// [`closest`] once the root box is met, for a ray in octant `OCT`.
#[inline(always)]
fn closest_from<const N: usize, const OCT: usize>(tree: &Wide, ray: &Ray4, t_max: f32, skip: &Range<u32>) -> Option<TriHit> {
    let mut best: Option<TriHit> = None;
    // Boxes are tested up to the best hit so far; triangles up to t_max, so each
    // triangle's answer (t, b1, b2) does not depend on the order of the visits.
    let mut t_cap = f32x4::splat(t_max);
    let mut t_best = t_max;
    let mut stack = [(0u32, 0f32); N];
    let mut sp = 0;
    let mut cur = tree.root;
    loop {
        if cur & LEAF == 0 {
            let node = &tree.nodes[cur as usize];
            let (hit, t_near) = ray.boxes::<OCT>(node, t_cap);
            if hit & hit.wrapping_sub(1) == 0 {
                // None or one box hit: no order to follow, and nothing to test again.
                if hit != 0 {
                    cur = node.child[hit.trailing_zeros() as usize];
                    continue;
                }
            } else {
                let mut near = [0.0; WIDTH];
                near[..4].copy_from_slice(&t_near[0].to_array());
                near[4..].copy_from_slice(&t_near[1].to_array());
                // As in `occluded_from`, with each box's entry distance.
                let order = node.order[OCT];
                for k in (0..WIDTH).rev() {
                    let s = Node8::slot(order, k);
                    stack[sp] = (node.child[s], near[s]);
                    sp += (hit >> s) as usize & 1;
                }
            }
        } else {
            let block = &tree.blocks[(cur & !LEAF) as usize];
            let (hits, t, b1, b2) = ray.triangles(block, t_max);
            let hits = hits & !skipped(block, skip);
            if hits != 0 {
                keep_nearest(&mut best, block, hits, &t, &b1, &b2);
                if let Some(b) = best {
                    t_best = b.t;
                    t_cap = f32x4::splat(t_best);
                }
            }
        }
        // Pop, dropping boxes entered beyond the best hit found since they were pushed: the
        // test they passed, repeated with the smaller t_max (the far side is unchanged).
        loop {
            if sp == 0 {
                return best;
            }
            sp -= 1;
            let (c, t_near) = stack[sp];
            if t_near <= t_best * ULPS2 {
                cur = c;
                break;
            }
        }
    }
}
