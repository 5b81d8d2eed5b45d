//! The on-disk cache across runs: a second run reads what the first kept and writes the
//! same bytes; a changed lesson or asset, a damaged entry or `--no-cache` renders afresh.

use crate::helpers::shadelab;
use std::path::{Path, PathBuf};

/// A sphere and an OBJ quad under a gradient sky by Monte Carlo (slow enough to be kept),
/// with one compare figure of two cells.
fn lesson(dir: &Path, intensity: f32) -> PathBuf {
    std::fs::write(dir.join("quad.obj"), "v -1 -1 -1\nv 1 -1 -1\nv 1 -1 1\nv -1 -1 1\nf 1 2 3\nf 1 3 4\n").unwrap();
    let text = format!(
        r#"
[camera]
position = [0, 0.5, 4]
fov_deg = 40
size = [48, 48]

[[object]]
shape = "uv_sphere"
material = "gold"

[[object]]
shape = "mesh"
path = "quad.obj"
material = "gold"

[material.gold]
model = "cook_torrance"
roughness = 0.3

[environment]
kind = "gradient"
zenith = 2.0
horizon = 0.5
ground = 0.1
intensity = {intensity}

[render]
ibl = "reference"
env_samples = 1024

[[figure]]
name = "rough"
kind = "sweep"
vary = "material.gold.roughness"
values = [0.2, 0.5]
"#
    );
    let path = dir.join("lesson.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs `figures` on `lesson` with `args` into `out`; returns stdout.
fn figures(lesson: &Path, out: &Path, args: &[&str]) -> String {
    let o = shadelab().args(args).arg("figures").arg(lesson).arg("-o").arg(out).assert().success().get_output().clone();
    String::from_utf8(o.stdout).unwrap()
}

fn png(out: &Path) -> Vec<u8> {
    std::fs::read(out.join("lesson/rough.png")).unwrap()
}

fn entries(cache: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = walk(cache).into_iter().filter(|p| p.extension().is_some_and(|x| x == "bin")).collect();
    v.sort();
    v
}

fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        if e.path().is_dir() {
            out.extend(walk(&e.path()));
        } else {
            out.push(e.path());
        }
    }
    out
}

#[test]
fn a_second_run_reads_the_cells_and_writes_the_same_bytes() {
    let work = tempfile::tempdir().unwrap();
    let (cache, out) = (work.path().join("cache"), work.path().join("out"));
    let l = lesson(work.path(), 1.0);
    let c = cache.to_str().unwrap();
    let first = figures(&l, &out, &["--cache", c]);
    assert!(first.contains("0 frames read, 2 rendered") && !first.contains("from the cache"), "{first}");
    let kept = entries(&cache);
    assert_eq!(kept.len(), 2, "one entry a cell: {kept:?}");
    let before = png(&out);

    let second = figures(&l, &out, &["--cache", c]);
    assert!(second.contains("0 rasterizations, 2 from the cache"), "{second}");
    assert!(second.contains("2 frames read, 0 rendered"), "{second}");
    assert_eq!(png(&out), before, "the cached frames give the same PNG bytes");

    // Damaged entries (one flipped byte, one cut short) are dropped and rendered afresh.
    let mut bytes = std::fs::read(&kept[0]).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x40;
    std::fs::write(&kept[0], bytes).unwrap();
    let cut = std::fs::read(&kept[1]).unwrap();
    std::fs::write(&kept[1], &cut[..cut.len() - 7]).unwrap();
    let third = figures(&l, &out, &["--cache", c]);
    assert!(third.contains("0 frames read, 2 rendered, 2 of them replacing unusable entries"), "{third}");
    assert_eq!(png(&out), before);
    // ... and kept again, whole.
    let fourth = figures(&l, &out, &["--cache", c]);
    assert!(fourth.contains("2 frames read"), "{fourth}");

    // `shadelab cache` shows the folder and its entries; --clear empties it.
    let shown = shadelab().args(["--cache", c, "cache"]).assert().success().get_output().stdout.clone();
    assert!(String::from_utf8_lossy(&shown).contains(&format!("{c}: 2 entries")), "{}", String::from_utf8_lossy(&shown));
    let cleared = shadelab().args(["--cache", c, "cache", "--clear"]).assert().success().get_output().stdout.clone();
    let cleared = String::from_utf8_lossy(&cleared);
    assert!(cleared.contains("removed 2 files") && cleared.contains(": 0 entries, 0.0 MB"), "{cleared}");
    assert!(entries(&cache).is_empty());
}

#[test]
fn a_changed_lesson_or_asset_is_rendered_afresh_and_no_cache_keeps_nothing() {
    let work = tempfile::tempdir().unwrap();
    let (cache, out) = (work.path().join("cache"), work.path().join("out"));
    let c = cache.to_str().unwrap();
    let l = lesson(work.path(), 1.0);
    figures(&l, &out, &["--cache", c]);
    let dim = png(&out);
    // Another intensity: other keys.
    lesson(work.path(), 2.0);
    let brighter = figures(&l, &out, &["--cache", c]);
    assert!(brighter.contains("0 frames read, 2 rendered"), "{brighter}");
    assert_ne!(png(&out), dim);
    // The same lesson text, the mesh file moved: its contents are part of the key.
    std::fs::write(work.path().join("quad.obj"), "v -1 -1 -1.5\nv 1 -1 -1\nv 1 -1 1\nv -1 -1 1\nf 1 2 3\nf 1 3 4\n").unwrap();
    let moved = figures(&l, &out, &["--cache", c]);
    assert!(moved.contains("0 frames read, 2 rendered"), "{moved}");
    assert_eq!(entries(&cache).len(), 6);

    // --no-cache beats $SHADELAB_CACHE_DIR: nothing read, nothing written, no cache line.
    let other = work.path().join("other");
    let o = shadelab()
        .env_remove("SHADELAB_NO_CACHE")
        .env("SHADELAB_CACHE_DIR", &other)
        .args(["--no-cache", "figures"])
        .arg(&l)
        .arg("-o")
        .arg(&out)
        .assert()
        .success()
        .get_output()
        .clone();
    assert!(!String::from_utf8_lossy(&o.stdout).contains("cache ("));
    assert!(!other.exists());
    // Without flags, $SHADELAB_CACHE_DIR is the folder.
    shadelab()
        .env_remove("SHADELAB_NO_CACHE")
        .env("SHADELAB_CACHE_DIR", &other)
        .arg("figures")
        .arg(&l)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    assert_eq!(entries(&other).len(), 2);
}
