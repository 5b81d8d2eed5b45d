//! Snapshot comparison for a course's CI: rendered figure vs a blessed PNG.
//!
//! A pixel differs when any channel (alpha included) differs by more than
//! `per_pixel` codes; a snapshot matches when at most `max_share` of its pixels differ.

use image::{Rgba, RgbaImage};

/// How different a snapshot may be and still match.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Largest per-channel difference (0–255) that does not count.
    pub per_pixel: u8,
    /// Largest share of differing pixels (0–1) that still matches.
    pub max_share: f64,
}

impl Default for Tolerance {
    /// 2 codes per channel, 0.1% of pixels: absorbs last-bit float differences between
    /// compilers and CPUs, catches any visible change of a parameter.
    fn default() -> Self {
        Tolerance { per_pixel: 2, max_share: 0.001 }
    }
}

/// The outcome of comparing two images.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Pixels whose difference exceeds the per-pixel tolerance.
    pub differing: u64,
    /// Pixels compared.
    pub total: u64,
    /// Largest channel difference seen.
    pub max_delta: u8,
    /// Expected and actual sizes when they differ (then nothing else is compared).
    pub size_mismatch: Option<((u32, u32), (u32, u32))>,
}

impl Comparison {
    /// Share of differing pixels (1 on a size mismatch).
    pub fn share(&self) -> f64 {
        if self.size_mismatch.is_some() { 1.0 } else { self.differing as f64 / self.total.max(1) as f64 }
    }

    /// True when the images match within `tol`.
    pub fn matches(&self, tol: &Tolerance) -> bool {
        self.size_mismatch.is_none() && self.share() <= tol.max_share
    }
}

/// Compares `actual` with `expected` pixel by pixel.
pub fn compare(expected: &RgbaImage, actual: &RgbaImage, tol: &Tolerance) -> Comparison {
    if expected.dimensions() != actual.dimensions() {
        return Comparison { differing: 0, total: 0, max_delta: 255, size_mismatch: Some((expected.dimensions(), actual.dimensions())) };
    }
    let mut differing = 0;
    let mut max_delta = 0;
    for (e, a) in expected.pixels().zip(actual.pixels()) {
        let d = delta(e, a);
        max_delta = max_delta.max(d);
        differing += (d > tol.per_pixel) as u64;
    }
    Comparison { differing, total: expected.pixels().len() as u64, max_delta, size_mismatch: None }
}

/// A diff image: the expected image faded to grey, differing pixels in red (brighter = larger).
///
/// Preconditions: same size (otherwise the actual image is returned as is).
pub fn diff_image(expected: &RgbaImage, actual: &RgbaImage, tol: &Tolerance) -> RgbaImage {
    if expected.dimensions() != actual.dimensions() {
        return actual.clone();
    }
    let mut out = RgbaImage::new(expected.width(), expected.height());
    for ((e, a), o) in expected.pixels().zip(actual.pixels()).zip(out.pixels_mut()) {
        let d = delta(e, a);
        *o = if d > tol.per_pixel {
            Rgba([128 + d / 2, 0, 0, 255])
        } else {
            let grey = ((e[0] as u32 + e[1] as u32 + e[2] as u32) / 3 / 3 + 170) as u8;
            Rgba([grey, grey, grey, 255])
        };
    }
    out
}

fn delta(e: &Rgba<u8>, a: &Rgba<u8>) -> u8 {
    e.0.iter().zip(a.0.iter()).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerance_counts_only_larger_differences() {
        let a = RgbaImage::from_pixel(10, 10, Rgba([100, 100, 100, 255]));
        let mut b = a.clone();
        b.put_pixel(0, 0, Rgba([102, 100, 100, 255]));
        let tol = Tolerance::default();
        let c = compare(&a, &b, &tol);
        assert_eq!((c.differing, c.max_delta), (0, 2));
        assert!(c.matches(&tol));
        b.put_pixel(1, 0, Rgba([110, 100, 100, 255]));
        let c = compare(&a, &b, &tol);
        assert_eq!(c.differing, 1);
        assert!(!c.matches(&tol), "1% of pixels differ, more than 0.1%");
        assert!(c.matches(&Tolerance { per_pixel: 2, max_share: 0.02 }));
        let d = diff_image(&a, &b, &tol);
        assert!(d.get_pixel(1, 0)[0] > 128 && d.get_pixel(1, 0)[1] == 0);
        assert_eq!(d.get_pixel(0, 0)[0], d.get_pixel(0, 0)[1]);
    }

    #[test]
    fn size_mismatch_never_matches() {
        let c = compare(&RgbaImage::new(4, 4), &RgbaImage::new(4, 5), &Tolerance::default());
        assert!(!c.matches(&Tolerance { per_pixel: 255, max_share: 1.0 }));
    }
}
