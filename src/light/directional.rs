//! A directional light: parallel light from far away (the sun).
//!
//! | parameter | meaning |
//! | --- | --- |
//! | `direction` | unit direction the light travels; L = −direction at every point |
//!
//! It arrives unattenuated (d = 1, 1/r² = 1: its colour × intensity is the irradiance E⊥ on
//! a surface facing it) from an infinite distance. Shadows: by ray or by an orthographic map.

use crate::shading::incident::Incident;
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// A directional light's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Directional {
    /// Unit direction of travel.
    pub direction: Vec3,
}

impl Directional {
    /// Its incident at any point: `unlit` with L = −direction.
    #[inline(always)]
    pub fn incident<F: Lanes>(&self, unlit: Incident<F>) -> Incident<F> {
        Incident { l: V3::splat(-self.direction), ..unlit }
    }
}
