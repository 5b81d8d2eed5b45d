//! One strip: its visibility (rasterized now or read from a kept buffer), its samples
//! shaded triangle by triangle, and the resolve of each pixel row into the kept layers or
//! straight into 8-bit sRGB.

use super::bundle::scatter;
use super::developed::{Developed, zeroed};
use super::dispatch::{Lit, Renderer, STRIP_PIXELS};
use super::gather::Gathered;
use super::{RenderStats, count_shadows};
use crate::geometry::sampling::hash3;
use crate::raster::{StripTri, StripVis};
use crate::render::develop::{DevelopParams, srgb_decode};
use crate::render::frame::Layer;
use crate::render::plan::Pass;
use crate::render::texturing;
use crate::scene::Model;
use crate::scene::build::Geometry;
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
#[cfg(target_arch = "x86_64")]
use crate::simd::lanes::LaneTask;
use crate::simd::lanes::{F32x4, Lanes, V3};
use crate::simd::pair::Pair;
use crate::transport::medium::{FOG_SAMPLES, FOG_STEPS, FogPass};
use crate::transport::visibility as shadows;
use crate::transport::{At, shade_point};
use glam::Vec3;
use std::mem::MaybeUninit;

/// A worker's buffers, reused across strips and renders.
#[derive(Default)]
pub(super) struct Scratch {
    /// The strip's visibility.
    pub(super) vis: StripVis,
    /// Per sample of the strip: the shaded total I_tot.
    pub(super) totals: Vec<Vec3>,
    /// Per sample of the strip: the terms, when a term layer is kept.
    pub(super) terms: Vec<Components>,
    /// Per sample of the strip: the normal layer's colour, when it is kept.
    pub(super) normals: Vec<Vec3>,
    /// One pixel row of the developed layer (8-bit output only).
    pub(super) row: Vec<Vec3>,
    /// Coverage of `row`.
    pub(super) row_coverage: Vec<f32>,
    /// A plain render's strip as 4-byte pixels, when they are encoded sixteen at a time.
    pub(super) pixels: Vec<u32>,
}

/// Where a strip's shading goes, per sample of the strip.
pub(super) struct StripShading<'a, T: Totals + ?Sized> {
    /// The shaded total I_tot.
    pub(super) totals: &'a mut T,
    /// The terms, when a term layer is kept.
    pub(super) terms: Option<&'a mut [Components]>,
    /// The normal layer's colour, when it is kept.
    pub(super) normals: Option<&'a mut [Vec3]>,
}

/// Where the shaded totals I_tot of a strip's samples go.
pub(super) trait Totals {
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

/// The fog's jitter seed (mixed with the sample's grid position).
const FOG_SEED: u32 = 0xf06_5eed;

/// Where a strip's pixels go.
pub(super) enum StripOut<'a> {
    /// The strip's rows of each kept layer (in `wanted` order) and of the coverage.
    Frame { layers: Vec<&'a mut [Vec3]>, coverage: &'a mut [f32] },
    /// The strip's rows of 8-bit pixels, developed from the one kept layer; they arrive
    /// unwritten, and every path of [`Renderer::strip`] writes every byte.
    Image { bytes: &'a mut [MaybeUninit<u8>], develop: &'a DevelopParams },
}

impl Renderer<'_> {
    /// Rasterizes (or reads) strip `s`, shades its covered samples triangle by triangle, then
    /// filters and writes its pixels to `out` pixel row by pixel row.
    pub(super) fn strip(&self, s: usize, scratch: &mut Scratch, out: &mut StripOut) -> RenderStats {
        // Shadow work is counted on this thread: the strip's share is the difference.
        let before = shadows::thread_counts();
        let mut st = self.strip_inner(s, scratch, out);
        let after = shadows::thread_counts();
        count_shadows(&mut st.counters, after.since(before));
        st
    }

    fn strip_inner(&self, s: usize, scratch: &mut Scratch, out: &mut StripOut) -> RenderStats {
        let Scratch { vis, totals, terms, normals, row, row_coverage, pixels } = scratch;
        let mut st = RenderStats::default();
        let (w, aa) = (self.w as usize, self.aa as usize);
        let row_samples = aa * aa * w;
        // This strip's samples: rasterized now, or a slice of the reused buffer.
        match (&self.setup, self.vis) {
            (Some(setup), _) => {
                st.raster = setup.rasterize_strip(s, vis);
                // The course's scanline interpolation: one pass over the strip's triangles,
                // the shading loops below unchanged.
                if self.screen_space {
                    vis.interpolate_in_screen_space();
                }
            }
            (None, Some(v)) => {
                let strip_samples = STRIP_PIXELS as usize * row_samples;
                let samples = &v.samples[s * strip_samples..((s + 1) * strip_samples).min(v.samples.len())];
                vis.load(samples, (s * STRIP_PIXELS as usize * aa) as u32, v.width);
                // The raster pass's strip half: this strip's visibility, read from the buffer.
                st.passes |= Pass::Raster.bit();
            }
            (None, None) => unreachable!("setup exists when no buffer is given"),
        }
        if let StripOut::Image { bytes, develop } = out
            && aa == 1
            && self.wanted == [Layer::Total]
            && develop.opaque_rgb()
            && !self.runs(Pass::Fog)
            && self.sky.is_none()
        {
            // A plain render: each pixel is its sample, developed as it is shaded; every pixel
            // no sample covers keeps the background's bytes (`Developed::strip`).
            let nan = Developed::strip(bytes, develop, pixels, |d| {
                self.shade_strip(vis, StripShading { totals: d, terms: None, normals: None }, &mut st)
            });
            st.nan_samples += nan;
            st.samples_shaded += vis.listed() as u64;
            // The resolve of a plain render: each pixel developed as its sample is shaded.
            st.passes |= Pass::Resolve.bit();
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
        if self.runs(Pass::Fog) {
            self.fog_strip(s, vis, totals, &mut st);
        }
        st.passes |= Pass::Resolve.bit();
        // An image's rows are developed over zeroed bytes: each row then writes all of its own.
        let (mut frame, mut image) = match out {
            StripOut::Frame { layers, coverage } => (Some((layers, coverage)), None),
            StripOut::Image { bytes, develop } => (None, Some((zeroed(bytes), *develop))),
        };
        for (y, depth) in vis.depth().chunks(row_samples).enumerate() {
            let py = (s * STRIP_PIXELS as usize + y) as u32;
            let rows = y * row_samples..y * row_samples + depth.len();
            let totals = &totals[rows.clone()];
            let terms = self.want_terms.then(|| &terms[rows.clone()]);
            let normals = self.want_normal.then(|| &normals[rows.clone()]);
            if let Some((layers, coverage)) = &mut frame {
                self.filter_row(depth, totals, terms, normals, layers, coverage, (y * w, py), &mut st);
            }
            if let Some((bytes, develop)) = &mut image {
                row.resize(w, Vec3::ZERO);
                row_coverage.resize(w, 0.0);
                self.filter_row(depth, totals, terms, normals, &mut [&mut row[..]], row_coverage, (0, py), &mut st);
                let c = develop.channels();
                develop.develop_into(row, row_coverage, &mut bytes[y * w * c..(y + 1) * w * c]);
            }
        }
        st
    }

    /// Box-filters the aa² samples of each pixel of row `py` (`depth` > 0 where covered, with
    /// their `totals`, `terms` and normal colours) into the kept layers (`layers[k][base + x]`,
    /// in `wanted` order) and the coverage. With an environment drawn as the background, an
    /// uncovered sample takes the environment's radiance along its camera ray (into `total`
    /// only) and counts as covered.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn filter_row(
        &self,
        depth: &[f32],
        totals: &[Vec3],
        terms: Option<&[Components]>,
        normals: Option<&[Vec3]>,
        layers: &mut [&mut [Vec3]],
        coverage: &mut [f32],
        (base, py): (usize, u32),
        st: &mut RenderStats,
    ) {
        let (w, aa) = (self.w as usize, self.aa as usize);
        if aa == 1 && self.wanted == [Layer::Total] && self.sky.is_none() {
            // A plain render (one sample per pixel, only I_tot kept): each pixel is its sample,
            // as the general loop below computes it (0 + t = t, × 1), without its bookkeeping.
            let (out, coverage) = (&mut layers[0][base..base + w], &mut coverage[base..base + w]);
            let (mut shaded, mut nan) = (0, 0);
            for x in 0..w {
                // With fog every sample is covered: the fog fills the background.
                let covered = depth[x] > 0.0 || self.runs(Pass::Fog);
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
            let mut sky = 0u32;
            for sy in 0..aa {
                let first = sy * sample_width + x * aa;
                for i in first..first + aa {
                    if depth[i] <= 0.0 && !self.runs(Pass::Fog) {
                        if let Some((env, rays)) = &self.sky {
                            let d = rays.ray((x as u32, py), ((i - first) as u32, sy as u32), aa as u32).dir.normalize().as_vec3();
                            total += env.radiance(d);
                            sky += 1;
                        }
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
            coverage[i] = (covered + sky) as f32 * inv;
        }
    }

    /// Shades every covered sample of the strip into `totals` (and `terms`, and the normal
    /// layer's colours into `normals`, when given), one owning triangle at a time: its
    /// vertices are loaded once and its samples shaded in bundles of lanes, sixteen at a time
    /// on a CPU with AVX-512F or AVX (two registers of eight), else eight (two SSE2 registers).
    pub(super) fn shade_strip<T: Totals + ?Sized>(&self, vis: &StripVis, out: StripShading<T>, st: &mut RenderStats) {
        // The token again (a cached check): only a token runs the AVX lanes.
        #[cfg(target_arch = "x86_64")]
        if self.lanes == 16
            && let Some(avx512) = crate::simd::Cpu::get().avx512()
        {
            return avx512.run(ShadeStrip { r: self, vis, out, st });
        }
        #[cfg(target_arch = "x86_64")]
        if self.lanes == 8
            && let Some(avx) = crate::simd::Cpu::get().avx()
        {
            return avx.run(ShadeStrip { r: self, vis, out, st });
        }
        // Without AVX, a pair of SSE2 registers: eight lanes in two chains (sphere 10.04 →
        // 9.17 ms with the AVX path switched off, docs/performance.md).
        self.shade_strip_lanes::<Pair<F32x4>, F32x4, T>(vis, out, st)
    }

    /// [`Renderer::shade_strip`] in bundles of `W::WIDTH` lanes. A Phong triangle's rest
    /// waits with other triangles' rests until a full bundle of `W` gathers (`gather.rs`); a
    /// Gouraud triangle's rest wider than `H::WIDTH` goes in one partial bundle of `W`, a
    /// narrower one in bundles of `H`, its last samples in one bundle of four when at most
    /// four are left, else in one partial bundle of `H` (the same formula, so the same bits;
    /// a partial bundle costs what a full one does).
    #[inline(always)]
    pub(super) fn shade_strip_lanes<W: Lanes, H: Lanes, T: Totals + ?Sized>(
        &self,
        vis: &StripVis,
        out: StripShading<T>,
        st: &mut RenderStats,
    ) {
        let StripShading { totals, mut terms, mut normals } = out;
        if matches!(self.lit, Lit::Samples) {
            st.passes |= Pass::ShadeSamples.bit();
        }
        let g = self.g;
        let clipped = vis.clipped();
        let mut k = EvalCounts::default();
        // Phong triangles' rests gathered into full bundles (`gather.rs`).
        let mut queue = Gathered::new(!self.lighting.is_plain());
        let tris = vis.tris();
        for (ti, t) in tris.iter().enumerate() {
            prefetch_ahead(g, tris, ti);
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
            // Full bundles of W lanes, then (Gouraud, or Phong with gathering off) of H; a last
            // rest of more than four samples in one partial bundle of H (it costs what one of
            // four does), else in one of four.
            let full = owned.len / W::WIDTH * W::WIDTH;
            let rest = owned.len - full;
            let half = if rest % H::WIDTH > F32x4::WIDTH { owned.len } else { full + rest / H::WIDTH * H::WIDTH };
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
                    // A rest wider than H in one partial bundle of W (it costs what one of H does).
                    let (full, half) = if rest > H::WIDTH { (owned.len, owned.len) } else { (full, half) };
                    self.gouraud_lanes::<W>(t, clipped, &owned, 0..full, lit, &mut *totals, terms.as_deref_mut());
                    self.gouraud_lanes::<H>(t, clipped, &owned, full..half, lit, &mut *totals, terms.as_deref_mut());
                    self.gouraud_lanes::<F32x4>(t, clipped, &owned, half..owned.len, lit, &mut *totals, terms.as_deref_mut());
                }
                Lit::Nothing => {}
                Lit::Samples => {
                    let mi = g.material[orig] as usize;
                    let m = &self.scene.materials[mi];
                    if let Some(tex) = self.scene.textures.get(mi).filter(|t| t.any()) {
                        // Textured: one sample at a time, the material's values read at its uv.
                        let rays = self.scene.spec.camera.rays();
                        let filter = self.scene.spec.settings.texture_filter;
                        let frame = tex.normal.is_some().then(|| texturing::triangle_tangent(g, orig));
                        for e in 0..owned.len {
                            let b = bary(e);
                            let (p, mut n, v) = self.surface(orig, b);
                            let i = owned.index[e];
                            let uv = texturing::uv_at(g, orig, b);
                            let duv = texturing::uv_footprint(g, orig, &rays, (i % vis.width, vis.y0 + i / vis.width), self.aa);
                            let textured = tex.apply(m, tex.sample(uv, duv, filter));
                            if let (Some(map), Some(frame)) = (&tex.normal, frame) {
                                n = texturing::bend_normal(n, frame, map.sample(uv, duv, filter));
                            }
                            let at = At {
                                tri: orig as u32,
                                object: g.object_of_triangle(orig),
                                ng: g.face_normals[orig].into(),
                                ..At::point(p, n)
                            };
                            let c = shade_point(&textured, &self.lighting, self.scene.spec.ambient, at, v, &mut k);
                            totals.put_one(i, c.total());
                            if let Some(terms) = terms.as_deref_mut() {
                                terms[i as usize] = c;
                            }
                        }
                    } else if let Model::Classic(c) = &m.model {
                        self.phong_lanes::<W>(t, clipped, &owned, 0..full, (m, c), &mut *totals, terms.as_deref_mut(), &mut k);
                        if self.gather {
                            // The rest waits for other triangles' rests to fill a bundle.
                            let rest = full..owned.len;
                            self.phong_gather::<W, H>(t, clipped, &owned, rest, mi, &mut queue, &mut *totals, terms.as_deref_mut(), &mut k);
                        } else {
                            self.phong_lanes::<H>(t, clipped, &owned, full..half, (m, c), &mut *totals, terms.as_deref_mut(), &mut k);
                            self.phong_lanes::<F32x4>(
                                t,
                                clipped,
                                &owned,
                                half..owned.len,
                                (m, c),
                                &mut *totals,
                                terms.as_deref_mut(),
                                &mut k,
                            );
                        }
                    } else {
                        // Physically based: one sample at a time.
                        for e in 0..owned.len {
                            let (p, n, v) = self.surface(orig, bary(e));
                            let at = At {
                                tri: orig as u32,
                                object: g.object_of_triangle(orig),
                                ng: g.face_normals[orig].into(),
                                ..At::point(p, n)
                            };
                            let c = shade_point(m, &self.lighting, self.scene.spec.ambient, at, v, &mut k);
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
        self.phong_flush::<W>(&mut queue, &mut *totals, terms, &mut k);
        st.light_evaluations += k.lights;
        st.light_evaluations_per_sample += k.lights;
        st.diffuse_evaluations += k.diffuse;
        st.specular_evaluations += k.specular;
        totals.flush::<W>();
    }

    /// The fog pass of strip `s`: every sample's total, covered or not, through
    /// [`FogPass::apply`] with its eye ray and its distance from the depth buffer (the
    /// reversed depth z/w = near/z_view, and the camera ray's unit forward component makes
    /// z_view its parameter).
    fn fog_strip(&self, s: usize, vis: &StripVis, totals: &mut [Vec3], st: &mut RenderStats) {
        let Some(pass) = FogPass::new(self.scene, &self.lighting.lights, &self.lighting.shadows) else { return };
        let cam = &self.scene.spec.camera;
        let rays = cam.rays();
        let (aa, width) = (self.aa, self.w * self.aa);
        let near = cam.near;
        let y0 = s as u32 * STRIP_PIXELS * aa;
        let depth = vis.depth();
        for (i, (total, &d)) in totals.iter_mut().zip(depth).enumerate() {
            let (sx, sy) = (i as u32 % width, y0 + i as u32 / width);
            let ray = rays.ray((sx / aa, sy / aa), (sx % aa, sy % aa), aa);
            let dir = ray.dir.as_vec3();
            let len = dir.length();
            let hit = (d > 0.0).then(|| near / d * len);
            // A ray that hits nothing sees the skybox (or the camera background) beyond the fog.
            let surface = match &self.sky {
                _ if d > 0.0 => *total,
                Some((env, _)) => env.radiance(dir / len),
                None => pass.background,
            };
            // The sample's streams, from its position on the sample grid (DESIGN.md, Determinism).
            *total = pass.apply(cam.position, dir / len, hit, surface, hash3(sx, sy, FOG_SEED));
        }
        st.counters.add(FOG_SAMPLES, depth.len() as u64);
        st.counters.add(FOG_STEPS, depth.len() as u64 * pass.steps() as u64);
        st.passes |= Pass::Fog.bit();
    }

    /// Position, shading normal and view vector of a sample (Phong interpolation, scalar).
    #[inline]
    pub(super) fn surface(&self, t: usize, b: Vec3) -> (Vec3, Vec3, Vec3) {
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
    pub(super) fn normal(&self, t: usize, b: Vec3) -> Vec3 {
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

/// Triangles ahead in a strip whose data [`prefetch_ahead`] fetches: their index entry this
/// far ahead, and their vertices half as far (by then their index entry has arrived).
const PREFETCH_AHEAD: usize = 8;

/// Starts fetching what the strip's shading of later triangles reads: a strip's triangles
/// lie scattered over the mesh (its order crosses every strip), so their vertex indices,
/// vertices and face data are cache misses the hardware prefetcher cannot foresee.
#[inline(always)]
fn prefetch_ahead(g: &Geometry, tris: &[StripTri], ti: usize) {
    use crate::simd::prefetch;
    if let Some(t) = tris.get(ti + PREFETCH_AHEAD) {
        prefetch(g.triangles.as_ptr().wrapping_add(t.orig as usize));
        prefetch(g.face_normals.as_ptr().wrapping_add(t.orig as usize));
    }
    let near = tris.get(ti + PREFETCH_AHEAD / 2).and_then(|t| g.triangles.get(t.orig as usize));
    for &v in near.into_iter().flatten() {
        prefetch(g.positions.as_ptr().wrapping_add(v as usize));
        prefetch(g.normals.as_ptr().wrapping_add(v as usize));
    }
}
