//! Stage two: serde mirror → validated [`Lesson`], every error tied to a key path.
//!
//! One `impl Validator` per concept: this file holds the entry points and the serde
//! error plumbing; the sections, figures, materials and scalar checks have their own files.

mod environment;
mod figure;
mod figure_keys;
mod figure_models;
mod fog;
mod hints;
mod material;
mod numbers;
mod probe;
mod scene;
mod text;
mod texture;

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

pub(super) use super::limits::{MAX_AA, MAX_LIGHT_SAMPLES, MAX_PIXELS, MAX_SAMPLES, MAX_SHADOW_MAP, MAX_SIDE, MAX_TRIANGLES};

type R<T> = Result<T, LessonError>;

/// Removes the value at `path` from `table`; false when there is none.
fn remove(table: &mut toml::Table, path: &KeyPath) -> bool {
    let Some((last, parents)) = path.0.split_last() else { return false };
    let mut at: &mut toml::Value = match parents.first() {
        Some(Segment::Key(k)) => match table.get_mut(k) {
            Some(v) => v,
            None => return false,
        },
        Some(Segment::Index(_)) => return false,
        None => {
            return match last {
                Segment::Key(k) => table.remove(k).is_some(),
                Segment::Index(_) => false,
            };
        }
    };
    for seg in &parents[1..] {
        let next = match (seg, at) {
            (Segment::Key(k), toml::Value::Table(t)) => t.get_mut(k),
            (Segment::Index(i), toml::Value::Array(a)) => a.get_mut(*i),
            _ => None,
        };
        match next {
            Some(v) => at = v,
            None => return false,
        }
    }
    match (last, at) {
        (Segment::Key(k), toml::Value::Table(t)) => t.remove(k).is_some(),
        // An element of an array is not removed (that would renumber the rest): stop.
        _ => false,
    }
}

/// The value of `r`, or `None` with its error added to `errors`.
fn keep<T>(errors: &mut Vec<LessonError>, r: R<T>) -> Option<T> {
    r.map_err(|e| errors.push(e)).ok()
}

/// Carries the text (for spans) and the overrides (to blame `--set` rather than the file).
pub(super) struct Validator<'a> {
    text: &'a str,
    file: &'a Path,
    sets: &'a [Override],
    /// Whether `[[figure]]` tables are read (not for a figure's cells, see [`Validator::cell`]).
    figures: bool,
    /// The lesson's language, once `[lesson] lang` is read: it picks `{ en, ja }` texts.
    lang: std::cell::Cell<crate::lesson::i18n::Lang>,
    /// Every value checked against a range or a set of names, in the order checked.
    checked: std::cell::RefCell<Vec<crate::lesson::Checked>>,
}

impl<'a> Validator<'a> {
    pub(super) fn new(text: &'a str, file: &'a Path, sets: &'a [Override]) -> Self {
        Validator { text, file, sets, figures: true, lang: Default::default(), checked: Default::default() }
    }

    /// A validator for one cell of a figure (or a rung of a ladder): the lesson with the
    /// cell's overrides, without its `[[figure]]` tables. They were checked with the lesson
    /// itself, and a cell may replace what other figures name (a grid that swaps every
    /// material leaves a lobe figure's materials undefined in that cell).
    pub(super) fn cell(text: &'a str, file: &'a Path, sets: &'a [Override]) -> Self {
        Validator { text, file, sets, figures: false, lang: Default::default(), checked: Default::default() }
    }

    /// What [`Validator::run`] checked against ranges and names (after it ran).
    pub(super) fn checked(self) -> Vec<crate::lesson::Checked> {
        self.checked.into_inner()
    }

    /// Notes a checked value, unless it is one component of a vector (the vector is noted).
    fn note(&self, path: &KeyPath, value: crate::lesson::CheckedValue) {
        if !matches!(path.0.last(), Some(crate::lesson::path::Segment::Index(_)))
            || matches!(value, crate::lesson::CheckedValue::Vector { .. })
        {
            self.checked.borrow_mut().push(crate::lesson::Checked { key: path.to_string(), value });
        }
    }

    pub(super) fn run(&self) -> R<Lesson> {
        let mut table: toml::Table = toml::from_str(self.text).map_err(|e| {
            let span = e.span().unwrap_or(0..0);
            let (line, col) = spans::line_col(self.text, span.start);
            let (message, hint) = match e.message().trim() {
                m if m.starts_with("duplicate key") => duplicate_key(self.text, span),
                m => (format!("not valid TOML: {m}"), toml_hint(m).to_string()),
            };
            LessonError {
                file: self.file.to_path_buf(),
                location: Location::File { line, col },
                key: None,
                message,
                hint: Some(hint),
                others: Default::default(),
            }
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
                    others: Default::default(),
                });
            }
        }
        self.created_materials(&table, &file_materials)?;
        // Unknown keys and wrong types: each one found is reported, removed and the table
        // read again, so one run lists them all (up to MAX_ERRORS).
        let mut errors = Vec::new();
        let mut removed: Vec<String> = Vec::new();
        let raw = loop {
            match serde_path_to_error::deserialize::<_, RawLesson>(toml::Value::Table(table.clone())) {
                Ok(raw) => break Some(raw),
                Err(e) => {
                    let error = self.serde_error(e, &table);
                    // A key removed for its type is then missing: reported once, not twice.
                    if error.key.as_ref().is_some_and(|k| removed.contains(k)) {
                        break None;
                    }
                    let path = error.key.as_deref().and_then(KeyPath::parse);
                    let missing = error.message.starts_with("missing required key");
                    errors.push(error);
                    match path {
                        Some(path) if !missing && errors.len() < super::limits::MAX_ERRORS && remove(&mut table, &path) => {
                            removed.push(path.to_string());
                        }
                        _ => break None,
                    }
                }
            }
        };
        match raw.map(|raw| self.lesson(raw)) {
            Some(Ok(lesson)) if errors.is_empty() => Ok(lesson),
            Some(Ok(_)) | None => Err(LessonError::combine(errors).expect("an error")),
            Some(Err(e)) => {
                errors.push(e);
                Err(LessonError::combine(errors).expect("an error"))
            }
        }
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
                others: Default::default(),
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
        LessonError { file: self.file.to_path_buf(), location, key, message: message.into(), hint, others: Default::default() }
    }

    /// The file a lesson names at `key` (`object.0.path`; later environment maps, cube
    /// faces, textures), resolved by [`crate::lesson::assets::resolve`]: inside the
    /// lesson's folder tree or an `--allow-dir` folder, symlinks followed, a regular file.
    pub(super) fn asset_path(&self, key: &KeyPath, written: &str) -> R<std::path::PathBuf> {
        super::assets::resolve(self.file, written).map_err(|r| self.err(key, Target::Value, r.message, Some(r.hint)))
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
            _ => "expected a number, [r, g, b], sRGB hex (\"#cc1111\") or a CSS colour name",
        };
        let param = format!("{either}, or a texture table (`{{ texture = \"file.png\" }}`)");
        let mut message = raw
            .replace("data did not match any variant of untagged enum RawColor", either)
            .replace("data did not match any variant of untagged enum RawParam", &param)
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

    /// The analytic shapes' triangles after tessellation, summed in file order, within
    /// [`MAX_TRIANGLES`] (meshes are counted when read, by the scene builder).
    fn triangle_total(&self, root: &KeyPath, objects: &[super::ObjectSpec]) -> R<()> {
        let mut total = 0u64;
        for (i, o) in objects.iter().enumerate() {
            total += o.shape.triangles().unwrap_or(0);
            if total > MAX_TRIANGLES {
                return Err(self.err(
                    &root.key("object").index(i),
                    Target::Key,
                    format!("objects 0 to {i} have {total} triangles after tessellation, more than the limit of {MAX_TRIANGLES}"),
                    Some(
                        "lower `segments`, `rings`, `sides` or `subdivisions`, or use fewer objects (docs/lesson-format.md, Limits)".into(),
                    ),
                ));
            }
        }
        Ok(())
    }

    /// What the lights ask together, within the limits that hold in combination: their
    /// count, their samples per shaded point, and their shadow maps' texels.
    fn light_totals(&self, root: &KeyPath, lights: &[super::light::LightSpec], render: &super::RenderSettings) -> R<()> {
        use super::limits::{MAX_LIGHT_SAMPLES_TOTAL, MAX_LIGHTS, MAX_SHADOW_MAP_TEXELS};
        use super::{LightType, kinds::ShadowMethod};
        let at = |i: usize| root.key("light").index(i);
        if lights.len() > MAX_LIGHTS {
            return Err(self.err(
                &at(MAX_LIGHTS),
                Target::Key,
                format!("{} lights, more than the limit of {MAX_LIGHTS}: every shaded sample asks each light", lights.len()),
                Some("merge lights, or light a large area with one rect, disk or sky light (docs/lesson-format.md, Limits)".into()),
            ));
        }
        let sampled = |l: &super::light::LightSpec| {
            matches!(l.kind, LightType::Rect | LightType::Disk | LightType::Sphere | LightType::Line | LightType::Sky)
        };
        let mut samples = 0i64;
        for (i, l) in lights.iter().enumerate().filter(|(_, l)| sampled(l)) {
            samples += i64::from(l.samples);
            if samples > MAX_LIGHT_SAMPLES_TOTAL {
                return Err(self.err(
                    &at(i).key("samples"),
                    Target::Value,
                    format!(
                        "lights 0 to {i} take {samples} samples a shaded point together, more than the limit of {MAX_LIGHT_SAMPLES_TOTAL}"
                    ),
                    Some("lower the lights' `samples` (the sampler ladder shows 64 are often enough), or use fewer sampled lights".into()),
                ));
            }
        }
        // A point light's map is a cube; a spot's is one face up to 80° of cone, a cube past it.
        let side = u64::from(render.shadow_map.size);
        let mut texels = 0u64;
        let mut faces = 0u64;
        for (i, l) in lights.iter().enumerate() {
            if l.shadows.unwrap_or(render.shadows) != ShadowMethod::Map {
                continue;
            }
            let n = match l.kind {
                LightType::Point => 6,
                LightType::Spot if l.cos_cutoff < 80f32.to_radians().cos() => 6,
                LightType::Directional | LightType::Spot => 1,
                _ => 0,
            };
            faces += n;
            texels += n * side * side;
            if texels > MAX_SHADOW_MAP_TEXELS {
                return Err(self.err(
                    &at(i),
                    Target::Key,
                    format!(
                        "the shadow maps of lights 0 to {i} are {faces} faces of {side}² texels, {:.0} M texels ({:.1} GB), more than the \
                         limit of {:.0} M ({:.1} GB)",
                        texels as f64 / 1e6,
                        texels as f64 * 4.0 / 1e9,
                        MAX_SHADOW_MAP_TEXELS as f64 / 1e6,
                        MAX_SHADOW_MAP_TEXELS as f64 * 4.0 / 1e9
                    ),
                    Some("lower `render.shadow_map_size`, or give some lights `shadows = \"ray\"` (exact, no map)".into()),
                ));
            }
        }
        Ok(())
    }

    /// Samples per image, width × height × aa², within [`MAX_SAMPLES`].
    fn sample_total(&self, root: &KeyPath, camera: &crate::geometry::Camera, render: &super::RenderSettings) -> R<()> {
        let samples = camera.width as i64 * camera.height as i64 * (render.aa as i64).pow(2);
        if samples > MAX_SAMPLES {
            return Err(self.err(
                &root.key("render").key("aa"),
                Target::Value,
                format!(
                    "{}×{} pixels with aa {} is {samples} samples, more than the limit {MAX_SAMPLES}",
                    camera.width, camera.height, render.aa
                ),
                Some("lower `render.aa` or `camera.size`".into()),
            ));
        }
        Ok(())
    }

    // ---- sections ----------------------------------------------------------------------

    /// Builds the lesson, validating each section, material, object, light and figure on
    /// its own so that one run reports every error (up to
    /// [`crate::lesson::limits::MAX_ERRORS`], in file order).
    fn lesson(&self, raw: RawLesson) -> R<Lesson> {
        let root = KeyPath::default();
        let mut errors = Vec::new();
        let camera = keep(&mut errors, self.camera(&root.key("camera"), &raw.camera));
        let mut materials = Vec::with_capacity(raw.material.len());
        let mut material_maps = Vec::with_capacity(raw.material.len());
        let mut failed_materials = Vec::new();
        for (name, m) in &raw.material {
            match keep(&mut errors, self.material(&root.key("material").key(name), name, m)) {
                Some((m, maps)) => {
                    materials.push(m);
                    material_maps.push(maps);
                }
                None => failed_materials.push(name.as_str()),
            }
        }
        let mut objects = Vec::with_capacity(raw.object.len());
        for (i, o) in raw.object.iter().enumerate() {
            let p = root.key("object").index(i);
            match self.object(&p, o, &materials) {
                Ok(spec) => objects.push(spec),
                // A material that failed is reported once, not again by its objects.
                Err(e) if e.key == Some(p.key("material").to_string()) && failed_materials.contains(&o.material.as_str()) => {}
                Err(e) => errors.push(e),
            }
        }
        if objects.len() == raw.object.len() {
            keep(&mut errors, self.triangle_total(&root, &objects));
        }
        let lights: Vec<_> =
            raw.light.iter().enumerate().filter_map(|(i, l)| keep(&mut errors, self.light(&root.key("light").index(i), l))).collect();
        let ambient = match &raw.scene.ambient {
            Some(c) => keep(&mut errors, self.color(&root.key("scene").key("ambient"), c, 0.0, 1e6)).unwrap_or(Vec3::ZERO),
            None => Vec3::ZERO,
        };
        let render = keep(&mut errors, self.render(&root.key("render"), &raw.render));
        let fog = raw.fog.as_ref().and_then(|f| keep(&mut errors, self.fog(&root.key("fog"), f)));
        let environment = raw.environment.as_ref().and_then(|e| keep(&mut errors, self.environment(&root.key("environment"), e)));
        let probes = self.probes(&root, &raw.probe, &mut errors);
        let lang = match &raw.lesson.lang {
            Some(s) => keep(&mut errors, self.choice(&root.key("lesson").key("lang"), s, &crate::lesson::i18n::Lang::NAMES)),
            None => None,
        };
        self.lang.set(lang.unwrap_or_default());
        let info = root.key("lesson");
        let title = keep(&mut errors, self.opt_text(&info.key("title"), raw.lesson.title.as_ref()));
        let summary = keep(&mut errors, self.opt_text(&info.key("summary"), raw.lesson.summary.as_ref()));
        let notes = keep(&mut errors, self.opt_text(&info.key("notes"), raw.lesson.notes.as_ref()));
        let mut figures: Vec<FigureSpec> = Vec::new();
        let size = camera.as_ref().map(|c| (c.width, c.height));
        // Figures name materials: checked only when every material is valid.
        for (i, f) in raw.figure.iter().enumerate().filter(|_| self.figures && failed_materials.is_empty()) {
            if let Some(spec) = keep(&mut errors, self.figure(&root.key("figure").index(i), f, &figures, &raw, &materials, size)) {
                figures.push(spec);
            }
        }
        if let (Some(camera), Some(render)) = (&camera, &render) {
            keep(&mut errors, self.sample_total(&root, camera, render));
        }
        if let Some(render) = &render
            && lights.len() == raw.light.len()
        {
            keep(&mut errors, self.light_totals(&root, &lights, render));
        }
        if let Some(e) = LessonError::combine(errors) {
            return Err(e);
        }
        let (camera, render) = (camera.expect("no errors"), render.expect("no errors"));
        let stem = self.file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        Ok(Lesson {
            path: self.file.to_path_buf(),
            title: title.flatten().unwrap_or(stem),
            summary: summary.flatten().unwrap_or_default(),
            notes: notes.flatten().unwrap_or_default(),
            lang: lang.unwrap_or_default(),
            scene: crate::lesson::SceneSpec { camera, lights, ambient, settings: render, fog, probes },
            objects,
            materials,
            material_maps,
            environment,
            figures,
            source: self.text.to_string(),
            overrides: self.sets.to_vec(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::limits::MAX_ERRORS;

    /// Every key that names a file goes through `asset_path`: a key the format does not
    /// have yet (an environment map) is located and refused exactly like `object.0.path`.
    #[test]
    fn asset_path_serves_every_key_that_names_a_file() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("l");
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("sky.hdr"), "x").unwrap();
        let text = "[environment]\nmap = \"../../etc/passwd\"\n";
        let file = folder.join("l.toml");
        let v = Validator::new(text, &file, &[]);
        let key = KeyPath::parse("environment.map").unwrap();
        let e = v.asset_path(&key, "../../etc/passwd").unwrap_err();
        assert_eq!((e.key.as_deref(), &e.location), (Some("environment.map"), &Location::File { line: 2, col: 7 }));
        assert!(e.message.starts_with("../../etc/passwd: outside the lesson's folder"), "{e}");
        assert!(e.hint.as_deref().is_some_and(|h| h.contains("--allow-dir")), "{e}");
        let ok = v.asset_path(&key, "sky.hdr").unwrap();
        assert_eq!(ok, folder.join("sky.hdr").canonicalize().unwrap());
    }

    #[test]
    fn errors_are_combined_in_file_order_and_capped() {
        let at = |line| LessonError {
            file: "l.toml".into(),
            location: Location::File { line, col: 1 },
            key: Some(format!("k{line}")),
            message: "m".into(),
            hint: None,
            others: Default::default(),
        };
        let flag = LessonError { location: Location::Flag("--set a=1".into()), ..at(0) };
        let e = LessonError::combine(vec![at(9), flag, at(3), at(5)]).unwrap();
        let order: Vec<&Location> = std::iter::once(&e.location).chain(e.others.iter().map(|o| &o.location)).collect();
        assert_eq!(
            order[..3],
            [&Location::File { line: 3, col: 1 }, &Location::File { line: 5, col: 1 }, &Location::File { line: 9, col: 1 }]
        );
        assert!(matches!(order[3], Location::Flag(_)));
        let many = LessonError::combine((1..=50).rev().map(at).collect()).unwrap();
        assert_eq!(many.count(), MAX_ERRORS);
        assert_eq!(many.others.last().unwrap().location, Location::File { line: MAX_ERRORS, col: 1 });
        assert!(LessonError::combine(Vec::new()).is_none());
    }

    #[test]
    fn unknown_keys_and_wrong_types_are_all_reported() {
        let text = "[camera]\nposition = [0, 0, 4]\nfov = 30\n\n[material.m]\nmodel = \"phong\"\nshininess = \"high\"\n\n\
                    [[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\nsegmentz = 3\n\n[[light]]\nkind = \"point\"\nposition = [0, 0, 1]\nintensity = -1\n";
        let e = crate::lesson::parse(text, Path::new("l.toml"), &[]).unwrap_err();
        let keys: Vec<&str> = std::iter::once(&e).chain(e.others.iter()).filter_map(|e| e.key.as_deref()).collect();
        assert_eq!(keys, ["camera.fov", "material.m.shininess", "object.0.segmentz", "light.0.intensity"], "{e}");
        // A key removed for its wrong type is not reported again as missing.
        let e = crate::lesson::parse("[camera]\nposition = 4\n", Path::new("l.toml"), &[]).unwrap_err();
        assert_eq!(e.count(), 1, "{e}");
    }
}

#[cfg(test)]
mod totals {
    use std::path::Path;

    fn lesson_with(lights: &str, render: &str) -> String {
        format!(
            "[camera]\nposition = [0, 0, 4]\nsize = [32, 32]\n\n[[object]]\nshape = \"plane\"\nmaterial = \"m\"\n\n\
             [material.m]\nmodel = \"lambert\"\n\n[render]\n{render}\n{lights}"
        )
    }

    fn error(text: &str) -> String {
        crate::lesson::parse(text, Path::new("l.toml"), &[]).unwrap_err().to_string()
    }

    /// Reliability round two, finding 2: every light within its own limit, the sum unbounded.
    #[test]
    fn limits_hold_for_the_lights_together() {
        let point = "[[light]]\nkind = \"point\"\nposition = [0, 2, 0]\n";
        // Two point lights with 8192² maps are 12 faces: refused at the second, with the numbers.
        let e = error(&lesson_with(&point.repeat(2), "shadows = \"map\"\nshadow_map_size = 8192"));
        assert!(e.contains("l.toml:") && e.contains("lights 0 to 1 are 12 faces of 8192² texels"), "{e}");
        // One is within the limit, and so are two with ray-cast shadows.
        assert!(crate::lesson::parse(&lesson_with(point, "shadows = \"map\"\nshadow_map_size = 8192"), Path::new("l.toml"), &[]).is_ok());
        assert!(crate::lesson::parse(&lesson_with(&point.repeat(2), "shadow_map_size = 8192"), Path::new("l.toml"), &[]).is_ok());
        // 257 lights.
        let e = error(&lesson_with(&point.repeat(257), ""));
        assert!(e.contains("257 lights, more than the limit of 256"), "{e}");
        // Five rect lights at 4096 samples each.
        let rect = "[[light]]\nkind = \"rect\"\nposition = [0, 2, 0]\ndirection = [0, -1, 0]\nsize = [1, 1]\nsamples = 4096\n";
        let e = error(&lesson_with(&rect.repeat(5), ""));
        assert!(e.contains("lights 0 to 4 take 20480 samples a shaded point together"), "{e}");
    }
}

#[cfg(test)]
mod every_error {
    /// A material's unused keys and its bad values are reported together (docs: one run,
    /// every error): a `cook_torrance` with `base_color` and `roughness = -0.2` gave only the first.
    #[test]
    fn a_material_reports_its_unused_keys_and_its_bad_value_in_one_run() {
        let text = "[camera]\nposition = [0, 0, 4]\n\n[[object]]\nshape = \"uv_sphere\"\nmaterial = \"m\"\n\n\
                    [material.m]\nmodel = \"cook_torrance\"\nbase_color = [0.5, 0.5, 0.5]\nmetallic = 1\nroughness = -0.2\n";
        let e = crate::lesson::parse(text, std::path::Path::new("l.toml"), &[]).unwrap_err();
        assert_eq!(e.count(), 3, "{e}");
        let shown = e.to_string();
        assert!(
            shown.contains("`base_color` is not used")
                && shown.contains("`metallic` is not used")
                && shown.contains("-0.2 is out of range"),
            "{shown}"
        );
    }
}
