//! A plain render's strip developed to 8-bit sRGB as its samples are shaded: the totals
//! batched channel by channel, then clamped in lanes and encoded (the table, eight AVX2
//! lanes into 3-byte pixels, or sixteen AVX-512 lanes into a 4-byte strip packed at the end).

use super::strip::Totals;
use crate::render::develop::DevelopParams;
use crate::simd::lanes::{F32x4, Lanes, MAX_WIDTH, V3};
use glam::Vec3;
use std::mem::MaybeUninit;

/// Samples a [`Developed`] buffers before developing them.
pub(super) const DEVELOP_BATCH: usize = 256;

/// A plain render's pixels (one sample each, only I_tot kept, opaque RGB), developed to 8-bit
/// sRGB from their samples' totals ([`DevelopParams::develop_covered`]): the shading bundles
/// leave their totals here channel by channel, and every [`DEVELOP_BATCH`] samples are
/// developed in lanes of the bundles' width. No strip of totals is scattered and read back
/// pixel by pixel, and no four pixels' channels are regrouped into registers.
pub(super) struct Developed<'a> {
    out: Out<'a>,
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

/// Where a [`Developed`] writes its codes, chosen once per strip.
enum Out<'a> {
    /// The strip's 3-byte pixels, holding the background's bytes until a sample's codes
    /// overwrite them, through the table ([`DevelopParams::develop_covered`]).
    Bytes(&'a mut [u8]),
    /// The same, eight pixels at a time with AVX2 ([`DevelopParams::encode_covered`]).
    #[cfg(target_arch = "x86_64")]
    Eight(crate::simd::avx2::Avx2, &'a mut [u8]),
    /// With AVX-512BW: the strip as 4-byte pixels (R | G << 8 | B << 16) holding the
    /// background's codes, sixteen at a time ([`DevelopParams::encode_covered_wide`]), then
    /// packed into the strip's bytes (not yet written) when the shading is done.
    #[cfg(target_arch = "x86_64")]
    Wide(crate::simd::avx512::Avx512Bw, &'a mut [u32], &'a mut [MaybeUninit<u8>]),
}

impl<'a> Developed<'a> {
    /// Develops a plain render's strip into its `bytes` (3 a pixel, not yet written) as
    /// `shade` leaves its samples' totals (it ends with a flush), with `pixels` as the 4-byte
    /// strip when this CPU encodes sixteen pixels at a time. Every byte of `bytes` is written
    /// when this returns; returns the covered samples whose total was not finite.
    pub(super) fn strip(
        bytes: &'a mut [MaybeUninit<u8>],
        develop: &'a DevelopParams,
        pixels: &'a mut Vec<u32>,
        shade: impl FnOnce(&mut Developed<'a>),
    ) -> u64 {
        let empty = develop.empty_rgb();
        #[cfg(target_arch = "x86_64")]
        let out = match (develop.avx512bw(), develop.avx2()) {
            (Some(t), _) => {
                pixels.clear();
                pixels.resize(bytes.len() / 3, u32::from_le_bytes([empty[0], empty[1], empty[2], 0]));
                Out::Wide(t, &mut pixels[..], bytes)
            }
            (None, Some(t)) => Out::Eight(t, fill_pixels(bytes, empty)),
            (None, None) => Out::Bytes(fill_pixels(bytes, empty)),
        };
        #[cfg(not(target_arch = "x86_64"))]
        let out = {
            let _ = pixels;
            Out::Bytes(fill_pixels(bytes, empty))
        };
        let zero = [0f32; DEVELOP_BATCH + MAX_WIDTH];
        let mut d = Developed { out, develop, nan: 0, x: zero, y: zero, z: zero, index: [0; DEVELOP_BATCH + MAX_WIDTH], len: 0 };
        shade(&mut d);
        // `shade` ends with a flush; one that did not leaves no batch behind either.
        if d.len > 0 {
            d.flush::<F32x4>();
        }
        #[cfg(target_arch = "x86_64")]
        if let Out::Wide(t, px, bytes) = d.out {
            develop.pack_rgb(t, px, bytes);
        }
        d.nan
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
        let n = self.len;
        self.len = 0;
        // In lanes, the batch is encoded in one pass after its bundles' lane steps
        // (sphere-gouraud 0.94× at one thread with eight); with the table, each bundle's
        // lanes go through it as they are developed.
        match &mut self.out {
            Out::Bytes(bytes) => {
                for j in (0..n).step_by(F::WIDTH) {
                    let v = V3 { x: F::load(&self.x[j..]), y: F::load(&self.y[j..]), z: F::load(&self.z[j..]) };
                    self.nan += self.develop.develop_covered(v, &self.index[j..(j + F::WIDTH).min(n)], bytes);
                }
            }
            #[cfg(target_arch = "x86_64")]
            Out::Eight(t, bytes) => {
                self.nan += clamp_batch::<F>(self.develop, [&mut self.x, &mut self.y, &mut self.z], n);
                self.develop.encode_covered(*t, [&self.x[..n], &self.y[..n], &self.z[..n]], &self.index[..n], bytes);
            }
            #[cfg(target_arch = "x86_64")]
            Out::Wide(t, px, _) => {
                self.nan += clamp_batch::<F>(self.develop, [&mut self.x, &mut self.y, &mut self.z], n);
                self.develop.encode_covered_wide(*t, [&self.x[..n], &self.y[..n], &self.z[..n]], &self.index[..n], px);
            }
        }
    }
}

/// The lane steps of a batch's `n` totals (channels `c`) in place, `F::WIDTH` at a time,
/// before an encode in lanes; returns how many of them were not finite.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn clamp_batch<F: Lanes>(develop: &DevelopParams, c: [&mut [f32]; 3], n: usize) -> u64 {
    let [x, y, z] = c;
    let mut nan = 0;
    for j in (0..n).step_by(F::WIDTH) {
        nan += develop.clamp_covered::<F>([&mut x[j..], &mut y[j..], &mut z[j..]], (n - j).min(F::WIDTH));
    }
    nan
}

/// Writes `pixel` over every pixel of `out` (whose length is a multiple of 3) and returns it
/// initialised: the background of an image's strip, which its samples then overwrite.
fn fill_pixels(out: &mut [MaybeUninit<u8>], pixel: [u8; 3]) -> &mut [u8] {
    // Sixteen pixels (48 bytes) at a time, as one copy (vector stores, not 48 byte stores).
    let sixteen: [MaybeUninit<u8>; 48] = std::array::from_fn(|i| MaybeUninit::new(pixel[i % 3]));
    let mut runs = out.chunks_exact_mut(48);
    for run in &mut runs {
        run.copy_from_slice(&sixteen);
    }
    for px in runs.into_remainder().chunks_exact_mut(3) {
        for (o, b) in px.iter_mut().zip(pixel) {
            o.write(b);
        }
    }
    assert!(out.len().is_multiple_of(3), "whole pixels");
    // SAFETY: every element of `out` was written above (the runs of 48 bytes, then the whole
    // pixels of the remainder: its length is a multiple of 3); `MaybeUninit<u8>` and `u8`
    // have the same layout.
    unsafe { &mut *(out as *mut [MaybeUninit<u8>] as *mut [u8]) }
}

/// `out` zeroed, as initialised bytes (for a strip whose rows then write every byte).
pub(super) fn zeroed(out: &mut [MaybeUninit<u8>]) -> &mut [u8] {
    out.fill(MaybeUninit::new(0));
    // SAFETY: every element was written just above; `MaybeUninit<u8>` and `u8` have the same
    // layout.
    unsafe { &mut *(out as *mut [MaybeUninit<u8>] as *mut [u8]) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::settings::Tonemap;
    use crate::render::frame::Layer;

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn a_batch_develops_as_its_bundles() {
        // The AVX2 and AVX-512 batch paths (lane steps in place, then the encode eight or
        // sixteen pixels at a time) give the bytes and the non-finite count of `develop_covered`
        // bundle by bundle: totals over the whole range and past it, NaN and ∞, scattered
        // pixels and runs, a partial bundle.
        let n = 61;
        let totals: Vec<Vec3> = (0..n)
            .map(|i| match i % 11 {
                0 => Vec3::new(f32::NAN, 0.5, 0.5),
                1 => Vec3::new(0.25, f32::NEG_INFINITY, 2.0),
                _ => Vec3::new(i as f32 * 0.021, 1.3 - i as f32 * 0.023, (i * i) as f32 * 1e-4),
            })
            .collect();
        let index: Vec<u32> = (0..n as u32).map(|i| if i < 24 { i } else { 100 - i }).collect();
        for op in [Tonemap::Clamp, Tonemap::Reinhard, Tonemap::Aces, Tonemap::Agx] {
            let d = DevelopParams::new(Layer::Total, 0.5, op, 3, false, Vec3::new(0.1, 0.2, 0.3));
            let Some(t) = d.avx2() else {
                crate::simd::cpu::missing(crate::simd::Level::Avx2, "AVX2");
                return;
            };
            let mut want = vec![9u8; 300];
            let mut nan_want = 0;
            for (run, v) in index.chunks(4).zip(totals.chunks(4)) {
                let v = |k: usize| v[k.min(v.len() - 1)];
                nan_want += d.develop_covered(V3::<F32x4>::from_lanes(&[v(0), v(1), v(2), v(3)]), run, &mut want);
            }
            let mut c: [Vec<f32>; 3] = [0, 1, 2].map(|k| {
                let mut c: Vec<f32> = totals.iter().map(|t| t[k]).collect();
                c.resize(n + 4, 0.0);
                c
            });
            let mut nan = 0;
            for j in (0..n).step_by(4) {
                let [r, g, b] = &mut c;
                nan += d.clamp_covered::<F32x4>([&mut r[j..], &mut g[j..], &mut b[j..]], (n - j).min(4));
            }
            let mut got = vec![9u8; 300];
            d.encode_covered(t, [&c[0][..n], &c[1][..n], &c[2][..n]], &index, &mut got);
            assert_eq!(got, want, "{op:?}");
            assert_eq!((nan, nan_want), (12, 12));
            // Sixteen at a time into 4-byte pixels, then packed.
            if let Some(t) = d.avx512bw() {
                let mut px = vec![0x0009_0909u32; 100];
                d.encode_covered_wide(t, [&c[0][..n], &c[1][..n], &c[2][..n]], &index, &mut px);
                let mut got = Vec::with_capacity(300);
                d.pack_rgb(t, &px, &mut got.spare_capacity_mut()[..300]);
                // SAFETY: `pack_rgb` wrote all 300 bytes.
                unsafe { got.set_len(300) };
                assert_eq!(got, want, "{op:?}, sixteen lanes");
            } else {
                crate::simd::cpu::missing(crate::simd::Level::Avx512, "AVX-512BW (sixteen lanes)");
            }
        }
    }

    #[test]
    fn the_fill_writes_every_pixel_and_zeroed_every_byte() {
        // 17 pixels: one run of sixteen, then a rest of one.
        let mut out = [MaybeUninit::new(9u8); 51];
        assert_eq!(fill_pixels(&mut out, [1, 2, 3]), [1, 2, 3].repeat(17));
        assert_eq!(zeroed(&mut out), [0; 51]);
    }
}
