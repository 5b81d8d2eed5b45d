//! Numerical-stability suite for the physically based BRDFs (issue 4, §4), through the public API.
//!
//! Hard cases: n·l, n·v ∈ {0, 1e-7, 1e-4, 1} with the light on the same side, the mirror side
//! and at right angles to the viewer; l = v; l = −v; l or v below the horizon; cosines down to
//! the smallest subnormal; α ∈ {0, 1e-6, 1e-4, 1}; shininess ∈ {0, 1e-6, 1e4, 1e6};
//! η ∈ {1, 1.0001, 1.5, 3}; σ ∈ {0°, 90°}; every NDF × masking × Fresnel combination.
//!
//! | test | what | tolerance |
//! | --- | --- | --- |
//! | `finite_and_non_negative_in_every_hard_case` | f finite and ≥ 0 (NaN never escapes), 0 below the horizon | exact |
//! | `continuous_in_every_parameter_at_its_hard_values` | f(p) vs f(p + ε) at each hard α, n, σ, roughness; the step of F from η to the next f32 vs the f64 step | 1e-2 relative (α, n, σ); 1e-6 absolute (F) |
//! | `continuous_across_every_clamp` | values just below, at and above ALPHA_MIN, COS_FLOOR, Blinn's α ≤ 1, the Gaussian branch at α = 0.4 | 1e-2 relative |
//! | `continuous_in_direction_at_the_hard_cases` | f at each hard (l, v) vs (l, v) tilted by 1e-4 of the smallest scale | 1e-2 relative |
//! | `radiance_vanishes_at_the_horizon` | f·cos θ_l → 0 linearly as n·l → 0⁺ (v not grazing) | ratio ≤ 1.01e-3 over 1e-4 → 1e-7, or below 1e-9 |
//! | `f32_matches_f64_reference` (proptest) and `f32_error_sweep` | the f32 models vs f64 transcriptions of the same formulas over random directions, including needle lobes near the mirror direction and grazing ones | 1e-4 relative ([`reference::F32_RTOL`]); measured ≤ 3.5e-5 |
//! | `reciprocity` (proptest) and `reciprocity_for_every_model` | f(l, v) = f(v, l), at random models and at every hard model (each `Brdf` variant), hard and random directions | 2e-6 relative |
//! | `ndf_normalization` | ∫ D(h)(n·h) dω = 1 for every NDF and GTR1 at α ∈ {1e-3, 0.01, 0.1, 0.5, 1} (+2 where defined) | 1e-5 |
//! | `weak_white_furnace_smith` | ∫ G1(v, m) D(m) ⟨v·m⟩ dm = n·v with each NDF's Smith Λ | GGX 1e-5; Beckmann 3e-3; Blinn, Gaussian (borrowed Λ): 1e-3 … 0.8, measured per α |
//! | `weak_white_furnace_v_cavity` | the same with the V-cavity G1, for every NDF | 5e-5 |
//! | `energy_*` | directional albedo ≤ 1 + its error bound for the energy-conserving configurations (Lambert; GGX/Beckmann × Smith/correlated × F ∈ {1, dielectric, gold}, α ∈ [1e-4, 1]; normalized Phong, = 1 at normal incidence; principled metal); printed for the others (Oren-Nayar, normalized Blinn-Phong, principled dielectric, V-cavity, Blinn/Gaussian with Smith) | the returned error bound + 1e-6 |
//! | `fresnel_*` | F(0°) = ((η−1)/(η+1))², F = 1 beyond the critical angle, F → 1 at grazing | 1e-6 relative / exact |
//! | `mitsuba_*` | values from Mitsuba 3.9.1 (tools/mitsuba_reference.py, tests/fixtures/mitsuba) | 1e-6 … 1e-4 per fixture, beyond only where the f64 reference sides with shadelab, see [`mitsuba::MITSUBA_RTOL`] |
//! | `clamp_thresholds_are_measured` | the raw f32 formulas overflow just below the thresholds behind ALPHA_MIN and COS_FLOOR | exact |
//!
//! This file holds the hard cases shared by the topic files: the directions, the models, [`close`].

mod continuity;
mod energy;
mod finite;
mod fresnel;
mod mitsuba;
mod reference;

use glam::Vec3;
use shadelab::shading::brdf::Brdf;
use shadelab::shading::cook_torrance::CookTorrance;
use shadelab::shading::diffuse::Diffuse;
use shadelab::shading::microfacet::{Fresnel, Masking, Ndf};
use shadelab::shading::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use shadelab::shading::oren_nayar::{OrenNayar, OrenNayarModel};
use shadelab::shading::principled::Principled;
use std::f64::consts::PI;

// ------------------------------------------------------------------------------------------------
// Hard cases
// ------------------------------------------------------------------------------------------------

const COSINES: [f32; 4] = [0.0, 1e-7, 1e-4, 1.0];
const ALPHAS: [f32; 4] = [0.0, 1e-6, 1e-4, 1.0];
const SHININESS: [f32; 4] = [0.0, 1e-6, 1e4, 1e6];
const IORS: [f32; 4] = [1.0, 1.0001, 1.5, 3.0];
const SIGMAS_DEG: [f32; 2] = [0.0, 90.0];
const GOLD_ETA: Vec3 = Vec3::new(0.143, 0.374, 1.442);
const GOLD_K: Vec3 = Vec3::new(3.983, 2.386, 1.603);

/// Unit vector with polar cosine `c` and azimuth `phi` (computed in f64, rounded once).
fn dir(c: f64, phi: f64) -> Vec3 {
    let s = (1.0 - c * c).max(0.0).sqrt();
    Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32)
}

/// Unit vector at polar angle `theta`, azimuth `phi`.
fn dir_theta(theta: f64, phi: f64) -> Vec3 {
    Vec3::new((theta.sin() * phi.cos()) as f32, (theta.sin() * phi.sin()) as f32, theta.cos() as f32)
}

/// The exact mirror of `w` about the normal: (−w_x, −w_y, w_z), so l + v has no tangent part.
fn mirror(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

/// The hard direction pairs, labelled.
fn hard_directions() -> Vec<(String, Vec3, Vec3)> {
    let mut out = Vec::new();
    let phi = 0.3;
    for &cl in &COSINES {
        for &cv in &COSINES {
            let l = dir(cl as f64, phi);
            out.push((format!("n·l={cl} n·v={cv} same side"), l, dir(cv as f64, phi)));
            out.push((format!("n·l={cl} n·v={cv} right angle"), l, dir(cv as f64, phi + PI / 2.0)));
            let v = if cl == cv { mirror(l) } else { dir(cv as f64, phi + PI) };
            out.push((format!("n·l={cl} n·v={cv} mirror side"), l, v));
        }
        let l = dir(cl as f64, phi);
        out.push((format!("l = v, n·l={cl}"), l, l));
        out.push((format!("l = −v, n·l={cl}"), l, -l));
        out.push((format!("v below, n·l={cl}"), l, dir(-0.5, 1.0)));
        out.push((format!("l below, n·v={cl}"), dir(-1e-7, 2.0), l));
    }
    out.push(("l = −n".into(), -Vec3::Z, Vec3::Z));
    out.push(("both below".into(), dir(-0.3, 0.0), dir(-0.9, 1.0)));
    // Beyond the list: cosines down to the smallest subnormal ("all unit inputs").
    for c in [1e-45f64, 1e-38, 1e-30, 1e-20, 1e-19] {
        let l = dir(c, phi);
        out.push((format!("tiny n·l=n·v={c} mirror"), l, mirror(l)));
        out.push((format!("tiny n·l=n·v={c} same"), l, l));
        out.push((format!("tiny n·l={c}, n·v=1"), l, Vec3::Z));
        out.push((format!("tiny n·l={c}, n·v=1e-4 mirror side"), l, dir(1e-4, phi + PI)));
    }
    out
}

/// Every Fresnel variant at every hard index of refraction.
fn hard_fresnels() -> Vec<Fresnel> {
    let mut out = vec![Fresnel::None, Fresnel::Conductor { eta: GOLD_ETA, k: GOLD_K }];
    for eta in IORS {
        out.push(Fresnel::schlick_from_ior(eta));
        out.push(Fresnel::Dielectric { eta });
    }
    out
}

/// Every model with every combination of its hard parameters.
fn hard_models() -> Vec<(String, Brdf)> {
    let mut out = Vec::new();
    out.push(("diffuse".into(), Brdf::Diffuse(Diffuse { albedo: Vec3::ONE })));
    for ndf in Ndf::ALL {
        for masking in Masking::ALL {
            for fresnel in hard_fresnels() {
                for alpha in ALPHAS {
                    for diffuse in [Vec3::ZERO, Vec3::splat(0.5)] {
                        let ct = CookTorrance { ndf, masking, fresnel, alpha, specular: Vec3::ONE, diffuse };
                        out.push((
                            format!("cook_torrance {ndf:?} {masking:?} {fresnel:?} α={alpha} ρ={}", diffuse.x),
                            Brdf::CookTorrance(ct),
                        ));
                    }
                }
            }
        }
    }
    for model in [OrenNayarModel::Full, OrenNayarModel::Qualitative] {
        for sigma in SIGMAS_DEG {
            let on = OrenNayar::from_degrees(Vec3::ONE, sigma, model);
            out.push((format!("oren_nayar {model:?} σ={sigma}°"), Brdf::OrenNayar(on)));
        }
    }
    for roughness in ALPHAS {
        for metallic in [0.0, 1.0] {
            for specular in [0.0, 1.0] {
                for lobes in [0.0, 1.0] {
                    for base_color in [Vec3::new(0.8, 0.5, 0.1), Vec3::ZERO] {
                        let p = Principled {
                            base_color,
                            metallic,
                            roughness,
                            specular,
                            specular_tint: lobes,
                            sheen: lobes,
                            sheen_tint: lobes,
                            clearcoat: lobes,
                            clearcoat_gloss: lobes,
                            subsurface: lobes,
                            anisotropic: lobes,
                            ..Principled::default()
                        };
                        out.push((
                            format!("principled r={roughness} metallic={metallic} specular={specular} lobes={lobes} C={base_color}"),
                            Brdf::Principled(p),
                        ));
                    }
                }
            }
        }
    }
    for shininess in SHININESS {
        for diffuse in [0.0, 0.5] {
            let (d, s) = (Vec3::splat(diffuse), Vec3::splat(1.0 - diffuse));
            out.push((
                format!("normalized_phong n={shininess} k_d={diffuse}"),
                Brdf::NormalizedPhong(NormalizedPhong { diffuse: d, specular: s, shininess }),
            ));
            out.push((
                format!("normalized_blinn_phong n={shininess} k_d={diffuse}"),
                Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: d, specular: s, shininess }),
            ));
        }
    }
    out
}

/// |a − b| ≤ rel · max(|a|, |b|) + abs, per channel.
fn close(a: Vec3, b: Vec3, rel: f32, abs: f32) -> bool {
    (a - b).abs().cmple(a.abs().max(b.abs()) * rel + Vec3::splat(abs)).all()
}
