//! Command-line interface: one file per subcommand; no rendering logic here.

mod bench;
mod brdf;
mod check;
mod explain;
mod figures;
mod lessons;
mod render;
mod snapshot;

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
    /// Physically based BRDFs: `eval` values from stdin, `lobe` polar plots, `albedo` (white furnace).
    Brdf(brdf::BrdfArgs),
    /// Time fixed workloads (sphere, sphere-gouraud, dense, slide): median/min/max per frame.
    ///
    /// `median_ms` (with min, max, Mpix/s, Mtri/s) is render + develop to the 8-bit sRGB
    /// image a user gets, comparable to a peer's clear + draw + readback; beside it
    /// `render_median_ms` is the linear frame only and `png_median_ms` adds PNG encoding
    /// in memory. The scene is built once, before timing.
    Bench(bench::BenchArgs),
    /// Show each material's equation with its values, and which passes, terms and lights run and why.
    Explain(explain::ExplainArgs),
    /// Render every [[figure]] of lessons (files or folders) to DIR/<lesson>/<figure>.png.
    Figures(figures::FiguresArgs),
    /// Compare variants side by side: --vary KEY=V1,V2,...
    Compare(figures::VaryArgs),
    /// Sweep a parameter (--vary once) or two as a grid (--vary twice: rows, then columns).
    Sweep(figures::VaryArgs),
    /// Split one render into its terms: ambient | diffuse | specular | total.
    Split(figures::SplitArgs),
    /// List lessons with their titles and figures.
    Lessons(lessons::LessonsArgs),
    /// Compare every figure with blessed PNGs (exit 1 on a mismatch); --bless writes them.
    Snapshot(snapshot::SnapshotArgs),
}

/// Flags shared by the figure commands.
#[derive(Debug, Clone, clap::Args)]
pub struct FigureFlags {
    /// Colour theme.
    #[arg(long, value_enum, default_value = "light")]
    pub theme: ThemeArg,
    /// Scale of text and spacing (2 for high-DPI slides); cells keep their size.
    #[arg(long, default_value_t = 1.0, value_name = "FACTOR")]
    pub scale: f32,
    /// Size of each cell in pixels, e.g. 320x320 (default: the figure's `cell`, else the camera size).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub cell: Option<(u32, u32)>,
    /// Print the render time under each cell.
    #[arg(long)]
    pub timings: bool,
}

/// `--theme` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum ThemeArg {
    /// White background, dark text (slides).
    Light,
    /// Dark background, light text.
    Dark,
    /// Transparent background, dark text; cells keep their coverage as alpha.
    Transparent,
}

impl FigureFlags {
    /// Validated figure options.
    fn options(&self) -> Result<crate::figure::FigureOptions, CliError> {
        if !(self.scale.is_finite() && (0.25..=8.0).contains(&self.scale)) {
            return Err(CliError::Input(format!("--scale {}: give a factor from 0.25 to 8", self.scale)));
        }
        if let Some((w, h)) = self.cell
            && !((8..=4096).contains(&w) && (8..=4096).contains(&h))
        {
            return Err(CliError::Input(format!("--cell {w}x{h}: each side must be 8 to 4096 pixels")));
        }
        let theme = match self.theme {
            ThemeArg::Light => crate::figure::grid::Theme::Light,
            ThemeArg::Dark => crate::figure::grid::Theme::Dark,
            ThemeArg::Transparent => crate::figure::grid::Theme::Transparent,
        };
        Ok(crate::figure::FigureOptions { theme, scale: self.scale, cell: self.cell, timings: self.timings })
    }
}

/// Parses `WxH` (e.g. `1024x768`) into a size of at least 1×1.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(|| format!("`{s}` is not WxH, e.g. 1024x768"))?;
    let w: u32 = w.trim().parse().map_err(|_| format!("width `{w}` is not a positive integer"))?;
    let h: u32 = h.trim().parse().map_err(|_| format!("height `{h}` is not a positive integer"))?;
    if w == 0 || h == 0 {
        return Err(format!("`{s}`: width and height must be at least 1"));
    }
    Ok((w, h))
}

/// A failed command: bad input (exit 2) or an internal failure (exit 1).
#[derive(Debug)]
pub enum CliError {
    /// The user's input is wrong: a lesson, an argument, a mesh file.
    Input(String),
    /// Something failed that the input did not cause (e.g. the disk).
    Internal(String),
    /// A check ran and found differences (snapshots): exit 1.
    Mismatch(String),
}

impl CliError {
    /// The process exit code: 2 for bad input, 1 for internal failures.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Input(_) => 2,
            CliError::Internal(_) | CliError::Mismatch(_) => 1,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Input(m) | CliError::Internal(m) | CliError::Mismatch(m) => f.write_str(m),
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

impl From<crate::figure::FigureError> for CliError {
    fn from(e: crate::figure::FigureError) -> Self {
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
        Command::Bench(a) => bench::run_bench(a),
        Command::Brdf(a) => brdf::run(a),
        Command::Explain(a) => explain::run(a),
        Command::Figures(a) => figures::run_figures(a),
        Command::Compare(a) => figures::run_vary(a, crate::lesson::FigureKind::Compare),
        Command::Sweep(a) => figures::run_vary(a, crate::lesson::FigureKind::Sweep),
        Command::Split(a) => figures::run_split(a),
        Command::Lessons(a) => lessons::run(a),
        Command::Snapshot(a) => snapshot::run(a),
    })
}

/// Parses `--set` arguments plus shorthand overrides (`--size`, `--aa`) into overrides.
fn overrides(sets: &[String], extra: Vec<String>) -> Result<Vec<crate::lesson::Override>, CliError> {
    sets.iter().chain(extra.iter()).map(|s| crate::lesson::Override::parse(s).map_err(|m| CliError::Input(format!("--set: {m}")))).collect()
}
