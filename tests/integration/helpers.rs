//! Shared helpers: run the binary, write temporary lessons, read PNGs.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The bundled lessons folder.
pub fn lessons_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons")
}

/// A `shadelab` command.
pub fn shadelab() -> assert_cmd::Command {
    assert_cmd::Command::cargo_bin("shadelab").expect("binary is built")
}

/// Writes `text` as `name` in a fresh temporary folder; returns the folder (keep it alive) and the path.
pub fn lesson_file(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("write lesson");
    (dir, path)
}

/// Reads a PNG written by the program as 8-bit RGB.
pub fn read_png(path: &Path) -> image::RgbImage {
    image::open(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display())).to_rgb8()
}

/// Renders lesson text (as if read from `test.toml`, with `--set` overrides) through the
/// public API, keeping `layers`.
pub fn render_text(
    text: &str,
    sets: &[&str],
    layers: &[shadelab::render::Layer],
) -> (shadelab::render::Frame, shadelab::render::RenderStats) {
    let sets: Vec<shadelab::lesson::Override> = sets.iter().map(|s| shadelab::lesson::Override::parse(s).unwrap()).collect();
    let lesson = shadelab::lesson::parse(text, Path::new("test.toml"), &sets).unwrap_or_else(|e| panic!("{e}"));
    let scene = shadelab::scene::build::build(&lesson).unwrap();
    shadelab::render::render(&scene, layers)
}
