//! Shared helpers: run the binary, write temporary lessons, read PNGs.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The bundled lessons folder.
pub fn lessons_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons")
}

/// A `shadelab` command, with the on-disk cache off (a test that wants it passes `--cache`),
/// so no test reads another's results or writes outside its folders.
pub fn shadelab() -> assert_cmd::Command {
    let mut cmd = assert_cmd::Command::cargo_bin("shadelab").expect("binary is built");
    cmd.env("SHADELAB_NO_CACHE", "1");
    cmd
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

/// A unit sphere seen from (0, 0, 4), fov 30°, 41² pixels, under the gradient sky of zenith 2,
/// horizon 0.5, ground 0.1 (radiance), made of `[material.m]` with the keys `material`; `sky`
/// adds keys to `[environment]` (e.g. `background = true`). The environment and glass tests'
/// scene, the hidden checks' geometry.
pub fn sky_sphere(sky: &str, material: &str) -> String {
    format!(
        "[camera]\nposition = [0, 0, 4]\nfov_deg = 30\nsize = [41, 41]\n\n[[object]]\nshape = \"uv_sphere\"\nsegments = 128\nrings = 64\n\
         material = \"m\"\n\n[environment]\nkind = \"gradient\"\nzenith = 2.0\nhorizon = 0.5\nground = 0.1\n{sky}\n[material.m]\n{material}\n"
    )
}

/// The names of the `[[figure]]`s of lesson `path`, in file order.
pub fn figure_names(path: &std::path::Path) -> Vec<String> {
    let lesson = shadelab::lesson::load(path, &[]).expect("a valid lesson");
    lesson.figures.iter().map(|f| f.name.clone()).collect()
}
