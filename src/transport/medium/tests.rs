//! The fog's tests: transmittance through a slab, attenuation alone when σ_s = 0, the
//! marched in-scattering of a point light against a high-accuracy quadrature of the same
//! integral and against the closed form of Sun, Ramamoorthi, Narasimhan & Nayar 2005, no
//! NaN at g = ±0.99, and the classic blends.

use super::{EyeRay, FogPass, march};
use crate::effects::fog::blend_factor;
use crate::effects::fog::medium::transmittance;
use crate::effects::fog::phase::tests::gauss_legendre_8;
use crate::geometry::sampler::Sampler;
use crate::lesson::fog::{Fog, FogDistance, FogKind, Medium};
use crate::light::{Light, LightKind, Point};
use crate::transport::visibility::Shadows;
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

fn point(position: Vec3, intensity: f32) -> Light {
    Light {
        kind: LightKind::Point(Point { position }),
        radiance: Vec3::splat(intensity),
        specular: Vec3::splat(intensity),
        ambient: Vec3::ZERO,
        attenuation: Vec3::new(0.0, 0.0, 1.0),
        samples: 1,
        shadows: None,
    }
}

fn medium(sigma_s: f32, sigma_a: f32, g: f32, steps: u32) -> Medium {
    Medium { sigma_s, sigma_a, g, steps, sampling: crate::lesson::fog::FogSampling::Uniform }
}

/// ∫_a^b f by composite 8-point Gauss-Legendre on `panels` equal panels, in f64.
fn gauss(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let (x, w) = gauss_legendre_8();
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * h;
        for k in 0..8 {
            sum += w[k] * f(mid + 0.5 * h * x[k]);
        }
    }
    sum * 0.5 * h
}

/// The single-scattering airlight of an isotropic point light (intensity `i`) along a ray from
/// `eye` along unit `dir` for `d`, by quadrature of the integral itself:
/// ∫₀ᵈ e^(−σ_t s) σ_s/(4π) I e^(−σ_t r)/r² ds.
fn airlight_quadrature(sigma_s: f64, sigma_t: f64, i: f64, eye: DVec3, dir: DVec3, light: DVec3, d: f64) -> f64 {
    let f = |s: f64| {
        let r2 = (eye + dir * s - light).length_squared();
        (-sigma_t * s).exp() * sigma_s / (4.0 * PI) * i * (-sigma_t * r2.sqrt()).exp() / r2
    };
    gauss(f, 0.0, d, 4000)
}

/// Sun et al. 2005's special function F(u, v) = ∫₀^v e^(−u tan ξ) dξ (their eq. 8), by
/// quadrature (they tabulate it; 4000 Gauss-Legendre panels are exact to f64 rounding here).
fn sun_f(u: f64, v: f64) -> f64 {
    gauss(|xi| (-u * xi.tan()).exp(), 0.0, v, 4000)
}

/// The airlight in closed form (Sun et al. 2005, eqs. 6–7), extended from their β (σ_s = σ_t)
/// to a medium that absorbs too: with T_sv = σ_t D_sv, T_vp = σ_t d_vp, γ the angle at the
/// eye between the ray and the light,
/// L_a = A₀ [F(A₁, π/4 + ½ arctan((T_vp − T_sv cos γ)/(T_sv sin γ))) − F(A₁, γ/2)],
/// A₀ = σ_s σ_t I e^(−T_sv cos γ)/(2π T_sv sin γ), A₁ = T_sv sin γ.
fn airlight_sun(sigma_s: f64, sigma_t: f64, i: f64, eye: DVec3, dir: DVec3, light: DVec3, d: f64) -> f64 {
    let to = light - eye;
    let d_sv = to.length();
    let gamma = (to.dot(dir) / d_sv).clamp(-1.0, 1.0).acos();
    let (t_sv, t_vp) = (sigma_t * d_sv, sigma_t * d);
    let a0 = sigma_s * sigma_t * i * (-t_sv * gamma.cos()).exp() / (2.0 * PI * t_sv * gamma.sin());
    let a1 = t_sv * gamma.sin();
    let upper = PI / 4.0 + 0.5 * ((t_vp - t_sv * gamma.cos()) / (t_sv * gamma.sin())).atan();
    a0 * (sun_f(a1, upper) - sun_f(a1, gamma / 2.0))
}

#[test]
fn transmittance_through_a_slab_is_exactly_the_exponential() {
    // σ_s = 0: only attenuation, whatever the light.
    let m = medium(0.0, 0.35, 0.0, 16);
    let lights = [point(Vec3::new(0.0, 1.0, -2.0), 50.0)];
    let shadows = Shadows::unshadowed(1);
    for d in [0.0f32, 0.5, 2.0, 7.25, 30.0] {
        let l = march(
            &m,
            &lights,
            &shadows,
            EyeRay { origin: Vec3::ZERO, dir: -Vec3::Z, length: d },
            Vec3::new(1.0, 0.5, 0.25),
            0.37,
            Sampler::Sobol,
            0,
        );
        let t = (-0.35f64 * d as f64).exp();
        for (got, want) in [(l.x, t), (l.y, 0.5 * t), (l.z, 0.25 * t)] {
            assert!((got as f64 - want).abs() <= want * 2e-7, "d = {d}: {got} vs {want}");
        }
    }
    assert_eq!(transmittance(0.0, f32::INFINITY), 1.0);
    assert_eq!(transmittance(0.1, f32::INFINITY), 0.0);
}

#[test]
fn without_scattering_only_attenuation_remains_and_without_absorption_light_still_fades() {
    let lights = [point(Vec3::new(0.3, 0.5, -1.0), 10.0)];
    let shadows = Shadows::unshadowed(1);
    // σ_s = 0: no light is added, even along a ray that passes the lamp.
    let dark = march(
        &medium(0.0, 0.2, 0.0, 64),
        &lights,
        &shadows,
        EyeRay { origin: Vec3::ZERO, dir: -Vec3::Z, length: 5.0 },
        Vec3::ZERO,
        0.5,
        Sampler::Sobol,
        0,
    );
    assert_eq!(dark, Vec3::ZERO);
    // σ_a = 0 still extinguishes the surface: scattering out of the ray is a loss too.
    let s = march(
        &medium(0.2, 0.0, 0.0, 64),
        &[],
        &Shadows::unshadowed(0),
        EyeRay { origin: Vec3::ZERO, dir: -Vec3::Z, length: 5.0 },
        Vec3::ONE,
        0.5,
        Sampler::Sobol,
        0,
    );
    assert!((s.x as f64 - (-1.0f64).exp()).abs() < 1e-6);
}

#[test]
fn sun_closed_form_equals_the_quadrature_of_the_integral() {
    let eye = DVec3::ZERO;
    for (light, dir, d, ss, st) in [
        (DVec3::new(2.0, 4.0, 2.0), DVec3::new(0.0, -0.3, -1.0).normalize(), 6.0, 0.12, 0.15),
        (DVec3::new(0.5, 0.2, -3.0), DVec3::new(0.0, 0.0, -1.0), 10.0, 0.5, 0.5),
        (DVec3::new(-1.0, 2.0, -1.0), DVec3::new(0.3, 0.1, -1.0).normalize(), 2.0, 0.05, 0.3),
    ] {
        let q = airlight_quadrature(ss, st, 30.0, eye, dir, light, d);
        let s = airlight_sun(ss, st, 30.0, eye, dir, light, d);
        eprintln!("airlight {q:.9e}: Sun et al. − quadrature = {:.1e} relative", (s - q) / q);
        assert!((q - s).abs() <= 1e-9 * q, "quadrature {q} vs Sun et al. {s}");
    }
}

/// The march of the renderer (f32, jittered) converges to both references: relative error
/// below 5e-6 at 4096 steps (f32 rounding), falling with the steps.
#[test]
fn marched_in_scattering_converges_to_the_quadrature_and_to_sun_et_al() {
    let (ss, sa) = (0.12f32, 0.03f32);
    let light = Vec3::new(2.0, 4.0, 2.0);
    let eye = Vec3::new(0.0, 1.2, 5.5);
    let dir = Vec3::new(0.1, -0.25, -1.0).normalize();
    let d = 9.0f32;
    let lights = [point(light, 30.0)];
    let shadows = Shadows::unshadowed(1);
    let (e64, d64, l64) = (eye.as_dvec3(), dir.as_dvec3().normalize(), light.as_dvec3());
    let q = airlight_quadrature(ss as f64, (ss + sa) as f64, 30.0, e64, d64, l64, d as f64);
    let sun = airlight_sun(ss as f64, (ss + sa) as f64, 30.0, e64, d64, l64, d as f64);
    assert!((q - sun).abs() < 1e-9 * q);
    let err = |steps: u32, u: f32| {
        let l =
            march(&medium(ss, sa, 0.0, steps), &lights, &shadows, EyeRay { origin: eye, dir, length: d }, Vec3::ZERO, u, Sampler::Sobol, 0);
        (l.x as f64 - q).abs() / q
    };
    let (e16, e128, e4096) = (err(16, 0.5), err(128, 0.5), err(4096, 0.5));
    eprintln!("relative error of the march: 16 steps {e16:.2e}, 128 {e128:.2e}, 4096 {e4096:.2e}; airlight {q:.6e}");
    assert!(e4096 < 5e-6, "4096 steps: relative error {e4096}");
    assert!(e16 > e128 && e128 > e4096, "errors {e16} {e128} {e4096} do not fall");
    // Jittered: the mean over many jitters is the integral (unbiased), even at 8 steps.
    let mean = (0..256).map(|k| err_signed(&lights, &shadows, (ss, sa), (eye, dir, d), 8, (k as f32 + 0.5) / 256.0)).sum::<f64>() / 256.0;
    eprintln!("mean of 256 jittered 8-step marches: {:.1e} relative", (mean - q) / q);
    assert!((mean - q).abs() / q < 1e-6, "mean of jittered 8-step marches {mean} vs {q}");
}

fn err_signed(lights: &[Light], shadows: &Shadows, (ss, sa): (f32, f32), (eye, dir, d): (Vec3, Vec3, f32), steps: u32, u: f32) -> f64 {
    march(&medium(ss, sa, 0.0, steps), lights, shadows, EyeRay { origin: eye, dir, length: d }, Vec3::ZERO, u, Sampler::Sobol, 0).x as f64
}

#[test]
fn strongly_forward_and_backward_media_give_no_nan_even_through_the_lamp() {
    // The ray passes through the light itself (r = 0 at one step) and grazes it.
    let lights = [point(Vec3::new(0.0, 0.0, -2.0), 30.0), point(Vec3::new(0.0, 1e-4, -3.0), 30.0)];
    let shadows = Shadows::unshadowed(2);
    for g in [-0.99f32, 0.99] {
        for u in [0.0f32, 0.25, 0.5, 0.999] {
            for steps in [1u32, 4, 64, 1000] {
                let l = march(
                    &medium(0.2, 0.1, g, steps),
                    &lights,
                    &shadows,
                    EyeRay { origin: Vec3::ZERO, dir: -Vec3::Z, length: 5.0 },
                    Vec3::ONE,
                    u,
                    Sampler::Sobol,
                    0,
                );
                assert!(l.is_finite() && l.min_element() >= 0.0, "g {g}, u {u}, steps {steps}: {l}");
            }
        }
    }
}

#[test]
fn classic_blends_follow_their_formulas_and_the_background_takes_the_fog_colour() {
    let lin = FogKind::Linear { start: 2.0, end: 10.0 };
    assert_eq!(blend_factor(&lin, 1.0), 1.0);
    assert_eq!(blend_factor(&lin, 6.0), 0.5);
    assert_eq!(blend_factor(&lin, 12.0), 0.0);
    assert_eq!(blend_factor(&lin, f32::INFINITY), 0.0);
    let e = blend_factor(&FogKind::Exp { density: 0.3 }, 2.0);
    assert!((e as f64 - (-0.6f64).exp()).abs() < 1e-7);
    let e2 = blend_factor(&FogKind::Exp2 { density: 0.3 }, 2.0);
    assert!((e2 as f64 - (-0.36f64).exp()).abs() < 1e-7);
    assert_eq!(blend_factor(&FogKind::Exp { density: 0.3 }, f32::INFINITY), 0.0);
    // C = f C_obj + (1 − f) C_fog; radial z against view depth for a ray 60° off the axis.
    let shadows = Shadows::unshadowed(0);
    let pass = |distance| FogPass {
        fog: Fog { kind: lin, color: Vec3::splat(0.8), distance },
        lights: &[],
        shadows: &shadows,
        forward: -Vec3::Z,
        far: f32::INFINITY,
        background: Vec3::ZERO,
        sampler: Sampler::Sobol,
    };
    let dir = Vec3::new(60f32.to_radians().sin(), 0.0, -60f32.to_radians().cos());
    let radial = pass(FogDistance::Radial).apply(Vec3::ZERO, dir, Some(8.0), Vec3::splat(0.2), 7);
    let depth = pass(FogDistance::Depth).apply(Vec3::ZERO, dir, Some(8.0), Vec3::splat(0.2), 7);
    // Radial z = 8: f = 0.25; view depth z = 4: f = 0.75.
    assert!((radial.x - (0.25 * 0.2 + 0.75 * 0.8)).abs() < 1e-6);
    assert!((depth.x - (0.75 * 0.2 + 0.25 * 0.8)).abs() < 1e-6);
    assert_eq!(pass(FogDistance::Radial).apply(Vec3::ZERO, dir, None, Vec3::ONE, 7), Vec3::splat(0.8));
}

/// Equiangular sampling (Kulla & Fajardo 2012) of a point light's in-scattering is unbiased
/// (the mean over many streams is the quadrature of the integral) and, for a ray passing near
/// the lamp, far less noisy than the jittered uniform march with as many samples.
#[test]
fn equiangular_samples_are_unbiased_and_quieter_than_the_march_near_the_lamp() {
    let (ss, sa) = (0.12f32, 0.03f32);
    let light = Vec3::new(0.3, 0.1, -3.0);
    let (eye, dir, d) = (Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), 9.0f32);
    let lights = [point(light, 30.0)];
    let shadows = Shadows::unshadowed(1);
    let q = airlight_quadrature(ss as f64, (ss + sa) as f64, 30.0, eye.as_dvec3(), dir.as_dvec3(), light.as_dvec3(), d as f64);
    let steps = 16;
    let stats = |sampling: crate::lesson::fog::FogSampling| {
        let m = Medium { sampling, ..medium(ss, sa, 0.0, steps) };
        let (mut sum, mut sq) = (0.0f64, 0.0f64);
        let n = 2000;
        for k in 0..n {
            let seed = crate::geometry::sampling::hash(k);
            let u = (seed >> 8) as f32 / (1u32 << 24) as f32;
            let l = march(&m, &lights, &shadows, EyeRay { origin: eye, dir, length: d }, Vec3::ZERO, u, Sampler::Sobol, seed).x as f64;
            sum += l;
            sq += (l - q) * (l - q);
        }
        (sum / n as f64, (sq / n as f64).sqrt())
    };
    let (mean_eq, rmse_eq) = stats(crate::lesson::fog::FogSampling::Equiangular);
    let (mean_un, rmse_un) = stats(crate::lesson::fog::FogSampling::Uniform);
    eprintln!("16 samples, ray 0.32 from the lamp: equiangular RMSE {:.2e}, uniform {:.2e} (relative)", rmse_eq / q, rmse_un / q);
    assert!((mean_eq - q).abs() < 4.0 * rmse_eq / (2000f64).sqrt() + 1e-6 * q, "equiangular mean {mean_eq} vs {q}");
    assert!((mean_un - q).abs() < 4.0 * rmse_un / (2000f64).sqrt() + 1e-6 * q, "uniform mean {mean_un} vs {q}");
    assert!(rmse_eq < rmse_un / 4.0, "equiangular {rmse_eq} against uniform {rmse_un}");
}
