//! `shadelab check`: validate lessons (parse, validate, load meshes) without rendering.

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Lesson files to validate.
    #[arg(required = true, value_name = "LESSON")]
    pub lessons: Vec<PathBuf>,
    /// Override a value by dotted path, e.g. material.plastic.shininess=64 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

/// Checks every lesson and reports each; fails (exit 2) if any is invalid.
pub fn run(args: CheckArgs) -> Result<(), CliError> {
    let sets = super::overrides(&args.sets, Vec::new())?;
    let mut failed = 0;
    for path in &args.lessons {
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
                outln!("ok    {}  ({}; {drawn} triangles, {n} figure{plural})", path.display(), lesson.title)?;
                super::repair_notes(&lesson, &scene);
            }
            Err(e) => {
                failed += 1;
                eprintln!("error: {e}");
            }
        }
    }
    if failed > 0 {
        return Err(CliError::Input(format!("{failed} of {} lessons are invalid", args.lessons.len())));
    }
    Ok(())
}
