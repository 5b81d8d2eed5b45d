//! Lights → incidents → shading: the seam between the scene's lights and shading.
//!
//! Every shaded point asks each light for its [`Incident`](crate::shading::incident::Incident)
//! (today one per light; an area light will give several, a shadowed light a visibility
//! below 1) and hands them to shading, which knows nothing of light kinds.

use crate::scene::{Light, Material};
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::shading::shade::shade;
use glam::Vec3;

/// Shades one point `p` (normal `n`, view `v`, both unit) of material `m` lit by `lights`.
#[inline]
pub fn shade_point(m: &Material, lights: &[Light], global_ambient: Vec3, p: Vec3, n: Vec3, v: Vec3, counts: &mut EvalCounts) -> Components {
    shade(m, lights.iter().map(|l| l.incident::<f32>(p.into())), global_ambient, n, v, counts)
}
