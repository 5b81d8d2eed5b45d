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
    // Every figure of lesson 01 shows the plastic sphere: each one fails.
    let figures = crate::helpers::figure_names(&lesson);
    for name in &figures {
        assert!(out.contains(&format!("FAILED  01-first-light/{name}")), "{out}");
    }
    assert!(out.contains(&format!("{} failed", figures.len())), "{out}");
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

/// The `<testcase>`s of a JUnit document as (classname, name, outcome): "pass", "failure" or "error".
fn junit_cases(xml: &str) -> Vec<(String, String, &'static str)> {
    let attr = |tag: &str, name: &str| -> String {
        // A space before the name: `name="` also ends `classname="`.
        let key = format!(" {name}=\"");
        let at = format!(" {tag}").find(&key).unwrap_or_else(|| panic!("no {name} in {tag}")) + key.len() - 1;
        tag[at..at + tag[at..].find('"').unwrap()].to_string()
    };
    xml.split("<testcase ")
        .skip(1)
        .map(|rest| {
            let tag = &rest[..rest.find('>').unwrap()];
            let body = if tag.ends_with('/') { "" } else { &rest[..rest.find("</testcase>").unwrap()] };
            let outcome = if body.contains("<failure ") {
                "failure"
            } else if body.contains("<error ") {
                "error"
            } else {
                "pass"
            };
            (attr(tag, "classname"), attr(tag, "name"), outcome)
        })
        .collect()
}

/// Course CI, items 1 and 4: the JUnit file holds one test per figure with the run's own
/// counts, a changed figure as a failure with its numbers and diff, an invalid lesson as an
/// error while the others are still checked (exit 2); and the shards 1/3, 2/3, 3/3 of a run
/// together check each figure once.
#[test]
fn junit_reports_the_run_and_shards_split_it_into_parts_that_make_the_whole() {
    let dir = copy_snapshots();
    let work = tempfile::tempdir().unwrap();
    // Lesson 04 with another colour (its two figures change), lesson 01 as it is, one broken lesson.
    let changed = work.path().join("04-shininess.toml");
    let text = std::fs::read_to_string(lessons_dir().join("04-shininess.toml")).unwrap();
    std::fs::write(&changed, text.replacen("diffuse = [0.4, 0.08, 0.04]", "diffuse = [0.1, 0.4, 0.04]", 1)).unwrap();
    let broken = work.path().join("05-broken.toml");
    std::fs::write(&broken, "[camera]\nsize = [10, 10\n").unwrap();
    let lessons = [lessons_dir().join("01-first-light.toml"), changed, broken, lessons_dir().join("16-shadows.toml")];
    let report = work.path().join("junit.xml");
    let out = shadelab().arg("snapshot").args(&lessons).arg("-o").arg(dir.path()).arg("--junit").arg(&report).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "an invalid lesson: exit 2\n{}", String::from_utf8_lossy(&out.stderr));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let xml = std::fs::read_to_string(&report).unwrap();
    let cases = junit_cases(&xml);
    let count = |o: &str| cases.iter().filter(|c| c.2 == o).count();
    // 01: its figures; 04: sweep, ks-by-n (both changed); 16: its figures; the broken lesson.
    let figures_01 = crate::helpers::figure_names(&lessons_dir().join("01-first-light.toml"));
    let figures_16 = crate::helpers::figure_names(&lessons_dir().join("16-shadows.toml"));
    assert_eq!(cases.len(), figures_01.len() + 2 + figures_16.len() + 1, "{xml}");
    assert_eq!((count("failure"), count("error")), (2, 1), "{xml}");
    assert!(xml.contains(&format!("tests=\"{}\" failures=\"2\" errors=\"1\"", cases.len())), "{xml}");
    assert!(cases.contains(&("05-broken".into(), "(lesson)".into(), "error")) && xml.contains("05-broken.toml:2:"), "{xml}");
    assert!(cases.contains(&("04-shininess".into(), "sweep".into(), "failure")), "{xml}");
    assert!(xml.contains("% of pixels differ by more than 2 (allowed 0.100%), max Δ") && xml.contains("sweep.diff.png"), "{xml}");
    // The run's own summary agrees with the file.
    let passed = count("pass");
    assert!(stdout.contains(&format!("{passed} passed, 2 failed")), "{stdout}");

    // Shards: each figure in exactly one part, the parts within one of each other in size.
    let ids = |cases: &[(String, String, &str)]| {
        cases.iter().filter(|c| c.1 != "(lesson)").map(|c| format!("{}/{}", c.0, c.1)).collect::<Vec<_>>()
    };
    let mut whole = ids(&cases);
    whole.sort();
    let mut parts = Vec::new();
    for k in 1..=3 {
        let part = work.path().join(format!("part{k}.xml"));
        let out = shadelab()
            .arg("snapshot")
            .args(&lessons)
            .arg("-o")
            .arg(dir.path())
            .args(["--shard", &format!("{k}/3"), "--junit"])
            .arg(&part)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        parts.push(ids(&junit_cases(&std::fs::read_to_string(&part).unwrap())));
    }
    let sizes: Vec<usize> = parts.iter().map(Vec::len).collect();
    assert!(sizes.iter().max().unwrap() - sizes.iter().min().unwrap() <= 1, "{sizes:?}");
    let mut together: Vec<String> = parts.concat();
    together.sort();
    assert_eq!(together, whole, "the three parts together, each figure once");
}

/// Course CI, item 2: the review page shows each failure as blessed | actual | difference
/// with its numbers before the folded passes, every image it names exists beside it, and
/// no script; `--bless --only` accepts one figure and leaves the other failing.
#[test]
fn the_report_shows_failures_first_and_only_blesses_what_it_is_told() {
    let dir = copy_snapshots();
    let work = tempfile::tempdir().unwrap();
    let changed = work.path().join("04-shininess.toml");
    let text = std::fs::read_to_string(lessons_dir().join("04-shininess.toml")).unwrap();
    std::fs::write(&changed, text.replacen("diffuse = [0.4, 0.08, 0.04]", "diffuse = [0.1, 0.4, 0.04]", 1)).unwrap();
    let lessons = [lessons_dir().join("01-first-light.toml"), changed.clone()];
    let report = work.path().join("report");
    let out = shadelab().arg("snapshot").args(&lessons).arg("-o").arg(dir.path()).arg("--report").arg(&report).output().unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(!html.contains("<script"), "no script");
    let first_failure = html.find("<h2 id=\"04-shininess/").expect("the failures have sections");
    let passes = html.find("<details>").expect("the passes are folded");
    assert!(first_failure < passes && html[passes..].contains("01-first-light/split"), "failures first, then the passes");
    assert!(html.contains("% of pixels differ by more than 2 (allowed 0.100%), max Δ"), "the numbers");
    let srcs: Vec<&str> = html.split("src=\"").skip(1).map(|s| &s[..s.find('"').unwrap()]).collect();
    assert_eq!(srcs.len(), 2 * 3, "blessed, actual and difference for each of lesson 04's two figures");
    for s in &srcs {
        let path = report.join(percent_encoding::percent_decode_str(s).decode_utf8().unwrap().as_ref());
        assert!(path.is_file(), "{s} resolves");
    }
    // Accept only the sweep: it is blessed, ks-by-n still fails.
    let out = shadelab()
        .arg("snapshot")
        .arg(&changed)
        .arg("-o")
        .arg(dir.path())
        .args(["--bless", "--only", "04-shininess/sweep"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stdout));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.contains("blessed 04-shininess/sweep") && stdout.contains("0 passed, 1 failed, 1 blessed"), "{stdout}");
    let out = shadelab().arg("snapshot").arg(&changed).arg("-o").arg(dir.path()).output().unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.contains("ok      04-shininess/sweep") && stdout.contains("1 passed, 1 failed"), "{stdout}");
    // A figure that is not there is refused before any work.
    let out = shadelab()
        .arg("snapshot")
        .arg(&changed)
        .arg("-o")
        .arg(dir.path())
        .args(["--bless", "--only", "04-shininess/nope"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--only 04-shininess/nope: no such figure"));
}

/// Course CI, item 7: a figure's PNG records what made it; `reproduce` renders it again and
/// says it matches bit for bit, or which input changed; a failing snapshot's actual image
/// reproduces, and the FAILED line says how.
#[test]
fn a_figure_carries_its_provenance_and_reproduce_says_what_changed() {
    let work = tempfile::tempdir().unwrap();
    let lesson = work.path().join("04-shininess.toml");
    let text = std::fs::read_to_string(lessons_dir().join("04-shininess.toml")).unwrap();
    std::fs::write(&lesson, &text).unwrap();
    let out = work.path().join("out");
    shadelab().arg("figures").arg(&lesson).arg("-o").arg(&out).args(["--cell", "64x64", "-q"]).assert().success();
    let png = out.join("04-shininess/sweep.png");
    let run = || shadelab().arg("reproduce").arg(&png).output().unwrap();
    let ok = run();
    assert_eq!(ok.status.code(), Some(0), "{}", String::from_utf8_lossy(&ok.stderr));
    assert!(String::from_utf8_lossy(&ok.stdout).contains("reproduced bit for bit"));
    // Another colour in the lesson: the figure differs, and the lesson is named as changed.
    std::fs::write(&lesson, text.replacen("diffuse = [0.4, 0.08, 0.04]", "diffuse = [0.1, 0.4, 0.04]", 1)).unwrap();
    let changed = run();
    assert_eq!(changed.status.code(), Some(1));
    let err = String::from_utf8_lossy(&changed.stderr);
    assert!(err.contains("pixels differ") && err.contains("what changed since:") && err.contains("04-shininess.toml changed"), "{err}");
    // A PNG without a record.
    let plain = work.path().join("plain.png");
    image::RgbImage::new(4, 4).save(&plain).unwrap();
    let none = shadelab().arg("reproduce").arg(&plain).output().unwrap();
    assert_eq!(none.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&none.stderr).contains("no shadelab record"));
    // A failing snapshot's actual image reproduces, and its line says how.
    let dir = copy_snapshots();
    let snap = shadelab().arg("snapshot").arg(&lesson).arg("-o").arg(dir.path()).output().unwrap();
    assert_eq!(snap.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&snap.stdout).into_owned() + &String::from_utf8_lossy(&snap.stderr);
    let actual = dir.path().join("04-shininess/sweep.actual.png");
    assert!(stdout.contains(&format!("reproduce: shadelab reproduce {}", actual.display())), "{stdout}");
    let again = shadelab().arg("reproduce").arg(&actual).output().unwrap();
    assert_eq!(again.status.code(), Some(0), "{}", String::from_utf8_lossy(&again.stderr));
}

/// Course CI, item 5: `new --course` writes a course whose checks pass as written: the
/// script the workflows call runs here, part by part, and both workflow files are YAML
/// that runs that script for each part and keeps its reports.
#[test]
fn a_new_course_passes_its_own_checks_and_its_workflows_run_them() {
    let tmp = tempfile::tempdir().unwrap();
    let course = tmp.path().join("my-course");
    shadelab().args(["new", "--course"]).arg(&course).args(["--shadelab-git", "https://example.org/shadelab.git"]).assert().success();
    let bin = assert_cmd::cargo::cargo_bin("shadelab");
    let path = format!("{}:{}", bin.parent().unwrap().display(), std::env::var("PATH").unwrap_or_default());
    let mut tests = 0;
    for part in ["1/2", "2/2"] {
        let out = std::process::Command::new("sh")
            .arg(course.join("ci/run-checks.sh"))
            .arg(part)
            .env("PATH", &path)
            .env("SHADELAB_NO_CACHE", "1")
            .env_remove("GITHUB_ACTIONS")
            .output()
            .unwrap();
        assert!(out.status.success(), "part {part}: {}\n{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        let junit = std::fs::read_to_string(course.join(format!("reports/junit-{}.xml", part.replace('/', "-")))).unwrap();
        assert!(junit.contains("failures=\"0\" errors=\"0\""), "{junit}");
        tests += junit.matches("<testcase ").count();
        assert!(course.join(format!("reports/review-{}/index.html", part.replace('/', "-"))).is_file());
    }
    assert_eq!(tests, 2, "the two parts together check the course's two figures");
    // The workflows: YAML, a job per part, each running the script and keeping the reports.
    let yaml = |p: &str| {
        let text = std::fs::read_to_string(course.join(p)).unwrap();
        yaml_rust2::YamlLoader::load_from_str(&text).unwrap_or_else(|e| panic!("{p}: {e}")).remove(0)
    };
    let gh = yaml(".github/workflows/shadelab.yml");
    let job = &gh["jobs"]["check"];
    let shards: Vec<&str> = job["strategy"]["matrix"]["shard"].as_vec().unwrap().iter().filter_map(|s| s.as_str()).collect();
    assert_eq!(shards, ["1/2", "2/2"]);
    let steps = job["steps"].as_vec().unwrap();
    assert!(steps.iter().any(|s| s["run"].as_str() == Some("sh ci/run-checks.sh \"${{ matrix.shard }}\"")), "{steps:?}");
    assert!(steps.iter().any(|s| s["with"]["path"].as_str() == Some("reports/")), "the review pages are uploaded");
    assert_eq!(gh["env"]["SHADELAB_GIT"].as_str(), Some("https://example.org/shadelab.git"));
    let gl = yaml(".gitlab-ci.yml");
    let job = &gl["shadelab"];
    let shards: Vec<&str> = job["parallel"]["matrix"][0]["SHARD"].as_vec().unwrap().iter().filter_map(|s| s.as_str()).collect();
    assert_eq!(shards, ["1/2", "2/2"]);
    assert!(job["script"].as_vec().unwrap().iter().any(|s| s.as_str() == Some("sh ci/run-checks.sh \"$SHARD\"")));
    assert_eq!(job["artifacts"]["reports"]["junit"].as_str(), Some("reports/junit-*.xml"));
    // A folder that is not empty is refused.
    let out = shadelab().args(["new", "--course"]).arg(&course).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
}
