//! A grade as text (the terminal), as Markdown (a pull-request comment, GitHub Classroom)
//! with its images, and the images themselves: reference | yours | ꟻLIP per term.

use super::rubric::Term;
use super::{Grade, IMAGE_TERMS, Rendered};
use std::fmt::Write as _;

/// What a report names besides the grade: the two lessons and the pass mark.
#[derive(Debug, Clone)]
pub struct Heading {
    /// The student's lesson, as given.
    pub student: String,
    /// The reference lesson, as given.
    pub reference: String,
    /// Points needed to pass.
    pub pass: f32,
}

/// "72.5 of 100 points (pass mark 60): passed".
pub fn verdict(g: &Grade, pass: f32) -> String {
    format!(
        "{} of {} points (pass mark {}): {}",
        tenths(g.points),
        tenths(g.total),
        tenths(pass),
        if g.passed { "passed" } else { "failed" }
    )
}

/// A number of points with at most one decimal: 72.5, 100.
fn tenths(x: f32) -> String {
    let r = (x * 10.0).round() / 10.0;
    if r.fract() == 0.0 { format!("{r:.0}") } else { format!("{r:.1}") }
}

/// The table's rows: term, points of weight, ꟻLIP, mean, p95 (the shadows' one number is 1 − IoU).
fn rows(g: &Grade) -> Vec<[String; 5]> {
    g.terms
        .iter()
        .map(|t| {
            let shown = |x: f32| if t.present { format!("{x:.3}") } else { "–".into() };
            let (flip, mean, p95) = if t.term == Term::Shadows {
                (format!("{} (1 − IoU)", shown(t.error)), String::new(), String::new())
            } else {
                (shown(t.error), shown(t.mean), shown(t.p95))
            };
            [t.term.name().to_string(), format!("{}/{}", tenths(t.points), tenths(t.weight)), flip, mean, p95]
        })
        .collect()
}

/// The terminal report.
pub fn text(g: &Grade, h: &Heading) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "grade: {}", verdict(g, h.pass));
    let _ = writeln!(s, "  yours:     {}\n  reference: {}\n", h.student, h.reference);
    let _ = writeln!(s, "  {:<13} {:>9}  {:>15}  {:>6}  {:>6}", "term", "points", "ꟻLIP", "mean", "p95");
    for r in rows(g) {
        let _ = writeln!(s, "  {:<13} {:>9}  {:>15}  {:>6}  {:>6}", r[0], r[1], r[2], r[3], r[4]);
    }
    if g.findings.is_empty() {
        let _ = writeln!(s, "\nNothing differs that the rubric counts.");
    } else {
        let _ = writeln!(s, "\nWhat differs, the most points lost first:");
        for f in &g.findings {
            let _ = writeln!(s, "  - {} (−{}): {}", f.term.name(), tenths(f.lost), f.text);
        }
    }
    s
}

/// The failed grade of a student lesson that cannot be graded: 0 points and why.
pub fn failed_text(reason: &str, h: &Heading, total: f32) -> String {
    format!(
        "grade: 0 of {} points (pass mark {}): failed\n  yours:     {}\n  reference: {}\n\nYour lesson cannot be graded:\n{}\n",
        tenths(total),
        tenths(h.pass),
        h.student,
        h.reference,
        reason.lines().map(|l| format!("  {l}")).collect::<Vec<_>>().join("\n")
    )
}

/// The Markdown report: the verdict, the table, the findings, and each term present as
/// reference | yours | ꟻLIP images (files under `images/`, as [`images`] names them).
pub fn markdown(g: &Grade, h: &Heading, images: &[(Term, [String; 3])]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Grade: {}\n", verdict(g, h.pass));
    let _ = writeln!(s, "Yours: `{}`  \nReference: `{}`\n", h.student, h.reference);
    if !g.findings.is_empty() {
        let _ = writeln!(s, "## What differs\n");
        for f in &g.findings {
            let _ = writeln!(s, "- **{}** (−{} points): {}", f.term.name(), tenths(f.lost), escape(&f.text));
        }
        s.push('\n');
    }
    let _ = writeln!(s, "## Points\n\n| term | points | ꟻLIP | mean | p95 |\n| --- | ---: | ---: | ---: | ---: |");
    for r in rows(g) {
        let _ = writeln!(s, "| {} | {} | {} | {} | {} |", r[0], r[1], r[2], r[3], r[4]);
    }
    if !images.is_empty() {
        let _ = writeln!(
            s,
            "\n## Side by side\n\n| term | reference | yours | ꟻLIP (black: same, yellow: most different) |\n| --- | --- | --- | --- |"
        );
        for (term, [r, y, f]) in images {
            let _ = writeln!(s, "| {} | ![reference]({r}) | ![yours]({y}) | ![difference]({f}) |", term.name());
        }
    }
    let _ = writeln!(
        s,
        "\nꟻLIP: Andersson et al. 2020, over the pixels where either image shows the term; the rubric and the metrics are in shadelab's docs/grading.md."
    );
    s
}

/// Markdown's table and emphasis characters in a finding, taken literally.
fn escape(t: &str) -> String {
    t.replace('|', "\\|").replace('*', "\\*")
}

/// The images of each term either lesson has: (term, [reference, yours, ꟻLIP]) as 8-bit RGB
/// of `size`; the shadows as masks (white: shadowed; the ꟻLIP column red where only one is).
pub fn images(g: &Grade, reference: &Rendered, student: &Rendered) -> Vec<(Term, [Vec<u8>; 3])> {
    let mut out = Vec::new();
    for (i, &term) in IMAGE_TERMS.iter().enumerate() {
        let score = &g.terms[i];
        if !score.present {
            continue;
        }
        let heat: Vec<u8> = score.map.iter().flat_map(|&e| crate::cost::metrics::heat_colour(e)).collect();
        out.push((term, [reference.developed[i].clone(), student.developed[i].clone(), heat]));
    }
    let (rm, sm) = (reference.shadow_mask(), student.shadow_mask());
    if rm.iter().chain(&sm).any(|&b| b) {
        let mask = |m: &[bool]| m.iter().flat_map(|&b| if b { [255u8; 3] } else { [0u8; 3] }).collect::<Vec<u8>>();
        let diff = rm.iter().zip(&sm).flat_map(|(&a, &b)| if a != b { [230, 40, 40] } else { [0, 0, 0] }).collect();
        out.push((Term::Shadows, [mask(&rm), mask(&sm), diff]));
    }
    out
}
