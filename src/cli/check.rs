//! `shadelab check`: validate lessons (parse, validate, load meshes) without rendering.

use super::CliError;
use super::diagnostics::{self, Diagnostic};
use crate::lesson::LessonError;
use std::path::PathBuf;

/// Arguments of `shadelab check`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Every lesson of a folder (each *.toml in it; every error reported, exit 2 if any failed):
    shadelab check lessons/
  One lesson with a changed value, as `render --set` would read it:
    shadelab check lessons/04-shininess.toml --set material.plastic.shininess=64
  Only the verdict (the exit code) and the summary line:
    shadelab check -q lessons/
  Every error as one JSON object per line, for a tool:
    shadelab check lessons/ --format jsonl")]
pub struct CheckArgs {
    /// Lesson files, or folders of lessons (every *.toml inside).
    #[arg(required = true, value_name = "PATH")]
    pub lessons: Vec<PathBuf>,
    #[command(flatten)]
    pub set: super::SetArgs,
    #[command(flatten)]
    pub report: diagnostics::ReportFlags,
}

/// Why a lesson failed, kept in its structure for the machine-readable formats.
enum Failure {
    /// The lesson or one of its figures does not validate.
    Lesson(Box<LessonError>, &'static str),
    /// Known only as text (a budget, a figure that cannot be made).
    Text(CliError, &'static str),
}

impl Failure {
    fn diagnostics(&self, path: &std::path::Path) -> Vec<Diagnostic> {
        match self {
            Failure::Lesson(e, code) => diagnostics::of_lesson_error(e, code),
            Failure::Text(e, code) => vec![diagnostics::of_text(Some(path), code, &e.to_string())],
        }
    }
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Lesson(e, _) => e.fmt(f),
            Failure::Text(e, _) => e.fmt(f),
        }
    }
}

/// Checks every lesson and reports each; fails (exit 2) if any is invalid.
pub fn run(args: CheckArgs, quiet: bool) -> Result<(), CliError> {
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let start = std::time::Instant::now();
    let files = super::figures::lesson_files(&args.lessons)?;
    if let Some(empty) =
        args.lessons.iter().find(|p| p.is_dir() && super::figures::lesson_files(std::slice::from_ref(*p)).is_ok_and(|f| f.is_empty()))
    {
        return Err(CliError::Input(format!(
            "{}: no *.toml lessons in this folder\n  hint: give a lesson file or a folder of them",
            empty.display()
        )));
    }
    let mut failed = 0;
    let jsonl = args.report.configure().jsonl;
    for path in &files {
        let result = (|| -> Result<_, Failure> {
            let l = crate::lesson::load(path, &sets).map_err(|e| Failure::Lesson(Box::new(e), "lesson"))?;
            for spec in &l.figures {
                crate::figure::check_figure(&l, spec, &crate::figure::FigureOptions::default()).map_err(|e| match e {
                    crate::figure::FigureError::Lesson(e) => Failure::Lesson(Box::new(e), "lesson"),
                    crate::figure::FigureError::Scene(e) => Failure::Lesson(e.lesson, "asset"),
                    other => Failure::Text(CliError::from(other), "figure"),
                })?;
            }
            let scene = crate::scene::build::build(&l).map_err(|e| Failure::Lesson(e.lesson, "asset"))?;
            let estimate =
                crate::render::budget::check(&scene).map_err(|e| Failure::Text(CliError::from(e.at(path.display())), "budget"))?;
            Ok((l, scene, estimate))
        })();
        match result {
            Ok((lesson, scene, estimate)) => {
                let n = lesson.figures.len();
                let plural = if n == 1 { "" } else { "s" };
                // Degenerate triangles are named by the note below, not counted as drawn.
                let drawn = scene.geometry.triangles.len() - scene.repairs.degenerate_triangles;
                if !quiet && !jsonl {
                    outln!(
                        "ok    {}  ({}; {drawn} triangles, {n} figure{plural}; a render {})",
                        path.display(),
                        lesson.title,
                        estimate.summary()
                    )?;
                }
                if !quiet || jsonl {
                    super::repair_notes(&lesson, &scene);
                }
            }
            Err(e) => {
                failed += 1;
                diagnostics::emit(&e.diagnostics(path))?;
                if !jsonl {
                    super::out::eprint_line(format_args!("error: {e}"));
                }
            }
        }
    }
    if failed > 0 {
        return Err(CliError::Input(invalid_line(failed, files.len())));
    }
    if jsonl {
        // The verdict is the exit code; stdout holds only the diagnostics.
        return Ok(());
    }
    outln!("{}: all valid", super::progress::summary(files.len(), "lesson", "lessons", start.elapsed(), None))
}

/// "2 of 3 lessons are invalid", "1 of 3 lessons is invalid", "the lesson is invalid".
pub(super) fn invalid_line(failed: usize, total: usize) -> String {
    match (failed, total) {
        (_, 1) => "the lesson is invalid".into(),
        (1, _) => format!("1 of {total} lessons is invalid"),
        _ => format!("{failed} of {total} lessons are invalid"),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_summary_agrees_in_number() {
        assert_eq!(super::invalid_line(1, 1), "the lesson is invalid");
        assert_eq!(super::invalid_line(1, 3), "1 of 3 lessons is invalid");
        assert_eq!(super::invalid_line(2, 3), "2 of 3 lessons are invalid");
    }
}
