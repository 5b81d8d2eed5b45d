//! `shadelab snapshot`: render every figure and compare it with a blessed PNG.

use super::junit::{Case, Outcome};
use super::progress::{Progress, summary};
use super::report::{Entry, Status};
use super::{CliError, FigureFlags, ThemeArg};
use crate::figure::snapshot::{Tolerance, compare, diff_image};
use std::path::{Path, PathBuf};

/// The file in the snapshot folder that records how the images were drawn.
pub const LOOK_FILE: &str = "snapshot.toml";

/// Arguments of `shadelab snapshot`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Bless one lesson's figures into snapshots/, then check them:
    shadelab snapshot lessons/01-first-light.toml -o snapshots/ --bless
    shadelab snapshot lessons/01-first-light.toml -o snapshots/
  Only the failures and the summary line:
    shadelab snapshot lessons/01-first-light.toml -o snapshots/ -q
  The project's own suite (from the source folder): shadelab snapshot lessons/ -o tests/snapshots")]
pub struct SnapshotArgs {
    /// Lesson files or folders of lessons.
    #[arg(required = true, value_name = "PATH")]
    pub paths: Vec<PathBuf>,
    /// Folder of blessed snapshots: DIR/<lesson>/<figure>.png (`--dir` is the same flag).
    #[arg(short = 'o', long = "output", visible_alias = "dir", value_name = "DIR")]
    pub dir: PathBuf,
    /// Write (or overwrite) the snapshots instead of comparing. Every lesson and figure is
    /// validated first: if one is bad, nothing is written.
    #[arg(long)]
    pub bless: bool,
    /// Largest per-channel difference (0–255) that does not count as a difference. The
    /// default lets a 2% change of a colour coefficient pass (docs/cli.md, "Snapshots").
    #[arg(long, value_name = "CODES", default_value_t = 2)]
    pub tolerance: u8,
    /// Largest share of differing pixels, in percent, that still matches.
    #[arg(long, value_name = "PERCENT", default_value_t = 0.1)]
    pub max_diff: f64,
    /// Every pixel the same (as --tolerance 0 --max-diff 0), and snapshots with no figure
    /// behind them fail too.
    #[arg(long, conflicts_with_all = ["tolerance", "max_diff"])]
    pub strict: bool,
    /// Also write the run as JUnit XML to FILE (a test per figure, a lesson that does not
    /// validate as an error), for a CI's test report.
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
    /// Check only part K of N of the figures (e.g. 2/3): a stable split by lesson and
    /// figure name, so N jobs together check every figure once.
    #[arg(long, value_name = "K/N", value_parser = super::shard::parse_shard)]
    pub shard: Option<super::shard::Shard>,
    /// Also write a review page to DIR/index.html: failures first, each as blessed |
    /// actual | difference with its numbers, the passes folded (no script; a CI artifact).
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
    /// With --bless: bless only this figure, LESSON/FIGURE as the report names it
    /// (repeatable); the others are checked as without --bless.
    #[arg(long, value_name = "LESSON/FIGURE", requires = "bless")]
    pub only: Vec<String>,
    #[command(flatten)]
    pub set: super::SetArgs,
    #[command(flatten)]
    pub report_flags: super::diagnostics::ReportFlags,
    /// How figures are drawn. `--bless` records the flags in DIR/snapshot.toml; a later check
    /// or bless without them uses the recorded ones.
    #[command(flatten)]
    pub look: SnapshotLook,
}

/// `shadelab snapshot`'s drawing flags: as the figure commands', but each may be left out
/// (then the recorded one applies), and no timings (they would change every run).
#[derive(Debug, Clone, clap::Args)]
pub struct SnapshotLook {
    /// Colour theme [default: recorded, else light].
    #[arg(long, value_enum)]
    pub theme: Option<ThemeArg>,
    /// Scale of text and spacing [default: recorded, else 1].
    #[arg(long, value_name = "FACTOR")]
    pub scale: Option<f32>,
    /// Size of each cell in pixels, e.g. 96x96 [default: recorded, else the figure's own].
    #[arg(long, value_name = "WxH", value_parser = super::parse_size)]
    pub cell: Option<(u32, u32)>,
}

/// What DIR/snapshot.toml holds.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Recorded {
    theme: String,
    scale: f32,
    cell: Option<[u32; 2]>,
}

fn theme_name(t: ThemeArg) -> &'static str {
    match t {
        ThemeArg::Light => "light",
        ThemeArg::Dark => "dark",
        ThemeArg::Transparent => "transparent",
    }
}

/// Reads DIR/snapshot.toml, if there is one.
fn read_recorded(dir: &Path) -> Result<Option<Recorded>, CliError> {
    let path = dir.join(LOOK_FILE);
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(CliError::Input(format!("{}: cannot read: {e}", path.display()))),
    };
    toml::from_str(&text).map(Some).map_err(|e| {
        CliError::Input(format!("{}: not a snapshot record ({e})\n  hint: re-bless with `shadelab snapshot ... --bless`", path.display()))
    })
}

impl SnapshotLook {
    /// The flags in effect: given, else recorded, else the figure commands' defaults (when
    /// blessing too, so a re-bless keeps the folder's flags); when checking, a note on stderr
    /// if they differ from the recorded ones.
    fn resolve(&self, recorded: Option<&Recorded>, bless: bool) -> Result<(FigureFlags, Recorded), CliError> {
        let theme_of = |name: &str| match name {
            "dark" => Ok(ThemeArg::Dark),
            "transparent" => Ok(ThemeArg::Transparent),
            "light" => Ok(ThemeArg::Light),
            other => Err(CliError::Input(format!("{LOOK_FILE}: unknown theme `{other}` (light, dark or transparent)"))),
        };
        let rec = recorded;
        let theme = match (self.theme, rec) {
            (Some(t), _) => t,
            (None, Some(r)) => theme_of(&r.theme)?,
            (None, None) => ThemeArg::Light,
        };
        let scale = self.scale.or(rec.map(|r| r.scale)).unwrap_or(1.0);
        let cell = self.cell.or(rec.and_then(|r| r.cell.map(|[w, h]| (w, h))));
        let now = Recorded { theme: theme_name(theme).into(), scale, cell: cell.map(|(w, h)| [w, h]) };
        if let Some(r) = recorded.filter(|_| !bless)
            && *r != now
        {
            let show = |r: &Recorded| {
                let cell = r.cell.map_or("the figures' own".to_string(), |[w, h]| format!("{w}x{h}"));
                format!("--theme {} --scale {} --cell {cell}", r.theme, r.scale)
            };
            super::out::eprint_line(format_args!("note: the snapshots were blessed with {}; checking with {}", show(r), show(&now)));
        }
        Ok((FigureFlags { theme, scale, cell, timings: false, fit: None }, now))
    }
}

/// Compares (or blesses) every figure; exit 1 on any mismatch.
pub fn run(args: SnapshotArgs, quiet: bool) -> Result<(), CliError> {
    let sink = args.report_flags.configure();
    // Under --format jsonl stdout holds only diagnostics: the per-figure lines go.
    let quiet = quiet || sink.jsonl;
    let diagnosed = sink.jsonl || sink.annotations != super::diagnostics::Annotations::None;
    if !(0.0..=100.0).contains(&args.max_diff) {
        return Err(CliError::Input(format!("--max-diff {}: give a percentage from 0 to 100", args.max_diff)));
    }
    let tol = if args.strict {
        Tolerance { per_pixel: 0, max_share: 0.0 }
    } else {
        Tolerance { per_pixel: args.tolerance, max_share: args.max_diff / 100.0 }
    };
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    crate::output::check_folder(&args.dir, &args.dir)?;
    let recorded = read_recorded(&args.dir)?;
    let (look, record) = args.look.resolve(recorded.as_ref(), args.bless)?;
    // Cost figures are drawn untimed: a snapshot must not depend on how fast the machine is.
    let opts = crate::figure::FigureOptions { measure_time: false, ..look.options()? };
    // Validate every lesson and figure (and load the meshes) first: one bad lesson must not
    // leave half the snapshots blessed.
    // With --junit, a lesson that does not validate is reported there (and on stderr) and
    // the others are still checked; the run then exits 2.
    if let Some(file) = &args.junit {
        crate::output::check_destination(file)?;
    }
    let mut cases: Vec<Case> = Vec::new();
    let mut invalid = 0;
    let mut lessons = Vec::new();
    for path in super::figures::lesson_files(&args.paths)? {
        let checked = || -> Result<crate::lesson::Lesson, CliError> {
            let lesson = crate::lesson::load(&path, &sets)?;
            for spec in &lesson.figures {
                crate::figure::check_figure(&lesson, spec, &opts)?;
            }
            crate::scene::build::build(&lesson)?;
            Ok(lesson)
        };
        match checked() {
            Ok(lesson) => lessons.push((path, lesson)),
            Err(e) if args.junit.is_some() || diagnosed => {
                super::diagnostics::emit(&super::diagnostics::of_error(&e))?;
                if !sink.jsonl {
                    super::out::eprint_line(format_args!("error: {e}"));
                }
                let message = e.to_string().lines().next().unwrap_or_default().to_string();
                let (class, name) = (super::figures::stem(&path), "(lesson)".to_string());
                cases.push(Case { class, name, seconds: 0.0, outcome: Outcome::Error { message, details: e.to_string() } });
                invalid += 1;
            }
            Err(e) => return Err(e),
        }
    }
    // --only names figures of the lessons given.
    let ids: Vec<String> =
        lessons.iter().flat_map(|(p, l)| l.figures.iter().map(move |f| format!("{}/{}", super::figures::stem(p), f.name))).collect();
    if let Some(unknown) = args.only.iter().find(|o| !ids.contains(o)) {
        return Err(CliError::Input(format!(
            "--only {unknown}: no such figure among the lessons given\n  hint: name it LESSON/FIGURE as the report or a FAILED line does, e.g. {}",
            ids.first().map_or("04-shininess/sweep", String::as_str)
        )));
    }
    let mut entries: Vec<Entry> = cases
        .iter()
        .map(|c| Entry {
            id: format!("{}/{}", c.class, c.name),
            status: Status::Error,
            message: error_message(&c.outcome),
            images: [None, None, None],
        })
        .collect();
    // Orphans are judged against every figure, this part's or not.
    let orphans = orphans(&args.dir, &lessons, args.paths.iter().any(|p| p.is_dir()));
    if let Some(shard) = args.shard {
        shard.keep(&mut lessons);
    }
    let (mut passed, mut failed, mut blessed) = (0, 0, 0);
    let total: usize = lessons.iter().map(|(_, l)| l.figures.len()).sum();
    let bar = Progress::new(total as u64, quiet);
    for (path, lesson) in lessons {
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        for (index, spec) in lesson.figures.iter().enumerate() {
            let id = format!("{stem}/{}", spec.name);
            bar.message(id.clone());
            let file = args.dir.join(&stem).join(format!("{}.png", spec.name));
            let started = std::time::Instant::now();
            let mut case = |status: Status, outcome: Outcome, images: [Option<PathBuf>; 3]| {
                let seconds = started.elapsed().as_secs_f64();
                let message = match &outcome {
                    Outcome::Passed => format!("{seconds:.2} s"),
                    Outcome::Failed { message, .. } | Outcome::Error { message, .. } => message.clone(),
                };
                entries.push(Entry { id: id.clone(), status, message, images });
                cases.push(Case { class: stem.clone(), name: spec.name.clone(), seconds, outcome });
            };
            let actual = crate::figure::render_figure(&lesson, spec, &opts)?.image;
            bar.inc();
            if args.bless && (args.only.is_empty() || args.only.contains(&id)) {
                crate::output::write_png_rgba_tagged(&file, &actual, &made(&lesson, spec, &opts))?;
                remove_stale(&file);
                if !quiet {
                    bar.println(format_args!("blessed {id}"))?;
                }
                blessed += 1;
                case(Status::Blessed, Outcome::Passed, [Some(file.clone()), None, None]);
                continue;
            }
            let expected = match image::open(&file) {
                Ok(img) => img.to_rgba8(),
                Err(e) => {
                    let why = if file.exists() {
                        format!("cannot read {} ({e})", file.display())
                    } else {
                        format!("no snapshot at {}", file.display())
                    };
                    let hint = format!("bless it with `shadelab snapshot {} -o {} --bless`", path.display(), args.dir.display());
                    mismatch(&lesson, index, &why, &hint)?;
                    if !sink.jsonl {
                        bar.println(format_args!("FAILED  {id}: {why}\n  hint: {hint}"))?;
                    }
                    let actual_file = file.with_extension("actual.png");
                    crate::output::write_png_rgba_tagged(&actual_file, &actual, &made(&lesson, spec, &opts))?;
                    case(Status::Failed, Outcome::Failed { message: why, details: hint }, [None, Some(actual_file), None]);
                    failed += 1;
                    continue;
                }
            };
            let c = compare(&expected, &actual, &tol);
            if c.matches(&tol) {
                remove_stale(&file);
                if !quiet {
                    bar.println(format_args!("ok      {id} ({} of {} pixels differ, max Δ {})", c.differing, c.total, c.max_delta))?;
                }
                case(Status::Passed, Outcome::Passed, [None, None, None]);
                passed += 1;
            } else {
                let diff = file.with_extension("diff.png");
                let new = file.with_extension("actual.png");
                crate::output::write_png_rgba(&diff, &diff_image(&expected, &actual, &tol))?;
                crate::output::write_png_rgba_tagged(&new, &actual, &made(&lesson, spec, &opts))?;
                let message = match c.size_mismatch {
                    Some((e, a)) => format!("size {}×{} expected, got {}×{}", e.0, e.1, a.0, a.1),
                    None => format!(
                        "{:.3}% of pixels differ by more than {} (allowed {:.3}%), max Δ {}",
                        c.share() * 100.0,
                        tol.per_pixel,
                        tol.max_share * 100.0,
                        c.max_delta
                    ),
                };
                let details = match c.size_mismatch {
                    Some(_) => format!("actual: {}", new.display()),
                    None => format!("diff: {}\nactual: {}\nblessed: {}", diff.display(), new.display(), file.display()),
                };
                let details = format!("{details}\nreproduce: shadelab reproduce {}", new.display());
                let shown =
                    if c.size_mismatch.is_some() { format!("actual: {}", new.display()) } else { format!("diff: {}", diff.display()) };
                mismatch(
                    &lesson,
                    index,
                    &format!("figure `{}` differs from its snapshot: {message}", spec.name),
                    &format!("see {shown}; `shadelab reproduce {}` says what changed; bless it if it is right", new.display()),
                )?;
                if !sink.jsonl {
                    bar.println(format_args!("FAILED  {id}: {message}; {shown}"))?;
                    bar.println(format_args!("  reproduce: shadelab reproduce {}", new.display()))?;
                }
                let images = [Some(file.clone()), Some(new.clone()), c.size_mismatch.is_none().then(|| diff.clone())];
                case(Status::Failed, Outcome::Failed { message, details }, images);
                failed += 1;
            }
        }
    }
    let elapsed = bar.finish();
    for o in &orphans {
        let what = match &o.figure {
            Some(name) => format!("{}/{name}: the lesson has no figure `{name}`", o.stem),
            None => format!("{}: no lesson `{}.toml` among those checked", o.stem, o.stem),
        };
        let fix = match (&o.figure, args.bless) {
            (Some(_), true) => {
                let _ = std::fs::remove_file(&o.path);
                remove_stale(&o.path);
                "removed".to_string()
            }
            (Some(_), false) => format!("delete {} if the figure is gone for good (or --bless the lesson)", o.path.display()),
            (None, _) => format!("delete {} if the lesson is gone for good", o.path.display()),
        };
        super::diagnostics::warn(
            super::diagnostics::Diagnostic::warning("snapshot", format!("orphan {what}; {fix}"), Some(o.path.clone()), None),
            format_args!("orphan  {what}; {fix}"),
        );
    }
    let orphan_failures = if args.strict && !args.bless { orphans.len() } else { 0 };
    if let Some(file) = &args.junit {
        let text = super::junit::document("shadelab snapshot", &cases, &super::junit::now());
        crate::output::write_atomic(file, |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
    }
    if let Some(dir) = &args.report {
        super::report::write(dir, &entries, tol.per_pixel, tol.max_share)?;
    }
    if args.bless {
        let text = format!(
            "# Written by `shadelab snapshot --bless`: how the images here were drawn.\n# `shadelab snapshot` without these flags uses them.\n{}",
            toml::to_string(&record).map_err(|e| CliError::Internal(format!("cannot record the flags: {e}")))?
        );
        crate::output::write_atomic(&args.dir.join(LOOK_FILE), |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
        if args.only.is_empty() {
            let line = summary(blessed, "snapshot blessed", "snapshots blessed", elapsed, Some(&args.dir));
            super::out::result_line(&format!("{line} (flags recorded in {LOOK_FILE})"))?;
            return if invalid > 0 { Err(not_valid(invalid, &args.junit)) } else { Ok(()) };
        }
    }
    let orphaned = if orphans.is_empty() { String::new() } else { format!(", {} orphaned", orphans.len()) };
    // With --only, the figures blessed beside those checked.
    let blessed_too = if blessed > 0 { format!(", {blessed} blessed") } else { String::new() };
    let total = passed + failed + blessed;
    super::out::result_line(&format!(
        "{}: {passed} passed, {failed} failed{blessed_too}{orphaned}",
        summary(total, "snapshot", "snapshots", elapsed, Some(&args.dir))
    ))?;
    if invalid > 0 {
        return Err(not_valid(invalid, &args.junit));
    }
    if failed > 0 {
        return Err(CliError::Mismatch(format!("{failed} snapshot{} did not match", if failed == 1 { "" } else { "s" })));
    }
    if orphan_failures > 0 {
        let s = if orphan_failures == 1 { "" } else { "s" };
        return Err(CliError::Mismatch(format!(
            "{orphan_failures} snapshot{s} with no figure behind {} (--strict)",
            if orphan_failures == 1 { "it" } else { "them" }
        )));
    }
    Ok(())
}

/// Reports figure `index` of `lesson` failing its snapshot as a diagnostic at the figure's
/// `name` in the lesson (where a CI annotation shows it).
fn mismatch(lesson: &crate::lesson::Lesson, index: usize, message: &str, hint: &str) -> Result<(), CliError> {
    use crate::lesson::spans;
    let key = crate::lesson::KeyPath::parse(&format!("figure.{index}.name")).expect("a valid path");
    let at =
        (!lesson.source.is_empty()).then(|| spans::line_col(&lesson.source, spans::find(&lesson.source, &key, spans::Target::Value).start));
    super::diagnostics::emit(&[super::diagnostics::Diagnostic {
        level: "error",
        code: "snapshot",
        message: message.to_string(),
        file: Some(lesson.path.clone()),
        at,
        flag: None,
        hint: Some(hint.to_string()),
        key: Some(format!("figure.{index}.name")),
    }])
}

/// The provenance chunks of a snapshot image of figure `spec` of `lesson`.
fn made(
    lesson: &crate::lesson::Lesson,
    spec: &crate::lesson::FigureSpec,
    opts: &crate::figure::FigureOptions,
) -> Vec<(&'static str, String)> {
    super::provenance::tags(lesson, super::provenance::Made::Figure(&spec.name, opts))
}

/// The report's message for a case recorded before any figure was made (a lesson error).
fn error_message(o: &Outcome) -> String {
    match o {
        Outcome::Failed { message, .. } | Outcome::Error { message, .. } => message.clone(),
        Outcome::Passed => String::new(),
    }
}

/// The end of a run in which `invalid` lessons did not validate (reported in `junit`).
fn not_valid(invalid: usize, junit: &Option<PathBuf>) -> CliError {
    let s = if invalid == 1 { "" } else { "s" };
    let place = junit.as_ref().map_or("above".to_string(), |f| format!("above, and as errors in {}", f.display()));
    CliError::Input(format!("{invalid} lesson{s} did not validate ({place}); the other figures were checked"))
}

/// A blessed snapshot with no figure behind it any more.
struct Orphan {
    /// The lesson's folder name in DIR.
    stem: String,
    /// The figure's name, `None` for a whole lesson's folder.
    figure: Option<String>,
    /// The PNG, or the folder.
    path: PathBuf,
}

/// The snapshots in `dir` that no checked figure makes: a PNG in a checked lesson's folder
/// that is not one of its figures, and (when a folder of lessons was checked, `whole`) a
/// lesson folder whose lesson is gone.
fn orphans(dir: &Path, lessons: &[(PathBuf, crate::lesson::Lesson)], whole: bool) -> Vec<Orphan> {
    let stem_of = |p: &Path| p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let mut found = Vec::new();
    for (path, lesson) in lessons {
        let stem = stem_of(path);
        let Ok(entries) = std::fs::read_dir(dir.join(&stem)) else { continue };
        let mut names: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        names.sort();
        for png in names {
            let name = png.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let Some(figure) = name.strip_suffix(".png") else { continue };
            if figure.ends_with(".diff") || figure.ends_with(".actual") || lesson.figures.iter().any(|f| f.name == figure) {
                continue;
            }
            found.push(Orphan { stem: stem.clone(), figure: Some(figure.to_string()), path: png });
        }
    }
    if whole && let Ok(entries) = std::fs::read_dir(dir) {
        let mut folders: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.is_dir()).collect();
        folders.sort();
        for folder in folders {
            let stem = folder.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if !lessons.iter().any(|(p, _)| stem_of(p) == stem) {
                found.push(Orphan { stem, figure: None, path: folder });
            }
        }
    }
    found
}

/// Removes the `.diff.png` and `.actual.png` a failed check left beside the snapshot `file`,
/// once it matches (or is blessed) again: what is left in the folder is what still fails.
fn remove_stale(file: &std::path::Path) {
    for stale in [file.with_extension("diff.png"), file.with_extension("actual.png")] {
        let _ = std::fs::remove_file(stale);
    }
}
