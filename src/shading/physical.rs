//! Physically based shading of one point: L_o = Σ_k f(l, v) E_k (n·l), split into layers.
//!
//! Lights are radiometric here (DESIGN.md): a directional light's colour × intensity is the
//! irradiance E⊥ on a surface facing it; a point or spot light's is its radiant intensity I
//! (W/sr), so E⊥ = I / r² (the lesson's S_c, S_l, S_q apply to the classic models only).
//! A spot keeps its cone factor C_spot. The ambient term treats L_glob (and each light's
//! ambient part) as uniform incident radiance seen through the material's ambient
//! reflectance: L_o = K_amb ⊗ L_glob (for a Lambert surface K_amb = ρ).

use super::brdf::{Brdf, local_frame, to_local};
use super::classic::EvalCounts;
use super::components::Components;
use super::incident::Incident;
use super::lobe::Part;
use super::material::Material;
use glam::Vec3;

/// A BRDF value split into the frame's layers (1/sr, cosine excluded).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Lobes {
    /// Diffuse lobes (Lambert, Oren-Nayar, Disney diffuse, subsurface and sheen).
    pub diffuse: Vec3,
    /// Specular lobes (microfacet, Phong lobes, Disney specular and clearcoat).
    pub specular: Vec3,
}

/// A number for `explain`: four significant digits, trailing zeros dropped (0.16000001 → 0.16).
fn num(x: f32) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (3 - x.abs().log10().floor() as i32).clamp(0, 9) as usize;
    let s = format!("{x:.digits$}");
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
}

/// A colour for `explain`: one number when grey, else `[r, g, b]`.
fn rgb(v: Vec3) -> String {
    if v.x == v.y && v.y == v.z { num(v.x) } else { format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z)) }
}

/// The BRDF's equation with its values substituted, for `explain` (names as in the course
/// and docs/models.md; the equations of each model's module docs).
pub fn describe(brdf: &Brdf) -> String {
    use super::microfacet::{Fresnel, Masking, Ndf};
    match brdf {
        Brdf::Diffuse(m) => format!("f = ρ/π (Lambert) = {}/π", rgb(m.albedo)),
        Brdf::OrenNayar(m) => {
            let s2 = m.sigma * m.sigma;
            match m.model {
                super::oren_nayar::OrenNayarModel::Full => format!(
                    "f = ρ/π [C1 + cos Δφ C2 tan β + (1 − |cos Δφ|) C3 tan((α + β)/2)] + interreflection (Oren-Nayar, full model), ρ = {}, σ = {}°, C1 = 1 − 0.5 σ²/(σ² + 0.33) = {}",
                    rgb(m.albedo),
                    num(m.sigma.to_degrees()),
                    num(1.0 - 0.5 * s2 / (s2 + 0.33))
                ),
                super::oren_nayar::OrenNayarModel::Qualitative => format!(
                    "f = ρ/π [A + B max(0, cos Δφ) sin α tan β] (Oren-Nayar, qualitative model) = {}/π [{} + {} max(0, cos Δφ) sin α tan β], σ = {}°",
                    rgb(m.albedo),
                    num(1.0 - 0.5 * s2 / (s2 + 0.33)),
                    num(0.45 * s2 / (s2 + 0.09)),
                    num(m.sigma.to_degrees())
                ),
            }
        }
        Brdf::CookTorrance(m) => {
            let d = match m.ndf {
                Ndf::Blinn => "normalized Blinn",
                Ndf::Beckmann => "Beckmann",
                Ndf::Ggx => "GGX (Trowbridge-Reitz)",
                Ndf::Gaussian => "Gaussian (Torrance-Sparrow)",
            };
            let g = match m.masking {
                Masking::CookTorrance => "Cook-Torrance V-cavity",
                Masking::Smith => "Smith, separable",
                Masking::SmithCorrelated => "Smith, height-correlated",
            };
            let f = match m.fresnel {
                Fresnel::Schlick { f0 } => format!("Schlick with F₀ = {}", rgb(f0)),
                Fresnel::Dielectric { eta } => format!("exact dielectric with η = {}", num(eta)),
                Fresnel::Conductor { eta, k } => format!("exact conductor with η = {}, κ = {}", rgb(eta), rgb(k)),
                Fresnel::None => "none (F = 1)".to_string(),
            };
            format!(
                "f = k_s D G F / (4 (n·l)(n·v)) + ρ/π = {}⊗D G F / (4 (n·l)(n·v)) + {}/π with D = {d}, α = {}, G = {g}, F = {f}",
                rgb(m.specular),
                rgb(m.diffuse),
                num(m.alpha)
            )
        }
        Brdf::Principled(m) => {
            let c = m.base_color;
            let (_, spec0) = m.tint_and_spec0();
            let (ax, ay) = m.alphas();
            let alpha = if ax == ay { format!("α = {}", num(ax)) } else { format!("α_x = {}, α_y = {}", num(ax), num(ay)) };
            format!(
                "f = (1 − {m})[{c}/π mix(f_d, f_ss, {ss}) + {sh} mix(1, C_tint, {sht}) F_H] + D_GTR2 G F / (4 (n·l)(n·v)) + 0.25·{cc} D_GTR1 mix(0.04, 1, F_H) G / (4 (n·l)(n·v)) (Disney principled) with F_D90 = 0.5 + 2·{r} cos²θ_d, GTR2 {alpha}, F = mix(C_spec0, 1, F_H), C_spec0 = {spec0}, GTR1 α = {a1}",
                m = num(m.metallic),
                c = rgb(c),
                ss = num(m.subsurface),
                sh = num(m.sheen),
                sht = num(m.sheen_tint),
                cc = num(m.clearcoat),
                r = num(m.roughness),
                spec0 = rgb(spec0),
                a1 = num(m.clearcoat_alpha()),
            )
        }
        Brdf::NormalizedPhong(m) => {
            format!(
                "f = k_d/π + k_s (n+2)/(2π) max(R·V, 0)^n = {}/π + {} ({}/(2π)) max(R·V, 0)^{}",
                rgb(m.diffuse),
                rgb(m.specular),
                num(m.shininess + 2.0),
                num(m.shininess)
            )
        }
        Brdf::NormalizedBlinnPhong(m) => {
            format!(
                "f = k_d/π + k_s (n+8)/(8π) max(N·H, 0)^n = {}/π + {} ({}/(8π)) max(N·H, 0)^{}",
                rgb(m.diffuse),
                rgb(m.specular),
                num(m.shininess + 8.0),
                num(m.shininess)
            )
        }
    }
}

/// Shades one point with physically based material `m` whose BRDF is `brdf`: one term per
/// incident light.
///
/// Lights are radiometric: E⊥ = radiance × 1/r² (1 for directional lights); a spot keeps
/// its cone factor and a shadow its visibility. Preconditions: `n`, `v` normalized.
#[inline]
pub fn shade_physical(
    m: &Material,
    brdf: &Brdf,
    incidents: impl IntoIterator<Item = Incident<f32>>,
    global_ambient: Vec3,
    n: Vec3,
    v: Vec3,
    counts: &mut EvalCounts,
) -> Components {
    let mut c = Components { emission: m.emission, ambient: global_ambient * m.ambient, ..Components::ZERO };
    let (t, b) = local_frame(n);
    let v_local = to_local(v, t, b, n);
    let parts = brdf.lobes();
    let lobes_on = (parts.has(Part::Diffuse), parts.has(Part::Specular));
    for inc in incidents {
        counts.lights += 1;
        if inc.ambient_only {
            c.ambient += inc.ambient * m.ambient;
            continue;
        }
        let l = Vec3::from(inc.l);
        // A light exactly at the point has no direction: it contributes nothing.
        if l == Vec3::ZERO || inc.c_spot <= 0.0 {
            continue;
        }
        c.ambient += inc.c_spot * inc.ambient * m.ambient;
        let l_local = to_local(l, t, b, n);
        // One-sided BRDFs: nothing from below the surface or towards a viewer below it.
        if l_local.z <= 0.0 || v_local.z <= 0.0 {
            continue;
        }
        counts.diffuse += lobes_on.0 as u64;
        counts.specular += lobes_on.1 as u64;
        let f = brdf.eval_parts(l_local, v_local);
        let e = inc.radiance * inc.inv_r2;
        let w = e * (inc.c_spot * l_local.z * inc.visibility);
        c.diffuse += f.diffuse * w;
        c.specular += f.specular * w;
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::cook_torrance::CookTorrance;
    use crate::shading::diffuse::Diffuse;
    use crate::shading::incident::directional;

    #[test]
    fn describe_uses_the_course_names_and_short_numbers() {
        let ct = CookTorrance { alpha: 0.4f32 * 0.4, ..CookTorrance::default() };
        let d = describe(&Brdf::CookTorrance(ct));
        assert!(d.contains("α = 0.16,") && d.contains("GGX (Trowbridge-Reitz)") && d.contains("Schlick with F₀ = 0.04"), "{d}");
        assert!(d.contains("= 1⊗D G F / (4 (n·l)(n·v)) + 0/π"), "values substituted: {d}");
        let p = crate::shading::principled::Principled {
            base_color: Vec3::ONE,
            metallic: 0.0,
            roughness: 0.5,
            specular: 0.5,
            ..Default::default()
        };
        let d = describe(&Brdf::Principled(p));
        // C_spec0 = 0.08 · 0.5 for a white dielectric; α = 0.5².
        assert!(d.contains("C_spec0 = 0.04") && d.contains("GTR2 α = 0.25") && d.contains("(1 − 0)[1/π"), "{d}");
        let on = crate::shading::oren_nayar::OrenNayar::from_degrees(
            Vec3::splat(0.8),
            90.0,
            crate::shading::oren_nayar::OrenNayarModel::Qualitative,
        );
        // σ = π/2: A = 1 − 0.5·2.467/2.797 = 0.559, B = 0.45·2.467/2.557 = 0.4342.
        assert!(describe(&Brdf::OrenNayar(on)).contains("= 0.8/π [0.559 + 0.4342 max(0, cos Δφ)"), "{}", describe(&Brdf::OrenNayar(on)));
        assert!(!d.contains("Vec3") && !d.contains('{'), "{d}");
        assert_eq!(
            (num(0.16000001), num(2.0), num(1234.5678), num(0.0001234)),
            ("0.16".into(), "2".into(), "1235".into(), "0.0001234".into())
        );
    }

    fn material(brdf: Brdf) -> Material {
        Material { name: "m".into(), model: crate::shading::material::Model::Physical(brdf), ambient: Vec3::ZERO, emission: Vec3::ZERO }
    }

    fn shade_with(m: &Material, incidents: &[Incident<f32>], n: Vec3, v: Vec3) -> Components {
        shade_physical(m, m.brdf().unwrap(), incidents.iter().copied(), Vec3::ZERO, n, v, &mut EvalCounts::default())
    }

    #[test]
    fn lambert_under_a_directional_light_is_rho_over_pi_times_e_cos() {
        let brdf = Brdf::Diffuse(Diffuse { albedo: Vec3::new(0.5, 0.25, 1.0) });
        let l = Vec3::new(0.0, 0.6, 0.8);
        let c = shade_with(&material(brdf), &[directional(l, Vec3::splat(3.0), Vec3::ZERO)], Vec3::Z, Vec3::Z);
        let expect = Vec3::new(0.5, 0.25, 1.0) / std::f32::consts::PI * 3.0 * 0.8;
        assert!((c.diffuse - expect).abs().max_element() < 1e-6, "{} vs {expect}", c.diffuse);
        assert_eq!(c.specular, Vec3::ZERO);
    }

    #[test]
    fn irradiance_is_radiance_times_inv_r2_and_ignores_classic_attenuation() {
        let brdf = Brdf::Diffuse(Diffuse { albedo: Vec3::ONE });
        // A point light at distance h above: 1/r² = 1/h², classic d = 1/(1 + 5h) (ignored here).
        let at = |h: f32| {
            let i = Incident {
                distance: h,
                attenuation: 1.0 / (1.0 + 5.0 * h),
                inv_r2: 1.0 / (h * h),
                ..directional(Vec3::Z, Vec3::ONE, Vec3::ZERO)
            };
            shade_with(&material(brdf), &[i], Vec3::Z, Vec3::Z).diffuse.x
        };
        assert!((at(1.0) / at(2.0) - 4.0).abs() < 1e-5);
        assert!((at(1.0) - std::f32::consts::FRAC_1_PI).abs() < 1e-6, "classic attenuation is ignored");
        // Half visible: half the light.
        let half = Incident { visibility: 0.5, ..directional(Vec3::Z, Vec3::ONE, Vec3::ZERO) };
        let full = shade_with(&material(brdf), &[directional(Vec3::Z, Vec3::ONE, Vec3::ZERO)], Vec3::Z, Vec3::Z).diffuse.x;
        assert_eq!(shade_with(&material(brdf), &[half], Vec3::Z, Vec3::Z).diffuse.x, 0.5 * full);
    }

    #[test]
    fn lobes_add_up_to_the_brdf() {
        let brdf = Brdf::CookTorrance(CookTorrance { diffuse: Vec3::splat(0.3), ..CookTorrance::default() });
        let l = Vec3::new(0.3, 0.1, 0.9).normalize();
        let v = Vec3::new(-0.2, 0.0, 1.0).normalize();
        let lobes = brdf.eval_parts(l, v);
        assert!(((lobes.diffuse + lobes.specular) - brdf.eval(l, v)).abs().max_element() < 1e-6);
        assert!(lobes.specular.x > 0.0 && lobes.diffuse.x > 0.0);
    }
}
