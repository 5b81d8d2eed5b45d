//! Stage two: serde mirror → validated [`Lesson`], every error tied to a key path.
//!
//! One `impl Validator` per concept: this file holds the entry points and the serde
//! error plumbing; the sections, figures, materials and scalar checks have their own files.

mod environment;
mod figure;
mod hints;
mod material;
mod numbers;
mod scene;

pub(crate) use hints::suggest;

use super::Lesson;
use super::error::{LessonError, Location};
use super::figure::FigureSpec;
use super::overrides::Override;
use super::path::{KeyPath, Segment};
use super::raw::RawLesson;
use super::spans::{self, Target};
use glam::Vec3;
use hints::{duplicate_key, key_help, last_key, material_names, toml_hint, variant_keys};
use std::path::Path;

/// Largest image side in pixels.
pub const MAX_SIDE: i64 = 16384;
/// Largest image area in pixels (about 8K × 5K).
pub const MAX_PIXELS: i64 = 40_000_000;
/// Largest supersampling factor per pixel side.
pub const MAX_AA: i64 = 16;
/// Most samples one area, line or sky light may take per shaded point.
pub const MAX_LIGHT_SAMPLES: i64 = 4096;
/// Largest shadow-map side in texels (a point light has six such faces).
pub const MAX_SHADOW_MAP: i64 = 8192;

type R<T> = Result<T, LessonError>;

/// Carries the text (for spans) and the overrides (to blame `--set` rather than the file).
pub(super) struct Validator<'a> {
    text: &'a str,
    file: &'a Path,
    sets: &'a [Override],
    /// Whether `[[figure]]` tables are read (not for a figure's cells, see [`Validator::cell`]).
    figures: bool,
}

impl<'a> Validator<'a> {
    pub(super) fn new(text: &'a str, file: &'a Path, sets: &'a [Override]) -> Self {
        Validator { text, file, sets, figures: true }
    }

    /// A validator for one cell of a figure (or a rung of a ladder): the lesson with the
    /// cell's overrides, without its `[[figure]]` tables. They were checked with the lesson
    /// itself, and a cell may replace what other figures name (a grid that swaps every
    /// material leaves a lobe figure's materials undefined in that cell).
    pub(super) fn cell(text: &'a str, file: &'a Path, sets: &'a [Override]) -> Self {
        Validator { text, file, sets, figures: false }
    }

    pub(super) fn run(&self) -> R<Lesson> {
        let mut table: toml::Table = toml::from_str(self.text).map_err(|e| {
            let span = e.span().unwrap_or(0..0);
            let (line, col) = spans::line_col(self.text, span.start);
            let (message, hint) = match e.message().trim() {
                m if m.starts_with("duplicate key") => duplicate_key(self.text, span),
                m => (format!("not valid TOML: {m}"), toml_hint(m).to_string()),
            };
            LessonError { file: self.file.to_path_buf(), location: Location::File { line, col }, key: None, message, hint: Some(hint) }
        })?;
        let file_materials: Vec<String> = material_names(&table);
        for set in self.sets {
            if let Err(e) = set.apply(&mut table) {
                // A key the lesson lacks may be one the schema does not know either
                // (`lighht.0.intensity`): then say so, with the schema's did-you-mean.
                if let Some(absent) = &e.absent
                    && let Some(unknown) = self.unknown_key(&table, absent)
                {
                    return Err(unknown);
                }
                return Err(LessonError {
                    file: self.file.to_path_buf(),
                    location: Location::Flag(format!("--set {}", set.arg)),
                    key: Some(set.path.to_string()),
                    message: e.message,
                    hint: e.hint,
                });
            }
        }
        self.created_materials(&table, &file_materials)?;
        let raw: RawLesson =
            serde_path_to_error::deserialize(toml::Value::Table(table.clone())).map_err(|e| self.serde_error(e, &table))?;
        self.lesson(raw)
    }

    /// A `--set` (or figure value) that made up a material without a `model` most likely
    /// misspelt a name: `--set material.plastik.shininess=3` on a lesson with `plastic`.
    fn created_materials(&self, table: &toml::Table, file_materials: &[String]) -> R<()> {
        let Some(materials) = table.get("material").and_then(toml::Value::as_table) else { return Ok(()) };
        for (name, m) in materials {
            if file_materials.contains(name) || m.as_table().is_none_or(|t| t.contains_key("model")) {
                continue;
            }
            let key = KeyPath::default().key("material").key(name);
            let Some(set) = self.sets.iter().find(|s| s.path.starts_with(&key)) else { continue };
            let names: Vec<&str> = file_materials.iter().map(String::as_str).collect();
            let define = format!("to define a new material, also set its model, e.g. --set {}=phong", key.key("model"));
            let hint = match suggest(name, &names) {
                Some(s) => format!("did you mean `{s}`? ({define})"),
                None if names.is_empty() => format!("the lesson defines no materials; {define}"),
                None => format!("materials: {}; {define}", names.join(", ")),
            };
            return Err(LessonError {
                file: self.file.to_path_buf(),
                location: Location::Flag(format!("--set {}", set.arg)),
                key: Some(key.to_string()),
                message: format!("the lesson has no material `{name}`"),
                hint: Some(hint),
            });
        }
        Ok(())
    }

    /// The unknown-key error for `absent` if the schema does not allow a key there.
    fn unknown_key(&self, table: &toml::Table, absent: &KeyPath) -> Option<LessonError> {
        let mut probe = table.clone();
        let placeholder = Override { arg: String::new(), path: absent.clone(), value: toml::Value::Table(toml::Table::new()) };
        placeholder.apply(&mut probe).ok()?;
        let e = serde_path_to_error::deserialize::<_, RawLesson>(toml::Value::Table(probe.clone())).err()?;
        let e = self.serde_error(e, &probe);
        (e.key == Some(absent.to_string()) && e.message.starts_with("unknown key")).then_some(e)
    }

    /// An error about `path`, located in the file or in the `--set` that wrote it.
    ///
    /// A `--set` is blamed when it wrote `path` or one of its ancestors, or when it
    /// created the part of `path` that the file does not have (`--set material.new.diffuse=1`
    /// is blamed for the missing `material.new.model`; a missing `camera.position` is the
    /// file's fault even if `--set camera.fov_deg=30` touched `camera`).
    pub(super) fn err(&self, path: &KeyPath, target: Target, message: impl Into<String>, hint: Option<String>) -> LessonError {
        let in_file = spans::depth(self.text, path);
        let created = (in_file < path.0.len()).then(|| KeyPath(path.0[..=in_file].to_vec()));
        let blamed = self.sets.iter().rev().find(|s| path.starts_with(&s.path) || created.as_ref().is_some_and(|c| s.path.starts_with(c)));
        let location = match blamed {
            Some(set) => Location::Flag(format!("--set {}", set.arg)),
            None => {
                let span = spans::find(self.text, path, target);
                let (line, col) = spans::line_col(self.text, span.start);
                Location::File { line, col }
            }
        };
        let key = (!path.0.is_empty()).then(|| path.to_string());
        LessonError { file: self.file.to_path_buf(), location, key, message: message.into(), hint }
    }

    /// The lesson error for a serde error; `table` is what was deserialized (it tells
    /// which keys the entry's `model`, `kind` or `shape` reads).
    fn serde_error(&self, e: serde_path_to_error::Error<toml::de::Error>, table: &toml::Table) -> LessonError {
        let mut path = KeyPath::default();
        for seg in e.path().iter() {
            match seg {
                serde_path_to_error::Segment::Seq { index } => path.0.push(Segment::Index(*index)),
                serde_path_to_error::Segment::Map { key } => path.0.push(Segment::Key(key.clone())),
                serde_path_to_error::Segment::Enum { .. } | serde_path_to_error::Segment::Unknown => {}
            }
        }
        let raw = e.inner().message().trim().to_string();
        let ticked: Vec<&str> = raw.split('`').skip(1).step_by(2).collect();
        if raw.starts_with("unknown field") {
            let field = ticked.first().copied().unwrap_or("");
            if path.0.last() != Some(&Segment::Key(field.to_string())) {
                path = path.key(field);
            }
            let all = &ticked[1.min(ticked.len())..];
            // Only the keys this entry's model, kind or shape reads; did-you-mean still
            // looks at every key, and says when the match is not read here.
            let (variant, allowed) = match variant_keys(table, &path) {
                Some((variant, keys)) => (Some(variant), keys),
                None => (None, all.to_vec()),
            };
            let hint = match (suggest(field, &allowed), suggest(field, all), variant) {
                (Some(s), _, _) => format!("did you mean `{s}`? Keys allowed here: {}", allowed.join(", ")),
                (None, Some(s), Some(v)) => {
                    format!("did you mean `{s}`? It is not read by {v}, though. Keys allowed here: {}", allowed.join(", "))
                }
                _ => format!("keys allowed here: {}", allowed.join(", ")),
            };
            return self.err(&path, Target::Key, format!("unknown key `{field}`"), Some(hint));
        }
        if raw.starts_with("missing field") {
            let field = ticked.first().copied().unwrap_or("");
            // Only `[camera]` is required at the top level; below it, keys such as `model`.
            let hint = if path.0.is_empty() {
                format!("add a `[{field}]` table (see docs/lesson-format.md)")
            } else {
                format!("add `{field} = ...` to `{path}` (see docs/lesson-format.md)")
            };
            // The key path names the missing key; the location is the table it belongs in.
            return self.err(&path.key(field), Target::Key, format!("missing required key `{field}`"), Some(hint));
        }
        // A colour-or-scalar that is neither; `scale` is the one such key that is not a colour.
        let either = match path.0.last() {
            Some(Segment::Key(k)) if k == "scale" => "expected a number or [x, y, z]",
            _ => "expected a number or [r, g, b]",
        };
        let mut message = raw
            .replace("data did not match any variant of untagged enum RawColor", either)
            .replace("expected f64", "expected a number")
            .replace("expected i64", "expected an integer")
            .replace("expected an array of length 3", "expected [x, y, z]")
            .replace("expected an array of length 2", "expected [width, height]")
            // serde's words for TOML's tables and arrays.
            .replace("invalid type: map", "invalid type: table")
            .replace("expected a map", "expected a table")
            .replace("invalid type: sequence", "invalid type: array")
            .replace("expected a sequence", "expected an array");
        // `expected struct RawMaterial` names an internal type: say `a table`.
        if let Some(at) = message.find("expected struct Raw") {
            let end = message[at + "expected struct ".len()..]
                .find(|c: char| !c.is_alphanumeric())
                .map_or(message.len(), |i| at + "expected struct ".len() + i);
            message.replace_range(at..end, "expected a table");
        }
        let quoted_number = message.contains("invalid type: string") && message.contains("expected a number");
        let hint = match (key_help(&path), quoted_number) {
            (Some(h), true) => format!("give a number (no quotes); {h}"),
            (Some(h), false) => h,
            (None, true) => "give a number (no quotes), e.g. 0.5".to_string(),
            (None, false) => format!("see the `{}` row in docs/lesson-format.md", last_key(&path).unwrap_or("key")),
        };
        self.err(&path, Target::Value, message, Some(hint))
    }

    // ---- sections ----------------------------------------------------------------------

    fn lesson(&self, raw: RawLesson) -> R<Lesson> {
        let root = KeyPath::default();
        let camera = self.camera(&root.key("camera"), &raw.camera)?;
        let mut materials = Vec::with_capacity(raw.material.len());
        for (name, m) in &raw.material {
            materials.push(self.material(&root.key("material").key(name), name, m)?);
        }
        let objects =
            raw.object.iter().enumerate().map(|(i, o)| self.object(&root.key("object").index(i), o, &materials)).collect::<R<Vec<_>>>()?;
        let lights = raw.light.iter().enumerate().map(|(i, l)| self.light(&root.key("light").index(i), l)).collect::<R<Vec<_>>>()?;
        let ambient = match raw.scene.ambient {
            Some(c) => self.color(&root.key("scene").key("ambient"), c, 0.0, 1e6)?,
            None => Vec3::ZERO,
        };
        let render = self.render(&root.key("render"), &raw.render)?;
        let environment = match &raw.environment {
            Some(e) => Some(self.environment(&root.key("environment"), e)?),
            None => None,
        };
        let mut figures: Vec<FigureSpec> = Vec::new();
        for (i, f) in raw.figure.iter().enumerate().filter(|_| self.figures) {
            let spec = self.figure(&root.key("figure").index(i), f, &figures, &raw, &materials)?;
            figures.push(spec);
        }
        let samples = camera.width as i64 * camera.height as i64 * (render.aa as i64).pow(2);
        if samples > MAX_PIXELS * 4 {
            return Err(self.err(
                &root.key("render").key("aa"),
                Target::Value,
                format!(
                    "{}×{} pixels with aa {} is {samples} samples, more than the limit {}",
                    camera.width,
                    camera.height,
                    render.aa,
                    MAX_PIXELS * 4
                ),
                Some("lower `render.aa` or `camera.size`".into()),
            ));
        }
        let stem = self.file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        Ok(Lesson {
            path: self.file.to_path_buf(),
            title: raw.lesson.title.unwrap_or(stem),
            summary: raw.lesson.summary.unwrap_or_default(),
            notes: raw.lesson.notes.unwrap_or_default(),
            camera,
            objects,
            materials,
            lights,
            ambient,
            render,
            environment,
            figures,
            source: self.text.to_string(),
            overrides: self.sets.to_vec(),
        })
    }
}
