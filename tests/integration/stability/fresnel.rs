//! Fresnel factors: F(0°) = ((η−1)/(η+1))², total internal reflection beyond the critical angle,
//! F → 1 at grazing.

use super::IORS;
use glam::Vec3;
use shadelab::shading::microfacet::{Fresnel, fresnel};

// ------------------------------------------------------------------------------------------------
// Fresnel
// ------------------------------------------------------------------------------------------------

#[test]
fn fresnel_normal_incidence() {
    for eta in IORS {
        let want = ((eta as f64 - 1.0) / (eta as f64 + 1.0)).powi(2);
        let got = fresnel::dielectric(1.0, eta) as f64;
        assert!((got - want).abs() <= 1e-6 * want, "η={eta}: {got} vs {want}");
        let schlick = Fresnel::schlick_from_ior(eta).eval(1.0).x as f64;
        assert!((schlick - want).abs() <= 1e-6 * want);
        // A conductor with κ = 0 is the dielectric.
        assert!((fresnel::conductor(1.0, eta, 0.0) as f64 - want).abs() <= 1e-6 * want);
    }
    assert_eq!(fresnel::dielectric(1.0, 1.0), 0.0);
}

#[test]
fn fresnel_total_internal_reflection() {
    for eta in [1.0 / 1.0001f32, 1.0 / 1.5, 1.0 / 3.0] {
        let cc = fresnel::critical_cos(eta).unwrap();
        for i in 0..1000 {
            let c = cc * i as f32 / 1000.0;
            assert_eq!(fresnel::dielectric(c, eta), 1.0, "η={eta} c={c} (critical {cc})");
            assert_eq!(fresnel::conductor(c, eta, 0.0), 1.0);
        }
        assert!(fresnel::dielectric((cc * 1.01).min(1.0), eta) < 1.0);
    }
}

#[test]
fn fresnel_tends_to_one_at_grazing() {
    for eta in [1.0001f32, 1.5, 3.0] {
        assert_eq!(fresnel::dielectric(0.0, eta), 1.0);
        let mut prev = 1.0;
        for c in [1e-9f32, 1e-7, 1e-5, 1e-3, 1e-1] {
            let f = fresnel::dielectric(c, eta);
            assert!(f <= prev && f > 0.0, "η={eta}: not decreasing from grazing at c={c}");
            prev = f;
        }
        // Near grazing 1 − F ≈ 4c·(1/w + η²/w)/2 with w = √(η² − 1): linear in c.
        assert!(1.0 - fresnel::dielectric(1e-7, eta) < 3e-5, "η={eta}");
    }
    assert!((fresnel::conductor(0.0, 0.143, 3.983) - 1.0).abs() < 1e-6);
    assert_eq!(fresnel::schlick(Vec3::splat(0.04), 0.0), Vec3::ONE);
}
