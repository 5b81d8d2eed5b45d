//! Linear radiance → display: exposure, tone map, sRGB transfer, 8-bit quantization.
//!
//! One develop loop ([`DevelopParams`]) serves whole frames ([`develop`], [`develop_rgba`])
//! and rows rendered straight to 8 bits (`render::render_image`), so both give the same
//! bytes. Measured on the 1024² `sphere` frame, one thread, inside `render_image` (min of 8):
//! 8.0 ms with the tone map matched per channel and a `while` loop over thresholds, 5.9 ms
//! with the tone map hoisted, channels in lanes, the branch-free encode and empty pixels
//! developed once (callgrind: 89M → 35M instructions a frame).
//!
//! Opaque RGB goes four pixels at a time: their twelve channels in output order fill three
//! registers, so over, exposure, tone map, the encode's clamp and its bucket are lane
//! operations, and only the two table loads and the step stay per channel (`bt`, the
//! threshold above each bucket's code, makes those loads independent). A plain render
//! (one sample a pixel, `total` only) developed straight from the shaded samples, four
//! coverage and finiteness tests at once (`develop_samples`, since replaced by
//! [`DevelopParams::develop_covered`]: the covered samples in the shading bundles' lanes,
//! measured in docs/performance.md). Measured (callgrind, `shadelab --threads 1 bench --workload sphere --frames 1 --warmup
//! 0`, three frames of which two develop): 0.717e9 → 0.610e9 instructions for the run
//! (sphere-gouraud 0.610e9 → 0.503e9, dense 2.789e9 → 2.684e9); the develop of the plain
//! render went from about 100 instructions a pixel (filter and develop, one pixel at a time)
//! to 57. Array `map`s and closures left out of line in this loop cost 0.08e9 of that until
//! written out. One thread, alternating, best of 8: image 16.8 → 14.8 ms.
//!
//! On a CPU with AVX2 a plain render's batch of covered pixels is encoded eight at a time
//! without table loads (`encode_avx2`: the same bytes), after the batch's lane steps
//! ([`DevelopParams::clamp_covered`]); with AVX-512BW sixteen at a time into a strip of
//! 4-byte pixels, packed to 3-byte pixels when the strip is shaded (`encode_avx512`, the
//! same bytes); measured in docs/performance.md.
//!
//! **Tone maps and saturated colours.** `clamp`, `reinhard` and `aces` are curves applied to
//! each channel on its own; AgX ([`tonemap_pixel`]) mixes the channels before and after its
//! curve. A curve per channel shifts hue wherever a colour's strongest channels reach its
//! shoulder before the weakest: they are squeezed together (or cut off, by `clamp`) while the
//! weakest is not, so the colour slides towards the secondary the two strongest make, then to
//! white. Measured on gold (F0 ≈ (0.97, 0.80, 0.32), OKLCh hue 95°) in lesson 10's sphere
//! (issue 42): `clamp` keeps 95° until it clips (2.54, 2.11, 0.85) to (255, 255, 237), 107°;
//! `aces` gives that pixel (248, 246, 227), 101°, and puts 14 % of the sphere past 100°, towards
//! yellow-green; `agx` gives (230, 225, 198), 98°, and 0.2 % past 100°, at a lower chroma
//! (0.053 against `aces`' 0.074: AgX desaturates on purpose, as film does). In the toe `aces`
//! darkens the weakest channel most, so dark colours come out more saturated. The unit test
//! `agx_keeps_gold_s_hue_where_per_channel_curves_turn_it_yellow` holds the difference.

use super::agx::agx;
use super::frame::{Frame, Layer};
use super::srgb::{BUCKETS, srgb_table};
pub use super::srgb::{encode_u8, srgb_decode, srgb_encode};
use crate::lesson::settings::Tonemap;
use crate::simd::lanes::{F32x4, Lanes, MAX_WIDTH, V3};
use glam::Vec3;
use rayon::prelude::*;

/// Applies the tone map to one linear grey value (after exposure): the curve on the grey axis.
/// For the operators that work channel by channel this is the curve of every channel; AgX
/// mixes the channels, so a colour must go through [`tonemap_rgb`].
#[inline]
pub fn tonemap(x: f32, op: Tonemap) -> f32 {
    tonemap_lanes(x, op)
}

/// Applies the tone map to one linear pixel (after exposure). Every value in [0, 1]; a
/// negative or NaN channel counts as 0, +∞ as the brightest.
#[inline]
pub fn tonemap_rgb(c: Vec3, op: Tonemap) -> Vec3 {
    tonemap_pixel::<f32>(c.into(), op).into()
}

/// [`tonemap_rgb`] for lanes of pixels: the one formula of every develop path.
#[inline(always)]
pub fn tonemap_pixel<F: Lanes>(c: V3<F>, op: Tonemap) -> V3<F> {
    match op {
        Tonemap::Agx => agx(c),
        _ => V3 { x: tonemap_lanes(c.x, op), y: tonemap_lanes(c.y, op), z: tonemap_lanes(c.z, op) },
    }
}

/// [`tonemap`] for lanes: the one formula of a channel-by-channel curve (max, min and clamp as
/// selects with `f32`'s NaN behaviour: a NaN input becomes 0); AgX's grey axis.
#[inline(always)]
pub fn tonemap_lanes<F: Lanes>(x: F, op: Tonemap) -> F {
    let (zero, one) = (F::splat(0.0), F::splat(1.0));
    let x = F::select(x.gt(zero), x, zero);
    match op {
        Tonemap::Clamp => F::select(x.lt(one), x, one),
        // Reinhard et al. 2002, eq. 3.
        Tonemap::Reinhard => x / (one + x),
        // Narkowicz 2015, "ACES Filmic Tone Mapping Curve".
        Tonemap::Aces => {
            let c = (x * (F::splat(2.51) * x + F::splat(0.03))) / (x * (F::splat(2.43) * x + F::splat(0.59)) + F::splat(0.14));
            F::select(c.lt(zero), zero, F::select(c.gt(one), one, c))
        }
        Tonemap::Agx => agx(V3 { x, y: x, z: x }).x,
    }
}

/// A pixel's channels in the first three lanes of an `F32x4` through the tone map (the fourth
/// lane unused): [`tonemap_lanes`] on the register, or AgX on the pixel.
#[inline(always)]
fn tone_rgb_lanes(p: F32x4, op: Tonemap) -> F32x4 {
    match op {
        Tonemap::Agx => {
            let a = p.to_array();
            let v = agx::<f32>(V3 { x: a[0], y: a[1], z: a[2] });
            F32x4::from_array([v.x, v.y, v.z, 0.0])
        }
        _ => tonemap_lanes(p, op),
    }
}

/// Develops one layer of a frame to interleaved 8-bit sRGB: composite over the
/// background, × 2^exposure, tone map, encode. `None` when the layer was not kept.
pub fn develop(frame: &Frame, layer: Layer, exposure: f32, op: Tonemap) -> Option<Vec<u8>> {
    develop_pixels(frame, layer, exposure, op, 3, false)
}

/// Develops one layer to interleaved 8-bit sRGB with alpha. Opaque: composited over the
/// background, alpha 255. Transparent: the surface colour (the layer divided by coverage)
/// with alpha = coverage, so antialiased edges blend onto any slide.
pub fn develop_rgba(frame: &Frame, layer: Layer, exposure: f32, op: Tonemap, transparent: bool) -> Option<Vec<u8>> {
    develop_pixels(frame, layer, exposure, op, 4, transparent)
}

/// Everything developing one pixel needs, fixed per image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DevelopParams {
    /// 2^exposure (1 for the normal layer).
    scale: f32,
    /// Tone map (clamp for the normal layer).
    op: Tonemap,
    /// 3 (RGB) or 4 (RGBA).
    channels: usize,
    /// RGBA with alpha = coverage instead of compositing over the background.
    transparent: bool,
    /// Linear background under partly covered pixels.
    background: Vec3,
    /// Present when this CPU runs AVX2: covered pixels are then encoded eight at a time.
    #[cfg(target_arch = "x86_64")]
    avx2: Option<crate::simd::avx2::Avx2>,
    /// Present when this CPU runs AVX-512BW: covered pixels are then encoded sixteen at a
    /// time into 4-byte pixels ([`DevelopParams::encode_covered_wide`]).
    #[cfg(target_arch = "x86_64")]
    avx512bw: Option<crate::simd::avx512::Avx512Bw>,
}

#[cfg(test)]
thread_local! {
    /// Set by a test: develop parameters made on this thread encode in at most this many
    /// lanes (16, 8, or 1: the table).
    pub(crate) static MAX_ENCODE_LANES: std::cell::Cell<usize> = const { std::cell::Cell::new(16) };
}

impl DevelopParams {
    /// The parameters for `layer`: normals are colours already, so no exposure and no tone curve.
    pub fn new(layer: Layer, exposure: f32, op: Tonemap, channels: usize, transparent: bool, background: Vec3) -> DevelopParams {
        let (scale, op) = if layer == Layer::Normal { (1.0, Tonemap::Clamp) } else { (exposure.exp2(), op) };
        #[cfg(test)]
        let most = MAX_ENCODE_LANES.with(|f| f.get());
        #[cfg(not(test))]
        let most = 16;
        #[cfg(not(target_arch = "x86_64"))]
        let _ = most;
        DevelopParams {
            scale,
            op,
            channels,
            transparent,
            background,
            #[cfg(target_arch = "x86_64")]
            avx2: crate::simd::Cpu::get().avx2().filter(|_| most >= 8),
            #[cfg(target_arch = "x86_64")]
            avx512bw: crate::simd::Cpu::get().avx512bw().filter(|_| most >= 16),
        }
    }

    /// Bytes per pixel.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// Develops a run of pixels (layer values and coverage) into `out` (`channels` bytes each):
    /// the one develop loop, used for whole frames and for strips rendered straight to 8 bits.
    pub fn develop_into(&self, pixels: &[Vec3], coverage: &[f32], out: &mut [u8]) {
        // One instance per tone map, so the curve is inlined without a match per channel.
        match self.op {
            // The encode clamps to [0, 1] (NaN to 0) exactly as the clamp tone map does, so the
            // clamp is left to it (same codes: tested in clamp_is_the_encode_clamp).
            Tonemap::Clamp => self.develop_into_with(pixels, coverage, out, |x| x),
            Tonemap::Reinhard => self.develop_into_with(pixels, coverage, out, |x| tonemap_lanes(x, Tonemap::Reinhard)),
            Tonemap::Aces => self.develop_into_with(pixels, coverage, out, |x| tonemap_lanes(x, Tonemap::Aces)),
            // AgX mixes a pixel's channels, so the four-pixel registers (channels in output
            // order) do not apply: one pixel at a time, its channels in one register.
            Tonemap::Agx => {
                let tone = |p: F32x4| tone_rgb_lanes(p, Tonemap::Agx);
                for ((&p, &a), o) in pixels.iter().zip(coverage).zip(out.chunks_exact_mut(self.channels)) {
                    self.develop_one(p, a, &tone, o);
                }
            }
        }
    }

    /// [`DevelopParams::develop_into`] with the tone curve `tone`.
    #[inline(always)]
    fn develop_into_with(&self, pixels: &[Vec3], coverage: &[f32], out: &mut [u8], tone: impl Fn(F32x4) -> F32x4) {
        let d = self;
        {
            let mut done = 0;
            if d.opaque_rgb() {
                let ctx = d.four(&tone);
                for ((p, a), o) in pixels.chunks_exact(4).zip(coverage.chunks_exact(4)).zip(out.chunks_exact_mut(12)) {
                    if a == [0.0; 4] && p.iter().all(|p| *p == Vec3::ZERO) {
                        o.copy_from_slice(&ctx.empty);
                        continue;
                    }
                    // 1 − a of each channel's pixel.
                    let t = (F32x4::splat(1.0) - F32x4::from_array([a[0], a[1], a[2], a[3]])).to_array();
                    let rest = [
                        F32x4::from_array([t[0], t[0], t[0], t[1]]),
                        F32x4::from_array([t[1], t[1], t[2], t[2]]),
                        F32x4::from_array([t[2], t[3], t[3], t[3]]),
                    ];
                    o.copy_from_slice(&d.develop_four(&ctx, channels_of(p), rest, &tone));
                }
                done = pixels.len() / 4 * 4;
            }
            for ((&p, &a), o) in pixels[done..].iter().zip(&coverage[done..]).zip(out[done * d.channels..].chunks_exact_mut(d.channels)) {
                d.develop_one(p, a, &tone, o);
            }
        }
    }

    /// The bytes of an opaque RGB pixel no sample covers: the background developed, as every
    /// develop loop here gives it (0 + background × 1, exposure, tone map, encode).
    pub fn empty_rgb(&self) -> [u8; 3] {
        let mut o = [0u8; 3];
        match self.op {
            Tonemap::Clamp => self.develop_one(Vec3::ZERO, 0.0, &|x| x, &mut o),
            op => self.develop_one(Vec3::ZERO, 0.0, &|x| tone_rgb_lanes(x, op), &mut o),
        }
        o
    }

    /// Develops covered one-sample pixels of an opaque RGB image from their shaded totals,
    /// in lanes: lane l of `v` is the total of pixel `index[l]` (for the lanes in `index`),
    /// whose three bytes go to `out[3 index[l]..]`. The bytes are those
    /// [`DevelopParams::develop_into`] gives the pixel of a covered sample (its total if
    /// finite, else 0, with coverage 1: over the background with weight 1 − 1 = 0; exposure,
    /// tone map, encode): the same per-channel operations, so the same bits at any width
    /// (tested: `covered_samples_develop_as_their_filtered_row`). Returns the lanes whose
    /// total is not finite. With AVX2, a batch of bundles goes through
    /// [`DevelopParams::clamp_covered`] and then [`DevelopParams::encode_covered`] instead;
    /// with AVX-512BW through [`DevelopParams::encode_covered_wide`] into 4-byte pixels, then
    /// [`DevelopParams::pack_rgb`].
    #[inline(always)]
    pub fn develop_covered<F: Lanes>(&self, v: V3<F>, index: &[u32], out: &mut [u8]) -> u64 {
        let finite = v.is_finite();
        let nan = F::count(F::first(index.len()) & !finite);
        let x = self.covered_pixel(v, finite);
        let channel = |x: F| {
            let (mut a, mut bucket) = ([0f32; MAX_WIDTH], [0i32; MAX_WIDTH]);
            x.store(&mut a);
            (x * F::splat(BUCKETS as f32)).trunc_i32(&mut bucket);
            (a, bucket)
        };
        let (r, g, b) = (channel(x.x), channel(x.y), channel(x.z));
        let table = srgb_table();
        for (l, &i) in index.iter().enumerate() {
            let o = &mut out[3 * i as usize..3 * i as usize + 3];
            let code = |c: &([f32; MAX_WIDTH], [i32; MAX_WIDTH])| table.encode_bucket(c.0[l], c.1[l]);
            (o[0], o[1], o[2]) = (code(&r), code(&g), code(&b));
        }
        nan
    }

    /// The AVX2 token when this CPU encodes eight pixels at a time
    /// ([`DevelopParams::encode_covered`]).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn avx2(&self) -> Option<crate::simd::avx2::Avx2> {
        self.avx2
    }

    /// The first step of [`DevelopParams::develop_covered`] on a batch: `F::WIDTH` lanes of the
    /// channels `c` (totals in, values in [0, 1] out, in place), of which the first `lanes`
    /// are pixels. Returns how many of those totals were not finite.
    #[inline(always)]
    pub fn clamp_covered<F: Lanes>(&self, c: [&mut [f32]; 3], lanes: usize) -> u64 {
        let v = V3 { x: F::load(c[0]), y: F::load(c[1]), z: F::load(c[2]) };
        let finite = v.is_finite();
        let x = self.covered_pixel(v, finite);
        let [r, g, b] = c;
        x.x.store(r);
        x.y.store(g);
        x.z.store(b);
        F::count(F::first(lanes) & !finite)
    }

    /// The last step of [`DevelopParams::develop_covered`] on a batch: the 8-bit sRGB codes of
    /// pixel `index[l]`'s channels `c[k][l]` (in [0, 1], from
    /// [`DevelopParams::clamp_covered`]) to `out[3 index[l]..]`, eight pixels at a time in
    /// AVX2 registers (the table's bytes: see `encode_avx2`).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn encode_covered(&self, t: crate::simd::avx2::Avx2, c: [&[f32]; 3], index: &[u32], out: &mut [u8]) {
        super::encode_avx2::encode_rgb(t, c, index, out);
    }

    /// The AVX-512BW token when this CPU encodes sixteen pixels at a time
    /// ([`DevelopParams::encode_covered_wide`]).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn avx512bw(&self) -> Option<crate::simd::avx512::Avx512Bw> {
        self.avx512bw
    }

    /// [`DevelopParams::encode_covered`] sixteen pixels at a time, into 4-byte pixels
    /// `px[index[l]]` = R | G << 8 | B << 16 (the table's bytes: see `encode_avx512`); the
    /// strip's pixels then go to 3-byte RGB with [`DevelopParams::pack_rgb`].
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn encode_covered_wide(&self, t: crate::simd::avx512::Avx512Bw, c: [&[f32]; 3], index: &[u32], px: &mut [u32]) {
        super::encode_avx512::encode_rgb(t, c, index, px);
    }

    /// The 4-byte pixels of [`DevelopParams::encode_covered_wide`] as 3-byte RGB (`out` is
    /// three bytes a pixel; every byte is written).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub fn pack_rgb(&self, t: crate::simd::avx512::Avx512Bw, px: &[u32], out: &mut [std::mem::MaybeUninit<u8>]) {
        super::encode_avx512::pack_rgb(t, px, out);
    }

    /// [`DevelopParams::develop_covered`] up to the encode: the pixels `v` of lanes that are
    /// `finite` (else 0), over the background with weight 0, exposure, tone map and the
    /// encode's clamp to [0, 1].
    #[inline(always)]
    fn covered_pixel<F: Lanes>(&self, v: V3<F>, finite: F::Mask) -> V3<F> {
        let (zero, one) = (F::splat(0.0), F::splat(1.0));
        let bg = self.background;
        let exposed = |c: F, background: f32| (F::select(finite, c, zero) + F::splat(background) * zero) * F::splat(self.scale);
        let x = V3 { x: exposed(v.x, bg.x), y: exposed(v.y, bg.y), z: exposed(v.z, bg.z) };
        // The clamp tone map is left to the encode's clamp, as in `develop_into`.
        let x = if self.op == Tonemap::Clamp { x } else { tonemap_pixel(x, self.op) };
        // The encode's clamp (NaN to 0), in lanes as in `SrgbTable::encode4`.
        let clamp = |x: F| F::select(x.gt(zero), F::select(x.lt(one), x, one), zero);
        V3 { x: clamp(x.x), y: clamp(x.y), z: clamp(x.z) }
    }

    /// Opaque RGB: the case developed four pixels at a time.
    #[inline(always)]
    pub fn opaque_rgb(&self) -> bool {
        self.channels == 3 && !self.transparent
    }

    /// What developing four opaque RGB pixels at a time needs, computed once per run.
    #[inline(always)]
    fn four(&self, tone: &impl Fn(F32x4) -> F32x4) -> Four {
        let bg = self.background;
        let background = [[bg.x, bg.y, bg.z, bg.x], [bg.y, bg.z, bg.x, bg.y], [bg.z, bg.x, bg.y, bg.z]].map(F32x4::from_array);
        // An empty pixel (no coverage, nothing rendered) develops to the same bytes everywhere:
        // four of them computed once (the same arithmetic: 0 + background × 1).
        let (zero, one, scale) = (F32x4::splat(0.0), F32x4::splat(1.0), F32x4::splat(self.scale));
        let empty = encode12(&background.map(|b| tone((zero + b * one) * scale)));
        Four { background, empty }
    }

    /// Four opaque RGB pixels: their twelve channels in output order in three registers
    /// (r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3) with 1 − coverage of each channel's pixel in
    /// `rest`: over the background, exposure, tone map and encode, three lane operations
    /// each. Everything is per channel, so lanes give the bits of [`DevelopParams::develop_one`].
    #[inline(always)]
    fn develop_four(&self, four: &Four, c: [F32x4; 3], rest: [F32x4; 3], tone: &impl Fn(F32x4) -> F32x4) -> [u8; 12] {
        let scale = F32x4::splat(self.scale);
        // over(c, a, background) = c + background (1 − a), then exposure and the tone map.
        let channel = |k: usize| tone((c[k] + four.background[k] * rest[k]) * scale);
        encode12(&[channel(0), channel(1), channel(2)])
    }

    /// One pixel (its channels in the lanes of an `F32x4`, the fourth unused) into `o`.
    #[inline(always)]
    fn develop_one(&self, p: Vec3, a: f32, tone: &impl Fn(F32x4) -> F32x4, o: &mut [u8]) {
        let lanes = |v: Vec3| F32x4::from_array([v.x, v.y, v.z, 0.0]);
        let (p, alpha) = match self.transparent {
            true if a > 0.0 => (lanes(p / a), (a * 255.0).round() as u8),
            true => (lanes(p), 0),
            // over(c, a, background) = c + background (1 − a), channel by channel.
            false => (lanes(p) + lanes(self.background) * F32x4::splat(1.0 - a), 255),
        };
        let v = tone(p * F32x4::splat(self.scale)).to_array();
        let table = srgb_table();
        (o[0], o[1], o[2]) = (table.encode(v[0]), table.encode(v[1]), table.encode(v[2]));
        if self.channels == 4 {
            o[3] = alpha;
        }
    }
}

/// Per run of four-pixel groups: the background in each register's channel order, and the
/// bytes of four empty pixels.
struct Four {
    background: [F32x4; 3],
    empty: [u8; 12],
}

/// Four pixels' channels in output order in three registers (r0 g0 b0 r1 | g1 b1 r2 g2 | b2 r3 g3 b3).
#[inline(always)]
fn channels_of(p: &[Vec3]) -> [F32x4; 3] {
    [
        F32x4::from_array([p[0].x, p[0].y, p[0].z, p[1].x]),
        F32x4::from_array([p[1].y, p[1].z, p[2].x, p[2].y]),
        F32x4::from_array([p[2].z, p[3].x, p[3].y, p[3].z]),
    ]
}

/// The codes of twelve channels (three registers of four), in order.
#[inline(always)]
fn encode12(v: &[F32x4; 3]) -> [u8; 12] {
    let table = srgb_table();
    let (a, b, c) = (table.encode4(v[0]), table.encode4(v[1]), table.encode4(v[2]));
    [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3], c[0], c[1], c[2], c[3]]
}

/// The one develop loop over a frame: 3 channels (RGB) or 4 (RGBA).
fn develop_pixels(frame: &Frame, layer: Layer, exposure: f32, op: Tonemap, channels: usize, transparent: bool) -> Option<Vec<u8>> {
    let pixels = frame.raw(layer)?;
    let d = DevelopParams::new(layer, exposure, op, channels, transparent, frame.background);
    let mut out = vec![0u8; pixels.len() * channels];
    const CHUNK: usize = 8192;
    out.par_chunks_mut(channels * CHUNK)
        .zip(pixels.par_chunks(CHUNK))
        .zip(frame.coverage.par_chunks(CHUNK))
        .for_each(|((o, p), a)| d.develop_into(p, a, o));
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::srgb::{midpoint, midpoint_f64};

    /// round(255 · encode(x)) in f64: the reference the 8-bit encode must match exactly.
    fn reference_f64(x: f32) -> u8 {
        let x = (x as f64).clamp(0.0, 1.0);
        let e = if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 };
        (e * 255.0).round() as u8
    }

    #[test]
    fn encode_matches_rounded_transfer_function() {
        for i in 0..=100_000 {
            let x = i as f32 / 100_000.0;
            assert_eq!(encode_u8(x), reference_f64(x), "x={x}");
        }
        assert_eq!(encode_u8(0.0), 0);
        assert_eq!(encode_u8(1.0), 255);
        assert_eq!(encode_u8(f32::NAN), 0);
        // Known value: linear 0.5 is sRGB 188 (not 186 as a 2.2 power would give).
        assert_eq!(encode_u8(0.5), 188);
        // Exactly the linear value of code 128.
        assert_eq!(encode_u8(srgb_decode(128.0 / 255.0)), 128);
    }

    #[test]
    fn srgb_encode_rounding_slip_at_a_midpoint() {
        // 0.25215057 is 137.4999971 codes in exact arithmetic: 137, not 138.
        let x = 0.252_150_57_f32;
        assert_eq!(reference_f64(x), 137);
        assert_eq!(encode_u8(x), 137);
        assert_eq!(encode_u8(x.next_up()), reference_f64(x.next_up()));
    }

    #[test]
    fn every_f32_in_0_1_matches_the_f64_reference() {
        // The f64 reference is monotone, so it is the count of f64 midpoints at or below x:
        // walk every f32 of [0, 1] in order with a pointer over the midpoints (a second in
        // release builds; a stride in debug). At each midpoint's neighbours the f64 transfer
        // function itself is checked too.
        let mids: Vec<f64> = (0..255).map(midpoint_f64).collect();
        for (k, &m) in mids.iter().enumerate() {
            let t = midpoint(k);
            for x in [t.next_down(), t, t.next_up()] {
                assert_eq!(encode_u8(x), reference_f64(x), "x = {x:e} near the midpoint {m:e} of codes {k}, {}", k + 1);
            }
        }
        let step = if cfg!(debug_assertions) { 9973 } else { 1 };
        let (mut bits, mut code) = (0u32, 0usize);
        while bits <= 1.0f32.to_bits() {
            let x = f32::from_bits(bits);
            while code < 255 && x as f64 >= mids[code] {
                code += 1;
            }
            assert_eq!(encode_u8(x) as usize, code, "x = {x:e}");
            bits += step;
        }
    }

    #[test]
    fn one_step_from_the_bucket_is_exact_for_every_f32_in_0_1() {
        // Reference: walk up the thresholds as far as needed.
        let t = &srgb_table().t;
        let reference = |x: f32| {
            let x = if x > 0.0 { x.min(1.0) } else { 0.0 };
            let mut code = srgb_table().b[(x * BUCKETS as f32) as usize] as usize;
            while code < 255 && x >= t[code] {
                code += 1;
            }
            code as u8
        };
        // Every f32 in [0, 1] in release builds (about 1e9 values, a second); a stride in debug.
        let step = if cfg!(debug_assertions) { 9973 } else { 1 };
        let mut bits = 0u32;
        while bits <= 1.0f32.to_bits() {
            let x = f32::from_bits(bits);
            assert_eq!(encode_u8(x), reference(x), "x = {x:e}");
            bits += step;
        }
    }

    #[test]
    fn four_lanes_encode_as_one() {
        let table = srgb_table();
        let mut values = vec![f32::NAN, -0.0, 0.0, -1.0, 1.0, 1.5, f32::INFINITY, f32::NEG_INFINITY, f32::from_bits(1)];
        values.extend(table.t[..255].iter().flat_map(|&t| [t, t.next_down(), t.next_up()]));
        let mut bits = 0u32;
        while bits < u32::MAX - 10_007 {
            values.push(f32::from_bits(bits));
            bits += 10_007;
        }
        for x in values.chunks_exact(4) {
            let lanes = table.encode4(F32x4::from_array([x[0], x[1], x[2], x[3]]));
            assert_eq!(lanes, [0, 1, 2, 3].map(|i| table.encode(x[i])), "{x:?}");
        }
    }

    #[test]
    fn covered_samples_develop_as_their_filtered_row() {
        // Covered, uncovered, non-finite and out-of-range samples, developed as a plain render
        // does (empty pixels, then the covered ones in lanes of one, four and a partial four):
        // the bytes of the filter's row through develop_into.
        let totals: Vec<Vec3> = (0..23)
            .map(|i| match i % 7 {
                0 => Vec3::new(f32::NAN, 0.5, 0.5),
                1 => Vec3::new(0.25, f32::INFINITY, 0.0),
                _ => Vec3::new(i as f32 * 0.05, 1.0 - i as f32 * 0.04, (i * i) as f32 * 0.003),
            })
            .collect();
        let depth: Vec<f32> = (0..23).map(|i| if i % 3 == 1 { 0.0 } else { 0.5 }).collect();
        let row: Vec<Vec3> = totals.iter().zip(&depth).map(|(t, &d)| if d > 0.0 && t.is_finite() { *t } else { Vec3::ZERO }).collect();
        let coverage: Vec<f32> = depth.iter().map(|&d| if d > 0.0 { 1.0 } else { 0.0 }).collect();
        let covered: Vec<u32> = (0..23).filter(|&i| depth[i as usize] > 0.0).collect();
        for op in [Tonemap::Clamp, Tonemap::Reinhard, Tonemap::Aces, Tonemap::Agx] {
            let d = DevelopParams::new(Layer::Total, 0.5, op, 3, false, Vec3::new(0.1, 0.2, 0.3));
            let mut filtered = vec![0u8; 69];
            d.develop_into(&row, &coverage, &mut filtered);
            for lanes in [1, 4] {
                let mut a: Vec<u8> = (0..23).flat_map(|_| d.empty_rgb()).collect();
                let mut nan = 0;
                for run in covered.chunks(lanes) {
                    // Lanes past the run repeat its first sample.
                    let v = |k: usize| totals[run[if k < run.len() { k } else { 0 }] as usize];
                    nan += match lanes {
                        1 => d.develop_covered::<f32>(v(0).into(), run, &mut a),
                        _ => d.develop_covered(V3::<F32x4>::from_lanes(&[v(0), v(1), v(2), v(3)]), run, &mut a),
                    };
                }
                assert_eq!(a, filtered, "{op:?} {lanes}");
                assert_eq!(nan, 5);
            }
        }
    }

    #[test]
    fn clamp_is_the_encode_clamp() {
        let mut bits = 0u32;
        while bits < u32::MAX - 40_009 {
            let x = f32::from_bits(bits);
            assert_eq!(encode_u8(tonemap(x, Tonemap::Clamp)), encode_u8(x), "{x:e}");
            bits += 40_009;
        }
        for x in [f32::NAN, -0.0, 0.0, 1.0, 1.5, f32::INFINITY, f32::NEG_INFINITY] {
            assert_eq!(encode_u8(tonemap(x, Tonemap::Clamp)), encode_u8(x), "{x:e}");
        }
    }

    #[test]
    fn decode_inverts_encode() {
        for i in 0..=255 {
            let e = i as f32 / 255.0;
            assert!((srgb_encode(srgb_decode(e)) - e).abs() < 1e-5);
        }
    }

    #[test]
    fn tonemaps_are_monotone_and_bounded() {
        for op in [Tonemap::Clamp, Tonemap::Reinhard, Tonemap::Aces, Tonemap::Agx] {
            let mut prev = 0.0;
            for i in 0..1000 {
                let y = tonemap(i as f32 * 0.05, op);
                assert!((0.0..=1.0).contains(&y) && y >= prev, "{op:?}");
                prev = y;
            }
        }
        assert_eq!(tonemap(1.0, Tonemap::Reinhard), 0.5);
    }

    /// AgX gives a value in [0, 1] for every input, lanes or not: negative, NaN, ±∞, denormal,
    /// huge; black stays black, grey stays grey, +∞ is the brightest.
    #[test]
    fn agx_is_never_nan_and_keeps_grey_grey() {
        let specials =
            [0.0, -0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY, f32::from_bits(1), 1e-30, 0.18, 1.0, 16.0, 1e30, f32::MAX];
        let mut next = crate::simd::lanes::test_rng(42, 1e3);
        let mut pixels: Vec<Vec3> = specials.iter().flat_map(|&a| specials.iter().map(move |&b| Vec3::new(a, b, 0.5))).collect();
        pixels.extend((0..4000).map(|_| Vec3::new(next(), next(), next())));
        for p in pixels.chunks_exact(4) {
            let lanes = tonemap_pixel(V3::<F32x4>::from_lanes(&[p[0], p[1], p[2], p[3]]), Tonemap::Agx).to_lanes();
            for (c, l) in p.iter().zip(lanes) {
                let one = tonemap_rgb(*c, Tonemap::Agx);
                assert!(one.to_array().iter().all(|x| (0.0..=1.0).contains(x)), "{c:?} → {one:?}");
                assert_eq!(one.to_array().map(f32::to_bits), l.to_array().map(f32::to_bits), "{c:?}: lanes");
            }
        }
        assert_eq!(tonemap_rgb(Vec3::ZERO, Tonemap::Agx), Vec3::ZERO);
        assert_eq!(tonemap_rgb(Vec3::splat(f32::INFINITY), Tonemap::Agx), tonemap_rgb(Vec3::splat(1e9), Tonemap::Agx));
        for x in [0.01, 0.18, 1.0, 4.0] {
            let c = tonemap_rgb(Vec3::splat(x), Tonemap::Agx).to_array().map(encode_u8);
            assert!(c[0].abs_diff(c[1]) <= 1 && c[1].abs_diff(c[2]) <= 1, "grey {x}: {c:?}");
        }
        // Mid-grey 0.18 sits at 0.606 of the log range, where the sigmoid gives about 0.497.
        assert!(encode_u8(tonemap(0.18, Tonemap::Agx)).abs_diff(127) <= 1);
    }

    /// Gold's F0 (0.97, 0.80, 0.32) from 1/16 to 4 times: AgX keeps the 8-bit colour's hue within
    /// 5° of F0's own (hexcone hue, 47.3°), where the per-channel ACES curve slides it towards
    /// yellow (R and G reach the shoulder together) and the clamp clips it to (255, 255, x):
    /// the olive gold of issue 42.
    #[test]
    fn agx_keeps_gold_s_hue_where_per_channel_curves_turn_it_yellow() {
        let hue = |c: Vec3| {
            let [r, g, b] = c.to_array().map(|x| encode_u8(x) as f32);
            60.0 * (g - b) / (r - b)
        };
        let f0 = Vec3::new(0.97, 0.80, 0.32);
        let own = hue(f0);
        let worst = |op| (-4..=2).map(|k| (hue(tonemap_rgb(f0 * 2f32.powi(k), op)) - own).abs()).fold(0f32, f32::max);
        assert!((own - 47.3).abs() < 0.1, "{own}");
        assert!(worst(Tonemap::Agx) < 5.0, "agx: {}", worst(Tonemap::Agx));
        assert!(worst(Tonemap::Aces) > 5.5, "aces: {}", worst(Tonemap::Aces));
        assert!(worst(Tonemap::Clamp) > 10.0, "clamp: {}", worst(Tonemap::Clamp));
    }
}
