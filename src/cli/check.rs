//! `shadelab check`: validate lessons (parse, validate, load meshes) without rendering.

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab check`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Every lesson of a folder (each *.toml in it; every error reported, exit 2 if any failed):
    shadelab check lessons/
  One lesson with a changed value, as `render --set` would read it:
    shadelab check lessons/04-shininess.toml --set material.plastic.shininess=64
  Only the verdict (the exit code) and the summary line:
    shadelab check -q lessons/")]
pub struct CheckArgs {
    /// Lesson files, or folders of lessons (every *.toml inside).
    #[arg(required = true, value_name = "PATH")]
    pub lessons: Vec<PathBuf>,
    #[command(flatten)]
    pub set: super::SetArgs,
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
    for path in &files {
        let result = crate::lesson::load(path, &sets).map_err(CliError::from).and_then(|l| {
            for spec in &l.figures {
                crate::figure::check_figure(&l, spec, &crate::figure::FigureOptions::default())?;
            }
            let scene = crate::scene::build::build(&l)?;
            let estimate = crate::render::budget::check(&scene).map_err(|e| e.at(path.display()))?;
            Ok((l, scene, estimate))
        });
        match result {
            Ok((lesson, scene, estimate)) => {
                let n = lesson.figures.len();
                let plural = if n == 1 { "" } else { "s" };
                // Degenerate triangles are named by the note below, not counted as drawn.
                let drawn = scene.geometry.triangles.len() - scene.repairs.degenerate_triangles;
                if !quiet {
                    outln!(
                        "ok    {}  ({}; {drawn} triangles, {n} figure{plural}; a render {})",
                        path.display(),
                        lesson.title,
                        estimate.summary()
                    )?;
                    super::repair_notes(&lesson, &scene);
                }
            }
            Err(e) => {
                failed += 1;
                super::out::eprint_line(format_args!("error: {e}"));
            }
        }
    }
    if failed > 0 {
        return Err(CliError::Input(invalid_line(failed, files.len())));
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
