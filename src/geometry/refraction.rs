//! Refraction through a sphere in closed form, the course's construction.
//!
//! With the course's V (unit, from the surface towards the viewer), the outward unit normal
//! n at the entry point p and the relative index n₁₂ = n₂/n₁ (Snell: n₁ sin θ₁ = n₂ sin θ₂):
//!
//! - entry direction t = (1/n₁₂)[((V·n) − √(n₁₂² − 1 + (V·n)²)) n − V]; a negative radicand
//!   is total internal reflection (only possible for n₁₂ < 1);
//! - exit point h = p + d t with the chord d = −2r(n·t) (r the radius);
//! - exit direction e = cos θ₁ n(h) + sin θ₁ τ/‖τ‖, τ = t − (t·n(h)) n(h) the tangential part
//!   of t at h: by symmetry the ray leaves at the angle it entered. At normal incidence τ = 0
//!   and e = n(h); for n₁₂ = 1, t = −V and e = −V (the identity).
//!
//! It is the reference the traced path of `glass` is tested against (f64 throughout).

use glam::DVec3;

/// The course's refracted direction t (unit, into the surface) of `v` (unit, away from the
/// surface on the side `n` faces) for n₁₂ = `n12`; `None` on total internal reflection.
/// Preconditions: `v`, `n` unit, n·v ≥ 0, `n12` > 0.
pub fn refract_course(v: DVec3, n: DVec3, n12: f64) -> Option<DVec3> {
    let c = v.dot(n);
    // n₁₂² − 1 + (V·n)² as (n₁₂ − 1)(n₁₂ + 1) + c²: exact near n₁₂ = 1, so 1 is the identity.
    let radicand = (n12 - 1.0) * (n12 + 1.0) + c * c;
    if radicand < 0.0 {
        return None;
    }
    Some(((c - radicand.sqrt()) * n - v) / n12)
}

/// A ray's way through a sphere: the direction inside, the exit point and the direction out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpherePath {
    /// t: the unit direction inside the sphere.
    pub inside: DVec3,
    /// h: where the ray leaves.
    pub exit: DVec3,
    /// e: the unit direction after leaving.
    pub out: DVec3,
}

/// The path through the sphere (`centre`, `radius`) of a ray arriving at the surface point
/// `p` from the direction `v` (unit, pointing from `p` back towards where the ray came from),
/// refracting twice with n₁₂ = `n12`; `None` on total internal reflection at entry or when
/// `v` comes from inside (n·V < 0). Preconditions: `p` on the sphere, `radius` > 0.
pub fn sphere_path(centre: DVec3, radius: f64, p: DVec3, v: DVec3, n12: f64) -> Option<SpherePath> {
    let n = (p - centre) / radius;
    let cos1 = v.dot(n);
    if cos1 < 0.0 {
        return None;
    }
    let t = refract_course(v, n, n12)?;
    let d = -2.0 * radius * n.dot(t);
    let exit = p + d * t;
    let nh = (exit - centre) / radius;
    let tau = t - t.dot(nh) * nh;
    let sin1 = (1.0 - cos1 * cos1).max(0.0).sqrt();
    // τ = 0 at normal incidence (and sin θ₁ = 0 there): the ray leaves along n(h).
    let out = match tau.try_normalize() {
        Some(u) => cos1 * nh + sin1 * u,
        None => nh,
    };
    Some(SpherePath { inside: t, exit, out })
}

/// The critical angle θ_c = arcsin(n₂/n₁) in radians, beyond which light in the medium of
/// index `n1` is totally reflected at a boundary with `n2`; `None` unless n₁ > n₂.
pub fn critical_angle(n1: f64, n2: f64) -> Option<f64> {
    (n1 > n2 && n2 > 0.0).then(|| (n2 / n1).asin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::analytic::{Analytic, AnalyticKind};
    use crate::geometry::ray::Ray;
    use crate::geometry::vector::refract;
    use glam::DAffine3;

    /// The traced path with the renderer's pieces: `vector::refract` (f32) at each interface and
    /// the exact sphere intersection for the exit point.
    fn traced(sphere: &Analytic, centre: DVec3, p: DVec3, v: DVec3, eta: f64) -> Option<(DVec3, DVec3, DVec3)> {
        let n = sphere.normal(p - centre);
        let t = refract(v.as_vec3(), n.as_vec3(), eta as f32)?.as_dvec3();
        let [_, far] = sphere.intersect(&Ray { origin: p, dir: t });
        let (s, _) = far?;
        let h = p + t * s;
        let nh = (h - centre).normalize();
        // From inside: v = −t with n(h) outward, so `refract` flips n and inverts η itself.
        let e = refract((-t).as_vec3(), nh.as_vec3(), eta as f32)?.as_dvec3();
        Some((t, h, e))
    }

    #[test]
    fn the_closed_form_and_the_traced_path_agree_on_a_sphere() {
        let (centre, radius) = (DVec3::new(0.3, -0.2, 0.1), 1.7);
        let sphere = Analytic::new(
            AnalyticKind::Sphere,
            DAffine3::from_scale_rotation_translation(DVec3::splat(radius), Default::default(), centre),
        )
        .unwrap();
        let mut checked = 0;
        for eta in [1.0, 1.05, 1.2, 1.33, 1.5, 2.4] {
            for i in 0..40 {
                // Entry points from normal incidence to 85° off it. Nearer grazing the exit angle
                // amplifies the traced path's f32 rounding by η² sin θ₂ / cos θ₁ (137 at 89° for
                // η = 2.4: measured 1.7e-5 there), an f32 limit, not a difference of the paths.
                let theta = (i as f64 / 39.0) * 85f64.to_radians();
                let phi = i as f64 * 2.39996;
                let n = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
                let p = centre + radius * n;
                let v = DVec3::Z; // camera far along +z: every ray arrives travelling −z
                let closed = sphere_path(centre, radius, p, v, eta).unwrap();
                let (t, h, e) = traced(&sphere, centre, p, v, eta).unwrap();
                for (a, b, what) in [(closed.inside, t, "inside"), (closed.exit, h, "exit"), (closed.out, e, "out")] {
                    let tol = if what == "exit" { 1e-5 * radius } else { 1e-5 };
                    assert!((a - b).length() < tol, "η {eta}, θ {:.1}°: {what} {a} vs {b}", theta.to_degrees());
                }
                checked += 1;
            }
        }
        assert_eq!(checked, 240);
    }

    #[test]
    fn an_index_ratio_of_one_passes_rays_straight_through() {
        let v = DVec3::new(0.3, 0.4, 0.866).normalize();
        let p = DVec3::new(0.6, 0.0, 0.8);
        let path = sphere_path(DVec3::ZERO, 1.0, p, v, 1.0).unwrap();
        assert!((path.inside + v).length() < 1e-15);
        assert!((path.out + v).length() < 1e-12, "{}", path.out);
        // The exit point is on the straight line through p, on the sphere.
        assert!(((path.exit - p).normalize() + v).length() < 1e-12);
        assert!((path.exit.length() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn normal_incidence_goes_through_the_centre_without_nan() {
        let path = sphere_path(DVec3::ZERO, 2.0, DVec3::new(0.0, 0.0, 2.0), DVec3::Z, 1.5).unwrap();
        assert_eq!(path.inside, -DVec3::Z);
        assert_eq!(path.exit, DVec3::new(0.0, 0.0, -2.0));
        assert_eq!(path.out, -DVec3::Z);
        // Grazing incidence (θ₁ = 90°): the ray enters at the critical angle and stays finite.
        let grazing = sphere_path(DVec3::ZERO, 1.0, DVec3::X, DVec3::Z, 1.5).unwrap();
        assert!(grazing.inside.is_finite() && grazing.exit.is_finite() && grazing.out.is_finite());
        assert!((grazing.inside.dot(-DVec3::X) - (1.0 - 1.0 / 2.25f64).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn the_critical_angle_is_arcsin_n2_over_n1() {
        let theta_c = critical_angle(1.5, 1.0).unwrap();
        assert!((theta_c - (1.0f64 / 1.5).asin()).abs() < 1e-15);
        assert!((theta_c.to_degrees() - 41.8103148958).abs() < 1e-9);
        assert_eq!(critical_angle(1.0, 1.5), None);
        // Seen from the glass (n₁₂ = 1/1.5): just inside θ_c the ray leaves, just beyond it is reflected.
        let at = |theta: f64| refract_course(DVec3::new(theta.sin(), 0.0, theta.cos()), DVec3::Z, 1.0 / 1.5);
        assert!(at(theta_c - 1e-9).is_some());
        assert!(at(theta_c + 1e-9).is_none());
        // And the renderer's `refract` agrees on where total internal reflection starts.
        let f32_at = |theta: f64| refract(DVec3::new(theta.sin(), 0.0, theta.cos()).as_vec3(), glam::Vec3::Z, 1.0 / 1.5);
        assert!(f32_at(theta_c - 1e-4).is_some() && f32_at(theta_c + 1e-4).is_none());
    }

    /// A ball lens brings paraxial rays to a focus n r / (2(n − 1)) from its centre
    /// (Hecht, Optics, §6.2: the effective focal length of a sphere).
    #[test]
    fn a_ball_lens_focuses_at_n_r_over_2_n_minus_1() {
        for (n, r) in [(1.5, 1.0), (1.33, 2.0), (1.9, 0.5)] {
            let y = 1e-4 * r; // paraxial: spherical aberration grows as y²
            let p = DVec3::new(0.0, y, (r * r - y * y).sqrt());
            let path = sphere_path(DVec3::ZERO, r, p, DVec3::Z, n).unwrap();
            // Where the exit ray crosses the axis y = 0.
            let s = -path.exit.y / path.out.y;
            let focus = -(path.exit.z + s * path.out.z);
            let expected = n * r / (2.0 * (n - 1.0));
            assert!((focus - expected).abs() < 1e-6 * expected, "n {n}: {focus} vs {expected}");
        }
    }

    #[test]
    fn total_internal_reflection_has_no_path() {
        // A bubble (n₁₂ < 1) seen from the denser medium: beyond θ_c no light enters.
        let theta = 60f64.to_radians();
        let n = DVec3::new(theta.sin(), 0.0, theta.cos());
        assert_eq!(sphere_path(DVec3::ZERO, 1.0, n, DVec3::Z, 0.75), None);
        assert!(sphere_path(DVec3::ZERO, 1.0, DVec3::new(0.1, 0.0, 0.99f64.sqrt()), DVec3::Z, 0.75).is_some());
    }
}
