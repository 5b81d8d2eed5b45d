//! Phong's specular term (Phong 1975).
//!
//! | parameter | range | meaning |
//! | --- | --- | --- |
//! | `specular` K_spec | [0, 1] RGB | strength of the highlight |
//! | `shininess` K_shi | [0, 1e6] | highlight sharpness |
//!
//! I_spec = max(R·V, 0)^K_shi K_spec ⊗ L_spec with R = 2(L·N)N − L.

use crate::geometry::vector::{reflect, reflect_lanes};
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// The Phong factor max(R·V, 0)^K_shi, zero when the light is below the surface.
///
/// Preconditions: `n`, `l`, `v` normalized. The N·L > 0 gate keeps a highlight from
/// appearing on the unlit side, where the course's figures show none.
#[inline]
pub fn phong(n: Vec3, l: Vec3, v: Vec3, shininess: f32) -> f32 {
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    specular_power(reflect(l, n).dot(v), shininess)
}

/// [`phong`] for lanes, without the N·L gate (the caller masks lanes with N·L ≤ 0).
#[inline(always)]
pub fn phong_lobe_lanes<F: Lanes>(n: V3<F>, l: V3<F>, v: V3<F>, shininess: f32) -> F {
    specular_power_lanes(reflect_lanes(l, n).dot(v), shininess)
}

/// max(c, 0)^k, finite for every k ≥ 0 (0^0 = 1, as powf defines it); the power is the
/// deterministic [`pow`](crate::simd::pow::pow) (≤ 0.5 + 2⁻¹⁷ ULP).
#[inline]
pub fn specular_power(c: f32, k: f32) -> f32 {
    specular_power_lanes(c, k)
}

/// [`specular_power`] for lanes: clamp(c, 0, 1)^k (NaN stays NaN, as `f32::clamp`).
#[inline(always)]
pub fn specular_power_lanes<F: Lanes>(c: F, k: f32) -> F {
    let (zero, one) = (F::splat(0.0), F::splat(1.0));
    let c = F::select(c.lt(zero), zero, F::select(c.gt(one), one, c));
    c.pow(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peak_is_where_r_equals_v() {
        let n = Vec3::Z;
        let l = Vec3::new(0.5, 0.0, 1.0).normalize();
        let r = reflect(l, n);
        assert!((phong(n, l, r, 50.0) - 1.0).abs() < 1e-5);
        let off = Vec3::new(-0.3, 0.2, 1.0).normalize();
        assert!(phong(n, l, off, 50.0) < 1.0);
        // Analytic value: cos of the angle between R and V, to the K_shi.
        let v = Vec3::new(0.0, 0.0, 1.0);
        let expect = r.dot(v).powf(10.0);
        assert!((phong(n, l, v, 10.0) - expect).abs() < 1e-6);
    }

    #[test]
    fn no_highlight_from_below_and_finite_extremes() {
        let n = Vec3::Z;
        assert_eq!(phong(n, -Vec3::Z, Vec3::Z, 10.0), 0.0);
        for k in [0.0, 1e-6, 1e4, 1e6] {
            let f = phong(n, Vec3::new(0.3, 0.0, 1.0).normalize(), Vec3::Z, k);
            assert!(f.is_finite() && (0.0..=1.0).contains(&f), "k={k} f={f}");
        }
    }
}
