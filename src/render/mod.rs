//! Scene → frame: the vertex stage, the rasterizer, shading and development to sRGB.

mod agx;
pub mod budget;
pub mod cached;
pub mod develop;
#[cfg(target_arch = "x86_64")]
mod encode_avx2;
#[cfg(target_arch = "x86_64")]
mod encode_avx512;
pub mod explain;
pub mod frame;
pub mod path;
pub mod pipeline;
pub mod pixel;
pub mod pixel_text;
pub mod plan;
pub mod probe;
pub mod srgb;
pub mod texturing;

pub use crate::lesson::settings::{Cull, Interpolation, RenderSettings, Tonemap};
pub use frame::{Frame, Layer};
pub use pipeline::{RenderStats, rasterize, render, render_image, render_with, same_raster};
pub use plan::{Plan, plan};
