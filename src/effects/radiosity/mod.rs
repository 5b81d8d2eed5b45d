//! Radiosity: global illumination between diffuse surfaces, baked before the raster pass
//! (Goral, Torrance, Greenberg & Battaile, "Modeling the Interaction of Light Between
//! Diffuse Surfaces", SIGGRAPH 1984; Cohen & Wallace, *Radiosity and Realistic Image
//! Synthesis*, 1993).
//!
//! One concept per file:
//! - [`mesh`]: the surfaces cut into patches (the display mesh too), and their E and ρ;
//! - [`hemicube`] and [`ray_cast`]: the form factors F_ij, two ways;
//! - [`solve`]: Jacobi, Gauss-Seidel and progressive refinement, with their residuals;
//! - [`display`]: patch radiances to what the raster pass shows (flat per patch, Gouraud
//!   vertex radiances), with or without a final gather;
//! - [`reuse`]: form factors computed once per run and shared by every render of the same
//!   patch mesh and form-factor settings.
//!
//! Units: emission is radiance (docs/conventions.md), so everything here is radiance:
//! a patch shows L_i = B_i / π. [`needed`] answers the plan; [`bake`] is the pass.

pub mod display;
pub mod hemicube;
pub mod mesh;
pub mod ray_cast;
pub mod reuse;
pub mod solve;

pub use display::Baked;
pub use mesh::{Patches, mesh_scene};

use crate::geometry::bvh::Bvh;
use crate::lesson::settings::{FormFactorMethod, RenderMethod, Solver};
use crate::scene::Scene;
use glam::Vec3;
use rayon::prelude::*;
use web_time::Instant;

/// The two ray queries radiosity asks of the meshed scene's triangles (patch i is triangle
/// i): the render's one ray-query structure (`transport::SceneRays`) answers them in a render;
/// a BVH of the patches, built here, outside one (the convergence chart, tests).
pub trait RayQuery: Sync {
    /// True when a triangle meets the ray `origin + t·dir` for t in (0, `t_max`); nothing is
    /// skipped and the origin is not moved.
    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool;
    /// The nearest triangle the ray `origin + t·dir` meets for t > 0, if any.
    fn closest_triangle(&self, origin: Vec3, dir: Vec3) -> Option<u32>;
    /// What answers the queries (part of [`reuse::gather_rows`]'s key: two kinds may break
    /// ties between equally near triangles differently).
    fn kind(&self) -> &'static str;
}

impl RayQuery for Bvh {
    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        Bvh::occluded(self, origin, dir, t_max, 0..0)
    }

    fn closest_triangle(&self, origin: Vec3, dir: Vec3) -> Option<u32> {
        self.closest_hit(origin, dir, f32::INFINITY, 0..0).map(|h| h.tri)
    }

    fn kind(&self) -> &'static str {
        "patch bvh"
    }
}

/// Patches from which on the form-factor pass shows a progress bar (when stderr is a terminal).
const PROGRESS_FROM: usize = 2000;

/// The count of radiosity patches (`RenderStats::counters`).
pub const PATCHES: &str = "radiosity patches";
/// The count of non-zero form factors stored.
pub const FORM_FACTORS: &str = "radiosity form factors (non-zero)";
/// The count of solver iterations.
pub const ITERATIONS: &str = "radiosity iterations";

/// The patches the scene's triangles are cut into at its `patch_size`, counted without cutting.
pub fn patch_count(scene: &Scene) -> u64 {
    let g = &scene.geometry;
    let size = scene.spec.settings.radiosity.patch_size;
    g.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| g.positions[i as usize]);
            (crate::geometry::subdivide::divisions(a, b, c, size) as u64).pow(2)
        })
        .sum()
}

/// Whether the radiosity pass runs for this scene, and why.
pub fn needed(scene: &Scene) -> (bool, String) {
    let s = &scene.spec.settings;
    if s.method != RenderMethod::Radiosity {
        return (false, "method = \"raster\": direct light and the ambient term".into());
    }
    let r = s.radiosity;
    let g = &scene.geometry;
    let patches = patch_count(scene);
    let ff = match r.form_factors {
        FormFactorMethod::Hemicube => format!("hemicube {}²", r.hemicube_size),
        FormFactorMethod::Ray => "ray-cast point to patch".into(),
    };
    let solver = match r.solver {
        Solver::Jacobi => "Jacobi",
        Solver::GaussSeidel => "Gauss-Seidel",
        Solver::Progressive if r.ambient_correction => "progressive refinement + ambient",
        Solver::Progressive => "progressive refinement",
    };
    (
        !g.triangles.is_empty(),
        format!(
            "{patches} patches (patch_size {}), form factors by {ff}, {solver} (≤ {} iterations, tolerance {}){}",
            r.patch_size,
            r.iterations,
            r.tolerance,
            if r.final_gather { ", final gather" } else { "" }
        ),
    )
}

/// What the radiosity pass did, for `explain` and the lessons.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Patches N.
    pub patches: usize,
    /// Non-zero form factors F_ij stored.
    pub form_factors: u64,
    /// Time of the form-factor pass in milliseconds (when reused: the first time's).
    pub form_factor_ms: f64,
    /// The form factors came from this run's earlier work or the on-disk cache ([`reuse`]).
    pub form_factors_reused: bool,
    /// ... from the on-disk cache, computed by an earlier run.
    pub form_factors_cached: bool,
    /// Time of the solver in milliseconds.
    pub solve_ms: f64,
    /// Time of the display pass (vertex radiances, final gather) in milliseconds.
    pub display_ms: f64,
    /// Iterations the solver ran.
    pub iterations: u32,
    /// Relative residual after each iteration (the first for L = E).
    pub residuals: Vec<f32>,
}

/// A length that scales with the scene: the largest distance of an object's bounding
/// sphere from the origin, at least 1.
pub(super) fn scene_scale(scene: &Scene) -> f32 {
    scene.geometry.objects.iter().map(|o| o.centre.length() + o.radius).filter(|x| x.is_finite()).fold(1.0, f32::max)
}

/// The form-factor matrix of a meshed scene by the settings' method, as sparse rows; `rays`
/// answers the ray-cast method's visibility.
pub fn form_factors(scene: &Scene, patches: &Patches, rays: &dyn RayQuery) -> Vec<Vec<(u32, f32)>> {
    let g = &scene.geometry;
    form_factors_of(&g.positions, &g.triangles, patches, &scene.spec.settings.radiosity, scene_scale(scene), rays)
}

/// [`form_factors`] of the patches `triangles` (indices into `positions`, patch i is
/// triangle i) in a scene whose size is about `scale`.
pub fn form_factors_of(
    positions: &[glam::Vec3],
    triangles: &[[u32; 3]],
    patches: &Patches,
    r: &crate::lesson::settings::RadiositySettings,
    scale: f32,
    rays: &dyn RayQuery,
) -> Vec<Vec<(u32, f32)>> {
    let n = patches.len();
    let bar = progress(n);
    let tick = || {
        if let Some(b) = &bar {
            b.inc(1);
        }
    };
    let rows = match r.form_factors {
        FormFactorMethod::Hemicube => {
            let table = hemicube::DeltaTable::new(r.hemicube_size);
            let near = 1e-5 * scale;
            (0..n)
                .into_par_iter()
                .map_init(crate::raster::StripVis::default, |strip, i| {
                    let row = hemicube::row(i, patches, positions, triangles, &table, near, strip);
                    tick();
                    row
                })
                .collect()
        }
        FormFactorMethod::Ray => {
            let targets: Vec<Vec<glam::Vec3>> =
                (0..n).map(|j| ray_cast::targets(patches.corners[j], patches.emission[j] != glam::Vec3::ZERO)).collect();
            (0..n)
                .into_par_iter()
                .map(|i| {
                    let row = ray_cast::row(i, patches, rays, &targets);
                    tick();
                    row
                })
                .collect()
        }
    };
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    rows
}

/// A progress bar on stderr for a form-factor pass over `n` patches: only for large scenes
/// and only when stderr is a terminal (never in captured output).
fn progress(n: usize) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if n < PROGRESS_FROM || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = indicatif::ProgressBar::with_draw_target(Some(n as u64), indicatif::ProgressDrawTarget::stderr());
    if let Ok(style) = indicatif::ProgressStyle::with_template("form factors {bar:40} {pos}/{len} patches, {eta} left") {
        bar.set_style(style);
    }
    Some(bar)
}

/// Every solver's run on one scene, for the convergence chart and `explain`.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    /// Patches N.
    pub patches: usize,
    /// Non-zero form factors F_ij stored.
    pub form_factors: u64,
    /// Time of the form-factor pass in milliseconds (when reused: the first time's).
    pub form_factor_ms: f64,
    /// The form factors came from this run's earlier work or the on-disk cache ([`reuse`]).
    pub form_factors_reused: bool,
    /// ... from the on-disk cache, computed by an earlier run.
    pub form_factors_cached: bool,
    /// Each solver asked for, its solution (with its residuals) and its time in milliseconds.
    pub runs: Vec<(Solver, solve::Solution, f64)>,
}

/// Meshes `scene` (a `method = "radiosity"` scene, as [`mesh_scene`] expects), computes its
/// form factors once and solves with each of `solvers` under the scene's settings, with
/// `tolerance` instead of the scene's when given.
pub fn convergence(scene: &Scene, solvers: &[Solver], tolerance: Option<f32>) -> Convergence {
    let meshed = mesh_scene(scene);
    let patches = Patches::of(&meshed);
    let ff = reuse::cached(&meshed, &patches, || {
        // Not a render: the patches' own BVH answers the ray-cast method (the hemicube asks none).
        let g = &meshed.geometry;
        let bvh = if meshed.spec.settings.radiosity.form_factors == FormFactorMethod::Ray {
            Bvh::build(&g.positions, &g.triangles)
        } else {
            Bvh::default()
        };
        form_factors(&meshed, &patches, &bvh)
    });
    let rows = &ff.rows;
    let r = meshed.spec.settings.radiosity;
    let runs = solvers
        .iter()
        .map(|&solver| {
            let st = crate::lesson::settings::RadiositySettings { solver, tolerance: tolerance.unwrap_or(r.tolerance), ..r };
            let start = Instant::now();
            let sol = solve::solve(rows, &patches.emission, &patches.reflectance, &patches.area, &st);
            (solver, sol, start.elapsed().as_secs_f64() * 1e3)
        })
        .collect();
    Convergence {
        patches: patches.len(),
        form_factors: rows.iter().map(|r| r.len() as u64).sum(),
        form_factor_ms: ff.ms,
        form_factors_reused: ff.reused,
        form_factors_cached: ff.cached,
        runs,
    }
}

/// The pass: form factors, solution and display values of a scene meshed by [`mesh_scene`],
/// with `rays` the render's ray queries on that scene.
pub fn bake(scene: &Scene, rays: &dyn RayQuery) -> Baked {
    let patches = Patches::of(scene);
    let ff = reuse::cached(scene, &patches, || form_factors(scene, &patches, rays));
    let rows = &ff.rows;
    let start = Instant::now();
    let solution = solve::solve(rows, &patches.emission, &patches.reflectance, &patches.area, &scene.spec.settings.radiosity);
    let solve_ms = start.elapsed().as_secs_f64() * 1e3;
    let start = Instant::now();
    let mut baked = display::display(scene, &patches, &solution.radiance, rays);
    baked.report = Report {
        patches: patches.len(),
        form_factors: rows.iter().map(|r| r.len() as u64).sum(),
        form_factor_ms: ff.ms,
        form_factors_reused: ff.reused,
        form_factors_cached: ff.cached,
        solve_ms,
        display_ms: start.elapsed().as_secs_f64() * 1e3,
        iterations: solution.iterations,
        residuals: solution.residuals,
    };
    baked
}

#[cfg(test)]
mod tests;
