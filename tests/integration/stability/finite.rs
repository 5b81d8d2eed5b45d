//! Finite and non-negative in every hard case, zero below the horizon, and the clamp thresholds
//! (ALPHA_MIN, COS_FLOOR) that keep it so, measured against the raw f32 formulas.

use super::{dir, hard_directions, hard_models, mirror};
use glam::Vec3;
use shadelab::shading::cook_torrance::CookTorrance;
use shadelab::shading::microfacet::{ALPHA_MIN, COS_FLOOR, Fresnel, Masking, Ndf};

// ------------------------------------------------------------------------------------------------
// Finite, non-negative, one-sided
// ------------------------------------------------------------------------------------------------

#[test]
fn finite_and_non_negative_in_every_hard_case() {
    let dirs = hard_directions();
    let mut count = 0;
    for (name, brdf) in hard_models() {
        for (case, l, v) in &dirs {
            let f = brdf.eval(*l, *v);
            assert!(f.is_finite() && f.min_element() >= 0.0, "{name}, {case}: f = {f}");
            if l.z <= 0.0 || v.z <= 0.0 {
                assert_eq!(f, Vec3::ZERO, "{name}, {case}: one-sided");
            }
            count += 1;
        }
    }
    assert!(count > 80_000, "only {count} evaluations");
}

// ------------------------------------------------------------------------------------------------
// Clamp thresholds, measured
// ------------------------------------------------------------------------------------------------

#[test]
fn clamp_thresholds_are_measured() {
    use std::f32::consts::PI as PI32;
    // ALPHA_MIN = 1e-12. The raw f32 V-cavity lobe at the mirror configuration with
    // n·l = n·v = 1e-7 (a hard case), D/(4 (n·l)(n·v)) with D = 1/(πα²), overflows below α = 1.5e-13.
    let raw_lobe = |a: f32| {
        let d = 1.0 / (PI32 * a * a);
        d / (4.0 * 1e-7 * 1e-7)
    };
    assert!(raw_lobe(1.4e-13).is_infinite() && raw_lobe(1.6e-13).is_finite());
    assert!(raw_lobe(ALPHA_MIN).is_finite() && raw_lobe(ALPHA_MIN) < f32::MAX / 10.0);
    // The distributions alone would last until α² turns subnormal and 2/α² overflows (~1e-19).
    let raw_blinn_exponent = |a: f32| 2.0 / (a * a) - 2.0;
    assert!(raw_blinn_exponent(7e-20).is_infinite() && raw_blinn_exponent(8e-20).is_finite());
    assert!((1.0e-19f32 * 1.0e-19).is_subnormal() && (1.1e-19f32 * 1.1e-19).is_normal());
    for ndf_kind in Ndf::ALL {
        let peak = ndf_kind.d(Vec3::Z, 0.0);
        assert!(peak.is_finite() && peak > 1e23, "{ndf_kind:?}: {peak}");
    }
    // The library at α = 0 in that hard case: finite and below the D·V cap.
    let l = dir(1e-7, 0.3);
    for masking in Masking::ALL {
        let ct = CookTorrance { alpha: 0.0, masking, fresnel: Fresnel::None, ..CookTorrance::default() };
        let f = ct.eval(l, mirror(l)).x;
        assert!(f.is_finite() && f < f32::MAX / 10.0, "{masking:?}: {f}");
    }
    // COS_FLOOR = 1e-19: 1/(4 cos²) overflows f32 for cos ≤ 2.7e-20.
    let raw_vis = |c: f32| 1.0 / (4.0 * c * c);
    assert!(raw_vis(2.6e-20).is_infinite() && raw_vis(2.8e-20).is_finite());
    assert!(raw_vis(COS_FLOOR).is_finite());
}
