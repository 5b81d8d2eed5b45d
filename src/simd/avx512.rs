//! Sixteen lanes in one AVX-512 register ([`F32x16`]), for the shading bundles of CPUs that
//! have AVX-512F.
//!
//! **Same bits as four and eight lanes.** Every operation is the AVX-512 form of the AVX
//! instruction [`F32x8`](super::avx::F32x8) uses, with the same IEEE-754 rounding (no
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
//! **Chosen at run time, and safety,** as for [`F32x8`](super::avx::F32x8): values of this
//! type are only made and used on a CPU where [`avx512_available`] is true, inside the
//! `#[target_feature(enable = "avx512f")]` entry point of `render::pipeline` (called after
//! that check) and tests guarded by it.

use super::lanes::{Lanes, MAX_WIDTH};
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// True when this CPU runs AVX-512F (cached by the standard library after the first call).
#[inline]
pub fn avx512_available() -> bool {
    is_x86_feature_detected!("avx512f")
}

/// Sixteen f32 lanes in one AVX-512 register (only on CPUs with AVX-512F: see the module docs).
#[derive(Debug, Clone, Copy)]
pub(crate) struct F32x16(__m512);

/// Sixteen lane masks, one bit each (bit i = lane i).
#[derive(Debug, Clone, Copy)]
pub(crate) struct M16(__mmask16);

/// Lanes per AVX-512 register.
const WIDTH: usize = 16;

impl F32x16 {
    /// Lanes from an array (lane i is `a[i]`).
    #[inline(always)]
    pub(crate) fn from_array(a: [f32; WIDTH]) -> F32x16 {
        // SAFETY: an unaligned load of 16 f32 from an array of 16; AVX-512F per the module invariant.
        F32x16(unsafe { _mm512_loadu_ps(a.as_ptr()) })
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f32; WIDTH] {
        let mut a = [0f32; WIDTH];
        // SAFETY: an unaligned store of 16 f32 into an array of 16; AVX-512F per the module invariant.
        unsafe { _mm512_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
}

/// `$t($f(a.0, b.0))` for an AVX-512 intrinsic `$f` (AVX-512F per the module invariant).
macro_rules! op {
    ($t:ident, $tr:ident, $f:ident, $intr:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, b: $t) -> $t {
                // SAFETY: AVX-512F per the module invariant.
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
        // SAFETY: AVX-512F per the module invariant.
        F32x16(unsafe { _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(self.0), _mm512_set1_epi32(i32::MIN))) })
    }
}

/// A comparison with predicate `$p` into a mask (AVX-512F per the module invariant).
macro_rules! cmp {
    ($a:expr, $b:expr, $p:ident) => {
        // SAFETY: AVX-512F per the module invariant.
        M16(unsafe { _mm512_cmp_ps_mask::<$p>($a.0, $b.0) })
    };
}

impl Lanes for F32x16 {
    type Mask = M16;
    const WIDTH: usize = WIDTH;
    #[inline(always)]
    fn splat(x: f32) -> F32x16 {
        // SAFETY: AVX-512F per the module invariant.
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
        // SAFETY: AVX-512F per the module invariant.
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
        // SAFETY: AVX-512F per the module invariant.
        let abs = F32x16(unsafe { _mm512_abs_ps(self.0) });
        cmp!(abs, F32x16::splat(f32::INFINITY), _CMP_LT_OQ)
    }
    #[inline(always)]
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]) {
        // SAFETY: an unaligned store of 16 i32 into an array of 16; AVX-512F per the module invariant.
        unsafe { _mm512_storeu_si512(out.as_mut_ptr().cast(), _mm512_cvttps_epi32(self.0)) };
    }
    #[inline(always)]
    fn select(m: M16, a: F32x16, b: F32x16) -> F32x16 {
        // a where the mask bit is set, else b.
        // SAFETY: AVX-512F per the module invariant.
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
