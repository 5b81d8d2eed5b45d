//! Sixteen lanes in one AVX-512 register (`F32x16`), for the shading bundles of CPUs that
//! have AVX-512F; and the `Avx512Bw` token of the sixteen-lane raster walk and sRGB encode.
//!
//! **Same bits as four and eight lanes.** Every operation is the AVX-512 form of the AVX
//! instruction `F32x8` uses, with the same IEEE-754 rounding (no
//! embedded rounding control) and the same comparison predicates, into a mask register;
//! select is a masked blend, negation flips the sign bit, finiteness is |x| < ∞. Nothing
//! is fused: Rust emits no contracted multiply-adds, whatever the target features. So the
//! generic shading formula gives the same bits with sixteen lanes (tested in
//! `render/pipeline/tests.rs`: `eight_lanes_give_the_bits_of_four`, which checks sixteen too, and in `classic.rs`).
//!
//! **Why.** A shading bundle is one long dependency chain (divisions, square roots, the
//! powering) whose latency does not grow with its width: sixteen lanes walk it once for
//! sixteen samples. Measured: see docs/performance.md.
//!
//! **Chosen at run time, and safety,** as for [`F32x8`](super::avx): the renderer asks
//! [`Avx512::detect`] for a token and runs a strip's bundles through [`Avx512::run`] in one
//! `#[target_feature(enable = "avx512f")]` function. The invariant: *an AVX-512 lane
//! operation runs only in a process where an [`Avx512`] token was made*, which
//! [`Avx512::detect`] does only after finding AVX-512F and every feature `avx512f` implies.
//! The lane types are visible only inside [`crate::simd`], where only `run_avx512` names
//! them, as type arguments of a [`LaneTask`].

use super::avx::{Avx, F32x8};
use super::lanes::{LaneTask, Lanes, MAX_WIDTH};
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Proof that this CPU runs AVX-512F (and AVX): only [`Avx512::detect`] makes one.
///
/// The lane type itself is private to `simd`, so safe code cannot make one without a token:
///
/// ```compile_fail,E0603
/// let _ = shadelab::simd::avx512::F32x16::from_array([0.0; 16]);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Avx512(());

impl Avx512 {
    /// The token, when this CPU runs AVX-512F (the check is cached by the standard library).
    #[inline]
    pub(super) fn detect() -> Option<Avx512> {
        // Every feature `#[target_feature(enable = "avx512f")]` turns on: rustc's `avx512f`
        // implies `avx2`, `fma` and `f16c`, and `avx` with its SSE levels (the `Avx` token).
        let ok = Avx::detect().is_some()
            && is_x86_feature_detected!("avx512f")
            && is_x86_feature_detected!("avx2")
            && is_x86_feature_detected!("fma")
            && is_x86_feature_detected!("f16c");
        ok.then_some(Avx512(()))
    }

    /// Runs `task` with bundles of sixteen AVX-512 lanes, the rest in eight AVX lanes
    /// (`W` = sixteen, `H` = eight), compiled with AVX-512F.
    #[inline]
    pub fn run<K: LaneTask>(self, task: K) -> K::Output {
        // SAFETY: `self` exists, so `detect` found every feature `run_avx512` enables.
        unsafe { run_avx512(task) }
    }
}

/// Proof that this CPU runs AVX-512BW (byte and word lanes, with AVX-512F), AVX-512DQ and POPCNT: only
/// [`Avx512Bw::detect`] makes one. The sixteen-pixel sRGB encode (`render::encode_avx512`)
/// scatters its pixels and shuffles their bytes with it; the sixteen-lane raster walk
/// (`raster::walk_avx512`) compresses its lanes and counts them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Avx512Bw(());

impl Avx512Bw {
    /// The token, when this CPU runs AVX-512BW (the checks are cached by the standard library).
    #[inline]
    pub(super) fn detect() -> Option<Avx512Bw> {
        // `avx512bw` implies `avx512f` and what it implies (the `Avx512` token's checks).
        // AVX-512DQ (every AVX-512BW CPU has it) converts i64 lanes to f32 in the walk of
        // triangles whose edge values exceed i32.
        let ok = Avx512::detect().is_some()
            && is_x86_feature_detected!("avx512bw")
            && is_x86_feature_detected!("avx512dq")
            && is_x86_feature_detected!("popcnt");
        ok.then_some(Avx512Bw(()))
    }
}

/// `task` with sixteen and eight lanes, in the one function compiled with AVX-512F.
#[target_feature(enable = "avx512f")]
fn run_avx512<K: LaneTask>(task: K) -> K::Output {
    // F32x8 needs AVX, which `avx512f` enables and `detect` checked (with `Avx::detect`).
    task.run::<F32x16, F32x8>()
}

/// Sixteen f32 lanes in one AVX-512 register (only reachable through [`Avx512::run`]: see the module docs).
#[derive(Debug, Clone, Copy)]
pub(super) struct F32x16(__m512);

/// Sixteen lane masks, one bit each (bit i = lane i).
#[derive(Debug, Clone, Copy)]
pub(super) struct M16(__mmask16);

/// Lanes per AVX-512 register.
const WIDTH: usize = 16;

impl F32x16 {
    /// Lanes from an array (lane i is `a[i]`).
    #[inline(always)]
    fn from_array(a: [f32; WIDTH]) -> F32x16 {
        // SAFETY: an unaligned load of 16 f32 from an array of 16; this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        F32x16(unsafe { _mm512_loadu_ps(a.as_ptr()) })
    }

    /// The lanes as an array.
    #[inline(always)]
    fn to_array(self) -> [f32; WIDTH] {
        let mut a = [0f32; WIDTH];
        // SAFETY: an unaligned store of 16 f32 into an array of 16; this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        unsafe { _mm512_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
}

/// `$t($f(a.0, b.0))` for an AVX-512 intrinsic `$f` (this CPU runs AVX-512F, as an `Avx512` token exists (module docs)).
macro_rules! op {
    ($t:ident, $tr:ident, $f:ident, $intr:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, b: $t) -> $t {
                // SAFETY: this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
                $t(unsafe { $intr(self.0, b.0) })
            }
        }
    };
}
op!(F32x16, Add, add, _mm512_add_ps);
op!(F32x16, Sub, sub, _mm512_sub_ps);
op!(F32x16, Mul, mul, _mm512_mul_ps);
op!(F32x16, Div, div, _mm512_div_ps);

impl BitAnd for M16 {
    type Output = M16;
    #[inline(always)]
    fn bitand(self, b: M16) -> M16 {
        M16(self.0 & b.0)
    }
}

impl BitOr for M16 {
    type Output = M16;
    #[inline(always)]
    fn bitor(self, b: M16) -> M16 {
        M16(self.0 | b.0)
    }
}

impl Not for M16 {
    type Output = M16;
    #[inline(always)]
    fn not(self) -> M16 {
        M16(!self.0)
    }
}

impl Neg for F32x16 {
    type Output = F32x16;
    /// Flips the sign bit, as scalar negation and `F32x8`.
    #[inline(always)]
    fn neg(self) -> F32x16 {
        // SAFETY: this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        F32x16(unsafe { _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(self.0), _mm512_set1_epi32(i32::MIN))) })
    }
}

/// A comparison with predicate `$p` into a mask (this CPU runs AVX-512F, as an `Avx512` token exists (module docs)).
macro_rules! cmp {
    ($a:expr, $b:expr, $p:ident) => {
        // SAFETY: this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        M16(unsafe { _mm512_cmp_ps_mask::<$p>($a.0, $b.0) })
    };
}

// The safe `Lanes` API is sound for `F32x16` because the type is reached only through
// `Avx512::run` (module docs): whichever method runs, AVX-512F is there.
impl Lanes for F32x16 {
    type Mask = M16;
    const WIDTH: usize = WIDTH;
    #[inline(always)]
    fn splat(x: f32) -> F32x16 {
        // SAFETY: this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        F32x16(unsafe { _mm512_set1_ps(x) })
    }
    #[inline(always)]
    fn load(s: &[f32]) -> F32x16 {
        F32x16::from_array(s[..WIDTH].try_into().expect("sixteen values"))
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        out[..WIDTH].copy_from_slice(&self.to_array());
    }
    #[inline(always)]
    fn first(n: usize) -> M16 {
        M16(if n >= WIDTH { u16::MAX } else { (1u16 << n) - 1 })
    }
    #[inline(always)]
    fn mask(b: bool) -> M16 {
        M16(if b { u16::MAX } else { 0 })
    }
    #[inline(always)]
    fn sqrt(self) -> F32x16 {
        // SAFETY: this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        F32x16(unsafe { _mm512_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn lt(self, o: F32x16) -> M16 {
        cmp!(self, o, _CMP_LT_OS)
    }
    #[inline(always)]
    fn le(self, o: F32x16) -> M16 {
        cmp!(self, o, _CMP_LE_OS)
    }
    #[inline(always)]
    fn gt(self, o: F32x16) -> M16 {
        cmp!(self, o, _CMP_GT_OS)
    }
    #[inline(always)]
    fn ne(self, o: F32x16) -> M16 {
        cmp!(self, o, _CMP_NEQ_UQ)
    }
    #[inline(always)]
    fn is_finite(self) -> M16 {
        // |x| < ∞ (false for NaN), as `F32x8`.
        // SAFETY: this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        let abs = F32x16(unsafe { _mm512_abs_ps(self.0) });
        cmp!(abs, F32x16::splat(f32::INFINITY), _CMP_LT_OQ)
    }
    #[inline(always)]
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]) {
        // SAFETY: an unaligned store of 16 i32 into an array of 16; this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        unsafe { _mm512_storeu_si512(out.as_mut_ptr().cast(), _mm512_cvttps_epi32(self.0)) };
    }
    #[inline(always)]
    fn select(m: M16, a: F32x16, b: F32x16) -> F32x16 {
        // a where the mask bit is set, else b.
        // SAFETY: this CPU runs AVX-512F, as an `Avx512` token exists (module docs).
        F32x16(unsafe { _mm512_mask_blend_ps(m.0, b.0, a.0) })
    }
    #[inline(always)]
    fn pow(self, k: f32) -> F32x16 {
        F32x16::from_array(super::pow::pow_lanes(self.to_array(), k))
    }
    #[inline(always)]
    fn count(m: M16) -> u64 {
        m.0.count_ones() as u64
    }
    #[inline(always)]
    fn any(m: M16) -> bool {
        m.0 != 0
    }
    #[inline(always)]
    fn all(m: M16) -> bool {
        m.0 == u16::MAX
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The widths a token runs a task at.
    struct Widths;
    impl LaneTask for Widths {
        type Output = (usize, usize);
        #[inline(always)]
        fn run<W: Lanes, H: Lanes>(self) -> (usize, usize) {
            (W::WIDTH, H::WIDTH)
        }
    }

    #[test]
    fn the_token_runs_sixteen_lanes_only_on_a_cpu_with_avx512f() {
        match Avx512::detect() {
            Some(token) => {
                assert!(is_x86_feature_detected!("avx512f"));
                assert_eq!(token.run(Widths), (16, 8));
            }
            None => crate::simd::cpu::missing(crate::simd::cpu::Level::Avx512, "AVX-512"),
        }
    }
}
