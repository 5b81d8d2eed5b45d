//! shadelab: a small software renderer that teaches shading models.
//!
//! Data flows forward only: `lesson` (TOML → validated lesson) → `scene` (meshes,
//! camera, lights, materials) → `render` (vertex stage, `raster`, `shading`) →
//! `render::develop` (tone map, sRGB) → `output` (atomic PNG/EXR). The library never
//! prints or exits; the `cli` module turns its errors into messages and exit codes.
#![warn(missing_docs)]

pub mod bench;
pub mod cli;
pub mod cost;
pub mod effects;
pub mod figure;
pub mod geometry;
pub mod lesson;
pub mod output;
pub mod raster;
pub mod render;
pub mod scene;
pub mod shading;
pub mod simd;
