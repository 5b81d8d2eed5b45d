//! `shadelab site`: the lessons as a static HTML gallery that works from `file://` with no
//! script: an index with a thumbnail per lesson, and a page per lesson with its title,
//! summary and notes, its equations in MathML, every figure with its caption, the `explain`
//! text, cost ladders as HTML tables with their charts as SVG, and the lesson's TOML source.
//!
//! Figures are made by [`figure::render_figure`] (and [`figure::cost_figure`] for ladders),
//! the same path as `shadelab figures`; the explanation is [`crate::render::explain::text`].
//! Every lesson and figure is checked before any file is written, and every file is
//! written atomically.

pub mod font;
pub mod html;
pub mod live;
pub mod math;

use crate::figure::{self, FigureError, FigureOptions};
use crate::lesson::{FigureBody, Lesson, LessonError, Override};
use crate::output::OutputError;
use crate::render::{self, Layer};
use std::path::{Path, PathBuf};

/// How the site is made.
#[derive(Debug, Clone, PartialEq)]
pub struct SiteOptions {
    /// How figures are drawn (theme, scale, cell size).
    pub figure: FigureOptions,
    /// Width in pixels of each lesson's own image (its thumbnail on the index); the height
    /// keeps the camera's aspect ratio. The camera's size is used when it is smaller.
    pub thumb_width: u32,
    /// The live lab's WebAssembly build: with it, each page gets the live view.
    pub live: Option<std::sync::Arc<live::LiveBuild>>,
}

impl Default for SiteOptions {
    fn default() -> Self {
        SiteOptions { figure: FigureOptions::default(), thumb_width: 320, live: None }
    }
}

/// A site that could not be made.
#[derive(Debug, thiserror::Error)]
pub enum SiteError {
    /// A lesson does not validate (or a variant of its figures does not).
    #[error("{0}")]
    Lesson(#[from] LessonError),
    /// A figure cannot be made (boxed: a figure's error is large, and this one is rare).
    #[error("{0}")]
    Figure(Box<FigureError>),
    /// A mesh could not be loaded.
    #[error("{0}")]
    Scene(#[from] crate::scene::build::SceneError),
    /// A file cannot be written.
    #[error("{0}")]
    Output(#[from] OutputError),
    /// A render is over the work and memory budget.
    #[error("{0}")]
    Budget(#[from] render::budget::OverBudget),
    /// The Japanese font could not be cut to the pages' characters.
    #[error("{0}")]
    Font(String),
    /// A file a lesson reads could not be read for its live view.
    #[error("{0}")]
    Live(String),
}

impl From<FigureError> for SiteError {
    fn from(e: FigureError) -> Self {
        SiteError::Figure(Box::new(e))
    }
}

/// One lesson of the site: where it came from and what it is.
#[derive(Debug, Clone)]
pub struct SiteLesson {
    /// The file name without `.toml`: the page is `<stem>.html`, its files under `<stem>/`.
    pub stem: String,
    /// The validated lesson.
    pub lesson: Lesson,
}

/// What was written.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SiteReport {
    /// Lesson pages.
    pub pages: usize,
    /// Figure images.
    pub figures: usize,
    /// Every file written, relative to the site's folder.
    pub files: Vec<PathBuf>,
    /// Characters the label font lacks, per figure file.
    pub missing_glyphs: Vec<(PathBuf, Vec<char>)>,
}

/// One figure as a page shows it.
#[derive(Debug, Clone)]
pub struct PageFigure {
    /// The figure's name (its anchor and file name).
    pub name: String,
    /// Its title, if it has one.
    pub title: Option<String>,
    /// Its caption in plain text.
    pub caption: Option<String>,
    /// The PNG, relative to the site's folder.
    pub png: String,
    /// The PNG's size.
    pub size: (u32, u32),
    /// A measured ladder: its table and chart.
    pub cost: Option<CostSection>,
}

/// A cost ladder as a page shows it.
#[derive(Debug, Clone)]
pub struct CostSection {
    /// The HTML `<table>`.
    pub table: String,
    /// The chart's SVG file, relative to the site's folder (none when not timed).
    pub svg: Option<String>,
}

/// Checks every lesson's figures (as `shadelab figures` does) before anything is written.
///
/// # Errors
/// The first figure that does not validate.
pub fn check(lessons: &[SiteLesson], opts: &SiteOptions) -> Result<(), SiteError> {
    for l in lessons {
        for spec in &l.lesson.figures {
            figure::check_figure(&l.lesson, spec, &opts.figure)?;
        }
        thumb_lesson(&l.lesson, opts.thumb_width)?;
    }
    Ok(())
}

/// The lesson at its thumbnail size: `thumb_width` wide (or the camera's width if smaller),
/// the camera's aspect ratio kept.
fn thumb_lesson(lesson: &Lesson, thumb_width: u32) -> Result<Lesson, LessonError> {
    let (w, h) = (lesson.scene.camera.width, lesson.scene.camera.height);
    if w <= thumb_width {
        return Ok(lesson.clone());
    }
    let th = ((h as u64 * thumb_width as u64 + w as u64 / 2) / w as u64).max(1) as u32;
    let size = Override::parse(&format!("camera.size=[{thumb_width}, {th}]")).expect("a valid override");
    let sets: Vec<Override> = lesson.overrides.iter().cloned().chain([size]).collect();
    crate::lesson::parse(&lesson.source, &lesson.path, &sets)
}

/// One lesson's images and texts, made: what its page and its index card need. Kept by
/// `shadelab watch` so a save re-makes only the lessons it touched.
#[derive(Debug, Clone)]
pub struct MadeLesson {
    /// Its image, relative to the site's folder.
    pub thumb: String,
    /// The image's size.
    pub thumb_size: (u32, u32),
    /// Its figures, written.
    pub figures: Vec<PageFigure>,
    /// Its live view's data script (`<stem>/live.js`), when the site has the live lab.
    pub live: Option<String>,
    /// The equations of its materials.
    pub equations: Vec<math::Equation>,
    /// `shadelab explain`'s text.
    pub explain: String,
}

/// Writes the site into `dir`: `index.html`, `style.css`, and per lesson `<stem>.html` with
/// its images under `<stem>/`. `progress` is called after each lesson with (done, total, stem).
///
/// # Errors
/// [`SiteError`]; call [`check`] first so bad input writes nothing.
pub fn build(
    lessons: &[SiteLesson],
    dir: &Path,
    opts: &SiteOptions,
    progress: &mut dyn FnMut(usize, usize, &str),
) -> Result<SiteReport, SiteError> {
    let mut report = SiteReport::default();
    let mut made = Vec::with_capacity(lessons.len());
    for (i, l) in lessons.iter().enumerate() {
        made.push(make_lesson(l, dir, opts, &mut report)?);
        progress(i + 1, lessons.len(), &l.stem);
    }
    write_pages(lessons, &made, dir, opts.live.as_deref(), &mut report)?;
    Ok(report)
}

/// Renders one lesson's image and figures into `dir/<stem>/` (the expensive part of
/// [`build`]); its page is written by [`write_pages`].
///
/// # Errors
/// [`SiteError`]; call [`check`] first so bad input writes nothing.
pub fn make_lesson(l: &SiteLesson, dir: &Path, opts: &SiteOptions, report: &mut SiteReport) -> Result<MadeLesson, SiteError> {
    let lesson = &l.lesson;
    // The lesson's own image: its page's first picture and the index's thumbnail.
    let small = thumb_lesson(lesson, opts.thumb_width)?;
    let scene = crate::scene::build::build(&small)?;
    render::budget::check(&scene).map_err(|e| e.at(lesson.path.display()))?;
    let (rgb, _) = render::render_image(&scene, Layer::Total, scene.spec.settings.exposure, scene.spec.settings.tonemap);
    let thumb = format!("{}/render.png", l.stem);
    write_file(dir, &thumb, report, |p| crate::output::write_png(p, scene.spec.camera.width, scene.spec.camera.height, &rgb))?;
    let thumb_size = (scene.spec.camera.width, scene.spec.camera.height);

    let mut figures = Vec::new();
    for spec in &lesson.figures {
        let png = format!("{}/{}.png", l.stem, spec.name);
        // The page shows the caption as text under the image, not drawn into it too.
        let drawn = crate::lesson::FigureSpec { caption: None, ..spec.clone() };
        let (fig, cost) = match &spec.body {
            FigureBody::Cost { ladder, repeat } => {
                let (fig, r) = figure::cost_figure(lesson, &drawn, *ladder, *repeat, &opts.figure, false)?;
                let svg = if opts.figure.measure_time {
                    let chart = figure::cost::chart(&r, &format!("{}: error against time", ladder.name()), 1.0, lesson.lang)
                        .map_err(FigureError::Chart)?;
                    let name = format!("{}/{}-chart.svg", l.stem, spec.name);
                    write_file(dir, &name, report, |p| {
                        crate::output::write_atomic(p, |w| w.write_all(chart.svg.as_bytes()).map_err(|e| e.to_string()))
                    })?;
                    Some(name)
                } else {
                    None
                };
                (fig, Some(CostSection { table: html::cost_table(&r), svg }))
            }
            _ => (figure::render_figure(lesson, &drawn, &opts.figure)?, None),
        };
        write_file(dir, &png, report, |p| crate::output::write_png_rgba(p, &fig.image))?;
        if !fig.missing_glyphs.is_empty() {
            report.missing_glyphs.push((PathBuf::from(&png), fig.missing_glyphs.clone()));
        }
        report.figures += 1;
        figures.push(PageFigure {
            name: spec.name.clone(),
            title: spec.title.as_deref().map(figure::text::to_plain_text),
            caption: spec.caption.as_deref().map(figure::text::to_plain_text),
            png,
            size: (fig.image.width(), fig.image.height()),
            cost,
        });
    }

    let full = crate::scene::build::build(lesson)?;
    let live = match &opts.live {
        Some(_) => {
            let controls = live::controls(lesson)?;
            let script = live::lesson_script(lesson, &l.stem, &controls).map_err(SiteError::Live)?;
            let name = format!("{}/live.js", l.stem);
            write_file(dir, &name, report, |p| write_text(p, &script))?;
            Some(name)
        }
        None => None,
    };
    Ok(MadeLesson {
        live,
        thumb,
        thumb_size,
        figures,
        equations: math::equations(&full.materials),
        explain: render::explain::text(&full, true, lesson.lang),
    })
}

/// Writes every lesson's page (`made` is parallel to `lessons`), `style.css` and `index.html`.
///
/// # Errors
/// [`SiteError::Output`] for a file that cannot be written.
pub fn write_pages(
    lessons: &[SiteLesson],
    made: &[MadeLesson],
    dir: &Path,
    live: Option<&live::LiveBuild>,
    report: &mut SiteReport,
) -> Result<(), SiteError> {
    let mut cards = Vec::new();
    // Every page's text, for the Japanese font cut to what the pages use.
    let mut text = String::new();
    for (i, (l, m)) in lessons.iter().zip(made).enumerate() {
        let lesson = &l.lesson;
        let nav = html::Nav {
            prev: i.checked_sub(1).map(|j| (page_name(&lessons[j].stem), lessons[j].lesson.title.clone())),
            next: lessons.get(i + 1).map(|n| (page_name(&n.stem), n.lesson.title.clone())),
        };
        let page = html::lesson_page(&html::LessonPage {
            stem: &l.stem,
            lesson,
            thumb: &m.thumb,
            thumb_size: m.thumb_size,
            figures: &m.figures,
            equations: &m.equations,
            explain: &m.explain,
            live: m.live.as_deref(),
            nav,
        });
        let name = page_name(&l.stem);
        write_file(dir, &name, report, |p| write_text(p, &page))?;
        text.push_str(&page);
        report.pages += 1;
        cards.push(html::Card {
            page: name,
            title: lesson.title.clone(),
            summary: lesson.summary.clone(),
            thumb: m.thumb.clone(),
            thumb_size: m.thumb_size,
            figures: m.figures.len(),
        });
    }
    let index = html::index_page(&cards);
    text.push_str(&index);
    let glossary = html::glossary_page();
    text.push_str(&glossary);
    write_file(dir, "glossary.html", report, |p| write_text(p, &glossary))?;
    let mut style = String::new();
    if let Some((bytes, _glyphs)) = font::subset_for(&text).map_err(SiteError::Font)? {
        write_file(dir, font::FILE, report, |p| crate::output::write_atomic(p, |w| w.write_all(&bytes).map_err(|e| e.to_string())))?;
        // The SIL Open Font License travels with the font.
        write_file(dir, "shadelab-ja-LICENSE.txt", report, |p| write_text(p, NOTO_LICENSE))?;
        style.push_str(&font::face_rule());
    }
    style.push_str(html::STYLE);
    if let Some(build) = live {
        write_file(dir, "live/shadelab_wasm.js", report, |p| write_text(p, &build.glue))?;
        write_file(dir, "live/shadelab_wasm_bg.js", report, |p| write_text(p, &build.wasm_script))?;
        write_file(dir, "live/lab.js", report, |p| write_text(p, live::LAB_JS))?;
        style.push_str(html::LIVE_STYLE);
    }
    write_file(dir, "style.css", report, |p| write_text(p, &style))?;
    write_file(dir, "index.html", report, |p| write_text(p, &index))?;
    Ok(())
}

/// The license of the Japanese font the site ships.
const NOTO_LICENSE: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/fonts/NotoSansJP-LICENSE.txt"));

/// `<stem>.html`.
fn page_name(stem: &str) -> String {
    format!("{stem}.html")
}

/// Writes `name` under `dir` with `write` and records it.
fn write_file(
    dir: &Path,
    name: &str,
    report: &mut SiteReport,
    write: impl FnOnce(&Path) -> Result<(), OutputError>,
) -> Result<(), SiteError> {
    write(&dir.join(name))?;
    report.files.push(PathBuf::from(name));
    Ok(())
}

/// Writes UTF-8 text atomically.
fn write_text(path: &Path, text: &str) -> Result<(), OutputError> {
    crate::output::write_atomic(path, |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))
}
