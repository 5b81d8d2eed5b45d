//! Vertex stage → rasterizer → shading, strip by strip in parallel.
//!
//! The rasterizer hands back a visibility buffer (triangle id and barycentrics per
//! sample); shading reads it, so every visible sample is shaded exactly once whatever
//! the overdraw. Gouraud lights the vertices before rasterizing and flat lights each
//! face once; only Phong interpolation evaluates lights per sample.

use super::develop::srgb_decode;
use super::frame::{Frame, Layer};
use super::settings::{Cull, Interpolation};
use crate::raster::{self, CullMode, RasterStats, StripVis, VisBuffer, VisSample};
use crate::scene::build::Geometry;
use crate::scene::{Light, Scene};
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::shading::shade::shade;
use glam::{Vec3, Vec4};
use rayon::prelude::*;

thread_local! {
    /// Each worker keeps one strip buffer across strips and renders: no allocation (and no
    /// page faults) per strip; measured 2–4 ms of a 1024² render before this.
    static STRIP: std::cell::RefCell<StripVis> = std::cell::RefCell::new(StripVis::default());
}

/// Pixel rows per strip: 16 rows of a 1024-wide image keep a strip's samples in L2.
const STRIP_PIXELS: u32 = 16;

/// What a render did, returned with every frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Rasterizer counts.
    pub raster: RasterStats,
    /// Visible samples shaded (interpolated or lit).
    pub samples_shaded: u64,
    /// Light evaluations, wherever they ran (vertices, faces or samples).
    pub light_evaluations: u64,
    /// Light evaluations at samples (Phong interpolation only).
    pub light_evaluations_per_sample: u64,
    /// Diffuse-term evaluations (lit side only).
    pub diffuse_evaluations: u64,
    /// Specular-lobe evaluations.
    pub specular_evaluations: u64,
    /// Vertices lit (Gouraud).
    pub vertices_lit: u64,
    /// Faces lit (flat).
    pub faces_lit: u64,
    /// Samples whose shading was not finite (replaced by zero; always 0 unless there is a bug).
    pub nan_samples: u64,
    /// Degenerate mesh triangles found while building normals.
    pub degenerate_mesh_triangles: u64,
    /// Vertex normals repaired.
    pub repaired_normals: u64,
}

impl std::ops::AddAssign<&RenderStats> for RenderStats {
    fn add_assign(&mut self, o: &RenderStats) {
        self.raster += o.raster;
        self.samples_shaded += o.samples_shaded;
        self.light_evaluations += o.light_evaluations;
        self.light_evaluations_per_sample += o.light_evaluations_per_sample;
        self.diffuse_evaluations += o.diffuse_evaluations;
        self.specular_evaluations += o.specular_evaluations;
        self.vertices_lit += o.vertices_lit;
        self.faces_lit += o.faces_lit;
        self.nan_samples += o.nan_samples;
        self.degenerate_mesh_triangles += o.degenerate_mesh_triangles;
        self.repaired_normals += o.repaired_normals;
    }
}

/// Lighting precomputed before rasterization.
enum Lit {
    /// Per vertex (Gouraud).
    Vertices(Vec<Components>),
    /// Per face (flat).
    Faces(Vec<Components>),
    /// Per sample (Phong).
    Samples,
}

/// Renders the scene into a linear frame keeping the given layers (deduplicated, in order).
pub fn render(scene: &Scene, layers: &[Layer]) -> (Frame, RenderStats) {
    render_with(scene, layers, None)
}

/// Rasterizes the scene once into a whole-image visibility buffer, for shading many
/// variants that share geometry, camera and sampling (see [`same_raster`]).
pub fn rasterize(scene: &Scene) -> VisBuffer {
    let (w, h, aa) = (scene.camera.width, scene.camera.height, scene.settings.aa);
    raster::rasterize(&clip_space(scene), &scene.geometry.triangles, w * aa, h * aa, cull_mode(scene))
}

/// True when two scenes produce the same visibility buffer: same camera (but for the
/// background), triangles, positions, supersampling and culling. Materials, lights,
/// normals and interpolation may differ.
pub fn same_raster(a: &Scene, b: &Scene) -> bool {
    let cam = |s: &Scene| crate::scene::Camera { background: glam::Vec3::ZERO, ..s.camera };
    cam(a) == cam(b)
        && a.settings.aa == b.settings.aa
        && a.settings.cull == b.settings.cull
        && a.geometry.triangles == b.geometry.triangles
        && a.geometry.positions == b.geometry.positions
}

fn clip_space(scene: &Scene) -> Vec<Vec4> {
    let vp = scene.camera.view_projection();
    scene.geometry.positions.par_iter().map(|p| vp * p.extend(1.0)).collect()
}

fn cull_mode(scene: &Scene) -> CullMode {
    if scene.settings.cull == Cull::None { CullMode::None } else { CullMode::Back }
}

/// [`render`], shading a visibility buffer from [`rasterize`] instead of rasterizing
/// when one is given (precondition: it was made from a scene with [`same_raster`]).
pub fn render_with(scene: &Scene, layers: &[Layer], vis: Option<&VisBuffer>) -> (Frame, RenderStats) {
    let mut wanted: Vec<Layer> = Vec::new();
    for l in layers {
        if !wanted.contains(l) {
            wanted.push(*l);
        }
    }
    let cam = &scene.camera;
    let g = &scene.geometry;
    let aa = scene.settings.aa;
    let (w, h) = (cam.width, cam.height);
    let eye = cam.position;
    let two_sided = scene.settings.cull == Cull::None;
    let mut stats = RenderStats {
        degenerate_mesh_triangles: scene.repairs.degenerate_triangles as u64,
        repaired_normals: scene.repairs.repaired_normals as u64,
        ..Default::default()
    };

    // Lighting that does not need the rasterizer.
    // Only the lights the plan keeps are evaluated (a spot that misses every object is culled).
    let lights = super::plan::plan(scene).active_lights(scene);
    let (lit, counts) = light_ahead(scene, &lights, two_sided);
    stats.light_evaluations += counts.lights;
    stats.diffuse_evaluations += counts.diffuse;
    stats.specular_evaluations += counts.specular;
    match &lit {
        Lit::Vertices(v) => stats.vertices_lit = v.len() as u64,
        Lit::Faces(f) => stats.faces_lit = f.len() as u64,
        Lit::Samples => {}
    }

    // Vertex stage and triangle setup, unless a visibility buffer is reused.
    let setup = match vis {
        Some(_) => None,
        None => Some(raster::setup(&clip_space(scene), &g.triangles, w * aa, h * aa, STRIP_PIXELS * aa, cull_mode(scene))),
    };
    if let Some(s) = &setup {
        stats.raster += s.stats;
    }
    let strip_count = h.div_ceil(STRIP_PIXELS) as usize;
    let strip_samples = (STRIP_PIXELS * aa * w * aa) as usize;

    let want_normal = wanted.contains(&Layer::Normal);
    let mut buffers: Vec<Vec<Vec3>> = wanted.iter().map(|_| vec![Vec3::ZERO; (w * h) as usize]).collect();
    let mut coverage = vec![0f32; (w * h) as usize];
    let rows = (STRIP_PIXELS * w) as usize;
    // Hand each strip its rows of every kept layer.
    let mut strip_layers: Vec<Vec<&mut [Vec3]>> = (0..strip_count).map(|_| Vec::with_capacity(wanted.len())).collect();
    for buf in buffers.iter_mut() {
        for (s, chunk) in buf.chunks_mut(rows).enumerate() {
            strip_layers[s].push(chunk);
        }
    }
    let strips: Vec<RenderStats> = strip_layers
        .into_par_iter()
        .zip(coverage.par_chunks_mut(rows))
        .enumerate()
        .map(|(s, (mut out, cov))| {
            STRIP.with_borrow_mut(|local| {
                let mut st = RenderStats::default();
                // This strip's samples: rasterized now, or a slice of the reused buffer.
                let samples: &[VisSample] = match (&setup, vis) {
                    (Some(setup), _) => {
                        st.raster = setup.rasterize_strip(s, local);
                        &local.samples
                    }
                    (None, Some(v)) => &v.samples[s * strip_samples..((s + 1) * strip_samples).min(v.samples.len())],
                    (None, None) => unreachable!("setup exists when no buffer is given"),
                };
                let sample_width = w * aa;
                let inv = 1.0 / (aa * aa) as f32;
                let ctx = ShadeContext { scene, lights: &lights, g, lit: &lit, eye, two_sided };
                for y in 0..(cov.len() as u32 / w) {
                    for x in 0..w {
                        let i = (y * w + x) as usize;
                        let mut sum = Components::ZERO;
                        let mut normal_sum = Vec3::ZERO;
                        let mut covered = 0u32;
                        for sy in 0..aa {
                            let row = ((y * aa + sy) * sample_width + x * aa) as usize;
                            for sample in &samples[row..row + aa as usize] {
                                if sample.tri == raster::NO_TRIANGLE {
                                    continue;
                                }
                                covered += 1;
                                let c = ctx.shade(sample.tri as usize, sample.bary(), &mut st);
                                if want_normal {
                                    normal_sum += normal_colour(ctx.normal(sample.tri as usize, sample.bary()));
                                }
                                if c.is_finite() {
                                    sum += c;
                                } else {
                                    st.nan_samples += 1;
                                }
                            }
                        }
                        if covered == 0 {
                            continue;
                        }
                        st.samples_shaded += covered as u64;
                        for (layer, buf) in wanted.iter().zip(out.iter_mut()) {
                            buf[i] = if *layer == Layer::Normal { normal_sum * inv } else { layer.of(&sum) * inv };
                        }
                        cov[i] = covered as f32 * inv;
                    }
                }
                st
            })
        })
        .collect();
    for s in &strips {
        stats += s;
    }
    (Frame { width: w, height: h, layers: wanted.into_iter().zip(buffers).collect(), coverage, background: cam.background }, stats)
}

/// What shading a sample reads, gathered once per strip.
struct ShadeContext<'a> {
    scene: &'a Scene,
    lights: &'a [Light],
    g: &'a Geometry,
    lit: &'a Lit,
    eye: Vec3,
    two_sided: bool,
}

/// A unit normal as a linear colour that encodes to (N + 1)/2 in sRGB (the usual normal-map look).
#[inline]
fn normal_colour(n: Vec3) -> Vec3 {
    let e = (n + Vec3::ONE) * 0.5;
    Vec3::new(srgb_decode(e.x), srgb_decode(e.y), srgb_decode(e.z))
}

impl ShadeContext<'_> {
    /// The shading normal of a sample: face normal (flat), else the renormalized
    /// interpolated vertex normal, flipped towards the viewer when two-sided.
    #[inline]
    fn normal(&self, t: usize, b: Vec3) -> Vec3 {
        let g = self.g;
        let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
        let face = g.face_normals[t];
        let n = match self.lit {
            Lit::Faces(_) => face,
            _ => (g.normals[i0] * b.x + g.normals[i1] * b.y + g.normals[i2] * b.z).normalize_or(face),
        };
        let p = g.positions[i0] * b.x + g.positions[i1] * b.y + g.positions[i2] * b.z;
        if self.two_sided && face.dot(self.eye - p) < 0.0 { -n } else { n }
    }

    /// Shades one visible sample of triangle `t` at barycentrics `b`.
    #[inline]
    fn shade(&self, t: usize, b: Vec3, st: &mut RenderStats) -> Components {
        let g = self.g;
        let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
        match self.lit {
            Lit::Vertices(c) => c[i0] * b.x + c[i1] * b.y + c[i2] * b.z,
            Lit::Faces(c) => c[t],
            Lit::Samples => {
                let p = g.positions[i0] * b.x + g.positions[i1] * b.y + g.positions[i2] * b.z;
                let face = g.face_normals[t];
                // Interpolated normals are renormalized per sample (Phong 1975).
                let mut n = (g.normals[i0] * b.x + g.normals[i1] * b.y + g.normals[i2] * b.z).normalize_or(face);
                let v = (self.eye - p).normalize_or(face);
                if self.two_sided && face.dot(v) < 0.0 {
                    n = -n;
                }
                let mut k = EvalCounts::default();
                let scene = self.scene;
                let c = shade(&scene.materials[g.material[t] as usize], self.lights, scene.ambient, p, n, v, &mut k);
                st.light_evaluations += k.lights;
                st.light_evaluations_per_sample += k.lights;
                st.diffuse_evaluations += k.diffuse;
                st.specular_evaluations += k.specular;
                c
            }
        }
    }
}

/// Gouraud: light every vertex; flat: light every face at its centroid; Phong: nothing yet.
fn light_ahead(scene: &Scene, lights: &[Light], two_sided: bool) -> (Lit, EvalCounts) {
    let g = &scene.geometry;
    let eye = scene.camera.position;
    let light = |m: usize, p: Vec3, n: Vec3| {
        let v = (eye - p).normalize_or(n);
        let n = if two_sided && n.dot(v) < 0.0 { -n } else { n };
        let mut k = EvalCounts::default();
        let c = shade(&scene.materials[m], lights, scene.ambient, p, n, v, &mut k);
        (if c.is_finite() { c } else { Components::ZERO }, k)
    };
    let sum = |v: &[(Components, EvalCounts)]| {
        v.iter().fold(EvalCounts::default(), |a, (_, k)| EvalCounts {
            lights: a.lights + k.lights,
            diffuse: a.diffuse + k.diffuse,
            specular: a.specular + k.specular,
        })
    };
    match scene.settings.interpolation {
        Interpolation::Phong => (Lit::Samples, EvalCounts::default()),
        Interpolation::Gouraud => {
            // A vertex takes the material of the first triangle that uses it.
            let mut vertex_material = vec![0u32; g.positions.len()];
            for (t, tri) in g.triangles.iter().enumerate().rev() {
                for &i in tri {
                    vertex_material[i as usize] = g.material[t];
                }
            }
            let r: Vec<(Components, EvalCounts)> =
                (0..g.positions.len()).into_par_iter().map(|i| light(vertex_material[i] as usize, g.positions[i], g.normals[i])).collect();
            let k = sum(&r);
            (Lit::Vertices(r.into_iter().map(|(c, _)| c).collect()), k)
        }
        Interpolation::Flat => {
            let r: Vec<(Components, EvalCounts)> = g
                .triangles
                .par_iter()
                .enumerate()
                .map(|(t, tri)| {
                    let centroid = tri.iter().map(|&i| g.positions[i as usize]).sum::<Vec3>() / 3.0;
                    light(g.material[t] as usize, centroid, g.face_normals[t])
                })
                .collect();
            let k = sum(&r);
            (Lit::Faces(r.into_iter().map(|(c, _)| c).collect()), k)
        }
    }
}
