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

/// The ray-query structure of a scene: a BVH per object.
#[derive(Debug, Clone, Default)]
pub struct SceneRays {
    /// Per object: its BVH (over its own triangles, indices from 0), its first triangle in
    /// the scene and whether it is convex or flat.
    objects: Vec<(Bvh, u32, bool)>,
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
                (Bvh::build(&g.positions, tris), o.first_triangle as u32, o.convex)
            })
            .collect();
        SceneRays { objects }
    }

    /// Nodes of all the objects' BVHs.
    pub fn node_count(&self) -> usize {
        self.objects.iter().map(|(b, _, _)| b.node_count()).sum()
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
        let n = if o.ng.dot(l) >= 0.0 { o.ng } else { -o.ng };
        let start = offset_ray_origin(o.p, n);
        let t_max = if distance.is_finite() { (distance * (1.0 - 1e-4) - (start - o.p).length()).max(0.0) } else { f32::MAX };
        if t_max <= 0.0 {
            return false;
        }
        self.objects.iter().enumerate().any(|(k, (bvh, first, convex))| {
            let own = k as u32 == o.object;
            if own && *convex {
                return false;
            }
            // The point's own triangle, in this BVH's numbering.
            let skip = if own && o.tri != u32::MAX { o.tri - first..o.tri - first + 1 } else { 0..0 };
            bvh.occluded(start, l, t_max, skip)
        })
    }
}

impl crate::effects::radiosity::RayQuery for SceneRays {
    fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        self.objects.iter().any(|(bvh, _, _)| bvh.occluded(origin, dir, t_max, 0..0))
    }

    fn closest_triangle(&self, origin: Vec3, dir: Vec3) -> Option<u32> {
        let mut best: Option<(f32, u32)> = None;
        for (bvh, first, _) in &self.objects {
            let t_max = best.map_or(f32::INFINITY, |b| b.0);
            if let Some(h) = bvh.closest_hit(origin, dir, t_max, 0..0) {
                best = Some((h.t, h.tri + first));
            }
        }
        best.map(|b| b.1)
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
        let mut live = 0u16;
        for j in 0..RayPacket::MAX {
            if active & (1 << j) == 0 {
                continue;
            }
            let o = &origins[j];
            let n = if o.ng.dot(l[j]) >= 0.0 { o.ng } else { -o.ng };
            let start = offset_ray_origin(o.p, n);
            let t_max = if distance[j].is_finite() { (distance[j] * (1.0 - 1e-4) - (start - o.p).length()).max(0.0) } else { f32::MAX };
            if t_max > 0.0 {
                packet.set(j, start, l[j], t_max, 0..0);
                live |= 1 << j;
            }
        }
        let mut hit = 0u16;
        for (k, (bvh, first, convex)) in self.objects.iter().enumerate() {
            let mut ask = live & !hit;
            for j in 0..RayPacket::MAX {
                if ask & (1 << j) == 0 {
                    continue;
                }
                let o = &origins[j];
                let own = k as u32 == o.object;
                if own && *convex {
                    ask &= !(1 << j);
                    continue;
                }
                // The point's own triangle, in this BVH's numbering.
                packet.skip[j] = if own && o.tri != u32::MAX { o.tri - first..o.tri - first + 1 } else { 0..0 };
            }
            if ask != 0 {
                hit |= bvh.occluded_packet(&packet, ask);
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
        for (k, (bvh, first, convex)) in self.objects.iter().enumerate() {
            let own = k as u32 == o.object;
            if own && *convex && leaving {
                continue;
            }
            let skip = if own && o.tri != u32::MAX { o.tri - first..o.tri - first + 1 } else { 0..0 };
            let t_max = best.map_or(f32::MAX, |b| b.t);
            if let Some(h) = bvh.closest_hit(start, d, t_max, skip) {
                best = Some(SceneHit { object: k as u32, tri: h.tri + first, b1: h.b1, b2: h.b2, t: h.t });
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
        for (k, (bvh, first, _)) in self.objects.iter().enumerate() {
            if k as u32 == o.object {
                continue;
            }
            let t_max = best.map_or(f32::MAX, |b| b.t);
            if let Some(h) = bvh.closest_hit(start, d, t_max, 0..0) {
                best = Some(SceneHit { object: k as u32, tri: h.tri + first, b1: h.b1, b2: h.b2, t: h.t });
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
