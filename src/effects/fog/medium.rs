//! A homogeneous participating medium: transmittance and the ray-marched single-scattering
//! integral along an eye ray.
//!
//! Which light paths it counts: light → (medium, attenuated) → one scattering event in the
//! medium → (attenuated) → eye, plus the surface's radiance attenuated on its way to the eye
//! (the surface itself is lit by light attenuated on its way there, `render::incidents`).
//! Multiple scattering is not counted. The radiance reaching the eye along a ray of length d
//! (Sun et al. 2005, eq. 1; Pharr, Jakob & Humphreys, pbrt-v4 §11.1, the volume rendering
//! equation restricted to single scattering):
//!
//! L = L_surface·T(d) + ∫₀ᵈ T(s) σ_s Σ_lights p(θ) E⊥(x(s)) V(x(s)) ds,  T(s) = e^(−σ_t s),
//!
//! with E⊥ = I·C_spot·e^(−σ_t r)/r² for a point or spot light r away (radiometric: the
//! falloff physically based surfaces see; the classic `attenuation` coefficients are a
//! surface convention and are not read here) and E⊥ = L for a directional light (taken to
//! arrive with the given strength: a light infinitely far in an infinite medium would be
//! extinguished), V the light's shadow method seen from the medium point. Lights with extent
//! (rect, disk, sphere, line, sky) and ambient light light the surfaces through the medium
//! but scatter nothing into the eye ray.
//!
//! The integral is a jittered Riemann sum of N steps: s_k = (k + u) d/N, u in [0, 1) one
//! hash per sample, so the estimate is unbiased and the error falls as N grows (measured in
//! docs/accuracy-and-cost.md, `fog_steps`). The transmittances are exact exponentials.

use super::phase::henyey_greenstein;
use crate::effects::shadows::{Origin, Shadows};
use crate::lesson::fog::Medium;
use crate::scene::{Light, LightKind};
use glam::Vec3;

/// The transmittance whose distance bounds an eye ray that hits nothing: the in-scattered
/// light beyond it is weighted by less than this.
pub const FAR_TRANSMITTANCE: f64 = 1e-4;

/// T = e^(−σ_t s), in f64 rounded to f32 (the same bits on every machine but for rare
/// rounding-boundary cases, as `geometry::sampling::sin_cos`); 1 for s = ∞ with σ_t = 0 and
/// 0 for s = ∞ otherwise.
#[inline]
pub fn transmittance(sigma_t: f32, s: f32) -> f32 {
    if sigma_t == 0.0 {
        return 1.0;
    }
    (-(sigma_t as f64) * s as f64).exp() as f32
}

/// How far an eye ray that hits nothing is marched: where T falls to [`FAR_TRANSMITTANCE`],
/// s = ln(10⁴)/σ_t, but no farther than `cap` (a multiple of the scene's size, so that a thin
/// medium does not spread its steps over thousands of units where no light reaches).
pub fn far_bound(sigma_t: f32, cap: f32) -> f32 {
    if sigma_t <= 0.0 {
        return cap;
    }
    ((1.0 / FAR_TRANSMITTANCE).ln() / sigma_t as f64).min(cap as f64) as f32
}

/// The lights that scatter into eye rays: point, spot and directional lights.
pub fn scatters(l: &Light) -> bool {
    matches!(l.kind, LightKind::Point { .. } | LightKind::Spot { .. } | LightKind::Directional { .. })
}

/// The light scattered towards the eye at point `x` per unit length and per unit σ_s:
/// Σ_lights p(θ) E⊥ V, `dir` the eye ray's unit direction. Counts its shadow queries.
#[inline]
pub fn in_scatter(m: &Medium, lights: &[Light], shadows: &Shadows, x: Vec3, dir: Vec3) -> Vec3 {
    let sigma_t = m.sigma_t();
    let mut sum = Vec3::ZERO;
    for (i, light) in lights.iter().enumerate() {
        if !scatters(light) {
            continue;
        }
        let inc = light.incident::<f32>(x.into());
        let l = Vec3::from(inc.l);
        if inc.c_spot <= 0.0 || l == Vec3::ZERO {
            continue;
        }
        // E⊥: I/r² through the medium, or a directional light's own strength.
        let e = if inc.distance.is_finite() { inc.inv_r2 * transmittance(sigma_t, inc.distance) } else { 1.0 };
        let w = e * inc.c_spot * henyey_greenstein(l.dot(dir), m.g);
        // Also skips a NaN weight (none is expected: every factor is finite for |g| < 1).
        if w.is_nan() || w <= 0.0 {
            continue;
        }
        let v = if shadows.casts(i) {
            // A point in the medium lies on no surface: no triangle or object to skip, and
            // its "normal" faces the light (no offset sideways, no slope bias).
            let o = Origin { p: x, ng: l, tri: u32::MAX, object: u32::MAX };
            shadows.counted(i, 1);
            shadows.visibility(i, &o, l, inc.distance)
        } else {
            1.0
        };
        sum += light.radiance * (w * v);
    }
    sum
}

/// A stretch of an eye ray: from `origin` along unit `dir` for `length`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EyeRay {
    /// The eye.
    pub origin: Vec3,
    /// Unit direction, away from the eye.
    pub dir: Vec3,
    /// How far it crosses the medium (to the surface it hits, or the far bound).
    pub length: f32,
}

/// `ray` through the medium, with `surface` the radiance at its end: L_surface·T(length) +
/// the marched in-scattering of `lights` (with their `shadows`), with jitter `u` in [0, 1).
pub fn march(m: &Medium, lights: &[Light], shadows: &Shadows, ray: EyeRay, surface: Vec3, u: f32) -> Vec3 {
    let EyeRay { origin: eye, dir, length } = ray;
    let sigma_t = m.sigma_t();
    let attenuated = surface * transmittance(sigma_t, length);
    // A zero (or NaN) length has nothing to march.
    if m.sigma_s == 0.0 || length.is_nan() || length <= 0.0 {
        return attenuated;
    }
    let n = m.steps.max(1);
    let ds = length / n as f32;
    let mut sum = Vec3::ZERO;
    for k in 0..n {
        let s = (k as f32 + u) * ds;
        sum += in_scatter(m, lights, shadows, eye + dir * s, dir) * transmittance(sigma_t, s);
    }
    attenuated + sum * (m.sigma_s * ds)
}
