//! The watertight ray–triangle test and the self-intersection offset for secondary rays.
//!
//! [`intersect`] is Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection", JCGT
//! 2(1), 2013: the vertices are moved into a frame where the ray is the +z axis (a
//! translation to the origin, a permutation of the axes and a shear, §3), and the 2D edge
//! functions U, V, W of the sheared vertices decide the hit. Two triangles that share an edge
//! compute that edge's function from the same two vertices in the same way, up to its sign,
//! so a ray through the edge sees U = 0 on both or opposite signs: it can never slip between
//! them. An edge function that comes out exactly 0 in f32 is recomputed in f64 (the paper's
//! fallback, §4), so a ray through a shared vertex still hits one of the triangles there.
//!
//! [`offset_ray_origin`] is Wächter and Binder, "A Fast and Robust Method for Avoiding
//! Self-Intersection", Ray Tracing Gems, ch. 6 (2019): the hit point moves along the
//! geometric normal by a fixed number of ulps of each coordinate (a fixed distance near the
//! world origin, where ulps vanish), which is more than the rounding of any point computed
//! on the triangle.

use glam::Vec3;

/// Per-ray constants of the watertight test: the axis permutation and the shear.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayPrecomp {
    /// The axis where |dir| is largest, which becomes z.
    kz: usize,
    /// The axis that becomes x.
    kx: usize,
    /// The axis that becomes y.
    ky: usize,
    /// Shear of x: dir[kx] / dir[kz].
    sx: f32,
    /// Shear of y: dir[ky] / dir[kz].
    sy: f32,
    /// Scale of z: 1 / dir[kz].
    sz: f32,
}

impl RayPrecomp {
    /// The constants for direction `dir` (any length; must be non-zero and finite for a hit).
    pub fn new(dir: Vec3) -> RayPrecomp {
        let d = dir.to_array();
        let a = dir.abs();
        // Woop et al. §3: kz is the dimension where the direction is largest in magnitude.
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        // Swapping x and y keeps the winding when the ray looks down −z, so U, V, W keep their sign.
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        RayPrecomp { kz, kx, ky, sx: d[kx] / d[kz], sy: d[ky] / d[kz], sz: 1.0 / d[kz] }
    }

    /// The axes that become x, y and z, and the shear (sx, sy, sz): for tests of several
    /// triangles in SIMD lanes that must repeat [`intersect`]'s arithmetic exactly (the BVH's
    /// leaf blocks).
    pub(crate) fn parts(&self) -> ([usize; 3], [f32; 3]) {
        ([self.kx, self.ky, self.kz], [self.sx, self.sy, self.sz])
    }
}

/// Where the ray `origin + t·dir` (the `dir` of `pre`) meets triangle `a b c`, either side
/// facing: `Some((t, b1, b2))` with 0 < t < `t_max` and the barycentrics b1 of `b` and b2 of
/// `c` (the hit is (1 − b1 − b2)·a + b1·b + b2·c).
///
/// A zero-area triangle is missed, except that rounding may let a ray that grazes the line it
/// lies on report a finite hit; non-finite input never yields NaN (it is missed).
#[inline]
pub fn intersect(pre: &RayPrecomp, origin: Vec3, a: Vec3, b: Vec3, c: Vec3, t_max: f32) -> Option<(f32, f32, f32)> {
    let (kx, ky, kz) = (pre.kx, pre.ky, pre.kz);
    // Vertices relative to the ray origin (Woop et al. Fig. 2).
    let a = (a - origin).to_array();
    let b = (b - origin).to_array();
    let c = (c - origin).to_array();
    // Shear and scale so the ray is the +z axis through the origin.
    let ax = a[kx] - pre.sx * a[kz];
    let ay = a[ky] - pre.sy * a[kz];
    let bx = b[kx] - pre.sx * b[kz];
    let by = b[ky] - pre.sy * b[kz];
    let cx = c[kx] - pre.sx * c[kz];
    let cy = c[ky] - pre.sy * c[kz];
    // Scaled barycentrics: twice the signed areas of the sub-triangles seen from the ray.
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    // §4: an edge function that is exactly 0 may be a rounded non-zero; recompute all three
    // in f64, where the products of two f32 are exact.
    if u == 0.0 || v == 0.0 || w == 0.0 {
        let (ax, ay, bx, by, cx, cy) = (ax as f64, ay as f64, bx as f64, by as f64, cx as f64, cy as f64);
        u = (cx * by - cy * bx) as f32;
        v = (ax * cy - ay * cx) as f32;
        w = (bx * ay - by * ax) as f32;
    }
    // Double-sided: the ray is inside when all three share a sign. Written so NaN fails both.
    let all_non_negative = u >= 0.0 && v >= 0.0 && w >= 0.0;
    let all_non_positive = u <= 0.0 && v <= 0.0 && w <= 0.0;
    if !(all_non_negative || all_non_positive) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    // The scaled hit distance, compared with t_max before the division (Woop et al. Fig. 6).
    let az = pre.sz * a[kz];
    let bz = pre.sz * b[kz];
    let cz = pre.sz * c[kz];
    let t_scaled = u * az + v * bz + w * cz;
    let (t_abs, det_abs) = if det < 0.0 { (-t_scaled, -det) } else { (t_scaled, det) };
    if !(t_abs > 0.0 && t_abs < t_max * det_abs) {
        return None;
    }
    let rcp_det = 1.0 / det;
    let t = t_scaled * rcp_det;
    // The division can round onto an end of the open interval; keep the promise.
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    Some((t, v * rcp_det, w * rcp_det))
}

/// The point `p` on a surface moved off it along `n`, so that a ray from there in any
/// direction on `n`'s side cannot hit the surface it left (Wächter and Binder, Ray Tracing
/// Gems ch. 6, listing 6-1).
///
/// `n` must be the unit geometric normal, pointing to the side the ray leaves on (flip it
/// for a transmitted ray).
#[inline]
pub fn offset_ray_origin(p: Vec3, n: Vec3) -> Vec3 {
    // Their constants: within ORIGIN of 0 move by FLOAT_SCALE·n (ulps are too fine there);
    // elsewhere by INT_SCALE·n ulps, enough for the rounding of a computed hit point.
    const ORIGIN: f32 = 1.0 / 32.0;
    const FLOAT_SCALE: f32 = 1.0 / 65536.0;
    const INT_SCALE: f32 = 256.0;
    let offset = |p: f32, n: f32| -> f32 {
        if p.abs() < ORIGIN {
            return p + FLOAT_SCALE * n;
        }
        // Truncation towards zero, as the paper's int conversion. Moving the bits of a negative
        // number up moves it down, hence the sign flip.
        let of_i = (INT_SCALE * n) as i32;
        let of_i = if p < 0.0 { -of_i } else { of_i };
        f32::from_bits((p.to_bits() as i32).wrapping_add(of_i) as u32)
    };
    Vec3::new(offset(p.x, n.x), offset(p.y, n.y), offset(p.z, n.z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::lanes::test_rng;

    fn hit(o: Vec3, d: Vec3, tri: [Vec3; 3], t_max: f32) -> Option<(f32, f32, f32)> {
        intersect(&RayPrecomp::new(d), o, tri[0], tri[1], tri[2], t_max)
    }

    #[test]
    fn hit_reports_the_analytic_distance_and_barycentrics() {
        let tri = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)];
        // The point 0.25·b + 0.5·c = (1, 1, 0), reached from z = 3 along −z with |dir| = 2: t = 1.5.
        let (t, b1, b2) = hit(Vec3::new(1.0, 1.0, 3.0), Vec3::new(0.0, 0.0, -2.0), tri, f32::INFINITY).unwrap();
        assert_eq!((t, b1, b2), (1.5, 0.25, 0.5));
        // From behind: double-sided, same barycentrics.
        let (t, b1, b2) = hit(Vec3::new(1.0, 1.0, -1.0), Vec3::new(0.0, 0.0, 1.0), tri, f32::INFINITY).unwrap();
        assert_eq!((t, b1, b2), (1.0, 0.25, 0.5));
        // An oblique ray, against the plane equation: hit point = o + t d lies at the barycentric point.
        let mut rng = test_rng(7, 1.0);
        for _ in 0..1000 {
            let tri = [0, 1, 2].map(|_| Vec3::new(rng(), rng(), rng()) * 3.0);
            let (s1, s2) = (rng() * 0.5 + 0.5, rng() * 0.5 + 0.5);
            let (s1, s2) = if s1 + s2 > 1.0 { (1.0 - s1, 1.0 - s2) } else { (s1, s2) };
            let target = tri[0] * (1.0 - s1 - s2) + tri[1] * s1 + tri[2] * s2;
            let o = Vec3::new(rng(), rng(), rng()) * 5.0;
            if (tri[1] - tri[0]).cross(tri[2] - tri[0]).length() < 0.1 {
                continue;
            }
            let d = (target - o) * 0.5;
            let (t, b1, b2) = hit(o, d, tri, f32::INFINITY).expect("aimed at the interior");
            assert!((t - 2.0).abs() < 1e-3, "t {t}");
            assert!((b1 - s1).abs() < 1e-3 && (b2 - s2).abs() < 1e-3, "{b1} {b2} vs {s1} {s2}");
            // t_max is an open bound: a hit at or beyond it is no hit.
            assert!(hit(o, d, tri, t * 0.999).is_none());
            assert!(hit(o, d, tri, t).is_none());
        }
    }

    #[test]
    fn hits_behind_the_origin_are_missed() {
        let tri = [Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
        assert!(hit(Vec3::new(0.0, 0.0, 1.0), Vec3::Z, tri, f32::INFINITY).is_none());
        // The origin on the triangle: t = 0 is outside (0, t_max).
        assert!(hit(Vec3::ZERO, Vec3::Z, tri, f32::INFINITY).is_none());
    }

    /// The quad [0, 1]² at z = 0 cut along a diagonal (`b` = the other diagonal).
    fn quad(anti: bool) -> [[Vec3; 3]; 2] {
        let p = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
        if anti { [[p[0], p[1], p[3]], [p[1], p[2], p[3]]] } else { [[p[0], p[1], p[2]], [p[0], p[2], p[3]]] }
    }

    #[test]
    fn rays_through_a_shared_edge_or_vertex_never_miss_both_triangles() {
        let mut rng = test_rng(11, 1.0);
        let mut misses = 0;
        for i in 0..20_000 {
            let anti = i % 2 == 0;
            let tris = quad(anti);
            // A point on the shared diagonal (in f32, so usually just off the exact line), or
            // the quad's centre.
            // (The diagonal's ends are corners of the quad, where a ray may pass outside.)
            let s = 0.01 + (rng() * 0.5 + 0.5) * 0.98;
            let target = match i % 7 {
                0 => Vec3::new(0.5, 0.5, 0.0),
                _ if anti => Vec3::new(1.0 - s, s, 0.0),
                _ => Vec3::new(s, s, 0.0),
            };
            let o = Vec3::new(rng() * 10.0, rng() * 10.0, (0.5 + rng().abs() * 10.0).copysign(rng()));
            let d = target - o;
            let pre = RayPrecomp::new(d);
            let n = tris.iter().filter(|t| intersect(&pre, o, t[0], t[1], t[2], f32::INFINITY).is_some()).count();
            if n == 0 {
                misses += 1;
            }
        }
        assert_eq!(misses, 0, "rays through the shared diagonal slipped between the triangles");
    }

    #[test]
    fn a_fan_of_rays_through_a_triangulated_quad_never_leaks() {
        // An 8×8 grid of quads, two triangles each, with jittered (shared) vertices: every ray
        // aimed at the interior of the whole patch must hit at least one triangle.
        let mut rng = test_rng(5, 1.0);
        let n = 8;
        let mut grid = vec![Vec3::ZERO; (n + 1) * (n + 1)];
        for j in 0..=n {
            for i in 0..=n {
                let inner = i > 0 && i < n && j > 0 && j < n;
                let jitter = if inner { Vec3::new(rng(), rng(), rng()) * 0.3 } else { Vec3::ZERO };
                grid[j * (n + 1) + i] = Vec3::new(i as f32, j as f32, 0.0) / n as f32 + jitter / n as f32 * Vec3::new(1.0, 1.0, 0.5);
            }
        }
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let v = |di: usize, dj: usize| grid[(j + dj) * (n + 1) + i + di];
                tris.push([v(0, 0), v(1, 0), v(1, 1)]);
                tris.push([v(0, 0), v(1, 1), v(0, 1)]);
            }
        }
        let mut tested = 0;
        for k in 0..200_000 {
            // Aim at a vertex or a point on an edge of the grid.
            let tri = tris[k % tris.len()];
            let s = rng() * 0.5 + 0.5;
            let target = match k % 3 {
                0 => tri[(k / 3) % 3],
                1 => tri[0] + (tri[1] - tri[0]) * s,
                _ => tri[1] + (tri[2] - tri[1]) * s,
            };
            // Boundary vertices and edges of the patch may be missed legitimately (and the
            // patch's slight relief may move a target near them outside it as seen from o).
            let eps = 0.05;
            if target.x < eps || target.y < eps || target.x > 1.0 - eps || target.y > 1.0 - eps {
                continue;
            }
            tested += 1;
            let o = Vec3::new(rng() * 4.0, rng() * 4.0, 3.0 + rng() * 2.0) * if k % 2 == 0 { 1.0 } else { -1.0 };
            let pre = RayPrecomp::new(target - o);
            let hit = tris.iter().any(|t| intersect(&pre, o, t[0], t[1], t[2], f32::INFINITY).is_some());
            assert!(hit, "ray {k} from {o} through {target} leaked");
        }
        assert!(tested > 100_000);
    }

    #[test]
    fn parallel_rays_and_zero_area_triangles_are_missed_without_nan() {
        let tri = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
        // In the triangle's plane, through it.
        assert!(hit(Vec3::new(-1.0, 0.25, 0.0), Vec3::X, tri, f32::INFINITY).is_none());
        // Parallel, off the plane.
        assert!(hit(Vec3::new(-1.0, 0.25, 1.0), Vec3::X, tri, f32::INFINITY).is_none());
        // A zero direction.
        assert!(hit(Vec3::new(0.2, 0.2, 1.0), Vec3::ZERO, tri, f32::INFINITY).is_none());
        // Coincident vertices and collinear vertices, hit head-on through their line.
        let p = Vec3::new(0.3, 0.4, 0.0);
        let degenerate = [
            [p, p, p],
            [p, p, Vec3::new(1.0, 1.0, 0.0)],
            [Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0)],
            [Vec3::ZERO, Vec3::new(0.5, 0.5, 0.5), Vec3::new(1.0, 1.0, 1.0)],
        ];
        for tri in degenerate {
            for o in [Vec3::new(0.3, 0.4, 1.0), Vec3::new(0.5, 0.0, 1.0), Vec3::new(0.5, 0.5, 2.0)] {
                assert!(hit(o, -Vec3::Z, tri, f32::INFINITY).is_none(), "{tri:?} from {o}");
            }
        }
        // Random collinear triangles and random rays: any answer is finite.
        let mut rng = test_rng(3, 1.0);
        for _ in 0..20_000 {
            let (a, d) = (Vec3::new(rng(), rng(), rng()), Vec3::new(rng(), rng(), rng()));
            let tri = [a, a + d * rng(), a + d * rng()];
            let o = Vec3::new(rng(), rng(), rng()) * 2.0;
            let dir = Vec3::new(rng(), rng(), rng());
            if let Some((t, b1, b2)) = hit(o, dir, tri, f32::INFINITY) {
                assert!(t.is_finite() && b1.is_finite() && b2.is_finite());
            }
        }
        // Non-finite input is missed rather than NaN.
        let nan = [Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X, Vec3::Y];
        assert!(hit(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z, nan, f32::INFINITY).is_none());
        assert!(hit(Vec3::new(0.2, 0.2, 1.0), Vec3::new(0.0, 0.0, f32::NAN), tri, f32::INFINITY).is_none());
    }

    #[test]
    fn offset_origins_never_hit_their_own_triangle() {
        let mut rng = test_rng(23, 1.0);
        let mut tested = 0;
        for scale in [1e-3f32, 1e-2, 1.0, 1e2, 1e4] {
            for i in 0..20_000 {
                // Triangles of this size, near the world origin or moved away from it.
                let shift = if i % 2 == 0 { Vec3::ZERO } else { Vec3::new(rng(), rng(), rng()) * scale * 100.0 };
                let tri = [0, 1, 2].map(|_| Vec3::new(rng(), rng(), rng()) * scale + shift);
                let Some(n) = (tri[1] - tri[0]).cross(tri[2] - tri[0]).try_normalize() else { continue };
                let (s1, s2) = (rng() * 0.5 + 0.5, rng() * 0.5 + 0.5);
                let (s1, s2) = if s1 + s2 > 1.0 { (1.0 - s1, 1.0 - s2) } else { (s1, s2) };
                // The hit point as a renderer computes it from barycentrics, with its rounding.
                let p = tri[0] * (1.0 - s1 - s2) + tri[1] * s1 + tri[2] * s2;
                // Leave on a random side, along the normal and tilted up to ~60° from it.
                let n = if rng() < 0.0 { -n } else { n };
                let o = offset_ray_origin(p, n);
                let tilt = Vec3::new(rng(), rng(), rng()) * 0.7;
                for d in [n, (n + tilt - n * tilt.dot(n)).normalize()] {
                    let pre = RayPrecomp::new(d);
                    let h = intersect(&pre, o, tri[0], tri[1], tri[2], f32::INFINITY);
                    assert!(h.is_none(), "scale {scale}: {tri:?} at {p} along {d}: {h:?}");
                }
                tested += 1;
            }
        }
        assert!(tested > 90_000);
        // Without the offset the same test does fail often: it can fail.
        let mut rng = test_rng(23, 1.0);
        let mut self_hits = 0;
        for _ in 0..20_000 {
            let tri = [0, 1, 2].map(|_| Vec3::new(rng(), rng(), rng()) * 100.0);
            let Some(n) = (tri[1] - tri[0]).cross(tri[2] - tri[0]).try_normalize() else { continue };
            let p = tri[0] * 0.3 + tri[1] * 0.3 + tri[2] * 0.4;
            for n in [n, -n] {
                self_hits += intersect(&RayPrecomp::new(n), p, tri[0], tri[1], tri[2], f32::INFINITY).is_some() as usize;
            }
        }
        assert!(self_hits > 1000, "{self_hits}");
    }

    #[test]
    fn offset_moves_towards_the_normal_near_and_far_from_the_world_origin() {
        let n = Vec3::new(0.0, 1.0, 0.0);
        let near = offset_ray_origin(Vec3::new(0.0, 0.01, 0.0), n);
        assert_eq!(near, Vec3::new(0.0, 0.01 + 1.0 / 65536.0, 0.0));
        let far = offset_ray_origin(Vec3::new(0.0, -1000.0, 0.0), n);
        assert!(far.y > -1000.0 && far.y < -999.98);
        assert_eq!((-1000.0f32).to_bits() - far.y.to_bits(), 256);
    }
}
