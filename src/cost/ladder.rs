//! Quality ladders: one approximation stepped from cheap to exact, each rung an override set.
//!
//! A ladder may name its own reference ([`NamedReference`]): the shadow ladders compare with
//! the lesson's ray-cast shadows, `area_samples` with the exact rect-light irradiance or a
//! 4096-sample render. The others leave the choice to [`super::measure`] (the exact ray cast
//! of the analytic shapes, or the finest rung).

use super::rungs::{Ladder, NamedReference, Rung, set};
use crate::effects::shadows::{can_occlude, shadowing};
use crate::lesson::kinds::LightType;
use crate::lesson::limits::{MAX_BOUNCES, MAX_DEPTH, MAX_SPP};
use crate::lesson::settings::RenderMethod;
use crate::lesson::{Interpolation, LadderKind, Lesson, Override};
use crate::light::LightKind;
use crate::scene::{Scene, Shape};
use crate::shading::brdf::Brdf;
use crate::shading::material::Model;
use crate::shading::microfacet::Fresnel;

/// Segments around each curved object (a sphere's rings, a torus's sides: half as many) of
/// the `shadow_methods` ladder.
pub const SHADOW_METHOD_SEGMENTS: [i64; 4] = [8, 16, 32, 64];
/// The hard-shadow methods the `shadow_methods` ladder compares, each a series.
pub const SHADOW_METHODS: [&str; 4] = ["ray", "map", "volume", "polygons"];

/// Shadow-map sizes of the `shadow_map` ladder, in texels per side.
pub const SHADOW_MAP_SIZES: [i64; 5] = [256, 512, 1024, 2048, 4096];
/// Filter widths of the `pcf` ladder, in texels.
pub const PCF_WIDTHS: [i64; 4] = [1, 3, 5, 9];
/// Samples per light of the `area_samples` ladder.
pub const AREA_SAMPLES: [i64; 5] = [1, 4, 16, 64, 256];
/// Samples per sampled light of each series of the `sampler` ladder.
pub const SAMPLER_COUNTS: [i64; 3] = [4, 16, 64];
/// Ray-march steps per sample of the `fog_steps` ladder.
pub const FOG_STEPS: [i64; 4] = [4, 16, 64, 256];
/// Samples per eye ray of the `fog_steps` reference, equiangular: four times the best rung's,
/// whose error it must undercut by a factor of four (docs/accuracy-and-cost.md, "The
/// reference": measured 1.37e-6 against 4096 samples, where the best rung has 5.9e-6).
pub const FOG_REFERENCE_STEPS: i64 = 1024;
/// Samples per light of the `area_samples` reference when there is no closed form.
pub const AREA_REFERENCE_SAMPLES: i64 = 4096;
/// Constant depth biases of the `shadow_bias` ladder, in world units, with their labels
/// (every rung also sets `shadow_slope_bias` and `shadow_normal_offset` to 0).
pub const SHADOW_BIASES: [(&str, f64); 6] = [("0", 0.0), ("0.001", 0.001), ("0.005", 0.005), ("0.02", 0.02), ("0.1", 0.1), ("0.5", 0.5)];

/// The rungs of `kind` for `lesson`, or why the ladder does not apply to it.
///
/// # Errors
/// As [`ladder`].
pub fn rungs(kind: LadderKind, lesson: &Lesson) -> Result<Vec<Rung>, String> {
    ladder(kind, lesson).map(|l| l.rungs)
}

/// The rungs of `kind` for `lesson` and the reference it names, or why it does not apply.
///
/// # Errors
/// A sentence naming what the lesson lacks (no sphere to tessellate, no physically based
/// material for the Fresnel ladder, no light a shadow map can serve, nothing that can cast
/// a shadow, no sampled light), or why its scene cannot be built.
pub fn ladder(kind: LadderKind, lesson: &Lesson) -> Result<Ladder, String> {
    let rung = |name: String, sets: Vec<Override>| Rung { name, sets, exact: false, series: String::new() };
    // The reference is the exact ray cast or the finest rung (`measure` decides), or the ladder's own.
    let plain = |rungs: Vec<Rung>| Ok(Ladder { rungs, reference: None });
    let own = |rungs: Vec<Rung>, reference: NamedReference| Ok(Ladder { rungs, reference: Some(reference) });
    let map = || set("render.shadows", "map".into());
    match kind {
        LadderKind::Interpolation => {
            let mut r: Vec<Rung> =
                ["flat", "gouraud", "phong"].iter().map(|i| rung((*i).into(), vec![set("render.interpolation", (*i).into())])).collect();
            r.push(Rung { name: "exact".into(), sets: Vec::new(), exact: true, series: String::new() });
            plain(r)
        }
        LadderKind::InterpolationSpace => {
            // Only Gouraud and Phong interpolate: flat shading is the same in both spaces.
            if lesson.scene.settings.interpolation == Interpolation::Flat {
                return Err("the interpolation_space ladder needs Gouraud or Phong interpolation (flat interpolates nothing)".into());
            }
            plain(
                ["screen", "perspective"].iter().map(|s| rung((*s).into(), vec![set("render.interpolation_space", (*s).into())])).collect(),
            )
        }
        LadderKind::NormalTransform => {
            if lesson.scene.settings.interpolation == Interpolation::Flat {
                return Err("the normal_transform ladder needs Gouraud or Phong interpolation (flat uses face normals)".into());
            }
            plain(
                ["naive", "inverse_transpose"]
                    .iter()
                    .map(|s| rung((*s).into(), vec![set("render.normal_transform", (*s).into())]))
                    .collect(),
            )
        }
        LadderKind::Tessellation => match lesson.objects.first().map(|o| &o.shape) {
            Some(Shape::UvSphere { .. }) => plain(
                [8i64, 16, 32, 64, 128, 256]
                    .iter()
                    .map(|s| {
                        rung(format!("{s}×{}", s / 2), vec![set("object.0.segments", (*s).into()), set("object.0.rings", (s / 2).into())])
                    })
                    .collect(),
            ),
            Some(Shape::Icosphere { .. }) => {
                plain((0i64..=6).map(|s| rung(format!("subdivisions {s}"), vec![set("object.0.subdivisions", s.into())])).collect())
            }
            Some(Shape::Torus { .. }) => plain(
                [12i64, 24, 48, 96, 192]
                    .iter()
                    .map(|s| {
                        rung(format!("{s}×{}", s / 2), vec![set("object.0.segments", (*s).into()), set("object.0.sides", (s / 2).into())])
                    })
                    .collect(),
            ),
            _ => Err("the tessellation ladder needs a uv_sphere, icosphere or torus as the first object".into()),
        },
        LadderKind::Aa => plain([1i64, 2, 4, 8].iter().map(|a| rung(format!("aa {a}"), vec![set("render.aa", (*a).into())])).collect()),
        LadderKind::Fresnel => {
            let names: Vec<&str> = lesson
                .materials
                .iter()
                .filter(|m| match m.brdf() {
                    // Conductors have their own exact Fresnel; the ladder compares dielectric ones.
                    Some(Brdf::CookTorrance(c)) => !matches!(c.fresnel, Fresnel::Conductor { .. } | Fresnel::None),
                    _ => false,
                })
                .map(|m| m.name.as_str())
                .collect();
            if names.is_empty() {
                return Err("the fresnel ladder needs a cook_torrance material with a dielectric (schlick or dielectric) Fresnel".into());
            }
            let all = |f: &str| names.iter().map(|n| set(&format!("material.{n}.fresnel"), f.into())).collect();
            plain(vec![rung("schlick".into(), all("schlick")), rung("exact".into(), all("dielectric"))])
        }
        LadderKind::ShadowMethods => {
            shadow_ladder_applies(kind, lesson)?;
            // Every sphere and torus gets finer together: the occluders' triangles grow as n².
            let fine = |n: i64| -> Vec<Override> {
                lesson
                    .objects
                    .iter()
                    .enumerate()
                    .flat_map(|(i, o)| match o.shape {
                        Shape::UvSphere { .. } => {
                            vec![set(&format!("object.{i}.segments"), n.into()), set(&format!("object.{i}.rings"), (n / 2).into())]
                        }
                        Shape::Torus { .. } => {
                            vec![set(&format!("object.{i}.segments"), n.into()), set(&format!("object.{i}.sides"), (n / 2).into())]
                        }
                        _ => Vec::new(),
                    })
                    .collect()
            };
            if fine(8).is_empty() {
                return Err("the shadow_methods ladder needs a uv_sphere or a torus to tessellate".into());
            }
            let r = SHADOW_METHODS.iter().flat_map(|m| {
                SHADOW_METHOD_SEGMENTS.iter().map(move |n| {
                    let mut sets = vec![set("render.shadows", (*m).into())];
                    sets.extend(fine(*n));
                    Rung { name: format!("{m} {n}"), sets, exact: false, series: (*m).into() }
                })
            });
            let finest = *SHADOW_METHOD_SEGMENTS.last().expect("not empty");
            let mut sets = vec![set("render.shadows", "ray".into())];
            sets.extend(fine(finest));
            let reference = NamedReference {
                name: format!("ray-cast shadows, {finest} segments"),
                sets,
                exact_area: false,
                describe: format!(
                    "the lesson with `[render] shadows = \"ray\"` and every sphere and torus at {finest} segments (the finest \
                     rung's meshes), rendered by the rasterizer: a rung's error is its coarser mesh plus its method's own"
                ),
            };
            own(r.collect(), reference)
        }
        LadderKind::ShadowMap => {
            shadow_ladder_applies(kind, lesson)?;
            let r = SHADOW_MAP_SIZES.iter().map(|n| rung(format!("map {n}"), vec![map(), set("render.shadow_map_size", (*n).into())]));
            own(r.collect(), ray_reference())
        }
        LadderKind::Pcf => {
            shadow_ladder_applies(kind, lesson)?;
            let r = PCF_WIDTHS.iter().map(|n| rung(format!("pcf {n}"), vec![map(), set("render.shadow_pcf", (*n).into())]));
            own(r.collect(), ray_reference())
        }
        LadderKind::ShadowBias => {
            shadow_ladder_applies(kind, lesson)?;
            // The constant bias alone: with the slope bias and the normal offset at 0 nothing
            // else keeps acne away, so both ends of the trade show.
            let alone = || vec![map(), set("render.shadow_slope_bias", 0.0.into()), set("render.shadow_normal_offset", 0.0.into())];
            let r = SHADOW_BIASES.iter().map(|(label, b)| {
                let mut sets = alone();
                sets.push(set("render.shadow_bias", (*b).into()));
                rung(format!("bias {label}"), sets)
            });
            own(r.collect(), ray_reference())
        }
        LadderKind::FogSteps => {
            if !lesson.scene.fog.is_some_and(|f| f.medium().is_some_and(|m| m.sigma_s > 0.0)) {
                return Err(
                    "the fog_steps ladder needs `[fog] kind = \"medium\"` with sigma_s > 0 (only a scattering medium is marched)".into()
                );
            }
            // Both ways of placing the samples along the eye ray, each a series.
            let r = ["uniform", "equiangular"]
                .iter()
                .flat_map(|how| {
                    FOG_STEPS.iter().map(move |n| Rung {
                        name: format!("{how} {n}"),
                        sets: vec![set("fog.sampling", (*how).into()), set("fog.steps", (*n).into())],
                        exact: false,
                        series: (*how).into(),
                    })
                })
                .collect();
            let reference = NamedReference {
                name: format!("{FOG_REFERENCE_STEPS} equiangular samples"),
                sets: vec![set("fog.sampling", "equiangular".into()), set("fog.steps", FOG_REFERENCE_STEPS.into())],
                exact_area: false,
                describe: format!(
                    "the lesson with {FOG_REFERENCE_STEPS} equiangular samples per point or spot light per eye ray (and \
                     {FOG_REFERENCE_STEPS} march steps for directional lights), rendered by the rasterizer (both converge to the \
                     closed form of Sun et al. 2005 for a point light's airlight: src/transport/medium/tests.rs)"
                ),
            };
            own(r, reference)
        }
        LadderKind::AreaSamples | LadderKind::Sampler => {
            let sampled: Vec<usize> = lesson.scene.lights.iter().enumerate().filter(|(_, l)| l.kind.is_sampled()).map(|(i, _)| i).collect();
            if sampled.is_empty() {
                return Err(format!("the {} ladder needs a sampled light (rect, disk, sphere, line or sky)", kind.name()));
            }
            // The lights whose samples can be placed by area or by solid angle.
            let placed: Vec<usize> = sampled
                .iter()
                .copied()
                .filter(|i| matches!(lesson.scene.lights[*i].kind, LightType::Rect | LightType::Sphere | LightType::Line))
                .collect();
            let all = |n: i64| sampled.iter().map(|i| set(&format!("light.{i}.samples"), n.into())).collect::<Vec<_>>();
            let series = |name: &str, extra: &dyn Fn() -> Vec<Override>, counts: &[i64]| -> Vec<Rung> {
                counts
                    .iter()
                    .map(|n| {
                        let mut sets = extra();
                        sets.extend(all(*n));
                        Rung { name: format!("{name} {n}"), sets, exact: false, series: name.to_string() }
                    })
                    .collect()
            };
            let r: Vec<Rung> = if kind == LadderKind::Sampler {
                // Where the samples fall, at three counts each.
                ["independent", "stratified", "sobol"]
                    .iter()
                    .flat_map(|s| series(s, &|| vec![set("render.sampler", (*s).into())], &SAMPLER_COUNTS))
                    .collect()
            } else if placed.is_empty() {
                AREA_SAMPLES.iter().map(|n| rung(format!("samples {n}"), all(*n))).collect()
            } else {
                // How a sample becomes a point of the light, each way a series.
                let how = |m: &'static str| placed.iter().map(|i| set(&format!("light.{i}.sampling"), m.into())).collect::<Vec<_>>();
                let mut r = series("by area", &|| how("area"), &AREA_SAMPLES);
                r.extend(series("by solid angle", &|| how("solid_angle"), &AREA_SAMPLES));
                r
            };
            let scene = scene_of(lesson)?;
            let reference = match no_closed_form(&scene) {
                None => NamedReference {
                    name: "the exact rect-light irradiance".into(),
                    sets: Vec::new(),
                    exact_area: true,
                    describe: "the exact unoccluded rect-light irradiance by Lambert's polygon formula, rendered by the rasterizer: \
                               exact for the diffuse term of a Lambertian receiver (here every sampled light is a rect light, \
                               every material diffuse-only, and nothing can block the lights)"
                        .into(),
                },
                Some(why) => NamedReference {
                    name: format!("{AREA_REFERENCE_SAMPLES} samples a light"),
                    sets: all(AREA_REFERENCE_SAMPLES),
                    exact_area: false,
                    describe: format!(
                        "every sampled light at {AREA_REFERENCE_SAMPLES} samples (the lesson's sampler and sampling), rendered by \
                         the rasterizer (no closed form: {why})"
                    ),
                },
            };
            own(r, reference)
        }
        LadderKind::Ibl => {
            environment_ladder_applies(kind, lesson)?;
            let r = ["sh", "prefiltered", "reference"].iter().map(|i| rung((*i).into(), vec![set("render.ibl", (*i).into())]));
            own(r.collect(), ibl_reference(IBL_REFERENCE_SAMPLES))
        }
        LadderKind::EnvSamples => {
            environment_ladder_applies(kind, lesson)?;
            let r = ENV_SAMPLES
                .iter()
                .map(|n| rung(format!("{n} samples"), vec![set("render.ibl", "reference".into()), set("render.env_samples", (*n).into())]));
            own(r.collect(), ibl_reference(ENV_REFERENCE_SAMPLES))
        }
        LadderKind::PrefilterSize => {
            environment_ladder_applies(kind, lesson)?;
            let r = PREFILTER_SIZES.iter().map(|n| {
                rung(format!("size {n}"), vec![set("render.ibl", "prefiltered".into()), set("render.prefilter_size", (*n).into())])
            });
            own(r.collect(), ibl_reference(IBL_REFERENCE_SAMPLES))
        }
        LadderKind::Patches | LadderKind::Hemicube | LadderKind::Iterations => super::radiosity::ladder(kind, lesson),
        LadderKind::Probe => {
            if lesson.scene.probes.is_empty() || !lesson.materials.iter().any(|m| matches!(m.model, Model::Mirror(_))) {
                return Err("the probe ladder needs a [[probe]] and a mirror material".into());
            }
            let r = [("naive", "probe"), ("box", "probe_box")].into_iter().flat_map(|(label, how)| {
                PROBE_SIZES.iter().map(move |n| {
                    let mut sets = vec![set("render.reflections", how.into())];
                    sets.extend((0..lesson.scene.probes.len()).map(|i| set(&format!("probe.{i}.size"), (*n).into())));
                    rung(format!("{label} {n}"), sets)
                })
            });
            let reference = NamedReference {
                name: "the traced reflection".into(),
                sets: vec![set("render.reflections", "traced".into())],
                exact_area: false,
                describe: "the lesson with `[render] reflections = \"traced\"` (each mirror's reflected ray through the BVH, \
                           the hit shaded as the camera would see it), rendered by the rasterizer"
                    .into(),
            };
            own(r.collect(), reference)
        }
        LadderKind::MaxBounces => {
            if !lesson.materials.iter().any(|m| matches!(m.model, Model::Glass(_))) {
                return Err("the max_bounces ladder needs a `glass` material".into());
            }
            let r = BOUNCES.iter().map(|n| rung(format!("bounces {n}"), vec![set("render.max_bounces", (*n).into())]));
            let reference = NamedReference {
                name: format!("{MAX_BOUNCES} bounces"),
                sets: vec![set("render.max_bounces", MAX_BOUNCES.into())],
                exact_area: false,
                describe: format!(
                    "the lesson with `[render] max_bounces = {MAX_BOUNCES}` (the most it allows): every path through the glass that \
                     reflects or refracts up to {MAX_BOUNCES} times, rendered by the rasterizer and the glass pass"
                ),
            };
            own(r.collect(), reference)
        }
        LadderKind::Spp | LadderKind::MaxDepth => {
            if lesson.scene.settings.method != RenderMethod::Path {
                return Err(format!("the {} ladder needs `[render] method = \"path\"`", kind.name()));
            }
            let spp = lesson.scene.settings.path.spp;
            if kind == LadderKind::Spp {
                let r = SPP.iter().map(|n| rung(format!("spp {n}"), vec![set("render.spp", (*n).into())]));
                let reference = NamedReference {
                    name: format!("{SPP_REFERENCE} paths"),
                    sets: vec![set("render.spp", SPP_REFERENCE.into())],
                    exact_area: false,
                    describe: format!(
                        "the lesson path traced with {SPP_REFERENCE} paths a pixel sample: its noise is a quarter of the best rung's \
                         (1/√16), so it adds at most 3 % to that rung's measured error"
                    ),
                };
                return own(r.collect(), reference);
            }
            let r = DEPTHS.iter().map(|n| rung(format!("depth {n}"), vec![set("render.max_depth", (*n).into())]));
            let paths = (i64::from(spp) * 16).min(MAX_SPP);
            let reference = NamedReference {
                name: format!("depth {MAX_DEPTH}, {paths} paths"),
                sets: vec![set("render.max_depth", MAX_DEPTH.into()), set("render.spp", paths.into())],
                exact_area: false,
                describe: format!(
                    "the lesson path traced with paths of up to {MAX_DEPTH} segments (the most allowed) and {paths} paths a pixel \
                     sample (16 × the rungs', so a quarter of their noise): each rung's error is the light its shorter paths \
                     leave out plus its own noise"
                ),
            };
            own(r.collect(), reference)
        }
        LadderKind::TextureFilter => {
            if lesson.material_maps.iter().all(|m| m.is_empty()) {
                return Err(
                    "the texture_filter ladder needs a material with a texture (e.g. `diffuse = { checker = { scale = 8 } }`)".into()
                );
            }
            let r = ["nearest", "bilinear", "trilinear"].iter().map(|f| rung((*f).into(), vec![set("render.texture_filter", (*f).into())]));
            let reference = NamedReference {
                name: format!("bilinear, aa {TEXTURE_REFERENCE_AA}"),
                sets: vec![set("render.texture_filter", "bilinear".into()), set("render.aa", TEXTURE_REFERENCE_AA.into())],
                exact_area: false,
                describe: format!(
                    "the lesson with {n} × {n} samples a pixel, each reading the full-size texture bilinearly: the box filter of \
                     the pixel over the texture, which mip-mapping approximates with one lookup",
                    n = TEXTURE_REFERENCE_AA
                ),
            };
            own(r.collect(), reference)
        }
    }
}

/// Face sizes of the `probe` ladder, in texels per side (each for the naive and the box-projected lookup).
pub const PROBE_SIZES: [i64; 4] = [32, 64, 128, 256];
/// `max_bounces` of the `max_bounces` ladder (its reference is [`MAX_BOUNCES`]).
pub const BOUNCES: [i64; 5] = [1, 2, 3, 4, 8];
/// Paths a pixel sample of the `spp` ladder.
pub const SPP: [i64; 5] = [1, 4, 16, 64, 256];
/// Paths a pixel sample of the `spp` reference: 16 × the best rung's, a quarter of its noise.
pub const SPP_REFERENCE: i64 = 4096;
/// `max_depth` of the `max_depth` ladder (its reference is [`MAX_DEPTH`]).
pub const DEPTHS: [i64; 5] = [1, 2, 3, 4, 8];
/// Supersamples per pixel side of the `texture_filter` reference.
pub const TEXTURE_REFERENCE_AA: i64 = 8;

/// Samples per point of the `env_samples` ladder.
pub const ENV_SAMPLES: [i64; 5] = [16, 64, 256, 1024, 4096];
/// Samples per point of the reference of the `env_samples` ladder.
pub const ENV_REFERENCE_SAMPLES: i64 = 16384;
/// Samples per point of the Monte Carlo reference of the `ibl` and `prefilter_size` ladders:
/// eight times the best rung's 256, whose error it must undercut by a factor of four
/// (docs/accuracy-and-cost.md, "The reference": 0.028 against 16384 samples, where 256
/// samples have 0.138; the Sobol points converge faster than 1/√N).
pub const IBL_REFERENCE_SAMPLES: i64 = 2048;
/// Widths of the `prefilter_size` ladder.
pub const PREFILTER_SIZES: [i64; 5] = [32, 64, 128, 256, 512];

/// The Monte Carlo reference of the environment ladders, at `samples` per point.
fn ibl_reference(samples: i64) -> NamedReference {
    NamedReference {
        name: format!("Monte Carlo IBL, {samples} samples"),
        sets: vec![set("render.ibl", "reference".into()), set("render.env_samples", samples.into())],
        exact_area: false,
        describe: format!(
            "`[render] ibl = \"reference\"` at {samples} samples a point (luminance and BRDF sampling by MIS), rendered by the rasterizer"
        ),
    }
}

/// Checks that an environment ladder changes something: an `[environment]` and a physically based material.
fn environment_ladder_applies(kind: LadderKind, lesson: &Lesson) -> Result<(), String> {
    if lesson.environment.is_none() || !lesson.materials.iter().any(|m| m.brdf().is_some()) {
        return Err(format!("the {} ladder needs an [environment] and a physically based material", kind.name()));
    }
    Ok(())
}

/// The reference of the shadow ladders: the lesson with ray-cast shadows.
fn ray_reference() -> NamedReference {
    NamedReference {
        name: "ray-cast shadows".into(),
        sets: vec![set("render.shadows", "ray".into())],
        exact_area: false,
        describe: "the lesson with `[render] shadows = \"ray\"` (a shadow ray per light sample through the BVH: exact hard \
                   shadows), rendered by the rasterizer"
            .into(),
    }
}

/// The scene of `lesson`, or why it cannot be built.
fn scene_of(lesson: &Lesson) -> Result<Scene, String> {
    crate::scene::build::build(lesson).map_err(|e| format!("its scene cannot be built: {e}"))
}

/// Checks that a shadow ladder changes something on `lesson`: a directional, point or spot
/// light that follows `[render] shadows` (lights that set their own `shadows` keep it in every
/// rung and in the reference), and something that can block it.
fn shadow_ladder_applies(kind: LadderKind, lesson: &Lesson) -> Result<(), String> {
    let name = kind.name();
    let served = lesson
        .scene
        .lights
        .iter()
        .any(|l| l.shadows.is_none() && matches!(l.kind, LightType::Directional | LightType::Point | LightType::Spot));
    if !served {
        return Err(format!(
            "the {name} ladder needs a directional, point or spot light without its own `shadows` (only those cast a \
             shadow map that `[render]` sets)"
        ));
    }
    if !can_occlude(&scene_of(lesson)?) {
        return Err(format!(
            "the {name} ladder needs something that can cast a shadow: two or more objects, or a torus or a mesh that is \
             not convex (one convex or flat object shadows only itself, where N·L ≤ 0)"
        ));
    }
    Ok(())
}

/// Why the sampled lights of `scene` have no closed form that Lambert's polygon formula gives
/// exactly, or `None` when they do: every sampled light a rect light that nothing blocks,
/// every material diffuse-only (Lambert, or the physically based `diffuse`).
fn no_closed_form(scene: &Scene) -> Option<String> {
    for (i, l) in scene.lights.iter().enumerate().filter(|(_, l)| l.kind.is_sampled()) {
        if !matches!(l.kind, LightKind::Rect(_)) {
            return Some(format!("light {i} is not a rect light"));
        }
        if shadowing(l, scene).method.is_some() {
            return Some(format!("something can block light {i}"));
        }
    }
    for m in &scene.materials {
        let diffuse_only = match &m.model {
            Model::Classic(c) => !c.has_specular(),
            Model::Physical(b) => matches!(b, Brdf::Diffuse(_)),
            Model::Mirror(_) | Model::Glass(_) => false,
        };
        if !diffuse_only {
            return Some(format!("material `{}` is not diffuse-only", m.name));
        }
    }
    None
}

#[cfg(test)]
#[path = "ladder_tests.rs"]
mod tests;
