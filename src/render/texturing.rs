//! Textures at a shaded sample: its uv (perspective-correct, from the resolved barycentrics),
//! the uv footprint of one sample step (ray differentials), the tangent frame of a normal map.
//!
//! The footprint follows pbrt's ray differentials (Pharr, Jakob & Humphreys, *Physically
//! Based Rendering* 3rd ed., §10.1.1): the camera rays through the next sample to the right
//! and below meet the triangle's plane; their uvs minus this sample's are ∂uv/∂x and
//! ∂uv/∂y. On the rasterizer's grid this is exactly the finite difference a GPU's 2 × 2 quad
//! takes, without needing the neighbours to be covered by the same triangle. With `aa > 1`
//! the step is one sample, so each sample filters its own footprint and the box filter of
//! the pixel averages them.

use crate::geometry::camera::CameraRays;
use crate::scene::Geometry;
use glam::{DVec3, Vec2, Vec3};

/// The uv of triangle `t` at barycentrics `b` (weights of corners 0, 1, 2).
#[inline]
pub fn uv_at(g: &Geometry, t: usize, b: Vec3) -> Vec2 {
    let [a, c1, c2] = g.uvs[t];
    a * b.x + c1 * b.y + c2 * b.z
}

/// The barycentrics of world point `q` in triangle `t` (its plane), or `None` when the
/// triangle has no area.
fn barycentric(g: &Geometry, t: usize, q: Vec3) -> Option<Vec3> {
    let [p0, p1, p2] = g.triangles[t].map(|i| g.positions[i as usize]);
    let (e1, e2, w) = (p1 - p0, p2 - p0, q - p0);
    let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d20, d21) = (w.dot(e1), w.dot(e2));
    let denom = d00 * d11 - d01 * d01;
    // (Also a NaN denominator.)
    if denom.abs() <= f32::MIN_POSITIVE || denom.is_nan() {
        return None;
    }
    let b1 = (d11 * d20 - d01 * d21) / denom;
    let b2 = (d00 * d21 - d01 * d20) / denom;
    Some(Vec3::new(1.0 - b1 - b2, b1, b2))
}

/// Where the camera ray through sample `(sx, sy)` of the `aa`-per-side grid meets the plane
/// of triangle `t`, or `None` when it runs parallel to it or meets it behind the eye.
fn plane_hit(g: &Geometry, t: usize, rays: &CameraRays, (sx, sy): (u32, u32), aa: u32) -> Option<Vec3> {
    let ray = rays.ray((sx / aa, sy / aa), (sx % aa, sy % aa), aa);
    let p0 = g.positions[g.triangles[t][0] as usize].as_dvec3();
    let n: DVec3 = g.face_normals[t].as_dvec3();
    let denom = n.dot(ray.dir);
    if denom.abs() < 1e-12 {
        return None;
    }
    let s = n.dot(p0 - ray.origin) / denom;
    (s > 0.0 && s.is_finite()).then(|| (ray.origin + ray.dir * s).as_vec3())
}

/// ∂uv/∂x and ∂uv/∂y of triangle `t` at sample `(sx, sy)`: one sample step right and down.
/// A step whose ray misses the plane (past the horizon) is infinite, which selects the
/// coarsest mip level.
pub fn uv_footprint(g: &Geometry, t: usize, rays: &CameraRays, (sx, sy): (u32, u32), aa: u32) -> [Vec2; 2] {
    let uv = |s: (u32, u32)| plane_hit(g, t, rays, s, aa).and_then(|q| barycentric(g, t, q)).map(|b| uv_at(g, t, b));
    let Some(here) = uv((sx, sy)) else { return [Vec2::INFINITY; 2] };
    let step = |s| uv(s).map_or(Vec2::INFINITY, |o| o - here);
    [step((sx + 1, sy)), step((sx, sy + 1))]
}

/// The tangent of triangle `t` along increasing u and the sign of its bitangent (Lengyel,
/// "Computing Tangent Space Basis Vectors for an Arbitrary Mesh", 2001), per triangle.
/// A triangle whose uvs have no area (or a degenerate one) gets any tangent perpendicular
/// to its face normal and sign +1, so a normal map never makes a NaN.
pub fn triangle_tangent(g: &Geometry, t: usize) -> (Vec3, f32) {
    let [p0, p1, p2] = g.triangles[t].map(|i| g.positions[i as usize]);
    let [w0, w1, w2] = g.uvs[t];
    let (e1, e2) = (p1 - p0, p2 - p0);
    let (d1, d2) = (w1 - w0, w2 - w0);
    let r = d1.x * d2.y - d2.x * d1.y;
    let face = g.face_normals[t];
    let fallback = (face.any_orthonormal_vector(), 1.0);
    if r.abs() <= 1e-20 || r.is_nan() {
        return fallback;
    }
    let tangent = (e1 * d2.y - e2 * d1.y) / r;
    let bitangent = (e2 * d1.x - e1 * d2.x) / r;
    if !tangent.is_finite() || !bitangent.is_finite() || tangent.length_squared() < 1e-30 {
        return fallback;
    }
    let sign = if face.cross(tangent).dot(bitangent) < 0.0 { -1.0 } else { 1.0 };
    (tangent, sign)
}

/// The shading normal `n` bent by a tangent-space normal-map texel `c` (n_ts = 2c − 1), in the
/// frame of the triangle's `tangent` made perpendicular to `n` (Gram-Schmidt) and the
/// bitangent `sign`·n × T. A flat texel (n_ts = (0, 0, 1)) returns `n` unchanged; a
/// tangent parallel to `n` or a result that is not finite falls back to `n`.
pub fn bend_normal(n: Vec3, (tangent, sign): (Vec3, f32), c: Vec3) -> Vec3 {
    let ts = c * 2.0 - Vec3::ONE;
    if ts.x == 0.0 && ts.y == 0.0 {
        return n;
    }
    let t = (tangent - n * n.dot(tangent)).normalize_or_zero();
    if t == Vec3::ZERO {
        return n;
    }
    let b = n.cross(t) * sign;
    let bent = (t * ts.x + b * ts.y + n * ts.z.max(0.0)).normalize_or_zero();
    if bent == Vec3::ZERO { n } else { bent }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Camera;
    use crate::scene::{Mesh, shapes};

    /// The plane of `shapes::plane` scaled by `s` as a one-object geometry.
    fn plane_geometry(s: f32) -> Geometry {
        let m: Mesh = shapes::plane();
        Geometry {
            positions: m.positions.iter().map(|p| *p * s).collect(),
            normals: vec![Vec3::Y; 4],
            triangles: m.triangles.clone(),
            uvs: m.uvs.clone(),
            material: vec![0; 2],
            face_normals: vec![Vec3::Y; 2],
            ..Default::default()
        }
    }

    #[test]
    fn uv_interpolates_the_corners() {
        let g = plane_geometry(1.0);
        for t in 0..2 {
            for (k, b) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
                assert_eq!(uv_at(&g, t, b), g.uvs[t][k]);
            }
            let p = (g.positions[g.triangles[t][0] as usize] + g.positions[g.triangles[t][1] as usize]) * 0.5;
            let b = barycentric(&g, t, p).unwrap();
            let want = (g.uvs[t][0] + g.uvs[t][1]) * 0.5;
            assert!((uv_at(&g, t, b) - want).length() < 1e-6);
        }
    }

    #[test]
    fn footprint_of_a_plane_seen_from_straight_above() {
        // A 2 × 2 plane (uv over [0, 1]) seen from 1 unit above, fov 90°, 100 pixels: the view
        // spans 2 units, so one pixel is 0.02 units = 0.01 in u (and −0.01 in v, downwards is +z).
        let g = plane_geometry(1.0);
        let cam = Camera {
            position: Vec3::new(0.0, 1.0, 0.0),
            look_at: Vec3::ZERO,
            up: Vec3::NEG_Z,
            fov_y_deg: 90.0,
            width: 100,
            height: 100,
            near: 0.01,
            background: Vec3::ZERO,
        };
        let rays = cam.rays();
        for t in 0..2 {
            let [dx, dy] = uv_footprint(&g, t, &rays, (50, 50), 1);
            assert!((dx - Vec2::new(0.01, 0.0)).length() < 1e-5, "{dx}");
            assert!((dy - Vec2::new(0.0, -0.01)).length() < 1e-5, "{dy}");
        }
        // With aa = 4 a step is a quarter pixel.
        let [dx, _] = uv_footprint(&g, 0, &rays, (200, 200), 4);
        assert!((dx - Vec2::new(0.0025, 0.0)).length() < 1e-5, "{dx}");
    }

    #[test]
    fn flat_normal_map_texel_leaves_the_normal_unchanged() {
        let g = plane_geometry(1.0);
        let frame = triangle_tangent(&g, 0);
        for n in [Vec3::Y, Vec3::new(0.3, 0.9, -0.1).normalize()] {
            assert_eq!(bend_normal(n, frame, Vec3::new(0.5, 0.5, 1.0)), n);
        }
        // The plane's tangent runs along +x (u grows with x), its bitangent along −z (v grows as z falls).
        let (t, sign) = frame;
        assert!((t.normalize() - Vec3::X).length() < 1e-6, "{t}");
        let bent = bend_normal(Vec3::Y, frame, Vec3::new(1.0, 0.5, 0.5));
        assert!((bent - Vec3::X).length() < 1e-6, "{bent}");
        let bent = bend_normal(Vec3::Y, (t, sign), Vec3::new(0.5, 1.0, 0.5));
        assert!((bent - Vec3::NEG_Z).length() < 1e-6, "{bent}");
    }

    #[test]
    fn degenerate_uvs_give_a_finite_frame() {
        let mut g = plane_geometry(1.0);
        g.uvs[0] = [Vec2::splat(0.5); 3];
        let (t, sign) = triangle_tangent(&g, 0);
        assert!(t.is_finite() && t.length() > 0.5 && t.dot(Vec3::Y).abs() < 1e-6 && sign == 1.0);
        let bent = bend_normal(Vec3::Y, (t, sign), Vec3::new(0.9, 0.2, 0.6));
        assert!(bent.is_finite() && (bent.length() - 1.0).abs() < 1e-5);
        // A NaN uv does not poison the frame either.
        g.uvs[1] = [Vec2::NAN; 3];
        assert!(triangle_tangent(&g, 1).0.is_finite());
    }
}
