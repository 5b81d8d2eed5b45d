//! Tests of [`Brdf::sample`] and [`Brdf::pdf`] against each other and against `eval`, after
//! pbrt-v4's `bsdfs_test.cpp` (its χ² test `Chi2Test`) and Mitsuba 3's `chi2` module.
//!
//! For every model with several parameter sets (26: rough, smooth α = 0.01, anisotropic,
//! metal, clearcoat, every NDF and masking, narrow and n = 0 Phong lobes) and viewers at
//! θ_v = 10°, 50°, 85° (azimuth 0):
//!
//! (a) **χ² goodness of fit.** [`SAMPLES`] = 10⁶ independent samples (the project's hash, one
//!     stream per dimension, fixed seeds) are binned on a (θ, φ) grid of the upper hemisphere
//!     whose edges are graded geometrically (widths 10⁻³·2^k rad) towards the mirror direction
//!     (θ_v, φ_v + π), so narrow and wide lobes are both resolved (19–22 × 24 cells); the
//!     horizon is a cell edge, so no cell straddles the pdf's discontinuity there. A cell's
//!     expected count is N ∫_cell pdf dω by 5 × 5 Gauss-Legendre, quartered until two levels
//!     agree within 10⁻⁸ (depth ≤ 6). As in pbrt-v4, cells are sorted by expected count, those
//!     below [`MIN_EXPECTED`] = 5 are pooled (until the pool reaches 5), more than 10⁻⁵ N samples
//!     in cells of expected count 0 fail at once, and the statistic, with dof = cells − 1, must
//!     have a p-value of at least the significance 0.01 Šidák-corrected for the [`CHI2_TESTS`]
//!     tests: 1 − 0.99^{1/79} = 1.27·10⁻⁴.
//! (b) **Normalization.** ∫ pdf dω over the upper hemisphere (the sum of the cells) is 1 within
//!     10⁻⁴ for mixtures that cannot lose samples (diffuse lobes only; at most 10⁻⁵ N samples may
//!     fall on the rim, u on the square's border); otherwise 1 − ∫ pdf equals the measured
//!     fraction of lost samples within z binomial standard errors + 10⁻⁴.
//! (c) **Consistency.** Every sample is a finite unit l above the surface with a finite pdf > 0;
//!     on every 8th, f equals `eval(l, v)` and the pdf `pdf(v, l)` (relative 10⁻⁴).
//! (d) **Albedo.** mean(f cos θ_l / pdf) over the 10⁶ samples (lost ones count 0) matches
//!     [`directional_albedo_rgb`] per channel within z standard errors of the mean + the
//!     quadrature's error bound + 10⁻⁶ relative (the f32 rounding of weights that are exactly ρ).
//!
//! **The bound z.** 3 standard errors is a 0.27 % test; (b) and (d) make [`COMPARISONS`] = 312
//! of them (about half independent: the channels are correlated), so at z = 3 a third to a half
//! of all sets of seeds would fail somewhere by chance (the first one here did:
//! a 3.56σ lost fraction and a 3.83σ albedo, both back within 1σ with 8·10⁶ samples). As for
//! χ², the bound is Šidák-corrected to an overall significance of 0.01: z = 4.16 standard
//! errors. A bias still fails it once it exceeds 4.16 × 10⁻³ of the standard deviation of the weights.
//!
//! Measured (run with `--nocapture` for the table): all p-values at 10⁶ samples lie between 0.003
//! and 0.996; a run at 8·10⁶ samples gave p-values spread uniformly (6 of 78 below 0.1). The
//! per-dimension streams matter: `hash3(k, seed, dim)` with dim = 0, 1, 2 gives correlated
//! streams that fail correct samplers at 8·10⁶ samples.

use super::brdf::{Brdf, directional_albedo_rgb};
use super::cook_torrance::CookTorrance;
use super::diffuse::Diffuse;
use super::lobe::LobeKind;
use super::microfacet::{Fresnel, Masking, Ndf};
use super::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use super::oren_nayar::{OrenNayar, OrenNayarModel};
use super::principled::Principled;
use crate::geometry::sampling::{hash, hash3};
use glam::{DVec3, Vec2, Vec3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Samples per case.
const SAMPLES: u32 = 1_000_000;
/// Cells with fewer expected samples are pooled.
const MIN_EXPECTED: f64 = 5.0;
/// Overall significance of all the χ² tests together.
const SIGNIFICANCE: f64 = 0.01;
/// Number of χ² tests run in this module (for the Šidák correction).
const CHI2_TESTS: usize = 26 * VIEW_ANGLES.len() + 1;
/// The viewers' polar angles (degrees), at azimuth 0.
const VIEW_ANGLES: [f32; 3] = [10.0, 50.0, 85.0];
/// Number of z-tests in (b) and (d): one lost fraction and three albedo channels per case.
const COMPARISONS: usize = 4 * 26 * VIEW_ANGLES.len();

/// The two-sided normal bound z with P(|Z| > z) = the Šidák-corrected level of one of the
/// [`COMPARISONS`] z-tests (P(|Z| > z) = Q(½, z²/2), by bisection).
fn z_bound() -> f64 {
    let level = 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / COMPARISONS as f64);
    let (mut lo, mut hi) = (0.0f64, 10.0f64);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if gamma_q(0.5, 0.5 * mid * mid) > level { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// A unit direction from polar angle θ and azimuth φ.
pub(super) fn dir(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
}

/// An independent uniform in [0, 1) from the project's hash: sample `k`, stream `seed`, dimension `dim`.
pub(super) fn uniform(k: u32, seed: u32, dim: u32) -> f32 {
    // Each dimension gets its own hashed stream word: hash3(k, seed, dim) with consecutive small
    // `dim` gives streams correlated enough (they differ only before the last of its three
    // rounds) for the χ² test to reject correct samplers at 8·10⁶ samples.
    let stream = hash(seed ^ (dim + 1).wrapping_mul(0x9e37_79b9));
    (hash3(k, stream, 0x2545_f491) >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// Panel edges in [lo, hi] graded geometrically towards `center`: center ± 1e-3·2^k.
fn graded(lo: f64, hi: f64, center: f64) -> Vec<f64> {
    let mut e = vec![lo, hi];
    if center > lo && center < hi {
        e.push(center);
    }
    let mut w = 1e-3;
    while w < hi - lo {
        for x in [center - w, center + w] {
            if x > lo && x < hi {
                e.push(x);
            }
        }
        w *= 2.0;
    }
    e.sort_by(f64::total_cmp);
    e.dedup();
    e
}

/// The χ² grid for viewer `v`: θ edges on [0, π/2], φ edges on [0, 2π), graded towards the mirror direction.
struct Grid {
    theta: Vec<f64>,
    phi: Vec<f64>,
}

impl Grid {
    fn new(v: Vec3) -> Grid {
        let theta_v = (v.x.hypot(v.y) as f64).atan2(v.z as f64);
        let phi_mirror = ((v.y as f64).atan2(v.x as f64) + PI).rem_euclid(TAU);
        Grid { theta: graded(0.0, FRAC_PI_2, theta_v), phi: graded(0.0, TAU, phi_mirror) }
    }

    fn cells(&self) -> usize {
        (self.theta.len() - 1) * (self.phi.len() - 1)
    }

    /// The cell holding direction `l` (l.z > 0).
    fn cell_of(&self, l: Vec3) -> usize {
        let (l, nphi) = (l.as_dvec3(), self.phi.len() - 1);
        let theta = l.x.hypot(l.y).atan2(l.z);
        let phi = l.y.atan2(l.x).rem_euclid(TAU);
        let find = |e: &[f64], x: f64| e.partition_point(|&b| b <= x).clamp(1, e.len() - 1) - 1;
        find(&self.theta, theta) * nphi + find(&self.phi, phi)
    }
}

/// Gauss-Legendre nodes and weights on [−1, 1], 5 points.
const GL5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// ∫∫ pdf(l(θ, φ)) sin θ dθ dφ over the cell [θ0, θ1] × [φ0, φ1] by the 5 × 5 Gauss-Legendre rule.
fn gl_cell(pdf: &dyn Fn(Vec3) -> f64, [t0, t1, p0, p1]: [f64; 4]) -> f64 {
    let mut sum = 0.0;
    for &(xt, wt) in &GL5 {
        let t = 0.5 * (t1 - t0) * xt + 0.5 * (t1 + t0);
        let (st, ct) = t.sin_cos();
        for &(xp, wp) in &GL5 {
            let p = 0.5 * (p1 - p0) * xp + 0.5 * (p1 + p0);
            let (sp, cp) = p.sin_cos();
            let l = Vec3::new((st * cp) as f32, (st * sp) as f32, ct as f32);
            sum += wt * wp * pdf(l) * st;
        }
    }
    sum * 0.25 * (t1 - t0) * (p1 - p0)
}

/// The cell integral, refined by quartering until two levels agree within `tol` (absolute);
/// `coarse` is the cell's own [`gl_cell`].
fn adaptive_cell(pdf: &dyn Fn(Vec3) -> f64, cell: [f64; 4], coarse: f64, tol: f64, depth: u32) -> f64 {
    let [t0, t1, p0, p1] = cell;
    let (tm, pm) = (0.5 * (t0 + t1), 0.5 * (p0 + p1));
    let quads = [[t0, tm, p0, pm], [t0, tm, pm, p1], [tm, t1, p0, pm], [tm, t1, pm, p1]];
    let parts = quads.map(|q| gl_cell(pdf, q));
    let fine: f64 = parts.iter().sum();
    if depth == 0 || (fine - coarse).abs() <= tol {
        return fine;
    }
    quads.iter().zip(parts).map(|(&q, part)| adaptive_cell(pdf, q, part, 0.25 * tol, depth - 1)).sum()
}

/// N ∫_cell pdf dω for every cell of `grid` (adaptive to 1e-8 per cell, depth ≤ 6).
fn expected_counts(grid: &Grid, pdf: &dyn Fn(Vec3) -> f64, n: f64) -> Vec<f64> {
    let mut expected = Vec::with_capacity(grid.cells());
    for t in grid.theta.windows(2) {
        for p in grid.phi.windows(2) {
            let cell = [t[0], t[1], p[0], p[1]];
            expected.push(n * adaptive_cell(pdf, cell, gl_cell(pdf, cell), 1e-8, 6));
        }
    }
    expected
}

/// ln Γ(x) for x > 0 (Lanczos, g = 7, 9 terms; relative error ~1e-15).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, &c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (TAU).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// The upper regularized incomplete gamma function Q(a, x) (series below a + 1, continued
/// fraction above; Numerical Recipes §6.2): the χ² p-value is Q(dof/2, χ²/2).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let front = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut sum, mut term, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * front
    } else {
        // Lentz's method for the continued fraction.
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-15 {
                break;
            }
        }
        front * h
    }
}

/// The χ² statistic of observed against expected counts with pbrt-v4's pooling: (χ², dof),
/// or an error when samples fall where none are expected.
fn chi2(observed: &[f64], expected: &[f64], n: f64) -> Result<(f64, usize), String> {
    let mut order: Vec<usize> = (0..observed.len()).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let (mut pooled_obs, mut pooled_exp, mut chsq, mut dof) = (0.0, 0.0, 0.0, 0usize);
    for i in order {
        let (o, e) = (observed[i], expected[i]);
        if e <= 0.0 {
            if o > n * 1e-5 {
                return Err(format!("{o} samples in a cell with expected count 0"));
            }
        } else if e < MIN_EXPECTED || (pooled_exp > 0.0 && pooled_exp < MIN_EXPECTED) {
            pooled_obs += o;
            pooled_exp += e;
        } else {
            chsq += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pooled_exp > 0.0 || pooled_obs > 0.0 {
        chsq += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp.max(1e-300);
        dof += 1;
    }
    // All parameters are known: no further reduction of the degrees of freedom.
    if dof < 2 {
        return Err(format!("too few degrees of freedom ({dof})"));
    }
    Ok((chsq, dof - 1))
}

/// The measured statistics of one case, for the printed table.
struct Stats {
    chi2: f64,
    dof: usize,
    p_value: f64,
    lost: f64,
    integral: f64,
    albedo_mc: DVec3,
    albedo_quadrature: DVec3,
    z_score: f64,
}

/// Runs tests (a)–(d) for `brdf` seen from `v` (azimuth 0 for the albedo check): the failures
/// as messages, and the statistics.
fn check_sampling(name: &str, brdf: &Brdf, v: Vec3, seed: u32) -> (Vec<String>, Stats) {
    let mut fail = Vec::new();
    let grid = Grid::new(v);
    let n = SAMPLES;
    let mut observed = vec![0.0f64; grid.cells()];
    let (mut lost, mut sum, mut sum2) = (0u32, DVec3::ZERO, DVec3::ZERO);
    for k in 0..n {
        let u = Vec2::new(uniform(k, seed, 1), uniform(k, seed, 2));
        let Some(s) = brdf.sample(v, uniform(k, seed, 0), u) else {
            lost += 1;
            continue;
        };
        // (c) consistency with eval and pdf (every 8th sample: they cost as much as sampling);
        // a unit direction above the surface.
        let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * a.abs().max(b.abs());
        let consistent = k % 8 != 0 || {
            let (f, p) = (brdf.eval(s.l, v), brdf.pdf(v, s.l));
            close(s.f.x, f.x) && close(s.f.y, f.y) && close(s.f.z, f.z) && close(s.pdf, p) && s.kind == brdf.lobes().as_slice()[s.lobe].kind
        };
        let valid = s.l.z > 0.0 && (s.l.length() - 1.0).abs() < 1e-5 && s.f.is_finite() && s.pdf.is_finite() && s.pdf > 0.0;
        if !valid || !consistent || s.delta {
            if fail.len() < 5 {
                fail.push(format!("{name}: sample {k} inconsistent: {s:?}, eval {}, pdf {}", brdf.eval(s.l, v), brdf.pdf(v, s.l)));
            }
            continue;
        }
        observed[grid.cell_of(s.l)] += 1.0;
        let w = s.weight().as_dvec3();
        sum += w;
        sum2 += w * w;
    }
    // Expected counts: N ∫_cell pdf dω; their sum over N is ∫ pdf over the hemisphere.
    let expected = expected_counts(&grid, &|l| brdf.pdf(v, l) as f64, n as f64);
    let integral = expected.iter().sum::<f64>() / n as f64;
    // (b) the integral of the pdf against the fraction of lost samples.
    let lost_fraction = lost as f64 / n as f64;
    let can_lose = brdf.lobes().as_slice().iter().any(|l| l.kind == LobeKind::Glossy && l.weight != Vec3::ZERO);
    if can_lose {
        let q = lost_fraction.max(1.0 - integral).clamp(1.0 / n as f64, 1.0);
        let bound = z_bound() * (q * (1.0 - q) / n as f64).sqrt() + 1e-4;
        if ((1.0 - integral) - lost_fraction).abs() > bound {
            fail.push(format!(
                "{name}: 1 − ∫pdf = {:.6} but {lost_fraction:.6} of the samples were lost (bound {bound:.2e})",
                1.0 - integral
            ));
        }
    } else if lost_fraction > 1e-5 || (integral - 1.0).abs() > 1e-4 {
        // Only u on the border of the square (probability 2⁻²³) gives l.z = 0, a pdf of 0.
        fail.push(format!("{name}: ∫pdf = {integral:.6}, {lost} samples lost (want 1 and none)"));
    }
    // (a) χ².
    let (chsq, dof, p_value) = match chi2(&observed, &expected, n as f64) {
        Ok((chsq, dof)) => {
            let p = gamma_q(dof as f64 / 2.0, chsq / 2.0);
            let level = 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / CHI2_TESTS as f64);
            if p.is_nan() || p < level {
                fail.push(format!("{name}: χ² = {chsq:.1} with {dof} dof, p = {p:.2e} < {level:.2e}"));
            }
            (chsq, dof, p)
        }
        Err(e) => {
            fail.push(format!("{name}: {e}"));
            (f64::NAN, 0, f64::NAN)
        }
    };
    // (d) the albedo against the quadrature (viewer at azimuth 0).
    let mean = sum / n as f64;
    let variance = (sum2 / n as f64 - mean * mean).max(DVec3::ZERO);
    let se = (variance / n as f64).powf(0.5);
    let (want, quad_err) = directional_albedo_rgb(brdf, v.z as f64, 8);
    let z = ((mean - want).abs() / (se + quad_err + 1e-6 * want).max(DVec3::splat(1e-300))).max_element();
    // 1e-6 relative: the f32 rounding of the weights (exactly ρ for Lambert, where se = 0).
    if ((mean - want).abs() - (z_bound() * se + quad_err + 1e-6 * want)).max_element() > 0.0 {
        fail.push(format!("{name}: albedo {mean} by sampling, {want} ± {quad_err} by quadrature, standard error {se}"));
    }
    let stats = Stats { chi2: chsq, dof, p_value, lost: lost_fraction, integral, albedo_mc: mean, albedo_quadrature: want, z_score: z };
    (fail, stats)
}

/// Runs [`check_sampling`] for every case at every view angle, prints the table and fails with all messages.
fn run(cases: &[(&str, Brdf)]) {
    let mut failures = Vec::new();
    for (c, (name, brdf)) in cases.iter().enumerate() {
        for (a, &deg) in VIEW_ANGLES.iter().enumerate() {
            let v = dir(deg.to_radians(), 0.0);
            let label = format!("{name} θv={deg}°");
            let (fail, s) = check_sampling(&label, brdf, v, hash3(c as u32, a as u32, 0x5a3c_1e77));
            eprintln!(
                "{label:<44} χ² {:>8.1} dof {:>3} p {:.3}  lost {:.5} ∫pdf {:.5}  albedo {:.5} (quadrature {:.5}, |z| {:.2})",
                s.chi2,
                s.dof,
                s.p_value,
                s.lost,
                s.integral,
                s.albedo_mc.max_element(),
                s.albedo_quadrature.max_element(),
                s.z_score
            );
            failures.extend(fail);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn chi2_diffuse_and_oren_nayar() {
    run(&[
        ("diffuse", Brdf::Diffuse(Diffuse { albedo: Vec3::new(0.8, 0.5, 0.2) })),
        ("oren_nayar full σ=30°", Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::splat(0.7), 30.0, OrenNayarModel::Full))),
        ("oren_nayar qualitative σ=60°", Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::splat(0.9), 60.0, OrenNayarModel::Qualitative))),
    ]);
}

/// The Cook-Torrance cases: every NDF, every masking, Lambert base or not, rough and smooth, metal.
fn cook_torrance_cases() -> Vec<(&'static str, Brdf)> {
    let ct = |ndf, masking, alpha, diffuse: f32, fresnel| {
        Brdf::CookTorrance(CookTorrance { ndf, masking, fresnel, alpha, specular: Vec3::ONE, diffuse: Vec3::splat(diffuse) })
    };
    let schlick = Fresnel::default();
    let gold = Fresnel::Conductor { eta: Vec3::new(0.143, 0.374, 1.442), k: Vec3::new(3.983, 2.386, 1.603) };
    vec![
        ("ct ggx smith α=0.5 + lambert", ct(Ndf::Ggx, Masking::Smith, 0.5, 0.4, schlick)),
        ("ct ggx smith α=0.01", ct(Ndf::Ggx, Masking::Smith, 0.01, 0.0, schlick)),
        ("ct ggx correlated α=0.2 gold", ct(Ndf::Ggx, Masking::SmithCorrelated, 0.2, 0.0, gold)),
        ("ct ggx correlated α=1", ct(Ndf::Ggx, Masking::SmithCorrelated, 1.0, 0.0, Fresnel::None)),
        ("ct ggx v-cavity α=0.3 + lambert", ct(Ndf::Ggx, Masking::CookTorrance, 0.3, 0.2, Fresnel::Dielectric { eta: 1.5 })),
        ("ct beckmann smith α=0.3 + lambert", ct(Ndf::Beckmann, Masking::Smith, 0.3, 0.3, schlick)),
        ("ct beckmann v-cavity α=0.01", ct(Ndf::Beckmann, Masking::CookTorrance, 0.01, 0.0, Fresnel::None)),
        ("ct blinn smith α=0.3", ct(Ndf::Blinn, Masking::Smith, 0.3, 0.0, gold)),
        ("ct blinn correlated α=0.01", ct(Ndf::Blinn, Masking::SmithCorrelated, 0.01, 0.0, Fresnel::None)),
        ("ct gaussian smith α=0.3 + lambert", ct(Ndf::Gaussian, Masking::Smith, 0.3, 0.1, schlick)),
        ("ct gaussian v-cavity α=1", ct(Ndf::Gaussian, Masking::CookTorrance, 1.0, 0.0, Fresnel::None)),
    ]
}

#[test]
fn chi2_cook_torrance() {
    run(&cook_torrance_cases());
}

/// The principled cases: dielectric, metal, anisotropic, clearcoat with sheen and subsurface, smooth.
fn principled_cases() -> Vec<(&'static str, Brdf)> {
    let p = Principled::default();
    let gold = Vec3::new(1.0, 0.71, 0.29);
    vec![
        ("principled default", Brdf::Principled(p)),
        ("principled metal r=0.3", Brdf::Principled(Principled { metallic: 1.0, roughness: 0.3, base_color: gold, ..p })),
        (
            "principled anisotropic 0.8",
            Brdf::Principled(Principled { metallic: 1.0, roughness: 0.5, anisotropic: 0.8, base_color: gold, ..p }),
        ),
        (
            "principled clearcoat+sheen+subsurface",
            Brdf::Principled(Principled {
                roughness: 0.6,
                clearcoat: 1.0,
                clearcoat_gloss: 0.5,
                sheen: 1.0,
                subsurface: 0.5,
                base_color: Vec3::new(0.2, 0.3, 0.8),
                ..p
            }),
        ),
        ("principled r=0.1 half metal", Brdf::Principled(Principled { roughness: 0.1, metallic: 0.5, specular_tint: 1.0, ..p })),
        ("principled black, clearcoat only", Brdf::Principled(Principled { base_color: Vec3::ZERO, specular: 0.0, clearcoat: 1.0, ..p })),
    ]
}

#[test]
fn chi2_principled() {
    run(&principled_cases());
}

/// The normalized Phong and Blinn-Phong cases: medium, needle (n = 1000), and n = 0 lobes.
fn phong_cases() -> Vec<(&'static str, Brdf)> {
    let (d, s) = (Vec3::new(0.3, 0.2, 0.1), Vec3::splat(0.6));
    vec![
        ("phong n=32", Brdf::NormalizedPhong(NormalizedPhong { diffuse: d, specular: s, shininess: 32.0 })),
        ("phong n=1000 no diffuse", Brdf::NormalizedPhong(NormalizedPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess: 1000.0 })),
        ("phong n=0", Brdf::NormalizedPhong(NormalizedPhong { diffuse: d, specular: s, shininess: 0.0 })),
        ("blinn_phong n=32", Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: d, specular: s, shininess: 32.0 })),
        (
            "blinn_phong n=1000 no diffuse",
            Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: Vec3::ZERO, specular: Vec3::ONE, shininess: 1000.0 }),
        ),
        ("blinn_phong n=0", Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: d, specular: s, shininess: 0.0 })),
    ]
}

#[test]
fn chi2_normalized_phong() {
    run(&phong_cases());
}

/// The anisotropic lobe seen from an azimuth off its axes (the χ² test alone: the albedo
/// quadrature assumes a viewer at azimuth 0).
#[test]
fn chi2_anisotropic_off_axis() {
    let brdf = Brdf::Principled(Principled { metallic: 1.0, roughness: 0.4, anisotropic: 1.0, ..Principled::default() });
    let v = dir(60f32.to_radians(), 0.7);
    let grid = Grid::new(v);
    let mut observed = vec![0.0; grid.cells()];
    for k in 0..SAMPLES {
        let u = Vec2::new(uniform(k, 99, 1), uniform(k, 99, 2));
        if let Some(s) = brdf.sample(v, uniform(k, 99, 0), u) {
            observed[grid.cell_of(s.l)] += 1.0;
        }
    }
    let expected = expected_counts(&grid, &|l| brdf.pdf(v, l) as f64, SAMPLES as f64);
    let (chsq, dof) = chi2(&observed, &expected, SAMPLES as f64).unwrap();
    let p = gamma_q(dof as f64 / 2.0, chsq / 2.0);
    eprintln!("principled anisotropic 1.0 off-axis φv=0.7 χ² {chsq:.1} dof {dof} p {p:.3}");
    assert!(p >= 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / CHI2_TESTS as f64), "χ² = {chsq} with {dof} dof: p = {p}");
}

/// The χ² machinery itself: a wrong pdf is rejected, the p-value function is right.
#[test]
fn chi2_rejects_a_wrong_pdf_and_p_values_are_right() {
    // The z bound of (b) and (d): P(|Z| > 4.16) = 3.2e-5 = 1 − 0.99^{1/312}.
    assert!((z_bound() - 4.157).abs() < 0.01, "{}", z_bound());
    // Q(k/2, x/2) against tabulated χ² quantiles: P(χ²₁₀ > 23.209) = 0.01, P(χ²₁ > 3.841) = 0.05.
    assert!((gamma_q(5.0, 23.209 / 2.0) - 0.01).abs() < 1e-4);
    assert!((gamma_q(0.5, 3.841 / 2.0) - 0.05).abs() < 1e-4);
    assert!((gamma_q(50.0, 50.0) - 0.4811).abs() < 1e-3);
    // Cosine samples binned against a uniform-hemisphere pdf: rejected.
    let v = dir(0.5, 0.0);
    let grid = Grid::new(v);
    let mut observed = vec![0.0; grid.cells()];
    let n = 100_000;
    for k in 0..n {
        if let Some(l) = super::lobe::sample_cosine(Vec2::new(uniform(k, 5, 1), uniform(k, 5, 2))) {
            observed[grid.cell_of(l)] += 1.0;
        }
    }
    let expected = expected_counts(&grid, &|_| 1.0 / TAU, n as f64);
    let (chsq, dof) = chi2(&observed, &expected, n as f64).unwrap();
    assert!(gamma_q(dof as f64 / 2.0, chsq / 2.0) < 1e-10, "χ² = {chsq}, dof {dof}");
}

/// Every model used by the tests above, with extra degenerate ones.
pub(super) fn all_cases() -> Vec<(&'static str, Brdf)> {
    let mut all = vec![
        ("diffuse", Brdf::Diffuse(Diffuse { albedo: Vec3::new(0.8, 0.5, 0.2) })),
        ("oren_nayar", Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::splat(0.7), 30.0, OrenNayarModel::Full))),
        ("oren_nayar qualitative", Brdf::OrenNayar(OrenNayar::from_degrees(Vec3::splat(0.7), 80.0, OrenNayarModel::Qualitative))),
        ("ct α=0", Brdf::CookTorrance(CookTorrance { alpha: 0.0, diffuse: Vec3::splat(0.5), ..CookTorrance::default() })),
        ("ct v-cavity α=0", Brdf::CookTorrance(CookTorrance { alpha: 0.0, masking: Masking::CookTorrance, ..CookTorrance::default() })),
        ("principled r=0", Brdf::Principled(Principled { roughness: 0.0, clearcoat: 1.0, sheen: 1.0, ..Principled::default() })),
        ("phong n=1e6", Brdf::NormalizedPhong(NormalizedPhong { shininess: 1e6, ..NormalizedPhong::default() })),
        ("blinn_phong n=1e6", Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { shininess: 1e6, ..NormalizedBlinnPhong::default() })),
    ];
    for ndf in Ndf::ALL {
        for masking in Masking::ALL {
            for alpha in [0.0, 0.4] {
                all.push(("ct every ndf and masking", Brdf::CookTorrance(CookTorrance { ndf, masking, alpha, ..CookTorrance::default() })));
            }
        }
    }
    all.extend(cook_torrance_cases());
    all.extend(principled_cases());
    all.extend(phong_cases());
    all
}
