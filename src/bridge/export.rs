//! `shadelab export`: a lesson as a glTF 2.0 binary (.glb) Blender opens.
//!
//! Objects are written as rendered (tessellated, in world space, one mesh per object),
//! materials as pbrMetallicRoughness with KHR_materials_ior / _emissive_strength /
//! _transmission / _clearcoat / _sheen, point, spot and directional lights as
//! KHR_lights_punctual ([`super::units`]), lights with extent as emissive geometry, the
//! camera as a perspective camera, the environment map's file name in the scene's `extras`.
//! Every reading that is not exact is a warning naming the material or light.

use std::borrow::Cow;
use std::collections::BTreeMap;

use gj::validation::{Checked::Valid, USize64};
use glam::{Mat3, Quat, Vec3};
use gltf::json as gj;

use super::units;
use crate::lesson::Lesson;
use crate::lesson::kinds::LightType;
use crate::lesson::light::LightSpec;
use crate::scene::Scene;
use crate::shading::brdf::Brdf;
use crate::shading::material::{Material, Model};
use crate::shading::microfacet::fresnel::Fresnel;

/// A lesson written as a .glb, with what could not be written exactly.
pub struct Exported {
    /// The .glb bytes.
    pub glb: Vec<u8>,
    /// One line per approximation or dropped part.
    pub warnings: Vec<String>,
}

/// Builds the .glb of `lesson`, whose scene `scene` was built from it.
///
/// # Errors
/// A message when the file would exceed 4 GiB (a .glb's limit).
pub fn export(lesson: &Lesson, scene: &Scene) -> Result<Exported, String> {
    let mut b = Builder::new();
    let materials: Vec<gj::Index<gj::Material>> =
        scene.materials.iter().enumerate().map(|(i, m)| b.material(m, lesson.material_maps.get(i))).collect();
    let g = &scene.geometry;
    for (i, o) in g.objects.iter().enumerate() {
        let tris = &g.triangles[o.first_triangle..o.first_triangle + o.triangles];
        let base = o.first_vertex as u32;
        let (positions, normals, uvs, indices): (Vec<Vec3>, Vec<Vec3>, Vec<[f32; 2]>, Vec<u32>) = if g.uvs.is_empty() {
            let p = g.positions[o.first_vertex..o.first_vertex + o.vertices].to_vec();
            let n = g.normals[o.first_vertex..o.first_vertex + o.vertices].to_vec();
            (p, n, Vec::new(), tris.iter().flat_map(|t| t.map(|v| v - base)).collect())
        } else {
            // Uvs are per corner: one vertex per corner (v flipped to glTF's top-down).
            let uv = &g.uvs[o.first_triangle..o.first_triangle + o.triangles];
            let corners = tris.iter().zip(uv).flat_map(|(t, u)| (0..3).map(move |k| (t[k], u[k])));
            let (mut p, mut n, mut w) = (Vec::new(), Vec::new(), Vec::new());
            for (v, u) in corners {
                p.push(g.positions[v as usize]);
                n.push(g.normals[v as usize]);
                w.push([u.x, 1.0 - u.y]);
            }
            let count = p.len() as u32;
            (p, n, w, (0..count).collect())
        };
        // Named as a student would name it in Blender: the shape (or the mesh file) and its number.
        let name = match &lesson.objects[i].shape {
            crate::lesson::Shape::Mesh { path, .. } => {
                format!("{} {i}", path.file_stem().map_or_else(|| "mesh".into(), |s| s.to_string_lossy()))
            }
            other => format!("{} {i}", other.name()),
        };
        let mesh = b.mesh(&name, &positions, &normals, &uvs, &indices, materials[o.material as usize]);
        let node = b.root.push(gj::Node { mesh: Some(mesh), name: Some(name), ..Default::default() });
        b.nodes.push(node);
    }
    for (i, l) in lesson.scene.lights.iter().enumerate() {
        b.light(i, l);
    }
    if lesson.scene.ambient.max_element() > 0.0 {
        b.warnings.push("[scene] ambient is not written: glTF has no ambient light (set Blender's World colour)".into());
    }
    b.camera(lesson);
    let bg = lesson.scene.camera.background;
    let mut extras = serde_json::json!({ "shadelab": { "lesson": lesson.title, "background": [bg.x, bg.y, bg.z] } });
    // The lesson's `[render]` table as written (tone map, exposure, samples...): glTF has no
    // word for them, and shadelab's import gives them back.
    if let Ok(t) = toml::from_str::<toml::Table>(&lesson.source)
        && let Some(render) = t.get("render")
        && let Ok(v) = serde_json::to_value(render)
    {
        extras["shadelab"]["render"] = v;
    }
    if let Some(env) = &lesson.environment {
        let name = match &env.source {
            crate::lesson::environment::EnvSource::LatLong { written, .. }
            | crate::lesson::environment::EnvSource::CubeCross { written, .. }
            | crate::lesson::environment::EnvSource::MirrorBall { written, .. } => written.clone(),
            crate::lesson::environment::EnvSource::CubeFaces { written, .. } => written.join(", "),
            other => format!("{other:?}"),
        };
        extras["shadelab"]["environment"] = serde_json::Value::String(name.clone());
        b.warnings.push(format!("the environment map ({name}) is named in the scene's extras only: set it as Blender's World texture"));
    }
    if lesson.scene.fog.is_some() {
        b.warnings.push("[fog] is not written: glTF has no participating media".into());
    }
    b.finish(extras)
}

struct Builder {
    root: gj::Root,
    bin: Vec<u8>,
    buffer: gj::Index<gj::Buffer>,
    nodes: Vec<gj::Index<gj::Node>>,
    used: Vec<&'static str>,
    warnings: Vec<String>,
}

impl Builder {
    fn new() -> Builder {
        let mut root = gj::Root::default();
        root.asset.generator = Some(format!("shadelab {}", env!("CARGO_PKG_VERSION")));
        let buffer = root.push(gj::Buffer { byte_length: USize64(0), name: None, uri: None, extensions: None, extras: None });
        Builder { root, bin: Vec::new(), buffer, nodes: Vec::new(), used: Vec::new(), warnings: Vec::new() }
    }

    fn uses(&mut self, ext: &'static str) {
        if !self.used.contains(&ext) {
            self.used.push(ext);
        }
    }

    /// `bytes` appended to the binary chunk (4-byte aligned) as a view; `target` for vertex
    /// and index data, none for images.
    fn view(&mut self, bytes: &[u8], target: Option<gj::buffer::Target>) -> gj::Index<gj::buffer::View> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.root.push(gj::buffer::View {
            buffer: self.buffer,
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: target.map(Valid),
            extensions: None,
            extras: None,
        })
    }

    fn accessor(
        &mut self,
        bytes: &[u8],
        count: usize,
        ct: gj::accessor::ComponentType,
        ty: gj::accessor::Type,
        bounds: Option<(Vec3, Vec3)>,
    ) -> gj::Index<gj::Accessor> {
        let target =
            if ty == gj::accessor::Type::Scalar { gj::buffer::Target::ElementArrayBuffer } else { gj::buffer::Target::ArrayBuffer };
        let view = self.view(bytes, Some(target));
        self.root.push(gj::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(gj::accessor::GenericComponentType(ct)),
            type_: Valid(ty),
            min: bounds.map(|(lo, _)| serde_json::json!(lo.to_array())),
            max: bounds.map(|(_, hi)| serde_json::json!(hi.to_array())),
            name: None,
            normalized: false,
            sparse: None,
            extensions: None,
            extras: None,
        })
    }

    fn mesh(
        &mut self,
        name: &str,
        positions: &[Vec3],
        normals: &[Vec3],
        uvs: &[[f32; 2]],
        indices: &[u32],
        material: gj::Index<gj::Material>,
    ) -> gj::Index<gj::Mesh> {
        use gj::accessor::{ComponentType as CT, Type as AT};
        let f32s = |v: &mut dyn Iterator<Item = f32>| v.flat_map(f32::to_le_bytes).collect::<Vec<u8>>();
        let lo = positions.iter().fold(Vec3::splat(f32::MAX), |a, p| a.min(*p));
        let hi = positions.iter().fold(Vec3::splat(f32::MIN), |a, p| a.max(*p));
        let pos =
            self.accessor(&f32s(&mut positions.iter().flat_map(|p| p.to_array())), positions.len(), CT::F32, AT::Vec3, Some((lo, hi)));
        let nrm = self.accessor(&f32s(&mut normals.iter().flat_map(|p| p.to_array())), normals.len(), CT::F32, AT::Vec3, None);
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(gj::mesh::Semantic::Positions), pos);
        attributes.insert(Valid(gj::mesh::Semantic::Normals), nrm);
        if !uvs.is_empty() {
            let uv = self.accessor(&f32s(&mut uvs.iter().flatten().copied()), uvs.len(), CT::F32, AT::Vec2, None);
            attributes.insert(Valid(gj::mesh::Semantic::TexCoords(0)), uv);
        }
        let idx: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let idx = self.accessor(&idx, indices.len(), CT::U32, AT::Scalar, None);
        self.root.push(gj::Mesh {
            name: Some(name.into()),
            weights: None,
            extensions: None,
            extras: None,
            primitives: vec![gj::mesh::Primitive {
                attributes,
                indices: Some(idx),
                material: Some(material),
                mode: Valid(gj::mesh::Mode::Triangles),
                targets: None,
                extensions: None,
                extras: None,
            }],
        })
    }

    /// A material as pbrMetallicRoughness plus extensions (the nearest reading, with a
    /// warning, for what glTF has no word for).
    /// A texture file as an embedded image (PNG and JPEG; glTF core reads no other), or a
    /// warning naming what is not written.
    fn texture(&mut self, material: &str, slot: &str, t: &crate::lesson::texture::TextureRef) -> Option<gj::Index<gj::Texture>> {
        let crate::lesson::texture::TextureSource::File { path, written, .. } = &t.source else {
            self.warnings
                .push(format!("material `{material}`: the procedural `{slot}` texture is not written (glTF has no procedural textures)"));
            return None;
        };
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        let mime = match ext.as_deref() {
            Some("png") => "image/png",
            Some("jpg" | "jpeg") => "image/jpeg",
            _ => {
                self.warnings.push(format!(
                    "material `{material}`: the `{slot}` texture {written} is not PNG or JPEG, which glTF reads: not written"
                ));
                return None;
            }
        };
        let Ok(bytes) = std::fs::read(path) else {
            self.warnings.push(format!("material `{material}`: the `{slot}` texture {written} could not be read again: not written"));
            return None;
        };
        let view = self.view(&bytes, None);
        let image = self.root.push(gj::Image {
            buffer_view: Some(view),
            mime_type: Some(gj::image::MimeType(mime.into())),
            name: Some(written.clone()),
            uri: None,
            extensions: None,
            extras: None,
        });
        Some(self.root.push(gj::Texture { name: None, sampler: None, source: image, extensions: None, extras: None }))
    }

    fn material(&mut self, m: &Material, maps: Option<&crate::lesson::texture::MaterialMaps>) -> gj::Index<gj::Material> {
        let info = |index| gj::texture::Info { index, tex_coord: 0, extensions: None, extras: None };
        let mut base_texture = None;
        let mut normal_texture = None;
        let mut occlusion_texture = None;
        let mut metal_rough_texture = None;
        if let Some(maps) = maps {
            base_texture = maps.albedo.as_ref().and_then(|t| self.texture(&m.name, "base colour", t)).map(info);
            normal_texture = maps
                .normal
                .as_ref()
                .and_then(|t| self.texture(&m.name, "normal map", t))
                .map(|index| gj::material::NormalTexture { index, scale: 1.0, tex_coord: 0, extensions: None, extras: None });
            occlusion_texture = maps.occlusion.as_ref().and_then(|t| self.texture(&m.name, "occlusion map", t)).map(|index| {
                gj::material::OcclusionTexture {
                    index,
                    strength: gj::material::StrengthFactor(1.0),
                    tex_coord: 0,
                    extensions: None,
                    extras: None,
                }
            });
            // glTF has one image for both: roughness in green, metallic in blue (a lesson
            // imported from glTF reads them so).
            use crate::lesson::texture::TextureSource::File;
            let channel = |t: &Option<crate::lesson::texture::TextureRef>| match t.as_ref().map(|t| &t.source) {
                Some(File { path, channel, .. }) => Some((path.clone(), *channel)),
                _ => None,
            };
            let (r, mt) = (channel(&maps.roughness), channel(&maps.metallic));
            let packed = match (&r, &mt) {
                (Some((a, 1)), Some((b, 2))) if a == b => maps.roughness.as_ref(),
                (Some((_, 1)), None) if maps.metallic.is_none() => maps.roughness.as_ref(),
                (None, Some((_, 2))) if maps.roughness.is_none() => maps.metallic.as_ref(),
                _ => None,
            };
            match packed {
                Some(t) => metal_rough_texture = self.texture(&m.name, "metallic-roughness", t).map(info),
                None => {
                    for (slot, t) in [("roughness", &maps.roughness), ("metallic", &maps.metallic)] {
                        if t.is_some() {
                            self.warnings.push(format!(
                                "material `{}`: the `{slot}` texture is not written (glTF packs roughness in an image's green and metallic in its blue: give `channel = \"g\"` and `\"b\"` of one file)",
                                m.name
                            ));
                        }
                    }
                }
            }
        }
        let name = &m.name;
        let mut warn = |s: String| self.warnings.push(format!("material `{name}`: {s}"));
        // (base colour, metallic, roughness, ior, specular factor, transmission)
        let mut ext = gj::extensions::material::Material::default();
        let (base, metallic, roughness, ior, spec_factor, transmission) = match &m.model {
            Model::Physical(Brdf::Principled(p)) => {
                if p.clearcoat > 0.0 {
                    ext.others.insert(
                        "KHR_materials_clearcoat".into(),
                        serde_json::json!({ "clearcoatFactor": p.clearcoat, "clearcoatRoughnessFactor": 1.0 - p.clearcoat_gloss }),
                    );
                }
                if p.sheen > 0.0 {
                    ext.others.insert("KHR_materials_sheen".into(), serde_json::json!({ "sheenColorFactor": [p.sheen, p.sheen, p.sheen] }));
                }
                for (key, v) in [("specular_tint", p.specular_tint), ("subsurface", p.subsurface), ("anisotropic", p.anisotropic)] {
                    if v > 0.0 {
                        warn(format!("`{key}` is not written"));
                    }
                }
                (p.base_color, p.metallic, p.roughness, units::ior_from_disney_specular(p.specular), 1.0, 0.0)
            }
            Model::Physical(Brdf::Diffuse(d)) => {
                warn(
                    "Lambert is written as a rough dielectric without specular (Blender's Principled BSDF reads it as Burley's diffuse)"
                        .into(),
                );
                (d.albedo, 0.0, 1.0, 1.5, 0.0, 0.0)
            }
            Model::Physical(Brdf::OrenNayar(d)) => {
                warn("Oren-Nayar is written as a rough dielectric without specular".into());
                (d.albedo, 0.0, 1.0, 1.5, 0.0, 0.0)
            }
            Model::Physical(Brdf::CookTorrance(c)) => {
                let roughness = c.alpha.max(0.0).sqrt();
                match c.fresnel {
                    Fresnel::Conductor { eta, k } => {
                        // F0 of the complex index at normal incidence.
                        let f0 = ((eta - 1.0) * (eta - 1.0) + k * k) / ((eta + 1.0) * (eta + 1.0) + k * k);
                        warn("a conductor is written as metallic with its F0 as the base colour (Schlick's curve in glTF)".into());
                        (f0 * c.specular, 1.0, roughness, 1.5, 1.0, 0.0)
                    }
                    Fresnel::Dielectric { eta } => (c.diffuse, 0.0, roughness, eta, c.specular.max_element(), 0.0),
                    Fresnel::Schlick { f0 } => {
                        let r = f0.max_element().clamp(0.0, 0.64).sqrt();
                        (c.diffuse, 0.0, roughness, (1.0 + r) / (1.0 - r), c.specular.max_element(), 0.0)
                    }
                    Fresnel::None => {
                        warn("F = 1 has no glTF reading: written with η = 1.5".into());
                        (c.diffuse, 0.0, roughness, 1.5, 1.0, 0.0)
                    }
                }
            }
            Model::Physical(Brdf::NormalizedPhong(p)) => {
                warn("a normalized Phong lobe is written as GGX of the Blinn-Phong-equivalent roughness".into());
                (p.diffuse, 0.0, roughness_of_exponent(p.shininess), 1.5, 1.0, 0.0)
            }
            Model::Physical(Brdf::NormalizedBlinnPhong(p)) => {
                warn("a normalized Blinn-Phong lobe is written as GGX of the equivalent roughness".into());
                (p.diffuse, 0.0, roughness_of_exponent(p.shininess), 1.5, 1.0, 0.0)
            }
            Model::Classic(c) => {
                warn(format!(
                    "a classic `{}` material is written by its nearest physically based reading: K_diff as base colour, K_shi as roughness",
                    c.model.name()
                ));
                let roughness = if c.has_specular() { roughness_of_exponent(c.shininess) } else { 1.0 };
                (c.diffuse, 0.0, roughness, 1.5, if c.has_specular() { 1.0 } else { 0.0 }, 0.0)
            }
            Model::Mirror(mi) => (mi.tint, 1.0, 0.0, 1.5, 1.0, 0.0),
            Model::Glass(g) => {
                if g.ior.x != g.ior.y || g.ior.y != g.ior.z {
                    warn("per-channel ior (dispersion) is written as its mean".into());
                }
                if g.thin {
                    warn("`thin` glass is written as solid glass".into());
                }
                (g.tint, 0.0, 0.0, g.ior.element_sum() / 3.0, 1.0, 1.0)
            }
        };
        if ior != 1.5 {
            ext.ior = Some(gj::extensions::material::Ior {
                ior: gj::extensions::material::IndexOfRefraction(ior.clamp(1.0, 10.0)),
                extras: None,
            });
            self.uses("KHR_materials_ior");
        }
        if spec_factor != 1.0 {
            ext.specular = Some(gj::extensions::material::Specular {
                specular_factor: gj::extensions::material::SpecularFactor(spec_factor.clamp(0.0, 1.0)),
                ..Default::default()
            });
            self.uses("KHR_materials_specular");
        }
        if transmission > 0.0 {
            ext.transmission = Some(gj::extensions::material::Transmission {
                transmission_factor: gj::extensions::material::TransmissionFactor(transmission),
                ..Default::default()
            });
            self.uses("KHR_materials_transmission");
        }
        let peak = m.emission.max_element();
        let emissive = if peak > 1.0 {
            ext.emissive_strength = Some(gj::extensions::material::EmissiveStrength {
                emissive_strength: gj::extensions::material::EmissiveStrengthFactor(peak),
            });
            self.uses("KHR_materials_emissive_strength");
            m.emission / peak
        } else {
            m.emission
        };
        for key in ext.others.keys() {
            match key.as_str() {
                "KHR_materials_clearcoat" => self.uses("KHR_materials_clearcoat"),
                "KHR_materials_sheen" => self.uses("KHR_materials_sheen"),
                _ => {}
            }
        }
        let base = base.clamp(Vec3::ZERO, Vec3::ONE);
        let textured = base_texture.is_some();
        // The factors multiply the texture in glTF: 1 lets the texture say it alone.
        let (metallic, roughness) = if metal_rough_texture.is_some() { (1.0, 1.0) } else { (metallic, roughness) };
        self.root.push(gj::Material {
            name: Some(m.name.clone()),
            normal_texture,
            occlusion_texture,
            pbr_metallic_roughness: gj::material::PbrMetallicRoughness {
                base_color_texture: base_texture,
                metallic_roughness_texture: metal_rough_texture,
                base_color_factor: gj::material::PbrBaseColorFactor(if textured { [1.0; 4] } else { [base.x, base.y, base.z, 1.0] }),
                metallic_factor: gj::material::StrengthFactor(metallic.clamp(0.0, 1.0)),
                roughness_factor: gj::material::StrengthFactor(roughness.clamp(0.0, 1.0)),
                ..Default::default()
            },
            emissive_factor: gj::material::EmissiveFactor(emissive.clamp(Vec3::ZERO, Vec3::ONE).to_array()),
            extensions: Some(ext),
            ..Default::default()
        })
    }

    /// Light `i`: punctual lights as KHR_lights_punctual, lights with extent as emissive
    /// geometry, ambient and sky lights dropped with a warning.
    fn light(&mut self, i: usize, l: &LightSpec) {
        use gj::extensions::scene::khr_lights_punctual as klp;
        let peak = l.radiance.max_element();
        let color = if peak > 0.0 { l.radiance / peak } else { Vec3::ONE };
        let name = format!("light {i}");
        let (kind, intensity, spot, translation, facing) = match l.kind {
            LightType::Directional => (klp::Type::Directional, units::lux_from_irradiance(peak), None, None, Some(l.direction)),
            LightType::Point => (klp::Type::Point, units::candela_from_watts_per_sr(peak), None, Some(l.position), None),
            LightType::Spot => {
                let (inner, outer) = spot_cones(l);
                if l.profile.is_none() {
                    self.warnings.push(format!(
                        "{name}: the spot's cos^{} falloff is written as glTF's cone from {:.1}° to {:.1}°",
                        l.exponent,
                        inner.to_degrees(),
                        outer.to_degrees()
                    ));
                }
                let spot = klp::Spot { inner_cone_angle: inner, outer_cone_angle: outer };
                (klp::Type::Spot, units::candela_from_watts_per_sr(peak), Some(spot), Some(l.position), Some(l.direction))
            }
            LightType::Rect | LightType::Disk | LightType::Sphere => {
                self.area_light(&name, l);
                return;
            }
            LightType::Ambient | LightType::Sky | LightType::Line => {
                self.warnings.push(format!("{name}: a `{}` light has no glTF form and is not written", l.kind.name()));
                return;
            }
        };
        if l.attenuation != Vec3::new(1.0, 0.0, 0.0) {
            self.warnings.push(format!("{name}: `attenuation` is not written (glTF lights fall off as 1/r²)"));
        }
        if l.specular != l.radiance {
            self.warnings.push(format!("{name}: `specular` is not written (a glTF light has one colour, its `color`)"));
        }
        // A spot's own law, for shadelab's import (the cone above is its glTF reading).
        let extras = (l.kind == LightType::Spot).then(|| {
            // The lesson keeps cos(cutoff); degrees to 1e-4 give back the number it was written as.
            let cutoff = (l.cos_cutoff > -1.0).then(|| (l.cos_cutoff.clamp(-1.0, 1.0).acos().to_degrees() as f64 * 1e4).round() / 1e4);
            let law = match &l.profile {
                Some(p) => serde_json::json!({ "profile": p.iter().map(|(a, f)| [*a, *f]).collect::<Vec<_>>(), "cutoff_deg": cutoff }),
                None => serde_json::json!({ "exponent": l.exponent, "cutoff_deg": cutoff }),
            };
            raw_extras(&serde_json::json!({ "shadelab": law }))
        });
        let light = self.root.push(klp::Light {
            name: Some(name.clone()),
            color: color.to_array(),
            intensity,
            range: None,
            spot,
            type_: Valid(kind),
            extensions: None,
            extras: extras.flatten(),
        });
        self.uses("KHR_lights_punctual");
        let rotation = facing.map(|d| gj::scene::UnitQuaternion(Quat::from_rotation_arc(-Vec3::Z, d.normalize()).to_array()));
        let node = self.root.push(gj::Node {
            name: Some(name),
            translation: translation.map(|p| p.to_array()),
            rotation,
            extensions: Some(gj::extensions::scene::Node {
                khr_lights_punctual: Some(klp::KhrLightsPunctual { light }),
                ..Default::default()
            }),
            ..Default::default()
        });
        self.nodes.push(node);
    }

    /// A rect, disk or sphere light as an emissive mesh of its shape.
    fn area_light(&mut self, name: &str, l: &LightSpec) {
        self.warnings.push(format!("{name}: a `{}` light is written as emissive geometry (glTF has no area lights): Cycles lights the scene with it, Eevee needs its light probes", l.kind.name()));
        let shape = match l.kind {
            LightType::Sphere => crate::scene::shapes::uv_sphere(32, 16).transformed(glam::Affine3A::from_scale_rotation_translation(
                Vec3::splat(l.radius),
                Quat::IDENTITY,
                l.position,
            )),
            _ => {
                // The plane faces +y; turn it to face `direction`, sized as the light.
                let (w, h) = match l.kind {
                    LightType::Rect => (l.size[0], l.size[1]),
                    _ => (2.0 * l.radius, 2.0 * l.radius),
                };
                let [u, v] = l.frame;
                let basis = Mat3::from_cols(u * w / 2.0, l.direction.normalize(), v * h / 2.0);
                let mut mesh = if l.kind == LightType::Disk { disk(48) } else { crate::scene::shapes::plane() };
                crate::scene::normals::compute_vertex_normals(&mut mesh, crate::lesson::NormalWeighting::Average);
                mesh.transformed(glam::Affine3A::from_mat3_translation(basis, l.position))
            }
        };
        let mut emissive = Material {
            name: format!("{name} (emitter)"),
            model: Model::Mirror(crate::shading::mirror::Mirror { tint: Vec3::ZERO }),
            ambient: Vec3::ZERO,
            emission: l.radiance,
        };
        emissive.model = Model::Physical(Brdf::Diffuse(crate::shading::diffuse::Diffuse { albedo: Vec3::ZERO }));
        let before = self.warnings.len();
        let material = self.material(&emissive, None);
        self.warnings.truncate(before);
        let mut mesh = shape;
        if mesh.normals.len() != mesh.positions.len() {
            crate::scene::normals::compute_vertex_normals(&mut mesh, crate::lesson::NormalWeighting::Average);
        }
        let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
        let m = self.mesh(name, &mesh.positions, &mesh.normals, &[], &indices, material);
        let node = self.root.push(gj::Node { mesh: Some(m), name: Some(name.to_string()), ..Default::default() });
        self.nodes.push(node);
    }

    /// The lesson's camera as a perspective camera node (−z forward, +y up).
    fn camera(&mut self, lesson: &Lesson) {
        let c = &lesson.scene.camera;
        let forward = (c.look_at - c.position).normalize();
        let right = forward.cross(c.up).normalize();
        let up = right.cross(forward);
        let rotation = Quat::from_mat3(&Mat3::from_cols(right, up, -forward)).normalize();
        let camera = self.root.push(gj::Camera {
            name: Some("camera".into()),
            type_: Valid(gj::camera::Type::Perspective),
            orthographic: None,
            perspective: Some(gj::camera::Perspective {
                aspect_ratio: Some(c.width as f32 / c.height as f32),
                yfov: c.fov_y_deg.to_radians(),
                znear: c.near,
                zfar: None,
                extensions: None,
                extras: None,
            }),
            extensions: None,
            // The camera as the lesson wrote it, for shadelab's import (the node's rotation and
            // yfov are its glTF reading; glTF keeps only the aspect ratio of the size).
            extras: raw_extras(&serde_json::json!({ "shadelab": {
                "size": [c.width, c.height],
                "look_at": c.look_at.to_array(),
                "up": c.up.to_array(),
                "fov_deg": c.fov_y_deg,
            } })),
        });
        let node = self.root.push(gj::Node {
            name: Some("camera".into()),
            camera: Some(camera),
            translation: Some(c.position.to_array()),
            rotation: Some(gj::scene::UnitQuaternion(rotation.to_array())),
            ..Default::default()
        });
        self.nodes.push(node);
    }

    fn finish(mut self, extras: serde_json::Value) -> Result<Exported, String> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        if self.bin.len() > u32::MAX as usize - 1024 * 1024 {
            return Err(format!("the scene's {} bytes of geometry exceed a .glb's 4 GiB", self.bin.len()));
        }
        self.root.buffers[0].byte_length = USize64::from(self.bin.len());
        let scene = self.root.push(gj::Scene {
            name: Some("shadelab".into()),
            nodes: self.nodes.clone(),
            extensions: None,
            extras: raw_extras(&extras),
        });
        self.root.scene = Some(scene);
        self.root.extensions_used = self.used.iter().map(|s| s.to_string()).collect();
        let json = gj::serialize::to_vec(&self.root).map_err(|e| e.to_string())?;
        let glb = gltf::binary::Glb {
            header: gltf::binary::Header { magic: *b"glTF", version: 2, length: 0 },
            json: Cow::Owned(json),
            bin: Some(Cow::Owned(self.bin)),
        };
        Ok(Exported { glb: glb.to_vec().map_err(|e| e.to_string())?, warnings: self.warnings })
    }
}

/// `value` as a glTF `extras` object.
fn raw_extras(value: &serde_json::Value) -> Option<Box<serde_json::value::RawValue>> {
    serde_json::value::RawValue::from_string(value.to_string()).ok()
}

/// GGX roughness for a Blinn-Phong exponent n: α = √(2/(n + 2)) (Walter et al. 2007,
/// eq. 29's correspondence), roughness = √α.
fn roughness_of_exponent(n: f32) -> f32 {
    (2.0 / (n.max(0.0) + 2.0)).sqrt().sqrt().clamp(0.0, 1.0)
}

/// A spot's glTF cones (radians): from a profile, the last angle at full strength and the
/// last angle given; from cos^L_exp, where it falls to ½ and to 1/100, within the cutoff.
fn spot_cones(l: &LightSpec) -> (f32, f32) {
    let cutoff = if l.cos_cutoff > -1.0 { l.cos_cutoff.clamp(-1.0, 1.0).acos() } else { std::f32::consts::FRAC_PI_2 };
    let (inner, outer) = match &l.profile {
        Some(p) => {
            let full = p.iter().take_while(|(_, f)| *f >= 0.999).last().map_or(0.0, |(a, _)| a.to_radians());
            (full, p.last().map_or(cutoff, |(a, _)| a.to_radians()))
        }
        None => {
            let at = |f: f32| f.powf(1.0 / l.exponent.max(1e-3)).acos();
            (at(0.5), at(0.01))
        }
    };
    let outer = outer.min(cutoff).clamp(1e-3, std::f32::consts::FRAC_PI_2);
    (inner.clamp(0.0, outer * 0.999), outer)
}

/// A unit disk in the xz plane facing +y, as a fan of `n` triangles.
fn disk(n: u32) -> crate::scene::Mesh {
    let mut m = crate::scene::Mesh { positions: vec![Vec3::ZERO], ..Default::default() };
    for k in 0..n {
        let a = std::f32::consts::TAU * k as f32 / n as f32;
        m.positions.push(Vec3::new(a.cos(), 0.0, -a.sin()));
        m.triangles.push([0, 1 + k, 1 + (k + 1) % n]);
    }
    m
}
