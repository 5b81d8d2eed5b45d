//! `[material.NAME]` tables: the classic models and the physically based BRDFs.

use super::{R, Validator};
use crate::lesson::LessonError;
use crate::lesson::kinds::{FresnelKind, ModelKind, choices};
use crate::lesson::path::KeyPath;
use crate::lesson::raw::{RawColor, RawMaterial, RawParam};
use crate::lesson::spans::Target;
use crate::lesson::texture::{MaterialMaps, TextureRef};
use crate::shading::brdf::Brdf;
use crate::shading::cook_torrance::CookTorrance;
use crate::shading::diffuse::Diffuse;
use crate::shading::glass::Glass;
use crate::shading::material::{Classic, ClassicModel, Material, Model};
use crate::shading::metals::{self, Metal};
use crate::shading::microfacet::{Fresnel, Masking, Ndf};
use crate::shading::mirror::Mirror;
use crate::shading::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use crate::shading::oren_nayar::{OrenNayar, OrenNayarModel};
use crate::shading::principled::Principled;
use glam::Vec3;

/// The range of a glass `ior`: above 0 (η < 1 is a bubble of a thinner medium, η = 1 lets
/// rays through unbent) and no denser than any real material (diamond 2.4, rutile 2.9).
const GLASS_IOR: (f64, f64) = (0.1, 10.0);

/// A material's constant parameters: a textured one holds a placeholder (the value the
/// key's default would be), which the renderer replaces per shaded point.
struct Consts {
    ambient: Option<RawColor>,
    diffuse: Option<RawColor>,
    specular: Option<RawColor>,
    emission: Option<RawColor>,
    eta: Option<RawColor>,
    k: Option<RawColor>,
    base_color: Option<RawColor>,
    tint: Option<RawColor>,
    roughness: Option<f64>,
    metallic: Option<f64>,
}

impl Validator<'_> {
    pub(super) fn material(&self, p: &KeyPath, name: &str, m: &RawMaterial) -> R<(Material, MaterialMaps)> {
        let kind = self.choice(&p.key("model"), &m.model, &choices(ModelKind::ALL, ModelKind::name))?;
        // Every key the model does not read is reported, and beside them the first bad value:
        // one run shows a student every mistake of the table.
        let unused = self.unused_keys(p, kind, m);
        match self.material_values(p, name, kind, m) {
            Ok(done) if unused.is_empty() => Ok(done),
            Ok(_) => Err(LessonError::combine(unused).expect("not empty")),
            Err(e) => Err(LessonError::combine(unused.into_iter().chain([e]).collect()).expect("not empty")),
        }
    }

    /// The errors for the keys of `m` that model `kind` does not read, one each.
    fn unused_keys(&self, p: &KeyPath, kind: ModelKind, m: &RawMaterial) -> Vec<LessonError> {
        let (allowed, why) = match kind {
            // Keys of the physically based models mean nothing to the classic ones (Lambert's
            // unused K_spec and K_shi get their own message in `material_values`).
            ModelKind::Classic(_) => (
                ModelKind::Classic(ClassicModel::Phong).keys(),
                format!("by `{}` (a classic model: K_amb, K_diff, K_spec, K_shi, L_emi)", m.model),
            ),
            _ => (kind.keys(), format!("by `{}` (it reads: {})", kind.name(), kind.keys().join(", "))),
        };
        present_keys(m)
            .into_iter()
            .filter(|(key, set)| *set && !allowed.contains(key))
            .filter_map(|(key, _)| self.unused(p, key, &Some(()), &why).err())
            .collect()
    }

    /// The material's values, each checked (the unused keys are [`Validator::unused_keys`]'s).
    fn material_values(&self, p: &KeyPath, name: &str, kind: ModelKind, m: &RawMaterial) -> R<(Material, MaterialMaps)> {
        let (c, maps) = self.split_params(p, kind, m)?;
        let ModelKind::Classic(model) = kind else {
            return Ok((self.physical_material(p, name, kind, m, &c)?, maps));
        };
        let coef = |key: &str, v: &Option<RawColor>, default: Vec3| -> R<Vec3> {
            v.as_ref().map_or(Ok(default), |c| self.color(&p.key(key), c, 0.0, 1.0))
        };
        let diffuse = coef("diffuse", &c.diffuse, Vec3::splat(0.8))?;
        let ambient = coef("ambient", &c.ambient, diffuse)?;
        let (specular, shininess) = if model == ClassicModel::Lambert {
            self.unused(p, "specular", &c.specular, "by `lambert` (it has no specular term; use `phong` or `blinn_phong`)")?;
            self.unused(p, "shininess", &m.shininess, "by `lambert` (it has no specular term; use `phong` or `blinn_phong`)")?;
            (Vec3::ZERO, 1.0)
        } else {
            let s = coef("specular", &c.specular, Vec3::splat(0.5))?;
            let n = m.shininess.map_or(Ok(32.0), |v| self.number(&p.key("shininess"), v, 0.0, 1e6))?;
            (s, n)
        };
        let emission = c.emission.as_ref().map_or(Ok(Vec3::ZERO), |c| self.color(&p.key("emission"), c, 0.0, 1e6))?;
        let clamp_n_dot_l = m.clamp_n_dot_l.unwrap_or(true);
        let model = Model::Classic(Classic { model, diffuse, specular, shininess, clamp_n_dot_l });
        Ok((Material { name: name.to_string(), model, ambient, emission }, maps))
    }

    /// The constants and the textures of `m`, each texture on a key that may take one.
    fn split_params(&self, p: &KeyPath, kind: ModelKind, m: &RawMaterial) -> R<(Consts, MaterialMaps)> {
        let param = |key: &'static str, v: &Option<RawParam>| self.param(p, kind, key, v);
        // A scalar key: one number (a colour is an error), or a texture.
        let scalar = |key: &'static str, v: &Option<RawParam>| -> R<(Option<f64>, Option<TextureRef>)> {
            match self.param(p, kind, key, v)? {
                (Some(RawColor::Scalar(x)), t) => Ok((Some(x), t)),
                (Some(RawColor::Rgb(_) | RawColor::Text(_)), _) => Err(self.err(
                    &p.key(key),
                    Target::Value,
                    format!("`{key}` is one number"),
                    Some(format!("e.g. `{key} = 0.5`, or a texture `{key} = {{ texture = \"map.png\" }}`")),
                )),
                (None, t) => Ok((None, t)),
            }
        };
        let (diffuse, diffuse_map) = param("diffuse", &m.diffuse)?;
        let (base_color, base_map) = param("base_color", &m.base_color)?;
        let (roughness, roughness_map) = scalar("roughness", &m.roughness)?;
        let (metallic, metallic_map) = scalar("metallic", &m.metallic)?;
        let consts = Consts {
            ambient: param("ambient", &m.ambient)?.0,
            // A textured key keeps a placeholder so the constant's checks (and `alpha` vs
            // `roughness`) see it given.
            diffuse: diffuse.or(diffuse_map.as_ref().map(|_| RawColor::Scalar(0.8))),
            specular: param("specular", &m.specular)?.0,
            emission: param("emission", &m.emission)?.0,
            eta: param("eta", &m.eta)?.0,
            k: param("k", &m.k)?.0,
            base_color: base_color.or(base_map.as_ref().map(|_| RawColor::Scalar(0.8))),
            tint: param("tint", &m.tint)?.0,
            roughness: roughness.or(roughness_map.as_ref().map(|_| 0.5)),
            metallic: metallic.or(metallic_map.as_ref().map(|_| 0.0)),
        };
        let maps = MaterialMaps {
            albedo: diffuse_map.or(base_map),
            roughness: roughness_map,
            metallic: metallic_map,
            normal: self.file_map(
                p,
                kind,
                "normal_map",
                &m.normal_map,
                "its rays leave the smooth surface; normal maps bend shaded normals only",
            )?,
            // An ambient-occlusion map: its red channel, as glTF's.
            occlusion: self.file_map(p, kind, "occlusion_map", &m.occlusion_map, "it has no ambient term for the map to darken")?,
            ambient_follows_albedo: m.ambient.is_none(),
        };
        Ok((consts, maps))
    }

    /// A physically based material: the keys its model reads, each checked; any other key is an error.
    fn physical_material(&self, p: &KeyPath, name: &str, kind: ModelKind, m: &RawMaterial, c: &Consts) -> R<Material> {
        if kind == ModelKind::Mirror {
            // A mirror reflects no ambient light: its one colour is its tint.
            self.unused(p, "ambient", &c.ambient, "by `mirror` (it reflects only what its mirrored ray finds)")?;
            let tint = c.tint.as_ref().map_or(Ok(Vec3::ONE), |c| self.color(&p.key("tint"), c, 0.0, 1.0))?;
            let emission = c.emission.as_ref().map_or(Ok(Vec3::ZERO), |c| self.color(&p.key("emission"), c, 0.0, 1e6))?;
            return Ok(Material { name: name.to_string(), model: Model::Mirror(Mirror { tint }), ambient: Vec3::ZERO, emission });
        }
        if kind == ModelKind::Glass {
            // Glass, like a mirror, shows only what its rays find: no ambient term.
            self.unused(p, "ambient", &c.ambient, "by `glass` (it shows only what its reflected and refracted rays find)")?;
            let ior = match &m.ior {
                Some(c) => self.triple(&p.key("ior"), c, GLASS_IOR.0, GLASS_IOR.1)?,
                None => Vec3::splat(1.5),
            };
            let tint = c.tint.as_ref().map_or(Ok(Vec3::ONE), |c| self.color(&p.key("tint"), c, 0.0, 1.0))?;
            let thin = m.thin.unwrap_or(false);
            let emission = c.emission.as_ref().map_or(Ok(Vec3::ZERO), |c| self.color(&p.key("emission"), c, 0.0, 1e6))?;
            let roughness = c.roughness.map_or(Ok(0.0), |v| self.number(&p.key("roughness"), v, 0.0, 1.0))?;
            if thin && roughness > 0.0 {
                return Err(self.err(
                    &p.key("roughness"),
                    Target::Key,
                    "a `thin` glass is one smooth interface; rough glass is a solid boundary",
                    Some("remove `thin = true`, or set `roughness = 0`".into()),
                ));
            }
            let model = Model::Glass(Glass { ior, thin, tint, roughness });
            return Ok(Material { name: name.to_string(), model, ambient: Vec3::ZERO, emission });
        }
        let color = |key: &str, v: &Option<RawColor>, default: Vec3| -> R<Vec3> {
            v.as_ref().map_or(Ok(default), |c| self.color(&p.key(key), c, 0.0, 1.0))
        };
        let unit = |key: &str, v: Option<f64>, default: f32| -> R<f32> { v.map_or(Ok(default), |x| self.number(&p.key(key), x, 0.0, 1.0)) };
        let brdf = match kind {
            ModelKind::Diffuse => Brdf::Diffuse(Diffuse { albedo: color("diffuse", &c.diffuse, Vec3::splat(0.8))? }),
            ModelKind::OrenNayar => {
                let variant = match &m.variant {
                    Some(v) => {
                        self.choice(&p.key("variant"), v, &[("full", OrenNayarModel::Full), ("qualitative", OrenNayarModel::Qualitative)])?
                    }
                    None => OrenNayarModel::Full,
                };
                let sigma = m.sigma_deg.map_or(Ok(20.0), |x| self.number(&p.key("sigma_deg"), x, 0.0, 90.0))?;
                Brdf::OrenNayar(OrenNayar::from_degrees(color("diffuse", &c.diffuse, Vec3::splat(0.8))?, sigma, variant))
            }
            ModelKind::CookTorrance => {
                let ndf = match &m.ndf {
                    Some(v) => self.choice(&p.key("ndf"), v, &choices(Ndf::ALL, Ndf::name))?,
                    None => Ndf::Ggx,
                };
                let masking = match &m.masking {
                    Some(v) => self.choice(&p.key("masking"), v, &choices(Masking::ALL, Masking::name))?,
                    // Smith's Λ is exact for GGX and Beckmann only; the V-cavity masking is exact for
                    // any NDF, so Blinn and Gaussian default to it (Smith is off by up to 75% at α = 1).
                    None if matches!(ndf, Ndf::Blinn | Ndf::Gaussian) => Masking::CookTorrance,
                    None => Masking::Smith,
                };
                let alpha = match (c.roughness, m.alpha) {
                    (Some(_), Some(_)) => {
                        return Err(self.err(
                            &p.key("alpha"),
                            Target::Key,
                            "give `roughness` or `alpha`, not both",
                            Some("α = roughness²; keep one of them".into()),
                        ));
                    }
                    (Some(r), None) => self.number(&p.key("roughness"), r, 0.0, 1.0)?.powi(2),
                    (None, Some(a)) => self.number(&p.key("alpha"), a, 0.0, 1.0)?,
                    (None, None) => 0.25,
                };
                // A preset names a conductor, so it implies `fresnel = "conductor"`.
                let preset = m.preset.as_deref().map(|name| self.metal(&p.key("preset"), name)).transpose()?;
                let fresnel_name = m.fresnel.as_deref().unwrap_or(if preset.is_some() { "conductor" } else { "schlick" });
                let fresnel_kind = self.choice(&p.key("fresnel"), fresnel_name, &choices(FresnelKind::ALL, FresnelKind::name))?;
                if !fresnel_kind.keys().contains(&"ior") {
                    self.unused(p, "ior", &m.ior, &format!("by fresnel `{fresnel_name}` (a conductor has `eta` and `k`)"))?;
                }
                if !fresnel_kind.keys().contains(&"eta") {
                    let why = format!("by fresnel `{fresnel_name}` (only `conductor` reads `eta`, `k` and `preset`)");
                    self.unused(p, "eta", &c.eta, &why)?;
                    self.unused(p, "k", &c.k, &why)?;
                    self.unused(p, "preset", &m.preset, &why)?;
                }
                let ior = match &m.ior {
                    None => 1.5,
                    Some(RawColor::Scalar(x)) => self.number(&p.key("ior"), *x, 1.0, 10.0)?,
                    Some(RawColor::Rgb(_) | RawColor::Text(_)) => {
                        return Err(self.err(
                            &p.key("ior"),
                            Target::Value,
                            "cook_torrance `ior` is one number",
                            Some("use e.g. `ior = 1.5`; only `glass` takes one per channel (dispersion)".into()),
                        ));
                    }
                };
                let fresnel = match (fresnel_kind, preset) {
                    (FresnelKind::Schlick, _) => Fresnel::schlick_from_ior(ior),
                    (FresnelKind::Dielectric, _) => Fresnel::Dielectric { eta: ior },
                    (FresnelKind::Conductor, Some(metal)) => {
                        // A preset is the whole complex index: η or κ beside it would half-override it.
                        let why = "beside `preset` (the preset gives both η and κ; remove `preset` to give your own)";
                        self.unused(p, "eta", &c.eta, why)?;
                        self.unused(p, "k", &c.k, why)?;
                        Fresnel::Conductor { eta: metal.eta, k: metal.k }
                    }
                    (FresnelKind::Conductor, None) => {
                        let need = |key: &str, v: Option<RawColor>| {
                            v.ok_or_else(|| {
                                self.err(
                                    &p.key(key),
                                    Target::Key,
                                    format!("fresnel `conductor` needs `{key}`"),
                                    Some(format!(
                                        "give `eta` and `k`, or a measured metal: preset = \"gold\" ({})",
                                        metals::names().join(", ")
                                    )),
                                )
                            })
                        };
                        let eta = self.triple(&p.key("eta"), &need("eta", c.eta.clone())?, 1e-3, 20.0)?;
                        let k = self.triple(&p.key("k"), &need("k", c.k.clone())?, 0.0, 20.0)?;
                        Fresnel::Conductor { eta, k }
                    }
                    (FresnelKind::None, _) => Fresnel::None,
                };
                Brdf::CookTorrance(CookTorrance {
                    ndf,
                    masking,
                    fresnel,
                    alpha,
                    specular: color("specular", &c.specular, Vec3::ONE)?,
                    diffuse: color("diffuse", &c.diffuse, Vec3::ZERO)?,
                })
            }
            ModelKind::Principled => {
                let specular = match &c.specular {
                    None => 0.5,
                    Some(RawColor::Scalar(x)) => self.number(&p.key("specular"), *x, 0.0, 1.0)?,
                    Some(RawColor::Rgb(_) | RawColor::Text(_)) => {
                        return Err(self.err(
                            &p.key("specular"),
                            Target::Value,
                            "principled `specular` is one number",
                            Some("use `specular = 0.5` (tint it with `specular_tint`)".into()),
                        ));
                    }
                };
                let d = Principled::default();
                let principled = Principled {
                    base_color: color("base_color", &c.base_color, Vec3::splat(0.8))?,
                    metallic: unit("metallic", c.metallic, d.metallic)?,
                    roughness: unit("roughness", c.roughness, d.roughness)?,
                    specular,
                    specular_tint: unit("specular_tint", m.specular_tint, d.specular_tint)?,
                    sheen: unit("sheen", m.sheen, d.sheen)?,
                    sheen_tint: unit("sheen_tint", m.sheen_tint, d.sheen_tint)?,
                    clearcoat: unit("clearcoat", m.clearcoat, d.clearcoat)?,
                    clearcoat_gloss: unit("clearcoat_gloss", m.clearcoat_gloss, d.clearcoat_gloss)?,
                    subsurface: unit("subsurface", m.subsurface, d.subsurface)?,
                    anisotropic: unit("anisotropic", m.anisotropic, d.anisotropic)?,
                    specular_transmission: unit("specular_transmission", m.specular_transmission, d.specular_transmission)?,
                    ior: match &m.ior {
                        None => d.ior,
                        Some(RawColor::Scalar(x)) => self.number(&p.key("ior"), *x, 1.0, 3.0)?,
                        Some(RawColor::Rgb(_) | RawColor::Text(_)) => {
                            return Err(self.err(
                                &p.key("ior"),
                                Target::Value,
                                "principled `ior` is one number",
                                Some("use e.g. `ior = 1.45`; only `glass` takes one per channel (dispersion)".into()),
                            ));
                        }
                    },
                    transmittance_color: color("transmittance_color", &m.transmittance_color, d.transmittance_color)?,
                    transmittance_distance: match m.transmittance_distance {
                        None => d.transmittance_distance,
                        Some(x) => self.number(&p.key("transmittance_distance"), x, 1e-4, 1e6)?,
                    },
                    diffuse_transmission: unit("diffuse_transmission", m.diffuse_transmission, d.diffuse_transmission)?,
                    // Up to 10⁴ world units: past that the walk's steps are longer than any scene.
                    subsurface_radius: m
                        .subsurface_radius
                        .as_ref()
                        .map_or(Ok(d.subsurface_radius), |r| self.triple(&p.key("subsurface_radius"), r, 0.0, 1e4))?,
                    subsurface_scale: m
                        .subsurface_scale
                        .map_or(Ok(d.subsurface_scale), |x| self.number(&p.key("subsurface_scale"), x, 0.0, 1e4))?,
                };
                if principled.transmits() && m.subsurface_radius.is_some() {
                    return Err(self.err(
                        &p.key("subsurface_radius"),
                        Target::Key,
                        "`subsurface_radius` with transmission: light either goes through the surface or walks under it",
                        Some("remove `specular_transmission` and `diffuse_transmission`, or `subsurface_radius`".into()),
                    ));
                }
                if principled.metallic > 0.0 && m.subsurface_radius.is_some() {
                    return Err(self.err(
                        &p.key("subsurface_radius"),
                        Target::Key,
                        "`subsurface_radius` on a metallic material: a metal lets no light under its surface",
                        Some("set `metallic = 0`, or remove `subsurface_radius`".into()),
                    ));
                }
                Brdf::Principled(principled)
            }
            // Classic models returned from `material` before this; they share no key handling here.
            ModelKind::NormalizedPhong
            | ModelKind::NormalizedBlinnPhong
            | ModelKind::UnnormalizedPhong
            | ModelKind::Classic(_)
            | ModelKind::Mirror
            | ModelKind::Glass => {
                let diffuse = color("diffuse", &c.diffuse, Vec3::splat(0.5))?;
                let specular = color("specular", &c.specular, Vec3::splat(0.5))?;
                let shininess = m.shininess.map_or(Ok(32.0), |v| self.number(&p.key("shininess"), v, 0.0, 1e6))?;
                if kind == ModelKind::NormalizedPhong {
                    Brdf::NormalizedPhong(NormalizedPhong { diffuse, specular, shininess })
                } else if kind == ModelKind::UnnormalizedPhong {
                    // f = k_d/π + k_s cos^n α_r: the classic lobe without (n+2)/(2π), stored as a
                    // normalized Phong whose k_s absorbs 2π/(n+2) (so its albedo can exceed 1).
                    let scale = 2.0 * std::f32::consts::PI / (shininess + 2.0);
                    Brdf::NormalizedPhong(NormalizedPhong { diffuse, specular: specular * scale, shininess })
                } else {
                    Brdf::NormalizedBlinnPhong(NormalizedBlinnPhong { diffuse, specular, shininess })
                }
            }
        };
        // What the ambient light sees: the diffuse albedo (or base colour) unless given.
        let albedo = brdf.ambient_albedo();
        let ambient = color("ambient", &c.ambient, albedo)?;
        let emission = c.emission.as_ref().map_or(Ok(Vec3::ZERO), |c| self.color(&p.key("emission"), c, 0.0, 1e6))?;
        Ok(Material { name: name.to_string(), model: Model::Physical(brdf), ambient, emission })
    }
}

impl Validator<'_> {
    /// A `preset = "gold"`: the measured metal, or an error naming the presets.
    fn metal(&self, path: &KeyPath, name: &str) -> R<Metal> {
        metals::find(name).ok_or_else(|| {
            let names = metals::names();
            let hint = match crate::lesson::suggest(&name.to_ascii_lowercase(), &names) {
                Some(s) => format!("did you mean `{s}`? Presets: {}", names.join(", ")),
                None => format!("presets: {} (or give `eta` and `k`)", names.join(", ")),
            };
            self.err(path, Target::Value, format!("unknown metal `{name}`"), Some(hint))
        })
    }
}

/// Every model-specific key of a `[material.NAME]` table and whether the lesson sets it,
/// in the order messages report them.
fn present_keys(m: &RawMaterial) -> [(&'static str, bool); 32] {
    [
        ("clamp_n_dot_l", m.clamp_n_dot_l.is_some()),
        ("diffuse", m.diffuse.is_some()),
        ("specular", m.specular.is_some()),
        ("shininess", m.shininess.is_some()),
        ("ndf", m.ndf.is_some()),
        ("masking", m.masking.is_some()),
        ("fresnel", m.fresnel.is_some()),
        ("ior", m.ior.is_some()),
        ("eta", m.eta.is_some()),
        ("k", m.k.is_some()),
        ("preset", m.preset.is_some()),
        ("roughness", m.roughness.is_some()),
        ("alpha", m.alpha.is_some()),
        ("sigma_deg", m.sigma_deg.is_some()),
        ("variant", m.variant.is_some()),
        ("base_color", m.base_color.is_some()),
        ("metallic", m.metallic.is_some()),
        ("specular_tint", m.specular_tint.is_some()),
        ("sheen", m.sheen.is_some()),
        ("sheen_tint", m.sheen_tint.is_some()),
        ("clearcoat", m.clearcoat.is_some()),
        ("clearcoat_gloss", m.clearcoat_gloss.is_some()),
        ("subsurface", m.subsurface.is_some()),
        ("anisotropic", m.anisotropic.is_some()),
        ("specular_transmission", m.specular_transmission.is_some()),
        ("transmittance_color", m.transmittance_color.is_some()),
        ("transmittance_distance", m.transmittance_distance.is_some()),
        ("diffuse_transmission", m.diffuse_transmission.is_some()),
        ("subsurface_radius", m.subsurface_radius.is_some()),
        ("subsurface_scale", m.subsurface_scale.is_some()),
        ("tint", m.tint.is_some()),
        ("thin", m.thin.is_some()),
    ]
}

#[cfg(test)]
mod tests {
    use crate::lesson::{LessonError, parse};
    use crate::shading::brdf::Brdf;
    use crate::shading::material::{Material, Model};
    use crate::shading::metals;
    use crate::shading::microfacet::Fresnel;
    use glam::Vec3;
    use std::path::Path;

    const BASE: &str =
        "[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n[material.m]\n";

    fn material(body: &str) -> Result<Material, LessonError> {
        parse(&format!("{BASE}{body}\n"), Path::new("t.toml"), &[]).map(|l| l.materials[0].clone())
    }

    fn conductor(body: &str) -> (Vec3, Vec3) {
        match material(body).map(|m| m.model) {
            Ok(Model::Physical(Brdf::CookTorrance(c))) => match c.fresnel {
                Fresnel::Conductor { eta, k } => (eta, k),
                other => panic!("{body}: {other:?}"),
            },
            other => panic!("{body}: {other:?}"),
        }
    }

    #[test]
    fn colours_as_hex_and_css_names_decode_to_linear() {
        let Model::Classic(c) = material("model = \"phong\"\ndiffuse = \"#808080\"\nspecular = \"white\"").unwrap().model else {
            panic!("phong is classic")
        };
        assert!((c.diffuse - Vec3::splat(0.21586)).abs().max_element() < 5e-6, "{}", c.diffuse);
        assert_eq!(c.specular, Vec3::ONE);
        let m = material("model = \"lambert\"\ndiffuse = \"steelblue\"\nemission = \"#000\"").unwrap();
        assert_eq!(m.emission, Vec3::ZERO);
        let e = material("model = \"lambert\"\ndiffuse = \"bleu\"").unwrap_err();
        assert!(e.message.contains("unknown colour name `bleu`"), "{}", e.message);
        assert!(e.hint.as_deref().is_some_and(|h| h.contains("did you mean `blue`")), "{:?}", e.hint);
        let e = material("model = \"lambert\"\ndiffuse = \"#12345\"").unwrap_err();
        assert!(e.message.contains("not sRGB hex"), "{}", e.message);
    }

    #[test]
    fn presets_give_measured_conductors() {
        for m in metals::METALS {
            let (eta, k) = conductor(&format!("model = \"cook_torrance\"\npreset = \"{}\"", m.name));
            assert_eq!((eta, k), (m.eta, m.k), "{}", m.name);
        }
        assert_eq!(conductor("model = \"cook_torrance\"\nfresnel = \"conductor\"\npreset = \"aluminum\"").0, metals::METALS[3].eta);
        // A preset with its own η or κ is refused: the preset is the whole complex index.
        let e = material("model = \"cook_torrance\"\npreset = \"gold\"\neta = [0.2, 0.4, 1.5]").unwrap_err();
        assert_eq!(e.key.as_deref(), Some("material.m.eta"), "{}", e.message);
        assert!(e.message.contains("beside `preset`"), "{}", e.message);
        let e = material("model = \"cook_torrance\"\nfresnel = \"schlick\"\npreset = \"gold\"").unwrap_err();
        assert!(e.message.contains("`preset` is not used"), "{}", e.message);
        let e = material("model = \"cook_torrance\"\npreset = \"gld\"").unwrap_err();
        assert!(e.hint.as_deref().is_some_and(|h| h.contains("did you mean `gold`")), "{:?}", e.hint);
        // η and κ take numbers, not colour names.
        let e = material("model = \"cook_torrance\"\nfresnel = \"conductor\"\neta = \"gold\"\nk = 1").unwrap_err();
        assert!(e.message.contains("is not a colour"), "{}", e.message);
    }

    #[test]
    fn names_are_read_in_any_case() {
        assert!(matches!(material("model = \"Blinn_Phong\"").unwrap().model, Model::Classic(_)));
        let (eta, _) = conductor("model = \"COOK_TORRANCE\"\nfresnel = \"Conductor\"\neta = 0.5\nk = 2");
        assert_eq!(eta, Vec3::splat(0.5));
    }
}
