//! A homogeneous participating medium: its transmittance and how far an eye ray that hits
//! nothing is marched; the march itself (single scattering along an eye ray, with each
//! light's visibility) is `transport::medium`, whose docs give the integral.

use crate::light::{Light, LightKind};

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
    matches!(l.kind, LightKind::Point(_) | LightKind::Spot(_) | LightKind::Directional(_))
}
