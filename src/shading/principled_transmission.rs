//! The principled material's transmission parameters, as the lecture lists them (Burley 2015,
//! "Extending the Disney BRDF to a BSDF with integrated subsurface scattering", section 3):
//! specular transmission and its IOR, the transmittance colour at a distance, and diffuse
//! transmission. Only the path tracer draws them (a rasterizer sees one side of a surface).
//!
//! The BSDF is a mixture, each part energy-conserving on its own:
//!
//! f = w_g f_glass + (1 − w_g) (f_brdf + f_dt),  w_g = (1 − metallic) · specular_transmission,
//!
//! - f_glass: a rough dielectric boundary of the material's `ior` and α = roughness² (Walter et
//!   al. 2007, [`RoughDielectric`]), each refraction tinted by √C so that light passing in and
//!   out keeps the base colour C;
//! - f_brdf: the principled BRDF (Burley 2012) with its diffuse lobe scaled by 1 − d_t;
//! - f_dt = d_t (1 − metallic) C/π on the other side of the surface: diffuse transmission, a
//!   Lambertian BTDF (Burley 2015's diffTrans, for thin surfaces: leaves, paper, lamp shades).
//!
//! Inside the object light is absorbed by Beer-Lambert, T(d) = exp(−σ_a d) with
//! σ_a = −ln(T_c)/d_T per channel, so light that travelled `transmittance_distance` d_T keeps
//! `transmittance_color` T_c (the definition of glTF's KHR_materials_volume, attenuationColor at
//! attenuationDistance).
//!
//! Clamps: T_c ≥ [`MIN_TRANSMITTANCE`] per channel (a black T_c would make σ_a infinite and
//! σ_a · 0 a NaN at a zero-length segment).

use super::principled::Principled;
use super::rough_dielectric::RoughDielectric;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// Smallest transmittance colour per channel: σ_a stays finite (about 13.8/d_T).
pub const MIN_TRANSMITTANCE: f32 = 1e-6;

impl Principled {
    /// True when some light goes through the surface (specular or diffuse transmission).
    pub fn transmits(&self) -> bool {
        (self.specular_transmission > 0.0 || self.diffuse_transmission > 0.0) && self.metallic < 1.0
    }

    /// w_g = (1 − metallic) · specular_transmission: the rough glass's share of the mixture.
    pub fn glass_share(&self) -> f32 {
        (1.0 - self.metallic) * self.specular_transmission
    }

    /// The rough dielectric boundary of the glass part.
    pub fn boundary(&self) -> RoughDielectric {
        RoughDielectric::new(self.ior, self.roughness)
    }

    /// The tint of one refraction, √C: in and out, light keeps the base colour.
    pub fn refraction_tint(&self) -> Vec3 {
        self.base_color.max(Vec3::ZERO).powf(0.5)
    }

    /// σ_a = −ln(T_c)/d_T per channel (0 for an infinite distance or a white T_c).
    pub fn absorption(&self) -> Vec3 {
        let d = self.transmittance_distance;
        if !(d.is_finite() && d > 0.0) {
            return Vec3::ZERO;
        }
        let t = self.transmittance_color.clamp(Vec3::splat(MIN_TRANSMITTANCE), Vec3::ONE);
        Vec3::new(-t.x.ln(), -t.y.ln(), -t.z.ln()) / d
    }

    /// The diffuse transmission lobe, when the material has one.
    pub fn diffuse_transmission_lobe(&self) -> Option<DiffuseTransmission> {
        let value = self.base_color * (self.diffuse_transmission * (1.0 - self.metallic) * FRAC_1_PI);
        if value == Vec3::ZERO {
            return None;
        }
        // Chosen in proportion to its albedo against the BRDF's lobe weights.
        let dt = (value * std::f32::consts::PI).element_sum();
        let brdf: f32 = self.lobes().as_slice().iter().map(|l| l.weight.element_sum()).sum();
        Some(DiffuseTransmission { value, q: (dt / (dt + brdf)).clamp(0.05, 0.95) })
    }
}

/// The Lambertian BTDF f_dt and the probability q that sampling picks it over the BRDF.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffuseTransmission {
    /// f_dt = d_t (1 − metallic) C/π, in 1/sr.
    pub value: Vec3,
    /// Probability of sampling the other side, in [0.05, 0.95].
    pub q: f32,
}

impl DiffuseTransmission {
    /// A cosine-weighted direction on the side of the surface opposite v (local frame).
    pub fn sample(&self, v: Vec3, u: Vec2) -> Option<Vec3> {
        let l = super::lobe::sample_cosine(u)?;
        Some(if v.z >= 0.0 { Vec3::new(l.x, l.y, -l.z) } else { l })
    }

    /// Its pdf for l on the side opposite v (0 on v's side), before the choice's q.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        if v.z * l.z < 0.0 { l.z.abs() * FRAC_1_PI } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absorption_keeps_the_colour_at_the_distance() {
        let p = Principled { transmittance_color: Vec3::new(0.8, 0.5, 0.2), transmittance_distance: 0.25, ..Principled::default() };
        let s = p.absorption();
        for (k, c) in [0.8f32, 0.5, 0.2].iter().enumerate() {
            assert!(((-s[k] * 0.25).exp() - c).abs() < 1e-6, "channel {k}");
            // Twice the distance: the square.
            assert!(((-s[k] * 0.5).exp() - c * c).abs() < 1e-6);
        }
        assert_eq!(Principled::default().absorption(), Vec3::ZERO);
        let black = Principled { transmittance_color: Vec3::ZERO, transmittance_distance: 1.0, ..Principled::default() };
        assert!(black.absorption().is_finite() && (black.absorption() * 0.0).is_finite());
    }

    #[test]
    fn diffuse_transmission_moves_the_diffuse_albedo_to_the_other_side() {
        // A white Lambert-like principled at normal view: the reflected diffuse plus the
        // transmitted share is the base colour, whatever d_t.
        for dt in [0.0f32, 0.3, 1.0] {
            let p = Principled { base_color: Vec3::splat(0.6), diffuse_transmission: dt, specular: 0.0, ..Principled::default() };
            let front = p.eval_lobes(Vec3::Z, Vec3::Z).diffuse * std::f32::consts::PI;
            let back = p.diffuse_transmission_lobe().map_or(Vec3::ZERO, |d| d.value * std::f32::consts::PI);
            assert!((front + back - Vec3::splat(0.6)).abs().max_element() < 1e-6, "d_t {dt}: {front} + {back}");
            assert!((back - Vec3::splat(0.6 * dt)).abs().max_element() < 1e-6);
        }
        // Sampled on the other side, with its cosine pdf; never on v's side.
        let d = Principled { diffuse_transmission: 0.5, ..Principled::default() }.diffuse_transmission_lobe().unwrap();
        let l = d.sample(Vec3::Z, Vec2::new(0.3, 0.7)).unwrap();
        assert!(l.z < 0.0 && (d.pdf(Vec3::Z, l) - (-l.z) / std::f32::consts::PI).abs() < 1e-7);
        assert_eq!(d.pdf(Vec3::Z, -l), 0.0);
        assert!(d.sample(Vec3::NEG_Z, Vec2::new(0.3, 0.7)).unwrap().z > 0.0);
    }

    #[test]
    fn the_glass_share_and_tint() {
        let p = Principled { specular_transmission: 0.8, metallic: 0.25, base_color: Vec3::new(0.81, 0.25, 0.04), ..Principled::default() };
        assert!((p.glass_share() - 0.6).abs() < 1e-6);
        assert!((p.refraction_tint() * p.refraction_tint() - p.base_color).abs().max_element() < 1e-6);
        assert!(!Principled { specular_transmission: 1.0, metallic: 1.0, ..Principled::default() }.transmits());
        assert!(!Principled::default().transmits());
    }
}
