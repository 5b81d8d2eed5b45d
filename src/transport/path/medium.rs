//! The `[fog]` medium of the path tracer: where a ray is inside its ball, and the
//! transmittance along a segment.

use crate::effects::fog::medium::transmittance;
use crate::geometry::sampling::sin_cos;
use crate::shading::brdf::local_frame;
use glam::{Vec2, Vec3};

/// The `[fog]` medium as the path tracer sees it: grey coefficients in a ball about the eye.
#[derive(Debug, Clone, Copy)]
pub(super) struct Medium {
    pub(super) sigma_s: f32,
    pub(super) sigma_t: f32,
    pub(super) g: f32,
    pub(super) centre: Vec3,
    pub(super) radius: f32,
}

impl Medium {
    /// The part [t0, t1] of the ray o + t d (unit d, t ≥ 0) inside the ball, or `None`.
    pub(super) fn interval(&self, o: Vec3, d: Vec3) -> Option<(f32, f32)> {
        let oc = o - self.centre;
        let b = oc.dot(d);
        let c = oc.length_squared() - self.radius * self.radius;
        let disc = b * b - c;
        if disc.is_nan() || disc <= 0.0 {
            return None;
        }
        let s = disc.sqrt();
        let (t0, t1) = ((-b - s).max(0.0), -b + s);
        (t1 > t0).then_some((t0, t1))
    }

    /// Transmittance along o + t d for t in [0, distance] (∞ for a light at infinity).
    pub(super) fn transmittance(&self, o: Vec3, d: Vec3, distance: f32) -> f32 {
        match self.interval(o, d) {
            Some((t0, t1)) => transmittance(self.sigma_t, (t1.min(distance) - t0).max(0.0)),
            None => 1.0,
        }
    }
}

/// A direction drawn from the Henyey-Greenstein phase about the travel direction `d` (unit),
/// by inverting its cumulative distribution in μ = cos θ (pbrt-v3 §15.2.3): the pdf is the
/// phase itself, p(μ) of [`henyey_greenstein`] with μ = l·d.
pub fn sample_henyey_greenstein(d: Vec3, g: f32, u: Vec2) -> Vec3 {
    let mu = if g.abs() < 1e-3 {
        1.0 - 2.0 * u.x
    } else {
        let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        (1.0 + g * g - s * s) / (2.0 * g)
    }
    .clamp(-1.0, 1.0);
    let sin = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let (sp, cp) = sin_cos(std::f32::consts::TAU * u.y);
    let (t, b) = local_frame(d);
    (t * (sin * cp) + b * (sin * sp) + d * mu).normalize_or(d)
}
