//! A pinhole camera: right-handed, y up, looking down −z in view space.

use glam::{Mat4, Vec3, Vec4};

/// Camera as the lesson gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3,
    /// Point looked at.
    pub look_at: Vec3,
    /// Up vector (need not be orthogonal to the view direction).
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub fov_y_deg: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Near clipping distance.
    pub near: f32,
    /// Linear RGB background.
    pub background: Vec3,
}

impl Camera {
    /// World → view transform.
    pub fn view(&self) -> Mat4 {
        // Orthonormal basis: f forward, s right, u up; the view matrix is its transpose with the eye moved to the origin.
        let f = (self.look_at - self.position).normalize();
        let s = f.cross(self.up).normalize();
        let u = s.cross(f);
        let e = self.position;
        Mat4::from_cols(
            Vec4::new(s.x, u.x, -f.x, 0.0),
            Vec4::new(s.y, u.y, -f.y, 0.0),
            Vec4::new(s.z, u.z, -f.z, 0.0),
            Vec4::new(-s.dot(e), -u.dot(e), f.dot(e), 1.0),
        )
    }

    /// View → clip transform: infinite far plane, reversed depth (z/w = near/distance, 1 at the
    /// near plane, → 0 far away) for even f32 depth precision.
    pub fn projection(&self) -> Mat4 {
        let aspect = self.width as f32 / self.height as f32;
        let f = 1.0 / (0.5 * self.fov_y_deg.to_radians()).tan();
        // x_c = f/aspect·x, y_c = f·y, z_c = near, w_c = −z: so z/w = near/(−z).
        Mat4::from_cols(
            Vec4::new(f / aspect, 0.0, 0.0, 0.0),
            Vec4::new(0.0, f, 0.0, 0.0),
            Vec4::new(0.0, 0.0, 0.0, -1.0),
            Vec4::new(0.0, 0.0, self.near, 0.0),
        )
    }

    /// World → clip transform.
    pub fn view_projection(&self) -> Mat4 {
        self.projection() * self.view()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_point_projects_to_the_centre_with_reversed_depth() {
        let cam = Camera {
            position: Vec3::new(1.0, 2.0, 5.0),
            look_at: Vec3::new(0.0, 0.5, 0.0),
            up: Vec3::Y,
            fov_y_deg: 40.0,
            width: 200,
            height: 100,
            near: 0.1,
            background: Vec3::ZERO,
        };
        let c = cam.view_projection() * cam.look_at.extend(1.0);
        let d = (cam.look_at - cam.position).length();
        assert!((c.x / c.w).abs() < 1e-6 && (c.y / c.w).abs() < 1e-6);
        assert!((c.w - d).abs() < 1e-5);
        assert!((c.z / c.w - 0.1 / d).abs() < 1e-6);
        // A point on the top edge of the field of view lands at y_ndc = 1.
        let view = cam.view();
        let top = view.inverse() * Vec4::new(0.0, 20f32.to_radians().tan() * 3.0, -3.0, 1.0);
        let t = cam.view_projection() * top;
        assert!((t.y / t.w - 1.0).abs() < 1e-5);
        // x is scaled by the aspect ratio: the right edge is at the same angle × 2.
        let right = view.inverse() * Vec4::new(2.0 * 20f32.to_radians().tan() * 3.0, 0.0, -3.0, 1.0);
        let r = cam.view_projection() * right;
        assert!((r.x / r.w - 1.0).abs() < 1e-5);
    }
}
