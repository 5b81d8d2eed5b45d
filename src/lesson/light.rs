//! The validated `[[light]]`: what the file says, every value checked against its range and
//! its kind's keys. The light room (`light::Light::from_spec`, one layer up) turns it into
//! the kind's parameters and behaviour; this file knows no light physics.

use super::kinds::{LightSampling, LightType, ShadowMethod};
use glam::Vec3;

/// One `[[light]]` as validated. Keys the kind does not read hold their defaults (zero
/// vectors, `None`), never a value from the file: validation refuses them.
#[derive(Debug, Clone, PartialEq)]
pub struct LightSpec {
    /// `kind`.
    pub kind: LightType,
    /// `color` × `intensity` (for `ambient`, L_amb).
    pub radiance: Vec3,
    /// `specular` × `intensity`, L_spec^k of the classic models (default: `radiance`).
    pub specular: Vec3,
    /// `ambient` (for an `ambient` light, its `radiance`).
    pub ambient: Vec3,
    /// `attenuation` [S_c, S_l, S_q] (default [1, 0, 0]).
    pub attenuation: Vec3,
    /// `samples` (16 for the sampled kinds, 64 for `sky`, 1 for the others).
    pub samples: u32,
    /// `shadows`, when the light sets its own.
    pub shadows: Option<ShadowMethod>,
    /// `sampling` (rect, sphere, line).
    pub sampling: LightSampling,
    /// `position` (point, spot, rect, disk, sphere).
    pub position: Vec3,
    /// `direction`, unit (directional, spot, rect, disk).
    pub direction: Vec3,
    /// Spot: `exponent` L_exp (default 1).
    pub exponent: f32,
    /// Spot: cos of `cutoff_deg` (−1 without one).
    pub cos_cutoff: f32,
    /// Spot: `profile` as (θ in degrees, I), θ increasing from 0.
    pub profile: Option<Vec<(f32, f32)>>,
    /// Rect: `size` [width, height].
    pub size: [f32; 2],
    /// Rect: the unit vector along its width (direction × up) and along its height.
    pub frame: [Vec3; 2],
    /// Disk, sphere, line: `radius`.
    pub radius: f32,
    /// Line: `start` and `end`.
    pub ends: [Vec3; 2],
    /// Sky: `ground_color` × `intensity`.
    pub ground: Vec3,
}

impl LightSpec {
    /// A light of `kind` with radiance `radiance` and every other key at its default.
    pub fn new(kind: LightType, radiance: Vec3) -> LightSpec {
        LightSpec {
            kind,
            radiance,
            specular: radiance,
            ambient: Vec3::ZERO,
            attenuation: Vec3::X,
            samples: 1,
            shadows: None,
            sampling: LightSampling::default(),
            position: Vec3::ZERO,
            direction: Vec3::ZERO,
            exponent: 1.0,
            cos_cutoff: -1.0,
            profile: None,
            size: [0.0; 2],
            frame: [Vec3::ZERO; 2],
            radius: 0.0,
            ends: [Vec3::ZERO; 2],
            ground: Vec3::ZERO,
        }
    }
}
