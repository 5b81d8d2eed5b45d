//! The reference image-based lighting: Monte Carlo integration of
//! L_o(v) = ∫ L_env(l) f(l, v) (n·l) dω_l over the sphere, deterministic from a hash.
//!
//! Which light paths it counts: the environment seen directly from the shaded point (blocked
//! by the scene when it can block itself), one reflection: Mitsuba's `direct` integrator for
//! an `envmap` emitter. Two strategies share the samples: half sample the map by luminance
//! ([`EnvDistribution`]), half the BRDF (its own [`Brdf::sample`], lobe by lobe: cosine for
//! the diffuse parts, visible normals for GGX); each sample is weighted by the
//! balance heuristic of the multi-sample estimator, f L cos / (n_env p_env + n_brdf p_brdf)
//! (Veach 1997, eq. 9.12), which is unbiased and keeps both small bright light sources (the
//! map's strategy) and sharp lobes (the BRDF's) at low noise. The sample points are
//! Owen-scrambled Sobol streams seeded by a hash of the point ([`sobol_2d`], [`sobol_4d`]),
//! so a pixel has the same samples on every run and thread.

use super::distribution::EnvDistribution;
use crate::geometry::sampling::hash;
use crate::geometry::sobol::{sobol_2d, sobol_4d};
use crate::scene::Environment;
use crate::scene::environment::direction_to_uv;
use crate::shading::brdf::{Brdf, from_local, local_frame, to_local};
use glam::Vec3;

/// ∫ L_env f cos dω at a point with unit normal `n`, seen from unit `v`, by `samples` samples
/// seeded by `seed`; `visible(l)` says whether the environment is seen along the world `l`.
#[allow(clippy::too_many_arguments)]
pub fn estimate(
    brdf: &Brdf,
    n: Vec3,
    v: Vec3,
    env: &Environment,
    dist: Option<&EnvDistribution>,
    samples: u32,
    seed: u32,
    visible: impl Fn(Vec3) -> bool,
) -> Vec3 {
    let (t, b) = local_frame(n);
    let vl = to_local(v, t, b, n);
    if vl.z <= 0.0 || samples == 0 {
        return Vec3::ZERO;
    }
    let n_env = if dist.is_some() { samples.div_ceil(2) } else { 0 };
    let n_brdf = samples - n_env;
    let (ne, nb) = (n_env as f32, n_brdf as f32);
    // The lobes' probabilities once for all samples; the map coordinates once per sample
    // (the radiance and the map's pdf both read them).
    let prepared = brdf.prepare();
    let contribution = |lw: Vec3, ll: Vec3| -> Vec3 {
        if ll.z <= 0.0 {
            return Vec3::ZERO;
        }
        let f = brdf.eval(ll, vl);
        if f == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let uv = direction_to_uv(env.to_map(lw));
        let radiance = env.radiance_at(uv);
        if radiance == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let p_env = dist.map_or(0.0, |d| d.pdf_at(uv));
        let denominator = ne * p_env + nb * prepared.pdf(vl, ll);
        if denominator.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || !visible(lw) {
            return Vec3::ZERO;
        }
        f * radiance * (ll.z / denominator)
    };
    let mut sum = Vec3::ZERO;
    if let Some(dist) = dist {
        for k in 0..n_env {
            let (dm, _) = dist.sample(sobol_2d(k, seed));
            let lw = env.from_map(dm);
            sum += contribution(lw, to_local(lw, t, b, n));
        }
    }
    let seed_b = hash(seed ^ 0x0b5d_f00d);
    for k in 0..n_brdf {
        let u = sobol_4d(k, seed_b);
        // The sample's f and pdf would be at s.l; the estimate needs them at the
        // renormalized direction, so only the direction is drawn.
        if let Some((l, _, _)) = prepared.sample_direction(vl, u.x, glam::Vec2::new(u.y, u.z)) {
            let lw = from_local(l, t, b, n).normalize();
            sum += contribution(lw, to_local(lw, t, b, n));
        }
    }
    if sum.is_finite() { sum.max(Vec3::ZERO) } else { Vec3::ZERO }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sampling::sample_2d;
    use crate::scene::EnvMap;
    use crate::shading::brdf::directional_albedo;
    use crate::shading::cook_torrance::CookTorrance;
    use crate::shading::diffuse::Diffuse;
    use crate::shading::microfacet::Fresnel;
    use std::f32::consts::PI;
    use std::sync::Arc;

    fn env(map: EnvMap) -> (Environment, Option<EnvDistribution>) {
        let dist = EnvDistribution::new(&map);
        (Environment::new(Arc::new(map), Vec3::ONE, 0.0, false), dist)
    }

    /// Unit directions spread over the sphere.
    fn directions(n: u32) -> impl Iterator<Item = Vec3> {
        (0..n).map(|k| {
            let u = sample_2d(k, 99);
            let z = 1.0 - 2.0 * u.x;
            let r = (1.0 - z * z).max(0.0).sqrt();
            Vec3::new(r * (u.y * std::f32::consts::TAU).cos(), r * (u.y * std::f32::consts::TAU).sin(), z)
        })
    }

    /// The body of `estimate` before the BRDF was prepared once and the map coordinates read
    /// once a sample, kept verbatim.
    #[allow(clippy::too_many_arguments)]
    fn estimate_before(brdf: &Brdf, n: Vec3, v: Vec3, env: &Environment, dist: Option<&EnvDistribution>, samples: u32, seed: u32) -> Vec3 {
        let (t, b) = local_frame(n);
        let vl = to_local(v, t, b, n);
        if vl.z <= 0.0 || samples == 0 {
            return Vec3::ZERO;
        }
        let n_env = if dist.is_some() { samples.div_ceil(2) } else { 0 };
        let n_brdf = samples - n_env;
        let (ne, nb) = (n_env as f32, n_brdf as f32);
        let contribution = |lw: Vec3, ll: Vec3| -> Vec3 {
            if ll.z <= 0.0 {
                return Vec3::ZERO;
            }
            let f = brdf.eval(ll, vl);
            if f == Vec3::ZERO {
                return Vec3::ZERO;
            }
            let radiance = env.radiance(lw);
            if radiance == Vec3::ZERO {
                return Vec3::ZERO;
            }
            let p_env = dist.map_or(0.0, |d| d.pdf(env.to_map(lw)));
            let denominator = ne * p_env + nb * brdf.pdf(vl, ll);
            if denominator.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return Vec3::ZERO;
            }
            f * radiance * (ll.z / denominator)
        };
        let mut sum = Vec3::ZERO;
        if let Some(dist) = dist {
            for k in 0..n_env {
                let (dm, _) = dist.sample(sobol_2d(k, seed));
                let lw = env.from_map(dm);
                sum += contribution(lw, to_local(lw, t, b, n));
            }
        }
        let seed_b = hash(seed ^ 0x0b5d_f00d);
        for k in 0..n_brdf {
            let u = sobol_4d(k, seed_b);
            if let Some(s) = brdf.sample(vl, u.x, glam::Vec2::new(u.y, u.z)) {
                let lw = from_local(s.l, t, b, n).normalize();
                sum += contribution(lw, to_local(lw, t, b, n));
            }
        }
        if sum.is_finite() { sum.max(Vec3::ZERO) } else { Vec3::ZERO }
    }

    #[test]
    fn the_estimate_is_the_one_before_bit_for_bit() {
        use crate::shading::microfacet::Fresnel;
        let map = EnvMap::from_fn(64, 32, |d| {
            if d.x > 0.6 && d.y > 0.3 { Vec3::new(40.0, 30.0, 20.0) } else { Vec3::new(0.3, 0.2, 0.1) * (1.0 + d.y) }
        });
        let dist = EnvDistribution::new(&map);
        let e = Environment::new(Arc::new(map), Vec3::ONE, 30.0, false);
        let gold = Fresnel::Conductor { eta: Vec3::new(0.143, 0.374, 1.442), k: Vec3::new(3.983, 2.385, 1.603) };
        let brdfs = [
            Brdf::Diffuse(Diffuse { albedo: Vec3::new(0.8, 0.5, 0.2) }),
            Brdf::CookTorrance(CookTorrance { alpha: 0.09, fresnel: gold, diffuse: Vec3::ZERO, ..CookTorrance::default() }),
            Brdf::CookTorrance(CookTorrance { alpha: 0.5, diffuse: Vec3::splat(0.3), ..CookTorrance::default() }),
        ];
        let bits = |x: Vec3| x.to_array().map(f32::to_bits);
        for brdf in &brdfs {
            for (k, n) in directions(40).enumerate() {
                let (t, _) = local_frame(n);
                let v = (n + (k as f32 * 0.1 - 1.5) * t).normalize();
                for d in [dist.as_ref(), None] {
                    let now = estimate(brdf, n, v, &e, d, 64, k as u32, |_| true);
                    assert_eq!(bits(now), bits(estimate_before(brdf, n, v, &e, d, 64, k as u32)), "{brdf:?} at n {n:?}");
                }
            }
        }
    }

    /// The white furnace: under a constant L every Lambert point reflects ρL.
    #[test]
    fn a_lambert_surface_in_a_constant_environment_reflects_rho_l() {
        let (e, dist) = env(EnvMap::constant(Vec3::splat(1.5), 64));
        let brdf = Brdf::Diffuse(Diffuse { albedo: Vec3::new(0.8, 0.5, 0.2) });
        for (k, n) in directions(24).enumerate() {
            let (t, _) = local_frame(n);
            let v = (n + 0.7 * t).normalize();
            let got = estimate(&brdf, n, v, &e, dist.as_ref(), 1024, k as u32, |_| true);
            let want = Vec3::new(0.8, 0.5, 0.2) * 1.5;
            assert!(((got - want) / want).abs().max_element() < 0.02, "n {n:?}: {got:?} against {want:?}");
        }
    }

    /// GGX with F = 1 in the furnace reflects its directional albedo × L, never more than L.
    #[test]
    fn ggx_without_fresnel_in_a_constant_environment_reflects_its_albedo() {
        let (e, dist) = env(EnvMap::constant(Vec3::ONE, 64));
        let brdf = Brdf::CookTorrance(CookTorrance { alpha: 0.3, fresnel: Fresnel::None, ..CookTorrance::default() });
        for cos_v in [1.0f32, 0.7, 0.3] {
            let v = Vec3::new((1.0 - cos_v * cos_v).sqrt(), 0.0, cos_v);
            let got = estimate(&brdf, Vec3::Z, v, &e, dist.as_ref(), 4096, 5, |_| true).x;
            let (albedo, _) = directional_albedo(&brdf, cos_v as f64, 16);
            assert!(got <= 1.0 && (got as f64 - albedo).abs() < 0.02 * albedo, "cos θ_v {cos_v}: {got} against albedo {albedo}");
        }
    }

    /// The gradient sky L = h + (z − h) cos θ above, g below, has closed-form irradiances:
    /// facing up E = π h + 2π (z − h)/3; facing the horizon E = π h/2 + 2(z − h)/3 + π g/2.
    #[test]
    fn a_lambert_surface_under_the_gradient_sky_matches_its_closed_form() {
        let (z, h, g) = (2.0, 0.5, 0.1);
        let (e, dist) = env(EnvMap::gradient(Vec3::splat(z), Vec3::splat(h), Vec3::splat(g)));
        let brdf = Brdf::Diffuse(Diffuse { albedo: Vec3::ONE });
        let up = estimate(&brdf, Vec3::Y, Vec3::Y, &e, dist.as_ref(), 4096, 1, |_| true).x;
        let want_up = h + 2.0 * (z - h) / 3.0;
        assert!((up - want_up).abs() < 0.01 * want_up, "facing up: {up} against {want_up}");
        let side = estimate(&brdf, Vec3::Z, Vec3::Z, &e, dist.as_ref(), 4096, 2, |_| true).x;
        let want_side = (PI * h / 2.0 + 2.0 * (z - h) / 3.0 + PI * g / 2.0) / PI;
        assert!((side - want_side).abs() < 0.01 * want_side, "facing the horizon: {side} against {want_side}");
        let down = estimate(&brdf, -Vec3::Y, -Vec3::Y, &e, dist.as_ref(), 4096, 3, |_| true).x;
        assert!((down - g).abs() < 0.01 * g, "facing down: {down} against {g}");
    }

    #[test]
    fn the_estimate_is_finite_and_zero_when_the_view_is_below_the_surface() {
        let (e, dist) = env(EnvMap::gradient(Vec3::ONE, Vec3::ONE, Vec3::ZERO));
        let brdf = Brdf::CookTorrance(CookTorrance { alpha: 1e-6, ..CookTorrance::default() });
        assert_eq!(estimate(&brdf, Vec3::Z, -Vec3::Z, &e, dist.as_ref(), 64, 0, |_| true), Vec3::ZERO);
        for v in directions(50) {
            assert!(estimate(&brdf, Vec3::Z, v, &e, dist.as_ref(), 16, 0, |_| true).is_finite());
        }
    }
}
