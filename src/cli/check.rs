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
            crate::scene::build::build(&l).map(|s| (l, s)).map_err(CliError::from)
        });
        match result {
            Ok((lesson, scene)) => {
                let n = lesson.figures.len();
                let plural = if n == 1 { "" } else { "s" };
                // Degenerate triangles are named by the note below, not counted as drawn.
                let drawn = scene.geometry.triangles.len() - scene.repairs.degenerate_triangles;
                if !quiet {
                    outln!("ok    {}  ({}; {drawn} triangles, {n} figure{plural})", path.display(), lesson.title)?;
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
        return Err(CliError::Input(format!("{failed} of {} lessons are invalid", files.len())));
    }
    outln!("{}: all valid", super::progress::summary(files.len(), "lesson", "lessons", start.elapsed(), None))
}
