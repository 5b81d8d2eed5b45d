//! The validated `[[probe]]` table: a reflection probe, a cube map rendered from `position`
//! and looked up by mirrors inside its box (`effects::probe`).

use glam::Vec3;

/// Face resolution when `size` is not given.
pub const DEFAULT_PROBE_SIZE: u32 = 128;

/// One `[[probe]]`: where it is captured, at what resolution, and the box that its
/// parallax correction assumes (the room's walls).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeSpec {
    /// The capture point C (strictly inside the box).
    pub position: Vec3,
    /// Texels along a face's side.
    pub size: u32,
    /// The box's smallest corner B_min.
    pub box_min: Vec3,
    /// The box's largest corner B_max (greater than `box_min` on every axis).
    pub box_max: Vec3,
    /// The moved centre C′ that `reflections = "probe_moved"` reads the capture from
    /// (strictly inside the box); `position` when not given.
    pub moved_to: Vec3,
}

impl ProbeSpec {
    /// True when `x` lies in the closed box.
    pub fn contains(&self, x: Vec3) -> bool {
        x.cmpge(self.box_min).all() && x.cmple(self.box_max).all()
    }
}
