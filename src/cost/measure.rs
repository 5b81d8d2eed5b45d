//! One ladder measured: every rung rendered, timed, and compared with the reference.
//!
//! Which reference (see docs/accuracy-and-cost.md):
//! - **the exact ray cast** ([`super::reference`]) when every object is a sphere or a
//!   plane and the ladder is not `fresnel`. It is sampled like the rungs (the lesson's
//!   `aa`), so the error measures the approximation the ladder names and nothing else;
//!   the `aa` ladder, whose subject is sampling, uses [`AA_REFERENCE_SAMPLES`] per side.
//! - **the ladder's top rung**, rendered by the rasterizer, otherwise (meshes, cubes,
//!   tori; and `fresnel`, where only the Fresnel term may differ between rungs).
//! - **the reference the ladder names** ([`super::rungs::NamedReference`]), rendered by the
//!   rasterizer, before both: ray-cast shadows for the shadow-map ladders, the exact
//!   rect-light irradiance or 4096 samples for `area_samples`. The rungs differ from it only
//!   in what the ladder steps, so the error is that approximation's.
//!
//! A rung's time is what the approximation costs a user: building the scene (mesh
//! generation and vertex normals included, which is what tessellation costs) and
//! rendering the linear frame, median of N runs after a warm-up. Developing and
//! encoding are the same for every rung and are left out. The exact rung's time is the
//! ray cast's.

use super::ladder::ladder;
use super::metrics::{ErrorMetrics, MetricsError, error_metrics};
use super::reference::{self, ReferenceError};
use super::rungs::Rung;
use super::timing::{Timing, time_keeping};
use crate::lesson::{self, LadderKind, Lesson, LessonError};
use crate::render::{self, Frame, Layer, RenderStats};
use crate::scene::Scene;
use crate::scene::build::SceneError;

/// Samples per pixel side of the `aa` ladder's exact reference: twice its top rung (8).
pub const AA_REFERENCE_SAMPLES: u32 = 16;

/// How a ladder is measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostOptions {
    /// Timed runs per rung (≥ 1).
    pub repeat: usize,
    /// Untimed runs before them.
    pub warmup: usize,
    /// Samples per pixel side of the exact reference, instead of the default rule.
    pub reference_aa: Option<u32>,
    /// Time the rungs; when false each rung is rendered once and its timing is zero, so
    /// the report (and a figure made from it) is the same on every run.
    pub timed: bool,
    /// A time budget per rung in milliseconds: the timed runs stop once three have
    /// run and together took this long (`repeat` is then the most; [`super::timing::MIN_RUNS`]). `None`: exactly `repeat`.
    pub budget_ms: Option<f64>,
}

impl Default for CostOptions {
    fn default() -> Self {
        CostOptions { repeat: 5, warmup: 1, reference_aa: None, timed: true, budget_ms: None }
    }
}

/// What the rungs were compared with.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReferenceSource {
    /// The exact ray cast of the analytic shapes.
    RayCast {
        /// Samples per pixel side.
        samples_per_side: u32,
    },
    /// The named rung (the ladder's finest), rendered by the rasterizer.
    TopRung {
        /// Its name.
        rung: String,
    },
    /// The reference the ladder names for itself (ray-cast shadows, the exact rect-light
    /// irradiance, many light samples), rendered by the rasterizer.
    Rung {
        /// A short name that reads after "against".
        name: String,
        /// The line reports print.
        describe: String,
    },
}

impl ReferenceSource {
    /// One line for reports.
    pub fn describe(&self) -> String {
        match self {
            ReferenceSource::RayCast { samples_per_side: n } => {
                format!("exact ray cast of the analytic shapes, exact normals, {n}×{n} samples per pixel")
            }
            ReferenceSource::TopRung { rung } => {
                format!("the finest rung, `{rung}` (the scene has no analytic form, or the ladder is fresnel)")
            }
            ReferenceSource::Rung { describe, .. } => describe.clone(),
        }
    }
}

/// One measured rung.
#[derive(Debug, Clone)]
pub struct RungResult {
    /// Its name (`flat`, `32×16`, `aa 4`, `schlick`).
    pub name: String,
    /// Render time (all zero when not timed).
    pub timing: Timing,
    /// Error against the reference.
    pub metrics: ErrorMetrics,
    /// The rung's frame (the `total` layer).
    pub frame: Frame,
    /// Triangles rendered (0 for the ray cast).
    pub triangles: u64,
    /// True when this rung is the reference itself (its error is 0 by construction).
    pub is_reference: bool,
    /// True for the exact ray-cast rung.
    pub exact: bool,
    /// Render counts of one run (default for the ray cast).
    pub stats: RenderStats,
    /// Its series (empty for a single one).
    pub series: String,
}

/// A measured ladder.
#[derive(Debug, Clone)]
pub struct LadderReport {
    /// Which ladder.
    pub ladder: LadderKind,
    /// What the rungs were compared with.
    pub reference: ReferenceSource,
    /// The reference frame.
    pub reference_frame: Frame,
    /// True when the reference came from the on-disk cache, not rendered in this run.
    pub reference_cached: bool,
    /// The rungs, cheap to costly.
    pub rungs: Vec<RungResult>,
    /// Worker threads the rungs were timed with.
    pub threads: usize,
    /// Timed runs per rung asked for, the most with a budget (0 when not timed).
    pub repeat: usize,
}

/// The spread above which a ladder's times are flagged ([`Timing::spread`], robust to one
/// slow run): one rung's runs differing by more than a quarter of their median mean the
/// machine was busy, and the front may follow noise.
pub const BUSY_SPREAD: f64 = 0.25;

impl LadderReport {
    /// The largest [`Timing::spread`] over the rungs: 0 untimed.
    pub fn spread(&self) -> f64 {
        self.rungs.iter().map(|r| r.timing.spread).fold(0.0, f64::max)
    }

    /// A sentence for a figure or a table when [`LadderReport::spread`] exceeds
    /// [`BUSY_SPREAD`], else nothing.
    pub fn spread_warning(&self) -> Option<String> {
        let s = self.spread();
        (s > BUSY_SPREAD).then(|| {
            format!(
                "the runs of one rung spread by up to {:.0}% of its median: the machine was busy, so read the times (and the \
                 front they draw) with care, or time again with more runs",
                s * 100.0
            )
        })
    }

    /// How many timed runs each rung's median is of, as text: "5", or "3–5" when a budget
    /// cut the slow rungs short.
    pub fn runs_text(&self) -> String {
        let runs = self.rungs.iter().map(|r| r.timing.runs);
        match (runs.clone().min(), runs.max()) {
            (Some(lo), Some(hi)) if lo != hi => format!("{lo}–{hi}"),
            (Some(n), _) => n.to_string(),
            _ => self.repeat.to_string(),
        }
    }

    /// Indices of the Pareto-optimal rungs: no other rung is at least as fast and at
    /// least as accurate (RMSE) and strictly better in one of the two. Sorted by time.
    pub fn pareto(&self) -> Vec<usize> {
        let r = &self.rungs;
        let dominated = |i: usize| {
            (0..r.len()).any(|j| {
                let (a, b) = (&r[j], &r[i]);
                j != i
                    && a.timing.median_ms <= b.timing.median_ms
                    && a.metrics.rmse <= b.metrics.rmse
                    && (a.timing.median_ms < b.timing.median_ms || a.metrics.rmse < b.metrics.rmse)
            })
        };
        let mut front: Vec<usize> = (0..r.len()).filter(|&i| !dominated(i)).collect();
        front.sort_by(|&a, &b| r[a].timing.median_ms.total_cmp(&r[b].timing.median_ms));
        front
    }
}

/// A ladder that could not be measured: always bad input.
#[derive(Debug, thiserror::Error)]
pub enum CostError {
    /// A rung's overrides do not validate.
    #[error("{0}")]
    Lesson(#[from] LessonError),
    /// A mesh could not be loaded.
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// The ladder does not apply to this lesson.
    #[error("{file}: the {ladder} ladder: {why}")]
    Ladder {
        /// The lesson file.
        file: String,
        /// The ladder's name.
        ladder: &'static str,
        /// What the lesson lacks.
        why: String,
    },
    /// The exact reference cannot be made.
    #[error("{0}")]
    Reference(#[from] ReferenceError),
    /// Frames that cannot be compared (a rung changed the image size).
    #[error("{0}")]
    Metrics(#[from] MetricsError),
    /// A rung's or the reference's render is over the work and memory budget.
    #[error("{0}")]
    Budget(#[from] crate::render::budget::OverBudget),
}

/// Progress of a measurement, for a progress bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress<'a> {
    /// Steps done so far.
    pub done: usize,
    /// Steps in all (the reference, then each rung).
    pub total: usize,
    /// What runs next.
    pub next: &'a str,
}

/// The lesson of one rung: the base lesson's overrides, then the rung's.
/// The scene of `l`, refused before any work when its render is over the budget.
fn build(l: &Lesson) -> Result<Scene, CostError> {
    let scene = crate::scene::build::build(l)?;
    render::budget::check(&scene).map_err(|e| e.at(l.path.display()))?;
    Ok(scene)
}

fn rung_lesson(base: &Lesson, rung: &Rung) -> Result<Lesson, LessonError> {
    with_sets(base, &rung.sets)
}

/// `base` with `sets` applied after its own overrides.
fn with_sets(base: &Lesson, sets: &[lesson::Override]) -> Result<Lesson, LessonError> {
    let sets: Vec<_> = base.overrides.iter().chain(sets).cloned().collect();
    lesson::parse_cell(&base.source, &base.path, &sets)
}

/// Measures ladder `kind` on `lesson`, calling `progress` before each step.
///
/// # Errors
/// [`CostError`] when the ladder does not apply, a rung does not validate, a mesh
/// cannot be loaded or the reference cannot be made.
pub fn measure(
    lesson: &Lesson,
    kind: LadderKind,
    opts: &CostOptions,
    progress: &mut dyn FnMut(Progress),
) -> Result<LadderReport, CostError> {
    let ladder_err = |why: String| CostError::Ladder { file: lesson.path.display().to_string(), ladder: kind.name(), why };
    let super::rungs::Ladder { rungs: mut ladder, reference: named } = ladder(kind, lesson).map_err(ladder_err)?;
    let analytic = named.is_none() && kind != LadderKind::Fresnel && reference::check(lesson).is_ok();
    if !analytic {
        // Without analytic shapes there is no exact rung; the finest raster rung is the reference.
        ladder.retain(|r| !r.exact);
    }
    if ladder.is_empty() {
        return Err(ladder_err("it has no rungs for this lesson".into()));
    }
    let lessons: Vec<Lesson> = ladder.iter().map(|r| rung_lesson(lesson, r)).collect::<Result<_, _>>()?;
    let (warmup, repeat) = if opts.timed { (opts.warmup, opts.repeat.max(1)) } else { (0, 1) };
    let total = ladder.len() + 1;
    let untimed = Timing { median_ms: 0.0, min_ms: 0.0, max_ms: 0.0, runs: 0, spread: 0.0 };

    // The reference first: every rung is compared with it as soon as it is rendered.
    progress(Progress { done: 0, total, next: "reference" });
    let lesson_aa = lesson.scene.settings.aa;
    let ((source, reference_frame), reference_cached) = if let Some(named) = named {
        let l = with_sets(lesson, &named.sets)?;
        let area = [u8::from(named.exact_area)];
        let (frame, hit) = render::cached::frame(&l, "reference", &[b"named", &area], || -> Result<Frame, CostError> {
            let mut scene = build(&l)?;
            scene.spec.settings.area_reference = named.exact_area;
            Ok(render::render(&scene, &[Layer::Total]).0)
        })?;
        ((ReferenceSource::Rung { name: named.name, describe: named.describe }, frame), hit)
    } else if analytic {
        let n = opts.reference_aa.unwrap_or(if kind == LadderKind::Aa { AA_REFERENCE_SAMPLES } else { lesson_aa });
        let (frame, hit) = render::cached::frame(lesson, "reference", &[b"ray cast", &n.to_le_bytes()], || -> Result<Frame, CostError> {
            let scene = build(lesson)?;
            // The ray cast takes n² samples a pixel: budgeted as a render at aa = n.
            let at = || format!("{}: the ray-cast reference ({n}² samples a pixel)", lesson.path.display());
            render::budget::check_at(&scene, n).map_err(|e| e.at(at()))?;
            Ok(reference::reference(lesson, &scene, &[Layer::Total], n)?)
        })?;
        ((ReferenceSource::RayCast { samples_per_side: n }, frame), hit)
    } else {
        let top = lessons.last().expect("not empty");
        let (frame, hit) = render::cached::frame(top, "reference", &[b"top rung"], || -> Result<Frame, CostError> {
            Ok(render::render(&build(top)?, &[Layer::Total]).0)
        })?;
        ((ReferenceSource::TopRung { rung: ladder.last().expect("not empty").name.clone() }, frame), hit)
    };
    let exposure = lesson.scene.settings.exposure;

    let mut results = Vec::with_capacity(ladder.len());
    for (i, (rung, l)) in ladder.iter().zip(&lessons).enumerate() {
        progress(Progress { done: i + 1, total, next: &rung.name });
        let scene = build(l)?;
        // Timed, the last timed run's frame is the rung's (renders are deterministic).
        let (frame, stats, timing) = if rung.exact {
            let cast = || reference::reference(l, &scene, &[Layer::Total], lesson_aa);
            let (timing, frame) = if opts.timed { time_keeping(warmup, repeat, opts.budget_ms, cast) } else { (untimed, cast()) };
            (frame?, RenderStats::default(), timing)
        } else if opts.timed {
            // Timed as a rung alone would run: form factors computed afresh each time.
            let (timing, (frame, stats)) = crate::effects::radiosity::reuse::without_reuse(|| {
                time_keeping(warmup, repeat, opts.budget_ms, || {
                    let scene = build(l).expect("built once above");
                    render::render(&scene, &[Layer::Total])
                })
            });
            (frame, stats, timing)
        } else {
            let (frame, stats) = render::render(&scene, &[Layer::Total]);
            (frame, stats, untimed)
        };
        let metrics = error_metrics(&frame, &reference_frame, Layer::Total, exposure)?;
        let is_reference = match &source {
            ReferenceSource::TopRung { .. } => i + 1 == ladder.len(),
            ReferenceSource::RayCast { samples_per_side } => rung.exact && *samples_per_side == lesson_aa,
            ReferenceSource::Rung { .. } => false,
        };
        results.push(RungResult {
            name: rung.name.clone(),
            timing,
            metrics,
            frame,
            triangles: if rung.exact { 0 } else { scene.geometry.triangles.len() as u64 },
            is_reference,
            exact: rung.exact,
            stats,
            series: rung.series.clone(),
        });
    }
    progress(Progress { done: total, total, next: "" });
    Ok(LadderReport {
        ladder: kind,
        reference: source,
        reference_frame,
        reference_cached,
        rungs: results,
        threads: rayon::current_num_threads(),
        repeat: if opts.timed { repeat } else { 0 },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use std::path::Path;

    fn lesson(shape: &str, extra_render: &str) -> Lesson {
        let text = format!(
            r#"
[camera]
position = [0.0, 0.0, 4.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 35.0
size = [64, 64]

[[object]]
{shape}
material = "plastic"

[material.plastic]
model = "blinn_phong"
ambient = 0.1
diffuse = [0.7, 0.3, 0.2]
specular = 0.5
shininess = 40

[[light]]
kind = "directional"
direction = [-0.5, -0.6, -0.6]

[scene]
ambient = 0.1

[render]
{extra_render}
"#
        );
        lesson::parse(&text, Path::new("t.toml"), &[]).unwrap()
    }

    fn untimed() -> CostOptions {
        CostOptions { timed: false, ..CostOptions::default() }
    }

    fn rmse(r: &LadderReport, name: &str) -> f64 {
        r.rungs.iter().find(|x| x.name == name).unwrap_or_else(|| panic!("no rung {name}")).metrics.rmse
    }

    #[test]
    fn interpolation_ladder_orders_flat_gouraud_phong_and_the_exact_rung_is_the_reference() {
        let l = lesson("shape = \"uv_sphere\"\nsegments = 16\nrings = 8", "");
        let r = measure(&l, LadderKind::Interpolation, &untimed(), &mut |_| {}).unwrap();
        assert_eq!(r.rungs.iter().map(|x| x.name.as_str()).collect::<Vec<_>>(), ["flat", "gouraud", "phong", "exact"]);
        assert_eq!(r.reference, ReferenceSource::RayCast { samples_per_side: 1 });
        let (f, g, p) = (rmse(&r, "flat"), rmse(&r, "gouraud"), rmse(&r, "phong"));
        assert!(f > g && g > p && p > 0.0, "flat {f}, gouraud {g}, phong {p}");
        let exact = r.rungs.last().unwrap();
        assert!(exact.is_reference && exact.exact);
        assert_eq!((exact.metrics.rmse, exact.metrics.max_err, exact.metrics.visible_pct), (0.0, 0.0, 0.0));
        assert_eq!(exact.metrics.psnr, f64::INFINITY);
        assert_eq!(exact.triangles, 0);
        // Untimed: every timing is zero, so the report is reproducible.
        assert!(r.rungs.iter().all(|x| x.timing.runs == 0 && x.timing.median_ms == 0.0));
    }

    #[test]
    fn tessellation_error_falls_as_segments_rise() {
        let l = lesson("shape = \"uv_sphere\"\nsegments = 16\nrings = 8", "");
        let r = measure(&l, LadderKind::Tessellation, &untimed(), &mut |_| {}).unwrap();
        let errors: Vec<f64> = r.rungs.iter().map(|x| x.metrics.rmse).collect();
        assert_eq!(errors.len(), 6);
        assert!(errors.windows(2).all(|w| w[0] > w[1]), "{errors:?}");
        let triangles: Vec<u64> = r.rungs.iter().map(|x| x.triangles).collect();
        assert!(triangles.windows(2).all(|w| w[0] < w[1]), "{triangles:?}");
        assert!(r.rungs.iter().all(|x| !x.is_reference));
    }

    #[test]
    fn aa_ladder_uses_a_finer_reference_and_error_falls() {
        let l = lesson("shape = \"uv_sphere\"\nsegments = 64\nrings = 32", "");
        let r = measure(&l, LadderKind::Aa, &untimed(), &mut |_| {}).unwrap();
        assert_eq!(r.reference, ReferenceSource::RayCast { samples_per_side: AA_REFERENCE_SAMPLES });
        let errors: Vec<f64> = r.rungs.iter().map(|x| x.metrics.rmse).collect();
        assert!(errors.windows(2).all(|w| w[0] > w[1]), "{errors:?}");
    }

    #[test]
    fn a_mesh_without_analytic_form_is_measured_against_its_finest_rung() {
        let l = lesson("shape = \"torus\"", "");
        let r = measure(&l, LadderKind::Tessellation, &untimed(), &mut |_| {}).unwrap();
        assert!(matches!(&r.reference, ReferenceSource::TopRung { rung } if rung == "192×96"));
        let last = r.rungs.last().unwrap();
        assert!(last.is_reference && last.metrics.rmse == 0.0);
        // The interpolation ladder on a cube has no exact rung; Phong is the reference.
        let cube = lesson("shape = \"cube\"\nrotate_deg = [20.0, 30.0, 0.0]", "");
        let r = measure(&cube, LadderKind::Interpolation, &untimed(), &mut |_| {}).unwrap();
        assert_eq!(r.rungs.iter().map(|x| x.name.as_str()).collect::<Vec<_>>(), ["flat", "gouraud", "phong"]);
        assert!(r.rungs[2].is_reference);
    }

    #[test]
    fn ladders_that_do_not_apply_are_errors_naming_the_file() {
        let cube = lesson("shape = \"cube\"", "");
        let e = measure(&cube, LadderKind::Tessellation, &untimed(), &mut |_| {}).unwrap_err().to_string();
        assert!(e.contains("t.toml") && e.contains("tessellation") && e.contains("uv_sphere"), "{e}");
        let e = measure(&cube, LadderKind::Fresnel, &untimed(), &mut |_| {}).unwrap_err().to_string();
        assert!(e.contains("cook_torrance"), "{e}");
    }

    #[test]
    fn progress_counts_every_step_and_timing_runs_repeat_times() {
        let l = lesson("shape = \"uv_sphere\"\nsegments = 8\nrings = 4", "");
        let mut steps = Vec::new();
        let opts = CostOptions { repeat: 3, warmup: 0, ..CostOptions::default() };
        let r = measure(&l, LadderKind::Interpolation, &opts, &mut |p| steps.push((p.done, p.total, p.next.to_string()))).unwrap();
        assert_eq!(steps.first().unwrap(), &(0, 5, "reference".to_string()));
        assert_eq!(steps.last().unwrap(), &(5, 5, String::new()));
        assert_eq!(steps.len(), 6);
        assert!(r.rungs.iter().all(|x| x.timing.runs == 3 && x.timing.min_ms <= x.timing.median_ms));
        assert_eq!(r.repeat, 3);
    }

    #[test]
    fn pareto_front_drops_dominated_rungs() {
        let l = lesson("shape = \"uv_sphere\"\nsegments = 8\nrings = 4", "");
        let mut r = measure(&l, LadderKind::Interpolation, &untimed(), &mut |_| {}).unwrap();
        // Times 1, 2, 3, 4 ms with errors from the render: flat, gouraud, phong, exact (0).
        for (i, x) in r.rungs.iter_mut().enumerate() {
            x.timing.median_ms = 1.0 + i as f64;
        }
        assert_eq!(r.pareto(), vec![0, 1, 2, 3]);
        // Make Gouraud slower than Phong: it is dominated.
        r.rungs[1].timing.median_ms = 3.5;
        assert_eq!(r.pareto(), vec![0, 2, 3]);
    }
}
