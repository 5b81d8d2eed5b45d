//! A thin tube (a line light) sampled by the solid angle it subtends.
//!
//! Seen from p, the axis a → b lies on a line at distance d from p; x is the position along
//! that line measured from the foot of the perpendicular from p, r = √(x² + d²) the distance
//! to the axis point, and θ = atan(x/d) the angle from the perpendicular (so x = d tan θ and
//! sin θ = x/r). A tube of radius R ≪ r shows the element dx as a strip of projected area
//! 2R sin φ dx, φ the angle between the axis and the way to p, and sin φ = d/r, so
//!
//! dω = 2R sin φ dx / r² = 2R d dx / r³ = (2R/d) cos θ dθ = (2R/d) d(sin θ).
//!
//! The subtended solid angle is therefore Ω = 2R (sin θ_b − sin θ_a)/d, and sampling sin θ
//! uniformly on [sin θ_a, sin θ_b] samples it exactly: every sample carries the same dω = Ω
//! (divided by the sample count), where sampling x uniformly (today's `scene::area`) gives
//! weights ∝ d/r³ that vary by (r_max/r_min)³ along a long tube. Sampling θ uniformly
//! (pdf ∝ 1/r², the equiangular form) would leave a weight ∝ cos θ = d/r, so it is not used.
//! The inverse is x = d s/√(1 − s²) for s = sin θ.
//!
//! This is the thin-tube limit of Gamito's solid-angle sampling of cylinder lights
//! (M. N. Gamito, "Solid Angle Sampling of Disk and Cylinder Lights", EGSR 2016), which
//! also counts the end caps and the exact outline; the renderer's tube model has neither.
//!
//! Accuracy: everything runs in f64, and the differences that cancel are rewritten:
//! sin θ_b − sin θ_a for x_a, x_b of one sign is d² (x_b − x_a)(x_a + x_b) / (r_a r_b (x_b r_a + x_a r_b))
//! and 1 − sin θ = d² / (r (r + x)), so a point on the line's extension (d → 0, both sines → ±1)
//! gives Ω → 0 smoothly instead of 0/0. The same one-dimensional map samples the second
//! coordinate of a spherical rectangle ([`super::spherical_rect`]), whose columns are such lines.
//!
//! Determinism: only `+ − × ÷` and `sqrt` in f64, rounded to f32 at the end: the same bits on
//! every machine and thread.

use super::spherical_rect::SolidAngleSample;
use glam::{DVec3, Vec3};

/// The interval [x0, x1] of a line at distance d > 0 from a point, parametrized by
/// s = sin θ = x/√(x² + d²): s is uniform in solid angle for a thin tube (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SineInterval {
    /// Distance from the point to the line (> 0).
    d: f64,
    /// sin θ at the interval's start.
    s0: f64,
    /// s1 − s0 ≥ 0, without cancellation.
    ds: f64,
    /// 1 − s and 1 + s at both ends, without cancellation.
    one_minus: [f64; 2],
    /// See `one_minus`.
    one_plus: [f64; 2],
}

/// √(a² + b²) by `sqrt`, which is correctly rounded on every machine (libm's `hypot` need not
/// be); the inputs come from f32, so the squares neither overflow nor underflow in f64.
#[inline]
pub(crate) fn hyp(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

/// x/√(x² + d²).
#[inline]
fn sine(d: f64, x: f64) -> f64 {
    x / hyp(x, d)
}

/// 1 − x/r and 1 + x/r with r = √(x² + d²), each from whichever form does not cancel.
#[inline]
fn one_minus_plus(d: f64, x: f64) -> (f64, f64) {
    let r = hyp(x, d);
    // r − |x| = d²/(r + |x|): the small side of 1 ∓ x/r.
    let small = d * (d / (r * (r + x.abs())));
    let large = 1.0 + x.abs() / r;
    if x > 0.0 { (small, large) } else { (large, small) }
}

/// s(b) − s(a) for a ≤ b at distance d, without cancellation when a and b have one sign.
#[inline]
pub(crate) fn sine_difference(d: f64, a: f64, b: f64) -> f64 {
    if a > 0.0 && b > 0.0 {
        let (ra, rb) = (hyp(a, d), hyp(b, d));
        // b/r_b − a/r_a = (b² r_a² − a² r_b²) / (r_a r_b (b r_a + a r_b)), and b² r_a² − a² r_b² = d² (b² − a²).
        d * (d * ((b - a) * (a + b)) / (ra * rb * (b * ra + a * rb)))
    } else if a < 0.0 && b < 0.0 {
        // Mirror: s is odd in x.
        sine_difference(d, -b, -a)
    } else {
        sine(d, b) - sine(d, a)
    }
}

impl SineInterval {
    /// The interval [x0, x1] (x0 ≤ x1) at distance `d` > 0.
    pub(crate) fn new(d: f64, x0: f64, x1: f64) -> SineInterval {
        let (m0, p0) = one_minus_plus(d, x0);
        let (m1, p1) = one_minus_plus(d, x1);
        SineInterval { d, s0: sine(d, x0), ds: sine_difference(d, x0, x1).max(0.0), one_minus: [m0, m1], one_plus: [p0, p1] }
    }

    /// s1 − s0: the interval's measure in s.
    #[inline]
    pub(crate) fn measure(&self) -> f64 {
        self.ds
    }

    /// The x whose s is the fraction `u` of the way from s0 to s1.
    ///
    /// 1 ∓ s interpolate their two positive ends, so neither cancels; the result is finite for
    /// u in [0, 1] (d > 0 keeps (1 − s)(1 + s) > 0 unless it underflows, then the end is returned).
    #[inline]
    pub(crate) fn sample(&self, u: f64) -> f64 {
        let s = self.s0 + u * self.ds;
        let lerp = |e: [f64; 2]| (1.0 - u) * e[0] + u * e[1];
        let c2 = lerp(self.one_minus) * lerp(self.one_plus);
        if c2 > 0.0 {
            self.d * s / c2.sqrt()
        } else if s > 0.0 {
            f64::MAX
        } else {
            -f64::MAX
        }
    }

    /// The fraction u at which [`Self::sample`] gives x (clamped to [0, 1]); `x0` is the interval's start.
    #[inline]
    pub(crate) fn invert(&self, x0: f64, x: f64) -> f64 {
        if self.ds > 0.0 { (sine_difference(self.d, x0, x.max(x0)) / self.ds).clamp(0.0, 1.0) } else { 0.5 }
    }
}

/// A thin tube (axis a → b, radius R) seen from a point, sampled uniformly in the solid angle
/// of its thin-tube model: every sample carries the same dω.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThinTube {
    /// The point.
    p: DVec3,
    /// The foot of the perpendicular from p on the axis line.
    foot: DVec3,
    /// Unit axis a → b.
    axis: DVec3,
    /// Positions of a and b along the axis, from the foot.
    x0: f64,
    /// See `x0`.
    x1: f64,
    /// The sine parametrization; `None` when nothing is seen (see [`ThinTube::new`]).
    interval: Option<SineInterval>,
    /// Ω = 2R (sin θ_b − sin θ_a) / max(d, R).
    solid_angle: f64,
}

impl ThinTube {
    /// The tube with axis `a` → `b` and radius `radius` seen from `p`.
    ///
    /// Degenerate views subtend nothing and give zero-weight samples: a zero-length axis,
    /// p on the axis line (d = 0: seen end-on, the thin tube shows no area), a non-finite input,
    /// or a radius ≤ 0. Inside the tube (d < R) the thin-tube model fails; Ω is evaluated at
    /// distance R (the way today's sampler clamps r to R), which keeps it below 4 sr.
    pub fn new(p: Vec3, a: Vec3, b: Vec3, radius: f32) -> ThinTube {
        let (pd, ad, bd) = (p.as_dvec3(), a.as_dvec3(), b.as_dvec3());
        let axis_vec = bd - ad;
        let len = axis_vec.length();
        let empty = ThinTube { p: pd, foot: ad, axis: DVec3::X, x0: 0.0, x1: 0.0, interval: None, solid_angle: 0.0 };
        let radius = radius as f64;
        if !(len > 0.0 && len.is_finite() && pd.is_finite() && ad.is_finite() && radius > 0.0 && radius.is_finite()) {
            return empty;
        }
        let axis = axis_vec / len;
        let to_a = ad - pd;
        // d from the cross product: accurate when p is near the line, where |to_a − (to_a·axis) axis| cancels.
        let d = to_a.cross(axis).length();
        // (d is finite: every input is.)
        if d <= 0.0 {
            return ThinTube { axis, ..empty };
        }
        let x0 = to_a.dot(axis);
        let x1 = x0 + len;
        let interval = SineInterval::new(d, x0, x1);
        let solid_angle = 2.0 * radius * interval.measure() / d.max(radius);
        ThinTube { p: pd, foot: pd + (to_a - axis * x0), axis, x0, x1, interval: Some(interval), solid_angle }
    }

    /// Ω, the solid angle of the thin-tube model (sr): the weight of every sample.
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// The axis point for u in [0, 1), uniform in the tube's solid angle, with the direction
    /// and distance from p and the weight dω = Ω (divide by the sample count); zero weight when
    /// the tube subtends nothing.
    pub fn sample(&self, u: f32) -> SolidAngleSample {
        let Some(interval) = self.interval else {
            return SolidAngleSample::empty(self.foot, self.p);
        };
        let x = interval.sample(u as f64).clamp(self.x0, self.x1);
        SolidAngleSample::towards(self.p, self.foot + self.axis * x, self.solid_angle)
    }

    /// The density of [`Self::sample`]'s points per unit length of the axis at the axis point
    /// `q`: d² / (r³ (sin θ_b − sin θ_a)); 0 when nothing is seen.
    pub fn pdf_length(&self, q: Vec3) -> f32 {
        let Some(interval) = self.interval.filter(|i| i.ds > 0.0) else {
            return 0.0;
        };
        let x = (q.as_dvec3() - self.foot).dot(self.axis);
        let r = hyp(x, interval.d);
        (interval.d * interval.d / (r * r * r) / interval.ds) as f32
    }

    /// The u in [0, 1] that [`Self::sample`] maps to the axis point nearest `q` (its inverse).
    pub fn invert(&self, q: Vec3) -> f32 {
        let Some(interval) = self.interval else {
            return 0.5;
        };
        let x = (q.as_dvec3() - self.foot).dot(self.axis).clamp(self.x0, self.x1);
        interval.invert(self.x0, x) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sobol::sobol_1d;
    use crate::geometry::test_stats::{chi2_test, independent_1d};

    /// ∫ 2R d / r³ dx over the axis by Gauss–Legendre-free brute force: the midpoint rule on
    /// 2²⁰ pieces (error ~ (L/n)² f'' ≪ 1e-9 for the cases below).
    fn quadrature(p: DVec3, a: DVec3, b: DVec3, radius: f64) -> f64 {
        let n = 1 << 20;
        let mut sum = 0.0;
        for i in 0..n {
            let q = a + (b - a) * ((i as f64 + 0.5) / n as f64);
            let l = q - p;
            let r = l.length();
            let sin_phi = l.cross((b - a).normalize()).length() / r;
            sum += 2.0 * radius * sin_phi / (r * r);
        }
        sum * (b - a).length() / n as f64
    }

    #[test]
    fn solid_angle_matches_quadrature() {
        let r = 0.01;
        for (p, a, b) in [
            (DVec3::ZERO, DVec3::new(-1.0, 1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)),
            (DVec3::new(0.3, 0.0, 0.2), DVec3::new(0.5, 2.0, -1.0), DVec3::new(3.0, 0.5, 2.0)),
            (DVec3::ZERO, DVec3::new(2.0, 0.1, 0.0), DVec3::new(5.0, 0.1, 0.0)),
            (DVec3::ZERO, DVec3::new(1.0, 5.0, 0.0), DVec3::new(1.01, 5.0, 0.0)),
        ] {
            let want = quadrature(p, a, b, r);
            let tube = ThinTube::new(p.as_vec3(), a.as_vec3(), b.as_vec3(), r as f32);
            let got = tube.solid_angle() as f64;
            assert!((got / want - 1.0).abs() < 1e-5, "{p} {a} {b}: {got} vs {want}");
        }
    }

    #[test]
    fn pdf_integrates_to_one_and_matches_the_histogram() {
        let (p, a, b) = (Vec3::new(0.2, 0.0, 0.0), Vec3::new(-3.0, 0.5, 0.0), Vec3::new(4.0, 0.5, 0.0));
        let tube = ThinTube::new(p, a, b, 0.02);
        let len = (b - a).length() as f64;
        // ∫ pdf dx over the axis by the midpoint rule.
        let n = 1 << 16;
        let integral: f64 =
            (0..n).map(|i| tube.pdf_length(a + (b - a) * ((i as f32 + 0.5) / n as f32)) as f64).sum::<f64>() * len / n as f64;
        // (Measured within 1e-10 of 1.)
        assert!((integral - 1.0).abs() < 1e-7, "∫ pdf = {integral}");
        // χ² of 64 equal-length bins against the pdf's integral over each bin.
        let bins = 64;
        let mut expected = vec![0.0; bins];
        for (i, e) in expected.iter_mut().enumerate() {
            let m = 256;
            *e = (0..m).map(|j| tube.pdf_length(a + (b - a) * (((i * m + j) as f32 + 0.5) / (bins * m) as f32)) as f64).sum::<f64>() * len
                / (bins * m) as f64;
        }
        let samples = 200_000;
        let mut observed = vec![0.0; bins];
        for k in 0..samples {
            let s = tube.sample(independent_1d(k, 41));
            let t = ((s.q - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 0.999_999);
            observed[(t * bins as f32) as usize] += 1.0;
        }
        chi2_test("thin tube", &observed, &expected.iter().map(|e| e * samples as f64).collect::<Vec<_>>());
    }

    #[test]
    fn every_sample_carries_the_same_weight_and_the_estimate_is_exact() {
        // The unoccluded solid angle Σ dω/N from any N samples is Ω exactly; today's uniform-x
        // weights 2R L sin φ / r² vary: here (p 0.1 from a 4-long tube's end) by a factor of 10⁴.
        let tube = ThinTube::new(Vec3::new(0.0, 0.1, 0.0), Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), 0.01);
        let w = tube.solid_angle();
        for k in 0..64 {
            let s = tube.sample(sobol_1d(k, 5));
            assert_eq!(s.weight, w);
            assert!((s.l.length() - 1.0).abs() < 1e-6 && s.distance > 0.0);
        }
    }

    #[test]
    fn sample_and_invert_round_trip() {
        let tube = ThinTube::new(Vec3::new(0.3, 1.0, -0.2), Vec3::new(-2.0, 0.0, 0.0), Vec3::new(2.0, 0.5, 0.0), 0.05);
        for k in 0..1000 {
            let u = independent_1d(k, 7);
            let back = tube.invert(tube.sample(u).q);
            assert!((back - u).abs() < 2e-6, "{u} → {back}");
        }
    }

    #[test]
    fn degenerate_views_are_finite_with_zero_or_bounded_weight() {
        let (a, b) = (Vec3::ZERO, Vec3::X);
        // (p, the largest Ω allowed).
        let cases = [
            (Vec3::new(-1.0, 0.0, 0.0), 0.0),    // on the extension: seen end-on, nothing
            (Vec3::new(2.0, 1e-30, 0.0), 1e-25), // just off the extension: Ω ~ d
            (Vec3::new(0.5, 0.0, 0.0), 0.0),     // on the axis itself
            (Vec3::new(0.5, 1e-3, 0.0), 4.0),    // inside the tube: bounded
            (Vec3::new(f32::NAN, 0.0, 0.0), 0.0),
            (Vec3::splat(f32::INFINITY), 0.0),
            (Vec3::new(1e30, 1e30, 0.0), 1e-25),
        ];
        for (p, max) in cases {
            let tube = ThinTube::new(p, a, b, 0.01);
            assert!((0.0..=max).contains(&tube.solid_angle()), "{p}: {}", tube.solid_angle());
            for u in [0.0, 0.5, 1.0 - 2f32.powi(-24)] {
                let s = tube.sample(u);
                let finite = s.q.is_finite() && s.l.is_finite() && !s.distance.is_nan() && s.weight.is_finite();
                assert!(finite && s.weight >= 0.0 && s.weight <= max, "{p}: {s:?}");
            }
        }
        for (a, b, r) in [(Vec3::ONE, Vec3::ONE, 0.1), (Vec3::ZERO, Vec3::X, 0.0), (Vec3::ZERO, Vec3::X, f32::NAN)] {
            let s = ThinTube::new(Vec3::Y, a, b, r).sample(0.3);
            assert_eq!(s.weight, 0.0);
            assert!(s.q.is_finite() && s.l.is_finite());
        }
        // Just off the extension Ω shrinks continuously (no 0/0): like d² within the radius
        // (Ω = 2 Δs, Δs ∝ d²), like d beyond it (Ω = 2R Δs/d).
        let w = |d: f32| ThinTube::new(Vec3::new(2.0, d, 0.0), a, b, 0.01).solid_angle() as f64;
        assert!((w(1e-3) / w(1e-4) - 100.0).abs() < 1e-2, "{} {}", w(1e-3), w(1e-4));
        assert!((w(1e-15) / w(1e-16) - 100.0).abs() < 1e-2, "{} {}", w(1e-15), w(1e-16));
        let w = |d: f32| ThinTube::new(Vec3::new(20.0, d, 0.0), a, b, 1e-6).solid_angle() as f64;
        assert!((w(1e-2) / w(1e-3) - 10.0).abs() < 1e-3, "{} {}", w(1e-2), w(1e-3));
    }

    #[test]
    fn sine_samples_converge_faster_than_uniform_ones() {
        // Lesson 19's tube (−1.5, 3, 0.3) → (1.5, 3, 0.3), R = 0.05: the relative RMSE of
        // A′ = Σ dω cos θ / N over 2000 streams (measured; the test runs 400), for R2 points
        // uniform along the axis (today) / independent sine samples / Sobol sine samples:
        //   from the floor past its end (2.5, 0, 0), N = 16: 9.0e-2 / 2.9e-2 / 2.1e-3
        //   from 0.5 below its end (1.4, 2.5, 0.3),  N = 16: 4.1e-1 / 6.0e-2 / 7.2e-3
        //                                             N = 64: 9.2e-2 / 3.1e-2 / 9.0e-4
        let (a, b, radius) = (Vec3::new(-1.5, 3.0, 0.3), Vec3::new(1.5, 3.0, 0.3), 0.05);
        let axis = b - a;
        for p in [Vec3::new(2.5, 0.0, 0.0), Vec3::new(1.4, 2.5, 0.3)] {
            let n = Vec3::Y;
            // A′ by the midpoint rule on 2²⁰ pieces of the axis.
            let m = 1 << 20;
            let want = (0..m)
                .map(|i| {
                    let q = (a + axis * ((i as f32 + 0.5) / m as f32)).as_dvec3() - p.as_dvec3();
                    let (r, l) = (q.length(), q.normalize());
                    2.0 * radius * l.cross(axis.normalize().as_dvec3()).length() / (r * r) * l.dot(n.as_dvec3()).max(0.0)
                })
                .sum::<f64>()
                * axis.length() as f64
                / m as f64;
            let tube = ThinTube::new(p, a, b, radius as f32);
            let rmse = |samples: u32, f: &dyn Fn(u32, u32) -> f64| {
                let seeds = 400;
                let sq: f64 = (0..seeds)
                    .map(|seed| {
                        let e = (0..samples).map(|k| f(k, crate::geometry::sampling::hash(seed + 1))).sum::<f64>() / samples as f64;
                        (e - want) * (e - want)
                    })
                    .sum();
                (sq / seeds as f64).sqrt() / want
            };
            let today = |k, seed| {
                let u = crate::geometry::sampling::sample_2d(k, seed).x;
                let q = (a + axis * u - p).as_dvec3();
                let (r, l) = (q.length(), q.normalize());
                let sin = l.cross(axis.normalize().as_dvec3()).length();
                2.0 * radius * axis.length() as f64 * sin / (r * r) * l.dot(n.as_dvec3()).max(0.0)
            };
            let sine = |k, seed| {
                let s = tube.sample(sobol_1d(k, seed));
                (s.weight * s.l.dot(n).max(0.0)) as f64
            };
            for samples in [16, 64] {
                let (e_today, e_sine) = (rmse(samples, &today), rmse(samples, &sine));
                assert!(e_sine < 0.1 * e_today, "{p}, N = {samples}: {e_sine:.1e} vs {e_today:.1e}");
            }
        }
    }
}
