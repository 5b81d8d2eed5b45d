//! Figures: grids of variants of one lesson, labelled for slides.
//!
//! Every kind (compare, sweep, grid, split) is the same mechanism: [`variants::expand`]
//! turns a figure into a grid of override sets; each cell is rendered and developed;
//! [`grid::compose`] lays the cells out with headers, title and caption. Cells whose
//! scenes rasterize identically (only materials, lights, normals or interpolation
//! differ) share one visibility buffer: the sweep rasterizes once and shades many times.

pub mod bsdf;
pub mod bssrdf;
mod chart_text;
pub mod charts;
pub mod colorbar;
pub mod cost;
mod diff;
pub mod fit;
pub mod grid;
pub mod kept;
pub mod overlay;
pub mod plot;
pub mod probe;
pub mod snapshot;
pub mod text;
pub mod variants;
pub mod walk;

use crate::lesson::limits::MAX_FIGURE_PIXELS;
use crate::lesson::settings::Solver;
use crate::lesson::{FigureBody, FigureSpec, LadderKind, Lesson, LessonError, Normals, Override};
use crate::light::{Light, LightKind, Spot};
use crate::raster::VisBuffer;
use crate::render::{self, Frame, Layer, RenderStats};
use crate::scene::build::{SceneError, build};
use crate::shading::brdf::Brdf;
use crate::shading::material::Model;
use grid::{Cell, GridSpec, Theme};
use web_time::Instant;

/// Gauss-Legendre nodes per panel of the coarse rule in `albedo` figures (the fine rule has
/// twice as many). The chart prints the resulting error bound under it.
const ALBEDO_SAMPLES: usize = 4;

/// How a figure is drawn (command-line flags; the lesson gives what is shown).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FigureOptions {
    /// Colour theme.
    pub theme: Theme,
    /// Text and spacing scale (2 for high-DPI slides).
    pub scale: f32,
    /// Cell size in pixels; overrides the figure's `cell` and the camera size.
    pub cell: Option<(u32, u32)>,
    /// Print the render time under each cell.
    pub timings: bool,
    /// Time the rungs of `cost` figures (and add their chart). Off for snapshots: times
    /// change from run to run, and a snapshot must not.
    pub measure_time: bool,
    /// Lay the figure out for a slide of this size (overrides the figure's `fit`).
    pub fit: Option<(u32, u32)>,
}

impl Default for FigureOptions {
    fn default() -> Self {
        FigureOptions { theme: Theme::Light, scale: 1.0, cell: None, timings: false, measure_time: true, fit: None }
    }
}

/// A composed figure and what it cost.
#[derive(Debug, Clone)]
pub struct Figure {
    /// The image (RGBA, 8-bit sRGB).
    pub image: image::RgbaImage,
    /// Render counts summed over the cells.
    pub stats: RenderStats,
    /// How many times the scene was rasterized (1 for a material sweep).
    pub rasterizations: usize,
    /// Cells (or a cost figure's reference) read from the on-disk cache instead of rendered.
    pub cached: usize,
    /// Characters the label font lacks (drawn as boxes).
    pub missing_glyphs: Vec<char>,
    /// The whole figure was read from the on-disk cache ([`kept`]), not drawn.
    pub kept: bool,
}

/// A figure that could not be made: always bad input.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// A variant's lesson is invalid.
    #[error("{0}")]
    Lesson(#[from] LessonError),
    /// A mesh could not be loaded.
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// A chart figure names a material it cannot plot.
    #[error("{0}")]
    Chart(String),
    /// A cost figure's ladder cannot be measured on this lesson.
    #[error("{0}")]
    Cost(#[from] crate::cost::CostError),
    /// A cell's render is over the work and memory budget.
    #[error("{0}")]
    Budget(#[from] crate::render::budget::OverBudget),
}

/// The overrides every cell gets from the options (the cell size).
fn cell_overrides(spec: &FigureSpec, opts: &FigureOptions) -> Vec<Override> {
    let mut extra = Vec::new();
    if let Some((w, h)) = opts.cell.or(spec.cell) {
        extra.push(Override {
            arg: format!("camera.size=[{w}, {h}]"),
            path: crate::lesson::KeyPath::parse("camera.size").expect("valid path"),
            value: toml::Value::Array(vec![(w as i64).into(), (h as i64).into()]),
        });
    }
    extra
}

/// How each kind is made: the one match on a figure's body, so a new kind is not missed.
enum Drawing<'a> {
    /// lobe: the materials, their legend entries, the angles of incidence, and what else is drawn.
    Lobe(&'a [String], &'a [String], &'a [f64], charts::LobeOptions),
    /// lobe of `lights`: the spot lights' indices.
    Distribution(&'a [usize]),
    /// albedo: the materials and their legend entries.
    Albedo(&'a [String], &'a [String]),
    /// cost: the ladder and the timed runs per rung.
    Cost(LadderKind, usize),
    /// convergence: the radiosity solvers and the tolerance they run to.
    Convergence(&'a [Solver], Option<f32>),
    /// probe: the pixels explained, and the key varied across its panels.
    Probe(&'a [(u32, u32)], Option<&'a crate::lesson::figure::Axis>),
    /// walk: the slab and the number of walks.
    Walk(crate::transport::slab::Slab, u32),
    /// bsdf: the index, the roughnesses and the angle of incidence.
    Bsdf(f64, &'a [f64], f64),
    /// bssrdf: the subsurface material.
    Bssrdf(&'a str),
    /// compare, sweep, grid, split: what the cells vary, the layers each shows, the normals over them.
    Cells(variants::Layout<'a>, &'a [Layer], Option<Normals>),
}

/// What `spec`'s body asks for.
fn drawing(spec: &FigureSpec) -> Drawing<'_> {
    match &spec.body {
        FigureBody::Compare { cols, layer, normals } | FigureBody::Sweep { cols, layer, normals } => {
            Drawing::Cells(variants::Layout::Row(cols), std::slice::from_ref(layer), *normals)
        }
        FigureBody::Grid { rows, cols, layer, normals } => {
            Drawing::Cells(variants::Layout::Grid(rows, cols), std::slice::from_ref(layer), *normals)
        }
        FigureBody::Split { layers, normals } => Drawing::Cells(variants::Layout::Split(layers), layers, *normals),
        FigureBody::Lobe { materials, legend, incidence, azimuth, swap, terms } => {
            Drawing::Lobe(materials, legend, incidence, charts::LobeOptions { swap: *swap, terms: terms.clone(), azimuth: azimuth.clone() })
        }
        FigureBody::Distribution { lights } => Drawing::Distribution(lights),
        FigureBody::Albedo { materials, legend } => Drawing::Albedo(materials, legend),
        FigureBody::Cost { ladder, repeat } => Drawing::Cost(*ladder, *repeat),
        FigureBody::Convergence { solvers, tolerance } => Drawing::Convergence(solvers, *tolerance),
        FigureBody::Probe { pixels, cols } => Drawing::Probe(pixels, cols.as_ref()),
        FigureBody::Walk { albedo, incidence, walks, thickness } => Drawing::Walk(
            crate::transport::slab::Slab { albedo: *albedo, cos_incidence: incidence.to_radians().cos(), thickness: *thickness },
            *walks,
        ),
        FigureBody::Bsdf { ior, roughness, incidence } => Drawing::Bsdf(*ior, roughness, *incidence),
        FigureBody::Bssrdf { material } => Drawing::Bssrdf(material),
    }
}

/// A `lobe` or `albedo` figure: the chart, with the caption under it.
fn chart_figure(spec: &FigureSpec, opts: &FigureOptions, chart: Result<plot::Chart, String>) -> Result<Figure, FigureError> {
    chart_row(spec, opts, None, vec![chart.map_err(FigureError::Chart)?])
}

/// A `walk` figure: the two charts of a slab's random walk side by side, under the title.
fn walk_figure(
    base: &Lesson,
    spec: &FigureSpec,
    slab: &crate::transport::slab::Slab,
    walks: u32,
    opts: &FigureOptions,
) -> Result<Figure, FigureError> {
    let charts = walk::walk_charts(slab, walks, base.lang).map_err(FigureError::Chart)?;
    side_by_side(spec, opts, base.lang.tr("A random walk in a slab: why diffuse light is coloured"), charts.directions, charts.colour)
}

/// A `bssrdf` figure: the material's radial exit profile (the validator checked it walks).
fn bssrdf_figure(base: &Lesson, spec: &FigureSpec, name: &str, opts: &FigureOptions) -> Result<Figure, FigureError> {
    let p = match base.materials.iter().find(|m| m.name == name).and_then(|m| m.brdf()) {
        Some(Brdf::Principled(p)) if p.walks() => *p,
        _ => return Err(FigureError::Chart(format!("figure `{}`: `{name}` has no subsurface walk", spec.name))),
    };
    let (chart, _) = bssrdf::bssrdf_chart(p.base_color, p.subsurface_radius * p.subsurface_scale, base.lang).map_err(FigureError::Chart)?;
    chart_row(spec, opts, Some(spec.title.clone().unwrap_or_else(|| base.title.clone())), vec![chart])
}

/// Two charts side by side under the figure's title (`default` when it has none) and above its caption.
fn side_by_side(
    spec: &FigureSpec,
    opts: &FigureOptions,
    default: &str,
    left: plot::Chart,
    right: plot::Chart,
) -> Result<Figure, FigureError> {
    let title = spec.title.clone().unwrap_or_else(|| default.to_string());
    chart_row(spec, opts, Some(title), vec![left, right])
}

/// Charts in one row, under `title` (if any) and above the figure's caption.
fn chart_row(spec: &FigureSpec, opts: &FigureOptions, title: Option<String>, charts: Vec<plot::Chart>) -> Result<Figure, FigureError> {
    let row: Vec<Cell> = charts.into_iter().map(|c| Cell::new(image::DynamicImage::ImageRgb8(c.png).to_rgba8())).collect();
    let spec_grid = GridSpec { title, caption: spec.caption.clone(), theme: opts.theme, scale: opts.scale, ..GridSpec::default() };
    let composed = grid::compose(&[row], &spec_grid);
    Ok(Figure {
        image: composed.image,
        stats: RenderStats::default(),
        rasterizations: 0,
        cached: 0,
        missing_glyphs: composed.missing_glyphs,
        kept: false,
    })
}

/// `plotted` with each entry named by its legend entry instead of its material's name.
fn relabel<T>(plotted: Vec<(String, T)>, legend: &[String]) -> Vec<(String, T)> {
    plotted.into_iter().zip(legend).map(|((_, m), l)| (l.clone(), m)).collect()
}

/// The named materials of a lobe figure: physically based or classic.
fn lobe_materials(base: &Lesson, spec: &FigureSpec, materials: &[String]) -> Result<Vec<(String, charts::Plotted)>, FigureError> {
    materials
        .iter()
        .map(|name| match base.materials.iter().find(|m| &m.name == name).map(|m| &m.model) {
            Some(Model::Physical(b)) => Ok((name.clone(), charts::Plotted::Brdf(*b))),
            Some(Model::Classic(c)) => Ok((name.clone(), charts::Plotted::Classic(*c))),
            Some(Model::Mirror(_)) => Err(FigureError::Chart(format!(
                "{}: figure `{}`: `{name}` is a mirror, whose BRDF is a Dirac delta with no lobe to draw",
                base.path.display(),
                spec.name
            ))),
            Some(Model::Glass(_)) => Err(FigureError::Chart(format!(
                "{}: figure `{}`: `{name}` is glass, whose BSDF is two Dirac deltas with no lobe to draw",
                base.path.display(),
                spec.name
            ))),
            None => Err(FigureError::Chart(format!(
                "{}: figure `{}`: `{name}` is not a material of this lesson",
                base.path.display(),
                spec.name
            ))),
        })
        .collect()
}

/// The spot lights of a distribution figure, each labelled by its law as the course writes
/// it (`cos θ`, `cos⁸ θ`, `measured profile`); the light's number only tells apart two
/// lights of the same law.
fn spot_lights(base: &Lesson, spec: &FigureSpec, lights: &[usize]) -> Result<Vec<(String, LightKind)>, FigureError> {
    let law = |kind: &LightKind| match kind {
        LightKind::Spot(Spot { profile: Some(_), .. }) => base.lang.tr("measured profile").to_string(),
        LightKind::Spot(Spot { exponent, .. }) if *exponent == 1.0 => "cos θ".to_string(),
        LightKind::Spot(Spot { exponent, .. }) => text::to_plain_text(&format!("cos^{{{exponent}}} θ")),
        _ => String::new(),
    };
    let kinds: Vec<Option<LightKind>> = lights.iter().map(|&i| base.scene.lights.get(i).map(|l| Light::from_spec(l).kind)).collect();
    let laws: Vec<String> = kinds.iter().map(|k| k.as_ref().map(law).unwrap_or_default()).collect();
    lights
        .iter()
        .zip(kinds)
        .enumerate()
        .map(|(n, (&i, kind))| match kind {
            Some(kind @ LightKind::Spot(_)) => {
                let shared = laws.iter().filter(|l| **l == laws[n]).count() > 1;
                let label = if shared { format!("{} (light {i})", laws[n]) } else { laws[n].clone() };
                Ok((label, kind))
            }
            found => Err(FigureError::Chart(format!(
                "{}: figure `{}`: light {i} is {} (a `lobe` figure of `lights` plots spot lights)",
                base.path.display(),
                spec.name,
                match found {
                    Some(k) => format!("a `{}` light", k.light_type().name()),
                    None => format!("not a light of this lesson ({} defined)", base.scene.lights.len()),
                }
            ))),
        })
        .collect()
}

/// The named materials of an albedo figure, each physically based.
fn chart_materials(base: &Lesson, spec: &FigureSpec, materials: &[String]) -> Result<Vec<(String, Brdf)>, FigureError> {
    materials
        .iter()
        .map(|name| {
            let m = base.materials.iter().find(|m| &m.name == name);
            match m.and_then(|m| m.brdf().copied()) {
                Some(b) => Ok((name.clone(), b)),
                None => Err(FigureError::Chart(format!(
                    "{}: figure `{}`: `{name}` is {} (lobe and albedo figures plot physically based materials)",
                    base.path.display(),
                    spec.name,
                    if m.is_some() { "a classic material" } else { "not a material of this lesson" }
                ))),
            }
        })
        .collect()
}

/// The time budget of a cost figure's rung, in milliseconds: past it, three timed runs (or
/// two that agree, [`crate::cost::timing::AGREE`]).
pub const FIGURE_BUDGET_MS: f64 = 1000.0;

/// A `cost` figure: the ladder measured on the lesson (at the cell size, if one is set),
/// as a strip of renders over error heatmaps; with the error–time chart under it when timed.
/// The measured ladder comes back too (its table and chart for `shadelab site`, which
/// draws the chart itself: `with_chart` false).
///
/// # Errors
/// [`FigureError`] as [`render_figure`].
pub fn cost_figure(
    base: &Lesson,
    spec: &FigureSpec,
    kind: LadderKind,
    repeat: usize,
    opts: &FigureOptions,
    with_chart: bool,
) -> Result<(Figure, crate::cost::LadderReport), FigureError> {
    let lesson = cost_lesson(base, spec, opts)?;
    if let Ok(rungs) = crate::cost::ladder::rungs(kind, &lesson) {
        check_strip(base, spec, &lesson, rungs.len())?;
    }
    // No warm-up: the median sets a cold first run aside. A rung's runs stop when two agree
    // to 2%, or at three once they took FIGURE_BUDGET_MS (the figure says how many ran).
    let cost_opts =
        crate::cost::CostOptions { repeat, warmup: 0, timed: opts.measure_time, budget_ms: Some(FIGURE_BUDGET_MS), ..Default::default() };
    let report = crate::cost::measure(&lesson, kind, &cost_opts, &mut |_| {})?;
    let title = spec.title.clone().unwrap_or_else(|| match base.lang {
        crate::lesson::i18n::Lang::En => format!("What accuracy costs: the {} ladder", text::escape(kind.name())),
        lang => format!("{}: {}", lang.tr("What accuracy costs"), text::escape(lang.tr(kind.name()))),
    });
    // A strip of many renders is wide: its text grows so that it still reads on a slide.
    let opts = &match opts.fit {
        Some(_) => *opts,
        None => {
            let cam = &lesson.scene.camera;
            let wide = report.rungs.len() as u32 * (cam.width + 12) + 150;
            FigureOptions { scale: opts.scale * fit::wide_text_scale(wide), ..*opts }
        }
    };
    let strip = cost::strip(&lesson, &report, opts, opts.measure_time, Some(&title));
    let mut fig = strip;
    if opts.measure_time && with_chart {
        let chart =
            cost::chart(&report, &format!("{}: error against time", kind.name()), opts.scale, base.lang).map_err(FigureError::Chart)?;
        fig.image = stack(&fig.image, &image::DynamicImage::ImageRgb8(chart.png).to_rgba8(), opts.theme);
    }
    if let Some(caption) = &spec.caption {
        let g = GridSpec { caption: Some(caption.clone()), theme: opts.theme, scale: opts.scale, ..GridSpec::default() };
        let composed = grid::compose(&[vec![Cell::new(fig.image)]], &g);
        fig.image = composed.image;
        fig.missing_glyphs.extend(composed.missing_glyphs);
    }
    Ok((fig, report))
}

/// The lesson a cost figure measures: the base with the figure's cell size, if any.
fn cost_lesson(base: &Lesson, spec: &FigureSpec, opts: &FigureOptions) -> Result<Lesson, FigureError> {
    let extra = cell_overrides(spec, opts);
    if extra.is_empty() {
        return Ok(base.clone());
    }
    let sets: Vec<Override> = base.overrides.iter().cloned().chain(extra).collect();
    Ok(crate::lesson::parse(&base.source, &base.path, &sets)?)
}

/// Refuses a figure whose cells (or a cost strip's renders and heatmaps) hold more than
/// [`MAX_FIGURE_PIXELS`] pixels together, before any of them is rendered.
fn check_pixels(base: &Lesson, spec: &FigureSpec, cells: u64, (w, h): (u32, u32), what: &str) -> Result<(), FigureError> {
    let total = cells * w as u64 * h as u64;
    if total <= MAX_FIGURE_PIXELS {
        return Ok(());
    }
    Err(FigureError::Chart(format!(
        "{}: figure `{}`: {cells} {what} of {w}×{h} pixels is {total} pixels, more than the limit of {MAX_FIGURE_PIXELS} for a figure\n  hint: use a smaller `cell` (or --cell) or fewer values (docs/lesson-format.md, Limits)",
        base.path.display(),
        spec.name
    )))
}

/// The cells of an expanded figure: one per variant and layer.
fn check_grid(base: &Lesson, spec: &FigureSpec, g: &variants::Grid, layers: usize) -> Result<(), FigureError> {
    let Some(first) = g.variants.first() else { return Ok(()) };
    let size = (first.lesson.scene.camera.width, first.lesson.scene.camera.height);
    // Cells may differ in size only if a value varies `camera.size`: count the largest.
    let largest =
        g.variants.iter().map(|v| (v.lesson.scene.camera.width, v.lesson.scene.camera.height)).max_by_key(|(w, h)| *w as u64 * *h as u64);
    check_pixels(base, spec, (g.variants.len() * layers) as u64, largest.unwrap_or(size), "cells")
}

/// A cost strip: a render and an error heatmap per rung, each of the lesson's size.
fn check_strip(base: &Lesson, spec: &FigureSpec, lesson: &Lesson, rungs: usize) -> Result<(), FigureError> {
    check_pixels(base, spec, 2 * rungs as u64, (lesson.scene.camera.width, lesson.scene.camera.height), "renders and heatmaps")
}

/// `top` above `bottom`, each centred, on the theme's background.
fn stack(top: &image::RgbaImage, bottom: &image::RgbaImage, theme: Theme) -> image::RgbaImage {
    let w = top.width().max(bottom.width());
    let mut out = image::RgbaImage::from_pixel(w, top.height() + bottom.height(), theme.background());
    image::imageops::overlay(&mut out, top, ((w - top.width()) / 2) as i64, 0);
    image::imageops::overlay(&mut out, bottom, ((w - bottom.width()) / 2) as i64, top.height() as i64);
    out
}

/// Validates every cell of a figure without rendering (so a command can check all its
/// figures before writing any file).
///
/// # Errors
/// [`FigureError`] as [`render_figure`], except for mesh loading.
pub fn check_figure(base: &Lesson, spec: &FigureSpec, opts: &FigureOptions) -> Result<(), FigureError> {
    match drawing(spec) {
        Drawing::Lobe(materials, ..) => lobe_materials(base, spec, materials).map(|_| ()),
        Drawing::Distribution(lights) => spot_lights(base, spec, lights).map(|_| ()),
        Drawing::Albedo(materials, _) => chart_materials(base, spec, materials).map(|_| ()),
        Drawing::Cost(kind, _) => {
            let lesson = cost_lesson(base, spec, opts)?;
            let rungs = crate::cost::ladder::rungs(kind, &lesson).map_err(|why| {
                FigureError::Cost(crate::cost::CostError::Ladder { file: base.path.display().to_string(), ladder: kind.name(), why })
            })?;
            check_strip(base, spec, &lesson, rungs.len())
        }
        Drawing::Cells(layout, layers, _) => {
            let g = variants::expand(base, layout, &cell_overrides(spec, opts))?;
            check_grid(base, spec, &g, layers.len())
        }
        // The patch limit was checked with the lesson.
        Drawing::Convergence(..) => needs_radiosity(base, spec),
        // The walk's keys were checked with the lesson; it reads nothing else.
        Drawing::Walk(..) | Drawing::Bsdf(..) | Drawing::Bssrdf(..) => Ok(()),
        // The pixels were checked against the camera with the lesson.
        Drawing::Probe(_, None) => Ok(()),
        Drawing::Probe(_, Some(cols)) => variants::expand(base, variants::Layout::Row(cols), &[]).map(|_| ()).map_err(Into::into),
    }
}

/// A `convergence` figure: the lesson's radiosity system solved by each solver, its residual
/// drawn against the iteration.
fn convergence_figure(
    base: &Lesson,
    spec: &FigureSpec,
    solvers: &[Solver],
    tolerance: Option<f32>,
    opts: &FigureOptions,
) -> Result<Figure, FigureError> {
    needs_radiosity(base, spec)?;
    let scene = build(base)?;
    // The form factors and solves are a render's radiosity pass (once per solver after that).
    render::budget::check(&scene).map_err(|e| e.at(format!("{}: figure `{}`", base.path.display(), spec.name)))?;
    let c = crate::effects::radiosity::convergence(&scene, solvers, tolerance);
    let tolerance = tolerance.unwrap_or(scene.spec.settings.radiosity.tolerance);
    let series: Vec<plot::Series> = c
        .runs
        .iter()
        .map(|(solver, sol, _)| plot::Series {
            label: format!("{}: {} iterations", solver_label(*solver), sol.iterations),
            points: sol.residuals.iter().enumerate().map(|(k, r)| (k as f64, *r as f64)).collect(),
        })
        .collect();
    let note = format!(
        "{} patches, {} non-zero form factors; residual Σ A|E + ρFL − L| / Σ A L after each iteration (0: L = E)",
        c.patches, c.form_factors
    );
    let title = spec.title.as_deref().unwrap_or("Radiosity solvers: residual against iteration");
    chart_figure(spec, opts, plot::convergence_chart(&series, tolerance as f64, title, Some(&note), (900, 520), base.lang))
}

/// Refuses a `convergence` figure of a lesson that does not render by radiosity.
fn needs_radiosity(base: &Lesson, spec: &FigureSpec) -> Result<(), FigureError> {
    if base.scene.settings.method == crate::lesson::settings::RenderMethod::Radiosity {
        return Ok(());
    }
    Err(FigureError::Chart(format!(
        "{}: figure `{}`: a `convergence` figure plots the radiosity solvers, but this lesson renders with `method = \"raster\"`\n  hint: set `[render] method = \"radiosity\"` (and give a surface `emission`), or drop the figure",
        base.path.display(),
        spec.name
    )))
}

/// A solver's name in a chart's legend.
fn solver_label(s: Solver) -> &'static str {
    match s {
        Solver::Jacobi => "Jacobi",
        Solver::GaussSeidel => "Gauss-Seidel",
        Solver::Progressive => "progressive refinement",
    }
}

/// Renders one figure of a lesson.
///
/// # Errors
/// [`FigureError`] when a variant does not validate or a mesh cannot be loaded.
pub fn render_figure(base: &Lesson, spec: &FigureSpec, opts: &FigureOptions) -> Result<Figure, FigureError> {
    kept::figure(base, spec, opts, shows_times(spec, opts), || fitted_figure(base, spec, opts))
}

/// True when the figure shows times measured as it is drawn (a cost figure's timings, or
/// `--timings`), which the cache keeps only for the machine that measured them.
pub fn shows_times(spec: &FigureSpec, opts: &FigureOptions) -> bool {
    opts.timings || (opts.measure_time && matches!(drawing(spec), Drawing::Cost(..)))
}

/// [`render_figure`] without the cache: drawn, and put on its slide when it has one.
fn fitted_figure(base: &Lesson, spec: &FigureSpec, opts: &FigureOptions) -> Result<Figure, FigureError> {
    let Some(slide) = opts.fit.or(spec.fit) else { return draw_figure(base, spec, opts) };
    // The slide sets the text size; the cells' size is chosen in `draw_figure`.
    let opts = FigureOptions { scale: fit::text_scale(slide), fit: Some(slide), ..*opts };
    let mut figure = draw_figure(base, spec, &opts)?;
    figure.image = fit::on_slide(figure.image, slide, opts.theme.background());
    Ok(figure)
}

/// [`render_figure`] before the figure is put on its slide.
fn draw_figure(base: &Lesson, spec: &FigureSpec, opts: &FigureOptions) -> Result<Figure, FigureError> {
    let (layout, layers, normals) = match drawing(spec) {
        Drawing::Lobe(materials, legend, incidence, lobe) => {
            let title = spec.title.as_deref().unwrap_or(base.lang.tr("BRDF lobe: f·cos θₒ in the plane of incidence"));
            let plotted = relabel(lobe_materials(base, spec, materials)?, legend);
            return chart_figure(spec, opts, charts::lobe_chart_of(&plotted, incidence, &lobe, title, base.lang));
        }
        Drawing::Distribution(lights) => {
            let title = spec.title.as_deref().unwrap_or(base.lang.tr("Spot distribution: C_spot(θ) from the spot's axis"));
            let spots = spot_lights(base, spec, lights)?;
            return chart_figure(spec, opts, charts::distribution_chart(&spots, title, base.lang));
        }
        Drawing::Albedo(materials, legend) => {
            let title = spec.title.as_deref().unwrap_or(base.lang.tr("Directional albedo (white furnace)"));
            let brdfs = relabel(chart_materials(base, spec, materials)?, legend);
            return chart_figure(spec, opts, charts::albedo_chart(&brdfs, ALBEDO_SAMPLES, title, base.lang));
        }
        Drawing::Cost(kind, repeat) => return cost_figure(base, spec, kind, repeat, opts, opts.measure_time).map(|(fig, _)| fig),
        Drawing::Convergence(solvers, tolerance) => return convergence_figure(base, spec, solvers, tolerance, opts),
        Drawing::Probe(pixels, cols) => return probe::probe_figure(base, spec, pixels, cols, opts),
        Drawing::Walk(slab, walks) => return walk_figure(base, spec, &slab, walks, opts),
        Drawing::Bsdf(ior, roughness, incidence) => {
            let charts = bsdf::bsdf_charts(ior, roughness, incidence, base.lang).map_err(FigureError::Chart)?;
            let title = base.lang.tr("A rough dielectric: the BSDF as BRDF plus BTDF (Walter et al. 2007)");
            return side_by_side(spec, opts, title, charts.lobes, charts.split);
        }
        Drawing::Bssrdf(name) => return bssrdf_figure(base, spec, name, opts),
        Drawing::Cells(layout, layers, normals) => (layout, layers, normals),
    };
    let mut g = variants::expand(base, layout, &cell_overrides(spec, opts))?;
    let title = spec.title.clone().unwrap_or_else(|| base.title.clone());
    let mut spec_grid = GridSpec {
        title: Some(title),
        caption: spec.caption.clone(),
        col_labels: g.col_labels.clone(),
        theme: opts.theme,
        scale: opts.scale,
        show_timings: opts.timings,
        wrap_labels: opts.fit.is_some(),
        ..GridSpec::default()
    };
    let mut arrangement = None;
    if let Some(slide) = opts.fit {
        let first = &g.variants.first().map_or(&base.scene.camera, |v| &v.lesson.scene.camera);
        let aspect = first.height as f32 / first.width.max(1) as f32;
        let mut proto = GridSpec { row_labels: g.row_labels.clone(), ..spec_grid.clone() };
        let rows = if spec.diff {
            // The difference row and its colour bar, with a stand-in scale.
            proto.row_labels = vec![base.lang.tr("render").into(), base.lang.tr("|difference|").into()];
            let label = base.lang.say(&format!("|difference| from the first cell, {} layer", layers[0].name()));
            let bar = colorbar::ColorBar::heat(label, "0", "8.8e-8");
            proto.colorbar = Some(bar);
            g.rows + 1
        } else {
            if let Some(vb) = &spec.colorbar {
                // A value bar's place, with stand-in values as wide as real ones.
                let ticks = [0.25, 0.5, 0.75].map(|t| (t, "0.00".to_string())).to_vec();
                proto.colorbar = Some(colorbar::ColorBar { ticks, ..colorbar::ColorBar::heat(vb.label.clone(), "0", "0.00") });
            }
            g.rows
        };
        // The longest line under a cell: a timing, or the difference row's note.
        let under = match (opts.timings, spec.diff) {
            (true, true) => Some("000 ms · the reference"),
            (true, false) => Some("000 ms"),
            (false, true) => Some("the reference"),
            (false, false) => None,
        };
        let a = fit::arrange(rows, g.cols, !spec.diff, aspect, slide, &proto, under);
        g = variants::expand(base, layout, &cell_overrides(spec, &FigureOptions { cell: Some(a.cell), ..*opts }))?;
        arrangement = Some(a);
    }
    check_grid(base, spec, &g, layers.len())?;
    let transparent = opts.theme == Theme::Transparent;
    let mut stats = RenderStats::default();
    let mut rasterizations = 0;
    let mut cached = 0;
    let mut memo: Option<(crate::scene::Scene, VisBuffer)> = None;
    let mut cells: Vec<Vec<Cell>> = vec![Vec::with_capacity(g.cols); g.rows];
    // The frames a difference row compares (compare and sweep: one row, one layer).
    let mut frames = Vec::new();
    // A value bar's top, when the tone map never saturates: the cells' largest value.
    let mut largest = 0.0f32;
    // A cell's frame may come from the on-disk cache unless its time or its raster is shown.
    let keep = !opts.timings && normals.is_none();
    let layers_part = render::cached::layers_part(layers);
    for v in &g.variants {
        let start = Instant::now();
        let mut draw = || -> Result<Frame, FigureError> {
            let scene = build(&v.lesson)?;
            let sets: Vec<&str> = v.sets.iter().map(|o| o.arg.as_str()).collect();
            let at = || format!("{}: figure `{}`, the cell {}", v.lesson.path.display(), spec.name, sets.join(" "));
            render::budget::check(&scene).map_err(|e| e.at(at()))?;
            // Reuse the visibility buffer when only shading inputs changed.
            let reuse = matches!(&memo, Some((s, _)) if render::same_raster(s, &scene));
            if !reuse {
                let vis = render::rasterize(&scene);
                stats.raster += vis.stats;
                memo = Some((scene.clone(), vis));
                rasterizations += 1;
            }
            let (_, vis) = memo.as_ref().expect("filled above");
            let (frame, st) = render::render_with(&scene, layers, Some(vis));
            stats += &st;
            Ok(frame)
        };
        let (frame, hit) = if keep { render::cached::frame(&v.lesson, "cell", &[&layers_part], draw)? } else { (draw()?, false) };
        cached += usize::from(hit);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let settings = &v.lesson.scene.settings;
        for layer in layers {
            let rgba =
                render::develop::develop_rgba(&frame, *layer, settings.exposure, settings.tonemap, transparent).expect("layer is kept");
            let mut image = image::RgbaImage::from_raw(frame.width, frame.height, rgba).expect("size matches");
            if let (Some(which), Some((scene, vis))) = (normals, &memo) {
                // Drawn on the raster it was rendered from (same geometry and camera).
                overlay::draw_normals(&mut image, scene, vis, which);
            }
            cells[v.row].push(Cell { image, time_ms: Some(ms), note: None });
        }
        if spec.colorbar.is_some() {
            let px = frame.layer(layers[0]).expect("layer is kept");
            largest = px.iter().map(|c| c.max_element()).filter(|v| v.is_finite()).fold(largest, f32::max);
        }
        if spec.diff {
            frames.push(frame);
        }
    }
    let mut row_labels = g.row_labels;
    let colorbar = if spec.diff && g.rows == 1 && !frames.is_empty() {
        let (row, bar) = diff::row(&frames, layers[0], base.lang);
        cells.push(row);
        row_labels = vec![
            if row_labels.first().is_some_and(|l| !l.is_empty()) { row_labels[0].clone() } else { base.lang.tr("render").into() },
            base.lang.tr("|difference|").into(),
        ];
        Some(bar)
    } else {
        spec.colorbar.as_ref().zip(g.variants.first()).map(|(bar, v)| {
            let s = &v.lesson.scene.settings;
            colorbar::value_bar(bar, layers[0], s.exposure, s.tonemap, largest)
        })
    };
    spec_grid.row_labels = row_labels;
    spec_grid.colorbar = colorbar;
    if let Some(a) = arrangement.filter(|a| a.rows > 1 && g.rows == 1 && cells.len() == 1) {
        // Reflowed onto several rows: each row's labels go above it.
        let row = cells.pop().expect("one row");
        cells = row.chunks(a.cols).map(<[Cell]>::to_vec).collect();
        spec_grid.cell_labels = spec_grid.col_labels.chunks(a.cols).map(<[String]>::to_vec).collect();
        spec_grid.col_labels.clear();
        spec_grid.row_labels.clear();
    }
    let composed = grid::compose(&cells, &spec_grid);
    Ok(Figure { image: composed.image, stats, rasterizations, cached, missing_glyphs: composed.missing_glyphs, kept: false })
}
