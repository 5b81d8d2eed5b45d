//! Course CI, item 3: `--format jsonl` and `--annotations` of `render`, `figures` and
//! `snapshot` put each error where a tool (or a pull request) reads it.

use crate::helpers::shadelab;
use serde_json::Value;
use std::path::Path;

/// A small valid lesson with one split figure named `terms`.
const TINY: &str = "[camera]\nposition = [0, 0, 4]\nsize = [16, 16]\n[[object]]\nshape = \"uv_sphere\"\nsegments = 8\nrings = 4\nmaterial = \"m\"\n[material.m]\nmodel = \"phong\"\ndiffuse = [0.8, 0.2, 0.2]\nshininess = 16\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n\n[[figure]]\nname = \"terms\"\nkind = \"split\"\nlayers = [\"diffuse\", \"total\"]\n";

/// Every line of `stdout` as JSON (the test fails on any other line).
fn json_lines(stdout: &[u8]) -> Vec<Value> {
    String::from_utf8_lossy(stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("a line of stdout is not JSON ({e}): {l}")))
        .collect()
}

/// The 1-based line of the first line of `text` that contains `needle`.
fn line_of(text: &str, needle: &str) -> u64 {
    text.lines().position(|l| l.contains(needle)).map(|i| i as u64 + 1).unwrap_or_else(|| panic!("no `{needle}`"))
}

#[test]
fn figures_reports_every_invalid_lesson_at_its_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("a.toml"), TINY).unwrap();
    let b = TINY.replace("shininess = 16", "shininess = -3");
    let c = TINY.replace("model = \"phong\"", "model = \"phang\"");
    std::fs::write(dir.path().join("b.toml"), &b).unwrap();
    std::fs::write(dir.path().join("c.toml"), &c).unwrap();
    let out = dir.path().join("out");
    let a = shadelab().arg("figures").arg(dir.path()).arg("-o").arg(&out).args(["--format", "jsonl"]).assert().code(2);
    let found = json_lines(&a.get_output().stdout);
    let places: Vec<(String, u64, u64)> = found
        .iter()
        .map(|d| {
            assert_eq!(d["level"], "error", "{d}");
            let file = Path::new(d["file"].as_str().unwrap()).file_name().unwrap().to_string_lossy().into_owned();
            (file, d["line"].as_u64().unwrap(), d["column"].as_u64().unwrap())
        })
        .collect();
    assert_eq!(places, [("b.toml".into(), line_of(&b, "shininess"), 13), ("c.toml".into(), line_of(&c, "model"), 9)], "{found:?}");
    assert!(!out.exists(), "figures wrote files despite invalid lessons");
    // The same places as `check` gives.
    let a = shadelab().arg("check").arg(dir.path()).args(["--format", "jsonl"]).assert().code(2);
    let checked = json_lines(&a.get_output().stdout);
    for (f, c) in found.iter().zip(&checked) {
        assert_eq!((&f["file"], &f["line"], &f["column"], &f["key"]), (&c["file"], &c["line"], &c["column"], &c["key"]));
    }
    // Text, as before, names both and counts them.
    let a = shadelab().arg("figures").arg(dir.path()).arg("-o").arg(&out).assert().code(2);
    let stderr = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(stderr.contains("b.toml:") && stderr.contains("c.toml:") && stderr.contains("2 of 3 lessons are invalid"), "{stderr}");
}

#[test]
fn a_failing_snapshot_is_an_error_on_its_figures_line_for_each_ci() {
    let dir = tempfile::tempdir().unwrap();
    let lesson = dir.path().join("a.toml");
    std::fs::write(&lesson, TINY).unwrap();
    let snaps = dir.path().join("snaps");
    shadelab().arg("snapshot").arg(&lesson).arg("-o").arg(&snaps).arg("--bless").assert().success();
    // Passing: stdout holds nothing but diagnostics, and there are none.
    let a = shadelab().arg("snapshot").arg(&lesson).arg("-o").arg(&snaps).args(["--format", "jsonl"]).assert().success();
    assert!(a.get_output().stdout.is_empty(), "{}", String::from_utf8_lossy(&a.get_output().stdout));
    let changed = TINY.replace("[0.8, 0.2, 0.2]", "[0.2, 0.8, 0.2]");
    std::fs::write(&lesson, &changed).unwrap();
    let name_line = line_of(&changed, "name = \"terms\"");
    let a = shadelab().arg("snapshot").arg(&lesson).arg("-o").arg(&snaps).args(["--format", "jsonl"]).assert().code(1);
    let found = json_lines(&a.get_output().stdout);
    assert_eq!(found.len(), 1, "{found:?}");
    let d = &found[0];
    assert_eq!(
        (d["level"].as_str(), d["code"].as_str(), d["line"].as_u64(), d["column"].as_u64()),
        (Some("error"), Some("snapshot"), Some(name_line), Some(8))
    );
    assert!(d["message"].as_str().unwrap().contains("`terms` differs") && d["hint"].as_str().unwrap().contains("reproduce"), "{d}");
    // GitHub: a workflow command on that line (chosen by the environment, as in Actions).
    let a = shadelab().arg("snapshot").arg(&lesson).arg("-o").arg(&snaps).env("GITHUB_ACTIONS", "true").assert().code(1);
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    let command = stdout.lines().find(|l| l.starts_with("::error ")).unwrap_or_else(|| panic!("no workflow command:\n{stdout}"));
    assert!(command.contains(&format!("a.toml,line={name_line},col=8,title=shadelab snapshot::")), "{command}");
    assert!(stdout.contains("FAILED  a/terms"), "the text lines stay:\n{stdout}");
    // ...and none with --annotations none.
    let a = shadelab()
        .arg("snapshot")
        .arg(&lesson)
        .arg("-o")
        .arg(&snaps)
        .env("GITHUB_ACTIONS", "true")
        .args(["--annotations", "none"])
        .assert()
        .code(1);
    assert!(!String::from_utf8_lossy(&a.get_output().stdout).contains("::error"));
    // GitLab: a code-quality report in the current folder.
    let a =
        shadelab().arg("snapshot").arg(&lesson).arg("-o").arg(&snaps).args(["--annotations", "gitlab"]).current_dir(dir.path()).assert();
    a.code(1);
    let report: Value = serde_json::from_slice(&std::fs::read(dir.path().join("gl-code-quality-report.json")).unwrap()).unwrap();
    let entries = report.as_array().unwrap();
    assert_eq!(entries.len(), 1, "{report}");
    assert_eq!(entries[0]["check_name"], "shadelab-snapshot");
    assert_eq!(entries[0]["location"]["lines"]["begin"].as_u64(), Some(name_line));
    assert!(entries[0]["location"]["path"].as_str().unwrap().ends_with("a.toml"));
}

#[test]
fn render_gives_warnings_notes_and_usage_errors_as_json_too() {
    let dir = tempfile::tempdir().unwrap();
    let text = TINY.replace("shape = \"uv_sphere\"\nsegments = 8\nrings = 4", "shape = \"mesh\"\npath = \"m.obj\"");
    let lesson = dir.path().join("a.toml");
    std::fs::write(&lesson, &text).unwrap();
    // One degenerate triangle: a note at the object's table.
    std::fs::write(dir.path().join("m.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 1 2 4\nf 2 5 4\n").unwrap();
    let image = dir.path().join("x.png");
    let a = shadelab().arg("render").arg(&lesson).arg("-o").arg(&image).args(["--format", "jsonl"]).assert().success();
    assert!(image.is_file(), "the image's type comes from -o: a PNG");
    let found = json_lines(&a.get_output().stdout);
    assert_eq!(found.len(), 1, "only the note: no `wrote` line, no notes of the lesson\n{found:?}");
    assert_eq!((found[0]["level"].as_str(), found[0]["code"].as_str()), (Some("note"), Some("mesh")));
    assert!(found[0]["message"].as_str().unwrap().contains("1 degenerate triangle skipped"), "{}", found[0]);
    assert_eq!(found[0]["line"].as_u64(), Some(line_of(&text, "[[object]]")), "{}", found[0]);
    // `--format exr` still names the image's type.
    shadelab().arg("render").arg(&lesson).arg("-o").arg(dir.path().join("y/")).args(["--format", "exr"]).assert().success();
    assert!(dir.path().join("y/a.exr").is_file());
    // A command line that does not parse: a usage error, as JSON as well (exit 2).
    let a = shadelab().arg("render").arg(&lesson).args(["--size", "0x4", "--format", "jsonl"]).assert().code(2);
    let found = json_lines(&a.get_output().stdout);
    assert_eq!((found.len(), found[0]["code"].as_str(), found[0]["file"].is_null()), (1, Some("usage"), true), "{found:?}");
    assert!(found[0]["message"].as_str().unwrap().contains("--size"), "{}", found[0]);
}
