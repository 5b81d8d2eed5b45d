//! Clipping in homogeneous clip space (Sutherland & Hodgman 1974).
//!
//! A triangle that crosses the near plane (or the far guard band) is cut into a convex
//! polygon; each new vertex remembers its barycentric coordinates in the original
//! triangle, so the visibility buffer can always speak of the original triangle.

use glam::{Vec3, Vec4};

/// A clip-space vertex with its barycentrics in the original triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipVertex {
    /// Clip-space position.
    pub pos: Vec4,
    /// Barycentric coordinates in the original triangle.
    pub bary: Vec3,
}

/// Most vertices a triangle can have after clipping by [`PLANES`] planes.
pub const MAX_VERTS: usize = 3 + PLANES;
/// Number of clip planes: near plus four guard-band planes.
pub const PLANES: usize = 5;

/// A convex polygon of at most [`MAX_VERTS`] vertices, on the stack.
#[derive(Debug, Clone, Copy)]
pub struct Polygon {
    /// Storage.
    pub verts: [ClipVertex; MAX_VERTS],
    /// Number of vertices in use.
    pub len: usize,
}

/// Signed distances of `p` to the clip planes; inside when all are ≥ 0.
///
/// Near plane: with the reversed infinite projection, z_clip = near, so z ≤ w ⇔ w ≥ near.
/// Guard band: |x|, |y| ≤ g·w keeps fixed-point screen coordinates in range.
#[inline]
pub fn distances(p: Vec4, g: f32) -> [f32; PLANES] {
    [p.w - p.z, g * p.w - p.x, g * p.w + p.x, g * p.w - p.y, g * p.w + p.y]
}

/// Clips a triangle against all planes. Returns `None` when nothing is left.
pub fn clip_triangle(v: [Vec4; 3], g: f32) -> Option<Polygon> {
    let none = ClipVertex { pos: Vec4::ZERO, bary: Vec3::ZERO };
    let mut poly = Polygon { verts: [none; MAX_VERTS], len: 3 };
    poly.verts[0] = ClipVertex { pos: v[0], bary: Vec3::X };
    poly.verts[1] = ClipVertex { pos: v[1], bary: Vec3::Y };
    poly.verts[2] = ClipVertex { pos: v[2], bary: Vec3::Z };
    for plane in 0..PLANES {
        let mut out = Polygon { verts: [none; MAX_VERTS], len: 0 };
        for i in 0..poly.len {
            let a = poly.verts[i];
            let b = poly.verts[(i + 1) % poly.len];
            let da = distances(a.pos, g)[plane];
            let db = distances(b.pos, g)[plane];
            if da >= 0.0 {
                out.push(a);
            }
            // The edge crosses the plane: add the intersection (linear in clip space).
            if (da >= 0.0) != (db >= 0.0) {
                let t = da / (da - db);
                out.push(ClipVertex { pos: a.pos.lerp(b.pos, t), bary: a.bary.lerp(b.bary, t) });
            }
        }
        if out.len < 3 {
            return None;
        }
        poly = out;
    }
    Some(poly)
}

impl Polygon {
    #[inline]
    fn push(&mut self, v: ClipVertex) {
        // Each plane adds at most one vertex to a convex polygon, so this never overflows.
        if self.len < MAX_VERTS {
            self.verts[self.len] = v;
            self.len += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_across_the_near_plane_becomes_a_quad() {
        // Two vertices in front (w = 2), one behind (w = -1); z = near = 0.1 everywhere.
        let v = [Vec4::new(0.0, 0.0, 0.1, 2.0), Vec4::new(1.0, 0.0, 0.1, 2.0), Vec4::new(0.0, 1.0, 0.1, -1.0)];
        let p = clip_triangle(v, 100.0).unwrap();
        assert_eq!(p.len, 4);
        for cv in &p.verts[..p.len] {
            assert!(cv.pos.w >= 0.1 - 1e-6);
            // Barycentrics reproduce the position.
            let re = v[0] * cv.bary.x + v[1] * cv.bary.y + v[2] * cv.bary.z;
            assert!((re - cv.pos).length() < 1e-5);
            assert!((cv.bary.x + cv.bary.y + cv.bary.z - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn fully_behind_is_rejected() {
        let v = [Vec4::new(0.0, 0.0, 0.1, -1.0), Vec4::new(1.0, 0.0, 0.1, -2.0), Vec4::new(0.0, 1.0, 0.1, -1.0)];
        assert!(clip_triangle(v, 100.0).is_none());
    }
}
