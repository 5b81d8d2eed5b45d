//! One entry point for shading a point, whatever family the material belongs to.

use super::classic::{EvalCounts, shade_classic};
use super::components::Components;
use super::incident::Incident;
use super::material::{Material, Model};
use super::physical::shade_physical;
use glam::Vec3;

/// Shades one point lit by `incidents`: the course's classic equation, or L_o = Σ f E cos
/// for a physically based material. Preconditions: `n`, `v` normalized.
#[inline(always)]
pub fn shade(
    m: &Material,
    incidents: impl IntoIterator<Item = Incident<f32>>,
    global_ambient: Vec3,
    n: Vec3,
    v: Vec3,
    counts: &mut EvalCounts,
) -> Components {
    match &m.model {
        Model::Physical(brdf) => shade_physical(m, brdf, incidents, global_ambient, n, v, counts),
        Model::Classic(c) => shade_classic(m, c, incidents, global_ambient, n, v, counts),
        // A delta BRDF sees no point or area light: only its emission here; its reflection
        // is traced by render.
        Model::Mirror(_) | Model::Glass(_) => Components { emission: m.emission, ..Components::ZERO },
    }
}
