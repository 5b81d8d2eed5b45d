//! Help, flags and the first run: every example in `--help` runs, every `shadelab ...`
//! line of the README, the docs and the lessons' `Try:` comments parses, one meaning per
//! flag, completions and man pages, progress and summary lines, `check` of folders,
//! `shadelab new`.

use crate::helpers::{lessons_dir, read_png, shadelab};
use clap::{CommandFactory, Parser};
use std::path::{Path, PathBuf};

/// Every command of the tree with its full name (`brdf lobe`), depth first.
fn commands() -> Vec<(String, clap::Command)> {
    fn walk(prefix: &str, cmd: &clap::Command, out: &mut Vec<(String, clap::Command)>) {
        for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
            let name = format!("{prefix}{}", sub.get_name()).trim().to_string();
            out.push((name.clone(), sub.clone()));
            walk(&format!("{name} "), sub, out);
        }
    }
    let mut cmd = shadelab::cli::Args::command();
    cmd.build();
    let mut out = vec![(String::new(), cmd.clone())];
    walk("", &cmd, &mut out);
    out
}

/// The command lines of a help text's `Examples:` section: its lines indented by four spaces.
fn examples(help: &str) -> Vec<String> {
    let Some((_, section)) = help.split_once("Examples:\n") else { return Vec::new() };
    section.lines().take_while(|l| l.is_empty() || l.starts_with("  ")).filter_map(|l| l.strip_prefix("    ")).map(String::from).collect()
}

/// Copies a folder tree (the bundled lessons, so examples write into a temporary folder).
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_tree(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).unwrap();
        }
    }
}

#[test]
fn every_subcommand_ends_its_help_with_examples_that_run() {
    let work = tempfile::tempdir().unwrap();
    copy_tree(&lessons_dir(), &work.path().join("lessons"));
    let bin = assert_cmd::cargo::cargo_bin("shadelab");
    let path = format!("{}:{}", bin.parent().unwrap().display(), std::env::var("PATH").unwrap_or_default());
    let mut ran = 0;
    for (name, cmd) in commands() {
        let help = cmd.get_after_help().map(|h| h.to_string()).unwrap_or_default();
        let lines = examples(&help);
        // A group's own help (`brdf`) and every leaf: two to four examples, real commands.
        let commands = lines.iter().filter(|l| l.contains("shadelab ")).count();
        assert!(commands >= 2, "`shadelab {name} --help` has {commands} example commands:\n{help}");
        for line in lines {
            let out = std::process::Command::new("sh")
                .arg("-c")
                .arg(&line)
                .current_dir(work.path())
                .env("PATH", &path)
                .env("SHADELAB_NO_CACHE", "1")
                .output()
                .expect("run sh");
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "`shadelab {name} --help` example failed ({:?}): {line}\n{stderr}", out.status.code());
            assert!(!stderr.contains("panicked"), "{line}\n{stderr}");
            ran += 1;
        }
    }
    assert!(ran >= 40, "only {ran} examples ran");
}

/// Splits a shell line into words: single and double quotes, `\` escapes, a trailing `# comment`.
fn words(line: &str) -> Vec<String> {
    let (mut out, mut cur, mut quote, mut any) = (Vec::new(), String::new(), None, false);
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        match (quote, c) {
            (None, '#') if cur.is_empty() && !any => break,
            (None, '\'' | '"') => {
                quote = Some(c);
                any = true;
            }
            (Some(q), c) if c == q => quote = None,
            (None | Some('"'), '\\') => cur.extend(chars.next()),
            (None, c) if c.is_whitespace() => {
                if any {
                    out.push(std::mem::take(&mut cur));
                    any = false;
                }
            }
            (_, c) => {
                cur.push(c);
                any = true;
            }
        }
    }
    if any {
        out.push(cur);
    }
    out
}

/// The `shadelab ...` lines a reader would copy: README's and the docs' code blocks, and
/// the lessons' `# Try:` comments; each with where it is.
fn documented_command_lines() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut lines = Vec::new();
    let mut md: Vec<PathBuf> = vec![root.join("README.md")];
    md.extend(
        std::fs::read_dir(root.join("docs")).unwrap().map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|x| x == "md")),
    );
    for file in md {
        let text = std::fs::read_to_string(&file).unwrap();
        let mut in_code = false;
        for (i, l) in text.lines().enumerate() {
            if l.trim_start().starts_with("```") {
                in_code = !in_code;
            } else if in_code && let Some(rest) = l.trim_start().strip_prefix("shadelab ") {
                lines.push((format!("{}:{}", file.display(), i + 1), rest.to_string()));
            }
        }
    }
    for e in std::fs::read_dir(root.join("lessons")).unwrap() {
        let file = e.unwrap().path();
        if file.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        for (i, l) in text.lines().enumerate() {
            let t = l.trim_start_matches('#').trim_start();
            let t = t.strip_prefix("Try:").map(str::trim_start).unwrap_or(t);
            if l.starts_with('#') && (l.contains("Try: shadelab ") || l.starts_with("#      shadelab ")) {
                lines.push((format!("{}:{}", file.display(), i + 1), t.strip_prefix("shadelab ").unwrap().to_string()));
            }
        }
    }
    lines
}

#[test]
fn every_documented_command_line_parses_and_names_files_that_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let lines = documented_command_lines();
    assert!(lines.len() >= 80, "found only {} documented command lines", lines.len());
    let mut bad = Vec::new();
    for (at, line) in &lines {
        // `a && b`: each command on its own.
        for part in line.split("&& shadelab ") {
            let mut argv = vec!["shadelab".to_string()];
            argv.extend(words(part).into_iter().take_while(|w| !matches!(w.as_str(), ">" | "|" | "<" | "&&")));
            if let Err(e) = shadelab::cli::Args::try_parse_from(&argv) {
                bad.push(format!("{at}: shadelab {part}\n  {}", e.to_string().lines().next().unwrap_or_default()));
            }
            for w in argv.iter().filter(|w| w.contains('/') && w.ends_with(".toml") && !w.contains('*')) {
                if !root.join(w).is_file() {
                    bad.push(format!("{at}: {w} does not exist"));
                }
            }
        }
    }
    assert!(bad.is_empty(), "documented commands that would fail as written:\n{}", bad.join("\n"));
}

#[test]
fn the_readme_says_how_to_install_and_how_to_run_without_installing() {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let install = readme.find("cargo install --path .").expect("README names `cargo install --path .`");
    let run_form = readme.find("cargo run --release -- ").expect("README names the `cargo run --release --` form");
    let first_shadelab = readme.find("\nshadelab ").expect("README has shadelab lines");
    assert!(install < first_shadelab, "the install step must come before the first `shadelab` line");
    assert!(run_form < readme.find("## What you can do").expect("a section of commands"), "the cargo run form comes with the quick start");
}

/// The help text of `shadelab ARGS --help`.
fn help(args: &[&str]) -> String {
    let a = shadelab().args(args).arg("--help").assert().success();
    String::from_utf8_lossy(&a.get_output().stdout).into_owned()
}

#[test]
fn one_meaning_per_flag_across_subcommands() {
    for (name, _) in commands().into_iter().filter(|(n, _)| !n.is_empty() && n != "brdf") {
        let args: Vec<&str> = name.split(' ').collect();
        let h = help(&args);
        assert!(h.contains("-q, --quiet"), "`{name}` has no -q/--quiet:\n{h}");
        // A file or folder is written with -o/--output wherever one is written.
        if !matches!(name.as_str(), "check" | "explain" | "lessons" | "bench" | "brdf eval" | "completions" | "cache" | "reproduce") {
            assert!(h.contains("-o, --output"), "`{name}` has no -o/--output:\n{h}");
        }
    }
    // `snapshot --dir` stays, as a visible alias of -o.
    assert!(help(&["snapshot"]).contains("[alias: --dir]"));
    // Commands with a default file name say it.
    assert!(help(&["compare"]).contains("LESSON-compare.png"));
    assert!(help(&["sweep"]).contains("LESSON-sweep.png") && help(&["sweep"]).contains("LESSON-grid.png"));
    assert!(help(&["split"]).contains("LESSON-split.png"));
    // --format values name what they select; the old spellings still parse.
    let parses = |a: &[&str]| shadelab::cli::Args::try_parse_from(std::iter::once("shadelab").chain(a.iter().copied())).is_ok();
    for (new, old) in [
        (&["bench", "--format", "jsonl"][..], &["bench", "--format", "json"][..]),
        (&["cost", "x.toml", "--format", "jsonl"], &["cost", "x.toml", "--format", "json"]),
        (
            &["brdf", "albedo", "x.toml", "--material", "m", "--format", "chart"],
            &["brdf", "albedo", "x.toml", "--material", "m", "--format", "png"],
        ),
    ] {
        assert!(parses(new) && parses(old), "{new:?} / {old:?}");
    }
}

#[test]
fn global_flags_a_subcommand_ignores_are_not_shown_on_it_but_still_parse() {
    let h = help(&["completions"]);
    assert!(!h.contains("--threads") && !h.contains("--budget") && !h.contains("--lang") && h.contains("--quiet"), "{h}");
    let h = help(&["check"]);
    assert!(!h.contains("--threads") && h.contains("--budget") && h.contains("--allow-dir"), "{h}");
    let h = help(&["render"]);
    assert!(["--threads", "--budget", "--lang", "--allow-dir", "--cache", "--no-cache"].iter().all(|f| h.contains(f)), "{h}");
    // Still accepted where a script puts them, and still read: a bad budget is refused.
    shadelab().args(["completions", "bash", "--threads", "2"]).assert().success();
    shadelab().args(["completions", "bash", "--budget", "-1"]).assert().code(2);
    // A thread count that would exhaust memory is refused before any thread starts.
    let a = shadelab().args(["--threads", "100000000000", "lessons"]).assert().code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("give 1 to 1024 worker threads"));
}

#[test]
fn completions_and_man_pages_cover_every_subcommand() {
    let subs: Vec<String> = commands().into_iter().filter(|(n, _)| !n.is_empty() && !n.contains(' ')).map(|(n, _)| n).collect();
    assert!(subs.len() >= 15, "{subs:?}");
    let a = shadelab().args(["completions", "bash"]).assert().success();
    let bash = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(bash.contains("complete -F") && bash.contains("_shadelab"), "not a bash completion script");
    for s in &subs {
        assert!(bash.contains(&format!("shadelab,{s})")), "bash completion lacks `{s}`");
    }
    for shell in ["zsh", "fish", "powershell"] {
        let a = shadelab().args(["completions", shell]).assert().success();
        assert!(String::from_utf8_lossy(&a.get_output().stdout).contains("render"), "{shell}");
    }
    let a = shadelab().arg("man").assert().success();
    let man = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(man.starts_with(".ie") || man.contains("\n.TH shadelab 1"), "not roff:\n{}", &man[..200.min(man.len())]);
    assert!(man.contains(".TH shadelab 1"), "no .TH line");
    for s in &subs {
        assert!(man.contains(&format!("shadelab\\-{s}(1)")), "the man page does not list `{s}`");
    }
    let dir = tempfile::tempdir().unwrap();
    shadelab().arg("man").arg("-o").arg(dir.path()).assert().success();
    for s in &subs {
        let page = std::fs::read_to_string(dir.path().join(format!("shadelab-{s}.1"))).unwrap_or_else(|e| panic!("{s}: {e}"));
        assert!(page.contains(&format!(".TH shadelab-{s} 1")), "{s}: {page}");
    }
    assert!(dir.path().join("shadelab-brdf-lobe.1").is_file());
}

/// A small valid lesson with one figure.
const TINY: &str = "[camera]\nposition = [0, 0, 4]\nsize = [16, 16]\n[[object]]\nshape = \"uv_sphere\"\nsegments = 8\nrings = 4\nmaterial = \"m\"\n[material.m]\nmodel = \"lambert\"\n[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n[lesson]\nnotes = \"NOTES OF THE LESSON\"\n[[figure]]\nname = \"f\"\nkind = \"split\"\nlayers = [\"diffuse\", \"total\"]\n";

#[test]
fn check_takes_folders_and_reports_every_invalid_lesson() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("a.toml"), TINY).unwrap();
    std::fs::write(dir.path().join("b.toml"), TINY.replace("lambert", "lambart")).unwrap();
    std::fs::write(dir.path().join("c.toml"), TINY.replace("size = [16, 16]", "size = [0, 16]")).unwrap();
    let a = shadelab().arg("check").arg(dir.path()).assert().code(2);
    let stderr = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(stdout.contains("ok    ") && stdout.contains("a.toml"), "{stdout}");
    assert!(stderr.contains("b.toml") && stderr.contains("lambart") && stderr.contains("c.toml"), "{stderr}");
    assert!(stderr.contains("2 of 3 lessons are invalid"), "{stderr}");
    // The bundled folder: one line per lesson, then the summary.
    let a = shadelab().arg("check").arg(lessons_dir()).assert().success();
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    let n =
        std::fs::read_dir(lessons_dir()).unwrap().filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "toml")).count();
    assert_eq!(stdout.lines().filter(|l| l.starts_with("ok    ")).count(), n, "{stdout}");
    let last = stdout.lines().last().unwrap();
    assert!(summary_line(last, "lesson").is_some() && last.ends_with(": all valid"), "{last}");
    // An empty folder is an error, not "0 lessons: all valid".
    let empty = tempfile::tempdir().unwrap();
    shadelab().arg("check").arg(empty.path()).assert().code(2);
}

/// `N NOUNs in S.S s[ → DIR/]`: returns N (no regex crate: the format is checked by hand).
fn summary_line(line: &str, noun: &str) -> Option<usize> {
    let (n, rest) = line.split_once(' ')?;
    let n: usize = n.parse().ok()?;
    let (_, rest) = rest.strip_prefix(noun)?.split_once(" in ")?;
    let (secs, rest) = rest.split_once(" s")?;
    let (whole, tenth) = secs.split_once('.')?;
    (whole.chars().all(|c| c.is_ascii_digit()) && tenth.len() == 1 && tenth.chars().all(|c| c.is_ascii_digit())).then_some(())?;
    (rest.is_empty() || rest.starts_with(" → ") || rest.starts_with(':') || rest.starts_with(" (")).then_some(n)
}

#[test]
fn figures_ends_with_one_summary_line_without_notes_or_a_bar_when_piped() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("a.toml"), TINY).unwrap();
    std::fs::write(dir.path().join("b.toml"), TINY.replace("name = \"f\"", "name = \"g\"")).unwrap();
    let out = dir.path().join("out");
    let a = shadelab().arg("figures").arg(dir.path()).arg("-o").arg(&out).assert().success();
    let (stdout, stderr) = (&a.get_output().stdout, &a.get_output().stderr);
    let text = String::from_utf8_lossy(stdout);
    assert!(!stdout.contains(&0x1b) && !stderr.contains(&0x1b), "escape codes in piped output:\n{text}");
    assert!(!text.contains("NOTES OF THE LESSON"), "figures repeated the lesson's notes:\n{text}");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 4, "one line per figure, the slowest figures and the summary:\n{text}");
    // The slowest figures, longest first, each with its time.
    assert!(lines[2].starts_with("slowest: ") && lines[2].contains("a/f ") && lines[2].contains("b/g "), "{}", lines[2]);
    assert_eq!(summary_line(lines[3], "figure"), Some(2), "{}", lines[3]);
    assert!(lines[3].ends_with(&format!("→ {}/", out.display())), "{}", lines[3]);
    // No terminal on stderr, so no bar: a line per lesson with its time instead.
    let err = String::from_utf8_lossy(stderr);
    let per_lesson: Vec<&str> = err.lines().collect();
    assert_eq!(per_lesson.len(), 2, "{err}");
    assert!(per_lesson[0].starts_with("a: 1 figure in ") && per_lesson[0].ends_with(" s"), "{err}");
    assert!(per_lesson[1].starts_with("b: 1 figure in "), "{err}");
    assert!(out.join("a/f.png").is_file() && out.join("b/g.png").is_file());
    // -q keeps the summary line, which says where the files went.
    let a = shadelab().arg("figures").arg(dir.path()).arg("-o").arg(&out).arg("-q").assert().success();
    let text = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert_eq!(text.lines().count(), 1, "{text}");
    assert_eq!(summary_line(text.trim_end(), "figure"), Some(2), "{text}");
    assert!(a.get_output().stderr.is_empty());
    // `render` prints the notes (unless -q).
    let a = shadelab().arg("render").arg(dir.path().join("a.toml")).arg("-o").arg(dir.path().join("a.png")).assert().success();
    assert!(String::from_utf8_lossy(&a.get_output().stdout).contains("NOTES OF THE LESSON"));
    let a = shadelab().arg("render").arg(dir.path().join("a.toml")).arg("-o").arg(dir.path().join("a.png")).arg("-q").assert().success();
    assert!(a.get_output().stdout.is_empty());
}

#[test]
fn snapshot_and_cost_end_with_a_summary_line() {
    let dir = tempfile::tempdir().unwrap();
    let lesson = dir.path().join("a.toml");
    std::fs::write(&lesson, TINY).unwrap();
    let snaps = dir.path().join("snaps");
    let a = shadelab().arg("snapshot").arg(&lesson).arg("-o").arg(&snaps).arg("--bless").assert().success();
    let text = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert_eq!(summary_line(text.lines().last().unwrap(), "snapshot blessed"), Some(1), "{text}");
    let a = shadelab().arg("snapshot").arg(&lesson).arg("--dir").arg(&snaps).arg("-q").assert().success();
    let text = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert_eq!(text.lines().count(), 1, "{text}");
    assert_eq!(summary_line(text.trim_end(), "snapshot"), Some(1), "{text}");
    assert!(text.trim_end().ends_with(": 1 passed, 0 failed"), "{text}");
    // cost: the table's last line is the summary; with CSV it goes to stderr.
    let cost = |fmt: &str| {
        shadelab()
            .arg("cost")
            .arg(&lesson)
            .args(["--ladder", "aa", "--repeat", "1", "--warmup", "0", "--format", fmt])
            .assert()
            .success()
            .get_output()
            .clone()
    };
    let o = cost("table");
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(summary_line(text.lines().last().unwrap(), "ladder, "), Some(1), "{text}");
    let o = cost("csv");
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(text.lines().all(|l| l.contains(',')), "CSV stdout has a non-CSV line:\n{text}");
    assert_eq!(summary_line(String::from_utf8_lossy(&o.stderr).trim_end(), "ladder, "), Some(1));
}

#[test]
fn bench_names_its_columns_for_what_they_time() {
    let a = shadelab().args(["bench", "--workload", "sphere", "--frames", "1", "--warmup", "0"]).assert().success();
    let text = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(text.contains("8-bit med") && text.contains("float med") && !text.contains("render med"), "{text}");
    let a = shadelab().args(["bench", "--workload", "sphere", "--frames", "1", "--warmup", "0", "--format", "jsonl"]).assert().success();
    let v: serde_json::Value = serde_json::from_slice(&a.get_output().stdout).unwrap();
    for key in ["median_ms", "float_frame_median_ms", "png_median_ms"] {
        assert!(v[key].as_f64().is_some_and(|x| x > 0.0), "{key} in {v}");
    }
    assert!(v.get("render_median_ms").is_none() && v.get("develop_median_ms").is_none(), "{v}");
}

#[test]
fn new_writes_each_template_as_a_lesson_that_checks_and_renders() {
    let dir = tempfile::tempdir().unwrap();
    for t in ["classic", "pbr", "lights"] {
        let name = format!("my-{t}");
        shadelab().args(["new", &name, "--template", t, "-o"]).arg(dir.path()).assert().success();
        let file = dir.path().join(format!("{name}.toml"));
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(text.starts_with("# ") && text.contains("What to look at") && text.contains("caption = "), "{t}: not commented");
        shadelab().arg("check").arg(&file).assert().success();
        let png = dir.path().join(format!("{name}.png"));
        shadelab().arg("render").arg(&file).arg("-o").arg(&png).args(["--size", "64x64", "-q"]).assert().success();
        // Not a blank frame: a fifth of the pixels or more are lit objects, brighter than the
        // corner's background.
        let img = read_png(&png);
        let sum = |p: &image::Rgb<u8>| p.0.iter().map(|&x| x as u32).sum::<u32>();
        let background = sum(img.get_pixel(0, 0));
        let lit = img.pixels().filter(|p| sum(p) > background + 30).count();
        assert!(lit * 5 >= (64 * 64), "{t}: only {lit} of 4096 pixels are lit");
        shadelab().arg("figures").arg(&file).arg("-o").arg(dir.path().join("figs")).args(["-q", "--cell", "32x32"]).assert().success();
        // A second `new` of the same name refuses and leaves the file as it was.
        std::fs::write(&file, "# mine\n").unwrap();
        let a = shadelab().args(["new", &name, "--template", t, "-o"]).arg(dir.path()).assert().code(2);
        assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("already exists"));
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "# mine\n");
    }
    shadelab().args(["new", "../escape"]).current_dir(dir.path()).assert().code(2);
}
