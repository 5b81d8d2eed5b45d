//! Cost figures: a measured ladder as a strip (each rung's render above its error
//! heatmap) and as a chart of error against time with the Pareto front.

use super::colorbar::ColorBar;
use super::grid::{self, Cell, GridSpec};
use super::plot::{Chart, CostPoint, cost_chart};
use super::text::escape;
use super::{Figure, FigureOptions};
use crate::cost::metrics::{error_heatmap, pixel_errors, psnr_text, quantile};
use crate::cost::{LadderReport, ReferenceSource};
use crate::lesson::Lesson;
use crate::render::{Layer, RenderStats, develop::develop_rgba};
use image::{DynamicImage, RgbaImage};

/// Share of pixels the heatmap's top colour may saturate: the scale is the 99th
/// percentile of the errors over all rungs, so a few silhouette pixels (errors near 1)
/// do not turn every interior error black.
pub const HEAT_QUANTILE: f64 = 0.99;

/// The heatmap scale of a report: the [`HEAT_QUANTILE`] of every rung's per-pixel error,
/// at least 1e-4 (so an all-zero ladder still has a scale).
pub fn heat_scale(report: &LadderReport) -> f32 {
    let mut all = Vec::new();
    for r in report.rungs.iter().filter(|r| !r.is_reference) {
        if let Ok(e) = pixel_errors(&r.frame, &report.reference_frame, Layer::Total) {
            all.extend(e.into_iter().filter(|x| *x > 0.0));
        }
    }
    quantile(&all, HEAT_QUANTILE).max(1e-4)
}

/// A rung's name as figures show it, in the course's spelling (`Gouraud`, `Phong`, `Schlick`).
pub fn display_name(rung: &str) -> String {
    match rung {
        "gouraud" => "Gouraud".into(),
        "phong" => "Phong".into(),
        "schlick" => "Schlick".into(),
        "exact" => "exact".into(),
        other => other.into(),
    }
}

/// `1.2e-3`: an error for a label.
fn sci(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x:.1e}") }
}

/// The strip: one column per rung, its render on top and its error heatmap below, with
/// the time under the render (when `show_times`) and RMSE and PSNR under the heatmap.
pub fn strip(lesson: &Lesson, report: &LadderReport, opts: &FigureOptions, show_times: bool, title: Option<&str>) -> Figure {
    let scale = heat_scale(report);
    let (exposure, tonemap) = (lesson.scene.settings.exposure, lesson.scene.settings.tonemap);
    let mut renders = Vec::new();
    let mut heat = Vec::new();
    for r in &report.rungs {
        let rgba = develop_rgba(&r.frame, Layer::Total, exposure, tonemap, false).expect("rungs keep the total layer");
        let image = RgbaImage::from_raw(r.frame.width, r.frame.height, rgba).expect("size matches");
        let time = show_times.then_some(r.timing.median_ms);
        renders.push(Cell { image, time_ms: time, note: None });
        let map = error_heatmap(&r.frame, &report.reference_frame, Layer::Total, scale).expect("same size as the reference");
        let note = if r.is_reference {
            lesson.lang.tr("the reference").to_string()
        } else {
            format!("RMSE {} · PSNR {}", sci(r.metrics.rmse), psnr_text(r.metrics.psnr))
        };
        heat.push(Cell { image: DynamicImage::ImageRgb8(map).to_rgba8(), time_ms: None, note: Some(note) });
    }
    let lang = lesson.lang;
    let reference = match &report.reference {
        ReferenceSource::RayCast { samples_per_side: n } => format!("the exact ray cast ({n}×{n} samples a pixel)"),
        ReferenceSource::TopRung { rung } => format!("the finest rung, {rung}"),
        ReferenceSource::Rung { name, .. } => name.clone(),
    };
    // Sentence by sentence, each in the lesson's language (English: one space between them).
    let mut caption = lang.say(&format!(
        "Bottom: |error| against {reference}, black 0 → pale yellow ≥ {} (linear radiance, largest channel).",
        sci(scale as f64)
    ));
    let mut sentence = |s: String| {
        // Japanese sentences follow a 。 without a space.
        if !caption.ends_with('。') {
            caption.push(' ');
        }
        caption.push_str(&lang.say(&s));
    };
    if report.rungs.iter().any(|r| r.metrics.psnr < 0.0) {
        sentence(format!("{}.", crate::cost::metrics::NEGATIVE_PSNR));
    }
    if show_times {
        sentence(format!("Times: median of {} runs on {} threads (scene build + render).", report.runs_text(), report.threads));
        if let Some(w) = report.spread_warning() {
            sentence(format!("Note: {w}."));
        }
    }
    let spec = GridSpec {
        title: Some(
            title.map_or_else(|| lang.say(&format!("{}: the {} ladder", lesson.title, escape(report.ladder.name()))), str::to_string),
        ),
        caption: Some(caption),
        col_labels: report.rungs.iter().map(|r| escape(&lang.say(&display_name(&r.name)))).collect(),
        row_labels: vec![lang.tr("render").into(), lang.tr("error").into()],
        theme: opts.theme,
        scale: opts.scale,
        show_timings: show_times,
        colorbar: Some(ColorBar::heat(lang.tr("|error|, linear radiance"), "0", sci(scale as f64))),
        ..GridSpec::default()
    };
    let composed = grid::compose(&[renders, heat], &spec);
    let mut stats = RenderStats::default();
    for r in &report.rungs {
        stats += &r.stats;
    }
    Figure {
        image: composed.image,
        stats,
        rasterizations: report.rungs.iter().filter(|r| !r.exact).count(),
        cached: usize::from(report.reference_cached),
        missing_glyphs: composed.missing_glyphs,
        kept: false,
    }
}

/// The chart: RMSE against median time on log axes, one labelled point per rung, the
/// Pareto front joined; its bitmap and text `zoom`× the chart's own size.
///
/// # Errors
/// A message when the report was not timed (every time is zero) or plotters fails.
pub fn chart(report: &LadderReport, title: &str, zoom: f32, lang: crate::lesson::i18n::Lang) -> Result<Chart, String> {
    let front = report.pareto();
    let points: Vec<CostPoint> = report
        .rungs
        .iter()
        .enumerate()
        .map(|(i, r)| CostPoint {
            label: display_name(&r.name),
            ms: r.timing.median_ms,
            error: r.metrics.rmse,
            pareto: front.contains(&i),
            series: r.series.clone(),
        })
        .collect();
    let note = format!(
        "median of {} runs, {} threads; error: RMSE in linear radiance against {}; filled: on the front",
        report.runs_text(),
        report.threads,
        match &report.reference {
            ReferenceSource::RayCast { .. } => "the exact ray cast",
            ReferenceSource::TopRung { .. } => "the finest rung",
            ReferenceSource::Rung { name, .. } => name,
        }
    );
    cost_chart(&points, title, "RMSE (log scale)", Some(&note), (900, 560), zoom, lang)
}
