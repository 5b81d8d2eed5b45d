//! Shadows: whether each light needs them, and the shadow-map pass.
//!
//! Which light paths it counts: direct light only, blocked or not by the scene's triangles
//! (a binary visibility per light sample; soft shadows come from sampling area lights).
//! Each light's method (`ray`, `map`, `volume`, `polygons`, `none`) is chosen by the light room
//! (`light::Shadowing::choose`) with what only the scene knows: whether anything in it can
//! occlude ([`can_occlude`]). The map pass renders depth from the light with the project's
//! own rasterizer ([`map`]); the shadow-volume pass extrudes silhouettes ([`volume`]), the
//! shadow-polygon pass projects occluders onto receivers ([`polygons`]), both from what
//! [`occluders`] finds of the meshes; the visibility queries themselves, by ray through the scene's
//! one BVH or by a map lookup, are answered in `transport::visibility`.
//!
//! A light gets no shadow pass at all when nothing can block it ([`shadowing`]): a scene
//! of one convex or flat object cannot occlude itself where the shading sees the light (N·L > 0).
//! Ambient is never shadowed.

pub mod map;
pub mod occluders;
pub mod polygons;
#[cfg(target_arch = "x86_64")]
mod texels_avx512;
pub mod volume;

use crate::light::{Light, Shadowing};
use crate::scene::Scene;

pub use map::{MapDepths, ShadowMap};
pub use polygons::ShadowPolygons;
pub use volume::ShadowVolume;

/// The shadow method light `l` needs in `scene`, and why: the light's own choice
/// ([`Shadowing::choose`]) given the render's default and whether anything can occlude.
pub fn shadowing(l: &Light, scene: &Scene) -> Shadowing {
    Shadowing::choose(l, scene.spec.settings.shadows, can_occlude(scene))
}

/// True when some object can block light falling on another point of the scene: two or
/// more objects, or one that is neither convex nor flat (a torus, a mesh that is not
/// convex), or any object in a scattering medium (it shadows the medium behind it: light
/// shafts).
pub fn can_occlude(scene: &Scene) -> bool {
    let objects = &scene.geometry.objects;
    objects.len() > 1 || objects.iter().any(|o| !o.convex) || (!objects.is_empty() && crate::effects::fog::scatters(scene))
}
