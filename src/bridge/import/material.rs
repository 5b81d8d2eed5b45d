//! The materials of an imported file: pbrMetallicRoughness and the KHR_materials_* that
//! `principled` can read, clear glass and smooth metal, and their textures (files beside the
//! glTF file named, embedded images extracted beside the lesson, each checked to decode).

use std::fmt::Write as _;
use std::path::Path;

use glam::Vec3;

use super::{Writer, key, num, quote, vec3};
use crate::bridge::units;

impl Writer<'_> {
    /// The `[material.NAME]` tables of the materials the objects use.
    pub(super) fn materials(&mut self) -> Vec<String> {
        let mut used = vec![false; self.material_names.len()];
        for n in self.file.mesh_nodes() {
            let node = self.file.doc.nodes().nth(n.node).expect("a node");
            for p in node.mesh().expect("a mesh node").primitives() {
                used[p.material().index().unwrap_or(self.material_names.len() - 1)] = true;
            }
        }
        let mut out = Vec::new();
        let doc = &self.file.doc;
        for (i, name) in self.material_names.clone().iter().enumerate() {
            if !used[i] {
                continue;
            }
            let m = doc.materials().nth(i);
            out.push(match m {
                Some(m) => self.material(&m, name),
                None => format!(
                    "[material.{}]         # glTF's default material (a primitive without one)\nmodel = \"principled\"\nbase_color = [1.0, 1.0, 1.0]\nmetallic = 1.0\nroughness = 1.0\n",
                    key(name)
                ),
            });
        }
        out
    }

    fn material(&mut self, m: &gltf::Material, name: &str) -> String {
        let at = format!("/materials/{}", m.index().unwrap_or(0));
        let pbr = m.pbr_metallic_roughness();
        let [r, g, b, a] = pbr.base_color_factor();
        let base = Vec3::new(r, g, b).clamp(Vec3::ZERO, Vec3::ONE);
        let (metallic, roughness) = (pbr.metallic_factor().clamp(0.0, 1.0), pbr.roughness_factor().clamp(0.0, 1.0));
        let ior = m.ior().unwrap_or(1.5);
        let emission = Vec3::from(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0);
        let transmission = m.transmission().map_or(0.0, |t| t.transmission_factor());
        let mut t = String::new();
        if metallic >= 0.999 && roughness <= 1e-3 && transmission == 0.0 {
            let _ = writeln!(t, "[material.{}]      # a perfectly smooth metal: a mirror", key(name));
            let _ = writeln!(t, "model = \"mirror\"");
            let _ = writeln!(t, "tint = {}", vec3(base));
            if emission.max_element() > 0.0 {
                let _ = writeln!(t, "emission = {}", vec3(emission.clamp(Vec3::ZERO, Vec3::splat(1e6))));
            }
            return t;
        }
        if transmission >= 0.5 && metallic < 0.5 && roughness < 0.1 {
            let _ = writeln!(
                t,
                "[material.{}]      # clear glass: transmission {}, roughness {}",
                key(name),
                num(transmission),
                num(roughness)
            );
            let _ = writeln!(t, "model = \"glass\"");
            let _ = writeln!(t, "ior = {}", num(ior.clamp(0.1, 10.0)));
            let _ = writeln!(t, "tint = {}", vec3(base));
            return t;
        }
        if transmission > 0.0 {
            self.warnings.push(format!(
                "{at}: transmission {} is written commented out as principled's specular_transmission, which only method = \"path\" draws (clear glass becomes `glass`)",
                num(transmission)
            ));
        }
        let _ = writeln!(t, "[material.{}]", key(name));
        let _ = writeln!(t, "model = \"principled\"             # Blender's Principled BSDF, read as Disney 2012");
        if transmission > 0.0 {
            // The rasterizer refuses transmission: left for the student to switch on with the path tracer.
            let _ = writeln!(t, "# specular_transmission = {}    # with [render] method = \"path\"", num(transmission.clamp(0.0, 1.0)));
            let _ = writeln!(t, "# ior = {}", num(ior.clamp(1.0, 3.0)));
        }
        match pbr.base_color_texture() {
            Some(info) => {
                if let Some(path) = self.texture(&info.texture(), &format!("{at}/pbrMetallicRoughness/baseColorTexture")) {
                    let _ = writeln!(t, "base_color = {{ texture = {} }}", quote(&path));
                    if base != Vec3::ONE {
                        self.warnings
                            .push(format!("{at}: baseColorFactor {} times the texture is not read (the texture alone is)", vec3(base)));
                    }
                } else {
                    let _ = writeln!(t, "base_color = {}              # the factor: its texture is not read", vec3(base));
                }
                self.texture_info_warnings(info.tex_coord(), info.texture_transform().is_some(), &at, "baseColorTexture");
            }
            None => {
                let _ = writeln!(t, "base_color = {}", vec3(base));
            }
        }
        // The metallic-roughness image: roughness in green, metallic in blue (glTF 2.0, 3.9.2).
        let mr = pbr.metallic_roughness_texture();
        match mr.as_ref().and_then(|info| self.texture(&info.texture(), &format!("{at}/pbrMetallicRoughness/metallicRoughnessTexture"))) {
            Some(path) => {
                let _ = writeln!(t, "metallic = {{ texture = {}, channel = \"b\" }}", quote(&path));
                let _ = writeln!(t, "roughness = {{ texture = {}, channel = \"g\" }}", quote(&path));
                if metallic != 1.0 || roughness != 1.0 {
                    self.warnings.push(format!(
                        "{at}: metallicFactor {} and roughnessFactor {} times the metallic-roughness texture are not read (the texture alone is)",
                        num(metallic),
                        num(roughness)
                    ));
                }
                let info = mr.expect("a texture");
                self.texture_info_warnings(info.tex_coord(), info.texture_transform().is_some(), &at, "metallicRoughnessTexture");
            }
            None => {
                let _ = writeln!(t, "metallic = {}", num(metallic));
                let _ = writeln!(t, "roughness = {}", num(roughness));
            }
        }
        let spec = m.specular();
        let factor = spec.as_ref().map_or(1.0, |s| s.specular_factor());
        let _ = writeln!(
            t,
            "specular = {}                 # F0 = ((η−1)/(η+1))² = {} at η = {}, over 0.08",
            num(units::disney_specular(ior, factor)),
            num(units::disney_specular(ior, factor) * 0.08),
            num(ior)
        );
        if spec.as_ref().is_some_and(|s| s.specular_color_factor() != [1.0, 1.0, 1.0]) {
            self.warnings.push(format!("{at}: KHR_materials_specular's specularColorFactor is not read (principled's specular_tint tints towards the base colour only)"));
        }
        if let Some(cc) = m.extension_value("KHR_materials_clearcoat") {
            let f = cc.get("clearcoatFactor").and_then(serde_json::Value::as_f64).unwrap_or(0.0) as f32;
            let r = cc.get("clearcoatRoughnessFactor").and_then(serde_json::Value::as_f64).unwrap_or(0.0) as f32;
            let _ = writeln!(t, "clearcoat = {}", num(f.clamp(0.0, 1.0)));
            let _ = writeln!(t, "clearcoat_gloss = {}          # 1 − clearcoatRoughnessFactor", num((1.0 - r).clamp(0.0, 1.0)));
        }
        if let Some(sh) = m.extension_value("KHR_materials_sheen") {
            let c: Vec<f32> = sh
                .get("sheenColorFactor")
                .and_then(|v| v.as_array())
                .map_or_else(Vec::new, |a| a.iter().filter_map(|x| x.as_f64()).map(|x| x as f32).collect());
            let weight = c.iter().copied().fold(0.0, f32::max).clamp(0.0, 1.0);
            let _ = writeln!(t, "sheen = {}                    # the largest of sheenColorFactor", num(weight));
            self.warnings
                .push(format!("{at}: KHR_materials_sheen read as Disney's sheen weight only (its colour and roughness are not read)"));
        }
        if emission.max_element() > 0.0 {
            let _ = writeln!(
                t,
                "emission = {}         # emissiveFactor × emissiveStrength (radiance)",
                vec3(emission.clamp(Vec3::ZERO, Vec3::splat(1e6)))
            );
        }
        if let Some(n) = m.normal_texture() {
            if let Some(path) = self.texture(&n.texture(), &format!("{at}/normalTexture")) {
                let _ = writeln!(t, "normal_map = {}", quote(&path));
            }
            if n.scale() != 1.0 {
                self.warnings.push(format!("{at}/normalTexture: scale {} is not read", num(n.scale())));
            }
            self.texture_info_warnings(n.tex_coord(), false, &at, "normalTexture");
        }
        if let Some(o) = m.occlusion_texture() {
            // glTF's occlusion is in the red channel, as `occlusion_map` reads it; it scales
            // indirect light, which here is the ambient term.
            if let Some(path) = self.texture(&o.texture(), &format!("{at}/occlusionTexture")) {
                let _ = writeln!(t, "occlusion_map = {}   # darkens the ambient term only", quote(&path));
            }
            if o.strength() != 1.0 {
                self.warnings.push(format!("{at}/occlusionTexture: strength {} is not read", num(o.strength())));
            }
            self.texture_info_warnings(o.tex_coord(), false, &at, "occlusionTexture");
        }
        for (what, present) in [("emissiveTexture (the emissive factor is used)", m.emissive_texture().is_some())] {
            if present {
                self.warnings.push(format!("{at}: {what} is not read"));
            }
        }
        if a < 1.0 || m.alpha_mode() != gltf::material::AlphaMode::Opaque {
            self.warnings.push(format!("{at}: alpha ({:?}, {}) is not read: the material is opaque", m.alpha_mode(), num(a)));
        }
        t
    }

    fn texture_info_warnings(&mut self, tex_coord: u32, transform: bool, at: &str, slot: &str) {
        if tex_coord != 0 {
            self.warnings.push(format!("{at}/{slot}: texCoord {tex_coord} is not read (TEXCOORD_0 is used)"));
        }
        if transform {
            self.warnings.push(format!("{at}/{slot}: KHR_texture_transform is not read"));
        }
    }

    /// A texture's image as a path from the lesson: a file beside the glTF file, or the
    /// embedded bytes extracted beside the lesson. `None` (with a warning) when unusable.
    fn texture(&mut self, tex: &gltf::Texture, at: &str) -> Option<String> {
        let index = tex.source().index();
        let img = self.file.doc.as_json().images.get(index)?;
        let ext = |mime: &str| match mime {
            "image/png" => Some("png"),
            "image/jpeg" => Some("jpg"),
            _ => None,
        };
        let bytes_and_ext: Option<(Vec<u8>, &str)> = match (&img.uri, &img.buffer_view, &img.mime_type) {
            (Some(uri), _, _) if !uri.starts_with("data:") => {
                // A file beside the glTF file: named from the lesson's folder.
                let folder = Path::new(&self.glb_rel).parent().map(|p| p.to_string_lossy().into_owned()).unwrap_or_default();
                let decoded = percent_encoding::percent_decode_str(uri).decode_utf8_lossy().into_owned();
                match crate::scene::gltf::read_uri(self.file.path.parent().unwrap_or(Path::new(".")), uri) {
                    Ok(bytes) if image::load_from_memory(&bytes).is_err() => {
                        self.warnings.push(format!("{at}: image {index} (`{uri}`) does not decode; the texture is not read"));
                        return None;
                    }
                    Ok(_) => return Some(if folder.is_empty() { decoded } else { format!("{folder}/{decoded}") }),
                    Err((what, kind)) => {
                        // A missing image, or one outside the folder, is bad input as a missing buffer is.
                        self.fatal.get_or_insert_with(|| self.file.err(format!("/images/{index}/uri"), what, kind));
                        return None;
                    }
                }
            }
            (Some(uri), _, _) => match crate::scene::gltf::read_uri(Path::new("."), uri) {
                Ok(b) => {
                    let mime = uri.trim_start_matches("data:").split([';', ',']).next().unwrap_or("");
                    ext(mime).map(|e| (b, e))
                }
                Err((what, kind)) => {
                    self.fatal.get_or_insert_with(|| self.file.err(format!("/images/{index}/uri"), what, kind));
                    return None;
                }
            },
            (None, Some(view), Some(mime)) => {
                let v = self.file.doc.views().nth(view.value())?;
                let buf = self.file.buffers.get(v.buffer().index())?;
                let bytes = buf.get(v.offset()..v.offset().checked_add(v.length())?)?.to_vec();
                ext(&mime.0).map(|e| (bytes, e))
            }
            _ => None,
        };
        let Some((bytes, e)) = bytes_and_ext else {
            self.warnings.push(format!("{at}: image {index} is not a PNG or JPEG the lesson can read; the texture is not read"));
            return None;
        };
        // A lesson that names an image it cannot decode would not render: say so here instead.
        if let Err(why) = image::load_from_memory(&bytes) {
            self.warnings.push(format!("{at}: image {index} does not decode ({why}); the texture is not read"));
            return None;
        }
        let name = format!("{}-textures/image-{index}.{e}", self.lesson_stem);
        let path = self.lesson_dir.join(&name);
        if !self.files.iter().any(|(p, _)| *p == path) {
            self.files.push((path, bytes));
        }
        Some(name)
    }
}
