//! The work and memory budget (reliability round two, item 2): products of limits that each
//! value's own limit lets through are refused before any work, naming the largest terms,
//! the key to lower and the `--budget` that allows them; the estimate is held to the
//! render's own counts and to the process's peak memory.

use crate::helpers::{lessons_dir, shadelab};

/// `explain`'s output for bundled lesson `name` with `sets`.
fn explain(name: &str, sets: &[&str], extra: &[&str]) -> String {
    let mut cmd = shadelab();
    cmd.args(["--threads", "2", "explain"]).arg(lessons_dir().join(name)).args(extra);
    for s in sets {
        cmd.args(["--set", s]);
    }
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// A count as the estimate table prints it ("1.049 M", "12.3 k", "950").
fn si(s: &str) -> f64 {
    let mut it = s.split_whitespace();
    let x: f64 = it.next().unwrap().parse().unwrap();
    x * match it.next() {
        Some("k") => 1e3,
        Some("M") => 1e6,
        Some("G") => 1e9,
        Some("T") => 1e12,
        _ => 1.0,
    }
}

/// The estimated count of the term `what` (0 when the table has no such row).
fn estimated(text: &str, what: &str) -> f64 {
    let table = &text[text.find("Estimate (").unwrap()..];
    table
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with("    "))
        .find(|l| l.trim_start().starts_with(what) && l.trim_start()[what.len()..].starts_with("  "))
        .map_or(0.0, |l| {
            let rest = l.trim_start()[what.len()..].trim_start();
            // "1.049 M      31 ms ..." or "950      1 ms ...": the count is one or two words.
            let words: Vec<&str> = rest.split_whitespace().collect();
            if matches!(words.get(1), Some(&("k" | "M" | "G" | "T"))) { si(&format!("{} {}", words[0], words[1])) } else { si(words[0]) }
        })
}

/// The count the render reported under `label` in "What ran".
fn counted(text: &str, label: &str) -> f64 {
    let ran = &text[text.find("What ran").unwrap()..];
    let line = ran.lines().find(|l| l.trim_start().starts_with(label)).unwrap_or_else(|| panic!("no `{label}` in\n{ran}"));
    line.split_whitespace().last().unwrap().parse().unwrap()
}

/// A size as `bytes` prints it ("420 MB", "1.62 GB") in bytes.
fn size(s: &str) -> f64 {
    let (x, unit) = s.trim().split_once(' ').unwrap();
    x.parse::<f64>().unwrap() * if unit.starts_with("GB") { 1e9 } else { 1e6 }
}

/// (estimated bytes, the process's measured peak) from `explain`'s text.
fn memory(text: &str) -> (f64, f64) {
    let summary = text.lines().find(|l| l.contains("of work on one core, ")).unwrap();
    let est = size(summary.rsplit(", ").next().unwrap());
    let peak = text.lines().find(|l| l.contains("peak memory of the process")).unwrap();
    let peak = peak.split("process").nth(1).unwrap();
    (est, size(peak))
}

#[test]
fn products_of_limits_are_refused_before_any_work_with_the_terms_and_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.png");
    // The reproducers: a fine radiosity mesh with the largest hemicube, and 4096 fog steps
    // on a supersampled frame (each value within its own limit; neither finished in minutes).
    let cases: [(&str, &[&str], &str, &str); 2] = [
        ("27-radiosity.toml", &["render.hemicube_size=1024", "render.patch_size=0.125"], "hemicube cells read", "render.hemicube_size"),
        ("26-fog.toml", &["fog.steps=4096", "render.aa=4"], "fog march steps", "fog.steps"),
    ];
    for (name, sets, term, key) in cases {
        let mut cmd = shadelab();
        cmd.arg("render").arg(lessons_dir().join(name)).arg("-o").arg(&out);
        for s in sets {
            cmd.args(["--set", s]);
        }
        let o = cmd.output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(name) && err.contains("over its budget") && err.contains(term), "{name}: {err}");
        assert!(err.contains(&format!("lower `{key}`")) && err.contains("--budget "), "{name}: {err}");
        assert!(!out.exists(), "no output file");
        // `check` says the same, and a raised budget lets it through (check does no render).
        let mut check = shadelab();
        check.arg("check").arg(lessons_dir().join(name));
        for s in sets {
            check.args(["--set", s]);
        }
        let o = check.output().unwrap();
        assert_eq!(o.status.code(), Some(2), "{name}");
        assert!(String::from_utf8_lossy(&o.stderr).contains(term));
        let o = check.args(["--budget", "8"]).output().unwrap();
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stdout).contains("of work on one core"), "check reports the estimate");
    }
    // `explain` shows the estimate and skips the render instead of running the solve.
    let text = explain("27-radiosity.toml", &["render.hemicube_size=1024", "render.patch_size=0.125"], &[]);
    assert!(text.contains("over the budget: no render") && !text.contains("What ran"), "{text}");
}

#[test]
fn a_bad_budget_is_refused() {
    for bad in ["0", "-1", "nan", "1e9"] {
        let o = shadelab().args(["--budget", bad, "check"]).arg(lessons_dir().join("01-first-light.toml")).output().unwrap();
        assert_eq!(o.status.code(), Some(2), "--budget {bad}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("--budget"), "--budget {bad}");
    }
}

#[test]
fn a_figure_cell_over_the_budget_is_named() {
    let dir = tempfile::tempdir().unwrap();
    // A budget so small that lesson 16's 256² cells are over it.
    let o = shadelab()
        .args(["--budget", "0.001", "figures"])
        .arg(lessons_dir().join("16-shadows.toml"))
        .arg("-o")
        .arg(dir.path())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("figure `method`") && err.contains("render.shadows=") && err.contains("over its budget"), "{err}");
}

/// (lesson, sets, estimate term, render counter, the range of estimate / counted).
type Counted = (&'static str, &'static [&'static str], &'static str, &'static str, (f64, f64));

#[test]
fn the_estimated_counts_bound_the_counts_of_the_render() {
    // The estimate counts every sample as hitting a surface, so it is above the count by
    // the share of background (and, for shadow rays, of samples facing away from the light).
    let cases: [Counted; 4] = [
        ("16-shadows.toml", &[], "image samples", "samples shaded", (1.0, 2.0)),
        ("18-area-lights.toml", &[], "shadow rays", "shadow rays traced", (1.0, 3.0)),
        ("26-fog.toml", &["camera.size=[128, 128]"], "fog march steps", "fog: ray-march steps", (0.99, 1.5)),
        ("27-radiosity.toml", &["render.patch_size=0.25"], "form factors kept", "radiosity form factors (non-zero)", (0.6, 2.0)),
    ];
    for (name, sets, term, counter, (lo, hi)) in cases {
        let text = explain(name, sets, &[]);
        let (e, c) = (estimated(&text, term), counted(&text, counter));
        assert!(c > 0.0 && (lo..=hi).contains(&(e / c)), "{name}: estimated {e} {term}, counted {c} {counter}: ratio {}", e / c);
    }
}

#[test]
fn the_estimated_memory_is_within_a_factor_of_two_of_the_peak() {
    // Scenes whose memory is one large term: a point light's six 4096² depth faces
    // (403 MB), a 3840 × 2160 frame, a fine radiosity mesh's form factors.
    let cases: [(&str, &[&str]); 3] = [
        ("16-shadows.toml", &["render.shadows=\"map\"", "render.shadow_map_size=4096"]),
        ("01-first-light.toml", &["camera.size=[3840, 2160]", "render.aa=1"]),
        ("27-radiosity.toml", &["render.patch_size=0.125", "render.hemicube_size=16", "render.final_gather=false"]),
    ];
    for (name, sets) in cases {
        let text = explain(name, sets, &[]);
        let (est, peak) = memory(&text);
        assert!(peak > 40e6, "{name}: the case is dominated by its large term ({peak} bytes)");
        assert!((0.5..=2.0).contains(&(est / peak)), "{name}: estimated {est} bytes, peak {peak}");
    }
}
