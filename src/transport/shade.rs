//! The integrator at one point: the lights' incidents through shading, plus what the
//! environment, a mirror or glass brings (the reflection and transmission layers).

use super::environment::environment_light;
use super::glass::glass_light;
use super::incidents::incidents;
use super::lighting::{At, Lighting};
use crate::scene::{Material, Model};
use crate::shading::Components;
use crate::shading::classic::EvalCounts;
use crate::shading::shade::shade;
use glam::Vec3;

/// Shades one point `at` (unit normal `at.n`, view `v` unit) of material `m` lit by
/// `lighting`: its lights' incidents and, when the render has one, the environment's light
/// (the reflection layer).
#[inline]
pub fn shade_point(m: &Material, lighting: &Lighting, global_ambient: Vec3, at: At<f32>, v: Vec3, counts: &mut EvalCounts) -> Components {
    shade_point_at_depth(m, lighting, global_ambient, at, v, counts, 0)
}

/// [`shade_point`] for a point seen through `depth` mirrors.
#[inline]
pub fn shade_point_at_depth(
    m: &Material,
    lighting: &Lighting,
    global_ambient: Vec3,
    at: At<f32>,
    v: Vec3,
    counts: &mut EvalCounts,
    depth: u32,
) -> Components {
    let n = Vec3::from(at.n);
    let mut c = shade(m, incidents::<f32>(lighting, &at, true), global_ambient, n, v, counts);
    if let Some(env) = &lighting.env {
        // What a traced ray finds is shaded here again, one step deeper.
        let hit = |m: &Material, at: At<f32>, v: Vec3, counts: &mut EvalCounts, depth: u32| {
            shade_point_at_depth(m, lighting, global_ambient, at, v, counts, depth)
        };
        if let Model::Glass(g) = &m.model {
            let (r, t) = glass_light(g, lighting, env, &hit, &at, v, counts, depth);
            c.reflection += r;
            c.transmission += t;
        } else {
            c.reflection += environment_light(m, lighting, env, &hit, &at, v, counts, depth);
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::Light;
    use crate::light::{LightKind, Point};
    use crate::shading::brdf::Brdf;
    use crate::shading::diffuse::Diffuse;
    use crate::shading::material::Model;

    /// A point light through the seam: physically based shading falls off as 1/r² and ignores
    /// the classic attenuation, the classic equation applies d = 1/(S_c + S_l r + S_q r²).
    #[test]
    fn a_point_light_reaches_each_family_as_it_defines_light() {
        let light = |h: f32| Light {
            kind: LightKind::Point(Point { position: Vec3::new(0.0, 0.0, h) }),
            radiance: Vec3::ONE,
            specular: Vec3::ONE,
            ambient: Vec3::ZERO,
            attenuation: Vec3::new(1.0, 5.0, 0.0),
            samples: 1,
            shadows: None,
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
                clamp_n_dot_l: true,
            }),
            ambient: Vec3::ZERO,
            emission: Vec3::ZERO,
        };
        let at = |m: &Material, h: f32| {
            let lighting = Lighting::unshadowed(vec![light(h)]);
            shade_point(m, &lighting, Vec3::ZERO, At::point(Vec3::ZERO, Vec3::Z), Vec3::Z, &mut EvalCounts::default()).diffuse.x
        };
        assert!((at(&physical, 1.0) / at(&physical, 2.0) - 4.0).abs() < 1e-5);
        assert!((at(&physical, 1.0) - std::f32::consts::FRAC_1_PI).abs() < 1e-6, "classic attenuation is ignored");
        assert!((at(&classic, 1.0) - 1.0 / 6.0).abs() < 1e-6 && (at(&classic, 2.0) - 1.0 / 11.0).abs() < 1e-6);
    }
}
