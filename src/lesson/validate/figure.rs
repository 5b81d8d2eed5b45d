//! `[[figure]]` tables: each kind's keys, its axes and the `vary` paths they name.

use super::hints::{schema_fields, suggest};
use super::{R, Validator};
use crate::lesson::figure::{
    Axis, DEFAULT_REPEAT, FigureBody, FigureKind, FigureSpec, LadderKind, MAX_CELLS, MAX_PROBES, MAX_REPEAT, Normals, parse_range,
};
use crate::lesson::kinds::choices;
use crate::lesson::path::{KeyPath, Segment};
use crate::lesson::raw::{
    RawAxis, RawCamera, RawEnvironment, RawFigure, RawFog, RawLesson, RawLight, RawMaterial, RawObject, RawProbe, RawRender,
    RawSceneSettings,
};
use crate::lesson::settings::Solver;
use crate::lesson::spans::Target;
use crate::shading::components::Layer;
use crate::shading::cook_torrance::Terms;
use crate::shading::material::Material;

impl Validator<'_> {
    /// Refuses the first of `keys` that figure `f` sets: "`key` is not used {why}".
    pub(super) fn refuse_figure_keys(&self, path: &KeyPath, f: &RawFigure, keys: &[&str], why: &str) -> R<()> {
        match keys.iter().find(|k| f.is_set(k)) {
            Some(key) => self.unused(path, key, &Some(()), why),
            None => Ok(()),
        }
    }

    pub(super) fn figure(
        &self,
        p: &KeyPath,
        f: &RawFigure,
        earlier: &[FigureSpec],
        raw: &RawLesson,
        materials: &[Material],
        size: Option<(u32, u32)>,
    ) -> R<FigureSpec> {
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
        let kind = self.choice(&p.key("kind"), &f.kind, &choices(FigureKind::ALL, FigureKind::name))?;
        if !matches!(kind, FigureKind::Compare | FigureKind::Sweep) {
            let why = format!("by a `{}` figure (only `compare` and `sweep` add a difference row)", kind.name());
            self.refuse_figure_keys(p, f, &["diff"], &why)?;
        }
        if kind == FigureKind::Bssrdf {
            return self.bssrdf_figure(p, f, materials);
        }
        if kind == FigureKind::Walk {
            return self.walk_figure(p, f);
        }
        self.refuse_figure_keys(
            p,
            f,
            &["scattering_albedo", "walks", "thickness"],
            "by a figure other than `walk` (it walks light through a slab)",
        )?;
        if kind == FigureKind::Bsdf {
            return self.bsdf_figure(p, f);
        }
        self.refuse_figure_keys(p, f, &["ior", "roughness"], "by a figure other than `bsdf` (it draws a rough dielectric)")?;
        if matches!(kind, FigureKind::Lobe | FigureKind::Albedo) {
            return self.chart_figure(p, f, kind, materials);
        }
        if kind == FigureKind::Cost {
            return self.cost_figure(p, f);
        }
        if kind == FigureKind::Convergence {
            return self.convergence_figure(p, f);
        }
        if kind == FigureKind::Probe {
            return self.probe_figure(p, f, size, raw);
        }
        self.refuse_figure_keys(p, f, &["pixels"], "by a figure other than `probe` (it explains pixels)")?;
        self.refuse_figure_keys(p, f, &["solvers", "tolerance"], "by a figure other than `convergence` (it plots radiosity solvers)")?;
        self.refuse_figure_keys(
            p,
            f,
            &["ladder", "repeat"],
            &format!("by a `{}` figure (only `cost` figures measure a ladder)", kind.name()),
        )?;
        self.refuse_figure_keys(
            p,
            f,
            &["materials", "lights", "incidence", "azimuth_deg", "swap", "terms"],
            "by a figure of variants (only `lobe` and `albedo` plot materials)",
        )?;
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
        // What the cells vary, before the keys every figure of variants reads.
        enum Axes {
            Row(Axis),
            Grid(Axis, Axis),
            Split,
        }
        let axes = match kind {
            FigureKind::Compare | FigureKind::Sweep => {
                self.unused(p, "rows", &f.rows, &why)?;
                self.unused(p, "cols", &f.cols, &why)?;
                Axes::Row(one_axis(&f.vary, &f.values)?)
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
                Axes::Grid(
                    self.axis(&p.key("rows"), &r.vary, &r.values, r.labels.as_ref(), raw)?,
                    self.axis(&p.key("cols"), &c.vary, &c.values, c.labels.as_ref(), raw)?,
                )
            }
            FigureKind::Lobe
            | FigureKind::Albedo
            | FigureKind::Cost
            | FigureKind::Convergence
            | FigureKind::Probe
            | FigureKind::Walk
            | FigureKind::Bsdf
            | FigureKind::Bssrdf => {
                unreachable!("chart and cost figures return above")
            }
            FigureKind::Split => {
                self.refuse_figure_keys(p, f, &["vary", "values", "rows", "cols", "labels"], &why)?;
                Axes::Split
            }
        };
        let cells = match &axes {
            Axes::Row(cols) => cols.values.len(),
            Axes::Grid(rows, cols) => rows.values.len() * cols.values.len(),
            Axes::Split => 1,
        };
        if cells > MAX_CELLS {
            return Err(self.err(p, Target::Key, format!("{cells} cells is more than {MAX_CELLS}"), Some("use fewer values".into())));
        }
        // A split shows `layers` (ambient, diffuse, specular, total by default); the other kinds one `layer`.
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
        let layer = match (&f.layer, kind) {
            (Some(_), FigureKind::Split) => {
                return Err(self.err(
                    &p.key("layer"),
                    Target::Key,
                    "`layer` is not used by a `split` figure",
                    Some("use `layers = [...]`".into()),
                ));
            }
            (Some(name), _) => self.choice(&p.key("layer"), name, &Layer::ALL.map(|l| (l.name(), l)))?,
            (None, _) => Layer::Total,
        };
        let cell = self.cell_size(p, f)?;
        let normals = match &f.normals {
            Some(n) => {
                Some(self.choice(&p.key("normals"), n, &[("face", Normals::Face), ("vertex", Normals::Vertex), ("both", Normals::Both)])?)
            }
            None => None,
        };
        let body = match axes {
            Axes::Row(cols) if kind == FigureKind::Compare => FigureBody::Compare { cols, layer, normals },
            Axes::Row(cols) => FigureBody::Sweep { cols, layer, normals },
            Axes::Grid(rows, cols) => FigureBody::Grid { rows, cols, layer, normals },
            Axes::Split => FigureBody::Split { layers, normals },
        };
        self.spec(p, f, cell, body, f.diff == Some(true))
    }

    /// A `lobe` or `albedo` figure: physically based materials plotted, no variants.
    fn chart_figure(&self, p: &KeyPath, f: &RawFigure, kind: FigureKind, defined: &[Material]) -> R<FigureSpec> {
        let why = format!("by a `{}` figure (it plots `materials`)", kind.name());
        let variant_keys =
            ["vary", "values", "rows", "cols", "layers", "layer", "cell", "normals", "ladder", "repeat", "solvers", "tolerance"];
        self.refuse_figure_keys(p, f, &variant_keys, &why)?;
        if kind == FigureKind::Albedo {
            self.unused(p, "lights", &f.lights, "by an `albedo` figure (only `lobe` figures plot spot lights)")?;
            self.unused(p, "incidence", &f.incidence, "by an `albedo` figure (it sweeps every angle)")?;
            self.unused(p, "azimuth_deg", &f.azimuth_deg, "by an `albedo` figure (it integrates over every direction)")?;
            self.unused(p, "swap", &f.swap, "by an `albedo` figure (only `lobe` figures exchange l and v)")?;
            self.unused(p, "terms", &f.terms, "by an `albedo` figure (only `lobe` figures draw partial products)")?;
        }
        if let Some(list) = &f.lights {
            let why = "by a `lobe` figure of `lights` (it plots the spots' I(θ))";
            self.unused(p, "materials", &f.materials, why)?;
            self.unused(p, "labels", &f.labels, why)?;
            self.unused(p, "incidence", &f.incidence, why)?;
            self.unused(p, "azimuth_deg", &f.azimuth_deg, why)?;
            self.unused(p, "swap", &f.swap, why)?;
            self.unused(p, "terms", &f.terms, why)?;
            if list.is_empty() {
                return Err(self.err(
                    &p.key("lights"),
                    Target::Value,
                    "no lights",
                    Some("give e.g. `lights = [0, 1]` (indices of [[light]] tables)".into()),
                ));
            }
            let mut lights = Vec::with_capacity(list.len());
            for (i, v) in list.iter().enumerate() {
                lights.push(self.integer(&p.key("lights").index(i), *v, 0, 1 << 20)? as usize);
            }
            let body = FigureBody::Distribution { lights };
            return self.spec(p, f, None, body, false);
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
                Some(m) if m.brdf().is_none() && kind == FigureKind::Albedo => {
                    return Err(self.err(
                        &at,
                        Target::Value,
                        format!(
                            "`{name}` is a classic material ({}): an `{}` figure plots physically based BRDFs",
                            m.family_name(),
                            kind.name()
                        ),
                        Some(format!("{choose} (the classic models have no π and no units)")),
                    ));
                }
                Some(_) => {}
            }
        }
        let legend = match self.texts(&p.key("labels"), f.labels.as_ref())? {
            Some(l) if l.len() != materials.len() => {
                return Err(self.err(
                    &p.key("labels"),
                    Target::Value,
                    format!("{} labels for {} materials", l.len(), materials.len()),
                    Some("give one legend entry per material, in the order of `materials`".into()),
                ));
            }
            Some(l) => l,
            None => materials.clone(),
        };
        let body = if kind == FigureKind::Albedo {
            FigureBody::Albedo { materials, legend }
        } else {
            let mut incidence = Vec::new();
            match &f.incidence {
                Some(list) => {
                    for (i, a) in list.iter().enumerate() {
                        incidence.push(self.number(&p.key("incidence").index(i), *a, 0.0, 89.9)? as f64);
                    }
                }
                None => incidence.push(30.0),
            }
            let mut azimuth = Vec::new();
            for (i, a) in f.azimuth_deg.iter().flatten().enumerate() {
                azimuth.push(self.number(&p.key("azimuth_deg").index(i), *a, -180.0, 180.0)? as f64);
            }
            if f.azimuth_deg.as_ref().is_some_and(|a| a.is_empty() || a.len() > 8) {
                return Err(self.err(
                    &p.key("azimuth_deg"),
                    Target::Value,
                    "give 1 to 8 azimuths",
                    Some("e.g. `azimuth_deg = [0, 45, 90]`: 0 is the plane of incidence, 90 the plane across it".into()),
                ));
            }
            let mut terms = Vec::new();
            for (i, t) in f.terms.iter().flatten().enumerate() {
                let at = p.key("terms").index(i);
                let options = Terms::ALL.map(|t| (t.name(), t));
                terms.push(self.choice(&at, t, &options)?);
            }
            if f.terms.as_ref().is_some_and(|t| t.is_empty()) {
                return Err(self.err(
                    &p.key("terms"),
                    Target::Value,
                    "no terms",
                    Some("give e.g. `terms = [\"D\", \"DG\", \"DGF\"]`, or drop the key for the whole f".into()),
                ));
            }
            if !terms.is_empty() {
                for (i, name) in materials.iter().enumerate() {
                    let m = defined.iter().find(|m| &m.name == name).expect("checked above");
                    if !matches!(m.brdf(), Some(crate::shading::brdf::Brdf::CookTorrance(_))) {
                        return Err(self.err(
                            &p.key("materials").index(i),
                            Target::Value,
                            format!("`{name}` is not a `cook_torrance` material: `terms` splits the Cook-Torrance numerator D G F"),
                            Some("plot only cook_torrance materials in this figure, or drop `terms`".into()),
                        ));
                    }
                }
            }
            FigureBody::Lobe { materials, legend, incidence, azimuth, swap: f.swap.unwrap_or(false), terms }
        };
        self.spec(p, f, None, body, false)
    }

    /// A `cost` figure: a ladder measured on the lesson, no variants.
    fn cost_figure(&self, p: &KeyPath, f: &RawFigure) -> R<FigureSpec> {
        let why = "by a `cost` figure (its rungs come from `ladder`)";
        let other_keys = [
            "vary",
            "values",
            "rows",
            "cols",
            "labels",
            "layers",
            "layer",
            "materials",
            "incidence",
            "azimuth_deg",
            "swap",
            "terms",
            "normals",
            "solvers",
            "tolerance",
        ];
        self.refuse_figure_keys(p, f, &other_keys, why)?;
        let name = f.ladder.as_ref().ok_or_else(|| {
            self.err(
                p,
                Target::Key,
                "a `cost` figure needs `ladder`",
                Some(format!("add e.g. `ladder = \"interpolation\"` ({})", LadderKind::ALL.map(LadderKind::name).join(", "))),
            )
        })?;
        let options = LadderKind::ALL.map(|l| (l.name(), l));
        let ladder = self.choice(&p.key("ladder"), name, &options)?;
        let repeat = match f.repeat {
            Some(n) => self.integer(&p.key("repeat"), n, 1, MAX_REPEAT)? as usize,
            None => DEFAULT_REPEAT,
        };
        let cell = self.cell_size(p, f)?;
        let body = FigureBody::Cost { ladder, repeat };
        self.spec(p, f, cell, body, false)
    }

    /// A `convergence` figure: the residual of radiosity solvers, iteration by iteration.
    fn convergence_figure(&self, p: &KeyPath, f: &RawFigure) -> R<FigureSpec> {
        // `method = "radiosity"` is checked when the figure is made, so that `--set
        // render.method="raster"` still renders a radiosity lesson's image.
        let why = "by a `convergence` figure (it plots the radiosity solvers' residuals)";
        let other_keys = [
            "vary",
            "values",
            "rows",
            "cols",
            "labels",
            "layers",
            "layer",
            "cell",
            "materials",
            "lights",
            "incidence",
            "azimuth_deg",
            "swap",
            "terms",
            "normals",
            "ladder",
            "repeat",
        ];
        self.refuse_figure_keys(p, f, &other_keys, why)?;
        let options = Solver::ALL.map(|s| (s.name(), s));
        let solvers = match &f.solvers {
            None => Solver::ALL.to_vec(),
            Some(list) if list.is_empty() => {
                return Err(self.err(
                    &p.key("solvers"),
                    Target::Value,
                    "no solvers",
                    Some("give e.g. `solvers = [\"jacobi\", \"gauss_seidel\"]`, or drop the key for all three".into()),
                ));
            }
            Some(list) => {
                let mut out: Vec<Solver> = Vec::with_capacity(list.len());
                for (i, name) in list.iter().enumerate() {
                    let s = self.choice(&p.key("solvers").index(i), name, &options)?;
                    if out.contains(&s) {
                        return Err(self.err(
                            &p.key("solvers").index(i),
                            Target::Value,
                            format!("`{name}` is listed twice"),
                            Some("name each solver once".into()),
                        ));
                    }
                    out.push(s);
                }
                out
            }
        };
        // Strictly positive: at 0 a solver would run to its iteration cap.
        let tolerance = match f.tolerance {
            Some(t) => Some(self.number(&p.key("tolerance"), t, 1e-12, 1.0)?),
            None => None,
        };
        let body = FigureBody::Convergence { solvers, tolerance };
        self.spec(p, f, None, body, false)
    }

    /// A `probe` figure: pixels of the lesson's render explained. `size`: the camera's image
    /// size (`None` when the camera itself is invalid: its error is reported instead).
    fn probe_figure(&self, p: &KeyPath, f: &RawFigure, size: Option<(u32, u32)>, raw: &RawLesson) -> R<FigureSpec> {
        let why = "by a `probe` figure (it explains `pixels` of the lesson's own render)";
        let other_keys = [
            "rows",
            "cols",
            "layers",
            "layer",
            "cell",
            "materials",
            "lights",
            "incidence",
            "azimuth_deg",
            "swap",
            "terms",
            "normals",
            "ladder",
            "repeat",
            "solvers",
            "tolerance",
        ];
        self.refuse_figure_keys(p, f, &other_keys, why)?;
        let list = f.pixels.as_ref().ok_or_else(|| {
            self.err(
                p,
                Target::Key,
                "a `probe` figure needs `pixels`",
                Some("add e.g. `pixels = [[120, 80], [200, 150]]` (x, y from the image's top-left corner)".into()),
            )
        })?;
        if list.is_empty() || list.len() > MAX_PROBES {
            return Err(self.err(
                &p.key("pixels"),
                Target::Value,
                format!("{} pixels: a probe figure explains 1 to {MAX_PROBES}", list.len()),
                Some("give e.g. `pixels = [[120, 80]]`".into()),
            ));
        }
        let (w, h) = size.unwrap_or((u32::MAX, u32::MAX));
        let mut pixels = Vec::with_capacity(list.len());
        for (i, [x, y]) in list.iter().enumerate() {
            let at = p.key("pixels").index(i);
            if *x < 0 || *y < 0 || *x >= w as i64 || *y >= h as i64 {
                return Err(self.err(
                    &at,
                    Target::Value,
                    format!("pixel [{x}, {y}] is outside the {w}×{h} image"),
                    Some(format!("x must be 0 to {} and y 0 to {} (from the top-left corner, as in the PNG)", w - 1, h - 1)),
                ));
            }
            pixels.push((*x as u32, *y as u32));
        }
        // Optionally one panel per value of one key, the same pixels in each.
        let cols = match (&f.vary, &f.values) {
            (None, None) => {
                self.unused(p, "labels", &f.labels, "by a `probe` figure without `vary`")?;
                None
            }
            (Some(vary), Some(values)) => {
                let axis = self.axis(p, vary, values, f.labels.as_ref(), raw)?;
                if axis.values.len() > 4 {
                    return Err(self.err(
                        &p.key("values"),
                        Target::Value,
                        format!("{} panels: a probe figure shows at most 4", axis.values.len()),
                        Some("compare two to four values, e.g. `values = [\"phong\", \"gouraud\"]`".into()),
                    ));
                }
                Some(axis)
            }
            (Some(_), None) => {
                return Err(self.err(
                    &p.key("values"),
                    Target::Key,
                    "`vary` needs `values`",
                    Some("add e.g. `values = [\"phong\", \"gouraud\"]`".into()),
                ));
            }
            (None, Some(_)) => {
                return Err(self.err(
                    &p.key("vary"),
                    Target::Key,
                    "`values` needs `vary`",
                    Some("add e.g. `vary = \"render.interpolation\"`".into()),
                ));
            }
        };
        self.spec(p, f, None, FigureBody::Probe { pixels, cols }, false)
    }

    /// An axis: `vary` must be a dotted path, `values` an array or a range string.
    fn axis(&self, p: &KeyPath, vary: &str, values: &toml::Value, labels: Option<&Vec<toml::Value>>, raw: &RawLesson) -> R<Axis> {
        let labels = self.texts(&p.key("labels"), labels)?;
        let labels = labels.as_ref();
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
        "scene" => check_field(1, schema_fields::<RawSceneSettings>(), "in [scene]"),
        "fog" => check_field(1, schema_fields::<RawFog>(), "in [fog]"),
        "environment" => check_field(1, schema_fields::<RawEnvironment>(), "in [environment]"),
        "probe" => in_list(raw.probe.len(), "probes").and_then(|()| check_field(2, schema_fields::<RawProbe>(), "in a probe")),
        "lesson" | "figure" => Ok(()),
        other => unknown(other, schema_fields::<RawLesson>(), "at the top level"),
    }
}
