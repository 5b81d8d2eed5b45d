//! Lights → incidents → shading: the seam between the scene's lights and shading.
//!
//! Every shaded point asks each light for its [`Incident`](crate::shading::incident::Incident)
//! (today one per light; an area light will give several, a shadowed light a visibility
//! below 1) and hands them to shading, which knows nothing of light kinds.

use crate::scene::{Light, Material};
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::shading::incident::Incident;
use crate::shading::shade::shade;
use crate::simd::lanes::{Lanes, V3};
use glam::Vec3;

/// The incidents of `lights` at point `p` (one lane) or lanes of points: every shaded point,
/// scalar or in a bundle, asks here, so shadows and area lights change one place.
#[inline(always)]
pub fn incidents<F: Lanes>(lights: &[Light], p: V3<F>) -> Incidents<'_, F> {
    Incidents { lights: lights.iter(), p }
}

/// The iterator [`incidents`] returns.
#[derive(Debug, Clone)]
pub struct Incidents<'a, F> {
    lights: std::slice::Iter<'a, Light>,
    p: V3<F>,
}

impl<F: Lanes> Iterator for Incidents<'_, F> {
    type Item = Incident<F>;

    // Inlined into the shading bundles (and their AVX functions): measured 546e6 → 612e6
    // instructions on the sphere bench when `Map::next` was left out of line.
    #[inline(always)]
    fn next(&mut self) -> Option<Incident<F>> {
        self.lights.next().map(|l| l.incident(self.p))
    }
}

/// Shades one point `p` (normal `n`, view `v`, both unit) of material `m` lit by `lights`.
#[inline]
pub fn shade_point(m: &Material, lights: &[Light], global_ambient: Vec3, p: Vec3, n: Vec3, v: Vec3, counts: &mut EvalCounts) -> Components {
    shade(m, incidents::<f32>(lights, p.into()), global_ambient, n, v, counts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::LightKind;
    use crate::shading::brdf::Brdf;
    use crate::shading::diffuse::Diffuse;
    use crate::shading::material::Model;

    /// A point light through the seam: physically based shading falls off as 1/r² and ignores
    /// the classic attenuation, the classic equation applies d = 1/(S_c + S_l r + S_q r²).
    #[test]
    fn a_point_light_reaches_each_family_as_it_defines_light() {
        let light = |h: f32| Light {
            kind: LightKind::Point { position: Vec3::new(0.0, 0.0, h) },
            radiance: Vec3::ONE,
            ambient: Vec3::ZERO,
            attenuation: Vec3::new(1.0, 5.0, 0.0),
        };
        let physical = Material {
            name: "p".into(),
            model: Model::Physical(Brdf::Diffuse(Diffuse { albedo: Vec3::ONE })),
            ambient: Vec3::ZERO,
            emission: Vec3::ZERO,
        };
        let classic = Material {
            name: "c".into(),
            model: Model::Classic(crate::scene::Classic {
                model: crate::scene::ClassicModel::Lambert,
                diffuse: Vec3::ONE,
                specular: Vec3::ZERO,
                shininess: 1.0,
            }),
            ambient: Vec3::ZERO,
            emission: Vec3::ZERO,
        };
        let at = |m: &Material, h: f32| {
            shade_point(m, &[light(h)], Vec3::ZERO, Vec3::ZERO, Vec3::Z, Vec3::Z, &mut EvalCounts::default()).diffuse.x
        };
        assert!((at(&physical, 1.0) / at(&physical, 2.0) - 4.0).abs() < 1e-5);
        assert!((at(&physical, 1.0) - std::f32::consts::FRAC_1_PI).abs() < 1e-6, "classic attenuation is ignored");
        assert!((at(&classic, 1.0) - 1.0 / 6.0).abs() < 1e-6 && (at(&classic, 2.0) - 1.0 / 11.0).abs() < 1e-6);
    }
}
