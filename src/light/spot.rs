//! A spot light: a point light restricted to a cone, C_spot = max(−L·L_dir, 0)^L_exp inside
//! the cutoff (the course's Warn model), or a measured distribution I(θ) (a goniometric
//! profile, as IES files give) instead of the cos^L_exp law.
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `position` | world position |
//! | `direction` | unit axis of the cone, the way the light travels |
//! | `exponent` | L_exp ≥ 0 |
//! | `cos_cutoff` | cos of the cutoff half-angle (−1: no cutoff); outside it C_spot = 0 |
//! | `profile` | I(θ) points, linear in θ, 0 beyond the last angle |
//!
//! Shadows: by ray, by one perspective map up to an 80° cutoff, else by a cube of six.

use super::point::{attenuation, towards};
use crate::lesson::light::LightSpec;
use crate::shading::incident::Incident;
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// A spot light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spot {
    /// World position.
    pub position: Vec3,
    /// Unit axis of the cone (the way the light travels).
    pub direction: Vec3,
    /// L_exp.
    pub exponent: f32,
    /// cos of the cutoff half-angle; outside it C_spot = 0 (−1 = no cutoff).
    pub cos_cutoff: f32,
    /// A measured distribution I(θ) that replaces the cos^L_exp law.
    pub profile: Option<SpotProfile>,
}

impl Spot {
    /// The spot a validated `[[light]]` describes.
    pub fn from_spec(l: &LightSpec) -> Spot {
        Spot {
            position: l.position,
            direction: l.direction,
            exponent: l.exponent,
            cos_cutoff: l.cos_cutoff,
            profile: l.profile.as_deref().map(SpotProfile::new),
        }
    }

    /// Its incident at `p`: the point light's, with C_spot.
    #[inline(always)]
    pub fn incident<F: Lanes>(&self, s: Vec3, p: V3<F>, unlit: Incident<F>) -> Incident<F> {
        let one = F::splat(1.0);
        let (l, r, inv_r2) = towards(V3::splat(self.position), p);
        let cos_axis = (-l).dot(V3::splat(self.direction));
        // C_spot = 0 outside the cutoff or behind the light, else min(cos, 1)^L_exp,
        // or the profile's I(θ) lane by lane.
        let outside = cos_axis.lt(F::splat(self.cos_cutoff)) | cos_axis.le(F::splat(0.0));
        let cos = F::select(cos_axis.lt(one), cos_axis, one);
        let law = match self.profile {
            None => cos.pow(self.exponent),
            Some(profile) => {
                let mut c = [0f32; crate::simd::lanes::MAX_WIDTH];
                cos.store(&mut c);
                for x in c.iter_mut().take(F::WIDTH) {
                    *x = profile.at_cos(*x);
                }
                F::load(&c)
            }
        };
        let c_spot = F::select(outside, F::splat(0.0), law);
        Incident { l, distance: r, attenuation: attenuation(s, r), inv_r2, c_spot, ..unlit }
    }
}

/// Most points of a spot's `profile` (a lesson limit: the profile is held inline so that
/// lights stay `Copy`).
pub use crate::lesson::limits::MAX_PROFILE_POINTS;

/// A goniometric spot's intensity I(θ): points (θ in degrees, I) with θ increasing from 0,
/// linearly interpolated, 0 beyond the last angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpotProfile {
    /// How many of the points are used (1 ..= [`MAX_PROFILE_POINTS`]).
    pub len: usize,
    /// The angles θ in degrees from the spot's axis, increasing from 0.
    pub theta_deg: [f32; MAX_PROFILE_POINTS],
    /// I at each angle (≥ 0).
    pub value: [f32; MAX_PROFILE_POINTS],
}

impl SpotProfile {
    /// The profile of the given points (at most [`MAX_PROFILE_POINTS`], checked by the caller).
    pub fn new(points: &[(f32, f32)]) -> SpotProfile {
        let mut p = SpotProfile {
            len: points.len().min(MAX_PROFILE_POINTS),
            theta_deg: [0.0; MAX_PROFILE_POINTS],
            value: [0.0; MAX_PROFILE_POINTS],
        };
        for (i, (t, v)) in points.iter().take(MAX_PROFILE_POINTS).enumerate() {
            (p.theta_deg[i], p.value[i]) = (*t, *v);
        }
        p
    }

    /// I(θ) for θ in degrees: linear between the points, 0 beyond the last one.
    pub fn at(&self, theta_deg: f32) -> f32 {
        let (t, v) = (&self.theta_deg[..self.len], &self.value[..self.len]);
        if theta_deg.is_nan() || theta_deg > t[self.len - 1] {
            return 0.0;
        }
        let theta_deg = theta_deg.max(0.0);
        let k = t.partition_point(|&a| a <= theta_deg);
        if k == 0 || k == self.len {
            return v[k.saturating_sub(1)];
        }
        let f = (theta_deg - t[k - 1]) / (t[k] - t[k - 1]);
        v[k - 1] + (v[k] - v[k - 1]) * f
    }

    /// I at the angle whose cosine is `cos` (clamped to [−1, 1]).
    pub fn at_cos(&self, cos: f32) -> f32 {
        self.at(cos.clamp(-1.0, 1.0).acos().to_degrees())
    }
}
