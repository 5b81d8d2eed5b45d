//! Linear radiance → display: exposure, tone map, sRGB transfer, 8-bit quantization.
//!
//! One develop loop ([`DevelopParams`]) serves whole frames ([`develop`], [`develop_rgba`])
//! and rows rendered straight to 8 bits (`render::render_image`), so both give the same
//! bytes. Measured on the 1024² `sphere` frame, one thread, inside `render_image` (min of 8):
//! 8.0 ms with the tone map matched per channel and a `while` loop over thresholds, 5.9 ms
//! with the tone map hoisted, channels in lanes, the branch-free encode and empty pixels
//! developed once (callgrind: 89M → 35M instructions a frame).

use super::frame::{Frame, Layer};
use super::settings::Tonemap;
use crate::shading::lanes::{F32x4, Lanes};
use crate::shading::pow::pow;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::OnceLock;

/// The sRGB transfer function (IEC 61966-2-1): linear [0, 1] → encoded [0, 1]
/// (with the deterministic [`pow`]).
#[inline]
pub fn srgb_encode(x: f32) -> f32 {
    if x <= 0.003_130_8 { 12.92 * x } else { 1.055 * pow(x, 1.0 / 2.4) - 0.055 }
}

/// The inverse sRGB transfer function: encoded [0, 1] → linear [0, 1] (with the
/// deterministic [`pow`]).
#[inline]
pub fn srgb_decode(e: f32) -> f32 {
    if e <= 0.040_45 { e / 12.92 } else { pow((e + 0.055) / 1.055, 2.4) }
}

/// The tables of [`encode_u8`].
struct SrgbTable {
    /// Linear thresholds between consecutive 8-bit codes: code k + 1 wins from `t[k]` on;
    /// `t[255]` = ∞ so the step below never leaves the table.
    t: [f32; 256],
    /// For each bucket of [0, 1], the code of its lower end.
    b: [u8; BUCKETS + 1],
}

/// Buckets of the linear range for the first guess of [`encode_u8`].
const BUCKETS: usize = 4096;

/// The thresholds (comparing against them rounds exactly like round(255·encode(x)) without a
/// powf per pixel) and the bucket codes, computed once.
fn srgb_table() -> &'static SrgbTable {
    static T: OnceLock<SrgbTable> = OnceLock::new();
    T.get_or_init(|| {
        let mut t = [f32::INFINITY; 256];
        for (k, v) in t.iter_mut().take(255).enumerate() {
            // Midpoint between codes k and k+1 in encoded space, decoded in f64 for accuracy.
            let e = (k as f64 + 0.5) / 255.0;
            let lin = if e <= 0.040_45 { e / 12.92 } else { ((e + 0.055) / 1.055).powf(2.4) };
            *v = lin as f32;
        }
        let mut b = [0u8; BUCKETS + 1];
        for (i, v) in b.iter_mut().enumerate() {
            let x = i as f32 / BUCKETS as f32;
            *v = t.iter().take_while(|&&th| x >= th).count() as u8;
        }
        SrgbTable { t, b }
    })
}

impl SrgbTable {
    /// See [`encode_u8`].
    #[inline(always)]
    fn encode(&self, x: f32) -> u8 {
        // NaN and negatives land on 0; values above 1 on 255.
        let x = if x > 0.0 { x.min(1.0) } else { 0.0 };
        // x ∈ [0, 1], so the bucket is in 0..=4096 (an i32 conversion: one instruction).
        let code = self.b[((x * BUCKETS as f32) as i32 as usize).min(BUCKETS)];
        // At most one threshold lies inside a bucket: one branch-free step up.
        code + (x >= self.t[code as usize]) as u8
    }
}

/// Linear [0, 1] → 8-bit sRGB code, correctly rounded: a bucket table gives the code at
/// the bucket's start, then one comparison with the next threshold. A bucket is 1/4096
/// wide and two thresholds are at least 1/(255·12.92) = 1/3295 apart (the steepest slope
/// of the transfer function), so a bucket holds at most one threshold and one step is
/// exact (checked for every f32 in [0, 1] by a test). Measured 3× faster than a binary
/// search over the 255 thresholds; the branch-free step replaced a `while` loop.
#[inline]
pub fn encode_u8(x: f32) -> u8 {
    srgb_table().encode(x)
}

/// Applies the tone map to one linear value (after exposure).
#[inline]
pub fn tonemap(x: f32, op: Tonemap) -> f32 {
    tonemap_lanes(x, op)
}

/// [`tonemap`] for lanes: the one formula (max, min and clamp as selects with `f32`'s NaN
/// behaviour: a NaN input becomes 0).
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
}

impl DevelopParams {
    /// The parameters for `layer`: normals are colours already, so no exposure and no tone curve.
    pub fn new(layer: Layer, exposure: f32, op: Tonemap, channels: usize, transparent: bool, background: Vec3) -> DevelopParams {
        let (scale, op) = if layer == Layer::Normal { (1.0, Tonemap::Clamp) } else { (exposure.exp2(), op) };
        DevelopParams { scale, op, channels, transparent, background }
    }

    /// Bytes per pixel.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// Develops a run of pixels (layer values and coverage) into `out` (`channels` bytes each):
    /// the one develop loop, used for whole frames and for strips rendered straight to 8 bits.
    #[inline]
    pub fn develop_into(&self, pixels: &[Vec3], coverage: &[f32], out: &mut [u8]) {
        self.develop_iter(pixels.iter().copied().zip(coverage.iter().copied()), out);
    }

    /// [`DevelopParams::develop_into`] for pixels given as (value, coverage) pairs as they are
    /// resolved, so a row can be developed without being written out first.
    #[inline(always)]
    pub fn develop_iter(&self, pixels: impl Iterator<Item = (Vec3, f32)>, out: &mut [u8]) {
        // One loop per tone map, so the curve is inlined without a match per channel.
        match self.op {
            // The encode clamps to [0, 1] (NaN to 0) exactly as the clamp tone map does, so the
            // clamp is left to it (same codes: tested in clamp_is_the_encode_clamp).
            Tonemap::Clamp => self.develop_with(pixels, out, |x| x),
            Tonemap::Reinhard => self.develop_with(pixels, out, |x| tonemap_lanes(x, Tonemap::Reinhard)),
            Tonemap::Aces => self.develop_with(pixels, out, |x| tonemap_lanes(x, Tonemap::Aces)),
        }
    }

    /// One pixel's channels in the lanes of an `F32x4` (the fourth lane unused): over,
    /// exposure and tone map are per channel, so lanes give the scalar bits.
    #[inline(always)]
    fn develop_with(&self, pixels: impl Iterator<Item = (Vec3, f32)>, out: &mut [u8], tone: impl Fn(F32x4) -> F32x4) {
        let table = srgb_table();
        let lanes = |v: Vec3| F32x4::from_array([v.x, v.y, v.z, 0.0]);
        let (background, scale) = (lanes(self.background), F32x4::splat(self.scale));
        // An empty pixel (no coverage, nothing rendered) develops to the same bytes everywhere:
        // computed once (the same arithmetic: 0 + background × 1, or 0 with alpha 0).
        let empty = {
            let c = if self.transparent { F32x4::splat(0.0) } else { F32x4::splat(0.0) + background * F32x4::splat(1.0) };
            let v = tone(c * scale).to_array();
            [table.encode(v[0]), table.encode(v[1]), table.encode(v[2])]
        };
        for (o, (c, a)) in out.chunks_exact_mut(self.channels).zip(pixels) {
            if a == 0.0 && c == Vec3::ZERO {
                o[..3].copy_from_slice(&empty[..3]);
                if self.channels == 4 {
                    o[3] = if self.transparent { 0 } else { 255 };
                }
                continue;
            }
            let (c, alpha) = match self.transparent {
                true if a > 0.0 => (lanes(c / a), (a * 255.0).round() as u8),
                true => (lanes(c), 0),
                // over(c, a, background) = c + background (1 − a), channel by channel.
                false => (lanes(c) + background * F32x4::splat(1.0 - a), 255),
            };
            // Three independent table lookups: measured faster scalar (5.3 ms a 1024² frame)
            // than with the bucket index and threshold test in lanes (6.1 ms).
            let v = tone(c * scale).to_array();
            (o[0], o[1], o[2]) = (table.encode(v[0]), table.encode(v[1]), table.encode(v[2]));
            if self.channels == 4 {
                o[3] = alpha;
            }
        }
    }
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

    #[test]
    fn encode_matches_rounded_transfer_function() {
        for i in 0..=100_000 {
            let x = i as f32 / 100_000.0;
            let exact = (srgb_encode(x) * 255.0).round();
            let got = encode_u8(x) as f32;
            // Exact except where f32 rounding puts x on the other side of a midpoint.
            assert!((got - exact).abs() <= 1.0, "x={x} got={got} exact={exact}");
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
        for op in [Tonemap::Clamp, Tonemap::Reinhard, Tonemap::Aces] {
            let mut prev = 0.0;
            for i in 0..1000 {
                let y = tonemap(i as f32 * 0.05, op);
                assert!((0.0..=1.0).contains(&y) && y >= prev, "{op:?}");
                prev = y;
            }
        }
        assert_eq!(tonemap(1.0, Tonemap::Reinhard), 0.5);
    }
}
