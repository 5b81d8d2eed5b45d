//! One sample of a light with extent, as seen from a shaded point.
//!
//! Which light paths it counts: direct light from the emitter, one-sided where the kind is
//! (rect, disk), visibility left to the caller. Each sample carries its share of the solid
//! angle, dω = A cos θ_l / (r² N) for a point q sampled uniformly on an emitter of area A
//! (θ_l between the emitter's normal and the way to the shaded point), so that
//! - physically based shading, L_o = Σ f L_e cos θ dω, estimates ∫ f L_e cos θ dω;
//! - the classic equation, K_diff ⊗ L_e Σ cos θ dω, estimates the course's K_diff ⊗ L_e·A′
//!   with A′ = ∫ cos θ dω the light's projected solid angle (no π), and its specular term
//!   the sampled sum Σ K_spec (R·V)^K_shi L_e dω.
//!
//! Where the N samples fall is the render's [`Sampler`](crate::geometry::sampler::Sampler)
//! (independent, stratified or Sobol, hashed per shaded point and light); how a point
//! u ∈ [0, 1)² becomes a point of the emitter is the light's [`LightSampling`]: uniform over its
//! area, or uniform over the solid angle it subtends (spherical rectangles, cones, thin tubes),
//! which leaves only the receiver's cosine and the visibility to vary between samples.

pub use crate::lesson::kinds::LightSampling;
use glam::Vec3;

/// One sample of a sampled light as seen from a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaSample {
    /// Unit direction from the point towards the sample.
    pub l: Vec3,
    /// Distance to the emitter along `l` (infinite for the sky).
    pub distance: f32,
    /// This sample's solid angle dω, already divided by the sample count; 0 when it sends
    /// no light to the point (the back of a one-sided emitter).
    pub weight: f32,
    /// Radiance L_e arriving along `l`.
    pub radiance: Vec3,
}

impl AreaSample {
    /// No light: the sample of a kind that is not sampled, or a degenerate one.
    pub const NONE: AreaSample = AreaSample { l: Vec3::Z, distance: 0.0, weight: 0.0, radiance: Vec3::ZERO };
}

/// A sample drawn uniformly in solid angle: direction, distance and `weight` = its dω
/// (already the share of one sample of N), carrying `radiance`.
#[inline]
pub(super) fn by_solid_angle(s: crate::geometry::spherical_rect::SolidAngleSample, per: f32, radiance: Vec3) -> AreaSample {
    if s.weight > 0.0 && s.weight.is_finite() && s.distance > 0.0 {
        AreaSample { l: s.l, distance: s.distance, weight: s.weight * per, radiance }
    } else {
        AreaSample::NONE
    }
}

/// A point `q` of an emitter (facing `normal` when one-sided) seen from `p`: dω = A cos θ_l / r².
#[inline]
pub(super) fn towards(p: Vec3, q: Vec3, normal: Option<Vec3>, area: f32, radiance: Vec3) -> AreaSample {
    let to = q - p;
    let r2 = to.length_squared();
    if r2 <= 1e-20 || !r2.is_finite() {
        return AreaSample::NONE;
    }
    let r = r2.sqrt();
    let l = to / r;
    // The emitter sends light towards `normal`: it reaches p when −l·normal > 0.
    let cos_l = normal.map_or(1.0, |nl| -l.dot(nl));
    let weight = if cos_l > 0.0 { area * cos_l / r2 } else { 0.0 };
    AreaSample { l, distance: r, weight, radiance }
}
