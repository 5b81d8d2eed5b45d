//! Shadows: whether each light needs them, and the visibility of a light seen from a point.
//!
//! Which light paths it counts: direct light only, blocked or not by the scene's triangles
//! (a binary visibility per light sample; soft shadows come from sampling area lights).
//! Each light uses the `[render] shadows` method unless it sets its own `shadows`:
//! - `ray` ([`rays`]): a shadow ray per light (sample) per shaded point through the BVH of
//!   `geometry::bvh`, any-hit: exact hard shadows, the reference;
//! - `map` ([`map`]): the two-pass method, depth rendered from the light by the project's
//!   own rasterizer, then compared;
//! - `none`: nothing blocks light.
//!
//! A light gets no shadow pass at all when nothing can block it ([`Shadowing::of`]): a scene
//! of one convex or flat object cannot occlude itself where the shading sees the light (N·L > 0).
//! Ambient is never shadowed. The counts of rays and texels are kept per worker thread and
//! read by each strip, so they add up the same for any thread count.

pub mod map;
pub mod rays;
#[cfg(target_arch = "x86_64")]
mod texels_avx512;

use crate::lesson::settings::ShadowMethod;
use crate::scene::{Light, LightKind, Scene};
use glam::Vec3;
use std::cell::Cell;

pub use map::ShadowMap;
pub use rays::{Occluders, SceneBvh, SceneHit};

/// How one light's visibility is found in this render.
#[derive(Debug, Clone)]
pub enum LightShadow {
    /// Nothing blocks it (method `none`, an ambient light, or no possible occluder).
    Unshadowed,
    /// Shadow rays through the BVH.
    Ray,
    /// Looked up in its shadow map.
    Map(Box<ShadowMap>),
}

/// Why a light is or is not shadowed, and by which method: the plan prints it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shadowing {
    /// The method that runs, `None` when no shadow work is done for this light.
    pub method: Option<ShadowMethod>,
    /// Why.
    pub why: &'static str,
}

impl Shadowing {
    /// The shadow method light `l` needs in `scene`, and why (the one place it is decided).
    pub fn of(l: &Light, scene: &Scene) -> Shadowing {
        let method = l.shadows.unwrap_or(scene.settings.shadows);
        let none = |why| Shadowing { method: None, why };
        if matches!(l.kind, LightKind::Ambient) {
            return none("ambient light is never shadowed");
        }
        if method == ShadowMethod::None {
            return none("shadows = \"none\"");
        }
        if !can_occlude(scene) {
            return none("nothing can block it: one convex or flat object shadows only where N·L ≤ 0 (and no medium scatters)");
        }
        if method == ShadowMethod::Map && l.kind.is_sampled() {
            // A shadow map sees from one point: an emitter with extent is sampled by rays.
            return Shadowing {
                method: Some(ShadowMethod::Ray),
                why: "shadow rays (a shadow map cannot see from every point of an area light)",
            };
        }
        Shadowing { method: Some(method), why: if method == ShadowMethod::Ray { "shadow rays" } else { "shadow map" } }
    }
}

/// True when some object can block light falling on another point of the scene: two or
/// more objects, or one that is neither convex nor flat (a torus, a mesh), or any object in
/// a scattering medium (it shadows the medium behind it: light shafts).
pub fn can_occlude(scene: &Scene) -> bool {
    let objects = &scene.geometry.objects;
    objects.len() > 1 || objects.iter().any(|o| !o.convex) || (!objects.is_empty() && crate::effects::fog::scatters(scene))
}

/// What a shadow query starts from: a shaded point on the surface.
#[derive(Debug, Clone, Copy)]
pub struct Origin {
    /// The point.
    pub p: Vec3,
    /// Unit geometric normal (the face's; for a vertex, its shading normal).
    pub ng: Vec3,
    /// Its triangle, or `u32::MAX` for a vertex.
    pub tri: u32,
    /// Its object.
    pub object: u32,
}

/// Every light's shadow state for one render, in the order of the renderer's lights.
#[derive(Debug, Clone, Default)]
pub struct Shadows {
    /// Per light.
    pub per_light: Vec<LightShadow>,
    /// The ray-query structure, when a light uses rays.
    pub occluders: Option<Occluders>,
}

impl Shadows {
    /// No light shadowed (the state of a render without shadow passes).
    pub fn unshadowed(n_lights: usize) -> Shadows {
        Shadows { per_light: vec![LightShadow::Unshadowed; n_lights], occluders: None }
    }

    /// The shadow state of the lights with what shadow rays are traced against (built by the
    /// ray pass, when a light needs it) and each light's map (built by the map pass).
    pub fn new(per_light: Vec<LightShadow>, occluders: Option<Occluders>) -> Shadows {
        Shadows { per_light, occluders }
    }

    /// True when light `i` is shadowed at all.
    #[inline(always)]
    pub fn casts(&self, i: usize) -> bool {
        !matches!(self.per_light[i], LightShadow::Unshadowed)
    }

    /// The share of light `i` arriving at `o` from direction `l` (unit, towards the light)
    /// over `distance` (infinite for directional lights): 0 or 1 for a ray, a filtered share
    /// for a map. Precondition: the light is front-facing at `o` (N·L > 0). The caller
    /// counts its queries ([`Shadows::counted`]).
    pub fn visibility(&self, i: usize, o: &Origin, l: Vec3, distance: f32) -> f32 {
        match &self.per_light[i] {
            LightShadow::Unshadowed => 1.0,
            LightShadow::Ray => match &self.occluders {
                Some(occluders) if occluders.occluded(o, l, distance) => 0.0,
                _ => 1.0,
            },
            LightShadow::Map(m) => m.visibility(o.p, o.ng, l),
        }
    }

    /// The shadow map of light `i` when its lookups run in lanes ([`ShadowMap::has_lanes`]).
    #[inline(always)]
    pub fn lane_map(&self, i: usize) -> Option<&ShadowMap> {
        match &self.per_light[i] {
            LightShadow::Map(m) if m.has_lanes() => Some(m),
            _ => None,
        }
    }

    /// Adds `queries` visibility queries of light `i` to this thread's counts (once per
    /// bundle of lanes, not per query: a thread-local update per query cost 2% of a frame).
    #[inline]
    pub fn counted(&self, i: usize, queries: u64) {
        match self.per_light[i] {
            LightShadow::Unshadowed => {}
            LightShadow::Ray => count(|c| c.rays += queries),
            LightShadow::Map(_) => count(|c| c.lookups += queries),
        }
    }
}

/// Shadow work done on this thread: read before and after a strip.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ShadowCounts {
    /// Shadow rays traced.
    pub rays: u64,
    /// Shadow-map lookups.
    pub lookups: u64,
}

thread_local! {
    static COUNTS: Cell<ShadowCounts> = const { Cell::new(ShadowCounts { rays: 0, lookups: 0 }) };
}

#[inline(always)]
fn count(f: impl FnOnce(&mut ShadowCounts)) {
    COUNTS.with(|c| {
        let mut v = c.get();
        f(&mut v);
        c.set(v);
    });
}

/// The shadow work this thread has done so far (subtract two readings for a strip's share).
pub fn thread_counts() -> ShadowCounts {
    COUNTS.with(Cell::get)
}
