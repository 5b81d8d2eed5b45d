//! The lesson file format: TOML → serde mirror ([`raw`]) → validated [`Lesson`].
//!
//! Parsing happens in two stages (STYLE.md habit 1): serde structs that deny unknown
//! keys, then validation into domain types with key paths, so every message names
//! `file:line:col`, the key, the allowed range and a hint. `--set KEY=VALUE`
//! overrides are applied between the two stages and validated exactly like the file.

pub mod assets;
pub mod color;
pub mod environment;
pub mod error;
pub mod figure;
pub mod fog;
pub mod glossary;
pub mod i18n;
mod i18n_explain;
pub mod kinds;
pub mod light;
pub mod limits;
pub mod overrides;
pub mod path;
pub mod probe;
pub mod raw;
pub mod settings;
pub mod shape;
pub mod spans;
pub mod texture;
mod validate;

pub use error::{LessonError, Location, Others};
pub use figure::{Axis, FigureBody, FigureKind, FigureSpec, LadderKind, Normals};
pub use fog::{Fog, FogDistance, FogKind, Medium};
pub use kinds::{FresnelKind, LightType, ModelKind, ShapeKind};
pub use overrides::Override;
pub use path::KeyPath;
pub use settings::{Cull, Interpolation, InterpolationSpace, NormalTransform, NormalWeighting, RenderSettings, TextureFilter, Tonemap};
pub use shape::Shape;
pub(crate) use validate::suggest;

use crate::geometry::Camera;
use crate::shading::material::Material;
use glam::{Affine3A, Vec3};
use std::path::{Path, PathBuf};

/// A validated lesson: everything the scene builder needs, nothing unchecked.
#[derive(Debug, Clone)]
pub struct Lesson {
    /// The lesson file (mesh paths are resolved relative to it).
    pub path: PathBuf,
    /// `[lesson] title` (the file stem when absent).
    pub title: String,
    /// `[lesson] summary`.
    pub summary: String,
    /// `[lesson] notes`: what to look at, printed after a render.
    pub notes: String,
    /// `[lesson] lang` (or `--lang`): the language of built-in labels.
    pub lang: i18n::Lang,
    /// What the scene takes as it is: camera, lights, ambient, `[render]`, `[fog]`, probes.
    pub scene: SceneSpec,
    /// Objects in file order.
    pub objects: Vec<ObjectSpec>,
    /// Materials, sorted by name; objects refer to them by index.
    pub materials: Vec<Material>,
    /// Each material's textured parameters (parallel to `materials`).
    pub material_maps: Vec<texture::MaterialMaps>,
    /// `[environment]`, when the lesson has one.
    pub environment: Option<environment::EnvironmentSpec>,
    /// `[[figure]]` specifications, in file order.
    pub figures: Vec<FigureSpec>,
    /// The lesson text (figure variants re-validate it with their overrides).
    pub source: String,
    /// The `--set` overrides this lesson was loaded with.
    pub overrides: Vec<Override>,
}

/// The part of a lesson the runtime scene keeps as validated, handed over whole
/// (`scene::Scene::spec`): a new scene-wide key is a field here, read where it is used,
/// with no copy in the scene builder.
#[derive(Debug, Clone)]
pub struct SceneSpec {
    /// The camera.
    pub camera: Camera,
    /// Lights in file order, as the file gives them (the scene builds each `light::Light`).
    pub lights: Vec<light::LightSpec>,
    /// Global ambient L_glob.
    pub ambient: Vec3,
    /// `[render]` settings.
    pub settings: RenderSettings,
    /// `[fog]`, when the lesson has one.
    pub fog: Option<Fog>,
    /// `[[probe]]` reflection probes, in file order.
    pub probes: Vec<probe::ProbeSpec>,
}

/// One `[[object]]`: a shape, where it is, what it is made of.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectSpec {
    /// Geometry.
    pub shape: Shape,
    /// Object → world transform (scale, then rotate x, y, z, then translate).
    pub transform: Affine3A,
    /// Index into [`Lesson::materials`].
    pub material: usize,
    /// Auto-smooth angle in degrees: faces meeting at more than it keep their own normals.
    pub crease_deg: Option<f32>,
}

impl Lesson {
    /// Every file this lesson reads besides itself (OBJ meshes, textures, environment maps and
    /// cube faces), resolved and without repeats, so a watcher knows what it depends on.
    /// Files that only a figure's overrides name are not included.
    pub fn asset_files(&self) -> Vec<PathBuf> {
        let mut out: Vec<PathBuf> = Vec::new();
        let mut push = |p: &Path| {
            if !out.iter().any(|o| o == p) {
                out.push(p.to_path_buf());
            }
        };
        for o in &self.objects {
            if let Shape::Mesh { path, .. } = &o.shape {
                push(path);
                // A .gltf's buffers and images are files of their own.
                for uri in assets::gltf_external_files(path) {
                    push(&uri);
                }
            }
        }
        for maps in &self.material_maps {
            for t in [&maps.albedo, &maps.roughness, &maps.metallic, &maps.normal, &maps.occlusion].into_iter().flatten() {
                if let texture::TextureSource::File { path, .. } = &t.source {
                    push(path);
                }
            }
        }
        if let Some(env) = &self.environment {
            match &env.source {
                environment::EnvSource::LatLong { path, .. }
                | environment::EnvSource::CubeCross { path, .. }
                | environment::EnvSource::MirrorBall { path, .. } => push(path),
                environment::EnvSource::CubeFaces { paths, .. } => paths.iter().for_each(|p| push(p)),
                environment::EnvSource::Gradient { .. } => {}
            }
        }
        out
    }
}

impl Lesson {
    /// The start of a cache key for a result computed from this lesson's scene: everything
    /// a render reads (camera, lights, `[render]`, fog, probes, objects, materials, textures,
    /// environment, each by its exact `Debug` form, floats in their round-trip digits) and
    /// the contents of every file it reads. `None` when a file cannot be read.
    pub fn cache_key(&self, kind: &'static str) -> Option<crate::cache::KeyBuilder> {
        let mut key = crate::cache::KeyBuilder::new(kind);
        let what = format!("{:?}", (&self.scene, &self.objects, &self.materials, &self.material_maps, &self.environment));
        key.part(what.as_bytes());
        for f in self.asset_files() {
            key.file(&f)?;
        }
        Some(key)
    }
}

/// Reads, overrides and validates a lesson file.
///
/// # Errors
/// [`LessonError`] for an unreadable file, bad TOML, unknown keys, wrong types,
/// out-of-range values, unknown materials and missing mesh files.
pub fn load(path: &Path, overrides: &[Override]) -> Result<Lesson, LessonError> {
    let whole = |message: String, hint: &str| LessonError {
        file: path.to_path_buf(),
        location: Location::Whole,
        key: None,
        message,
        hint: Some(hint.into()),
        others: Default::default(),
    };
    let bytes = crate::files::read(path).map_err(|e| {
        whole(
            format!("cannot read the lesson: {}", crate::output::io_reason(&e)),
            "check the path; lessons are TOML files such as lessons/01-first-light.toml",
        )
    })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let (line, col) = spans::line_col(std::str::from_utf8(&e.as_bytes()[..at]).unwrap_or(""), at);
        LessonError {
            location: Location::File { line, col },
            ..whole(format!("not UTF-8 at byte {at}"), "save the lesson as UTF-8 text (TOML files are UTF-8)")
        }
    })?;
    // A byte-order mark is not TOML; editors on some systems write one.
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    parse(text, path, overrides)
}

/// Validates one cell of a figure (or one rung of a cost ladder): `text` with `overrides`,
/// like [`parse`], except that `[[figure]]` tables are not read (the result has no figures).
///
/// # Errors
/// As [`parse`].
pub fn parse_cell(text: &str, path: &Path, overrides: &[Override]) -> Result<Lesson, LessonError> {
    validate::Validator::cell(text, path, overrides).run()
}

/// An error about `key` of a validated lesson, located as the validator locates its own:
/// at the key's value in the file, or in the `--set` that wrote it (used for problems found
/// after validation, such as an OBJ file that does not parse).
pub fn error_at(lesson: &Lesson, key: &KeyPath, message: impl Into<String>, hint: Option<String>) -> LessonError {
    validate::Validator::new(&lesson.source, &lesson.path, &lesson.overrides).err(key, spans::Target::Value, message, hint)
}

/// A value the validator checked against its range or its names: where the live lab's
/// controls take their ranges from, so a slider never offers what validation would refuse.
#[derive(Debug, Clone, PartialEq)]
pub struct Checked {
    /// The key path, as `--set` writes it (`material.plastic.shininess`).
    pub key: String,
    /// Its value and what it may be.
    pub value: CheckedValue,
}

/// A checked value with its allowed range or names.
#[derive(Debug, Clone, PartialEq)]
pub enum CheckedValue {
    /// A number in `lo..=hi` (a whole number when `integer`).
    Number {
        /// As given.
        value: f64,
        /// The least allowed.
        lo: f64,
        /// The most allowed.
        hi: f64,
        /// Whether only whole numbers are allowed.
        integer: bool,
    },
    /// Three numbers, each in `lo..=hi`.
    Vector {
        /// As given.
        value: [f64; 3],
        /// The least allowed.
        lo: f64,
        /// The most allowed.
        hi: f64,
    },
    /// A linear RGB colour, each channel in `lo..=hi` (text colours decoded).
    Colour {
        /// Linear RGB.
        value: [f64; 3],
        /// The least allowed.
        lo: f64,
        /// The most allowed.
        hi: f64,
    },
    /// One of a set of names.
    Choice {
        /// As matched.
        value: String,
        /// Every allowed name.
        names: Vec<String>,
    },
}

/// Validates `text` as [`parse`] does and returns every value it checked against a range or
/// names, in the order checked.
///
/// # Errors
/// As [`parse`].
pub fn checked_values(text: &str, path: &Path, overrides: &[Override]) -> Result<Vec<Checked>, LessonError> {
    let v = validate::Validator::new(text, path, overrides);
    v.run()?;
    Ok(v.checked())
}

/// Validates lesson `text` as if read from `path` (used by [`load`] and by tests).
///
/// # Errors
/// As [`load`], except for reading the file.
pub fn parse(text: &str, path: &Path, overrides: &[Override]) -> Result<Lesson, LessonError> {
    validate::Validator::new(text, path, overrides).run()
}
