//! Command-line interface: one file per subcommand; no rendering logic here.

mod check;
mod render;

use clap::{Parser, Subcommand};
use std::fmt;

/// shadelab: render shading lessons with a small software rasterizer.
#[derive(Debug, Parser)]
#[command(name = "shadelab", version, about, long_about = None)]
pub struct Args {
    /// Worker threads (default: all cores). Output is identical for any count.
    #[arg(long, global = true, value_name = "N")]
    pub threads: Option<usize>,
    /// The subcommand.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a lesson to a PNG (8-bit sRGB) or EXR (linear float) image.
    Render(render::RenderArgs),
    /// Validate lesson files without rendering.
    Check(check::CheckArgs),
}

/// A failed command: bad input (exit 2) or an internal failure (exit 1).
#[derive(Debug)]
pub enum CliError {
    /// The user's input is wrong: a lesson, an argument, a mesh file.
    Input(String),
    /// Something failed that the input did not cause (e.g. the disk).
    Internal(String),
}

impl CliError {
    /// The process exit code: 2 for bad input, 1 for internal failures.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Input(_) => 2,
            CliError::Internal(_) => 1,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Input(m) | CliError::Internal(m) => f.write_str(m),
        }
    }
}

impl From<crate::lesson::LessonError> for CliError {
    fn from(e: crate::lesson::LessonError) -> Self {
        CliError::Input(e.to_string())
    }
}

impl From<crate::scene::build::SceneError> for CliError {
    fn from(e: crate::scene::build::SceneError) -> Self {
        CliError::Input(e.to_string())
    }
}

impl From<crate::output::OutputError> for CliError {
    fn from(e: crate::output::OutputError) -> Self {
        CliError::Internal(e.to_string())
    }
}

/// Runs a parsed command line.
///
/// # Errors
/// [`CliError`] with the message to print.
pub fn run(args: Args) -> Result<(), CliError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .map_err(|e| CliError::Internal(format!("cannot start threads: {e}")))?;
    pool.install(|| match args.command {
        Command::Render(a) => render::run(a),
        Command::Check(a) => check::run(a),
    })
}

/// Parses `--set` arguments plus shorthand overrides (`--size`, `--aa`) into overrides.
fn overrides(sets: &[String], extra: Vec<String>) -> Result<Vec<crate::lesson::Override>, CliError> {
    sets.iter().chain(extra.iter()).map(|s| crate::lesson::Override::parse(s).map_err(|m| CliError::Input(format!("--set: {m}")))).collect()
}
