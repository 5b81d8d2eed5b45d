//! Lanes: the classic equation written once, evaluated for one point (`f32`), for four
//! points at once ([`F32x4`]) or, on CPUs with AVX or AVX-512F, eight or sixteen
//! (`simd::avx`, `simd::avx512`, run through a [`LaneTask`]).
//!
//! [`Lanes`] is the handful of operations the classic terms need (arithmetic, square root,
//! comparisons into a mask, select, the deterministic [`pow`](super::pow)); [`V3`] is a
//! 3-vector of lanes with glam's `Vec3` operations in glam's evaluation order, so the
//! `f32` instance computes exactly what glam computes. [`F32x4`] is one SSE2 register
//! (baseline x86-64; no FMA); lane-wise IEEE arithmetic gives the same bits as the scalar
//! instance (tested at every width this CPU has, four, eight and sixteen, in
//! `shading/classic.rs`: `every_lane_width_gives_the_scalar_bits`, and `scene/light.rs`).
//!
//! Control flow becomes masks: where the scalar code skips work (`if n·l > 0`), the lane
//! code computes the term and keeps it only in lanes whose mask is set, and skips it
//! entirely when no lane needs it ([`Lanes::any`]), as the scalar code does.
//!
//! Measured with callgrind on `shadelab --threads 1 bench --workload sphere --frames 1
//! --warmup 0` (three 1024² frames: render, image, PNG): 2.48e9 instructions with the
//! scalar path and glibc `powf`, 1.38e9 with these lanes (and the row filter and develop
//! of render/pipeline/ and develop.rs). Eight lanes as `[f32; 8]` loops were worse than four
//! (register spills: 8.6e8 vs 7.5e8 instructions in the batch shader), and auto-vectorized
//! `[f32; 4]` loops worse than `wide` (7.3e8 vs 5.5e8). Eight lanes in AVX registers
//! (`__m256`, no spills) pay: measured in docs/performance.md.

use glam::Vec3;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Code written once over its lanes, which a CPU-feature token runs at the widths it proves
/// this CPU runs (`avx::Avx::run`, `avx512::Avx512::run`).
///
/// This is the only way to reach the AVX lane types: they cannot be named outside
/// [`crate::simd`], so generic code gets them only as `W` and `H` here. The impl should be
/// `#[inline(always)]`, so it is compiled with the token's features.
pub trait LaneTask {
    /// What the task returns.
    type Output;
    /// Runs with bundles of `W` lanes and, for what is left, of `H` (no wider than `W`).
    fn run<W: Lanes, H: Lanes>(self) -> Self::Output;
}

/// The operations the classic terms need, for one value or for a bundle of lanes.
pub trait Lanes: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self> {
    /// One boolean per lane.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    /// Number of lanes (at most [`MAX_WIDTH`]).
    const WIDTH: usize;
    /// Every lane `x`.
    fn splat(x: f32) -> Self;
    /// Lanes from the first `WIDTH` values of `s` (precondition: `s.len() >= WIDTH`).
    fn load(s: &[f32]) -> Self;
    /// Writes the lanes to the first `WIDTH` values of `out` (precondition: `out.len() >= WIDTH`).
    fn store(self, out: &mut [f32]);
    /// The first `n` lanes set (all of them when `n >= WIDTH`).
    fn first(n: usize) -> Self::Mask;
    /// Every lane `b`.
    fn mask(b: bool) -> Self::Mask;
    /// Square root per lane.
    fn sqrt(self) -> Self;
    /// `self < o` per lane (false for NaN).
    fn lt(self, o: Self) -> Self::Mask;
    /// `self <= o` per lane (false for NaN).
    fn le(self, o: Self) -> Self::Mask;
    /// `self > o` per lane (false for NaN).
    fn gt(self, o: Self) -> Self::Mask;
    /// `self != o` per lane (true for NaN).
    fn ne(self, o: Self) -> Self::Mask;
    /// Finite per lane.
    fn is_finite(self) -> Self::Mask;
    /// Each lane truncated toward zero to i32 into the first `WIDTH` values of `out`, as
    /// `x as i32` for lanes in i32's range (`cvttps2dq`).
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]);
    /// `a` where `m` is set, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// x^k per lane with the deterministic [`pow`](super::pow::pow).
    fn pow(self, k: f32) -> Self;
    /// Number of lanes set.
    fn count(m: Self::Mask) -> u64;
    /// True when any lane is set.
    fn any(m: Self::Mask) -> bool;
    /// True when every lane is set.
    fn all(m: Self::Mask) -> bool;
}

impl Lanes for f32 {
    type Mask = bool;
    const WIDTH: usize = 1;
    #[inline(always)]
    fn splat(x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn load(s: &[f32]) -> f32 {
        s[0]
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        out[0] = self;
    }
    #[inline(always)]
    fn first(n: usize) -> bool {
        n > 0
    }

    #[inline(always)]
    fn mask(b: bool) -> bool {
        b
    }
    #[inline(always)]
    fn sqrt(self) -> f32 {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn lt(self, o: f32) -> bool {
        self < o
    }
    #[inline(always)]
    fn le(self, o: f32) -> bool {
        self <= o
    }
    #[inline(always)]
    fn gt(self, o: f32) -> bool {
        self > o
    }
    #[inline(always)]
    fn ne(self, o: f32) -> bool {
        self != o
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline(always)]
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]) {
        out[0] = self as i32;
    }
    #[inline(always)]
    fn select(m: bool, a: f32, b: f32) -> f32 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn pow(self, k: f32) -> f32 {
        super::pow::pow(self, k)
    }
    #[inline(always)]
    fn count(m: bool) -> u64 {
        m as u64
    }
    #[inline(always)]
    fn any(m: bool) -> bool {
        m
    }
    #[inline(always)]
    fn all(m: bool) -> bool {
        m
    }
}

/// Lanes per bundle: one SSE2 register of f32.
pub const WIDTH: usize = 4;

/// The widest bundle of lanes (sixteen, one AVX-512 register), for buffers that serve every width.
pub const MAX_WIDTH: usize = 16;

/// Four f32 lanes in one SSE2 register (the `wide` crate's `f32x4`: baseline x86-64, a
/// portable fallback elsewhere). Every operation is one IEEE-754 instruction per lane with
/// the scalar instruction's rounding (addps/addss, divps/divss, sqrtps/sqrtss), so lanes give
/// the scalar bits; nothing here uses an approximation (no rcpps, no FMA). The `[f32; 4]`
/// loops LLVM auto-vectorized before this scalarized the finiteness tests and rebuilt masks
/// lane by lane.
#[derive(Debug, Clone, Copy)]
pub struct F32x4(wide::f32x4);

/// Four lane masks: all bits set (true) or clear (false), so select is a bitwise blend.
#[derive(Debug, Clone, Copy)]
pub struct M4(wide::f32x4);

impl F32x4 {
    /// Lanes from an array (lane i is `a[i]`).
    #[inline(always)]
    pub fn from_array(a: [f32; WIDTH]) -> F32x4 {
        F32x4(wide::f32x4::new(a))
    }

    /// The lanes as an array.
    #[inline(always)]
    pub fn to_array(self) -> [f32; WIDTH] {
        self.0.to_array()
    }

    /// Each lane truncated toward zero to i32, as `x as i32` for lanes in i32's range
    /// (cvttps2dq).
    #[inline(always)]
    pub fn trunc_i32(self) -> [i32; WIDTH] {
        self.0.trunc_int().to_array()
    }
}

impl M4 {
    /// The first `n` lanes set (a partial bundle).
    #[inline(always)]
    pub fn first(n: usize) -> M4 {
        let lane = wide::i32x4::new([0, 1, 2, 3]);
        M4(wide::bytemuck::cast(lane.simd_lt(wide::i32x4::splat(n as i32))))
    }

    /// One bit per lane (bit i = lane i).
    #[inline(always)]
    pub fn bits(self) -> u32 {
        self.0.to_bitmask()
    }
}

macro_rules! op {
    ($t:ident, $tr:ident, $f:ident, $op:tt) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, b: $t) -> $t {
                $t(self.0 $op b.0)
            }
        }
    };
}
op!(F32x4, Add, add, +);
op!(F32x4, Sub, sub, -);
op!(F32x4, Mul, mul, *);
op!(F32x4, Div, div, /);
op!(M4, BitAnd, bitand, &);
op!(M4, BitOr, bitor, |);

impl Neg for F32x4 {
    type Output = F32x4;
    /// Flips the sign bit, as scalar negation.
    #[inline(always)]
    fn neg(self) -> F32x4 {
        F32x4(-self.0)
    }
}

impl Not for M4 {
    type Output = M4;
    #[inline(always)]
    fn not(self) -> M4 {
        M4(!self.0)
    }
}

impl Lanes for F32x4 {
    type Mask = M4;
    const WIDTH: usize = WIDTH;
    #[inline(always)]
    fn splat(x: f32) -> F32x4 {
        F32x4(wide::f32x4::splat(x))
    }
    #[inline(always)]
    fn load(s: &[f32]) -> F32x4 {
        F32x4::from_array(s[..WIDTH].try_into().expect("four values"))
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        out[..WIDTH].copy_from_slice(&self.to_array());
    }
    #[inline(always)]
    fn first(n: usize) -> M4 {
        M4::first(n)
    }

    #[inline(always)]
    fn mask(b: bool) -> M4 {
        M4(wide::f32x4::splat(f32::from_bits(if b { !0 } else { 0 })))
    }
    #[inline(always)]
    fn sqrt(self) -> F32x4 {
        F32x4(self.0.sqrt())
    }
    #[inline(always)]
    fn lt(self, o: F32x4) -> M4 {
        M4(self.0.simd_lt(o.0))
    }
    #[inline(always)]
    fn le(self, o: F32x4) -> M4 {
        M4(self.0.simd_le(o.0))
    }
    #[inline(always)]
    fn gt(self, o: F32x4) -> M4 {
        M4(self.0.simd_gt(o.0))
    }
    #[inline(always)]
    fn ne(self, o: F32x4) -> M4 {
        M4(self.0.simd_ne(o.0))
    }
    #[inline(always)]
    fn is_finite(self) -> M4 {
        M4(self.0.is_finite())
    }
    #[inline(always)]
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]) {
        out[..WIDTH].copy_from_slice(&F32x4::trunc_i32(self));
    }
    #[inline(always)]
    fn select(m: M4, a: F32x4, b: F32x4) -> F32x4 {
        F32x4(m.0.bitselect(a.0, b.0))
    }
    #[inline(always)]
    fn pow(self, k: f32) -> F32x4 {
        F32x4::from_array(super::pow::pow_lanes(self.to_array(), k))
    }
    #[inline(always)]
    fn count(m: M4) -> u64 {
        m.bits().count_ones() as u64
    }
    #[inline(always)]
    fn any(m: M4) -> bool {
        m.bits() != 0
    }
    #[inline(always)]
    fn all(m: M4) -> bool {
        m.bits() == (1 << WIDTH) - 1
    }
}

/// A 3-vector of lanes with glam's `Vec3` operations, evaluated in glam's order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct V3<F> {
    /// x lanes.
    pub x: F,
    /// y lanes.
    pub y: F,
    /// z lanes.
    pub z: F,
}

impl<F: Lanes> V3<F> {
    /// Every lane `v`.
    #[inline(always)]
    pub fn splat(v: Vec3) -> V3<F> {
        V3 { x: F::splat(v.x), y: F::splat(v.y), z: F::splat(v.z) }
    }

    /// Zero in every lane.
    #[inline(always)]
    pub fn zero() -> V3<F> {
        V3::splat(Vec3::ZERO)
    }

    /// (x·x') + (y·y') + (z·z'), as `Vec3::dot`.
    #[inline(always)]
    pub fn dot(self, o: V3<F>) -> F {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }

    /// Length, as `Vec3::length`.
    #[inline(always)]
    pub fn length(self) -> F {
        self.dot(self).sqrt()
    }

    /// Each component times `s`, as `Vec3 * f32`.
    #[inline(always)]
    pub fn scale(self, s: F) -> V3<F> {
        V3 { x: self.x * s, y: self.y * s, z: self.z * s }
    }

    /// Normalized where 1/length is finite and positive, else `fallback`, as `Vec3::normalize_or`
    /// (and `try_normalize().unwrap_or(fallback)`).
    #[inline(always)]
    pub fn normalize_or(self, fallback: V3<F>) -> V3<F> {
        let rcp = F::splat(1.0) / self.length();
        V3::select_mostly(rcp.is_finite() & rcp.gt(F::splat(0.0)), self.scale(rcp), fallback)
    }

    /// `a` in lanes where `m` is set, else `b`.
    #[inline(always)]
    pub fn select(m: F::Mask, a: V3<F>, b: V3<F>) -> V3<F> {
        V3 { x: F::select(m, a.x, b.x), y: F::select(m, a.y, b.y), z: F::select(m, a.z, b.z) }
    }

    /// [`V3::select`] for masks that are usually all set: one test skips the blend then
    /// (same result; measured cheaper than always blending on the `sphere` bench).
    #[inline(always)]
    pub fn select_mostly(m: F::Mask, a: V3<F>, b: V3<F>) -> V3<F> {
        if F::all(m) { a } else { V3::select(m, a, b) }
    }

    /// Lanes where any component differs from zero (NaN counts as non-zero), as `v != Vec3::ZERO`.
    #[inline(always)]
    pub fn ne_zero(self) -> F::Mask {
        let z = F::splat(0.0);
        self.x.ne(z) | self.y.ne(z) | self.z.ne(z)
    }

    /// Lanes where every component is finite.
    #[inline(always)]
    pub fn is_finite(self) -> F::Mask {
        self.x.is_finite() & self.y.is_finite() & self.z.is_finite()
    }
}

impl<F: Lanes> Add for V3<F> {
    type Output = V3<F>;
    #[inline(always)]
    fn add(self, o: V3<F>) -> V3<F> {
        V3 { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }
}

impl<F: Lanes> Sub for V3<F> {
    type Output = V3<F>;
    #[inline(always)]
    fn sub(self, o: V3<F>) -> V3<F> {
        V3 { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
}

/// Component-wise product, as `Vec3 * Vec3`.
impl<F: Lanes> Mul for V3<F> {
    type Output = V3<F>;
    #[inline(always)]
    fn mul(self, o: V3<F>) -> V3<F> {
        V3 { x: self.x * o.x, y: self.y * o.y, z: self.z * o.z }
    }
}

impl<F: Lanes> Neg for V3<F> {
    type Output = V3<F>;
    #[inline(always)]
    fn neg(self) -> V3<F> {
        V3 { x: -self.x, y: -self.y, z: -self.z }
    }
}

impl From<Vec3> for V3<f32> {
    #[inline(always)]
    fn from(v: Vec3) -> V3<f32> {
        V3 { x: v.x, y: v.y, z: v.z }
    }
}

impl From<V3<f32>> for Vec3 {
    #[inline(always)]
    fn from(v: V3<f32>) -> Vec3 {
        Vec3::new(v.x, v.y, v.z)
    }
}

impl V3<F32x4> {
    /// The lanes as vectors.
    #[inline(always)]
    pub fn to_lanes(&self) -> [Vec3; WIDTH] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|i| Vec3::new(x[i], y[i], z[i]))
    }

    /// Lanes from four vectors.
    #[inline(always)]
    pub fn from_lanes(v: &[Vec3; WIDTH]) -> V3<F32x4> {
        V3 { x: F32x4::from_array(v.map(|v| v.x)), y: F32x4::from_array(v.map(|v| v.y)), z: F32x4::from_array(v.map(|v| v.z)) }
    }
}
/// A deterministic xorshift generator of f32 in [−`half_range`, `half_range`), for tests that
/// compare lane widths on many random inputs (the same sequence on every machine).
#[cfg(test)]
pub(crate) fn test_rng(seed: u64, half_range: f32) -> impl FnMut() -> f32 {
    let mut seed = seed;
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        ((seed >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0) * half_range
    }
}
