//! The analytic sphere and plane under an affine transform, intersected exactly in f64.
//!
//! The unit sphere and the square [−1, 1]² in xz at y = 0 (facing +y) are the shapes the
//! meshes `uv_sphere`/`icosphere` and `plane` approximate. Normals move by the cofactor
//! matrix det·M⁻ᵀ (as mesh normals do), so a non-uniformly scaled sphere is an exact ellipsoid.

use super::ray::Ray;
use glam::{DAffine3, DMat3, DVec3};

/// Which analytic surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnalyticKind {
    /// The unit sphere.
    Sphere,
    /// The square [−1, 1]² in xz at y = 0, facing +y.
    Plane,
}

/// One analytic surface placed in the world, ready for intersection.
#[derive(Debug, Clone, Copy)]
pub struct Analytic {
    /// Which surface.
    pub kind: AnalyticKind,
    /// World → object.
    to_object: DAffine3,
    /// Object normal → world normal direction (det·M⁻ᵀ with the sign of det, so outward stays outward).
    normal_matrix: DMat3,
}

impl Analytic {
    /// `kind` under the object → world map `m`; `None` when `m` cannot be inverted.
    pub fn new(kind: AnalyticKind, m: DAffine3) -> Option<Analytic> {
        let det = m.matrix3.determinant();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        // The cofactor matrix det·M⁻ᵀ, sign-corrected, as `Mesh::transformed` uses.
        let [c0, c1, c2] = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis];
        let cofactor = DMat3::from_cols(c1.cross(c2), c2.cross(c0), c0.cross(c1));
        let normal_matrix = if det < 0.0 { -cofactor } else { cofactor };
        Some(Analytic { kind, to_object: m.inverse(), normal_matrix })
    }

    /// The ray parameters where `ray` meets this surface, ascending, with the object-space
    /// point of each (any sign of t: the caller decides which it accepts).
    pub fn intersect(&self, ray: &Ray) -> [Option<(f64, DVec3)>; 2] {
        // An affine map keeps the ray parameter: intersect in object space.
        let oo = self.to_object.transform_point3(ray.origin);
        let od = self.to_object.transform_vector3(ray.dir);
        match self.kind {
            AnalyticKind::Sphere => {
                // |oo + t·od|² = 1: a t² + 2 b t + c = 0, solved without cancellation
                // (Press et al., Numerical Recipes, §5.6).
                let a = od.length_squared();
                let b = oo.dot(od);
                let c = oo.length_squared() - 1.0;
                let disc = b * b - a * c;
                if disc < 0.0 || a == 0.0 {
                    return [None, None];
                }
                let q = -(b + disc.sqrt().copysign(b));
                let (mut t0, mut t1) = (q / a, if q != 0.0 { c / q } else { q / a });
                if t0 > t1 {
                    std::mem::swap(&mut t0, &mut t1);
                }
                [Some((t0, oo + od * t0)), Some((t1, oo + od * t1))]
            }
            AnalyticKind::Plane => {
                if od.y == 0.0 {
                    return [None, None];
                }
                let t = -oo.y / od.y;
                let p = oo + od * t;
                if p.x.abs() <= 1.0 && p.z.abs() <= 1.0 { [Some((t, p)), None] } else { [None, None] }
            }
        }
    }

    /// The unit outward world normal at object-space point `p` on the surface.
    pub fn normal(&self, p: DVec3) -> DVec3 {
        let object_normal = match self.kind {
            AnalyticKind::Sphere => p,
            AnalyticKind::Plane => DVec3::Y,
        };
        (self.normal_matrix * object_normal).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray { origin: DVec3::from(o), dir: DVec3::from(d) }
    }

    #[test]
    fn unit_sphere_is_hit_at_distance_minus_one_and_plus_one() {
        let s = Analytic::new(AnalyticKind::Sphere, DAffine3::IDENTITY).unwrap();
        let [a, b] = s.intersect(&ray([0.0, 0.0, 5.0], [0.0, 0.0, -1.0]));
        let ((ta, pa), (tb, _)) = (a.unwrap(), b.unwrap());
        assert_eq!((ta, tb), (4.0, 6.0));
        assert_eq!(s.normal(pa), DVec3::Z);
        // A ray that passes beside the sphere misses.
        assert_eq!(s.intersect(&ray([0.0, 1.5, 5.0], [0.0, 0.0, -1.0])), [None, None]);
    }

    #[test]
    fn scaled_sphere_is_an_ellipsoid_with_cofactor_normals() {
        let m = DAffine3::from_scale(DVec3::new(2.0, 1.0, 1.0));
        let s = Analytic::new(AnalyticKind::Sphere, m).unwrap();
        // Along x the ellipsoid reaches 2.
        let (t, p) = s.intersect(&ray([5.0, 0.0, 0.0], [-1.0, 0.0, 0.0]))[0].unwrap();
        assert!((t - 3.0).abs() < 1e-12);
        assert!((s.normal(p) - DVec3::X).length() < 1e-12);
        // At 45° in object space the normal leans towards y (the short axis): (1/2, 1, 0) normalized.
        let q = DVec3::new(1.0, 1.0, 0.0).normalize();
        let expect = DVec3::new(0.5 * q.x, q.y, 0.0).normalize();
        assert!((s.normal(q) - expect).length() < 1e-12);
        // A singular map has no analytic surface.
        assert!(Analytic::new(AnalyticKind::Sphere, DAffine3::from_scale(DVec3::new(1.0, 0.0, 1.0))).is_none());
    }

    #[test]
    fn plane_is_the_unit_square_facing_up() {
        let p = Analytic::new(AnalyticKind::Plane, DAffine3::IDENTITY).unwrap();
        let (t, q) = p.intersect(&ray([0.5, 2.0, 0.5], [0.0, -1.0, 0.0]))[0].unwrap();
        assert_eq!((t, p.normal(q)), (2.0, DVec3::Y));
        assert_eq!(p.intersect(&ray([1.5, 2.0, 0.0], [0.0, -1.0, 0.0])), [None, None]);
        // Parallel to the plane: no hit, no division by zero.
        assert_eq!(p.intersect(&ray([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])), [None, None]);
    }
}
