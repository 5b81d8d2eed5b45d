//! The ray-query service: the one acceleration structure of a render's scene, built once
//! and asked by every ray — shadow rays (ray-cast shadows, area and sky light samples, the
//! fog's light shafts), the environment's visibility, mirror and glass rays, probe checks,
//! radiosity's form factors and final gather.
//!
//! One BVH per object (a two-level scene in its simplest form: the objects are few, so a
//! ray walks them in a list). A ray from a convex or flat object skips that object's BVH
//! whole: with one BVH over the scene it descended into the sphere's nodes around its own
//! origin only to skip their triangles (the `shadow-ray` bench: 56 → 30 ms a frame). The
//! render builds it at most once ([`crate::render`]'s dispatch, when the first pass asks) and
//! every pass shares it through an [`Arc`].

use crate::geometry::bvh::{Bvh, RayPacket};
use crate::geometry::triangle::offset_ray_origin;
use crate::geometry::{Analytic, Ray};
use crate::scene::Scene;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::Arc;

/// The count of nodes of the render's ray-query structure (`RenderStats::counters`).
pub const BVH_NODES: &str = "BVH nodes";

/// What a ray query starts from: a point on a surface (or in a medium).
#[derive(Debug, Clone, Copy)]
pub struct Origin {
    /// The point.
    pub p: Vec3,
    /// Unit geometric normal (the face's; for a vertex, its shading normal).
    pub ng: Vec3,
    /// Its triangle, or `u32::MAX` for a vertex.
    pub tri: u32,
    /// Its object.
    pub object: u32,
}

impl Origin {
    /// A placeholder for a lane that asks nothing.
    pub const NONE: Origin = Origin { p: Vec3::ZERO, ng: Vec3::Z, tri: u32::MAX, object: u32::MAX };
}

/// A shadow ray ready for the scene's queries: started off its surface, bounded short of
/// the light, and knowing whose triangle it leaves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowRay {
    /// The origin moved off the surface (Wächter & Binder 2019).
    pub start: Vec3,
    /// Unit direction towards the light.
    pub dir: Vec3,
    /// The open bound on t: just short of the light (f32::MAX for a directional light).
    pub t_max: f32,
    /// The object it leaves.
    pub object: u32,
    /// The triangle it leaves (`u32::MAX` for none).
    pub tri: u32,
}

impl ShadowRay {
    /// The ray from `o` towards the light `distance` away along unit `l` (infinite for a
    /// directional light): the origin moves off the surface along the geometric normal on the
    /// side the ray leaves, so rounding never shadows a surface by itself; the ray stops just
    /// short of the light, so an emitter modelled as an object does not block its own light.
    /// `None` when nothing is left between the two.
    #[inline]
    pub fn new(o: &Origin, l: Vec3, distance: f32) -> Option<ShadowRay> {
        let n = if o.ng.dot(l) >= 0.0 { o.ng } else { -o.ng };
        let start = offset_ray_origin(o.p, n);
        let t_max = if distance.is_finite() { (distance * (1.0 - 1e-4) - (start - o.p).length()).max(0.0) } else { f32::MAX };
        (t_max > 0.0).then_some(ShadowRay { start, dir: l, t_max, object: o.object, tri: o.tri })
    }
}

/// The ray-query structure of a scene: a BVH per object.
#[derive(Debug, Clone, Default)]
pub struct SceneRays {
    /// Per object: its BVH and what a ray asks before it.
    objects: Vec<ObjectRays>,
}

/// One object's part of the ray-query structure.
#[derive(Debug, Clone)]
struct ObjectRays {
    /// Its BVH, over its own triangles (indices from 0).
    bvh: Bvh,
    /// Its first triangle in the scene's numbering.
    first: u32,
    /// Convex or flat: a ray leaving its surface on the side it faces cannot meet it again.
    convex: bool,
    /// The centre of a ball holding every triangle of the object.
    centre: Vec3,
    /// That ball's radius, enlarged by a margin far above the rounding of [`ObjectRays::misses`].
    radius: f32,
}

impl ObjectRays {
    /// True when the ray `o + t·d`, t in (0, t_max), cannot meet the object: it passes its
    /// bounding ball, or the ball lies behind the origin or beyond t_max. Conservative (the
    /// ball holds the triangles, its radius has a margin), so it changes no answer; it turns
    /// the rays that enter an object's box but miss the object itself (a sphere fills 52% of
    /// its box) into a few multiplications.
    #[inline(always)]
    fn misses(&self, o: Vec3, d: Vec3, t_max: f32) -> bool {
        let oc = self.centre - o;
        let dd = d.length_squared();
        let b = oc.dot(d) / dd;
        // The distance from the centre to the ray's line, from the perpendicular part itself
        // (|oc|² − b² |d|² would cancel for a far object).
        let perp = oc - d * b;
        let r2 = self.radius * self.radius;
        let outside = oc.length_squared() > r2;
        perp.length_squared() > r2 || (outside && b < 0.0) || (outside && b - self.radius / dd.sqrt() > t_max)
    }
}

impl SceneRays {
    /// The pass: a BVH over each object's triangles, built in parallel.
    pub fn build(scene: &Scene) -> SceneRays {
        let g = &scene.geometry;
        let objects = g
            .objects
            .par_iter()
            .map(|o| {
                let tris = &g.triangles[o.first_triangle..o.first_triangle + o.triangles];
                // The object's ball: its vertices lie within `radius` of `centre` (scene::build),
                // so do its triangles; the margin covers the f32 rounding of the test.
                let radius = if o.radius.is_finite() && o.centre.is_finite() {
                    o.radius * (1.0 + 1e-4) + 1e-4 * (o.centre.abs().max_element() + o.radius).max(1e-3)
                } else {
                    f32::INFINITY
                };
                ObjectRays {
                    bvh: Bvh::build(&g.positions, tris),
                    first: o.first_triangle as u32,
                    convex: o.convex,
                    centre: o.centre,
                    radius,
                }
            })
            .collect();
        SceneRays { objects }
    }

    /// Nodes of all the objects' BVHs.
    pub fn node_count(&self) -> usize {
        self.objects.iter().map(|ob| ob.bvh.node_count()).sum()
    }

    /// True when something lies between `o` and the light `distance` away along `l` (unit;
    /// `distance` infinite for a directional light).
    ///
    /// The origin moves off the surface along the geometric normal on the side the ray
    /// leaves (Wächter & Binder 2019, Ray Tracing Gems ch. 6), so rounding never shadows a
    /// surface by itself; the ray stops just short of the light, so an emitter modelled as
    /// an object does not block its own light. It ignores the point's own object when that
    /// is convex or flat (it cannot block itself where N·L > 0, and this removes the
    /// shadow-terminator artefact of tessellated spheres), else the point's own triangle.
    #[inline]
    pub fn occluded(&self, o: &Origin, l: Vec3, distance: f32) -> bool {
        ShadowRay::new(o, l, distance).is_some_and(|r| self.blocked(&r))
    }

    /// True when something blocks the prepared shadow ray `r` ([`ShadowRay::new`]).
    #[inline]
    pub fn blocked(&self, r: &ShadowRay) -> bool {
        self.objects.iter().enumerate().any(|(k, ob)| {
            let own = k as u32 == r.object;
            if (own && ob.convex) || ob.misses(r.start, r.dir, r.t_max) {
                return false;
            }
            // The point's own triangle, in this BVH's numbering.
            let skip = if own && r.tri != u32::MAX { r.tri - ob.first..r.tri - ob.first + 1 } else { 0..0 };
            ob.bvh.occluded(r.start, r.dir, r.t_max, skip)
        })
    }
}

impl crate::effects::radiosity::RayQuery for SceneRays {
    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        self.objects.iter().any(|ob| !ob.misses(origin, dir, t_max) && ob.bvh.occluded(origin, dir, t_max, 0..0))
    }

    fn closest_triangle(&self, origin: Vec3, dir: Vec3) -> Option<u32> {
        let mut best: Option<(f32, u32)> = None;
        for ob in &self.objects {
            let t_max = best.map_or(f32::INFINITY, |b| b.0);
            if ob.misses(origin, dir, t_max) {
                continue;
            }
            if let Some(h) = ob.bvh.closest_hit(origin, dir, t_max, 0..0) {
                best = Some((h.t, h.tri + ob.first));
            }
        }
        best.map(|b| b.1)
    }

    fn kind(&self) -> &'static str {
        "scene rays"
    }
}

impl SceneRays {
    /// [`SceneRays::occluded`] for up to sixteen rays at once, as a packet through each
    /// object's BVH (`Bvh::occluded_packet`): bit j of the answer is lane j's
    /// `occluded(&origins[j], l[j], distance[j])`, for the lanes whose bit is set in `active`.
    /// Each lane's ray starts and stops where the single ray would; the packet gives the
    /// single-ray answer bit for bit (tested in `geometry::bvh`).
    pub fn occluded_packet(
        &self,
        origins: &[Origin; RayPacket::MAX],
        l: &[Vec3; RayPacket::MAX],
        distance: &[f32; RayPacket::MAX],
        active: u16,
    ) -> u16 {
        let mut packet = RayPacket::default();
        let mut owners = [(u32::MAX, u32::MAX); RayPacket::MAX];
        let mut live = 0u16;
        for j in 0..RayPacket::MAX {
            if active & (1 << j) != 0
                && let Some(r) = ShadowRay::new(&origins[j], l[j], distance[j])
            {
                packet.set(j, r.start, r.dir, r.t_max, 0..0);
                owners[j] = (r.object, r.tri);
                live |= 1 << j;
            }
        }
        self.blocked_packet(&mut packet, &owners, live)
    }

    /// [`SceneRays::blocked`] for the rays of `packet` whose bit is set in `active`, each
    /// leaving the (object, triangle) of `owners` (the packet's skip ranges are set here).
    pub fn blocked_packet(&self, packet: &mut RayPacket, owners: &[(u32, u32); RayPacket::MAX], active: u16) -> u16 {
        let mut hit = 0u16;
        for (k, ob) in self.objects.iter().enumerate() {
            let mut ask = active & !hit;
            for (j, &(object, tri)) in owners.iter().enumerate() {
                if ask & (1 << j) == 0 {
                    continue;
                }
                let own = k as u32 == object;
                if (own && ob.convex) || ob.misses(packet.origin(j), packet.dir(j), packet.t_max[j]) {
                    ask &= !(1 << j);
                    continue;
                }
                // The point's own triangle, in this BVH's numbering.
                packet.skip[j] = if own && tri != u32::MAX { tri - ob.first..tri - ob.first + 1 } else { 0..0 };
            }
            if ask != 0 {
                hit |= ob.bvh.occluded_packet(packet, ask);
            }
        }
        hit
    }
}

/// A closest hit in the scene: the object, the triangle (scene numbering), its barycentrics
/// (of vertices 1 and 2) and the distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneHit {
    /// The object hit.
    pub object: u32,
    /// The triangle hit, in the scene's numbering.
    pub tri: u32,
    /// Barycentric weight of the triangle's vertex 1.
    pub b1: f32,
    /// Barycentric weight of the triangle's vertex 2.
    pub b2: f32,
    /// Distance along the (unit) direction.
    pub t: f32,
}

impl SceneRays {
    /// The nearest surface along the unit direction `d` from `o` (offset off the surface as
    /// for a shadow ray; the point's own triangle is skipped, and its whole object when that
    /// is convex or flat and `d` leaves on the side the normal faces, where it cannot hit itself).
    pub fn closest(&self, o: &Origin, d: Vec3) -> Option<SceneHit> {
        let leaving = o.ng.dot(d) >= 0.0;
        let n = if leaving { o.ng } else { -o.ng };
        let start = offset_ray_origin(o.p, n);
        let mut best: Option<SceneHit> = None;
        for (k, ob) in self.objects.iter().enumerate() {
            let own = k as u32 == o.object;
            let t_max = best.map_or(f32::MAX, |b| b.t);
            if (own && ob.convex && leaving) || ob.misses(start, d, t_max) {
                continue;
            }
            let skip = if own && o.tri != u32::MAX { o.tri - ob.first..o.tri - ob.first + 1 } else { 0..0 };
            if let Some(h) = ob.bvh.closest_hit(start, d, t_max, skip) {
                best = Some(SceneHit { object: k as u32, tri: h.tri + ob.first, b1: h.b1, b2: h.b2, t: h.t });
            }
        }
        best
    }

    /// [`SceneRays::closest`] that ignores the point's whole object: the refracted ray of a
    /// `thin` glass surface, which never meets its own object again.
    pub fn closest_elsewhere(&self, o: &Origin, d: Vec3) -> Option<SceneHit> {
        let n = if o.ng.dot(d) >= 0.0 { o.ng } else { -o.ng };
        let start = offset_ray_origin(o.p, n);
        let mut best: Option<SceneHit> = None;
        for (k, ob) in self.objects.iter().enumerate() {
            let t_max = best.map_or(f32::MAX, |b| b.t);
            if k as u32 == o.object || ob.misses(start, d, t_max) {
                continue;
            }
            if let Some(h) = ob.bvh.closest_hit(start, d, t_max, 0..0) {
                best = Some(SceneHit { object: k as u32, tri: h.tri + ob.first, b1: h.b1, b2: h.b2, t: h.t });
            }
        }
        best
    }
}

/// What shadow rays are traced against.
#[derive(Debug, Clone)]
pub enum Occluders {
    /// The scene's triangles, a BVH per object (the renderer): the render's one [`SceneRays`].
    Meshes(Arc<SceneRays>),
    /// Exact spheres and planes, one per object (the reference ray cast of `cost`).
    Analytic(Vec<Analytic>),
}

impl Occluders {
    /// True when something lies between `o` and the light `distance` away along `l`
    /// ([`SceneRays::occluded`]; analytic shapes are all convex or flat, so a ray ignores
    /// its own object's shape, and starts 10⁻⁵ of the scene's scale off the surface).
    #[inline]
    pub fn occluded(&self, o: &Origin, l: Vec3, distance: f32) -> bool {
        match self {
            Occluders::Meshes(bvh) => bvh.occluded(o, l, distance),
            Occluders::Analytic(shapes) => {
                let n = if o.ng.dot(l) >= 0.0 { o.ng } else { -o.ng };
                let p = o.p.as_dvec3();
                let origin = p + n.as_dvec3() * (1e-5 * p.length().max(1.0));
                let ray = Ray { origin, dir: l.as_dvec3() };
                let t_max = if distance.is_finite() { distance as f64 * (1.0 - 1e-4) } else { f64::INFINITY };
                shapes.iter().enumerate().any(|(k, shape)| {
                    k as u32 != o.object && shape.intersect(&ray).into_iter().flatten().any(|(t, _)| t > 0.0 && t < t_max)
                })
            }
        }
    }

    /// Nodes of the BVHs (0 for analytic shapes).
    pub fn node_count(&self) -> usize {
        match self {
            Occluders::Meshes(bvh) => bvh.node_count(),
            Occluders::Analytic(_) => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sampling::hash;
    use std::path::Path;

    /// A ball on a floor, a torus (not convex) beside it and a thin box: shadow rays from
    /// every object's surface in every direction.
    fn scene() -> Scene {
        let text = r#"
[camera]
position = [0, 2, 6]
size = [8, 8]
[[object]]
shape = "uv_sphere"
segments = 32
rings = 16
translate = [0, 0.2, 0]
material = "m"
[[object]]
shape = "plane"
scale = 3
translate = [0, -1, 0]
material = "m"
[[object]]
shape = "torus"
major_radius = 0.8
minor_radius = 0.25
translate = [1.5, -0.5, 0.5]
material = "m"
[[object]]
shape = "cube"
scale = [0.1, 1.0, 1.5]
translate = [-1.6, 0, 0]
material = "m"
[material.m]
model = "lambert"
diffuse = 0.8
[[light]]
kind = "directional"
direction = [-1, -1, -1]
"#;
        let lesson = crate::lesson::parse(text, Path::new("rays.toml"), &[]).unwrap();
        crate::scene::build::build(&lesson).unwrap()
    }

    /// Random shadow rays leaving random triangles' surfaces (some towards the inside), and
    /// from points in the air.
    fn rays(scene: &Scene, n: u32) -> Vec<(Origin, Vec3, f32)> {
        let g = &scene.geometry;
        let u = |k: u32| hash(k) as f32 / u32::MAX as f32;
        (0..n)
            .map(|k| {
                let t = (hash(k * 7 + 1) as usize) % g.triangles.len();
                let [a, b, c] = g.triangles[t].map(|i| g.positions[i as usize]);
                let (s, r) = (u(k * 7 + 2), u(k * 7 + 3));
                let (s, r) = if s + r > 1.0 { (1.0 - s, 1.0 - r) } else { (s, r) };
                let p = a + (b - a) * s + (c - a) * r;
                let dir = Vec3::new(u(k * 7 + 4) - 0.5, u(k * 7 + 5) - 0.5, u(k * 7 + 6) - 0.5).normalize_or(Vec3::Y);
                let distance = if k % 3 == 0 { f32::INFINITY } else { 0.1 + 6.0 * u(k * 7 + 7) };
                let o = if k % 11 == 0 {
                    Origin { p: p + Vec3::Y * 0.3, ng: dir, tri: u32::MAX, object: u32::MAX }
                } else {
                    Origin { p, ng: g.face_normals[t], tri: t as u32, object: g.object_of_triangle(t) }
                };
                (o, dir, distance)
            })
            .collect()
    }

    /// The ball test only ever turns away rays the BVH would not have stopped: with it and
    /// without it (each object's BVH asked directly) every ray gets the same answer, and many
    /// rays are turned away by it.
    #[test]
    fn the_bounding_ball_changes_no_answer() {
        let s = scene();
        let r = SceneRays::build(&s);
        let mut turned_away = 0;
        for (o, l, d) in rays(&s, 40_000) {
            let Some(ray) = ShadowRay::new(&o, l, d) else { continue };
            let direct = r.objects.iter().enumerate().any(|(k, ob)| {
                let own = k as u32 == ray.object;
                if own && ob.convex {
                    return false;
                }
                let skip = if own && ray.tri != u32::MAX { ray.tri - ob.first..ray.tri - ob.first + 1 } else { 0..0 };
                ob.bvh.occluded(ray.start, ray.dir, ray.t_max, skip)
            });
            assert_eq!(r.blocked(&ray), direct, "{ray:?}");
            turned_away += r.objects.iter().filter(|ob| ob.misses(ray.start, ray.dir, ray.t_max)).count();
        }
        assert!(turned_away > 10_000, "the ball test turned away only {turned_away} object queries");
    }

    /// A packet of sixteen shadow rays (any mix of objects, triangles, lengths and inactive
    /// lanes) gives each lane the single ray's answer.
    #[test]
    fn packets_give_each_ray_the_single_answer() {
        let s = scene();
        let r = SceneRays::build(&s);
        let all = rays(&s, 16_000);
        let (mut blocked, mut seen) = (0, 0);
        for (c, chunk) in all.chunks(16).enumerate() {
            let origins: [Origin; 16] = std::array::from_fn(|j| chunk[j].0);
            let l: [Vec3; 16] = std::array::from_fn(|j| chunk[j].1);
            let d: [f32; 16] = std::array::from_fn(|j| chunk[j].2);
            let active = if c % 4 == 0 { (hash(c as u32) & 0xffff) as u16 } else { u16::MAX };
            let got = r.occluded_packet(&origins, &l, &d, active);
            for j in 0..16 {
                let want = active & (1 << j) != 0 && r.occluded(&origins[j], l[j], d[j]);
                assert_eq!(got & (1 << j) != 0, want, "packet {c} lane {j}");
                blocked += want as u32;
                seen += (active & (1 << j) != 0) as u32;
            }
        }
        // Both answers occur often enough to mean something.
        assert!(blocked > seen / 10 && blocked < seen * 9 / 10, "{blocked} blocked of {seen}");
    }
}
