//! Vertices onto the sample grid: clip space to fixed point, snapped to 1/256 sample, or
//! marked for the clipping path when outside the guard band or the near plane.

use super::{ONE, clip};
use glam::Vec4;

/// A vertex on the sample grid: fixed-point position, reversed depth z/w, 1/w
/// ([`Projected::CLIP`] when its triangles need the clipping path).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C)]
pub(super) struct Projected {
    pub(super) x: i32,
    pub(super) y: i32,
    pub(super) z: f32,
    pub(super) q: f32,
}

impl Projected {
    /// Marks a vertex outside the guard band or the near plane, or not finite (x is never
    /// i32::MIN on the grid: the guard band keeps |x| < 2^28).
    pub(super) const CLIP: Projected = Projected { x: i32::MIN, y: 0, z: 0.0, q: 0.0 };
}

/// Vertex `p` (clip space) on the sample grid, or [`Projected::CLIP`] when it is outside the
/// guard band or the near plane, or not finite.
#[inline]
pub(super) fn project_one(p: Vec4, width: u32, height: u32, g: f32) -> Projected {
    let inside = p.is_finite() && clip::distances(p, g).iter().all(|d| *d >= 0.0);
    if inside { project_vertex(p, width, height) } else { Projected::CLIP }
}

/// Clip space → sample grid: x right, y down (row 0 at the top), snapped to 1/256 sample.
///
/// Precondition: `v` is inside the guard band and in front of the near plane.
#[inline]
pub(super) fn project_vertex(v: Vec4, width: u32, height: u32) -> Projected {
    let q = 1.0 / v.w;
    let sx = (v.x * q + 1.0) * 0.5 * width as f32;
    let sy = (1.0 - v.y * q) * 0.5 * height as f32;
    Projected { x: round_half_away(sx * ONE as f32), y: round_half_away(sy * ONE as f32), z: v.z * q, q }
}

/// `x.round() as i32` for |x| < 2^30 without the libm call `f32::round` is on baseline x86-64
/// (no SSE4.1 `roundss`): truncate, then step away from zero when the dropped fraction is at
/// least ½. Exact: for |x| < 2^23 the fraction x − trunc(x) is computed exactly, and above
/// that x is an integer (tested against `f32::round`). Measured: `roundf` was 5.7% of the
/// dense bench.
#[inline]
pub(super) fn round_half_away(x: f32) -> i32 {
    let t = x as i32;
    let frac = x - t as f32;
    t + (frac >= 0.5) as i32 - (frac <= -0.5) as i32
}
