//! Sampling directions after a BRDF: a mixture of the cosine-weighted hemisphere (the
//! diffuse part) and GGX half vectors (the glossy part) with the BRDF's lobe width.
//!
//! It need not match the BRDF exactly: the reference estimator combines it with sampling
//! the environment by multiple importance sampling, which stays unbiased for any pair of
//! strategies whose pdfs together cover the integrand (Veach 1997, §9.2). A closer match
//! only lowers the noise.
//!
//! GGX half vectors after Walter et al. 2007: θ_h = arctan(α √(ξ/(1 − ξ))) (eq. 35),
//! φ_h = 2π ξ′ (eq. 36), D(h) = α² / (π ((α² − 1) cos² θ_h + 1)²) (eq. 33), and the pdf of the
//! reflected l = 2(v·h)h − v is D(h) cos θ_h / (4 |v·h|) (eqs. 14 and 38).

use crate::geometry::sampling::{cosine_hemisphere, sin_cos};
use crate::scene::environment::luminance;
use crate::shading::brdf::Brdf;
use crate::shading::microfacet::clamp_alpha;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, TAU};

/// The mixture that stands in for a BRDF when sampling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrdfSampler {
    /// Probability of the cosine-weighted (diffuse) component.
    pub diffuse_share: f32,
    /// GGX width of the glossy component.
    pub alpha: f32,
}

impl BrdfSampler {
    /// The sampler for `brdf`: the diffuse share from the lobes' reflectances, α from its
    /// microfacet width (or half [`Brdf::lobe_width`] for a Phong lobe).
    pub fn of(brdf: &Brdf) -> BrdfSampler {
        let share = |d: Vec3, s: Vec3| {
            let (d, s) = (luminance(d), luminance(s));
            if d + s > 0.0 { d / (d + s) } else { 1.0 }
        };
        let lobe_alpha = (0.5 * brdf.lobe_width()).clamp(1e-4, 1.0);
        match brdf {
            Brdf::Diffuse(_) | Brdf::OrenNayar(_) => BrdfSampler { diffuse_share: 1.0, alpha: 1.0 },
            Brdf::CookTorrance(c) => BrdfSampler { diffuse_share: share(c.diffuse, c.specular), alpha: clamp_alpha(c.alpha).max(1e-4) },
            Brdf::Principled(p) => {
                let (ax, ay) = p.alphas();
                BrdfSampler { diffuse_share: 0.5 * (1.0 - p.metallic), alpha: (ax * ay).sqrt().clamp(1e-4, 1.0) }
            }
            Brdf::NormalizedPhong(n) => BrdfSampler { diffuse_share: share(n.diffuse, n.specular), alpha: lobe_alpha },
            Brdf::NormalizedBlinnPhong(n) => BrdfSampler { diffuse_share: share(n.diffuse, n.specular), alpha: lobe_alpha },
        }
    }

    /// A direction l in the local frame (z = normal) for u in [0, 1)², seen from `v` (local,
    /// v.z > 0); `None` when the glossy component reflects below the surface.
    pub fn sample(&self, u: Vec2, v: Vec3) -> Option<Vec3> {
        if u.x < self.diffuse_share {
            let ux = u.x / self.diffuse_share;
            return Some(cosine_hemisphere(Vec2::new(ux.min(1.0 - f32::EPSILON / 2.0), u.y)));
        }
        let ux = ((u.x - self.diffuse_share) / (1.0 - self.diffuse_share)).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        let a2 = self.alpha * self.alpha;
        // cos² θ_h = (1 − ξ) / (1 + (α² − 1) ξ), the same as eq. 35 without the tangent.
        let cos2 = ((1.0 - ux) / (1.0 + (a2 - 1.0) * ux)).clamp(0.0, 1.0);
        let (cos_h, sin_h) = (cos2.sqrt(), (1.0 - cos2).max(0.0).sqrt());
        let (sin_p, cos_p) = sin_cos(TAU * u.y);
        let h = Vec3::new(sin_h * cos_p, sin_h * sin_p, cos_h);
        let l = 2.0 * v.dot(h) * h - v;
        (l.z > 0.0).then_some(l)
    }

    /// The pdf (1/sr) of [`BrdfSampler::sample`] giving the local `l`, seen from `v`.
    pub fn pdf(&self, l: Vec3, v: Vec3) -> f32 {
        if l.z <= 0.0 {
            return 0.0;
        }
        let diffuse = l.z * FRAC_1_PI;
        if self.diffuse_share >= 1.0 {
            return self.diffuse_share * diffuse;
        }
        let h = (l + v).normalize_or_zero();
        let v_h = v.dot(h);
        if h.z <= 0.0 || v_h <= 0.0 {
            return self.diffuse_share * diffuse;
        }
        let a2 = self.alpha * self.alpha;
        let t = (a2 - 1.0) * h.z * h.z + 1.0;
        let d = a2 * FRAC_1_PI / (t * t);
        self.diffuse_share * diffuse + (1.0 - self.diffuse_share) * d * h.z / (4.0 * v_h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sampling::sample_2d;

    /// The pdf integrates to the share of samples kept above the surface, and a histogram of
    /// samples over a cap agrees with the pdf integrated over it.
    #[test]
    fn samples_follow_the_pdf() {
        let v = Vec3::new(0.5, 0.0, 0.866_025_4).normalize();
        for s in [BrdfSampler { diffuse_share: 0.3, alpha: 0.2 }, BrdfSampler { diffuse_share: 0.0, alpha: 0.5 }] {
            let n = 200_000;
            // A cap of 25° around the mirror direction of v.
            let r = Vec3::new(-v.x, -v.y, v.z);
            let cos_cap = 25f32.to_radians().cos();
            let inside = (0..n).filter_map(|k| s.sample(sample_2d(k, 11), v)).filter(|l| l.dot(r) > cos_cap).count();
            // ∫ over the cap of the pdf, by a midpoint rule in (cos θ, φ) about r.
            let (nt, np) = (400, 400);
            let mut cap = 0f64;
            let (t, b) = crate::geometry::sampling::basis(r);
            for i in 0..nt {
                let c = 1.0 - (1.0 - cos_cap as f64) * (i as f64 + 0.5) / nt as f64;
                let sn = (1.0 - c * c).sqrt();
                for j in 0..np {
                    let phi = std::f64::consts::TAU * (j as f64 + 0.5) / np as f64;
                    let l = (t * (sn * phi.cos()) as f32 + b * (sn * phi.sin()) as f32 + r * c as f32).normalize();
                    cap += s.pdf(l, v) as f64 * (1.0 - cos_cap as f64) * std::f64::consts::TAU / (nt * np) as f64;
                }
            }
            let share = inside as f64 / n as f64;
            assert!((share - cap).abs() < 5e-3, "{s:?}: {share} of samples in the cap, pdf says {cap}");
        }
    }
}
