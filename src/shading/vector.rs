//! Reflection and half vectors in the course's convention (all vectors point away from the surface).

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
    fn half_vector_is_defined_when_l_is_minus_v() {
        let n = Vec3::Z;
        assert_eq!(half_vector(Vec3::X, -Vec3::X, n), n);
        let h = half_vector(Vec3::X, Vec3::Z, n);
        assert!((h - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
    }
}
