//! The perfect mirror: all light leaves in the mirror direction r = 2(n·v)n − v.
//!
//! | parameter | range | meaning |
//! | --- | --- | --- |
//! | `tint` | [0, 1]³ | the reflectance (1: a perfect mirror, as Mitsuba's `conductor` with `material = "none"`) |
//!
//! L_o(v) = tint ⊗ L_i(r). The BRDF is a Dirac delta, so a point, spot or area light (a set
//! of measure zero or a finite set of directions) is never seen in it: a mirror shows only
//! what its reflected ray finds, the environment or another object (the reflection layer,
//! added by render). Its direct diffuse and specular terms are zero.

use glam::Vec3;

/// A perfect specular reflector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mirror {
    /// Reflectance per channel.
    pub tint: Vec3,
}
