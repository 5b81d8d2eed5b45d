//! One entry point for shading a point, whatever family the material belongs to.

use super::classic::{EvalCounts, shade_classic};
use super::components::Components;
use super::physical::shade_physical;
use crate::scene::{Light, Material};
use glam::Vec3;

/// Shades one point: the course's classic equation, or L_o = Σ f E cos for a physically
/// based material. Preconditions as [`shade_classic`].
#[inline(always)]
pub fn shade(m: &Material, lights: &[Light], global_ambient: Vec3, p: Vec3, n: Vec3, v: Vec3, counts: &mut EvalCounts) -> Components {
    match &m.physical {
        Some(_) => shade_physical(m, lights, global_ambient, p, n, v, counts),
        None => shade_classic(m, lights, global_ambient, p, n, v, counts),
    }
}
