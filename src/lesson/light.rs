//! Lights as the lesson gives them: colour, position or direction, attenuation, spot cone;
//! the area, line and sky lights with their sample counts; each light's shadow method.
//! What each delivers at a shaded point is computed by the scene (`Light::incident`).

use crate::lesson::settings::ShadowMethod;
use glam::Vec3;

/// The closed set of light kinds.
// A spot's profile is held inline (a fixed array) so that lights stay `Copy`.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightKind {
    /// Parallel light; `direction` (unit) is the way it travels, so L = −direction.
    Directional {
        /// Unit direction of travel.
        direction: Vec3,
    },
    /// Light from a point.
    Point {
        /// World position.
        position: Vec3,
    },
    /// A point light restricted to a cone: C_spot = max(−L·L_dir, 0)^L_exp, or the
    /// goniometric `profile` I(θ) when one is given.
    Spot {
        /// World position.
        position: Vec3,
        /// Unit axis of the cone (the way the light travels).
        direction: Vec3,
        /// L_exp.
        exponent: f32,
        /// cos of the cutoff half-angle; outside it C_spot = 0 (−1 = no cutoff).
        cos_cutoff: f32,
        /// A measured distribution I(θ) that replaces the cos^L_exp law.
        profile: Option<SpotProfile>,
    },
    /// Only an ambient contribution I_amb = K_amb ⊗ L_amb.
    Ambient,
    /// A one-sided rectangle emitting radiance L_e towards `direction`.
    Rect {
        /// Centre.
        position: Vec3,
        /// Unit normal of the emitting side (the way the light travels).
        direction: Vec3,
        /// Half the `w` side, as a vector in the rectangle's plane.
        half_w: Vec3,
        /// Half the `h` side, as a vector in the rectangle's plane (⊥ `half_w`).
        half_h: Vec3,
    },
    /// A one-sided disk emitting radiance L_e towards `direction`.
    Disk {
        /// Centre.
        position: Vec3,
        /// Unit normal of the emitting side.
        direction: Vec3,
        /// Radius (> 0).
        radius: f32,
    },
    /// A sphere emitting radiance L_e all round.
    Sphere {
        /// Centre.
        position: Vec3,
        /// Radius (> 0).
        radius: f32,
    },
    /// A thin tube from `start` to `end` emitting radiance L_e all round (a fluorescent lamp).
    Line {
        /// One end of the axis.
        start: Vec3,
        /// The other end.
        end: Vec3,
        /// Tube radius (> 0).
        radius: f32,
    },
    /// A hemisphere light: radiance `color × intensity` from above the horizon, `ground`
    /// from below.
    Sky {
        /// Radiance from below the horizon (y < 0).
        ground: Vec3,
    },
}

/// Most points of a spot's `profile`.
pub const MAX_PROFILE_POINTS: usize = 32;

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

impl LightKind {
    /// True for the lights sampled at several points (rect, disk, sphere, line, sky).
    pub fn is_sampled(&self) -> bool {
        matches!(
            self,
            LightKind::Rect { .. } | LightKind::Disk { .. } | LightKind::Sphere { .. } | LightKind::Line { .. } | LightKind::Sky { .. }
        )
    }
}

/// One light of the illumination equation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Kind and geometry.
    pub kind: LightKind,
    /// L_diff = L_spec: colour × intensity (for `Ambient`, this is L_amb).
    pub radiance: Vec3,
    /// This light's ambient part L_amb^k (for `Ambient` lights equal to `radiance`).
    pub ambient: Vec3,
    /// [S_c, S_l, S_q] for d = 1/(S_c + S_l r + S_q r²); ignored by directional lights.
    pub attenuation: Vec3,
    /// Samples per shaded point for the sampled kinds (1 for the others).
    pub samples: u32,
    /// This light's own shadow method (`None`: the `[render]` one).
    pub shadows: Option<ShadowMethod>,
}
