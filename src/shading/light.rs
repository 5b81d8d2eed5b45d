//! What one light delivers at a surface point: direction L, attenuation d, spot factor C_spot.

use crate::scene::{Light, LightKind};
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

/// Incident light at point `p`.
///
/// A point light at the surface point itself (r = 0) has no direction: L falls back
/// to the zero vector, so the diffuse and specular terms vanish instead of NaN.
#[inline]
pub fn incident(light: &Light, p: Vec3) -> Incident {
    match light.kind {
        LightKind::Directional { direction } => Incident { l: -direction, d: 1.0, c_spot: 1.0 },
        LightKind::Point { position } => {
            let (l, r) = towards(position, p);
            Incident { l, d: attenuation(light.attenuation, r), c_spot: 1.0 }
        }
        LightKind::Spot { position, direction, exponent, cos_cutoff } => {
            let (l, r) = towards(position, p);
            let cos_axis = (-l).dot(direction);
            let c_spot = if cos_axis < cos_cutoff || cos_axis <= 0.0 { 0.0 } else { cos_axis.min(1.0).powf(exponent) };
            Incident { l, d: attenuation(light.attenuation, r), c_spot }
        }
        LightKind::Ambient => Incident { l: Vec3::ZERO, d: 1.0, c_spot: 1.0 },
    }
}

/// Unit vector from `p` to `position` and the distance.
#[inline]
fn towards(position: Vec3, p: Vec3) -> (Vec3, f32) {
    let to = position - p;
    let r = to.length();
    (if r > 0.0 { to / r } else { Vec3::ZERO }, r)
}

/// d = 1/(S_c + S_l r + S_q r²), capped at 1/1e-12 so r → 0 with S_c = 0 stays finite.
#[inline]
pub fn attenuation(s: Vec3, r: f32) -> f32 {
    1.0 / (s.x + s.y * r + s.z * r * r).max(1e-12)
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
