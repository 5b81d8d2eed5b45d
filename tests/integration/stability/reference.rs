//! The f64 reference implementations and the f32-vs-f64 comparison (proptests and a sweep).
//!
//! Textbook transcriptions in f64 (angles, tangents, cos θ_t), sharing only the documented
//! clamps (ALPHA_MIN, the 0.001 floor of the principled α) with the f32 code.

use super::{ALPHAS, GOLD_ETA, GOLD_K, IORS, SHININESS, close, dir, dir_theta, hard_directions, hard_models};
// The evaluators below call the transcriptions as `reference::…`, as they did beside the inline module.
use super::reference;
use glam::{DVec3, Vec3};
use proptest::prelude::*;
use shadelab::shading::brdf::Brdf;
use shadelab::shading::cook_torrance::CookTorrance;
use shadelab::shading::diffuse::Diffuse;
use shadelab::shading::microfacet::{ALPHA_MIN, Fresnel, Masking, Ndf};
use shadelab::shading::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use shadelab::shading::oren_nayar::{OrenNayar, OrenNayarModel};
use shadelab::shading::principled::Principled;
use std::f64::consts::PI;

// ------------------------------------------------------------------------------------------------
// f64 reference implementations: the same formulas, written plainly in f64
// ------------------------------------------------------------------------------------------------

fn sin2(w: DVec3) -> f64 {
    (w.x * w.x + w.y * w.y) / w.length_squared()
}

fn tan2(w: DVec3) -> f64 {
    (w.x * w.x + w.y * w.y) / (w.z * w.z)
}

/// cos^k θ from sin²θ (in f64 cos θ itself rounds to 1 for the needle lobes of α = 1e-12).
pub fn cos_pow(cos: f64, sin2: f64, k: f64) -> f64 {
    if cos <= 0.0 {
        0.0
    } else if k == 0.0 {
        1.0
    } else {
        (0.5 * k * (-sin2).ln_1p()).exp()
    }
}

/// N(α) by a 4000-point midpoint rule (independent of the f32 series/Chebyshev form).
pub fn gaussian_norm(alpha: f64) -> f64 {
    let n = 4000;
    let hi = (PI / 2.0).min(12.0 * alpha);
    let h = hi / n as f64;
    2.0 * PI * h * (0..n).map(|i| (i as f64 + 0.5) * h).map(|t| (-(t / alpha).powi(2)).exp() * t.sin() * t.cos()).sum::<f64>()
}

pub fn d(ndf: Ndf, m: DVec3, alpha: f64) -> f64 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a = alpha.max(ALPHA_MIN as f64);
    let cos = m.z / m.length();
    match ndf {
        Ndf::Blinn => {
            let a = a.min(1.0);
            let k = 2.0 / (a * a) - 2.0;
            (k + 2.0) / (2.0 * PI) * cos_pow(cos, sin2(m), k)
        }
        Ndf::Beckmann => (-tan2(m) / (a * a)).exp() / (PI * a * a * cos.powi(4)),
        Ndf::Ggx => a * a / (PI * cos.powi(4) * (a * a + tan2(m)).powi(2)),
        Ndf::Gaussian => {
            let theta = sin2(m).sqrt().atan2(cos);
            (-(theta / a).powi(2)).exp() / gaussian_norm(a)
        }
    }
}

pub fn ggx_aniso(m: DVec3, ax: f64, ay: f64) -> f64 {
    if m.z <= 0.0 {
        return 0.0;
    }
    1.0 / (PI * ax * ay * ((m.x / ax).powi(2) + (m.y / ay).powi(2) + m.z * m.z).powi(2))
}

pub fn lambda(ndf: Ndf, w: DVec3, alpha: f64) -> f64 {
    let a = alpha.max(ALPHA_MIN as f64);
    match ndf {
        Ndf::Ggx => ((1.0 + a * a * tan2(w)).sqrt() - 1.0) / 2.0,
        _ => {
            let x = 1.0 / (a * tan2(w).sqrt());
            if x >= 1.6 { 0.0 } else { ((1.0 - 1.259 * x + 0.396 * x * x) / (3.535 * x + 2.181 * x * x)).max(0.0) }
        }
    }
}

/// G; `vh` = v·h, which the f32 code evaluates as |l + v|/2 (exact for unit vectors).
pub fn g(masking: Masking, ndf: Ndf, l: DVec3, v: DVec3, h: DVec3, vh: f64, alpha: f64) -> f64 {
    match masking {
        Masking::CookTorrance => (2.0 * h.z * v.z / vh).min(2.0 * h.z * l.z / vh).min(1.0),
        Masking::Smith => 1.0 / (1.0 + lambda(ndf, l, alpha)) / (1.0 + lambda(ndf, v, alpha)),
        Masking::SmithCorrelated => 1.0 / (1.0 + lambda(ndf, l, alpha) + lambda(ndf, v, alpha)),
    }
}

/// Exact dielectric Fresnel with cos θ_t (Born & Wolf form).
pub fn dielectric(c: f64, eta: f64) -> f64 {
    if eta == 1.0 {
        return 0.0; // no interface (the documented value, also at c = 0)
    }
    let s2t = (1.0 - c * c) / (eta * eta);
    if s2t >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - s2t).sqrt();
    let rs = (c - eta * ct) / (c + eta * ct);
    let rp = (eta * c - ct) / (eta * c + ct);
    0.5 * (rs * rs + rp * rp)
}

/// Exact conductor Fresnel with complex cos θ_t, complex arithmetic written out.
pub fn conductor(c: f64, eta: f64, k: f64) -> f64 {
    type C = (f64, f64);
    let mul = |a: C, b: C| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let div = |a: C, b: C| {
        let d = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    let sqrt = |a: C| {
        let r = (a.0 * a.0 + a.1 * a.1).sqrt();
        let re = ((r + a.0) / 2.0).sqrt();
        let im = ((r - a.0) / 2.0).max(0.0).sqrt().copysign(a.1);
        (re, im)
    };
    let n: C = (eta, k);
    let n2 = mul(n, n);
    let s2t = div((1.0 - c * c, 0.0), n2);
    let ct = sqrt((1.0 - s2t.0, -s2t.1));
    let nct = mul(n, ct);
    let nc = (n.0 * c, n.1 * c);
    let rs = div((c - nct.0, -nct.1), (c + nct.0, nct.1));
    let rp = div((nc.0 - ct.0, nc.1 - ct.1), (nc.0 + ct.0, nc.1 + ct.1));
    0.5 * (rs.0 * rs.0 + rs.1 * rs.1 + rp.0 * rp.0 + rp.1 * rp.1)
}

pub fn schlick(f0: f64, c: f64) -> f64 {
    f0 + (1.0 - f0) * (1.0 - c).clamp(0.0, 1.0).powi(5)
}

/// The Fresnel factor of `fresnel` per channel.
pub fn fresnel(fresnel: &shadelab::shading::microfacet::Fresnel, c: f64) -> DVec3 {
    use shadelab::shading::microfacet::Fresnel as F;
    match *fresnel {
        F::Schlick { f0 } => DVec3::new(schlick(f0.x as f64, c), schlick(f0.y as f64, c), schlick(f0.z as f64, c)),
        F::Dielectric { eta } => DVec3::splat(dielectric(c, eta as f64)),
        F::Conductor { eta, k } => DVec3::new(
            conductor(c, eta.x as f64, k.x as f64),
            conductor(c, eta.y as f64, k.y as f64),
            conductor(c, eta.z as f64, k.z as f64),
        ),
        F::None => DVec3::ONE,
    }
}

/// The f64 value of `brdf` at (l, v), from the reference transcriptions.
pub(super) fn reference_eval(brdf: &Brdf, l: Vec3, v: Vec3) -> DVec3 {
    reference_eval_scaled(brdf, l, v).0
}

/// The f64 value and the magnitude its rounding error scales with: the value itself, except for
/// the full Oren-Nayar model, whose value is a sum of terms of both signs that nearly cancel in
/// forward-grazing configurations (and is clamped at 0 where they overshoot), so its error is
/// measured against the sum of the terms' magnitudes.
fn reference_eval_scaled(brdf: &Brdf, l: Vec3, v: Vec3) -> (DVec3, DVec3) {
    let (l, v) = (l.as_dvec3(), v.as_dvec3());
    if l.z <= 0.0 || v.z <= 0.0 {
        return (DVec3::ZERO, DVec3::ZERO);
    }
    if let Brdf::OrenNayar(m) = brdf
        && m.model == OrenNayarModel::Full
    {
        return reference_oren_nayar_full(m, l, v);
    }
    let value = match brdf {
        Brdf::Diffuse(m) => m.albedo.as_dvec3() / PI,
        Brdf::CookTorrance(m) => {
            let alpha = (m.alpha as f64).max(ALPHA_MIN as f64);
            let h = (l + v).normalize();
            let vh = 0.5 * (l + v).length(); // = v·h for unit vectors, as the f32 code evaluates it
            let d = reference::d(m.ndf, h, alpha);
            let g = reference::g(m.masking, m.ndf, l, v, h, vh, alpha);
            let f = reference::fresnel(&m.fresnel, vh);
            m.specular.as_dvec3() * f * (d * g / (4.0 * l.z * v.z)) + m.diffuse.as_dvec3() / PI
        }
        Brdf::OrenNayar(m) => {
            let rho = m.albedo.as_dvec3();
            let s2 = (m.sigma as f64).powi(2);
            let (ti, tr) = (l.z.acos(), v.z.acos());
            let (alpha, beta) = (ti.max(tr), ti.min(tr));
            let sin_l = (l.x * l.x + l.y * l.y).sqrt();
            let sin_v = (v.x * v.x + v.y * v.y).sqrt();
            let cos_phi = if sin_l * sin_v > 0.0 { ((l.x * v.x + l.y * v.y) / (sin_l * sin_v)).clamp(-1.0, 1.0) } else { 0.0 };
            match m.model {
                OrenNayarModel::Qualitative => {
                    let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
                    let b = 0.45 * s2 / (s2 + 0.09);
                    rho / PI * (a + b * cos_phi.max(0.0) * alpha.sin() * beta.tan())
                }
                OrenNayarModel::Full => unreachable!("handled by reference_oren_nayar_full"),
            }
        }
        Brdf::Principled(p) => {
            let [diffuse, sheen, specular, clearcoat] = reference_principled_lobes(p, l, v);
            diffuse + sheen + specular + clearcoat
        }
        Brdf::NormalizedPhong(m) => {
            let n = (m.shininess as f64).max(0.0);
            let r = DVec3::new(-l.x, -l.y, l.z);
            let cos = r.dot(v) / (r.length() * v.length());
            let sin2 = r.cross(v).length_squared() / (r.length_squared() * v.length_squared());
            let lobe = (n + 2.0) / (2.0 * PI) * reference::cos_pow(cos, sin2, n);
            m.diffuse.as_dvec3() / PI + m.specular.as_dvec3() * lobe
        }
        Brdf::NormalizedBlinnPhong(m) => {
            let n = (m.shininess as f64).max(0.0);
            let h = (l + v).normalize();
            let lobe = (n + 8.0) / (8.0 * PI) * reference::cos_pow(h.z, h.x * h.x + h.y * h.y, n);
            m.diffuse.as_dvec3() / PI + m.specular.as_dvec3() * lobe
        }
    };
    (value, value)
}

/// The full Oren-Nayar model in f64 (textbook angles), and the sum of its terms' magnitudes.
fn reference_oren_nayar_full(m: &OrenNayar, l: DVec3, v: DVec3) -> (DVec3, DVec3) {
    let rho = m.albedo.as_dvec3();
    let s2 = (m.sigma as f64).powi(2);
    let (ti, tr) = (l.z.acos(), v.z.acos());
    let (alpha, beta) = (ti.max(tr), ti.min(tr));
    let sin_l = (l.x * l.x + l.y * l.y).sqrt();
    let sin_v = (v.x * v.x + v.y * v.y).sqrt();
    let cos_phi = if sin_l * sin_v > 0.0 { ((l.x * v.x + l.y * v.y) / (sin_l * sin_v)).clamp(-1.0, 1.0) } else { 0.0 };
    let c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    let k = s2 / (s2 + 0.09);
    let c2 = if cos_phi >= 0.0 { 0.45 * k * alpha.sin() } else { 0.45 * k * (alpha.sin() - (2.0 * beta / PI).powi(3)) };
    let c3 = 0.125 * k * (4.0 * alpha * beta / (PI * PI)).powi(2);
    let (t2, t3) = (cos_phi * c2 * beta.tan(), (1.0 - cos_phi.abs()) * c3 * ((alpha + beta) / 2.0).tan());
    let inter = 0.17 * rho * rho / PI * s2 / (s2 + 0.13) * (1.0 - cos_phi * (2.0 * beta / PI).powi(2));
    let value = (rho / PI * (c1 + t2 + t3) + inter).max(DVec3::ZERO); // the documented clamp (σ > 38.07°)
    (value, rho / PI * (c1 + t2.abs() + t3.abs()) + inter.abs())
}

/// Burley's disney.brdf transcribed in f64 (base colour already linear), lobe by lobe:
/// [diffuse, sheen, specular, clearcoat]. Preconditions: l.z > 0, v.z > 0.
pub(super) fn reference_principled_lobes(p: &Principled, l: DVec3, v: DVec3) -> [DVec3; 4] {
    let mix = |x: f64, y: f64, a: f64| x * (1.0 - a) + y * a;
    let mix3 = |x: DVec3, y: DVec3, a: f64| x * (1.0 - a) + y * a;
    let schlick_w = |u: f64| (1.0 - u).clamp(0.0, 1.0).powi(5);
    let (ndl, ndv) = (l.z, v.z);
    let h = (l + v).normalize();
    let (ndh, ldh) = (h.z, 0.5 * (l + v).length()); // l·h = |l + v|/2 for unit vectors
    let cd = p.base_color.as_dvec3();
    let lum = 0.3 * cd.x + 0.6 * cd.y + 0.1 * cd.z;
    let tint = if lum > 0.0 { cd / lum } else { DVec3::ONE };
    let spec0 = mix3(p.specular as f64 * 0.08 * mix3(DVec3::ONE, tint, p.specular_tint as f64), cd, p.metallic as f64);
    let sheen_c = mix3(DVec3::ONE, tint, p.sheen_tint as f64);
    let (fl, fv) = (schlick_w(ndl), schlick_w(ndv));
    let r = p.roughness as f64;
    let fd90 = 0.5 + 2.0 * ldh * ldh * r;
    let fd = mix(1.0, fd90, fl) * mix(1.0, fd90, fv);
    let fss90 = ldh * ldh * r;
    let fss = mix(1.0, fss90, fl) * mix(1.0, fss90, fv);
    let ss = 1.25 * (fss * (1.0 / (ndl + ndv) - 0.5) + 0.5);
    let aspect = (1.0 - p.anisotropic as f64 * 0.9).sqrt();
    let ax = (r * r / aspect).max(0.001);
    let ay = (r * r * aspect).max(0.001);
    let ds = reference::ggx_aniso(h, ax, ay);
    let fh = schlick_w(ldh);
    let fs = mix3(spec0, DVec3::ONE, fh);
    let gs_aniso = |w: DVec3| 1.0 / (w.z + ((w.x * ax).powi(2) + (w.y * ay).powi(2) + w.z * w.z).sqrt());
    let gs = gs_aniso(l) * gs_aniso(v);
    let a_cc = mix(0.1, 0.001, p.clearcoat_gloss as f64);
    let dr = if a_cc >= 1.0 {
        1.0 / PI
    } else {
        let a2 = a_cc * a_cc;
        // 1 + (α² − 1)cos²θ_h written as α² cos²θ_h + sin²θ_h: the f64 form of Burley's t.
        (a2 - 1.0) / (PI * a2.ln() * (a2 * ndh * ndh + h.x * h.x + h.y * h.y))
    };
    let fr = mix(0.04, 1.0, fh);
    let smith_g = |ndw: f64| {
        let (a, b) = (0.0625, ndw * ndw);
        1.0 / (ndw + (a + b - a * b).sqrt())
    };
    let gr = smith_g(ndl) * smith_g(ndv);
    let metal = 1.0 - p.metallic as f64;
    [
        cd * mix(fd, ss, p.subsurface as f64) / PI * metal,
        fh * p.sheen as f64 * sheen_c * metal,
        gs * ds * fs,
        DVec3::splat(if p.clearcoat > 0.0 { 0.25 * p.clearcoat as f64 * gr * fr * dr } else { 0.0 }),
    ]
}

// ------------------------------------------------------------------------------------------------
// f32 vs f64
// ------------------------------------------------------------------------------------------------

/// Stated agreement of the f32 models with the f64 reference, per channel:
/// |f32 − f64| ≤ F32_RTOL · scale + F32_ATOL, with scale = |f64| (for the full Oren-Nayar model
/// the sum of its terms' magnitudes, see [`reference_eval_scaled`]). The references share the
/// f32 code's formulas, including v·h = |l + v|/2 and cos^n from sin²; they do not sample the one
/// documented ill-conditioned spot, the critical angle of η < 1. Measured maxima
/// (`f32_error_sweep`, 40 000 cases): Cook-Torrance 3.5e-6, principled 3.5e-5, others ≤ 1.7e-6.
const F32_RTOL: f64 = 1e-4;
/// Values below this (1/sr) may underflow differently in f32 and f64.
const F32_ATOL: f64 = 1e-30;

/// A random model: each family with random parameters drawn around its hard values.
fn model_strategy() -> impl Strategy<Value = Brdf> {
    let alpha = prop_oneof![prop::sample::select(ALPHAS.to_vec()), 1e-3f32..1.0];
    let ior = prop_oneof![prop::sample::select(IORS.to_vec()), 1.0f32..3.0];
    let fresnel = prop_oneof![
        Just(Fresnel::None),
        ior.clone().prop_map(Fresnel::schlick_from_ior),
        ior.prop_map(|eta| Fresnel::Dielectric { eta }),
        Just(Fresnel::Conductor { eta: GOLD_ETA, k: GOLD_K }),
    ];
    let ct = (prop::sample::select(Ndf::ALL.to_vec()), prop::sample::select(Masking::ALL.to_vec()), fresnel, alpha.clone(), 0.0f32..1.0)
        .prop_map(|(ndf, masking, fresnel, alpha, d)| {
            Brdf::CookTorrance(CookTorrance { ndf, masking, fresnel, alpha, specular: Vec3::ONE, diffuse: Vec3::splat(d) })
        });
    let on = (
        prop::sample::select(vec![OrenNayarModel::Full, OrenNayarModel::Qualitative]),
        prop_oneof![Just(0.0f32), Just(90.0f32), 0.0f32..90.0],
        0.0f32..1.0,
    )
        .prop_map(|(model, sigma, rho)| Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::new(rho, 0.5, 1.0), sigma, model)));
    let unit = || 0.0f32..=1.0;
    let pr = (alpha, unit(), unit(), unit(), unit(), unit(), unit(), unit(), unit(), unit(), unit()).prop_map(
        |(roughness, metallic, specular, specular_tint, sheen, sheen_tint, clearcoat, clearcoat_gloss, subsurface, anisotropic, red)| {
            Brdf::Principled(Principled {
                base_color: Vec3::new(red, 0.5, 0.1),
                metallic,
                roughness,
                specular,
                specular_tint,
                sheen,
                sheen_tint,
                clearcoat,
                clearcoat_gloss,
                subsurface,
                anisotropic,
                ..Principled::default()
            })
        },
    );
    let shininess = prop_oneof![prop::sample::select(SHININESS.to_vec()), (0.0f32..6.0).prop_map(|e| 10f32.powf(e))];
    let ph = (shininess.clone(), any::<bool>()).prop_map(|(shininess, blinn)| {
        let (diffuse, specular) = (Vec3::splat(0.3), Vec3::splat(0.7));
        if blinn {
            Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse, specular, shininess })
        } else {
            Brdf::NormalizedPhong(NormalizedPhong { diffuse, specular, shininess })
        }
    });
    prop_oneof![Just(Brdf::Diffuse(Diffuse { albedo: Vec3::new(0.2, 0.5, 1.0) })), ct, on, pr, ph]
}

/// Random (l, v) in the upper hemisphere: uniform, log-uniform near the horizon, or l near the
/// mirror direction of v (so narrow lobes are sampled where they are non-zero).
fn directions_strategy() -> impl Strategy<Value = (Vec3, Vec3)> {
    let cosine = prop_oneof![1e-3f64..1.0, (-7.0f64..0.0).prop_map(|e| 10f64.powf(e))];
    let angle = 0.0f64..(2.0 * PI);
    (cosine.clone(), angle.clone(), cosine, angle, 0usize..3, -9.0f64..-1.0).prop_map(|(cl, pl, cv, pv, kind, spread)| {
        let v = dir(cv, pv);
        let l = match kind {
            0 => dir(cl, pl),
            _ => {
                // Mirror of v tilted by 10^spread rad (down to 1e-9) in a random azimuth.
                let t = (cv.acos() + 10f64.powf(spread) * pl.cos()).clamp(0.0, PI / 2.0 - 1e-9);
                dir_theta(t, pv + PI + 10f64.powf(spread) * pl.sin())
            }
        };
        (l, v)
    })
}

/// max over channels of |f32 − f64| / max(scale, F32_ATOL), or 0 where |f32 − f64| ≤ F32_ATOL.
fn f32_error(brdf: &Brdf, l: Vec3, v: Vec3) -> f64 {
    let got = brdf.eval(l, v).as_dvec3();
    let (want, scale) = reference_eval_scaled(brdf, l, v);
    let mut worst: f64 = 0.0;
    for i in 0..3 {
        let err = (got[i] - want[i]).abs();
        if err > F32_ATOL {
            worst = worst.max(err / scale[i].abs().max(F32_ATOL));
        }
    }
    worst
}

proptest! {
    // No regression file: failures are reported with their minimal input instead.
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

    /// The f32 implementation agrees with the f64 transcription to F32_RTOL.
    #[test]
    fn f32_matches_f64_reference(brdf in model_strategy(), (l, v) in directions_strategy()) {
        let err = f32_error(&brdf, l, v);
        prop_assert!(err <= F32_RTOL, "{brdf:?} l={l} v={v}: relative error {err:e}");
    }

    /// Helmholtz reciprocity at random parameters and directions.
    #[test]
    fn reciprocity(brdf in model_strategy(), (l, v) in directions_strategy()) {
        let (a, b) = (brdf.eval(l, v), brdf.eval(v, l));
        prop_assert!(close(a, b, 2e-6, 1e-30), "{brdf:?} l={l} v={v}: {a} vs {b}");
    }
}

/// Helmholtz reciprocity for every model with every combination of its hard parameters, at
/// every hard direction pair and at fixed random ones (the proptest above draws its models at
/// random, so it need not reach each one).
#[test]
fn reciprocity_for_every_model() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut runner = TestRunner::new_with_rng(Config::default(), TestRng::from_seed(RngAlgorithm::ChaCha, &[3; 32]));
    let random = directions_strategy();
    let mut dirs = hard_directions();
    for i in 0..200 {
        let (l, v) = random.new_tree(&mut runner).unwrap().current();
        dirs.push((format!("random {i}"), l, v));
    }
    // Per Brdf variant: the pairs where f is non-zero.
    let mut families = std::collections::BTreeMap::<String, usize>::new();
    for (name, brdf) in hard_models() {
        let mut nonzero = 0;
        for (case, l, v) in &dirs {
            let (a, b) = (brdf.eval(*l, *v), brdf.eval(*v, *l));
            assert!(close(a, b, 2e-6, 1e-30), "{name}, {case}: f(l, v) = {a}, f(v, l) = {b}");
            nonzero += (a != Vec3::ZERO) as usize;
        }
        let family = name.split(' ').next().unwrap().to_string();
        *families.entry(family).or_default() += nonzero;
    }
    let want = ["cook_torrance", "diffuse", "normalized_blinn_phong", "normalized_phong", "oren_nayar", "principled"];
    assert_eq!(families.keys().map(String::as_str).collect::<Vec<_>>(), want, "every Brdf variant");
    // Values compared, not only zeros (a model with F = 0, η = 1, is zero everywhere).
    for (family, nonzero) in &families {
        eprintln!("reciprocity, {family}: {nonzero} non-zero pairs");
        assert!(*nonzero >= 100, "{family}: only {nonzero} non-zero pairs");
    }
}

/// Deterministic sweep over the same strategies: prints the worst relative error per family.
#[test]
fn f32_error_sweep() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mut runner = TestRunner::new_with_rng(Config::default(), TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]));
    let (models, dirs) = (model_strategy(), directions_strategy());
    let mut worst = std::collections::BTreeMap::<&str, (f64, String)>::new();
    for _ in 0..40_000 {
        let brdf = models.new_tree(&mut runner).unwrap().current();
        let (l, v) = dirs.new_tree(&mut runner).unwrap().current();
        let family = match brdf {
            Brdf::Diffuse(_) => "diffuse",
            Brdf::CookTorrance(_) => "cook_torrance",
            Brdf::OrenNayar(_) => "oren_nayar",
            Brdf::Principled(_) => "principled",
            Brdf::NormalizedPhong(_) => "normalized_phong",
            Brdf::NormalizedBlinnPhong(_) => "normalized_blinn_phong",
        };
        let err = f32_error(&brdf, l, v);
        let entry = worst.entry(family).or_insert((0.0, String::new()));
        if err > entry.0 {
            *entry = (err, format!("{brdf:?} l={l} v={v}"));
        }
    }
    for (family, (err, at)) in &worst {
        eprintln!("f32 vs f64, {family}: max relative error {err:.2e} ({at})");
        assert!(*err <= F32_RTOL, "{family}: {err:e} at {at}");
    }
}
