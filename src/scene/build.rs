//! Lesson → runtime scene: meshes generated or loaded, normals computed, placed in the world.

use super::environment::{EnvError, EnvMap, EnvSource, Environment};
use super::mesh::{Mesh, MeshRepairs};
use super::normals::compute_vertex_normals;
use super::smoothing::{Smoothing, smooth};
use super::texture::{MaterialTextures, TexelSpace, TextureError};
use super::{Material, Model, Shape, obj, shapes};
use crate::geometry::subdivide::divisions;
use crate::lesson::NormalTransform;
use crate::lesson::limits::MAX_PATCHES;
use crate::lesson::limits::MAX_TRIANGLES;
use crate::lesson::settings::RenderMethod;
use crate::lesson::texture::{TextureRef, TextureSource};
use crate::lesson::{KeyPath, Lesson, LessonError, SceneSpec};
use crate::light::Light;
use crate::shading::brdf::Brdf;
use glam::{Affine3A, Vec2, Vec3};
use std::sync::Arc;

/// All objects' triangles in one world-space soup, ready for the vertex stage.
#[derive(Debug, Clone, Default)]
pub struct Geometry {
    /// World positions.
    pub positions: Vec<Vec3>,
    /// Unit world vertex normals.
    pub normals: Vec<Vec3>,
    /// Triangles (indices into the arrays above).
    pub triangles: Vec<[u32; 3]>,
    /// Material index per triangle.
    pub material: Vec<u32>,
    /// Texture coordinates per triangle corner ((0, 0) for a mesh without them); empty when
    /// no material is textured.
    pub uvs: Vec<[Vec2; 3]>,
    /// Unit world face normal per triangle (+y for a degenerate triangle, which the rasterizer skips anyway).
    pub face_normals: Vec<Vec3>,
    /// One entry per object, in lesson order.
    pub objects: Vec<ObjectBounds>,
}

impl Geometry {
    /// The object triangle `t` belongs to.
    pub fn object_of_triangle(&self, t: usize) -> u32 {
        (self.objects.partition_point(|o| o.first_triangle <= t) as u32).saturating_sub(1)
    }

    /// The object vertex `v` belongs to.
    pub fn object_of_vertex(&self, v: usize) -> u32 {
        (self.objects.partition_point(|o| o.first_vertex <= v) as u32).saturating_sub(1)
    }
}

/// Where an object's triangles are and a sphere around them (for culling lights).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectBounds {
    /// Its triangles are `first_triangle..first_triangle + triangles`.
    pub first_triangle: usize,
    /// Triangle count.
    pub triangles: usize,
    /// Its vertices are `first_vertex..first_vertex + vertices`.
    pub first_vertex: usize,
    /// Vertex count.
    pub vertices: usize,
    /// Centre of the bounding sphere (the centre of the bounding box).
    pub centre: Vec3,
    /// Radius of the bounding sphere.
    pub radius: f32,
    /// Material index.
    pub material: u32,
    /// Degenerate triangles and repaired vertex normals found in this object's mesh.
    pub repairs: MeshRepairs,
    /// Convex or flat (sphere, icosphere, cube, plane, or a mesh that passes
    /// [`Mesh::is_convex`], under any affine map): it cannot block light falling on itself
    /// where N·L > 0, so its shadow rays may ignore it.
    pub convex: bool,
}

/// The runtime scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// What the lesson hands over as validated: camera, lights (as the file gives them),
    /// ambient L_glob, `[render]` settings, `[fog]` and `[[probe]]`s.
    pub spec: SceneSpec,
    /// The lights, built from `spec.lights` by the light room, in file order.
    pub lights: Vec<Light>,
    /// Geometry of every object.
    pub geometry: Geometry,
    /// Materials (indexed by `Geometry::material`).
    pub materials: Vec<Material>,
    /// Each material's textures (parallel to `materials`).
    pub textures: Vec<MaterialTextures>,
    /// What mesh repair found.
    pub repairs: MeshRepairs,
    /// The distant light all round, when the lesson has an `[environment]`.
    pub environment: Option<Environment>,
}

/// Why a file the lesson names could not be used.
#[derive(Debug)]
pub enum SceneCause {
    /// An OBJ mesh.
    Obj(obj::ObjError),
    /// A glTF file.
    Gltf(super::gltf::GltfError),
    /// An environment map.
    Environment(EnvError),
    /// A material's texture.
    Texture(TextureError),
    /// A scene-wide check, such as the radiosity patch limit: nothing was loaded.
    Limit,
}

/// A mesh or an environment map that could not be loaded (bad input: exit code 2).
///
/// It prints as a lesson error at the object's `path`, naming the OBJ file as the lesson
/// wrote it and the OBJ line when there is one:
/// `lesson.toml:7:8: `object.0.path`: bad.obj:2: `v 1 0 zero`: ...` plus a hint.
#[derive(Debug, thiserror::Error)]
#[error("{lesson}")]
pub struct SceneError {
    /// The message, located in the lesson file (or the `--set` that chose the mesh).
    pub lesson: Box<LessonError>,
    /// What the loader found.
    pub cause: Box<SceneCause>,
}

impl SceneError {
    /// The error for object `index` of `lesson`, whose OBJ file `path` failed to load.
    fn new(lesson: &Lesson, index: usize, path: &std::path::Path, cause: obj::ObjError) -> SceneError {
        // The file as the lesson names it (relative to the lesson's folder), not the full path.
        let shown = crate::lesson::assets::shown(&lesson.path, path);
        let place = match cause.line() {
            Some(line) => format!("{shown}:{line}"),
            None => shown,
        };
        let hint = match &cause {
            obj::ObjError::Read { cause: io, .. } if io.kind() == std::io::ErrorKind::NotFound => {
                "the path is relative to the lesson file's folder".to_string()
            }
            obj::ObjError::BadIndex { .. } => {
                "face indices count from 1 (negative ones back from the latest entry); check the `f` line against the `v`, `vt` and `vn` lines above it".into()
            }
            obj::ObjError::TooLarge { .. } => "simplify the mesh or split it into several objects".into(),
            obj::ObjError::TooBig { .. } | obj::ObjError::OverLimit { .. } => {
                "simplify (decimate) the mesh, or use fewer or coarser objects (docs/lesson-format.md, Limits)".into()
            }
            obj::ObjError::NotUtf8 { .. } => "OBJ files are UTF-8 (or ASCII) text".into(),
            _ => "check the file is a Wavefront OBJ with `v` and `f` lines (e.g. `v 0 0 0` … `f 1 2 3`)".into(),
        };
        let key = KeyPath::default().key("object").index(index).key("path");
        let lesson = crate::lesson::error_at(lesson, &key, format!("{place}: {}", cause.what()), Some(hint));
        SceneError { lesson: Box::new(lesson), cause: Box::new(SceneCause::Obj(cause)) }
    }

    /// The error for object `index` of `lesson`, whose glTF file failed to load: the file
    /// as the lesson names it and the JSON path in it.
    fn gltf(lesson: &Lesson, index: usize, cause: super::gltf::GltfError) -> SceneError {
        use super::gltf::GltfErrorKind as K;
        let shown = crate::lesson::assets::shown(&lesson.path, &cause.file);
        let at = if cause.at.is_empty() { String::new() } else { format!("{}: ", cause.at) };
        let hint = match cause.kind {
            K::Missing => "the path is relative to the lesson file's folder; a .gltf's buffers and images must be beside it",
            K::Invalid => "export it again (Blender: File → Export → glTF 2.0), or check it with the Khronos glTF validator",
            K::Outside => "a glTF file may read only files in its own folder (or data: URIs); copy them beside it",
            K::Limit => "simplify (decimate) the mesh, or use fewer objects (docs/lesson-format.md, Limits)",
            K::Selection => "name a mesh node of the file (`shadelab import FILE` lists them in the lesson it writes)",
        };
        let key = KeyPath::default().key("object").index(index).key(if cause.kind == K::Selection { "node" } else { "path" });
        let key = if cause.kind == K::Selection && !matches!(&lesson.objects[index].shape, Shape::Mesh { part, .. } if part.node.is_some())
        {
            KeyPath::default().key("object").index(index).key("path")
        } else {
            key
        };
        let message = format!("{shown}: {at}{}", cause.what);
        let lesson = crate::lesson::error_at(lesson, &key, message, Some(hint.into()));
        SceneError { lesson: Box::new(lesson), cause: Box::new(SceneCause::Gltf(cause)) }
    }

    /// The error for the environment map `written` (as the lesson wrote it, at `key` under
    /// `[environment]`) that failed to load.
    fn environment(lesson: &Lesson, key: KeyPath, written: &str, cause: EnvError) -> SceneError {
        let mut full = KeyPath::default().key("environment");
        full.0.extend(key.0);
        let key = full;
        let hint = if matches!(lesson.environment.as_ref().map(|e| &e.source), Some(EnvSource::LatLong { .. })) {
            "give a Radiance .hdr, OpenEXR .exr, PNG or JPEG latitude-longitude map, 2:1 (e.g. 1024×512)"
        } else {
            "give Radiance .hdr, OpenEXR .exr, PNG or JPEG cube faces: six square images of one size, or one 4:3 horizontal cross"
        }
        .to_string();
        let lesson = crate::lesson::error_at(lesson, &key, format!("{written}: {}", cause.message), Some(hint));
        SceneError { lesson: Box::new(lesson), cause: Box::new(SceneCause::Environment(cause)) }
    }
}

/// The textures of every material, each file decoded once per run and space.
fn textures(lesson: &Lesson) -> Result<Vec<MaterialTextures>, SceneError> {
    let load = |m: usize, r: &Option<TextureRef>, space: TexelSpace| -> Result<_, SceneError> {
        let Some(r) = r else { return Ok(None) };
        super::texture::resolve(&r.source, space).map(Some).map_err(|cause| {
            let mut key = KeyPath::default().key("material").key(&lesson.materials[m].name).key(r.key);
            let written = match &r.source {
                TextureSource::File { written, .. } => written.clone(),
                TextureSource::Checker { .. } => "checker".into(),
            };
            if r.key != "normal_map" && r.key != "occlusion_map" {
                key = key.key("texture");
            }
            let hint = "give a PNG, JPEG, OpenEXR or Radiance .hdr image, relative to the lesson's folder".to_string();
            let e = crate::lesson::error_at(lesson, &key, format!("{written}: {}", cause.message), Some(hint));
            SceneError { lesson: Box::new(e), cause: Box::new(SceneCause::Texture(cause)) }
        })
    };
    lesson
        .material_maps
        .iter()
        .enumerate()
        .map(|(m, maps)| {
            Ok(MaterialTextures {
                albedo: load(m, &maps.albedo, TexelSpace::Srgb)?,
                roughness: load(m, &maps.roughness, TexelSpace::Linear)?,
                metallic: load(m, &maps.metallic, TexelSpace::Linear)?,
                normal: load(m, &maps.normal, TexelSpace::Linear)?,
                occlusion: load(m, &maps.occlusion, TexelSpace::Linear)?,
                ambient_follows_albedo: maps.ambient_follows_albedo,
            })
        })
        .collect()
}

/// The environment of a lesson: its map decoded (once per file, see [`EnvMap::load_cached`])
/// or its gradient baked.
fn environment(lesson: &Lesson) -> Result<Option<Environment>, SceneError> {
    let Some(spec) = &lesson.environment else { return Ok(None) };
    let map = match &spec.source {
        EnvSource::LatLong { path, written } => {
            EnvMap::load_cached(path).map_err(|e| SceneError::environment(lesson, KeyPath::default().key("map"), written, e))?
        }
        EnvSource::CubeFaces { paths, written } => super::cube::load_faces(paths).map_err(|(k, e)| {
            SceneError::environment(lesson, KeyPath::default().key("faces").index(k), &written[k.min(written.len() - 1)], e)
        })?,
        EnvSource::CubeCross { path, written } => {
            super::cube::load_cross(path).map_err(|e| SceneError::environment(lesson, KeyPath::default().key("cross"), written, e))?
        }
        EnvSource::MirrorBall { path, written } => {
            super::mirror_ball::load(path).map_err(|e| SceneError::environment(lesson, KeyPath::default().key("map"), written, e))?
        }
        EnvSource::Gradient { zenith, horizon, ground } => {
            static BAKED: std::sync::Mutex<Vec<([Vec3; 3], Arc<EnvMap>)>> = std::sync::Mutex::new(Vec::new());
            let key = [*zenith, *horizon, *ground];
            let mut baked = BAKED.lock().unwrap_or_else(|e| e.into_inner());
            match baked.iter().find(|(k, _)| *k == key) {
                Some((_, m)) => m.clone(),
                None => {
                    let m = Arc::new(EnvMap::gradient(*zenith, *horizon, *ground));
                    // A few skies per run at most; keep the last eight.
                    if baked.len() >= 8 {
                        baked.remove(0);
                    }
                    baked.push((key, m.clone()));
                    m
                }
            }
        }
    };
    Ok(Some(Environment::new(map, spec.scale(), spec.rotate_deg, spec.background)))
}

/// Builds the scene of a validated lesson.
///
/// # Errors
/// [`SceneError`] when an OBJ file cannot be read or parsed, or an environment map decoded.
pub fn build(lesson: &Lesson) -> Result<Scene, SceneError> {
    let mut geometry = Geometry::default();
    let mut repairs = MeshRepairs::default();
    // Validation bounded the analytic shapes; each mesh is counted as it is read.
    let mut total: u64 = lesson.objects.iter().filter_map(|o| o.shape.triangles()).sum();
    let textured = lesson.material_maps.iter().any(|m| !m.is_empty());
    for (index, o) in lesson.objects.iter().enumerate() {
        let mut mine = MeshRepairs::default();
        let mut groups = None;
        let mut mesh = match &o.shape {
            Shape::UvSphere { segments, rings } => shapes::uv_sphere(*segments, *rings),
            Shape::Icosphere { subdivisions } => shapes::icosphere(*subdivisions),
            Shape::Plane => shapes::plane(),
            Shape::Cube => shapes::cube(),
            Shape::Torus { major_radius, minor_radius, segments, sides } => shapes::torus(*major_radius, *minor_radius, *segments, *sides),
            Shape::Mesh { path, part } if super::gltf::is_gltf(path) => {
                let file = super::gltf::open(path).map_err(|cause| SceneError::gltf(lesson, index, cause))?;
                let loaded = file.load(part, total).map_err(|cause| SceneError::gltf(lesson, index, cause))?;
                total += loaded.mesh.triangles.len() as u64;
                let mut mesh = loaded.mesh;
                if loaded.had_normals && o.crease_deg.is_none() {
                    // The file's normals, zero or broken ones repaired as an OBJ's are.
                    mine = super::normals::repair_vertex_normals(&mut mesh);
                } else {
                    mesh.normals.clear();
                }
                mesh
            }
            Shape::Mesh { path, .. } => {
                let loaded = obj::load_obj(path).map_err(|cause| SceneError::new(lesson, index, path, cause))?;
                let mut mesh = loaded.mesh;
                total += mesh.triangles.len() as u64;
                if total > MAX_TRIANGLES {
                    let cause = obj::ObjError::OverLimit { path: path.clone(), triangles: mesh.triangles.len(), total };
                    return Err(SceneError::new(lesson, index, path, cause));
                }
                groups = loaded.groups;
                if loaded.had_normals && o.crease_deg.is_none() {
                    mine = loaded.repairs;
                } else {
                    // Recompute with the lesson's weighting (the loader used the plain average).
                    mesh.normals.clear();
                }
                mesh
            }
        };
        if o.crease_deg.is_some() || (groups.is_some() && mesh.normals.is_empty()) {
            // A crease angle replaces any normals (the shapes' and a file's `vn`); smoothing
            // groups replace computed ones only.
            let how = Smoothing { crease_deg: o.crease_deg, groups: groups.as_deref() };
            mine = smooth(&mut mesh, lesson.scene.settings.normals, how);
        } else if mesh.normals.len() != mesh.positions.len() {
            mine = compute_vertex_normals(&mut mesh, lesson.scene.settings.normals);
        }
        repairs.degenerate_triangles += mine.degenerate_triangles;
        repairs.repaired_normals += mine.repaired_normals;
        if !textured {
            // Untextured scenes keep no uvs (24 bytes a triangle, twice, on a million-triangle mesh).
            mesh.uvs = Vec::new();
        } else if mesh.uvs.len() != mesh.triangles.len() {
            // An OBJ without `vt`: (0, 0) at every corner.
            mesh.uvs = vec![[Vec2::ZERO; 3]; mesh.triangles.len()];
        }
        let convex = match o.shape {
            Shape::UvSphere { .. } | Shape::Icosphere { .. } | Shape::Plane | Shape::Cube => true,
            Shape::Torus { .. } => false,
            // A file's mesh is tested: lesson 35's cylinder, its smooth normals over 15° facets,
            // otherwise shadows its own side where a facet turns from the fill light.
            Shape::Mesh { .. } => mesh.is_convex(),
        };
        append(&mut geometry, &mesh, (o.transform, lesson.scene.settings.normal_transform), o.material as u32, mine, convex);
    }
    let environment = environment(lesson)?;
    let textures = textures(lesson)?;
    // A textured material's constants are its textures' means: what Gouraud vertices, flat
    // faces and the environment's per-material terms read; samples read the textures.
    let materials = lesson
        .materials
        .iter()
        .zip(&textures)
        .map(|(m, t)| if t.any() { Material { name: m.name.clone(), ..t.apply(m, t.means()) } } else { m.clone() })
        .collect();
    if lesson.scene.settings.method == RenderMethod::Radiosity {
        radiosity_limits(lesson, &geometry)?;
    }
    if lesson.scene.settings.method == RenderMethod::Path {
        path_limits(lesson, &geometry)?;
    } else {
        rough_glass_limit(lesson, &geometry)?;
    }
    let lights = lesson.scene.lights.iter().map(Light::from_spec).collect();
    Ok(Scene { spec: lesson.scene.clone(), lights, environment, geometry, materials, textures, repairs })
}

/// The checks of `method = "radiosity"` that need the meshes, before any work: the patch
/// count against [`MAX_PATCHES`], and at least one emitting surface.
fn radiosity_limits(lesson: &Lesson, g: &Geometry) -> Result<(), SceneError> {
    let size = lesson.scene.settings.radiosity.patch_size;
    let patches: u64 = g
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| g.positions[i as usize]);
            (divisions(a, b, c, size) as u64).pow(2)
        })
        .sum();
    let render = KeyPath::default().key("render");
    let at = |key: &str, message: String, hint: &str| SceneError {
        lesson: Box::new(crate::lesson::error_at(lesson, &render.key(key), message, Some(hint.into()))),
        cause: Box::new(SceneCause::Limit),
    };
    if patches > MAX_PATCHES as u64 {
        return Err(at(
            "patch_size",
            format!("patch_size = {size} makes {patches} patches; the limit is {MAX_PATCHES}"),
            "raise patch_size (the patch count grows as 1/patch_size²), or give radiosity fewer or smaller objects",
        ));
    }
    let emits = g.material.iter().any(|&m| lesson.materials[m as usize].emission != Vec3::ZERO);
    if !emits {
        // An error, not a black image: with no emitter every radiosity is exactly 0, which is
        // never what a lesson means; the usual slip is a [[light]], which radiosity does not use.
        return Err(at(
            "method",
            "method = \"radiosity\" needs a surface with `emission`, and no object's material has any".into(),
            "radiosity is lit by emitting surfaces only (its [[light]]s are not used): give a material `emission = 17` and an object that uses it",
        ));
    }
    Ok(())
}

/// The checks of `method = "path"`, before any work: every drawn material has a BRDF the
/// path tracer can sample (a physically based model, a mirror or glass), and the fog, if
/// any, is a participating medium (the classic blends are not light transport).
fn path_limits(lesson: &Lesson, g: &Geometry) -> Result<(), SceneError> {
    let limit = |key: KeyPath, message: String, hint: String| SceneError {
        lesson: Box::new(crate::lesson::error_at(lesson, &key, message, Some(hint))),
        cause: Box::new(SceneCause::Limit),
    };
    let mut drawn: Vec<u32> = g.material.clone();
    drawn.sort_unstable();
    drawn.dedup();
    for m in drawn {
        let material = &lesson.materials[m as usize];
        if let Some(c) = material.classic() {
            return Err(limit(
                KeyPath::default().key("material").key(&material.name).key("model"),
                format!(
                    "method = \"path\" traces light as a BRDF scatters it, and material `{}` uses the classic `{}` model, which is not a BRDF (no 1/π, no energy bound)",
                    material.name,
                    c.model.name()
                ),
                "use a physically based model: `diffuse` for lambert, `normalized_phong` or `normalized_blinn_phong` for phong and blinn_phong (lesson 20 converts K_shi and K_spec), or render it with method = \"raster\"".into(),
            ));
        }
    }
    if let Some(fog) = &lesson.scene.fog
        && fog.medium().is_none()
    {
        return Err(limit(
            KeyPath::default().key("fog").key("kind"),
            format!(
                "method = \"path\" traces light through a participating medium, and `[fog] kind = \"{}\"` is a classic blend",
                fog.kind.name()
            ),
            "use kind = \"medium\" with sigma_s and sigma_a, or render the blend with method = \"raster\"".into(),
        ));
    }
    Ok(())
}

/// Rough glass and the principled material's transmission are drawn by the path tracer only:
/// the rasterizer's glass pass traces one reflected and one refracted ray, which a rough
/// interface would spread over a lobe, and its shading sees one side of a surface.
fn rough_glass_limit(lesson: &Lesson, g: &Geometry) -> Result<(), SceneError> {
    let mut drawn: Vec<u32> = g.material.clone();
    drawn.sort_unstable();
    drawn.dedup();
    let renderer = lesson.scene.settings.method.name();
    let found = drawn.iter().map(|&m| &lesson.materials[m as usize]).find_map(|m| match &m.model {
        Model::Glass(g) if g.roughness > 0.0 => Some((
            m,
            "roughness",
            format!("material `{}` is rough glass, which only method = \"path\" draws (the {renderer} renderer traces one reflected and one refracted ray)", m.name),
            "set `[render] method = \"path\"`, or `roughness = 0` for smooth glass",
        )),
        Model::Physical(Brdf::Principled(p)) if p.transmits() => Some((
            m,
            if p.specular_transmission > 0.0 { "specular_transmission" } else { "diffuse_transmission" },
            format!("material `{}` lets light through (principled transmission), which only method = \"path\" draws (the {renderer} renderer shades one side of a surface)", m.name),
            "set `[render] method = \"path\"`, or remove `specular_transmission` and `diffuse_transmission`",
        )),
        _ => None,
    });
    let Some((material, key, message, hint)) = found else {
        return Ok(());
    };
    let key = KeyPath::default().key("material").key(&material.name).key(key);
    Err(SceneError {
        lesson: Box::new(crate::lesson::error_at(lesson, &key, message, Some(hint.into()))),
        cause: Box::new(SceneCause::Limit),
    })
}

/// Appends `mesh` placed in the world by `m`, its normals carried as `how` says.
fn append(g: &mut Geometry, mesh: &Mesh, (m, how): (Affine3A, NormalTransform), material: u32, repairs: MeshRepairs, convex: bool) {
    let base = g.positions.len() as u32;
    let mesh = mesh.transformed_with(m, how);
    let (lo, hi) = mesh.positions.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let centre = if mesh.positions.is_empty() { Vec3::ZERO } else { (lo + hi) * 0.5 };
    let radius = mesh.positions.iter().map(|p| p.distance(centre)).fold(0.0, f32::max);
    g.objects.push(ObjectBounds {
        first_triangle: g.triangles.len(),
        triangles: mesh.triangles.len(),
        first_vertex: base as usize,
        vertices: mesh.positions.len(),
        centre,
        radius,
        material,
        repairs,
        convex,
    });
    g.positions.extend_from_slice(&mesh.positions);
    g.normals.extend_from_slice(&mesh.normals);
    // Empty when the scene is untextured, else one entry per triangle (see `build`).
    g.uvs.extend_from_slice(&mesh.uvs);
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| g.positions[(base + i) as usize]);
        g.triangles.push(t.map(|i| base + i));
        g.material.push(material);
        g.face_normals.push((b - a).cross(c - a).normalize_or(Vec3::Y));
    }
}
