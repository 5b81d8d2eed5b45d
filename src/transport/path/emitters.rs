//! Emitting surfaces as lights of the path tracer: every triangle whose material has an
//! `emission`, chosen by area for next-event estimation, and the solid-angle pdf with which
//! that strategy would have found a point a BSDF-sampled ray hit (for multiple importance
//! sampling).
//!
//! One-sided, as radiosity reads them: a triangle emits L_emi towards its face normal.

use crate::scene::Scene;
use glam::{Vec2, Vec3};

/// The scene's emitting triangles and their cumulative areas.
#[derive(Debug, Clone, Default)]
pub struct Emitters {
    /// Triangle indices (scene numbering).
    triangles: Vec<u32>,
    /// Cumulative area up to and including each triangle.
    cdf: Vec<f32>,
    /// Their total area A.
    total: f32,
}

/// A point chosen on an emitter, seen from a shaded point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmitterSample {
    /// Unit direction towards the point.
    pub l: Vec3,
    /// Distance to it.
    pub distance: f32,
    /// The radiance it sends along −l.
    pub radiance: Vec3,
    /// The solid-angle pdf of this choice, r²/(A cos θ_e) (1/sr).
    pub pdf: f32,
}

impl Emitters {
    /// The emitting triangles of `scene` (zero-area ones dropped).
    pub fn new(scene: &Scene) -> Emitters {
        let g = &scene.geometry;
        let mut e = Emitters::default();
        for (t, &m) in g.material.iter().enumerate() {
            if scene.materials[m as usize].emission == Vec3::ZERO {
                continue;
            }
            let a = area(scene, t);
            if a > 0.0 && a.is_finite() {
                e.total += a;
                e.triangles.push(t as u32);
                e.cdf.push(e.total);
            }
        }
        e
    }

    /// True when no surface emits.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// A point chosen by area (`u_pick` the triangle, `u` the point in it, uniform) seen from
    /// `p`; `None` when nothing emits or the point's back faces `p`.
    pub fn sample(&self, scene: &Scene, p: Vec3, u_pick: f32, u: Vec2) -> Option<EmitterSample> {
        if self.is_empty() {
            return None;
        }
        let target = u_pick * self.total;
        let i = self.cdf.partition_point(|&c| c <= target).min(self.triangles.len() - 1);
        let t = self.triangles[i] as usize;
        let g = &scene.geometry;
        let [a, b, c] = g.triangles[t].map(|k| g.positions[k as usize]);
        // The square folded onto the triangle: uniform in area.
        let (s, r) = if u.x + u.y > 1.0 { (1.0 - u.x, 1.0 - u.y) } else { (u.x, u.y) };
        let q = a + (b - a) * s + (c - a) * r;
        let to = q - p;
        let r2 = to.length_squared();
        if !(r2 > 1e-20 && r2.is_finite()) {
            return None;
        }
        let distance = r2.sqrt();
        let l = to / distance;
        let pdf = self.pdf(g.face_normals[t], l, distance)?;
        let radiance = scene.materials[g.material[t] as usize].emission;
        Some(EmitterSample { l, distance, radiance, pdf })
    }

    /// The solid-angle pdf r²/(A cos θ_e) of reaching, along unit `l` at `distance`, a point of
    /// an emitter with face normal `face`; `None` when its back faces the ray (it sends nothing).
    pub fn pdf(&self, face: Vec3, l: Vec3, distance: f32) -> Option<f32> {
        let cos_e = -face.dot(l);
        (cos_e > 0.0 && self.total > 0.0).then(|| distance * distance / (self.total * cos_e))
    }
}

/// Triangle `t`'s area.
fn area(scene: &Scene, t: usize) -> f32 {
    let g = &scene.geometry;
    let [a, b, c] = g.triangles[t].map(|k| g.positions[k as usize]);
    0.5 * (b - a).cross(c - a).length()
}
