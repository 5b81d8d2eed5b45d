//! Normals drawn over a render: face normals at triangle centroids and vertex normals at
//! vertices, as short anti-aliased lines (a "hedgehog"), so a figure can show that each
//! vertex normal is the average of the face normals around it.
//!
//! Only what the camera sees is drawn: a normal's foot must pass the depth test against
//! the render's own visibility buffer (the nearest surface at that sample), and a face
//! normal belongs to a front-facing triangle. Lines are drawn with exact coverage of a
//! round-capped segment (distance to the segment, 1-pixel feather), in sRGB over the
//! developed image, so the result is deterministic.

use crate::lesson::Normals;
use crate::raster::{NO_TRIANGLE, VisBuffer};
use crate::scene::Scene;
use glam::{Vec2, Vec3, Vec4};
use image::RgbaImage;

/// Face normals: warm yellow.
pub const FACE_COLOUR: [u8; 3] = [255, 200, 40];
/// Vertex normals: cyan.
pub const VERTEX_COLOUR: [u8; 3] = [60, 210, 255];

/// A normal's length as a share of its object's bounding radius.
const LENGTH: f32 = 0.22;

/// Draws the chosen normals of `scene` onto `img` (the developed render of `scene`,
/// `img` pixels = camera pixels), testing visibility against `vis` (made from `scene`).
/// Returns how many normals were drawn.
pub fn draw_normals(img: &mut RgbaImage, scene: &Scene, vis: &VisBuffer, which: Normals) -> usize {
    let g = &scene.geometry;
    let cam = &scene.spec.camera;
    let vp = cam.view_projection();
    let (w, h) = (cam.width as f32, cam.height as f32);
    let aa = (vis.width / cam.width.max(1)).max(1);
    // World point → (pixel position, reversed depth z/w), if in front of the near plane.
    let project = |p: Vec3| -> Option<(Vec2, f32)> {
        let c: Vec4 = vp * p.extend(1.0);
        (c.w > cam.near).then(|| (Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h), c.z / c.w))
    };
    // Visible when the buffer's nearest surface at that sample is (about) this point.
    let visible = |at: Vec2, depth: f32| -> bool {
        let (sx, sy) = ((at.x * aa as f32) as i64, (at.y * aa as f32) as i64);
        if sx < 0 || sy < 0 || sx >= vis.width as i64 || sy >= vis.height as i64 {
            return false;
        }
        let s = vis.samples[(sy as u64 * vis.width as u64 + sx as u64) as usize];
        s.tri != NO_TRIANGLE && depth >= s.depth * (1.0 - 2e-3)
    };
    // Objects are in triangle order: the owner of triangle t by binary search.
    let length = |t: usize| {
        let o = g.objects.partition_point(|o| o.first_triangle + o.triangles <= t);
        g.objects.get(o).filter(|o| (o.first_triangle..o.first_triangle + o.triangles).contains(&t)).map_or(0.3, |o| o.radius * LENGTH)
    };
    let width = (cam.height as f32 / 256.0).clamp(1.0, 4.0);
    let mut drawn = 0;
    let mut segment = |from: Vec3, dir: Vec3, len: f32, colour: [u8; 3], img: &mut RgbaImage| {
        let Some((a, depth)) = project(from) else { return };
        let Some((b, _)) = project(from + dir * len) else { return };
        if visible(a, depth) {
            line(img, a, b, width, colour);
            dot(img, a, width * 1.2, colour);
            drawn += 1;
        }
    };
    if matches!(which, Normals::Face | Normals::Both) {
        for (t, tri) in g.triangles.iter().enumerate() {
            let n = g.face_normals[t];
            let centroid = tri.iter().map(|&i| g.positions[i as usize]).sum::<Vec3>() / 3.0;
            // Back faces are never drawn, whatever the culling setting.
            if n.dot(cam.position - centroid) > 0.0 {
                segment(centroid, n, length(t), FACE_COLOUR, img);
            }
        }
    }
    if matches!(which, Normals::Vertex | Normals::Both) {
        // Each vertex once: the first triangle that uses it gives its object (for the length).
        let mut owner = vec![usize::MAX; g.positions.len()];
        for (t, tri) in g.triangles.iter().enumerate() {
            for &i in tri {
                if owner[i as usize] == usize::MAX {
                    owner[i as usize] = t;
                }
            }
        }
        // Seams duplicate vertices: draw a position/normal pair once. The duplicates are
        // bit-for-bit equal (the same formula, or the same OBJ line, through the same
        // transform), so a hash set of the bits finds them in linear time; the scan over
        // every earlier pair it replaces made 200k triangles take 19 s.
        let mut seen: std::collections::HashSet<[u32; 6]> = std::collections::HashSet::with_capacity(owner.len());
        for (i, &t) in owner.iter().enumerate() {
            if t == usize::MAX {
                continue;
            }
            let (p, n) = (g.positions[i], g.normals[i]);
            // +0.0 for −0.0, so the two zeros are one key.
            let key = [p.x, p.y, p.z, n.x, n.y, n.z].map(|c| (c + 0.0).to_bits());
            if n.dot(cam.position - p) <= 0.0 || !seen.insert(key) {
                continue;
            }
            segment(p, n, length(t), VERTEX_COLOUR, img);
        }
    }
    drawn
}

/// Blends `colour` at coverage `a` (0..=1) over pixel (x, y), opaque result.
fn blend(img: &mut RgbaImage, x: i64, y: i64, colour: [u8; 3], a: f32) {
    if a <= 0.0 || x < 0 || y < 0 || x >= img.width() as i64 || y >= img.height() as i64 {
        return;
    }
    let px = img.get_pixel_mut(x as u32, y as u32);
    for c in 0..3 {
        px[c] = (px[c] as f32 + (colour[c] as f32 - px[c] as f32) * a.min(1.0)).round() as u8;
    }
    px[3] = px[3].max((a.min(1.0) * 255.0).round() as u8);
}

/// A round-capped segment from `a` to `b`, `width` pixels wide, anti-aliased by distance.
pub fn line(img: &mut RgbaImage, a: Vec2, b: Vec2, width: f32, colour: [u8; 3]) {
    let r = width * 0.5;
    let (lo, hi) = (a.min(b) - Vec2::splat(r + 1.0), a.max(b) + Vec2::splat(r + 1.0));
    let ab = b - a;
    let len2 = ab.length_squared().max(1e-12);
    for y in lo.y.floor() as i64..=hi.y.ceil() as i64 {
        for x in lo.x.floor() as i64..=hi.x.ceil() as i64 {
            let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
            let d = (p - (a + ab * t)).length();
            blend(img, x, y, colour, r + 0.5 - d);
        }
    }
}

/// A filled disc of radius `r` at `c`, anti-aliased.
pub fn dot(img: &mut RgbaImage, c: Vec2, r: f32, colour: [u8; 3]) {
    line(img, c, c, 2.0 * r, colour);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_covers_its_pixels_and_fades_at_the_edge() {
        let mut img = RgbaImage::from_pixel(20, 10, image::Rgba([0, 0, 0, 255]));
        line(&mut img, Vec2::new(2.0, 5.0), Vec2::new(18.0, 5.0), 2.5, [255, 255, 255]);
        // Pixel centres within the half-width: full colour; 1.5 px away: partial; far: untouched.
        assert_eq!(img.get_pixel(10, 4)[0], 255);
        assert_eq!(img.get_pixel(10, 5)[0], 255);
        let edge = img.get_pixel(10, 6)[0];
        assert!(edge > 0 && edge < 255, "{edge}");
        assert_eq!(img.get_pixel(10, 8)[0], 0);
        assert_eq!(img.get_pixel(0, 0)[0], 0);
    }
}
