//! The course's illumination equation for one surface point, term by term.

use super::blinn_phong::blinn_phong;
use super::components::Components;
use super::lambert::lambert;
use super::light::incident;
use super::phong::phong;
use crate::scene::{ClassicModel, Light, Material};
use glam::Vec3;

/// Evaluates I_tot = L_glob⊗K_amb + L_emi + Σ_k C_spot^k { I_amb^k + d^k (I_diff^k + I_spec^k) }.
///
/// Preconditions: `n` and `v` normalized; `p` is the world position of the point.
/// Returns the terms separately (see [`Components`]); `counts` receives the number of
/// light and specular evaluations performed.
#[inline(always)]
pub fn shade_classic(
    m: &Material,
    lights: &[Light],
    global_ambient: Vec3,
    p: Vec3,
    n: Vec3,
    v: Vec3,
    counts: &mut EvalCounts,
) -> Components {
    let mut c = Components { emission: m.emission, ambient: global_ambient * m.ambient, ..Components::ZERO };
    let has_specular = m.has_specular();
    let has_diffuse = m.diffuse != Vec3::ZERO;
    for light in lights {
        counts.lights += 1;
        let inc = incident(light, p);
        if inc.c_spot <= 0.0 {
            continue;
        }
        c.ambient += inc.c_spot * light.ambient * m.ambient;
        if inc.l == Vec3::ZERO {
            continue;
        }
        let w = inc.c_spot * inc.d;
        let n_dot_l = n.dot(inc.l);
        if has_diffuse && n_dot_l > 0.0 {
            counts.diffuse += 1;
            c.diffuse += w * lambert(n_dot_l) * m.diffuse * light.radiance;
        }
        if has_specular && n_dot_l > 0.0 {
            counts.specular += 1;
            let s = match m.model {
                ClassicModel::Phong => phong(n, inc.l, v, m.shininess),
                ClassicModel::BlinnPhong => blinn_phong(n, inc.l, v, m.shininess),
                ClassicModel::Lambert => 0.0,
            };
            c.specular += w * s * m.specular * light.radiance;
        }
    }
    c
}

/// How much work shading did (summed into the render stats).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EvalCounts {
    /// Light evaluations (one per light per shading point).
    pub lights: u64,
    /// Diffuse-term evaluations (lit side only).
    pub diffuse: u64,
    /// Specular-lobe evaluations.
    pub specular: u64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::LightKind;

    fn mat(model: ClassicModel) -> Material {
        Material {
            name: "m".into(),
            model,
            ambient: Vec3::splat(0.2),
            diffuse: Vec3::new(0.8, 0.4, 0.2),
            specular: Vec3::splat(0.5),
            shininess: 16.0,
            emission: Vec3::new(0.0, 0.0, 0.1),
            physical: None,
        }
    }

    #[test]
    fn equation_term_by_term() {
        let m = mat(ClassicModel::BlinnPhong);
        let l_dir = Vec3::new(0.0, 1.0, 1.0).normalize();
        let light = Light {
            kind: LightKind::Directional { direction: -l_dir },
            radiance: Vec3::splat(2.0),
            ambient: Vec3::splat(0.5),
            attenuation: Vec3::X,
        };
        let n = Vec3::Z;
        let v = Vec3::Z;
        let mut k = EvalCounts::default();
        let c = shade_classic(&m, &[light], Vec3::splat(0.1), Vec3::ZERO, n, v, &mut k);
        assert_eq!(c.emission, m.emission);
        assert!((c.ambient - (0.1 * m.ambient + 0.5 * m.ambient)).length() < 1e-6);
        let cos = l_dir.z;
        assert!((c.diffuse - cos * m.diffuse * 2.0).length() < 1e-6);
        let h = (l_dir + v).normalize();
        assert!((c.specular - h.z.powf(16.0) * m.specular * 2.0).length() < 1e-5);
        assert_eq!(k, EvalCounts { lights: 1, diffuse: 1, specular: 1 });
    }

    #[test]
    fn lambert_material_never_evaluates_specular() {
        let m = Material { specular: Vec3::ZERO, ..mat(ClassicModel::Lambert) };
        let light =
            Light { kind: LightKind::Directional { direction: -Vec3::Z }, radiance: Vec3::ONE, ambient: Vec3::ZERO, attenuation: Vec3::X };
        let mut k = EvalCounts::default();
        let c = shade_classic(&m, &[light], Vec3::ZERO, Vec3::ZERO, Vec3::Z, Vec3::Z, &mut k);
        assert_eq!(c.specular, Vec3::ZERO);
        assert_eq!(k.specular, 0);
        assert!((c.diffuse - m.diffuse).length() < 1e-6);
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use crate::scene::LightKind;
    use proptest::prelude::*;

    fn unit() -> impl Strategy<Value = Vec3> {
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_filter_map("non-zero", |(x, y, z)| Vec3::new(x, y, z).try_normalize())
    }

    proptest! {
        /// Every term is finite and non-negative for any unit n, l, v and any exponent in range.
        #[test]
        fn terms_are_finite_and_non_negative(n in unit(), l in unit(), v in unit(), k in prop::sample::select(vec![0.0f32, 1e-6, 1.0, 32.0, 1e4, 1e6]), phong in any::<bool>()) {
            let model = if phong { ClassicModel::Phong } else { ClassicModel::BlinnPhong };
            let m = Material { name: "m".into(), model, ambient: Vec3::ONE, diffuse: Vec3::ONE, specular: Vec3::ONE, shininess: k, emission: Vec3::ZERO, physical: None };
            let light = Light { kind: LightKind::Directional { direction: -l }, radiance: Vec3::ONE, ambient: Vec3::ONE, attenuation: Vec3::X };
            let c = shade_classic(&m, &[light], Vec3::ONE, Vec3::ZERO, n, v, &mut EvalCounts::default());
            prop_assert!(c.is_finite());
            for t in [c.ambient, c.diffuse, c.specular] {
                prop_assert!(t.min_element() >= 0.0);
            }
            // The classic terms are bounded by the coefficients: N·L ≤ 1 and the lobe ≤ 1.
            prop_assert!(c.diffuse.max_element() <= 1.0 + 1e-6 && c.specular.max_element() <= 1.0 + 1e-6);
        }
    }

    #[test]
    fn grazing_and_opposite_directions() {
        let m = Material {
            name: "m".into(),
            model: ClassicModel::BlinnPhong,
            ambient: Vec3::ZERO,
            diffuse: Vec3::ONE,
            specular: Vec3::ONE,
            shininess: 1e6,
            emission: Vec3::ZERO,
            physical: None,
        };
        let n = Vec3::Z;
        // Light exactly at grazing (N·L = 0), and l = −v.
        for (l, v) in [(Vec3::X, Vec3::Z), (Vec3::new(1.0, 0.0, 1e-7).normalize(), Vec3::new(-1.0, 0.0, -1e-7).normalize())] {
            let light =
                Light { kind: LightKind::Directional { direction: -l }, radiance: Vec3::ONE, ambient: Vec3::ZERO, attenuation: Vec3::X };
            let c = shade_classic(&m, &[light], Vec3::ZERO, Vec3::ZERO, n, v, &mut EvalCounts::default());
            assert!(c.is_finite() && c.total().min_element() >= 0.0);
            assert!(c.diffuse.max_element() < 1e-6);
        }
    }
}
