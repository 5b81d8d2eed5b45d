//! SIMD lanes: one generic formula evaluated on one value or on four, eight or sixteen lanes.
//!
//! [`lanes::Lanes`] is implemented by `f32` and by SSE2 ([`lanes::F32x4`]), AVX
//! ([`avx::F32x8`]) and AVX-512F ([`avx512::F32x16`]) vectors with the same IEEE-754 rounding,
//! so every width gives the bits of the scalar code. [`pow`] is the deterministic x^k the
//! lanes and the sRGB transfer share.

#[cfg(target_arch = "x86_64")]
pub mod avx;
#[cfg(target_arch = "x86_64")]
pub mod avx512;
pub mod lanes;
pub mod pow;
