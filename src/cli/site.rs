//! `shadelab site`: lessons as a static HTML gallery (the work is in `crate::site`).

use super::{CliError, FigureFlags};
use crate::site::{self, SiteLesson, SiteOptions};
use std::path::PathBuf;

/// Arguments of `shadelab site`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Two lessons as a gallery; open site/index.html (give lessons/ for every lesson):
    shadelab site lessons/01-first-light.toml lessons/04-shininess.toml -o site/
  Small cells, for a quick look:
    shadelab site lessons/04-shininess.toml --cell 96x96 -o quick/
  Larger labels for a projector:
    shadelab site lessons/01-first-light.toml -o slides/ --scale 2")]
pub struct SiteArgs {
    /// Lesson files or folders of lessons.
    #[arg(required = true, value_name = "PATH")]
    pub paths: Vec<PathBuf>,
    /// Output folder: index.html, style.css, LESSON.html and LESSON/*.png.
    #[arg(short, long, value_name = "DIR", default_value = "site")]
    pub output: PathBuf,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// Width in pixels of each lesson's own image (the index's thumbnail).
    #[arg(long, default_value_t = 320, value_name = "PX")]
    pub thumb_width: u32,
    /// How figures are drawn.
    #[command(flatten)]
    pub look: FigureFlags,
    /// The live lab's build (shadelab_wasm.js and shadelab_wasm_bg.wasm, from
    /// tools/build-live.sh) [default: $SHADELAB_LIVE, else target/live beside this program].
    #[arg(long, value_name = "DIR")]
    pub live: Option<PathBuf>,
}

/// The live lab's build: from `--live DIR` (an error when it is not there), else from
/// `$SHADELAB_LIVE` or `../live` beside the executable (`target/live` for a cargo build), else
/// none: the pages are static, and a note says how to build it.
pub fn live_build(flag: Option<PathBuf>, quiet: bool) -> Result<Option<std::sync::Arc<site::live::LiveBuild>>, CliError> {
    if let Some(dir) = flag {
        return site::live::LiveBuild::read(&dir)
            .map(|b| Some(b.into()))
            .map_err(|m| CliError::Input(format!("--live {}: {m}", dir.display())));
    }
    if let Some(dir) = std::env::var_os("SHADELAB_LIVE").filter(|v| !v.is_empty()).map(PathBuf::from) {
        // Asked for by name: a missing build is an error, as for --live.
        return site::live::LiveBuild::read(&dir)
            .map(|b| Some(b.into()))
            .map_err(|m| CliError::Input(format!("SHADELAB_LIVE={}: {m}", dir.display())));
    }
    let exe = std::env::current_exe().ok().and_then(|e| e.parent().map(|d| d.join("../live")));
    match exe.map(|d| site::live::LiveBuild::read(&d)) {
        Some(Ok(b)) => Ok(Some(b.into())),
        _ => {
            if !quiet {
                super::out::eprint_line(format_args!(
                    "note: no live lab build found, so the pages have no live view\n  hint: build it with tools/build-live.sh, or give --live DIR"
                ));
            }
            Ok(None)
        }
    }
}

/// Checks every lesson and figure, then writes the site.
pub fn run(args: SiteArgs, quiet: bool) -> Result<(), CliError> {
    if !(16..=4096).contains(&args.thumb_width) {
        return Err(CliError::Input(format!("--thumb-width {}: give 16 to 4096 pixels", args.thumb_width)));
    }
    let sets = super::overrides(&args.set.sets, Vec::new())?;
    let opts = SiteOptions { figure: args.look.options()?, thumb_width: args.thumb_width, live: live_build(args.live.clone(), quiet)? };
    crate::output::check_folder(&args.output, &args.output)?;
    let mut lessons = Vec::new();
    for path in super::figures::lesson_files(&args.paths)? {
        let lesson = crate::lesson::load(&path, &sets)?;
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "lesson".into());
        if lessons.iter().any(|l: &SiteLesson| l.stem == stem) {
            return Err(CliError::Input(format!(
                "{}: another lesson is also named `{stem}`; each page is named after its file\n  hint: give lessons with different file names",
                path.display()
            )));
        }
        lessons.push(SiteLesson { stem, lesson });
    }
    if lessons.is_empty() {
        return Err(CliError::Input("no lesson files (*.toml) found\n  hint: give lesson files or a folder of them".into()));
    }
    site::check(&lessons, &opts).map_err(|e| CliError::Input(e.to_string()))?;
    let start = std::time::Instant::now();
    // A progress bar on a terminal only: a redirected stderr gets no progress lines.
    let bar = super::progress::Progress::new(lessons.len() as u64, quiet);
    let report = site::build(&lessons, &args.output, &opts, &mut |_, _, stem| {
        bar.message(stem.to_string());
        bar.inc();
    })
    .map_err(|e| match e {
        site::SiteError::Output(o) => CliError::from(o),
        site::SiteError::Font(m) => CliError::Internal(m),
        other => CliError::Input(other.to_string()),
    })?;
    bar.finish();
    for (file, chars) in &report.missing_glyphs {
        super::out::eprint_line(format_args!(
            "warning: {}: the label font has no glyph for {chars:?}; drawn as boxes",
            args.output.join(file).display()
        ));
    }
    // The summary line stays under -q: it says where the files went (docs/cli.md).
    outln!(
        "{} lesson pages, {} figures in {:.1} s → {}",
        report.pages,
        report.figures,
        start.elapsed().as_secs_f64(),
        args.output.join("index.html").display()
    )?;
    Ok(())
}
