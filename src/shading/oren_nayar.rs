//! Oren-Nayar rough diffuse BRDF: Lambertian V-grooves with masking, shadowing and
//! interreflection (Oren & Nayar 1994).
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `diffuse` ρ | [0, 1] RGB | 0.5 | albedo of each facet |
//! | `sigma_deg` σ | [0°, 90°] in lessons (degrees); **radians** in [`OrenNayar::sigma`] | 20° | standard deviation of the facet slope angle (0 = Lambert) |
//! | `variant` | `full`, `qualitative` | `full` | the full model with the C1, C2, C3 and interreflection terms, or the simplified (A, B) model |
//!
//! With θ_i = θ_l, θ_r = θ_v, α = max(θ_i, θ_r), β = min(θ_i, θ_r), Δφ = φ_r − φ_i:
//!
//! Full model (Oren & Nayar 1994, §4: the direct term L¹_r and the interreflection term L²_r,
//! divided by E₀ cos θ_i to give a BRDF):
//!
//! f = ρ/π [C1 + cos Δφ · C2 · tan β + (1 − |cos Δφ|) C3 tan((α + β)/2)]
//!   + 0.17 ρ²/π · σ²/(σ² + 0.13) · [1 − cos Δφ (2β/π)²]
//!
//! C1 = 1 − 0.5 σ²/(σ² + 0.33);
//! C2 = 0.45 σ²/(σ² + 0.09) sin α if cos Δφ ≥ 0, else 0.45 σ²/(σ² + 0.09) (sin α − (2β/π)³);
//! C3 = 0.125 σ²/(σ² + 0.09) (4αβ/π²)².
//!
//! Qualitative model (Oren & Nayar 1994, §5 "a simpler qualitative model"):
//! f = ρ/π [A + B max(0, cos Δφ) sin α tan β], A = 1 − 0.5 σ²/(σ² + 0.33), B = 0.45 σ²/(σ² + 0.09).
//!
//! The model is written in the paper's slope-angle σ, not in the microfacet α of the specular
//! models (Mitsuba 0.5's `roughdiffuse` maps α = √2 σ). σ = 0 reduces both models to Lambert
//! exactly: C1 = A = 1 and every other term is multiplied by σ² = 0 (tested bit for bit).
//! Reciprocal: every term depends on (α, β, cos Δφ) only, symmetric in l and v. One-sided.
//!
//! **Numerics.** No trigonometric function is needed except atan2 for α and β:
//! cos Δφ sin α tan β = (l_x v_x + l_y v_y)/cos β exactly, tan((α+β)/2) = (sin α + sin β)/(cos α + cos β),
//! and cos Δφ (undefined when l or v is the normal) is set to 0 there, where every term that uses it
//! is multiplied by sin β = 0 or β = 0. The factor sin α − (2β/π)³, multiplied by tan β, is
//! evaluated as u(3 − 3u + u²) − cos²α/(1 + sin α) with u = 1 − 2β/π from the complement angle:
//! the direct difference cancels completely near grazing (f32 errors of O(1) at cos = 1e-7).
//! Likewise 1 − |cos Δφ| is evaluated as sin²Δφ/(1 + |cos Δφ|) from the tangent components in
//! f64, since tan((α + β)/2) reaches 1e7 when both directions graze.
//!
//! Clamps: cos β and cos α + cos β are at least [`COS_FLOOR`] = 1e-19 in the divisions that grow
//! without bound at grazing, p/cos β (the back-scatter term) and tan((α+β)/2) (f·cos θ stays
//! bounded); the forward-scatter product tan β (sin α − (2β/π)³) is bounded and needs none. The full model is clamped at f ≥ 0: for σ > 38.07°
//! (0.664 rad) its direct term tends to ρ/π (C1 − 0.45·(6/π)·σ²/(σ² + 0.09)) < 0 as θ_l, θ_v → 90°
//! with Δφ = 180° (the limit of tan β · (sin α − (2β/π)³) is 6/π; the threshold solves
//! C1 = 0.45 (6/π) k with k = σ²/(σ² + 0.09)), and the ρ² interreflection term makes up for it
//! only when ρ is large. Measured by `oren_nayar_full_goes_negative_beyond_38_degrees`.
//!
//! **Lobes and sampling** ([`super::lobe`]): one diffuse lobe of weight ρ (the facet albedo: the
//! model's directional albedo departs from it by the masking loss and the interreflection gain,
//! a few percent for σ ≤ 30°), the whole f in the diffuse part. Sampled by the cosine-weighted
//! hemisphere, pdf cos θ_l/π (as pbrt-v3 and Mitsuba 0.5 `roughdiffuse` do). The weight
//! f cos θ_l / pdf = π f; for a fixed viewer f is bounded (its terms that grow at grazing divide
//! by cos β or cos α + cos β, both ≥ n·v), so the estimator has finite variance for every v.

use super::lobe::{Lobe, LobeKind, LobeSet};
use super::microfacet::COS_FLOOR;
use glam::Vec3;
use std::f32::consts::{FRAC_1_PI, FRAC_2_PI};

/// Which of the two Oren-Nayar models to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OrenNayarModel {
    /// The full model: C1, C2, C3 and the interreflection term.
    #[default]
    Full,
    /// The qualitative (A, B) model.
    Qualitative,
}

/// An Oren-Nayar rough diffuse material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrenNayar {
    /// Facet albedo ρ per channel.
    pub albedo: Vec3,
    /// Slope-angle standard deviation σ in **radians** (lessons give degrees; see [`OrenNayar::from_degrees`]).
    pub sigma: f32,
    /// Full or qualitative model.
    pub model: OrenNayarModel,
}

impl Default for OrenNayar {
    /// ρ = 0.5, σ = 20°, full model.
    fn default() -> Self {
        OrenNayar { albedo: Vec3::splat(0.5), sigma: 20f32.to_radians(), model: OrenNayarModel::Full }
    }
}

impl OrenNayar {
    /// A material with σ given in degrees, as lessons give it.
    pub fn from_degrees(albedo: Vec3, sigma_degrees: f32, model: OrenNayarModel) -> OrenNayar {
        OrenNayar { albedo, sigma: sigma_degrees.to_radians(), model }
    }

    /// One diffuse lobe of weight ρ.
    pub fn lobes(&self) -> LobeSet {
        LobeSet::new(&[Lobe::new(LobeKind::Diffuse, self.albedo)])
    }

    /// f(l, v) in 1/sr for unit `l`, `v` in the local frame (z = normal); 0 below the horizon.
    #[inline]
    pub fn eval(&self, l: Vec3, v: Vec3) -> Vec3 {
        if l.z <= 0.0 || v.z <= 0.0 {
            return Vec3::ZERO;
        }
        let s2 = self.sigma * self.sigma;
        let rho_pi = self.albedo * FRAC_1_PI;
        let sin_l = (l.x * l.x + l.y * l.y).sqrt();
        let sin_v = (v.x * v.x + v.y * v.y).sqrt();
        // p = sin θ_l sin θ_v cos Δφ, computed without dividing (in f64: one rounding, since the
        // 1/cos β factor below amplifies its error at grazing).
        let p = (l.x as f64 * v.x as f64 + l.y as f64 * v.y as f64) as f32;
        // α is the larger angle (smaller cosine), β the smaller angle. At equal cosines the
        // larger sine decides, so f(l, v) and f(v, l) pick the same pair (reciprocity to the bit).
        let l_is_alpha = l.z < v.z || (l.z == v.z && sin_l >= sin_v);
        let (sin_a, cos_a, sin_b, cos_b) = if l_is_alpha { (sin_l, l.z, sin_v, v.z) } else { (sin_v, v.z, sin_l, l.z) };
        let cos_b_safe = cos_b.max(COS_FLOOR); // cos β ≥ 1e-19: p / cos β finite
        match self.model {
            OrenNayarModel::Qualitative => {
                let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
                let b = 0.45 * s2 / (s2 + 0.09);
                // B max(0, cos Δφ) sin α tan β = B max(0, p) / cos β.
                rho_pi * (a + b * p.max(0.0) / cos_b_safe)
            }
            OrenNayarModel::Full => {
                // cos Δφ and 1 − |cos Δφ| = sin²Δφ/(1 + |cos Δφ|) from the tangent components in f64
                // (1 − |cos Δφ| cancels near Δφ = 0°, 180° and is amplified by tan((α+β)/2) at grazing).
                let (lx, ly, vx, vy) = (l.x as f64, l.y as f64, v.x as f64, v.y as f64);
                let sin2_prod = (lx * lx + ly * ly) * (vx * vx + vy * vy);
                // cos Δφ is undefined at the pole; there every term using it is multiplied by 0.
                let (cos_phi, one_minus_abs_cos) = if sin2_prod > 0.0 {
                    let cos_phi = ((lx * vx + ly * vy) / sin2_prod.sqrt()).clamp(-1.0, 1.0);
                    let sin2_phi = (lx * vy - ly * vx).powi(2) / sin2_prod;
                    (cos_phi as f32, (sin2_phi / (1.0 + cos_phi.abs())) as f32)
                } else {
                    (0.0, 1.0)
                };
                let alpha = sin_a.atan2(cos_a);
                let beta = sin_b.atan2(cos_b);
                // u = 1 − 2β/π = 2(π/2 − β)/π, from the complement angle (accurate near grazing).
                let u = cos_b.atan2(sin_b) * FRAC_2_PI;
                let k = s2 / (s2 + 0.09);
                let c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
                // cos Δφ C2 tan β. For cos Δφ ≥ 0 it is 0.45k p / cos β (cos Δφ sin α tan β = p / cos β,
                // unbounded at grazing: cos β ≥ 1e-19 keeps it finite). For cos Δφ < 0 the factor
                // sin α − (2β/π)³ = u(3 − 3u + u²) − cos²α/(1 + sin α) is written without cancellation,
                // and tan β times it as sin β (u/cos β (3 − 3u + u²) − (cos α/cos β) cos α/(1 + sin α)),
                // bounded (→ 6/π as both directions graze; cos α ≤ cos β), so it needs no floor.
                let term2 = if cos_phi >= 0.0 {
                    0.45 * k * p / cos_b_safe
                } else {
                    let u_over_cos = cos_b.atan2(sin_b) * FRAC_2_PI / cos_b; // cos β > 0 (one-sided)
                    let tan_diff = sin_b * (u_over_cos * (3.0 - 3.0 * u + u * u) - (cos_a / cos_b) * cos_a / (1.0 + sin_a));
                    0.45 * k * cos_phi * tan_diff
                };
                let c3 = 0.125 * k * (4.0 * alpha * beta * FRAC_1_PI * FRAC_1_PI).powi(2);
                let tan_half = (sin_a + sin_b) / (cos_a + cos_b).max(COS_FLOOR); // cos α + cos β ≥ 1e-19
                let term3 = one_minus_abs_cos * c3 * tan_half;
                let single = rho_pi * (c1 + term2 + term3);
                let two_beta_pi = 1.0 - u;
                let inter = 0.17 * FRAC_1_PI * s2 / (s2 + 0.13) * (1.0 - cos_phi * two_beta_pi * two_beta_pi);
                // f ≥ 0: for σ > 38.07° the fitted C2 drives the direct term below zero as θ_l, θ_v → 90°
                // with Δφ = 180° (exact arithmetic; the ρ² interreflection compensates only for large ρ).
                (single + self.albedo * self.albedo * inter).max(Vec3::ZERO)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mirrored directions have equal cosines but sines that differ in the last bit: the
    /// roles of α and β must not swap with the arguments (f32 reciprocity to the bit).
    #[test]
    fn equal_cosines_are_reciprocal_to_the_bit() {
        let m = OrenNayar::from_degrees(Vec3::splat(0.8), 90.0, OrenNayarModel::Full);
        let mut checked = 0;
        for i in 1..400 {
            let (t, phi) = (i as f32 * 0.0039, i as f32 * 0.731);
            let l = Vec3::new(t.sin() * 0.6, t.sin() * 0.8, t.cos());
            // The same polar angle at another azimuth: equal z, sines equal only up to rounding.
            let v = Vec3::new(l.x * phi.cos() - l.y * phi.sin(), l.x * phi.sin() + l.y * phi.cos(), l.z);
            assert_eq!(m.eval(l, v).to_array().map(f32::to_bits), m.eval(v, l).to_array().map(f32::to_bits), "{l} {v}");
            checked += ((l.x * l.x + l.y * l.y).sqrt() != (v.x * v.x + v.y * v.y).sqrt()) as u32;
        }
        assert!(checked > 0, "no pair had sines differing in the last bit; the test would not catch the swap");
    }
    use crate::shading::diffuse::lambert_brdf;
    use std::f32::consts::FRAC_PI_2;

    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    #[test]
    fn sigma_zero_is_lambert_bit_for_bit() {
        let rho = Vec3::new(0.9, 0.5, 0.1);
        for model in [OrenNayarModel::Full, OrenNayarModel::Qualitative] {
            let on = OrenNayar { albedo: rho, sigma: 0.0, model };
            for (l, v) in
                [(dir(0.3, 0.0), dir(1.2, 2.0)), (Vec3::Z, dir(1.5, 0.0)), (dir(FRAC_PI_2 - 1e-4, 0.0), dir(FRAC_PI_2 - 1e-4, 0.0))]
            {
                assert_eq!(on.eval(l, v), lambert_brdf(rho), "{model:?}");
            }
        }
    }

    #[test]
    fn qualitative_by_hand() {
        // θ_l = 60°, θ_v = 30°, same azimuth: α = 60°, β = 30°, cos Δφ = 1.
        let sigma = 0.5f32;
        let on = OrenNayar { albedo: Vec3::ONE, sigma, model: OrenNayarModel::Qualitative };
        let s2 = sigma * sigma;
        let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
        let b = 0.45 * s2 / (s2 + 0.09);
        let expect = FRAC_1_PI * (a + b * 60f32.to_radians().sin() * 30f32.to_radians().tan());
        let f = on.eval(dir(60f32.to_radians(), 0.0), dir(30f32.to_radians(), 0.0));
        assert!((f.x / expect - 1.0).abs() < 1e-6);
    }

    #[test]
    fn retro_reflection_brighter_than_forward() {
        let on = OrenNayar { albedo: Vec3::ONE, sigma: 0.6, model: OrenNayarModel::Full };
        let l = dir(1.0, 0.0);
        let back = on.eval(l, dir(1.0, 0.0)).x;
        let forward = on.eval(l, dir(1.0, std::f32::consts::PI)).x;
        assert!(back > forward);
    }

    #[test]
    fn oren_nayar_full_goes_negative_beyond_38_degrees() {
        // Forward scattering with both directions 1e-4 rad above the horizon, ρ small so the
        // ρ² interreflection cannot compensate: the unclamped direct term changes sign at 38.07°.
        let direct = |sigma_deg: f32| {
            let on = OrenNayar { albedo: Vec3::splat(1e-3), sigma: sigma_deg.to_radians(), model: OrenNayarModel::Full };
            let l = dir(std::f32::consts::FRAC_PI_2 - 1e-4, 0.0);
            let v = dir(std::f32::consts::FRAC_PI_2 - 1e-4, std::f32::consts::PI);
            on.eval(l, v).x
        };
        assert!(direct(37.5) > 0.0);
        assert_eq!(direct(38.7), 0.0, "clamped");
        assert_eq!(direct(90.0), 0.0, "clamped");
    }

    #[test]
    fn pole_is_continuous() {
        // l at the normal: cos Δφ undefined; nearby azimuths must agree.
        let on = OrenNayar { albedo: Vec3::ONE, sigma: 1.0, model: OrenNayarModel::Full };
        let v = dir(0.8, 0.0);
        let at = on.eval(Vec3::Z, v).x;
        for phi in [0.0f32, 1.0, 3.0] {
            let near = on.eval(dir(1e-4, phi), v).x;
            assert!((near - at).abs() < 1e-3 * at, "φ={phi}: {near} vs {at}");
        }
    }
}
