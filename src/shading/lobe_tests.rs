//! Tests of the lobes and parts of [`Brdf`]: `eval_parts` is bit for bit the split every
//! layer used before, the parts sum to `eval`, the lobe weights are the documented
//! estimates and pick lobes in proportion, and degenerate inputs (grazing, roughness 0,
//! huge exponents) stay finite. The χ² tests of `sample` and `pdf` are `sampling_tests.rs`;
//! the cases and the hash streams are shared with it.

use super::brdf::Brdf;
use super::cook_torrance::CookTorrance;
use super::diffuse::Diffuse;
use super::lobe::{LobeKind, Part};
use super::microfacet::{Fresnel, Masking, Ndf};
use super::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use super::oren_nayar::OrenNayar;
use super::physical::Lobes;
use super::principled::Principled;
use super::sampling_tests::{all_cases, dir, uniform};
use glam::{Vec2, Vec3};
use std::f64::consts::TAU;

/// The old body of `physical::eval_lobes`, kept verbatim: [`Brdf::eval_parts`] must give its bits.
fn eval_lobes_before(brdf: &Brdf, l: Vec3, v: Vec3) -> Lobes {
    use std::f32::consts::FRAC_1_PI;
    if l.z <= 0.0 || v.z <= 0.0 {
        return Lobes::default();
    }
    match brdf {
        Brdf::Diffuse(_) | Brdf::OrenNayar(_) => Lobes { diffuse: brdf.eval(l, v), specular: Vec3::ZERO },
        Brdf::CookTorrance(m) => Lobes { diffuse: m.eval_diffuse(l, v), specular: m.eval_specular(l, v) },
        Brdf::Principled(m) => {
            let p = m.eval_lobes(l, v);
            Lobes { diffuse: p.diffuse + p.sheen, specular: p.specular + p.clearcoat }
        }
        Brdf::NormalizedPhong(m) => {
            Lobes { diffuse: m.diffuse * FRAC_1_PI, specular: m.specular * super::normalized_phong::phong_lobe(l, v, m.shininess) }
        }
        Brdf::NormalizedBlinnPhong(m) => {
            Lobes { diffuse: m.diffuse * FRAC_1_PI, specular: m.specular * super::normalized_phong::blinn_phong_lobe(l, v, m.shininess) }
        }
    }
}

/// A random unit direction (either hemisphere), sometimes grazing or at the pole.
fn random_dir(k: u32, seed: u32) -> Vec3 {
    match k % 7 {
        0 => Vec3::Z,
        1 => dir(std::f32::consts::FRAC_PI_2 - 1e-6 * uniform(k, seed, 3), TAU as f32 * uniform(k, seed, 4)),
        _ => {
            let z = 2.0 * uniform(k, seed, 3) - 1.0;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = TAU as f32 * uniform(k, seed, 4);
            Vec3::new(r * phi.cos(), r * phi.sin(), z)
        }
    }
}

/// (e) The parts: eval_parts is bit for bit the old eval_lobes (so the frame's layers are
/// unchanged); eval_part picks its fields; the parts sum to eval.
#[test]
fn parts_are_the_old_eval_lobes_bit_for_bit_and_sum_to_eval() {
    let bits = |x: Lobes| [x.diffuse.to_array(), x.specular.to_array()].map(|a| a.map(f32::to_bits));
    for (name, brdf) in all_cases() {
        for k in 0..20_000 {
            let (l, v) = (random_dir(k, 1), random_dir(k, 2));
            let parts = brdf.eval_parts(l, v);
            assert_eq!(bits(parts), bits(eval_lobes_before(&brdf, l, v)), "{name}: l={l} v={v}");
            assert_eq!(brdf.eval_part(Part::Diffuse, l, v).to_array().map(f32::to_bits), parts.diffuse.to_array().map(f32::to_bits));
            assert_eq!(brdf.eval_part(Part::Specular, l, v).to_array().map(f32::to_bits), parts.specular.to_array().map(f32::to_bits));
            let (sum, f) = (parts.diffuse + parts.specular, brdf.eval(l, v));
            // Exact but for the principled model, whose eval adds its sub-lobes in another order.
            let tolerance = if matches!(brdf, Brdf::Principled(_)) { 1e-6 * f.max_element() } else { 0.0 };
            assert!((sum - f).abs().max_element() <= tolerance, "{name}: {sum} vs {f} at l={l} v={v}");
        }
    }
}

/// (e) The weights: the documented albedo estimates, the diffuse weight of cook_torrance is its
/// ρ (radiosity's current 0 would fail here), a lobe of weight 0 has f = 0, and the kinds.
#[test]
fn lobe_weights_are_the_documented_estimates() {
    let rho = Vec3::new(0.5, 0.25, 0.125);
    let ct = Brdf::CookTorrance(CookTorrance { diffuse: rho, ..CookTorrance::default() });
    assert_eq!(ct.lobes().weight(Part::Diffuse), rho, "cook_torrance's Lambert base is its diffuse reflectance");
    assert_ne!(ct.lobes().weight(Part::Diffuse), Vec3::ZERO);
    let f_avg = 0.04 + 0.96 / 21.0;
    assert!((ct.lobes().weight(Part::Specular) - Vec3::splat(f_avg)).abs().max_element() < 1e-7);
    assert_eq!(ct.lobes().as_slice().iter().map(|l| l.kind).collect::<Vec<_>>(), [LobeKind::Diffuse, LobeKind::Glossy]);

    // Principled: diffuse (1 − m)(C + sheen C_sheen s̄), specular C_spec0 + (1 − C_spec0)/21, clearcoat 0.25 cc F̄.
    let p = Principled { metallic: 0.25, sheen: 1.0, sheen_tint: 0.0, clearcoat: 0.5, ..Principled::default() };
    let lobes = Brdf::Principled(p).lobes();
    let want_d = (p.base_color + Vec3::splat(super::lobe::SHEEN_ALBEDO)) * 0.75;
    assert!((lobes.weight(Part::Diffuse) - want_d).abs().max_element() < 1e-7, "{}", lobes.weight(Part::Diffuse));
    let (_, spec0) = p.tint_and_spec0();
    let want_s = spec0 + (Vec3::ONE - spec0) / 21.0 + Vec3::splat(0.125 * f_avg);
    assert!((lobes.weight(Part::Specular) - want_s).abs().max_element() < 1e-7);
    // Split sum today takes base_color (1 − metallic) as principled's diffuse albedo: equal without sheen.
    let plain = Principled { sheen: 0.0, ..p };
    assert_eq!(Brdf::Principled(plain).lobes().weight(Part::Diffuse), plain.base_color * (1.0 - plain.metallic));

    // Every model: a part whose weight is 0 is 0 everywhere, and one with a weight is non-zero somewhere.
    for (name, brdf) in all_cases() {
        let lobes = brdf.lobes();
        assert!(lobes.as_slice().iter().all(|l| l.weight.is_finite() && l.weight.min_element() >= 0.0), "{name}");
        for part in Part::ALL {
            let mut nonzero = false;
            for k in 0..5_000 {
                let (l, v) = (random_dir(k, 3).abs(), random_dir(k, 4).abs());
                // Also the mirror pair, where needle lobes (α = 1e-12, n = 1e6) are non-zero.
                let mirror = Vec3::new(-v.x, -v.y, v.z);
                nonzero |= brdf.eval_part(part, l, v) != Vec3::ZERO || brdf.eval_part(part, mirror, v) != Vec3::ZERO;
            }
            assert_eq!(nonzero, lobes.has(part), "{name} {part:?}");
        }
    }
    // A metal has no diffuse part; a black principled dielectric without sheen neither.
    let metal = Brdf::Principled(Principled { metallic: 1.0, sheen: 1.0, ..Principled::default() });
    assert!(!metal.lobes().has(Part::Diffuse));
    let black = Brdf::Principled(Principled { base_color: Vec3::ZERO, ..Principled::default() });
    assert!(!black.lobes().has(Part::Diffuse) && black.lobes().has(Part::Specular));
}

/// Lobe choice: each lobe is drawn with its probability, and the mixture pdf uses the same ones.
#[test]
fn lobes_are_chosen_in_proportion_to_their_weights() {
    let brdf = Brdf::Principled(Principled { clearcoat: 1.0, sheen: 0.5, roughness: 0.3, ..Principled::default() });
    let lobes = brdf.lobes();
    let p = lobes.probabilities().unwrap();
    assert!((p.iter().sum::<f32>() - 1.0).abs() < 1e-6);
    let n = 300_000u32;
    let mut count = [0u32; 3];
    for k in 0..n {
        count[lobes.choose((k as f32 + 0.5) / n as f32).unwrap()] += 1;
    }
    for i in 0..3 {
        assert!((count[i] as f32 / n as f32 - p[i]).abs() < 1e-5, "{i}: {count:?} {p:?}");
    }
    // The mixture pdf is Σ P_i p_i: with the diffuse lobe's probability and cos/π known, the
    // pdf at a direction far from every glossy lobe is P_0 cos θ/π within the glossy tails.
    let v = dir(0.3, 0.0);
    let l = dir(1.2, 0.0); // back-scattering, far from the mirror direction
    let expect = p[0] * l.z / std::f32::consts::PI;
    let got = brdf.pdf(v, l);
    assert!(got >= expect && got < 1.2 * expect, "{got} vs {expect}");
    assert_eq!(lobes.choose(1.0), Some(2), "u at the top still chooses a lobe");
}

/// Degenerate inputs: roughness 0, grazing and below-horizon viewers, black materials, the
/// corners of the unit square. Everything stays finite, never NaN; None or 0 where documented.
#[test]
fn degenerate_inputs_stay_finite() {
    let corners = [0.0f32, 0.5, 1.0 - f32::EPSILON / 2.0, 1.0];
    let grazing = [1e-30f32, 1e-19, 1e-7, 1e-3];
    for (name, brdf) in all_cases() {
        // Below or in the horizon: nothing.
        for v in [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.6, 0.0, -0.8), -Vec3::Z, Vec3::new(0.0, 1.0, -0.0)] {
            assert!(brdf.sample(v, 0.5, Vec2::splat(0.5)).is_none(), "{name}: v = {v}");
            assert_eq!(brdf.pdf(v, Vec3::Z), 0.0, "{name}");
        }
        assert_eq!(brdf.pdf(Vec3::Z, Vec3::new(0.6, 0.0, -0.8)), 0.0);
        assert_eq!(brdf.pdf(Vec3::Z, Vec3::X), 0.0);
        for &c in &grazing {
            let v = Vec3::new((1.0 - c * c).sqrt(), 0.0, c).normalize();
            for &a in &corners {
                for &b in &corners {
                    for &ul in &corners {
                        let Some(s) = brdf.sample(v, ul, Vec2::new(a, b)) else { continue };
                        assert!(s.l.is_finite() && s.l.z > 0.0 && s.f.is_finite() && s.pdf.is_finite() && s.pdf > 0.0, "{name}: {s:?}");
                        assert!(s.weight().is_finite(), "{name}: {s:?}");
                    }
                }
            }
            for k in 0..2_000 {
                let u = Vec2::new(uniform(k, 8, 1), uniform(k, 8, 2));
                if let Some(s) = brdf.sample(v, uniform(k, 8, 0), u) {
                    assert!(s.f.is_finite() && s.pdf.is_finite() && s.pdf > 0.0 && s.weight().is_finite(), "{name} v.z={c}: {s:?}");
                }
                let l = random_dir(k, 9);
                let p = brdf.pdf(v, l);
                assert!(p.is_finite() && p >= 0.0, "{name} v.z={c} l={l}: {p}");
            }
        }
    }
    // Black materials: no lobe to choose, no sample, pdf 0.
    let blacks = [
        Brdf::Diffuse(Diffuse { albedo: Vec3::ZERO }),
        Brdf::OrenNayar(OrenNayar { albedo: Vec3::ZERO, ..OrenNayar::default() }),
        Brdf::CookTorrance(CookTorrance { specular: Vec3::ZERO, diffuse: Vec3::ZERO, ..CookTorrance::default() }),
        Brdf::NormalizedPhong(NormalizedPhong { diffuse: Vec3::ZERO, specular: Vec3::ZERO, shininess: 10.0 }),
        Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: Vec3::ZERO, specular: Vec3::ZERO, shininess: 10.0 }),
    ];
    for brdf in blacks {
        assert!(brdf.lobes().probabilities().is_none() && brdf.sample(Vec3::Z, 0.5, Vec2::splat(0.5)).is_none());
        assert_eq!(brdf.pdf(Vec3::Z, Vec3::Z), 0.0);
        assert_eq!(brdf.eval(Vec3::Z, Vec3::Z), Vec3::ZERO);
    }
}

/// Roughness 0 (α clamped to ALPHA_MIN = 1e-12): every sample is the mirror direction and
/// its weight f cos/pdf is F (here 1: no masking at α → 0). With GGX every sample survives.
/// The exponential tails of Beckmann, Blinn and the Gaussian vanish within the f32 rounding of
/// l (1e-7 rad = 10⁵ α): D, hence f and pdf, are 0 at the rounded l, and such a sample is
/// dropped (`None`), consistently with `eval` there.
#[test]
fn roughness_zero_samples_the_mirror_direction() {
    for masking in Masking::ALL {
        for ndf in Ndf::ALL {
            let brdf = Brdf::CookTorrance(CookTorrance { alpha: 0.0, ndf, masking, fresnel: Fresnel::None, ..CookTorrance::default() });
            let v = dir(0.7, 0.3);
            for k in 0..64 {
                let u = Vec2::new(uniform(k, 4, 1), uniform(k, 4, 2));
                let Some(s) = brdf.sample(v, 0.5, u) else {
                    assert_ne!(ndf, Ndf::Ggx, "{masking:?} k={k}: GGX keeps every sample");
                    continue;
                };
                assert!((s.l - Vec3::new(-v.x, -v.y, v.z)).length() < 1e-5, "{ndf:?} {masking:?}: {}", s.l);
                assert!((s.weight() - Vec3::ONE).abs().max_element() < 1e-3, "{ndf:?} {masking:?}: {:?}", s.weight());
            }
        }
    }
}
