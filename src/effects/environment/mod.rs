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
//! - [`reference`]: the Monte Carlo estimate that combines them;
//! - [`sh`], [`prefilter`], [`split_sum`]: the fast path, irradiance by nine SH coefficients
//!   or a convolved map and the split sum for the specular part.

pub mod brdf_sampling;
pub mod distribution;
pub mod prefilter;
pub mod reference;
pub mod sh;
pub mod split_sum;

use super::probe::Probes;
use super::shadows::{SceneBvh, can_occlude};
use crate::lesson::settings::Ibl;
use crate::scene::build::Geometry;
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
            let s = &scene.settings;
            let physical = lit.iter().any(|m| matches!(m.model, Model::Physical(_)));
            let what = match env {
                Some(e) if s.ibl == Ibl::Reference || !physical => format!(
                    "{}×{} map: luminance sampling tables; Monte Carlo (ibl = \"reference\"), {} samples per point (MIS with the BRDF)",
                    e.map.width, e.map.height, s.env_samples
                ),
                Some(e) => {
                    let cache = match Prefiltered::lookup(&e.map, s.prefilter_size) {
                        Some(p) => format!("cache hit, computed in {:.0} ms", p.millis),
                        None => "cache miss: computed now".into(),
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
    /// The scene's rays, when it can block itself: environment visibility and mirror hits.
    pub bvh: Option<SceneBvh>,
    /// The scene's surfaces and materials, for shading what a mirror sees.
    pub surfaces: Option<Arc<(Geometry, Vec<Material>)>>,
    /// Back faces are drawn (lit with the flipped normal).
    pub two_sided: bool,
    /// The captured reflection probes mirrors read instead of tracing (set by the probe
    /// capture pass, after this one).
    pub probes: Option<Arc<Probes>>,
    /// Glass: most interface events on a traced path (`[render] max_bounces`).
    pub max_bounces: u32,
}

/// The surface a traced ray (a mirror's or glass's) found: its point, interpolated unit
/// normal, outward face normal and material.
pub struct RayHit<'a> {
    /// The point hit.
    pub p: Vec3,
    /// The shading normal, interpolated from the vertices (the face normal if that vanishes).
    pub n: Vec3,
    /// The triangle's face normal (outward, counter-clockwise).
    pub face: Vec3,
    /// The surface's material.
    pub material: &'a Material,
}

impl RayHit<'_> {
    /// (shading, geometric) normals as seen from `v`, the way back along the ray: flipped on
    /// a back face, or `None` where back faces are culled (black, as the camera sees them).
    pub fn facing(&self, v: Vec3, two_sided: bool) -> Option<(Vec3, Vec3)> {
        match self.face.dot(v) < 0.0 {
            false => Some((self.n, self.face)),
            true if two_sided => Some((-self.n, -self.face)),
            true => None,
        }
    }
}

impl EnvLighting {
    /// The surface at `hit` (a hit of [`EnvLighting::bvh`]), when the pass kept the surfaces.
    pub fn surface(&self, hit: &super::shadows::SceneHit) -> Option<RayHit<'_>> {
        let (g, materials) = self.surfaces.as_deref().map(|s| (&s.0, &s.1))?;
        let t = hit.tri as usize;
        let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
        let b0 = 1.0 - hit.b1 - hit.b2;
        let p = g.positions[i0] * b0 + g.positions[i1] * hit.b1 + g.positions[i2] * hit.b2;
        let face = g.face_normals[t];
        let n = (g.normals[i0] * b0 + g.normals[i1] * hit.b1 + g.normals[i2] * hit.b2).normalize_or(face);
        Some(RayHit { p, n, face, material: &materials[g.material[t] as usize] })
    }

    /// The pass: sampling tables of the map, and the BVH when the scene can block itself.
    pub fn build(scene: &Scene) -> EnvLighting {
        let reference = scene.settings.ibl == Ibl::Reference;
        let distribution = scene.environment.as_ref().filter(|_| reference).and_then(|e| EnvDistribution::new(&e.map));
        let prefiltered = match &scene.environment {
            Some(e) if !reference => Some(Prefiltered::cached(&e.map, scene.settings.prefilter_size).0),
            _ => None,
        };
        let split = if reference { Vec::new() } else { scene.materials.iter().filter_map(|m| m.brdf()).map(SplitSum::new).collect() };
        let bvh = can_occlude(scene).then(|| SceneBvh::build(scene));
        let mirrors = scene.materials.iter().any(traces);
        let surfaces = (bvh.is_some() && mirrors).then(|| Arc::new((scene.geometry.clone(), scene.materials.clone())));
        EnvLighting {
            env: scene.environment.clone(),
            miss: scene.camera.background,
            distribution,
            samples: scene.settings.env_samples,
            ibl: scene.settings.ibl,
            prefiltered,
            split,
            bvh,
            surfaces,
            two_sided: scene.settings.cull == crate::lesson::Cull::None,
            probes: None,
            max_bounces: scene.settings.max_bounces,
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
