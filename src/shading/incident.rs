//! The incident-light seam: what one light delivers at one shaded point.
//!
//! Render asks each light for its [`Incident`]s at a point (a point light: one; an area
//! light, later: one per sample) and shading turns them into [`Components`](super::Components)
//! without knowing what kind of light made them. A shadow is a `visibility` below 1; no BRDF
//! changes when shadows or area lights arrive.

use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// One light's incidence at one point, or at lanes of points (see [`crate::simd::lanes`]).
#[derive(Debug, Clone, Copy)]
pub struct Incident<F: Lanes> {
    /// Unit vector from the point towards the light; zero where the light has no direction
    /// (an ambient light, or a light exactly at the point), so direct terms vanish there.
    pub l: V3<F>,
    /// Distance r to the light (infinite for directional and ambient lights).
    pub distance: F,
    /// The classic distance attenuation d = 1/(S_c + S_l r + S_q r²) (1 when r is infinite).
    pub attenuation: F,
    /// The radiometric falloff 1/r² that physically based shading uses (1 when r is infinite).
    pub inv_r2: F,
    /// Spot factor C_spot = max(−L·L_dir, 0)^L_exp, 0 outside the cutoff (1 for other kinds).
    pub c_spot: F,
    /// Share of the light that reaches the point, in [0, 1] (1: unshadowed).
    pub visibility: F,
    /// L_diff for the classic models; E⊥ (directional) or I (point, spot) for the
    /// physically based ones, which read it for their whole BRDF.
    pub radiance: Vec3,
    /// L_spec for the classic models (equal to `radiance` unless the light's `specular` key
    /// sets it: the lecture's separate L_diff^k and L_spec^k).
    pub specular: Vec3,
    /// The light's ambient part L_amb^k.
    pub ambient: Vec3,
    /// True for a purely ambient light: it adds only its ambient part, whatever `c_spot`.
    pub ambient_only: bool,
}

/// The incident of a directional light for shading's own tests: L = `l`, d = C_spot =
/// visibility = 1 (render builds real ones from the scene's lights).
#[cfg(test)]
pub(crate) fn directional(l: Vec3, radiance: Vec3, ambient: Vec3) -> Incident<f32> {
    let (distance, one) = (f32::INFINITY, 1.0);
    Incident {
        l: l.into(),
        distance,
        attenuation: one,
        inv_r2: one,
        c_spot: one,
        visibility: one,
        radiance,
        specular: radiance,
        ambient,
        ambient_only: false,
    }
}
