//! A rectangle sampled uniformly in the solid angle it subtends (Ureña, Fajardo & King 2013).
//!
//! C. Ureña, M. Fajardo and A. King, "An Area-Preserving Parametrization for Spherical
//! Rectangles", Computer Graphics Forum 32(4) (EGSR 2013): the parametrization and its
//! pseudocode (`SphQuadInit`, `SphQuadSample`); pbrt-v4's `SampleSphericalRectangle`
//! (`util/sampling.cpp`) is the same algorithm. In a frame with the
//! shaded point p at the origin, x and y along the rectangle's edges and the rectangle in the
//! plane at distance h > 0, the rectangle is [x0, x1] × [y0, y1], and the solid angle of its part
//! [x0, x] × [y0, y1] is Ω(x) = G(x) − G(x0), with
//!
//! G(x) = F(x, y1) − F(x, y0),  F(x, y) = atan(x y / (h √(x² + y² + h²)))
//!
//! (F is the signed solid angle of [0, x] × [0, y]; the paper writes the same through the
//! rectangle's interior angles, S = Σγᵢ − 2π, and its parameter a_u = π + G). A sample
//! (u, v) ∈ [0, 1)² is placed in two steps, each inverting a cumulative solid angle:
//! 1. x_u solves G(x_u) = G(x0) + u S. With δ = G(x_u), b0 = −y0/√(y0² + h²),
//!    b1 = y1/√(y1² + h²) and M = b0 cos δ + b1, the paper's cu/xu steps reduce to
//!    x_u = h sin δ sign(M) / √(M² − (1 − b0²) sin² δ).
//! 2. In the column x = x_u, at distance d = √(x_u² + h²), the solid angle is uniform in
//!    y/√(y² + d²) (the thin-line measure of [`super::tube`]): h_v = lerp(h0, h1, v),
//!    y_v = h_v d / √(1 − h_v²).
//!
//! The density over the solid angle is 1/S everywhere: each sample carries dω = S.
//!
//! Accuracy (everything in f64): the paper's a_u = u S + k loses S against k ≈ π when the
//! rectangle is small, and its cos/sin of a_u divide 0 by 0 at a_u = π. Here G is computed from
//! its tangent, tan G = x h Δs / (h² + x² s0 s1) with Δs = s1 − s0 written without cancellation,
//! the step-1 formula has no division by sin δ, 1 − h_v² is interpolated from its two ends
//! ([`super::tube`]), and S itself is a sum of van Oosterom–Strackee triangle solid angles,
//! tan(Ω/2) = |a·(b×c)| / (abc + (a·b)c + (a·c)b + (b·c)a) (A. van Oosterom and J. Strackee,
//! "The Solid Angle of a Plane Triangle", IEEE Trans. Biomed. Eng. 30(2), 1983), whose triple
//! products are exact products of the inputs (h × width × height for a diagonal's triangles):
//! S keeps full precision from 2π down to the smallest rectangles (`rect_solid_angle`). Tested
//! below: in f64 the warp inverts to 3e-9 from S ≈ 2π down to S ≈ 1e-12 sr; below
//! S ≈ 2.5e-8 |G(x0)| (a sliver far to the side) step 1 would lose digits, and the rectangle is
//! sampled by area with its exact weight instead (`AREA_FALLBACK`).
//!
//! Determinism: a pure function of its inputs. Besides `+ − × ÷ sqrt` it calls libm's f64
//! `atan2` and `sin`, whose last bit may differ between machines; the results are rounded to
//! f32, so that shows only for inputs within an f64 ULP of an f32 rounding boundary (as
//! [`super::sampling::sin_cos`]). Threads never change a bit.

use super::tube::{SineInterval, hyp, sine_difference};
use glam::{DVec2, DVec3, Vec2, Vec3};

/// A point q on an emitter sampled from p: the direction and distance to it and its weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidAngleSample {
    /// The sampled point.
    pub q: Vec3,
    /// Unit direction from p towards q (+z when p and q coincide).
    pub l: Vec3,
    /// |q − p|.
    pub distance: f32,
    /// dω/du, the inverse of the density in solid angle: the sample's share of the solid angle
    /// before dividing by the sample count; 0 when the emitter subtends nothing from p.
    pub weight: f32,
}

impl SolidAngleSample {
    /// A sample that carries nothing (finite fields whatever the inputs).
    pub(crate) fn empty(q: DVec3, p: DVec3) -> SolidAngleSample {
        let q = if q.is_finite() {
            q
        } else if p.is_finite() {
            p
        } else {
            DVec3::ZERO
        };
        SolidAngleSample { q: q.as_vec3(), l: Vec3::Z, distance: 0.0, weight: 0.0 }
    }

    /// The sample at q seen from p with weight `weight`; empty when q = p or anything is not finite.
    pub(crate) fn towards(p: DVec3, q: DVec3, weight: f64) -> SolidAngleSample {
        let to = q - p;
        let r = to.length();
        if !(r > 0.0 && r.is_finite() && weight.is_finite()) {
            return SolidAngleSample::empty(q, p);
        }
        SolidAngleSample { q: q.as_vec3(), l: (to / r).as_vec3(), distance: r as f32, weight: weight.max(0.0) as f32 }
    }
}

/// A rectangle seen from a point, ready to be sampled uniformly in solid angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalRect {
    /// The point p.
    o: DVec3,
    /// Unit vector along the first edge.
    x: DVec3,
    /// Unit vector along the second edge (⊥ x, in the rectangle's plane).
    y: DVec3,
    /// From p to the rectangle's plane, perpendicular to it: length h.
    to_plane: DVec3,
    /// h > 0, the distance from p to the plane.
    h: f64,
    /// The rectangle is [x0, x1] × [y0, y1] in the plane's (x, y) about p's foot.
    x0: f64,
    /// See `x0`.
    x1: f64,
    /// See `x0`.
    y0: f64,
    /// See `x0`.
    y1: f64,
    /// G(x0): step 1 solves G(x_u) = G(x0) + u S.
    g0: f64,
    /// b0 = −y0/√(y0² + h²).
    b0: f64,
    /// b0 + b1 = s(y1) − s(y0) at distance h, without cancellation.
    b_sum: f64,
    /// 1 − b0² = h²/(y0² + h²).
    one_minus_b0_sq: f64,
    /// S, the solid angle (sr); 0 when the rectangle subtends nothing.
    solid_angle: f64,
    /// Sample by area instead (the solid angle is too small for step 1's precision).
    by_area: bool,
}

/// Step 1 places x_u through δ = G(x0) + u S, whose rounding is 2⁻⁵³ |G(x0)|: below
/// S = |G(x0)| × 2.5e-8 that is more than 1e-8 of S, so a rectangle that small against its
/// strip's G (only a distant sliver far to the side, S ≲ 1e-12 sr) is sampled uniformly by area,
/// where 1/r² and the cosine hardly vary across it, with its exact weight A cos θ_q / r².
const AREA_FALLBACK: f64 = 2.5e-8;

/// The solid angle of the triangle with vertices a, b, c seen from the origin, given
/// |a·(b×c)| (van Oosterom & Strackee 1983): 2 atan2(|a·(b×c)|, abc + (a·b)c + (a·c)b + (b·c)a).
#[inline]
fn triangle_solid_angle(triple: f64, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * triple.atan2(denominator)
}

/// The solid angle of [x0, x1] × [y0, y1] in the plane at distance h > 0 from the origin, as
/// van Oosterom–Strackee triangles whose triple products are exact products of the inputs.
///
/// With the foot of the perpendicular (0, 0) inside the rectangle (or on its border), the fan of
/// four triangles from the foot (triple products h |y0| (x1 − x0) and so on), which stays exact
/// as h → 0, where a diagonal's triangles would each approach π with a denominator of noise.
/// With the foot outside, the two triangles of a diagonal (triple product h (x1 − x0)(y1 − y0)
/// each; a fan would sum angles of order 1 to a result of order h). One case keeps an error:
/// p within about 10⁻¹² (relative to the rectangle's size) of its plane *and* its foot within
/// about 10⁻¹² outside an edge, where that edge's triangle nears π; S then stays finite in [0, 2π].
#[inline]
fn rect_solid_angle(h: f64, x0: f64, x1: f64, y0: f64, y1: f64) -> f64 {
    let v = |x: f64, y: f64| DVec3::new(x, y, h);
    let (v00, v10, v11, v01) = (v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y1));
    let (w, l) = (x1 - x0, y1 - y0);
    if x0 <= 0.0 && 0.0 <= x1 && y0 <= 0.0 && 0.0 <= y1 {
        fan_triangle(h, -y0 * w, v00, v10)
            + fan_triangle(h, x1 * l, v10, v11)
            + fan_triangle(h, y1 * w, v11, v01)
            + fan_triangle(h, -x0 * l, v01, v00)
    } else {
        let triple = h * w * l;
        triangle_solid_angle(triple, v00, v10, v11) + triangle_solid_angle(triple, v00, v11, v01)
    }
}

/// The solid angle of the triangle (f, b, c) with f = (0, 0, h) the foot of the perpendicular from
/// the origin, given twice the area of its projection `cross` = |b_x c_y − b_y c_x|.
///
/// The van Oosterom–Strackee denominator is h (|b||c| + b·c) + h² (|b| + |c|) here; |b||c| + b·c
/// cancels when b and c point almost opposite ways (p close above the edge b c), so it is taken
/// as |b × c|² / (|b||c| − b·c) then.
#[inline]
fn fan_triangle(h: f64, cross: f64, b: DVec3, c: DVec3) -> f64 {
    let (lb, lc) = (b.length(), c.length());
    let dot = b.dot(c);
    let sum = if dot >= 0.0 { lb * lc + dot } else { b.cross(c).length_squared() / (lb * lc - dot) };
    2.0 * (h * cross).atan2(h * sum + h * h * (lb + lc))
}

/// G(x) = F(x, y1) − F(x, y0) from its tangent: tan G = x h Δs / (h² + x² s0 s1), s_i the sines
/// y_i/√(y_i² + x² + h²) and Δs = s1 − s0 without cancellation (both angles lie in (−π/2, π/2),
/// so atan2 of the numerator and denominator of the tangent subtraction formula gives G itself).
#[inline]
fn g(h: f64, y0: f64, y1: f64, x: f64) -> f64 {
    let d = hyp(x, h);
    let (s0, s1) = (y0 / hyp(y0, d), y1 / hyp(y1, d));
    (x * h * sine_difference(d, y0, y1)).atan2(h * h + x * x * s0 * s1)
}

/// The least corner weight of the cosine warp: keeps the density positive everywhere.
const MIN_COSINE_WEIGHT: f64 = 0.01;

/// Samples t ∈ [0, 1) with density ∝ (1 − t) a + t b (a, b ≥ 0, not both 0): the root of the
/// quadratic cumulative distribution, in the form u (a + b)/(a + √((1 − u) a² + u b²)) that does not
/// cancel (pbrt-v4 `SampleLinear`).
#[inline]
fn sample_linear(u: f64, a: f64, b: f64) -> f64 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    (u * (a + b) / (a + ((1.0 - u) * a * a + u * b * b).sqrt())).clamp(0.0, 1.0)
}

/// Samples [0, 1)² with density ∝ the bilinear interpolation of the corner values
/// w = [w(0,0), w(1,0), w(0,1), w(1,1)]: y from its marginal, then x from its conditional
/// (pbrt-v4 `SampleBilinear`).
#[inline]
fn sample_bilinear(u: DVec2, w: [f64; 4]) -> DVec2 {
    let y = sample_linear(u.y, w[0] + w[1], w[2] + w[3]);
    let x = sample_linear(u.x, (1.0 - y) * w[0] + y * w[2], (1.0 - y) * w[1] + y * w[3]);
    DVec2::new(x, y)
}

/// The density of [`sample_bilinear`] at p: 4 × bilinear(p) / Σ w.
#[inline]
fn bilinear_pdf(p: DVec2, w: [f64; 4]) -> f64 {
    let sum = w[0] + w[1] + w[2] + w[3];
    let (x, y) = (p.x, p.y);
    4.0 * ((1.0 - x) * (1.0 - y) * w[0] + x * (1.0 - y) * w[1] + (1.0 - x) * y * w[2] + x * y * w[3]) / sum
}

impl SphericalRect {
    /// The rectangle with corner `s` and edges `ex`, `ey` seen from `p`.
    ///
    /// Precondition: `ex` ⊥ `ey` (a rectangle; a parallelogram is sampled as if its second edge
    /// were the part of `ey` perpendicular to `ex`). Either side of the rectangle may face p:
    /// the solid angle is the same, and a one-sided emitter's caller tests the side once
    /// (every sample lies on the same side). Subtends nothing (zero-weight samples): a zero-
    /// length or parallel edge, p in the rectangle's plane (seen edge-on), non-finite input.
    pub fn new(p: Vec3, s: Vec3, ex: Vec3, ey: Vec3) -> SphericalRect {
        let (o, s, ex, ey) = (p.as_dvec3(), s.as_dvec3(), ex.as_dvec3(), ey.as_dvec3());
        let mut rect = SphericalRect {
            o,
            x: DVec3::X,
            y: DVec3::Y,
            to_plane: DVec3::ZERO,
            h: 0.0,
            x0: 0.0,
            x1: 0.0,
            y0: 0.0,
            y1: 0.0,
            g0: 0.0,
            b0: 0.0,
            b_sum: 0.0,
            one_minus_b0_sq: 0.0,
            solid_angle: 0.0,
            by_area: false,
        };
        let (exl, eyl) = (ex.length(), ey.length());
        if !(exl > 0.0 && eyl > 0.0 && exl.is_finite() && eyl.is_finite() && o.is_finite() && s.is_finite()) {
            return rect;
        }
        let x = ex / exl;
        let Some(normal) = x.cross(ey).try_normalize() else {
            return rect;
        };
        let y = normal.cross(x);
        let d = s - o;
        let height = d.dot(normal);
        let h = height.abs();
        rect.o = o;
        rect.x = x;
        rect.y = y;
        rect.x0 = d.dot(x);
        rect.y0 = d.dot(y);
        rect.x1 = rect.x0 + exl;
        rect.y1 = rect.y0 + eyl;
        if h <= 0.0 || h.is_nan() {
            // Edge-on: the samples (area-uniform, for finiteness) carry nothing.
            return rect;
        }
        rect.h = h;
        rect.to_plane = normal * height;
        // S ≤ 2π holds exactly (a plane's half-space); the clamp removes rounding.
        let solid_angle = rect_solid_angle(h, rect.x0, rect.x1, rect.y0, rect.y1).min(std::f64::consts::TAU);
        if !(solid_angle > 0.0 && solid_angle.is_finite()) {
            return rect;
        }
        rect.solid_angle = solid_angle;
        rect.g0 = g(h, rect.y0, rect.y1, rect.x0);
        rect.b0 = -rect.y0 / hyp(rect.y0, h);
        rect.b_sum = sine_difference(h, rect.y0, rect.y1);
        rect.one_minus_b0_sq = h / hyp(rect.y0, h) * (h / hyp(rect.y0, h));
        rect.by_area = solid_angle < AREA_FALLBACK * rect.g0.abs();
        rect
    }

    /// S, the solid angle the rectangle subtends from p (sr), in [0, 2π]; the density of
    /// [`Self::sample`] is 1/S over it (but for the by-area fallback, see [`Self::sample`]).
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// The point of the rectangle for u in [0, 1)², uniform over the solid angle, with weight S.
    ///
    /// The map is continuous and area-preserving, so stratified u (e.g. [`super::sobol::sobol_2d`])
    /// stay stratified in solid angle. When the rectangle subtends nothing, the point is
    /// s + u.x ex + u.y ey (for finiteness) with weight 0; for a rectangle too small to
    /// parametrize (see `AREA_FALLBACK`) it is that point with weight A cos θ_q / r².
    pub fn sample(&self, u: Vec2) -> SolidAngleSample {
        let (xu, yv) = self.sample_local(u.as_dvec2());
        let q = self.o + self.to_plane + self.x * xu + self.y * yv;
        if self.solid_angle == 0.0 {
            return SolidAngleSample::empty(q, self.o);
        }
        if self.by_area {
            // dω/du = A cos θ_q / r² with cos θ_q = h/r.
            let r = (q - self.o).length();
            let area = (self.x1 - self.x0) * (self.y1 - self.y0);
            return SolidAngleSample::towards(self.o, q, area * self.h / (r * r * r));
        }
        SolidAngleSample::towards(self.o, q, self.solid_angle)
    }

    /// Like [`Self::sample`], with u first warped towards the directions a receiver with unit
    /// normal `n` weights most: the density over the solid angle becomes bilinear_pdf(u′)/S,
    /// approximately ∝ cos θ (Hart et al. 2020; pbrt-v4's `BilinearPatch::Sample`).
    ///
    /// The bilinear function takes the receiver's cosine towards the four corners, raised to at
    /// least 0.01 so that no part of the rectangle gets a density of 0 (D. Hart, M. Pharr,
    /// T. Müller, W. Lopes, M. McGuire and P. Shirley, "Practical Product Sampling by Fitting and
    /// Composing Warps", CGF 39(4), EGSR 2020). The weight is S / bilinear_pdf(u′), so
    /// Σ weight · cos θ / N estimates the projected solid angle with the receiver's cosine mostly
    /// divided out. The warp is continuous and monotone, so stratification survives it.
    /// Falls back to [`Self::sample`] when the rectangle is sampled by area or subtends nothing.
    pub fn sample_cosine_weighted(&self, u: Vec2, n: Vec3) -> SolidAngleSample {
        self.cosine_weighted(n).sample(u)
    }

    /// The rectangle with the warp of [`Self::sample_cosine_weighted`] towards a receiver with
    /// unit normal `n` fitted once: its corner weights depend on the point, not on u.
    pub fn cosine_weighted(self, n: Vec3) -> CosineWeighted {
        if self.solid_angle == 0.0 || self.by_area {
            return CosineWeighted { rect: self, w: [0.0; 4] };
        }
        let n = n.as_dvec3();
        let corner = |x: f64, y: f64| {
            let d = self.to_plane + self.x * x + self.y * y;
            (n.dot(d) / d.length()).max(MIN_COSINE_WEIGHT)
        };
        // Corner (i, j) of the u-square is the rectangle's corner (x_i, y_j): u = 0 ↦ x0, y0.
        let w = [corner(self.x0, self.y0), corner(self.x1, self.y0), corner(self.x0, self.y1), corner(self.x1, self.y1)];
        CosineWeighted { rect: self, w }
    }

    /// [`Self::sample`] in the plane's coordinates (x_u, y_v), in f64.
    fn sample_local(&self, u: DVec2) -> (f64, f64) {
        if self.solid_angle == 0.0 || self.by_area {
            return (self.x0 + u.x * (self.x1 - self.x0), self.y0 + u.y * (self.y1 - self.y0));
        }
        let xu = self.column(u.x);
        let yv = SineInterval::new(hyp(xu, self.h), self.y0, self.y1).sample(u.y).clamp(self.y0, self.y1);
        (xu, yv)
    }

    /// Step 1: the x_u whose strip [x0, x_u] holds the fraction u of the solid angle.
    #[inline]
    fn column(&self, u: f64) -> f64 {
        let delta = self.g0 + u * self.solid_angle;
        let sin = delta.sin();
        // M = b0 cos δ + b1 = (b0 + b1) − b0 (1 − cos δ), and 1 − cos δ = 2 sin²(δ/2) without cancellation.
        let half = (0.5 * delta).sin();
        let m = self.b_sum - self.b0 * (2.0 * half * half);
        let radicand = m * m - self.one_minus_b0_sq * sin * sin;
        // A radicand ≤ 0 is |x_u| = ∞ (rounding past a grazing end): the end on the side of sin δ · M.
        let xu = if radicand > 0.0 {
            self.h * sin * m.signum() / radicand.sqrt()
        } else if sin * m > 0.0 {
            self.x1
        } else {
            self.x0
        };
        xu.clamp(self.x0, self.x1)
    }

    /// The u ∈ [0, 1]² that [`Self::sample`] maps to the point of the rectangle nearest `q`
    /// (its inverse): u.x = Ω([x0, x_q] × [y0, y1])/S and u.y the sine fraction of y_q in its column.
    pub fn invert(&self, q: Vec3) -> Vec2 {
        let r = q.as_dvec3() - self.o;
        self.invert_local(r.dot(self.x), r.dot(self.y)).as_vec2()
    }

    /// [`Self::invert`] from the plane's coordinates, in f64.
    fn invert_local(&self, xq: f64, yq: f64) -> DVec2 {
        let (xq, yq) = (xq.clamp(self.x0, self.x1), yq.clamp(self.y0, self.y1));
        if self.solid_angle == 0.0 || self.by_area {
            let f = |a: f64, lo: f64, hi: f64| if hi > lo { (a - lo) / (hi - lo) } else { 0.5 };
            return DVec2::new(f(xq, self.x0, self.x1), f(yq, self.y0, self.y1));
        }
        let u = (rect_solid_angle(self.h, self.x0, xq, self.y0, self.y1) / self.solid_angle).clamp(0.0, 1.0);
        let v = SineInterval::new(hyp(xq, self.h), self.y0, self.y1).invert(self.y0, yq);
        DVec2::new(u, v)
    }
}

/// A [`SphericalRect`] with its warp towards a receiver's cosine fitted
/// ([`SphericalRect::cosine_weighted`]): what every sample of one shaded point shares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CosineWeighted {
    /// The rectangle seen from the point.
    rect: SphericalRect,
    /// The bilinear warp's corner weights (unused when the rectangle is sampled by area or
    /// subtends nothing).
    w: [f64; 4],
}

impl CosineWeighted {
    /// [`SphericalRect::sample_cosine_weighted`] at u, for the fitted normal.
    pub fn sample(&self, u: Vec2) -> SolidAngleSample {
        let r = &self.rect;
        if r.solid_angle == 0.0 || r.by_area {
            return r.sample(u);
        }
        let warped = sample_bilinear(u.as_dvec2(), self.w);
        let pdf = bilinear_pdf(warped, self.w);
        let (xu, yv) = r.sample_local(warped);
        let q = r.o + r.to_plane + r.x * xu + r.y * yv;
        SolidAngleSample::towards(r.o, q, if pdf > 0.0 { r.solid_angle / pdf } else { 0.0 })
    }
}

#[cfg(test)]
#[path = "spherical_rect_tests.rs"]
mod tests;
