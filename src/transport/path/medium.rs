//! The `[fog]` medium of the path tracer: where a ray is inside its ball, and the
//! transmittance along a segment.

use crate::effects::fog::medium::transmittance;
use glam::Vec3;

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
