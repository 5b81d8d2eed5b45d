//! The environment as a light: what a render keeps to light materials with it, and whether
//! the scene needs that at all.
//!
//! Which light paths it counts: for a physically based material, the environment seen
//! directly from the shaded point (one bounce, blocked by the scene when the scene can block
//! itself), integrated by [`reference::estimate`]; for a `mirror`, the one direction
//! r = 2(n·v)n − v, followed through up to [`MAX_MIRROR_DEPTH`] mirrors to the first
//! non-mirror surface (shaded as if seen by the camera) or the environment. Classic
//! materials (the course's equation has no incident radiance to integrate) are not lit by it.
//!
//! - [`distribution`]: the map's luminance as a 2D distribution (importance sampling);
//! - [`reference`]: the Monte Carlo estimate, the map's samples and the BRDF's own
//!   (`Brdf::sample`) combined by multiple importance sampling;
//! - [`sh`], [`prefilter`], [`split_sum`]: the fast path, irradiance by nine SH coefficients
//!   or a convolved map and the split sum for the specular part.

pub mod distribution;
pub mod prefilter;
pub mod reference;
pub mod sh;
pub mod split_sum;

use super::shadows::can_occlude;
use crate::lesson::settings::Ibl;
use crate::scene::{Environment, Material, Model, Scene};
use distribution::EnvDistribution;
use glam::Vec3;
use prefilter::Prefiltered;
use split_sum::SplitSum;
use std::sync::Arc;

/// Mirrors followed from one shaded point before the ray is given the environment's radiance
/// (two facing mirrors would otherwise reflect each other forever).
pub const MAX_MIRROR_DEPTH: u32 = 8;

/// True when the environment (or a mirror's or glass's ray) lights material `m`.
pub fn lights(m: &Material) -> bool {
    matches!(m.model, Model::Physical(_) | Model::Mirror(_) | Model::Glass(_))
}

/// True when material `m` traces rays into the scene: a mirror or glass.
pub fn traces(m: &Material) -> bool {
    matches!(m.model, Model::Mirror(_) | Model::Glass(_))
}

/// Whether the environment pass is needed for `scene`, and why: some object's material is
/// lit by the environment (physically based, or a mirror, which needs its rays even without
/// an `[environment]`).
pub fn needed(scene: &Scene) -> (bool, String) {
    let g = &scene.geometry;
    let used = |m: usize| g.objects.iter().any(|o| o.material as usize == m && o.triangles > 0);
    let lit: Vec<&Material> = scene.materials.iter().enumerate().filter(|(i, m)| used(*i) && lights(m)).map(|(_, m)| m).collect();
    let mirrors = lit.iter().any(|m| traces(m));
    match (&scene.environment, lit.is_empty()) {
        (_, true) => (false, "no physically based, mirror or glass material is drawn".into()),
        (None, _) if !mirrors => (false, "no [environment]".into()),
        (env, false) => {
            let s = &scene.spec.settings;
            let physical = lit.iter().any(|m| matches!(m.model, Model::Physical(_)));
            let what = match env {
                Some(e) if s.ibl == Ibl::Reference || !physical => format!(
                    "{}×{} map: luminance sampling tables; Monte Carlo (ibl = \"reference\"), {} samples per point (MIS with the BRDF)",
                    e.map.width, e.map.height, s.env_samples
                ),
                Some(e) => {
                    let cache = match Prefiltered::lookup(&e.map, s.prefilter_size) {
                        Some(p) => format!("cache hit, computed in {:.0} ms", p.millis),
                        None => "not yet in this run: read from the on-disk cache when an earlier run kept it, else computed now".into(),
                    };
                    format!(
                        "prefilter of the {}×{} map ({cache}): {} GGX levels from {}×{}, irradiance {} (ibl = \"{}\"); specular albedo tables",
                        e.map.width,
                        e.map.height,
                        prefilter::LEVELS,
                        s.prefilter_size,
                        s.prefilter_size / 2,
                        if s.ibl == Ibl::Sh { "by 9 SH coefficients" } else { "map 64×32" },
                        s.ibl.name()
                    )
                }
                None => "no [environment]: mirrors and glass see the scene and the background colour".into(),
            };
            let rays = if can_occlude(scene) { "; BVH for environment visibility and mirror rays" } else { "" };
            (true, format!("{what}{rays}"))
        }
    }
}

/// What shading needs to light a point with the environment, built once per render.
#[derive(Debug, Clone)]
pub struct EnvLighting {
    /// The environment, or `None` when only mirrors need rays (a miss then sees `miss`).
    pub env: Option<Environment>,
    /// What a mirror ray that hits nothing sees without an environment: the camera background.
    pub miss: Vec3,
    /// The map's sampling tables (`None` for a black map).
    pub distribution: Option<EnvDistribution>,
    /// Monte Carlo samples per shaded point.
    pub samples: u32,
    /// How materials are lit: Monte Carlo, or the prefiltered maps.
    pub ibl: Ibl,
    /// The prefiltered maps (`ibl = "prefiltered"` or `"sh"`).
    pub prefiltered: Option<Arc<Prefiltered>>,
    /// The split-sum terms of each physically based material of the scene.
    pub split: Vec<SplitSum>,
}

impl EnvLighting {
    /// The pass: sampling tables of the map, or the prefiltered maps and split-sum terms.
    /// (The scene's rays, which mirrors and the environment's visibility use, are the
    /// render's one `transport::rays::SceneRays`.)
    pub fn build(scene: &Scene) -> EnvLighting {
        let reference = scene.spec.settings.ibl == Ibl::Reference;
        let distribution = scene.environment.as_ref().filter(|_| reference).and_then(|e| EnvDistribution::new(&e.map));
        let prefiltered = match &scene.environment {
            Some(e) if !reference => Some(Prefiltered::cached(&e.map, scene.spec.settings.prefilter_size).0),
            _ => None,
        };
        let split = if reference { Vec::new() } else { scene.materials.iter().filter_map(|m| m.brdf()).map(SplitSum::cached).collect() };
        EnvLighting {
            env: scene.environment.clone(),
            miss: scene.spec.camera.background,
            distribution,
            samples: scene.spec.settings.env_samples,
            ibl: scene.spec.settings.ibl,
            prefiltered,
            split,
        }
    }

    /// Radiance arriving along the world direction `d` from far away.
    #[inline]
    pub fn radiance(&self, d: Vec3) -> Vec3 {
        match &self.env {
            Some(e) => e.radiance(d),
            None => self.miss,
        }
    }
}
