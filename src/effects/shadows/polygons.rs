//! Two-pass object-space shadow polygons (Atherton, Weiler & Greenberg 1978, "Polygon
//! shadow generation"): pass 1, seen from the light, projects every occluder triangle onto
//! the plane of every receiver triangle and clips it to the receiver, giving the receiver's
//! shadow polygons; pass 2, drawing from the eye, a shaded point of a receiver is in shadow
//! when it lies inside one of its receiver's polygons.
//!
//! Pass 1 for receiver R and occluder O (the light at L):
//! 1. only the part of O strictly between R's plane and the light can block light falling
//!    on R (a part behind the plane, or beyond a point light, casts nothing on it): O is
//!    clipped to that slab (Sutherland & Hodgman 1974);
//! 2. each corner x is projected from the light onto R's plane (central projection: the
//!    point of the plane on the line L–x; parallel along the light's direction for a
//!    directional light);
//! 3. the projection is clipped to R's triangle in R's plane and kept if it has area.
//!
//! The work is every (receiver, occluder) pair: n² for n triangles, the cost the lecture
//! names for this method; it is counted (`polygon pairs`) and budgeted. Occluders are the
//! same triangles the shadow volumes cast (`occluders`: a closed mesh's light-facing ones).
//! A receiver facing away from the light gets no polygons: shading gives it no direct light.

use super::occluders::{LightFrom, Occluders};
use crate::light::LightKind;
use crate::scene::Scene;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// The count of (receiver, occluder) pairs projected in pass 1.
pub const POLYGON_PAIRS: &str = "shadow-polygon pairs projected";
/// The count of shadow polygons kept (with area on their receiver).
pub const POLYGONS_KEPT: &str = "shadow polygons kept";
/// The count of point-in-polygon tests made by pass 2.
pub const POLYGON_TESTS: &str = "shadow-polygon tests";

/// Corners of a clipped polygon: a triangle clipped by five planes has at most eight.
type Poly = Vec<Vec3>;

/// One receiver's frame and polygons.
#[derive(Debug, Clone, Default)]
struct Receiver {
    /// A corner, and two unit axes of the plane.
    origin: Vec3,
    u: Vec3,
    v: Vec3,
    /// How far outside a polygon's edge still counts as on it: a point on the receiver's
    /// own edge, where a clipped polygon ends, must not fall between two receivers.
    tol: f32,
    /// Start of its polygons in `ShadowPolygons::starts` (`end` one past the last).
    first: u32,
    end: u32,
}

/// One light's shadow polygons, per receiver triangle of the scene.
#[derive(Debug, Clone)]
pub struct ShadowPolygons {
    receivers: Vec<Receiver>,
    /// Each polygon's first corner in `corners`, with one more entry at the end.
    starts: Vec<u32>,
    /// Corners in receiver coordinates, counter-clockwise.
    corners: Vec<Vec2>,
    /// Each polygon's bounding box (min, max): most points are rejected by it.
    boxes: Vec<(Vec2, Vec2)>,
    /// (receiver, occluder) pairs projected.
    pub pairs: u64,
    /// Triangles of the scene, for vertices (which belong to no one triangle).
    tris: Vec<[Vec3; 3]>,
}

impl ShadowPolygons {
    /// Pass 1 for light `kind` in `scene`: every receiver's shadow polygons; `None` for a
    /// light with extent.
    pub fn build(scene: &Scene, kind: &LightKind) -> Option<ShadowPolygons> {
        let from = LightFrom::of(kind)?;
        let occ = Occluders::find(scene, from);
        let g = &scene.geometry;
        let tris: Vec<[Vec3; 3]> = g.triangles.iter().map(|t| t.map(|i| g.positions[i as usize])).collect();
        // Receivers in parallel, each keeping its own polygons in order: the same bytes for
        // any thread count.
        let per: Vec<(Receiver, Vec<Vec<Vec2>>, u64)> = tris.par_iter().map(|r| receive(r, &occ.caps, from)).collect();
        let mut out = ShadowPolygons {
            receivers: Vec::with_capacity(per.len()),
            starts: vec![0],
            corners: Vec::new(),
            boxes: Vec::new(),
            pairs: 0,
            tris,
        };
        for (mut r, polys, pairs) in per {
            out.pairs += pairs;
            r.first = out.starts.len() as u32 - 1;
            for p in polys {
                let lo = p.iter().fold(Vec2::splat(f32::INFINITY), |a, q| a.min(*q));
                let hi = p.iter().fold(Vec2::splat(f32::NEG_INFINITY), |a, q| a.max(*q));
                out.boxes.push((lo, hi));
                out.corners.extend(p);
                out.starts.push(out.corners.len() as u32);
            }
            r.end = out.starts.len() as u32 - 1;
            out.receivers.push(r);
        }
        Some(out)
    }

    /// Shadow polygons kept.
    pub fn polygons(&self) -> u64 {
        self.starts.len() as u64 - 1
    }

    /// Pass 2: 0 when `p` (on triangle `tri` of the scene, or a vertex: `u32::MAX`) lies
    /// inside one of its receiver's shadow polygons, else 1; and the polygons tested.
    pub fn visibility(&self, p: Vec3, tri: u32) -> (f32, u64) {
        if let Some(r) = self.receivers.get(tri as usize) {
            return self.in_receiver(r, p);
        }
        // A vertex or a point off every surface: the first triangle whose plane and area
        // hold it answers.
        for (r, t) in self.receivers.iter().zip(&self.tris) {
            if on_triangle(t, p) {
                return self.in_receiver(r, p);
            }
        }
        (1.0, 0)
    }

    fn in_receiver(&self, r: &Receiver, p: Vec3) -> (f32, u64) {
        let q = Vec2::new((p - r.origin).dot(r.u), (p - r.origin).dot(r.v));
        for k in r.first..r.end {
            let (lo, hi) = self.boxes[k as usize];
            if q.cmplt(lo - r.tol).any() || q.cmpgt(hi + r.tol).any() {
                continue;
            }
            let c = &self.corners[self.starts[k as usize] as usize..self.starts[k as usize + 1] as usize];
            if inside_convex(c, q, r.tol) {
                return (0.0, u64::from(k - r.first + 1));
            }
        }
        (1.0, u64::from(r.end - r.first))
    }
}

/// True when `p` lies on triangle `t` (within a small distance of its plane and inside it).
fn on_triangle(t: &[Vec3; 3], p: Vec3) -> bool {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let len = n.length();
    if len <= 0.0 || !len.is_finite() {
        return false;
    }
    let scale = (t[1] - t[0]).length().max((t[2] - t[0]).length());
    if (p - t[0]).dot(n / len).abs() > 1e-4 * scale {
        return false;
    }
    (0..3).all(|k| n.dot((t[(k + 1) % 3] - t[k]).cross(p - t[k])) >= 0.0)
}

/// True when `q` lies inside the convex counter-clockwise polygon `c` or within `tol` of it.
fn inside_convex(c: &[Vec2], q: Vec2, tol: f32) -> bool {
    (0..c.len()).all(|k| {
        let (a, b) = (c[k], c[(k + 1) % c.len()]);
        (b - a).perp_dot(q - a) >= -tol * (b - a).length()
    })
}

/// Pass 1 for one receiver `r`: its frame, the shadow polygons the `caps` cast on it, and
/// the pairs looked at.
fn receive(r: &[Vec3; 3], caps: &[[Vec3; 3]], from: LightFrom) -> (Receiver, Vec<Vec<Vec2>>, u64) {
    let n = (r[1] - r[0]).cross(r[2] - r[0]);
    let u = (r[1] - r[0]).normalize_or_zero();
    let nu = n.normalize_or_zero();
    let v = nu.cross(u);
    let size = (r[1] - r[0]).length().max((r[2] - r[0]).length()).max((r[2] - r[1]).length());
    let frame = Receiver { origin: r[0], u, v, tol: 1e-5 * size, first: 0, end: 0 };
    // Height above the receiver's plane, positive towards the light.
    let towards = from.towards(r[0]).dot(nu);
    if nu == Vec3::ZERO || towards <= 0.0 || !towards.is_finite() {
        return (frame, Vec::new(), 0); // degenerate, or facing away: no direct light to block
    }
    let h = |x: Vec3| (x - r[0]).dot(nu);
    let to_2d = |x: Vec3| Vec2::new((x - r[0]).dot(u), (x - r[0]).dot(v));
    let tri_2d = [to_2d(r[0]), to_2d(r[1]), to_2d(r[2])];
    // Within this (relative) height of the plane counts as on it: a neighbour sharing an
    // edge with the receiver does not shadow it.
    let eps = 1e-5 * (r[1] - r[0]).length().max((r[2] - r[0]).length()).max(1e-6);
    let mut polys = Vec::new();
    for c in caps {
        // The slab between the plane and a point light.
        let mut poly: Poly = c.to_vec();
        poly = clip(&poly, |x| h(x) - eps);
        if let LightFrom::Point(l) = from {
            let hl = h(l);
            poly = clip(&poly, |x| hl - eps - h(x));
        }
        if poly.len() < 3 {
            continue;
        }
        // Projected from the light onto the plane (h = 0).
        let projected: Vec<Vec2> = poly
            .iter()
            .map(|&x| match from {
                LightFrom::Point(l) => {
                    let (hl, hx) = (h(l), h(x));
                    to_2d(l + (x - l) * (hl / (hl - hx)))
                }
                LightFrom::Direction(d) => to_2d(x + d * (h(x) / -d.dot(nu))),
            })
            .collect();
        // Counter-clockwise in the receiver's frame (a cap seen from below is reversed).
        let mut p2 = projected;
        if signed_area(&p2) < 0.0 {
            p2.reverse();
        }
        for k in 0..3 {
            let (a, b) = (tri_2d[k], tri_2d[(k + 1) % 3]);
            p2 = clip2(&p2, |q| (b - a).perp_dot(q - a));
            if p2.len() < 3 {
                break;
            }
        }
        if p2.len() >= 3 && signed_area(&p2) > eps * eps && p2.iter().all(|q| q.is_finite()) {
            polys.push(p2);
        }
    }
    (frame, polys, caps.len() as u64)
}

fn signed_area(p: &[Vec2]) -> f32 {
    0.5 * (0..p.len()).map(|k| p[k].perp_dot(p[(k + 1) % p.len()])).sum::<f32>()
}

/// Sutherland–Hodgman: the part of polygon `p` where `f ≥ 0`.
fn clip(p: &[Vec3], f: impl Fn(Vec3) -> f32) -> Poly {
    let mut out = Vec::with_capacity(p.len() + 2);
    for k in 0..p.len() {
        let (a, b) = (p[k], p[(k + 1) % p.len()]);
        let (fa, fb) = (f(a), f(b));
        if fa >= 0.0 {
            out.push(a);
        }
        if (fa >= 0.0) != (fb >= 0.0) {
            out.push(a + (b - a) * (fa / (fa - fb)));
        }
    }
    out
}

/// [`clip`] in the plane.
fn clip2(p: &[Vec2], f: impl Fn(Vec2) -> f32) -> Vec<Vec2> {
    let mut out = Vec::with_capacity(p.len() + 2);
    for k in 0..p.len() {
        let (a, b) = (p[k], p[(k + 1) % p.len()]);
        let (fa, fb) = (f(a), f(b));
        if fa >= 0.0 {
            out.push(a);
        }
        if (fa >= 0.0) != (fb >= 0.0) {
            out.push(a + (b - a) * (fa / (fa - fb)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_caps(y: f32, s: f32) -> Vec<[Vec3; 3]> {
        let p = [Vec3::new(-s, y, -s), Vec3::new(s, y, -s), Vec3::new(s, y, s), Vec3::new(-s, y, s)];
        vec![[p[0], p[2], p[1]], [p[0], p[3], p[2]]]
    }

    /// A floor triangle covering [−10, 10]² (and more), facing up.
    fn floor() -> [Vec3; 3] {
        [Vec3::new(-10.0, 0.0, -10.0), Vec3::new(-10.0, 0.0, 30.0), Vec3::new(30.0, 0.0, -10.0)]
    }

    fn area(polys: &[Vec<Vec2>]) -> f32 {
        polys.iter().map(|p| signed_area(p)).sum()
    }

    #[test]
    fn a_square_over_the_floor_casts_the_analytic_square() {
        // Point light at height 2, square [−1, 1]² at height 1: the shadow is [−2, 2]², area
        // 16, with corners at (±2, ±2).
        let (fr, polys, pairs) = receive(&floor(), &square_caps(1.0, 1.0), LightFrom::Point(Vec3::new(0.0, 2.0, 0.0)));
        assert_eq!(pairs, 2);
        assert!((area(&polys) - 16.0).abs() < 1e-3, "area {}", area(&polys));
        let corners: Vec<Vec3> = polys.iter().flatten().map(|q| fr.origin + fr.u * q.x + fr.v * q.y).collect();
        for c in [Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 2.0), Vec3::new(-2.0, 0.0, 2.0)] {
            assert!(corners.iter().any(|x| (*x - c).length() < 1e-4), "corner {c} missing from {corners:?}");
        }
        // Directional light straight down: the square itself, area 4.
        let (_, polys, _) = receive(&floor(), &square_caps(1.0, 1.0), LightFrom::Direction(-Vec3::Y));
        assert!((area(&polys) - 4.0).abs() < 1e-4);
    }

    #[test]
    fn occluders_behind_the_plane_or_beyond_the_light_cast_nothing() {
        let l = LightFrom::Point(Vec3::new(0.0, 2.0, 0.0));
        assert!(receive(&floor(), &square_caps(-1.0, 1.0), l).1.is_empty(), "under the floor");
        assert!(receive(&floor(), &square_caps(3.0, 1.0), l).1.is_empty(), "above the light");
        // Half the square below the floor: only the part above casts.
        let tilted = [[Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0), Vec3::new(1.0, 1.0, 1.0)]];
        let (_, polys, _) = receive(&floor(), &tilted, l);
        assert_eq!(polys.len(), 1);
    }

    #[test]
    fn a_receiver_clips_its_shadow_and_a_degenerate_one_gets_none() {
        // A small floor triangle inside the shadow is covered whole: its own area.
        let small = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 0.0)];
        let (_, polys, _) = receive(&small, &square_caps(1.0, 1.0), LightFrom::Point(Vec3::new(0.0, 2.0, 0.0)));
        assert!((area(&polys) - 0.5).abs() < 1e-5);
        let flat = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        assert!(receive(&flat, &square_caps(1.0, 1.0), LightFrom::Point(Vec3::Y * 2.0)).1.is_empty());
        // The light in the receiver's plane: no polygons, no NaN.
        assert!(receive(&floor(), &square_caps(1.0, 1.0), LightFrom::Point(Vec3::new(50.0, 0.0, 0.0))).1.is_empty());
    }
}
