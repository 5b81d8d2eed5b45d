//! Triangle meshes: positions, per-vertex normals, triangle indices and per-corner uvs.
//!
//! Shapes and OBJ files produce a [`Mesh`]; smooth surfaces share vertices between
//! adjacent triangles so that averaging face normals (the course's vertex normals)
//! works by index adjacency. Hard edges (cube faces, a plane's border) use separate
//! vertices per face.

use crate::lesson::NormalTransform;
use glam::{Vec2, Vec3};

/// An indexed triangle mesh in object space. Triangles wind counter-clockwise seen
/// from outside (right-handed, y up).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position (empty until computed).
    pub normals: Vec<Vec3>,
    /// Triangles as three indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Texture coordinates per triangle corner (empty when the mesh has none). Per corner,
    /// not per vertex, so a seam needs no duplicated vertices and vertex normals stay smooth.
    pub uvs: Vec<[Vec2; 3]>,
}

/// What mesh repair found: counted, never fatal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MeshRepairs {
    /// Triangles with zero area (or non-finite vertices), ignored for normals and skipped by the rasterizer.
    pub degenerate_triangles: usize,
    /// Vertex normals that came out zero-length or non-finite and were replaced.
    pub repaired_normals: usize,
}

impl Mesh {
    /// This mesh with positions moved by `m` and normals by its inverse transpose
    /// (renormalized; a normal the transform collapses becomes +y).
    ///
    /// A mirroring transform (negative determinant) also reverses each triangle's
    /// winding, so triangles stay counter-clockwise seen from outside.
    pub fn transformed(&self, m: glam::Affine3A) -> Mesh {
        self.transformed_with(m, NormalTransform::InverseTranspose)
    }

    /// [`Mesh::transformed`], the normals carried as `how` says: [`NormalTransform::Naive`]
    /// multiplies them by the linear part itself (the mistake a lesson shows).
    pub fn transformed_with(&self, m: glam::Affine3A, how: NormalTransform) -> Mesh {
        let linear = glam::Mat3::from(m.matrix3);
        let det = linear.determinant();
        // The cofactor matrix is det·M⁻ᵀ: the same directions without dividing by det,
        // so it stays finite for singular transforms; the sign keeps normals outward.
        let [c0, c1, c2] = [linear.x_axis, linear.y_axis, linear.z_axis];
        let cofactor = glam::Mat3::from_cols(c1.cross(c2), c2.cross(c0), c0.cross(c1));
        let normal_matrix = match how {
            NormalTransform::InverseTranspose if det < 0.0 => -cofactor,
            NormalTransform::InverseTranspose => cofactor,
            NormalTransform::Naive => linear,
        };
        let mut triangles = self.triangles.clone();
        let mut uvs = self.uvs.clone();
        if det < 0.0 {
            triangles.iter_mut().for_each(|t| t.swap(1, 2));
            uvs.iter_mut().for_each(|t| t.swap(1, 2));
        }
        Mesh {
            positions: self.positions.iter().map(|&p| m.transform_point3(p)).collect(),
            normals: self.normals.iter().map(|&n| (normal_matrix * n).normalize_or(Vec3::Y)).collect(),
            triangles,
            uvs,
        }
    }

    /// True when every vertex lies on or behind the plane of every triangle (within 10⁻⁵ of
    /// the mesh's size; degenerate triangles have no plane and are passed over): a convex
    /// solid wound outwards, a convex cap of one, or a flat mesh. A ray leaving such a mesh
    /// on the side a triangle faces cannot meet it again, so its shadow rays may skip it
    /// whole, as those of the built-in sphere, cube and plane do, and a point whose smooth
    /// normal sees a light its flat triangle turns from is not shadowed by its own facets
    /// (the shadow terminator). False for an empty mesh, a non-finite vertex, and a mesh of
    /// more than [`MAX_CONVEX_TEST`] triangles × vertices, which is not tested.
    pub fn is_convex(&self) -> bool {
        let work = self.triangles.len() as u64 * self.positions.len() as u64;
        if self.triangles.is_empty() || work > MAX_CONVEX_TEST || !self.positions.iter().all(|p| p.is_finite()) {
            return false;
        }
        let (lo, hi) = self.positions.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let tolerance = 1e-5 * (hi - lo).length();
        let at = |i: u32| self.positions.get(i as usize).copied();
        self.triangles.iter().all(|t| {
            let (Some(a), Some(b), Some(c)) = (at(t[0]), at(t[1]), at(t[2])) else { return false };
            let Some(n) = (b - a).cross(c - a).try_normalize() else { return true };
            self.positions.iter().all(|p| n.dot(*p - a) <= tolerance)
        })
    }
}

/// The most triangles × vertices [`Mesh::is_convex`] compares (16.8 million dot products,
/// a few milliseconds): a larger mesh counts as not convex, so its shadow rays test its own
/// triangles as any other mesh's do.
pub const MAX_CONVEX_TEST: u64 = 1 << 24;

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Affine3A, Quat};

    fn triangle() -> Mesh {
        Mesh { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y], normals: vec![Vec3::Z; 3], triangles: vec![[0, 1, 2]], uvs: Vec::new() }
    }

    /// The face normal from the (transformed) winding, for comparison with the normals.
    fn winding_normal(m: &Mesh) -> Vec3 {
        let [a, b, c] = m.triangles[0].map(|i| m.positions[i as usize]);
        (b - a).cross(c - a).normalize()
    }

    #[test]
    fn naive_normals_agree_under_rotation_and_uniform_scale_and_tilt_under_a_stretch() {
        let mut mesh = triangle();
        mesh.positions[2] = Vec3::new(0.0, 1.0, 1.0);
        let n = winding_normal(&mesh);
        mesh.normals = vec![n; 3];
        let even = Affine3A::from_scale_rotation_translation(Vec3::splat(2.5), Quat::from_rotation_y(0.7), Vec3::ONE);
        let (right, naive) = (mesh.transformed(even), mesh.transformed_with(even, NormalTransform::Naive));
        assert!((right.normals[0] - naive.normals[0]).length() < 1e-6);
        let stretch = Affine3A::from_scale(Vec3::new(1.0, 4.0, 1.0));
        let (right, naive) = (mesh.transformed(stretch), mesh.transformed_with(stretch, NormalTransform::Naive));
        let edge = right.positions[2] - right.positions[0];
        assert!(right.normals[0].dot(edge).abs() < 1e-5, "the right normal is perpendicular");
        assert!(naive.normals[0].dot(edge).abs() > 0.3, "the naive one is not: {}", naive.normals[0].dot(edge));
    }

    #[test]
    fn transformed_normals_stay_perpendicular_and_agree_with_winding() {
        // A slanted triangle so non-uniform scale actually tilts its normal.
        let mut mesh = triangle();
        mesh.positions[2] = Vec3::new(0.0, 1.0, 1.0);
        let n = winding_normal(&mesh);
        mesh.normals = vec![n; 3];
        let transforms = [
            Affine3A::from_scale_rotation_translation(Vec3::new(3.0, 0.5, 2.0), Quat::from_rotation_y(0.7), Vec3::new(1.0, 2.0, 3.0)),
            Affine3A::from_scale(Vec3::new(-1.0, 2.0, 1.0)),
        ];
        for transform in transforms {
            let moved = mesh.transformed(transform);
            let expected = winding_normal(&moved);
            for &normal in &moved.normals {
                assert!(normal.abs_diff_eq(expected, 1e-5), "{normal} vs {expected}");
            }
        }
    }

    #[test]
    fn convex_meshes_are_told_from_the_rest() {
        use crate::scene::shapes;
        assert!(shapes::cube().is_convex() && shapes::uv_sphere(24, 12).is_convex() && shapes::icosphere(2).is_convex());
        assert!(shapes::plane().is_convex(), "flat");
        assert!(!shapes::torus(1.0, 0.3, 24, 12).is_convex());
        // The cylinders of lesson 35, whose caps share the rims with the sides.
        for file in ["cylinder.obj", "cylinder-groups.obj", "cube.obj"] {
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/meshes").join(file);
            assert!(crate::scene::obj::load_obj(&path).unwrap().mesh.is_convex(), "{file}");
        }
        // A dent (one corner pushed inwards), and a cube wound inside out, are not.
        let mut dented = shapes::cube();
        let corner = dented.positions[0];
        dented.positions.iter_mut().filter(|p| **p == corner).for_each(|p| *p *= 0.5);
        assert!(!dented.is_convex());
        let mut inside_out = shapes::cube();
        inside_out.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        assert!(!inside_out.is_convex());
        assert!(!Mesh::default().is_convex());
    }

    #[test]
    fn singular_transform_gives_finite_normals() {
        let moved = triangle().transformed(Affine3A::from_scale(Vec3::new(1.0, 1.0, 0.0)));
        assert!(moved.normals.iter().all(|&n| n == Vec3::Z));
        let moved = triangle().transformed(Affine3A::from_scale(Vec3::ZERO));
        assert!(moved.normals.iter().all(|&n| n == Vec3::Y));
    }
}
