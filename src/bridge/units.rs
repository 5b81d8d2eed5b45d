//! Light and material units between glTF 2.0 and lessons.
//!
//! KHR_lights_punctual gives point and spot lights in candela (lm/sr) and directional
//! lights in lux (lm/m²) (KHR_lights_punctual, "Light Types"). A lesson's lights are
//! radiometric: a point or spot light's `intensity` is its radiant intensity I (W/sr, so
//! E = I/r²), a directional light's is its irradiance E⊥ (W/m²). The bridge uses the
//! luminous efficacy 683 lm/W, as Blender's glTF add-on does (`PBR_WATTS_TO_LUMENS = 683`,
//! io_scene_gltf2/blender/com/conversion.py), so a file exported from Blender converts
//! back to the watts Blender shows: a Blender point light of P watts is exported as
//! P·683/(4π) cd, which is I = P/(4π) W/sr here, the radiant intensity Cycles gives it.

use std::f32::consts::PI;

/// Luminous efficacy used for every conversion, lm/W (Blender's glTF add-on).
pub const LUMENS_PER_WATT: f32 = 683.0;

/// A point or spot light's radiant intensity (W/sr) from candela.
pub fn watts_per_sr_from_candela(cd: f32) -> f32 {
    cd / LUMENS_PER_WATT
}

/// Candela from a radiant intensity in W/sr.
pub fn candela_from_watts_per_sr(i: f32) -> f32 {
    i * LUMENS_PER_WATT
}

/// A directional light's irradiance (W/m²) from lux.
pub fn irradiance_from_lux(lux: f32) -> f32 {
    lux / LUMENS_PER_WATT
}

/// Lux from an irradiance in W/m².
pub fn lux_from_irradiance(e: f32) -> f32 {
    e * LUMENS_PER_WATT
}

/// The power Blender shows for a point or spot light of radiant intensity `i` (W/sr): 4πI.
pub fn blender_watts(i: f32) -> f32 {
    4.0 * PI * i
}

/// The glTF spot's angular falloff: smoothstep-like from 1 inside `inner` to 0 at `outer`
/// (radians), the curve KHR_lights_punctual's reference implementation gives:
/// a = clamp((cos θ − cos θ_o) / (cos θ_i − cos θ_o), 0, 1)².
pub fn spot_falloff(theta: f32, inner: f32, outer: f32) -> f32 {
    let scale = 1.0 / (inner.cos() - outer.cos()).max(1e-3);
    let a = ((theta.cos() - outer.cos()) * scale).clamp(0.0, 1.0);
    a * a
}

/// The glTF spot falloff as a lesson's `profile`: (θ in degrees, factor) from the axis
/// to `outer`, linear between the points (at most 32), 1 up to `inner`.
pub fn spot_profile(inner: f32, outer: f32) -> Vec<(f32, f32)> {
    let (inner, outer) = (inner.clamp(0.0, outer), outer.clamp(1e-3, std::f32::consts::FRAC_PI_2));
    let mut points = vec![(0.0, 1.0)];
    if inner > 1e-4 {
        points.push((inner.to_degrees(), 1.0));
    }
    const STEPS: usize = 16;
    for k in 1..=STEPS {
        let theta = inner + (outer - inner) * k as f32 / STEPS as f32;
        points.push((theta.to_degrees(), spot_falloff(theta, inner, outer)));
    }
    points
}

/// Disney's `specular` (0.5 ↔ F0 = 0.04) from an index of refraction and
/// KHR_materials_specular's factor: F0 = ((η − 1)/(η + 1))² × factor, specular = F0 / 0.08
/// (Burley 2012, §5.6), at most 1.
pub fn disney_specular(ior: f32, factor: f32) -> f32 {
    let r = (ior - 1.0) / (ior + 1.0);
    (r * r * factor / 0.08).clamp(0.0, 1.0)
}

/// The index of refraction whose F0 is Disney's `specular` × 0.08 (the inverse of
/// [`disney_specular`] with factor 1), from 1 to 10.
pub fn ior_from_disney_specular(specular: f32) -> f32 {
    let r = (0.08 * specular).max(0.0).sqrt().min(0.8181818);
    ((1.0 + r) / (1.0 - r)).clamp(1.0, 10.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blender_units_round_trip() {
        // A 1000 W Blender point light: 1000 × 683 / 4π = 54351 cd (the add-on's export).
        let cd = 1000.0 * LUMENS_PER_WATT / (4.0 * PI);
        assert!((cd - 54_351.4).abs() < 0.5, "{cd}");
        let i = watts_per_sr_from_candela(cd);
        assert!((blender_watts(i) - 1000.0).abs() < 1e-2);
        // A sun of 3 W/m² is 2049 lux.
        assert_eq!(lux_from_irradiance(3.0), 2049.0);
        assert_eq!(irradiance_from_lux(2049.0), 3.0);
        assert_eq!(candela_from_watts_per_sr(watts_per_sr_from_candela(100.0)), 100.0);
    }

    #[test]
    fn the_spot_profile_follows_the_specification_curve() {
        let (inner, outer) = (20f32.to_radians(), 40f32.to_radians());
        let p = spot_profile(inner, outer);
        assert!(p.len() <= 32);
        assert_eq!(p[0], (0.0, 1.0));
        assert!((p[1].0 - 20.0).abs() < 1e-4 && p[1].1 == 1.0);
        let last = p.last().unwrap();
        assert!((last.0 - 40.0).abs() < 1e-3 && last.1 == 0.0);
        assert!(p.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 >= w[1].1), "θ rises, the factor falls");
        // Halfway in cos: a = 0.5, a² = 0.25.
        let mid = ((inner.cos() + outer.cos()) / 2.0).acos();
        assert!((spot_falloff(mid, inner, outer) - 0.25).abs() < 1e-5);
    }

    #[test]
    fn glass_at_1_5_is_disney_specular_one_half() {
        assert!((disney_specular(1.5, 1.0) - 0.5).abs() < 1e-6);
        assert!((ior_from_disney_specular(0.5) - 1.5).abs() < 1e-5);
        assert_eq!(disney_specular(1.5, 0.0), 0.0);
    }
}
