//! A homogeneous participating medium: its transmittance and how far an eye ray that hits
//! nothing is marched; the march itself (single scattering along an eye ray, with each
//! light's visibility) is `transport::medium`, whose docs give the integral.

use crate::geometry::fdlibm;
use crate::light::{Light, LightKind};
#[cfg(target_arch = "x86_64")]
use crate::simd::Cpu;
use crate::simd::lanes::{LaneTask, Lanes};

/// The transmittance whose distance bounds an eye ray that hits nothing: the in-scattered
/// light beyond it is weighted by less than this.
pub const FAR_TRANSMITTANCE: f64 = 1e-4;

/// T = e^(−σ_t s), in f64 rounded to f32 (fdlibm's exp: the same bits on every machine, and
/// lanes in a loop); 1 for s = ∞ with σ_t = 0 and 0 for s = ∞ otherwise.
#[inline(always)]
pub fn transmittance(sigma_t: f32, s: f32) -> f32 {
    let t = fdlibm::exp(-(sigma_t as f64) * s as f64) as f32;
    if sigma_t == 0.0 { 1.0 } else { t }
}

/// How many transmittances [`transmittance_many`] takes at once.
pub const MANY: usize = 16;

/// [`transmittance`] of sixteen distances, the same bits, in AVX-512 lanes where the CPU has
/// them (fdlibm's exp is selects and arithmetic: sixteen of them side by side).
pub fn transmittance_many(sigma_t: f32, s: &[f32; MANY]) -> [f32; MANY] {
    let many = Many { sigma_t, s };
    #[cfg(target_arch = "x86_64")]
    if let Some(avx512) = Cpu::get().avx512() {
        return avx512.run(many);
    }
    many.each()
}

/// Sixteen transmittances: a task any lane width runs the same way.
#[derive(Clone, Copy)]
struct Many<'a> {
    /// σ_t.
    sigma_t: f32,
    /// The distances.
    s: &'a [f32; MANY],
}

impl Many<'_> {
    /// Each one's transmittance, as a loop the compiler puts in lanes.
    #[inline(always)]
    fn each(self) -> [f32; MANY] {
        std::array::from_fn(|j| transmittance(self.sigma_t, self.s[j]))
    }
}

impl LaneTask for Many<'_> {
    type Output = [f32; MANY];
    #[inline(always)]
    fn run<W: Lanes, H: Lanes>(self) -> Self::Output {
        // The lane types are not used: inlined here, the loop is compiled for the token's CPU.
        self.each()
    }
}

/// How far an eye ray that hits nothing is marched: where T falls to [`FAR_TRANSMITTANCE`],
/// s = ln(10⁴)/σ_t, but no farther than `cap` (a multiple of the scene's size, so that a thin
/// medium does not spread its steps over thousands of units where no light reaches).
pub fn far_bound(sigma_t: f32, cap: f32) -> f32 {
    if sigma_t <= 0.0 {
        return cap;
    }
    ((1.0 / FAR_TRANSMITTANCE).ln() / sigma_t as f64).min(cap as f64) as f32
}

/// The lights that scatter into eye rays: point, spot and directional lights.
pub fn scatters(l: &Light) -> bool {
    matches!(l.kind, LightKind::Point(_) | LightKind::Spot(_) | LightKind::Directional(_))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sixteen_transmittances_are_the_one_at_a_time_bits() {
        // Zero, ∞, NaN, huge and tiny distances and ordinary ones, for σ_t = 0 and others.
        let specials = [0.0, f32::INFINITY, f32::NAN, 1e30, 1e-30, 5000.0, 0.5, 3.0];
        for sigma_t in [0.0f32, 0.03, 0.15, 1.0, 40.0] {
            for round in 0..200u32 {
                let s: [f32; MANY] = std::array::from_fn(|j| {
                    if round == 0 && j < specials.len() { specials[j] } else { (round * 16 + j as u32) as f32 * 0.0137 }
                });
                let many = transmittance_many(sigma_t, &s);
                for j in 0..MANY {
                    assert_eq!(many[j].to_bits(), transmittance(sigma_t, s[j]).to_bits(), "σ_t {sigma_t}, s {}", s[j]);
                }
            }
        }
        assert_eq!((transmittance(0.0, f32::INFINITY), transmittance(0.1, f32::INFINITY)), (1.0, 0.0));
    }
}
