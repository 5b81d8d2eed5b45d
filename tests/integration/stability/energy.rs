//! NDF normalization, the weak white furnace (Smith and V-cavity masking), and directional albedo
//! against 1 for the energy-conserving configurations (measured for the others).

use super::{GOLD_ETA, GOLD_K, dir_theta};
use glam::Vec3;
use shadelab::shading::brdf::{Brdf, directional_albedo};
use shadelab::shading::cook_torrance::CookTorrance;
use shadelab::shading::diffuse::Diffuse;
use shadelab::shading::microfacet::{Fresnel, Masking, Ndf, ndf};
use shadelab::shading::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use shadelab::shading::oren_nayar::{OrenNayar, OrenNayarModel};
use shadelab::shading::principled::Principled;
use std::f64::consts::PI;

// ------------------------------------------------------------------------------------------------
// Normalization and the weak white furnace
// ------------------------------------------------------------------------------------------------

/// Gauss-Legendre nodes and weights on [−1, 1] (f64, Newton on P_n).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-15 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// ∫_a^b g by 24-point Gauss-Legendre on panels graded geometrically towards `a` from width `w0`.
fn integrate_graded(a: f64, b: f64, w0: f64, g: impl Fn(f64) -> f64) -> f64 {
    let rule = gauss_legendre(24);
    let mut breaks = vec![a];
    let mut w = w0;
    while a + w < b {
        breaks.push(a + w);
        w *= 2.0;
    }
    breaks.push(b);
    let mut total = 0.0;
    for p in breaks.windows(2) {
        let (x0, x1) = (p[0], p[1]);
        total += 0.5 * (x1 - x0) * rule.iter().map(|&(x, wt)| wt * g(0.5 * (x1 - x0) * x + 0.5 * (x1 + x0))).sum::<f64>();
    }
    total
}

/// ∫ D(h)(n·h) dω for an isotropic D given as a function of θ.
fn projected_area(alpha: f64, d_of_theta: impl Fn(f64) -> f64) -> f64 {
    2.0 * PI * integrate_graded(0.0, PI / 2.0, 1e-3 * alpha, |t| d_of_theta(t) * t.cos() * t.sin())
}

#[test]
fn ndf_normalization() {
    let m_at = |t: f64| dir_theta(t, 0.7);
    for ndf_kind in Ndf::ALL {
        let mut alphas = vec![1e-3f32, 0.01, 0.1, 0.5, 1.0];
        if ndf_kind != Ndf::Blinn {
            alphas.push(2.0); // Blinn caps α at 1 (k ≥ 0)
        }
        for alpha in alphas {
            let area = projected_area(alpha as f64, |t| ndf_kind.d(m_at(t), alpha) as f64);
            eprintln!("∫ D cos, {ndf_kind:?} α={alpha}: {area:.9}");
            assert!((area - 1.0).abs() < 1e-5, "{ndf_kind:?} α={alpha}: {area}");
        }
    }
    for alpha in [1e-3f32, 0.01, 0.1, 0.5] {
        let area = projected_area(alpha as f64, |t| ndf::gtr1(m_at(t), alpha) as f64);
        assert!((area - 1.0).abs() < 1e-5, "GTR1 α={alpha}: {area}");
    }
    // Anisotropic GGX: a 2D integral (uniform midpoint rule in φ is spectrally accurate).
    for (ax, ay) in [(0.05f32, 0.3f32), (0.5, 0.1), (1.0, 0.02)] {
        let nphi = 4096;
        let total: f64 = (0..nphi)
            .map(|j| {
                let phi = (j as f64 + 0.5) * 2.0 * PI / nphi as f64;
                integrate_graded(0.0, PI / 2.0, 1e-3 * ax.min(ay) as f64, |t| {
                    ndf::ggx_aniso(dir_theta(t, phi), ax, ay) as f64 * t.cos() * t.sin()
                }) * 2.0
                    * PI
                    / nphi as f64
            })
            .sum();
        assert!((total - 1.0).abs() < 1e-5, "GGX α=({ax}, {ay}): {total}");
    }
}

/// ∫ G1(v, m) D(m) ⟨v·m⟩ dω_m over the upper hemisphere, v at azimuth 0, for the masking
/// function `g1(v, m)`.
fn weak_white_furnace(ndf_kind: Ndf, alpha: f32, theta_v: f64, g1: impl Fn(Vec3, Vec3) -> f64) -> f64 {
    let v = dir_theta(theta_v, 0.0);
    let rule = gauss_legendre(48);
    let (cv, sv) = (theta_v.cos(), theta_v.sin());
    integrate_graded(0.0, PI / 2.0, 1e-3 * alpha as f64, |t| {
        // v·m > 0 for |φ| < φ*, cos φ* = −cot θ_v cot θ_m: split there so the integrand is smooth.
        let (ct, st) = (t.cos(), t.sin());
        let cphi = if sv * st == 0.0 { -2.0 } else { -cv * ct / (sv * st) };
        let phi_max = if cphi <= -1.0 {
            PI
        } else if cphi >= 1.0 {
            return 0.0;
        } else {
            cphi.acos()
        };
        let inner: f64 = rule
            .iter()
            .map(|&(x, w)| {
                let phi = 0.5 * phi_max * (x + 1.0);
                let m = dir_theta(t, phi);
                let vm = v.dot(m).max(0.0) as f64;
                w * 0.5 * phi_max * g1(v, m) * ndf_kind.d(m, alpha) as f64 * vm
            })
            .sum();
        2.0 * inner * st
    })
}

/// Smith's weak white furnace with each NDF's own Λ. GGX's Λ is exact (the residual is the
/// quadrature's); Beckmann's is Walter's rational fit; Blinn and Gaussian borrow Beckmann's Λ at
/// the same α (Walter et al. 2007's advice for Phong), which fails badly for broad lobes at
/// grazing. Tolerances: the measured maxima over θ_v ∈ {0°, 30°, 60°, 80°, 89°}, rounded up.
#[test]
fn weak_white_furnace_smith() {
    let tolerance = |n: Ndf, alpha: f32| match (n, alpha) {
        (Ndf::Ggx, _) => 1e-5,                                // measured 5.0e-7
        (Ndf::Beckmann, _) => 3e-3,                           // measured 2.9e-3 (θ_v = 60°, α = 1)
        (Ndf::Blinn | Ndf::Gaussian, a) if a <= 0.01 => 1e-3, // measured 9.0e-4
        (Ndf::Blinn | Ndf::Gaussian, a) if a <= 0.1 => 1e-2,  // measured 5.5e-3, 4.0e-3
        (Ndf::Blinn, a) if a <= 0.5 => 0.15,                  // measured 0.102 (θ_v = 89°)
        (Ndf::Blinn, _) => 0.8,                               // measured 0.747 (α = 1: D is uniform)
        (Ndf::Gaussian, a) if a <= 0.5 => 0.05,               // measured 0.040
        (Ndf::Gaussian, _) => 0.08,                           // measured 0.064
    };
    let mut failures = Vec::new();
    for ndf_kind in Ndf::ALL {
        for alpha in [0.01f32, 0.1, 0.5, 1.0] {
            let mut worst: (f64, f64) = (0.0, 0.0);
            for deg in [0.0f64, 30.0, 60.0, 80.0, 89.0] {
                let theta = deg.to_radians();
                let got = weak_white_furnace(ndf_kind, alpha, theta, |v, m| ndf_kind.g1(v, m, alpha) as f64);
                let rel = (got / theta.cos() - 1.0).abs();
                if rel > worst.0 {
                    worst = (rel, deg);
                }
            }
            eprintln!("weak white furnace (Smith), {ndf_kind:?} α={alpha}: max relative error {:.2e} (θ_v = {}°)", worst.0, worst.1);
            if worst.0 > tolerance(ndf_kind, alpha) {
                failures.push(format!("{ndf_kind:?} α={alpha}: {:.3e} at θ_v = {}°", worst.0, worst.1));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The V-cavity masking G1(v, m) = min(1, 2 (n·m)(n·v)/(v·m)) satisfies the furnace for every
/// D (Heitz 2014): the residual is the quadrature's, slowed by the kink of the min().
#[test]
fn weak_white_furnace_v_cavity() {
    let g1 = |v: Vec3, m: Vec3| {
        let vm = v.dot(m) as f64;
        if vm <= 0.0 { 0.0 } else { (2.0 * m.z as f64 * v.z as f64 / vm).min(1.0) }
    };
    for ndf_kind in Ndf::ALL {
        for alpha in [0.1f32, 0.5, 1.0] {
            for deg in [0.0f64, 30.0, 60.0, 89.0] {
                let theta = deg.to_radians();
                let rel = (weak_white_furnace(ndf_kind, alpha, theta, g1) / theta.cos() - 1.0).abs();
                assert!(rel < 5e-5, "{ndf_kind:?} α={alpha} θ_v={deg}°: {rel:e}"); // measured ≤ 2.1e-5
            }
        }
    }
}

// ------------------------------------------------------------------------------------------------
// Energy
// ------------------------------------------------------------------------------------------------

/// Asserts albedo ≤ 1 + error bound at several incidences; returns the largest albedo.
fn assert_energy_conserving(name: &str, brdf: &Brdf) -> f64 {
    let mut most: f64 = 0.0;
    for c in [1.0, 0.7, 0.3, 0.05, 1e-3] {
        let (albedo, error) = directional_albedo(brdf, c, 4);
        assert!(albedo <= 1.0 + error + 1e-6, "{name} at n·v={c}: albedo {albedo} ± {error}");
        most = most.max(albedo);
    }
    most
}

#[test]
fn energy_microfacet_lobes() {
    for ndf_kind in [Ndf::Ggx, Ndf::Beckmann] {
        for masking in [Masking::Smith, Masking::SmithCorrelated] {
            for fresnel in [Fresnel::None, Fresnel::Dielectric { eta: 1.5 }, Fresnel::Conductor { eta: GOLD_ETA, k: GOLD_K }] {
                for alpha in [1e-4f32, 0.01, 0.1, 0.5, 1.0] {
                    let ct = CookTorrance { ndf: ndf_kind, masking, fresnel, alpha, specular: Vec3::ONE, diffuse: Vec3::ZERO };
                    let most = assert_energy_conserving(&format!("{ct:?}"), &Brdf::CookTorrance(ct));
                    if fresnel == Fresnel::None {
                        eprintln!("albedo, {ndf_kind:?} {masking:?} F=1 α={alpha}: max {most:.6}");
                    }
                }
            }
        }
    }
}

#[test]
fn energy_diffuse_models() {
    assert_energy_conserving("lambert", &Brdf::Diffuse(Diffuse { albedo: Vec3::ONE }));
    // Oren-Nayar is not energy conserving: with ρ = 1 the qualitative model exceeds 1 for small σ
    // and grazing n·v (its B term adds to A ≈ 1). Measured and printed here, not asserted.
    for model in [OrenNayarModel::Qualitative, OrenNayarModel::Full] {
        for sigma in [5.0f32, 10.0, 20.0, 30.0, 45.0, 60.0, 90.0] {
            let on = Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::ONE, sigma, model));
            let (mut most, mut at, mut err) = (0.0f64, 0.0, 0.0);
            for c in [1.0, 0.7, 0.5, 0.3, 0.2, 0.1, 0.05, 1e-3] {
                let (a, e) = directional_albedo(&on, c, 4);
                if a > most {
                    (most, at, err) = (a, c, e);
                }
            }
            eprintln!("albedo, Oren-Nayar {model:?} σ={sigma}°, ρ = 1: max {most:.5} ± {err:.0e} at n·v = {at}");
            assert!(most.is_finite() && most < 1.2, "{model:?} σ={sigma}°: {most}"); // a sanity bound, not a claim
        }
    }
}

#[test]
fn energy_normalized_phong() {
    for shininess in [0.0f32, 1.0, 10.0, 100.0, 1e4, 1e6] {
        let p = NormalizedPhong { diffuse: Vec3::splat(0.3), specular: Vec3::splat(0.7), shininess };
        let most = assert_energy_conserving(&format!("{p:?}"), &Brdf::NormalizedPhong(p));
        // At normal incidence the lobe integrates to exactly k_s: the normalization.
        let (a, e) = directional_albedo(&Brdf::NormalizedPhong(p), 1.0, 4);
        assert!((a - 1.0).abs() <= e + 1e-5, "n={shininess}: {a} ± {e}");
        eprintln!("albedo, normalized Phong n={shininess}: max {most:.6}");
    }
}

#[test]
fn energy_principled_metal() {
    for roughness in [0.0f32, 0.2, 0.5, 1.0] {
        for anisotropic in [0.0, 1.0] {
            let p = Principled { base_color: Vec3::ONE, metallic: 1.0, roughness, anisotropic, ..Principled::default() };
            assert_energy_conserving(&format!("{p:?}"), &Brdf::Principled(p));
        }
    }
}

/// Not energy-conserving configurations, measured so their behaviour is on record.
#[test]
fn energy_measured_for_the_rest() {
    let cases: Vec<(String, Brdf)> = vec![
        (
            "normalized Blinn-Phong n=1 k_s=1".into(),
            Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess: 1.0 }),
        ),
        (
            "normalized Blinn-Phong n=10 k_s=1".into(),
            Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess: 10.0 }),
        ),
        (
            "normalized Blinn-Phong n=1000 k_s=1".into(),
            Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess: 1000.0 }),
        ),
        ("Oren-Nayar full σ=90° ρ=1".into(), Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::ONE, 90.0, OrenNayarModel::Full))),
        ("Oren-Nayar full σ=30° ρ=1".into(), Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::ONE, 30.0, OrenNayarModel::Full))),
        (
            "principled dielectric white r=1".into(),
            Brdf::Principled(Principled { base_color: Vec3::ONE, roughness: 1.0, ..Principled::default() }),
        ),
        (
            "GGX V-cavity F=1 α=1".into(),
            Brdf::CookTorrance(CookTorrance {
                masking: Masking::CookTorrance,
                fresnel: Fresnel::None,
                alpha: 1.0,
                ..CookTorrance::default()
            }),
        ),
        (
            "Blinn NDF Smith F=1 α=0.5".into(),
            Brdf::CookTorrance(CookTorrance { ndf: Ndf::Blinn, fresnel: Fresnel::None, alpha: 0.5, ..CookTorrance::default() }),
        ),
        (
            "Gaussian NDF Smith F=1 α=1".into(),
            Brdf::CookTorrance(CookTorrance { ndf: Ndf::Gaussian, fresnel: Fresnel::None, alpha: 1.0, ..CookTorrance::default() }),
        ),
    ];
    for (name, brdf) in cases {
        let curve: Vec<String> = [1.0, 0.7, 0.3, 0.05]
            .iter()
            .map(|&c| {
                let (a, e) = directional_albedo(&brdf, c, 4);
                assert!(a.is_finite() && e.is_finite());
                format!("{c}: {a:.4}±{e:.0e}")
            })
            .collect();
        eprintln!("albedo, {name}: {}", curve.join(", "));
    }
}
