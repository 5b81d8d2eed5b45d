//! Ray-cast shadows: one any-hit ray per light (sample) per shaded point, the exact hard
//! shadow that the shadow map and the cost ladders are measured against.

use super::Origin;
use crate::geometry::bvh::Bvh;
use crate::geometry::triangle::offset_ray_origin;
use crate::scene::Scene;
use glam::Vec3;

/// The pass: the BVH over every triangle of the scene.
pub fn build(scene: &Scene) -> Bvh {
    Bvh::build(&scene.geometry.positions, &scene.geometry.triangles)
}

/// True when something lies between `o` and the light `distance` away along `l` (unit;
/// `distance` infinite for a directional light), ignoring the triangles `skip`.
///
/// The origin moves off the surface along the geometric normal on the side the ray leaves
/// (Wächter & Binder 2019, Ray Tracing Gems ch. 6), so rounding never shadows a surface
/// by itself; the ray stops just short of the light, so an emitter modelled as an object
/// does not block its own light.
#[inline]
pub fn occluded(bvh: &Bvh, o: &Origin, l: Vec3, distance: f32, skip: std::ops::Range<u32>) -> bool {
    let n = if o.ng.dot(l) >= 0.0 { o.ng } else { -o.ng };
    let start = offset_ray_origin(o.p, n);
    let t_max = if distance.is_finite() { (distance * (1.0 - 1e-4) - (start - o.p).length()).max(0.0) } else { f32::MAX };
    t_max > 0.0 && bvh.occluded(start, l, t_max, skip)
}
