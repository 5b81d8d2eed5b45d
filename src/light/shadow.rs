//! How a light's visibility is found: the shadow methods, and the one place a light's
//! method is chosen ([`Shadowing::choose`]).
//!
//! Each light uses the `[render] shadows` method unless it sets its own `shadows`:
//! - `ray`: a shadow ray per light (sample) per shaded point, any-hit: exact hard shadows,
//!   the reference;
//! - `map`: the two-pass method, depth rendered from the light by the project's own
//!   rasterizer, then compared (directional, point and spot lights; a light with extent is
//!   sampled by rays, since a map sees from one point);
//! - `volume`: shadow volumes (Crow 1977), `effects::shadows::volume` (point, spot and
//!   directional lights);
//! - `polygons`: two-pass object-space shadow polygons (Atherton, Weiler & Greenberg 1978),
//!   `effects::shadows::polygons` (the same lights);
//! - `none`: nothing blocks light.
//!
//! Ambient light is never shadowed, and no light is when nothing in the scene can block it
//! (the caller says so: `effects::shadows::can_occlude`).

pub use crate::lesson::kinds::ShadowMethod;

use super::{Light, LightKind};

/// Why a light is or is not shadowed, and by which method: the plan prints it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shadowing {
    /// The method that runs, `None` when no shadow work is done for this light.
    pub method: Option<ShadowMethod>,
    /// Why.
    pub why: &'static str,
}

impl Shadowing {
    /// The shadow method of light `l` when the render's default is `default` and the scene
    /// `can_occlude` (something can block light falling on another point), and why.
    pub fn choose(l: &Light, default: ShadowMethod, can_occlude: bool) -> Shadowing {
        let method = l.shadows.unwrap_or(default);
        let none = |why| Shadowing { method: None, why };
        if matches!(l.kind, LightKind::Ambient) {
            return none("ambient light is never shadowed");
        }
        if method == ShadowMethod::None {
            return none("shadows = \"none\"");
        }
        if !can_occlude {
            return none("nothing can block it: one convex or flat object shadows only where N·L ≤ 0 (and no medium scatters)");
        }
        if method == ShadowMethod::Map && l.kind.is_sampled() {
            // A shadow map sees from one point: an emitter with extent is sampled by rays.
            return Shadowing {
                method: Some(ShadowMethod::Ray),
                why: "shadow rays (a shadow map cannot see from every point of an area light)",
            };
        }
        if matches!(method, ShadowMethod::Volume | ShadowMethod::Polygons) && l.kind.is_sampled() {
            // Only the render's default can ask this (a light's own key is refused): volumes
            // and shadow polygons are cast from one point.
            return Shadowing {
                method: Some(ShadowMethod::Ray),
                why: "shadow rays (shadow volumes and shadow polygons are cast from one point, not from an area light)",
            };
        }
        let why = match method {
            ShadowMethod::Ray => "shadow rays",
            ShadowMethod::Map => "shadow map",
            ShadowMethod::Volume => "shadow volumes (Crow 1977): silhouette edges extruded from the light, z-pass count from the eye",
            _ => "shadow polygons (Atherton, Weiler & Greenberg 1978): occluders projected onto each receiver from the light",
        };
        Shadowing { method: Some(method), why }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::{Directional, Rect};
    use glam::Vec3;

    fn light(kind: LightKind, shadows: Option<ShadowMethod>) -> Light {
        Light { kind, radiance: Vec3::ONE, specular: Vec3::ONE, ambient: Vec3::ZERO, attenuation: Vec3::X, samples: 4, shadows }
    }

    #[test]
    fn a_light_takes_its_own_method_the_default_or_none_with_its_reason() {
        let sun = light(LightKind::Directional(Directional { direction: -Vec3::Y }), None);
        assert_eq!(Shadowing::choose(&sun, ShadowMethod::Map, true).method, Some(ShadowMethod::Map));
        let own = light(LightKind::Directional(Directional { direction: -Vec3::Y }), Some(ShadowMethod::Ray));
        assert_eq!(Shadowing::choose(&own, ShadowMethod::Map, true).method, Some(ShadowMethod::Ray));
        assert_eq!(Shadowing::choose(&sun, ShadowMethod::Ray, false).method, None);
        assert_eq!(Shadowing::choose(&light(LightKind::Ambient, None), ShadowMethod::Ray, true).method, None);
        let panel = Rect { position: Vec3::Y, direction: -Vec3::Y, half_w: Vec3::X, half_h: Vec3::Z, sampling: Default::default() };
        let s = Shadowing::choose(&light(LightKind::Rect(panel), None), ShadowMethod::Map, true);
        assert_eq!(s.method, Some(ShadowMethod::Ray), "an area light falls back to rays");
        assert!(s.why.contains("area light"));
        for m in [ShadowMethod::Volume, ShadowMethod::Polygons] {
            assert_eq!(Shadowing::choose(&sun, m, true).method, Some(m), "a directional light keeps {m:?}");
            let s = Shadowing::choose(&light(LightKind::Rect(panel), None), m, true);
            assert_eq!(s.method, Some(ShadowMethod::Ray), "an area light under the render's {m:?} falls back to rays");
            assert!(s.why.contains("cast from one point"));
        }
    }
}
