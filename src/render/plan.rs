//! The render plan: which passes, terms and lights a scene needs, decided before any work.
//!
//! The plan is executable: the pipeline runs the passes of [`Plan::passes`] that are marked
//! to run, in order, and nothing else (each pass it ran is recorded in
//! [`RenderStats::passes`](super::RenderStats::passes), and a test holds the two equal). A
//! material with K_spec = 0 never evaluates a specular term, Gouraud lights vertices and
//! never samples, a light that reaches no object is culled. `shadelab explain` prints this
//! very plan with its reasons.
//!
//! A new effect (a shadow map, fog, radiosity, ...) is a new [`Pass`] whose "is it needed
//! for this scene, and why?" is answered in one place, [`needed`], by its file in
//! `src/effects/`.

use crate::effects::shadows::shadowing;
use crate::lesson::settings::{Interpolation, Reflections, RenderMethod};
use crate::light::ShadowMethod;
use crate::light::Shadowing;
use crate::light::{Light, LightKind, Spot};
use crate::scene::{ClassicModel, Model, Scene};
use crate::shading::lobe::Part;
use glam::Vec3;

/// One decision: what, whether it runs, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decision {
    /// The pass, term or light.
    pub what: String,
    /// True when it runs.
    pub runs: bool,
    /// Why (in the course's notation where it helps).
    pub why: String,
}

/// The closed set of pipeline passes, in the order they run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    /// World positions to clip space.
    VertexStage,
    /// The BVH that shadow rays query (`transport::rays`, the render's one `SceneRays`).
    ShadowRays,
    /// Depth rendered from each light that uses a shadow map (`effects::shadows::map`).
    ShadowMaps,
    /// Silhouettes extruded from each light that uses shadow volumes (`effects::shadows::volume`).
    ShadowVolumes,
    /// Occluders projected onto receivers from each light that uses shadow polygons (`effects::shadows::polygons`).
    ShadowPolygons,
    /// The environment's sampling tables and the scene's rays for it and for mirrors (`effects::environment`).
    Environment,
    /// Each `[[probe]]` rendered into six cube faces, for mirrors that read probes (`effects::probe`, run by `render::probe`).
    ProbeCapture,
    /// The scene's rays for glass: reflected and refracted rays (`effects::refraction`).
    Refraction,
    /// Radiosity: patches, form factors, the solution and its display values (`effects::radiosity`).
    Radiosity,
    /// The path tracer: every pixel's paths from the camera (`transport::path`, `render::path`).
    PathTrace,
    /// Gouraud: every vertex lit once, before rasterizing.
    LightVertices,
    /// Flat: every face lit once at its centroid, before rasterizing.
    LightFaces,
    /// Triangle setup and binning, then each strip's visibility.
    Raster,
    /// Phong: every visible sample lit.
    ShadeSamples,
    /// Fog after lighting, every sample with its depth (`effects::fog`).
    Fog,
    /// Each pixel's samples box-filtered into the kept layers.
    Resolve,
}

impl Pass {
    /// Every pass, in pipeline order.
    pub const ALL: [Pass; 16] = [
        Pass::VertexStage,
        Pass::ShadowRays,
        Pass::ShadowMaps,
        Pass::ShadowVolumes,
        Pass::ShadowPolygons,
        Pass::Environment,
        Pass::ProbeCapture,
        Pass::Refraction,
        Pass::Radiosity,
        Pass::PathTrace,
        Pass::LightVertices,
        Pass::LightFaces,
        Pass::Raster,
        Pass::ShadeSamples,
        Pass::Fog,
        Pass::Resolve,
    ];

    /// Its name in `explain`.
    pub fn name(self) -> &'static str {
        match self {
            Pass::VertexStage => "vertex stage",
            Pass::ShadowRays => "shadow rays (BVH)",
            Pass::ShadowMaps => "shadow maps",
            Pass::ShadowVolumes => "shadow volumes",
            Pass::ShadowPolygons => "shadow polygons",
            Pass::Environment => "environment light",
            Pass::ProbeCapture => "probe capture",
            Pass::Refraction => "refraction (glass rays)",
            Pass::Radiosity => "radiosity",
            Pass::PathTrace => "path tracing",
            Pass::LightVertices => "lighting at vertices",
            Pass::LightFaces => "lighting per face",
            Pass::Raster => "rasterization",
            Pass::ShadeSamples => "lighting per sample",
            Pass::Fog => "fog",
            Pass::Resolve => "resolve",
        }
    }

    /// This pass's bit in a set of passes ([`RenderStats::passes`](super::RenderStats::passes)).
    pub fn bit(self) -> u32 {
        1 << self as u32
    }
}

/// One pass of the plan: whether it runs for this scene, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Step {
    /// The pass.
    pub pass: Pass,
    /// True when it runs.
    pub runs: bool,
    /// Why (in the course's notation where it helps).
    pub why: String,
}

/// The plan of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Every pass of the pipeline, in order, each marked to run or not.
    pub passes: Vec<Step>,
    /// Per material (same order as the scene's), its terms.
    pub terms: Vec<Vec<Decision>>,
    /// Per light (same order as the scene's), whether it is evaluated.
    pub lights: Vec<Decision>,
    /// Per light (same order as the scene's), its shadows: the method that runs, and why.
    pub shadows: Vec<Shadowing>,
}

impl Plan {
    /// The passes that run, in order: what the pipeline executes.
    pub fn running(&self) -> impl Iterator<Item = Pass> + '_ {
        self.passes.iter().filter(|s| s.runs).map(|s| s.pass)
    }

    /// The set of passes that run, one [`Pass::bit`] each.
    pub fn running_bits(&self) -> u32 {
        self.running().fold(0, |b, p| b | p.bit())
    }

    /// The lights that are evaluated.
    pub fn active_lights(&self, scene: &Scene) -> Vec<Light> {
        scene.lights.iter().zip(&self.lights).filter(|(_, d)| d.runs).map(|(l, _)| *l).collect()
    }

    /// The shadow method of each evaluated light (in [`Plan::active_lights`] order).
    pub fn active_shadows(&self) -> Vec<Option<ShadowMethod>> {
        self.shadows.iter().zip(&self.lights).filter(|(_, d)| d.runs).map(|(s, _)| s.method).collect()
    }
}

fn decide(what: impl Into<String>, runs: bool, why: impl Into<String>) -> Decision {
    Decision { what: what.into(), runs, why: why.into() }
}

/// Derives the plan of a scene.
pub fn plan(scene: &Scene) -> Plan {
    let g = &scene.geometry;
    let lights: Vec<Decision> = scene.lights.iter().enumerate().map(|(i, l)| light_decision(i, l, scene)).collect();
    let active: Vec<&Light> = scene.lights.iter().zip(&lights).filter(|(_, d)| d.runs).map(|(l, _)| l).collect();
    let direct = active.iter().filter(|l| l.kind != LightKind::Ambient && l.radiance != Vec3::ZERO).count();
    let shadows: Vec<Shadowing> = scene.lights.iter().map(|l| shadowing(l, scene)).collect();
    let methods: Vec<Option<ShadowMethod>> = shadows.iter().zip(&lights).filter(|(_, d)| d.runs).map(|(s, _)| s.method).collect();
    let passes = Pass::ALL
        .into_iter()
        .map(|pass| {
            let (runs, why) = needed(pass, scene, active.len(), &methods);
            Step { pass, runs, why }
        })
        .collect();
    let used: Vec<bool> = (0..scene.materials.len()).map(|m| g.material.contains(&(m as u32))).collect();
    let terms = scene
        .materials
        .iter()
        .zip(&used)
        .map(|(m, used)| {
            if !used {
                return vec![decide("all terms", false, "no object uses this material")];
            }
            let light_ambient = active.iter().any(|l| l.ambient != Vec3::ZERO);
            let ambient_on = m.ambient != Vec3::ZERO && (scene.spec.ambient != Vec3::ZERO || light_ambient);
            let ambient = decide(
                "ambient",
                ambient_on,
                match (m.ambient == Vec3::ZERO, scene.spec.ambient != Vec3::ZERO || light_ambient) {
                    (true, _) => "K_amb = 0".to_string(),
                    (false, false) => "L_glob = 0 and no light has an ambient part".to_string(),
                    (false, true) => "L_glob⊗K_amb + Σ I_amb".to_string(),
                },
            );
            let emission = decide("emission", m.emission != Vec3::ZERO, if m.emission == Vec3::ZERO { "L_emi = 0" } else { "L_emi" });
            if scene.spec.settings.method == RenderMethod::Path {
                return path_terms(m, emission);
            }
            let c = match &m.model {
                Model::Classic(c) => c,
                Model::Mirror(_) => {
                    let why = match (crate::effects::probe::needed(scene).0, scene.spec.settings.reflections) {
                        (true, Reflections::ProbeBox) => "tint⊗L_i(r): the probe along R' = P − C inside its box, else the traced ray",
                        (true, Reflections::ProbeProjector) => {
                            "tint⊗L_i(r): the traced ray's surface x as the probe saw it, along s = x − C inside its box, else the traced ray"
                        }
                        (true, Reflections::ProbeMoved) => {
                            "tint⊗L_i(r): the probe read from its moved centre C' along s' = P − C inside its box, else the traced ray"
                        }
                        (true, _) => "tint⊗L_i(r): the probe along r inside its box (no parallax), else the traced ray",
                        _ => "tint⊗L_i(r): the environment or the mirrored scene",
                    };
                    return vec![decide("mirror reflection", true, why), emission];
                }
                Model::Glass(_) => {
                    return vec![
                        decide("glass reflection", true, "F L_i(r): the Fresnel share of the reflected ray"),
                        decide("glass transmission", true, "(1 − F) tint⊗L_i(t): the refracted ray, through the glass and out"),
                        emission,
                    ];
                }
                Model::Physical(brdf) => {
                    let parts = brdf.lobes();
                    let (spec, diffuse_lobe) = (parts.has(Part::Specular), parts.has(Part::Diffuse));
                    let mut terms = subsurface_walk(brdf, false);
                    terms.extend([
                        ambient,
                        decide(
                            "diffuse lobe",
                            diffuse_lobe && direct > 0,
                            if !diffuse_lobe {
                                "the BRDF has no diffuse lobe"
                            } else if direct == 0 {
                                "no direct light"
                            } else {
                                "f_d E (n·l)"
                            },
                        ),
                        decide(
                            "specular lobe",
                            spec && direct > 0,
                            if !spec {
                                "the BRDF has no specular lobe"
                            } else if direct == 0 {
                                "no direct light"
                            } else {
                                "f_s E (n·l)"
                            },
                        ),
                        emission,
                    ]);
                    return terms;
                }
            };
            vec![
                ambient,
                decide(
                    "diffuse",
                    c.diffuse != Vec3::ZERO && direct > 0,
                    if c.diffuse == Vec3::ZERO {
                        "K_diff = 0".to_string()
                    } else if direct == 0 {
                        "no direct light".to_string()
                    } else {
                        "max(N·L, 0) K_diff⊗L_diff".to_string()
                    },
                ),
                decide(
                    "specular",
                    c.has_specular() && direct > 0,
                    match (c.model, c.specular == Vec3::ZERO, direct) {
                        (ClassicModel::Lambert, _, _) => "lambert has no specular term".to_string(),
                        (_, true, _) => "K_spec = 0".to_string(),
                        (_, _, 0) => "no direct light".to_string(),
                        (ClassicModel::Phong, _, _) => "max(R·V, 0)^K_shi K_spec⊗L_spec".to_string(),
                        (ClassicModel::BlinnPhong, _, _) => "max(N·H, 0)^K_shi K_spec⊗L_spec".to_string(),
                    },
                ),
                emission,
            ]
        })
        .collect();
    Plan { passes, terms, lights, shadows }
}

/// A material's terms in the path tracer: what each path vertex does with it.
fn path_terms(m: &crate::scene::Material, emission: Decision) -> Vec<Decision> {
    let what = match &m.model {
        Model::Physical(_) => {
            "f sampled (Brdf::sample) for the next segment; f L cos / p from each light, emitter and the environment (MIS)"
        }
        Model::Mirror(_) => "a delta: the reflected ray, times the tint",
        Model::Glass(_) => "a delta: reflected with probability F, else refracted (times the tint)",
        Model::Classic(_) => "refused: a classic model is not a BRDF",
    };
    let mut terms = m.brdf().map_or(Vec::new(), |b| subsurface_walk(b, true));
    terms.push(decide("path vertex", !matches!(m.model, Model::Classic(_)), what));
    if let Model::Physical(crate::shading::brdf::Brdf::Principled(p)) = &m.model
        && p.transmits()
    {
        terms.push(decide(
            "specular transmission",
            p.glass_share() > 0.0,
            "a rough glass boundary (its ior, α = roughness²) at a (1 − metallic)·specular_transmission share of the vertices, each refraction tinted √C; inside, light is absorbed by exp(−σ_a d), σ_a = −ln(T_c)/d_T",
        ));
        terms.push(decide(
            "diffuse transmission",
            p.diffuse_transmission > 0.0,
            "d_t (1 − metallic) C/π to the other side of the surface (a Lambertian BTDF); next-event estimation also asks the lights behind it",
        ));
    }
    terms.push(emission);
    terms
}

/// What the path tracer's photon passes do, for `explain`: "" without them, else each
/// part after "; " (the caustic map, the global map and its final gather, or local light only).
fn photon_passes(p: &crate::lesson::settings::PathSettings) -> String {
    use crate::lesson::settings::{Caustics, Indirect, PhotonGather};
    let gathered = |r: f32| match p.photon_gather {
        PhotonGather::Radius => format!("within r = {r}"),
        PhotonGather::Nearest => format!("from the {} nearest within r = {r}", p.photon_nearest),
    };
    let mut parts = Vec::new();
    if p.caustics == Caustics::Photons {
        parts.push(format!(
            "caustics from a photon map gathered {}: {} photons from the rect, disk, sphere, point and spot lights through mirrors and glass",
            gathered(p.photon_radius),
            p.photons
        ));
    }
    match p.indirect {
        Indirect::Path => {}
        Indirect::Photons if p.gather_rays > 0 => parts.push(format!(
            "indirect light by a final gather: the global photon map of {} photons, gathered {}, read where {} rays from the first diffuse vertex land",
            p.global_photons,
            gathered(p.global_radius),
            p.gather_rays
        )),
        Indirect::Photons => parts.push(format!(
            "indirect light read from the global photon map of {} photons at the first diffuse vertex, {} (no final gather)",
            p.global_photons,
            gathered(p.global_radius)
        )),
        Indirect::None => parts.push("no indirect light: paths end at the first diffuse vertex (local illumination)".into()),
    }
    parts.iter().map(|t| format!("; {t}")).collect()
}

/// The path-tracing line's note of the materials with a random walk under their surface.
fn walks_under(scene: &Scene) -> String {
    let n = scene
        .materials
        .iter()
        .filter_map(|m| m.brdf())
        .filter(|b| matches!(b, crate::shading::brdf::Brdf::Principled(p) if crate::transport::path::subsurface::Interior::of(p).is_some()))
        .count();
    if n == 0 {
        return String::new();
    }
    format!(
        "; random-walk subsurface scattering for {n} of the materials, at most {} steps a walk",
        crate::transport::path::subsurface::MAX_STEPS
    )
}

/// A principled material's random walk under its surface (`subsurface_radius`): what the path
/// tracer does with it, or that the rasterizer does not (it keeps the flattened diffuse lobe).
fn subsurface_walk(brdf: &crate::shading::brdf::Brdf, path: bool) -> Vec<Decision> {
    let crate::shading::brdf::Brdf::Principled(p) = brdf else { return Vec::new() };
    if p.subsurface_radius == Vec3::ZERO {
        return Vec::new();
    }
    let r = p.subsurface_radius * p.subsurface_scale;
    let why = match (path, p.subsurface > 0.0) {
        (_, false) => "subsurface = 0: no light goes under the surface".to_string(),
        (true, true) => format!(
            "random walk under the surface for a share {} of the diffuse lobe: mean free path ({}, {}, {}), isotropic, at most {} steps",
            super::pixel_text::num(p.subsurface),
            super::pixel_text::num(r.x),
            super::pixel_text::num(r.y),
            super::pixel_text::num(r.z),
            crate::transport::path::subsurface::MAX_STEPS,
        ),
        (false, true) => "only method = \"path\" walks under the surface; here the flattened diffuse lobe stands for it".to_string(),
    };
    vec![decide("subsurface walk", path && p.subsurface > 0.0, why)]
}

/// Whether `pass` is needed for `scene` (lit by `n_lights` lights whose shadow methods are
/// `shadows`, from [`shadowing`]), and why: the one place each pass answers it.
pub fn needed(pass: Pass, scene: &Scene, n_lights: usize, shadows: &[Option<ShadowMethod>]) -> (bool, String) {
    let (g, s) = (&scene.geometry, &scene.spec.settings);
    let (w, h, aa) = (scene.spec.camera.width, scene.spec.camera.height, s.aa);
    let (tris, verts) = (g.triangles.len(), g.positions.len());
    let plural = if n_lights == 1 { "" } else { "s" };
    let radiosity = s.method == RenderMethod::Radiosity;
    let path = s.method == RenderMethod::Path;
    match pass {
        Pass::PathTrace if path => {
            let p = s.path;
            (
                true,
                format!(
                    "{} paths a pixel ({aa}² samples × spp {}), up to {} segments each, next-event estimation with MIS{}{}",
                    aa * aa * p.spp,
                    p.spp,
                    p.max_depth,
                    photon_passes(&p),
                    walks_under(scene),
                ),
            )
        }
        Pass::PathTrace => (false, "only method = \"path\" traces paths".into()),
        _ if path => (false, "the path tracer traces its own rays from the camera and finds its own light".into()),
        Pass::Radiosity => crate::effects::radiosity::needed(scene),
        Pass::LightVertices | Pass::LightFaces | Pass::ShadeSamples if radiosity => {
            (false, "radiosity bakes the radiance it displays (flat per patch or Gouraud per vertex)".into())
        }
        Pass::VertexStage => (tris > 0, format!("{verts} vertices to clip space")),
        Pass::ShadowRays => {
            let n = shadows.iter().filter(|m| **m == Some(ShadowMethod::Ray)).count();
            match n {
                0 => (false, "no light casts shadows by ray".into()),
                _ => (tris > 0, format!("BVH over {tris} triangles; any-hit shadow rays for {n} light{}", if n == 1 { "" } else { "s" })),
            }
        }
        Pass::ShadowMaps => {
            let n = shadows.iter().filter(|m| **m == Some(ShadowMethod::Map)).count();
            let m = s.shadow_map;
            match n {
                0 => (false, "no light casts shadows by map".into()),
                _ => (
                    tris > 0,
                    format!(
                        "depth from {n} light{} at {}² texels a face (bias {}, slope {}, normal offset {} texels, PCF {})",
                        if n == 1 { "" } else { "s" },
                        m.size,
                        m.bias,
                        m.slope_bias,
                        m.normal_offset,
                        m.pcf
                    ),
                ),
            }
        }
        Pass::ShadowVolumes => {
            let n = shadows.iter().filter(|m| **m == Some(ShadowMethod::Volume)).count();
            match n {
                0 => (false, "no light casts shadows by volume".into()),
                _ => (
                    tris > 0,
                    format!(
                        "silhouettes of {tris} triangles seen from {n} light{} extruded away from it; each sample counts the volume faces in front of it (z-pass)",
                        if n == 1 { "" } else { "s" }
                    ),
                ),
            }
        }
        Pass::ShadowPolygons => {
            let n = shadows.iter().filter(|m| **m == Some(ShadowMethod::Polygons)).count();
            match n {
                0 => (false, "no light casts shadows by polygons".into()),
                _ => (
                    tris > 0,
                    format!(
                        "{tris} receivers × {tris} occluders projected from {n} light{} (n² pairs); each sample tests its receiver's polygons",
                        if n == 1 { "" } else { "s" }
                    ),
                ),
            }
        }
        Pass::Environment => crate::effects::environment::needed(scene),
        Pass::ProbeCapture => crate::effects::probe::needed(scene),
        Pass::Refraction => crate::effects::refraction::needed(scene),
        Pass::LightVertices => match s.interpolation {
            Interpolation::Gouraud => (true, format!("Gouraud: {verts} vertices × {n_lights} light{plural}, colours interpolated")),
            _ => (false, "only Gouraud lights vertices".into()),
        },
        Pass::LightFaces => match s.interpolation {
            Interpolation::Flat => (true, format!("flat: {tris} faces × {n_lights} light{plural}, once each at the centroid")),
            _ => (false, "only flat shading lights faces".into()),
        },
        Pass::Raster => (tris > 0, format!("{tris} triangles on {}×{} samples (aa {aa}: {} per pixel)", w * aa, h * aa, aa * aa)),
        Pass::ShadeSamples => match s.interpolation {
            Interpolation::Phong => (tris > 0, format!("Phong: normals interpolated, {n_lights} light{plural} at every visible sample")),
            _ => (false, "Gouraud and flat interpolate lighting computed earlier".into()),
        },
        Pass::Fog => crate::effects::fog::needed(scene),
        Pass::Resolve => {
            (true, if aa > 1 { format!("box filter of {} samples per pixel", aa * aa) } else { "one sample per pixel".into() })
        }
    }
}

fn light_decision(i: usize, l: &Light, scene: &Scene) -> Decision {
    let what = format!("light {i} ({})", l.kind.name());
    if scene.spec.settings.method == RenderMethod::Radiosity {
        return decide(what, false, "not used: radiosity takes its light from emitting surfaces");
    }
    if scene.spec.settings.method == RenderMethod::Path {
        let why = match l.kind {
            LightKind::Ambient => {
                return decide(
                    what,
                    false,
                    "not used: an ambient light is not light transport (the path tracer finds indirect light itself)",
                );
            }
            LightKind::Rect(_) | LightKind::Disk(_) | LightKind::Sphere(_) => {
                "one point of its surface a path vertex, weighted by MIS against the BSDF's rays that cross it"
            }
            LightKind::Sky(_) => "one cosine-weighted direction a path vertex, weighted by MIS against the BSDF's rays that escape",
            LightKind::Line(_) => "one sample a path vertex (next-event estimation alone)",
            _ => "its incident at every path vertex (next-event estimation)",
        };
        return decide(what, true, why);
    }
    if l.radiance == Vec3::ZERO && l.ambient == Vec3::ZERO && l.ground().is_none_or(|g| g == Vec3::ZERO) {
        return decide(what, false, "culled: its colour × intensity is 0");
    }
    if let LightKind::Spot(Spot { position, direction, cos_cutoff, .. }) = l.kind {
        // The cone is limited by the cutoff, or by C_spot = 0 beyond 90° without one.
        let half_angle = cos_cutoff.max(0.0).acos();
        let reaches = |o: &crate::scene::build::ObjectBounds| {
            let to = o.centre - position;
            let d = to.length();
            if d <= o.radius {
                return true;
            }
            let phi = (to.dot(direction) / d).clamp(-1.0, 1.0).acos();
            phi - (o.radius / d).min(1.0).asin() <= half_angle
        };
        // In a scattering medium the cone lights the fog even where it misses every object.
        if !scene.geometry.objects.iter().any(reaches) && !crate::effects::fog::scatters(scene) {
            return decide(what, false, format!("culled: its {:.0}° cone misses every object", half_angle.to_degrees()));
        }
    }
    if l.kind.is_sampled() {
        // Sampled lights: how many samples, and whose (grain or steps).
        let whose = match scene.spec.settings.sample_pattern {
            crate::geometry::sampler::SamplePattern::PerPoint => "each point its own pattern",
            crate::geometry::sampler::SamplePattern::Shared => "one pattern for every point (steps, not grain)",
        };
        return decide(what, true, format!("reaches the scene; {} samples a point, {whose}", l.samples));
    }
    decide(what, true, "reaches the scene")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson;
    use std::path::Path;

    fn scene(text: &str) -> Scene {
        crate::scene::build::build(&lesson::parse(text, Path::new("t.toml"), &[]).unwrap()).unwrap()
    }

    const BASE: &str = "[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\nmodel = \"lambert\"\n";

    #[test]
    fn a_spot_aimed_away_is_culled_and_one_aimed_at_the_object_is_not() {
        let away = format!("{BASE}[[light]]\nkind = \"spot\"\nposition = [0, 3, 0]\ndirection = [0, 1, 0]\ncutoff_deg = 30\n");
        let at = format!("{BASE}[[light]]\nkind = \"spot\"\nposition = [0, 3, 0]\ndirection = [0, -1, 0]\ncutoff_deg = 30\n");
        // Aimed beside the sphere: 30° cone, axis 45° off the centre, sphere subtends ~20° → 45 − 20 < 30: reaches.
        let grazing = format!("{BASE}[[light]]\nkind = \"spot\"\nposition = [0, 3, 0]\ndirection = [1, -1, 0]\ncutoff_deg = 30\n");
        assert!(!plan(&scene(&away)).lights[0].runs);
        assert!(plan(&scene(&at)).lights[0].runs);
        assert!(plan(&scene(&grazing)).lights[0].runs);
    }

    #[test]
    fn a_sampled_light_says_its_samples_and_whose_they_are() {
        let rect = format!("{BASE}[[light]]\nkind = \"rect\"\nposition = [0, 3, 0]\ndirection = [0, -1, 0]\nsize = [1, 1]\nsamples = 64\n");
        let why = |extra: &str| plan(&scene(&format!("{rect}{extra}"))).lights[0].why.clone();
        assert_eq!(why(""), "reaches the scene; 64 samples a point, each point its own pattern");
        assert!(why("[render]\nsample_pattern = \"shared\"\n").ends_with("one pattern for every point (steps, not grain)"));
    }

    #[test]
    fn lambert_skips_specular_and_gouraud_skips_per_sample_lighting() {
        let text = format!("{BASE}[[light]]\nkind = \"directional\"\ndirection = [0, 0, -1]\n[render]\ninterpolation = \"gouraud\"\n");
        let p = plan(&scene(&text));
        let spec = p.terms[0].iter().find(|d| d.what == "specular").unwrap();
        assert!(!spec.runs && spec.why.contains("lambert"));
        assert_eq!(p.running().collect::<Vec<_>>(), [Pass::VertexStage, Pass::LightVertices, Pass::Raster, Pass::Resolve]);
    }
}
