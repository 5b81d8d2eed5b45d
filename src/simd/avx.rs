//! Eight lanes in one AVX register (`F32x8`), for the shading bundles of CPUs that have AVX.
//!
//! **Same bits as four lanes.** Every operation is the AVX form of the SSE2 instruction
//! [`F32x4`](super::lanes::F32x4) uses, with the same IEEE-754 rounding and the same
//! comparison predicates (`vaddps`/`addps`, `vdivps`/`divps`, `vsqrtps`/`sqrtps`, `vcmpps`
//! LT_OS/LE_OS/GT_OS/NEQ_UQ as `cmpltps`/`cmpleps`/`cmpnltps`-swapped/`cmpneqps`; negation
//! flips the sign bit; finiteness is |x| < ∞). Only `avx` is enabled, never `fma`, so nothing
//! is contracted; the f64 powering of [`pow`](super::pow) vectorizes as `vmulpd`, also exact.
//! So the generic shading formula gives the same bits with eight lanes as with four or one,
//! on every machine (tested in `shading/classic.rs` and `render/pipeline/tests.rs`).
//!
//! **Chosen at run time.** The global target features stay baseline x86-64 (SSE2): the
//! renderer asks [`Avx::detect`] for a token (a cached check, once per render to choose the
//! width and again per strip) and, when it gets one, runs a
//! strip's bundles through [`Avx::run`]: one `#[target_feature(enable = "avx")]` function,
//! into which the task and these `#[inline(always)]` methods inline.
//!
//! **Safety.** An AVX instruction on a CPU without AVX is undefined behaviour, and every
//! method of `F32x8` and `M8` (the `Lanes` constructors `splat`, `load`, `first`, `mask`
//! included) executes AVX instructions. So the invariant of this module is: *an AVX lane
//! operation runs only in a process where an [`Avx`] token was made*, which
//! [`Avx::detect`] does only after `is_x86_feature_detected!` found AVX (and every feature
//! `avx` implies). It holds because the lane types are visible only inside [`crate::simd`],
//! where only `run_avx` and `avx512::run_avx512` name them, as type arguments of a
//! [`LaneTask`], and both run only with a token. A task can keep such code past `run` (a
//! boxed closure, say), but it still executes on this CPU, which has AVX.
//!
//! Measured: see docs/performance.md.

use super::lanes::{LaneTask, Lanes, MAX_WIDTH};
use super::pair::Pair;
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Proof that this CPU runs AVX: only [`Avx::detect`] makes one.
///
/// The lane type itself is private to `simd`, so safe code cannot make one without a token:
///
/// ```compile_fail,E0603
/// let _ = shadelab::simd::avx::F32x8::from_array([0.0; 8]);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Avx(());

impl Avx {
    /// The token, when this CPU runs AVX (the check is cached by the standard library).
    #[inline]
    pub(super) fn detect() -> Option<Avx> {
        // Every feature `#[target_feature(enable = "avx")]` turns on: rustc's `avx` implies
        // the SSE levels below it, which a CPU (or a VM's CPUID) could in principle lack.
        let ok = is_x86_feature_detected!("avx")
            && is_x86_feature_detected!("sse4.2")
            && is_x86_feature_detected!("sse4.1")
            && is_x86_feature_detected!("ssse3")
            && is_x86_feature_detected!("sse3");
        ok.then_some(Avx(()))
    }

    /// Runs `task` with bundles of sixteen lanes, a [`Pair`] of AVX registers (`W`), and of
    /// eight (`H`), compiled with AVX.
    #[inline]
    pub fn run<K: LaneTask>(self, task: K) -> K::Output {
        // SAFETY: `self` exists, so `detect` found every feature `run_avx` enables.
        unsafe { run_avx(task) }
    }
}

/// `task` with AVX lanes, in the one function compiled with AVX (see the module docs).
#[target_feature(enable = "avx")]
fn run_avx<K: LaneTask>(task: K) -> K::Output {
    task.run::<Pair<F32x8>, F32x8>()
}

/// Eight f32 lanes in one AVX register (only reachable through [`Avx::run`]: see the module docs).
#[derive(Debug, Clone, Copy)]
pub(super) struct F32x8(__m256);

/// Eight lane masks: all bits set (true) or clear (false).
#[derive(Debug, Clone, Copy)]
pub(super) struct M8(__m256);

/// Lanes per AVX register.
const WIDTH: usize = 8;

impl F32x8 {
    /// Lanes from an array (lane i is `a[i]`).
    #[inline(always)]
    fn from_array(a: [f32; WIDTH]) -> F32x8 {
        // SAFETY: an unaligned load of 8 f32 from an array of 8; this CPU runs AVX, as an `Avx` token exists (module docs).
        F32x8(unsafe { _mm256_loadu_ps(a.as_ptr()) })
    }

    /// The lanes as an array.
    #[inline(always)]
    fn to_array(self) -> [f32; WIDTH] {
        let mut a = [0f32; WIDTH];
        // SAFETY: an unaligned store of 8 f32 into an array of 8; this CPU runs AVX, as an `Avx` token exists (module docs).
        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
}

impl M8 {
    /// One bit per lane (bit i = lane i).
    #[inline(always)]
    fn bits(self) -> u32 {
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        unsafe { _mm256_movemask_ps(self.0) as u32 }
    }
}

/// `$t($f(a.0, b.0))` for an AVX intrinsic `$f` (this CPU runs AVX, as an `Avx` token exists (module docs)).
macro_rules! op {
    ($t:ident, $tr:ident, $f:ident, $intr:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, b: $t) -> $t {
                // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
                $t(unsafe { $intr(self.0, b.0) })
            }
        }
    };
}
op!(F32x8, Add, add, _mm256_add_ps);
op!(F32x8, Sub, sub, _mm256_sub_ps);
op!(F32x8, Mul, mul, _mm256_mul_ps);
op!(F32x8, Div, div, _mm256_div_ps);
op!(M8, BitAnd, bitand, _mm256_and_ps);
op!(M8, BitOr, bitor, _mm256_or_ps);

impl Neg for F32x8 {
    type Output = F32x8;
    /// Flips the sign bit, as scalar negation and `F32x4`.
    #[inline(always)]
    fn neg(self) -> F32x8 {
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        F32x8(unsafe { _mm256_xor_ps(self.0, _mm256_set1_ps(-0.0)) })
    }
}

impl Not for M8 {
    type Output = M8;
    #[inline(always)]
    fn not(self) -> M8 {
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        M8(unsafe { _mm256_xor_ps(self.0, _mm256_castsi256_ps(_mm256_set1_epi32(-1))) })
    }
}

/// A comparison with predicate `$p` into a mask (this CPU runs AVX, as an `Avx` token exists (module docs)).
macro_rules! cmp {
    ($a:expr, $b:expr, $p:ident) => {
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        M8(unsafe { _mm256_cmp_ps::<$p>($a.0, $b.0) })
    };
}

// The safe `Lanes` API is sound for `F32x8` because the type is reached only through
// `Avx::run` (module docs): whichever method runs, AVX is there.
impl Lanes for F32x8 {
    type Mask = M8;
    const WIDTH: usize = WIDTH;
    #[inline(always)]
    fn splat(x: f32) -> F32x8 {
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        F32x8(unsafe { _mm256_set1_ps(x) })
    }
    #[inline(always)]
    fn load(s: &[f32]) -> F32x8 {
        F32x8::from_array(s[..WIDTH].try_into().expect("eight values"))
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        out[..WIDTH].copy_from_slice(&self.to_array());
    }
    #[inline(always)]
    fn first(n: usize) -> M8 {
        let lane = F32x8::from_array([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        cmp!(lane, F32x8::splat(n.min(MAX_WIDTH) as f32), _CMP_LT_OS)
    }
    #[inline(always)]
    fn mask(b: bool) -> M8 {
        M8(F32x8::splat(f32::from_bits(if b { !0 } else { 0 })).0)
    }
    #[inline(always)]
    fn sqrt(self) -> F32x8 {
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        F32x8(unsafe { _mm256_sqrt_ps(self.0) })
    }
    #[inline(always)]
    fn lt(self, o: F32x8) -> M8 {
        cmp!(self, o, _CMP_LT_OS)
    }
    #[inline(always)]
    fn le(self, o: F32x8) -> M8 {
        cmp!(self, o, _CMP_LE_OS)
    }
    #[inline(always)]
    fn gt(self, o: F32x8) -> M8 {
        cmp!(self, o, _CMP_GT_OS)
    }
    #[inline(always)]
    fn ne(self, o: F32x8) -> M8 {
        cmp!(self, o, _CMP_NEQ_UQ)
    }
    #[inline(always)]
    fn is_finite(self) -> M8 {
        // |x| < ∞ (false for NaN): the lanes whose exponent is not all ones, as `F32x4`.
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        let abs = F32x8(unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0) });
        cmp!(abs, F32x8::splat(f32::INFINITY), _CMP_LT_OQ)
    }
    #[inline(always)]
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]) {
        // SAFETY: an unaligned store of 8 i32 into an array of 8; this CPU runs AVX, as an `Avx` token exists (module docs).
        unsafe { _mm256_storeu_si256(out.as_mut_ptr().cast(), _mm256_cvttps_epi32(self.0)) };
    }
    #[inline(always)]
    fn select(m: M8, a: F32x8, b: F32x8) -> F32x8 {
        // (a & m) | (b & !m), as `F32x4`'s bitwise blend.
        // SAFETY: this CPU runs AVX, as an `Avx` token exists (module docs).
        F32x8(unsafe { _mm256_or_ps(_mm256_and_ps(a.0, m.0), _mm256_andnot_ps(m.0, b.0)) })
    }
    #[inline(always)]
    fn pow(self, k: f32) -> F32x8 {
        F32x8::from_array(super::pow::pow_lanes(self.to_array(), k))
    }
    #[inline(always)]
    fn count(m: M8) -> u64 {
        m.bits().count_ones() as u64
    }
    #[inline(always)]
    fn any(m: M8) -> bool {
        m.bits() != 0
    }
    #[inline(always)]
    fn all(m: M8) -> bool {
        m.bits() == (1 << WIDTH) - 1
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
    fn the_token_runs_avx_lanes_only_on_a_cpu_with_avx() {
        match Avx::detect() {
            Some(token) => {
                assert!(is_x86_feature_detected!("avx"));
                assert_eq!(token.run(Widths), (16, 8));
            }
            None => crate::simd::cpu::missing(crate::simd::cpu::Level::Avx, "AVX"),
        }
    }
}
