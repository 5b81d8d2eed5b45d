//! The render entry points and the plan's frame-level passes; the strips run in parallel.

use super::bundle::bundle_lanes;
use super::gather::gather_allowed;
use super::strip::{Scratch, StripOut};
use super::vertices;
use super::{RenderStats, count_shadows};
use crate::effects::environment::EnvLighting;
use crate::effects::probe::Probes;
use crate::effects::radiosity;
use crate::effects::shadows::map::SHADOW_MAP_TEXELS;
use crate::effects::shadows::polygons::{POLYGON_PAIRS, POLYGONS_KEPT};
use crate::effects::shadows::volume::VOLUME_QUADS;
use crate::effects::shadows::{ShadowMap, ShadowPolygons, ShadowVolume};
use crate::geometry::camera::CameraRays;
use crate::lesson::settings::RenderMethod;
use crate::lesson::settings::{Cull, InterpolationSpace, Tonemap};
use crate::light::ShadowMethod;
use crate::raster::{self, CullMode, Setup, VisBuffer};
use crate::render::develop::DevelopParams;
use crate::render::frame::{Frame, Layer};
use crate::render::plan::Pass;
use crate::render::probe::PROBE_TEXELS;
use crate::scene::build::Geometry;
use crate::scene::{Environment, Scene};
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::transport::rays::BVH_NODES;
use crate::transport::visibility::{self as shadows, LightShadow, ShadowCounts, Shadows};
use crate::transport::{At, Lighting, Occluders, SceneRays, Tracing, shade_point};
use glam::{Vec3, Vec4};
use rayon::prelude::*;
use std::cell::OnceCell;
use std::sync::Arc;

thread_local! {
    /// Each worker keeps its strip buffers across strips and renders: no allocation (and no
    /// page faults) per strip.
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

/// Pixel rows per strip: 16 rows of a 1024-wide image keep a strip's samples in L2.
pub(super) const STRIP_PIXELS: u32 = 16;

/// Lighting precomputed before rasterization: per vertex or face, its terms and their total.
pub(super) enum Lit {
    /// Per vertex (Gouraud); no terms when no term layer is kept and the vertices were lit
    /// in lanes.
    Vertices { terms: Vec<Components>, totals: Vec<Vec3> },
    /// Per face (flat).
    Faces { terms: Vec<Components>, totals: Vec<Vec3> },
    /// Per sample (Phong).
    Samples,
    /// No lighting pass runs (nothing to draw): the strips shade nothing.
    Nothing,
}

/// Renders the scene into a linear frame keeping the given layers (deduplicated, in order).
pub fn render(scene: &Scene, layers: &[Layer]) -> (Frame, RenderStats) {
    render_with(scene, layers, None)
}

/// Rasterizes the scene once into a whole-image visibility buffer, for shading many
/// variants that share geometry, camera and sampling (see [`same_raster`]).
pub fn rasterize(scene: &Scene) -> VisBuffer {
    let meshed = radiosity_mesh(scene);
    let scene = meshed.as_ref().unwrap_or(scene);
    let (w, h, aa) = (scene.spec.camera.width, scene.spec.camera.height, scene.spec.settings.aa);
    let screen = scene.spec.settings.interpolation_space == InterpolationSpace::Screen;
    raster::rasterize_in(&clip_space(scene), &scene.geometry.triangles, w * aa, h * aa, cull_mode(scene), screen)
}

/// True when two scenes produce the same visibility buffer: same camera (but for the
/// background), triangles, positions, supersampling, culling and interpolation space (the
/// buffer holds resolved barycentrics). Materials, lights, normals and interpolation may differ.
pub fn same_raster(a: &Scene, b: &Scene) -> bool {
    let cam = |s: &Scene| crate::scene::Camera { background: glam::Vec3::ZERO, ..s.spec.camera };
    cam(a) == cam(b)
        && a.spec.settings.aa == b.spec.settings.aa
        && a.spec.settings.cull == b.spec.settings.cull
        && a.spec.settings.interpolation_space == b.spec.settings.interpolation_space
        // Radiosity rasterizes its patch mesh, which the patch size decides.
        && a.spec.settings.method == b.spec.settings.method
        // The path tracer rasterizes nothing: there is no buffer to share.
        && a.spec.settings.method != RenderMethod::Path
        && (a.spec.settings.method == RenderMethod::Raster || a.spec.settings.radiosity.patch_size == b.spec.settings.radiosity.patch_size)
        && a.geometry.triangles == b.geometry.triangles
        && a.geometry.positions == b.geometry.positions
}

/// With `method = "radiosity"`, the scene cut into patches (what is rasterized and shown).
pub(super) fn radiosity_mesh(scene: &Scene) -> Option<Scene> {
    (scene.spec.settings.method == RenderMethod::Radiosity).then(|| radiosity::mesh_scene(scene))
}

/// The vertex stage as a function: vertex i's world position to clip space (for
/// `raster::setup_with`, which fuses it with the projection to the sample grid).
fn clip_of(scene: &Scene) -> impl Fn(usize) -> Vec4 + Sync + '_ {
    let vp = scene.spec.camera.view_projection();
    move |i| vp * scene.geometry.positions[i].extend(1.0)
}

/// Every vertex in clip space, stored (for a whole-image visibility buffer).
fn clip_space(scene: &Scene) -> Vec<Vec4> {
    (0..scene.geometry.positions.len()).into_par_iter().map(clip_of(scene)).collect()
}

fn cull_mode(scene: &Scene) -> CullMode {
    if scene.spec.settings.cull == Cull::None { CullMode::None } else { CullMode::Back }
}

/// [`render`], shading a visibility buffer from [`rasterize`] instead of rasterizing
/// when one is given (precondition: it was made from a scene with [`same_raster`]).
pub fn render_with(scene: &Scene, layers: &[Layer], vis: Option<&VisBuffer>) -> (Frame, RenderStats) {
    if scene.spec.settings.method == RenderMethod::Path {
        return crate::render::path::render(scene, layers);
    }
    let meshed = radiosity_mesh(scene);
    let scene = meshed.as_ref().unwrap_or(scene);
    let r = Renderer::new(scene, layers, vis);
    let (w, h) = (r.w as usize, r.h as usize);
    let mut buffers: Vec<Vec<Vec3>> = r.wanted.iter().map(|_| vec![Vec3::ZERO; w * h]).collect();
    let mut coverage = vec![0f32; w * h];
    let rows = STRIP_PIXELS as usize * w;
    // Hand each strip its rows of every kept layer.
    let mut strip_layers: Vec<Vec<&mut [Vec3]>> = (0..h.div_ceil(rows / w)).map(|_| Vec::with_capacity(r.wanted.len())).collect();
    for buf in buffers.iter_mut() {
        for (s, chunk) in buf.chunks_mut(rows).enumerate() {
            strip_layers[s].push(chunk);
        }
    }
    let strips: Vec<RenderStats> = strip_layers
        .into_par_iter()
        .zip(coverage.par_chunks_mut(rows))
        .enumerate()
        .with_max_len(1)
        .map(|(s, (layers, coverage))| SCRATCH.with_borrow_mut(|scratch| r.strip(s, scratch, &mut StripOut::Frame { layers, coverage })))
        .collect();
    let stats = r.finish(&strips);
    let layers = r.wanted.into_iter().zip(buffers).collect();
    (Frame { width: w as u32, height: h as u32, layers, coverage, background: scene.spec.camera.background }, stats)
}

/// Renders one layer straight to interleaved 8-bit sRGB: the bytes
/// [`develop`](crate::render::develop::develop) gives for `render(scene, &[layer])` with the same
/// exposure and tone map, without keeping the linear frame: each pixel row is developed
/// while it is in cache, so no full-frame linear buffer is written and read back.
pub fn render_image(scene: &Scene, layer: Layer, exposure: f32, op: Tonemap) -> (Vec<u8>, RenderStats) {
    let develop = DevelopParams::new(layer, exposure, op, 3, false, scene.spec.camera.background);
    if scene.spec.settings.method == RenderMethod::Path {
        let (frame, stats) = crate::render::path::render(scene, &[layer]);
        let mut bytes = vec![0u8; frame.coverage.len() * 3];
        develop.develop_into(frame.raw(layer).expect("the layer asked for"), &frame.coverage, &mut bytes);
        return (bytes, stats);
    }
    let meshed = radiosity_mesh(scene);
    let scene = meshed.as_ref().unwrap_or(scene);
    let r = Renderer::new(scene, &[layer], None);
    let (w, h) = (r.w as usize, r.h as usize);
    // Not zeroed: each strip writes its own bytes, in parallel, before anything reads them
    // (a `vec![0; n]` is a serial 3 MB memset before the first strip starts).
    let n = w * h * 3;
    let mut bytes = Vec::with_capacity(n);
    let strips: Vec<RenderStats> = bytes.spare_capacity_mut()[..n]
        .par_chunks_mut(STRIP_PIXELS as usize * w * 3)
        .enumerate()
        // Every strip its own job, so an idle worker can take any strip left (not only a
        // half of another's run): see the module docs.
        .with_max_len(1)
        .map(|(s, bytes)| SCRATCH.with_borrow_mut(|scratch| r.strip(s, scratch, &mut StripOut::Image { bytes, develop: &develop })))
        .collect();
    // SAFETY: the strips cover `..n` and `Renderer::strip` writes every byte of an image's
    // strip (`StripOut::Image`); a strip that panicked unwinds through `collect` before
    // this line.
    unsafe { bytes.set_len(n) };
    (bytes, r.finish(&strips))
}

/// One render: what every strip reads.
pub(super) struct Renderer<'a> {
    pub(super) scene: &'a Scene,
    pub(super) g: &'a Geometry,
    /// The lights the plan keeps (a spot that misses every object is culled), with their shadows.
    pub(super) lighting: Lighting,
    pub(super) lit: Lit,
    /// Triangle setup, unless a visibility buffer is reused.
    pub(super) setup: Option<Setup>,
    pub(super) vis: Option<&'a VisBuffer>,
    /// The kept layers, deduplicated, in order.
    pub(super) wanted: Vec<Layer>,
    /// Stats of the work done before the strips.
    pub(super) stats: RenderStats,
    pub(super) w: u32,
    pub(super) h: u32,
    pub(super) aa: u32,
    pub(super) eye: Vec3,
    pub(super) two_sided: bool,
    /// `[render] interpolation_space = "screen"`: the strips' triangles resolve screen-space
    /// barycentrics (a reused buffer already holds them).
    pub(super) screen_space: bool,
    /// A term layer (ambient, diffuse, specular, emission) is kept.
    pub(super) want_terms: bool,
    pub(super) want_normal: bool,
    /// Lanes per shading bundle: 16 (AVX-512F), 8 (AVX) or 4 (SSE2), the widest this CPU runs.
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))] // only the x86 paths read it
    pub(super) lanes: usize,
    /// Whether triangles' rests are gathered across triangles into full bundles (`gather.rs`).
    pub(super) gather: bool,
    /// The plan's running passes ([`Pass::bit`] each). A pass that works in the strips asks
    /// [`Renderer::runs`] there, so it needs no field and no arm of its own here.
    pub(super) running: u32,
    /// The environment drawn behind the objects, with the camera's rays to look it up.
    pub(super) sky: Option<(Environment, CameraRays)>,
}

impl<'a> Renderer<'a> {
    /// Whether the plan runs `pass` in this render.
    pub(super) fn runs(&self, pass: Pass) -> bool {
        self.running & pass.bit() != 0
    }

    /// Lighting ahead (Gouraud, flat), vertex stage and triangle setup.
    pub(super) fn new(scene: &'a Scene, layers: &[Layer], vis: Option<&'a VisBuffer>) -> Renderer<'a> {
        let mut wanted: Vec<Layer> = Vec::new();
        for l in layers {
            if !wanted.contains(l) {
                wanted.push(*l);
            }
        }
        let cam = &scene.spec.camera;
        let g = &scene.geometry;
        let aa = scene.spec.settings.aa;
        let (w, h) = (cam.width, cam.height);
        let two_sided = scene.spec.settings.cull == Cull::None;
        let want_terms = wanted.iter().any(|l| !matches!(l, Layer::Total | Layer::Normal));
        let mut stats = RenderStats {
            degenerate_mesh_triangles: scene.repairs.degenerate_triangles as u64,
            repaired_normals: scene.repairs.repaired_normals as u64,
            ..Default::default()
        };
        // Run the plan's frame-level passes in order; the strip-level ones (the strips'
        // visibility, per-sample lighting, resolve) run in `strip`. Only the lights the plan
        // keeps are evaluated (a spot that misses every object is culled).
        let plan = crate::render::plan::plan(scene);
        let lights = plan.active_lights(scene);
        let methods = plan.active_shadows();
        let mut per_light: Vec<LightShadow> =
            methods.iter().map(|m| if *m == Some(ShadowMethod::Ray) { LightShadow::Ray } else { LightShadow::Unshadowed }).collect();
        // Built once the shadow passes have run (moved in: a map is megabytes, a BVH more).
        let mut lighting: Option<Lighting> = None;
        let fog = plan.running().any(|p| p == Pass::Fog);
        let mut env: Option<Arc<EnvLighting>> = None;
        // The render's one ray-query structure, built when the first pass asks for it.
        let rays: OnceCell<Arc<SceneRays>> = OnceCell::new();
        let scene_rays = || rays.get_or_init(|| Arc::new(SceneRays::build(scene))).clone();
        let (mut environment, mut refraction, mut probes) = (false, false, None);
        let made = |per_light: &mut Vec<LightShadow>,
                    occluders: &mut Option<_>,
                    env: &Option<Arc<EnvLighting>>,
                    (environment, refraction): (bool, bool),
                    probes: &mut Option<Arc<Probes>>| {
            let mut l = Lighting::new(lights.clone(), Shadows::new(std::mem::take(per_light), occluders.take()));
            l.exact_area = scene.spec.settings.area_reference;
            l.sampler = scene.spec.settings.sampler;
            l.pattern = scene.spec.settings.sample_pattern;
            l.env = env.clone();
            if env.is_some() {
                l.tracing = Tracing::prepare(scene, environment, refraction, scene_rays);
                l.tracing.probes = probes.take();
            }
            // Light reaching surfaces crosses the medium too.
            if fog {
                l = l.through_medium(crate::effects::fog::extinction(scene));
            }
            l
        };
        // Each pass's bit is set where its work is done (here, or in `strip`), so the stats
        // show what ran, not what was planned.
        let mut lit = Lit::Nothing;
        let mut setup = None;
        let mut occluders = None;
        for pass in plan.running() {
            match pass {
                // A reused visibility buffer needs neither clip space nor setup.
                // Fused into the raster setup (`raster::setup_with`): each vertex goes to
                // clip space and onto the sample grid in one pass.
                Pass::VertexStage if vis.is_none() => stats.passes |= pass.bit(),
                Pass::ShadowRays => {
                    let b = scene_rays();
                    stats.counters.add(BVH_NODES, b.node_count() as u64);
                    occluders = Some(Occluders::Meshes(b));
                    stats.passes |= pass.bit();
                }
                Pass::ShadowMaps => {
                    for (i, m) in methods.iter().enumerate() {
                        if *m == Some(ShadowMethod::Map)
                            && let Some(map) = ShadowMap::render(scene, &lights[i].kind, scene.spec.settings.shadow_map)
                        {
                            stats.counters.add(SHADOW_MAP_TEXELS, map.texels_written);
                            per_light[i] = LightShadow::Map(Box::new(map));
                        }
                    }
                    stats.passes |= pass.bit();
                }
                Pass::ShadowVolumes => {
                    for (i, m) in methods.iter().enumerate() {
                        if *m == Some(ShadowMethod::Volume)
                            && let Some(v) = ShadowVolume::build(scene, &lights[i].kind)
                        {
                            stats.counters.add(VOLUME_QUADS, v.quads());
                            per_light[i] = LightShadow::Volume(Box::new(v));
                        }
                    }
                    stats.passes |= pass.bit();
                }
                Pass::ShadowPolygons => {
                    for (i, m) in methods.iter().enumerate() {
                        if *m == Some(ShadowMethod::Polygons)
                            && let Some(p) = ShadowPolygons::build(scene, &lights[i].kind)
                        {
                            stats.counters.add(POLYGON_PAIRS, p.pairs);
                            stats.counters.add(POLYGONS_KEPT, p.polygons());
                            per_light[i] = LightShadow::Polygons(Box::new(p));
                        }
                    }
                    stats.passes |= pass.bit();
                }
                Pass::Environment => {
                    env = Some(Arc::new(EnvLighting::build(scene)));
                    environment = true;
                    stats.passes |= pass.bit();
                }
                Pass::ProbeCapture => {
                    let maps = crate::render::probe::capture(scene);
                    stats.counters.add(PROBE_TEXELS, maps.iter().map(|m| 6 * u64::from(m.spec.size) * u64::from(m.spec.size)).sum());
                    // The environment pass runs first whenever a mirror is drawn.
                    if env.is_some() {
                        probes = Some(Arc::new(Probes { maps, reflections: scene.spec.settings.reflections }));
                    }
                    stats.passes |= pass.bit();
                }
                Pass::Refraction => {
                    // The environment pass ran before (glass needs its rays): glass adds its own.
                    if env.is_none() {
                        env = Some(Arc::new(EnvLighting::build(scene)));
                        environment = true;
                    }
                    refraction = true;
                    stats.passes |= pass.bit();
                }
                Pass::Radiosity => {
                    let baked = radiosity::bake(scene, &*scene_rays());
                    stats.counters.add(radiosity::PATCHES, baked.report.patches as u64);
                    stats.counters.add(radiosity::FORM_FACTORS, baked.report.form_factors);
                    stats.counters.add(radiosity::ITERATIONS, baked.report.iterations as u64);
                    let totals = baked.values.iter().map(Components::total).collect();
                    lit = if baked.per_vertex {
                        stats.vertices_lit = baked.values.len() as u64;
                        Lit::Vertices { terms: baked.values, totals }
                    } else {
                        stats.faces_lit = baked.values.len() as u64;
                        Lit::Faces { terms: baked.values, totals }
                    };
                    stats.passes |= pass.bit();
                }
                Pass::LightVertices | Pass::LightFaces => {
                    let lighting =
                        lighting.get_or_insert_with(|| made(&mut per_light, &mut occluders, &env, (environment, refraction), &mut probes));
                    // The raster setup needs nothing the lighting makes: both run at once, so
                    // each one's serial steps overlap the other's parallel ones.
                    let raster_too = vis.is_none() && setup.is_none() && plan.running().any(|p| p == Pass::Raster);
                    let ((l, counts, shadow), s) = rayon::join(
                        || light_ahead(scene, pass, lighting, two_sided, want_terms),
                        || raster_too.then(|| raster_setup(scene)),
                    );
                    if let Some(s) = s {
                        stats.raster += s.stats;
                        stats.passes |= Pass::Raster.bit();
                        setup = Some(s);
                    }
                    count_shadows(&mut stats.counters, shadow);
                    stats.passes |= pass.bit();
                    lit = l;
                    stats.light_evaluations += counts.lights;
                    stats.diffuse_evaluations += counts.diffuse;
                    stats.specular_evaluations += counts.specular;
                    match &lit {
                        Lit::Vertices { totals, .. } => stats.vertices_lit = totals.len() as u64,
                        Lit::Faces { terms, .. } => stats.faces_lit = terms.len() as u64,
                        Lit::Samples | Lit::Nothing => {}
                    }
                }
                // Unless it ran beside the lighting.
                Pass::Raster if vis.is_none() && setup.is_none() => {
                    let s = raster_setup(scene);
                    stats.raster += s.stats;
                    stats.passes |= pass.bit();
                    setup = Some(s);
                }
                // Per-sample lighting runs in the strips (`strip.rs`), as does every pass without
                // an arm above (fog, the resolve): they ask `Renderer::runs`.
                Pass::ShadeSamples => lit = Lit::Samples,
                _ => {}
            }
        }
        let lighting = lighting.unwrap_or_else(|| made(&mut per_light, &mut occluders, &env, (environment, refraction), &mut probes));
        // No triangles: nothing to rasterize, every strip is background.
        if setup.is_none() && vis.is_none() {
            setup = Some(raster::setup(&[], &[], w * aa, h * aa, STRIP_PIXELS * aa, cull_mode(scene)));
        }
        let want_normal = wanted.contains(&Layer::Normal);
        Renderer {
            scene,
            g,
            lighting,
            lit,
            setup,
            vis,
            wanted,
            stats,
            w,
            h,
            aa,
            eye: cam.position,
            two_sided,
            screen_space: scene.spec.settings.interpolation_space == InterpolationSpace::Screen,
            want_terms,
            want_normal,
            lanes: bundle_lanes(),
            gather: gather_allowed(),
            running: plan.running_bits(),
            sky: scene.environment.as_ref().filter(|e| e.background).map(|e| (e.clone(), cam.rays())),
        }
    }

    /// The render's stats: the work before the strips plus every strip's.
    fn finish(&self, strips: &[RenderStats]) -> RenderStats {
        let mut stats = self.stats;
        for s in strips {
            stats += s;
        }
        stats
    }
}

/// The raster pass: every vertex to clip space and onto the sample grid, each triangle set
/// up and binned by strip (`raster::setup_with`).
fn raster_setup(scene: &Scene) -> raster::Setup {
    let (w, h, aa) = (scene.spec.camera.width, scene.spec.camera.height, scene.spec.settings.aa);
    raster::setup_with(
        scene.geometry.positions.len(),
        clip_of(scene),
        &scene.geometry.triangles,
        w * aa,
        h * aa,
        STRIP_PIXELS * aa,
        cull_mode(scene),
    )
}

/// Two workers' evaluation counts together.
fn add_counts(a: EvalCounts, b: EvalCounts) -> EvalCounts {
    EvalCounts { lights: a.lights + b.lights, diffuse: a.diffuse + b.diffuse, specular: a.specular + b.specular }
}

/// Vertices a job of the lanes' vertex lighting takes.
const VERTEX_CHUNK: usize = 1024;

/// The lighting passes before rasterizing: [`Pass::LightVertices`] lights every vertex (Gouraud),
/// [`Pass::LightFaces`] every face at its centroid (flat). Without `want_terms` (no term layer
/// kept), the lanes' vertex lighting keeps the totals only.
fn light_ahead(scene: &Scene, pass: Pass, lighting: &Lighting, two_sided: bool, want_terms: bool) -> (Lit, EvalCounts, ShadowCounts) {
    let g = &scene.geometry;
    let eye = scene.spec.camera.position;
    // Shadow work is counted on the worker that does it, and returned with the point.
    let light = |m: usize, at: At<f32>| {
        let p = Vec3::from(at.p);
        let n = Vec3::from(at.n);
        let v = (eye - p).normalize_or(n);
        let n = if two_sided && n.dot(v) < 0.0 { -n } else { n };
        let mut k = EvalCounts::default();
        let before = shadows::thread_counts();
        let c = shade_point(&scene.materials[m], lighting, scene.spec.ambient, At { n: n.into(), ..at }, v, &mut k);
        let after = shadows::thread_counts();
        let s = after.since(before);
        (if c.is_finite() { c } else { Components::ZERO }, k, s)
    };
    let sum = |v: &[(Components, EvalCounts, ShadowCounts)]| {
        v.iter().fold((EvalCounts::default(), ShadowCounts::default()), |(a, s), (_, k, t)| (add_counts(a, *k), s.plus(*t)))
    };
    match pass {
        Pass::LightVertices => {
            // A vertex takes the material of the first triangle that uses it, or 0 (when
            // every triangle's is 0, the zeros are already that: no scattered write per corner).
            let mut vertex_material = vec![0u32; g.positions.len()];
            if g.material.iter().any(|&m| m != 0) {
                for (t, tri) in g.triangles.iter().enumerate().rev() {
                    for &i in tri {
                        vertex_material[i as usize] = g.material[t];
                    }
                }
            }
            if vertices::lanes_apply(scene, lighting) {
                // Plain lighting and classic materials: lit in lanes, chunk by chunk, each
                // chunk's totals beside its terms (none when no term layer is kept).
                let n = g.positions.len();
                let mut totals = vec![Vec3::ZERO; n];
                let mut terms = vec![Components::ZERO; if want_terms { n } else { 0 }];
                let mut term_chunks: Vec<Option<&mut [Components]>> = terms.chunks_mut(VERTEX_CHUNK).map(Some).collect();
                term_chunks.resize_with(n.div_ceil(VERTEX_CHUNK), || None);
                let k = totals
                    .par_chunks_mut(VERTEX_CHUNK)
                    .zip(term_chunks)
                    .enumerate()
                    .map(|(c, (totals, terms))| {
                        let mut k = EvalCounts::default();
                        let out = vertices::VertexOut { totals, terms };
                        vertices::light_vertices(scene, lighting, two_sided, &vertex_material, c * VERTEX_CHUNK, out, &mut k);
                        k
                    })
                    .reduce(EvalCounts::default, add_counts);
                return (Lit::Vertices { totals, terms }, k, ShadowCounts::default());
            }
            let r: Vec<(Components, EvalCounts, ShadowCounts)> = (0..g.positions.len())
                .into_par_iter()
                .map(|i| {
                    let at = At { object: g.object_of_vertex(i), ..At::point(g.positions[i], g.normals[i]) };
                    light(vertex_material[i] as usize, at)
                })
                .collect();
            let (k, s) = sum(&r);
            let terms: Vec<Components> = r.into_iter().map(|(c, _, _)| c).collect();
            (Lit::Vertices { totals: terms.iter().map(Components::total).collect(), terms }, k, s)
        }
        _ => {
            let r: Vec<(Components, EvalCounts, ShadowCounts)> = g
                .triangles
                .par_iter()
                .enumerate()
                .map(|(t, tri)| {
                    let centroid = tri.iter().map(|&i| g.positions[i as usize]).sum::<Vec3>() / 3.0;
                    let at = At { tri: t as u32, object: g.object_of_triangle(t), ..At::point(centroid, g.face_normals[t]) };
                    light(g.material[t] as usize, at)
                })
                .collect();
            let (k, s) = sum(&r);
            let terms: Vec<Components> = r.into_iter().map(|(c, _, _)| c).collect();
            (Lit::Faces { totals: terms.iter().map(Components::total).collect(), terms }, k, s)
        }
    }
}
