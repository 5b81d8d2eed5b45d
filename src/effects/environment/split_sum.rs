//! The split sum (Karis 2013): image-based lighting of a BRDF read from the prefiltered maps.
//!
//! L_o(v) ≈ (ρ_d/π) E(n) + E_s(n·v) · L_pre(r, roughness), r = 2(n·v)n − v, where
//! - E(n) is the irradiance (SH or the convolved map) and ρ_d the weight of the BRDF's
//!   diffuse part (`Brdf::lobes`, taken as Lambert: Oren-Nayar's ρ, principled's
//!   (1 − metallic)·base colour with its sheen);
//! - E_s(μ) = ∫ f_s(l, v) cos θ_l dω_l is the directional albedo of the BRDF's specular part
//!   (`Brdf::eval_part`, the same split as the frame's layers) at n·v = μ: Karis' DFG term,
//!   here tabulated per material at [`TABLE`] values of μ (importance-sampled with the
//!   BRDF's own `sample`, [`ALBEDO_SAMPLES`] Sobol samples each) instead of his
//!   F0-scale-and-bias fit, so it holds for every Fresnel and masking choice;
//! - L_pre is the map convolved with GGX of the BRDF's roughness about n = v = r.
//!
//! The approximation splits the integral of a product into a product of integrals and
//! takes n = v = r inside the prefilter, so its lobes are rounder than the true ones at
//! grazing angles, and it ignores the scene's occlusion of the sky; its error against the
//! Monte Carlo reference is measured in docs/accuracy-and-cost.md.

use crate::geometry::sobol::sobol_4d;
use crate::shading::brdf::Brdf;
use crate::shading::lobe::Part;
use glam::Vec3;

/// Values of n·v in the specular albedo table.
pub const TABLE: usize = 16;
/// Samples per entry of the table (the graded quadrature of `shading::brdf` took 2.4 s a
/// material for 16 entries; this takes milliseconds, within 1 % of it).
pub const ALBEDO_SAMPLES: u32 = 4096;

/// E_s(μ) = ∫ f_s cos θ_l dω_l of `b`'s specular part seen at n·v = μ, by importance
/// sampling the whole BRDF (its mixture pdf covers the specular lobes).
fn albedo(b: &Brdf, mu: f32) -> Vec3 {
    let v = Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    let mut sum = Vec3::ZERO;
    for k in 0..ALBEDO_SAMPLES {
        let u = sobol_4d(k, 0x00a1_bed0);
        if let Some(s) = b.sample(v, u.x, glam::Vec2::new(u.y, u.z))
            && s.pdf > 0.0
        {
            sum += b.eval_part(Part::Specular, s.l, v) * (s.l.z / s.pdf);
        }
    }
    let r = sum / ALBEDO_SAMPLES as f32;
    if r.is_finite() { r.max(Vec3::ZERO) } else { Vec3::ZERO }
}

/// Distinct BRDFs whose terms [`SplitSum::cached`] keeps: a run's lessons have a few dozen.
const KEEP: usize = 256;

/// The terms computed in this run, by the BRDF's exact `Debug` form, oldest first.
static DONE: std::sync::Mutex<Vec<(String, SplitSum)>> = std::sync::Mutex::new(Vec::new());

/// One material's split-sum terms.
#[derive(Debug, Clone, PartialEq)]
pub struct SplitSum {
    /// The BRDF these terms belong to.
    pub brdf: Brdf,
    /// ρ_d of the diffuse part.
    pub diffuse: Vec3,
    /// E_s at μ_i = (i + ½)/TABLE.
    pub specular: [Vec3; TABLE],
    /// Perceptual roughness of the specular lobe (√α).
    pub roughness: f32,
}

impl SplitSum {
    /// The terms of `brdf`: its diffuse part's weight and its specular part's albedo table
    /// (the one split of `Brdf::lobes`), and its specular lobe's roughness.
    pub fn new(brdf: &Brdf) -> SplitSum {
        let parts = brdf.lobes();
        let specular = if parts.has(Part::Specular) {
            std::array::from_fn(|i| albedo(brdf, (i as f32 + 0.5) / TABLE as f32))
        } else {
            [Vec3::ZERO; TABLE]
        };
        SplitSum { brdf: *brdf, diffuse: parts.weight(Part::Diffuse), specular, roughness: brdf.specular_roughness() }
    }

    /// [`SplitSum::new`] computed once per run for each distinct BRDF (16 × 4096 samples, about
    /// 12 ms a material, which every render of a prefiltered scene would otherwise spend on
    /// every physically based material of the lesson): the same terms, bit for bit.
    pub fn cached(brdf: &Brdf) -> SplitSum {
        // The Debug form is exact (every f32 in its round-trip digits).
        let key = format!("{brdf:?}");
        if let Some((_, s)) = DONE.lock().unwrap_or_else(|e| e.into_inner()).iter().find(|(k, _)| *k == key) {
            return s.clone();
        }
        let s = SplitSum::new(brdf);
        let mut done = DONE.lock().unwrap_or_else(|e| e.into_inner());
        if done.len() >= KEEP {
            done.remove(0);
        }
        done.push((key, s.clone()));
        s
    }

    /// E_s at n·v = `mu`, linear between the table's entries.
    #[inline]
    pub fn specular_albedo(&self, mu: f32) -> Vec3 {
        let x = (mu.clamp(0.0, 1.0) * TABLE as f32 - 0.5).clamp(0.0, (TABLE - 1) as f32);
        let i = (x as usize).min(TABLE - 2);
        let f = x - i as f32;
        self.specular[i] * (1.0 - f) + self.specular[i + 1] * f
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::brdf::directional_albedo_rgb;
    use crate::shading::cook_torrance::CookTorrance;
    use crate::shading::microfacet::Fresnel;

    /// The sampled table agrees with the project's graded quadrature: within 2 % (the worst,
    /// measured: 1.1 % at the most grazing entry μ = 1/32, where sampling half vectors by D
    /// alone puts many directions below the surface).
    #[test]
    fn a_cached_table_is_the_computed_one_and_kept() {
        let b = Brdf::CookTorrance(CookTorrance { alpha: 0.123_456, ..CookTorrance::default() });
        let kept = || DONE.lock().unwrap().iter().any(|(k, _)| *k == format!("{b:?}"));
        assert_eq!(SplitSum::cached(&b), SplitSum::new(&b));
        assert!(kept(), "computed once, then kept for every later render");
        assert_eq!(SplitSum::cached(&b), SplitSum::new(&b), "read back");
    }

    #[test]
    fn the_specular_albedo_table_matches_the_quadrature() {
        for (alpha, fresnel) in [(0.09, Fresnel::None), (0.5, Fresnel::default()), (0.01, Fresnel::None)] {
            let b = Brdf::CookTorrance(CookTorrance { alpha, fresnel, ..CookTorrance::default() });
            let s = SplitSum::new(&b);
            for i in [0, 5, 15] {
                let mu = (i as f64 + 0.5) / TABLE as f64;
                let want = directional_albedo_rgb(&b, mu, 6).0.as_vec3();
                let got = s.specular[i];
                assert!(
                    (got - want).abs().max_element() < 0.02 * want.max_element().max(0.05),
                    "α {alpha}, μ {mu}: {got:?} against {want:?}"
                );
            }
        }
    }
}
