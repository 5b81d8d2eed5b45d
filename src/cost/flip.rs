//! LDR-ꟻLIP, the perceptual difference evaluator of Andersson, Nilsson, Akenine-Möller,
//! Oskarsson, Åström and Fairchild, "ꟻLIP: A Difference Evaluator for Alternating Images"
//! (HPG 2020), in pure Rust so that it builds everywhere the crate builds (no C++, WebAssembly).
//!
//! It follows NVIDIA's reference implementation (github.com/NVlabs/flip, `src/cpp/FLIP.h`, LDR
//! path) step by step, in 32-bit floats and in the same order of operations, so the error maps
//! agree with it to float rounding:
//!
//! 1. **Colour pipeline.** sRGB → linear RGB → XYZ → YCxCz (opponent space); each channel is
//!    filtered with the contrast sensitivity function, a (sum of) Gaussian(s) in the spatial
//!    domain, separably and with clamp-to-edge borders; the result is clamped back into the
//!    linear RGB gamut, taken to L\*a\*b\*, Hunt-adjusted, compared with HyAB, and
//!    redistributed into [0, 1] (the colour error ΔEc).
//! 2. **Feature pipeline.** Edges (first derivative of a Gaussian) and points (second
//!    derivative) are detected on the luminance Y ∈ [0, 1] of both images; the larger of the
//!    two magnitude differences, normalized by √2, gives the feature error ΔEf.
//! 3. **Combination.** ΔE = ΔEc^(1 − ΔEf).

use rayon::prelude::*;
use std::f32::consts::PI;

/// Pixels per degree of the reference's default observer: 0.7 m from a 0.7 m wide monitor
/// 3840 pixels across, i.e. 3840 · π/180 ≈ 67.02 (reference `FLIP::calculatePPD`).
pub const DEFAULT_PPD: f32 = 0.7 * (3840.0 / 0.7) * (PI / 180.0);

/// Exponent of the colour difference, qc (Andersson et al. 2020, colour pipeline).
const QC: f32 = 0.7;
/// Share of cmax below which colour differences are compressed, pc.
const PC: f32 = 0.4;
/// Error that a difference of pc · cmax is mapped to, pt.
const PT: f32 = 0.95;
/// Width of the edge/point detectors in degrees, w (σ = w/2 degrees).
const GW: f32 = 0.082;
/// Exponent of the feature difference, qf.
const QF: f32 = 0.5;
/// CSF Gaussians (amplitude a, scale b) of the achromatic channel Y.
const CSF_Y: (f32, f32) = (1.0, 0.0047);
/// CSF Gaussian of the red–green channel Cx.
const CSF_CX: (f32, f32) = (1.0, 0.0053);
/// The two CSF Gaussians of the blue–yellow channel Cz.
const CSF_CZ: [(f32, f32); 2] = [(34.1, 0.04), (13.5, 0.025)];
/// Largest scale parameter b of all CSF Gaussians; it sets the spatial filter's radius.
const CSF_MAX_B: f32 = 0.04;
/// D65 reference white in XYZ (digits as the reference prints them; they round to the same f32).
#[allow(clippy::excessive_precision)]
const D65: [f32; 3] = [0.950428545, 1.0, 1.088900371];
/// Reciprocal of [`D65`], componentwise.
#[allow(clippy::excessive_precision)]
const INV_D65: [f32; 3] = [1.052156925, 1.0, 0.918357670];
/// Range the ppd is clamped to: it keeps every filter finite and the kernels a sane size.
const PPD_RANGE: (f32, f32) = (1e-3, 1e4);

/// sRGB transfer function inverted (IEC 61966-2-1), one channel.
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// 3×3 matrix times a column vector.
fn mul3(m: &[[f32; 3]; 3], v: [f32; 3]) -> [f32; 3] {
    m.map(|r| r[0] * v[0] + r[1] * v[1] + r[2] * v[2])
}

/// Linear sRGB (D65) → XYZ, the exact rational matrix the reference uses.
fn linear_to_xyz(rgb: [f32; 3]) -> [f32; 3] {
    const M: [[f32; 3]; 3] = [
        [10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0],
        [2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0],
        [1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0],
    ];
    mul3(&M, rgb)
}

/// XYZ → linear sRGB (D65).
fn xyz_to_linear(xyz: [f32; 3]) -> [f32; 3] {
    #[allow(clippy::excessive_precision)] // The reference's digits.
    const M: [[f32; 3]; 3] =
        [[3.241003275, -1.537398934, -0.498615861], [-0.969224334, 1.875930071, 0.041554224], [0.055639423, -0.204011202, 1.057148933]];
    mul3(&M, xyz)
}

/// XYZ → YCxCz, the linearized CIELAB opponent space (Andersson et al. 2020, colour pipeline).
fn xyz_to_ycxcz(xyz: [f32; 3]) -> [f32; 3] {
    let [x, y, z] = [xyz[0] * INV_D65[0], xyz[1] * INV_D65[1], xyz[2] * INV_D65[2]];
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// YCxCz → XYZ, the inverse of [`xyz_to_ycxcz`].
fn ycxcz_to_xyz(c: [f32; 3]) -> [f32; 3] {
    let y = (c[0] + 16.0) / 116.0;
    let (cx, cz) = (c[1] / 500.0, c[2] / 200.0);
    [(y + cx) * D65[0], y * D65[1], (y - cz) * D65[2]]
}

/// XYZ → CIE L\*a\*b\* (CIE 15:2004) with the D65 white.
fn xyz_to_lab(xyz: [f32; 3]) -> [f32; 3] {
    let delta = 6.0f32 / 29.0;
    let delta_sq = delta * delta;
    let delta_cube = delta * delta_sq;
    let f = |t: f32| if t > delta_cube { t.powf(1.0 / 3.0) } else { 1.0 / (3.0 * delta_sq) * t + 4.0 / 29.0 };
    let [fx, fy, fz] = [f(xyz[0] * INV_D65[0]), f(xyz[1] * INV_D65[1]), f(xyz[2] * INV_D65[2])];
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// Hunt adjustment: chroma scaled by 0.01·L\* (Andersson et al. 2020, colour pipeline, Hunt effect).
fn hunt(lab: [f32; 3]) -> [f32; 3] {
    [lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]]
}

/// HyAB distance: |ΔL| + ‖Δ(a, b)‖ (Abasi et al. 2020, as used by Andersson et al. 2020).
fn hyab(p: [f32; 3], q: [f32; 3]) -> f32 {
    let (da, db) = (p[1] - q[1], p[2] - q[2]);
    (p[0] - q[0]).abs() + (da * da + db * db).sqrt()
}

/// cmax: the qc-th power of the Hunt-adjusted HyAB distance between pure green and pure blue.
fn cmax() -> f32 {
    let lab = |rgb| hunt(xyz_to_lab(linear_to_xyz(rgb)));
    hyab(lab([0.0, 1.0, 0.0]), lab([0.0, 0.0, 1.0])).powf(QC)
}

/// CSF Gaussian in the spatial domain, a·√(π/b)·exp(−π²x²/b) (Andersson et al. 2020, colour pipeline).
fn csf_gaussian(x2: f32, (a, b): (f32, f32)) -> f32 {
    a * (PI / b).sqrt() * (-(PI * PI) * x2 / b).exp()
}

/// Separable CSF kernels: per tap, the (Y, Cx) weights and the two Cz factors. Each 2-D
/// Cz Gaussian is the outer product of √(a·√(π/b))·exp(−π²x²/b) with itself, so the
/// 1-D factors are normalized such that their 2-D sum Σ₁² + Σ₂² is 1 (reference
/// `setSpatialFilters`, misc/separatedConvolutions.pdf).
fn csf_kernels(ppd: f32) -> (usize, Vec<[f32; 2]>, Vec<[f32; 2]>) {
    let radius = (3.0 * (CSF_MAX_B / (2.0 * (PI * PI))).sqrt() * ppd).ceil() as usize;
    let (mut ycx, mut cz) = (Vec::new(), Vec::new());
    let (mut sum_ycx, mut sum_cz) = ([0.0f32; 2], [0.0f32; 2]);
    for k in 0..=2 * radius {
        let x = (k as f32 - radius as f32) * (1.0 / ppd);
        let x2 = x * x;
        let w = [csf_gaussian(x2, CSF_Y), csf_gaussian(x2, CSF_CX)];
        let root = |(a, b): (f32, f32)| (a * (PI / b).sqrt()).sqrt() * (-(PI * PI) * x2 / b).exp();
        let v = [root(CSF_CZ[0]), root(CSF_CZ[1])];
        (0..2).for_each(|c| (sum_ycx[c], sum_cz[c]) = (sum_ycx[c] + w[c], sum_cz[c] + v[c]));
        ycx.push(w);
        cz.push(v);
    }
    let norm_ycx = [1.0 / sum_ycx[0], 1.0 / sum_ycx[1]];
    let norm_cz = 1.0 / (sum_cz[0] * sum_cz[0] + sum_cz[1] * sum_cz[1]).sqrt();
    ycx.iter_mut().for_each(|w| *w = [w[0] * norm_ycx[0], w[1] * norm_ycx[1]]);
    cz.iter_mut().for_each(|v| *v = [v[0] * norm_cz, v[1] * norm_cz]);
    (radius, ycx, cz)
}

/// Edge/point detector taps [G, G′, G″] with σ = w/2 · ppd pixels: G sums to 1, the positive
/// and negative lobes of G′ and G″ to ±1 (Andersson et al. 2020, feature pipeline; reference
/// `setFeatureFilter`). An empty lobe (tiny σ) gets zero weights instead of 0/0.
fn feature_kernel(ppd: f32) -> (usize, Vec<[f32; 3]>) {
    let sd = 0.5 * GW * ppd;
    let radius = (3.0 * sd).ceil() as usize;
    let taps: Vec<[f32; 3]> = (0..=2 * radius)
        .map(|k| {
            let x = k as f32 - radius as f32;
            let g = (-(x * x) / (2.0 * sd * sd)).exp();
            [g, -x * g, (x * x / (sd * sd) - 1.0) * g]
        })
        .collect();
    let mut sums = [0.0f32; 5]; // Σg, Σg′⁺, Σg′⁻, Σg″⁺, Σg″⁻ (lobes as magnitudes).
    for t in &taps {
        sums[0] += t[0];
        for (c, v) in [(1, t[1]), (3, t[2])] {
            if v > 0.0 { sums[c] += v } else { sums[c + 1] -= v }
        }
    }
    let div = |v: f32, s: f32| if s > 0.0 { v / s } else { 0.0 };
    let lobe = |v: f32, c: usize| div(v, if v > 0.0 { sums[c] } else { sums[c + 1] });
    (radius, taps.iter().map(|t| [div(t[0], sums[0]), lobe(t[1], 1), lobe(t[2], 3)]).collect())
}

/// Horizontal pass: out(x, y) = Σₖ tap(k, src(clamp(x + k − r), y)), clamp-to-edge borders.
fn pass_x<S: Copy + Sync, const N: usize>(
    src: &[S],
    width: usize,
    radius: usize,
    tap: impl Fn(usize, S) -> [f32; N] + Sync,
) -> Vec<[f32; N]> {
    let mut out = vec![[0.0; N]; src.len()];
    out.par_chunks_mut(width).zip(src.par_chunks(width)).for_each(|(row, s)| {
        for (x, o) in row.iter_mut().enumerate() {
            for k in 0..=2 * radius {
                let t = tap(k, s[(x + k).saturating_sub(radius).min(width - 1)]);
                (0..N).for_each(|c| o[c] += t[c]);
            }
        }
    });
    out
}

/// Vertical sum at (x, y): Σₖ tap(k, mid(x, clamp(y + k − r))), clamp-to-edge borders.
fn sum_y<const N: usize, const M: usize>(
    mid: &[[f32; N]],
    (width, height): (usize, usize),
    (x, y): (usize, usize),
    radius: usize,
    tap: impl Fn(usize, &[f32; N]) -> [f32; M],
) -> [f32; M] {
    let mut acc = [0.0; M];
    for k in 0..=2 * radius {
        let t = tap(k, &mid[(y + k).saturating_sub(radius).min(height - 1) * width + x]);
        (0..M).for_each(|c| acc[c] += t[c]);
    }
    acc
}

/// Per-pixel LDR-ꟻLIP error between two sRGB-encoded images, each value in [0, 1].
///
/// `reference` and `test` are row-major, `width × height` pixels of display-encoded sRGB
/// (8-bit codes / 255). Values are clamped to [0, 1] first (NaN counts as 0); `ppd` (pixels
/// per degree of visual angle, [`DEFAULT_PPD`] for the reference's default observer) is
/// clamped to [0.001, 10 000], NaN meaning [`DEFAULT_PPD`]. Identical images give exactly 0;
/// the result is deterministic and independent of the number of rayon threads.
///
/// # Panics
///
/// If `reference.len()` or `test.len()` is not `width * height`.
pub fn flip_ldr(reference: &[[f32; 3]], test: &[[f32; 3]], width: usize, height: usize, ppd: f32) -> Vec<f32> {
    let n = width.checked_mul(height).expect("flip_ldr: width × height overflows");
    assert!(
        reference.len() == n && test.len() == n,
        "flip_ldr: {width}×{height} = {n} pixels, but the reference has {} and the test {}",
        reference.len(),
        test.len()
    );
    if n == 0 {
        return Vec::new();
    }
    let ppd = if ppd.is_nan() { DEFAULT_PPD } else { ppd.clamp(PPD_RANGE.0, PPD_RANGE.1) };
    let to_ycxcz = |img: &[[f32; 3]]| -> Vec<[f32; 3]> {
        let lin = |c: f32| srgb_to_linear(if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
        img.par_iter().map(|p| xyz_to_ycxcz(linear_to_xyz(p.map(lin)))).collect()
    };
    let (ref_ycc, test_ycc) = (to_ycxcz(reference), to_ycxcz(test));
    let dims = (width, height);

    // Colour pipeline: CSF filtering, gamut clamp, Hunt-adjusted L*a*b*, HyAB, redistribution.
    let (r, ycx, cz) = csf_kernels(ppd);
    let csf_x = |k: usize, p: [f32; 3]| [ycx[k][0] * p[0], ycx[k][1] * p[1], cz[k][0] * p[2], cz[k][1] * p[2]];
    let (ref_mid, test_mid) = (pass_x(&ref_ycc, width, r, csf_x), pass_x(&test_ycc, width, r, csf_x));
    let (c_max, pc_cmax) = (cmax(), PC * cmax());
    let mut color = vec![0.0f32; n];
    color.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let lab = |mid: &[[f32; 4]]| {
                let csf_y = |k: usize, m: &[f32; 4]| [ycx[k][0] * m[0], ycx[k][1] * m[1], cz[k][0] * m[2], cz[k][1] * m[3]];
                let f = sum_y(mid, dims, (x, y), r, csf_y);
                let rgb = xyz_to_linear(ycxcz_to_xyz([f[0], f[1], f[2] + f[3]])).map(|c| c.clamp(0.0, 1.0));
                hunt(xyz_to_lab(linear_to_xyz(rgb)))
            };
            let d = hyab(lab(&ref_mid), lab(&test_mid)).powf(QC);
            // Redistribution: [0, pc·cmax) → [0, pt), [pc·cmax, cmax] → [pt, 1].
            *out = if d < pc_cmax { d * (PT / pc_cmax) } else { PT + ((d - pc_cmax) / (c_max - pc_cmax)) * (1.0 - PT) };
        }
    });

    // Feature pipeline on Y = (Y_YCxCz + 16)/116 ∈ [0, 1], then ΔE = ΔEc^(1 − ΔEf).
    let (fr, fk) = feature_kernel(ppd);
    let feat_x = |k: usize, p: [f32; 3]| {
        let v = p[0] * (1.0 / 116.0) + 16.0 / 116.0;
        [fk[k][1] * v, fk[k][2] * v, fk[k][0] * v]
    };
    let (ref_feat, test_feat) = (pass_x(&ref_ycc, width, fr, feat_x), pass_x(&test_ycc, width, fr, feat_x));
    color.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let edge_point = |mid: &[[f32; 3]]| {
                let feat_y = |k: usize, m: &[f32; 3]| [fk[k][0] * m[0], fk[k][0] * m[1], fk[k][1] * m[2], fk[k][2] * m[2]];
                let [dx, ddx, dy, ddy] = sum_y(mid, dims, (x, y), fr, feat_y);
                ((dx * dx + dy * dy).sqrt(), (ddx * ddx + ddy * ddy).sqrt())
            };
            let ((er, pr), (et, pt)) = (edge_point(&ref_feat), edge_point(&test_feat));
            let (de, dp) = ((er - et).abs(), (pr - pt).abs());
            let fd = (std::f32::consts::FRAC_1_SQRT_2 * if de > dp { de } else { dp }).powf(QF);
            // 1 − ΔEf ≥ 0 in exact arithmetic; the guard keeps 0^negative = ∞ out of rounding.
            *out = out.powf((1.0 - fd).max(0.0)).min(1.0);
        }
    });
    color
}

/// Mean of a ꟻLIP error map (summed in f64); 0 for an empty map.
pub fn mean(errors: &[f32]) -> f32 {
    if errors.is_empty() { 0.0 } else { (errors.iter().map(|&e| f64::from(e)).sum::<f64>() / errors.len() as f64) as f32 }
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: usize = 64;
    const H: usize = 48;

    /// Integer hash of the synthetic noise (same formula as the C++ generator).
    fn hash(i: u32) -> u32 {
        let mut i = i.wrapping_mul(2_654_435_761);
        i ^= i >> 15;
        i = i.wrapping_mul(0x2c1b_3c6d);
        i ^ (i >> 12)
    }

    /// Synthetic pair `pair` (0 gradient, 1 checkerboard, 2 noise) as 8-bit codes / 255.
    fn synthetic(pair: usize, test: bool) -> Vec<[f32; 3]> {
        let cl = |v: i32| v.clamp(0, 255);
        let chk = |x: i32, y: i32| if (x.clamp(0, W as i32 - 1) / 4 + y.clamp(0, H as i32 - 1) / 4) % 2 == 1 { 215 } else { 40 };
        let px = |x: i32, y: i32| -> [i32; 3] {
            match pair {
                0 if test => [cl(x * 4 + 20), y * 5, 98],
                0 => [x * 4, y * 5, 128],
                1 if test => {
                    let s: i32 = (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy))).map(|(dx, dy)| chk(x + dx, y + dy)).sum();
                    [(s + 4) / 9; 3]
                }
                1 => [chk(x, y); 3],
                _ => [0, 1, 2].map(|c| {
                    let i = ((y * W as i32 + x) * 3 + c) as u32;
                    let v = ((hash(i) >> 8) & 255) as i32;
                    if test { cl(v + ((hash(i + 1_000_003) >> 8) & 31) as i32 - 16) } else { v }
                }),
            }
        };
        (0..H as i32).flat_map(|y| (0..W as i32).map(move |x| (x, y))).map(|(x, y)| px(x, y).map(|v| v as f32 / 255.0)).collect()
    }

    #[test]
    fn identical_images_give_zero_error() {
        for pair in 0..3 {
            let img = synthetic(pair, false);
            assert!(flip_ldr(&img, &img, W, H, DEFAULT_PPD).iter().all(|&e| e == 0.0), "pair {pair}");
        }
    }

    #[test]
    fn black_vs_white_matches_reference() {
        // Reference (NVlabs/flip v1.6 FLIP.h, 64×48 black vs white): 0.967388332 at every pixel,
        // the redistributed HyAB distance of black and white (features cancel on flat images).
        let (black, white) = (vec![[0.0; 3]; W * H], vec![[1.0; 3]; W * H]);
        let err = flip_ldr(&black, &white, W, H, DEFAULT_PPD);
        assert!(err.iter().all(|&e| (e - 0.967_388_3).abs() < 1e-5), "{:?}", &err[..4]);
    }

    #[test]
    fn bright_dot_error_is_local() {
        // A 3×3 white dot on mid grey at (32, 32) of a 64×64 image.
        let n = 64;
        let grey = vec![[0.5; 3]; n * n];
        let mut dot = grey.clone();
        (31..=33).for_each(|y| (31..=33).for_each(|x| dot[y * n + x] = [1.0; 3]));
        let err = flip_ldr(&grey, &dot, n, n, DEFAULT_PPD);
        let at = |x: usize, y: usize| err[y * n + x];
        assert!(at(32, 32) > 0.5 && at(32, 32) > 2.0 * at(38, 32) && at(38, 32) > 0.0, "{} {}", at(32, 32), at(38, 32));
        // Symmetric kernels, symmetric dot: mirrored pixels agree.
        assert!((at(26, 32) - at(38, 32)).abs() < 1e-6 && (at(32, 26) - at(32, 38)).abs() < 1e-6);
        // Beyond the CSF radius (10 px at the default ppd) from the dot's edge, exactly 0.
        for (x, y) in (0..n).flat_map(|y| (0..n).map(move |x| (x, y))) {
            if x.abs_diff(32).max(y.abs_diff(32)) > 11 {
                assert_eq!(at(x, y), 0.0, "({x}, {y})");
            }
        }
    }

    /// A pair's reference mean and three (x, y, ꟻLIP) pixels.
    type Expected = (f32, [(usize, usize, f32); 3]);

    #[test]
    #[allow(clippy::excessive_precision)] // The reference's digits.
    fn matches_reference_implementation() {
        // NVlabs/flip at 1eb247c (v1.6), built with
        //   g++ -O2 -std=c++17 -fopenmp src/cpp/tool/FLIP-tool.cpp -o flip
        // and run as `flip -r <pair>_ref.png -t <pair>_test.png -nerm` (LDR, default ppd 67.02) on
        // the PNGs of these formulas. Tool means (f32 sum): gradient 0.328188, checker 0.262234,
        // noise 0.090443. The f64 means and the pixels are from an exact-float dump of the same
        // maps through FLIP::evaluate (same loader, sRGB → linear, LDR); all 3 × 3072 pixels of
        // this implementation matched that dump bit for bit when this test was written.
        let cases: [Expected; 3] = [
            (0.328_187_64, [(0, 0, 0.250_488_55), (31, 23, 0.323_608_13), (50, 40, 0.409_324_23)]),
            (0.262_235_93, [(0, 0, 0.075_353_67), (31, 23, 0.278_441_01), (10, 5, 0.342_023_94)]),
            (0.090_443_22, [(63, 47, 0.163_504_84), (31, 23, 0.043_316_51), (10, 5, 0.110_244_04)]),
        ];
        for (pair, (ref_mean, pixels)) in cases.into_iter().enumerate() {
            let err = flip_ldr(&synthetic(pair, false), &synthetic(pair, true), W, H, DEFAULT_PPD);
            let m = mean(&err);
            assert!((m - ref_mean).abs() < 1e-3, "pair {pair}: mean {m} vs reference {ref_mean}");
            for (x, y, e) in pixels {
                assert!((err[y * W + x] - e).abs() < 1e-4, "pair {pair} ({x}, {y}): {} vs {e}", err[y * W + x]);
            }
        }
    }

    #[test]
    fn thread_count_does_not_change_bits() {
        let (a, b) = (synthetic(2, false), synthetic(2, true));
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let serial = one.install(|| flip_ldr(&a, &b, W, H, DEFAULT_PPD));
        let parallel = flip_ldr(&a, &b, W, H, DEFAULT_PPD);
        assert!(serial.iter().zip(&parallel).all(|(s, p)| s.to_bits() == p.to_bits()));
    }

    #[test]
    fn extreme_inputs_stay_in_unit_range() {
        let a: Vec<[f32; 3]> = (0..48).map(|i| [[-1e30, 2.0, 0.3], [f32::INFINITY, -0.0, f32::MAX]][i % 2]).collect();
        let b: Vec<[f32; 3]> = (0..48).map(|i| [(i as f32 * 0.37).sin() * 4.0; 3]).collect();
        for ppd in [0.0, 1e-20, 0.5, 1.7, DEFAULT_PPD, 1e9, f32::NAN] {
            let err = flip_ldr(&a, &b, 8, 6, ppd);
            assert!(err.iter().all(|e| (0.0..=1.0).contains(e)), "ppd {ppd}: {err:?}");
        }
        assert!(flip_ldr(&[], &[], 0, 5, DEFAULT_PPD).is_empty() && mean(&[]) == 0.0);
    }

    #[test]
    #[should_panic(expected = "pixels")]
    fn mismatched_lengths_panic() {
        flip_ldr(&[[0.0; 3]; 4], &[[0.0; 3]; 3], 2, 2, DEFAULT_PPD);
    }
}
