//! `[render] method = "path"`: the path tracer's frame. Each pixel is traced by
//! [`transport::path`](crate::transport::path) (its aa² samples × `spp` paths, averaged),
//! rows in parallel on the render's one [`SceneRays`]; the stats count paths, segments and
//! next-event rays, and a long render shows a progress bar on a terminal.

use crate::render::frame::{Frame, Layer};
use crate::render::pipeline::RenderStats;
use crate::render::plan::Pass;
use crate::scene::Scene;
use crate::transport::SceneRays;
use crate::transport::path::subsurface::WALK_STEPS;
use crate::transport::path::{
    GATHER_RAYS, GLOBAL_STORED, NEE_RAYS, PATHS, PHOTONS_EMITTED, PHOTONS_STORED, PathCounts, PathTracer, SEGMENTS,
};
use crate::transport::rays::BVH_NODES;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::Arc;

#[cfg(test)]
mod photon_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod transmission_tests;

/// The path-traced frame of `scene` in `layers` (the total; every other layer is zero: a
/// path carries no split into the equation's terms) and its stats.
pub fn render(scene: &Scene, layers: &[Layer]) -> (Frame, RenderStats) {
    let plan = crate::render::plan::plan(scene);
    let rays = Arc::new(SceneRays::build(scene));
    let tracer = PathTracer::new(scene, rays.clone(), &plan.active_lights(scene));
    let cam = &scene.spec.camera;
    let (w, h) = (cam.width, cam.height);
    let camera = cam.rays();
    let per_pixel = tracer.paths_per_pixel() as f32;
    let bar = progress(u64::from(h), u64::from(w) * u64::from(h) * u64::from(tracer.paths_per_pixel()));
    let rows: Vec<(Vec<Vec3>, Vec<f32>, PathCounts)> = (0..h)
        .into_par_iter()
        .map(|y| {
            let mut counts = PathCounts::default();
            let (mut radiance, mut coverage) = (Vec::with_capacity(w as usize), Vec::with_capacity(w as usize));
            for x in 0..w {
                let (sum, covered) = tracer.pixel(&camera, x, y, &mut counts);
                radiance.push(sum / per_pixel);
                coverage.push(covered as f32 / per_pixel);
            }
            if let Some(b) = &bar {
                b.inc(1);
            }
            (radiance, coverage, counts)
        })
        .collect();
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let (mut total, mut coverage) = (Vec::with_capacity((w * h) as usize), Vec::with_capacity((w * h) as usize));
    let mut counts = PathCounts::default();
    for (r, c, n) in rows {
        total.extend(r);
        coverage.extend(c);
        counts += n;
    }
    let mut wanted: Vec<Layer> = Vec::new();
    for l in layers {
        if !wanted.contains(l) {
            wanted.push(*l);
        }
    }
    let layers = wanted.into_iter().map(|l| (l, if l == Layer::Total { total.clone() } else { vec![Vec3::ZERO; total.len()] })).collect();
    let mut stats = RenderStats { passes: Pass::PathTrace.bit(), ..Default::default() };
    stats.counters.add(BVH_NODES, rays.node_count() as u64);
    stats.counters.add(PATHS, counts.paths);
    stats.counters.add(SEGMENTS, counts.segments);
    stats.counters.add(NEE_RAYS, counts.nee_rays);
    if counts.walk_steps > 0 {
        stats.counters.add(WALK_STEPS, counts.walk_steps);
    }
    if let Some(maps) = tracer.photon_maps() {
        stats.counters.add(PHOTONS_EMITTED, u64::from(maps.emitted));
        if let Some(map) = &maps.caustic {
            stats.counters.add(PHOTONS_STORED, map.len() as u64);
        }
        if let Some(map) = &maps.global {
            stats.counters.add(GLOBAL_STORED, map.len() as u64);
            stats.counters.add(GATHER_RAYS, counts.gather_rays);
        }
    }
    (Frame { width: w, height: h, layers, coverage, background: cam.background }, stats)
}

/// Paths in a render from which on it shows a progress bar (about 10 s on one core).
const PROGRESS_FROM: u64 = 5_000_000;

/// A progress bar on stderr over a render's `rows`: only for renders of at least
/// [`PROGRESS_FROM`] paths, and only when stderr is a terminal (never in captured output).
fn progress(rows: u64, paths: u64) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if paths < PROGRESS_FROM || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = indicatif::ProgressBar::with_draw_target(Some(rows), indicatif::ProgressDrawTarget::stderr());
    if let Ok(style) = indicatif::ProgressStyle::with_template("path tracing {bar:40} {pos}/{len} rows, {eta} left") {
        bar.set_style(style);
    }
    Some(bar)
}
