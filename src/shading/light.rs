//! What one light delivers at a surface point: direction L, attenuation d, spot factor C_spot.

use crate::scene::{Light, LightKind};
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// The incident geometry of one light at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Incident {
    /// Unit vector from the point towards the light (zero for ambient lights).
    pub l: Vec3,
    /// Distance attenuation d = 1/(S_c + S_l r + S_q r²) (1 for directional and ambient).
    pub d: f32,
    /// Spot factor C_spot = max(−L·L_dir, 0)^L_exp, 0 outside the cutoff (1 for other kinds).
    pub c_spot: f32,
}

/// [`Incident`] for lanes of points (see [`crate::simd::lanes`]).
#[derive(Debug, Clone, Copy)]
pub struct IncidentLanes<F> {
    /// Unit vector towards the light (zero for ambient lights).
    pub l: V3<F>,
    /// Distance attenuation d.
    pub d: F,
    /// Spot factor C_spot.
    pub c_spot: F,
}

/// Incident light at point `p`.
///
/// A point light at the surface point itself (r = 0) has no direction: L falls back
/// to the zero vector, so the diffuse and specular terms vanish instead of NaN.
#[inline]
pub fn incident(light: &Light, p: Vec3) -> Incident {
    let i = incident_lanes::<f32>(light, p.into());
    Incident { l: i.l.into(), d: i.d, c_spot: i.c_spot }
}

/// [`incident`] for lanes of points: the one formula, lane by lane.
#[inline(always)]
pub fn incident_lanes<F: Lanes>(light: &Light, p: V3<F>) -> IncidentLanes<F> {
    let one = F::splat(1.0);
    match light.kind {
        LightKind::Directional { direction } => IncidentLanes { l: V3::splat(-direction), d: one, c_spot: one },
        LightKind::Point { position } => {
            let (l, r) = towards(V3::splat(position), p);
            IncidentLanes { l, d: attenuation(light.attenuation, r), c_spot: one }
        }
        LightKind::Spot { position, direction, exponent, cos_cutoff } => {
            let (l, r) = towards(V3::splat(position), p);
            let cos_axis = (-l).dot(V3::splat(direction));
            // C_spot = 0 outside the cutoff or behind the light, else min(cos, 1)^L_exp.
            let outside = cos_axis.lt(F::splat(cos_cutoff)) | cos_axis.le(F::splat(0.0));
            let cos = F::select(cos_axis.lt(one), cos_axis, one);
            let c_spot = F::select(outside, F::splat(0.0), cos.pow(exponent));
            IncidentLanes { l, d: attenuation(light.attenuation, r), c_spot }
        }
        LightKind::Ambient => IncidentLanes { l: V3::zero(), d: one, c_spot: one },
    }
}

/// Unit vector from `p` to `position` and the distance.
#[inline(always)]
fn towards<F: Lanes>(position: V3<F>, p: V3<F>) -> (V3<F>, F) {
    let to = position - p;
    let r = to.length();
    let l = V3 { x: to.x / r, y: to.y / r, z: to.z / r };
    (V3::select(r.gt(F::splat(0.0)), l, V3::zero()), r)
}

/// d = 1/(S_c + S_l r + S_q r²), capped at 1/1e-12 so r → 0 with S_c = 0 stays finite.
#[inline(always)]
pub fn attenuation<F: Lanes>(s: Vec3, r: F) -> F {
    let denom = F::splat(s.x) + F::splat(s.y) * r + F::splat(s.z) * r * r;
    // max(denom, 1e-12) as f32::max: a NaN denominator gives the cap.
    let cap = F::splat(1e-12);
    F::splat(1.0) / F::select(denom.gt(cap), denom, cap)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(kind: LightKind, att: Vec3) -> Light {
        Light { kind, radiance: Vec3::ONE, ambient: Vec3::ZERO, attenuation: att }
    }

    #[test]
    fn directional_l_is_minus_direction() {
        let i = incident(&light(LightKind::Directional { direction: -Vec3::Y }, Vec3::X), Vec3::ZERO);
        assert_eq!(i.l, Vec3::Y);
        assert_eq!((i.d, i.c_spot), (1.0, 1.0));
    }

    #[test]
    fn attenuation_follows_the_course_formula() {
        let p = Vec3::new(0.0, 2.0, 0.0);
        let i = incident(&light(LightKind::Point { position: p }, Vec3::new(1.0, 0.5, 0.25)), Vec3::ZERO);
        assert!((i.d - 1.0 / (1.0 + 0.5 * 2.0 + 0.25 * 4.0)).abs() < 1e-6);
        assert_eq!(i.l, Vec3::Y);
        // r = 0 with pure inverse-square: finite.
        let at = incident(&light(LightKind::Point { position: Vec3::ZERO }, Vec3::Z), Vec3::ZERO);
        assert!(at.d.is_finite() && at.l == Vec3::ZERO);
    }

    #[test]
    fn spot_factor_is_cos_to_the_exponent_inside_the_cutoff() {
        let kind = LightKind::Spot {
            position: Vec3::new(0.0, 1.0, 0.0),
            direction: -Vec3::Y,
            exponent: 4.0,
            cos_cutoff: 30f32.to_radians().cos(),
        };
        let l = light(kind, Vec3::X);
        let on_axis = incident(&l, Vec3::ZERO);
        assert!((on_axis.c_spot - 1.0).abs() < 1e-6);
        // 20° off axis: cos(20°)^4.
        let p = Vec3::new(20f32.to_radians().tan(), 0.0, 0.0);
        assert!((incident(&l, p).c_spot - 20f32.to_radians().cos().powf(4.0)).abs() < 1e-5);
        // 40° off axis: outside the 30° cutoff.
        let q = Vec3::new(40f32.to_radians().tan(), 0.0, 0.0);
        assert_eq!(incident(&l, q).c_spot, 0.0);
    }
}
