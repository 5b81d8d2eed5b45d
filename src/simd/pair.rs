//! Two bundles of lanes as one ([`Pair`]): every operation is its half-width operation on
//! each half, so a pair gives the bits of its halves, which give the scalar bits.
//!
//! **Why.** A shading bundle is one long chain of dependent operations (interpolate, then
//! normalize: a square root and a division; the light; the `pow`), and eight lanes leave
//! the divider and the square root waiting on each other. Two independent eight-lane
//! chains in one loop body give the out-of-order core the second chain to run in those
//! waits: sixteen lanes on AVX machines (as AVX-512 has them in one register), eight on SSE2.

use super::lanes::{Lanes, MAX_WIDTH};
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// Two bundles of `F` lanes: lanes `0..F::WIDTH` in `.0`, the next `F::WIDTH` in `.1`.
#[derive(Debug, Clone, Copy)]
pub struct Pair<F>(F, F);

/// The masks of a [`Pair`]'s two halves.
#[derive(Debug, Clone, Copy)]
pub struct PairMask<M>(M, M);

/// `Pair(a.0 op b.0, a.1 op b.1)` for a binary operator trait.
macro_rules! op {
    ($t:ident, $bound:ident, $tr:ident, $f:ident) => {
        impl<F: $bound> $tr for $t<F> {
            type Output = $t<F>;
            #[inline(always)]
            fn $f(self, b: $t<F>) -> $t<F> {
                $t(self.0.$f(b.0), self.1.$f(b.1))
            }
        }
    };
}
op!(Pair, Lanes, Add, add);
op!(Pair, Lanes, Sub, sub);
op!(Pair, Lanes, Mul, mul);
op!(Pair, Lanes, Div, div);
op!(PairMask, MaskOps, BitAnd, bitand);
op!(PairMask, MaskOps, BitOr, bitor);

/// The operations a lane mask has (what [`Lanes::Mask`] requires), to name them as a bound.
pub trait MaskOps: Copy + BitAnd<Output = Self> + BitOr<Output = Self> + Not<Output = Self> {}
impl<M: Copy + BitAnd<Output = M> + BitOr<Output = M> + Not<Output = M>> MaskOps for M {}

impl<F: Lanes> Neg for Pair<F> {
    type Output = Pair<F>;
    #[inline(always)]
    fn neg(self) -> Pair<F> {
        Pair(-self.0, -self.1)
    }
}

impl<M: MaskOps> Not for PairMask<M> {
    type Output = PairMask<M>;
    #[inline(always)]
    fn not(self) -> PairMask<M> {
        PairMask(!self.0, !self.1)
    }
}

impl<F: Lanes> Lanes for Pair<F> {
    type Mask = PairMask<F::Mask>;
    const WIDTH: usize = {
        assert!(2 * F::WIDTH <= MAX_WIDTH, "a pair is at most MAX_WIDTH lanes");
        2 * F::WIDTH
    };
    #[inline(always)]
    fn splat(x: f32) -> Pair<F> {
        Pair(F::splat(x), F::splat(x))
    }
    #[inline(always)]
    fn load(s: &[f32]) -> Pair<F> {
        Pair(F::load(s), F::load(&s[F::WIDTH..]))
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        self.0.store(out);
        self.1.store(&mut out[F::WIDTH..]);
    }
    #[inline(always)]
    fn first(n: usize) -> PairMask<F::Mask> {
        PairMask(F::first(n), F::first(n.saturating_sub(F::WIDTH)))
    }
    #[inline(always)]
    fn mask(b: bool) -> PairMask<F::Mask> {
        PairMask(F::mask(b), F::mask(b))
    }
    #[inline(always)]
    fn sqrt(self) -> Pair<F> {
        Pair(self.0.sqrt(), self.1.sqrt())
    }
    #[inline(always)]
    fn lt(self, o: Pair<F>) -> PairMask<F::Mask> {
        PairMask(self.0.lt(o.0), self.1.lt(o.1))
    }
    #[inline(always)]
    fn le(self, o: Pair<F>) -> PairMask<F::Mask> {
        PairMask(self.0.le(o.0), self.1.le(o.1))
    }
    #[inline(always)]
    fn gt(self, o: Pair<F>) -> PairMask<F::Mask> {
        PairMask(self.0.gt(o.0), self.1.gt(o.1))
    }
    #[inline(always)]
    fn ne(self, o: Pair<F>) -> PairMask<F::Mask> {
        PairMask(self.0.ne(o.0), self.1.ne(o.1))
    }
    #[inline(always)]
    fn is_finite(self) -> PairMask<F::Mask> {
        PairMask(self.0.is_finite(), self.1.is_finite())
    }
    #[inline(always)]
    fn trunc_i32(self, out: &mut [i32; MAX_WIDTH]) {
        let mut hi = [0i32; MAX_WIDTH];
        self.0.trunc_i32(out);
        self.1.trunc_i32(&mut hi);
        out[F::WIDTH..2 * F::WIDTH].copy_from_slice(&hi[..F::WIDTH]);
    }
    #[inline(always)]
    fn select(m: PairMask<F::Mask>, a: Pair<F>, b: Pair<F>) -> Pair<F> {
        Pair(F::select(m.0, a.0, b.0), F::select(m.1, a.1, b.1))
    }
    #[inline(always)]
    fn pow(self, k: f32) -> Pair<F> {
        // Each half on its own: one powering loop over both through memory measured slower.
        Pair(self.0.pow(k), self.1.pow(k))
    }
    #[inline(always)]
    fn count(m: PairMask<F::Mask>) -> u64 {
        F::count(m.0) + F::count(m.1)
    }
    #[inline(always)]
    fn any(m: PairMask<F::Mask>) -> bool {
        F::any(m.0 | m.1)
    }
    #[inline(always)]
    fn all(m: PairMask<F::Mask>) -> bool {
        F::all(m.0 & m.1)
    }
}
