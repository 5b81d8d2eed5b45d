//! The work and memory budget: what one render will cost, estimated from the scene and its
//! plan before any work, and refused when over the budget.
//!
//! Every limit in `lesson::limits` bounds one value; the budget bounds their products (four
//! point lights at the largest shadow map, 4096 fog steps on a large supersampled frame,
//! a fine radiosity mesh with a large hemicube). The estimate is a sum of terms, each a
//! count the plan implies (samples, rays, march steps, texels, patch pairs) times a cost per
//! unit measured on one core (AMD EPYC Zen 4; docs/performance.md, "The budget"), and the
//! bytes that count keeps. The counts are tested against the render's own counters and the
//! memory against the process's peak (tests/integration/budget.rs); the seconds are a model,
//! within a factor of about three of a measured render.
//!
//! A user raises the budget on purpose with `--budget FACTOR` ([`configure`]).

use crate::effects::shadows::map::faces_for;
use crate::lesson::settings::{FormFactorMethod, Ibl, Interpolation};
use crate::light::{LightKind, ShadowMethod};
use crate::render::plan::{Pass, plan};
use crate::scene::Scene;
use std::sync::atomic::{AtomicU64, Ordering};

/// Work one render may take by default: 5 minutes of one core, as estimated. Every bundled
/// lesson's render, figure cell and cost reference is within it (`figures lessons/`); the
/// largest lesson render is estimated at 8.6 s (lesson 26, fog).
pub const DEFAULT_SECONDS: f64 = 300.0;
/// Memory one render may keep by default: 4 GiB, a sixth of a 24 GB machine (the bundled
/// lessons' largest render is estimated at 86 MB, lesson 27).
pub const DEFAULT_BYTES: f64 = 4.0 * (1u64 << 30) as f64;
/// The largest `--budget` factor: 1000 × the default is days of work and terabytes.
pub const MAX_FACTOR: f64 = 1000.0;

/// Nanoseconds per unit of each term on one core (AMD EPYC Zen 4, 2026-12; each measured by
/// timing a lesson dominated by that term and dividing by its count).
mod ns {
    /// One image sample rasterized, shaded with its terms and resolved.
    pub const SAMPLE: f64 = 60.0;
    /// One light evaluated at a sample (or vertex, or face).
    pub const LIGHT: f64 = 40.0;
    /// One point sampled on an area, line or sky light.
    pub const LIGHT_SAMPLE: f64 = 60.0;
    /// One shadow ray through the BVH.
    pub const SHADOW_RAY: f64 = 110.0;
    /// One shadow-map texel rendered.
    pub const MAP_TEXEL: f64 = 2.0;
    /// One shadow-volume quad tested against a point's eye segment (lesson 45 with
    /// `shadows = "volume"` at 32 segments: 74 M tests, 1.4 s on 2 threads; see
    /// docs/accuracy-and-cost.md, "Classic shadow algorithms").
    pub const VOLUME_QUAD: f64 = 25.0;
    /// One (receiver, occluder) pair of the estimate, with pass 2's share: lesson 45 with
    /// `shadows = "polygons"` at 64 segments, 32.6 M pairs estimated (14.2 M projected, the
    /// rest face away) and 967 M point-in-polygon tests took 3.9 s on 2 threads.
    pub const POLYGON_PAIR: f64 = 200.0;
    /// One fog march step per light.
    pub const FOG_STEP: f64 = 15.0;
    /// One environment sample (BRDF and map importance sampling, MIS weights, lookups).
    pub const ENV_SAMPLE: f64 = 60.0;
    /// One lookup of the prefilter's GGX convolution.
    pub const PREFILTER_LOOKUP: f64 = 150.0;
    /// One texel of the environment map through its setup (luminance tables, irradiance, albedo tables).
    pub const ENV_TEXEL: f64 = 1000.0;
    /// One probe texel rendered (as an image sample).
    pub const PROBE_TEXEL: f64 = SAMPLE;
    /// One glass ray (intersection, Fresnel split).
    pub const GLASS_RAY: f64 = 150.0;
    /// One path segment: its closest-hit ray, the BSDF sample, and next-event rays to the
    /// emitters and the environment (measured: lesson 27's box, 1.48 CPU s for 3.27 M segments).
    pub const PATH_SEGMENT: f64 = 450.0;
    /// One triangle through the vertex stage, and into a BVH when rays are cast.
    pub const TRIANGLE: f64 = 40.0;
    /// ... and into the BVH.
    pub const TRIANGLE_BVH: f64 = 250.0;
    /// One patch drawn onto one hemicube (five faces: setup and clipping).
    pub const HEMICUBE_PATCH: f64 = 240.0;
    /// One hemicube cell read back per patch.
    pub const HEMICUBE_CELL: f64 = 25.0;
    /// One patch pair by ray casting: the polygon's form factor and four visibility rays.
    pub const PATCH_PAIR_RAYS: f64 = 300.0;
    /// One multiply-add of a solver iteration.
    pub const SOLVE: f64 = 1.5;
}

/// One term of an estimate: a count of work with its time and the bytes it keeps.
#[derive(Debug, Clone, PartialEq)]
pub struct Term {
    /// What is counted, e.g. "shadow rays".
    pub what: &'static str,
    /// How the count comes about, e.g. "65536 samples × 64 samples of 1 light".
    pub how: String,
    /// The lesson key that sets its size most directly, e.g. "render.fog.steps" ("" for none).
    pub key: &'static str,
    /// The count.
    pub count: f64,
    /// Estimated seconds on one core.
    pub seconds: f64,
    /// Estimated bytes kept while the render runs.
    pub bytes: f64,
}

/// What one render is estimated to cost.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Estimate {
    /// The terms, in pipeline order.
    pub terms: Vec<Term>,
}

impl Estimate {
    /// Estimated seconds of work on one core.
    pub fn seconds(&self) -> f64 {
        self.terms.iter().map(|t| t.seconds).sum()
    }

    /// Estimated peak bytes.
    pub fn bytes(&self) -> f64 {
        self.terms.iter().map(|t| t.bytes).sum()
    }

    /// The count of the term `what` (0 when there is none).
    pub fn count(&self, what: &str) -> f64 {
        self.terms.iter().filter(|t| t.what == what).map(|t| t.count).sum()
    }

    /// The terms with the most work (or memory), largest first, at most `n`.
    fn largest(&self, n: usize, key: impl Fn(&Term) -> f64) -> Vec<&Term> {
        let mut v: Vec<&Term> = self.terms.iter().filter(|t| key(t) > 0.0).collect();
        v.sort_by(|a, b| key(b).total_cmp(&key(a)));
        v.truncate(n);
        v
    }

    /// One line: "≈ 1.2 s of work on one core, 85 MB".
    pub fn summary(&self) -> String {
        format!("≈ {} of work on one core, {}", seconds(self.seconds()), bytes(self.bytes()))
    }

    /// The estimate term by term, for `explain`: each with its count, time and memory, the
    /// terms' names in `lang`.
    pub fn table(&self, lang: crate::lesson::i18n::Lang) -> Vec<String> {
        self.terms
            .iter()
            .map(|t| {
                let name = crate::render::explain::pad(lang.tr(t.what), 28);
                format!("{name} {:>10}  {:>9}  {:>9}   {}", count(t.count), seconds(t.seconds), bytes(t.bytes), t.how)
            })
            .collect()
    }
}

/// A count with an SI suffix: 950, 12.3 k, 4.19 M, 1.07 G.
pub fn count(x: f64) -> String {
    match x {
        x if x >= 1e12 => format!("{:.3} T", x / 1e12),
        x if x >= 1e9 => format!("{:.3} G", x / 1e9),
        x if x >= 1e6 => format!("{:.3} M", x / 1e6),
        x if x >= 1e4 => format!("{:.1} k", x / 1e3),
        x => format!("{x:.0}"),
    }
}

/// Seconds as a person reads them: 12 ms, 3.4 s, 12 min, 5.0 h.
pub fn seconds(s: f64) -> String {
    match s {
        s if s >= 3600.0 * 48.0 => format!("{:.0} h", s / 3600.0),
        s if s >= 3600.0 => format!("{:.1} h", s / 3600.0),
        s if s >= 600.0 => format!("{:.0} min", s / 60.0),
        s if s >= 10.0 => format!("{s:.0} s"),
        s if s >= 1.0 => format!("{s:.1} s"),
        s => format!("{:.0} ms", (s * 1e3).max(if s > 0.0 { 1.0 } else { 0.0 })),
    }
}

/// Bytes in MB or GB (decimal, as `check` and the docs print them).
pub fn bytes(b: f64) -> String {
    if b >= 1e9 { format!("{:.2} GB", b / 1e9) } else { format!("{:.0} MB", (b / 1e6).max(if b > 0.0 { 1.0 } else { 0.0 })) }
}

/// The lesson key a user lowers to shrink the term `what`.
fn key_of(what: &str) -> &'static str {
    match what {
        "image samples" | "lights × points" => "camera.size` or `render.aa",
        "area-light samples" | "shadow rays" => "samples` of the lights or `render.aa",
        "shadow-map texels" => "render.shadow_map_size",
        "shadow-volume quad tests" | "shadow-polygon pairs" => "render.shadows` or the meshes' triangles",
        "fog march steps" => "fog.steps",
        "path segments" => "render.spp` or `render.max_depth",
        "photon segments" => "render.photons` or `render.global_photons",
        "gather rays" => "render.gather_rays",
        "subsurface walk steps" => "render.spp` or the materials' `subsurface_radius",
        "environment samples" => "render.env_samples",
        "prefilter lookups" => "render.prefilter_size",
        "probe texels" => "size` of the probes",
        "glass rays" => "render.max_bounces",
        "hemicube cells read" => "render.hemicube_size",
        "hemicube patches drawn" | "patch pairs (rays)" | "form factors kept" | "solver multiply-adds" | "final-gather pairs" => {
            "render.patch_size"
        }
        "triangles" => "the meshes' triangles",
        _ => "",
    }
}

/// The share of patch pairs with a non-zero form factor assumed for memory and the solver.
const FORM_FACTOR_FILL: f64 = 0.5;
/// The process itself (code, tables, the thread pool) before any scene: measured at 8 MB.
const BASE_BYTES: f64 = 8e6;
/// Bytes a frame keeps per pixel (the linear total, the 8-bit image and its PNG): measured
/// 16.6 on a 3840 × 2160 frame.
const FRAME_BYTES_PER_PIXEL: f64 = 17.0;
/// Bytes a triangle keeps (positions, normals, indices, and its share of vertices).
const TRIANGLE_BYTES: f64 = 80.0;
/// Bytes a triangle adds to a BVH (nodes and leaf blocks).
const TRIANGLE_BVH_BYTES: f64 = 64.0;

/// The estimate of one render of `scene`, from its plan: no work is done.
pub fn estimate(scene: &Scene) -> Estimate {
    estimate_at(scene, scene.spec.settings.aa)
}

/// [`estimate`] with `aa`² samples a pixel (a ray-cast reference's count) instead of the scene's.
pub fn estimate_at(scene: &Scene, aa: u32) -> Estimate {
    let p = plan(scene);
    let runs = |pass: Pass| p.running().any(|x| x == pass);
    let s = &scene.spec.settings;
    let cam = &scene.spec.camera;
    let pixels = f64::from(cam.width) * f64::from(cam.height);
    let side = aa.max(1);
    let aa = f64::from(side);
    let samples = pixels * aa * aa;
    let mut terms = Vec::new();
    let mut term = |what: &'static str, how: String, count: f64, ns: f64, bytes: f64| {
        if count > 0.0 || bytes > 0.0 {
            terms.push(Term { what, how, key: key_of(what), count, seconds: count * ns * 1e-9, bytes });
        }
    };
    term("process", "code and tables".into(), 0.0, 0.0, BASE_BYTES);
    let tris = scene.geometry.triangles.len() as f64;
    let rays =
        runs(Pass::ShadowRays) || runs(Pass::Environment) || runs(Pass::Refraction) || runs(Pass::Radiosity) || runs(Pass::PathTrace);
    let (tri_ns, tri_bytes) =
        if rays { (ns::TRIANGLE + ns::TRIANGLE_BVH, TRIANGLE_BYTES + TRIANGLE_BVH_BYTES) } else { (ns::TRIANGLE, TRIANGLE_BYTES) };
    term("triangles", format!("{tris} triangles{}", if rays { ", with a BVH" } else { "" }), tris, tri_ns, tris * tri_bytes);
    term(
        "image samples",
        format!("{}×{} pixels × {side}² samples", cam.width, cam.height),
        samples,
        ns::SAMPLE,
        pixels * FRAME_BYTES_PER_PIXEL,
    );

    let lights = p.active_lights(scene);
    let methods = p.active_shadows();
    let lit = |l: &crate::light::Light| l.kind != LightKind::Ambient && l.radiance != glam::Vec3::ZERO;
    let direct = lights.iter().filter(|l| lit(l)).count() as f64;
    // Where lights are evaluated: every sample (Phong), every vertex (Gouraud), every face (flat).
    let points = match s.interpolation {
        Interpolation::Gouraud => scene.geometry.positions.len() as f64,
        Interpolation::Flat => tris,
        _ => samples,
    };
    let area_samples: f64 = lights.iter().filter(|l| lit(l) && l.kind.is_sampled()).map(|l| f64::from(l.samples.max(1))).sum();
    term("lights × points", format!("{} points × {direct} lights", count(points)), points * direct, ns::LIGHT, 0.0);
    term("area-light samples", format!("{} points × {area_samples} samples", count(points)), points * area_samples, ns::LIGHT_SAMPLE, 0.0);
    // Each light's rays (one per sample it takes) and maps.
    let per_point = |l: &crate::light::Light| if l.kind.is_sampled() { f64::from(l.samples.max(1)) } else { 1.0 };
    let ray_lights: f64 =
        lights.iter().zip(&methods).filter(|(l, m)| lit(l) && **m == Some(ShadowMethod::Ray)).map(|(l, _)| per_point(l)).sum();
    term("shadow rays", format!("{} points × {ray_lights} rays", count(points)), points * ray_lights, ns::SHADOW_RAY, 0.0);
    let side = f64::from(s.shadow_map.size);
    let faces: f64 =
        lights.iter().zip(&methods).filter(|(l, m)| lit(l) && **m == Some(ShadowMethod::Map)).map(|(l, _)| faces_for(l) as f64).sum();
    let texels = faces * side * side;
    term("shadow-map texels", format!("{faces} faces × {}²", s.shadow_map.size), texels, ns::MAP_TEXEL, texels * 4.0);
    // Shadow volumes: every point tests every silhouette quad, about 2√n for an object of n
    // triangles (its outline) plus its corners; a point that may be hidden also tests the caps.
    let of = |m: ShadowMethod| lights.iter().zip(&methods).filter(|(l, k)| lit(l) && **k == Some(m)).count() as f64;
    let volume_lights = of(ShadowMethod::Volume);
    if volume_lights > 0.0 {
        let g = &scene.geometry;
        let quads: f64 = g.objects.iter().map(|o| 2.0 * (o.triangles as f64).sqrt() + 4.0).sum::<f64>()
            + if s.interpolation == Interpolation::Phong { 0.0 } else { tris / 2.0 };
        let tests = points * quads * volume_lights;
        term(
            "shadow-volume quad tests",
            format!("{} points × ≈ {} quads × {volume_lights} lights", count(points), count(quads)),
            tests,
            ns::VOLUME_QUAD,
            quads * 40.0,
        );
    }
    // Shadow polygons: every receiver against every light-facing occluder, n × n/2 pairs.
    let polygon_lights = of(ShadowMethod::Polygons);
    if polygon_lights > 0.0 {
        let pairs = tris * (tris / 2.0) * polygon_lights;
        term(
            "shadow-polygon pairs",
            format!("{} receivers × {} occluders × {polygon_lights} lights", count(tris), count(tris / 2.0)),
            pairs,
            ns::POLYGON_PAIR,
            tris * 120.0,
        );
    }

    if runs(Pass::PathTrace) {
        // Lesson 27's box averages 3.1 segments a path at max_depth 16 (Russian roulette and
        // escapes end the rest): min(max_depth, 4) a path, each with its next-event rays.
        let paths = samples * f64::from(s.path.spp);
        let segments = paths * f64::from(s.path.max_depth.min(4));
        term(
            "path segments",
            format!("{} samples × spp {} × ≤ {} segments", count(samples), s.path.spp, s.path.max_depth.min(4)),
            segments,
            ns::PATH_SEGMENT + ns::SHADOW_RAY * direct,
            0.0,
        );
        let (caustic, global) =
            (s.path.caustics == crate::lesson::settings::Caustics::Photons, s.path.indirect == crate::lesson::settings::Indirect::Photons);
        // A caustic photon is a few closest-hit rays (the lamp, the glass, where it lands); a
        // global one goes on by Russian roulette: ≤ 8. Each stored one is 36 bytes and a grid entry.
        let photons =
            if caustic { f64::from(s.path.photons) * 4.0 } else { 0.0 } + if global { f64::from(s.path.global_photons) * 8.0 } else { 0.0 };
        if photons > 0.0 {
            term("photon segments", format!("{} photon segments", count(photons)), photons, ns::PATH_SEGMENT, photons * 11.0);
        }
        if global && s.path.gather_rays > 0 {
            // Each first diffuse vertex sends gather_rays rays, one closest hit and a map read each.
            let rays = samples * f64::from(s.path.spp) * f64::from(s.path.gather_rays);
            term(
                "gather rays",
                format!("{} samples × spp {} × {} rays", count(samples), s.path.spp, s.path.gather_rays),
                rays,
                ns::PATH_SEGMENT * 2.0,
                0.0,
            );
        }
        if scene.materials.iter().filter_map(|m| m.brdf()).any(
            |b| matches!(b, crate::shading::brdf::Brdf::Principled(p) if crate::transport::path::subsurface::Interior::of(p).is_some()),
        ) {
            // Lesson 46 measures 3.4 walk segments a path at its scale 0.1 (each walk is capped at 256).
            term("subsurface walk steps", format!("{} paths × ~8 steps", count(paths)), paths * 8.0, ns::PATH_SEGMENT, 0.0);
        }
    }
    if runs(Pass::Fog)
        && let Some(m) = scene.spec.fog.as_ref().and_then(|f| f.medium())
        && m.sigma_s > 0.0
    {
        let steps = f64::from(m.steps.max(1));
        let shadowed = lights.iter().zip(&methods).filter(|(l, m)| lit(l) && **m == Some(ShadowMethod::Ray)).count() as f64;
        let per_step = ns::FOG_STEP * direct.max(1.0) + ns::SHADOW_RAY * shadowed;
        term("fog march steps", format!("{} samples × {steps} steps × {direct} lights", count(samples)), samples * steps, per_step, 0.0);
    }
    if runs(Pass::Environment)
        && let Some(env) = &scene.environment
    {
        let map = f64::from(env.map.width) * f64::from(env.map.height);
        // The map, its luminance tables and (for the split sum) its prefiltered chain.
        term(
            "environment map",
            format!("{}×{} texels and their tables", env.map.width, env.map.height),
            map,
            ns::ENV_TEXEL,
            map * 12.0 * 3.0,
        );
        if s.ibl == Ibl::Reference {
            let n = f64::from(s.env_samples.max(1));
            term("environment samples", format!("{} samples × {n}", count(samples)), samples * n, ns::ENV_SAMPLE, 0.0);
        } else {
            let w = f64::from(s.prefilter_size.max(1));
            let lookups = w * w / 2.0 * 4.0 / 3.0 * 64.0;
            term(
                "prefilter lookups",
                format!("{}×{} texels × 64, with its levels", w, w / 2.0),
                lookups,
                ns::PREFILTER_LOOKUP,
                w * w * 8.0,
            );
        }
    }
    if runs(Pass::ProbeCapture) {
        let texels: f64 = scene.spec.probes.iter().map(|pr| 6.0 * f64::from(pr.size).powi(2)).sum();
        term(
            "probe texels",
            format!("{} probes × 6 faces", scene.spec.probes.len()),
            texels,
            ns::PROBE_TEXEL * (1.0 + direct),
            texels * 16.0,
        );
    }
    if runs(Pass::Refraction) {
        // Each interface event may split a ray in two; a convex glass object costs at most
        // two rays per event. An upper bound: every sample sees glass.
        let per = 2.0 * f64::from(s.max_bounces.max(1));
        term("glass rays", format!("{} samples × ≤ {per} rays", count(samples)), samples * per, ns::GLASS_RAY, 0.0);
    }
    if runs(Pass::Radiosity) {
        let r = s.radiosity;
        let n = crate::effects::radiosity::patch_count(scene) as f64;
        let pairs = n * n;
        // The longest row of non-zero factors a patch keeps.
        let row = match r.form_factors {
            FormFactorMethod::Hemicube => {
                let h = f64::from(r.hemicube_size);
                let cells = 3.0 * h * h;
                term(
                    "hemicube patches drawn",
                    format!("{n} patches × ({n} patches + {} cells)", count(cells)),
                    pairs,
                    ns::HEMICUBE_PATCH,
                    0.0,
                );
                term("hemicube cells read", format!("{n} patches × 3·{h}²"), n * cells, ns::HEMICUBE_CELL, cells * 8.0);
                // A cell holds one patch: a row has at most as many factors as cells (and
                // about 60% of that where the cells bound it, lesson 27 at 16²).
                (n * FORM_FACTOR_FILL).min(cells * 0.75)
            }
            FormFactorMethod::Ray => {
                term("patch pairs (rays)", format!("{n}² patch pairs"), pairs, ns::PATCH_PAIR_RAYS, 0.0);
                n * FORM_FACTOR_FILL
            }
        };
        // Rows of (patch, factor) pairs, 8 bytes each. About half the pairs of a closed room
        // see each other (lesson 27: 32–38% of the factors are non-zero).
        let kept = n * row;
        let iterations = f64::from(r.iterations.min(100));
        term("form factors kept", format!("{n} rows × ~{} entries", count(row)), kept, 0.0, kept * 8.0);
        term("solver multiply-adds", format!("≤ {iterations} iterations × {} entries", count(kept)), iterations * kept, ns::SOLVE, 0.0);
        if r.final_gather {
            term("final-gather pairs", format!("{n}² patch pairs"), pairs, ns::PATCH_PAIR_RAYS, 0.0);
        }
    }
    let tex: f64 = scene
        .textures
        .iter()
        .flat_map(|t| [&t.albedo, &t.roughness, &t.metallic, &t.normal, &t.occlusion])
        .flatten()
        .map(|t| t.texel_count() as f64)
        .sum();
    term("texture texels", "with their mip levels".into(), 0.0, 0.0, tex * 12.0);
    Estimate { terms }
}

/// The process's peak resident memory so far (Linux's VmHWM), `None` elsewhere.
pub fn peak_bytes() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.trim_start_matches("VmHWM:").trim().trim_end_matches("kB").trim().parse().ok()?;
    Some(kb * 1024.0)
}

/// The factor `--budget` gave, as f64 bits (1.0 until [`configure`]).
static FACTOR: AtomicU64 = AtomicU64::new(0x3FF0_0000_0000_0000);

/// Sets the budget to `factor` × the defaults for the rest of the process.
///
/// # Errors
/// A message when `factor` is not a number from 0.001 to [`MAX_FACTOR`].
pub fn configure(factor: f64) -> Result<(), String> {
    if !(factor.is_finite() && (0.001..=MAX_FACTOR).contains(&factor)) {
        return Err(format!("--budget {factor}: give a factor from 0.001 to {MAX_FACTOR} (1 is the default budget)"));
    }
    FACTOR.store(factor.to_bits(), Ordering::Relaxed);
    Ok(())
}

/// The budget factor in force.
pub fn factor() -> f64 {
    f64::from_bits(FACTOR.load(Ordering::Relaxed))
}

/// A render refused before any work: the estimate with its largest terms and the fix.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct OverBudget(pub String);

impl OverBudget {
    /// The same refusal, naming where it happened first (the lesson file, a figure's cell).
    pub fn at(self, place: impl std::fmt::Display) -> OverBudget {
        OverBudget(format!("{place}: {}", self.0))
    }
}

/// The estimate of `scene`, or [`OverBudget`] when its work or memory exceeds the budget in force.
///
/// # Errors
/// [`OverBudget`], naming the largest terms and the factor of `--budget` that would allow it.
pub fn check(scene: &Scene) -> Result<Estimate, OverBudget> {
    check_at(scene, scene.spec.settings.aa)
}

/// [`check`] of [`estimate_at`]: `aa`² samples a pixel.
///
/// # Errors
/// [`OverBudget`], as [`check`].
pub fn check_at(scene: &Scene, aa: u32) -> Result<Estimate, OverBudget> {
    let e = estimate_at(scene, aa);
    let f = factor();
    let (work, memory) = (e.seconds() / (DEFAULT_SECONDS * f), e.bytes() / (DEFAULT_BYTES * f));
    if work <= 1.0 && memory <= 1.0 {
        return Ok(e);
    }
    let mut lines = Vec::new();
    if work > 1.0 {
        lines.push(format!(
            "estimated work {} on one core, over the budget of {}; the largest terms:",
            seconds(e.seconds()),
            seconds(DEFAULT_SECONDS * f)
        ));
        lines.extend(
            e.largest(3, |t| t.seconds).iter().map(|t| format!("    {}: {} ({}) ≈ {}", t.what, count(t.count), t.how, seconds(t.seconds))),
        );
    }
    if memory > 1.0 {
        lines.push(format!("estimated memory {}, over the budget of {}; the largest terms:", bytes(e.bytes()), bytes(DEFAULT_BYTES * f)));
        lines.extend(e.largest(3, |t| t.bytes).iter().map(|t| format!("    {}: {} ({})", t.what, bytes(t.bytes), t.how)));
    }
    // The smallest factor that allows it, rounded up to a readable number.
    let need = (work.max(memory) * f * 1.05).max(1.0);
    let need = if need < 10.0 { (need * 10.0).ceil() / 10.0 } else { need.ceil() };
    let top = if work >= memory { e.largest(1, |t| t.seconds) } else { e.largest(1, |t| t.bytes) };
    let lower = match top.first().map(|t| t.key) {
        Some(k) if !k.is_empty() => format!("lower `{k}`"),
        _ => "lower the largest term's setting".into(),
    };
    let hint = if need <= MAX_FACTOR {
        format!("{lower}, or raise the budget on purpose with --budget {need} (docs/cli.md, \"The budget\")")
    } else {
        format!("{lower}: even --budget {MAX_FACTOR} does not allow it")
    };
    Err(OverBudget(format!("the render is over its budget: {}\n  hint: {hint}", lines.join("\n  "))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn scene(extra: &str) -> Scene {
        sized(64, extra)
    }

    fn sized(side: u32, extra: &str) -> Scene {
        let text = format!(
            "[lesson]\ntitle = \"t\"\n[camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov_deg = 40\nsize = [{side}, {side}]\n\
             [material.m]\nmodel = \"phong\"\ndiffuse = 0.5\nspecular = 0.2\nshininess = 20\n\
             [[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[[object]]\nshape = \"plane\"\nmaterial = \"m\"\ntranslate = [0, -1, 0]\nscale = 4\n{extra}"
        );
        crate::scene::build::build(&crate::lesson::parse(&text, Path::new("t.toml"), &[]).unwrap()).unwrap()
    }

    #[test]
    fn a_product_of_limits_is_counted_and_refused_over_the_budget() {
        // Each value within its own limit: 4096 fog steps, aa 4 on 512², a shadowed light.
        let light = "[[light]]\nkind = \"point\"\nposition = [2, 3, 2]\nintensity = 1\n";
        let fog = "[fog]\nkind = \"medium\"\nsigma_s = 0.1\nsigma_a = 0.0\nsteps = 4096\n";
        let s = scene(&format!("[render]\naa = 4\nshadows = \"ray\"\n{light}{fog}"));
        let e = estimate(&s);
        assert_eq!(e.count("fog march steps"), 64.0 * 64.0 * 16.0 * 4096.0);
        assert!(check(&s).is_ok(), "{}", e.summary());
        // The same at 512²: 64 times the work, over the default budget.
        let big = sized(512, &format!("[render]\naa = 4\nshadows = \"ray\"\n{light}{fog}"));
        let err = check(&big).unwrap_err().0;
        assert!(err.contains("estimated work") && err.contains("fog march steps: 17.180 G") && err.contains("--budget"), "{err}");
    }

    #[test]
    fn counts_follow_the_plan() {
        let s = scene("[[light]]\nkind = \"point\"\nposition = [2, 3, 2]\nintensity = 1\n");
        let e = estimate(&s);
        assert_eq!(e.count("image samples"), 64.0 * 64.0);
        assert_eq!(e.count("lights × points"), 64.0 * 64.0);
        // The default shadow method for a point light is the ray; a plane and a sphere can occlude.
        assert_eq!(e.count("shadow rays"), 64.0 * 64.0);
        assert!(check(&s).is_ok());
    }

    #[test]
    fn the_factor_is_bounded() {
        assert!(configure(0.0).is_err() && configure(f64::NAN).is_err() && configure(1e6).is_err());
    }

    #[test]
    fn numbers_read_as_people_write_them() {
        assert_eq!(seconds(0.0123), "12 ms");
        assert_eq!(seconds(3.44), "3.4 s");
        assert_eq!(seconds(725.0), "12 min");
        assert_eq!(bytes(6.44e9), "6.44 GB");
        assert_eq!(count(4_194_304.0), "4.194 M");
    }
}
