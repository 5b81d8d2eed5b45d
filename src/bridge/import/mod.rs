//! `shadelab import`: a glTF 2.0 scene as a lesson that renders it.
//!
//! The geometry stays in the glTF file: each mesh node (each primitive, when a mesh has
//! several materials) becomes an `[[object]]` naming the file and its node. Materials
//! (pbrMetallicRoughness and the KHR_materials_* extensions principled can read) become
//! `principled` (clear glass: `glass`), KHR_lights_punctual lights become point, spot and
//! directional lights in radiometric units ([`super::units`]), and the first perspective
//! camera the camera. What is not read is a warning naming it, never dropped in silence.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};
use gltf::khr_lights_punctual::Kind;

use super::units;

mod material;
use crate::scene::gltf::{GltfError, GltfErrorKind, GltfFile};

/// A lesson made from a glTF file, with the files it needs written beside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Imported {
    /// The lesson's TOML text.
    pub lesson: String,
    /// Other files to write (embedded textures, the glTF file when it lies outside the
    /// lesson's folder), by path.
    pub files: Vec<(PathBuf, Vec<u8>)>,
    /// What was not read, one line each.
    pub warnings: Vec<String>,
    /// What was supplied (a framing camera, a light), one line each.
    pub notes: Vec<String>,
}

/// Extensions the import reads (others are named in a warning).
const READ_EXTENSIONS: [&str; 7] = [
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_materials_specular",
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
];

/// `source` (a `.glb` or `.gltf`) as a lesson to be written at `lesson_path`.
///
/// # Errors
/// [`GltfError`] for a file that cannot be read or is invalid (nothing is written then).
pub fn import(source: &Path, lesson_path: &Path) -> Result<Imported, GltfError> {
    let file = crate::scene::gltf::open(source)?;
    let mut w = Writer::new(&file, source, lesson_path)?;
    w.whole_file_warnings();
    let objects = w.objects()?;
    let camera = w.camera(&objects.1)?;
    let lights = w.lights();
    let materials = w.materials();
    if let Some(e) = w.fatal.take() {
        return Err(e);
    }
    let stem = source.file_stem().and_then(|s| s.to_str()).unwrap_or("scene").to_string();
    let mut t = String::new();
    let _ = writeln!(t, "# {stem}: imported from {} by `shadelab import` (glTF 2.0).", w.glb_rel);
    let _ = writeln!(t, "#");
    let _ = writeln!(t, "# The geometry stays in the glTF file: each [[object]] names a node of it (and a primitive");
    let _ = writeln!(t, "# when its mesh has several materials), placed by the node's transform; `translate`,");
    let _ = writeln!(t, "# `rotate_deg` and `scale` move it further. Lights are converted from KHR_lights_punctual's");
    let _ = writeln!(t, "# photometric units at 683 lm/W, as Blender's glTF add-on does (docs/gltf.md).");
    let shown = lesson_path.display().to_string();
    let _ = writeln!(t, "# Try: shadelab render {shown}");
    let _ = writeln!(t, "#      shadelab split {shown}");
    let _ = writeln!(
        t,
        "#      shadelab new my-lights --template three-point --scene {shown} -o {}",
        lesson_path.parent().filter(|d| !d.as_os_str().is_empty()).map_or_else(|| ".".into(), |d| format!("{}/", d.display()))
    );
    let _ = writeln!(t);
    let _ = writeln!(t, "[lesson]");
    let _ = writeln!(t, "title = {}", quote(&stem));
    let summary = format!(
        "A glTF scene: {} object{}, {} light{}, {} material{}.",
        objects.0.len(),
        plural(objects.0.len()),
        lights.len(),
        plural(lights.len()),
        materials.len(),
        plural(materials.len())
    );
    let _ = writeln!(t, "summary = {}", quote(&summary));
    let _ = writeln!(t);
    t.push_str(&camera);
    for o in &objects.0 {
        t.push('\n');
        t.push_str(o);
    }
    for m in &materials {
        t.push('\n');
        t.push_str(m);
    }
    for l in &lights {
        t.push('\n');
        t.push_str(l);
    }
    let _ = writeln!(t);
    let _ = writeln!(t, "[render]");
    // A file shadelab exported carries its lesson's `[render]` table; else Blender's look.
    let own = file.doc.scenes().find_map(|sc| ours(sc.extras())).map(|v| v.get("render").cloned().unwrap_or(serde_json::json!({})));
    match own.and_then(|v| serde_json::from_value::<toml::Table>(v).ok()).and_then(|r| toml::to_string(&r).ok()) {
        Some(render) => {
            let _ = writeln!(t, "# as the exported lesson had it");
            t.push_str(&render);
        }
        None => {
            let _ = writeln!(t, "interpolation = \"phong\"");
            let _ = writeln!(t, "tonemap = \"agx\"              # Blender's default view transform");
            let _ = writeln!(t, "aa = 2");
        }
    }
    Ok(Imported { lesson: t, files: w.files, warnings: w.warnings, notes: w.notes })
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// A TOML string.
fn quote(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// A table key: bare when TOML allows it, else quoted.
fn key(s: &str) -> String {
    if !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') { s.to_string() } else { quote(s) }
}

/// A number as TOML writes a float (always with a point), rounded to 6 significant digits.
fn num(x: f32) -> String {
    let x = if x.abs() < 1e-12 { 0.0 } else { x };
    let s = format!("{}", (x as f64 * 1e6).round() / 1e6);
    let s = if s == "-0" { "0".into() } else { s };
    if s.contains('.') { s } else { format!("{s}.0") }
}

/// `x` rounded to 1/`scale`, written as a TOML float.
fn round(x: f32, scale: f64) -> String {
    num(((x as f64 * scale).round() / scale) as f32)
}

/// An angle in radians, in degrees to a thousandth.
fn deg(radians: f32) -> String {
    round(radians.to_degrees(), 1e3)
}

/// A spot's `profile` or `exponent` and `cutoff_deg` lines from what `export` wrote, when valid.
fn spot_law(v: &serde_json::Value) -> Option<String> {
    let mut t = String::new();
    if let Some(points) = v.get("profile").and_then(|p| p.as_array()) {
        let pts: Option<Vec<(f64, f64)>> = points.iter().map(|p| Some((p.get(0)?.as_f64()?, p.get(1)?.as_f64()?))).collect();
        let pts =
            pts.filter(|p| !p.is_empty() && p.len() <= 32 && p.iter().all(|(a, f)| (0.0..=90.0).contains(a) && (0.0..=1e6).contains(f)))?;
        let written: Vec<String> = pts.iter().map(|(a, f)| format!("[{}, {}]", num(*a as f32), num(*f as f32))).collect();
        let _ = writeln!(t, "profile = [{}]", written.join(", "));
    } else {
        let e = v.get("exponent")?.as_f64().filter(|e| (0.0..=1e6).contains(e))?;
        let _ = writeln!(t, "exponent = {}", num(e as f32));
    }
    if let Some(c) = v.get("cutoff_deg").and_then(serde_json::Value::as_f64).filter(|c| (0.0..=180.0).contains(c)) {
        let _ = writeln!(t, "cutoff_deg = {}", num(c as f32));
    }
    Some(t)
}

fn vec3(v: Vec3) -> String {
    format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z))
}

/// What the import writes, as it goes: the file, where the lesson is, what it said.
struct Writer<'a> {
    file: &'a GltfFile,
    /// The glTF file as the lesson names it (relative to the lesson's folder).
    glb_rel: String,
    /// The lesson's folder and stem (for extracted textures).
    lesson_dir: PathBuf,
    lesson_stem: String,
    /// The material table name of each glTF material (and of the default material, last).
    material_names: Vec<String>,
    files: Vec<(PathBuf, Vec<u8>)>,
    warnings: Vec<String>,
    notes: Vec<String>,
    /// The first image that is bad input (missing, outside the folder, over a limit).
    fatal: Option<GltfError>,
}

impl<'a> Writer<'a> {
    fn new(file: &'a GltfFile, source: &Path, lesson_path: &Path) -> Result<Writer<'a>, GltfError> {
        let lesson_dir = match lesson_path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let lesson_stem = lesson_path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene").to_string();
        let mut w = Writer {
            file,
            glb_rel: String::new(),
            lesson_dir: lesson_dir.clone(),
            lesson_stem,
            material_names: Vec::new(),
            files: Vec::new(),
            warnings: Vec::new(),
            notes: Vec::new(),
            fatal: None,
        };
        w.glb_rel = w.place_source(source)?;
        let mut taken: Vec<String> = Vec::new();
        for m in file.doc.materials() {
            let base =
                m.name().filter(|n| !n.trim().is_empty()).map_or_else(|| format!("material-{}", m.index().unwrap_or(0)), str::to_string);
            let mut name = base.clone();
            let mut k = 2;
            while taken.contains(&name) {
                name = format!("{base} ({k})");
                k += 1;
            }
            taken.push(name.clone());
            w.material_names.push(name);
        }
        w.material_names.push("gltf-default".into());
        Ok(w)
    }

    /// The glTF file as the lesson will name it: its path from the lesson's folder when it
    /// lies inside that folder; else a `.glb` is copied beside the lesson (a lesson reads only
    /// files inside its folder).
    fn place_source(&mut self, source: &Path) -> Result<String, GltfError> {
        let dir =
            self.lesson_dir.canonicalize().map_err(|e| self.file.err("", format!("the lesson's folder: {e}"), GltfErrorKind::Missing))?;
        let src = source.canonicalize().map_err(|e| self.file.err("", e.to_string(), GltfErrorKind::Missing))?;
        if let Ok(rel) = src.strip_prefix(&dir) {
            return Ok(rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect::<Vec<_>>().join("/"));
        }
        let name = src.file_name().map_or_else(|| "scene.glb".into(), |n| n.to_string_lossy().into_owned());
        if !crate::scene::gltf::is_gltf(Path::new(&name)) || name.to_ascii_lowercase().ends_with(".gltf") {
            return Err(self.file.err(
                "",
                "a .gltf outside the lesson's folder cannot be copied with its buffers; write the lesson in the .gltf's folder (or above it)".to_string(),
                GltfErrorKind::Outside,
            ));
        }
        let bytes = std::fs::read(&src).map_err(|e| self.file.err("", e.to_string(), GltfErrorKind::Missing))?;
        let target = self.lesson_dir.join(&name);
        if let Ok(existing) = std::fs::read(&target)
            && existing != bytes
        {
            return Err(self.file.err(
                "",
                format!("{} already exists beside the lesson and differs; write the lesson in the .glb's folder", target.display()),
                GltfErrorKind::Outside,
            ));
        }
        self.notes.push(format!("copied {name} beside the lesson (a lesson reads only files inside its folder)"));
        self.files.push((target, bytes));
        Ok(name)
    }

    fn whole_file_warnings(&mut self) {
        let json = self.file.doc.as_json();
        for ext in self.file.doc.extensions_used() {
            if !READ_EXTENSIONS.contains(&ext) {
                self.warnings.push(format!("extension {ext} is not read"));
            }
        }
        if !json.animations.is_empty() {
            self.warnings.push(format!(
                "{} animation{} not read: the lesson shows the rest pose",
                json.animations.len(),
                plural(json.animations.len())
            ));
        }
        if !json.skins.is_empty() {
            self.warnings.push(format!("{} skin{} not read: meshes are shown unskinned", json.skins.len(), plural(json.skins.len())));
        }
        for (i, m) in json.meshes.iter().enumerate() {
            if m.primitives.iter().any(|p| p.targets.as_ref().is_some_and(|t| !t.is_empty())) {
                self.warnings.push(format!("/meshes/{i}: morph targets not read"));
            }
            for (k, p) in m.primitives.iter().enumerate() {
                for name in p.attributes.keys() {
                    if let gltf::json::validation::Checked::Valid(s) = name {
                        let s = s.to_string();
                        if !matches!(s.as_str(), "POSITION" | "NORMAL" | "TEXCOORD_0" | "TANGENT") {
                            self.warnings.push(format!("/meshes/{i}/primitives/{k}/attributes/{s} not read"));
                        }
                    }
                }
            }
        }
    }

    /// The `[[object]]` tables, and the world-space mesh of every mesh node (for framing).
    fn objects(&mut self) -> Result<(Vec<String>, Vec<Vec3>), GltfError> {
        let nodes = self.file.mesh_nodes();
        if nodes.is_empty() {
            return Err(self.file.err("/nodes", "the scene has no mesh node: nothing to render", GltfErrorKind::Selection));
        }
        // A node is named by its name when that is unique among mesh nodes, else by index.
        let unique = |name: &str| nodes.iter().filter(|n| n.name.as_deref() == Some(name)).count() == 1;
        let mut out = Vec::new();
        for n in &nodes {
            let node = self.file.doc.nodes().nth(n.node).expect("a node");
            let mesh = node.mesh().expect("a mesh node");
            let prims: Vec<gltf::Primitive> = mesh.primitives().collect();
            let several = prims.len() > 1;
            for p in &prims {
                if matches!(
                    p.mode(),
                    gltf::mesh::Mode::Points | gltf::mesh::Mode::Lines | gltf::mesh::Mode::LineLoop | gltf::mesh::Mode::LineStrip
                ) {
                    self.warnings.push(format!("/meshes/{}/primitives/{}: points and lines are not drawn", mesh.index(), p.index()));
                    continue;
                }
                let material = p
                    .material()
                    .index()
                    .map_or_else(|| self.material_names.last().cloned().expect("default"), |i| self.material_names[i].clone());
                let mut t = String::new();
                let label = n.name.clone().unwrap_or_else(|| format!("node {}", n.node));
                let _ = writeln!(t, "[[object]]                     # {label}");
                let _ = writeln!(t, "shape = \"mesh\"");
                let _ = writeln!(t, "path = {}", quote(&self.glb_rel));
                match &n.name {
                    Some(name) if unique(name) => {
                        let _ = writeln!(t, "node = {}", quote(name));
                    }
                    _ => {
                        let _ = writeln!(t, "node = {}", n.node);
                    }
                }
                if several {
                    let _ = writeln!(t, "primitive = {}", p.index());
                }
                let _ = writeln!(t, "material = {}", quote(&material));
                out.push(t);
            }
        }
        let all = self.file.load(&Default::default(), 0)?;
        Ok((out, all.mesh.positions))
    }

    /// `[camera]`: the first perspective camera of the scene, else one framing the meshes.
    fn camera(&mut self, positions: &[Vec3]) -> Result<String, GltfError> {
        let mut cameras: Vec<(Mat4, usize)> = Vec::new();
        self.file.walk(&mut |node, world| {
            if let Some(cam) = node.camera() {
                cameras.push((world, cam.index()));
            }
        });
        let mut ortho = false;
        let mut found = None;
        for (world, index) in cameras {
            let cam = self.file.doc.cameras().nth(index).expect("a camera of the document");
            match cam.projection() {
                gltf::camera::Projection::Perspective(p) => {
                    found = Some((world, p.yfov(), p.aspect_ratio(), p.znear(), ours(cam.extras()).unwrap_or_default()));
                    break;
                }
                gltf::camera::Projection::Orthographic(_) => ortho = true,
            }
        }
        let mut t = String::from("[camera]\n");
        match found {
            Some((world, yfov, aspect, znear, own)) => {
                let eye = world.transform_point3(Vec3::ZERO);
                let forward = world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Z);
                // What shadelab exported, when the file is ours: the camera exactly as written.
                let triple =
                    |key: &str| serde_json::from_value::<[f32; 3]>(own.get(key)?.clone()).ok().map(Vec3::from).filter(|v| v.is_finite());
                let size = own.get("size").and_then(|s| Some((s.get(0)?.as_u64()? as u32, s.get(1)?.as_u64()? as u32)));
                let up = triple("up").unwrap_or_else(|| world.transform_vector3(Vec3::Y).normalize_or(Vec3::Y));
                // Look at the point of the meshes' centre's depth along the view axis.
                let (centre, radius) = bounds(positions);
                let depth = (centre - eye).dot(forward).max(radius * 0.1).max(1e-3);
                let look_at = triple("look_at").filter(|l| (*l - eye).length() > 1e-6).unwrap_or(eye + forward * depth);
                let fov = own.get("fov_deg").and_then(serde_json::Value::as_f64).map_or(yfov.to_degrees(), |f| f as f32);
                let aspect = aspect.filter(|a| a.is_finite() && *a > 0.0).unwrap_or(1.0);
                // The size shadelab exported, else the longer side 640 at the aspect ratio.
                let (width, height) =
                    size.filter(|&(w, h)| (1..=16384).contains(&w) && (1..=16384).contains(&h)).unwrap_or(if aspect >= 1.0 {
                        (640, ((640.0 / aspect).round() as u32).max(16))
                    } else {
                        (((640.0 * aspect).round() as u32).max(16), 640)
                    });
                let _ = writeln!(t, "position = {}            # the glTF camera's node", vec3(eye));
                let _ = writeln!(t, "look_at = {}", vec3(look_at));
                let _ = writeln!(t, "up = {}", vec3(up));
                let _ = writeln!(t, "fov_deg = {}                 # yfov {} rad", num(fov.clamp(1.0, 179.0)), num(yfov));
                let _ = writeln!(t, "size = [{width}, {height}]");
                let _ = writeln!(t, "near = {}", num(znear.clamp(1e-4, 1e4)));
            }
            None => {
                if ortho {
                    self.warnings.push("the file's camera is orthographic, which lessons do not have: a framing camera is used".into());
                } else {
                    self.notes.push("the file has no camera: the lesson frames the meshes from the front".into());
                }
                let (centre, radius) = bounds(positions);
                let fov = 40f32;
                let distance = (radius / (fov.to_radians() / 2.0).sin()).max(1e-3) * 1.1;
                let eye = centre + Vec3::new(0.0, 0.35, 1.0).normalize() * distance;
                let _ = writeln!(t, "position = {}            # framing the meshes (the file has no perspective camera)", vec3(eye));
                let _ = writeln!(t, "look_at = {}", vec3(centre));
                let _ = writeln!(t, "fov_deg = 40.0");
                let _ = writeln!(t, "size = [512, 512]");
                let _ = writeln!(t, "near = {}", num((distance * 0.01).clamp(1e-4, 1e4)));
            }
        }
        let background = self.file.doc.scenes().find_map(|sc| ours(sc.extras())?.get("background").cloned());
        let background = background.and_then(|b| serde_json::from_value::<[f32; 3]>(b).ok()).filter(|b| b.iter().all(|x| x.is_finite()));
        let _ = writeln!(
            t,
            "background = {}",
            vec3(background.map_or(Vec3::new(0.05, 0.05, 0.06), |b| Vec3::from(b).clamp(Vec3::ZERO, Vec3::splat(1e6))))
        );
        Ok(t)
    }

    /// The `[[light]]` tables of KHR_lights_punctual, in the scene's node order.
    fn lights(&mut self) -> Vec<String> {
        let mut found: Vec<(Mat4, usize, Option<String>)> = Vec::new();
        self.file.walk(&mut |node, world| {
            if let Some(l) = node.light() {
                found.push((world, l.index(), node.name().map(str::to_string)));
            }
        });
        let mut out = Vec::new();
        for (world, index, name) in found {
            let l = self.file.doc.lights().and_then(|mut ls| ls.nth(index)).expect("a light of the document");
            let label = name.or_else(|| l.name().map(str::to_string)).unwrap_or_else(|| format!("light {}", l.index()));
            let color = Vec3::from(l.color()).clamp(Vec3::ZERO, Vec3::splat(1e6));
            let pos = world.transform_point3(Vec3::ZERO);
            let dir = world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Y);
            if l.range().is_some() {
                self.warnings.push(format!(
                    "/extensions/KHR_lights_punctual/lights/{}: range is not read (the light reaches everywhere, as in Blender)",
                    l.index()
                ));
            }
            let mut t = String::new();
            let _ = writeln!(t, "[[light]]                      # {label}");
            match l.kind() {
                Kind::Directional => {
                    let e = units::irradiance_from_lux(l.intensity()).clamp(0.0, 1e9);
                    let _ = writeln!(t, "kind = \"directional\"");
                    let _ = writeln!(t, "direction = {}", vec3(dir));
                    let _ = writeln!(t, "color = {}", vec3(color));
                    let _ = writeln!(t, "intensity = {}           # E⊥ in W/m²: {} lux ÷ 683 lm/W", num(e), num(l.intensity()));
                }
                Kind::Point => {
                    let i = units::watts_per_sr_from_candela(l.intensity()).clamp(0.0, 1e9);
                    let _ = writeln!(t, "kind = \"point\"");
                    let _ = writeln!(t, "position = {}", vec3(pos));
                    let _ = writeln!(t, "color = {}", vec3(color));
                    let _ = writeln!(
                        t,
                        "intensity = {}           # I in W/sr: {} cd ÷ 683 lm/W (Blender: {} W)",
                        num(i),
                        num(l.intensity()),
                        num(units::blender_watts(i))
                    );
                }
                Kind::Spot { inner_cone_angle, outer_cone_angle } => {
                    let i = units::watts_per_sr_from_candela(l.intensity()).clamp(0.0, 1e9);
                    let profile = units::spot_profile(inner_cone_angle, outer_cone_angle);
                    let law = ours(l.extras());
                    let _ = writeln!(t, "kind = \"spot\"");
                    let _ = writeln!(t, "position = {}", vec3(pos));
                    let _ = writeln!(t, "direction = {}", vec3(dir));
                    let _ = writeln!(t, "color = {}", vec3(color));
                    let _ = writeln!(
                        t,
                        "intensity = {}           # I on the axis, W/sr: {} cd ÷ 683 lm/W (Blender: {} W)",
                        num(i),
                        num(l.intensity()),
                        num(units::blender_watts(i))
                    );
                    match law.and_then(|v| spot_law(&v)) {
                        Some(law) => {
                            let _ = writeln!(t, "# The spot's own law, as shadelab exported it (the file's cone is its glTF reading)");
                            t.push_str(&law);
                        }
                        None => {
                            let _ = writeln!(
                                t,
                                "# The glTF falloff from the inner cone ({}°) to the outer ({}°): ((cos θ − cos θo)/(cos θi − cos θo))²",
                                deg(inner_cone_angle),
                                deg(outer_cone_angle)
                            );
                            let points: Vec<String> = profile.iter().map(|(a, f)| format!("[{}, {}]", round(*a, 1e3), num(*f))).collect();
                            let _ = writeln!(t, "profile = [{}]", points.join(", "));
                            let _ = writeln!(t, "cutoff_deg = {}", deg(outer_cone_angle.clamp(0.0, std::f32::consts::FRAC_PI_2)));
                        }
                    }
                }
            }
            out.push(t);
        }
        if out.is_empty() {
            self.notes.push("the file has no KHR_lights_punctual light: the lesson adds a sun; `shadelab new --template three-point` shows three lights to add".into());
            out.push(
                "[[light]]                      # added by the import: the file has no light\nkind = \"directional\"\ndirection = [-0.4, -1.0, -0.6]\nintensity = 3.0\n"
                    .into(),
            );
        }
        out
    }
}

/// The `shadelab` object of an `extras` (what `export` wrote for its own import).
fn ours(extras: &gltf::json::Extras) -> Option<serde_json::Value> {
    let raw = extras.as_ref()?;
    serde_json::from_str::<serde_json::Value>(raw.get()).ok()?.get("shadelab").cloned()
}

/// The centre and radius of the bounding box of `points` (the unit ball when there are none).
fn bounds(points: &[Vec3]) -> (Vec3, f32) {
    if points.is_empty() {
        return (Vec3::ZERO, 1.0);
    }
    let (lo, hi) = points.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    ((lo + hi) / 2.0, ((hi - lo).length() / 2.0).max(1e-3))
}
