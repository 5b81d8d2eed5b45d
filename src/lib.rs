//! shadelab: a small software renderer that teaches shading models.
//!
//! Data flows forward only: `lesson` (TOML → validated lesson) → `scene` (meshes in the
//! world, lights, materials) → `render` (the plan's passes: vertex stage, `raster`,
//! `shading` through the incident seam) → `render::develop` (tone map, sRGB) → `output`
//! (atomic PNG/EXR). Modules use only the layers below them (docs/architecture.md):
//! `simd`, `geometry`, `output`, `shading`, `raster`, `lesson`; then `scene`; `render` and
//! `effects`; `cost`, `figure`, `bench`; `site`; `cli`. The library never prints or exits; the
//! `cli` module turns its errors into messages and exit codes.
#![warn(missing_docs)]

pub mod bench;
pub mod bridge;
pub mod cache;
#[cfg(feature = "native")]
pub mod cli;
pub mod cost;
pub mod effects;
pub mod figure;
pub mod files;
pub mod geometry;
pub mod grade;
pub mod lesson;
pub mod light;
pub mod output;
pub mod raster;
pub mod render;
pub mod scene;
pub mod shading;
pub mod simd;
pub mod site;
pub mod transport;
