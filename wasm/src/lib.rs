//! The live lab's entry points: a lesson's text, its `--set` overrides and its files in, the
//! developed layers out. The same validation, scene build, budget and renderer as
//! `shadelab render`, so the same lesson gives the same bytes, and a bad value the same
//! message, as on the command line.

use shadelab::render::{self, Layer};
use std::path::Path;
use wasm_bindgen::prelude::*;

/// The layers the live view shows: the picture, then the illumination equation's terms.
const LAYERS: [Layer; 4] = [Layer::Total, Layer::Ambient, Layer::Diffuse, Layer::Specular];

/// One rendered frame: its size and each layer as 8-bit sRGB RGBA (opaque).
#[wasm_bindgen]
pub struct Frame {
    width: u32,
    height: u32,
    layers: Vec<Vec<u8>>,
    nan_samples: u64,
}

#[wasm_bindgen]
impl Frame {
    /// Width in pixels.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Layer `i` (0 total, 1 ambient, 2 diffuse, 3 specular) as RGBA bytes; empty when this
    /// render method does not separate it (the path tracer fills only the total).
    pub fn layer(&self, i: usize) -> Vec<u8> {
        self.layers.get(i).cloned().unwrap_or_default()
    }

    /// Samples that were not finite and were set to black (the CLI warns about them).
    #[wasm_bindgen(getter)]
    pub fn nan_samples(&self) -> u64 {
        self.nan_samples
    }
}

/// Hands the renderer a file a lesson reads (a mesh, a texture, an environment map), at the
/// path the lesson's folder gives it, e.g. `lessons/hdri/studio.hdr`.
#[wasm_bindgen]
pub fn provide_file(path: &str, bytes: Vec<u8>) {
    shadelab::files::provide(Path::new(path), bytes);
}

/// Renders the lesson `text` (read as the file `path`) with `sets`, each a `--set` argument
/// (`material.plastic.shininess=64`), as `shadelab render` does.
///
/// # Errors
/// The CLI's message (`error: FILE:LINE:COL: ...` with its hint) for a bad value, a bad
/// file or a render over the budget.
#[wasm_bindgen]
pub fn render(path: &str, text: &str, sets: Vec<String>) -> Result<Frame, String> {
    let path = Path::new(path);
    let overrides = sets
        .iter()
        .map(|s| shadelab::lesson::Override::parse(s).map_err(|m| format!("error: in --set {s}: {m}")))
        .collect::<Result<Vec<_>, _>>()?;
    let lesson = shadelab::lesson::parse(text, path, &overrides).map_err(|e| format!("error: {e}"))?;
    let scene = shadelab::scene::build::build(&lesson).map_err(|e| format!("error: {e}"))?;
    render::budget::check(&scene).map_err(|e| format!("error: {}", e.at(path.display())))?;
    // The path tracer fills the total alone: its terms are not asked for, so they stay empty.
    let s = &scene.spec.settings;
    let asked = if s.method == shadelab::lesson::settings::RenderMethod::Path { &LAYERS[..1] } else { &LAYERS[..] };
    let (frame, stats) = render::render(&scene, asked);
    let layers =
        asked.iter().map(|&l| render::develop::develop_rgba(&frame, l, s.exposure, s.tonemap, false).unwrap_or_default()).collect();
    Ok(Frame { width: scene.spec.camera.width, height: scene.spec.camera.height, layers, nan_samples: stats.nan_samples })
}

/// The build's version, for the page to check it matches the site that loads it.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}
