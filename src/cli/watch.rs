//! `shadelab watch`: re-render lessons each time a file they read is saved.
//!
//! The folders holding the lessons and their assets are watched (not the files: editors
//! often save by writing a new file and renaming it over the old one, which ends a watch on
//! the file). notify-debouncer-full folds the burst of events one save makes into one batch
//! after 200 ms of quiet, and keeps each event's kind: inotify also reports every open and
//! read, and reading a lesson to rebuild it must not count as a change (or it loops). A batch re-renders only the lessons that read a changed file, with
//! the code of `shadelab figures` (or of `shadelab site` under `--serve`); an invalid lesson
//! prints its error and keeps its last good output, and the next good save renders again.

use super::progress::summary;
use super::serve::Server;
use super::{CliError, FigureFlags};
use crate::figure::{self, FigureOptions};
use crate::lesson::{self, Lesson, Override};
use crate::render::{self, Layer};
use crate::site::{self, MadeLesson, SiteLesson, SiteOptions, SiteReport};
use notify_debouncer_full::notify::event::{AccessKind, AccessMode, EventKind};
use notify_debouncer_full::notify::{RecommendedWatcher, RecursiveMode};
use notify_debouncer_full::{DebounceEventResult, Debouncer, RecommendedCache};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// Arguments of `shadelab watch`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Render a lesson's image and figures into out/ once and exit; without --once it watches the
  lesson and its meshes and maps, and renders again at every save until Ctrl-C:
    shadelab watch lessons/01-first-light.toml --once
  The same into slides/, dark and twice as large:
    shadelab watch lessons/04-shininess.toml -o slides/ --theme dark --scale 2 --once
  The gallery of `shadelab site` in out/; without --once it is served at http://127.0.0.1:8080/
  and open pages reload after each rebuild:
    shadelab watch lessons/01-first-light.toml --serve --port 8080 --once")]
pub struct WatchArgs {
    /// Lesson files or folders of lessons (every *.toml inside, and new ones as they appear).
    #[arg(required = true, value_name = "LESSON|DIR")]
    pub paths: Vec<PathBuf>,
    /// Output folder: LESSON.png and LESSON/<figure>.png (with --serve, the files of `shadelab site`).
    #[arg(short, long, value_name = "DIR", default_value = "out")]
    pub output: PathBuf,
    /// Also serve the output folder as a site on http://127.0.0.1:PORT/ that reloads after each rebuild.
    #[arg(long)]
    pub serve: bool,
    /// Port for --serve (0: any free port; the address is printed).
    #[arg(long, default_value_t = 8000, value_name = "N", requires = "serve")]
    pub port: u16,
    /// Build once and exit (exit 2 if a lesson is invalid), without watching or serving.
    #[arg(long)]
    pub once: bool,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// How figures are drawn.
    #[command(flatten)]
    pub look: FigureFlags,
}

/// Quiet time after the last event of a save before rebuilding: one save is often a few
/// writes (truncate, write, rename), and this folds them into one rebuild.
const DEBOUNCE: Duration = Duration::from_millis(200);

/// What wakes the loop.
enum Msg {
    /// A batch of changed paths (or a watcher error).
    Files(DebounceEventResult),
    /// Ctrl-C.
    Stop,
}

/// One watched lesson and what it last built from.
struct Entry {
    /// The lesson file as given or found.
    path: PathBuf,
    /// Its canonical path, compared with the paths of events.
    key: PathBuf,
    /// The file name without `.toml`: its output files are named after it.
    stem: String,
    /// The last version that validated (kept while the file is being fixed).
    lesson: Option<Lesson>,
    /// Under `--serve`: its page's images and texts, as last made.
    made: Option<MadeLesson>,
    /// The files it reads besides itself, from its last version that parsed.
    assets: Vec<PathBuf>,
}

/// The whole watch: options, lessons, and where their output goes.
struct Watch {
    output: PathBuf,
    sets: Vec<Override>,
    figure: FigureOptions,
    /// `Some` under `--serve`: output is the site's.
    site: Option<SiteOptions>,
    /// Folders given on the command line (canonical): a new `*.toml` there is a new lesson.
    dirs: Vec<PathBuf>,
    entries: Vec<Entry>,
    /// Folders watched so far (canonical).
    watched: Vec<PathBuf>,
}

/// Builds every lesson, then (unless `--once`) rebuilds on each save until Ctrl-C.
pub fn run(args: WatchArgs, quiet: bool) -> Result<(), CliError> {
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let figure = args.look.options()?;
    crate::output::check_folder(&args.output, &args.output)?;
    let files = super::figures::lesson_files(&args.paths)?;
    if files.is_empty() {
        return Err(CliError::Input("no lesson files (*.toml) found\n  hint: give lesson files or a folder of them".into()));
    }
    let mut watch = Watch {
        output: args.output.clone(),
        sets,
        figure,
        site: if args.serve {
            Some(SiteOptions { figure, live: super::site::live_build(None, quiet)?, ..SiteOptions::default() })
        } else {
            None
        },
        dirs: args.paths.iter().filter(|p| p.is_dir()).filter_map(|p| p.canonicalize().ok()).collect(),
        entries: Vec::new(),
        watched: Vec::new(),
    };
    for f in files {
        watch.add(f)?;
    }
    let all: Vec<usize> = (0..watch.entries.len()).collect();
    if args.once {
        let failed = watch.rebuild(&all, None)?;
        if failed > 0 {
            return Err(CliError::Input(super::check::invalid_line(failed, all.len())));
        }
        return Ok(());
    }

    // Listen first: a port in use ends the command before any work.
    let server = if args.serve { Some(Server::start(&args.output, args.port)?) } else { None };
    let (tx, rx) = mpsc::channel();
    let stop = tx.clone();
    ctrlc::set_handler(move || {
        let _ = stop.send(Msg::Stop);
    })
    .map_err(|e| CliError::Internal(format!("cannot catch Ctrl-C: {e}")))?;
    let mut debouncer = notify_debouncer_full::new_debouncer(DEBOUNCE, None, move |r| {
        let _ = tx.send(Msg::Files(r));
    })
    .map_err(|e| CliError::Internal(format!("cannot watch files: {e}")))?;
    // Watching starts before the first build, so a save during it is not missed.
    watch.update_watches(&mut debouncer);
    watch.rebuild(&all, server.as_ref())?;
    watch.update_watches(&mut debouncer);
    if let Some(s) = &server {
        // Printed under -q too: it says where to look.
        outln!("serving {} at {}", args.output.display(), s.url())?;
    }
    if !quiet {
        let files: usize = watch.entries.iter().map(|e| 1 + e.assets.len()).sum();
        outln!("watching {files} file{} of {} lesson{}; Ctrl-C ends", plural(files), all.len(), plural(all.len()))?;
    }
    let result = loop {
        match rx.recv() {
            Ok(Msg::Files(Ok(events))) => {
                let changed: Vec<PathBuf> =
                    events.iter().filter(|e| is_change(&e.event.kind)).flat_map(|e| &e.event.paths).map(|p| normalize(p)).collect();
                let which = watch.affected(&changed);
                if which.is_empty() {
                    continue;
                }
                if let Err(e) = watch.rebuild(&which, server.as_ref()) {
                    break Err(e);
                }
                watch.update_watches(&mut debouncer);
            }
            Ok(Msg::Files(Err(errors))) => errors.iter().for_each(|e| super::out::eprint_line(format_args!("warning: watching: {e}"))),
            Ok(Msg::Stop) | Err(_) => break Ok(()),
        }
    };
    drop(debouncer);
    if let Some(s) = server {
        s.stop();
    }
    result
}

impl Watch {
    /// Adds a lesson file to watch (not built yet).
    fn add(&mut self, path: PathBuf) -> Result<usize, CliError> {
        let stem = super::figures::stem(&path);
        let key = normalize(&path);
        if let Some(other) = self.entries.iter().find(|e| e.stem == stem) {
            return Err(CliError::Input(format!(
                "{}: {} is also named `{stem}`; its output files are named after it\n  hint: give lessons with different file names",
                path.display(),
                other.path.display()
            )));
        }
        self.entries.push(Entry { path, key, stem, lesson: None, made: None, assets: Vec::new() });
        Ok(self.entries.len() - 1)
    }

    /// The lessons that read one of `changed` (and new lessons in a watched folder), in order.
    fn affected(&mut self, changed: &[PathBuf]) -> Vec<usize> {
        let mut which: Vec<usize> = Vec::new();
        for p in changed {
            let before = which.len();
            for (i, e) in self.entries.iter().enumerate() {
                if (e.key == *p || e.assets.contains(p)) && !which.contains(&i) {
                    which.push(i);
                }
            }
            let new_lesson = which.len() == before
                && p.extension().is_some_and(|x| x == "toml")
                && p.is_file()
                && p.parent().is_some_and(|d| self.dirs.iter().any(|w| w == d))
                && !self.entries.iter().any(|e| e.key == *p);
            if new_lesson {
                match self.add(p.clone()) {
                    Ok(i) => which.push(i),
                    Err(e) => super::out::eprint_line(format_args!("error: {e}")),
                }
            }
        }
        which.sort_unstable();
        which
    }

    /// Rebuilds lessons `which`: one summary line each, or its error; under `--serve`, then
    /// the pages and the counter. Returns how many failed.
    ///
    /// # Errors
    /// Only a closed stdout: a lesson's error is printed and the watch goes on.
    fn rebuild(&mut self, which: &[usize], server: Option<&Server>) -> Result<usize, CliError> {
        let mut failed = 0;
        for &i in which {
            let start = Instant::now();
            match self.build_one(i) {
                Ok(figures) => {
                    let line = summary(figures, "figure", "figures", start.elapsed(), Some(&self.output));
                    outln!("{}: {line}", self.entries[i].path.display())?;
                }
                Err(CliError::StdoutClosed) => return Err(CliError::StdoutClosed),
                Err(e) => {
                    failed += 1;
                    super::out::eprint_line(format_args!("error: {e}"));
                }
            }
        }
        if failed < which.len() {
            if self.site.is_some()
                && let Err(e) = self.write_pages()
            {
                failed += 1;
                super::out::eprint_line(format_args!("error: {e}"));
            }
            if let Some(s) = server {
                s.bump();
            }
        }
        Ok(failed)
    }

    /// Loads, checks and renders one lesson into the output folder.
    fn build_one(&mut self, i: usize) -> Result<usize, CliError> {
        let path = self.entries[i].path.clone();
        let lesson = lesson::load(&path, &self.sets)?;
        // Known once it parses, even if a figure fails below: fixing an asset rebuilds it.
        self.entries[i].assets = lesson.asset_files().iter().map(|p| normalize(p)).collect();
        let stem = self.entries[i].stem.clone();
        if let Some(opts) = &self.site {
            let one = [SiteLesson { stem, lesson }];
            let site_err = |e: site::SiteError| match e {
                site::SiteError::Output(o) => CliError::from(o),
                other => CliError::Input(other.to_string()),
            };
            site::check(&one, opts).map_err(site_err)?;
            let mut report = SiteReport::default();
            let made = site::make_lesson(&one[0], &self.output, opts, &mut report).map_err(site_err)?;
            for (file, chars) in &report.missing_glyphs {
                super::out::eprint_line(format_args!(
                    "warning: {}: the label font has no glyph for {chars:?}; drawn as boxes",
                    self.output.join(file).display()
                ));
            }
            let [one] = one;
            let e = &mut self.entries[i];
            e.lesson = Some(one.lesson);
            e.made = Some(made);
            return Ok(report.figures);
        }
        // Every figure is checked before any file is written, as `shadelab figures` does.
        for spec in &lesson.figures {
            figure::check_figure(&lesson, spec, &self.figure)?;
        }
        let scene = crate::scene::build::build(&lesson)?;
        crate::render::budget::check(&scene).map_err(|e| e.at(path.display()))?;
        let (rgb, _) = render::render_image(&scene, Layer::Total, scene.spec.settings.exposure, scene.spec.settings.tonemap);
        crate::output::write_png(&self.output.join(format!("{stem}.png")), scene.spec.camera.width, scene.spec.camera.height, &rgb)?;
        // Its own per-figure lines are left out: one summary line per rebuild.
        let n = super::figures::write_lesson_figures(&path, &lesson, &self.figure, &self.output, true, None)?.len();
        self.entries[i].lesson = Some(lesson);
        Ok(n)
    }

    /// The site's pages and index for every lesson made so far (`--serve`).
    fn write_pages(&self) -> Result<(), CliError> {
        let (lessons, made): (Vec<SiteLesson>, Vec<MadeLesson>) = self
            .entries
            .iter()
            .filter_map(|e| Some((SiteLesson { stem: e.stem.clone(), lesson: e.lesson.clone()? }, e.made.clone()?)))
            .unzip();
        let live = self.site.as_ref().and_then(|s| s.live.as_deref());
        site::write_pages(&lessons, &made, &self.output, live, &mut SiteReport::default()).map_err(|e| match e {
            site::SiteError::Output(o) => CliError::from(o),
            other => CliError::Internal(other.to_string()),
        })
    }

    /// Watches every folder that holds a lesson, an asset, or new lessons, once each.
    fn update_watches(&mut self, debouncer: &mut Debouncer<RecommendedWatcher, RecommendedCache>) {
        let mut want: Vec<PathBuf> = self.dirs.clone();
        for e in &self.entries {
            want.extend(std::iter::once(&e.key).chain(&e.assets).filter_map(|p| p.parent().map(Path::to_path_buf)));
        }
        for dir in want {
            if self.watched.contains(&dir) {
                continue;
            }
            match debouncer.watch(&dir, RecursiveMode::NonRecursive) {
                Ok(()) => self.watched.push(dir),
                Err(e) => super::out::eprint_line(format_args!("warning: cannot watch {}: {e}", dir.display())),
            }
        }
    }
}

/// True for an event that may change a file's bytes or name; opening, reading and closing
/// a file unwritten are not (the rebuild itself reads the lesson).
fn is_change(kind: &EventKind) -> bool {
    match kind {
        EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
        EventKind::Access(_) => false,
        _ => true,
    }
}

/// `path` made comparable with the paths of events: canonical, or (for a file that is gone
/// mid-save) its canonical folder joined with its name.
fn normalize(path: &Path) -> PathBuf {
    if let Ok(c) = path.canonicalize() {
        return c;
    }
    match (path.parent().map(|d| if d.as_os_str().is_empty() { Path::new(".") } else { d }), path.file_name()) {
        (Some(dir), Some(name)) => dir.canonicalize().map(|d| d.join(name)).unwrap_or_else(|_| path.to_path_buf()),
        _ => path.to_path_buf(),
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}
