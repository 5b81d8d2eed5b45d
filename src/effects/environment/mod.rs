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
//! - [`brdf_sampling`]: directions after a BRDF;
//! - [`reference`]: the Monte Carlo estimate that combines them.

pub mod brdf_sampling;
pub mod distribution;
pub mod reference;

use super::shadows::{SceneBvh, can_occlude};
use crate::scene::build::Geometry;
use crate::scene::{Environment, Material, Model, Scene};
use distribution::EnvDistribution;
use glam::Vec3;
use std::sync::Arc;

/// Mirrors followed from one shaded point before the ray is given the environment's radiance
/// (two facing mirrors would otherwise reflect each other forever).
pub const MAX_MIRROR_DEPTH: u32 = 8;

/// True when the environment (or a mirror's ray) lights material `m`.
pub fn lights(m: &Material) -> bool {
    matches!(m.model, Model::Physical(_) | Model::Mirror(_))
}

/// Whether the environment pass is needed for `scene`, and why: some object's material is
/// lit by the environment (physically based, or a mirror, which needs its rays even without
/// an `[environment]`).
pub fn needed(scene: &Scene) -> (bool, String) {
    let g = &scene.geometry;
    let used = |m: usize| g.objects.iter().any(|o| o.material as usize == m && o.triangles > 0);
    let lit: Vec<&Material> = scene.materials.iter().enumerate().filter(|(i, m)| used(*i) && lights(m)).map(|(_, m)| m).collect();
    let mirrors = lit.iter().any(|m| matches!(m.model, Model::Mirror(_)));
    match (&scene.environment, lit.is_empty()) {
        (_, true) => (false, "no physically based or mirror material is drawn".into()),
        (None, _) if !mirrors => (false, "no [environment]".into()),
        (env, false) => {
            let s = &scene.settings;
            let what = match env {
                Some(e) => format!(
                    "{}×{} map: luminance sampling tables; Monte Carlo (ibl = \"{}\"), {} samples per point (MIS with the BRDF)",
                    e.map.width,
                    e.map.height,
                    s.ibl.name(),
                    s.env_samples
                ),
                None => "no [environment]: mirrors see the scene and the background colour".into(),
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
    /// The scene's rays, when it can block itself: environment visibility and mirror hits.
    pub bvh: Option<SceneBvh>,
    /// The scene's surfaces and materials, for shading what a mirror sees.
    pub surfaces: Option<Arc<(Geometry, Vec<Material>)>>,
    /// Back faces are drawn (lit with the flipped normal).
    pub two_sided: bool,
}

impl EnvLighting {
    /// The pass: sampling tables of the map, and the BVH when the scene can block itself.
    pub fn build(scene: &Scene) -> EnvLighting {
        let distribution = scene.environment.as_ref().and_then(|e| EnvDistribution::new(&e.map));
        let bvh = can_occlude(scene).then(|| SceneBvh::build(scene));
        let mirrors = scene.materials.iter().any(|m| matches!(m.model, Model::Mirror(_)));
        let surfaces = (bvh.is_some() && mirrors).then(|| Arc::new((scene.geometry.clone(), scene.materials.clone())));
        EnvLighting {
            env: scene.environment.clone(),
            miss: scene.camera.background,
            distribution,
            samples: scene.settings.env_samples,
            bvh,
            surfaces,
            two_sided: scene.settings.cull == crate::lesson::Cull::None,
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
