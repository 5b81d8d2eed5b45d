//! The command line beyond lesson errors: a closed stdout, output files and their
//! extensions, `brdf eval` input, help texts, `snapshot --bless`, `lessons`, mesh notes.

use crate::helpers::{lesson_file, lessons_dir, shadelab};
use std::path::Path;
use std::process::{Command, Stdio};

/// A small lesson with one classic and one physically based material and a figure.
const LESSON: &str = r#"[camera]
position = [0, 0, 4]
size = [24, 24]

[[object]]
shape = "uv_sphere"
segments = 12
rings = 6
material = "plastic"

[material.plastic]
model = "blinn_phong"
diffuse = [0.8, 0.2, 0.2]

[material.ggx]
model = "cook_torrance"
alpha = 0.2

[[light]]
kind = "directional"
direction = [0, 0, -1]

[[figure]]
name = "shininess"
kind = "sweep"
vary = "material.plastic.shininess"
values = [4, 64]
"#;

/// Runs `shadelab ARGS` with stdout a pipe whose reader is already closed (as after
/// `| head -1`), stdin from `input`; returns (exit code, stderr).
fn with_closed_stdout(args: &[&str], input: &str) -> (Option<i32>, String) {
    let (reader, writer) = std::io::pipe().expect("pipe");
    // Closed before the program starts: its first write to stdout fails with EPIPE.
    drop(reader);
    let mut child = Command::new(env!("CARGO_BIN_EXE_shadelab"))
        .env("SHADELAB_NO_CACHE", "1")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(writer)
        .stderr(Stdio::piped())
        .spawn()
        .expect("run shadelab");
    {
        use std::io::Write;
        let mut stdin = child.stdin.take().expect("stdin");
        let _ = stdin.write_all(input.as_bytes());
    }
    let out = child.wait_with_output().expect("wait");
    (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn a_closed_stdout_is_a_quiet_successful_end_for_every_subcommand() {
    let (dir, lesson) = lesson_file("lesson.toml", LESSON);
    let out = dir.path().join("out");
    let l = lesson.to_str().expect("utf-8 path");
    let o = out.to_str().expect("utf-8 path");
    let png = format!("{o}/x.png");
    let lessons = lessons_dir();
    let lessons = lessons.to_str().expect("utf-8 path");
    let runs: Vec<(Vec<&str>, &str)> = vec![
        (vec!["render", l, "-o", &png], ""),
        (vec!["check", l], ""),
        (vec!["figures", l, "-o", o], ""),
        (vec!["compare", l, "--vary", "render.interpolation=flat,phong", "-o", &png], ""),
        (vec!["sweep", l, "--vary", "material.plastic.shininess=4,64", "-o", &png], ""),
        (vec!["split", l, "-o", &png], ""),
        (vec!["watch", l, "-o", o, "--once"], ""),
        (vec!["lessons", lessons], ""),
        (vec!["snapshot", l, "--dir", o, "--bless"], ""),
        (vec!["explain", l], ""),
        (vec!["brdf", "eval", l, "--material", "ggx"], "0,0,1,0,0,1\n"),
        (vec!["brdf", "albedo", l, "--material", "ggx", "--format", "csv", "--samples", "2"], ""),
        (vec!["brdf", "lobe", l, "--material", "ggx", "-o", &png], ""),
        (vec!["bench", "--workload", "sphere", "--frames", "1", "--warmup", "0"], ""),
        (vec!["cost", l, "--ladder", "aa", "--repeat", "1", "--warmup", "0", "--size", "16x16"], ""),
    ];
    for (args, input) in runs {
        let (code, stderr) = with_closed_stdout(&args, input);
        assert!(!stderr.contains("panicked"), "shadelab {args:?} panicked on a closed stdout:\n{stderr}");
        assert_eq!(code, Some(0), "shadelab {args:?} should end quietly with 0:\n{stderr}");
        assert!(!stderr.contains("Broken pipe") && !stderr.contains("error"), "shadelab {args:?} should print nothing about it:\n{stderr}");
    }
}

// ---- brdf ----------------------------------------------------------------------------------

fn brdf_eval(input: &str) -> (Option<i32>, String, String) {
    let (_dir, lesson) = lesson_file("lesson.toml", LESSON);
    let out = shadelab().args(["brdf", "eval"]).arg(&lesson).args(["--material", "ggx"]).write_stdin(input).output().expect("run");
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn brdf_eval_takes_only_a_header_of_words_and_prints_nothing_on_a_bad_line() {
    // A header of words, blank lines: fine.
    let (code, stdout, stderr) = brdf_eval("lx,ly,lz,vx,vy,vz\n\n0,0,1,0,0,1\n\n0.6,0,0.8,-0.6,0,0.8\n");
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stdout.lines().count(), 3, "{stdout}");
    // A first row that is numbers but not six of them is an error, not a header.
    let (code, stdout, stderr) = brdf_eval("0,0,1,0,0\n0,0,1,0,0,1\n");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("stdin:1: expected 6 numbers lx,ly,lz,vx,vy,vz, got `0,0,1,0,0` (5 fields)"), "{stderr}");
    assert!(stdout.is_empty(), "a bad batch printed {stdout:?}");
    let (code, _, stderr) = brdf_eval("0,0,1,zero,0,1\n");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("stdin:1: ") && stderr.contains("field 4 `zero` is not a number"), "{stderr}");
    // A bad line after good ones: still nothing printed.
    let (code, stdout, stderr) = brdf_eval("lx,ly,lz,vx,vy,vz\n0,0,1,0,0,1\n\n1,2,x\n");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("stdin:4: "), "{stderr}");
    assert!(stdout.is_empty(), "a bad batch printed {stdout:?}");
    // Only the first line may be a header.
    let (code, _, stderr) = brdf_eval("0,0,1,0,0,1\nlx,ly,lz,vx,vy,vz\n");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("stdin:2: "), "{stderr}");
    // A first line in another separator, or one word, is a bad line, not a header to drop.
    for first in ["0 0 1 0 0 1", "0;0;1;0;0;1", "foo"] {
        let (code, stdout, stderr) = brdf_eval(&format!("{first}\n0,0,1,0,0,1\n"));
        assert_eq!(code, Some(2), "{first}: {stderr}");
        assert!(stderr.contains(&format!("stdin:1: expected 6 numbers lx,ly,lz,vx,vy,vz, got `{first}`")), "{stderr}");
        assert!(stdout.is_empty(), "{stdout:?}");
    }
}

fn is_png(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|b| b.starts_with(b"\x89PNG"))
}

fn is_svg(path: &Path) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| t.contains("<svg"))
}

#[test]
fn brdf_lobe_and_albedo_write_the_files_named_by_o() {
    let (dir, lesson) = lesson_file("lesson.toml", LESSON);
    let d = dir.path();
    // `-o x.svg`: the SVG there, the PNG beside it; each file holds its own format.
    let a = shadelab().args(["brdf", "lobe"]).arg(&lesson).args(["--material", "ggx", "-o"]).arg(d.join("x.svg")).assert().success();
    assert!(is_svg(&d.join("x.svg")) && is_png(&d.join("x.png")));
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(stdout.contains("x.png and") && stdout.contains("x.svg"), "{stdout}");
    shadelab()
        .args(["brdf", "albedo"])
        .arg(&lesson)
        .args(["--material", "ggx", "--samples", "2", "-o"])
        .arg(d.join("a.png"))
        .assert()
        .success();
    assert!(is_png(&d.join("a.png")) && is_svg(&d.join("a.svg")));
    // Another extension is refused before anything is written.
    let a = shadelab().args(["brdf", "lobe"]).arg(&lesson).args(["--material", "ggx", "-o"]).arg(d.join("x.jpg")).assert().code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("must end in .png or .svg"));
    assert!(!d.join("x.jpg").exists());
    // CSV with -o goes to the file, not stdout.
    let csv = d.join("albedo.csv");
    let a = shadelab()
        .args(["brdf", "albedo"])
        .arg(&lesson)
        .args(["--material", "ggx", "--format", "csv", "--cos", "1,0.5", "--samples", "2", "-o"])
        .arg(&csv)
        .assert()
        .success();
    let text = std::fs::read_to_string(&csv).expect("the CSV is written to -o");
    assert_eq!(text.lines().next(), Some("material,cos_theta,albedo,error_bound"));
    assert_eq!(text.lines().count(), 3, "{text}");
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(!stdout.contains("material,cos_theta"), "the CSV went to stdout too: {stdout}");
    // --cos without csv would be ignored: refused.
    shadelab().args(["brdf", "albedo"]).arg(&lesson).args(["--material", "ggx", "--cos", "1", "-o"]).arg(d.join("b.png")).assert().code(2);
}

#[test]
fn figure_commands_refuse_a_name_that_is_not_png() {
    let (dir, lesson) = lesson_file("lesson.toml", LESSON);
    let jpg = dir.path().join("f.jpg");
    for args in [&["compare", "--vary", "render.aa=1,2"][..], &["sweep", "--vary", "render.aa=1,2"], &["split"]] {
        let a = shadelab().arg(args[0]).arg(&lesson).args(&args[1..]).arg("-o").arg(&jpg).assert().code(2);
        assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("figures are PNG images, not .jpg"), "{args:?}");
        assert!(!jpg.exists());
    }
}

// ---- help ------------------------------------------------------------------------------------

fn help(sub: &str) -> String {
    String::from_utf8_lossy(&shadelab().args([sub, "--help"]).assert().success().get_output().stdout).into_owned()
}

#[test]
fn compare_and_sweep_have_their_own_help() {
    let compare = help("compare");
    assert!(!compare.contains("twice") && !compare.contains("grid"), "compare does not make grids:\n{compare}");
    assert!(help("sweep").contains("twice for a rows × columns grid"));
    let (_dir, lesson) = lesson_file("lesson.toml", LESSON);
    let a = shadelab().arg("compare").arg(&lesson).args(["--vary", "render.aa=1,2", "--vary", "render.cull=back,none"]).assert().code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("--vary"));
}

// ---- snapshot, lessons -------------------------------------------------------------------------

#[test]
fn snapshot_bless_writes_nothing_when_one_lesson_is_bad() {
    let (dir, _) = lesson_file("a-good.toml", LESSON);
    std::fs::write(dir.path().join("b-bad.toml"), LESSON.replace("values = [4, 64]", "values = [4, -1]")).expect("write");
    let snaps = dir.path().join("snaps");
    let a = shadelab().arg("snapshot").arg(dir.path()).arg("--dir").arg(&snaps).arg("--bless").assert().code(2);
    let stderr = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(stderr.contains("b-bad.toml:") && stderr.contains("-1 is out of range"), "{stderr}");
    assert!(!snaps.exists(), "snapshots were blessed despite the bad lesson: {:?}", std::fs::read_dir(&snaps).map(|d| d.count()));
}

#[test]
fn lessons_outside_the_repository_says_where_it_looked() {
    let dir = tempfile::tempdir().expect("temp dir");
    // No `lessons` here: the source tree's bundled lessons are listed, and where they are.
    let a = shadelab().arg("lessons").current_dir(dir.path()).assert().success();
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    let stderr = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(stdout.contains("01-first-light.toml") && stdout.contains("15-cost.toml"), "{stdout}");
    assert!(stderr.contains(&format!("lessons in {}", lessons_dir().display())), "{stderr}");
    // A folder that is not there is named, with the fix.
    let a = shadelab().args(["lessons", "missing"]).current_dir(dir.path()).assert().code(2);
    let stderr = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    let looked = std::path::absolute(dir.path().join("missing")).expect("absolute");
    assert!(stderr.contains(&format!("no lessons folder: {} does not exist", looked.display())), "{stderr}");
    assert!(stderr.contains("hint: ") && stderr.contains("`shadelab lessons PATH`"), "{stderr}");
}

// ---- mesh repairs ------------------------------------------------------------------------------

#[test]
fn render_and_check_note_degenerate_triangles_and_repaired_normals() {
    let text = LESSON.replace("shape = \"uv_sphere\"\nsegments = 12\nrings = 6", "shape = \"mesh\"\npath = \"m.obj\"");
    let (dir, lesson) = lesson_file("lesson.toml", &text);
    // Triangle 1 is degenerate (three points on a line); vertex 3 is in no other triangle.
    std::fs::write(dir.path().join("m.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 1 2 4\nf 2 5 4\n").expect("write");
    let note = "note: object 0 (m.obj): 1 degenerate triangle skipped, 1 vertex normal repaired";
    let a = shadelab().arg("render").arg(&lesson).arg("-o").arg(dir.path().join("x.png")).assert().success();
    let stderr = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    assert!(stderr.contains(note), "{stderr}");
    let a = shadelab().arg("check").arg(&lesson).assert().success();
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains(note));
    // Three faces, one degenerate: two are drawn.
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(stdout.contains("; 2 triangles, "), "{stdout}");
    // A clean lesson has no note.
    let (dir, lesson) = lesson_file("lesson.toml", LESSON);
    let a = shadelab().arg("render").arg(&lesson).arg("-o").arg(dir.path().join("x.png")).assert().success();
    assert!(!String::from_utf8_lossy(&a.get_output().stderr).contains("note:"));
}
