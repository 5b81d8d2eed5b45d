//! A plain render's strip developed to 8-bit sRGB as its samples are shaded: the totals
//! batched channel by channel, then clamped in lanes and encoded (the table, eight AVX2
//! lanes into 3-byte pixels, or sixteen AVX-512 lanes into a 4-byte strip packed at the end).

use super::strip::Totals;
use crate::render::develop::DevelopParams;
use crate::simd::lanes::{Lanes, MAX_WIDTH, V3};
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
    pub(super) nan: u64,
    /// Totals waiting to be developed (channels x, y, z and sample index, `len` of them, then
    /// room for a bundle read past the end): developing them in a loop of their own keeps the
    /// shading bundles' long dependency chains apart from the develop's.
    x: [f32; DEVELOP_BATCH + MAX_WIDTH],
    y: [f32; DEVELOP_BATCH + MAX_WIDTH],
    z: [f32; DEVELOP_BATCH + MAX_WIDTH],
    index: [u32; DEVELOP_BATCH + MAX_WIDTH],
    len: usize,
}

/// Where a [`Developed`] writes its codes.
enum Out<'a> {
    /// The strip's 3-byte pixels, holding the background's bytes until a sample's codes
    /// overwrite them.
    Bytes(&'a mut [u8]),
    /// With AVX-512BW: the strip as 4-byte pixels (R | G << 8 | B << 16) holding the
    /// background's codes, then packed into the strip's bytes (not yet written) by
    /// [`Developed::finish`].
    #[cfg(target_arch = "x86_64")]
    Wide(crate::simd::avx512::Avx512Bw, &'a mut [u32], &'a mut [MaybeUninit<u8>]),
}

impl<'a> Developed<'a> {
    /// The develop of a strip's `bytes` (3 a pixel, not yet written), with `pixels` as the
    /// 4-byte strip when this CPU encodes sixteen pixels at a time.
    pub(super) fn new(bytes: &'a mut [MaybeUninit<u8>], develop: &'a DevelopParams, pixels: &'a mut Vec<u32>) -> Developed<'a> {
        let empty = develop.empty_rgb();
        #[cfg(target_arch = "x86_64")]
        let out = match develop.avx512bw() {
            Some(t) => {
                pixels.clear();
                pixels.resize(bytes.len() / 3, u32::from_le_bytes([empty[0], empty[1], empty[2], 0]));
                Out::Wide(t, &mut pixels[..], bytes)
            }
            None => Out::Bytes(fill_pixels(bytes, empty)),
        };
        #[cfg(not(target_arch = "x86_64"))]
        let out = {
            let _ = pixels;
            Out::Bytes(fill_pixels(bytes, empty))
        };
        let zero = [0f32; DEVELOP_BATCH + MAX_WIDTH];
        Developed { out, develop, nan: 0, x: zero, y: zero, z: zero, index: [0; DEVELOP_BATCH + MAX_WIDTH], len: 0 }
    }

    /// Finishes the strip (after the last flush): every byte of its `bytes` is then written.
    pub(super) fn finish(self) {
        debug_assert_eq!(self.len, 0, "flushed");
        match self.out {
            Out::Bytes(_) => {}
            #[cfg(target_arch = "x86_64")]
            Out::Wide(t, px, bytes) => self.develop.pack_rgb(t, px, bytes),
        }
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
        // With AVX2 the batch is encoded in one pass eight pixels at a time (sixteen into
        // the 4-byte strip with AVX-512BW), after its bundles' lane steps (sphere-gouraud
        // 0.94× at one thread); without, each bundle's lanes go through the table as they
        // are developed.
        #[cfg(target_arch = "x86_64")]
        if let Some(t) = self.develop.avx2() {
            for j in (0..n).step_by(F::WIDTH) {
                self.nan += self.develop.clamp_covered::<F>([&mut self.x[j..], &mut self.y[j..], &mut self.z[j..]], (n - j).min(F::WIDTH));
            }
            let c = [&self.x[..n], &self.y[..n], &self.z[..n]];
            match &mut self.out {
                Out::Wide(t, px, _) => self.develop.encode_covered_wide(*t, c, &self.index[..n], px),
                Out::Bytes(bytes) => self.develop.encode_covered(t, c, &self.index[..n], bytes),
            }
            return;
        }
        match &mut self.out {
            Out::Bytes(bytes) => {
                for j in (0..n).step_by(F::WIDTH) {
                    let v = V3 { x: F::load(&self.x[j..]), y: F::load(&self.y[j..]), z: F::load(&self.z[j..]) };
                    self.nan += self.develop.develop_covered(v, &self.index[j..(j + F::WIDTH).min(n)], bytes);
                }
            }
            #[cfg(target_arch = "x86_64")]
            Out::Wide(..) => unreachable!("AVX-512BW implies AVX2"),
        }
    }
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

    #[test]
    fn the_fill_writes_every_pixel_and_zeroed_every_byte() {
        // 17 pixels: one run of sixteen, then a rest of one.
        let mut out = [MaybeUninit::new(9u8); 51];
        assert_eq!(fill_pixels(&mut out, [1, 2, 3]), [1, 2, 3].repeat(17));
        assert_eq!(zeroed(&mut out), [0; 51]);
    }
}
