//! The environment's share of a shaded point: image-based lighting of a physically based
//! material and the ray of a mirror (the reflection layer of `Components`).
//!
//! A mirror's ray r = 2(n·v)n − v finds the nearest surface through the scene's BVH; that
//! surface is shaded through the same seam as a camera sample ([`shade_point`] with its
//! lights and its own environment light), seen from −r; a ray that finds nothing, or one
//! past [`MAX_MIRROR_DEPTH`] mirrors, takes the environment's radiance.

use super::lighting::{At, HitShader, Lighting};
use super::rays::Origin;
use crate::effects::environment::{EnvLighting, MAX_MIRROR_DEPTH, reference};
use crate::geometry::sampling::{hash3, point_seed};
use crate::geometry::vector::reflect;
use crate::lesson::settings::{Ibl, Reflections};
use crate::scene::{Material, Model};
use crate::shading::classic::EvalCounts;
use glam::Vec3;

/// The environment's light leaving point `at` (unit normal `at.n`) of material `m` towards
/// unit `v`: ∫ L_env f cos dω for a BRDF, tint ⊗ L_i(r) for a mirror, 0 for classic models.
/// `depth` counts the mirrors already followed.
#[allow(clippy::too_many_arguments)]
pub fn environment_light(
    m: &Material,
    lighting: &Lighting,
    env: &EnvLighting,
    shade: HitShader,
    at: &At<f32>,
    v: Vec3,
    counts: &mut EvalCounts,
    depth: u32,
) -> Vec3 {
    let n = Vec3::from(at.n);
    let origin = Origin { p: Vec3::from(at.p), ng: Vec3::from(at.ng), tri: at.tri, object: at.object };
    match &m.model {
        Model::Classic(_) => Vec3::ZERO,
        Model::Physical(brdf) => {
            let Some(e) = &env.env else { return Vec3::ZERO };
            if let (Some(pre), Some(split)) = (&env.prefiltered, env.split.iter().find(|s| s.brdf == *brdf)) {
                // The split sum: irradiance for the diffuse part, one prefiltered lookup for the specular.
                let n_map = e.to_map(n);
                let irradiance = if env.ibl == Ibl::Sh { pre.sh.irradiance(n_map) } else { pre.irradiance_map(n_map) };
                let mut c = split.diffuse * irradiance * std::f32::consts::FRAC_1_PI;
                let n_v = n.dot(v);
                if n_v > 0.0 && split.specular.iter().any(|s| *s != Vec3::ZERO) {
                    let r = e.to_map(reflect(v, n).normalize_or(n));
                    c += split.specular_albedo(n_v) * pre.radiance_lod(r, split.roughness);
                }
                return c * e.scale;
            }
            let seed = hash3(point_seed(origin.p), 0xe4f1_a9c3, depth);
            let visible = |l: Vec3| lighting.tracing.rays.as_ref().is_none_or(|b| !b.occluded(&origin, l, f32::INFINITY));
            reference::estimate(brdf, n, v, e, env.distribution.as_ref(), env.samples, seed, visible)
        }
        // Glass has its own rays (`render::glass`), split into reflection and transmission.
        Model::Glass(_) => Vec3::ZERO,
        Model::Mirror(mirror) => {
            let r = reflect(v, n).normalize_or(n);
            // Inside a probe's box the probe answers (`[render] reflections`); elsewhere the ray is traced.
            if let Some(probes) = lighting.tracing.probes.as_ref() {
                let c = if probes.reflections == Reflections::ProbeProjector {
                    // The probe as a projector: the real surface along R, its radiance as the probe saw it.
                    let tracing = &lighting.tracing;
                    let hit = tracing.rays.as_ref().and_then(|b| b.closest(&origin, r)).and_then(|h| tracing.surface(&h)).map(|s| s.p);
                    probes.projected(origin.p, hit, r)
                } else {
                    probes.radiance(origin.p, r)
                };
                if let Some(c) = c {
                    return mirror.tint * c;
                }
            }
            mirror.tint * trace(lighting, env, shade, &origin, r, counts, depth)
        }
    }
}

/// Radiance arriving at `origin` along the unit direction `r`: the nearest surface shaded as
/// seen from −r, or the environment.
fn trace(lighting: &Lighting, env: &EnvLighting, shade: HitShader, origin: &Origin, r: Vec3, counts: &mut EvalCounts, depth: u32) -> Vec3 {
    let tracing = &lighting.tracing;
    let Some(bvh) = tracing.rays.as_ref().filter(|_| depth < MAX_MIRROR_DEPTH) else { return env.radiance(r) };
    let Some((hit, s)) = bvh.closest(origin, r).and_then(|h| Some((h, tracing.surface(&h)?))) else { return env.radiance(r) };
    let v = -r;
    let Some((n, ng)) = s.facing(v, tracing.two_sided) else { return Vec3::ZERO };
    let at = At { tri: hit.tri, object: hit.object, ng: ng.into(), ..At::point(s.p, n) };
    let c = shade(s.material, at, v, counts, depth + 1);
    if c.is_finite() { c.total() } else { Vec3::ZERO }
}
