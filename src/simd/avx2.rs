//! The AVX2 token: 256-bit integer lanes, for the rasterizer's eight-sample walk
//! (`raster::walk`) and the eight-pixel sRGB encode (`render::encode_avx2`). Like
//! [`Avx`](super::avx::Avx), a token exists only when run-time detection found the features,
//! so code compiled with `#[target_feature(enable = "avx2")]` runs only on a CPU that has them.
//! The walk's f32 operations are the AVX forms of the SSE2 ones (no FMA is enabled), so its
//! bits are those of the four-lane and one-sample walks.

use super::avx::Avx;

/// Proof that this CPU runs AVX2: only [`Avx2::detect`] makes one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Avx2(());

impl Avx2 {
    /// The token, when this CPU runs AVX2 (the checks are cached by the standard library).
    #[inline]
    pub(super) fn detect() -> Option<Avx2> {
        // Every feature `#[target_feature(enable = "avx2")]` turns on: `avx` with its SSE
        // levels (the `Avx` token) and `avx2` itself.
        let ok = Avx::detect().is_some() && is_x86_feature_detected!("avx2");
        ok.then_some(Avx2(()))
    }
}
