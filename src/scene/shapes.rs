//! Procedural shapes, centred at the origin, about unit size, wound counter-clockwise
//! seen from outside.
//!
//! Every generator leaves `normals` empty: call
//! [`compute_vertex_normals`](super::normals::compute_vertex_normals) with the weighting
//! the lesson asks for. Smooth shapes (spheres, torus) share each vertex between all
//! the triangles around it, with no duplicated seam, so those normals come out smooth;
//! the cube and the plane give each face its own vertices, so their edges stay hard.
//!
//! Texture coordinates are per triangle corner (`Mesh::uvs`), so seams need no extra
//! vertices. Spheres: u = ½ + atan2(x, z)/2π (0.5 facing +z, growing to the right seen
//! from +z, the seam at −z), v = 1 − polar angle/π (1 at the north pole). The uv sphere's
//! come from its grid exactly, a pole corner taking its band's middle u; the icosphere's
//! from the formula, a triangle across the seam with 1 added to its small u's (so it
//! reads the texture across the seam without a jump) and a corner at a pole taking the
//! mean u of the other two; the triangles round a pole squeeze the texture, as any sphere
//! mapping must. The
//! plane: u = (x + 1)/2, v = (1 − z)/2. The cube: each face the whole unit square.
//! The torus: u = the step around y, v = the step around the tube, each from 0 to 1.

use std::collections::HashMap;
use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};

use super::mesh::Mesh;

fn mesh(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>, uvs: Vec<[Vec2; 3]>) -> Mesh {
    Mesh { positions, normals: Vec::new(), triangles, uvs }
}

/// The sphere mapping of a unit direction (see the module docs).
pub fn sphere_uv(p: Vec3) -> Vec2 {
    Vec2::new(0.5 + p.x.atan2(p.z) / TAU, 1.0 - p.y.clamp(-1.0, 1.0).acos() / PI)
}

/// A radius-1 sphere with poles on ±y, `segments` columns around y and `rings`
/// latitude bands: `2 + segments·(rings − 1)` vertices, `2·segments·(rings − 1)` triangles.
///
/// Each pole is a single vertex whose band is a fan of single triangles. Preconditions:
/// `segments ≥ 3`, `rings ≥ 2`; smaller values are raised to those.
pub fn uv_sphere(segments: u32, rings: u32) -> Mesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut positions = vec![Vec3::Y];
    for ring in 1..rings {
        // Polar angle from +y, evenly spaced so the bands have equal angular height.
        let (sin_phi, cos_phi) = (PI * ring as f32 / rings as f32).sin_cos();
        for segment in 0..segments {
            let (sin_theta, cos_theta) = (TAU * segment as f32 / segments as f32).sin_cos();
            positions.push(Vec3::new(sin_phi * cos_theta, cos_phi, sin_phi * sin_theta));
        }
    }
    positions.push(Vec3::NEG_Y);
    let (north, south) = (0, positions.len() as u32 - 1);

    // Vertex `column` (wrapping, so the seam reuses column 0) of ring `row` (0 = top ring).
    let at = |row: u32, column: u32| 1 + row * segments + column % segments;
    let mut triangles = Vec::with_capacity((2 * segments * (rings - 1)) as usize);
    // The uv of a grid corner (row 0 = north pole, column unwrapped, u = ¾ − column/segments
    // is the sphere mapping of the module docs on this grid).
    let uv = |row: f32, column: f32| Vec2::new(0.75 - column / segments as f32, 1.0 - row / rings as f32);
    let mut uvs = Vec::with_capacity(triangles.capacity());
    for j in 0..segments {
        let jf = j as f32;
        triangles.push([north, at(0, j + 1), at(0, j)]);
        uvs.push([uv(0.0, jf + 0.5), uv(1.0, jf + 1.0), uv(1.0, jf)]);
        for row in 0..rings - 2 {
            let (a, b) = (at(row, j), at(row, j + 1));
            let (c, d) = (at(row + 1, j), at(row + 1, j + 1));
            triangles.extend([[a, d, c], [a, b, d]]);
            let r = row as f32 + 1.0;
            let (ua, ub, uc, ud) = (uv(r, jf), uv(r, jf + 1.0), uv(r + 1.0, jf), uv(r + 1.0, jf + 1.0));
            uvs.extend([[ua, ud, uc], [ua, ub, ud]]);
        }
        triangles.push([at(rings - 2, j), at(rings - 2, j + 1), south]);
        let r = (rings - 1) as f32;
        uvs.push([uv(r, jf), uv(r, jf + 1.0), uv(r + 1.0, jf + 0.5)]);
    }
    mesh(positions, triangles, uvs)
}

/// A radius-1 sphere made by splitting each triangle of an icosahedron into four,
/// `subdivisions` times, sharing edge midpoints: `10·4ⁿ + 2` vertices, `20·4ⁿ` triangles.
///
/// The cost grows as 4ⁿ (n = 5 gives 20 480 triangles); callers validate `n`.
pub fn icosphere(subdivisions: u32) -> Mesh {
    // The 12 vertices (0, ±1, ±t) and their cyclic permutations, t the golden ratio.
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut positions: Vec<Vec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .into_iter()
    .map(|p| Vec3::from(p).normalize())
    .collect();
    let mut triangles = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        // One midpoint per edge, whichever of its two triangles asks first.
        let mut midpoints = HashMap::new();
        let mut midpoint = |i: u32, j: u32| {
            *midpoints.entry((i.min(j), i.max(j))).or_insert_with(|| {
                let p = (positions[i as usize] + positions[j as usize]).normalize();
                positions.push(p);
                positions.len() as u32 - 1
            })
        };
        triangles = triangles
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (midpoint(a, b), midpoint(b, c), midpoint(c, a));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    let uvs = triangles
        .iter()
        .map(|t| {
            let mut uv = t.map(|i| sphere_uv(positions[i as usize]));
            // A corner at a pole (an edge midpoint of the icosahedron) has no longitude: it
            // takes the mean u of the other two.
            let pole = t.map(|i| positions[i as usize].x.hypot(positions[i as usize].z) < 1e-6);
            // Across the seam: lift the small u's by one so the triangle does not span the texture.
            let max = (0..3).filter(|&k| !pole[k]).map(|k| uv[k].x).fold(f32::MIN, f32::max);
            for k in (0..3).filter(|&k| !pole[k]) {
                if max - uv[k].x > 0.5 {
                    uv[k].x += 1.0;
                }
            }
            let others: Vec<f32> = (0..3).filter(|&k| !pole[k]).map(|k| uv[k].x).collect();
            for k in (0..3).filter(|&k| pole[k]) {
                uv[k].x = others.iter().sum::<f32>() / others.len().max(1) as f32;
            }
            uv
        })
        .collect();
    mesh(positions, triangles, uvs)
}

/// The square [−1, 1]² in the xz plane at y = 0, facing +y: 4 vertices, 2 triangles.
pub fn plane() -> Mesh {
    let positions = vec![Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(-1.0, 0.0, 1.0)];
    let uv = |p: Vec3| Vec2::new((p.x + 1.0) * 0.5, (1.0 - p.z) * 0.5);
    let triangles = vec![[0, 2, 1], [0, 3, 2]];
    let uvs = triangles.iter().map(|t: &[u32; 3]| t.map(|i| uv(positions[i as usize]))).collect();
    mesh(positions, triangles, uvs)
}

/// The cube [−1, 1]³ with 4 vertices per face so its edges stay hard: 24 vertices,
/// 12 triangles.
pub fn cube() -> Mesh {
    let mut positions = Vec::with_capacity(24);
    let mut triangles = Vec::with_capacity(12);
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            let normal = Vec3::AXES[axis] * sign;
            // Tangents with u × v = normal make the corners below counter-clockwise.
            let (mut u, mut v) = (Vec3::AXES[(axis + 1) % 3], Vec3::AXES[(axis + 2) % 3]);
            if sign < 0.0 {
                std::mem::swap(&mut u, &mut v);
            }
            let base = positions.len() as u32;
            for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                positions.push(normal + u * s + v * t);
            }
            triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        }
    }
    // The corners (s, t) above in order: each face is the whole unit square.
    let corner = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)];
    let uvs = (0..6).flat_map(|_| [[corner[0], corner[1], corner[2]], [corner[0], corner[2], corner[3]]]).collect();
    mesh(positions, triangles, uvs)
}

/// A torus around the y axis: a tube of radius `minor_radius` whose centre circle has
/// radius `major_radius` in the xz plane; `segments` steps around y, `sides` around the
/// tube: `segments·sides` vertices, `2·segments·sides` triangles.
///
/// Preconditions: `0 < minor_radius < major_radius` (else the surface intersects
/// itself); `segments ≥ 3`, `sides ≥ 3`, smaller values are raised to 3.
pub fn torus(major_radius: f32, minor_radius: f32, segments: u32, sides: u32) -> Mesh {
    let (segments, sides) = (segments.max(3), sides.max(3));
    let mut positions = Vec::with_capacity((segments * sides) as usize);
    for i in 0..segments {
        let (sin_theta, cos_theta) = (TAU * i as f32 / segments as f32).sin_cos();
        for j in 0..sides {
            let (sin_phi, cos_phi) = (TAU * j as f32 / sides as f32).sin_cos();
            let r = major_radius + minor_radius * cos_phi;
            positions.push(Vec3::new(r * cos_theta, minor_radius * sin_phi, r * sin_theta));
        }
    }
    // Both indices wrap, so the seams reuse the first column and row.
    let at = |i: u32, j: u32| (i % segments) * sides + j % sides;
    let mut triangles = Vec::with_capacity((2 * segments * sides) as usize);
    let mut uvs = Vec::with_capacity(triangles.capacity());
    // Unwrapped grid steps, so the seams' triangles run to u = 1 and v = 1.
    let uv = |i: u32, j: u32| Vec2::new(i as f32 / segments as f32, j as f32 / sides as f32);
    for i in 0..segments {
        for j in 0..sides {
            let (a, b) = (at(i, j), at(i + 1, j));
            let (c, d) = (at(i, j + 1), at(i + 1, j + 1));
            triangles.extend([[c, b, a], [c, d, b]]);
            let (ua, ub, uc, ud) = (uv(i, j), uv(i + 1, j), uv(i, j + 1), uv(i + 1, j + 1));
            uvs.extend([[uc, ub, ua], [uc, ud, ub]]);
        }
    }
    mesh(positions, triangles, uvs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::NormalWeighting;
    use crate::scene::normals::{compute_vertex_normals, face_normal};
    use glam::Quat;

    fn corners(m: &Mesh, triangle: [u32; 3]) -> [Vec3; 3] {
        triangle.map(|i| m.positions[i as usize])
    }

    /// Panics unless every triangle is non-degenerate and its normal points away
    /// from `inside(centroid)`, a point inside the solid near the triangle.
    fn assert_outward(m: &Mesh, inside: impl Fn(Vec3) -> Vec3) {
        for &triangle in &m.triangles {
            let [a, b, c] = corners(m, triangle);
            let n = face_normal(a, b, c).expect("non-degenerate");
            let centroid = (a + b + c) / 3.0;
            assert!(n.dot(centroid - inside(centroid)) > 0.0, "{triangle:?} faces inwards");
        }
    }

    /// Panics unless every directed edge appears once and its reverse once: the mesh is
    /// closed by index (no seam) and consistently wound.
    fn assert_closed(m: &Mesh) {
        let mut edges = HashMap::new();
        for &[a, b, c] in &m.triangles {
            for edge in [(a, b), (b, c), (c, a)] {
                *edges.entry(edge).or_insert(0) += 1;
            }
        }
        for (&(a, b), &count) in &edges {
            assert_eq!(count, 1, "edge {a}->{b} used {count} times");
            assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}->{b} has no twin");
        }
    }

    /// Largest distance between a vertex normal and the expected direction at its position.
    fn max_normal_error(m: &Mesh, expected: impl Fn(Vec3) -> Vec3) -> f32 {
        let mut m = m.clone();
        let repairs = compute_vertex_normals(&mut m, NormalWeighting::Average);
        assert_eq!(repairs, Default::default());
        m.positions.iter().zip(&m.normals).map(|(&p, &n)| (n - expected(p)).length()).fold(0.0, f32::max)
    }

    #[test]
    fn uv_sphere_counts() {
        for (segments, rings) in [(3, 2), (4, 3), (7, 5), (32, 16)] {
            let m = uv_sphere(segments, rings);
            assert_eq!(m.positions.len() as u32, 2 + segments * (rings - 1));
            assert_eq!(m.triangles.len() as u32, 2 * segments * (rings - 1));
            assert!(m.normals.is_empty());
        }
        assert_eq!(uv_sphere(0, 0), uv_sphere(3, 2));
    }

    #[test]
    fn uv_sphere_is_a_closed_outward_unit_sphere() {
        for (segments, rings) in [(3, 2), (7, 5), (32, 16)] {
            let m = uv_sphere(segments, rings);
            assert!(m.positions.iter().all(|p| (p.length() - 1.0).abs() < 1e-6));
            assert_closed(&m);
            assert_outward(&m, |_| Vec3::ZERO);
        }
    }

    #[test]
    fn uv_sphere_normals_match_across_the_seam_and_at_the_poles() {
        let (segments, rings) = (32, 16);
        let mut m = uv_sphere(segments, rings);
        compute_vertex_normals(&mut m, NormalWeighting::Average);
        // A pole's fan is symmetric, so only rounding keeps its normal off the axis.
        for (n, y) in [(m.normals[0], 1.0), (m.normals[m.normals.len() - 1], -1.0)] {
            assert_eq!(n.y, y);
            assert!(n.x.abs() < 1e-6 && n.z.abs() < 1e-6, "{n}");
        }
        // Every column, including the last one that closes the seam, has the normals
        // of column 0 rotated about y: no column is special.
        for ring in 0..rings - 1 {
            let first = m.normals[(1 + ring * segments) as usize];
            for column in 0..segments {
                let theta = TAU * column as f32 / segments as f32;
                let expected = Quat::from_rotation_y(-theta) * first;
                let n = m.normals[(1 + ring * segments + column) as usize];
                assert!(n.abs_diff_eq(expected, 1e-5), "ring {ring}, column {column}");
            }
        }
    }

    /// Averaging face normals by index is only first-order accurate on these meshes:
    /// on the ring next to a pole, two fan triangles above a vertex meet three below,
    /// tilting its normal by about a tenth of the ring spacing (0.02 at 16 rings), and
    /// an icosphere's triangles differ in size. So the bounds (measured, plus margin)
    /// halve as the resolution doubles; a duplicated seam or pole would break them.
    #[test]
    fn sphere_normals_converge_to_radial() {
        let radial = Vec3::normalize;
        assert!(max_normal_error(&uv_sphere(32, 16), radial) < 0.025); // measured 0.0205
        assert!(max_normal_error(&uv_sphere(64, 32), radial) < 0.0125); // 0.0099
        assert!(max_normal_error(&icosphere(3), radial) < 0.01); // 0.0083
        assert!(max_normal_error(&icosphere(4), radial) < 0.005); // 0.0043
        // The icosahedron's 12 vertices keep their five-fold symmetry at every level.
        for n in 0..4 {
            let mut m = icosphere(n);
            compute_vertex_normals(&mut m, NormalWeighting::Average);
            for (p, normal) in m.positions.iter().zip(&m.normals).take(12) {
                assert!(normal.abs_diff_eq(*p, 1e-6), "level {n}: {normal} at {p}");
            }
        }
    }

    #[test]
    fn icosphere_counts() {
        for n in 0..4 {
            let m = icosphere(n);
            assert_eq!(m.positions.len(), 10 * 4usize.pow(n) + 2);
            assert_eq!(m.triangles.len(), 20 * 4usize.pow(n));
        }
    }

    #[test]
    fn icosphere_is_a_closed_outward_unit_sphere() {
        for n in 0..4 {
            let m = icosphere(n);
            assert!(m.positions.iter().all(|p| (p.length() - 1.0).abs() < 1e-6));
            assert_closed(&m);
            assert_outward(&m, |_| Vec3::ZERO);
        }
    }

    #[test]
    fn plane_faces_up() {
        let mut m = plane();
        assert_eq!((m.positions.len(), m.triangles.len()), (4, 2));
        compute_vertex_normals(&mut m, NormalWeighting::Average);
        assert!(m.normals.iter().all(|&n| n == Vec3::Y));
        assert!(m.positions.iter().all(|p| p.y == 0.0 && p.abs().max_element() == 1.0));
    }

    #[test]
    fn cube_faces_point_out_with_hard_edges() {
        let mut m = cube();
        assert_eq!((m.positions.len(), m.triangles.len()), (24, 12));
        assert!(m.positions.iter().all(|p| p.abs() == Vec3::ONE));
        assert_outward(&m, |_| Vec3::ZERO);
        compute_vertex_normals(&mut m, NormalWeighting::Average);
        // Each vertex normal is its face's axis, not a blend across the edge.
        for (p, n) in m.positions.iter().zip(&m.normals) {
            assert_eq!(n.abs().element_sum(), 1.0, "{n}");
            assert_eq!(p.dot(*n), 1.0, "{n} is not the normal of the face at {p}");
        }
    }

    #[test]
    fn torus_is_closed_outward_with_tube_normals() {
        let (major, minor) = (1.0, 0.25);
        // The point on the tube's centre circle nearest to `p`.
        let tube_centre = |p: Vec3| Vec3::new(p.x, 0.0, p.z).normalize() * major;
        for (segments, sides) in [(3, 3), (12, 8), (48, 24)] {
            let m = torus(major, minor, segments, sides);
            assert_eq!(m.positions.len() as u32, segments * sides);
            assert_eq!(m.triangles.len() as u32, 2 * segments * sides);
            assert_closed(&m);
            // At 3 segments the chords cut inside the centre circle, so skip that one.
            if segments > 3 {
                assert_outward(&m, tube_centre);
            }
        }
        let m = torus(major, minor, 48, 24);
        assert!(max_normal_error(&m, |p| (p - tube_centre(p)).normalize()) < 4e-3); // measured 0.0029
        assert_eq!(torus(major, minor, 0, 1), torus(major, minor, 3, 3));
    }

    #[test]
    fn sphere_uvs_follow_the_mapping_at_known_points() {
        // The north pole v = 1, the south v = 0; the equator facing +z at (0.5, 0.5), +x at u = 0.75.
        assert_eq!(sphere_uv(Vec3::Y).y, 1.0);
        assert_eq!(sphere_uv(Vec3::NEG_Y).y, 0.0);
        assert!((sphere_uv(Vec3::Z) - Vec2::new(0.5, 0.5)).length() < 1e-6);
        assert!((sphere_uv(Vec3::X) - Vec2::new(0.75, 0.5)).length() < 1e-6);
        for m in [uv_sphere(16, 8), icosphere(2)] {
            assert_eq!(m.uvs.len(), m.triangles.len());
            for (t, uv) in m.triangles.iter().zip(&m.uvs) {
                for (k, &i) in t.iter().enumerate() {
                    let p = m.positions[i as usize];
                    let want = sphere_uv(p);
                    assert!((uv[k].y - want.y).abs() < 1e-5, "v at {p}: {} vs {}", uv[k].y, want.y);
                    if p.y.abs() < 0.9999 {
                        // u up to whole turns (the seam), except at a pole where u is free.
                        let du = (uv[k].x - want.x).rem_euclid(1.0);
                        assert!(du.min(1.0 - du) < 1e-5, "u at {p}: {} vs {}", uv[k].x, want.x);
                    }
                }
                // No triangle spans the texture: the seam's triangles read past u = 1 instead.
                let (lo, hi) = uv.iter().fold((f32::MAX, f32::MIN), |(lo, hi), c| (lo.min(c.x), hi.max(c.x)));
                assert!(hi - lo < 0.5, "{uv:?}");
            }
        }
    }

    #[test]
    fn flat_shapes_and_the_torus_cover_the_unit_square() {
        let plane = plane();
        for (t, uv) in plane.triangles.iter().zip(&plane.uvs) {
            for (k, &i) in t.iter().enumerate() {
                let p = plane.positions[i as usize];
                assert_eq!(uv[k], Vec2::new((p.x + 1.0) / 2.0, (1.0 - p.z) / 2.0));
            }
        }
        let cube = cube();
        assert_eq!(cube.uvs.len(), 12);
        assert!(cube.uvs.iter().flatten().all(|c| c.x == 0.0 || c.x == 1.0));
        let torus = torus(1.0, 0.3, 8, 6);
        assert_eq!(torus.uvs.len(), torus.triangles.len());
        let (lo, hi) = torus.uvs.iter().flatten().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), c| (lo.min(*c), hi.max(*c)));
        assert_eq!((lo, hi), (Vec2::ZERO, Vec2::ONE));
    }
}
