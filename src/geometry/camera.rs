//! A pinhole camera: right-handed, y up, looking down −z in view space.

use super::ray::Ray;
use glam::{DVec3, Mat4, Vec3, Vec4};

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

    /// The camera's basis in f64, for casting many rays (see [`CameraRays::ray`]).
    pub fn rays(&self) -> CameraRays {
        // The basis of `view`: f forward, s right, u up.
        let eye = self.position.as_dvec3();
        let f = (self.look_at.as_dvec3() - eye).normalize();
        let s = f.cross(self.up.as_dvec3()).normalize();
        let u = s.cross(f);
        CameraRays {
            eye,
            f,
            s,
            u,
            tan_half: (0.5 * (self.fov_y_deg as f64).to_radians()).tan(),
            aspect: self.width as f64 / self.height as f64,
            width: self.width as f64,
            height: self.height as f64,
        }
    }

    /// The ray through sample `sample` of `per_side²` of pixel `pixel`: see [`CameraRays::ray`].
    pub fn ray(&self, pixel: (u32, u32), sample: (u32, u32), per_side: u32) -> Ray {
        self.rays().ray(pixel, sample, per_side)
    }
}

/// A camera's basis, computed once for all the rays of an image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraRays {
    eye: DVec3,
    f: DVec3,
    s: DVec3,
    u: DVec3,
    tan_half: f64,
    aspect: f64,
    width: f64,
    height: f64,
}

impl CameraRays {
    /// The ray from the eye through sample `sample = (sx, sy)` of pixel `pixel = (x, y)` on
    /// the grid the rasterizer uses for `aa = per_side` (sample centres at x + (sx + ½)/per_side).
    ///
    /// Its direction has unit forward component, so the ray parameter of a hit is its view
    /// depth (what the near plane and the depth buffer compare).
    #[inline]
    pub fn ray(&self, pixel: (u32, u32), sample: (u32, u32), per_side: u32) -> Ray {
        let n = per_side as f64;
        let py = pixel.1 as f64 + (sample.1 as f64 + 0.5) / n;
        let px = pixel.0 as f64 + (sample.0 as f64 + 0.5) / n;
        self.through(px, py)
    }

    /// The ray from the eye through the image point (`px`, `py`) in pixels (0 at the top-left
    /// corner, pixel centres at +½), with a unit forward component as [`CameraRays::ray`].
    #[inline]
    pub fn through(&self, px: f64, py: f64) -> Ray {
        let ndc_y = 1.0 - 2.0 * py / self.height;
        let ndc_x = 2.0 * px / self.width - 1.0;
        let dir = self.s * (ndc_x * self.aspect * self.tan_half) + self.u * (ndc_y * self.tan_half) + self.f;
        Ray { origin: self.eye, dir }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 200 × 100, fov 40°, looking from (1, 2, 5) at (0, 0.5, 0).
    fn camera() -> Camera {
        Camera {
            position: Vec3::new(1.0, 2.0, 5.0),
            look_at: Vec3::new(0.0, 0.5, 0.0),
            up: Vec3::Y,
            fov_y_deg: 40.0,
            width: 200,
            height: 100,
            near: 0.1,
            background: Vec3::ZERO,
        }
    }

    #[test]
    fn look_at_point_projects_to_the_centre_with_reversed_depth() {
        let cam = camera();
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

    #[test]
    fn camera_rays_project_back_to_their_sample() {
        let cam = camera();
        // The centre of the image looks at look_at, at depth 1 per unit of t.
        let r = cam.ray((100, 50), (0, 0), 2);
        let forward = (cam.look_at - cam.position).as_dvec3().normalize();
        assert!((r.dir.dot(forward) - 1.0).abs() < 1e-12);
        assert!(r.dir.normalize().dot(forward) > 0.999_99);
        // Any sample's ray, projected, lands on that sample's centre in pixels.
        for (pixel, sample, n) in [((0, 0), (0, 0), 1), ((13, 77), (2, 1), 4), ((199, 99), (0, 0), 1)] {
            let p = r_point(&cam, pixel, sample, n);
            let c = cam.view_projection() * p.extend(1.0);
            let sx = (c.x / c.w + 1.0) * 0.5 * 200.0;
            let sy = (1.0 - c.y / c.w) * 0.5 * 100.0;
            let ex = pixel.0 as f32 + (sample.0 as f32 + 0.5) / n as f32;
            let ey = pixel.1 as f32 + (sample.1 as f32 + 0.5) / n as f32;
            assert!((sx - ex).abs() < 1e-3 && (sy - ey).abs() < 1e-3, "{pixel:?} {sample:?}: ({sx}, {sy}) vs ({ex}, {ey})");
        }
    }

    fn r_point(cam: &Camera, pixel: (u32, u32), sample: (u32, u32), n: u32) -> Vec3 {
        cam.ray(pixel, sample, n).at(3.0).as_vec3()
    }
}
