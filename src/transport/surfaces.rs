//! What traced rays need beyond the lights: the scene's one ray-query structure, the
//! surfaces and materials to shade what a ray finds, the captured reflection probes, and
//! the limits of a traced path.
//!
//! Mirrors, glass and the environment's visibility trace rays; [`Tracing::prepare`] decides
//! once per render what they get, as the environment and refraction passes need it.

use super::rays::{SceneHit, SceneRays};
use crate::effects::environment::traces;
use crate::effects::probe::Probes;
use crate::effects::shadows::can_occlude;
use crate::lesson::Cull;
use crate::scene::build::Geometry;
use crate::scene::{Material, Scene};
use glam::Vec3;
use std::sync::Arc;

/// The scene's surfaces and materials, for shading what a traced ray finds.
pub type Surfaces = (Geometry, Vec<Material>);

/// What a render's traced rays (mirrors, glass, the environment's visibility) use.
#[derive(Debug, Clone, Default)]
pub struct Tracing {
    /// The scene's rays, when something traces them: the render's one [`SceneRays`].
    pub rays: Option<Arc<SceneRays>>,
    /// The scene's surfaces and materials, when a mirror or glass shades what it sees.
    pub surfaces: Option<Arc<Surfaces>>,
    /// Back faces are drawn (lit with the flipped normal).
    pub two_sided: bool,
    /// The captured reflection probes mirrors read instead of tracing (set by the probe
    /// capture pass, after the environment pass).
    pub probes: Option<Arc<Probes>>,
    /// Glass: most interface events on a traced path (`[render] max_bounces`).
    pub max_bounces: u32,
}

impl Tracing {
    /// What the passes that ran need: the `environment` pass traces the scene's rays when the
    /// scene can block itself (visibility of the environment, mirror hits), and shades hits
    /// when a material traces; `refraction` (glass) always traces and shades (a refracted
    /// ray meets its own object, even a single convex one). `rays` gives the render's one
    /// structure, built at its first use.
    pub fn prepare(scene: &Scene, environment: bool, refraction: bool, rays: impl FnOnce() -> Arc<SceneRays>) -> Tracing {
        let traced = refraction || (environment && can_occlude(scene));
        let rays = traced.then(rays);
        let shaded = refraction || (rays.is_some() && scene.materials.iter().any(traces));
        Tracing {
            rays,
            surfaces: shaded.then(|| Arc::new((scene.geometry.clone(), scene.materials.clone()))),
            two_sided: scene.spec.settings.cull == Cull::None,
            probes: None,
            max_bounces: scene.spec.settings.max_bounces,
        }
    }

    /// The surface at `hit` (a hit of [`Tracing::rays`]), when the surfaces are kept.
    pub fn surface(&self, hit: &SceneHit) -> Option<RayHit<'_>> {
        let (g, materials) = self.surfaces.as_deref().map(|s| (&s.0, &s.1))?;
        Some(surface_at(g, materials, hit))
    }
}

/// The surface of `g` at `hit`: the point and the normal interpolated with the hit's
/// barycentrics (the face normal where the normals cancel), the face normal and the material.
pub fn surface_at<'a>(g: &Geometry, materials: &'a [Material], hit: &SceneHit) -> RayHit<'a> {
    let t = hit.tri as usize;
    let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
    let b0 = 1.0 - hit.b1 - hit.b2;
    let p = g.positions[i0] * b0 + g.positions[i1] * hit.b1 + g.positions[i2] * hit.b2;
    let face = g.face_normals[t];
    let n = (g.normals[i0] * b0 + g.normals[i1] * hit.b1 + g.normals[i2] * hit.b2).normalize_or(face);
    RayHit { p, n, face, material: &materials[g.material[t] as usize] }
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
