//! Lights as the lesson gives them: colour, position or direction, attenuation, spot cone.
//! What each delivers at a shaded point is computed by the scene (`Light::incident`).

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
}
