//! Bad input through the real binary: every class of mistake exits with 2, names the
//! file, the `line:col` and the key path, gives a hint where one helps, never panics and
//! never leaves an image (or a temporary file) behind.
//!
//! This file holds the lesson and the workspace the topic files share.

mod files;
mod fog;
mod keys;
mod overrides;
mod probe;
mod textures;
mod values;

use crate::helpers::{read_png, shadelab};
use std::path::{Path, PathBuf};

/// The lesson most cases edit one line of. Line numbers, for the expected positions:
///
/// ```text
///  1 [camera]                       9 [material.plastic]
///  2 position = [0, 0, 4]          10 model = "blinn_phong"
///  3 size = [32, 32]               11 diffuse = [0.8, 0.2, 0.2]
///  4                               12 shininess = 32
///  5 [[object]]                    13
///  6 shape = "uv_sphere"           14 [[light]]
///  7 material = "plastic"          15 kind = "directional"
///  8                               16 direction = [0, 0, -1]
/// ```
const BASE: &str = r#"[camera]
position = [0, 0, 4]
size = [32, 32]

[[object]]
shape = "uv_sphere"
material = "plastic"

[material.plastic]
model = "blinn_phong"
diffuse = [0.8, 0.2, 0.2]
shininess = 32

[[light]]
kind = "directional"
direction = [0, 0, -1]
"#;

/// [`BASE`] with the text `from` (which must occur exactly once) replaced by `to`.
#[track_caller]
fn edit(from: &str, to: &str) -> String {
    assert_eq!(BASE.matches(from).count(), 1, "`{from}` must occur once in BASE");
    BASE.replacen(from, to, 1)
}

/// [`BASE`] followed by `tail` (line 17 is empty, so a table appended as
/// `"\n[render]\naa = 0\n"` has its header on line 18 and its first key on line 19).
fn append(tail: &str) -> String {
    format!("{BASE}{tail}")
}

/// A folder holding `lesson.toml` and an empty `out/` folder for the image.
struct Workspace {
    dir: tempfile::TempDir,
}

impl Workspace {
    fn new(text: &str) -> Workspace {
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::write(dir.path().join("lesson.toml"), text).expect("write lesson");
        std::fs::create_dir(dir.path().join("out")).expect("create out/");
        Workspace { dir }
    }

    /// Writes another file next to the lesson (an OBJ, a second lesson).
    fn write(&self, name: &str, text: &str) -> &Workspace {
        std::fs::write(self.dir.path().join(name), text).expect("write file");
        self
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn lesson(&self) -> PathBuf {
        self.path("lesson.toml")
    }

    fn output(&self) -> PathBuf {
        self.path("out").join("render.png")
    }

    /// `shadelab render LESSON -o out/render.png ARGS...`: must fail as bad input.
    #[track_caller]
    fn render_fails(&self, args: &[&str]) -> Failure {
        self.fails_with(&self.lesson(), args)
    }

    /// As [`Workspace::render_fails`] for another lesson path.
    #[track_caller]
    fn fails_with(&self, lesson: &Path, args: &[&str]) -> Failure {
        let out = shadelab().arg("render").arg(lesson).arg("-o").arg(self.output()).args(args).output().expect("run shadelab");
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let shown = format!("args: {args:?}\n--- stderr ---\n{stderr}--- stdout ---\n{stdout}");
        assert_eq!(out.status.code(), Some(2), "expected exit code 2 (bad input)\n{shown}");
        assert!(!stderr.contains("panicked"), "the program panicked\n{shown}");
        assert!(!self.output().exists(), "an image was written despite the error\n{shown}");
        let left: Vec<_> = std::fs::read_dir(self.path("out")).expect("read out/").map(|e| e.expect("entry").file_name()).collect();
        assert!(left.is_empty(), "files left in the output folder: {left:?}\n{shown}");
        same_places_in_jsonl(lesson, args, &stderr);
        Failure { stderr, shown }
    }

    /// `shadelab render LESSON -o out/render.png ARGS...`: must succeed; returns the image.
    #[track_caller]
    fn render_ok(&self, args: &[&str]) -> image::RgbImage {
        let out = shadelab().arg("render").arg(self.lesson()).arg("-o").arg(self.output()).args(args).output().expect("run shadelab");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "expected success, args {args:?}\n--- stderr ---\n{stderr}");
        read_png(&self.output())
    }
}

/// Course CI, item 3: every `FILE:LINE:COL` the text error names is a diagnostic of
/// `render --format jsonl` (which prints nothing else on stdout, and at least one error even
/// when the place is no line of the lesson, and writes no image) and of `check --format
/// jsonl` (when the run's arguments are only `--set`s, which `check` takes too), with the
/// same file, line and column.
#[track_caller]
fn same_places_in_jsonl(lesson: &Path, args: &[&str], stderr: &str) {
    let name = lesson.file_name().unwrap().to_string_lossy().into_owned();
    // The places the text names: "NAME:LINE:COL: " at a line's start or after "error: ".
    let mut places: Vec<(u64, u64)> = Vec::new();
    for line in stderr.lines() {
        let Some(at) = line.find(&format!("{name}:")) else { continue };
        let rest = &line[at + name.len() + 1..];
        let mut it = rest.splitn(3, ':');
        if let (Some(l), Some(c), Some(_)) = (it.next(), it.next(), it.next())
            && let (Ok(l), Ok(c)) = (l.parse(), c.parse())
        {
            places.push((l, c));
        }
    }
    let errors = |stdout: &str| -> Vec<serde_json::Value> {
        stdout
            .lines()
            .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap_or_else(|e| panic!("not JSON ({e}): {l}")))
            .filter(|d| d["level"] == "error")
            .collect()
    };
    let placed = |found: &[serde_json::Value]| -> Vec<(u64, u64)> {
        found
            .iter()
            .filter(|d| d["file"].as_str().is_some_and(|f| f.ends_with(&name)))
            .filter_map(|d| Some((d["line"].as_u64()?, d["column"].as_u64()?)))
            .collect()
    };
    if !args.contains(&"--format") {
        let dir = tempfile::tempdir().unwrap();
        let image = dir.path().join("x.png");
        let out = shadelab().arg("render").arg(lesson).arg("-o").arg(&image).args(args).args(["--format", "jsonl"]).output().unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.code(), Some(2), "render --format jsonl fails as render did:\n{stdout}");
        assert!(!image.exists(), "render --format jsonl wrote an image despite the error");
        let found = errors(&stdout);
        assert!(!found.is_empty(), "no error in render --format jsonl:\n{stdout}\n--- render said ---\n{stderr}");
        let found = placed(&found);
        for p in &places {
            assert!(found.contains(p), "{name}:{}:{} is not in render --format jsonl:\n{stdout}\n--- render said ---\n{stderr}", p.0, p.1);
        }
    }
    if args.chunks(2).any(|pair| pair[0] != "--set" || pair.len() < 2) {
        return;
    }
    let out = shadelab().arg("check").arg(lesson).args(args).args(["--format", "jsonl"]).output().expect("run shadelab");
    assert_eq!(out.status.code(), Some(2), "check fails as render did");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let found = placed(&errors(&stdout));
    for p in &places {
        assert!(found.contains(p), "{name}:{}:{} is not in check --format jsonl:\n{stdout}\n--- render said ---\n{stderr}", p.0, p.1);
    }
}

/// What a failed run printed, with assertions that show it all when they fail.
struct Failure {
    stderr: String,
    shown: String,
}

impl Failure {
    /// The message points at `lesson.toml:LINE:COL: `.
    #[track_caller]
    fn at(&self, line: usize, col: usize) -> &Failure {
        self.says(&format!("lesson.toml:{line}:{col}: "))
    }

    /// The message names the key path in backticks.
    #[track_caller]
    fn key(&self, key: &str) -> &Failure {
        self.says(&format!("`{key}`: "))
    }

    /// The message contains `text`.
    #[track_caller]
    fn says(&self, text: &str) -> &Failure {
        assert!(self.stderr.contains(text), "stderr should contain {text:?}\n{}", self.shown);
        self
    }

    /// A `  hint: ` line contains `text`.
    #[track_caller]
    fn hint(&self, text: &str) -> &Failure {
        let hints: Vec<&str> = self.stderr.lines().filter_map(|l| l.strip_prefix("  hint: ")).collect();
        assert!(hints.iter().any(|h| h.contains(text)), "a hint should contain {text:?}\n{}", self.shown);
        self
    }
}

/// Renders `text` and expects it to fail.
#[track_caller]
fn fails(text: &str) -> Failure {
    Workspace::new(text).render_fails(&[])
}
