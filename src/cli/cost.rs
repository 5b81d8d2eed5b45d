//! `shadelab cost`: what each approximation costs in time and buys in accuracy.

use super::CliError;
use super::progress::Progress;
use crate::cost::{CostOptions, LadderReport, measure};
use crate::figure::{self, FigureOptions};
use crate::lesson::LadderKind;
use std::path::PathBuf;

/// Arguments of `shadelab cost`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Each rung is timed as scene build + render (median of --repeat runs after --warmup), and compared \
with the reference: the exact ray cast when every object is a sphere or plane (sampled like the rungs; 16×16 for the aa \
ladder), else the ladder's finest rung; the shadow ladders (shadow_map, pcf, shadow_bias) against the lesson's ray-cast \
shadows, area_samples against the exact rect-light irradiance (or 4096 samples when something can block the light). \
See docs/accuracy-and-cost.md.

Examples:
  Flat, Gouraud, Phong and exact normals, timed and compared with the ray-cast sphere:
    shadelab cost lessons/15-cost.toml --ladder interpolation --size 128x128
  The shadow-map sizes, with a chart and an image strip per ladder in out/:
    shadelab cost lessons/17-shadow-map-artefacts.toml --ladder shadow_map --size 128x128 -o out/
  Supersampling as CSV for a spreadsheet:
    shadelab cost lessons/15-cost.toml --ladder aa --size 64x64 --format csv > aa.csv")]
pub struct CostArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    /// Ladders to run, comma-separated or repeated (default: every ladder that applies).
    #[arg(long, value_enum, value_delimiter = ',', value_name = "LADDER")]
    pub ladder: Vec<LadderArg>,
    /// Timed runs per rung.
    #[arg(long, default_value_t = 5, value_name = "N")]
    pub repeat: usize,
    /// Untimed runs per rung before the timed ones.
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub warmup: usize,
    /// Samples per pixel side of the exact ray cast (default: the rungs' own, 16 for the aa ladder); a
    /// reference a ladder names (shadow and area ladders) is sampled like its rungs.
    #[arg(long, value_name = "N")]
    pub reference_aa: Option<u32>,
    /// Text format of the results on stdout.
    #[arg(long, value_enum, default_value = "table")]
    pub format: CostFormat,
    /// Folder for each ladder's chart (PNG and SVG) and image strip (renders over error
    /// heatmaps), created if needed [default: none, only the results on stdout].
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub set: super::SetArgs,
    /// Image size in pixels, e.g. 256x256 (same as --set camera.size=[W,H]).
    #[arg(long, value_name = "WxH", value_parser = super::parse_size)]
    pub size: Option<(u32, u32)>,
}

/// `--ladder` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum LadderArg {
    /// flat → Gouraud → Phong → exact normals.
    Interpolation,
    /// The first object's mesh, coarse → fine.
    Tessellation,
    /// Supersamples per pixel side: 1, 2, 4, 8.
    Aa,
    /// Schlick's approximation → the exact dielectric Fresnel.
    Fresnel,
    /// Shadow-map size 256 … 4096 texels a side, against ray-cast shadows.
    #[value(name = "shadow_map")]
    ShadowMap,
    /// Shadow-map filter width 1, 3, 5, 9 texels, against ray-cast shadows.
    Pcf,
    /// Samples per area light 1 … 256, by area and by solid angle, against the exact rect-light irradiance or 4096 samples.
    #[value(name = "area_samples")]
    AreaSamples,
    /// Independent, stratified and Sobol samples at 4, 16, 64 per light, against the same reference.
    Sampler,
    /// Shadow-map depth bias 0 … 0.5, against ray-cast shadows: acne, then peter-panning.
    #[value(name = "shadow_bias")]
    ShadowBias,
    /// Screen-space (scanline) → perspective-correct interpolation.
    #[value(name = "interpolation_space")]
    InterpolationSpace,
    /// Normals transformed by W (the mistake) → by (W⁻¹)ᵀ.
    #[value(name = "normal_transform")]
    NormalTransform,
    /// Fog samples per eye ray 4 → 256, uniform and equiangular, against 1024 equiangular.
    #[value(name = "fog_steps")]
    FogSteps,
    /// Image-based lighting: SH, prefiltered, reference, against the reference at 2048 samples.
    Ibl,
    /// Environment samples 16 … 4096, against 16384.
    #[value(name = "env_samples")]
    EnvSamples,
    /// Prefiltered map width 32 … 512, against the Monte Carlo reference.
    #[value(name = "prefilter_size")]
    PrefilterSize,
    /// Radiosity patch size 1.0 … 0.2, against 0.14.
    Patches,
    /// Radiosity hemicube resolution 8 … 64, against 256.
    Hemicube,
    /// Jacobi iterations (bounces) 0 … 16, against the converged solution.
    Iterations,
    /// Texture filtering: nearest, bilinear, trilinear, against bilinear at 8 × 8 samples a pixel.
    #[value(name = "texture_filter")]
    TextureFilter,
    /// Glass: ray bounces 1 … 8, against 16.
    #[value(name = "max_bounces")]
    MaxBounces,
    /// Path tracer: paths a pixel sample 1 … 256, against 4096.
    Spp,
    /// Path tracer: the longest path 1 … 8 segments, against 64.
    #[value(name = "max_depth")]
    MaxDepth,
    /// Shadow rays, map, volumes and polygons as the spheres and tori get finer, against rays.
    #[value(name = "shadow_methods")]
    ShadowMethods,
}

impl LadderArg {
    fn kind(self) -> LadderKind {
        match self {
            LadderArg::Interpolation => LadderKind::Interpolation,
            LadderArg::Tessellation => LadderKind::Tessellation,
            LadderArg::Aa => LadderKind::Aa,
            LadderArg::Fresnel => LadderKind::Fresnel,
            LadderArg::ShadowMap => LadderKind::ShadowMap,
            LadderArg::Pcf => LadderKind::Pcf,
            LadderArg::AreaSamples => LadderKind::AreaSamples,
            LadderArg::Sampler => LadderKind::Sampler,
            LadderArg::ShadowBias => LadderKind::ShadowBias,
            LadderArg::InterpolationSpace => LadderKind::InterpolationSpace,
            LadderArg::NormalTransform => LadderKind::NormalTransform,
            LadderArg::FogSteps => LadderKind::FogSteps,
            LadderArg::Ibl => LadderKind::Ibl,
            LadderArg::EnvSamples => LadderKind::EnvSamples,
            LadderArg::PrefilterSize => LadderKind::PrefilterSize,
            LadderArg::Patches => LadderKind::Patches,
            LadderArg::Hemicube => LadderKind::Hemicube,
            LadderArg::Iterations => LadderKind::Iterations,
            LadderArg::TextureFilter => LadderKind::TextureFilter,
            LadderArg::MaxBounces => LadderKind::MaxBounces,
            LadderArg::Spp => LadderKind::Spp,
            LadderArg::MaxDepth => LadderKind::MaxDepth,
            LadderArg::ShadowMethods => LadderKind::ShadowMethods,
        }
    }
}

/// `--format` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CostFormat {
    /// A table per ladder, for people.
    Table,
    /// One header line, then one line per rung.
    Csv,
    /// JSON Lines: one JSON object per rung, one per line (`json` is an old name of it).
    #[value(alias = "json")]
    Jsonl,
}

/// The CSV columns, in order.
const CSV_HEADER: &str = "ladder,rung,triangles,median_ms,min_ms,max_ms,runs,threads,rmse,max_err,psnr,visible_pct,pareto,is_reference";

/// Runs the ladders and prints (and writes) the results.
pub fn run(args: CostArgs, quiet: bool) -> Result<(), CliError> {
    if !(1..=1000).contains(&args.repeat) {
        return Err(CliError::Input(format!("--repeat {}: give 1 to 1000", args.repeat)));
    }
    if args.warmup > 100 {
        return Err(CliError::Input(format!("--warmup {}: give 0 to 100", args.warmup)));
    }
    if let Some(n) = args.reference_aa
        && !(1..=crate::cost::reference::MAX_SAMPLES_PER_SIDE).contains(&n)
    {
        return Err(CliError::Input(format!("--reference-aa {n}: give 1 to {}", crate::cost::reference::MAX_SAMPLES_PER_SIDE)));
    }
    let extra = args.size.map(|(w, h)| vec![format!("camera.size=[{w}, {h}]")]).unwrap_or_default();
    let sets = super::overrides(&args.set.sets, extra)?;
    if let Some(dir) = &args.output {
        crate::output::check_folder(dir, dir)?;
    }
    let lesson = crate::lesson::load(&args.lesson, &sets)?;

    // Named ladders must apply; by default, every ladder that does.
    let ladders: Vec<LadderKind> = if args.ladder.is_empty() {
        let all: Vec<LadderKind> = LadderKind::ALL.into_iter().filter(|k| crate::cost::ladder::rungs(*k, &lesson).is_ok()).collect();
        for k in LadderKind::ALL.iter().filter(|k| !all.contains(k)) {
            if let Err(why) = crate::cost::ladder::rungs(*k, &lesson)
                && !quiet
            {
                super::out::eprint_line(format_args!("note: skipping the {} ladder: {why}", k.name()));
            }
        }
        all
    } else {
        let mut v: Vec<LadderKind> = args.ladder.iter().map(|l| l.kind()).collect();
        v.dedup();
        v
    };
    let opts = CostOptions { repeat: args.repeat, warmup: args.warmup, reference_aa: args.reference_aa, timed: true, budget_ms: None };

    if args.output.is_some() {
        // Each strip holds a render and a heatmap per rung: within the figure limit, checked first.
        let limit = crate::lesson::limits::MAX_FIGURE_PIXELS;
        let (w, h) = (lesson.scene.camera.width as u64, lesson.scene.camera.height as u64);
        for k in &ladders {
            let cells = 2 * crate::cost::ladder::rungs(*k, &lesson).map_or(0, |r| r.len()) as u64;
            if cells * w * h > limit {
                return Err(CliError::Input(format!(
                    "{}: the {} ladder's strip is {cells} images of {w}×{h} pixels, {} pixels, more than the limit of {limit}\n  hint: lower the size with --size (docs/lesson-format.md, Limits)",
                    args.lesson.display(),
                    k.name(),
                    cells * w * h
                )));
            }
        }
    }
    let total: usize = ladders.iter().map(|k| crate::cost::ladder::rungs(*k, &lesson).map_or(1, |r| r.len() + 1)).sum();
    // Drawn on stderr only when it is a terminal, and not under -q.
    let bar = Progress::new(total as u64, quiet);

    let stem = args.lesson.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "lesson".into());
    let (w, h) = (lesson.scene.camera.width, lesson.scene.camera.height);
    if args.format == CostFormat::Table && !quiet {
        outln!(
            "{} ({}): {w}×{h}, aa {}, {} threads, median of {} runs after {} warm-up\n",
            lesson.title,
            args.lesson.display(),
            lesson.scene.settings.aa,
            rayon::current_num_threads(),
            args.repeat,
            args.warmup
        )?;
    }
    if args.format == CostFormat::Csv && !quiet {
        outln!("{CSV_HEADER}")?;
    }
    let mut reports = Vec::new();
    for kind in ladders {
        let mut offset = bar.position();
        let report = measure(&lesson, kind, &opts, &mut |p| {
            bar.set(offset + p.done as u64);
            bar.message(format!("{}: {}", kind.name(), p.next));
        })
        .map_err(|e| CliError::Input(e.to_string()))?;
        offset += report.rungs.len() as u64 + 1;
        bar.set(offset);
        let text = match args.format {
            CostFormat::Table => table(&report, lesson.lang),
            CostFormat::Csv => csv(&report),
            CostFormat::Jsonl => json(&report),
        };
        if !quiet {
            bar.println(format_args!("{}", text.strip_suffix('\n').unwrap_or(&text)))?;
        }
        if let Some(w) = report.spread_warning() {
            super::out::eprint_line(format_args!("warning: {}: {w} (--repeat)", report.ladder.name()));
        }
        reports.push(report);
    }
    let elapsed = bar.finish();

    if let Some(dir) = &args.output {
        let look = FigureOptions::default();
        for report in &reports {
            let name = report.ladder.name();
            let chart = figure::cost::chart(
                report,
                &format!("{}: the {name} ladder, error against time", lesson.title),
                figure::fit::wide_text_scale(900),
                lesson.lang,
            )
            .map_err(CliError::Internal)?;
            let chart_png = dir.join(format!("{stem}-{name}-chart.png"));
            crate::output::write_png(&chart_png, chart.png.width(), chart.png.height(), chart.png.as_raw())?;
            crate::output::write_atomic(&chart_png.with_extension("svg"), |w| {
                w.write_all(chart.svg.as_bytes()).map_err(|e| e.to_string())
            })?;
            let strip = figure::cost::strip(&lesson, report, &look, true, None);
            let strip_png = dir.join(format!("{stem}-{name}-strip.png"));
            crate::output::write_png_rgba(&strip_png, &strip.image)?;
            if !quiet {
                super::out::eprint_line(format_args!("wrote {} (+ .svg) and {}", chart_png.display(), strip_png.display()));
            }
        }
    }
    let rungs: usize = reports.iter().map(|r| r.rungs.len()).sum();
    let (one, many) = (format!("ladder, {rungs} rungs"), format!("ladders, {rungs} rungs"));
    let line = super::progress::summary(reports.len(), &one, &many, elapsed, args.output.as_deref());
    // CSV and JSON Lines on stdout stay machine-readable: their summary goes to stderr.
    match args.format {
        CostFormat::Table => outln!("{line}"),
        CostFormat::Csv | CostFormat::Jsonl => {
            super::out::eprint_line(format_args!("{line}"));
            Ok(())
        }
    }
}

/// PSNR for a table or CSV cell.
fn psnr_cell(psnr: f64) -> String {
    crate::cost::metrics::format_psnr(psnr)
}

/// One ladder as a table.
fn table(r: &LadderReport, lang: crate::lesson::i18n::Lang) -> String {
    let front = r.pareto();
    let tr = |t| lang.tr(t);
    let cached = if r.reference_cached { " (read from the cache)" } else { "" };
    let mut s = format!("{} {}; {}: {}{cached}\n", r.ladder.name(), tr("ladder"), tr("reference"), r.reference.describe());
    s += &format!(
        "{:<16} {:>9} {:>9} {:>8} {:>8} {:>9} {:>9} {:>8} {:>9}  {}\n",
        tr("rung"),
        tr("triangles"),
        tr("median ms"),
        tr("min ms"),
        tr("max ms"),
        "RMSE",
        tr("max err"),
        "PSNR dB",
        tr("visible %"),
        tr("front")
    );
    for (i, x) in r.rungs.iter().enumerate() {
        let m = &x.metrics;
        s += &format!(
            "{:<16} {:>9} {:>9.2} {:>8.2} {:>8.2} {:>9.2e} {:>9.2e} {:>8} {:>9.2}  {}\n",
            x.name,
            if x.exact { "ray cast".to_string() } else { x.triangles.to_string() },
            x.timing.median_ms,
            x.timing.min_ms,
            x.timing.max_ms,
            m.rmse,
            m.max_err,
            psnr_cell(m.psnr),
            m.visible_pct,
            match (front.contains(&i), x.is_reference) {
                (_, true) => "reference",
                (true, false) => "*",
                (false, false) => "",
            }
        );
    }
    if r.rungs.iter().any(|x| x.metrics.psnr < 0.0) {
        // A negative PSNR is no quality: say what it means (an HDR reference, peak 1).
        s += crate::cost::metrics::NEGATIVE_PSNR;
        s.push('\n');
    }
    s.push('\n');
    s
}

/// One ladder as CSV rows (no header).
fn csv(r: &LadderReport) -> String {
    let front = r.pareto();
    let mut s = String::new();
    for (i, x) in r.rungs.iter().enumerate() {
        let m = &x.metrics;
        s += &format!(
            "{},{},{},{:.4},{:.4},{:.4},{},{},{:.6e},{:.6e},{},{:.4},{},{}\n",
            r.ladder.name(),
            x.name,
            x.triangles,
            x.timing.median_ms,
            x.timing.min_ms,
            x.timing.max_ms,
            x.timing.runs,
            r.threads,
            m.rmse,
            m.max_err,
            psnr_cell(m.psnr),
            m.visible_pct,
            front.contains(&i),
            x.is_reference
        );
    }
    s
}

/// One ladder as JSON lines: an object per rung (`psnr` is null for an exact match).
fn json(r: &LadderReport) -> String {
    let front = r.pareto();
    let mut s = String::new();
    for (i, x) in r.rungs.iter().enumerate() {
        let m = &x.metrics;
        let v = serde_json::json!({
            "ladder": r.ladder.name(),
            "rung": x.name,
            "triangles": x.triangles,
            "median_ms": x.timing.median_ms,
            "min_ms": x.timing.min_ms,
            "max_ms": x.timing.max_ms,
            "runs": x.timing.runs,
            "threads": r.threads,
            "rmse": m.rmse,
            "max_err": m.max_err,
            "psnr": if m.psnr.is_finite() { Some(m.psnr) } else { None },
            "visible_pct": m.visible_pct,
            "pareto": front.contains(&i),
            "is_reference": x.is_reference,
            "reference": r.reference.describe(),
        });
        s += &v.to_string();
        s.push('\n');
    }
    s
}
