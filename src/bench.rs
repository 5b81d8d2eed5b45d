//! `shadelab bench`: fixed workloads, defined once here and printed with the results.
//!
//! The workloads match ../shared/bench/workload.py (the peer benchmark): a unit uv sphere
//! seen from (0, 0, 4), fov 30°, 1024², one directional light from normalize(1, 1, 1),
//! K_diff (0.8, 0.2, 0.2), K_spec 0.5, K_shi 32, ambient 0.05, Blinn-Phong.
//!
//! Three measurements per workload, each `warmup` untimed frames then the median (with
//! min and max) of `frames` timed ones, with the scene built once beforehand:
//! - **8-bit image** (`median_ms`, `min_ms`, `max_ms`; the table's `8-bit` columns): the
//!   image a user gets, by the fused path of `render::render_image`, which develops each
//!   bundle of samples to 8-bit sRGB as shading leaves it. This is the headline figure and
//!   the one comparable to the peer's frame (clear + draw + readback of its 8-bit image);
//!   Mpix/s and Mtri/s are computed from it.
//! - **float frame** (`float_frame_median_ms`; `float med`): the other path,
//!   `render::render` to a linear float frame with its layers (EXR, splits, figures). It is
//!   not a part of the 8-bit time: it fills 16 bytes a pixel (three f32 channels and a
//!   coverage) instead of 3, and so usually takes *longer* than the whole 8-bit image
//!   (docs/performance.md).
//! - **png** (`png_median_ms`; `+png med`): the 8-bit image encoded as PNG in memory, as
//!   `shadelab render` writes it.
//!
//! The `slide` workload composes developed cells into one RGBA figure, so its render and
//! image measurements are the same figure.
//!
//! The `shadow` workload matches ../shared/bench/llvmpipe_shadow.py: the `sphere` workload's
//! sphere resting on the ground square y = −1, x and z in [−3, 3], seen from (0, 2, 6)
//! looking at (0, −0.5, 0), fov 35°, the same light and material, `shadows = "map"` with a
//! 2048² map and one bilinearly weighted compare (`shadow_pcf = 1`, the peer's 2 × 2 PCF).
//! `shadow-ray` is the same scene with a shadow ray per shaded sample (the reference); the
//! table adds its rays per second over the whole render, the BVH build time, and the rays
//! alone: the frame's shadow rays (one per pixel whose surface faces the light, from the
//! surface the camera ray finds, offset as the renderer offsets it) traced one at a time and
//! in packets of sixteen neighbours of a row, with no shading around them (the figure
//! comparable to a ray engine's rays per second on the same rays).
//! `bvh-build` builds the `dense` sphere's acceleration structure (1,046,528 triangles):
//! its time is the workload's time.
//! `path` path traces lesson 27's box (`[render] method = "path"`) at 256², 16 paths a pixel,
//! up to 16 segments: the table adds its paths and rays (segments and next-event rays) per
//! second, and per thread (run it with `--threads 1` and `--threads 2` for the scaling).

use crate::cost::timing::{Timing, peak_rss_mb, reset_peak_rss, time};
use crate::figure::{FigureOptions, render_figure};
use crate::geometry::bvh::RayPacket;
use crate::lesson::{self, FigureBody, FigureSpec, KeyPath, Lesson};
use crate::light::LightKind;
use crate::render::{self, Layer};
use crate::scene::Scene;
use crate::transport::{Origin, SceneRays, ShadowRay};
use glam::Vec3;
use std::path::Path;

/// One benchmark workload.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Workload {
    /// Name on the command line.
    pub name: &'static str,
    /// What it renders.
    pub description: &'static str,
    segments: u32,
    rings: u32,
    interpolation: &'static str,
    /// A 2×2 figure filling a 3840×2160 slide with aa 4 instead of one frame.
    slide: bool,
    /// The sphere on a ground square with this shadow method (the `shadow` workloads).
    shadows: Option<&'static str>,
}

/// The workloads' material, light and ambient light (../shared/bench/workload.py).
const MATERIAL_AND_LIGHT: &str = r#"[material.m]
model = "blinn_phong"
ambient = [0.8, 0.2, 0.2]
diffuse = [0.8, 0.2, 0.2]
specular = 0.5
shininess = 32
[[light]]
kind = "directional"
direction = [-1, -1, -1]
[scene]
ambient = 0.05
"#;

/// The `slide` workload's cell size.
const SLIDE_CELL: (u32, u32) = (1830, 1009);

/// Every workload, in the order `bench` runs them.
pub const WORKLOADS: [Workload; 8] = [
    Workload {
        name: "sphere",
        description: "uv_sphere 128×64 (16,128 triangles), 1024², per-pixel Blinn-Phong",
        segments: 128,
        rings: 64,
        interpolation: "phong",
        slide: false,
        shadows: None,
    },
    Workload {
        name: "sphere-gouraud",
        description: "the same, Gouraud (lit per vertex)",
        segments: 128,
        rings: 64,
        interpolation: "gouraud",
        slide: false,
        shadows: None,
    },
    Workload {
        name: "dense",
        description: "uv_sphere 1024×512 (1,046,528 triangles), 1024², per-pixel Blinn-Phong",
        segments: 1024,
        rings: 512,
        interpolation: "phong",
        slide: false,
        shadows: None,
    },
    Workload {
        name: "slide",
        description: "a 2×2 K_spec × K_shi figure filling a 3840×2160 slide (3839×2160, cells 1830×1009), aa 4",
        segments: 128,
        rings: 64,
        interpolation: "phong",
        slide: true,
        shadows: None,
    },
    Workload {
        name: "shadow",
        description: "the sphere on a ground square, a 2048² shadow map + the 1024² shading pass",
        segments: 128,
        rings: 64,
        interpolation: "phong",
        slide: false,
        shadows: Some("map"),
    },
    Workload {
        name: "shadow-ray",
        description: "the same scene, a shadow ray per shaded sample (BVH)",
        segments: 128,
        rings: 64,
        interpolation: "phong",
        slide: false,
        shadows: Some("ray"),
    },
    Workload {
        name: "path",
        description: "lesson 27's box path traced, 256², 16 paths a pixel, up to 16 segments",
        segments: 0,
        rings: 0,
        interpolation: "phong",
        slide: false,
        shadows: Some("path"),
    },
    Workload {
        name: "bvh-build",
        description: "the dense sphere's ray-query structure (1,046,528 triangles), built",
        segments: 1024,
        rings: 512,
        interpolation: "phong",
        slide: false,
        shadows: Some("build"),
    },
];

impl Workload {
    /// The workload as a lesson (the same code path as a user's lesson).
    pub fn lesson(&self) -> Lesson {
        // Cells that make the labelled figure 3839×2160: its margins and labels take 179×142
        // pixels at scale 1, and two equal cells cannot fill the odd 3661 left across.
        let (w, h) = if self.slide { (SLIDE_CELL.0, SLIDE_CELL.1) } else { (1024, 1024) };
        let aa = if self.slide { 4 } else { 1 };
        if self.shadows == Some("path") {
            return path_lesson();
        }
        if let Some(method) = self.shadows.filter(|m| *m != "build") {
            return self.shadow_lesson(method);
        }
        let text = format!(
            r#"[lesson]
title = "bench: {name}"
[camera]
position = [0, 0, 4]
look_at = [0, 0, 0]
fov_deg = 30
size = [{w}, {h}]
near = 0.1
[[object]]
shape = "uv_sphere"
segments = {s}
rings = {r}
material = "m"
{MATERIAL_AND_LIGHT}[render]
interpolation = "{i}"
aa = {aa}
"#,
            name = self.name,
            s = self.segments,
            r = self.rings,
            i = self.interpolation
        );
        lesson::parse(&text, Path::new("bench.toml"), &[]).expect("bench workloads are valid lessons")
    }

    /// The `shadow` workloads' lesson (../shared/bench/llvmpipe_shadow.py's scene).
    fn shadow_lesson(&self, method: &str) -> Lesson {
        let text = format!(
            r#"[lesson]
title = "bench: {name}"
[camera]
position = [0, 2, 6]
look_at = [0, -0.5, 0]
fov_deg = 35
size = [1024, 1024]
near = 0.1
[[object]]
shape = "uv_sphere"
segments = {s}
rings = {r}
material = "m"
[[object]]
shape = "plane"
scale = 3
translate = [0, -1, 0]
material = "m"
{MATERIAL_AND_LIGHT}[render]
interpolation = "{i}"
shadows = "{method}"
shadow_map_size = 2048
shadow_pcf = 1
"#,
            name = self.name,
            s = self.segments,
            r = self.rings,
            i = self.interpolation
        );
        lesson::parse(&text, Path::new("bench.toml"), &[]).expect("bench workloads are valid lessons")
    }
}

/// The `path` workload's lesson: lesson 27's box (built into the program), path traced.
fn path_lesson() -> Lesson {
    let text = include_str!("../lessons/27-radiosity.toml");
    let sets: Vec<lesson::Override> = ["render.method=\"path\"", "render.spp=16", "render.max_depth=16", "camera.size=[256, 256]"]
        .iter()
        .map(|s| lesson::Override::parse(s).expect("valid overrides"))
        .collect();
    lesson::parse(text, Path::new("27-radiosity.toml"), &sets).expect("lesson 27 is a valid lesson")
}

/// Results of one workload.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchResult {
    /// The workload.
    pub workload: Workload,
    /// Render + develop to 8-bit sRGB (the image a user gets; the headline figure), per frame.
    pub image: Timing,
    /// Render only (scene built once; vertex stage, raster, shading, resolve), per frame.
    pub render: Timing,
    /// The image + PNG encoding in memory, per frame.
    pub with_png: Timing,
    /// Pixels per frame.
    pub pixels: u64,
    /// Triangles per frame.
    pub triangles: u64,
    /// Worker threads.
    pub threads: usize,
    /// Peak resident memory during this workload, MB (the process's, reset before it where
    /// the OS allows).
    pub peak_rss_mb: Option<f64>,
    /// Shadow rays per frame (the `shadow-ray` workload; 0 elsewhere).
    pub shadow_rays: u64,
    /// BVH build over the scene's triangles, median ms (the `shadow-ray` workload).
    pub bvh_build: Option<Timing>,
    /// The frame's shadow rays alone, one at a time and in packets (the `shadow-ray` workload).
    pub trace: Option<TraceResult>,
    /// Paths per frame (the `path` workload; 0 elsewhere).
    pub paths: u64,
    /// Rays per frame of the `path` workload: segments (closest hits) and next-event rays.
    pub path_rays: u64,
}

/// The shadow rays of a `shadow-ray` frame traced with nothing around them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceResult {
    /// Rays traced.
    pub rays: u64,
    /// How many of them are blocked (the same for both ways: checked).
    pub occluded: u64,
    /// All of them one at a time (`SceneRays::occluded`).
    pub single: Timing,
    /// All of them in packets of sixteen neighbours of a row (`SceneRays::occluded_packet`).
    pub packet: Timing,
}

impl TraceResult {
    /// Million rays per second one at a time, at the median.
    pub fn single_mrays(&self) -> f64 {
        self.rays as f64 / 1e6 / (self.single.median_ms / 1e3)
    }

    /// Million rays per second in packets, at the median.
    pub fn packet_mrays(&self) -> f64 {
        self.rays as f64 / 1e6 / (self.packet.median_ms / 1e3)
    }
}

impl BenchResult {
    /// Megapixels per second at the median image time.
    pub fn mpix_per_s(&self) -> f64 {
        self.pixels as f64 / 1e6 / (self.image.median_ms / 1e3)
    }

    /// Million shadow rays per second at the median render time (0 without shadow rays).
    pub fn mrays_per_s(&self) -> f64 {
        self.shadow_rays as f64 / 1e6 / (self.render.median_ms / 1e3)
    }

    /// Million paths per second at the median image time (0 without paths).
    pub fn mpaths_per_s(&self) -> f64 {
        self.paths as f64 / 1e6 / (self.image.median_ms / 1e3)
    }

    /// Million path rays (segments and next-event rays) per second at the median image time.
    pub fn mpath_rays_per_s(&self) -> f64 {
        self.path_rays as f64 / 1e6 / (self.image.median_ms / 1e3)
    }

    /// Million triangles per second at the median image time.
    pub fn mtri_per_s(&self) -> f64 {
        self.triangles as f64 / 1e6 / (self.image.median_ms / 1e3)
    }
}

/// Runs one workload: `warmup` untimed frames, then `frames` timed ones, three times
/// (render only, the 8-bit image, the image as PNG).
pub fn run(w: &Workload, warmup: usize, frames: usize) -> BenchResult {
    reset_peak_rss();
    let lesson = w.lesson();
    let threads = rayon::current_num_threads();
    if w.slide {
        let spec = slide_spec();
        let opts = FigureOptions::default();
        let triangles = crate::scene::build::build(&lesson).expect("bench meshes are built in").geometry.triangles.len() as u64;
        let render = time(warmup, frames, || render_figure(&lesson, &spec, &opts).expect("valid figure"));
        let with_png = time(warmup, frames, || {
            let fig = render_figure(&lesson, &spec, &opts).expect("valid figure");
            let mut out = Vec::new();
            crate::output::encode_png_rgba(&mut out, &fig.image).expect("in-memory encode");
            out.len()
        });
        let (cw, ch) = (lesson.scene.camera.width as u64, lesson.scene.camera.height as u64);
        return BenchResult {
            workload: *w,
            image: render,
            render,
            with_png,
            pixels: 4 * cw * ch,
            triangles,
            threads,
            peak_rss_mb: peak_rss_mb(),
            shadow_rays: 0,
            bvh_build: None,
            trace: None,
            paths: 0,
            path_rays: 0,
        };
    }
    let scene = crate::scene::build::build(&lesson).expect("bench meshes are built in");
    if w.shadows == Some("build") {
        // The workload is the build: its time stands in every column.
        let build = time(warmup, frames, || SceneRays::build(&scene));
        return BenchResult {
            workload: *w,
            image: build,
            render: build,
            with_png: build,
            pixels: 0,
            triangles: scene.geometry.triangles.len() as u64,
            threads: rayon::current_num_threads(),
            peak_rss_mb: peak_rss_mb(),
            shadow_rays: 0,
            bvh_build: Some(build),
            trace: None,
            paths: 0,
            path_rays: 0,
        };
    }
    let image = || {
        let (rgb, _) = render::render_image(&scene, Layer::Total, scene.spec.settings.exposure, scene.spec.settings.tonemap);
        (scene.spec.camera.width, scene.spec.camera.height, rgb)
    };
    let render = time(warmup, frames, || render::render(&scene, &[Layer::Total]));
    let image_timing = time(warmup, frames, image);
    let with_png = time(warmup, frames, || {
        let (width, height, rgb) = image();
        let mut out = Vec::new();
        crate::output::encode_png(&mut out, width, height, &rgb).expect("in-memory encode");
        out.len()
    });
    let shadow_rays =
        if w.shadows.is_some() { render::render(&scene, &[Layer::Total]).1.count(crate::transport::visibility::SHADOW_RAYS) } else { 0 };
    let bvh_build = (w.shadows == Some("ray")).then(|| time(warmup, frames, || SceneRays::build(&scene)));
    let trace = (w.shadows == Some("ray")).then(|| trace(&scene, warmup, frames));
    let (paths, path_rays) = if w.shadows == Some("path") {
        let c = render::render(&scene, &[Layer::Total]).1.counters;
        use crate::transport::path::{NEE_RAYS, PATHS, SEGMENTS};
        (c.get(PATHS), c.get(SEGMENTS) + c.get(NEE_RAYS))
    } else {
        (0, 0)
    };
    BenchResult {
        workload: *w,
        image: image_timing,
        render,
        with_png,
        pixels: scene.spec.camera.width as u64 * scene.spec.camera.height as u64,
        triangles: scene.geometry.triangles.len() as u64,
        threads,
        peak_rss_mb: peak_rss_mb(),
        shadow_rays,
        bvh_build,
        trace,
        paths,
        path_rays,
    }
}

/// A frame's shadow rays toward the scene's one directional light: from the surface each
/// pixel's centre ray finds (where it faces the light), in pixel order.
fn shadow_rays(scene: &Scene, rays: &SceneRays) -> (Vec<Origin>, Vec3) {
    let l = match scene.lights.iter().find_map(|l| match l.kind {
        LightKind::Directional(d) => Some(-d.direction),
        _ => None,
    }) {
        Some(l) => l,
        None => return (Vec::new(), Vec3::Y),
    };
    let cam = scene.spec.camera.rays();
    let eye = Origin { p: scene.spec.camera.position, ng: Vec3::Y, tri: u32::MAX, object: u32::MAX };
    let g = &scene.geometry;
    let mut origins = Vec::new();
    for y in 0..scene.spec.camera.height {
        for x in 0..scene.spec.camera.width {
            let d = cam.ray((x, y), (0, 0), 1).dir.as_vec3().normalize();
            // The eye is on no surface: a zero offset along a normal facing the ray.
            let Some(hit) = rays.closest(&Origin { ng: d, ..eye }, d) else { continue };
            let ng = g.face_normals[hit.tri as usize];
            let ng = if ng.dot(d) > 0.0 { -ng } else { ng };
            if ng.dot(l) > 0.0 {
                origins.push(Origin { p: eye.p + d * hit.t, ng, tri: hit.tri, object: hit.object });
            }
        }
    }
    (origins, l)
}

/// A packet of prepared shadow rays, each ray's (object, triangle) and the lanes in use.
type Packet = (RayPacket, [(u32, u32); RayPacket::MAX], u16);

/// Times the frame's shadow rays one at a time and in packets of sixteen: the rays are
/// prepared first (moved off their surfaces, bounded, packed), as a ray engine is handed them.
fn trace(scene: &Scene, warmup: usize, frames: usize) -> TraceResult {
    let rays = SceneRays::build(scene);
    let (origins, l) = shadow_rays(scene, &rays);
    let prepared: Vec<ShadowRay> = origins.iter().filter_map(|o| ShadowRay::new(o, l, f32::INFINITY)).collect();
    let packets: Vec<Packet> = prepared
        .chunks(RayPacket::MAX)
        .map(|c| {
            let mut packet = RayPacket::default();
            let mut owners = [(u32::MAX, u32::MAX); RayPacket::MAX];
            for (j, r) in c.iter().enumerate() {
                packet.set(j, r.start, r.dir, r.t_max, 0..0);
                owners[j] = (r.object, r.tri);
            }
            (packet, owners, if c.len() == RayPacket::MAX { u16::MAX } else { (1u16 << c.len()) - 1 })
        })
        .collect();
    let single = || prepared.iter().filter(|r| rays.blocked(r)).count() as u64;
    let mut work = packets.clone();
    let mut in_packets = || work.iter_mut().map(|(p, o, a)| rays.blocked_packet(p, o, *a).count_ones() as u64).sum::<u64>();
    let occluded = single();
    assert_eq!(in_packets(), occluded, "packets and single rays disagree");
    let single_t = time(warmup, frames, single);
    let packet_t = time(warmup, frames, &mut in_packets);
    TraceResult { rays: prepared.len() as u64, occluded, single: single_t, packet: packet_t }
}

/// The `slide` workload's figure: K_spec down, K_shi across.
fn slide_spec() -> FigureSpec {
    let rows = lesson::Axis {
        key: KeyPath::parse("material.m.specular").expect("path"),
        values: vec![0.3.into(), 0.6.into()],
        labels: None,
        origin: KeyPath::default(),
    };
    let cols = lesson::Axis {
        key: KeyPath::parse("material.m.shininess").expect("path"),
        values: vec![8.into(), 64.into()],
        labels: None,
        origin: KeyPath::default(),
    };
    FigureSpec { title: Some("Blinn-Phong: K_spec × K_shi".into()), ..FigureSpec::new("slide", FigureBody::grid(rows, cols)) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn workloads_match_the_peer_benchmark_definition() {
        // ../shared/bench/workload.py: 16,128 and 1,046,528 triangles (pole rows are single triangles).
        let count = |name: &str| {
            let w = WORKLOADS.iter().find(|w| w.name == name).unwrap();
            crate::scene::build::build(&w.lesson()).unwrap().geometry.triangles.len()
        };
        assert_eq!(count("sphere"), 16_128);
        assert_eq!(count("dense"), 1_046_528);
        let l = WORKLOADS[0].lesson();
        assert_eq!((l.scene.camera.width, l.scene.camera.height, l.scene.camera.fov_y_deg), (1024, 1024, 30.0));
        assert_eq!(l.materials[0].classic().unwrap().shininess, 32.0);
    }

    #[test]
    fn slide_fills_a_3840_by_2160_slide() {
        let w = WORKLOADS.iter().find(|w| w.slide).unwrap();
        let mut lesson = w.lesson();
        assert_eq!(lesson.scene.settings.aa, 4);
        lesson.scene.settings.aa = 1; // the size does not depend on it; a quicker test
        let fig = render_figure(&lesson, &slide_spec(), &FigureOptions::default()).unwrap();
        assert_eq!(fig.image.dimensions(), (3839, 2160));
    }
}
