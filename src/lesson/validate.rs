//! Stage two: serde mirror → validated [`Lesson`], every error tied to a key path.

use super::error::{LessonError, Location};
use super::figure::{Axis, DEFAULT_REPEAT, FigureKind, FigureSpec, MAX_CELLS, MAX_REPEAT, parse_range};
use super::overrides::Override;
use super::path::{KeyPath, Segment};
use super::raw::{RawAxis, RawCamera, RawColor, RawFigure, RawLesson, RawLight, RawMaterial, RawObject, RawRender};
use super::spans::{self, Target};
use super::{Lesson, ObjectSpec};
use crate::cost::LadderKind;
use crate::figure::overlay::Normals;
use crate::render::{Cull, Interpolation, Layer, RenderSettings, Tonemap};
use crate::scene::{Camera, Classic, ClassicModel, Light, LightKind, Material, Model, NormalWeighting, Shape};
use crate::shading::brdf::Brdf;
use crate::shading::cook_torrance::CookTorrance;
use crate::shading::diffuse::Diffuse;
use crate::shading::microfacet::{Fresnel, Masking, Ndf};
use crate::shading::normalized_phong::{NormalizedBlinnPhong, NormalizedPhong};
use crate::shading::oren_nayar::{OrenNayar, OrenNayarModel};
use crate::shading::principled::Principled;
use glam::{Affine3A, EulerRot, Quat, Vec3};
use std::path::Path;

/// Largest image side in pixels.
pub const MAX_SIDE: i64 = 16384;
/// Largest image area in pixels (about 8K × 5K).
pub const MAX_PIXELS: i64 = 40_000_000;
/// Largest supersampling factor per pixel side.
pub const MAX_AA: i64 = 16;

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

    // ---- scalar checks ---------------------------------------------------------------

    fn number(&self, path: &KeyPath, v: f64, lo: f64, hi: f64) -> R<f32> {
        if !v.is_finite() {
            let hint = key_help(path)
                .map_or_else(|| format!("use a value between {lo} and {hi}"), |h| format!("use a value between {lo} and {hi}; {h}"));
            return Err(self.err(path, Target::Value, format!("must be a finite number, got {v}"), Some(hint)));
        }
        if v < lo || v > hi {
            return Err(self.err(
                path,
                Target::Value,
                format!("{v} is out of range: allowed {lo} to {hi}"),
                Some(range_hint(path, lo, hi)),
            ));
        }
        Ok(v as f32)
    }

    fn integer(&self, path: &KeyPath, v: i64, lo: i64, hi: i64) -> R<u32> {
        if v < lo || v > hi {
            let (lo_f, hi_f) = (lo as f64, hi as f64);
            return Err(self.err(
                path,
                Target::Value,
                format!("{v} is out of range: allowed {lo} to {hi}"),
                Some(range_hint(path, lo_f, hi_f)),
            ));
        }
        Ok(v as u32)
    }

    fn vec3(&self, path: &KeyPath, v: [f64; 3], lo: f64, hi: f64) -> R<Vec3> {
        let mut out = [0.0f32; 3];
        for (i, x) in v.iter().enumerate() {
            // Located at the component, named by the whole vector.
            out[i] = self.number(&path.index(i), *x, lo, hi).map_err(|e| LessonError {
                key: Some(path.to_string()),
                message: format!("component {i}: {}", e.message),
                ..e
            })?;
        }
        Ok(Vec3::from(out))
    }

    fn color(&self, path: &KeyPath, c: RawColor, lo: f64, hi: f64) -> R<Vec3> {
        match c {
            RawColor::Scalar(s) => Ok(Vec3::splat(self.number(path, s, lo, hi)?)),
            RawColor::Rgb(rgb) => self.vec3(path, rgb, lo, hi),
        }
    }

    fn direction(&self, path: &KeyPath, v: [f64; 3]) -> R<Vec3> {
        let d = self.vec3(path, v, -1e6, 1e6)?;
        d.try_normalize().ok_or_else(|| {
            self.err(path, Target::Value, "a direction cannot be [0, 0, 0]", Some("give the way the light travels, e.g. [0, 0, -1]".into()))
        })
    }

    fn choice<T: Copy>(&self, path: &KeyPath, got: &str, options: &[(&str, T)]) -> R<T> {
        if let Some((_, t)) = options.iter().find(|(name, _)| *name == got) {
            return Ok(*t);
        }
        let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
        let hint = match suggest(got, &names) {
            Some(s) => format!("did you mean `{s}`? Allowed: {}", names.join(", ")),
            None => format!("allowed: {}", names.join(", ")),
        };
        Err(self.err(path, Target::Value, format!("unknown value `{got}`"), Some(hint)))
    }

    /// Rejects a key that the chosen variant does not read (parameters nobody reads are errors).
    /// Refuses the first of `keys` that figure `f` sets: "`key` is not used {why}".
    fn refuse_figure_keys(&self, path: &KeyPath, f: &RawFigure, keys: &[&str], why: &str) -> R<()> {
        match keys.iter().find(|k| f.is_set(k)) {
            Some(key) => self.unused(path, key, &Some(()), why),
            None => Ok(()),
        }
    }

    fn unused<T>(&self, path: &KeyPath, key: &str, v: &Option<T>, why: &str) -> R<()> {
        match v {
            Some(_) => Err(self.err(&path.key(key), Target::Key, format!("`{key}` is not used {why}"), Some(format!("remove `{key}`")))),
            None => Ok(()),
        }
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
            figures,
            source: self.text.to_string(),
            overrides: self.sets.to_vec(),
        })
    }

    fn figure(&self, p: &KeyPath, f: &RawFigure, earlier: &[FigureSpec], raw: &RawLesson, materials: &[Material]) -> R<FigureSpec> {
        let name_ok = !f.name.is_empty() && f.name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
        if !name_ok {
            return Err(self.err(
                &p.key("name"),
                Target::Value,
                format!("`{}` cannot be a file name", f.name),
                Some("use letters, digits, `-` and `_`, e.g. \"shininess-sweep\"".into()),
            ));
        }
        if earlier.iter().any(|e| e.name == f.name) {
            return Err(self.err(
                &p.key("name"),
                Target::Value,
                format!("another figure is already named `{}`", f.name),
                Some("figure names must be unique within a lesson".into()),
            ));
        }
        let kind = self.choice(
            &p.key("kind"),
            &f.kind,
            &[
                ("compare", FigureKind::Compare),
                ("sweep", FigureKind::Sweep),
                ("grid", FigureKind::Grid),
                ("split", FigureKind::Split),
                ("lobe", FigureKind::Lobe),
                ("albedo", FigureKind::Albedo),
                ("cost", FigureKind::Cost),
            ],
        )?;
        if matches!(kind, FigureKind::Lobe | FigureKind::Albedo) {
            return self.chart_figure(p, f, kind, materials);
        }
        if kind == FigureKind::Cost {
            return self.cost_figure(p, f);
        }
        self.refuse_figure_keys(
            p,
            f,
            &["ladder", "repeat"],
            &format!("by a `{}` figure (only `cost` figures measure a ladder)", kind.name()),
        )?;
        self.refuse_figure_keys(p, f, &["materials", "incidence"], "by a figure of variants (only `lobe` and `albedo` plot materials)")?;
        let why = format!("by a `{}` figure", kind.name());
        let one_axis = |vary: &Option<String>, values: &Option<toml::Value>| -> R<Axis> {
            let vary = vary.as_ref().ok_or_else(|| {
                self.err(
                    &p.key("vary"),
                    Target::Key,
                    format!("a `{}` figure needs `vary`", kind.name()),
                    Some("add e.g. `vary = \"material.plastic.shininess\"`".into()),
                )
            })?;
            let values = values.as_ref().ok_or_else(|| {
                self.err(
                    &p.key("values"),
                    Target::Key,
                    format!("a `{}` figure needs `values`", kind.name()),
                    Some("add e.g. `values = [1, 10, 100]` or `values = \"1..256:log:8\"`".into()),
                )
            })?;
            self.axis(p, vary, values, f.labels.as_ref(), raw)
        };
        let (rows, cols) = match kind {
            FigureKind::Compare | FigureKind::Sweep => {
                self.unused(p, "rows", &f.rows, &why)?;
                self.unused(p, "cols", &f.cols, &why)?;
                (None, Some(one_axis(&f.vary, &f.values)?))
            }
            FigureKind::Grid => {
                self.unused(p, "vary", &f.vary, "by a `grid` figure (use `rows` and `cols`)")?;
                self.unused(p, "values", &f.values, "by a `grid` figure (use `rows` and `cols`)")?;
                self.unused(p, "labels", &f.labels, "by a `grid` figure (give `labels` inside `rows` and `cols`)")?;
                let need = |key: &str, a: &Option<RawAxis>| {
                    a.clone().ok_or_else(|| {
                        self.err(
                            &p.key(key),
                            Target::Key,
                            format!("a `grid` figure needs `{key}`"),
                            Some(format!("add `{key} = {{ vary = \"material.plastic.shininess\", values = [3, 10, 100] }}`")),
                        )
                    })
                };
                let r = need("rows", &f.rows)?;
                let c = need("cols", &f.cols)?;
                (
                    Some(self.axis(&p.key("rows"), &r.vary, &r.values, r.labels.as_ref(), raw)?),
                    Some(self.axis(&p.key("cols"), &c.vary, &c.values, c.labels.as_ref(), raw)?),
                )
            }
            FigureKind::Lobe | FigureKind::Albedo | FigureKind::Cost => unreachable!("chart and cost figures return above"),
            FigureKind::Split => {
                self.refuse_figure_keys(p, f, &["vary", "values", "rows", "cols", "labels"], &why)?;
                (None, None)
            }
        };
        let cells = rows.as_ref().map_or(1, |a| a.values.len()) * cols.as_ref().map_or(1, |a| a.values.len());
        if cells > MAX_CELLS {
            return Err(self.err(p, Target::Key, format!("{cells} cells is more than {MAX_CELLS}"), Some("use fewer values".into())));
        }
        let layers = match &f.layers {
            None => vec![Layer::Ambient, Layer::Diffuse, Layer::Specular, Layer::Total],
            Some(names) if kind == FigureKind::Split => {
                let options = Layer::ALL.map(|l| (l.name(), l));
                let mut out = Vec::new();
                for (i, n) in names.iter().enumerate() {
                    out.push(self.choice(&p.key("layers").index(i), n, &options)?);
                }
                if out.is_empty() {
                    return Err(self.err(&p.key("layers"), Target::Value, "a split needs at least one layer", None));
                }
                out
            }
            Some(_) => {
                return Err(self.err(
                    &p.key("layers"),
                    Target::Key,
                    format!("`layers` is not used {why}"),
                    Some("remove `layers`, or use `layer = \"specular\"` to show one layer in every cell".into()),
                ));
            }
        };
        let layers = match (&f.layer, kind) {
            (Some(_), FigureKind::Split) => {
                return Err(self.err(
                    &p.key("layer"),
                    Target::Key,
                    "`layer` is not used by a `split` figure",
                    Some("use `layers = [...]`".into()),
                ));
            }
            (Some(name), _) => vec![self.choice(&p.key("layer"), name, &Layer::ALL.map(|l| (l.name(), l)))?],
            (None, FigureKind::Split) => layers,
            (None, _) => vec![Layer::Total],
        };
        let cell = match f.cell {
            Some([w, h]) => {
                let cp = p.key("cell");
                Some((self.integer(&cp, w, 8, 4096)?, self.integer(&cp, h, 8, 4096)?))
            }
            None => None,
        };
        let normals = match &f.normals {
            Some(n) => {
                Some(self.choice(&p.key("normals"), n, &[("face", Normals::Face), ("vertex", Normals::Vertex), ("both", Normals::Both)])?)
            }
            None => None,
        };
        Ok(FigureSpec {
            name: f.name.clone(),
            kind,
            normals,
            rows,
            cols,
            title: f.title.clone(),
            caption: f.caption.clone(),
            layers,
            cell,
            materials: Vec::new(),
            incidence: Vec::new(),
            ladder: None,
            repeat: DEFAULT_REPEAT,
        })
    }

    /// A `lobe` or `albedo` figure: physically based materials plotted, no variants.
    fn chart_figure(&self, p: &KeyPath, f: &RawFigure, kind: FigureKind, defined: &[Material]) -> R<FigureSpec> {
        let why = format!("by a `{}` figure (it plots `materials`)", kind.name());
        let variant_keys = ["vary", "values", "rows", "cols", "labels", "layers", "layer", "cell", "normals", "ladder", "repeat"];
        self.refuse_figure_keys(p, f, &variant_keys, &why)?;
        if kind == FigureKind::Albedo {
            self.unused(p, "incidence", &f.incidence, "by an `albedo` figure (it sweeps every angle)")?;
        }
        let materials = f.materials.clone().ok_or_else(|| {
            self.err(
                p,
                Target::Key,
                format!("a `{}` figure needs `materials`", kind.name()),
                Some("add e.g. `materials = [\"gold\", \"plastic\"]` (physically based materials of this lesson)".into()),
            )
        })?;
        let physical: Vec<&str> = defined.iter().filter(|m| m.brdf().is_some()).map(|m| m.name.as_str()).collect();
        let choose = if physical.is_empty() {
            "this lesson has no physically based material; add one, e.g. [material.gold] with model = \"cook_torrance\"".to_string()
        } else {
            format!("physically based materials here: {}", physical.join(", "))
        };
        if materials.is_empty() {
            return Err(self.err(&p.key("materials"), Target::Value, "no materials", Some(format!("name at least one; {choose}"))));
        }
        for (i, name) in materials.iter().enumerate() {
            let at = p.key("materials").index(i);
            match defined.iter().find(|m| &m.name == name) {
                None => {
                    let all: Vec<&str> = defined.iter().map(|m| m.name.as_str()).collect();
                    let hint = match suggest(name, &physical).or_else(|| suggest(name, &all)) {
                        Some(s) => format!("did you mean `{s}`? ({choose})"),
                        None => choose.clone(),
                    };
                    return Err(self.err(&at, Target::Value, format!("no material named `{name}`"), Some(hint)));
                }
                Some(m) if m.brdf().is_none() => {
                    return Err(self.err(
                        &at,
                        Target::Value,
                        format!(
                            "`{name}` is a classic material ({}): a `{}` figure plots physically based BRDFs",
                            m.family_name(),
                            kind.name()
                        ),
                        Some(format!("{choose} (the classic models have no π and no units)")),
                    ));
                }
                Some(_) => {}
            }
        }
        let mut incidence = Vec::new();
        match &f.incidence {
            Some(list) => {
                for (i, a) in list.iter().enumerate() {
                    incidence.push(self.number(&p.key("incidence").index(i), *a, 0.0, 89.9)? as f64);
                }
            }
            None => incidence.push(30.0),
        }
        Ok(FigureSpec {
            name: f.name.clone(),
            kind,
            normals: None,
            rows: None,
            cols: None,
            title: f.title.clone(),
            caption: f.caption.clone(),
            layers: Vec::new(),
            cell: None,
            materials,
            incidence,
            ladder: None,
            repeat: DEFAULT_REPEAT,
        })
    }

    /// A `cost` figure: a ladder measured on the lesson, no variants.
    fn cost_figure(&self, p: &KeyPath, f: &RawFigure) -> R<FigureSpec> {
        let why = "by a `cost` figure (its rungs come from `ladder`)";
        let other_keys = ["vary", "values", "rows", "cols", "labels", "layers", "layer", "materials", "incidence", "normals"];
        self.refuse_figure_keys(p, f, &other_keys, why)?;
        let name = f.ladder.as_ref().ok_or_else(|| {
            self.err(
                p,
                Target::Key,
                "a `cost` figure needs `ladder`",
                Some("add e.g. `ladder = \"interpolation\"` (interpolation, tessellation, aa or fresnel)".into()),
            )
        })?;
        let options = LadderKind::ALL.map(|l| (l.name(), l));
        let ladder = self.choice(&p.key("ladder"), name, &options)?;
        let repeat = match f.repeat {
            Some(n) => self.integer(&p.key("repeat"), n, 1, MAX_REPEAT)? as usize,
            None => DEFAULT_REPEAT,
        };
        let cell = match f.cell {
            Some([w, h]) => {
                let cp = p.key("cell");
                Some((self.integer(&cp, w, 8, 4096)?, self.integer(&cp, h, 8, 4096)?))
            }
            None => None,
        };
        Ok(FigureSpec {
            name: f.name.clone(),
            kind: FigureKind::Cost,
            normals: None,
            rows: None,
            cols: None,
            title: f.title.clone(),
            caption: f.caption.clone(),
            layers: vec![Layer::Total],
            cell,
            materials: Vec::new(),
            incidence: Vec::new(),
            ladder: Some(ladder),
            repeat,
        })
    }

    /// An axis: `vary` must be a dotted path, `values` an array or a range string.
    fn axis(&self, p: &KeyPath, vary: &str, values: &toml::Value, labels: Option<&Vec<String>>, raw: &RawLesson) -> R<Axis> {
        let key = KeyPath::parse(vary).ok_or_else(|| {
            self.err(
                &p.key("vary"),
                Target::Value,
                format!("`{vary}` is not a dotted key path"),
                Some("e.g. \"material.plastic.shininess\" or \"light.0.intensity\"; quote names with spaces: 'material.\"GGX r = 1\".roughness'".into()),
            )
        })?;
        if let Err((message, hint)) = check_vary(&key, raw) {
            return Err(self.err(&p.key("vary"), Target::Value, message, Some(hint)));
        }
        let values: Vec<toml::Value> = match values {
            toml::Value::Array(a) => a.clone(),
            toml::Value::String(s) => match parse_range(s) {
                Ok(v) => v.into_iter().map(toml::Value::Float).collect(),
                // A single word is one value (e.g. a model name); anything range-like is an error.
                Err(e) if s.contains("..") => {
                    return Err(self.err(
                        &p.key("values"),
                        Target::Value,
                        e,
                        Some("e.g. \"1..256:log:8\" (8 values from 1 to 256, evenly spaced in log), \"0..1:lin:5\", or an array [1, 10, 100]".into()),
                    ));
                }
                Err(_) => vec![toml::Value::String(s.clone())],
            },
            other => vec![other.clone()],
        };
        if values.is_empty() {
            return Err(self.err(&p.key("values"), Target::Value, "no values", Some("give at least one value".into())));
        }
        if let Some(l) = labels
            && l.len() != values.len()
        {
            return Err(self.err(
                &p.key("labels"),
                Target::Value,
                format!("{} labels for {} values", l.len(), values.len()),
                Some("give one label per value".into()),
            ));
        }
        Ok(Axis { key, values, labels: labels.cloned(), origin: p.key("values") })
    }

    fn camera(&self, p: &KeyPath, c: &RawCamera) -> R<Camera> {
        let position = self.vec3(&p.key("position"), c.position, -1e6, 1e6)?;
        let look_at = match c.look_at {
            Some(v) => self.vec3(&p.key("look_at"), v, -1e6, 1e6)?,
            None => Vec3::ZERO,
        };
        let up = match c.up {
            Some(v) => self.vec3(&p.key("up"), v, -1e6, 1e6)?,
            None => Vec3::Y,
        };
        let forward = look_at - position;
        if forward.length() < 1e-6 {
            // Name the key the user wrote; an absent `look_at` is the origin.
            let (key, hint) = match c.look_at {
                Some(_) => ("look_at", "move `camera.position` away from `camera.look_at`"),
                None => ("position", "`camera.look_at` defaults to [0, 0, 0]: move `camera.position` or set `look_at`"),
            };
            return Err(self.err(&p.key(key), Target::Value, "the camera looks at its own position", Some(hint.into())));
        }
        if up.length() < 1e-6 {
            return Err(self.err(&p.key("up"), Target::Value, "`up` cannot be [0, 0, 0]", Some("use e.g. [0, 1, 0]".into())));
        }
        if forward.normalize().cross(up.normalize()).length() < 1e-4 {
            let default = if c.up.is_none() { "`up` defaults to [0, 1, 0]; " } else { "" };
            return Err(self.err(
                &p.key("up"),
                Target::Value,
                "`up` is parallel to the view direction (look_at − position)",
                Some(format!("{default}choose an `up` across the view direction, e.g. [0, 0, -1] when looking straight down")),
            ));
        }
        let fov_y_deg = match c.fov_deg {
            Some(v) => self.number(&p.key("fov_deg"), v, 1.0, 179.0)?,
            None => 40.0,
        };
        let (width, height) = match c.size {
            Some([w, h]) => {
                let sp = p.key("size");
                let side = |i: usize, v: i64, name: &str| {
                    self.integer(&sp.index(i), v, 1, MAX_SIDE).map_err(|e| LessonError {
                        key: Some(sp.to_string()),
                        message: format!("{name}: {}", e.message),
                        ..e
                    })
                };
                let (w, h) = (side(0, w, "width")?, side(1, h, "height")?);
                if w as i64 * h as i64 > MAX_PIXELS {
                    return Err(self.err(&sp, Target::Value, format!("{w}×{h} is more than {MAX_PIXELS} pixels"), None));
                }
                (w, h)
            }
            None => (512, 512),
        };
        let near = match c.near {
            Some(v) => self.number(&p.key("near"), v, 1e-4, 1e4)?,
            None => 0.05,
        };
        let background = match c.background {
            Some(b) => self.color(&p.key("background"), b, 0.0, 1e6)?,
            None => Vec3::ZERO,
        };
        Ok(Camera { position, look_at, up, fov_y_deg, width, height, near, background })
    }

    fn material(&self, p: &KeyPath, name: &str, m: &RawMaterial) -> R<Material> {
        let all = [
            "lambert",
            "phong",
            "blinn_phong",
            "diffuse",
            "cook_torrance",
            "oren_nayar",
            "principled",
            "normalized_phong",
            "normalized_blinn_phong",
            "unnormalized_phong",
        ];
        let kind = self.choice(&p.key("model"), &m.model, &all.map(|n| (n, n)))?;
        if !matches!(kind, "lambert" | "phong" | "blinn_phong") {
            return self.physical_material(p, name, kind, m);
        }
        let model = match kind {
            "lambert" => ClassicModel::Lambert,
            "phong" => ClassicModel::Phong,
            _ => ClassicModel::BlinnPhong,
        };
        // Keys of the physically based models mean nothing to the classic ones.
        let why = format!("by `{}` (a classic model: K_amb, K_diff, K_spec, K_shi, L_emi)", m.model);
        for (key, set) in [
            ("ndf", m.ndf.is_some()),
            ("masking", m.masking.is_some()),
            ("fresnel", m.fresnel.is_some()),
            ("ior", m.ior.is_some()),
            ("eta", m.eta.is_some()),
            ("k", m.k.is_some()),
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
        ] {
            if set {
                self.unused(p, key, &Some(()), &why)?;
            }
        }
        let coef =
            |key: &str, v: Option<RawColor>, default: Vec3| -> R<Vec3> { v.map_or(Ok(default), |c| self.color(&p.key(key), c, 0.0, 1.0)) };
        let diffuse = coef("diffuse", m.diffuse, Vec3::splat(0.8))?;
        let ambient = coef("ambient", m.ambient, diffuse)?;
        let (specular, shininess) = if model == ClassicModel::Lambert {
            self.unused(p, "specular", &m.specular, "by `lambert` (it has no specular term; use `phong` or `blinn_phong`)")?;
            self.unused(p, "shininess", &m.shininess, "by `lambert` (it has no specular term; use `phong` or `blinn_phong`)")?;
            (Vec3::ZERO, 1.0)
        } else {
            let s = coef("specular", m.specular, Vec3::splat(0.5))?;
            let n = m.shininess.map_or(Ok(32.0), |v| self.number(&p.key("shininess"), v, 0.0, 1e6))?;
            (s, n)
        };
        let emission = m.emission.map_or(Ok(Vec3::ZERO), |c| self.color(&p.key("emission"), c, 0.0, 1e6))?;
        let model = Model::Classic(Classic { model, diffuse, specular, shininess });
        Ok(Material { name: name.to_string(), model, ambient, emission })
    }

    /// A physically based material: the keys its model reads, each checked; any other key is an error.
    fn physical_material(&self, p: &KeyPath, name: &str, kind: &str, m: &RawMaterial) -> R<Material> {
        let allowed = model_keys(kind).expect("a known model");
        let present = [
            ("diffuse", m.diffuse.is_some()),
            ("specular", m.specular.is_some()),
            ("shininess", m.shininess.is_some()),
            ("ndf", m.ndf.is_some()),
            ("masking", m.masking.is_some()),
            ("fresnel", m.fresnel.is_some()),
            ("ior", m.ior.is_some()),
            ("eta", m.eta.is_some()),
            ("k", m.k.is_some()),
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
        ];
        for (key, set) in present {
            if set && !allowed.contains(&key) {
                self.unused(p, key, &Some(()), &format!("by `{kind}` (it reads: {})", allowed.join(", ")))?;
            }
        }
        let color =
            |key: &str, v: Option<RawColor>, default: Vec3| -> R<Vec3> { v.map_or(Ok(default), |c| self.color(&p.key(key), c, 0.0, 1.0)) };
        let unit = |key: &str, v: Option<f64>, default: f32| -> R<f32> { v.map_or(Ok(default), |x| self.number(&p.key(key), x, 0.0, 1.0)) };
        let brdf = match kind {
            "diffuse" => Brdf::Diffuse(Diffuse { albedo: color("diffuse", m.diffuse, Vec3::splat(0.8))? }),
            "oren_nayar" => {
                let variant = match &m.variant {
                    Some(v) => {
                        self.choice(&p.key("variant"), v, &[("full", OrenNayarModel::Full), ("qualitative", OrenNayarModel::Qualitative)])?
                    }
                    None => OrenNayarModel::Full,
                };
                let sigma = m.sigma_deg.map_or(Ok(20.0), |x| self.number(&p.key("sigma_deg"), x, 0.0, 90.0))?;
                Brdf::OrenNayar(OrenNayar::from_degrees(color("diffuse", m.diffuse, Vec3::splat(0.8))?, sigma, variant))
            }
            "cook_torrance" => {
                let ndf = match &m.ndf {
                    Some(v) => self.choice(
                        &p.key("ndf"),
                        v,
                        &[("blinn", Ndf::Blinn), ("beckmann", Ndf::Beckmann), ("ggx", Ndf::Ggx), ("gaussian", Ndf::Gaussian)],
                    )?,
                    None => Ndf::Ggx,
                };
                let masking = match &m.masking {
                    Some(v) => self.choice(
                        &p.key("masking"),
                        v,
                        &[
                            ("cook_torrance", Masking::CookTorrance),
                            ("smith", Masking::Smith),
                            ("smith_correlated", Masking::SmithCorrelated),
                        ],
                    )?,
                    // Smith's Λ is exact for GGX and Beckmann only; the V-cavity masking is exact for
                    // any NDF, so Blinn and Gaussian default to it (Smith is off by up to 75% at α = 1).
                    None if matches!(ndf, Ndf::Blinn | Ndf::Gaussian) => Masking::CookTorrance,
                    None => Masking::Smith,
                };
                let alpha = match (m.roughness, m.alpha) {
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
                let fresnel_name = m.fresnel.as_deref().unwrap_or("schlick");
                let fresnel_kind =
                    self.choice(&p.key("fresnel"), fresnel_name, &[("schlick", 0), ("dielectric", 1), ("conductor", 2), ("none", 3)])?;
                if fresnel_kind >= 2 {
                    self.unused(p, "ior", &m.ior, &format!("by fresnel `{fresnel_name}` (a conductor has `eta` and `k`)"))?;
                }
                if fresnel_kind != 2 {
                    self.unused(p, "eta", &m.eta, &format!("by fresnel `{fresnel_name}` (only `conductor` reads `eta` and `k`)"))?;
                    self.unused(p, "k", &m.k, &format!("by fresnel `{fresnel_name}` (only `conductor` reads `eta` and `k`)"))?;
                }
                let ior = m.ior.map_or(Ok(1.5), |x| self.number(&p.key("ior"), x, 1.0, 10.0))?;
                let fresnel = match fresnel_kind {
                    0 => Fresnel::schlick_from_ior(ior),
                    1 => Fresnel::Dielectric { eta: ior },
                    2 => {
                        let need = |key: &str, v: Option<RawColor>| {
                            v.ok_or_else(|| {
                                self.err(
                                    &p.key(key),
                                    Target::Key,
                                    format!("fresnel `conductor` needs `{key}`"),
                                    Some("e.g. gold: eta = [0.143, 0.374, 1.442], k = [3.983, 2.385, 1.603]".into()),
                                )
                            })
                        };
                        let eta = self.color(&p.key("eta"), need("eta", m.eta)?, 1e-3, 20.0)?;
                        let k = self.color(&p.key("k"), need("k", m.k)?, 0.0, 20.0)?;
                        Fresnel::Conductor { eta, k }
                    }
                    _ => Fresnel::None,
                };
                Brdf::CookTorrance(CookTorrance {
                    ndf,
                    masking,
                    fresnel,
                    alpha,
                    specular: color("specular", m.specular, Vec3::ONE)?,
                    diffuse: color("diffuse", m.diffuse, Vec3::ZERO)?,
                })
            }
            "principled" => {
                let specular = match m.specular {
                    None => 0.5,
                    Some(RawColor::Scalar(x)) => self.number(&p.key("specular"), x, 0.0, 1.0)?,
                    Some(RawColor::Rgb(_)) => {
                        return Err(self.err(
                            &p.key("specular"),
                            Target::Value,
                            "principled `specular` is one number",
                            Some("use `specular = 0.5` (tint it with `specular_tint`)".into()),
                        ));
                    }
                };
                let d = Principled::default();
                Brdf::Principled(Principled {
                    base_color: color("base_color", m.base_color, Vec3::splat(0.8))?,
                    metallic: unit("metallic", m.metallic, d.metallic)?,
                    roughness: unit("roughness", m.roughness, d.roughness)?,
                    specular,
                    specular_tint: unit("specular_tint", m.specular_tint, d.specular_tint)?,
                    sheen: unit("sheen", m.sheen, d.sheen)?,
                    sheen_tint: unit("sheen_tint", m.sheen_tint, d.sheen_tint)?,
                    clearcoat: unit("clearcoat", m.clearcoat, d.clearcoat)?,
                    clearcoat_gloss: unit("clearcoat_gloss", m.clearcoat_gloss, d.clearcoat_gloss)?,
                    subsurface: unit("subsurface", m.subsurface, d.subsurface)?,
                    anisotropic: unit("anisotropic", m.anisotropic, d.anisotropic)?,
                })
            }
            _ => {
                let diffuse = color("diffuse", m.diffuse, Vec3::splat(0.5))?;
                let specular = color("specular", m.specular, Vec3::splat(0.5))?;
                let shininess = m.shininess.map_or(Ok(32.0), |v| self.number(&p.key("shininess"), v, 0.0, 1e6))?;
                if kind == "normalized_phong" {
                    Brdf::NormalizedPhong(NormalizedPhong { diffuse, specular, shininess })
                } else if kind == "unnormalized_phong" {
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
        let albedo = match &brdf {
            Brdf::Diffuse(d) => d.albedo,
            Brdf::OrenNayar(o) => o.albedo,
            Brdf::CookTorrance(c) => c.diffuse,
            Brdf::Principled(pr) => pr.base_color * (1.0 - pr.metallic),
            Brdf::NormalizedPhong(n) => n.diffuse,
            Brdf::NormalizedBlinnPhong(n) => n.diffuse,
        };
        let ambient = color("ambient", m.ambient, albedo)?;
        let emission = m.emission.map_or(Ok(Vec3::ZERO), |c| self.color(&p.key("emission"), c, 0.0, 1e6))?;
        Ok(Material { name: name.to_string(), model: Model::Physical(brdf), ambient, emission })
    }

    fn object(&self, p: &KeyPath, o: &RawObject, materials: &[Material]) -> R<ObjectSpec> {
        let shapes = ["uv_sphere", "icosphere", "plane", "cube", "torus", "mesh"];
        let kind = self.choice(&p.key("shape"), &o.shape, &shapes.map(|s| (s, s)))?;
        let int = |key: &str, v: Option<i64>, default: i64, lo: i64, hi: i64| -> R<u32> {
            self.integer(&p.key(key), v.unwrap_or(default), lo, hi)
        };
        let why = format!("by shape `{kind}`");
        let mut allowed: Vec<&str> = Vec::new();
        let shape = match kind {
            "uv_sphere" => {
                allowed.extend(["segments", "rings"]);
                Shape::UvSphere { segments: int("segments", o.segments, 32, 3, 2048)?, rings: int("rings", o.rings, 16, 2, 1024)? }
            }
            "icosphere" => {
                allowed.push("subdivisions");
                Shape::Icosphere { subdivisions: int("subdivisions", o.subdivisions, 3, 0, 9)? }
            }
            "plane" => Shape::Plane,
            "cube" => Shape::Cube,
            "torus" => {
                allowed.extend(["segments", "sides", "major_radius", "minor_radius"]);
                let major_radius = self.number(&p.key("major_radius"), o.major_radius.unwrap_or(1.0), 1e-4, 1e4)?;
                let minor_radius = self.number(&p.key("minor_radius"), o.minor_radius.unwrap_or(0.35), 1e-4, 1e4)?;
                Shape::Torus {
                    major_radius,
                    minor_radius,
                    segments: int("segments", o.segments, 48, 3, 2048)?,
                    sides: int("sides", o.sides, 24, 3, 2048)?,
                }
            }
            _ => {
                allowed.push("path");
                let Some(rel) = &o.path else {
                    return Err(self.err(
                        &p.key("path"),
                        Target::Key,
                        "shape `mesh` needs `path`",
                        Some("add `path = \"model.obj\"` (relative to the lesson file)".into()),
                    ));
                };
                let full = self.file.parent().unwrap_or(Path::new(".")).join(rel);
                if !full.is_file() {
                    // Same form as an OBJ that does not load: `path`: the file as written: what.
                    let what = if full.is_dir() { "is a folder, not a mesh file" } else { "mesh file not found" };
                    return Err(self.err(
                        &p.key("path"),
                        Target::Value,
                        format!("{rel}: {what} (looked for {})", std::path::absolute(&full).unwrap_or_else(|_| full.clone()).display()),
                        Some(
                            "the path is relative to the lesson file's folder; give a Wavefront OBJ file, e.g. path = \"meshes/bunny.obj\""
                                .into(),
                        ),
                    ));
                }
                Shape::Mesh { path: full }
            }
        };
        for (key, set) in [
            ("segments", o.segments.is_some()),
            ("rings", o.rings.is_some()),
            ("subdivisions", o.subdivisions.is_some()),
            ("sides", o.sides.is_some()),
            ("major_radius", o.major_radius.is_some()),
            ("minor_radius", o.minor_radius.is_some()),
            ("path", o.path.is_some()),
        ] {
            if set && !allowed.contains(&key) {
                self.unused(p, key, &Some(()), &why)?;
            }
        }
        let material = materials.iter().position(|m| m.name == o.material).ok_or_else(|| {
            let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
            let hint = match suggest(&o.material, &names) {
                Some(s) => format!("did you mean `{s}`? Defined: {}", names.join(", ")),
                None if names.is_empty() => format!("define it with a [material.{}] table", o.material),
                None => format!("defined materials: {}", names.join(", ")),
            };
            self.err(&p.key("material"), Target::Value, format!("no material named `{}`", o.material), Some(hint))
        })?;
        let translate = o.translate.map_or(Ok(Vec3::ZERO), |v| self.vec3(&p.key("translate"), v, -1e6, 1e6))?;
        let rot = o.rotate_deg.map_or(Ok(Vec3::ZERO), |v| self.vec3(&p.key("rotate_deg"), v, -1e5, 1e5))?;
        let scale = match o.scale {
            Some(s) => self.color(&p.key("scale"), s, 1e-6, 1e6).map_err(|mut e| {
                e.hint = Some("scale must be positive; mirror an object with rotate_deg instead".into());
                e
            })?,
            None => Vec3::ONE,
        };
        // Rotate about x, then y, then z: R = Rz·Ry·Rx.
        let rotation = Quat::from_euler(EulerRot::ZYX, rot.z.to_radians(), rot.y.to_radians(), rot.x.to_radians());
        let transform = Affine3A::from_scale_rotation_translation(scale, rotation, translate);
        Ok(ObjectSpec { shape, transform, material })
    }

    fn light(&self, p: &KeyPath, l: &RawLight) -> R<Light> {
        #[derive(Clone, Copy, PartialEq)]
        enum K {
            Directional,
            Point,
            Spot,
            Ambient,
        }
        let kind = self.choice(
            &p.key("kind"),
            &l.kind,
            &[("directional", K::Directional), ("point", K::Point), ("spot", K::Spot), ("ambient", K::Ambient)],
        )?;
        let color = l.color.map_or(Ok(Vec3::ONE), |c| self.color(&p.key("color"), c, 0.0, 1e6))?;
        let intensity = l.intensity.map_or(Ok(1.0), |v| self.number(&p.key("intensity"), v, 0.0, 1e9))?;
        let radiance = color * intensity;
        let name = l.kind.as_str();
        let article = if matches!(kind, K::Ambient) { "an" } else { "a" };
        let why = format!("by {article} `{name}` light");
        let need = |key: &str, v: Option<[f64; 3]>| -> R<[f64; 3]> {
            v.ok_or_else(|| {
                self.err(&p.key(key), Target::Key, format!("a `{name}` light needs `{key}`"), Some(format!("add `{key} = [x, y, z]`")))
            })
        };
        if kind != K::Spot {
            self.unused(p, "exponent", &l.exponent, &why)?;
            self.unused(p, "cutoff_deg", &l.cutoff_deg, &why)?;
        }
        if matches!(kind, K::Directional | K::Ambient) {
            self.unused(p, "position", &l.position, &why)?;
            self.unused(p, "attenuation", &l.attenuation, &why)?;
        }
        if matches!(kind, K::Point | K::Ambient) {
            self.unused(p, "direction", &l.direction, &why)?;
        }
        if kind == K::Ambient {
            self.unused(p, "ambient", &l.ambient, "by an `ambient` light (its colour is its ambient part)")?;
        }
        let attenuation = match l.attenuation {
            Some(a) => {
                let a = self.vec3(&p.key("attenuation"), a, 0.0, 1e6)?;
                if a == Vec3::ZERO {
                    return Err(self.err(
                        &p.key("attenuation"),
                        Target::Value,
                        "[0, 0, 0] divides by zero",
                        Some("use [1, 0, 0] for no attenuation, [0, 1, 0] for 1/r, [0, 0, 1] for 1/r²".into()),
                    ));
                }
                a
            }
            None => Vec3::X,
        };
        let ambient = match (kind, l.ambient) {
            (K::Ambient, _) => radiance,
            (_, Some(c)) => self.color(&p.key("ambient"), c, 0.0, 1e6)?,
            (_, None) => Vec3::ZERO,
        };
        let kind = match kind {
            K::Directional => LightKind::Directional { direction: self.direction(&p.key("direction"), need("direction", l.direction)?)? },
            K::Point => LightKind::Point { position: self.vec3(&p.key("position"), need("position", l.position)?, -1e6, 1e6)? },
            K::Spot => LightKind::Spot {
                position: self.vec3(&p.key("position"), need("position", l.position)?, -1e6, 1e6)?,
                direction: self.direction(&p.key("direction"), need("direction", l.direction)?)?,
                exponent: l.exponent.map_or(Ok(1.0), |v| self.number(&p.key("exponent"), v, 0.0, 1e6))?,
                cos_cutoff: match l.cutoff_deg {
                    Some(v) => self.number(&p.key("cutoff_deg"), v, 0.0, 180.0)?.to_radians().cos(),
                    None => -1.0,
                },
            },
            K::Ambient => LightKind::Ambient,
        };
        Ok(Light { kind, radiance, ambient, attenuation })
    }

    fn render(&self, p: &KeyPath, r: &RawRender) -> R<RenderSettings> {
        let d = RenderSettings::default();
        Ok(RenderSettings {
            interpolation: match &r.interpolation {
                Some(s) => self.choice(
                    &p.key("interpolation"),
                    s,
                    &[("flat", Interpolation::Flat), ("gouraud", Interpolation::Gouraud), ("phong", Interpolation::Phong)],
                )?,
                None => d.interpolation,
            },
            normals: match &r.normals {
                Some(s) => self.choice(
                    &p.key("normals"),
                    s,
                    &[("average", NormalWeighting::Average), ("area", NormalWeighting::Area), ("angle", NormalWeighting::Angle)],
                )?,
                None => d.normals,
            },
            aa: match r.aa {
                Some(v) => self.integer(&p.key("aa"), v, 1, MAX_AA)?,
                None => d.aa,
            },
            exposure: match r.exposure {
                Some(v) => self.number(&p.key("exposure"), v, -20.0, 20.0)?,
                None => d.exposure,
            },
            tonemap: match &r.tonemap {
                Some(s) => self.choice(
                    &p.key("tonemap"),
                    s,
                    &[("clamp", Tonemap::Clamp), ("reinhard", Tonemap::Reinhard), ("aces", Tonemap::Aces)],
                )?,
                None => d.tonemap,
            },
            cull: match &r.cull {
                Some(s) => self.choice(&p.key("cull"), s, &[("back", Cull::Back), ("none", Cull::None)])?,
                None => d.cull,
            },
        })
    }
}

/// The names of the `[material.NAME]` tables of a parsed lesson.
fn material_names(table: &toml::Table) -> Vec<String> {
    table.get("material").and_then(toml::Value::as_table).map(|m| m.keys().cloned().collect()).unwrap_or_default()
}

/// The keys a model reads besides `model`, `ambient` and `emission` (`None`: not a model).
fn model_keys(model: &str) -> Option<&'static [&'static str]> {
    Some(match model {
        "lambert" => &["diffuse"],
        "phong" | "blinn_phong" => &["diffuse", "specular", "shininess"],
        "diffuse" => &["diffuse"],
        "oren_nayar" => &["diffuse", "sigma_deg", "variant"],
        "cook_torrance" => &["ndf", "masking", "fresnel", "ior", "eta", "k", "roughness", "alpha", "specular", "diffuse"],
        "principled" => &[
            "base_color",
            "metallic",
            "roughness",
            "specular",
            "specular_tint",
            "sheen",
            "sheen_tint",
            "clearcoat",
            "clearcoat_gloss",
            "subsurface",
            "anisotropic",
        ],
        "normalized_phong" | "normalized_blinn_phong" | "unnormalized_phong" => &["diffuse", "specular", "shininess"],
        _ => return None,
    })
}

/// For an unknown key at `path` inside a material, light or object: the entry's variant
/// (`model `phong``) and the keys it reads, from the entry's `model`, `kind` or `shape`.
fn variant_keys(table: &toml::Table, path: &KeyPath) -> Option<(String, Vec<&'static str>)> {
    let [Segment::Key(section), entry, Segment::Key(_)] = &path.0[..] else { return None };
    let get = |t: &toml::Table, k: &str| t.get(k).and_then(toml::Value::as_str).map(str::to_string);
    let entry_table = match (section.as_str(), entry) {
        ("material", Segment::Key(name)) => table.get("material")?.as_table()?.get(name)?.as_table()?,
        ("light" | "object", Segment::Index(i)) => table.get(section.as_str())?.as_array()?.get(*i)?.as_table()?,
        _ => return None,
    };
    match section.as_str() {
        "material" => {
            let model = get(entry_table, "model")?;
            let own = model_keys(&model)?;
            let keys = ["model"].into_iter().chain(["ambient"]).chain(own.iter().copied()).chain(["emission"]).collect();
            Some((format!("model `{model}`"), keys))
        }
        "light" => {
            let kind = get(entry_table, "kind")?;
            let own: &[&str] = match kind.as_str() {
                "directional" => &["direction", "ambient"],
                "point" => &["position", "attenuation", "ambient"],
                "spot" => &["position", "direction", "attenuation", "exponent", "cutoff_deg", "ambient"],
                "ambient" => &[],
                _ => return None,
            };
            Some((format!("a `{kind}` light"), ["kind", "color", "intensity"].into_iter().chain(own.iter().copied()).collect()))
        }
        _ => {
            let shape = get(entry_table, "shape")?;
            let own: &[&str] = match shape.as_str() {
                "uv_sphere" => &["segments", "rings"],
                "icosphere" => &["subdivisions"],
                "plane" | "cube" => &[],
                "torus" => &["major_radius", "minor_radius", "segments", "sides"],
                "mesh" => &["path"],
                _ => return None,
            };
            let keys = ["shape", "material"].into_iter().chain(own.iter().copied()).chain(["translate", "rotate_deg", "scale"]).collect();
            Some((format!("shape `{shape}`"), keys))
        }
    }
}

/// The keys serde knows for `T` (read from its unknown-field error, so never out of date).
fn schema_fields<T: serde::de::DeserializeOwned>() -> Vec<String> {
    let mut probe = toml::Table::new();
    probe.insert("\u{1}".into(), toml::Value::Integer(0));
    match toml::Value::Table(probe).try_into::<T>() {
        Err(e) => e.message().split('`').skip(3).step_by(2).map(str::to_string).collect(),
        Ok(_) => Vec::new(),
    }
}

/// Checks a figure's `vary` path against the lesson before any cell is built: the
/// section, the material name or the light/object index, and the key must exist, so the
/// error points at `vary` (not at a value) with a did-you-mean.
fn check_vary(key: &KeyPath, raw: &RawLesson) -> Result<(), (String, String)> {
    let segs = &key.0;
    let unknown = |got: &str, allowed: Vec<String>, place: &str| {
        let names: Vec<&str> = allowed.iter().map(String::as_str).collect();
        let hint = match suggest(got, &names) {
            Some(s) => format!("did you mean `{s}`? Keys allowed {place}: {}", names.join(", ")),
            None => format!("keys allowed {place}: {}", names.join(", ")),
        };
        Err((format!("unknown key `{got}`"), hint))
    };
    let Some(Segment::Key(section)) = segs.first() else {
        return Err(("a key path starts with a table name".into(), "e.g. \"material.plastic.shininess\"".into()));
    };
    let key_at = |i: usize| match segs.get(i) {
        Some(Segment::Key(k)) => Some(k.as_str()),
        _ => None,
    };
    let check_field = |i: usize, fields: Vec<String>, place: &str| match key_at(i) {
        Some(k) if !fields.iter().any(|f| f == k) => unknown(k, fields, place),
        _ => Ok(()),
    };
    let in_list = |len: usize, what: &str| -> Result<(), (String, String)> {
        match segs.get(1) {
            None => Ok(()),
            Some(Segment::Index(n)) if *n < len => Ok(()),
            Some(Segment::Index(n)) => {
                let has = match len {
                    0 => "no entries".to_string(),
                    1 => "1 entry (index 0)".to_string(),
                    _ => format!("{len} entries (indices 0 to {})", len - 1),
                };
                Err((format!("`{section}` has {has}, so there is no `{section}.{n}`"), format!("count {what} from 0 in file order")))
            }
            Some(Segment::Key(k)) => {
                Err((format!("`{section}` is a list: `{k}` is not an index"), format!("e.g. \"{section}.0.{}\"", key_at(2).unwrap_or(k))))
            }
        }
    };
    match section.as_str() {
        // `vary = "material"` replaces every material with each value (a table of tables).
        "material" if segs.len() == 1 => Ok(()),
        "material" => {
            let Some(Segment::Key(name)) = segs.get(1) else {
                return Err(("`material` holds named tables".into(), "e.g. \"material.plastic.shininess\"".into()));
            };
            // `vary = "material.NAME"` with whole tables as values may define a material.
            if segs.len() > 2 && !raw.material.contains_key(name) {
                let names: Vec<&str> = raw.material.keys().map(String::as_str).collect();
                let hint = match suggest(name, &names) {
                    Some(s) => format!("did you mean `{s}`? Defined: {}", names.join(", ")),
                    None if names.is_empty() => "the lesson defines no materials".into(),
                    None => format!("defined materials: {}", names.join(", ")),
                };
                return Err((format!("the lesson has no material `{name}`"), hint));
            }
            check_field(2, schema_fields::<RawMaterial>(), "in a material")
        }
        "light" => in_list(raw.light.len(), "lights").and_then(|()| check_field(2, schema_fields::<RawLight>(), "in a light")),
        "object" => in_list(raw.object.len(), "objects").and_then(|()| check_field(2, schema_fields::<RawObject>(), "in an object")),
        "camera" => check_field(1, schema_fields::<RawCamera>(), "in [camera]"),
        "render" => check_field(1, schema_fields::<RawRender>(), "in [render]"),
        "scene" => check_field(1, schema_fields::<super::raw::RawSceneSettings>(), "in [scene]"),
        "lesson" | "figure" => Ok(()),
        other => unknown(other, schema_fields::<RawLesson>(), "at the top level"),
    }
}

/// The last key of a path (`shininess` in `material.plastic.shininess`, `size` in `camera.size.0`).
fn last_key(path: &KeyPath) -> Option<&str> {
    path.0.iter().rev().find_map(|s| match s {
        Segment::Key(k) => Some(k.as_str()),
        Segment::Index(_) => None,
    })
}

/// What a key means and a typical value, for hints on wrong values; `None` for keys whose
/// message says enough.
fn key_help(path: &KeyPath) -> Option<String> {
    let section = match path.0.first() {
        Some(Segment::Key(k)) => k.as_str(),
        _ => return None,
    };
    let key = last_key(path)?;
    let coefficient = |symbol: &str| {
        format!(
            "`{key}` is {symbol}, a reflectance from 0 to 1 per channel: one number (0.8) or [r, g, b] such as [0.8, 0.2, 0.2]; to brighten the image, raise the light's intensity"
        )
    };
    let unit_weight = || format!("`{key}` is a weight from 0 to 1 (Disney's principled parameters); 0 turns it off");
    let text = match (section, key) {
        ("render", "aa") => {
            "aa is supersamples per pixel side (aa² samples per pixel, averaged); 2 or 4 smooths edges, 1 is fastest".into()
        }
        ("render", "exposure") => "exposure is in stops: +1 doubles the brightness, -1 halves it, 0 leaves it".into(),
        ("camera", "size") => "size is [width, height] in pixels, e.g. [512, 512] (or --size 512x512)".into(),
        ("camera", "fov_deg") => "fov_deg is the vertical field of view in degrees; 30 to 60 looks natural (default 40)".into(),
        ("camera", "near") => "near is the clipping distance in front of the eye; 0.05 suits most scenes".into(),
        ("camera", "background") => "background is a linear RGB colour: one number for a grey (0.05) or [r, g, b]".into(),
        ("camera", "position" | "look_at" | "up") => format!("`{key}` is a point or direction [x, y, z], e.g. [0, 1, 5]"),
        ("object", "segments") => "segments are the columns around the y axis; 32 to 64 looks round (default 32, torus 48)".into(),
        ("object", "rings") => "rings are the latitude bands from pole to pole; 16 to 32 looks round (default 16)".into(),
        ("object", "sides") => "sides are the segments around the torus's tube; 16 to 32 looks round (default 24)".into(),
        ("object", "subdivisions") => "each subdivision splits every triangle in four (20·4ⁿ triangles); 3 looks round (default 3)".into(),
        ("object", "major_radius" | "minor_radius") => format!("`{key}` is a length in scene units (defaults 1 and 0.35)"),
        ("object", "translate") => "translate is [x, y, z] in scene units, e.g. [0, 1, 0]".into(),
        ("object", "rotate_deg") => "rotate_deg is [x, y, z] in degrees, e.g. [0, 45, 0]".into(),
        ("object", "scale") => "scale is one positive number or [x, y, z], e.g. 2; mirror an object with rotate_deg instead".into(),
        ("material", "diffuse") => coefficient("K_diff (or the albedo ρ)"),
        ("material", "ambient") => coefficient("K_amb"),
        ("material", "specular") => coefficient("K_spec"),
        ("material", "base_color") => coefficient("the base colour"),
        ("material", "shininess") => {
            "shininess is the exponent K_shi: 1 to 10 is a broad highlight, 100 or more a small sharp one; 32 is typical".into()
        }
        ("material", "emission") => {
            "emission is light the surface gives off, a linear colour from 0 up: 0 for none, e.g. [1, 0.8, 0.5]".into()
        }
        ("material", "roughness") => "roughness goes from 0 (a mirror) to 1 (matte); α = roughness², 0.3 to 0.6 is typical".into(),
        ("material", "alpha") => "alpha is the microfacet α from 0 to 1 (α = roughness²), e.g. 0.25".into(),
        ("material", "ior") => "ior is the relative index of refraction η: 1.5 for glass and plastic, 1.33 for water".into(),
        ("material", "eta" | "k") => {
            "a conductor's complex index per channel, e.g. gold: eta = [0.143, 0.374, 1.442], k = [3.983, 2.385, 1.603]".into()
        }
        ("material", "sigma_deg") => "sigma_deg is the facet slope deviation σ in degrees: 0 is Lambert, 20 to 40 a rough clay".into(),
        (
            "material",
            "metallic" | "specular_tint" | "sheen" | "sheen_tint" | "clearcoat" | "clearcoat_gloss" | "subsurface" | "anisotropic",
        ) => unit_weight(),
        ("light", "intensity") => {
            "intensity scales the light's colour: 1 is the default; a point light with 1/r² falloff needs more, e.g. 10".into()
        }
        ("light", "color") => "color is a linear RGB colour: 1 for white or [r, g, b], e.g. [1, 0.9, 0.8]".into(),
        ("light", "ambient") => "this light's ambient part L_amb, a linear colour, e.g. 0.05".into(),
        ("light", "position") => "position is where the light is, [x, y, z], e.g. [2, 3, 4]".into(),
        ("light", "direction") => "direction is the way the light travels, [x, y, z]: [0, -1, 0] shines straight down".into(),
        ("light", "attenuation") => {
            "attenuation is [S_c, S_l, S_q] in d = 1/(S_c + S_l r + S_q r²): [1, 0, 0] is none, [0, 0, 1] is 1/r²".into()
        }
        ("light", "exponent") => "exponent is the spot's L_exp: 1 is a soft cone, 20 or more a tight one".into(),
        ("light", "cutoff_deg") => "cutoff_deg is the spot cone's half-angle in degrees, e.g. 30".into(),
        ("scene", "ambient") => "ambient is L_glob, the global ambient light, a linear colour; 0.05 to 0.2 lifts the shadows".into(),
        ("figure", "cell") => "cell is [width, height] of each cell in pixels, e.g. [256, 256]".into(),
        ("figure", "incidence") => "incidence lists angles from the normal in degrees, e.g. [30, 60]".into(),
        ("figure", "repeat") => "repeat is the timed runs per rung (the median is shown), e.g. 5".into(),
        _ => return None,
    };
    Some(text)
}

/// The hint for a value out of range: what the key means, else the range again.
fn range_hint(path: &KeyPath, lo: f64, hi: f64) -> String {
    key_help(path).unwrap_or_else(|| {
        format!("use a value from {lo} to {hi} (see the `{}` row in docs/lesson-format.md)", last_key(path).unwrap_or("key"))
    })
}

/// A duplicate key: which one, where it was first set, and how to fix it. `span` is the
/// second occurrence (a key, or a table header's last part).
fn duplicate_key(text: &str, span: std::ops::Range<usize>) -> (String, String) {
    let generic = ("not valid TOML: duplicate key".to_string(), "a key can appear only once in a table; remove one of the two".to_string());
    let Some(raw) = text.get(span.clone()) else { return generic };
    let name = raw.trim().trim_matches(['"', '\'']).to_string();
    if name.is_empty() {
        return generic;
    }
    let line_start = text[..span.start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[span.start..].find('\n').map_or(text.len(), |i| span.start + i);
    let this_line = text[line_start..line_end].trim();
    let lines: Vec<&str> = text.lines().collect();
    let here = text[..span.start].matches('\n').count();
    let is_header = |l: &str| l.trim_start().starts_with('[');
    if is_header(this_line) {
        // `[material.plastic]` twice: the header text identifies the table.
        let header = this_line.split('#').next().unwrap_or("").trim();
        let first = lines[..here].iter().position(|l| l.split('#').next().unwrap_or("").trim() == header);
        let at = first.map_or(String::new(), |i| format!(" (first on line {})", i + 1));
        let inner = header.trim_start_matches('[').trim_end_matches(']');
        return (
            format!("not valid TOML: duplicate key: table `{header}` is defined twice{at}"),
            format!("put all the keys of `{inner}` under one `{header}` header"),
        );
    }
    // A key: find its table (the last header above) and the earlier line setting it.
    let table_start = lines[..here].iter().rposition(|l| is_header(l)).map_or(0, |i| i + 1);
    let table = lines[..here].iter().rev().find(|l| is_header(l)).map(|l| l.split('#').next().unwrap_or("").trim().to_string());
    let sets_key = |l: &str| {
        let t = l.trim_start();
        let t = t.strip_prefix(raw.trim()).or_else(|| t.strip_prefix(name.as_str()));
        t.is_some_and(|rest| rest.trim_start().starts_with(['=', '.']))
    };
    let first = (table_start..here).find(|&i| sets_key(lines[i]));
    let place = table.map_or("at the top level".to_string(), |t| format!("in `{t}`"));
    let at = first.map_or(String::new(), |i| format!(", first set on line {}", i + 1));
    (
        format!("not valid TOML: duplicate key `{name}` {place}{at}"),
        format!("a key can appear only once in a table; keep one of the two `{name}` lines"),
    )
}

/// A hint for the TOML syntax errors beginners meet most; the reference otherwise.
fn toml_hint(message: &str) -> &'static str {
    if message.contains("must be quoted") {
        "text values need quotes, e.g. model = \"phong\""
    } else if message.contains("duplicate key") {
        "a key can appear only once in a table; remove one of the two"
    } else {
        "see docs/lesson-format.md for the syntax of a lesson"
    }
}

/// The closest allowed name when it is close enough to be a typo, differs only in case
/// (`ggx` → `GGX`), or is an allowed one without its unit suffix (`fov` → `fov_deg`,
/// `rotate` → `rotate_deg`).
pub(crate) fn suggest<'s>(got: &str, allowed: &[&'s str]) -> Option<&'s str> {
    if let Some(same) = allowed.iter().find(|a| a.eq_ignore_ascii_case(got)) {
        return Some(same);
    }
    let close = allowed
        .iter()
        .map(|a| (strsim::damerau_levenshtein(got, a), *a))
        .filter(|(d, a)| *d <= 2.max(a.len() / 4) && *d < a.len())
        .min_by_key(|(d, _)| *d)
        .map(|(_, a)| a);
    close.or_else(|| allowed.iter().copied().find(|a| got.len() >= 3 && a.strip_prefix(got).is_some_and(|rest| rest.starts_with('_'))))
}
