//! `shadelab explain`: the equation each material uses, with its values, and the render plan
//! (the text is `render::explain::text`, shared with `shadelab site`).

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab explain`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Each material's equation with its values, the plan and what one render ran:
    shadelab explain lessons/07-lights.toml
  The plan only, after a change of shadow method (no render):
    shadelab explain lessons/16-shadows.toml --set render.shadows=map --no-render")]
pub struct ExplainArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// Print the plan only: skip the render whose counts prove it.
    #[arg(long)]
    pub no_render: bool,
}

/// Prints the materials' equations and the plan.
pub fn run(args: ExplainArgs, quiet: bool) -> Result<(), CliError> {
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let lesson = crate::lesson::load(&args.lesson, &sets)?;
    let scene = crate::scene::build::build(&lesson)?;
    // The explanation is the result: -q only checks that the lesson can be explained.
    if quiet {
        return Ok(());
    }
    outln!("{} ({})\n", lesson.title, args.lesson.display())?;
    out!("{}", crate::render::explain::text(&scene, !args.no_render, lesson.lang))
}
