//! Fresnel reflectance F(θ): the fraction of light a smooth interface (one microfacet) reflects.
//!
//! | parameter | range | default | meaning |
//! | --- | --- | --- | --- |
//! | `fresnel` | `schlick`, `dielectric`, `conductor`, `none` | `schlick` | which F |
//! | `f0` (schlick) | [0, 1] RGB | 0.04 | reflectance at normal incidence; from `ior` as ((η − 1)/(η + 1))² when not given |
//! | `ior` η (dielectric) | (0, ∞), typically [1, 3] | 1.5 | relative index η_t/η_i; η < 1 means light arrives from the denser side (total internal reflection) |
//! | `eta` η, `k` κ (conductor) | ≥ 0 RGB | — | complex index η + iκ per channel (e.g. gold ≈ (0.143, 0.374, 1.442) + i(3.983, 2.386, 1.603)) |
//!
//! With c = cos θ_i (θ_i measured from the microfacet normal; in a BRDF c = v·h):
//!
//! - Schlick (Schlick 1994): F = F0 + (1 − F0)(1 − c)⁵.
//! - Exact unpolarized dielectric (Fresnel; Born & Wolf, *Principles of Optics* §1.5.2; pbrt-v4
//!   `FrDielectric`): with w = √(η² − sin²θ_i) = η cos θ_t, r_s = (c − w)/(c + w),
//!   r_p = (η²c − w)/(η²c + w), F = (r_s² + r_p²)/2; F = 1 when η² < sin²θ_i (total internal
//!   reflection, only possible for η < 1).
//! - Exact conductor (pbrt-v4 `FrComplex`): the same formula with complex η̃ = η + iκ and the
//!   principal complex square root, F = (|r_s|² + |r_p|²)/2. With κ = 0 it is the dielectric.
//! - None: F = 1 (isolates D·G in lessons).
//!
//! **Numerics.** Using d = η² − 1 = (η − 1)(η + 1) (exact for η near 1), the reflection
//! amplitudes are rewritten without cancellation: r_s = −d/(c + w)², r_p = d((η² + 1)c² − 1)/(η²c + w)²
//! (multiply numerator and denominator by the conjugate). So η = 1.0001 keeps full relative
//! precision (F(0°) = 2.5e-9), η = 1 gives exactly 0, and nothing divides by η, so η → 0 tends
//! to a perfect mirror (F → 1). Clamps: c is clamped to [0, 1]; the single undefined point
//! (η̃ = 1 at c = 0: a vanished interface seen edge-on) returns 0, its value for every other c.

use glam::Vec3;

/// Fresnel factor of a microfacet (a closed set, dispatched with `match`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Fresnel {
    /// Schlick's approximation F0 + (1 − F0)(1 − cos θ)⁵.
    Schlick {
        /// Reflectance at normal incidence, per channel.
        f0: Vec3,
    },
    /// Exact unpolarized Fresnel reflectance of a dielectric interface.
    Dielectric {
        /// Relative index of refraction η_t/η_i.
        eta: f32,
    },
    /// Exact unpolarized Fresnel reflectance of a conductor with complex index η + iκ.
    Conductor {
        /// Real part η per channel.
        eta: Vec3,
        /// Imaginary part (extinction) κ per channel.
        k: Vec3,
    },
    /// F = 1.
    None,
}

impl Default for Fresnel {
    /// Schlick with F0 = 0.04 (η = 1.5).
    fn default() -> Self {
        Fresnel::Schlick { f0: Vec3::splat(0.04) }
    }
}

impl Fresnel {
    /// Schlick's approximation with F0 computed from the index of refraction η.
    pub fn schlick_from_ior(eta: f32) -> Fresnel {
        Fresnel::Schlick { f0: Vec3::splat(f0_from_ior(eta)) }
    }

    /// An estimate of the cosine-weighted hemispherical average 2∫F(c) c dc: Schlick's exact
    /// average F0 + (1 − F0)/21 with F0 = F(1) (for the lobe weights of `shading::lobe`; the
    /// exact dielectric average for η = 1.5 is 0.0918 against the estimate's 0.0857).
    pub fn average(&self) -> Vec3 {
        let f0 = self.eval(1.0);
        f0 + (Vec3::ONE - f0) * (1.0 / 21.0)
    }

    /// F for the cosine `cos_theta_i` between the incident direction and the microfacet normal.
    #[inline]
    pub fn eval(&self, cos_theta_i: f32) -> Vec3 {
        match *self {
            Fresnel::Schlick { f0 } => schlick(f0, cos_theta_i),
            Fresnel::Dielectric { eta } => Vec3::splat(dielectric(cos_theta_i, eta)),
            Fresnel::Conductor { eta, k } => conductor_rgb(cos_theta_i, eta, k),
            Fresnel::None => Vec3::ONE,
        }
    }
}

/// Reflectance at normal incidence of a dielectric: F0 = ((η − 1)/(η + 1))².
#[inline]
pub fn f0_from_ior(eta: f32) -> f32 {
    ((eta - 1.0) / (eta + 1.0)).powi(2)
}

/// Schlick's weight (1 − c)⁵ with c clamped to [0, 1].
#[inline]
pub fn schlick_weight(cos_theta: f32) -> f32 {
    let m = (1.0 - cos_theta).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's approximation F = F0 + (1 − F0)(1 − c)⁵, per channel.
#[inline]
pub fn schlick(f0: Vec3, cos_theta: f32) -> Vec3 {
    f0 + (Vec3::ONE - f0) * schlick_weight(cos_theta)
}

/// Cosine of the critical angle, beyond which (smaller cosines) total internal reflection
/// occurs: √(1 − η²) for η < 1, `None` for η ≥ 1.
#[inline]
pub fn critical_cos(eta: f32) -> Option<f32> {
    (eta < 1.0).then(|| ((1.0 - eta) * (1.0 + eta)).max(0.0).sqrt())
}

/// Exact unpolarized Fresnel reflectance of a dielectric with relative index `eta` = η_t/η_i.
///
/// `cos_theta_i` is clamped to [0, 1]; returns 1 under total internal reflection and for
/// η ≤ 0 (the η → 0⁺ limit).
#[inline]
pub fn dielectric(cos_theta_i: f32, eta: f32) -> f32 {
    if eta <= 0.0 {
        return 1.0;
    }
    let c = cos_theta_i.clamp(0.0, 1.0);
    let d = (eta - 1.0) * (eta + 1.0); // η² − 1, exact near η = 1
    if d == 0.0 {
        return 0.0;
    }
    let w2 = d + c * c; // η² − sin²θ_i
    if w2 <= 0.0 {
        return 1.0; // total internal reflection
    }
    let w = w2.sqrt();
    let e2c = eta * eta * c;
    let r_s = -d / ((c + w) * (c + w));
    let r_p = d * ((eta * eta + 1.0) * c * c - 1.0) / ((e2c + w) * (e2c + w));
    (0.5 * (r_s * r_s + r_p * r_p)).min(1.0)
}

/// Exact unpolarized Fresnel reflectance of a conductor with complex index η + iκ (one channel).
///
/// `cos_theta_i` is clamped to [0, 1]. Preconditions: η ≥ 0, κ ≥ 0.
#[inline]
pub fn conductor(cos_theta_i: f32, eta: f32, k: f32) -> f32 {
    if k == 0.0 {
        return dielectric(cos_theta_i, eta);
    }
    let c = cos_theta_i.clamp(0.0, 1.0);
    let e2 = Complex::new(eta * eta - k * k, 2.0 * eta * k); // η̃²
    let d = Complex::new((eta - 1.0) * (eta + 1.0) - k * k, 2.0 * eta * k); // η̃² − 1
    let w = Complex::new(d.re + c * c, d.im).sqrt(); // √(η̃² − sin²θ_i)
    let s = Complex::new(c + w.re, w.im); // c + w
    let p = Complex::new(e2.re * c + w.re, e2.im * c + w.im); // η̃² c + w
    let q = Complex::new((e2.re + 1.0) * c * c - 1.0, e2.im * c * c); // (η̃² + 1)c² − 1
    let (s2, p2) = (s.norm_sqr(), p.norm_sqr());
    if s2 == 0.0 || p2 == 0.0 {
        return 1.0; // η̃ → 0: a perfect mirror (η̃ = 1 needs κ = 0, handled above)
    }
    let d2 = d.norm_sqr();
    let rs2 = d2 / (s2 * s2);
    let rp2 = d2 * q.norm_sqr() / (p2 * p2);
    (0.5 * (rs2 + rp2)).min(1.0)
}

/// [`conductor`] for the three channels of `eta` and `k`.
#[inline]
pub fn conductor_rgb(cos_theta_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    Vec3::new(conductor(cos_theta_i, eta.x, k.x), conductor(cos_theta_i, eta.y, k.y), conductor(cos_theta_i, eta.z, k.z))
}

/// √(x² + y²) in f64, rounded once: the squares of f32s are exact in f64, so only the sum and
/// the root round (glibc 2.35's `hypotf` for finite input).
#[inline]
fn hypot(x: f32, y: f32) -> f32 {
    let (x, y) = (x as f64, y as f64);
    (x * x + y * y).sqrt() as f32
}

/// A minimal complex number for the conductor Fresnel formula.
#[derive(Debug, Clone, Copy)]
struct Complex {
    re: f32,
    im: f32,
}

impl Complex {
    fn new(re: f32, im: f32) -> Complex {
        Complex { re, im }
    }

    fn norm_sqr(self) -> f32 {
        self.re * self.re + self.im * self.im
    }

    /// Principal square root (real part ≥ 0), computed without cancellation.
    fn sqrt(self) -> Complex {
        // |z| as glibc's hypotf computes it (one f64 sum of exact squares, rounded once),
        // inline rather than a library call, and the same bits on every target.
        let r = hypot(self.re, self.im);
        if r == 0.0 {
            return Complex::new(0.0, 0.0);
        }
        let t = (0.5 * (r + self.re.abs())).sqrt();
        if self.re >= 0.0 { Complex::new(t, self.im / (2.0 * t)) } else { Complex::new(self.im.abs() / (2.0 * t), t.copysign(self.im)) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Textbook form with cos θ_t, in f64, for comparison.
    fn dielectric_textbook(c: f64, eta: f64) -> f64 {
        let s2t = (1.0 - c * c) / (eta * eta);
        if s2t >= 1.0 {
            return 1.0;
        }
        let ct = (1.0 - s2t).sqrt();
        let rs = (c - eta * ct) / (c + eta * ct);
        let rp = (eta * c - ct) / (eta * c + ct);
        0.5 * (rs * rs + rp * rp)
    }

    #[test]
    fn normal_incidence_is_f0() {
        for eta in [1.0001f32, 1.33, 1.5, 3.0] {
            let f = dielectric(1.0, eta);
            assert!((f / f0_from_ior(eta) - 1.0).abs() < 1e-5, "η={eta}: {f}");
        }
        assert_eq!(dielectric(0.3, 1.0), 0.0);
    }

    #[test]
    fn matches_textbook_form() {
        for eta in [0.5f32, 0.8, 1.2, 1.5, 2.4] {
            for i in 0..=100 {
                let c = i as f32 / 100.0;
                // F has a square-root singularity at the critical angle (η = 0.8: c = 0.6),
                // where f32 rounding of η² − sin²θ is amplified without bound.
                if critical_cos(eta).is_some_and(|cc| (c - cc).abs() < 1e-3) {
                    continue;
                }
                let got = dielectric(c, eta) as f64;
                let want = dielectric_textbook(c as f64, eta as f64);
                assert!((got - want).abs() <= 1e-6 + 1e-5 * want, "η={eta} c={c}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn total_internal_reflection_and_grazing() {
        let eta = 1.0 / 1.5;
        let cc = critical_cos(eta).unwrap();
        assert_eq!(dielectric(cc * 0.999, eta), 1.0);
        assert!(dielectric(cc * 1.001, eta) < 1.0);
        assert!(dielectric(1e-6, 1.5) > 0.9999);
        assert_eq!(dielectric(0.0, 1.5), 1.0);
    }

    /// The inline hypot is the C library's bit for bit (native builds; f32::hypot is glibc's
    /// there), over random magnitudes and the Fresnel formula's range.
    #[test]
    #[cfg(not(target_arch = "wasm32"))]
    fn the_inline_hypot_is_the_libraries_bit_for_bit() {
        let mut s: u64 = 0x1234_5678_9abc_def0;
        for k in 0..2_000_000u32 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let (x, y) = if k % 2 == 0 {
                (f32::from_bits(s as u32 & 0x7f7f_ffff), f32::from_bits((s >> 32) as u32 & 0x7f7f_ffff))
            } else {
                ((s as u32 >> 8) as f32 / 16777216.0 * 40.0 - 20.0, ((s >> 40) as u32) as f32 / 16777216.0 * 40.0 - 20.0)
            };
            assert_eq!(hypot(x, y).to_bits(), x.hypot(y).to_bits(), "{x:e}, {y:e}");
        }
        assert_eq!(hypot(0.0, 0.0), 0.0);
        assert_eq!(hypot(3.0, -4.0), 5.0);
        assert_eq!(hypot(f32::MAX, f32::MAX), f32::INFINITY);
    }

    #[test]
    fn conductor_reduces_to_dielectric_and_to_f0() {
        for c in [0.0f32, 0.2, 0.7, 1.0] {
            let a = conductor(c, 1.5, 1e-7);
            let b = dielectric(c, 1.5);
            assert!((a - b).abs() < 1e-5, "c={c}: {a} vs {b}");
        }
        // Normal incidence: ((η−1)² + κ²)/((η+1)² + κ²).
        let (eta, k) = (0.2f32, 3.0f32);
        let f0 = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        assert!((conductor(1.0, eta, k) / f0 - 1.0).abs() < 1e-5);
        assert_eq!(conductor(0.5, 0.0, 0.0), 1.0);
        assert!((conductor(0.0, 0.2, 3.0) - 1.0).abs() < 1e-6);
    }

    /// The average estimate is Schlick's exact hemispherical average, and close to the exact
    /// dielectric's (0.0918 for η = 1.5 by quadrature).
    #[test]
    fn average_is_schlicks_hemispherical_average() {
        let average = |f: &dyn Fn(f32) -> f32| -> f32 {
            let n = 100_000;
            (0..n).map(|i| (i as f32 + 0.5) / n as f32).map(|c| 2.0 * f(c) * c / n as f32).sum()
        };
        let f0 = Vec3::new(0.04, 0.5, 0.9);
        let want = Fresnel::Schlick { f0 }.average();
        for i in 0..3 {
            assert!((average(&|c| schlick(f0, c)[i]) - want[i]).abs() < 1e-5);
        }
        let exact = average(&|c| dielectric(c, 1.5));
        assert!((exact - 0.0918).abs() < 5e-4, "{exact}");
        assert!((Fresnel::Dielectric { eta: 1.5 }.average().x - 0.0857).abs() < 1e-3);
        assert_eq!(Fresnel::None.average(), Vec3::ONE);
    }

    #[test]
    fn complex_sqrt_principal_branch() {
        for (re, im) in [(-4.0f32, 0.0f32), (3.0, 4.0), (-3.0, -4.0), (0.0, 2.0)] {
            let r = Complex::new(re, im).sqrt();
            assert!(r.re >= 0.0);
            assert!((r.re * r.re - r.im * r.im - re).abs() < 1e-5 && (2.0 * r.re * r.im - im).abs() < 1e-5);
        }
    }
}
