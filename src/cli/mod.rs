//! Command-line interface: one file per subcommand; no rendering logic here.
//!
//! Subcommands print to stdout only through [`outln!`] and [`out!`] (see [`out`]), so a
//! closed pipe ends any of them quietly.

/// `println!` for subcommands: evaluates to `Result<(), CliError>` (see [`out::print`]).
macro_rules! outln {
    () => {
        $crate::cli::out::print(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::cli::out::print(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` for subcommands: evaluates to `Result<(), CliError>` (see [`out::print`]).
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::out::print(format_args!($($arg)*))
    };
}

mod bench;
mod brdf;
mod cache;
mod check;
mod completions;
mod cost;
mod diagnostics;
mod envmap;
mod explain;
mod export;
mod figures;
mod grade;
mod import;
mod junit;
mod lessons;
mod new;
pub mod out;
mod progress;
mod provenance;
mod render;
mod report;
mod serve;
mod shard;
mod site;
mod snapshot;
mod watch;

use clap::{Parser, Subcommand};
use std::fmt;

/// Render shading lessons with a small software rasterizer (no GPU).
#[derive(Debug, Parser)]
#[command(name = "shadelab", version, about, long_about = None, after_help = EXAMPLES)]
pub struct Args {
    /// Print only errors, warnings and a multi-file command's one summary line (which says
    /// where the files went): no per-file lines, notes or progress bar.
    #[arg(short, long, global = true)]
    pub quiet: bool,
    /// Worker threads, 1 to 1024 (default: all cores). Output is identical for any count.
    #[arg(long, global = true, value_name = "N")]
    pub threads: Option<usize>,
    /// Also allow lessons to read files (meshes) under DIR; by default only files inside
    /// the lesson file's folder are read (repeatable).
    #[arg(long = "allow-dir", global = true, value_name = "DIR")]
    pub allow_dirs: Vec<std::path::PathBuf>,
    /// Language of built-in figure labels (as `[lesson] lang` in every lesson): en or ja.
    #[arg(long, global = true, value_name = "LANG", value_parser = ["en", "ja"])]
    pub lang: Option<String>,
    /// Keep references and rendered figure cells in DIR across runs (default:
    /// $SHADELAB_CACHE_DIR, else the platform's cache folder, e.g. ~/.cache/shadelab).
    #[arg(long, global = true, value_name = "DIR", conflicts_with = "no_cache")]
    pub cache: Option<std::path::PathBuf>,
    /// Compute everything afresh and keep nothing (as $SHADELAB_NO_CACHE=1).
    #[arg(long = "no-cache", global = true)]
    pub no_cache: bool,
    /// Allow each render FACTOR times the default work and memory budget (5 min of one
    /// core, 4 GiB, as estimated before any work; `explain` shows the estimate).
    #[arg(long, global = true, value_name = "FACTOR", allow_negative_numbers = true)]
    pub budget: Option<f64>,
    /// The subcommand.
    #[command(subcommand)]
    pub command: Command,
}

/// The top-level help's examples: the first steps of a new user.
const EXAMPLES: &str = "Examples:
  List the bundled lessons, then render the first one:
    shadelab lessons
    shadelab render lessons/01-first-light.toml -o out/first.png
  Validate every lesson of a folder:
    shadelab check lessons/
  Start a lesson of your own from a commented template:
    shadelab new my-first-lesson --template classic

Each subcommand's --help ends with its own examples; docs/cli.md has the rules every flag follows.";

/// The most worker threads `--threads` allows.
const MAX_THREADS: usize = 1024;

/// The global flags each subcommand ignores: hidden from its `--help`, completions and man
/// page (they still parse there, as a global flag must).
const IGNORED_GLOBALS: [(&str, &[&str]); 9] = [
    ("envmap", &["threads", "allow_dirs", "lang", "cache", "no_cache", "budget"]),
    ("import", &["threads", "allow_dirs", "lang", "cache", "no_cache", "budget"]),
    ("export", &["threads", "lang", "cache", "no_cache", "budget"]),
    ("completions", &["threads", "allow_dirs", "lang", "cache", "no_cache", "budget"]),
    ("man", &["threads", "allow_dirs", "lang", "cache", "no_cache", "budget"]),
    ("cache", &["threads", "allow_dirs", "lang", "budget"]),
    ("lessons", &["threads", "lang", "cache", "no_cache", "budget"]),
    ("check", &["threads", "lang", "cache", "no_cache"]),
    ("bench", &["allow_dirs", "lang", "cache", "no_cache", "budget"]),
];

/// The command line's definition as users see it: [`Args`] with each subcommand's ignored
/// global flags hidden (parsing, completions and man pages all use this one).
pub fn command() -> clap::Command {
    use clap::CommandFactory;
    let mut cmd = Args::command();
    let globals: Vec<clap::Arg> = cmd.get_arguments().filter(|a| a.is_global_set()).cloned().collect();
    // A subcommand's own hidden copy of a global flag: clap copies a global flag only into
    // the subcommands that do not define it, and hands its value up as the global one's.
    for (sub, ignored) in IGNORED_GLOBALS {
        cmd = cmd.mut_subcommand(sub, |s| {
            globals.iter().filter(|g| ignored.contains(&g.get_id().as_str())).fold(s, |s, g| s.arg(g.clone().global(false).hide(true)))
        });
    }
    cmd
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
    /// Time fixed workloads (sphere, sphere-gouraud, dense, slide, shadow, shadow-ray) per frame.
    ///
    /// `8-bit` (median, min, max; Mpix/s and Mtri/s from its median) times the image a user
    /// gets: the render developed straight to 8-bit sRGB (the fused path of `render -o
    /// x.png`), comparable to a peer's clear + draw + readback. `float` times the other
    /// path, a linear float frame (`render -o x.exr`, layers, figures): not a part of the
    /// 8-bit time, and usually longer. `+png` is the 8-bit path plus PNG encoding in memory.
    /// The scene is built once, before timing.
    Bench(bench::BenchArgs),
    /// Show each material's equation with its values, and which passes, terms and lights run and why.
    Explain(explain::ExplainArgs),
    /// What accuracy costs in time: each rung of a quality ladder timed and compared with a reference.
    Cost(cost::CostArgs),
    /// Render every [[figure]] of lessons (files or folders) to DIR/<lesson>/<figure>.png.
    Figures(figures::FiguresArgs),
    /// Compare variants side by side in one row: --vary KEY=V1,V2,... (once).
    Compare(figures::CompareArgs),
    /// Sweep a parameter in one row (--vary once), or two as a grid (--vary twice: rows, then columns).
    Sweep(figures::SweepArgs),
    /// Split one render into its terms: ambient | diffuse | specular | total.
    Split(figures::SplitArgs),
    /// List lessons with their titles and figures.
    Lessons(lessons::LessonsArgs),
    /// Compare every figure with blessed PNGs (exit 1 on a mismatch); --bless writes them.
    Snapshot(snapshot::SnapshotArgs),
    /// Write a commented starter lesson (classic, pbr or lights) that passes `check`.
    New(new::NewArgs),
    /// Print a shell completion script (bash, elvish, fish, powershell, zsh) to stdout.
    Completions(completions::CompletionsArgs),
    /// Print the man page (roff) to stdout, or write one page per subcommand with -o DIR.
    Man(completions::ManArgs),
    /// Write lessons as a static HTML gallery (works from file://, no script): index, a page per lesson.
    Site(site::SiteArgs),
    /// Re-render lessons' images and figures at every save of a lesson or a file it reads; --serve shows them live.
    Watch(watch::WatchArgs),
    /// Show where results are kept between runs (references, figure cells, form factors) and their size; --clear empties it.
    Cache(cache::CacheArgs),
    /// Render a PNG again from what it records (lesson, overrides, options) and say whether it matches, or which input changed.
    Reproduce(provenance::ReproduceArgs),
    /// Grade a student's lesson against a reference: points per term (ꟻLIP), what differs in words, a Markdown report.
    Grade(grade::GradeArgs),
    /// Write a lesson that renders a glTF 2.0 scene (.glb/.gltf, e.g. from Blender): meshes, materials, lights, camera.
    Import(import::ImportArgs),
    /// Write a lesson as a glTF 2.0 binary (.glb) for Blender: meshes as rendered, materials, lights, camera.
    Export(export::ExportArgs),
    /// Convert an environment image between layouts: lat-long map, cube cross, mirror ball (sphere map).
    Envmap(envmap::EnvmapArgs),
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
    /// Lay each figure out for a slide, e.g. 1920x1080: text sized for it (never under 16 px),
    /// the largest cells that fit, long labels wrapped, a long row split into rows; the PNG is
    /// exactly the slide's size. Overrides a figure's `fit`.
    #[arg(long, value_name = "WxH", value_parser = parse_size, conflicts_with_all = ["cell", "scale"])]
    pub fit: Option<(u32, u32)>,
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
        if let Some((w, h)) = self.fit {
            let (lo, hi) = crate::lesson::limits::FIT_SIDE;
            if !((lo..=hi).contains(&i64::from(w)) && (lo..=hi).contains(&i64::from(h))) {
                return Err(CliError::Input(format!("--fit {w}x{h}: each side must be {lo} to {hi} pixels")));
            }
        }
        Ok(crate::figure::FigureOptions {
            theme,
            scale: self.scale,
            cell: self.cell,
            timings: self.timings,
            measure_time: true,
            fit: self.fit,
        })
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
    /// A lesson that does not validate, kept whole for `--format jsonl` (exit 2); the code
    /// says what kind (see [`diagnostics::Diagnostic::code`]).
    Lesson(Box<crate::lesson::LessonError>, &'static str),
    /// The reader of stdout went away (`| head`): a quiet, successful end (exit 0).
    StdoutClosed,
}

impl CliError {
    /// The process exit code: 2 for bad input, 1 for internal failures, 0 for a closed stdout.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::StdoutClosed => 0,
            CliError::Input(_) | CliError::Lesson(..) => 2,
            CliError::Internal(_) | CliError::Mismatch(_) => 1,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Input(m) | CliError::Internal(m) | CliError::Mismatch(m) => f.write_str(m),
            CliError::Lesson(e, _) => e.fmt(f),
            CliError::StdoutClosed => f.write_str("stdout was closed"),
        }
    }
}

impl From<crate::lesson::LessonError> for CliError {
    fn from(e: crate::lesson::LessonError) -> Self {
        CliError::Lesson(Box::new(e), "lesson")
    }
}

impl From<crate::scene::build::SceneError> for CliError {
    fn from(e: crate::scene::build::SceneError) -> Self {
        CliError::Lesson(e.lesson, "asset")
    }
}

impl From<crate::render::budget::OverBudget> for CliError {
    fn from(e: crate::render::budget::OverBudget) -> Self {
        CliError::Input(e.0)
    }
}

impl From<crate::figure::FigureError> for CliError {
    fn from(e: crate::figure::FigureError) -> Self {
        match e {
            crate::figure::FigureError::Lesson(e) => e.into(),
            crate::figure::FigureError::Scene(e) => e.into(),
            other => CliError::Input(other.to_string()),
        }
    }
}

impl From<crate::output::OutputError> for CliError {
    /// A destination that cannot be written is the user's choice to change: exit 2.
    fn from(e: crate::output::OutputError) -> Self {
        CliError::Input(e.to_string())
    }
}

/// Prints a command line's usage error as a `--format jsonl` diagnostic on stdout when the
/// command line asks for JSON Lines (help and version are no errors: nothing is printed).
pub fn usage_error_json(e: &clap::Error, argv: impl Iterator<Item = std::ffi::OsString>) {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand) {
        return;
    }
    let argv: Vec<String> = argv.map(|a| a.to_string_lossy().into_owned()).collect();
    let jsonl = argv.windows(2).any(|w| w[0] == "--format" && w[1] == "jsonl") || argv.iter().any(|a| a == "--format=jsonl");
    if !jsonl {
        return;
    }
    let text = e.render().to_string();
    let message = text.lines().next().unwrap_or_default().trim_start_matches("error: ").to_string();
    let d = diagnostics::Diagnostic {
        level: "error",
        code: "usage",
        message,
        file: None,
        at: None,
        flag: None,
        hint: Some("see `shadelab help` and the subcommand's --help".into()),
        key: None,
    };
    let _ = outln!("{}", d.json());
}

/// Runs a parsed command line.
///
/// # Errors
/// [`CliError`] with the message to print.
pub fn run(args: Args) -> Result<(), CliError> {
    if let Some(lang) = &args.lang {
        // One process runs one command line: the first value is the only one.
        let _ = LANG.set(lang.clone());
    }
    crate::cache::configure(match (args.no_cache, &args.cache) {
        (true, _) => None,
        (false, Some(dir)) => Some(dir.clone()),
        (false, None) => crate::cache::default_dir(),
    });
    if let Some(f) = args.budget {
        crate::render::budget::configure(f)
            .map_err(|m| CliError::Input(format!("{m}\n  hint: e.g. --budget 4 allows four times the default")))?;
    }
    crate::lesson::assets::allow_dirs(&args.allow_dirs).map_err(|m| CliError::Input(format!("{m}\n  hint: give an existing folder")))?;
    if let Some(n) = args.threads
        && !(1..=MAX_THREADS).contains(&n)
    {
        // Each thread reserves a stack: a huge count would exhaust memory before any work.
        return Err(CliError::Input(format!(
            "--threads {n}: give 1 to {MAX_THREADS} worker threads\n  hint: leave it out to use every core; output is the same for any count"
        )));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .map_err(|e| CliError::Internal(format!("cannot start threads: {e}")))?;
    let quiet = args.quiet;
    let result = pool.install(|| match args.command {
        Command::Render(a) => render::run(a, quiet),
        Command::Check(a) => check::run(a, quiet),
        Command::Bench(a) => bench::run_bench(a, quiet),
        Command::Brdf(a) => brdf::run(a, quiet),
        Command::Explain(a) => explain::run(a, quiet),
        Command::Cost(a) => cost::run(a, quiet),
        Command::Figures(a) => figures::run_figures(a, quiet),
        Command::Compare(a) => figures::run_compare(a, quiet),
        Command::Sweep(a) => figures::run_sweep(a, quiet),
        Command::Split(a) => figures::run_split(a, quiet),
        Command::Lessons(a) => lessons::run(a, quiet),
        Command::Snapshot(a) => snapshot::run(a, quiet),
        Command::New(a) => new::run(a, quiet),
        Command::Completions(a) => completions::run_completions(a),
        Command::Man(a) => completions::run_man(a, quiet),
        Command::Site(a) => site::run(a, quiet),
        Command::Watch(a) => watch::run(a, quiet),
        Command::Cache(a) => cache::run(a, quiet),
        Command::Reproduce(a) => provenance::run(a, quiet),
        Command::Grade(a) => grade::run(a, quiet),
        Command::Import(a) => import::run(a, quiet),
        Command::Envmap(a) => envmap::run(a, quiet),
        Command::Export(a) => export::run(a, quiet),
    });
    texel_warnings();
    diagnostics::finish(&result)?;
    result
}

/// A warning per image file whose texels were not finite or were negative (read as 0):
/// counted while decoding, never fatal.
fn texel_warnings() {
    for (path, n) in crate::scene::texture::take_texel_repairs() {
        let texels = if n == 1 { "texel was" } else { "texels were" };
        let message = format!("{n} {texels} not finite, negative or above 10¹² (a damaged image?); repaired");
        let shown = crate::output::shown_path(&path);
        diagnostics::warn(
            diagnostics::Diagnostic::warning("asset", message.clone(), Some(path), None),
            format_args!("warning: {shown}: {message}"),
        );
    }
}

/// Notes on stderr for meshes that needed repair (degenerate triangles skipped, vertex
/// normals replaced), one line per object: counted while building, never fatal.
fn repair_notes(lesson: &crate::lesson::Lesson, scene: &crate::scene::Scene) {
    use crate::scene::Shape;
    let plural = |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    for (i, (spec, bounds)) in lesson.objects.iter().zip(&scene.geometry.objects).enumerate() {
        let r = bounds.repairs;
        if r == crate::scene::MeshRepairs::default() {
            continue;
        }
        let name = match &spec.shape {
            Shape::Mesh { path, .. } => crate::lesson::assets::shown(&lesson.path, path),
            other => other.name().into(),
        };
        let mut parts = Vec::new();
        if r.degenerate_triangles > 0 {
            parts.push(plural(r.degenerate_triangles, "degenerate triangle skipped", "degenerate triangles skipped"));
        }
        if r.repaired_normals > 0 {
            parts.push(plural(r.repaired_normals, "vertex normal repaired", "vertex normals repaired"));
        }
        // At the object's table in the lesson, where a CI annotation shows it.
        let key = crate::lesson::KeyPath::parse(&format!("object.{i}")).expect("a valid path");
        let span = crate::lesson::spans::find(&lesson.source, &key, crate::lesson::spans::Target::Value);
        let message = format!("object {i} ({name}): {}", parts.join(", "));
        let at = (!lesson.source.is_empty()).then(|| crate::lesson::spans::line_col(&lesson.source, span.start));
        diagnostics::warn(
            diagnostics::Diagnostic {
                level: "note",
                ..diagnostics::Diagnostic::warning("mesh", message.clone(), Some(lesson.path.clone()), at)
            },
            format_args!("note: {message}"),
        );
    }
}

/// `--set`, as every command that reads lessons takes it: declared once, flattened into each.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct SetArgs {
    /// Override a value of the lesson (of every lesson) by dotted path, e.g.
    /// material.plastic.shininess=64 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

/// `--lang`, for [`overrides`].
static LANG: std::sync::OnceLock<String> = std::sync::OnceLock::new();

/// Parses `--set` arguments plus shorthand overrides (`--size`, `--aa`, and `--lang` first,
/// so a `--set lesson.lang=...` wins) into overrides.
fn overrides(sets: &[String], extra: Vec<String>) -> Result<Vec<crate::lesson::Override>, CliError> {
    let lang = LANG.get().map(|l| format!("lesson.lang=\"{l}\""));
    lang.iter()
        .chain(sets.iter())
        .chain(extra.iter())
        .map(|s| crate::lesson::Override::parse(s).map_err(|m| CliError::Input(format!("in --set {s}: {m}"))))
        .collect()
}
