//! Snapshot testing: the bundled lessons against tests/snapshots, and proof the check can fail.

use crate::helpers::{lessons_dir, shadelab};
use std::path::Path;

/// The flags the project's snapshots are blessed with (small cells keep CI fast); they are
/// recorded in tests/snapshots/snapshot.toml, so the plain command checks with them.
/// Re-bless after an intended change with:
/// `cargo run --release -- snapshot lessons --dir tests/snapshots --bless`
const FLAGS: [&str; 4] = ["--cell", "96x96", "--scale", "0.5"];

fn snapshots_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots")
}

/// Copies the blessed snapshots to a temporary folder, so failures write their diff images there.
fn copy_snapshots() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(snapshots_dir().join("snapshot.toml"), dir.path().join("snapshot.toml")).unwrap();
    for lesson in std::fs::read_dir(snapshots_dir()).unwrap() {
        let lesson = lesson.unwrap().path();
        if !lesson.is_dir() {
            continue;
        }
        let to = dir.path().join(lesson.file_name().unwrap());
        std::fs::create_dir_all(&to).unwrap();
        for f in std::fs::read_dir(&lesson).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == "png")
                && !f.to_string_lossy().contains(".diff.")
                && !f.to_string_lossy().contains(".actual.")
            {
                std::fs::copy(&f, to.join(f.file_name().unwrap())).unwrap();
            }
        }
    }
    dir
}

#[test]
fn every_bundled_figure_matches_its_snapshot() {
    let dir = copy_snapshots();
    // No flags: the documented command, `shadelab snapshot lessons/ --dir tests/snapshots`,
    // checks with the flags recorded when the snapshots were blessed.
    let a = shadelab().arg("snapshot").arg(lessons_dir()).arg("--dir").arg(dir.path()).assert();
    let out = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(a.get_output().status.success(), "snapshots differ (re-bless if the change is intended):\n{out}");
    // Every lesson with figures was compared, none skipped.
    let lessons_with_figures = std::fs::read_dir(snapshots_dir()).unwrap().filter(|e| e.as_ref().unwrap().path().is_dir()).count();
    assert!(lessons_with_figures >= 8, "{lessons_with_figures} lessons have snapshots");
    assert!(out.contains(" 0 failed") && !out.contains("orphaned"), "{out}");
}

#[test]
fn strict_catches_the_small_change_the_default_tolerance_lets_through() {
    let dir = copy_snapshots();
    let lesson = lessons_dir().join("01-first-light.toml");
    let check = |strict: bool| {
        let mut cmd = shadelab();
        cmd.arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).args(["--set", "material.plastic.diffuse=[0.707, 0.04, 0.03]"]);
        if strict {
            cmd.arg("--strict");
        }
        cmd.output().unwrap()
    };
    // A 1% change of the diffuse red: within 2 codes, so the default passes it (documented).
    let loose = check(false);
    assert!(loose.status.success(), "{}", String::from_utf8_lossy(&loose.stdout));
    let strict = check(true);
    assert_eq!(strict.status.code(), Some(1), "{}", String::from_utf8_lossy(&strict.stdout));
    assert!(String::from_utf8_lossy(&strict.stdout).contains("FAILED  01-first-light/split"));
}

#[test]
fn snapshots_with_no_figure_behind_them_are_reported_failed_under_strict_and_removed_by_bless() {
    let dir = copy_snapshots();
    let lessons = tempfile::tempdir().unwrap();
    std::fs::copy(lessons_dir().join("01-first-light.toml"), lessons.path().join("01-first-light.toml")).unwrap();
    let old = dir.path().join("01-first-light/renamed-figure.png");
    std::fs::copy(dir.path().join("01-first-light/split.png"), &old).unwrap();
    let run = |extra: &[&str]| shadelab().arg("snapshot").arg(lessons.path()).arg("--dir").arg(dir.path()).args(extra).output().unwrap();
    let o = run(&[]);
    let (out, err) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success(), "orphans alone do not fail by default: {out}{err}");
    assert!(err.contains("orphan  01-first-light/renamed-figure: the lesson has no figure `renamed-figure`"), "{err}");
    // The folder holds every bundled lesson's snapshots; only lesson 01 was checked.
    assert!(err.contains("orphan  04-shininess: no lesson `04-shininess.toml`"), "{err}");
    assert!(out.contains("orphaned"), "{out}");
    assert_eq!(run(&["--strict"]).status.code(), Some(1));
    let o = run(&["--bless"]);
    assert!(o.status.success() && !old.exists(), "bless removes the figure's orphan: {}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.path().join("04-shininess").is_dir(), "a lesson's folder is only reported, never deleted");
}

#[test]
fn changing_one_shininess_value_makes_the_snapshot_mismatch() {
    let dir = copy_snapshots();
    let lesson = lessons_dir().join("01-first-light.toml");
    let a = shadelab()
        .arg("snapshot")
        .arg(&lesson)
        .arg("--dir")
        .arg(dir.path())
        .args(FLAGS)
        .args(["--set", "material.plastic.shininess=8"])
        .assert()
        .code(1);
    let out = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(out.contains("FAILED  01-first-light/split"), "{out}");
    assert!(out.contains("1 failed"), "{out}");
    let diff = dir.path().join("01-first-light/split.diff.png");
    let img = image::open(&diff).expect("a diff image is written").to_rgba8();
    // Differing pixels are drawn in red.
    assert!(img.pixels().any(|p| p[0] > 128 && p[1] == 0 && p[2] == 0));
    assert!(dir.path().join("01-first-light/split.actual.png").is_file());
    // Unchanged, it matches, and the failure's images are gone.
    shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).args(FLAGS).assert().success();
    assert!(!diff.exists() && !dir.path().join("01-first-light/split.actual.png").exists(), "stale diff images are removed");
}

#[test]
fn bless_writes_snapshots_that_then_match_and_a_missing_one_fails() {
    let dir = tempfile::tempdir().unwrap();
    let lesson = lessons_dir().join("01-first-light.toml");
    let a = shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).args(FLAGS).assert().code(1);
    // The missing file is named, with the command that blesses it.
    let out = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    let file = dir.path().join("01-first-light/split.png");
    assert!(out.contains(&format!("no snapshot at {}", file.display())), "{out}");
    assert!(
        out.contains(&format!("hint: bless it with `shadelab snapshot {} -o {} --bless`", lesson.display(), dir.path().display())),
        "{out}"
    );
    shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).args(FLAGS).arg("--bless").assert().success();
    assert!(dir.path().join("01-first-light/split.png").is_file());
    shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).args(FLAGS).assert().success();
    // The flags were recorded: a check without them uses them, and other flags are noted (and fail).
    let record = std::fs::read_to_string(dir.path().join("snapshot.toml")).unwrap();
    assert!(record.contains("cell = [96, 96]") && record.contains("scale = 0.5"), "{record}");
    shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).assert().success();
    let a = shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).args(["--cell", "64x64"]).assert().code(1);
    let err = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(err.contains("blessed with --theme light --scale 0.5 --cell 96x96") && err.contains("--cell 64x64"), "{err}");
    // A re-bless without flags keeps the recorded ones.
    shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(dir.path()).arg("--bless").assert().success();
    assert_eq!(std::fs::read_to_string(dir.path().join("snapshot.toml")).unwrap(), record);
}
