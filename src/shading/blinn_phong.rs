//! Blinn's half-vector variant of the Phong highlight (Blinn 1977).
//!
//! | parameter | range | meaning |
//! | --- | --- | --- |
//! | `specular` K_spec | [0, 1] RGB | strength of the highlight |
//! | `shininess` K_shi | [0, 1e6] | highlight sharpness |
//!
//! I_spec = max(N·H, 0)^K_shi K_spec ⊗ L_spec with H = normalize(L + V).

use super::phong::{specular_power, specular_power_lanes};
use crate::geometry::vector::{half_vector, half_vector_lanes};
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// The Blinn-Phong factor max(N·H, 0)^K_shi, zero when the light is below the surface.
///
/// Preconditions: `n`, `l`, `v` normalized.
#[inline]
pub fn blinn_phong(n: Vec3, l: Vec3, v: Vec3, shininess: f32) -> f32 {
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    specular_power(n.dot(half_vector(l, v, n)), shininess)
}

/// [`blinn_phong`] for lanes, without the N·L gate (the caller masks lanes with N·L ≤ 0).
#[inline(always)]
pub fn blinn_phong_lobe_lanes<F: Lanes>(n: V3<F>, l: V3<F>, v: V3<F>, shininess: f32) -> F {
    specular_power_lanes(n.dot(half_vector_lanes(l, v, n)), shininess)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peak_when_h_equals_n_and_wider_than_phong() {
        let n = Vec3::Z;
        let l = Vec3::new(0.4, 0.0, 1.0).normalize();
        let v = Vec3::new(-0.4, 0.0, 1.0).normalize();
        assert!((blinn_phong(n, l, v, 80.0) - 1.0).abs() < 1e-5);
        // Off the mirror direction, N·H falls more slowly than R·V: at equal K_shi the
        // Blinn-Phong highlight is wider (the half-angle is about half the Phong angle).
        let v2 = Vec3::new(0.0, 0.3, 1.0).normalize();
        assert!(blinn_phong(n, l, v2, 20.0) > super::super::phong::phong(n, l, v2, 20.0));
    }

    #[test]
    fn l_equals_minus_v_is_finite() {
        let n = Vec3::Z;
        let l = Vec3::new(1.0, 0.0, 1e-3).normalize();
        assert!(blinn_phong(n, l, -l, 5.0).is_finite());
    }
}
