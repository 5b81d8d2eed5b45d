//! Uniform subdivision of a triangle into k² similar triangles: how radiosity meshes
//! surfaces into patches.
//!
//! Each edge is cut into k equal parts, k = ⌈longest edge / size⌉, and the lattice points
//! p(i, j) = a + (i/k)(b − a) + (j/k)(c − a), i + j ≤ k, are joined into k² triangles, each
//! similar to the original with edges 1/k as long (so its longest edge is at most `size`).
//! The scene's limit check counts patches with [`divisions`] before any work.

use glam::Vec3;

/// The most cuts per edge, whatever the size: keeps k² well inside u64 and u32 indices.
const MAX_DIVISIONS: f64 = 65_536.0;

/// Cuts per edge, k = ⌈longest edge / size⌉ (at least 1), for the triangle `a b c`.
/// A zero-area or non-finite triangle, or a size that is not a positive finite number, gives 1.
pub fn divisions(a: Vec3, b: Vec3, c: Vec3, size: f32) -> u32 {
    // f64::max skips a NaN edge, so the corners are checked first.
    if !(a.is_finite() && b.is_finite() && c.is_finite()) {
        return 1;
    }
    let longest = [(a, b), (b, c), (c, a)].iter().map(|(p, q)| p.as_dvec3().distance(q.as_dvec3())).fold(0.0f64, f64::max);
    if !(longest.is_finite() && size.is_finite() && size > 0.0) {
        return 1;
    }
    (longest / size as f64).ceil().clamp(1.0, MAX_DIVISIONS) as u32
}

/// The lattice point (i, j) of a triangle cut k times per edge, i + j ≤ k.
#[inline]
pub fn lattice(a: Vec3, b: Vec3, c: Vec3, k: u32, i: u32, j: u32) -> Vec3 {
    let (u, v) = (i as f32 / k as f32, j as f32 / k as f32);
    a + (b - a) * u + (c - a) * v
}

/// The k² sub-triangles as lattice coordinates ((i, j) of each corner), wound as `a b c`.
pub fn sub_triangles(k: u32) -> impl Iterator<Item = [(u32, u32); 3]> {
    (0..k).flat_map(move |j| {
        (0..k - j).flat_map(move |i| {
            // The upright triangle at (i, j), and the inverted one beside it when it exists.
            let up = [(i, j), (i + 1, j), (i, j + 1)];
            let down = (i + j + 1 < k).then_some([(i + 1, j), (i + 1, j + 1), (i, j + 1)]);
            std::iter::once(up).chain(down)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn k_squared_triangles_that_tile_the_original_area_with_its_winding() {
        let (a, b, c) = (Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0));
        let k = divisions(a, b, c, 0.5);
        // Longest edge √5 ≈ 2.236 → 5 cuts.
        assert_eq!(k, 5);
        let n = (b - a).cross(c - a);
        let mut area = 0.0;
        let mut count = 0;
        for t in sub_triangles(k) {
            let [p, q, r] = t.map(|(i, j)| lattice(a, b, c, k, i, j));
            let m = (q - p).cross(r - p);
            assert!(m.dot(n) > 0.0, "same winding");
            assert!([(p, q), (q, r), (r, p)].iter().all(|(x, y)| x.distance(*y) <= 0.5 + 1e-6));
            area += 0.5 * m.length();
            count += 1;
        }
        assert_eq!(count, k * k);
        assert!((area - 0.5 * n.length()).abs() < 1e-5);
    }

    #[test]
    fn degenerate_input_gives_one_division() {
        assert_eq!(divisions(Vec3::ZERO, Vec3::X, Vec3::Y, 0.0), 1);
        assert_eq!(divisions(Vec3::ZERO, Vec3::X, Vec3::NAN, 0.1), 1);
        assert_eq!(divisions(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, 0.1), 1);
    }
}
