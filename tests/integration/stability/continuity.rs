//! Continuity at the hard cases: in every parameter, across every clamp, in direction, and the
//! radiance f·cos θ_l vanishing at the horizon.

use super::{
    ALPHAS, COSINES, GOLD_ETA, GOLD_K, IORS, SHININESS, SIGMAS_DEG, close, dir, dir_theta, hard_directions, hard_models, mirror, reference,
};
use glam::Vec3;
use shadelab::shading::brdf::Brdf;
use shadelab::shading::cook_torrance::CookTorrance;
use shadelab::shading::microfacet::{ALPHA_MIN, COS_FLOOR, Fresnel, Masking, Ndf, fresnel, ndf};
use shadelab::shading::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use shadelab::shading::oren_nayar::{OrenNayar, OrenNayarModel};
use shadelab::shading::principled::Principled;
use std::f64::consts::PI;

// ------------------------------------------------------------------------------------------------
// Continuity
// ------------------------------------------------------------------------------------------------

/// A parameter value just above `p` ("approaching the case from ε").
fn above(p: f32, floor: f32) -> f32 {
    if p == 0.0 { floor } else { p * (1.0 + 1e-5) }
}

/// (name, f at the hard value, f just above it) for every continuous parameter.
fn parameter_neighbours() -> Vec<(String, Brdf, Brdf)> {
    let mut out = Vec::new();
    for ndf in Ndf::ALL {
        for masking in Masking::ALL {
            for fresnel in [Fresnel::default(), Fresnel::Dielectric { eta: 1.5 }, Fresnel::Conductor { eta: GOLD_ETA, k: GOLD_K }] {
                for alpha in ALPHAS {
                    let a = CookTorrance { ndf, masking, fresnel, alpha, ..CookTorrance::default() };
                    let b = CookTorrance { alpha: above(alpha, ALPHA_MIN * (1.0 + 1e-5)), ..a };
                    out.push((format!("{ndf:?} {masking:?} {fresnel:?} α={alpha}"), Brdf::CookTorrance(a), Brdf::CookTorrance(b)));
                    // α = 0 is approached by α = 1e-30 too: both clamp to ALPHA_MIN.
                    if alpha == 0.0 {
                        let c = CookTorrance { alpha: 1e-30, ..a };
                        out.push((format!("{ndf:?} {masking:?} α=1e-30"), Brdf::CookTorrance(a), Brdf::CookTorrance(c)));
                    }
                }
            }
        }
    }
    for model in [OrenNayarModel::Full, OrenNayarModel::Qualitative] {
        for sigma in SIGMAS_DEG {
            let a = OrenNayar::from_degrees(Vec3::ONE, sigma, model);
            // The B term grows as σ² tan β, and tan β reaches 1e19 at the cosine floor: ε = 1e-12
            // at σ = 0 keeps the step below the tolerance there; at 90° the model is flat in σ.
            let b = OrenNayar { sigma: if sigma == 0.0 { 1e-12 } else { a.sigma * (1.0 + 1e-6) }, ..a };
            out.push((format!("oren_nayar {model:?} σ={sigma}°"), Brdf::OrenNayar(a), Brdf::OrenNayar(b)));
        }
    }
    for roughness in ALPHAS {
        for metallic in [0.0, 1.0] {
            let a =
                Principled { roughness, metallic, sheen: 1.0, clearcoat: 1.0, subsurface: 0.5, anisotropic: 0.5, ..Principled::default() };
            // The subsurface term grows as r² · 1/(n·l + n·v), up to r² · 5e18 at the cosine floor:
            // ε = 1e-15 at r = 0 keeps the step below the tolerance there.
            let b = Principled { roughness: above(roughness, 1e-15), ..a };
            out.push((format!("principled r={roughness} metallic={metallic}"), Brdf::Principled(a), Brdf::Principled(b)));
        }
    }
    for shininess in SHININESS {
        let a = NormalizedPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess };
        let b = NormalizedPhong { shininess: above(shininess, 1e-9), ..a };
        out.push((format!("phong n={shininess}"), Brdf::NormalizedPhong(a), Brdf::NormalizedPhong(b)));
        let a = NormalizedBlinnPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess };
        let b = NormalizedBlinnPhong { shininess: above(shininess, 1e-9), ..a };
        out.push((format!("blinn_phong n={shininess}"), Brdf::NormalizedBlinnPhong(a), Brdf::NormalizedBlinnPhong(b)));
    }
    out
}

#[test]
fn continuous_in_every_parameter_at_its_hard_values() {
    let dirs = hard_directions();
    for (name, a, b) in parameter_neighbours() {
        for (case, l, v) in &dirs {
            let (fa, fb) = (a.eval(*l, *v), b.eval(*l, *v));
            assert!(close(fa, fb, 1e-2, 1e-30), "{name}, {case}: {fa} → {fb}");
        }
    }
    // η: the Fresnel factor itself, approaching each hard η by one f32 step. F is steep near η = 1
    // at grazing (and discontinuous at η = 1, c = 0: F(1, θ) = 0 but F(1⁺, 90°) = 1, a property
    // of the Fresnel equations), so the f32 step is compared with the step of the f64 reference:
    // a jump caused by a guard would show up as a difference between the two.
    for eta in IORS {
        let eta1 = eta.next_up();
        for i in 0..=1000 {
            let c = if i == 0 { 0.0 } else { 10f32.powf(-7.0 + 7.0 * i as f32 / 1000.0) };
            let step = fresnel::dielectric(c, eta1) as f64 - fresnel::dielectric(c, eta) as f64;
            let step64 = reference::dielectric(c as f64, eta1 as f64) - reference::dielectric(c as f64, eta as f64);
            assert!((step - step64).abs() <= 1e-6, "dielectric η={eta} c={c}: f32 step {step:e}, f64 step {step64:e}");
            let s32 = Fresnel::schlick_from_ior(eta1).eval(c).x as f64 - Fresnel::schlick_from_ior(eta).eval(c).x as f64;
            let f0 = |e: f64| ((e - 1.0) / (e + 1.0)).powi(2);
            let s64 = reference::schlick(f0(eta1 as f64), c as f64) - reference::schlick(f0(eta as f64), c as f64);
            assert!((s32 - s64).abs() <= 1e-6, "schlick η={eta} c={c}");
        }
    }
}

#[test]
fn continuous_across_every_clamp() {
    let peak_dirs = [(Vec3::Z, Vec3::Z), (dir(0.5, 0.2), mirror(dir(0.5, 0.2))), (dir(1e-4, 1.0), mirror(dir(1e-4, 1.0)))];
    // ALPHA_MIN: below it α is raised to it (identical values), just above it f moves by ~2e-3.
    for ndf in Ndf::ALL {
        for masking in Masking::ALL {
            let at = CookTorrance { ndf, masking, alpha: ALPHA_MIN, ..CookTorrance::default() };
            let below = CookTorrance { alpha: ALPHA_MIN * 0.999, ..at };
            let over = CookTorrance { alpha: ALPHA_MIN * 1.001, ..at };
            for (l, v) in peak_dirs {
                assert_eq!(below.eval(l, v), at.eval(l, v));
                assert!(close(over.eval(l, v), at.eval(l, v), 1e-2, 0.0), "{ndf:?} {masking:?} {l} {v}");
            }
        }
    }
    // COS_FLOOR: mirror pairs at n·l = n·v just below, at and just above 1e-19.
    for c in [COS_FLOOR as f64 * 0.999, COS_FLOOR as f64 * 1.001] {
        let (l0, l1) = (dir(COS_FLOOR as f64, 0.4), dir(c, 0.4));
        for (name, brdf) in hard_models() {
            let (f0, f1) = (brdf.eval(l0, mirror(l0)), brdf.eval(l1, mirror(l1)));
            assert!(close(f0, f1, 1e-2, 0.0), "{name}: {f0} vs {f1} at n·l = {c}");
            let (g0, g1) = (brdf.eval(l0, l0), brdf.eval(l1, l1));
            assert!(close(g0, g1, 1e-2, 0.0), "{name}: l = v, {g0} vs {g1}");
        }
    }
    // Blinn caps α at 1 (k ≥ 0): α = 1 + ε equals α = 1, and α = 1 − ε is close.
    let m = dir(0.3, 0.0);
    assert_eq!(ndf::blinn(m, 1.0 + 1e-5), ndf::blinn(m, 1.0));
    assert!((ndf::blinn(m, 1.0 - 1e-5) / ndf::blinn(m, 1.0) - 1.0).abs() < 1e-3);
    // The Gaussian normalization switches from its series to its Chebyshev form at α = 0.4.
    let (lo, hi) = (ndf::gaussian_normalization(0.4), ndf::gaussian_normalization(0.4f32.next_up()));
    assert!((lo / hi - 1.0).abs() < 1e-6, "{lo} vs {hi}");
    // The D·V cap at f32::MAX is a min(), continuous by construction; check it is never reached
    // in the hard cases (cosines ≥ 1e-7) by the hard-case sweep: values stay below it.
    for (name, brdf) in hard_models() {
        for (case, l, v) in hard_directions().iter().filter(|(_, l, v)| l.z >= 1e-7 && v.z >= 1e-7) {
            assert!(brdf.eval(*l, *v).max_element() < f32::MAX, "{name}, {case}");
        }
    }
}

#[test]
fn continuous_in_direction_at_the_hard_cases() {
    let phi = 0.3;
    for (name, brdf) in hard_models() {
        let width = brdf.lobe_width() as f64;
        for &cl in &COSINES[1..] {
            for &cv in &COSINES[1..] {
                let (tl, tv) = ((cl as f64).acos(), (cv as f64).acos());
                for (rel, label) in [(0.0, "same side"), (PI, "mirror side"), (PI / 2.0, "right angle")] {
                    let l = dir_theta(tl, phi);
                    let v = if rel == PI && cl == cv { mirror(l) } else { dir_theta(tv, phi + rel) };
                    let f = brdf.eval(l, v);
                    // Tilt by 1e-4 of the smallest scale: the lobe width and both cosines.
                    let delta = 1e-4 * width.min(cl as f64).min(cv as f64);
                    for (l2, v2) in
                        [(dir_theta(tl + delta, phi), v), (l, dir_theta(tv + delta, phi + rel)), (dir_theta((tl - delta).max(0.0), phi), v)]
                    {
                        let v2 = if rel == PI && cl == cv && v2 == v { mirror(l2) } else { v2 };
                        let f2 = brdf.eval(l2, v2);
                        assert!(close(f, f2, 1e-2, 1e-30), "{name}, n·l={cl} n·v={cv} {label}: {f} → {f2}");
                    }
                }
            }
        }
    }
}

#[test]
fn radiance_vanishes_at_the_horizon() {
    // f = 0 at n·l = 0 by the one-sided definition; what is rendered is f·cos θ_l, which must
    // tend to that 0 continuously (linearly in n·l) when the viewer is not grazing. (With both
    // directions grazing at the mirror configuration, the V-cavity and correlated Smith lobes
    // keep f·cos finite and non-zero: a property of those models, not of a guard.)
    for (name, brdf) in hard_models() {
        for v in [Vec3::Z, dir(0.5, 0.3 + PI), dir(0.5, 0.3)] {
            let at = |c: f64| brdf.eval(dir(c, 0.3), v).max_element() * c as f32;
            let (near, far) = (at(1e-7), at(1e-4));
            // Linear decay, or a value negligible against ρ/π ~ 0.3 (needle lobes keep G1 ≈ 1
            // until tan θ_l ~ 1/α, so f·cos stays at ~1e-25 for α = 1e-12 before it drops).
            assert!(near <= 1.01e-3 * far + 1e-9, "{name}, v={v}: f·cos {far} at 1e-4 → {near} at 1e-7");
        }
    }
}
