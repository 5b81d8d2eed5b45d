//! Visibility: how each light's share of light reaching a point is found in one render, by
//! the method its shadowing chose — a shadow ray through the scene's one BVH
//! ([`SceneRays`](super::rays::SceneRays), or exact analytic shapes for the cost references),
//! a lookup in its shadow map (`effects::shadows::map`), a count of its shadow volumes'
//! faces along the eye's ray (`effects::shadows::volume`), a point-in-polygon test against
//! its receiver's shadow polygons (`effects::shadows::polygons`), or none.
//!
//! The counts of rays and texels are kept per worker thread and read by each strip, so they
//! add up the same for any thread count.

use super::rays::{Occluders, Origin};
use crate::effects::shadows::{ShadowMap, ShadowPolygons, ShadowVolume};
use crate::simd::lanes::MAX_WIDTH;
use glam::Vec3;
use std::cell::Cell;

/// The count of shadow rays traced (`RenderStats::counters`).
pub const SHADOW_RAYS: &str = "shadow rays traced";
/// The count of shadow-map lookups (one per light per shaded point; each filters `shadow_pcf` texels).
pub const SHADOW_MAP_LOOKUPS: &str = "shadow-map lookups";

/// How one light's visibility is found in this render.
#[derive(Debug, Clone)]
pub enum LightShadow {
    /// Nothing blocks it (method `none`, an ambient light, or no possible occluder).
    Unshadowed,
    /// Shadow rays through the BVH.
    Ray,
    /// Looked up in its shadow map.
    Map(Box<ShadowMap>),
    /// Counted against its shadow volumes.
    Volume(Box<ShadowVolume>),
    /// Tested against its receivers' shadow polygons.
    Polygons(Box<ShadowPolygons>),
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
            LightShadow::Volume(v) => {
                // A triangle's point is a visible sample (Phong); a vertex, a face centre
                // or a point in fog may be hidden, so its count includes the caps.
                let visible = o.tri != u32::MAX;
                count(|c| c.volume_tests += v.tests(visible));
                v.visibility(o.p, visible)
            }
            LightShadow::Polygons(p) => {
                let (vis, tests) = p.visibility(o.p, o.tri);
                count(|c| c.polygon_tests += tests);
                vis
            }
        }
    }

    /// [`Shadows::visibility`] for the lanes whose bit is set in `want` (1 elsewhere): shadow
    /// rays as one packet through the scene's rays, map lookups and analytic rays lane by lane.
    /// The caller counts the queries.
    pub fn visibility_lanes(
        &self,
        i: usize,
        origins: &[Origin; MAX_WIDTH],
        l: &[Vec3; MAX_WIDTH],
        distance: &[f32; MAX_WIDTH],
        want: u16,
    ) -> [f32; MAX_WIDTH] {
        let mut vis = [1f32; MAX_WIDTH];
        if want == 0 {
            return vis;
        }
        if let (LightShadow::Ray, Some(Occluders::Meshes(rays))) = (&self.per_light[i], &self.occluders) {
            let hit = rays.occluded_packet(origins, l, distance, want);
            for (j, v) in vis.iter_mut().enumerate() {
                if hit & (1 << j) != 0 {
                    *v = 0.0;
                }
            }
            return vis;
        }
        for (j, v) in vis.iter_mut().enumerate() {
            if want & (1 << j) != 0 {
                *v = self.visibility(i, &origins[j], l[j], distance[j]);
            }
        }
        vis
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
            // Volumes and polygons count their tests as they make them.
            LightShadow::Unshadowed | LightShadow::Volume(_) | LightShadow::Polygons(_) => {}
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
    /// Shadow-volume quads (and caps) tested.
    pub volume_tests: u64,
    /// Shadow polygons tested.
    pub polygon_tests: u64,
}

impl ShadowCounts {
    /// The work done between reading `before` and this reading.
    pub fn since(self, before: ShadowCounts) -> ShadowCounts {
        ShadowCounts {
            rays: self.rays - before.rays,
            lookups: self.lookups - before.lookups,
            volume_tests: self.volume_tests - before.volume_tests,
            polygon_tests: self.polygon_tests - before.polygon_tests,
        }
    }

    /// Both counts added.
    pub fn plus(self, o: ShadowCounts) -> ShadowCounts {
        ShadowCounts {
            rays: self.rays + o.rays,
            lookups: self.lookups + o.lookups,
            volume_tests: self.volume_tests + o.volume_tests,
            polygon_tests: self.polygon_tests + o.polygon_tests,
        }
    }
}

thread_local! {
    static COUNTS: Cell<ShadowCounts> =
        const { Cell::new(ShadowCounts { rays: 0, lookups: 0, volume_tests: 0, polygon_tests: 0 }) };
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
