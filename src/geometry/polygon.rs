//! The analytic polygon light: Lambert's (1760) point-to-polygon form factor.
//!
//! Seen from a point p with unit normal n, a polygon with unit vertex directions
//! v₁ … v_m (from p) has the form factor
//!
//! F = (1/2π) Σ_l β_l (n·γ_l),  β_l = ∠(v_l, v_{l+1}),  γ_l = (v_l × v_{l+1}) / |v_l × v_{l+1}|,
//!
//! the contour-integral (Stokes) form of ∫ cosθ dω / π over the polygon's solid angle
//! (J. H. Lambert, *Photometria*, 1760; Baum, Rushmeier and Winget, "Improving Radiosity
//! Solutions Through the Use of Analytically Determined Form-Factors", SIGGRAPH 1989;
//! Arvo, "Applications of Irradiance Tensors", SIGGRAPH 1995). The course writes the same sum
//! as I = (k L / 2) Σ β_l cos δ_l with cos δ_l = n·γ_l. The formula holds only for the part
//! of the polygon above p's tangent plane, so that part is clipped out first.
//!
//! Everything runs in f64: for a small or distant polygon the edge terms are of the order of
//! its angular size s and cancel down to F ~ s², so f32 would keep few digits of F; and
//! β = atan2(|a × b|, a·b) stays accurate near 0 and π, where acos loses half its digits.

use glam::{DVec3, Vec3};
use std::f64::consts::TAU;

/// The point-to-polygon form factor F = (1/2π) Σ_l β_l (n·γ_l) of a planar convex or concave (simple) polygon
/// seen from point p with unit normal n: β_l the angle the edge l subtends at p, γ_l the unit normal of the plane through p and the edge.
/// The part of the polygon below p's tangent plane is clipped away first (it sends no light), so F ∈ [0, 1].
/// Irradiance from a Lambertian emitter of radiance L is E = π L F; the projected solid angle is π F.
///
/// Either winding gives the same F (the absolute value of the signed sum); which side emits
/// is the caller's business. Vertices may be given in any number: fewer than three, or a
/// polygon wholly below the tangent plane, give 0. The clipping is Sutherland–Hodgman
/// against the plane n·(q − p) = 0; for a concave polygon it may leave edges running both
/// ways along the horizon, whose terms cancel.
///
/// Degenerate cases stay finite in [0, 1]: a vertex at p is skipped and an edge through p
/// (its ends opposite as seen from p) adds nothing. With p in the polygon's own plane (normal
/// m) the polygon is seen edge-on and F = |n·m| × the winding number of the clipped polygon
/// about p: 0 outside it; inside, 1 when it lies in the tangent plane (the limit from in
/// front) and |n·m|/2 when tilted; ½ on an edge in the tangent plane. A zero or non-finite
/// `n`, or a non-finite p or vertex, gives 0. Precondition: `n` is normalized (it is
/// renormalized in f64).
pub fn polygon_form_factor(p: Vec3, n: Vec3, vertices: &[Vec3]) -> f32 {
    let Some(n) = n.as_dvec3().try_normalize() else {
        return 0.0;
    };
    if !p.is_finite() || !vertices.iter().all(|q| q.is_finite()) {
        return 0.0;
    }
    let p = p.as_dvec3();
    let m = vertices.len();
    let mut contour = Contour { n, first: None, previous: None, sum: 0.0 };
    for i in 0..m {
        // One Sutherland–Hodgman step on the edge a → b, streamed: the kept points go
        // straight into the sum, so nothing is allocated.
        let a = vertices[i].as_dvec3() - p;
        let b = vertices[(i + 1) % m].as_dvec3() - p;
        let (da, db) = (n.dot(a), n.dot(b));
        if da >= 0.0 {
            contour.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            // Where the edge crosses the tangent plane; da − db ≠ 0 since their signs differ.
            contour.push(a + (b - a) * (da / (da - db)));
        }
    }
    if let (Some(first), Some(last)) = (contour.first, contour.previous) {
        contour.sum += edge_term(n, last, first);
    }
    let f = (contour.sum / TAU).abs();
    // F ≤ 1 holds exactly; the clamp removes rounding.
    f.min(1.0) as f32
}

/// The clipped polygon as it is emitted, as unit directions from p, and its running sum.
struct Contour {
    /// The shading normal.
    n: DVec3,
    /// The first direction kept, to close the loop.
    first: Option<DVec3>,
    /// The last direction kept.
    previous: Option<DVec3>,
    /// Σ β_l (n·γ_l) over the edges so far.
    sum: f64,
}

impl Contour {
    /// Appends the vertex at `r` (relative to p); a vertex at p has no direction and is skipped.
    fn push(&mut self, r: DVec3) {
        let Some(v) = r.try_normalize() else {
            return;
        };
        match self.previous {
            Some(u) => self.sum += edge_term(self.n, u, v),
            None => self.first = Some(v),
        }
        self.previous = Some(v);
    }
}

/// β (n·γ) for the edge from unit direction `a` to `b`: β = atan2(|a × b|, a·b), accurate at
/// every angle (acos loses half its digits near 0 and π), and γ = (a × b)/|a × b|.
/// Zero when a × b = 0: a repeated vertex, or an edge through p, which subtends no area.
#[inline]
fn edge_term(n: DVec3, a: DVec3, b: DVec3) -> f64 {
    let c = a.cross(b);
    let s = c.length();
    if s == 0.0 { 0.0 } else { s.atan2(a.dot(b)) * (n.dot(c) / s) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sampling::{basis, cosine_hemisphere, sample_2d};

    /// F from a point on the axis through one corner of a parallel w × h rectangle at
    /// distance c (Howell, "A Catalog of Radiation Heat Transfer Configuration Factors",
    /// differential area to a parallel rectangle): X = w/c, Y = h/c,
    /// F = (1/2π) [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))].
    fn corner(w: f64, h: f64, c: f64) -> f64 {
        let (x, y) = (w / c, h / c);
        let (ax, ay) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
        (x / ax * (y / ax).atan() + y / ay * (x / ay).atan()) / TAU
    }

    /// F from the origin (n = +z) of the rectangle [x0, x1] × [y0, y1] at height c, by
    /// adding and subtracting the four corner rectangles.
    fn rectangle(x0: f64, x1: f64, y0: f64, y1: f64, c: f64) -> f64 {
        let signed = |x: f64, y: f64| x.signum() * y.signum() * corner(x.abs(), y.abs(), c);
        signed(x1, y1) - signed(x0, y1) - signed(x1, y0) + signed(x0, y0)
    }

    /// The quad [x0, x1] × [y0, y1] at height z, counter-clockwise seen from above.
    fn quad(x0: f32, x1: f32, y0: f32, y1: f32, z: f32) -> Vec<Vec3> {
        vec![Vec3::new(x0, y0, z), Vec3::new(x1, y0, z), Vec3::new(x1, y1, z), Vec3::new(x0, y1, z)]
    }

    /// F from the origin with n = +z.
    fn from_origin(vertices: &[Vec3]) -> f64 {
        polygon_form_factor(Vec3::ZERO, Vec3::Z, vertices) as f64
    }

    #[test]
    fn unit_square_overhead_matches_the_closed_form() {
        let f = from_origin(&quad(-0.5, 0.5, -0.5, 0.5, 1.0));
        assert!((f - 0.239456).abs() < 1e-6, "{f}");
        assert!((f - 4.0 * corner(0.5, 0.5, 1.0)).abs() < 1e-7, "{f}");
        // Off-centre rectangles at several heights, including ones straddling the axis.
        for (x0, x1, y0, y1, c) in [(0.0, 1.0, 0.0, 2.0, 1.0), (-0.3, 2.0, 0.5, 1.5, 0.7), (-4.0, -1.0, -2.0, 3.0, 2.5)] {
            let f = from_origin(&quad(x0 as f32, x1 as f32, y0 as f32, y1 as f32, c as f32));
            assert!((f - rectangle(x0, x1, y0, y1, c)).abs() < 1e-6, "{x0} {x1} {y0} {y1} {c}: {f}");
        }
        // Far away, where the edge terms (~10⁻³) cancel to F ≈ 1/(π 10⁶): still 5 digits.
        let f = from_origin(&quad(-0.5, 0.5, -0.5, 0.5, 1e3));
        let exact = 4.0 * corner(0.5, 0.5, 1e3);
        assert!((f / exact - 1.0).abs() < 1e-5, "{f} vs {exact}");
    }

    #[test]
    fn triangle_gives_root_three_over_eighteen() {
        // Only the far edge is off the planes through +z: β = π/3, n·γ = 1/√3, F = 1/(6√3).
        let t = [Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 1.0)];
        let f = from_origin(&t);
        assert!((f - 3f64.sqrt() / 18.0).abs() < 1e-7, "{f}");
        // The other winding, and the same picture moved and turned, give the same F.
        assert_eq!(from_origin(&[t[2], t[1], t[0]]), f);
        let shift = Vec3::new(3.0, -2.0, 5.0);
        let turn = glam::Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let moved: Vec<Vec3> = t.iter().map(|&q| turn * q + shift).collect();
        let g = polygon_form_factor(shift, turn * Vec3::Z, &moved) as f64;
        assert!((g - f).abs() < 1e-6, "{g} vs {f}");
    }

    #[test]
    fn huge_square_fills_the_hemisphere() {
        let f = from_origin(&quad(-5e3, 5e3, -5e3, 5e3, 1.0));
        assert!(f > 1.0 - 1e-6 && f <= 1.0, "{f}");
        assert!((f - 4.0 * corner(5e3, 5e3, 1.0)).abs() < 1e-7, "{f}");
        // A unit square just above p, the limit from in front.
        let f = from_origin(&quad(-0.5, 0.5, -0.5, 0.5, 1e-4));
        assert!(f > 0.999 && f <= 1.0, "{f}");
    }

    #[test]
    fn below_the_tangent_plane_sends_nothing() {
        assert_eq!(from_origin(&quad(-1.0, 1.0, -1.0, 1.0, -1.0)), 0.0);
        // Above the plane but seen with the normal turned away.
        assert_eq!(polygon_form_factor(Vec3::ZERO, -Vec3::Z, &quad(-1.0, 1.0, -1.0, 1.0, 1.0)), 0.0);
        // Fewer than three vertices enclose nothing.
        assert_eq!(from_origin(&[]), 0.0);
        assert_eq!(from_origin(&[Vec3::Z]), 0.0);
        assert_eq!(from_origin(&[Vec3::Z, Vec3::new(1.0, 0.0, 1.0)]), 0.0);
    }

    #[test]
    fn clipping_keeps_exactly_the_part_above() {
        // A vertical square in x = 1 straddling the tangent plane z = 0 is its upper half.
        let wall = |z0: f32| [Vec3::new(1.0, -1.0, z0), Vec3::new(1.0, 1.0, z0), Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, 1.0)];
        let (whole, upper) = (from_origin(&wall(-1.0)), from_origin(&wall(0.0)));
        assert!(upper > 0.01 && (whole - upper).abs() < 1e-7, "{whole} vs {upper}");
        // A tilted normal and a tilted triangle with one vertex below: compare with the
        // quadrilateral the clip should produce, built by hand.
        let n = Vec3::new(0.3, -0.2, 1.0).normalize();
        let tri = [Vec3::new(-1.0, 0.5, 2.0), Vec3::new(1.5, 0.0, 1.0), Vec3::new(0.5, 2.0, -3.0)];
        let cut = |a: Vec3, b: Vec3| a + (b - a) * (n.dot(a) / (n.dot(a) - n.dot(b)));
        let hand = [tri[0], tri[1], cut(tri[1], tri[2]), cut(tri[2], tri[0])];
        let (f, g) = (polygon_form_factor(Vec3::ZERO, n, &tri), polygon_form_factor(Vec3::ZERO, n, &hand));
        assert!(g > 0.01 && (f - g).abs() < 1e-6, "{f} vs {g}");
    }

    /// A U in the plane x = 1: a base below z = −0.5 and two prongs rising to z = 2, so the
    /// clip at z = 0 cuts it into two rectangles.
    fn u_shape() -> Vec<Vec3> {
        [(-3.0, -1.0), (3.0, -1.0), (3.0, 2.0), (1.0, 2.0), (1.0, -0.5), (-1.0, -0.5), (-1.0, 2.0), (-3.0, 2.0)]
            .iter()
            .map(|&(y, z)| Vec3::new(1.0, y, z))
            .collect()
    }

    #[test]
    fn concave_polygons_add_like_their_pieces() {
        // An L of three unit squares at height 1 is the sum of the squares.
        let l_shape =
            [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)].map(|(x, y)| Vec3::new(x - 0.3, y - 0.6, 1.0));
        let pieces: f64 =
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].iter().map(|&(x, y)| from_origin(&quad(x - 0.3, x + 0.7, y - 0.6, y + 0.4, 1.0))).sum();
        let f = from_origin(&l_shape);
        assert!((f - pieces).abs() < 1e-6, "{f} vs {pieces}");
        // A U cut by the horizon into two prongs: the clip runs back and forth along z = 0.
        let prong = |y0: f32, y1: f32| [Vec3::new(1.0, y0, 0.0), Vec3::new(1.0, y1, 0.0), Vec3::new(1.0, y1, 2.0), Vec3::new(1.0, y0, 2.0)];
        let prongs = from_origin(&prong(-3.0, -1.0)) + from_origin(&prong(1.0, 3.0));
        let f = from_origin(&u_shape());
        assert!(prongs > 0.01 && (f - prongs).abs() < 1e-6, "{f} vs {prongs}");
    }

    /// Whether the ray from `o` along `d` hits the planar polygon, by the crossing number of
    /// the hit point in the polygon's plane (for concave polygons too).
    fn ray_hits(o: Vec3, d: Vec3, polygon: &[Vec3]) -> bool {
        let m = (polygon[1] - polygon[0]).cross(polygon[2] - polygon[0]).normalize();
        let t = m.dot(polygon[0] - o) / m.dot(d);
        if t.is_nan() || t <= 0.0 {
            return false;
        }
        let (e1, e2) = basis(m);
        let to_2d = |q: Vec3| (e1.dot(q - polygon[0]), e2.dot(q - polygon[0]));
        let (x, y) = to_2d(o + d * t);
        let mut inside = false;
        for i in 0..polygon.len() {
            let ((x0, y0), (x1, y1)) = (to_2d(polygon[i]), to_2d(polygon[(i + 1) % polygon.len()]));
            if (y0 > y) != (y1 > y) && x < x0 + (y - y0) * (x1 - x0) / (y1 - y0) {
                inside = !inside;
            }
        }
        inside
    }

    #[test]
    fn agrees_with_monte_carlo_over_cosine_weighted_rays() {
        // With pdf cosθ/π, the fraction of rays that hit is an unbiased estimate of F,
        // binomial with σ = √(F(1 − F)/N) (the low-discrepancy rays do better still).
        let tilted = [Vec3::new(-1.0, 0.5, 2.0), Vec3::new(1.5, 0.0, 1.0), Vec3::new(0.5, 2.0, -3.0)];
        let cases: [(&str, Vec3, Vec3, Vec<Vec3>); 3] = [
            ("square", Vec3::ZERO, Vec3::Z, quad(-0.5, 0.5, -0.5, 0.5, 1.0)),
            ("tilted triangle, clipped", Vec3::new(0.1, 0.2, -0.1), Vec3::new(0.3, -0.2, 1.0).normalize(), tilted.to_vec()),
            ("U, clipped", Vec3::ZERO, Vec3::new(0.2, 0.1, 1.0).normalize(), u_shape()),
        ];
        let rays = 1u32 << 16;
        for (name, p, n, polygon) in cases {
            let (t, b) = basis(n);
            let hits = (0..rays)
                .filter(|&k| {
                    let w = cosine_hemisphere(sample_2d(k, 77));
                    ray_hits(p, t * w.x + b * w.y + n * w.z, &polygon)
                })
                .count();
            let estimate = hits as f64 / rays as f64;
            let f = polygon_form_factor(p, n, &polygon) as f64;
            let sigma = (f * (1.0 - f) / rays as f64).sqrt();
            assert!(f > 0.01 && (estimate - f).abs() < 3.0 * sigma, "{name}: F = {f}, Monte Carlo {estimate} ± {sigma}");
        }
    }

    #[test]
    fn degenerate_views_stay_finite_in_range() {
        let square = quad(-0.5, 0.5, -0.5, 0.5, 1.0);
        let tilted = [Vec3::new(-1.0, 0.5, 2.0), Vec3::new(1.5, 0.0, 1.0), Vec3::new(0.5, 2.0, -3.0)];
        let on_square = [Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.5, 0.0, 1.0), Vec3::new(0.5, 0.5, 1.0), Vec3::new(2.0, 0.0, 1.0)];
        let on_tilted = [tilted[0], (tilted[0] + tilted[1]) / 2.0, (tilted[0] + tilted[1] + tilted[2]) / 3.0];
        let normals = [Vec3::Z, -Vec3::Z, Vec3::X, Vec3::new(1.0, 1.0, 1.0).normalize()];
        for (polygon, points) in [(&square[..], &on_square[..]), (&tilted[..], &on_tilted[..])] {
            for &p in points {
                for n in normals {
                    let f = polygon_form_factor(p, n, polygon);
                    assert!(f.is_finite() && (0.0..=1.0).contains(&f), "{p} {n}: {f}");
                }
            }
        }
        // In the tangent plane: 1 inside (the limit from in front), ½ on an edge, 0 outside.
        assert_eq!(polygon_form_factor(Vec3::new(0.0, 0.0, 1.0), Vec3::Z, &square), 1.0);
        assert!((polygon_form_factor(Vec3::new(0.5, 0.0, 1.0), Vec3::Z, &square) - 0.5).abs() < 1e-6);
        assert!(polygon_form_factor(Vec3::new(2.0, 0.0, 1.0), Vec3::Z, &square) < 1e-6);
        // In a tilted plane, inside: the clip leaves p on the cut, half a turn, |n·m|/2.
        let n = Vec3::new(1.0, 0.0, 1.0).normalize();
        assert!((polygon_form_factor(Vec3::new(0.0, 0.0, 1.0), n, &square) - n.z / 2.0).abs() < 1e-6);
        // Bad normals and bad vertices.
        assert_eq!(polygon_form_factor(Vec3::ZERO, Vec3::ZERO, &square), 0.0);
        assert_eq!(polygon_form_factor(Vec3::ZERO, Vec3::splat(f32::NAN), &square), 0.0);
        let mut broken = square.clone();
        broken[2].x = f32::NAN;
        assert_eq!(from_origin(&broken), 0.0);
        // Repeated vertices change nothing.
        let doubled = [square[0], square[0], square[1], square[2], square[2], square[3]];
        assert!((from_origin(&doubled) - from_origin(&square)).abs() < 1e-7);
    }
}
