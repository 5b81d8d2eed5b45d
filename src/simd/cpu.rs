//! The one CPU probe: which SIMD widths this process runs, detected once.
//!
//! Every run-time choice of a lane width asks [`Cpu::get`] (DESIGN.md, "One of each"): the
//! shading bundles, the raster walk and projection, the sRGB encode, the shadow-map texel
//! gathers and the BVH's node tests. The feature tokens ([`Avx`], [`Avx2`], [`Avx512`],
//! [`Avx512Bw`]) are made here and nowhere else, so a token still proves that the CPU has
//! the features its code is compiled with.
//!
//! **Capping the width.** `SHADELAB_SIMD=sse2|avx|avx2|avx512` (read once, at the first
//! probe) drops every feature above the named level: the same lesson then runs the narrower
//! paths, which give the same bytes (every width is one formula; `tests/integration` renders
//! a lesson at each level the CPU has and compares). A name the probe does not know is
//! ignored with no cap.
//!
//! **Requiring a width in tests.** A test that compares widths skips one the CPU lacks with
//! [`missing`], which prints `skipped: no …`, unless `SHADELAB_REQUIRE_SIMD` (a comma list
//! of the same names) requires it: then the test fails, so a CI machine that has AVX-512
//! cannot pass without running the AVX-512 paths. `.ci/run` sets it from the CPU's flags.

#[cfg(target_arch = "x86_64")]
use super::{avx::Avx, avx2::Avx2, avx512::Avx512, avx512::Avx512Bw};
use std::sync::OnceLock;

/// A SIMD level, narrowest first: each includes the ones before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    /// SSE2, part of every x86-64 CPU (and the portable fallback elsewhere): four lanes.
    Sse2,
    /// AVX (with SSE3 … SSE4.2): eight f32 lanes.
    Avx,
    /// AVX2: eight i32 lanes (the raster walk, the eight-pixel encode).
    Avx2,
    /// AVX-512F, BW and DQ: sixteen lanes.
    Avx512,
}

impl Level {
    /// Every level, narrowest first.
    pub const ALL: [Level; 4] = [Level::Sse2, Level::Avx, Level::Avx2, Level::Avx512];

    /// The name in `SHADELAB_SIMD` and `SHADELAB_REQUIRE_SIMD`.
    pub fn name(self) -> &'static str {
        match self {
            Level::Sse2 => "sse2",
            Level::Avx => "avx",
            Level::Avx2 => "avx2",
            Level::Avx512 => "avx512",
        }
    }

    /// The level called `name`, if any.
    pub fn parse(name: &str) -> Option<Level> {
        Level::ALL.into_iter().find(|l| l.name() == name.trim())
    }
}

/// What this CPU runs, as tokens (a token is proof that detection found its features).
#[derive(Debug, Clone, Copy, Default)]
pub struct Cpu {
    #[cfg(target_arch = "x86_64")]
    avx: Option<Avx>,
    #[cfg(target_arch = "x86_64")]
    avx2: Option<Avx2>,
    #[cfg(target_arch = "x86_64")]
    avx512: Option<Avx512>,
    #[cfg(target_arch = "x86_64")]
    avx512bw: Option<Avx512Bw>,
}

impl Cpu {
    /// The probe's answer: detected on the first call, capped by `SHADELAB_SIMD`.
    #[inline]
    pub fn get() -> Cpu {
        static CPU: OnceLock<Cpu> = OnceLock::new();
        *CPU.get_or_init(|| {
            let cap = std::env::var("SHADELAB_SIMD").ok().and_then(|s| Level::parse(&s)).unwrap_or(Level::Avx512);
            Cpu::detect().capped(cap)
        })
    }

    /// What the hardware has, without a cap.
    fn detect() -> Cpu {
        #[cfg(target_arch = "x86_64")]
        {
            Cpu { avx: Avx::detect(), avx2: Avx2::detect(), avx512: Avx512::detect(), avx512bw: Avx512Bw::detect() }
        }
        #[cfg(not(target_arch = "x86_64"))]
        Cpu {}
    }

    /// This CPU without the features above `level` (the same paths a CPU of that level takes).
    pub fn capped(self, level: Level) -> Cpu {
        #[cfg(target_arch = "x86_64")]
        {
            Cpu {
                avx: self.avx.filter(|_| level >= Level::Avx),
                avx2: self.avx2.filter(|_| level >= Level::Avx2),
                avx512: self.avx512.filter(|_| level >= Level::Avx512),
                avx512bw: self.avx512bw.filter(|_| level >= Level::Avx512),
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = level;
            self
        }
    }

    /// The widest level every token of which this CPU has.
    pub fn level(self) -> Level {
        Level::ALL.into_iter().rev().find(|l| self.has(*l)).unwrap_or(Level::Sse2)
    }

    /// True when this CPU runs `level` (SSE2 always: it is the portable baseline).
    pub fn has(self, level: Level) -> bool {
        #[cfg(target_arch = "x86_64")]
        {
            match level {
                Level::Sse2 => true,
                Level::Avx => self.avx.is_some(),
                Level::Avx2 => self.avx2.is_some(),
                Level::Avx512 => self.avx512.is_some() && self.avx512bw.is_some(),
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            level == Level::Sse2
        }
    }

    /// The AVX token (eight f32 lanes), when this CPU runs AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    pub fn avx(self) -> Option<Avx> {
        self.avx
    }

    /// The AVX2 token (eight i32 lanes), when this CPU runs AVX2.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    pub fn avx2(self) -> Option<Avx2> {
        self.avx2
    }

    /// The AVX-512F token (sixteen f32 lanes), when this CPU runs AVX-512F.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    pub fn avx512(self) -> Option<Avx512> {
        self.avx512
    }

    /// The AVX-512BW token (sixteen-lane walk and encode; with DQ), when this CPU runs them.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    pub fn avx512bw(self) -> Option<Avx512Bw> {
        self.avx512bw
    }

    /// Lanes of the widest f32 bundle this CPU shades with: 16, 8 (AVX) or 4 (SSE2).
    pub fn shading_lanes(self) -> usize {
        if self.has(Level::Avx512) {
            16
        } else if self.has(Level::Avx) {
            8
        } else {
            4
        }
    }
}

/// True when `SHADELAB_REQUIRE_SIMD` names `level` (a test must then run its paths).
pub fn required(level: Level) -> bool {
    std::env::var("SHADELAB_REQUIRE_SIMD").is_ok_and(|s| s.split(',').any(|n| Level::parse(n) == Some(level)))
}

/// For a test that lacks `level` on this CPU: prints `skipped: no …` (with `what`, the
/// instruction set the test needs), or fails when `SHADELAB_REQUIRE_SIMD` requires the level.
///
/// # Panics
/// When the level is required: a machine that should check it did not.
pub fn missing(level: Level, what: &str) {
    if required(level) {
        panic!("SHADELAB_REQUIRE_SIMD requires {} but this CPU (or SHADELAB_SIMD) lacks {what}", level.name());
    }
    eprintln!("skipped: no {what}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_ordered_and_named_both_ways() {
        for l in Level::ALL {
            assert_eq!(Level::parse(l.name()), Some(l));
        }
        assert!(Level::Sse2 < Level::Avx && Level::Avx < Level::Avx2 && Level::Avx2 < Level::Avx512);
        assert_eq!(Level::parse("avx1024"), None);
    }

    #[test]
    fn a_cap_drops_every_wider_token() {
        let cpu = Cpu::get();
        for cap in Level::ALL {
            let c = cpu.capped(cap);
            assert!(c.level() <= cap, "{cap:?}: {:?}", c.level());
            // Capping keeps what the CPU has up to the cap.
            for l in Level::ALL {
                assert_eq!(c.has(l), cpu.has(l) && l <= cap, "{cap:?} {l:?}");
            }
        }
        assert_eq!(cpu.capped(Level::Sse2).shading_lanes(), 4);
    }

    #[test]
    fn the_probe_agrees_with_the_hardware() {
        #[cfg(target_arch = "x86_64")]
        {
            let hw = Cpu::detect();
            assert_eq!(hw.has(Level::Avx), is_x86_feature_detected!("avx"));
            assert_eq!(hw.has(Level::Avx2), is_x86_feature_detected!("avx2"));
            let bw = is_x86_feature_detected!("avx512bw") && is_x86_feature_detected!("avx512dq");
            assert_eq!(hw.has(Level::Avx512), is_x86_feature_detected!("avx512f") && bw);
        }
        // What a test may require must be what the probe finds (a CI that sets the list
        // from /proc/cpuinfo fails here first when the two disagree).
        for l in Level::ALL {
            if required(l) {
                assert!(Cpu::get().has(l), "SHADELAB_REQUIRE_SIMD requires {} but the probe lacks it", l.name());
            }
        }
    }
}
