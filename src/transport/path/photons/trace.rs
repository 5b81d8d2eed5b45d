//! Pass 1 of photon mapping: photons sent from the lamps in proportion to their power and
//! followed through the scene (Jensen 2001, ch. 5).
//!
//! **Emission.** A rect, disk or sphere light sends from a point uniform in area along a
//! cosine-weighted direction about its normal (Φ = π L A); a point light uniformly over the
//! sphere (Φ = 4π I); a spot light uniformly over its cone, each photon weighted by the
//! spot's C_spot in its direction (Φ = I ∫ C_spot dω). Each light sends its share of the
//! `photons` by its power, so every photon of a grey scene carries about the same flux. Point
//! and spot lights cannot be hit by a ray: their caustics reach the camera only by photons.
//! Directional, line and sky lights send none.
//!
//! **Following.** A photon follows mirrors and smooth glass (their delta lobes, glass choosing
//! reflection or refraction by Fresnel: the flux splits, no η² as radiance has). At a diffuse
//! surface it is stored in the caustic map if it came through mirrors or glass alone; for the
//! global map it is stored there (from the first diffuse bounce on only when the map is read
//! directly, without a final gather: direct light is then next-event estimation's) and goes
//! on with a BRDF sample, surviving with probability q = min(1, max f cos / pdf) and its flux
//! times (f cos / pdf) / q: Russian roulette on the albedo (Jensen 2001, §5.4), so the flux
//! of a grey Lambertian bounce stays the same. The photons' numbers are the render's sampler
//! at the photon's index, in streams hashed from the light, the depth and the purpose: the
//! same maps on every thread count.

use super::{Photon, PhotonMap};
use crate::geometry::sampler::Sampler;
use crate::geometry::sampling::{cosine_hemisphere, hash3, uniform_cone};
use crate::lesson::settings::{Caustics, Indirect, PathSettings};
use crate::light::{Light, LightKind};
use crate::scene::{Model, Scene};
use crate::shading::brdf::{Brdf, from_local, local_frame, to_local};
use crate::simd::lanes::V3;
use crate::transport::path::shapes::Shape;
use crate::transport::rays::{Origin, SceneRays};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::f32::consts::PI;

/// The maps pass 1 built, and what it counted.
#[derive(Debug, Clone)]
pub struct Photons {
    /// The caustic map (`caustics = "photons"`).
    pub caustic: Option<PhotonMap>,
    /// The global map (`indirect = "photons"`).
    pub global: Option<PhotonMap>,
    /// Photons sent from the lamps.
    pub emitted: u32,
    /// Closest-hit rays traced for them.
    pub segments: u64,
}

/// How a light sends photons.
#[derive(Clone)]
enum Source {
    /// A surface with radiance L.
    Shape(Shape, Vec3),
    /// A point or spot light: its position, and its cone's cos (−1: the whole sphere).
    Point(Box<Light>, Vec3, f32),
}

impl Source {
    fn of(light: &Light) -> Option<Source> {
        if let Some(s) = Shape::of(light) {
            return Some(Source::Shape(s, light.radiance));
        }
        match light.kind {
            LightKind::Point(p) => Some(Source::Point(Box::new(*light), p.position, -1.0)),
            // C_spot is 0 behind the light whatever the cutoff.
            LightKind::Spot(s) => Some(Source::Point(Box::new(*light), s.position, s.cos_cutoff.max(0.0))),
            _ => None,
        }
    }

    /// The spot factor C_spot towards unit `d` (1 for a point light): the light's own
    /// incident at one unit along d, so the photons see the cone the raster and NEE see.
    fn c_spot(&self, d: Vec3) -> f32 {
        match self {
            Source::Point(l, at, _) => {
                let c = l.incident::<f32>(V3::from(*at + d)).c_spot;
                if c.is_finite() { c.max(0.0) } else { 0.0 }
            }
            Source::Shape(..) => 1.0,
        }
    }

    /// The total flux Φ (W, each channel).
    fn power(&self) -> Vec3 {
        match self {
            Source::Shape(s, l) => *l * (PI * s.area()),
            &Source::Point(ref l, _, cos_max) => {
                // ∫ C_spot dω = 2π ∫ C(μ) dμ over the cone, by the midpoint rule in μ = cos θ.
                const STEPS: usize = 512;
                let dmu = (1.0 - cos_max) / STEPS as f32;
                let axis = self.axis();
                let (t, _) = local_frame(axis);
                let c: f32 = (0..STEPS)
                    .map(|i| {
                        let mu = cos_max + (i as f32 + 0.5) * dmu;
                        self.c_spot(axis * mu + t * ((1.0 - mu * mu).max(0.0).sqrt()))
                    })
                    .sum();
                l.radiance * (2.0 * PI * c * dmu)
            }
        }
    }

    /// The cone's axis (any axis for a point light).
    fn axis(&self) -> Vec3 {
        match self {
            Source::Point(l, ..) => match l.kind {
                LightKind::Spot(s) => s.direction.normalize_or(Vec3::NEG_Y),
                _ => Vec3::NEG_Y,
            },
            Source::Shape(..) => Vec3::Z,
        }
    }

    /// Photon k's start, direction and flux, when `count` share the light's power.
    fn emit(&self, count: u32, u: &impl Fn(u32, u32) -> Vec2) -> (Origin, Vec3, Vec3) {
        match self {
            Source::Shape(shape, radiance) => {
                let (shape, radiance) = (*shape, *radiance);
                let (y, m) = shape.point(u(0, 0));
                let (t, b) = local_frame(m);
                let d = from_local(cosine_hemisphere(u(0, 1)), t, b, m).normalize_or_zero();
                (Origin { p: y, ng: m, tri: u32::MAX, object: u32::MAX }, d, radiance * (PI * shape.area() / count as f32))
            }
            Source::Point(light, at, cos_max) => {
                let (at, cos_max) = (*at, *cos_max);
                // Uniform in the cone: pdf 1/Ω with Ω = 2π (1 − cos_max); the flux I C_spot Ω / n.
                let axis = self.axis();
                let (t, b) = local_frame(axis);
                let d = from_local(uniform_cone(u(0, 1), cos_max), t, b, axis).normalize_or_zero();
                let solid = 2.0 * PI * (1.0 - cos_max);
                (Origin { p: at, ng: d, tri: u32::MAX, object: u32::MAX }, d, light.radiance * (self.c_spot(d) * solid / count as f32))
            }
        }
    }
}

/// Photons traced per parallel task (their order is kept: the maps are the same on any thread count).
const CHUNK: u32 = 4096;

/// What a task's photons left: the photons kept, segments traced.
type Left = (Vec<Photon>, u64);

/// Pass 1: about `settings.photons` photons for the caustic map and `settings.global_photons`
/// for the global map (two sets, in streams of their own) from `lights` into `scene`, each
/// followed through at most `max_depth` segments.
pub fn trace(scene: &Scene, rays: &SceneRays, lights: &[Light], settings: &PathSettings, sampler: Sampler) -> Photons {
    let two_sided = scene.spec.settings.cull == crate::lesson::Cull::None;
    let want =
        |caustic: bool| Want { caustic, global: !caustic, direct: settings.gather_rays > 0, two_sided, max_depth: settings.max_depth };
    let gather = settings.photon_gather;
    let mut out = Photons { caustic: None, global: None, emitted: 0, segments: 0 };
    if settings.caustics == Caustics::Photons {
        let (photons, emitted, segments) = shoot(scene, rays, lights, settings.photons, &want(true), sampler, 0);
        out.caustic = Some(PhotonMap::with_gather(photons, settings.photon_radius, gather, settings.photon_nearest));
        (out.emitted, out.segments) = (out.emitted + emitted, out.segments + segments);
    }
    if settings.indirect == Indirect::Photons {
        let (photons, emitted, segments) = shoot(scene, rays, lights, settings.global_photons, &want(false), sampler, 0x8000_0000);
        out.global = Some(PhotonMap::with_gather(photons, settings.global_radius, gather, settings.photon_nearest));
        (out.emitted, out.segments) = (out.emitted + emitted, out.segments + segments);
    }
    out
}

/// About `n` photons from `lights`, shared by power, in streams offset by `stream`: the
/// photons `want` keeps, how many were emitted, the segments traced.
fn shoot(scene: &Scene, rays: &SceneRays, lights: &[Light], n: u32, want: &Want, sampler: Sampler, stream: u32) -> (Vec<Photon>, u32, u64) {
    let sources: Vec<(usize, Source, f32)> = lights
        .iter()
        .enumerate()
        .filter_map(|(i, l)| {
            Source::of(l).map(|s| {
                let power = s.power().max_element().max(0.0);
                (i, s, power)
            })
        })
        .filter(|(_, _, p)| p.is_finite())
        .collect();
    let total: f32 = sources.iter().map(|s| s.2).sum();
    let (mut photons, mut emitted, mut segments) = (Vec::new(), 0u32, 0u64);
    if !(total > 0.0 && total.is_finite()) {
        return (photons, emitted, segments);
    }
    for (i, source, power) in &sources {
        let count = ((f64::from(n) * f64::from(power / total)).round() as u32).max(1);
        emitted += count;
        let chunks: Vec<Left> = (0..count.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let mut out: Left = (Vec::new(), 0);
                for k in c * CHUNK..((c + 1) * CHUNK).min(count) {
                    let u = |depth: u32, slot: u32| sampler.u2(k, count, hash3(*i as u32 ^ stream, depth, slot));
                    let (from, d, flux) = source.emit(count, &u);
                    follow(scene, rays, want, from, d, flux, &u, &mut out);
                }
                out
            })
            .collect();
        for (p, s) in chunks {
            photons.extend(p);
            segments += s;
        }
    }
    (photons, emitted, segments)
}

/// Which photons pass 1 keeps.
struct Want {
    caustic: bool,
    global: bool,
    /// The global map keeps the photons' first diffuse hits too (a final gather reads it).
    direct: bool,
    two_sided: bool,
    max_depth: u32,
}

/// A photon from `from` along `d` with flux `power`, through the scene: its hits the map
/// `want`s pushed on `out`.
#[allow(clippy::too_many_arguments)]
fn follow(
    scene: &Scene,
    rays: &SceneRays,
    want: &Want,
    mut from: Origin,
    mut d: Vec3,
    mut power: Vec3,
    u: &impl Fn(u32, u32) -> Vec2,
    out: &mut Left,
) {
    // Mirrors and glass met since the lamp or the last diffuse bounce; diffuse bounces so far.
    let (mut specular, mut diffuse) = (false, 0u32);
    for depth in 1..=want.max_depth {
        if d == Vec3::ZERO || power.max_element() <= 0.0 || !power.is_finite() {
            return;
        }
        out.1 += 1;
        let Some(hit) = rays.closest(&from, d) else { return };
        let s = crate::transport::surfaces::surface_at(&scene.geometry, &scene.materials, &hit);
        let v = -d;
        let front = s.face.dot(v) > 0.0;
        let (n, ng) = match (&s.material.model, front) {
            (Model::Glass(_), _) | (_, true) => (s.n, s.face),
            (_, false) if want.two_sided => (-s.n, -s.face),
            _ => return,
        };
        let (t, b) = local_frame(n);
        let vl = to_local(v, t, b, n);
        let (l, weight) = match &s.material.model {
            // Rough glass is not a delta: the path tracer keeps every path through it.
            Model::Glass(g) if g.roughness > 0.0 => return,
            // So is a principled surface that lets light through (`principled_transmission`).
            Model::Physical(Brdf::Principled(p)) if p.transmits() => return,
            Model::Glass(g) => match g.sample(vl, u(depth, 2).x, None) {
                Some(s) => (s.l, s.weight),
                None => return,
            },
            Model::Mirror(m) => match m.sample(vl) {
                Some(s) => (s.l, s.weight),
                None => return,
            },
            model => {
                let photon = Photon { p: s.p, wi: v, power };
                if want.caustic && specular && diffuse == 0 {
                    out.0.push(photon);
                }
                let Model::Physical(brdf) = model else { return };
                if !want.global {
                    return;
                }
                if diffuse > 0 || want.direct {
                    out.0.push(photon);
                }
                let Some(bs) = brdf.sample(vl, u(depth, 3).x, u(depth, 4)) else { return };
                let w = bs.weight();
                // Russian roulette on the albedo: survive with q = min(1, max f cos / pdf).
                let q = w.max_element().min(1.0);
                if q.is_nan() || q <= 0.0 || u(depth, 5).x >= q {
                    return;
                }
                diffuse += 1;
                specular = false;
                (bs.l, w / q)
            }
        };
        power *= weight;
        let bounced = matches!(s.material.model, Model::Physical(_));
        specular |= !bounced;
        from = Origin { p: s.p, ng: s.face, tri: hit.tri, object: hit.object };
        d = from_local(l, t, b, n).normalize_or_zero();
        // A diffuse bounce the shading normal allows but the face does not would leak through it.
        if bounced && d.dot(ng) <= 0.0 {
            return;
        }
    }
}
