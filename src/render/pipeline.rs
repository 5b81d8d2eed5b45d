//! Vertex stage → rasterizer → shading, strip by strip in parallel.
//!
//! The rasterizer hands back a strip's visibility ([`StripVis`]: per triangle that owns
//! samples, their indices and screen-space barycentrics); shading reads it, so every
//! visible sample is shaded exactly once whatever the overdraw. Gouraud lights the
//! vertices before rasterizing and flat lights each face once; only Phong interpolation
//! evaluates lights per sample.
//!
//! Each strip is shaded triangle by triangle into strip buffers, then filtered one pixel
//! row at a time: each pixel box-filters its aa² samples into the kept layers, or, for
//! [`render_image`], straight into 8-bit sRGB (a plain render: as the bundles leave their
//! totals). A triangle's samples are shaded in bundles of sixteen AVX-512 lanes when the CPU
//! has AVX-512F ([`crate::simd::avx512`]), of eight AVX lanes when it has AVX
//! ([`crate::simd::avx`]; both chosen at run time), else four SSE2 lanes
//! ([`crate::simd::lanes`]), its rest in eight and its last partial bundle in four, with
//! its vertices in every lane (loaded once) and the perspective division of the whole bundle
//! in one instruction ([`StripTri::resolve`]); Phong with a classic material and Gouraud run
//! in lanes, the same formula as the scalar `shade_classic` and interpolation, so the same
//! bits whatever the width (tested: `eight_lanes_give_the_bits_of_four`). Physically based
//! materials stay on the scalar path.
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
//! - the perspective division moved from the depth test (a `divss` stall on every passing
//!   sample) into the shading bundles, the strip's samples shaded triangle by triangle
//!   from the rasterizer's owned-sample lists (no bundle mixes triangles: vertices loaded
//!   once per triangle, about half the bundles gathered several before), only the depth
//!   cleared per strip (4 bytes a sample instead of 16): 1.03e9 → 0.88e9; sphere-gouraud
//!   0.70e9 → 0.64e9; dense 2.72e9 → 2.90e9 (+6.6%: a triangle there owns about three
//!   samples of a strip, so most bundles are partial: 320k bundles a frame for 191k full
//!   ones). One thread, alternating, median of 8 (`bench --frames 10`): sphere image 21.8 →
//!   20.4 ms, dense 58.1 → 65.4 ms.
//! - eight AVX lanes for a triangle's full bundles (run-time `is_x86_feature_detected!`, one
//!   `#[target_feature(enable = "avx")]` function per strip; no FMA, so the bits of four
//!   lanes): 0.88e9 → 0.72e9; sphere-gouraud 0.64e9 → 0.61e9; dense 2.90e9 → 2.79e9. One
//!   thread, alternating, median of 8: sphere image 20.9 → 17.2 ms;
//!   `tools/bench_vs_llvmpipe.py sphere --rounds 5` (2 threads): 9.4 ms vs llvmpipe 11.6 ms,
//!   ratio 0.81.
//! - opaque RGB developed four pixels at a time in lanes, a plain render developed straight
//!   from its samples: 0.72e9 → 0.61e9 (sphere-gouraud 0.61e9 → 0.50e9, dense 2.79e9 →
//!   2.68e9); overdraw found by counting a strip's covered samples once instead of a test per
//!   passing sample: 0.61e9 → 0.60e9 (dense 2.68e9 → 2.67e9). Then, 2 threads,
//!   `tools/bench_vs_llvmpipe.py WORKLOAD --rounds 7`: sphere 8.97 ms vs llvmpipe 11.42 ms
//!   (ratio 0.79), dense 34.9 vs 77.2 ms (0.45), sphere-gouraud 5.47 vs 6.44 ms (0.85).
//! - the walk four samples of a row at a time in i32 lanes (SSE2) for triangles whose edge
//!   values fit i32 over their box, each row's lanes started at its span
//!   (`raster::walk_lanes`; larger triangles keep the i64 walk): 0.602e9 → 0.553e9
//!   (rasterize_strip 0.196e9 → 0.147e9; sphere-gouraud 0.495e9 → 0.446e9). 2 threads,
//!   alternating, median of 10 (`bench --frames 20`): sphere image 10.66 → 9.71 ms (a slow
//!   spell of the machine; 1 thread, median of 10: 18.03 → 16.65 ms).
//! - a plain render developed from its samples' totals as the bundles leave them, channel by
//!   channel in batches of 256 samples developed in the bundles' lanes (`Developed`), instead
//!   of scattering them into the strip and developing it four pixels at a time: 0.553e9 →
//!   0.522e9 (sphere-gouraud 0.446e9 → 0.415e9). One thread, alternating, median of 10: sphere
//!   image 13.55 → 11.84 ms; 2 threads, median of 8: 7.24 → 6.93 ms.
//! - every strip its own rayon job (`with_max_len(1)`): before, the strips were split in runs,
//!   and a worker finishing early could not take the last strips of another's run (timed in
//!   one 2-thread frame: one worker idle the last 0.8 ms of 7.5). 2 threads, alternating,
//!   median of 14: sphere image 8.75 → 8.56 ms (a slow spell of the machine).
//! - a plain render's empty pixels written sixteen at a time before shading (one pixel a
//!   loop step before): 0.522e9 → 0.518e9; `Renderer::strip`'s own share of the bench's time
//!   (perf) 1.7% → 0.9%. One thread, alternating, median of 10: 12.44 → 11.87 ms.
//! - the encode's bucket tables a power of two long, the bucket masked instead of clamped
//!   (`develop.rs`): 0.518e9 → 0.514e9. One thread, alternating, median of 10: 11.46 →
//!   11.18 ms (min 11.33 → 11.02).
//! - sixteen AVX-512 lanes for a triangle's full bundles on CPUs with AVX-512F (the rest in
//!   eight, then four; the same bits, tested at every width): 2 threads, alternating, median
//!   of 12 (`bench --frames 20`): sphere image 8.26 → 7.63 ms (median of the paired ratios
//!   0.92; a slow spell of the machine); 1 thread, min of 16: 11.18 → 10.31 ms. Not in
//!   callgrind: valgrind runs no AVX-512, so there the renderer takes eight lanes, and the
//!   sixteen-lane buffers (`MAX_WIDTH`, `LIST_PAD`) cost that path 0.514e9 → 0.525e9.
//! - With the six changes above (i32 lane walk, batched develop, a job per strip, the empty
//!   fill, masked buckets, sixteen lanes), 2 threads: `bench --workload sphere` alternated six
//!   times with the build before them, median 7.35 → 5.34 ms;
//!   `tools/bench_vs_llvmpipe.py sphere --rounds 5`: 5.92 ms vs llvmpipe 10.37 ms (ratio 0.57).
//!   Merged, `tools/bench_vs_llvmpipe.py WORKLOAD --rounds 7` in a slower spell: sphere 6.29 vs
//!   10.10 ms (0.62), dense 41.8 vs 91.9 ms (0.45), sphere-gouraud 4.53 vs 6.11 ms (0.74).
//! - Thread-local strip buffers: measured 2–4 ms of a 1024² render before them.
//! - Not yet tried: AVX2/AVX-512 gathers for the sRGB encode's table lookups (the largest
//!   cost left in the develop), and overlapping the serial setup and the zeroing of the 3 MB
//!   output image (about 0.5 ms of a sphere frame before the strips start) with the strips.
//! - Tried and dropped: eight lanes as `[f32; 8]` (spills), SoA gathers through memory
//!   (store-forwarding stalls: slower in time though not in instructions), transposed
//!   gathers (no gain), a two-triangle blend path beside the one-triangle one (no gain in
//!   instructions or time), pre-biased edge functions (more instructions); with the bundles
//!   per triangle, gathering every triangle's remainder (its last `len mod 4` samples) into
//!   bundles of several triangles: dense 2.90e9 → 2.91e9 with the gathers through stack
//!   arrays, 2.99e9 with gathers into registers (sphere −0.5%), so a triangle's last bundle
//!   stays partial; a plain render developed inside each shading bundle, on its registers
//!   (0.553e9 → 0.511e9 instructions, but no faster: one thread 13.63 → 13.95 ms, median of
//!   10; the same develop run on batches of the bundles' totals, above, is what paid).

use super::develop::{DevelopParams, srgb_decode};
use super::frame::{Frame, Layer};
use super::incidents::shade_point;
use super::settings::{Cull, Interpolation, Tonemap};
use crate::raster::{self, CullMode, Owned, RasterStats, Setup, StripTri, StripVis, VisBuffer};
use crate::scene::build::Geometry;
use crate::scene::{Classic, Light, Material, Model, Scene};
use crate::shading::Components;
use crate::shading::classic::{EvalCounts, shade_classic_lanes};
#[cfg(target_arch = "x86_64")]
use crate::simd::avx::Avx;
#[cfg(target_arch = "x86_64")]
use crate::simd::avx512::Avx512;
#[cfg(target_arch = "x86_64")]
use crate::simd::lanes::LaneTask;
use crate::simd::lanes::{F32x4, Lanes, MAX_WIDTH, V3};
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
    /// The strip's visibility.
    vis: StripVis,
    /// Per sample of the strip: the shaded total I_tot.
    totals: Vec<Vec3>,
    /// Per sample of the strip: the terms, when a term layer is kept.
    terms: Vec<Components>,
    /// Per sample of the strip: the normal layer's colour, when it is kept.
    normals: Vec<Vec3>,
    /// One pixel row of the developed layer (8-bit output only).
    row: Vec<Vec3>,
    /// Coverage of `row`.
    row_coverage: Vec<f32>,
}

/// Where a strip's shading goes, per sample of the strip.
struct StripShading<'a, T: Totals + ?Sized> {
    /// The shaded total I_tot.
    totals: &'a mut T,
    /// The terms, when a term layer is kept.
    terms: Option<&'a mut [Components]>,
    /// The normal layer's colour, when it is kept.
    normals: Option<&'a mut [Vec3]>,
}

/// Where the shaded totals I_tot of a strip's samples go.
trait Totals {
    /// Lane l of `v` is the total of sample `index[l]`, for the lanes in `index`.
    fn put<F: Lanes>(&mut self, v: V3<F>, index: &[u32]);
    /// `v` is the total of sample `i`.
    fn put_one(&mut self, i: u32, v: Vec3);
    /// Finishes the strip's totals (work left in a buffer, done `F::WIDTH` lanes at a time).
    fn flush<F: Lanes>(&mut self) {}
}

/// Per sample of the strip, its total.
impl Totals for [Vec3] {
    #[inline(always)]
    fn put<F: Lanes>(&mut self, v: V3<F>, index: &[u32]) {
        scatter(v, index, self);
    }
    #[inline(always)]
    fn put_one(&mut self, i: u32, v: Vec3) {
        self[i as usize] = v;
    }
}

/// A plain render's pixels (one sample each, only I_tot kept, opaque RGB), developed to 8-bit
/// sRGB from their samples' totals ([`DevelopParams::develop_covered`]): the shading bundles
/// leave their totals here channel by channel, and every [`DEVELOP_BATCH`] samples are
/// developed in lanes of the bundles' width. No strip of totals is scattered and read back
/// pixel by pixel, and no four pixels' channels are regrouped into registers.
struct Developed<'a> {
    /// The strip's pixels, `develop.channels()` bytes each.
    bytes: &'a mut [u8],
    develop: &'a DevelopParams,
    /// Covered samples whose total was not finite.
    nan: u64,
    /// Totals waiting to be developed (channels x, y, z and sample index, `len` of them, then
    /// room for a bundle read past the end): developing them in a loop of their own keeps the
    /// shading bundles' long dependency chains apart from the develop's.
    x: [f32; DEVELOP_BATCH + MAX_WIDTH],
    y: [f32; DEVELOP_BATCH + MAX_WIDTH],
    z: [f32; DEVELOP_BATCH + MAX_WIDTH],
    index: [u32; DEVELOP_BATCH + MAX_WIDTH],
    len: usize,
}

/// Samples a [`Developed`] buffers before developing them.
const DEVELOP_BATCH: usize = 256;

impl<'a> Developed<'a> {
    fn new(bytes: &'a mut [u8], develop: &'a DevelopParams) -> Developed<'a> {
        let zero = [0f32; DEVELOP_BATCH + MAX_WIDTH];
        Developed { bytes, develop, nan: 0, x: zero, y: zero, z: zero, index: [0; DEVELOP_BATCH + MAX_WIDTH], len: 0 }
    }
}

impl Totals for Developed<'_> {
    #[inline(always)]
    fn put<F: Lanes>(&mut self, v: V3<F>, index: &[u32]) {
        if self.len + MAX_WIDTH > DEVELOP_BATCH {
            self.flush::<F>();
        }
        let n = self.len;
        v.x.store(&mut self.x[n..]);
        v.y.store(&mut self.y[n..]);
        v.z.store(&mut self.z[n..]);
        self.index[n..n + index.len()].copy_from_slice(index);
        self.len += index.len();
    }
    #[inline(always)]
    fn put_one(&mut self, i: u32, v: Vec3) {
        self.put::<f32>(v.into(), &[i]);
    }
    #[inline(always)]
    fn flush<F: Lanes>(&mut self) {
        for j in (0..self.len).step_by(F::WIDTH) {
            let v = V3 { x: F::load(&self.x[j..]), y: F::load(&self.y[j..]), z: F::load(&self.z[j..]) };
            self.nan += self.develop.develop_covered(v, &self.index[j..(j + F::WIDTH).min(self.len)], self.bytes);
        }
        self.len = 0;
    }
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
        .with_max_len(1)
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
        // Every strip its own job, so an idle worker can take any strip left (not only a
        // half of another's run): see the module docs.
        .with_max_len(1)
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
    /// Lanes per shading bundle: 16 (AVX-512F), 8 (AVX) or 4 (SSE2), the widest this CPU runs.
    lanes: usize,
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
        Renderer {
            scene,
            g,
            lights,
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
            want_terms,
            want_normal,
            lanes: bundle_lanes(),
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

    /// Rasterizes (or reads) strip `s`, shades its covered samples triangle by triangle, then
    /// filters and writes its pixels to `out` pixel row by pixel row.
    fn strip(&self, s: usize, scratch: &mut Scratch, out: &mut StripOut) -> RenderStats {
        let Scratch { vis, totals, terms, normals, row, row_coverage } = scratch;
        let mut st = RenderStats::default();
        let (w, aa) = (self.w as usize, self.aa as usize);
        let row_samples = aa * aa * w;
        // This strip's samples: rasterized now, or a slice of the reused buffer.
        match (&self.setup, self.vis) {
            (Some(setup), _) => st.raster = setup.rasterize_strip(s, vis),
            (None, Some(v)) => {
                let strip_samples = STRIP_PIXELS as usize * row_samples;
                let samples = &v.samples[s * strip_samples..((s + 1) * strip_samples).min(v.samples.len())];
                vis.load(samples, (s * STRIP_PIXELS as usize * aa) as u32, v.width);
            }
            (None, None) => unreachable!("setup exists when no buffer is given"),
        }
        if let StripOut::Image { bytes, develop } = out
            && aa == 1
            && self.wanted == [Layer::Total]
            && develop.opaque_rgb()
        {
            // A plain render: each pixel is its sample, developed as it is shaded, and every
            // pixel no sample covers is the background's bytes.
            let empty = develop.empty_rgb();
            // Sixteen pixels at a time: see the module docs.
            let sixteen: [u8; 48] = std::array::from_fn(|i| empty[i % 3]);
            let mut runs = bytes.chunks_exact_mut(48);
            for run in &mut runs {
                run.copy_from_slice(&sixteen);
            }
            for px in runs.into_remainder().chunks_exact_mut(3) {
                px.copy_from_slice(&empty);
            }
            let mut developed = Developed::new(bytes, develop);
            self.shade_strip(vis, StripShading { totals: &mut developed, terms: None, normals: None }, &mut st);
            st.samples_shaded += vis.listed() as u64;
            st.nan_samples += developed.nan;
            return st;
        }
        let n = vis.depth().len();
        totals.resize(n, Vec3::ZERO);
        if self.want_terms {
            terms.resize(n, Components::ZERO);
        }
        if self.want_normal {
            normals.resize(n, Vec3::ZERO);
        }
        let shading = StripShading {
            totals: &mut totals[..],
            terms: self.want_terms.then_some(&mut terms[..]),
            normals: self.want_normal.then_some(&mut normals[..]),
        };
        self.shade_strip(vis, shading, &mut st);
        for (y, depth) in vis.depth().chunks(row_samples).enumerate() {
            let rows = y * row_samples..y * row_samples + depth.len();
            let totals = &totals[rows.clone()];
            let terms = self.want_terms.then(|| &terms[rows.clone()]);
            let normals = self.want_normal.then(|| &normals[rows.clone()]);
            match out {
                StripOut::Frame { layers, coverage } => self.filter_row(depth, totals, terms, normals, layers, coverage, y * w, &mut st),
                StripOut::Image { bytes, develop } => {
                    row.resize(w, Vec3::ZERO);
                    row_coverage.resize(w, 0.0);
                    self.filter_row(depth, totals, terms, normals, &mut [&mut row[..]], row_coverage, 0, &mut st);
                    let c = develop.channels();
                    develop.develop_into(row, row_coverage, &mut bytes[y * w * c..(y + 1) * w * c]);
                }
            }
        }
        st
    }

    /// Box-filters the aa² samples of each pixel of one row (`depth` > 0 where covered, with
    /// their `totals`, `terms` and normal colours) into the kept layers (`layers[k][base + x]`,
    /// in `wanted` order) and the coverage.
    #[allow(clippy::too_many_arguments)]
    fn filter_row(
        &self,
        depth: &[f32],
        totals: &[Vec3],
        terms: Option<&[Components]>,
        normals: Option<&[Vec3]>,
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
                let covered = depth[x] > 0.0;
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
                    if depth[i] <= 0.0 {
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
                    if let Some(normals) = normals {
                        normal_sum += normals[i];
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

    /// Shades every covered sample of the strip into `totals` (and `terms`, and the normal
    /// layer's colours into `normals`, when given), one owning triangle at a time: its
    /// vertices are loaded once and its samples shaded in bundles of lanes, eight at a time
    /// on a CPU with AVX, else four.
    fn shade_strip<T: Totals + ?Sized>(&self, vis: &StripVis, out: StripShading<T>, st: &mut RenderStats) {
        // The token again (a cached check): only a token runs the AVX lanes.
        #[cfg(target_arch = "x86_64")]
        if self.lanes == 16
            && let Some(avx512) = Avx512::detect()
        {
            return avx512.run(ShadeStrip { r: self, vis, out, st });
        }
        #[cfg(target_arch = "x86_64")]
        if self.lanes == 8
            && let Some(avx) = Avx::detect()
        {
            return avx.run(ShadeStrip { r: self, vis, out, st });
        }
        self.shade_strip_lanes::<F32x4, F32x4, T>(vis, out, st)
    }

    /// [`Renderer::shade_strip`] in bundles of `W::WIDTH` lanes, a triangle's rest in full
    /// bundles of `H::WIDTH`, its last, partial bundles in four lanes (the same formula, so the
    /// same bits; a partial bundle of eight costs what a full one does).
    #[inline(always)]
    fn shade_strip_lanes<W: Lanes, H: Lanes, T: Totals + ?Sized>(&self, vis: &StripVis, out: StripShading<T>, st: &mut RenderStats) {
        let StripShading { totals, mut terms, mut normals } = out;
        let g = self.g;
        let clipped = vis.clipped();
        let mut k = EvalCounts::default();
        for t in vis.tris() {
            let owned = vis.owned(t);
            let orig = t.orig as usize;
            let bary = |e: usize| {
                let (b1, b2) = t.resolve::<f32>(clipped, owned.l1[e], owned.l2[e]);
                Vec3::new(1.0 - b1 - b2, b1, b2)
            };
            if let Some(normals) = normals.as_deref_mut() {
                for e in 0..owned.len {
                    normals[owned.index[e] as usize] = normal_colour(self.normal(orig, bary(e)));
                }
            }
            // Full bundles of W lanes, then the rest in bundles of four.
            let full = owned.len / W::WIDTH * W::WIDTH;
            let half = full + (owned.len - full) / H::WIDTH * H::WIDTH;
            match &self.lit {
                Lit::Faces { terms: lit_terms, totals: lit_totals } => {
                    // Flat: the face's lighting, no barycentrics needed.
                    for &i in &owned.index[..owned.len] {
                        totals.put_one(i, lit_totals[orig]);
                        if let Some(terms) = terms.as_deref_mut() {
                            terms[i as usize] = lit_terms[orig];
                        }
                    }
                }
                Lit::Vertices { terms: lit_terms, totals: lit_totals } => {
                    let lit = (&lit_totals[..], &lit_terms[..]);
                    self.gouraud_lanes::<W>(t, clipped, &owned, 0..full, lit, &mut *totals, terms.as_deref_mut());
                    self.gouraud_lanes::<H>(t, clipped, &owned, full..half, lit, &mut *totals, terms.as_deref_mut());
                    self.gouraud_lanes::<F32x4>(t, clipped, &owned, half..owned.len, lit, &mut *totals, terms.as_deref_mut());
                }
                Lit::Samples => {
                    let m = &self.scene.materials[g.material[orig] as usize];
                    if let Model::Classic(c) = &m.model {
                        self.phong_lanes::<W>(t, clipped, &owned, 0..full, (m, c), &mut *totals, terms.as_deref_mut(), &mut k);
                        self.phong_lanes::<H>(t, clipped, &owned, full..half, (m, c), &mut *totals, terms.as_deref_mut(), &mut k);
                        self.phong_lanes::<F32x4>(t, clipped, &owned, half..owned.len, (m, c), &mut *totals, terms.as_deref_mut(), &mut k);
                    } else {
                        // Physically based: one sample at a time.
                        for e in 0..owned.len {
                            let (p, n, v) = self.surface(orig, bary(e));
                            let c = shade_point(m, &self.lights, self.scene.ambient, p, n, v, &mut k);
                            let i = owned.index[e];
                            totals.put_one(i, c.total());
                            if let Some(terms) = terms.as_deref_mut() {
                                terms[i as usize] = c;
                            }
                        }
                    }
                }
            }
        }
        st.light_evaluations += k.lights;
        st.light_evaluations_per_sample += k.lights;
        st.diffuse_evaluations += k.diffuse;
        st.specular_evaluations += k.specular;
        totals.flush::<W>();
    }

    /// Phong with classic material `m = (material, its classic model)`: shades the samples `run` of the samples triangle `t`
    /// owns, `F::WIDTH` at a time, with the triangle's vertices in every lane (loaded once)
    /// and the perspective division done for the whole bundle ([`StripTri::resolve`]).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn phong_lanes<F: Lanes>(
        &self,
        t: &StripTri,
        clipped: &[[Vec3; 3]],
        owned: &Owned,
        run: std::ops::Range<usize>,
        m: (&Material, &Classic),
        totals: &mut (impl Totals + ?Sized),
        mut terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        if run.is_empty() {
            return;
        }
        let g = self.g;
        let orig = t.orig as usize;
        let v = g.triangles[orig].map(|i| i as usize);
        let (p, n) = (splat3(&g.positions, v), splat3(&g.normals, v));
        let face = V3::<F>::splat(g.face_normals[orig]);
        for j in run.clone().step_by(F::WIDTH) {
            let (active, b1, b2) = bundle::<F>(t, clipped, owned, j, run.end);
            let index = &owned.index[j..(j + F::WIDTH).min(run.end)];
            self.phong_bundle(m, active, b1, b2, &p, &n, face, index, &mut *totals, terms.as_deref_mut(), k);
        }
    }

    /// Phong with classic material `m`: shades one bundle of samples (perspective-correct
    /// barycentrics b1, b2 and the vertex positions `p`, normals `n` and face normal of each
    /// lane's triangle) into `totals[index[lane]]` (and `terms`) for the lanes in `index`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn phong_bundle<F: Lanes>(
        &self,
        (m, classic): (&Material, &Classic),
        active: F::Mask,
        b1: F,
        b2: F,
        p: &[V3<F>; 3],
        n: &[V3<F>; 3],
        face: V3<F>,
        index: &[u32],
        totals: &mut (impl Totals + ?Sized),
        terms: Option<&mut [Components]>,
        k: &mut EvalCounts,
    ) {
        // Barycentrics (1 − b1 − b2, b1, b2) as `VisSample::bary` makes them for one sample.
        let b0 = F::splat(1.0) - b1 - b2;
        let pos = interpolate(p, b0, b1, b2);
        // Interpolated normals are renormalized per sample (Phong 1975).
        let mut normal = interpolate(n, b0, b1, b2).normalize_or(face);
        let view = (V3::splat(self.eye) - pos).normalize_or(face);
        if self.two_sided {
            let back = face.dot(view).lt(F::splat(0.0));
            normal = V3::select(back, -normal, normal);
        }
        let incidents = self.lights.iter().map(|l| l.incident(pos));
        let c = shade_classic_lanes(m, classic, incidents, self.scene.ambient, normal, view, active, k);
        totals.put(c.total(), index);
        if let Some(terms) = terms {
            let (e, a, d, s) = (lanes_of(c.emission), lanes_of(c.ambient), lanes_of(c.diffuse), lanes_of(c.specular));
            for (lane, &i) in index.iter().enumerate() {
                terms[i as usize] = Components { emission: e[lane], ambient: a[lane], diffuse: d[lane], specular: s[lane] };
            }
        }
    }

    /// Gouraud: interpolates the lit vertex values over the samples `run` of the samples
    /// triangle `t` owns, `F::WIDTH` at a time (the vertex values in every lane, loaded once).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn gouraud_lanes<F: Lanes>(
        &self,
        t: &StripTri,
        clipped: &[[Vec3; 3]],
        owned: &Owned,
        run: std::ops::Range<usize>,
        (lit_totals, lit_terms): (&[Vec3], &[Components]),
        totals: &mut (impl Totals + ?Sized),
        mut terms: Option<&mut [Components]>,
    ) {
        if run.is_empty() {
            return;
        }
        let v = self.g.triangles[t.orig as usize].map(|i| i as usize);
        let tot = splat3(lit_totals, v);
        for j in run.clone().step_by(F::WIDTH) {
            let (_, b1, b2) = bundle::<F>(t, clipped, owned, j, run.end);
            // Each layer interpolates its vertex values, as `Vec3 * f32` and `+` do for one sample.
            let b0 = F::splat(1.0) - b1 - b2;
            let index = &owned.index[j..(j + F::WIDTH).min(run.end)];
            totals.put(interpolate(&tot, b0, b1, b2), index);
            if let Some(terms) = terms.as_deref_mut() {
                let c = [lit_terms[v[0]], lit_terms[v[1]], lit_terms[v[2]]];
                let layer = |e: [Vec3; 3]| [V3::<F>::splat(e[0]), V3::splat(e[1]), V3::splat(e[2])];
                let e = lanes_of(interpolate(&layer([c[0].emission, c[1].emission, c[2].emission]), b0, b1, b2));
                let a = lanes_of(interpolate(&layer([c[0].ambient, c[1].ambient, c[2].ambient]), b0, b1, b2));
                let d = lanes_of(interpolate(&layer([c[0].diffuse, c[1].diffuse, c[2].diffuse]), b0, b1, b2));
                let s = lanes_of(interpolate(&layer([c[0].specular, c[1].specular, c[2].specular]), b0, b1, b2));
                for (lane, &i) in index.iter().enumerate() {
                    terms[i as usize] = Components { emission: e[lane], ambient: a[lane], diffuse: d[lane], specular: s[lane] };
                }
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

/// Lanes `j..j + F::WIDTH` of the samples `t` owns: which lanes hold one (those before
/// `end`), and their perspective-correct barycentrics (b1, b2). Lanes past the end repeat
/// the first sample, so they compute valid values that nobody reads.
#[inline(always)]
fn bundle<F: Lanes>(t: &StripTri, clipped: &[[Vec3; 3]], owned: &Owned, j: usize, end: usize) -> (F::Mask, F, F) {
    let active = F::first(end - j);
    let l1 = F::select(active, F::load(&owned.l1[j..]), F::splat(owned.l1[j]));
    let l2 = F::select(active, F::load(&owned.l2[j..]), F::splat(owned.l2[j]));
    let (b1, b2) = t.resolve(clipped, l1, l2);
    (active, b1, b2)
}

/// `a[v[0]]`, `a[v[1]]`, `a[v[2]]` in every lane (a triangle's vertex values).
#[inline(always)]
fn splat3<F: Lanes>(a: &[Vec3], v: [usize; 3]) -> [V3<F>; 3] {
    [V3::splat(a[v[0]]), V3::splat(a[v[1]]), V3::splat(a[v[2]])]
}

/// a0 b0 + a1 b1 + a2 b2 per lane, as glam computes `a0 * b0 + a1 * b1 + a2 * b2` for one sample.
#[inline(always)]
fn interpolate<F: Lanes>(a: &[V3<F>; 3], b0: F, b1: F, b2: F) -> V3<F> {
    a[0].scale(b0) + a[1].scale(b1) + a[2].scale(b2)
}

/// The lanes of `v` as vectors (the first `F::WIDTH` of the array).
#[inline(always)]
fn lanes_of<F: Lanes>(v: V3<F>) -> [Vec3; MAX_WIDTH] {
    let (mut x, mut y, mut z) = ([0f32; MAX_WIDTH], [0f32; MAX_WIDTH], [0f32; MAX_WIDTH]);
    v.x.store(&mut x);
    v.y.store(&mut y);
    v.z.store(&mut z);
    std::array::from_fn(|i| Vec3::new(x[i], y[i], z[i]))
}

/// Writes lane `lane` of `v` to `out[index[lane]]` for each of the given sample indices.
#[inline(always)]
fn scatter<F: Lanes>(v: V3<F>, index: &[u32], out: &mut [Vec3]) {
    let v = lanes_of(v);
    for (lane, &i) in index.iter().enumerate() {
        out[i as usize] = v[lane];
    }
}

/// [`Renderer::shade_strip_lanes`] as a task an AVX token runs at its widths.
#[cfg(target_arch = "x86_64")]
struct ShadeStrip<'r, 'a, 's, T: Totals + ?Sized> {
    r: &'r Renderer<'a>,
    vis: &'s StripVis,
    out: StripShading<'s, T>,
    st: &'s mut RenderStats,
}

#[cfg(target_arch = "x86_64")]
impl<T: Totals + ?Sized> LaneTask for ShadeStrip<'_, '_, '_, T> {
    type Output = ();
    // Inlined into the token's `#[target_feature]` function, as the lanes are.
    #[inline(always)]
    fn run<W: Lanes, H: Lanes>(self) {
        self.r.shade_strip_lanes::<W, H, T>(self.vis, self.out, self.st)
    }
}

/// Lanes per shading bundle: the widest this CPU runs, 16 with AVX-512F, 8 with AVX, else 4
/// (a test on this thread may ask for fewer, to compare widths).
fn bundle_lanes() -> usize {
    #[cfg(test)]
    let most = tests::MAX_LANES.with(|f| f.get());
    #[cfg(not(test))]
    let most = 16;
    #[cfg(target_arch = "x86_64")]
    if most >= 16 && Avx512::detect().is_some() {
        return 16;
    }
    #[cfg(target_arch = "x86_64")]
    if most >= 8 && Avx::detect().is_some() {
        return 8;
    }
    4
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
        let c = shade_point(&scene.materials[m], lights, scene.ambient, p, n, v, &mut k);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::Override;
    use std::cell::Cell;
    use std::path::Path;

    thread_local! {
        /// Set by a test: renders started on this thread shade in at most this many lanes.
        pub(super) static MAX_LANES: Cell<usize> = const { Cell::new(16) };
    }

    /// Two objects (a classic and a physically based material), four kinds of light, a floor
    /// seen at a grazing angle and a sphere crossing the near plane's neighbourhood.
    const LESSON: &str = r#"
[lesson]
title = "lanes"
[camera]
position = [0.0, 1.2, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 50
size = [96, 72]
[[object]]
shape = "plane"
scale = 4
material = "floor"
[[object]]
shape = "uv_sphere"
segments = 40
rings = 20
scale = 0.8
translate = [0.3, 0.6, 0.0]
material = "plastic"
[[object]]
shape = "torus"
scale = 0.5
translate = [-1.0, 0.4, 0.8]
material = "metal"
[material.floor]
model = "phong"
diffuse = 0.6
specular = 0.3
shininess = 12.5
[material.plastic]
model = "blinn_phong"
diffuse = [0.7, 0.3, 0.05]
specular = 0.5
shininess = 40
[material.metal]
model = "cook_torrance"
alpha = 0.3
[[light]]
kind = "directional"
direction = [-1.0, -1.0, -0.5]
[[light]]
kind = "point"
position = [1.0, 1.5, 1.0]
attenuation = [1, 0.2, 0.1]
[[light]]
kind = "spot"
position = [0.0, 3.0, 0.0]
direction = [0.0, -1.0, 0.0]
exponent = 8
cutoff_deg = 40
[[light]]
kind = "ambient"
intensity = 0.1
[scene]
ambient = 0.05
"#;

    fn scene(overrides: &[&str]) -> Scene {
        let o: Vec<Override> = overrides.iter().map(|s| Override::parse(s).expect("override")).collect();
        let lesson = crate::lesson::parse(LESSON, Path::new("lanes.toml"), &o).expect("valid lesson");
        crate::scene::build::build(&lesson).expect("built-in meshes")
    }

    /// Every layer as bits, and the 8-bit image.
    fn render_bits(scene: &Scene, lanes: usize) -> (Vec<Vec<u32>>, Vec<u8>, RenderStats) {
        MAX_LANES.with(|f| f.set(lanes));
        let (frame, stats) = render(scene, &Layer::ALL);
        let (image, _) = render_image(scene, Layer::Total, 0.0, Tonemap::Aces);
        MAX_LANES.with(|f| f.set(16));
        let layers = frame.layers.iter().map(|(_, v)| v.iter().flat_map(|c| c.to_array().map(f32::to_bits)).collect()).collect();
        (layers, image, stats)
    }

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn eight_lanes_give_the_bits_of_four() {
        if Avx::detect().is_none() {
            eprintln!("skipped: no AVX");
            return;
        }
        let sixteen = Avx512::detect().is_some();
        if !sixteen {
            eprintln!("skipped: no AVX-512 (sixteen lanes)");
        }
        for overrides in [
            &[][..],
            &["render.interpolation=\"gouraud\""],
            &["render.interpolation=\"flat\""],
            &["render.cull=\"none\"", "render.aa=2"],
            &["camera.position=[0.0, 0.3, 0.9]", "render.cull=\"none\""],
        ] {
            let s = scene(overrides);
            let (four, eight) = (render_bits(&s, 4), render_bits(&s, 8));
            assert!(four.2.samples_shaded > 1000, "{overrides:?}");
            assert_eq!(four, eight, "{overrides:?}");
            if sixteen {
                assert_eq!(four, render_bits(&s, 16), "sixteen lanes: {overrides:?}");
            }
        }
    }

    #[test]
    fn a_reused_visibility_buffer_gives_the_bits_of_a_render() {
        let s = scene(&["render.aa=2"]);
        let vis = rasterize(&s);
        let (fresh, _) = render(&s, &Layer::ALL);
        let (reused, stats) = render_with(&s, &Layer::ALL, Some(&vis));
        assert!(stats.samples_shaded > 1000);
        for ((_, a), (_, b)) in fresh.layers.iter().zip(&reused.layers) {
            assert!(a.iter().zip(b).all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)));
        }
        assert_eq!(fresh.coverage, reused.coverage);
    }
}
