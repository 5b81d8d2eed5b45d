//! `shadelab figures`, `compare`, `sweep`, `split`: figures from lessons or from flags.

use super::progress::{Progress, summary};
use super::{CliError, FigureFlags};
use crate::figure::{self, FigureOptions};
use crate::lesson::{self, Axis, FigureBody, FigureKind, FigureSpec, KeyPath, Lesson};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// Arguments of `shadelab figures`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Every figure of two lessons, into out/<lesson>/<figure>.png:
    shadelab figures lessons/01-first-light.toml lessons/04-shininess.toml -o out/
  For dark slides, text and spacing twice as large:
    shadelab figures lessons/05-gouraud-vs-phong.toml -o slides/ --theme dark --scale 2
  Lessons 01 to 09, with only the summary line (where the files went):
    shadelab figures lessons/0*.toml -o out/ -q

The lessons' notes are printed by `shadelab render`, not here.")]
pub struct FiguresArgs {
    /// Lesson files or folders of lessons.
    #[arg(required = true, value_name = "PATH")]
    pub paths: Vec<PathBuf>,
    /// Output folder; each figure goes to DIR/<lesson>/<figure>.png.
    #[arg(short, long, value_name = "DIR", default_value = "out")]
    pub output: PathBuf,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// How figures are drawn.
    #[command(flatten)]
    pub look: FigureFlags,
    /// Make only part K of N of the figures (e.g. 2/3): a stable split by lesson and figure
    /// name, so N jobs together make every figure once.
    #[arg(long, value_name = "K/N", value_parser = super::shard::parse_shard)]
    pub shard: Option<super::shard::Shard>,
    /// Time the cost figures (and `--timings` figures) again instead of reading them from the
    /// cache, which keeps their times for the machine and thread count that measured them.
    #[arg(long)]
    pub retime: bool,
    #[command(flatten)]
    pub report: super::diagnostics::ReportFlags,
}

/// Arguments of `shadelab compare`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Flat, Gouraud and Phong interpolation side by side (written to 05-gouraud-vs-phong-compare.png):
    shadelab compare lessons/05-gouraud-vs-phong.toml --vary render.interpolation=flat,gouraud,phong
  Your own column labels and a caption:
    shadelab compare lessons/03-phong-vs-blinn.toml --vary material.glossy.model=phong,blinn_phong --labels Phong,Blinn-Phong --caption 'Same K_shi' -o out/cmp.png")]
pub struct CompareArgs {
    /// KEY=V1,V2,... : one column per value, e.g. render.interpolation=flat,gouraud,phong.
    #[arg(long, value_name = "KEY=VALUES")]
    pub vary: String,
    /// Output PNG, or a folder (an existing one, or a name ending in /) to write
    /// LESSON-compare.png in [default: LESSON-compare.png in the current folder].
    #[arg(short, long, value_name = "FILE|DIR")]
    pub output: Option<PathBuf>,
    /// The lesson, output and look.
    #[command(flatten)]
    pub common: VaryArgs,
}

/// Arguments of `shadelab sweep`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Eight shininess values, spaced evenly in log (written to 04-shininess-sweep.png):
    shadelab sweep lessons/04-shininess.toml --vary material.plastic.shininess=1..256:log:8
  A grid: K_spec down the rows, K_shi across (written to out/grid.png):
    shadelab sweep lessons/04-shininess.toml --vary material.plastic.specular=0.2,0.5,0.9 --vary material.plastic.shininess=4,16,64 -o out/grid.png")]
pub struct SweepArgs {
    /// KEY=V1,V2,... or KEY=A..B:log:N (e.g. material.plastic.shininess=1..256:log:8); give it
    /// twice for a rows × columns grid: the first down the rows, the second across.
    #[arg(long, value_name = "KEY=VALUES", required = true, num_args = 1)]
    pub vary: Vec<String>,
    /// Output PNG, or a folder (an existing one, or a name ending in /) to write the default
    /// name in [default: LESSON-sweep.png, or LESSON-grid.png for two --vary, in the current
    /// folder].
    #[arg(short, long, value_name = "FILE|DIR")]
    pub output: Option<PathBuf>,
    /// The lesson, output and look.
    #[command(flatten)]
    pub common: VaryArgs,
}

/// Arguments shared by `shadelab compare` and `shadelab sweep` (each has its own `-o`, to
/// name its own default file).
#[derive(Debug, clap::Args)]
pub struct VaryArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// Caption under the figure.
    #[arg(long)]
    pub caption: Option<String>,
    /// Column labels, comma-separated, one per value of the last --vary (instead of the
    /// generated `K_shi = 50`-style labels).
    #[arg(long, value_name = "L1,L2,...", value_delimiter = ',')]
    pub labels: Option<Vec<String>>,
    /// How the figure is drawn.
    #[command(flatten)]
    pub look: FigureFlags,
}

/// Arguments of `shadelab split`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Ambient | diffuse | specular | total of one render (written to 01-first-light-split.png):
    shadelab split lessons/01-first-light.toml
  Only the diffuse and specular terms, on a dark theme:
    shadelab split lessons/07-lights.toml --layers diffuse,specular --theme dark -o out/split.png")]
pub struct SplitArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    /// Output PNG, or a folder (an existing one, or a name ending in /) to write
    /// LESSON-split.png in [default: LESSON-split.png in the current folder].
    #[arg(short, long, value_name = "FILE|DIR")]
    pub output: Option<PathBuf>,
    /// Layers, in order.
    #[arg(long, value_delimiter = ',', default_value = "ambient,diffuse,specular,total")]
    pub layers: Vec<String>,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// How the figure is drawn.
    #[command(flatten)]
    pub look: FigureFlags,
}

/// The lesson files named by `paths`: files as given, folders as their `*.toml`, sorted.
pub fn lesson_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, CliError> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(p)
                .map_err(|e| CliError::Input(format!("{}: cannot read the folder: {e}", p.display())))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.extension().is_some_and(|x| x == "toml"))
                .collect();
            found.sort();
            out.extend(found);
        } else {
            out.push(p.clone());
        }
    }
    Ok(out)
}

/// The file name without its extension: the folder of a lesson's figures.
pub(super) fn stem(p: &Path) -> String {
    p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "lesson".into())
}

/// A figure is a PNG: `-o x.jpg` would put PNG bytes under a name that says otherwise, and
/// a name without an extension would not say what it is (docs/cli.md, the `-o` rule).
fn check_png_name(out: &Path) -> Result<(), CliError> {
    match out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()) {
        Some(e) if e != "png" => Err(CliError::Input(format!(
            "-o {}: figures are PNG images, not .{e}\n  hint: name the file {}",
            out.display(),
            out.with_extension("png").display()
        ))),
        None => Err(CliError::Input(format!(
            "-o {}: the name has no extension; figures are PNG images\n  hint: name the file {}",
            out.display(),
            out.with_extension("png").display()
        ))),
        Some(_) => Ok(crate::output::check_destination(out)?),
    }
}

/// Renders one figure and writes it; its line goes through `progress` when a bar runs.
/// Returns the time it took.
fn write(
    lesson: &Lesson,
    spec: &FigureSpec,
    opts: &FigureOptions,
    out: &Path,
    quiet: bool,
    progress: Option<&Progress>,
) -> Result<std::time::Duration, CliError> {
    let start = std::time::Instant::now();
    let fig = figure::render_figure(lesson, spec, opts)?;
    crate::output::write_png_rgba_tagged(
        out,
        &fig.image,
        &super::provenance::tags(lesson, super::provenance::Made::Figure(&spec.name, opts)),
    )?;
    if !fig.missing_glyphs.is_empty() {
        let message = format!("{}: the label font has no glyph for {:?}; drawn as boxes", out.display(), fig.missing_glyphs);
        super::diagnostics::warn(
            super::diagnostics::Diagnostic::warning("figure", message.clone(), Some(lesson.path.clone()), None),
            format_args!("warning: {message}"),
        );
    }
    if !quiet {
        let print = |line: std::fmt::Arguments<'_>| match progress {
            Some(p) => p.println(line),
            None => super::out::print(format_args!("{line}\n")),
        };
        let how = if fig.kept {
            let times = if figure::shows_times(spec, opts) { ", its times from an earlier run on this machine" } else { "" };
            format!("from the cache{times}")
        } else {
            let cached = if fig.cached > 0 { format!(", {} from the cache", fig.cached) } else { String::new() };
            format!("{} rasterization{}{cached}", fig.rasterizations, if fig.rasterizations == 1 { "" } else { "s" })
        };
        print(format_args!(
            "wrote {} ({}×{}, {how}, {:.0} ms)",
            crate::output::shown_path(out),
            fig.image.width(),
            fig.image.height(),
            start.elapsed().as_secs_f64() * 1e3
        ))?;
    }
    Ok(start.elapsed())
}

/// Writes every figure of one checked lesson to `output/<stem>/<figure>.png` (one lesson's
/// work of `shadelab figures`, shared with `shadelab watch`); returns each figure's
/// `lesson/figure` name and time.
pub(super) fn write_lesson_figures(
    path: &Path,
    lesson: &Lesson,
    opts: &FigureOptions,
    output: &Path,
    quiet: bool,
    progress: Option<&Progress>,
) -> Result<Vec<(String, std::time::Duration)>, CliError> {
    let mut times = Vec::with_capacity(lesson.figures.len());
    for spec in &lesson.figures {
        let name = format!("{}/{}", stem(path), spec.name);
        if let Some(p) = progress {
            p.message(name.clone());
        }
        let out = output.join(stem(path)).join(format!("{}.png", spec.name));
        times.push((name, write(lesson, spec, opts, &out, quiet, progress)?));
        if let Some(p) = progress {
            p.inc();
        }
    }
    Ok(times)
}

/// The line naming the slowest of `times` (at most three), e.g. `slowest: 26-fog/steps 25.5 s,
/// ...`: where an instructor's wait goes.
fn slowest(times: &mut [(String, std::time::Duration)]) -> String {
    times.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    let shown: Vec<String> = times.iter().take(3).map(|(n, d)| format!("{n} {:.1} s", d.as_secs_f64())).collect();
    format!("slowest: {}", shown.join(", "))
}

/// `shadelab figures`: every `[[figure]]` of every lesson.
pub fn run_figures(args: FiguresArgs, quiet: bool) -> Result<(), CliError> {
    // Under --format jsonl stdout holds only diagnostics: the per-figure lines go.
    let quiet = quiet || args.report.configure().jsonl;
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let opts = args.look.options()?;
    figure::kept::retime(args.retime);
    // `-o` of a folder command is a folder: an existing file there is refused before any work.
    crate::output::check_folder(&args.output, &args.output)?;
    // Validate every figure of every lesson first: bad input writes no file at all. Every
    // invalid lesson is reported, not only the first.
    let files = lesson_files(&args.paths)?;
    let mut lessons = Vec::new();
    let mut errors = Vec::new();
    for path in &files {
        let checked = || -> Result<Lesson, CliError> {
            let lesson = lesson::load(path, &sets)?;
            for spec in &lesson.figures {
                figure::check_figure(&lesson, spec, &opts)?;
            }
            Ok(lesson)
        };
        match checked() {
            Ok(lesson) => lessons.push((path.clone(), lesson)),
            Err(e) => errors.push(e),
        }
    }
    if let Some(e) = super::diagnostics::each(errors, files.len()) {
        return Err(e);
    }
    if let Some(shard) = args.shard {
        shard.keep(&mut lessons);
    }
    // The lessons' notes belong to `render`; here one line per figure, then the summary.
    let total: usize = lessons.iter().map(|(_, l)| l.figures.len()).sum();
    let progress = Progress::new(total as u64, quiet);
    let mut times = Vec::with_capacity(total);
    // Without a terminal there is no bar: a line per lesson on stderr says the run moves on.
    let lesson_lines = !quiet && !std::io::stderr().is_terminal();
    for (path, lesson) in lessons {
        let start = std::time::Instant::now();
        times.extend(write_lesson_figures(&path, &lesson, &opts, &args.output, quiet, Some(&progress))?);
        if lesson_lines && !lesson.figures.is_empty() {
            let n = lesson.figures.len();
            super::out::eprint_line(format_args!(
                "{}: {n} figure{} in {:.1} s",
                crate::output::shown_text(&stem(&path)),
                if n == 1 { "" } else { "s" },
                start.elapsed().as_secs_f64()
            ));
        }
        if lesson.figures.is_empty() && !quiet {
            progress.println(format_args!("{}: no [[figure]] tables", path.display()))?;
        }
    }
    let elapsed = progress.finish();
    if total == 0 {
        let line = format!("no figures found in {}", args.paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "));
        return super::out::result_line(&line);
    }
    if total > 1 && !quiet {
        outln!("{}", slowest(&mut times))?;
    }
    if let Some(line) = cache_line().filter(|_| !quiet) {
        outln!("{line}")?;
    }
    super::out::result_line(&summary(total, "figure", "figures", elapsed, Some(&args.output)))
}

/// What the on-disk cache did in this run, e.g. `cache (~/.cache/shadelab): 41 entries read
/// (38 whole figures), 12 computed`; `None` when it is off or was not asked.
pub(super) fn cache_line() -> Option<String> {
    let dir = crate::cache::dir()?;
    let c = crate::cache::counts();
    if c.hits + c.misses + c.dropped == 0 {
        return None;
    }
    let dropped = if c.dropped > 0 { format!(", {} of them replacing unusable entries", c.dropped) } else { String::new() };
    let entries = if c.hits == 1 { "entry" } else { "entries" };
    let whole = match figure::kept::read() {
        0 => String::new(),
        1 => " (1 whole figure)".into(),
        n => format!(" ({n} whole figures)"),
    };
    Some(format!("cache ({}): {} {entries} read{whole}, {} computed{dropped}", dir.display(), c.hits, c.misses + c.dropped))
}

/// Splits `KEY=V1,V2,...` at top-level commas (not inside brackets or quotes).
fn parse_vary(arg: &str) -> Result<Axis, CliError> {
    let bad = |m: String| CliError::Input(format!("--vary {arg}: {m}"));
    let (key, list) = lesson::path::split_assignment(arg)
        .ok_or_else(|| bad("expected KEY=V1,V2,... (e.g. material.plastic.shininess=1,10,100)".into()))?;
    let key = KeyPath::parse(key.trim()).ok_or_else(|| bad(format!("`{key}` is not a dotted key path")))?;
    let list = list.trim();
    let values: Vec<toml::Value> = if list.contains("..") && !list.contains(',') && !list.starts_with('[') {
        lesson::figure::parse_range(list).map_err(bad)?.into_iter().map(toml::Value::Float).collect()
    } else {
        let mut parts = Vec::new();
        let (mut depth, mut quoted, mut start) = (0i32, false, 0usize);
        for (i, c) in list.char_indices() {
            match c {
                '"' => quoted = !quoted,
                '[' | '{' if !quoted => depth += 1,
                ']' | '}' if !quoted => depth -= 1,
                ',' if !quoted && depth == 0 => {
                    parts.push(&list[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        parts.push(&list[start..]);
        parts.iter().map(|p| lesson::overrides::parse_value(p).map_err(bad)).collect::<Result<_, _>>()?
    };
    if values.is_empty() || values.len() > lesson::figure::MAX_CELLS {
        return Err(bad(format!("give 1 to {} values", lesson::figure::MAX_CELLS)));
    }
    Ok(Axis { key, values, labels: None, origin: KeyPath::default() })
}

fn default_output(lesson: &Path, what: &str) -> PathBuf {
    PathBuf::from(format!("{}-{what}.png", stem(lesson)))
}

/// True when `-o` names a folder: an existing one, or a name ending in a separator (as
/// `render -o DIR/`; docs/cli.md, the `-o` rule).
fn is_folder(out: &Path) -> bool {
    out.is_dir() || out.as_os_str().to_string_lossy().ends_with(['/', '\\'])
}

/// Where a one-figure command writes: `-o FILE`, `-o DIR/` + the default name, or the default
/// name in the current folder.
fn figure_output(output: Option<PathBuf>, lesson: &Path, what: &str) -> Result<PathBuf, CliError> {
    let out = match output {
        Some(o) if is_folder(&o) => o.join(default_output(lesson, what)),
        Some(o) => o,
        None => default_output(lesson, what),
    };
    check_png_name(&out)?;
    Ok(out)
}

/// The cell of an ad-hoc `compare` or `sweep` without `--cell` or `--fit`: the camera's
/// aspect with its longer side at most [`ADHOC_CELL`] pixels, so eight columns make a figure
/// a slide shows whole (at the camera's 512 px the README's sweep was 4228 px wide).
fn adhoc_cell(lesson: &Lesson) -> (u32, u32) {
    let (w, h) = (lesson.scene.camera.width.max(1), lesson.scene.camera.height.max(1));
    let scale = (ADHOC_CELL as f32 / w.max(h) as f32).min(1.0);
    (((w as f32 * scale).round() as u32).max(8), ((h as f32 * scale).round() as u32).max(8))
}

/// The longer side of an ad-hoc figure's cell by default, in pixels.
const ADHOC_CELL: u32 = 256;

/// `shadelab compare`: one row, one key varied.
pub fn run_compare(args: CompareArgs, quiet: bool) -> Result<(), CliError> {
    run_vary(&[args.vary], args.output, args.common, FigureKind::Compare, quiet)
}

/// `shadelab sweep`: one key varied (a row), or two (a grid).
pub fn run_sweep(args: SweepArgs, quiet: bool) -> Result<(), CliError> {
    run_vary(&args.vary, args.output, args.common, FigureKind::Sweep, quiet)
}

/// A figure from `--vary` flags.
fn run_vary(vary: &[String], output: Option<PathBuf>, args: VaryArgs, kind: FigureKind, quiet: bool) -> Result<(), CliError> {
    if let Some(o) = output.as_ref().filter(|o| !is_folder(o)) {
        check_png_name(o)?;
    }
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let lesson = lesson::load(&args.lesson, &sets)?;
    let axes = vary.iter().map(|v| parse_vary(v)).collect::<Result<Vec<_>, _>>()?;
    let n = axes.len();
    let mut axes = axes.into_iter();
    let (rows, mut cols) = match (axes.next(), axes.next(), axes.next()) {
        (Some(cols), None, None) => (None, cols),
        (Some(rows), Some(cols), None) if kind == FigureKind::Sweep => (Some(rows), cols),
        _ => {
            let hint = if kind == FigureKind::Sweep {
                "a grid varies two keys; for more, add [[figure]] tables to the lesson"
            } else {
                "for a rows × columns grid use `shadelab sweep` with two --vary"
            };
            return Err(CliError::Input(format!(
                "{} takes {} --vary, got {n}\n  hint: {hint}",
                kind.name(),
                if kind == FigureKind::Sweep { "one or two" } else { "one" }
            )));
        }
    };
    if let Some(labels) = &args.labels {
        if labels.len() != cols.values.len() {
            return Err(CliError::Input(format!(
                "--labels: {} label{} for {} values of --vary {}\n  hint: give one label per value, comma-separated",
                labels.len(),
                if labels.len() == 1 { "" } else { "s" },
                cols.values.len(),
                cols.key
            )));
        }
        cols.labels = Some(labels.iter().map(|l| l.trim().to_string()).collect());
    }
    // Two axes make a grid (named so, and its default file too).
    let body = match rows {
        Some(rows) => FigureBody::grid(rows, cols),
        None if kind == FigureKind::Sweep => FigureBody::sweep(cols),
        None => FigureBody::compare(cols),
    };
    let kind = body.kind();
    let spec = FigureSpec { caption: args.caption.clone(), ..FigureSpec::new(kind.name(), body) };
    let out = figure_output(output, &args.lesson, kind.name())?;
    let mut opts = args.look.options()?;
    if opts.cell.is_none() && opts.fit.is_none() {
        opts.cell = Some(adhoc_cell(&lesson));
    }
    write(&lesson, &spec, &opts, &out, quiet, None).map(|_| ())
}

/// `shadelab split`: one render read out per layer.
pub fn run_split(args: SplitArgs, quiet: bool) -> Result<(), CliError> {
    let out = figure_output(args.output.clone(), &args.lesson, "split")?;
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let lesson = lesson::load(&args.lesson, &sets)?;
    let layers = args
        .layers
        .iter()
        .map(|n| {
            crate::render::Layer::ALL.into_iter().find(|l| l.name() == n.trim()).ok_or_else(|| {
                CliError::Input(format!("--layers: unknown layer `{n}` (ambient, diffuse, specular, emission, total, normal)"))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let spec = FigureSpec::new("split", FigureBody::split(layers));
    write(&lesson, &spec, &args.look.options()?, &out, quiet, None).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slowest_line_names_the_three_longest_figures_longest_first() {
        let ms = |n: &str, t: u64| (n.to_string(), std::time::Duration::from_millis(t));
        let mut times = vec![ms("01/a", 20), ms("26-fog/steps", 25_500), ms("02/b", 900), ms("30/ibl-cost", 34_000)];
        assert_eq!(slowest(&mut times), "slowest: 30/ibl-cost 34.0 s, 26-fog/steps 25.5 s, 02/b 0.9 s");
    }
}
