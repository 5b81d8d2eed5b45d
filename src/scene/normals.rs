//! Face and vertex normals for indexed triangle meshes.
//!
//! A vertex normal is the normalized sum of the normals of the faces that share the
//! vertex by index (the course's definition is the plain average; area and angle
//! weights are options, see [`NormalWeighting`]). Degenerate triangles are skipped
//! and counted; a vertex whose sum vanishes (or cancels to rounding noise) gets a repaired
//! normal and is counted.
//! No input, however broken, produces a NaN normal.

use glam::Vec3;

use super::mesh::{Mesh, MeshRepairs};
use crate::lesson::NormalWeighting;

/// A triangle is degenerate when `|e1 × e2| ≤ DEGENERATE_RATIO · s²`, with `s` its
/// largest edge coordinate. An f32 cross product carries about 1e-7·s² of rounding,
/// so below this ratio its direction is noise; being relative, the test does not
/// depend on the mesh's scale.
const DEGENERATE_RATIO: f32 = 1e-6;

/// The normal a vertex gets when no non-degenerate face touches it (y is up).
const FALLBACK_NORMAL: Vec3 = Vec3::Y;

/// A vertex's sum has cancelled when `|sum|∞ ≤ CANCELLED_RATIO · Σ |weight|∞`: summing f32
/// normals carries about 1e-7 of rounding per term, so below this its direction is noise
/// (nearly opposite faces, a fold) and the vertex is repaired as if the sum were zero.
const CANCELLED_RATIO: f32 = 1e-6;

/// Below this squared length glam's normalize loses bits (the squares become subnormal), so
/// [`unit`] rescales first, as it does when the square overflows; between, the result is
/// glam's, bit for bit.
const TINY_SQUARED: f32 = 1e-30;

/// The unit normal of the counter-clockwise triangle `(a, b, c)`, or `None` when it
/// is degenerate (see [`is_degenerate`]).
pub fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Option<Vec3> {
    let (e1, e2) = (b - a, c - a);
    let scale = e1.abs().max(e2.abs()).max((c - b).abs()).max_element();
    // Dividing by the scale first keeps the cross product from under- or overflowing.
    let cross = (e1 / scale).cross(e2 / scale);
    let finite = a.is_finite() && b.is_finite() && c.is_finite();
    // NaN (from a zero scale or infinities) fails the comparison: degenerate.
    if finite && cross.length() > DEGENERATE_RATIO { cross.try_normalize() } else { None }
}

/// Whether the triangle `(a, b, c)` has (near-)zero area relative to its edge lengths
/// or a non-finite vertex; such triangles are skipped for normals and by the rasterizer.
pub fn is_degenerate(a: Vec3, b: Vec3, c: Vec3) -> bool {
    face_normal(a, b, c).is_none()
}

/// Fills `mesh.normals` (one unit normal per position, replacing any present) by
/// summing adjacent face normals with the given weighting.
///
/// Triangles that are degenerate or index past `positions` are skipped and counted.
/// A vertex whose sum is zero, cancelled to rounding noise or non-finite (isolated, or only
/// touched by degenerate or opposite-facing triangles) gets the normal of its first
/// non-degenerate adjacent face, else +y, and is counted.
pub fn compute_vertex_normals(mesh: &mut Mesh, weighting: NormalWeighting) -> MeshRepairs {
    let adjacency = accumulate(mesh, weighting);
    let (normals, repaired_normals) = resolve(&adjacency.sums, Some(&adjacency.magnitudes), &adjacency.first_face);
    mesh.normals = normals;
    MeshRepairs { degenerate_triangles: adjacency.degenerate, repaired_normals }
}

/// Normalizes the normals already in `mesh.normals` (e.g. read from a file), repairing
/// zero-length or non-finite ones as [`compute_vertex_normals`] does.
///
/// Missing normals (fewer than positions) are treated as zero and repaired; extra
/// ones are dropped.
pub fn repair_vertex_normals(mesh: &mut Mesh) -> MeshRepairs {
    let adjacency = accumulate(mesh, NormalWeighting::Average);
    mesh.normals.resize(mesh.positions.len(), Vec3::ZERO);
    let (normals, repaired_normals) = resolve(&mesh.normals, None, &adjacency.first_face);
    mesh.normals = normals;
    MeshRepairs { degenerate_triangles: adjacency.degenerate, repaired_normals }
}

/// Per-vertex sums of weighted face normals, gathered in one pass over the triangles.
struct Adjacency {
    sums: Vec<Vec3>,
    /// Σ |weight|∞ per vertex: the scale its sum's rounding is relative to.
    magnitudes: Vec<f32>,
    /// The normal of the first non-degenerate face that uses each vertex.
    first_face: Vec<Option<Vec3>>,
    degenerate: usize,
}

fn accumulate(mesh: &Mesh, weighting: NormalWeighting) -> Adjacency {
    let vertex_count = mesh.positions.len();
    let mut adjacency = Adjacency {
        sums: vec![Vec3::ZERO; vertex_count],
        magnitudes: vec![0.0; vertex_count],
        first_face: vec![None; vertex_count],
        degenerate: 0,
    };
    for triangle in &mesh.triangles {
        let corners = triangle.map(|i| mesh.positions.get(i as usize).copied());
        let normal = match corners {
            [Some(a), Some(b), Some(c)] => face_normal(a, b, c).map(|n| (n, [a, b, c])),
            _ => None,
        };
        let Some((n, [a, b, c])) = normal else {
            adjacency.degenerate += 1;
            continue;
        };
        // Each corner: its index, and the edges leaving it (for the interior angle).
        let corners = [(triangle[0], b - a, c - a), (triangle[1], c - b, a - b), (triangle[2], a - c, b - c)];
        for (index, e1, e2) in corners {
            let weight = match weighting {
                NormalWeighting::Average => n,
                // |e1 × e2| is twice the area, the same at every corner.
                NormalWeighting::Area => (b - a).cross(c - a),
                // atan2(|e1 × e2|, e1 · e2) stays accurate near 0 and π, unlike acos.
                NormalWeighting::Angle => n * e1.cross(e2).length().atan2(e1.dot(e2)),
            };
            let index = index as usize;
            adjacency.sums[index] += weight;
            // The max norm: exact at any scale, where a length could under- or overflow.
            adjacency.magnitudes[index] += weight.abs().max_element();
            adjacency.first_face[index].get_or_insert(n);
        }
    }
    adjacency
}

/// Normalizes each raw normal, replacing a zero, non-finite or (given the summed weight
/// `magnitudes`) cancelled one; returns the count replaced.
fn resolve(raw: &[Vec3], magnitudes: Option<&[f32]>, first_face: &[Option<Vec3>]) -> (Vec<Vec3>, usize) {
    let mut repaired = 0;
    let normals = raw
        .iter()
        .enumerate()
        .zip(first_face)
        .map(|((i, sum), first)| {
            let cancelled = magnitudes.is_some_and(|m| sum.abs().max_element() <= CANCELLED_RATIO * m[i]);
            (!cancelled).then(|| unit(*sum)).flatten().unwrap_or_else(|| {
                repaired += 1;
                first.unwrap_or(FALLBACK_NORMAL)
            })
        })
        .collect();
    (normals, repaired)
}

/// `v` normalized to unit length at any scale, or `None` when it is zero or not finite.
fn unit(v: Vec3) -> Option<Vec3> {
    if (TINY_SQUARED..=f32::MAX).contains(&v.length_squared()) {
        return v.try_normalize();
    }
    if !v.is_finite() {
        return None;
    }
    // Tiny or huge: divide by the largest component first (exact; zero gives NaN, so None).
    (v / v.abs().max_element()).try_normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn mesh(positions: &[Vec3], triangles: &[[u32; 3]]) -> Mesh {
        Mesh { positions: positions.to_vec(), normals: Vec::new(), triangles: triangles.to_vec(), uvs: Vec::new() }
    }

    fn assert_close(actual: Vec3, expected: Vec3) {
        assert!(actual.abs_diff_eq(expected, 1e-6), "expected {expected}, got {actual}");
    }

    #[test]
    fn face_normal_follows_counter_clockwise_winding() {
        let n = face_normal(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap();
        assert_close(n, Vec3::Z);
        let n = face_normal(Vec3::ZERO, Vec3::Y, Vec3::X).unwrap();
        assert_close(n, -Vec3::Z);
    }

    #[test]
    fn degeneracy_is_relative_to_scale() {
        // A well-shaped triangle is fine at any scale...
        for scale in [1e-30, 1e-12, 1.0, 1e12, 1e30] {
            let n = face_normal(Vec3::ZERO, Vec3::X * scale, Vec3::Y * scale);
            assert_eq!(n, Some(Vec3::Z), "scale {scale}");
        }
        // ...and a sliver is degenerate at any scale.
        for scale in [1e-6, 1.0, 1e6] {
            let sliver = [Vec3::ZERO, Vec3::X * scale, Vec3::new(0.5, 1e-8, 0.0) * scale];
            assert!(is_degenerate(sliver[0], sliver[1], sliver[2]), "scale {scale}");
        }
    }

    #[test]
    fn collinear_coincident_and_non_finite_triangles_are_degenerate() {
        assert!(is_degenerate(Vec3::ZERO, Vec3::X, Vec3::X * 2.0));
        assert!(is_degenerate(Vec3::ONE, Vec3::ONE, Vec3::ONE));
        assert!(is_degenerate(Vec3::ZERO, Vec3::X, Vec3::new(f32::NAN, 1.0, 0.0)));
        assert!(is_degenerate(Vec3::ZERO, Vec3::X, Vec3::new(0.0, f32::INFINITY, 0.0)));
        assert!(!is_degenerate(Vec3::ZERO, Vec3::X, Vec3::Y));
    }

    #[test]
    fn single_triangle_vertices_get_the_face_normal() {
        let mut m = mesh(&[Vec3::ZERO, Vec3::X, Vec3::Z], &[[0, 2, 1]]);
        let repairs = compute_vertex_normals(&mut m, NormalWeighting::Average);
        assert_eq!(repairs, MeshRepairs::default());
        assert_eq!(m.normals.len(), 3);
        for n in m.normals {
            assert_close(n, Vec3::Y);
        }
    }

    #[test]
    fn area_weighting_differs_from_average_on_an_irregular_fan() {
        // Vertex 0 is shared by a large triangle facing +z and a small one facing +x.
        let positions = [Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0), Vec3::new(0.0, 0.0, -1.0)];
        let triangles = [[0, 1, 2], [0, 3, 2]];
        let mut average = mesh(&positions, &triangles);
        let mut area = mesh(&positions, &triangles);
        compute_vertex_normals(&mut average, NormalWeighting::Average);
        compute_vertex_normals(&mut area, NormalWeighting::Area);
        // Areas are 8 and 2, so the area-weighted sum is 8 z + 2 x.
        assert_close(average.normals[0], Vec3::new(1.0, 0.0, 1.0).normalize());
        assert_close(area.normals[0], Vec3::new(2.0, 0.0, 8.0).normalize());
        assert_close(area.normals[1], Vec3::Z);
        assert_close(area.normals[3], Vec3::X);
    }

    #[test]
    fn angle_weighting_ignores_how_a_face_is_triangulated() {
        // A cube corner at the origin whose z = 0 face is split into two triangles.
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(1.0, 1.0, 0.0)];
        let triangles = [[0, 2, 4], [0, 4, 1], [0, 1, 3], [0, 3, 2]];
        let mut angle = mesh(&positions, &triangles);
        let mut average = mesh(&positions, &triangles);
        compute_vertex_normals(&mut angle, NormalWeighting::Angle);
        compute_vertex_normals(&mut average, NormalWeighting::Average);
        assert_close(angle.normals[0], -Vec3::ONE.normalize());
        assert_close(average.normals[0], Vec3::new(-1.0, -1.0, -2.0).normalize());
    }

    #[test]
    fn degenerate_triangle_is_counted_and_produces_no_nan() {
        // Triangle 1 is collinear; vertex 3 is used only by it.
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X * 2.0];
        let mut m = mesh(&positions, &[[0, 1, 2], [0, 1, 3]]);
        let repairs = compute_vertex_normals(&mut m, NormalWeighting::Area);
        assert_eq!(repairs.degenerate_triangles, 1);
        assert_eq!(repairs.repaired_normals, 1);
        assert_close(m.normals[0], Vec3::Z);
        assert_eq!(m.normals[3], Vec3::Y);
    }

    #[test]
    fn isolated_vertex_and_bad_indices_are_repaired() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::splat(5.0)];
        let mut m = mesh(&positions, &[[0, 1, 2], [0, 1, 99]]);
        let repairs = compute_vertex_normals(&mut m, NormalWeighting::Average);
        assert_eq!(repairs, MeshRepairs { degenerate_triangles: 1, repaired_normals: 1 });
        assert_eq!(m.normals[3], Vec3::Y);
    }

    #[test]
    fn opposite_faces_fall_back_to_the_first_face() {
        // The same triangle twice with opposite windings: every sum cancels to zero.
        let mut m = mesh(&[Vec3::ZERO, Vec3::X, Vec3::Y], &[[0, 1, 2], [0, 2, 1]]);
        let repairs = compute_vertex_normals(&mut m, NormalWeighting::Angle);
        assert_eq!(repairs.repaired_normals, 3);
        for n in m.normals {
            assert_eq!(n, Vec3::Z);
        }
    }

    #[test]
    fn repair_keeps_good_normals_and_replaces_bad_ones() {
        let mut m = mesh(&[Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z], &[[0, 1, 2]]);
        m.normals = vec![Vec3::X * 3.0, Vec3::ZERO, Vec3::NAN];
        let repairs = repair_vertex_normals(&mut m);
        assert_eq!(repairs.repaired_normals, 3);
        assert_eq!(m.normals, vec![Vec3::X, Vec3::Z, Vec3::Z, Vec3::Y]);
    }

    /// The minimal case `normals_are_always_unit_and_finite` found: faces [1, 6, 4] and
    /// [4, 6, 0] lie in one plane with opposite orientations, so at vertices 4 and 6 their
    /// normals cancel to (0, 0, −2.99e-23), whose square is subnormal: normalizing it gave
    /// (0, 0, −0.7986). A cancelled sum is noise, so those vertices take the first face's normal.
    #[test]
    fn nearly_opposite_faces_give_unit_normals() {
        let positions = [
            Vec3::ZERO,
            Vec3::new(0.0, 7.59e-22, -1.244),
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::new(-2.4489903, -8.382962, 0.0),
            Vec3::new(0.0, 0.0, -0.0),
            Vec3::new(0.0, 0.0, -8.363997),
        ];
        let triangles = [[1, 6, 4], [4, 6, 0]];
        let mut m = mesh(&positions, &triangles);
        let repairs = compute_vertex_normals(&mut m, NormalWeighting::Average);
        for n in &m.normals {
            assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-6, "{n}");
        }
        let first = face_normal(positions[1], positions[6], positions[4]).unwrap();
        assert_eq!((m.normals[4], m.normals[6]), (first, first));
        // Vertices 4 and 6 cancelled; 2, 3 and 5 are isolated.
        assert_eq!(repairs, MeshRepairs { degenerate_triangles: 0, repaired_normals: 5 });
    }

    #[test]
    fn tiny_area_weights_still_normalize_to_unit() {
        // |e1 × e2| = 9e-22: its square is subnormal, where glam's normalize loses bits.
        let s = 3e-11;
        let mut m = mesh(&[Vec3::ZERO, Vec3::X * s, Vec3::Y * s], &[[0, 1, 2]]);
        let repairs = compute_vertex_normals(&mut m, NormalWeighting::Area);
        assert_eq!(repairs, MeshRepairs::default());
        assert_eq!(m.normals, vec![Vec3::Z; 3]);
    }

    fn any_coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![-10.0f32..10.0, any::<f32>(), Just(0.0)]
    }

    proptest! {
        #[test]
        fn normals_are_always_unit_and_finite(
            positions in prop::collection::vec(
                (any_coordinate(), any_coordinate(), any_coordinate()), 0..12),
            triangles in prop::collection::vec(prop::array::uniform3(0u32..14), 0..16),
            weighting in prop_oneof![
                Just(NormalWeighting::Average),
                Just(NormalWeighting::Area),
                Just(NormalWeighting::Angle),
            ],
        ) {
            let positions: Vec<Vec3> = positions.into_iter().map(Vec3::from).collect();
            let mut m = mesh(&positions, &triangles);
            let repairs = compute_vertex_normals(&mut m, weighting);
            prop_assert_eq!(m.normals.len(), positions.len());
            prop_assert!(repairs.degenerate_triangles <= triangles.len());
            prop_assert!(repairs.repaired_normals <= positions.len());
            for n in &m.normals {
                prop_assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-5, "{}", n);
            }
        }
    }
}
