//! Lights as the lesson gives them: colour, position or direction, attenuation, spot cone;
//! the area, line and sky lights with their sample counts; each light's shadow method.
//! What each delivers at a shaded point is computed by the scene (`Light::incident`).

use crate::lesson::settings::ShadowMethod;
use glam::Vec3;

/// The closed set of light kinds.
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
    /// A point light restricted to a cone: C_spot = max(−L·L_dir, 0)^L_exp.
    Spot {
        /// World position.
        position: Vec3,
        /// Unit axis of the cone (the way the light travels).
        direction: Vec3,
        /// L_exp.
        exponent: f32,
        /// cos of the cutoff half-angle; outside it C_spot = 0 (−1 = no cutoff).
        cos_cutoff: f32,
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
