//! Deterministic hashed sampling for area lights: integer hashes, the R2 low-discrepancy
//! sequence with a per-point rotation, and the warps from [0, 1)² to the disk, the
//! cosine-weighted hemisphere and the uniform cone, plus an orthonormal basis to place them.
//!
//! There is no random state: a sample is a function of (sample index, seed), the seed a hash
//! of the shaded point (and of whatever else the caller mixes in with [`hash3`]), so a pixel
//! gets the same samples on every run and thread (DESIGN.md, Determinism). The hashes and the
//! sequence are integer arithmetic, the same bits on every machine; the warps add only
//! `+ − × ÷` and `sqrt` (correctly rounded everywhere; Rust never fuses a multiply and an add
//! on its own) and `sin`/`cos` taken in f64 and rounded to f32 ([`sin_cos`]): the libm's
//! last f64 bit may differ between machines (glibc picks an FMA path at run time), but that
//! moves the f32 result only when the f64 one lies within 1 f64 ULP of an f32 rounding
//! boundary, about one argument in 2²⁹.
//!
//! Warps follow pbrt-v4 (`util/sampling.h`): local frame with z the axis, u in [0, 1)².

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

/// A 32-bit integer hash with good avalanche: the `lowbias32` finalizer (C. Wellons,
/// "Prospecting for Hash Functions", 2018), bias ≈ 0.17 ‰, a bijection with `hash(0) = 0`.
#[inline]
pub fn hash(x: u32) -> u32 {
    let mut x = x;
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// Hash of three words: each is folded into the running hash of the ones before it.
///
/// The golden-ratio constant keeps `hash3(0, 0, 0)` away from `hash`'s fixed point at 0.
#[inline]
pub fn hash3(a: u32, b: u32, c: u32) -> u32 {
    let h = hash(a ^ 0x9e37_79b9);
    let h = hash(h ^ b);
    hash(h ^ c)
}

/// A seed from a point's f32 bits (the shaded point stands for its pixel: same point, same samples).
///
/// −0 and +0 give the same seed (adding +0 turns −0 into +0); any other change of a bit changes it.
#[inline]
pub fn point_seed(p: Vec3) -> u32 {
    hash3((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits(), (p.z + 0.0).to_bits())
}

/// 2⁶⁴/g and 2⁶⁴/g², g ≈ 1.3247 the plastic number (g³ = g + 1): the R2 steps in 0.64 fixed point.
const R2_STEP: [u64; 2] = [0xc13f_a9a9_02a6_328f, 0x91e1_0da5_c79e_7b1d];

/// Sample k of n in [0,1)²: the R2 low-discrepancy sequence (Roberts 2018) rotated by a
/// hashed offset from `seed` (Cranley–Patterson), so n samples are stratified for any n and each point gets its own pattern.
///
/// R2 is x_k = frac(½ + k (1/g, 1/g²)) (M. Roberts, "The Unreasonable Effectiveness of
/// Quasirandom Sequences", 2018). It runs in 64-bit fixed point, where frac is the wrap of
/// the integer and the rotation an integer add, so every machine gives the same bits; the top
/// 24 bits become an f32 exactly, hence each coordinate is at most 1 − 2⁻²⁴.
#[inline]
pub fn sample_2d(k: u32, seed: u32) -> Vec2 {
    // Two independent offsets in [0, 1) from the seed (the ½ of R2 is absorbed by them).
    let offset = [hash(seed ^ 0x85eb_ca6b), hash(seed ^ 0xc2b2_ae35)];
    let coordinate = |axis: usize| {
        let x = (k as u64).wrapping_mul(R2_STEP[axis]).wrapping_add((offset[axis] as u64) << 32);
        (x >> 40) as f32 * (1.0 / (1u32 << 24) as f32)
    };
    Vec2::new(coordinate(0), coordinate(1))
}

/// The concentric map as (r, φ) with r in [−1, 1] (the sign picks the half of the disk).
#[inline]
fn concentric_polar(u: Vec2) -> (f32, f32) {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return (0.0, 0.0);
    }
    // Squares map to circles: the larger coordinate is the radius, the ratio the angle in its wedge.
    if o.x.abs() > o.y.abs() { (o.x, FRAC_PI_4 * (o.y / o.x)) } else { (o.y, FRAC_PI_2 - FRAC_PI_4 * (o.x / o.y)) }
}

/// Uniform point on the unit disk from u in [0,1)² (Shirley & Chiu 1997 concentric map).
///
/// Area-preserving and continuous, so strata of [0, 1)² stay compact on the disk
/// (P. Shirley and K. Chiu, "A Low Distortion Map Between Disk and Square", JGT 2(3), 1997;
/// pbrt-v4 `SampleUniformDiskConcentric`). The length is at most 1 (up to one rounding of sin/cos).
#[inline]
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let (r, phi) = concentric_polar(u);
    let (sin, cos) = sin_cos(phi);
    Vec2::new(r * cos, r * sin)
}

/// Cosine-weighted direction about +z (Malley's method), pdf cosθ/π.
///
/// A uniform point on the disk lifted to the hemisphere (pbrt-v4 `SampleCosineHemisphere`);
/// z = √((1 − r)(1 + r)) rather than √(1 − x² − y²), which cancels near the rim. z ≥ 0, unit length;
/// z = 0 (a pdf of 0) only for u on the square's border, e.g. u.x = 0.
#[inline]
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let (r, phi) = concentric_polar(u);
    let (sin, cos) = sin_cos(phi);
    let r_abs = r.abs();
    Vec3::new(r * cos, r * sin, ((1.0 - r_abs) * (1.0 + r_abs)).max(0.0).sqrt())
}

/// Uniform direction in the cone of half-angle acos(cos_max) about +z, pdf 1/(2π(1−cos_max)).
///
/// cos θ = 1 − u.x (1 − cos_max), φ = 2π u.y (pbrt-v4 `SampleUniformCone`), with
/// sin θ = √((1 − cos θ)(1 + cos θ)) from 1 − cos θ directly, which keeps narrow cones accurate.
/// `cos_max` is clamped to [−1, 1] (−1: the whole sphere); 1 or more, or NaN, is a point-sized cone: +z.
#[inline]
pub fn uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    if cos_max >= 1.0 || cos_max.is_nan() {
        return Vec3::Z;
    }
    let one_minus_cos = u.x * (1.0 - cos_max.max(-1.0));
    let sin_theta = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
    let (sin, cos) = sin_cos(TAU * u.y);
    Vec3::new(sin_theta * cos, sin_theta * sin, 1.0 - one_minus_cos)
}

/// An orthonormal basis (t, b) with n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
///
/// Right-handed: t × b = n. Branch-free but for the sign of n.z, and accurate near n = −z,
/// where Frisvad's original 2012 construction fails (T. Duff et al., JCGT 6(1), 2017, listing 3).
/// Precondition: `n` is normalized.
#[inline]
pub fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bitangent = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    (t, bitangent)
}

/// sin and cos of `x` computed in f64 and rounded to f32: the same bits on every machine
/// but for arguments within an f64 ULP of an f32 rounding boundary (see the module docs).
#[inline]
pub fn sin_cos(x: f32) -> (f32, f32) {
    let (s, c) = (x as f64).sin_cos();
    (s as f32, c as f32)
}

/// The fraction of the cosine-weighted hemisphere about unit `n` that lies above the horizon
/// (y > 0): (1 + n_y)/2, in [0, 1].
///
/// The sky view factor of a plane tilted by β = acos n_y (a textbook configuration factor, e.g.
/// Howell's catalogue): a Lambertian receiver under a sky of radiance L_sky above the horizon
/// and L_ground below it, unblocked, receives E = π (F L_sky + (1 − F) L_ground). A sampled
/// sky can use it as a control variate, π (F L_sky + (1 − F) L_ground) − Σ_k (1 − V_k) π L(ω_k)/N
/// over cosine-weighted samples with visibility V_k, which is exact wherever nothing blocks
/// the sky. Non-finite n_y gives ½.
#[inline]
pub fn sky_view_factor(n: Vec3) -> f32 {
    if n.y.is_nan() { 0.5 } else { (0.5 + 0.5 * n.y).clamp(0.0, 1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest f32 below 1.
    const BELOW_ONE: f32 = 1.0 - f32::EPSILON / 2.0;

    /// u at the corners and edges of [0, 1)², the points where warps divide or take square roots of 0.
    fn awkward_u() -> Vec<Vec2> {
        let v = [0.0, 1e-30, 0.25, 0.5, 0.5 + f32::EPSILON, 0.75, BELOW_ONE];
        v.iter().flat_map(|&x| v.iter().map(move |&y| Vec2::new(x, y))).collect()
    }

    /// The largest per-coordinate distance between a and b on the unit torus.
    fn wrapped_distance(a: Vec2, b: Vec2) -> f32 {
        let d = (a - b).rem_euclid(Vec2::ONE);
        d.min(Vec2::ONE - d).max_element()
    }

    /// n points of the sequence for one seed.
    fn points(n: u32, seed: u32) -> Vec<Vec2> {
        (0..n).map(|k| sample_2d(k, seed)).collect()
    }

    #[test]
    fn hash_flips_each_output_bit_for_about_half_the_inputs() {
        // For every (input bit, output bit), flipping the input bit flips the output bit with
        // probability ½: 16384 inputs give σ ≈ 0.004, so 0.03 is over 7σ.
        let inputs: Vec<u32> = (0..1u32 << 14).map(|i| hash(i.wrapping_mul(0x2545_f491))).collect();
        let check = |name: &str, words: usize, f: &dyn Fn([u32; 3]) -> u32| {
            for word in 0..words {
                for bit in 0..32 {
                    let mut flips = [0u32; 32];
                    for (i, &x) in inputs.iter().enumerate() {
                        let mut w = [x, hash(x ^ 1), i as u32];
                        let before = f(w);
                        w[word] ^= 1 << bit;
                        let changed = before ^ f(w);
                        for (out, count) in flips.iter_mut().enumerate() {
                            *count += (changed >> out) & 1;
                        }
                    }
                    for (out, &count) in flips.iter().enumerate() {
                        let p = count as f64 / inputs.len() as f64;
                        assert!((p - 0.5).abs() < 0.03, "{name}: word {word} bit {bit} → out {out}: {p}");
                    }
                }
            }
        };
        check("hash", 1, &|w| hash(w[0]));
        check("hash3", 3, &|w| hash3(w[0], w[1], w[2]));
    }

    #[test]
    fn seeds_are_deterministic_and_tell_points_apart() {
        assert_eq!(hash(0), 0);
        assert_ne!(hash3(0, 0, 0), 0);
        // Fixed bits: a change to the hash changes every pixel's noise, so it should be deliberate.
        assert_eq!(hash(1), 0x6889_90c0);
        let p = Vec3::new(0.25, -1.5, 3.0);
        assert_eq!(point_seed(p), point_seed(Vec3::new(0.25, -1.5, 3.0)));
        assert_eq!(point_seed(Vec3::new(0.0, 1.0, 2.0)), point_seed(Vec3::new(-0.0, 1.0, 2.0)));
        let next = Vec3::new(f32::from_bits(0.25f32.to_bits() + 1), -1.5, 3.0);
        assert_ne!(point_seed(p), point_seed(next));
        // Swapping coordinates changes the seed.
        assert_ne!(point_seed(Vec3::new(1.0, 2.0, 3.0)), point_seed(Vec3::new(2.0, 1.0, 3.0)));
    }

    #[test]
    fn sample_2d_is_deterministic_in_range_and_rotated_per_seed() {
        for seed in [0, 1, 0xdead_beef] {
            for k in (0..1000).chain([u32::MAX - 1, u32::MAX]) {
                let u = sample_2d(k, seed);
                assert_eq!(u, sample_2d(k, seed));
                assert!(u.cmpge(Vec2::ZERO).all() && u.cmplt(Vec2::ONE).all(), "{k} {seed}: {u}");
            }
        }
        // A rotation: the difference of two samples (mod 1) is the same for every seed.
        let d = |seed| sample_2d(7, seed) - sample_2d(3, seed);
        for seed in [1, 2, 3] {
            assert!(wrapped_distance(d(seed), d(0)) < 1e-6, "{seed}");
        }
        assert_ne!(sample_2d(0, 1), sample_2d(0, 2));
        // Unrotated, the sequence is R2: k (1/g, 1/g²) mod 1.
        let g = 1.324_717_957_244_746_f64;
        for k in [1, 50, 12345] {
            let r2 = Vec2::new((k as f64 / g).fract() as f32, (k as f64 / (g * g)).fract() as f32);
            assert!(wrapped_distance(sample_2d(k, 5) - sample_2d(0, 5), r2) < 1e-6, "{k}");
        }
    }

    #[test]
    fn sample_2d_is_stratified_for_any_count() {
        // Every cell of a 16×16 grid gets 1 ± 1 of 256 points; uniform random points leave
        // about 256/e ≈ 94 cells empty (76 at fewest in 300 trials) and crowd 5 or more into
        // some. R2 leaves 34 to 52 empty over 3000 seeds.
        for seed in [0, 1, 2, 99, 0x1234_5678, 0xffff_ffff] {
            let mut cells = [0u32; 256];
            for u in points(256, seed) {
                cells[(u.y * 16.0) as usize * 16 + (u.x * 16.0) as usize] += 1;
            }
            let empty = cells.iter().filter(|&&c| c == 0).count();
            let most = *cells.iter().max().unwrap();
            assert!(empty <= 60 && most <= 2, "seed {seed}: {empty} empty, {most} at most");
        }
        // Star discrepancy D* (the largest error of the fraction in a box [0, a) × [0, b), on
        // a 64² grid of corners) for several n. Measured over 200 draws (20 for n ≥ 1000):
        // random points give D* ≈ 1.1/√n and never below 0.56/√n; rotated R2 stays under
        // 0.5/√n and falls like (log n)/n. (Below n ≈ 100 one draw cannot tell them apart.)
        for (n, seed) in [100, 256, 1000, 4096].into_iter().flat_map(|n| [(n, 17), (n, 0xabcd)]) {
            let pts = points(n, seed);
            let mut worst = 0.0f64;
            for i in 1..=64 {
                for j in 1..=64 {
                    let (a, b) = (i as f32 / 64.0, j as f32 / 64.0);
                    let inside = pts.iter().filter(|u| u.x < a && u.y < b).count();
                    worst = worst.max((inside as f64 / n as f64 - (a * b) as f64).abs());
                }
            }
            assert!(worst < 0.5 / (n as f64).sqrt(), "n = {n}, seed {seed}: D* ≈ {worst}");
        }
    }

    #[test]
    fn concentric_disk_is_uniform_on_the_unit_disk() {
        let n = 1u32 << 14;
        let mut quadrants = [0u32; 4];
        let mut inner = 0u32;
        let mut mean = Vec2::ZERO;
        for u in points(n, 3) {
            let d = concentric_disk(u);
            assert!(d.length() <= 1.0 + 1e-6, "{u} → {d}");
            quadrants[(d.x < 0.0) as usize + 2 * (d.y < 0.0) as usize] += 1;
            // Half the area lies within r = 1/√2.
            inner += (d.length_squared() < 0.5) as u32;
            mean += d / n as f32;
        }
        // Each count is within 4σ of a binomial (the low-discrepancy points do far better).
        let sigma = |p: f64| (n as f64 * p * (1.0 - p)).sqrt();
        for q in quadrants {
            assert!((q as f64 - n as f64 / 4.0).abs() < 4.0 * sigma(0.25), "{quadrants:?}");
        }
        assert!((inner as f64 - n as f64 / 2.0).abs() < 4.0 * sigma(0.5), "{inner}");
        assert!(mean.length() < 0.01, "{mean}");
        for u in awkward_u() {
            let d = concentric_disk(u);
            assert!(d.is_finite() && d.length() <= 1.0 + 1e-6, "{u} → {d}");
        }
        assert_eq!(concentric_disk(Vec2::splat(0.5)), Vec2::ZERO);
    }

    #[test]
    fn cosine_hemisphere_has_the_moments_of_cos_over_pi() {
        // For pdf cosθ/π: E[cosθ] = 2/3, E[cos²θ] = 1/2, E[x] = E[y] = 0.
        let n = 1u32 << 14;
        let (mut m1, mut m2, mut mx, mut my) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for u in points(n, 11) {
            let w = cosine_hemisphere(u);
            assert!((w.length() - 1.0).abs() < 1e-6 && w.z >= 0.0, "{u} → {w}");
            m1 += w.z as f64;
            m2 += (w.z * w.z) as f64;
            mx += w.x as f64;
            my += w.y as f64;
        }
        let n = n as f64;
        // σ(cosθ) = √(1/2 − 4/9) ≈ 0.24, so 4σ/√n ≈ 0.0075.
        assert!((m1 / n - 2.0 / 3.0).abs() < 0.0075, "E[cos] = {}", m1 / n);
        assert!((m2 / n - 0.5).abs() < 0.01, "E[cos²] = {}", m2 / n);
        assert!((mx / n).abs() < 0.01 && (my / n).abs() < 0.01, "{} {}", mx / n, my / n);
        for u in awkward_u() {
            let w = cosine_hemisphere(u);
            assert!(w.is_finite() && (w.length() - 1.0).abs() < 1e-6 && w.z >= 0.0, "{u} → {w}");
        }
        assert_eq!(cosine_hemisphere(Vec2::splat(0.5)), Vec3::Z);
    }

    #[test]
    fn uniform_cone_stays_inside_with_mean_cos_halfway() {
        let n = 1u32 << 14;
        for cos_max in [0.999, 0.9, 0.5, 0.0, -0.5, -1.0] {
            let mut mean = Vec3::ZERO.as_dvec3();
            for u in points(n, 23) {
                let w = uniform_cone(u, cos_max);
                assert!((w.length() - 1.0).abs() < 1e-6 && w.z >= cos_max - 1e-6, "{cos_max}: {u} → {w}");
                mean += w.as_dvec3() / n as f64;
            }
            // cosθ is uniform on [cos_max, 1]: mean (1 + cos_max)/2, σ = (1 − cos_max)/√12.
            let tol = 4.0 * (1.0 - cos_max as f64) / 12f64.sqrt() / (n as f64).sqrt();
            assert!((mean.z - (1.0 + cos_max as f64) / 2.0).abs() < tol, "{cos_max}: {mean}");
            assert!(mean.x.abs() < 0.01 && mean.y.abs() < 0.01, "{cos_max}: {mean}");
            for u in awkward_u() {
                let w = uniform_cone(u, cos_max);
                assert!(w.is_finite() && (w.length() - 1.0).abs() < 1e-6 && w.z >= cos_max - 1e-6, "{cos_max}: {u} → {w}");
            }
        }
        // A point-sized cone (and anything past it) is +z; below −1 is the sphere.
        for u in awkward_u() {
            assert_eq!(uniform_cone(u, 1.0), Vec3::Z);
            assert_eq!(uniform_cone(u, 2.0), Vec3::Z);
            assert_eq!(uniform_cone(u, f32::NAN), Vec3::Z);
            assert_eq!(uniform_cone(u, -3.0), uniform_cone(u, -1.0));
        }
        // A cone of 1e-3 rad keeps its angle: sin θ from 1 − cos θ directly, where
        // √(1 − cos²) in f32 would be off by about 3%.
        let cos_max = 1e-3f32.cos();
        let w = uniform_cone(Vec2::new(BELOW_ONE, 0.0), cos_max);
        let c = cos_max as f64;
        let sin_max = ((1.0 - c) * (1.0 + c)).sqrt();
        assert!((w.x as f64 / sin_max - 1.0).abs() < 1e-6, "{w} vs {sin_max}");
    }

    #[test]
    fn basis_is_orthonormal_and_right_handed() {
        let mut normals = vec![Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z, Vec3::new(0.0, 0.0, -0.0) - Vec3::Z];
        normals.push(Vec3::new(1e-4, 0.0, -1.0).normalize());
        normals.push(Vec3::new(0.0, 1e-7, -1.0).normalize());
        normals.push(Vec3::new(1.0, 0.0, -1e-7).normalize());
        normals.extend(points(2000, 31).into_iter().map(|u| uniform_cone(u, -1.0)));
        for n in normals {
            let (t, b) = basis(n);
            for (name, e) in [("|t|", t.length() - 1.0), ("|b|", b.length() - 1.0), ("t·b", t.dot(b)), ("t·n", t.dot(n)), ("b·n", b.dot(n))]
            {
                assert!(e.abs() < 1e-6, "{n}: {name} off by {e}");
            }
            assert!((t.cross(b) - n).length() < 1e-6, "{n}: t × b = {}", t.cross(b));
        }
    }

    #[test]
    fn sky_view_factor_matches_cosine_weighted_counts() {
        // The share of 4096 Sobol cosine-weighted directions about n with y > 0, against (1 + n_y)/2:
        // the stratified count is within 2e-3 (independent points would scatter by 8e-3).
        for n in [Vec3::Y, -Vec3::Y, Vec3::X, Vec3::new(0.3, 0.5, -0.2).normalize(), Vec3::new(0.0, -0.9, 0.1).normalize()] {
            let (t, b) = basis(n);
            let above = (0..4096)
                .filter(|&k| {
                    let d = cosine_hemisphere(crate::geometry::sobol::sobol_2d(k, 17));
                    (t * d.x + b * d.y + n * d.z).y > 0.0
                })
                .count();
            let got = above as f32 / 4096.0;
            assert!((got - sky_view_factor(n)).abs() < 2e-3, "{n}: {got} vs {}", sky_view_factor(n));
        }
        assert_eq!(sky_view_factor(Vec3::Y), 1.0);
        assert_eq!(sky_view_factor(-Vec3::Y), 0.0);
        assert_eq!(sky_view_factor(Vec3::NAN), 0.5);
        assert_eq!(sky_view_factor(Vec3::new(0.0, 2.0, 0.0)), 1.0);
    }
}
