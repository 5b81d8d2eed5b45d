//! The reference path tracer (`[render] method = "path"`): unidirectional path tracing
//! (Kajiya 1986) on the render's one [`SceneRays`], with next-event estimation and multiple
//! importance sampling (Veach 1997, ch. 9, the power heuristic), Russian roulette, and
//! free-flight sampling in the `[fog]` medium (volumetric path tracing).
//!
//! **Which light paths it counts.** Every path of at most `max_depth` segments from the
//! camera, as Mitsuba counts them: 1 sees only emitters (surfaces with `emission`, the
//! environment), 2 adds direct light, 3 one indirect bounce, and so on. At each vertex:
//! - *lights* ([`Light`]): point, spot and directional lights by their incident (they are
//!   deltas: only next-event estimation finds them); rect, disk and sphere lights by a point
//!   chosen on their surface ([`shapes`]), weighted by the power heuristic against the BSDF's
//!   pdf, and a BSDF-sampled ray that crosses one gets the other weight (their shapes block
//!   nothing and the camera does not see them, as in the rasterizer); sky lights by a
//!   cosine-weighted direction, weighted against the BSDF's sample escaping the same way;
//!   line lights by one sample placed as the raster's samples are ([`Light::area_sample`]),
//!   found by next-event estimation alone;
//! - *emitting surfaces*: a point chosen by area ([`emitters`]), weighted by the power
//!   heuristic against the BSDF's pdf; a BSDF-sampled ray that hits one gets the other weight;
//! - *the environment*: a direction by the map's luminance (`EnvDistribution`), weighted
//!   the same way against the BSDF; an escaping ray gets the other weight.
//!
//! **Materials.** Physically based BRDFs sample by [`Brdf::sample`] (cosine, GGX visible
//! normals, the principled lobes by weight) and are evaluated by [`Brdf::eval`]; mirror and
//! glass are delta lobes (glass picks reflection or refraction by Fresnel, the first
//! channel's index: no dispersion). Glass with `roughness` > 0 is Walter et al.'s rough
//! dielectric ([`RoughDielectric`]): from either side of the interface, next-event estimation
//! towards the outside of its face and its visible-normal sample, weighted by MIS like a BRDF
//! (a sample that goes into the glass has no next-event twin and counts a lamp in full). A
//! principled material with transmission ([`crate::shading::principled_transmission`]) is one
//! of its parts per vertex, chosen with its share: that rough glass, or its BRDF with the
//! diffuse transmission on the far side; segments ending on its inside are absorbed by
//! Beer-Lambert. The
//! classic models are not BRDFs and are refused when the scene is built. Textured materials use their textures' means. The ambient term and
//! `ambient` lights have no place in light transport and are not used.
//!
//! **The medium.** A homogeneous, grey `[fog] kind = "medium"` fills the ball about the eye
//! that the raster's march covers (radius `medium::far`, where an escaping eye ray's
//! transmittance is 10⁻⁴ or the scene's size times a cap). A segment scatters at a distance
//! drawn from σ_t e^(−σ_t t) (free flight), the throughput times the albedo σ_s/σ_t; a new
//! direction from the Henyey-Greenstein phase. At a point in the medium every light is
//! sampled but the sky (point, spot, directional, rect, disk, sphere and line lights, an
//! emitter point, an environment direction), each times the phase and e^(−σ_t s); the sky
//! reaches it through the phase's samples that escape.
//!
//! **Samples.** Every number is `[render] sampler` (Sobol by default) at index k of the pixel
//! sample's `spp` paths, in a stream seeded by a hash of the pixel, the sample, the depth and
//! the purpose (a padded sequence, as pbrt's `PaddedSobolSampler`): the same bytes on any
//! thread count, and the `spp` paths of a pixel stratified in every dimension.

pub mod emitters;
mod gather;
mod medium;
pub mod photons;
mod scatter;
pub mod shapes;
pub mod subsurface;

use super::rays::{Origin, SceneRays};
use super::surfaces::RayHit;
use crate::effects::environment::distribution::EnvDistribution;
use crate::effects::fog::phase::henyey_greenstein;
use crate::geometry::camera::CameraRays;
use crate::geometry::sampler::Sampler;
use crate::geometry::sampling::hash3;
use crate::lesson::settings::{Caustics, Indirect};
use crate::light::{Light, LightKind};
use crate::scene::{Environment, Model, Scene};
use crate::shading::brdf::{Brdf, from_local, local_frame, to_local};
use crate::shading::rough_dielectric::RoughDielectric;
use crate::simd::lanes::V3;
use emitters::Emitters;
use glam::{Vec2, Vec3};
use medium::Medium;
pub use medium::sample_henyey_greenstein;
use scatter::Scatter;
use shapes::Shape;
use std::sync::Arc;

/// Counter label: paths traced (`RenderStats::counters`).
pub const PATHS: &str = "paths";
/// Counter label: segments traced (closest-hit rays), for the mean path length.
pub const SEGMENTS: &str = "path segments";
/// Counter label: next-event (shadow) rays.
pub const NEE_RAYS: &str = "next-event rays";
/// Counter label: photons sent from the lamps for the caustic map.
pub const PHOTONS_EMITTED: &str = "photons emitted";
/// Counter label: photons stored in the caustic map.
pub const PHOTONS_STORED: &str = "caustic photons stored";
/// Counter label: photons stored in the global map.
pub const GLOBAL_STORED: &str = "global photons stored";
/// Counter label: final-gather rays (closest-hit rays from the first diffuse vertices).
pub const GATHER_RAYS: &str = "final-gather rays";

/// What one path-traced render counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PathCounts {
    /// Paths traced.
    pub paths: u64,
    /// Segments traced (closest-hit rays).
    pub segments: u64,
    /// Next-event rays (shadow rays to lights, emitters and the environment).
    pub nee_rays: u64,
    /// Final-gather rays.
    pub gather_rays: u64,
    /// Segments of the subsurface walks (closest-hit rays under a surface).
    pub walk_steps: u64,
}

impl std::ops::AddAssign for PathCounts {
    fn add_assign(&mut self, o: PathCounts) {
        self.paths += o.paths;
        self.segments += o.segments;
        self.nee_rays += o.nee_rays;
        self.gather_rays += o.gather_rays;
        self.walk_steps += o.walk_steps;
    }
}

/// What a vertex samples, one stream each (the slot in [`Stream`]).
#[derive(Clone, Copy)]
enum Slot {
    Pixel,
    Lobe,
    Direction,
    Roulette,
    EmitterPick,
    EmitterPoint,
    Environment,
    FreeFlight,
    /// Light `i`'s sample (the slot is `Light as u32 + i`).
    Light,
}

/// The sample streams of one path: index `k` of `n` in streams seeded by `seed`, the depth and the slot.
struct Stream {
    sampler: Sampler,
    k: u32,
    n: u32,
    seed: u32,
}

impl Stream {
    fn u1(&self, depth: u32, slot: Slot) -> f32 {
        self.u1_at(depth, slot as u32)
    }

    fn u1_at(&self, depth: u32, slot: u32) -> f32 {
        self.sampler.u1(self.k, self.n, hash3(self.seed, depth, slot))
    }

    fn u2(&self, depth: u32, slot: Slot) -> Vec2 {
        self.u2_at(depth, slot as u32)
    }

    fn u2_at(&self, depth: u32, slot: u32) -> Vec2 {
        self.sampler.u2(self.k, self.n, hash3(self.seed, depth, slot.wrapping_add(0x100)))
    }
}

/// The power heuristic with β = 2 for one sample of each strategy (Veach 1997, eq. 9.13).
#[inline]
fn power(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 && (a2 + b2).is_finite() {
        a2 / (a2 + b2)
    } else if a.is_infinite() {
        1.0
    } else {
        0.0
    }
}

/// The stream slot of a principled vertex's choice of part (glass or BRDF), and the next
/// one of its choice between BRDF and diffuse transmission: above the lights' slots.
const PART_SLOT: u32 = 0x7000_0000;

/// How a path's last direction was chosen.
#[derive(Debug, Clone, Copy)]
enum Last {
    /// From the camera.
    Camera,
    /// A delta lobe (mirror, glass): no pdf, nothing to weigh against.
    Delta,
    /// A BSDF sample at a surface with this shading normal, with its pdf.
    Bsdf { pdf: f32, n: Vec3 },
    /// A phase-function sample in the medium, with its pdf.
    Phase(f32),
}

impl Last {
    /// The pdf of the last direction, when it has one (for MIS).
    fn pdf(self) -> Option<f32> {
        match self {
            Last::Bsdf { pdf, .. } | Last::Phase(pdf) => Some(pdf),
            Last::Camera | Last::Delta => None,
        }
    }
}

/// One path-traced render's fixed parts: the scene's rays, its lights, emitters, environment
/// and medium, and the settings.
pub struct PathTracer<'a> {
    scene: &'a Scene,
    rays: Arc<SceneRays>,
    /// The lights next-event estimation asks, one sample each.
    lights: Vec<Light>,
    /// Each light's shape, for the kinds with a surface (rect, disk, sphere): sampled by area
    /// and hit by rays, with MIS.
    shapes: Vec<Option<Shape>>,
    emitters: Emitters,
    env: Option<&'a Environment>,
    env_dist: Option<EnvDistribution>,
    medium: Option<Medium>,
    spp: u32,
    max_depth: u32,
    sampler: Sampler,
    two_sided: bool,
    /// The photon maps (`caustics` or `indirect` = `"photons"`).
    photons: Option<photons::Photons>,
    /// How indirect light is found, and the final gather's rays.
    indirect: Indirect,
    gather_rays: u32,
    /// The random walks under the principled materials that have one.
    walks: subsurface::Subsurface,
}

impl<'a> PathTracer<'a> {
    /// The tracer of `scene` on its ray-query structure `rays`, lit by `lights` (the plan's
    /// kept lights).
    pub fn new(scene: &'a Scene, rays: Arc<SceneRays>, lights: &[Light]) -> PathTracer<'a> {
        let s = &scene.spec.settings;
        let lights: Vec<Light> = lights
            .iter()
            .filter(|l| l.kind != LightKind::Ambient && l.radiance.max(l.ground().unwrap_or(Vec3::ZERO)) != Vec3::ZERO)
            .map(|l| Light { samples: 1, ..*l })
            .collect();
        let shapes = lights.iter().map(Shape::of).collect();
        let env = scene.environment.as_ref();
        let medium = scene.spec.fog.as_ref().and_then(|f| f.medium().copied()).filter(|m| m.sigma_t() > 0.0).map(|m| Medium {
            sigma_s: m.sigma_s,
            sigma_t: m.sigma_t(),
            g: m.g,
            centre: scene.spec.camera.position,
            radius: super::medium::far(scene, &scene.lights, m.sigma_t()),
        });
        let p = s.path;
        let photons = (p.caustics == Caustics::Photons || p.indirect == Indirect::Photons)
            .then(|| photons::trace(scene, &rays, &lights, &p, s.sampler));
        PathTracer {
            scene,
            rays,
            lights,
            shapes,
            emitters: Emitters::new(scene),
            env,
            env_dist: env.and_then(|e| EnvDistribution::new(&e.map)),
            medium,
            spp: s.path.spp,
            max_depth: s.path.max_depth,
            sampler: s.sampler,
            two_sided: s.cull == crate::lesson::Cull::None,
            photons,
            indirect: p.indirect,
            gather_rays: p.gather_rays,
            walks: subsurface::Subsurface::new(&scene.materials),
        }
    }

    /// The photon maps, when the lesson asks for them.
    pub fn photon_maps(&self) -> Option<&photons::Photons> {
        self.photons.as_ref()
    }

    /// Paths per pixel: aa² samples × `spp`.
    pub fn paths_per_pixel(&self) -> u32 {
        let aa = self.scene.spec.settings.aa.max(1);
        aa * aa * self.spp
    }

    /// Pixel (`x`, `y`) through the camera `rays`: the sum of its paths' radiance (a
    /// non-finite path counts as zero, as the raster's NaN samples) and how many were covered.
    pub fn pixel(&self, rays: &CameraRays, x: u32, y: u32, counts: &mut PathCounts) -> (Vec3, u32) {
        let w = self.scene.spec.camera.width;
        let aa = self.scene.spec.settings.aa.max(1);
        let (mut sum, mut covered) = (Vec3::ZERO, 0u32);
        for sub in 0..aa * aa {
            let seed = hash3(y * w + x, sub, 0x9a7b_5eed);
            for k in 0..self.spp {
                let stream = Stream { sampler: self.sampler, k, n: self.spp, seed };
                // A uniform point of the sample's cell of the aa × aa grid: the box filter.
                let j = stream.u2(0, Slot::Pixel);
                let px = x as f64 + ((sub % aa) as f64 + j.x as f64) / aa as f64;
                let py = y as f64 + ((sub / aa) as f64 + j.y as f64) / aa as f64;
                let ray = rays.through(px, py);
                let (l, hit) = self.trace(ray.origin.as_vec3(), ray.dir.as_vec3().normalize(), &stream, counts);
                if l.is_finite() {
                    sum += l;
                }
                covered += hit as u32;
            }
        }
        (sum, covered)
    }

    /// The radiance along the camera ray from `o` in unit direction `d`, and whether the
    /// sample is covered (it met a surface, the drawn environment or the medium).
    fn trace(&self, o: Vec3, d: Vec3, stream: &Stream, counts: &mut PathCounts) -> (Vec3, bool) {
        counts.paths += 1;
        let mut origin = Origin { p: o, ng: d, tri: u32::MAX, object: u32::MAX };
        let mut d = d;
        let mut beta = Vec3::ONE;
        let mut radiance = Vec3::ZERO;
        // How the last direction was chosen: its BSDF or phase pdf (for MIS), or a delta.
        let mut last = Last::Camera;
        let mut covered = self.medium.is_some();
        // With a photon map: whether the path has gathered it (at its first surface that is not
        // a mirror or glass), and whether every vertex since then was a mirror or smooth glass
        // (a lamp met now is light the map holds).
        let (mut gathered, mut in_map) = (false, false);
        for depth in 1..=self.max_depth {
            counts.segments += 1;
            let hit = self.rays.closest(&origin, d);
            let t_hit = hit.map_or(f32::INFINITY, |h| h.t);
            // Free flight: scatter at t with pdf σ_t e^(−σ_t t); the grey ratio
            // σ_s e^(−σ_t t) / pdf is the albedo, and passing on has weight 1.
            let scatter = self.medium.as_ref().and_then(|m| {
                let (t0, t1) = m.interval(origin.p, d)?;
                let t = t0 - (1.0 - stream.u1(depth, Slot::FreeFlight)).ln() / m.sigma_t;
                (t < t1.min(t_hit)).then_some(t)
            });
            // Lights with a surface that the segment crosses before it ends (not seen by the
            // camera, as in the rasterizer): weighted against their next-event estimation.
            if depth > 1 && !(in_map && matches!(last, Last::Delta)) {
                radiance += beta * self.lights_crossed(origin.p, d, scatter.unwrap_or(t_hit), last.pdf());
            }
            if let Some(m) = &self.medium
                && let Some(t) = scatter
            {
                beta *= m.sigma_s / m.sigma_t;
                in_map = false;
                let p = origin.p + d * t;
                if depth == self.max_depth {
                    break;
                }
                radiance += beta * self.next_event_in_medium(p, d, m, stream, depth, counts);
                let l = sample_henyey_greenstein(d, m.g, stream.u2(depth, Slot::Direction));
                last = Last::Phase(henyey_greenstein(l.dot(d), m.g));
                origin = Origin { p, ng: l, tri: u32::MAX, object: u32::MAX };
                d = l;
                if !self.survives(&mut beta, depth, stream) {
                    break;
                }
                continue;
            }
            let Some(hit) = hit else {
                radiance += beta * self.escaped(d, depth, last);
                covered |= depth == 1 && self.env.is_some_and(|e| e.background);
                break;
            };
            covered |= depth == 1;
            let s = self.surface(&hit);
            let v = -d;
            let front = s.face.dot(v) > 0.0;
            // A principled material that lets light through: Beer-Lambert on a segment that
            // ends at its inside, and one part of its mixture per vertex, chosen with the
            // part's share (`shading::principled_transmission`): rough glass or the BRDF.
            let through = match &s.material.model {
                Model::Physical(Brdf::Principled(p)) if p.transmits() => {
                    if !front {
                        beta *= (-p.absorption() * hit.t).exp();
                    }
                    Some((p, stream.u1_at(depth, PART_SLOT) < p.glass_share()))
                }
                _ => None,
            };
            if front && s.material.emission != Vec3::ZERO {
                let w = match last.pdf() {
                    Some(pb) => self.emitters.pdf(s.face, d, hit.t).map_or(1.0, |pl| power(pb, pl)),
                    None => 1.0,
                };
                radiance += beta * s.material.emission * w;
            }
            if depth == self.max_depth {
                break;
            }
            // Random-walk subsurface scattering (`subsurface.rs`): the path may leave elsewhere.
            let Some((s, hit, v, front)) = self.subsurface(s, hit, v, front, stream, depth, &mut beta, counts) else { break };
            let here = Origin { p: s.p, ng: s.face, tri: hit.tri, object: hit.object };
            let (n, ng) = match (&s.material.model, front) {
                (Model::Glass(_), _) | (_, true) => (s.n, s.face),
                _ if through.is_some_and(|(_, glass)| glass) => (s.n, s.face),
                // Light goes through it: its back is a surface too.
                (_, false) if self.two_sided || through.is_some() => (-s.n, -s.face),
                // The back of a one-sided surface: black, as the rasterizer culls it.
                _ => break,
            };
            let (t, b) = local_frame(n);
            let vl = to_local(v, t, b, n);
            let translucent = through.and_then(|(p, _)| p.diffuse_transmission_lobe());
            let next = match &s.material.model {
                Model::Physical(Brdf::Principled(p)) if through.is_some_and(|(_, glass)| glass) => {
                    // Its rough glass part, as rough glass below (tinted √C each way).
                    let rough = p.boundary();
                    radiance +=
                        beta * self.next_event(Scatter::Rough(rough, p.refraction_tint()), &s, n, s.face, vl, &here, stream, depth, counts);
                    in_map = false;
                    let Some(rs) = rough.sample(vl, stream.u1(depth, Slot::Lobe), stream.u2(depth, Slot::Direction)) else { break };
                    beta *= if rs.transmitted { p.refraction_tint() } else { Vec3::ONE } * (rs.value * rs.l.z.abs() / rs.pdf);
                    let l = from_local(rs.l, t, b, n);
                    last = if rs.l.z > 0.0 && l.dot(s.face) > 0.0 { Last::Bsdf { pdf: rs.pdf, n } } else { Last::Delta };
                    l
                }
                Model::Physical(brdf) if translucent.is_some() => {
                    let Some(dt) = translucent else { break };
                    // The BRDF and its diffuse transmission, one of them sampled (chosen with q).
                    radiance += beta * self.next_event(Scatter::Translucent(brdf, dt), &s, n, ng, vl, &here, stream, depth, counts);
                    in_map = false;
                    let (ll, pdf, f) = if stream.u1_at(depth, PART_SLOT + 1) < dt.q {
                        let Some(ll) = dt.sample(vl, stream.u2(depth, Slot::Direction)) else { break };
                        (ll, dt.q * dt.pdf(vl, ll), dt.value)
                    } else {
                        let Some(bs) = brdf.sample(vl, stream.u1(depth, Slot::Lobe), stream.u2(depth, Slot::Direction)) else { break };
                        (bs.l, (1.0 - dt.q) * bs.pdf, bs.f)
                    };
                    if pdf.is_nan() || pdf <= 0.0 {
                        break;
                    }
                    beta *= f * (ll.z.abs() / pdf);
                    last = Last::Bsdf { pdf, n };
                    from_local(ll, t, b, n)
                }
                Model::Physical(brdf) => {
                    radiance += beta * self.next_event(Scatter::Brdf(brdf), &s, n, ng, vl, &here, stream, depth, counts);
                    in_map = false;
                    if let Some(map) = self.photons.as_ref().and_then(|m| m.caustic.as_ref()).filter(|_| !gathered) {
                        (gathered, in_map) = (true, true);
                        radiance += beta
                            * map.estimate(s.p, ng, |wi| {
                                let ll = to_local(wi, t, b, n);
                                if ll.z > 0.0 { brdf.eval(ll, vl) } else { Vec3::ZERO }
                            });
                    }
                    if self.indirect != Indirect::Path {
                        radiance += beta * self.indirect_at(brdf, &s, n, ng, vl, &here, stream, depth, counts);
                        break;
                    }
                    let Some(bs) = brdf.sample(vl, stream.u1(depth, Slot::Lobe), stream.u2(depth, Slot::Direction)) else { break };
                    beta *= bs.weight();
                    last = Last::Bsdf { pdf: bs.pdf, n };
                    from_local(bs.l, t, b, n)
                }
                Model::Mirror(m) => {
                    let Some(ds) = m.sample(vl) else { break };
                    beta *= ds.weight;
                    last = Last::Delta;
                    from_local(ds.l, t, b, n)
                }
                Model::Glass(g) if g.roughness > 0.0 => {
                    // Walter et al. 2007: a rough interface, with next-event estimation towards
                    // the outside of its face and its visible-normal sample, weighted by MIS.
                    // Photons stop at it: the path tracer keeps every path through it.
                    let rough = RoughDielectric::new(g.ior.x, g.roughness);
                    radiance += beta * self.next_event(Scatter::Rough(rough, g.tint), &s, n, s.face, vl, &here, stream, depth, counts);
                    in_map = false;
                    let Some(rs) = rough.sample(vl, stream.u1(depth, Slot::Lobe), stream.u2(depth, Slot::Direction)) else { break };
                    beta *= if rs.transmitted { g.tint } else { Vec3::ONE } * (rs.value * rs.l.z.abs() / rs.pdf);
                    let l = from_local(rs.l, t, b, n);
                    // Outwards, next-event estimation had the same direction (MIS); inwards it had none.
                    last = if rs.l.z > 0.0 && l.dot(s.face) > 0.0 { Last::Bsdf { pdf: rs.pdf, n } } else { Last::Delta };
                    l
                }
                Model::Glass(g) => {
                    // The Fresnel choice's probability cancels its factor: the weight is 1 or the tint.
                    let Some(ds) = g.sample(vl, stream.u1(depth, Slot::Lobe), None) else { break };
                    beta *= ds.weight;
                    last = Last::Delta;
                    from_local(ds.l, t, b, n)
                }
                // Refused when the scene is built (`scene::build`).
                Model::Classic(_) => break,
            };
            let next = next.normalize_or_zero();
            // A reflection the shading normal allows but the face does not is lost (it would
            // leak light through the surface); glass crosses its face on purpose.
            if next == Vec3::ZERO || (!matches!(s.material.model, Model::Glass(_)) && through.is_none() && next.dot(ng) <= 0.0) {
                break;
            }
            origin = here;
            d = next;
            if !self.survives(&mut beta, depth, stream) {
                break;
            }
        }
        (radiance, covered)
    }

    /// The radiance of the lights with a surface that the ray o + t d crosses for t < `t_end`,
    /// each weighted by the power heuristic against its area sampling after a BSDF or phase
    /// sample (`last_pdf`), in full after a delta lobe.
    fn lights_crossed(&self, o: Vec3, d: Vec3, t_end: f32, last_pdf: Option<f32>) -> Vec3 {
        let mut sum = Vec3::ZERO;
        for (light, shape) in self.lights.iter().zip(&self.shapes) {
            let Some(h) = shape.and_then(|s| s.hit(o, d, t_end, light.radiance)) else { continue };
            let w = last_pdf.map_or(1.0, |pb| power(pb, h.pdf));
            sum += h.radiance * w;
        }
        sum
    }

    /// Russian roulette after depth 3 (pbrt-v4): a path whose throughput's largest channel is
    /// below 1 ends with probability 1 − max β, and survives divided by max β (unbiased).
    fn survives(&self, beta: &mut Vec3, depth: u32, stream: &Stream) -> bool {
        if !beta.is_finite() || *beta == Vec3::ZERO {
            return false;
        }
        let m = beta.max_element();
        if depth < 3 || m >= 1.0 {
            return true;
        }
        if stream.u1(depth, Slot::Roulette) >= m {
            return false;
        }
        *beta /= m;
        true
    }

    /// What an escaping ray brings: the environment (weighted against its next-event
    /// strategy after a BSDF or phase sample), the sky lights (weighted against their
    /// cosine-weighted samples about the last surface's normal after a BSDF sample; in full
    /// after a phase or delta sample, where no sample of them was taken; never seen by the
    /// camera, as in the rasterizer), or the camera background seen through the medium.
    fn escaped(&self, d: Vec3, depth: u32, last: Last) -> Vec3 {
        let mut sum = match self.env {
            Some(env) if depth > 1 || env.background => {
                let w = match (last.pdf(), &self.env_dist) {
                    (Some(pb), Some(dist)) => power(pb, dist.pdf(env.to_map(d))),
                    _ => 1.0,
                };
                env.radiance(d) * w
            }
            _ if depth == 1 && self.medium.is_some() => self.scene.spec.camera.background,
            _ => Vec3::ZERO,
        };
        if depth > 1 {
            for light in &self.lights {
                let Some(ground) = light.ground() else { continue };
                let w = match last {
                    Last::Bsdf { pdf, n } => power(pdf, n.dot(d).max(0.0) * std::f32::consts::FRAC_1_PI),
                    _ => 1.0,
                };
                sum += if d.y >= 0.0 { light.radiance } else { ground } * w;
            }
        }
        sum
    }

    /// The surface at a hit: point, interpolated normal, face normal and material.
    fn surface(&self, hit: &super::rays::SceneHit) -> RayHit<'a> {
        super::surfaces::surface_at(&self.scene.geometry, &self.scene.materials, hit)
    }

    /// Transmittance of the medium along a next-event ray.
    fn through(&self, p: Vec3, l: Vec3, distance: f32) -> f32 {
        self.medium.map_or(1.0, |m| m.transmittance(p, l, distance))
    }

    /// Next-event estimation at a surface point: each light's sample, an emitter point and an
    /// environment direction, each unoccluded one f L cos / p (MIS-weighted where a BSDF ray
    /// could have found it too).
    #[allow(clippy::too_many_arguments)]
    fn next_event(
        &self,
        brdf: Scatter<'_>,
        s: &RayHit,
        n: Vec3,
        ng: Vec3,
        vl: Vec3,
        here: &Origin,
        stream: &Stream,
        depth: u32,
        counts: &mut PathCounts,
    ) -> Vec3 {
        if vl.z <= 0.0 && matches!(brdf, Scatter::Brdf(_)) {
            return Vec3::ZERO;
        }
        // Rough glass: n and ng are its outward normals, whichever side v is on.
        let (t, b) = local_frame(n);
        let p = s.p;
        let mut sum = Vec3::ZERO;
        // f |cos| for a world direction l, or `None` where the BSDF or the face sends nothing:
        // above the surface only. For rough glass that is the outside of its face, from
        // either side: a lamp is never seen straight through the glass's own inside (the
        // path's samples that go in have no next-event twin, see `trace`).
        let f_cos = |l: Vec3| -> Option<(Vec3, Vec3)> {
            let ll = to_local(l, t, b, n);
            // A translucent surface also sees the lights behind it, through its BTDF.
            let behind = matches!(brdf, Scatter::Translucent(..)) && ll.z < 0.0 && l.dot(ng) < 0.0;
            if (ll.z <= 0.0 || l.dot(ng) <= 0.0) && !behind {
                return None;
            }
            let f = brdf.eval(ll, vl);
            (f != Vec3::ZERO).then_some((f * ll.z.abs(), ll))
        };
        let mut visible = |l: Vec3, distance: f32| {
            counts.nee_rays += 1;
            !self.rays.occluded(here, l, distance)
        };
        for (i, (light, shape)) in self.lights.iter().zip(&self.shapes).enumerate() {
            let u = stream.u2_at(depth, Slot::Light as u32 + i as u32);
            if let Some(shape) = shape {
                // By area, weighted against the BSDF's sample finding the same point.
                if let Some(h) = shape.sample(p, u, light.radiance)
                    && let Some((fc, ll)) = f_cos(h.l)
                    && visible(h.l, h.t)
                {
                    let w = power(h.pdf, brdf.pdf(vl, ll));
                    sum += fc * h.radiance * (w / h.pdf) * self.through(p, h.l, h.t);
                }
                continue;
            }
            let (l, e, distance) = if light.kind.is_sampled() {
                let a = light.area_sample(p, n, u);
                if a.weight.is_nan() || a.weight <= 0.0 {
                    continue;
                }
                // A sky sample (pdf 1/dω = cos/π) is weighted against the BSDF's sample
                // escaping the same way; a line light is found by this sample alone.
                let w = match (light.ground(), f_cos(a.l)) {
                    (Some(_), Some((_, ll))) => power(1.0 / a.weight, brdf.pdf(vl, ll)),
                    _ => 1.0,
                };
                (a.l, a.radiance * (a.weight * w), a.distance)
            } else {
                let inc = light.incident::<f32>(V3::from(p));
                let l = Vec3::from(inc.l);
                if l == Vec3::ZERO || inc.c_spot.is_nan() || inc.c_spot <= 0.0 {
                    continue;
                }
                (l, light.radiance * (inc.inv_r2 * inc.c_spot), inc.distance)
            };
            let Some((fc, _)) = f_cos(l) else { continue };
            if visible(l, distance) {
                sum += fc * e * self.through(p, l, distance);
            }
        }
        if let Some(es) = self.emitters.sample(self.scene, p, stream.u1(depth, Slot::EmitterPick), stream.u2(depth, Slot::EmitterPoint))
            && let Some((fc, ll)) = f_cos(es.l)
            && visible(es.l, es.distance)
        {
            let w = power(es.pdf, brdf.pdf(vl, ll));
            sum += fc * es.radiance * (w / es.pdf) * self.through(p, es.l, es.distance);
        }
        if let (Some(env), Some(dist)) = (self.env, &self.env_dist) {
            let (dm, pe) = dist.sample(stream.u2(depth, Slot::Environment));
            let l = env.from_map(dm);
            if pe > 0.0
                && let Some((fc, ll)) = f_cos(l)
                && visible(l, f32::INFINITY)
            {
                let w = power(pe, brdf.pdf(vl, ll));
                sum += fc * env.radiance(l) * (w / pe) * self.through(p, l, f32::INFINITY);
            }
        }
        if sum.is_finite() { sum } else { Vec3::ZERO }
    }
}
