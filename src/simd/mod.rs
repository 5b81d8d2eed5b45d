//! SIMD lanes: one generic formula evaluated on one value or on four, eight or sixteen lanes.
//!
//! [`lanes::Lanes`] is implemented by `f32` and by SSE2 ([`lanes::F32x4`]), AVX (eight lanes)
//! and AVX-512F (sixteen) vectors with the same IEEE-754 rounding, so every width gives the
//! bits of the scalar code; [`pair::Pair`] runs two bundles as one (sixteen lanes on AVX as
//! two registers, eight on SSE2: two independent chains to overlap). The AVX types are
//! private to this module: generic code gets them only inside a [`lanes::LaneTask`] run by a token from run-time detection (`avx::Avx`,
//! `avx512::Avx512`), so safe code cannot run an AVX instruction on a CPU without AVX.
//! [`pow`] is the deterministic x^k the lanes and the sRGB transfer share.

#[cfg(target_arch = "x86_64")]
pub mod avx;
#[cfg(target_arch = "x86_64")]
pub mod avx2;
#[cfg(target_arch = "x86_64")]
pub mod avx512;
pub mod cpu;
pub mod lanes;
pub mod pair;
pub mod pow;

pub use cpu::{Cpu, Level};

/// Runs `task` at every lane width this CPU has: four SSE2 lanes and a pair of them always,
/// a pair of eight AVX lanes and sixteen AVX-512F lanes through the probe's tokens, saying
/// `skipped: no AVX` or `skipped: no AVX-512` on stderr for a width it lacks, or failing
/// when `SHADELAB_REQUIRE_SIMD` requires it ([`cpu::missing`]) (for tests that compare widths).
#[cfg(test)]
pub(crate) fn at_every_width<K: lanes::LaneTask + Copy>(task: K) {
    task.run::<lanes::F32x4, lanes::F32x4>();
    // Two four-lane halves as one bundle: the pair's bits on every CPU.
    task.run::<pair::Pair<lanes::F32x4>, lanes::F32x4>();
    #[cfg(target_arch = "x86_64")]
    {
        let cpu = Cpu::get();
        match cpu.avx() {
            Some(avx) => {
                avx.run(task);
            }
            None => cpu::missing(Level::Avx, "AVX"),
        }
        match cpu.avx512() {
            Some(avx512) => {
                avx512.run(task);
            }
            None => cpu::missing(Level::Avx512, "AVX-512"),
        }
    }
}

/// Asks the CPU to bring the cache line at `p` into the nearest cache, for data a loop reads a
/// few iterations later through indices (which the hardware prefetcher cannot follow). A hint
/// only: it reads nothing and changes no result, and `p` may point anywhere (callers form it
/// with `wrapping_add` and spend no bounds check on it: a prefetch never faults).
#[inline(always)]
pub fn prefetch<T>(p: *const T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: SSE is part of x86-64, and a prefetch reads nothing and never faults.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(p.cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}
