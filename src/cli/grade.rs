//! `shadelab grade STUDENT --against REFERENCE`: points per term from a rubric, what differs
//! in words, a Markdown report with the images, a JUnit entry.

use super::CliError;
use super::junit::{Case, Outcome};
use crate::grade::report::{self, Heading};
use crate::grade::rubric::{Rubric, Term};
use crate::grade::{self, Develop, Grade, GradeInputError};
use std::path::{Path, PathBuf};

/// Arguments of `shadelab grade`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Grade a student's copy of lesson 01 against the lesson itself (points, then what differs):
    shadelab grade lessons/01-first-light.toml --against lessons/01-first-light.toml
  With a Markdown report and its images for a pull-request comment, and a JUnit entry:
    shadelab grade lessons/01-first-light.toml --against lessons/01-first-light.toml -o grade/ --junit grade/junit.xml
  Also grade one figure of the reference, drawn from the student's lesson:
    shadelab grade lessons/04-shininess.toml --against lessons/04-shininess.toml --figure sweep

Exit 0 for a pass, 1 for a failed grade (also a student lesson that does not validate, reads
files outside its folder or has another image size: 0 points and why), 2 when the reference
or the rubric is wrong. docs/grading.md has the metrics, the default rubric and the findings.")]
pub struct GradeArgs {
    /// The student's lesson.
    #[arg(value_name = "STUDENT")]
    pub student: PathBuf,
    /// The reference lesson it is graded against (rendered with the same settings:
    /// its supersampling, exposure and tone map for both).
    #[arg(long, value_name = "REFERENCE")]
    pub against: PathBuf,
    /// Also grade this figure of the reference lesson, drawn from each lesson.
    #[arg(long, value_name = "NAME")]
    pub figure: Option<String>,
    /// Weights and thresholds per term, and the pass mark (TOML, docs/grading.md)
    /// [default: the built-in rubric, out of 100, pass at 60].
    #[arg(long, value_name = "FILE")]
    pub rubric: Option<PathBuf>,
    /// Write DIR/grade.md (a Markdown report: the findings, the points, reference | yours |
    /// ꟻLIP per term) and its images in DIR/images/.
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// Also write the grade as JUnit XML: a test per term, and one for the pass mark.
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
}

/// Grades the student's lesson; exit 1 when it does not pass.
pub fn run(args: GradeArgs, quiet: bool) -> Result<(), CliError> {
    let start = std::time::Instant::now();
    let rubric = match &args.rubric {
        Some(file) => {
            let text = std::fs::read_to_string(file).map_err(|e| {
                CliError::Input(format!(
                    "{}: cannot read the rubric: {e}\n  hint: give a TOML rubric file (docs/grading.md)",
                    file.display()
                ))
            })?;
            Rubric::parse(&text, &file.display().to_string()).map_err(CliError::Input)?
        }
        None => Rubric::default(),
    };
    if let Some(dir) = &args.output {
        crate::output::check_folder(dir, dir)?;
    }
    if let Some(file) = &args.junit {
        crate::output::check_destination(file)?;
    }
    let sets = super::overrides(&[], Vec::new())?;
    // The reference is the instructor's: anything wrong with it is bad input (exit 2).
    let reference = crate::lesson::load(&args.against, &sets)?;
    let spec = match &args.figure {
        Some(name) => Some(reference.figures.iter().find(|f| &f.name == name).cloned().ok_or_else(|| {
            let names: Vec<&str> = reference.figures.iter().map(|f| f.name.as_str()).collect();
            CliError::Input(format!(
                "--figure {name}: {} has no figure `{name}`\n  hint: its figures are {}",
                args.against.display(),
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ))
        })?),
        None => None,
    };
    let settings = reference.scene.settings;
    let develop = Develop { exposure: settings.exposure, tonemap: settings.tonemap };
    let rendered_reference = grade::render(&reference, develop).map_err(|e| match e {
        GradeInputError::Lesson(e) => CliError::from(e),
        GradeInputError::Scene(e) => CliError::from(e),
        GradeInputError::Budget(e) => CliError::from(e),
    })?;
    let heading = Heading { student: args.student.display().to_string(), reference: args.against.display().to_string(), pass: rubric.pass };
    let total: f32 = Term::ALL.iter().filter(|&&t| t != Term::Figure || spec.is_some()).map(|&t| rubric.rule(t).weight).sum();
    // The student's lesson, with the reference's supersampling: what goes wrong here is a
    // failed grade with its reason, never a crash.
    let student = (|| -> Result<_, String> {
        let mut sets = sets.clone();
        sets.push(crate::lesson::Override::parse(&format!("render.aa={}", settings.aa)).map_err(|e| e.to_string())?);
        let student = crate::lesson::load(&args.student, &sets).map_err(|e| e.to_string())?;
        let (rw, rh) = rendered_reference.size;
        let (sw, sh) = (student.scene.camera.width, student.scene.camera.height);
        if (sw, sh) != (rw, rh) {
            return Err(format!(
                "your image is {sw}×{sh} pixels, the reference's {rw}×{rh}: the two cannot be compared pixel by pixel\n  hint: set `[camera] size = [{rw}, {rh}]`"
            ));
        }
        let rendered = grade::render(&student, develop).map_err(|e| e.to_string())?;
        Ok((student, rendered))
    })();
    let (student, rendered) = match student {
        Ok(s) => s,
        Err(reason) => return fail(&args, &heading, &reason, total, quiet),
    };
    let mut g = grade::grade(&rendered_reference, &rendered, &rubric);
    let mut figure_images = None;
    if let Some(spec) = &spec {
        let opts = crate::figure::FigureOptions { measure_time: false, ..Default::default() };
        let drawn = |l: &crate::lesson::Lesson| {
            crate::figure::render_figure(l, spec, &opts).map(|f| image::DynamicImage::ImageRgba8(f.image).to_rgb8())
        };
        let r = drawn(&reference)?;
        let s = match drawn(&student) {
            Ok(s) if s.dimensions() == r.dimensions() => s,
            Ok(s) => {
                let reason = format!(
                    "the figure `{}` drawn from your lesson is {}×{} pixels, the reference's {}×{}",
                    spec.name,
                    s.width(),
                    s.height(),
                    r.width(),
                    r.height()
                );
                return fail(&args, &heading, &reason, total, quiet);
            }
            Err(e) => return fail(&args, &heading, &format!("the figure `{}`: {e}", spec.name), total, quiet),
        };
        let size = (r.width() as usize, r.height() as usize);
        let score = grade::image_score(Term::Figure, r.as_raw(), s.as_raw(), size, &rubric);
        let mut findings = g.findings.clone();
        if score.points < score.weight {
            findings.push(grade::findings::Finding {
                term: Term::Figure,
                lost: score.weight - score.points,
                text: format!(
                    "the figure `{}` differs most at the {} of it (ꟻLIP {:.2})",
                    spec.name,
                    grade::findings::worst_region(&score.map, size.0),
                    score.error
                ),
            });
            findings.sort_by(|a, b| b.lost.total_cmp(&a.lost));
        }
        let heat: Vec<u8> = score.map.iter().flat_map(|&e| crate::cost::metrics::heat_colour(e)).collect();
        figure_images = Some((size, [r.into_raw(), s.into_raw(), heat]));
        let mut terms = g.terms.clone();
        terms.push(score);
        g = Grade::of(terms, findings, &rubric);
    }
    if let Some(dir) = &args.output {
        write_markdown(dir, &g, &heading, &rendered_reference, &rendered, figure_images)?;
    }
    if let Some(file) = &args.junit {
        write_junit(file, &junit_cases(&args.student, &g, &heading, start.elapsed().as_secs_f64()))?;
    }
    if !quiet {
        out!("{}", report::text(&g, &heading))?;
        if let Some(dir) = &args.output {
            outln!("report: {}", dir.join("grade.md").display())?;
        }
    }
    if g.passed { Ok(()) } else { Err(CliError::Mismatch(format!("the grade is {}", report::verdict(&g, rubric.pass)))) }
}

/// A student lesson that cannot be graded: the report, the Markdown and the JUnit entry say
/// why; exit 1.
fn fail(args: &GradeArgs, heading: &Heading, reason: &str, total: f32, quiet: bool) -> Result<(), CliError> {
    let text = report::failed_text(reason, heading, total);
    if let Some(dir) = &args.output {
        let md = format!("# Grade: 0 of {total} points: failed\n\nYour lesson cannot be graded:\n\n```\n{reason}\n```\n");
        crate::output::write_atomic(&dir.join("grade.md"), |w| w.write_all(md.as_bytes()).map_err(|e| e.to_string()))?;
    }
    if let Some(file) = &args.junit {
        let first = reason.lines().next().unwrap_or_default().to_string();
        let case = Case {
            class: super::figures::stem(&args.student),
            name: "grade".into(),
            seconds: 0.0,
            outcome: Outcome::Failed { message: first, details: reason.to_string() },
        };
        write_junit(file, &[case])?;
    }
    if !quiet {
        out!("{text}")?;
    }
    Err(CliError::Mismatch("the lesson cannot be graded (above): 0 points".into()))
}

/// Three RGB images of one size: reference, yours, ꟻLIP.
type Images = [Vec<u8>; 3];

/// Writes DIR/grade.md and DIR/images/TERM-{reference,yours,flip}.png.
fn write_markdown(
    dir: &Path,
    g: &Grade,
    heading: &Heading,
    reference: &grade::Rendered,
    student: &grade::Rendered,
    figure: Option<((usize, usize), Images)>,
) -> Result<(), CliError> {
    let (w, h) = reference.size;
    let mut named = Vec::new();
    let mut all: Vec<(Term, (u32, u32), Images)> =
        report::images(g, reference, student).into_iter().map(|(t, imgs)| (t, (w, h), imgs)).collect();
    if let Some(((fw, fh), imgs)) = figure {
        all.push((Term::Figure, (fw as u32, fh as u32), imgs));
    }
    for (term, (iw, ih), imgs) in all {
        let names = ["reference", "yours", "flip"].map(|k| format!("images/{}-{k}.png", term.name()));
        for (name, rgb) in names.iter().zip(&imgs) {
            crate::output::write_png(&dir.join(name), iw, ih, rgb)?;
        }
        named.push((term, names));
    }
    let md = report::markdown(g, heading, &named);
    crate::output::write_atomic(&dir.join("grade.md"), |w| w.write_all(md.as_bytes()).map_err(|e| e.to_string()))?;
    Ok(())
}

/// A test per term (failed below half its weight) and one for the pass mark.
fn junit_cases(student: &Path, g: &Grade, heading: &Heading, seconds: f64) -> Vec<Case> {
    let class = super::figures::stem(student);
    let mut cases: Vec<Case> = g
        .terms
        .iter()
        .map(|t| {
            let lost: Vec<&str> = g.findings.iter().filter(|f| f.term == t.term).map(|f| f.text.as_str()).collect();
            let outcome = if t.points * 2.0 >= t.weight {
                Outcome::Passed
            } else {
                let metric = if t.term == Term::Shadows { "1 − IoU" } else { "ꟻLIP" };
                let details = if lost.is_empty() { "the terms' findings say why".to_string() } else { lost.join("\n") };
                Outcome::Failed { message: format!("{} of {} points ({metric} {:.3})", t.points, t.weight, t.error), details }
            };
            Case { class: class.clone(), name: t.term.name().into(), seconds: 0.0, outcome }
        })
        .collect();
    let outcome = if g.passed {
        Outcome::Passed
    } else {
        Outcome::Failed { message: report::verdict(g, heading.pass), details: report::text(g, heading) }
    };
    cases.push(Case { class, name: "grade".into(), seconds, outcome });
    cases
}

fn write_junit(file: &Path, cases: &[Case]) -> Result<(), CliError> {
    let text = super::junit::document("shadelab grade", cases, &super::junit::now());
    crate::output::write_atomic(file, |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
    Ok(())
}
