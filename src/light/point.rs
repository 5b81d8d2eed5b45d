//! A point light: light from one point, attenuated by distance.
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `position` | world position |
//!
//! The classic models apply the course's attenuation d = 1/(S_c + S_l r + S_q r²) (the
//! light's `attenuation`); the physically based ones read its colour × intensity as the
//! radiant intensity I (W/sr), so E⊥ = I/r² (`inv_r2`). Shadows: by ray or by a cube of six
//! maps.

use crate::shading::incident::Incident;
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// A point light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// World position.
    pub position: Vec3,
}

impl Point {
    /// Its incident at `p`: L towards the light, the distance, d and 1/r².
    #[inline(always)]
    pub fn incident<F: Lanes>(&self, s: Vec3, p: V3<F>, unlit: Incident<F>) -> Incident<F> {
        let (l, r, inv_r2) = towards(V3::splat(self.position), p);
        Incident { l, distance: r, attenuation: attenuation(s, r), inv_r2, ..unlit }
    }
}

/// Unit vector from `p` to `position` (zero when they coincide), the distance and 1/r².
#[inline(always)]
pub(super) fn towards<F: Lanes>(position: V3<F>, p: V3<F>) -> (V3<F>, F, F) {
    let to = position - p;
    let r2 = to.dot(to);
    let r = r2.sqrt();
    let l = V3 { x: to.x / r, y: to.y / r, z: to.z / r };
    (V3::select(r.gt(F::splat(0.0)), l, V3::zero()), r, F::splat(1.0) / r2)
}

/// d = 1/(S_c + S_l r + S_q r²), capped at 1/1e-12 so r → 0 with S_c = 0 stays finite.
#[inline(always)]
pub fn attenuation<F: Lanes>(s: Vec3, r: F) -> F {
    let denom = F::splat(s.x) + F::splat(s.y) * r + F::splat(s.z) * r * r;
    // max(denom, 1e-12) as f32::max: a NaN denominator gives the cap.
    let cap = F::splat(1e-12);
    F::splat(1.0) / F::select(denom.gt(cap), denom, cap)
}
