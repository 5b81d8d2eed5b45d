//! Eight lanes in one AVX register ([`F32x8`]), for the shading bundles of CPUs that have AVX.
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
//! renderer checks `is_x86_feature_detected!("avx")` once per render and, when AVX is there,
//! runs a strip's bundles inside one `#[target_feature(enable = "avx")]` function, into which
//! these `#[inline(always)]` methods inline. [`avx_available`] is the check.
//!
//! **Safety.** An AVX instruction on a CPU without AVX is undefined behaviour, so values of
//! this type may only be made and used on a CPU where [`avx_available`] is true: the type is
//! crate-private and only the AVX entry points of `render::pipeline` (called after that
//! check) and tests guarded by it instantiate it.
//!
//! Measured: see docs/performance.md.

use super::lanes::{Lanes, MAX_WIDTH};
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// True when this CPU runs AVX (cached by the standard library after the first call).
#[inline]
pub fn avx_available() -> bool {
    is_x86_feature_detected!("avx")
}

/// Eight f32 lanes in one AVX register (only on CPUs with AVX: see the module docs).
#[derive(Debug, Clone, Copy)]
pub(crate) struct F32x8(__m256);

/// Eight lane masks: all bits set (true) or clear (false).
#[derive(Debug, Clone, Copy)]
pub(crate) struct M8(__m256);

/// Lanes per AVX register.
const WIDTH: usize = 8;

impl F32x8 {
    /// Lanes from an array (lane i is `a[i]`).
    #[inline(always)]
    pub(crate) fn from_array(a: [f32; WIDTH]) -> F32x8 {
        // SAFETY: an unaligned load of 8 f32 from an array of 8; AVX per the module invariant.
        F32x8(unsafe { _mm256_loadu_ps(a.as_ptr()) })
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f32; WIDTH] {
        let mut a = [0f32; WIDTH];
        // SAFETY: an unaligned store of 8 f32 into an array of 8; AVX per the module invariant.
        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
}

impl M8 {
    /// One bit per lane (bit i = lane i).
    #[inline(always)]
    fn bits(self) -> u32 {
        // SAFETY: AVX per the module invariant.
        unsafe { _mm256_movemask_ps(self.0) as u32 }
    }
}

/// `$t($f(a.0, b.0))` for an AVX intrinsic `$f` (AVX per the module invariant).
macro_rules! op {
    ($t:ident, $tr:ident, $f:ident, $intr:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, b: $t) -> $t {
                // SAFETY: AVX per the module invariant.
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
        // SAFETY: AVX per the module invariant.
        F32x8(unsafe { _mm256_xor_ps(self.0, _mm256_set1_ps(-0.0)) })
    }
}

impl Not for M8 {
    type Output = M8;
    #[inline(always)]
    fn not(self) -> M8 {
        // SAFETY: AVX per the module invariant.
        M8(unsafe { _mm256_xor_ps(self.0, _mm256_castsi256_ps(_mm256_set1_epi32(-1))) })
    }
}

/// A comparison with predicate `$p` into a mask (AVX per the module invariant).
macro_rules! cmp {
    ($a:expr, $b:expr, $p:ident) => {
        // SAFETY: AVX per the module invariant.
        M8(unsafe { _mm256_cmp_ps::<$p>($a.0, $b.0) })
    };
}

impl Lanes for F32x8 {
    type Mask = M8;
    const WIDTH: usize = WIDTH;
    #[inline(always)]
    fn splat(x: f32) -> F32x8 {
        // SAFETY: AVX per the module invariant.
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
        // SAFETY: AVX per the module invariant.
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
        // SAFETY: AVX per the module invariant.
        let abs = F32x8(unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0) });
        cmp!(abs, F32x8::splat(f32::INFINITY), _CMP_LT_OQ)
    }
    #[inline(always)]
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]) {
        // SAFETY: an unaligned store of 8 i32 into an array of 8; AVX per the module invariant.
        unsafe { _mm256_storeu_si256(out.as_mut_ptr().cast(), _mm256_cvttps_epi32(self.0)) };
    }
    #[inline(always)]
    fn select(m: M8, a: F32x8, b: F32x8) -> F32x8 {
        // (a & m) | (b & !m), as `F32x4`'s bitwise blend.
        // SAFETY: AVX per the module invariant.
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
