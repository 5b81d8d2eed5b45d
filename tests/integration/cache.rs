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
fn a_second_run_reads_the_figure_and_writes_the_same_bytes() {
    let work = tempfile::tempdir().unwrap();
    let (cache, out) = (work.path().join("cache"), work.path().join("out"));
    let l = lesson(work.path(), 1.0);
    let c = cache.to_str().unwrap();
    let first = figures(&l, &out, &["--cache", c]);
    assert!(first.contains("0 entries read, 3 computed") && !first.contains("from the cache"), "{first}");
    let kept = entries(&cache);
    assert_eq!(kept.len(), 3, "one entry a cell and one for the figure: {kept:?}");
    let before = png(&out);

    let second = figures(&l, &out, &["--cache", c]);
    assert!(second.lines().any(|l| l.contains("rough.png") && l.contains("from the cache, ")), "{second}");
    assert!(second.contains("1 entry read (1 whole figure), 0 computed"), "{second}");
    assert_eq!(png(&out), before, "the cached figure gives the same PNG bytes");

    // Damaged entries (a flipped byte, a cut) are dropped and computed afresh.
    for (i, entry) in kept.iter().enumerate() {
        let mut bytes = std::fs::read(entry).unwrap();
        if i % 2 == 0 {
            let mid = bytes.len() / 2;
            bytes[mid] ^= 0x40;
        } else {
            bytes.truncate(bytes.len() - 7);
        }
        std::fs::write(entry, bytes).unwrap();
    }
    let third = figures(&l, &out, &["--cache", c]);
    assert!(third.contains("0 entries read, 3 computed, 3 of them replacing unusable entries"), "{third}");
    assert_eq!(png(&out), before);
    // ... and kept again, whole.
    let fourth = figures(&l, &out, &["--cache", c]);
    assert!(fourth.contains("1 entry read (1 whole figure)"), "{fourth}");
    assert_eq!(png(&out), before);

    // Another caption: the figure is drawn again, from its cells in the cache.
    let text = std::fs::read_to_string(&l).unwrap().replace("values = [0.2, 0.5]", "values = [0.2, 0.5]\ncaption = \"Rough\"");
    std::fs::write(&l, text).unwrap();
    let captioned = figures(&l, &out, &["--cache", c]);
    assert!(captioned.contains("0 rasterizations, 2 from the cache"), "{captioned}");
    assert!(captioned.contains("2 entries read, 1 computed"), "{captioned}");
    assert_ne!(png(&out), before, "the caption is drawn");

    // `shadelab cache` shows the folder and its entries; --clear empties it.
    // (The captioned figure is kept too when drawing it took 20 ms or more.)
    let n = entries(&cache).len();
    assert!(n == 3 || n == 4, "{n}");
    let shown = shadelab().args(["--cache", c, "cache"]).assert().success().get_output().stdout.clone();
    assert!(String::from_utf8_lossy(&shown).contains(&format!("{c}: {n} entries")), "{}", String::from_utf8_lossy(&shown));
    let cleared = shadelab().args(["--cache", c, "cache", "--clear"]).assert().success().get_output().stdout.clone();
    let cleared = String::from_utf8_lossy(&cleared);
    assert!(cleared.contains(&format!("removed {n} files")) && cleared.contains(": 0 entries, 0.0 MB"), "{cleared}");
    assert!(entries(&cache).is_empty());
}

#[test]
fn a_cost_figure_keeps_its_times_for_this_machine_until_retime() {
    let work = tempfile::tempdir().unwrap();
    let (cache, out) = (work.path().join("cache"), work.path().join("out"));
    let l = lesson(work.path(), 1.0);
    let text = std::fs::read_to_string(&l).unwrap() + "\n[[figure]]\nname = \"cost\"\nkind = \"cost\"\nladder = \"ibl\"\n";
    std::fs::write(&l, text).unwrap();
    let c = cache.to_str().unwrap();
    let cost = |args: &[&str]| {
        let o = figures(&l, &out, &[&["--cache", c][..], args].concat());
        let line = o.lines().find(|l| l.contains("cost.png")).unwrap().to_string();
        (line, std::fs::read(out.join("lesson/cost.png")).unwrap())
    };
    let (first, timed) = cost(&[]);
    assert!(first.contains("rasterizations") && !first.contains("from the cache,"), "{first}");
    // Read back with the times it showed, and said so.
    let (second, again) = cost(&[]);
    assert!(second.contains("from the cache, its times from an earlier run on this machine"), "{second}");
    assert_eq!(again, timed);
    // Another thread count is another machine: timed afresh, its reference from the cache.
    let (other, _) = cost(&["--threads", "1"]);
    assert!(other.contains("3 rasterizations, 1 from the cache"), "{other}");
    // --retime times it again on this one, and keeps the new times.
    let retimed = shadelab()
        .args(["--cache", c, "figures"])
        .arg(&l)
        .arg("-o")
        .arg(&out)
        .arg("--retime")
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let retimed = String::from_utf8(retimed).unwrap();
    let line = retimed.lines().find(|l| l.contains("cost.png")).unwrap();
    assert!(line.contains("3 rasterizations, 1 from the cache"), "{retimed}");
    assert!(retimed.lines().any(|l| l.contains("rough.png") && l.contains("from the cache,")), "untimed figures are still read: {retimed}");
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
    assert!(brighter.contains("0 entries read, 3 computed"), "{brighter}");
    assert_ne!(png(&out), dim);
    // The same lesson text, the mesh file moved: its contents are part of the key.
    std::fs::write(work.path().join("quad.obj"), "v -1 -1 -1.5\nv 1 -1 -1\nv 1 -1 1\nv -1 -1 1\nf 1 2 3\nf 1 3 4\n").unwrap();
    let moved = figures(&l, &out, &["--cache", c]);
    assert!(moved.contains("0 entries read, 3 computed"), "{moved}");
    assert_eq!(entries(&cache).len(), 9);

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
    assert_eq!(entries(&other).len(), 3);
}
