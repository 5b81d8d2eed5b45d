//! Vertex stage → rasterizer → shading, strip by strip in parallel.
//!
//! The rasterizer hands back a visibility buffer (triangle id and barycentrics per
//! sample); shading reads it, so every visible sample is shaded exactly once whatever
//! the overdraw. Gouraud lights the vertices before rasterizing and flat lights each
//! face once; only Phong interpolation evaluates lights per sample.
//!
//! Each strip is shaded one pixel row at a time: first every covered sample of the row
//! (its aa sample rows) is shaded into a row buffer, then each pixel box-filters its aa²
//! samples into the kept layers, or, for [`render_image`], straight into 8-bit sRGB.
//! Per-sample Phong shading of classic materials runs four consecutive covered samples
//! of one material at once ([`crate::shading::lanes`]): the same formula as the scalar
//! `shade_classic`, so the same bits. Physically based materials stay on the scalar path.
//!
//! A pixel's `total` is the mean of its samples' totals I_tot (each layer is the mean of
//! its samples' values); a sample whose I_tot is not finite is left out and counted in
//! [`RenderStats::nan_samples`].
//!
//! Measurements behind this structure (1024² `sphere` bench, 764k shaded samples; the
//! machine was shared with another build, so wall figures are medians taken in one run
//! alternating with the llvmpipe peer, `tools/bench_vs_llvmpipe.py`; instruction counts
//! are callgrind on `shadelab --threads 1 bench --workload sphere --frames 1 --warmup 0`,
//! which renders three frames):
//! - the branch point shaded one sample at a time through `Components` with glibc `powf`
//!   (2.48e9 instructions; image 54 ms vs llvmpipe 12.4 ms, ratio 4.4);
//! - lanes of four, the own `pow`, the row filter and develop in cache: 1.38e9;
//! - one run per single-material row, batches on one triangle loading its vertices once,
//!   empty pixels developed once, the plain render developed as resolved: 1.09e9;
//! - the walk stopping at the end of each row's span, the clamp left to the encode: 1.04e9;
//!   `tools/bench_vs_llvmpipe.py sphere --rounds 5`: image 12.5 ms vs llvmpipe 10.5 ms
//!   (ratio 1.19; dense 37.1 vs 86.6 ms, 0.43; sphere-gouraud 9.1 vs 7.0 ms, 1.31).
//! - Thread-local strip buffers: measured 2–4 ms of a 1024² render before them.
//! - Tried and dropped: eight lanes as `[f32; 8]` (spills), SoA gathers through memory
//!   (store-forwarding stalls: slower in time though not in instructions), transposed
//!   gathers (no gain), a two-triangle blend path beside the one-triangle one (no gain in
//!   instructions or time), pre-biased edge functions (more instructions).

use super::develop::{DevelopParams, srgb_decode};
use super::frame::{Frame, Layer};
use super::settings::{Cull, Interpolation, Tonemap};
use crate::raster::{self, CullMode, NO_TRIANGLE, RasterStats, Setup, StripVis, VisBuffer, VisSample};
use crate::scene::build::Geometry;
use crate::scene::{Light, Material, Scene};
use crate::shading::Components;
use crate::shading::classic::{EvalCounts, shade_classic_lanes};
use crate::shading::lanes::{F32x4, Lanes, M4, V3, WIDTH};
use crate::shading::shade::shade;
use glam::{Vec3, Vec4};
use rayon::prelude::*;

thread_local! {
    /// Each worker keeps its strip buffers across strips and renders: no allocation (and no
    /// page faults) per strip.
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

/// A worker's buffers, reused across strips and renders.
#[derive(Default)]
struct Scratch {
    /// The strip's visibility samples.
    vis: StripVis,
    /// Per sample of the current pixel row (its aa sample rows): the shaded total I_tot.
    totals: Vec<Vec3>,
    /// Per sample of the current pixel row: the terms, when a term layer is kept.
    terms: Vec<Components>,
    /// One pixel row of the developed layer (8-bit output only).
    row: Vec<Vec3>,
    /// Coverage of `row`.
    row_coverage: Vec<f32>,
    /// Indices of the covered samples of the current pixel row.
    covered: Vec<u32>,
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

/// Lighting precomputed before rasterization: per vertex or face, its terms and their total.
enum Lit {
    /// Per vertex (Gouraud).
    Vertices { terms: Vec<Components>, totals: Vec<Vec3> },
    /// Per face (flat).
    Faces { terms: Vec<Components>, totals: Vec<Vec3> },
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
        .map(|(s, (layers, coverage))| SCRATCH.with_borrow_mut(|scratch| r.strip(s, scratch, &mut StripOut::Frame { layers, coverage })))
        .collect();
    let stats = r.finish(&strips);
    let layers = r.wanted.into_iter().zip(buffers).collect();
    (Frame { width: w as u32, height: h as u32, layers, coverage, background: scene.camera.background }, stats)
}

/// Renders one layer straight to interleaved 8-bit sRGB: the bytes
/// [`develop`](super::develop::develop) gives for `render(scene, &[layer])` with the same
/// exposure and tone map, without keeping the linear frame: each pixel row is developed
/// while it is in cache, so no full-frame linear buffer is written and read back.
pub fn render_image(scene: &Scene, layer: Layer, exposure: f32, op: Tonemap) -> (Vec<u8>, RenderStats) {
    let develop = DevelopParams::new(layer, exposure, op, 3, false, scene.camera.background);
    let r = Renderer::new(scene, &[layer], None);
    let (w, h) = (r.w as usize, r.h as usize);
    let mut bytes = vec![0u8; w * h * 3];
    let strips: Vec<RenderStats> = bytes
        .par_chunks_mut(STRIP_PIXELS as usize * w * 3)
        .enumerate()
        .map(|(s, bytes)| SCRATCH.with_borrow_mut(|scratch| r.strip(s, scratch, &mut StripOut::Image { bytes, develop: &develop })))
        .collect();
    (bytes, r.finish(&strips))
}

/// Where a strip's pixels go.
enum StripOut<'a> {
    /// The strip's rows of each kept layer (in `wanted` order) and of the coverage.
    Frame { layers: Vec<&'a mut [Vec3]>, coverage: &'a mut [f32] },
    /// The strip's rows of 8-bit pixels, developed from the one kept layer.
    Image { bytes: &'a mut [u8], develop: &'a DevelopParams },
}

/// One render: what every strip reads.
struct Renderer<'a> {
    scene: &'a Scene,
    g: &'a Geometry,
    /// The lights the plan keeps (a spot that misses every object is culled).
    lights: Vec<Light>,
    lit: Lit,
    /// Triangle setup, unless a visibility buffer is reused.
    setup: Option<Setup>,
    vis: Option<&'a VisBuffer>,
    /// The kept layers, deduplicated, in order.
    wanted: Vec<Layer>,
    /// Stats of the work done before the strips.
    stats: RenderStats,
    w: u32,
    h: u32,
    aa: u32,
    eye: Vec3,
    two_sided: bool,
    /// A term layer (ambient, diffuse, specular, emission) is kept.
    want_terms: bool,
    want_normal: bool,
}

impl<'a> Renderer<'a> {
    /// Lighting ahead (Gouraud, flat), vertex stage and triangle setup.
    fn new(scene: &'a Scene, layers: &[Layer], vis: Option<&'a VisBuffer>) -> Renderer<'a> {
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
            Lit::Vertices { terms, .. } => stats.vertices_lit = terms.len() as u64,
            Lit::Faces { terms, .. } => stats.faces_lit = terms.len() as u64,
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
        let want_terms = wanted.iter().any(|l| !matches!(l, Layer::Total | Layer::Normal));
        let want_normal = wanted.contains(&Layer::Normal);
        Renderer { scene, g, lights, lit, setup, vis, wanted, stats, w, h, aa, eye: cam.position, two_sided, want_terms, want_normal }
    }

    /// The render's stats: the work before the strips plus every strip's.
    fn finish(&self, strips: &[RenderStats]) -> RenderStats {
        let mut stats = self.stats;
        for s in strips {
            stats += s;
        }
        stats
    }

    /// Rasterizes (or reads) strip `s`, shades it pixel row by pixel row and writes its pixels to `out`.
    fn strip(&self, s: usize, scratch: &mut Scratch, out: &mut StripOut) -> RenderStats {
        let Scratch { vis: local, totals, terms, row, row_coverage, covered } = scratch;
        let mut st = RenderStats::default();
        let (w, aa) = (self.w as usize, self.aa as usize);
        let row_samples = aa * aa * w;
        // This strip's samples: rasterized now, or a slice of the reused buffer.
        let samples: &[VisSample] = match (&self.setup, self.vis) {
            (Some(setup), _) => {
                st.raster = setup.rasterize_strip(s, local);
                &local.samples
            }
            (None, Some(v)) => {
                let strip_samples = STRIP_PIXELS as usize * row_samples;
                &v.samples[s * strip_samples..((s + 1) * strip_samples).min(v.samples.len())]
            }
            (None, None) => unreachable!("setup exists when no buffer is given"),
        };
        totals.resize(row_samples, Vec3::ZERO);
        if self.want_terms {
            terms.resize(row_samples, Components::ZERO);
        }
        for (y, samples) in samples.chunks(row_samples).enumerate() {
            self.shade_samples(samples, covered, totals, self.want_terms.then_some(&mut terms[..]), &mut st);
            let terms = self.want_terms.then_some(&terms[..]);
            match out {
                StripOut::Frame { layers, coverage } => self.filter_row(samples, totals, terms, layers, coverage, y * w, &mut st),
                StripOut::Image { bytes, develop } if aa == 1 && self.wanted == [Layer::Total] => {
                    // A plain render: each pixel is its sample (as the filter's fast path
                    // computes it), developed as it is resolved, without a row buffer.
                    let c = develop.channels();
                    let (mut shaded, mut nan) = (0, 0);
                    let pixels = samples.iter().zip(totals.iter()).map(|(sample, total)| {
                        let covered = sample.tri != NO_TRIANGLE;
                        let finite = total.is_finite();
                        shaded += covered as u64;
                        nan += (covered && !finite) as u64;
                        (if covered && finite { *total } else { Vec3::ZERO }, if covered { 1.0 } else { 0.0 })
                    });
                    develop.develop_iter(pixels, &mut bytes[y * w * c..(y + 1) * w * c]);
                    st.samples_shaded += shaded;
                    st.nan_samples += nan;
                }
                StripOut::Image { bytes, develop } => {
                    row.resize(w, Vec3::ZERO);
                    row_coverage.resize(w, 0.0);
                    self.filter_row(samples, totals, terms, &mut [&mut row[..]], row_coverage, 0, &mut st);
                    let c = develop.channels();
                    develop.develop_into(row, row_coverage, &mut bytes[y * w * c..(y + 1) * w * c]);
                }
            }
        }
        st
    }

    /// Box-filters the aa² samples of each pixel of one row into the kept layers
    /// (`layers[k][base + x]`, in `wanted` order) and the coverage.
    #[allow(clippy::too_many_arguments)]
    fn filter_row(
        &self,
        samples: &[VisSample],
        totals: &[Vec3],
        terms: Option<&[Components]>,
        layers: &mut [&mut [Vec3]],
        coverage: &mut [f32],
        base: usize,
        st: &mut RenderStats,
    ) {
        let (w, aa) = (self.w as usize, self.aa as usize);
        if aa == 1 && self.wanted == [Layer::Total] {
            // A plain render (one sample per pixel, only I_tot kept): each pixel is its sample,
            // as the general loop below computes it (0 + t = t, × 1), without its bookkeeping.
            let (out, coverage) = (&mut layers[0][base..base + w], &mut coverage[base..base + w]);
            let (mut shaded, mut nan) = (0, 0);
            for x in 0..w {
                let covered = samples[x].tri != NO_TRIANGLE;
                let finite = totals[x].is_finite();
                out[x] = if covered && finite { totals[x] } else { Vec3::ZERO };
                coverage[x] = if covered { 1.0 } else { 0.0 };
                shaded += covered as u64;
                nan += (covered && !finite) as u64;
            }
            st.samples_shaded += shaded;
            st.nan_samples += nan;
            return;
        }
        let sample_width = w * aa;
        let inv = 1.0 / (aa * aa) as f32;
        for x in 0..w {
            let mut total = Vec3::ZERO;
            let mut sum = Components::ZERO;
            let mut normal_sum = Vec3::ZERO;
            let mut covered = 0u32;
            for sy in 0..aa {
                let first = sy * sample_width + x * aa;
                for i in first..first + aa {
                    let sample = &samples[i];
                    if sample.tri == NO_TRIANGLE {
                        continue;
                    }
                    covered += 1;
                    if totals[i].is_finite() {
                        total += totals[i];
                        if let Some(terms) = terms {
                            sum += terms[i];
                        }
                    } else {
                        st.nan_samples += 1;
                    }
                    if self.want_normal {
                        normal_sum += normal_colour(self.normal(sample.tri as usize, sample.bary()));
                    }
                }
            }
            st.samples_shaded += covered as u64;
            let i = base + x;
            for (layer, buf) in self.wanted.iter().zip(layers.iter_mut()) {
                buf[i] = match layer {
                    Layer::Total => total * inv,
                    Layer::Normal => normal_sum * inv,
                    _ => layer.of(&sum) * inv,
                };
            }
            coverage[i] = covered as f32 * inv;
        }
    }

    /// Shades every covered sample of `samples` into `totals` (and `terms`, when given).
    fn shade_samples(
        &self,
        samples: &[VisSample],
        covered: &mut Vec<u32>,
        totals: &mut [Vec3],
        mut terms: Option<&mut [Components]>,
        st: &mut RenderStats,
    ) {
        let g = self.g;
        let (lit_terms, lit_totals) = match &self.lit {
            Lit::Samples => return self.shade_samples_lit(samples, covered, totals, terms, st),
            Lit::Vertices { terms, totals } | Lit::Faces { terms, totals } => (terms, totals),
        };
        let per_vertex = matches!(self.lit, Lit::Vertices { .. });
        for (i, sample) in samples.iter().enumerate() {
            if sample.tri == NO_TRIANGLE {
                continue;
            }
            let t = sample.tri as usize;
            if per_vertex {
                // Gouraud: each layer interpolates its vertex values.
                let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
                let b = sample.bary();
                totals[i] = lit_totals[i0] * b.x + lit_totals[i1] * b.y + lit_totals[i2] * b.z;
                if let Some(terms) = terms.as_deref_mut() {
                    terms[i] = lit_terms[i0] * b.x + lit_terms[i1] * b.y + lit_terms[i2] * b.z;
                }
            } else {
                totals[i] = lit_totals[t];
                if let Some(terms) = terms.as_deref_mut() {
                    terms[i] = lit_terms[t];
                }
            }
        }
    }

    /// Phong: lights every covered sample, a run of consecutive covered samples of one
    /// material at a time.
    fn shade_samples_lit(
        &self,
        samples: &[VisSample],
        covered: &mut Vec<u32>,
        totals: &mut [Vec3],
        mut terms: Option<&mut [Components]>,
        st: &mut RenderStats,
    ) {
        let g = self.g;
        covered.clear();
        covered.extend((0..samples.len() as u32).filter(|&i| samples[i as usize].tri != NO_TRIANGLE));
        if self.scene.materials.len() == 1 {
            // One material (the common case): one run, no per-sample material lookups.
            return self.shade_run(0, covered, samples, totals, terms, st);
        }
        let material = |i: u32| g.material[samples[i as usize].tri as usize];
        let mut rest = &covered[..];
        while let Some(&first) = rest.first() {
            let m = material(first);
            let len = rest.iter().position(|&i| material(i) != m).unwrap_or(rest.len());
            self.shade_run(m, &rest[..len], samples, totals, terms.as_deref_mut(), st);
            rest = &rest[len..];
        }
    }

    /// Shades the samples at `run` (indices into `samples`), all of material `material`:
    /// a classic material four samples at a time in lanes, a physically based one sample by sample.
    fn shade_run(
        &self,
        material: u32,
        run: &[u32],
        samples: &[VisSample],
        totals: &mut [Vec3],
        mut terms: Option<&mut [Components]>,
        st: &mut RenderStats,
    ) {
        let scene = self.scene;
        let m = &scene.materials[material as usize];
        let mut k = EvalCounts::default();
        if m.physical.is_some() {
            for &i in run {
                let sample = &samples[i as usize];
                let (p, n, v) = self.surface(sample.tri as usize, sample.bary());
                let c = shade(m, &self.lights, scene.ambient, p, n, v, &mut k);
                totals[i as usize] = c.total();
                if let Some(terms) = terms.as_deref_mut() {
                    terms[i as usize] = c;
                }
            }
        } else {
            for batch in run.chunks(WIDTH) {
                self.shade_lanes(m, batch, samples, totals, terms.as_deref_mut(), &mut k);
            }
        }
        st.light_evaluations += k.lights;
        st.light_evaluations_per_sample += k.lights;
        st.diffuse_evaluations += k.diffuse;
        st.specular_evaluations += k.specular;
    }

    /// Shades the samples at `batch` (one to four indices into `samples`) of classic material `m` in lanes.
    #[inline(always)]
    fn shade_lanes(
        &self,
        m: &Material,
        batch: &[u32],
        samples: &[VisSample],
        totals: &mut [Vec3],
        terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        let g = self.g;
        let lane_sample: [&VisSample; WIDTH] =
            std::array::from_fn(|lane| &samples[batch[if lane < batch.len() { lane } else { 0 }] as usize]);
        let b1 = F32x4::from_array(std::array::from_fn(|lane| lane_sample[lane].b1));
        let b2 = F32x4::from_array(std::array::from_fn(|lane| lane_sample[lane].b2));
        // Barycentrics (1 − b1 − b2, b1, b2) and attributes interpolated as `VisSample::bary`
        // and glam do it for one sample.
        let b0 = F32x4::splat(1.0) - b1 - b2;
        let (p, n, face);
        let t0 = lane_sample[0].tri as usize;
        if lane_sample.iter().all(|s| s.tri as usize == t0) {
            // All four samples on one triangle (most batches of a large-triangle mesh): its
            // vertices in every lane, loaded once instead of gathered and transposed (the
            // same values, so the same bits). About half the batches of the sphere bench;
            // callgrind: 578M → 487M instructions of shading for its three-frame run.
            let v = g.triangles[t0].map(|i| i as usize);
            p = v.map(|i| V3::splat(g.positions[i]));
            n = v.map(|i| V3::splat(g.normals[i]));
            face = V3::splat(g.face_normals[t0]);
        } else {
            // Gather each lane's triangle (lanes past the batch repeat its first sample).
            let mut pa = [[Vec3::ZERO; WIDTH]; 3];
            let mut na = [[Vec3::ZERO; WIDTH]; 3];
            let mut fa = [Vec3::ZERO; WIDTH];
            for lane in 0..WIDTH {
                let t = lane_sample[lane].tri as usize;
                for (j, &vi) in g.triangles[t].iter().enumerate() {
                    pa[j][lane] = g.positions[vi as usize];
                    na[j][lane] = g.normals[vi as usize];
                }
                fa[lane] = g.face_normals[t];
            }
            p = [V3::from_lanes(&pa[0]), V3::from_lanes(&pa[1]), V3::from_lanes(&pa[2])];
            n = [V3::from_lanes(&na[0]), V3::from_lanes(&na[1]), V3::from_lanes(&na[2])];
            face = V3::from_lanes(&fa);
        }
        let interpolate = |a: &[V3<F32x4>; 3]| a[0].scale(b0) + a[1].scale(b1) + a[2].scale(b2);
        let pos = interpolate(&p);
        // Interpolated normals are renormalized per sample (Phong 1975).
        let mut normal = interpolate(&n).normalize_or(face);
        let view = (V3::splat(self.eye) - pos).normalize_or(face);
        if self.two_sided {
            let back = face.dot(view).lt(F32x4::splat(0.0));
            normal = V3::select(back, -normal, normal);
        }
        let c = shade_classic_lanes(m, &self.lights, self.scene.ambient, pos, normal, view, M4::first(batch.len()), k);
        let total = c.total().to_lanes();
        for (lane, &i) in batch.iter().enumerate() {
            totals[i as usize] = total[lane];
        }
        if let Some(terms) = terms {
            let (e, a, d, s) = (c.emission.to_lanes(), c.ambient.to_lanes(), c.diffuse.to_lanes(), c.specular.to_lanes());
            for (lane, &i) in batch.iter().enumerate() {
                terms[i as usize] = Components { emission: e[lane], ambient: a[lane], diffuse: d[lane], specular: s[lane] };
            }
        }
    }

    /// Position, shading normal and view vector of a sample (Phong interpolation, scalar).
    #[inline]
    fn surface(&self, t: usize, b: Vec3) -> (Vec3, Vec3, Vec3) {
        let g = self.g;
        let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
        let p = g.positions[i0] * b.x + g.positions[i1] * b.y + g.positions[i2] * b.z;
        let face = g.face_normals[t];
        // Interpolated normals are renormalized per sample (Phong 1975).
        let mut n = (g.normals[i0] * b.x + g.normals[i1] * b.y + g.normals[i2] * b.z).normalize_or(face);
        let v = (self.eye - p).normalize_or(face);
        if self.two_sided && face.dot(v) < 0.0 {
            n = -n;
        }
        (p, n, v)
    }

    /// The shading normal of a sample: face normal (flat), else the renormalized
    /// interpolated vertex normal, flipped towards the viewer when two-sided.
    #[inline]
    fn normal(&self, t: usize, b: Vec3) -> Vec3 {
        let g = self.g;
        let [i0, i1, i2] = g.triangles[t].map(|i| i as usize);
        let face = g.face_normals[t];
        let n = match self.lit {
            Lit::Faces { .. } => face,
            _ => (g.normals[i0] * b.x + g.normals[i1] * b.y + g.normals[i2] * b.z).normalize_or(face),
        };
        let p = g.positions[i0] * b.x + g.positions[i1] * b.y + g.positions[i2] * b.z;
        if self.two_sided && face.dot(self.eye - p) < 0.0 { -n } else { n }
    }
}

/// A unit normal as a linear colour that encodes to (N + 1)/2 in sRGB (the usual normal-map look).
#[inline]
fn normal_colour(n: Vec3) -> Vec3 {
    let e = (n + Vec3::ONE) * 0.5;
    Vec3::new(srgb_decode(e.x), srgb_decode(e.y), srgb_decode(e.z))
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
            let terms: Vec<Components> = r.into_iter().map(|(c, _)| c).collect();
            (Lit::Vertices { totals: terms.iter().map(Components::total).collect(), terms }, k)
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
            let terms: Vec<Components> = r.into_iter().map(|(c, _)| c).collect();
            (Lit::Faces { totals: terms.iter().map(Components::total).collect(), terms }, k)
        }
    }
}
