//! `shadelab explain`: the equation each material uses, with its values, and the render plan
//! (the text is `render::explain::text`, shared with `shadelab site`).

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab explain`.
#[derive(Debug, clap::Args)]
pub struct ExplainArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    /// Override a value by dotted path (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Print the plan only: skip the render whose counts prove it.
    #[arg(long)]
    pub no_render: bool,
}

/// Prints the materials' equations and the plan.
pub fn run(args: ExplainArgs) -> Result<(), CliError> {
    let sets = super::overrides(&args.sets, Vec::new())?;
    let lesson = crate::lesson::load(&args.lesson, &sets)?;
    let scene = crate::scene::build::build(&lesson)?;
    outln!("{} ({})\n", lesson.title, args.lesson.display())?;
    out!("{}", crate::render::explain::text(&scene, !args.no_render))
}
