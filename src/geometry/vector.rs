//! Reflection, refraction and half vectors in the course's convention (all vectors point away
//! from the surface).

use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// Mirror reflection of `l` about `n`: R = 2(L·N)N − L.
///
/// Unlike glam's `Vec3::reflect`, which takes the incoming direction (towards the
/// surface), `l` here points away from the surface, towards the light.
/// Preconditions: `n` is normalized; the result has the length of `l`.
#[inline]
pub fn reflect(l: Vec3, n: Vec3) -> Vec3 {
    2.0 * l.dot(n) * n - l
}

/// Refraction of `v` (unit, pointing away from the surface on the side `n` points to) into
/// the other side: T = −η_r v + (η_r cos θ_i − cos θ_t) n with η_r = 1/`eta`,
/// cos θ_i = n·v and cos² θ_t = 1 − η_r² (1 − cos² θ_i) (Snell's law; pbrt-v4 `Refract`,
/// with `eta` = η_t/η_i, the index of the side `n` points away from over the index of `v`'s side).
///
/// Returns `None` on total internal reflection (cos² θ_t < 0). Like pbrt, a `v` below the
/// surface (n·v < 0) is refracted from the other side: `n` is flipped and `eta` inverted.
/// The result is unit length and points away from the surface, into the far side.
/// Preconditions: `n` and `v` normalized, `eta` > 0.
#[inline]
pub fn refract(v: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let (mut n, mut eta, mut cos_i) = (n, eta, n.dot(v));
    if cos_i < 0.0 {
        (n, eta, cos_i) = (-n, 1.0 / eta, -cos_i);
    }
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(-v / eta + (cos_i / eta - cos_t) * n)
}

/// Half vector H = normalize(L + V); for l = −v (undefined) returns `n`.
#[inline]
pub fn half_vector(l: Vec3, v: Vec3, n: Vec3) -> Vec3 {
    (l + v).try_normalize().unwrap_or(n)
}

/// [`reflect`] for lanes (the same operations in the same order).
#[inline(always)]
pub fn reflect_lanes<F: Lanes>(l: V3<F>, n: V3<F>) -> V3<F> {
    n.scale(F::splat(2.0) * l.dot(n)) - l
}

/// [`half_vector`] for lanes.
#[inline(always)]
pub fn half_vector_lanes<F: Lanes>(l: V3<F>, v: V3<F>, n: V3<F>) -> V3<F> {
    (l + v).normalize_or(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflect_is_the_mirror_direction() {
        let n = Vec3::Y;
        let l = Vec3::new(1.0, 1.0, 0.0).normalize();
        let r = reflect(l, n);
        assert!((r - Vec3::new(-1.0, 1.0, 0.0).normalize()).length() < 1e-6);
        // glam's reflect takes the incoming direction: reflect(l) == −glam(l).
        assert!((r + l.reflect(n)).length() < 1e-6);
    }

    #[test]
    fn refract_obeys_snells_law_and_reports_total_internal_reflection() {
        let n = Vec3::Y;
        // 45° from air into glass (η = 1.5): sin θ_t = sin 45° / 1.5.
        let v = Vec3::new(-1.0, 1.0, 0.0).normalize();
        let t = refract(v, n, 1.5).unwrap();
        assert!((t.length() - 1.0).abs() < 1e-6);
        let sin_t = (45f32.to_radians().sin() / 1.5).clamp(-1.0, 1.0);
        assert!((t.x - sin_t).abs() < 1e-6, "continues across: {t}");
        assert!((t.y + (1.0 - sin_t * sin_t).sqrt()).abs() < 1e-6, "goes below: {t}");
        // Normal incidence passes straight through.
        assert!((refract(Vec3::Y, n, 1.5).unwrap() + Vec3::Y).length() < 1e-6);
        // Equal indices: no bending.
        assert!((refract(v, n, 1.0).unwrap() + v).length() < 1e-6);
        // From glass to air beyond the critical angle asin(1/1.5) ≈ 41.8°: none.
        let grazing = Vec3::new(-(60f32.to_radians().sin()), 60f32.to_radians().cos(), 0.0);
        assert_eq!(refract(grazing, n, 1.0 / 1.5), None);
        // Just inside it: a ray, nearly tangent.
        let c = (1.0f32 / 1.5).asin() - 1e-3;
        assert!(refract(Vec3::new(-c.sin(), c.cos(), 0.0), n, 1.0 / 1.5).is_some());
        // Seen from below, the normal is flipped and η inverted: the way back reverses the way in.
        let back = refract(t, n, 1.5).unwrap();
        assert!((back - v).length() < 1e-5, "{back} vs {v}");
        // Grazing exactly (cos θ_i = 0) stays finite.
        assert!(refract(Vec3::X, n, 1.5).unwrap().is_finite());
    }

    #[test]
    fn half_vector_is_defined_when_l_is_minus_v() {
        let n = Vec3::Z;
        assert_eq!(half_vector(Vec3::X, -Vec3::X, n), n);
        let h = half_vector(Vec3::X, Vec3::Z, n);
        assert!((h - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
    }
}
