//! Vertex stage → rasterizer → shading, strip by strip in parallel.
//!
//! The rasterizer hands back a strip's visibility ([`StripVis`](crate::raster::StripVis): per triangle that owns
//! samples, their indices and screen-space barycentrics); shading reads it, so every
//! visible sample is shaded exactly once whatever the overdraw. Gouraud lights the
//! vertices before rasterizing and flat lights each face once; only Phong interpolation
//! evaluates lights per sample.
//!
//! Each strip is shaded triangle by triangle into strip buffers, then filtered one pixel
//! row at a time: each pixel box-filters its aa² samples into the kept layers, or, for
//! [`render_image`], straight into 8-bit sRGB (a plain render: as the bundles leave their
//! totals). A triangle's samples are shaded in bundles of sixteen AVX-512 lanes when the CPU
//! has AVX-512F ([`crate::simd::avx512`]), of eight AVX lanes when it has AVX
//! ([`crate::simd::avx`]; both chosen at run time), else four SSE2 lanes
//! ([`crate::simd::lanes`]), its rest in eight and its last partial bundle in four (Phong:
//! its rest interpolated in lanes and gathered with other triangles' rests into full
//! bundles, `gather.rs`), with its vertices in every lane (loaded once) and the perspective
//! division of the whole bundle in one instruction ([`StripTri::resolve`](crate::raster::StripTri::resolve)); Phong with a classic material and Gouraud run
//! in lanes, the same formula as the scalar `shade_classic` and interpolation, so the same
//! bits whatever the width (tested: `eight_lanes_give_the_bits_of_four`). Physically based
//! materials stay on the scalar path.
//!
//! A pixel's `total` is the mean of its samples' totals I_tot (each layer is the mean of
//! its samples' values); a sample whose I_tot is not finite is left out and counted in
//! [`RenderStats::nan_samples`].
//!
//! Files: `dispatch.rs` runs the plan's passes (the public entry points, the frame-level
//! passes, the strips in parallel), `strip.rs` one strip (its visibility, shading
//! triangle by triangle, the resolve), `developed.rs` a plain render's strip developed to
//! 8-bit sRGB as it is shaded, `bundle.rs` a bundle of a triangle's samples in lanes
//! (Phong with a classic material, Gouraud), `gather.rs` triangles' rests gathered into full
//! Phong bundles, `stats.rs` what a render did. The measurements
//! behind this structure are in docs/performance.md.

mod bundle;
mod developed;
mod dispatch;
mod gather;
mod sample;
mod stats;
mod strip;
#[cfg(test)]
mod tests;
mod vertices;

pub use dispatch::{rasterize, render, render_image, render_with, same_raster};
pub use sample::{LitBy, LitPoint, SampleInputs, SampleSurface, sample_inputs};
pub use stats::{Counters, RenderStats, count_shadows};
