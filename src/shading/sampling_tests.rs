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
use super::lobe::{LobeKind, Part};
use super::microfacet::{Fresnel, Masking, Ndf};
use super::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use super::oren_nayar::{OrenNayar, OrenNayarModel};
use super::physical::Lobes;
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
fn dir(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
}

/// An independent uniform in [0, 1) from the project's hash: sample `k`, stream `seed`, dimension `dim`.
fn uniform(k: u32, seed: u32, dim: u32) -> f32 {
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
fn all_cases() -> Vec<(&'static str, Brdf)> {
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

/// The old body of `physical::eval_lobes`, kept verbatim: [`Brdf::eval_parts`] must give its bits.
fn eval_lobes_before(brdf: &Brdf, l: Vec3, v: Vec3) -> Lobes {
    use std::f32::consts::FRAC_1_PI;
    if l.z <= 0.0 || v.z <= 0.0 {
        return Lobes::default();
    }
    match brdf {
        Brdf::Diffuse(_) | Brdf::OrenNayar(_) => Lobes { diffuse: brdf.eval(l, v), specular: Vec3::ZERO },
        Brdf::CookTorrance(m) => Lobes { diffuse: m.eval_diffuse(l, v), specular: m.eval_specular(l, v) },
        Brdf::Principled(m) => {
            let p = m.eval_lobes(l, v);
            Lobes { diffuse: p.diffuse + p.sheen, specular: p.specular + p.clearcoat }
        }
        Brdf::NormalizedPhong(m) => {
            Lobes { diffuse: m.diffuse * FRAC_1_PI, specular: m.specular * super::normalized_phong::phong_lobe(l, v, m.shininess) }
        }
        Brdf::NormalizedBlinnPhong(m) => {
            Lobes { diffuse: m.diffuse * FRAC_1_PI, specular: m.specular * super::normalized_phong::blinn_phong_lobe(l, v, m.shininess) }
        }
    }
}

/// A random unit direction (either hemisphere), sometimes grazing or at the pole.
fn random_dir(k: u32, seed: u32) -> Vec3 {
    match k % 7 {
        0 => Vec3::Z,
        1 => dir(std::f32::consts::FRAC_PI_2 - 1e-6 * uniform(k, seed, 3), TAU as f32 * uniform(k, seed, 4)),
        _ => {
            let z = 2.0 * uniform(k, seed, 3) - 1.0;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = TAU as f32 * uniform(k, seed, 4);
            Vec3::new(r * phi.cos(), r * phi.sin(), z)
        }
    }
}

/// (e) The parts: eval_parts is bit for bit the old eval_lobes (so the frame's layers are
/// unchanged); eval_part picks its fields; the parts sum to eval.
#[test]
fn parts_are_the_old_eval_lobes_bit_for_bit_and_sum_to_eval() {
    let bits = |x: Lobes| [x.diffuse.to_array(), x.specular.to_array()].map(|a| a.map(f32::to_bits));
    for (name, brdf) in all_cases() {
        for k in 0..20_000 {
            let (l, v) = (random_dir(k, 1), random_dir(k, 2));
            let parts = brdf.eval_parts(l, v);
            assert_eq!(bits(parts), bits(eval_lobes_before(&brdf, l, v)), "{name}: l={l} v={v}");
            assert_eq!(brdf.eval_part(Part::Diffuse, l, v).to_array().map(f32::to_bits), parts.diffuse.to_array().map(f32::to_bits));
            assert_eq!(brdf.eval_part(Part::Specular, l, v).to_array().map(f32::to_bits), parts.specular.to_array().map(f32::to_bits));
            let (sum, f) = (parts.diffuse + parts.specular, brdf.eval(l, v));
            // Exact but for the principled model, whose eval adds its sub-lobes in another order.
            let tolerance = if matches!(brdf, Brdf::Principled(_)) { 1e-6 * f.max_element() } else { 0.0 };
            assert!((sum - f).abs().max_element() <= tolerance, "{name}: {sum} vs {f} at l={l} v={v}");
        }
    }
}

/// (e) The weights: the documented albedo estimates, the diffuse weight of cook_torrance is its
/// ρ (radiosity's current 0 would fail here), a lobe of weight 0 has f = 0, and the kinds.
#[test]
fn lobe_weights_are_the_documented_estimates() {
    let rho = Vec3::new(0.5, 0.25, 0.125);
    let ct = Brdf::CookTorrance(CookTorrance { diffuse: rho, ..CookTorrance::default() });
    assert_eq!(ct.lobes().weight(Part::Diffuse), rho, "cook_torrance's Lambert base is its diffuse reflectance");
    assert_ne!(ct.lobes().weight(Part::Diffuse), Vec3::ZERO);
    let f_avg = 0.04 + 0.96 / 21.0;
    assert!((ct.lobes().weight(Part::Specular) - Vec3::splat(f_avg)).abs().max_element() < 1e-7);
    assert_eq!(ct.lobes().as_slice().iter().map(|l| l.kind).collect::<Vec<_>>(), [LobeKind::Diffuse, LobeKind::Glossy]);

    // Principled: diffuse (1 − m)(C + sheen C_sheen s̄), specular C_spec0 + (1 − C_spec0)/21, clearcoat 0.25 cc F̄.
    let p = Principled { metallic: 0.25, sheen: 1.0, sheen_tint: 0.0, clearcoat: 0.5, ..Principled::default() };
    let lobes = Brdf::Principled(p).lobes();
    let want_d = (p.base_color + Vec3::splat(super::lobe::SHEEN_ALBEDO)) * 0.75;
    assert!((lobes.weight(Part::Diffuse) - want_d).abs().max_element() < 1e-7, "{}", lobes.weight(Part::Diffuse));
    let (_, spec0) = p.tint_and_spec0();
    let want_s = spec0 + (Vec3::ONE - spec0) / 21.0 + Vec3::splat(0.125 * f_avg);
    assert!((lobes.weight(Part::Specular) - want_s).abs().max_element() < 1e-7);
    // Split sum today takes base_color (1 − metallic) as principled's diffuse albedo: equal without sheen.
    let plain = Principled { sheen: 0.0, ..p };
    assert_eq!(Brdf::Principled(plain).lobes().weight(Part::Diffuse), plain.base_color * (1.0 - plain.metallic));

    // Every model: a part whose weight is 0 is 0 everywhere, and one with a weight is non-zero somewhere.
    for (name, brdf) in all_cases() {
        let lobes = brdf.lobes();
        assert!(lobes.as_slice().iter().all(|l| l.weight.is_finite() && l.weight.min_element() >= 0.0), "{name}");
        for part in Part::ALL {
            let mut nonzero = false;
            for k in 0..5_000 {
                let (l, v) = (random_dir(k, 3).abs(), random_dir(k, 4).abs());
                // Also the mirror pair, where needle lobes (α = 1e-12, n = 1e6) are non-zero.
                let mirror = Vec3::new(-v.x, -v.y, v.z);
                nonzero |= brdf.eval_part(part, l, v) != Vec3::ZERO || brdf.eval_part(part, mirror, v) != Vec3::ZERO;
            }
            assert_eq!(nonzero, lobes.has(part), "{name} {part:?}");
        }
    }
    // A metal has no diffuse part; a black principled dielectric without sheen neither.
    let metal = Brdf::Principled(Principled { metallic: 1.0, sheen: 1.0, ..Principled::default() });
    assert!(!metal.lobes().has(Part::Diffuse));
    let black = Brdf::Principled(Principled { base_color: Vec3::ZERO, ..Principled::default() });
    assert!(!black.lobes().has(Part::Diffuse) && black.lobes().has(Part::Specular));
}

/// Lobe choice: each lobe is drawn with its probability, and the mixture pdf uses the same ones.
#[test]
fn lobes_are_chosen_in_proportion_to_their_weights() {
    let brdf = Brdf::Principled(Principled { clearcoat: 1.0, sheen: 0.5, roughness: 0.3, ..Principled::default() });
    let lobes = brdf.lobes();
    let p = lobes.probabilities().unwrap();
    assert!((p.iter().sum::<f32>() - 1.0).abs() < 1e-6);
    let n = 300_000u32;
    let mut count = [0u32; 3];
    for k in 0..n {
        count[lobes.choose((k as f32 + 0.5) / n as f32).unwrap()] += 1;
    }
    for i in 0..3 {
        assert!((count[i] as f32 / n as f32 - p[i]).abs() < 1e-5, "{i}: {count:?} {p:?}");
    }
    // The mixture pdf is Σ P_i p_i: with the diffuse lobe's probability and cos/π known, the
    // pdf at a direction far from every glossy lobe is P_0 cos θ/π within the glossy tails.
    let v = dir(0.3, 0.0);
    let l = dir(1.2, 0.0); // back-scattering, far from the mirror direction
    let expect = p[0] * l.z / std::f32::consts::PI;
    let got = brdf.pdf(v, l);
    assert!(got >= expect && got < 1.2 * expect, "{got} vs {expect}");
    assert_eq!(lobes.choose(1.0), Some(2), "u at the top still chooses a lobe");
}

/// Degenerate inputs: roughness 0, grazing and below-horizon viewers, black materials, the
/// corners of the unit square. Everything stays finite, never NaN; None or 0 where documented.
#[test]
fn degenerate_inputs_stay_finite() {
    let corners = [0.0f32, 0.5, 1.0 - f32::EPSILON / 2.0, 1.0];
    let grazing = [1e-30f32, 1e-19, 1e-7, 1e-3];
    for (name, brdf) in all_cases() {
        // Below or in the horizon: nothing.
        for v in [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.6, 0.0, -0.8), -Vec3::Z, Vec3::new(0.0, 1.0, -0.0)] {
            assert!(brdf.sample(v, 0.5, Vec2::splat(0.5)).is_none(), "{name}: v = {v}");
            assert_eq!(brdf.pdf(v, Vec3::Z), 0.0, "{name}");
        }
        assert_eq!(brdf.pdf(Vec3::Z, Vec3::new(0.6, 0.0, -0.8)), 0.0);
        assert_eq!(brdf.pdf(Vec3::Z, Vec3::X), 0.0);
        for &c in &grazing {
            let v = Vec3::new((1.0 - c * c).sqrt(), 0.0, c).normalize();
            for &a in &corners {
                for &b in &corners {
                    for &ul in &corners {
                        let Some(s) = brdf.sample(v, ul, Vec2::new(a, b)) else { continue };
                        assert!(s.l.is_finite() && s.l.z > 0.0 && s.f.is_finite() && s.pdf.is_finite() && s.pdf > 0.0, "{name}: {s:?}");
                        assert!(s.weight().is_finite(), "{name}: {s:?}");
                    }
                }
            }
            for k in 0..2_000 {
                let u = Vec2::new(uniform(k, 8, 1), uniform(k, 8, 2));
                if let Some(s) = brdf.sample(v, uniform(k, 8, 0), u) {
                    assert!(s.f.is_finite() && s.pdf.is_finite() && s.pdf > 0.0 && s.weight().is_finite(), "{name} v.z={c}: {s:?}");
                }
                let l = random_dir(k, 9);
                let p = brdf.pdf(v, l);
                assert!(p.is_finite() && p >= 0.0, "{name} v.z={c} l={l}: {p}");
            }
        }
    }
    // Black materials: no lobe to choose, no sample, pdf 0.
    let blacks = [
        Brdf::Diffuse(Diffuse { albedo: Vec3::ZERO }),
        Brdf::OrenNayar(OrenNayar { albedo: Vec3::ZERO, ..OrenNayar::default() }),
        Brdf::CookTorrance(CookTorrance { specular: Vec3::ZERO, diffuse: Vec3::ZERO, ..CookTorrance::default() }),
        Brdf::NormalizedPhong(NormalizedPhong { diffuse: Vec3::ZERO, specular: Vec3::ZERO, shininess: 10.0 }),
        Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse: Vec3::ZERO, specular: Vec3::ZERO, shininess: 10.0 }),
    ];
    for brdf in blacks {
        assert!(brdf.lobes().probabilities().is_none() && brdf.sample(Vec3::Z, 0.5, Vec2::splat(0.5)).is_none());
        assert_eq!(brdf.pdf(Vec3::Z, Vec3::Z), 0.0);
        assert_eq!(brdf.eval(Vec3::Z, Vec3::Z), Vec3::ZERO);
    }
}

/// Roughness 0 (α clamped to ALPHA_MIN = 1e-12): every sample is the mirror direction and
/// its weight f cos/pdf is F (here 1: no masking at α → 0). With GGX every sample survives.
/// The exponential tails of Beckmann, Blinn and the Gaussian vanish within the f32 rounding of
/// l (1e-7 rad = 10⁵ α): D, hence f and pdf, are 0 at the rounded l, and such a sample is
/// dropped (`None`), consistently with `eval` there.
#[test]
fn roughness_zero_samples_the_mirror_direction() {
    for masking in Masking::ALL {
        for ndf in Ndf::ALL {
            let brdf = Brdf::CookTorrance(CookTorrance { alpha: 0.0, ndf, masking, fresnel: Fresnel::None, ..CookTorrance::default() });
            let v = dir(0.7, 0.3);
            for k in 0..64 {
                let u = Vec2::new(uniform(k, 4, 1), uniform(k, 4, 2));
                let Some(s) = brdf.sample(v, 0.5, u) else {
                    assert_ne!(ndf, Ndf::Ggx, "{masking:?} k={k}: GGX keeps every sample");
                    continue;
                };
                assert!((s.l - Vec3::new(-v.x, -v.y, v.z)).length() < 1e-5, "{ndf:?} {masking:?}: {}", s.l);
                assert!((s.weight() - Vec3::ONE).abs().max_element() < 1e-3, "{ndf:?} {masking:?}: {:?}", s.weight());
            }
        }
    }
}
