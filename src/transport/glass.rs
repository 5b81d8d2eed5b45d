//! Glass at a shaded point: the Fresnel-weighted reflected and refracted rays, followed
//! through the scene (the reflection and transmission layers of `Components`).
//!
//! Which paths count, and what `max_bounces` means: `effects::refraction`. Each interface
//! splits the light into F along r = 2(n·v)n − v and 1 − F along Snell's t
//! (`geometry::vector::refract`; total internal reflection: F = 1); each ray finds the
//! nearest surface through the scene's BVH. A glass surface met from inside (its geometric
//! normal facing away from the ray's origin) is the way out: η is inverted there. A path
//! that would need more than `max_bounces` interface events brings no light. With an `ior`
//! per channel (dispersion) each channel follows its own path.

use super::lighting::{At, HitShader, Lighting};
use super::rays::{Origin, SceneRays};
use crate::effects::environment::EnvLighting;
use crate::geometry::vector::{reflect, refract};
use crate::scene::Model;
use crate::shading::classic::EvalCounts;
use crate::shading::glass::{Glass, fresnel_split};
use glam::Vec3;

/// What every ray of one shaded point needs.
struct Tracer<'a> {
    lighting: &'a Lighting,
    env: &'a EnvLighting,
    shade: HitShader<'a>,
    counts: &'a mut EvalCounts,
}

/// The light glass `g` sends from `at` (unit shading normal `at.n`, geometric normal `at.ng`
/// as the surface's outward one) towards unit `v`: (reflected, transmitted). `depth` counts
/// the interface events already on the path.
#[allow(clippy::too_many_arguments)]
pub fn glass_light(
    g: &Glass,
    lighting: &Lighting,
    env: &EnvLighting,
    shade: HitShader,
    at: &At<f32>,
    v: Vec3,
    counts: &mut EvalCounts,
    depth: u32,
) -> (Vec3, Vec3) {
    let mut tracer = Tracer { lighting, env, shade, counts };
    tracer.glass(g, at, v, depth, None)
}

impl Tracer<'_> {
    /// [`glass_light`]; `channel` is the colour channel whose path this is (dispersion), or
    /// `None` for all three.
    fn glass(&mut self, g: &Glass, at: &At<f32>, v: Vec3, depth: u32, channel: Option<usize>) -> (Vec3, Vec3) {
        match channel {
            Some(c) => self.interface(g, g.ior[c], at, v, depth, Some(c)),
            None if g.disperses() => {
                // One path per channel, each keeping its own channel.
                let (mut r, mut t) = (Vec3::ZERO, Vec3::ZERO);
                for c in 0..3 {
                    let (rc, tc) = self.interface(g, g.ior[c], at, v, depth, Some(c));
                    (r[c], t[c]) = (rc[c], tc[c]);
                }
                (r, t)
            }
            None => self.interface(g, g.ior.x, at, v, depth, None),
        }
    }

    /// One interface of glass with index `ior` (against air).
    fn interface(&mut self, g: &Glass, ior: f32, at: &At<f32>, v: Vec3, depth: u32, channel: Option<usize>) -> (Vec3, Vec3) {
        if depth >= self.lighting.tracing.max_bounces {
            return (Vec3::ZERO, Vec3::ZERO);
        }
        let ng = Vec3::from(at.ng);
        let n = Vec3::from(at.n);
        // The shading normal turned outward (the camera's may be flipped towards the viewer).
        let n_out = if n.dot(ng) < 0.0 { -n } else { n };
        // From inside (v behind the outward face), the interface is the way out: η inverted.
        // A thin surface has no inside: it always refracts into the glass.
        let entering = g.thin || ng.dot(v) >= 0.0;
        let mut n_side = if ng.dot(v) >= 0.0 { n_out } else { -n_out };
        if n_side.dot(v) <= 0.0 {
            // An interpolated normal turned away from v (a silhouette): the face's normal.
            n_side = if ng.dot(v) >= 0.0 { ng } else { -ng };
        }
        let eta = if entering { ior } else { 1.0 / ior };
        let (mut f, mut t_share) = fresnel_split(n_side.dot(v), eta);
        let refracted = refract(v, n_side, eta);
        if refracted.is_none() {
            // Total internal reflection (refract and Fresnel agree up to rounding at θ_c).
            (f, t_share) = (1.0, 0.0);
        }
        let origin = Origin { p: Vec3::from(at.p), ng, tri: at.tri, object: at.object };
        let r = reflect(v, n_side).normalize_or(n_side);
        let reflected = if f > 0.0 { f * self.follow(&origin, r, depth + 1, false, channel) } else { Vec3::ZERO };
        let transmitted = match refracted {
            Some(t) if t_share > 0.0 => t_share * g.tint * self.follow(&origin, t, depth + 1, g.thin, channel),
            _ => Vec3::ZERO,
        };
        (reflected, transmitted)
    }

    /// Radiance arriving at `origin` along unit `d`: the nearest surface (outside `origin`'s
    /// own object when `elsewhere`), or the environment. `depth` is the event count of the
    /// surface it finds.
    fn follow(&mut self, origin: &Origin, d: Vec3, depth: u32, elsewhere: bool, channel: Option<usize>) -> Vec3 {
        let env = self.env;
        let tracing = &self.lighting.tracing;
        let Some(bvh) = &tracing.rays else { return env.radiance(d) };
        let hit = if elsewhere { SceneRays::closest_elsewhere(bvh, origin, d) } else { bvh.closest(origin, d) };
        let Some((hit, s)) = hit.and_then(|h| Some((h, tracing.surface(&h)?))) else { return env.radiance(d) };
        let v = -d;
        let c = if let Model::Glass(g) = &s.material.model {
            // Glass is met from either side, whatever the culling: the face normal stays outward.
            let at = At { tri: hit.tri, object: hit.object, ng: s.face.into(), ..At::point(s.p, s.n) };
            let (r, tr) = self.glass(g, &at, v, depth, channel);
            s.material.emission + r + tr
        } else {
            // Any other surface as the camera would see it: its back black when back faces are culled.
            let Some((n, ng)) = s.facing(v, tracing.two_sided) else { return Vec3::ZERO };
            let at = At { tri: hit.tri, object: hit.object, ng: ng.into(), ..At::point(s.p, n) };
            (self.shade)(s.material, at, v, self.counts, depth).total()
        };
        if c.is_finite() { c } else { Vec3::ZERO }
    }
}
