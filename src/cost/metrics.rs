//! Error between a render and its reference: RMSE, max error, PSNR, the share of visibly
//! different pixels, and an error heatmap.
//!
//! Everything is measured on one layer composited over each frame's background
//! ([`Frame::layer`]), in linear radiance, before exposure and tone mapping; only
//! `visible_pct` looks at the developed 8-bit sRGB image, since "visible" is a statement
//! about what the display shows.
//!
//! | metric | definition |
//! | --- | --- |
//! | `rmse` | √(mean over all pixels and the 3 channels of (frame − reference)²) |
//! | `max_err` | the largest absolute channel difference |
//! | `psnr` | 20·log10([`PSNR_PEAK`] / rmse) in dB, peak = 1 (linear white); +∞ when rmse = 0 |
//! | `visible_pct` | % of pixels whose 8-bit sRGB codes (× 2^exposure, clamp tone map) differ by more than 1 in any channel |

use crate::lesson::settings::Tonemap;
use crate::render::develop::develop;
use crate::render::frame::{Frame, Layer};
use glam::Vec3;

/// The peak signal of the PSNR: 1, linear white (radiance can exceed it; PSNR is then still well defined).
pub const PSNR_PEAK: f64 = 1.0;

/// How far a frame is from its reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorMetrics {
    /// Root mean square error over all pixels and channels, linear radiance.
    pub rmse: f64,
    /// Largest absolute channel difference, linear radiance.
    pub max_err: f64,
    /// 20·log10(1/rmse) in dB; `f64::INFINITY` for identical images (print it with [`format_psnr`]).
    pub psnr: f64,
    /// Percentage (0–100) of pixels whose developed 8-bit sRGB codes differ by more than 1 in any channel.
    pub visible_pct: f64,
}

/// Two frames that cannot be compared.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MetricsError {
    /// Different image sizes.
    #[error("the frame is {frame:?} pixels but the reference is {reference:?}")]
    Size {
        /// (width, height) of the frame.
        frame: (u32, u32),
        /// (width, height) of the reference.
        reference: (u32, u32),
    },
    /// The layer was not kept in one of the frames.
    #[error("the {which} does not keep the `{layer}` layer")]
    MissingLayer {
        /// The layer's name.
        layer: &'static str,
        /// `frame` or `reference`.
        which: &'static str,
    },
}

/// PSNR for a table or CSV: `inf` for identical images, else dB with two decimals.
///
/// JSON has no infinity: JSON writers should emit `null` when `psnr.is_infinite()`.
pub fn format_psnr(psnr: f64) -> String {
    if psnr.is_infinite() { "inf".to_string() } else { format!("{psnr:.2}") }
}

/// PSNR as a figure or a page shows it: "42.14 dB", "∞ dB" for an exact match, and "< 0 dB"
/// for a negative value (an error above linear white, as against an HDR sky), which is no
/// quality to rank by: the figure's caption says what it means ([`NEGATIVE_PSNR`]).
pub fn psnr_text(psnr: f64) -> String {
    if psnr.is_infinite() {
        "∞ dB".to_string()
    } else if psnr < 0.0 {
        "< 0 dB".to_string()
    } else {
        format!("{} dB", format_psnr(psnr))
    }
}

/// What a PSNR below 0 dB means, for a caption or a table's foot.
pub const NEGATIVE_PSNR: &str = "PSNR < 0 dB: the RMSE is above linear white, the PSNR's peak (an HDR reference)";

/// The composited layer of both frames, checked to be comparable.
fn composited(frame: &Frame, reference: &Frame, layer: Layer) -> Result<(Vec<Vec3>, Vec<Vec3>), MetricsError> {
    if (frame.width, frame.height) != (reference.width, reference.height) {
        return Err(MetricsError::Size { frame: (frame.width, frame.height), reference: (reference.width, reference.height) });
    }
    let missing = |which| MetricsError::MissingLayer { layer: layer.name(), which };
    let a = frame.layer(layer).ok_or_else(|| missing("frame"))?;
    let b = reference.layer(layer).ok_or_else(|| missing("reference"))?;
    Ok((a, b))
}

/// The error of `frame` against `reference` on one layer; `exposure` (stops) only
/// affects `visible_pct`, which develops both with the clamp tone map.
///
/// # Errors
/// [`MetricsError::Size`] when the sizes differ, [`MetricsError::MissingLayer`] when a
/// frame did not keep `layer`.
pub fn error_metrics(frame: &Frame, reference: &Frame, layer: Layer, exposure: f32) -> Result<ErrorMetrics, MetricsError> {
    let (a, b) = composited(frame, reference, layer)?;
    // Sequential f64 sums: the same bits on every run.
    let (mut sum_sq, mut max_err) = (0f64, 0f64);
    for (p, q) in a.iter().zip(&b) {
        for (x, y) in p.to_array().into_iter().zip(q.to_array()) {
            let d = (x as f64 - y as f64).abs();
            sum_sq += d * d;
            max_err = max_err.max(d);
        }
    }
    let channels = 3 * a.len();
    let rmse = if channels == 0 { 0.0 } else { (sum_sq / channels as f64).sqrt() };
    let psnr = if rmse == 0.0 { f64::INFINITY } else { 20.0 * (PSNR_PEAK / rmse).log10() };

    let da = develop(frame, layer, exposure, Tonemap::Clamp).expect("layer checked above");
    let db = develop(reference, layer, exposure, Tonemap::Clamp).expect("layer checked above");
    let visible =
        da.chunks_exact(3).zip(db.chunks_exact(3)).filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > 1)).count();
    let visible_pct = if a.is_empty() { 0.0 } else { 100.0 * visible as f64 / a.len() as f64 };
    Ok(ErrorMetrics { rmse, max_err, psnr, visible_pct })
}

/// Stops of the heatmap ramp, evenly spaced from 0 to 1: matplotlib's "inferno"
/// (van der Walt & Smith), sampled at 10 points (black → purple → red → orange → pale yellow).
/// Perceptually ordered and readable in greyscale.
const INFERNO: [[u8; 3]; 10] = [
    [0x00, 0x00, 0x04],
    [0x1b, 0x0c, 0x42],
    [0x4b, 0x0c, 0x6b],
    [0x78, 0x1c, 0x6d],
    [0xa5, 0x2c, 0x60],
    [0xcf, 0x44, 0x46],
    [0xed, 0x69, 0x25],
    [0xfb, 0x9a, 0x06],
    [0xf7, 0xd0, 0x3c],
    [0xfc, 0xff, 0xa4],
];

/// The heatmap colour of `t` in [0, 1] (clamped; NaN counts as 1): the stops of the ramp
/// interpolated linearly in encoded sRGB.
pub fn heat_colour(t: f32) -> [u8; 3] {
    let t = if t.is_nan() { 1.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (INFERNO.len() - 1) as f32;
    let i = (x.floor() as usize).min(INFERNO.len() - 2);
    let f = x - i as f32;
    let (a, b) = (INFERNO[i], INFERNO[i + 1]);
    std::array::from_fn(|c| (a[c] as f32 + (b[c] as f32 - a[c] as f32) * f).round() as u8)
}

/// Per pixel, the largest absolute channel error of `frame` against `reference` on one
/// layer (composited, linear radiance).
///
/// # Errors
/// As [`error_metrics`].
pub fn pixel_errors(frame: &Frame, reference: &Frame, layer: Layer) -> Result<Vec<f32>, MetricsError> {
    let (a, b) = composited(frame, reference, layer)?;
    Ok(a.iter().zip(&b).map(|(p, q)| (*p - *q).abs().max_element()).collect())
}

/// The error of [`pixel_errors`] through the inferno-like ramp of [`heat_colour`]:
/// error 0 is black, errors of `scale` and above are the top (pale yellow), linear in
/// between. Precondition: `scale` > 0 (otherwise any non-zero error maps to the top).
///
/// # Errors
/// As [`error_metrics`].
pub fn error_heatmap(frame: &Frame, reference: &Frame, layer: Layer, scale: f32) -> Result<image::RgbImage, MetricsError> {
    let errors = pixel_errors(frame, reference, layer)?;
    let mut img = image::RgbImage::new(frame.width, frame.height);
    for (px, e) in img.pixels_mut().zip(errors) {
        let t = if scale > 0.0 {
            e / scale
        } else if e > 0.0 {
            1.0
        } else {
            0.0
        };
        *px = image::Rgb(heat_colour(t));
    }
    Ok(img)
}

/// The `q`-quantile (0..=1) of `values`, by rank (no interpolation); 0 for none.
pub fn quantile(values: &[f32], q: f64) -> f32 {
    if values.is_empty() {
        return 0.0;
    }
    let mut v: Vec<f32> = values.iter().copied().filter(|x| !x.is_nan()).collect();
    v.sort_by(f32::total_cmp);
    let i = ((v.len() - 1) as f64 * q.clamp(0.0, 1.0)).round() as usize;
    v.get(i).copied().unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::develop::encode_u8;

    fn flat(w: u32, h: u32, c: Vec3) -> Frame {
        let n = (w * h) as usize;
        Frame { width: w, height: h, layers: vec![(Layer::Total, vec![c; n])], coverage: vec![1.0; n], background: Vec3::ZERO }
    }

    #[test]
    fn identical_frames_have_no_error() {
        let f = flat(7, 5, Vec3::new(0.2, 0.5, 0.9));
        let m = error_metrics(&f, &f.clone(), Layer::Total, 0.0).unwrap();
        assert_eq!(m.rmse, 0.0);
        assert_eq!(m.max_err, 0.0);
        assert_eq!(m.psnr, f64::INFINITY);
        assert_eq!(m.visible_pct, 0.0);
        assert_eq!(format_psnr(m.psnr), "inf");
        assert_eq!(psnr_text(m.psnr), "∞ dB");
        let heat = error_heatmap(&f, &f, Layer::Total, 0.1).unwrap();
        assert!(heat.pixels().all(|p| p.0 == INFERNO[0]));
    }

    #[test]
    fn constant_offset_gives_the_analytic_errors() {
        // 1/128 is exact in f32, and so is 0.5 + 1/128.
        let d = 1.0 / 128.0;
        let a = flat(8, 4, Vec3::splat(0.5));
        let b = flat(8, 4, Vec3::splat(0.5 + d));
        let m = error_metrics(&b, &a, Layer::Total, 0.0).unwrap();
        assert!((m.rmse - d as f64).abs() < 1e-12, "{m:?}");
        assert!((m.max_err - d as f64).abs() < 1e-12, "{m:?}");
        assert!((m.psnr - 20.0 * 128f64.log10()).abs() < 1e-9, "{m:?}");
        assert_eq!(format_psnr(m.psnr), "42.14");
        assert_eq!(psnr_text(m.psnr), "42.14 dB");
        // An error of 2 against a signal of 1: 20 log10(1/2) < 0 is said, not shown as a quality.
        let big = error_metrics(&flat(8, 4, Vec3::splat(2.5)), &a, Layer::Total, 0.0).unwrap();
        assert!(big.psnr < 0.0 && psnr_text(big.psnr) == "< 0 dB", "{big:?}");
        // An offset in one channel only: RMSE over 3 channels is d/√3, max stays d.
        let c = flat(8, 4, Vec3::new(0.5 + d, 0.5, 0.5));
        let m = error_metrics(&c, &a, Layer::Total, 0.0).unwrap();
        assert!((m.rmse - d as f64 / 3f64.sqrt()).abs() < 1e-12, "{m:?}");
        assert!((m.max_err - d as f64).abs() < 1e-12, "{m:?}");
    }

    #[test]
    fn errors_are_measured_after_compositing_over_the_background() {
        // Half coverage over different backgrounds: same surface, different pixels.
        let mut a = flat(2, 2, Vec3::splat(0.25));
        a.coverage = vec![0.5; 4];
        let mut b = a.clone();
        b.background = Vec3::splat(0.5);
        let m = error_metrics(&a, &b, Layer::Total, 0.0).unwrap();
        assert!((m.rmse - 0.25).abs() < 1e-12 && (m.max_err - 0.25).abs() < 1e-12, "{m:?}");
    }

    #[test]
    fn visible_pct_counts_exactly_the_pixels_changed_beyond_one_code() {
        let base = Vec3::splat(0.5);
        let reference = flat(10, 10, base);
        let mut frame = reference.clone();
        let code = encode_u8(0.5) as i32;
        // A linear value whose code is exactly one above: not visible.
        let one_up = (1..10_000).map(|k| 0.5 + k as f32 * 1e-5).find(|x| encode_u8(*x) as i32 == code + 1).unwrap();
        let two_up = (1..10_000).map(|k| 0.5 + k as f32 * 1e-5).find(|x| encode_u8(*x) as i32 == code + 2).unwrap();
        let px = &mut frame.layers[0].1;
        for i in [3, 14, 15, 42, 77, 98, 99] {
            // Visible: two codes up in one channel.
            px[i].y = two_up;
        }
        for i in [0, 1, 2, 50, 51] {
            // Within one code: tiny changes and one-code changes.
            px[i] = Vec3::new(one_up, 0.5 + 1e-6, one_up);
        }
        let m = error_metrics(&frame, &reference, Layer::Total, 0.0).unwrap();
        assert!((m.visible_pct - 7.0).abs() < 1e-12, "{m:?}");
        // Exposure moves the codes: one stop down halves the linear values, one stop up clamps both to 255.
        let up = error_metrics(&frame, &reference, Layer::Total, 1.0).unwrap();
        assert_eq!(up.visible_pct, 0.0);
        assert!(m.rmse > 0.0 && m.rmse == up.rmse);
    }

    #[test]
    fn mismatched_frames_are_errors() {
        let a = flat(4, 4, Vec3::ZERO);
        assert_eq!(
            error_metrics(&a, &flat(4, 5, Vec3::ZERO), Layer::Total, 0.0),
            Err(MetricsError::Size { frame: (4, 4), reference: (4, 5) })
        );
        assert_eq!(error_metrics(&a, &a, Layer::Diffuse, 0.0), Err(MetricsError::MissingLayer { layer: "diffuse", which: "frame" }));
    }

    #[test]
    fn quantiles_by_rank() {
        let v: Vec<f32> = (0..=100).rev().map(|i| i as f32).collect();
        assert_eq!((quantile(&v, 0.0), quantile(&v, 0.5), quantile(&v, 0.99), quantile(&v, 1.0)), (0.0, 50.0, 99.0, 100.0));
        assert_eq!(quantile(&[], 0.5), 0.0);
        assert_eq!(quantile(&[f32::NAN, 2.0], 1.0), 2.0);
    }

    #[test]
    fn heatmap_maps_zero_to_black_and_scale_to_the_top() {
        let reference = flat(3, 1, Vec3::splat(0.5));
        let mut frame = reference.clone();
        frame.layers[0].1[1].z += 0.05;
        frame.layers[0].1[2].x -= 0.5;
        let heat = error_heatmap(&frame, &reference, Layer::Total, 0.1).unwrap();
        assert_eq!(heat.get_pixel(0, 0).0, INFERNO[0]);
        // Half the scale lands between the middle stops (4/9 and 5/9): a reddish purple-orange.
        let mid = heat.get_pixel(1, 0).0;
        assert_eq!(mid, heat_colour(0.5));
        assert!(mid[0] > mid[2] && mid[0] > 150, "{mid:?}");
        assert_eq!(heat.get_pixel(2, 0).0, INFERNO[9]);
        // The ramp is monotonic in luminance-ish brightness: each stop's channel sum grows.
        let sums: Vec<u32> = (0..=90).map(|k| heat_colour(k as f32 / 90.0).iter().map(|&c| c as u32).sum()).collect();
        assert!(sums.windows(2).all(|w| w[0] <= w[1]), "{sums:?}");
    }
}
