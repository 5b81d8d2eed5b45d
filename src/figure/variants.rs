//! A figure spec → a grid of override sets, each validated like `--set`, with labels
//! in the course's notation.

use crate::lesson::path::Segment;
use crate::lesson::spans::{self, Target};
use crate::lesson::{self, Axis, KeyPath, Lesson, LessonError, Location, Override};
use crate::render::Layer;

/// One cell of a figure: the overrides that make it and the lesson they give.
#[derive(Debug, Clone)]
pub struct Variant {
    /// Row index.
    pub row: usize,
    /// Column index.
    pub col: usize,
    /// The overrides on top of the base lesson's.
    pub sets: Vec<Override>,
    /// The validated lesson for this cell.
    pub lesson: Lesson,
}

/// A figure expanded into variants.
#[derive(Debug, Clone)]
pub struct Grid {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// Row labels (empty strings when the figure has one row).
    pub row_labels: Vec<String>,
    /// Column labels.
    pub col_labels: Vec<String>,
    /// Variants, row-major (a split has one).
    pub variants: Vec<Variant>,
}

/// What the cells of a figure of variants vary (the kinds that are not lobe, albedo or cost).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Layout<'a> {
    /// One row, a column per value (compare, sweep).
    Row(&'a Axis),
    /// A row per value of the first axis, a column per value of the second (grid).
    Grid(&'a Axis, &'a Axis),
    /// One render, a column per layer (split).
    Split(&'a [Layer]),
}

/// Expands `layout` on top of `base` (which keeps its own `--set`s); `extra` overrides
/// apply to every cell (e.g. the cell size).
///
/// # Errors
/// [`LessonError`] when a value does not validate; it points at the value in the
/// figure's `values` (or at the `--vary` argument when the axis came from the command line).
pub fn expand(base: &Lesson, layout: Layout<'_>, extra: &[Override]) -> Result<Grid, LessonError> {
    let (rows, cols) = match layout {
        Layout::Row(cols) => (None, Some(cols)),
        Layout::Grid(rows, cols) => (Some(rows), Some(cols)),
        Layout::Split(_) => (None, None),
    };
    let n_rows = rows.map_or(1, |a| a.values.len());
    let n_cols = cols.map_or(1, |a| a.values.len());
    let mut variants = Vec::with_capacity(n_rows * n_cols);
    for r in 0..n_rows {
        for c in 0..n_cols {
            let mut sets: Vec<Override> = base.overrides.iter().chain(extra).cloned().collect();
            let mut mine = Vec::new();
            for (axis, i) in [(rows, r), (cols, c)] {
                if let Some(a) = axis {
                    let o = value_override(a, i);
                    mine.push((a, i, o.clone()));
                    sets.push(o);
                }
            }
            let lesson = lesson::parse_cell(&base.source, &base.path, &sets).map_err(|e| relocate(e, base, &mine))?;
            variants.push(Variant { row: r, col: c, sets, lesson });
        }
    }
    let labels = |a: Option<&Axis>, n: usize| -> Vec<String> {
        match a {
            Some(a) => {
                (0..n).map(|i| a.labels.as_ref().map_or_else(|| base.lang.say(&label(&a.key, &a.values[i])), |l| l[i].clone())).collect()
            }
            None => vec![String::new(); n],
        }
    };
    // A split's columns are the layers of its one render, not variants.
    let (grid_cols, col_labels) = match layout {
        Layout::Split(layers) => (layers.len(), layers.iter().map(|l| base.lang.tr(layer_label(*l)).to_string()).collect()),
        Layout::Row(_) | Layout::Grid(..) => (n_cols, labels(cols, n_cols)),
    };
    Ok(Grid { rows: n_rows, cols: grid_cols, row_labels: labels(rows, n_rows), col_labels, variants })
}

/// The override for value `i` of an axis.
pub fn value_override(a: &Axis, i: usize) -> Override {
    Override { arg: format!("{}={}", a.key, show(&a.values[i])), path: a.key.clone(), value: a.values[i].clone() }
}

/// An error caused by a figure value points at that value in the file.
fn relocate(mut e: LessonError, base: &Lesson, mine: &[(&Axis, usize, Override)]) -> LessonError {
    let Location::Flag(arg) = &e.location else { return e };
    let Some((axis, i, o)) = mine.iter().find(|(_, _, o)| arg.strip_prefix("--set ") == Some(o.arg.as_str())) else { return e };
    if axis.origin.0.is_empty() {
        e.location = Location::Flag(format!("--vary {}", o.arg));
        return e;
    }
    let span = spans::find(&base.source, &axis.origin.index(*i), Target::Value);
    let (line, col) = spans::line_col(&base.source, span.start);
    e.location = Location::File { line, col };
    e.message = format!("figure value `{}` for `{}`: {}", show(&axis.values[*i]), axis.key, e.message);
    e
}

/// A TOML value as a person writes it: `50`, `0.3`, `gouraud`, `[1, 0, 0]`.
pub fn show(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Float(f) => format!("{f}"),
        toml::Value::Array(a) => format!("[{}]", a.iter().map(show).collect::<Vec<_>>().join(", ")),
        toml::Value::Table(t) => {
            let entries: Vec<String> = t.iter().map(|(k, v)| format!("{k} = {}", show_inline(v))).collect();
            format!("{{ {} }}", entries.join(", "))
        }
        other => other.to_string(),
    }
}

/// [`show`] with every float rounded to three significant figures, for labels: `2.21`, `10.8`, `256`.
fn show_rounded(v: &toml::Value) -> String {
    match v {
        toml::Value::Float(f) => sig3(*f),
        toml::Value::Array(a) => format!("[{}]", a.iter().map(show_rounded).collect::<Vec<_>>().join(", ")),
        other => show(other),
    }
}

/// `x` to three significant figures, trailing zeros dropped: 2.208 → `2.21`, 10.77 → `10.8`,
/// 0.5 → `0.5`, 256.0 → `256`; below 10⁻³ or from 10⁴ on, scientific: `1.23e-4`, `1.23e5`.
pub fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    // Round first, so 9.996 (→ 10.0) takes the exponent of the rounded value.
    let e = x.abs().log10().floor() as i32;
    let rounded: f64 = format!("{x:.2e}").parse().unwrap_or(x);
    let e = if rounded.abs() >= 10f64.powi(e + 1) { e + 1 } else { e };
    if !(-3..4).contains(&e) {
        let s = format!("{rounded:.2e}");
        let (m, exp) = s.split_once('e').unwrap_or((&s, "0"));
        return format!("{}e{exp}", trim_zeros(m));
    }
    let decimals = (2 - e).max(0) as usize;
    trim_zeros(&format!("{rounded:.decimals$}"))
}

/// `2.50` → `2.5`, `3.00` → `3`; integers untouched.
fn trim_zeros(s: &str) -> String {
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s.to_string() }
}

/// A value inside an inline table: strings quoted, as TOML writes them.
fn show_inline(v: &toml::Value) -> String {
    match v {
        toml::Value::String(_) => v.to_string(),
        other => show(other),
    }
}

/// The longest value a label shows in full.
const MAX_VALUE_CHARS: usize = 32;

/// The label of one value in the course's notation: `K_shi = 50`, `Gouraud`, `L_exp = 8`.
pub fn label(key: &KeyPath, v: &toml::Value) -> String {
    let first = match key.0.first() {
        Some(Segment::Key(k)) => k.as_str(),
        _ => "",
    };
    let last = match key.0.last() {
        Some(Segment::Key(k)) => k.as_str(),
        _ => "",
    };
    // A whole light, object or material is named by what it is: `Point`, `Torus`, `Phong`.
    if let toml::Value::Table(t) = v {
        for k in ["kind", "shape", "model"] {
            if let Some(toml::Value::String(s)) = t.get(k) {
                return super::text::escape(&pretty(s));
            }
        }
    }
    // Values and key names are literal text, not label markup (`max_depth` has no subscript);
    // a long value is cut so one label cannot widen every cell.
    let shown = show_rounded(v);
    let shown =
        if shown.chars().count() > MAX_VALUE_CHARS { shown.chars().take(MAX_VALUE_CHARS - 1).chain(['…']).collect() } else { shown };
    let value = super::text::escape(&shown);
    // An indexed path (`light.0`) is named whole.
    let last = if last.is_empty() { return format!("{} = {value}", super::text::escape(&key.to_string())) } else { last };
    let symbol = match (first, last) {
        (_, "interpolation") | (_, "tonemap") | (_, "model") | (_, "kind") | (_, "shape") => return super::text::escape(&pretty(&show(v))),
        ("material", "shininess") => "K_shi",
        ("material", "specular") => "K_spec",
        ("material", "diffuse") => "K_diff",
        ("material", "ambient") => "K_amb",
        ("material", "emission") => "L_emi",
        ("scene", "ambient") => "L_glob",
        ("light", "ambient") => "L_amb",
        ("light", "exponent") => "L_exp",
        ("light", "intensity") => "I",
        ("light", "attenuation") => "(S_c, S_l, S_q)",
        ("light", "direction") => "direction",
        ("light", "cutoff_deg") => return format!("cutoff = {value}°"),
        ("camera", "fov_deg") => return format!("fov = {value}°"),
        (_, "rotate_deg") => return format!("rotate = {value}°"),
        (_, other) => return format!("{} = {value}", super::text::escape(other)),
    };
    format!("{symbol} = {value}")
}

/// `blinn_phong` → `Blinn-Phong`, `gouraud` → `Gouraud`.
fn pretty(s: &str) -> String {
    s.split('_')
        .map(|w| {
            let mut c = w.chars();
            c.next().map_or_else(String::new, |f| f.to_uppercase().collect::<String>() + c.as_str())
        })
        .collect::<Vec<_>>()
        .join("-")
}

/// The column label of a split layer.
pub fn layer_label(l: crate::render::Layer) -> &'static str {
    use crate::render::Layer;
    match l {
        Layer::Ambient => "Ambient",
        Layer::Diffuse => "Diffuse",
        Layer::Specular => "Specular",
        Layer::Emission => "Emission",
        Layer::Reflection => "Reflection",
        Layer::Transmission => "Transmission",
        Layer::Total => "Total",
        Layer::Normal => "Normal",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_labels_have_three_significant_figures() {
        let cases = [
            (2.208, "2.21"),
            (4.876, "4.88"),
            (10.77, "10.8"),
            (256.0, "256"),
            (0.5, "0.5"),
            (1.0, "1"),
            (9.996, "10"),
            (0.012345, "0.0123"),
            (-3.14567, "-3.15"),
            (1234.5, "1230"),
            (12345.0, "1.23e4"),
            (0.00012345, "1.23e-4"),
            (0.0, "0"),
        ];
        for (x, want) in cases {
            assert_eq!(sig3(x), want, "{x}");
        }
        let k = KeyPath::parse("material.plastic.shininess").unwrap();
        assert_eq!(label(&k, &toml::Value::Float(2.2080048)), "K_shi = 2.21");
        assert_eq!(label(&k, &toml::Value::Integer(50)), "K_shi = 50");
    }

    #[test]
    fn labels_use_course_notation() {
        let k = |s: &str| KeyPath::parse(s).unwrap();
        assert_eq!(label(&k("material.plastic.shininess"), &toml::Value::Integer(50)), "K_shi = 50");
        assert_eq!(label(&k("material.plastic.specular"), &toml::Value::Float(0.3)), "K_spec = 0.3");
        assert_eq!(label(&k("render.interpolation"), &toml::Value::String("gouraud".into())), "Gouraud");
        assert_eq!(label(&k("material.m.model"), &toml::Value::String("blinn_phong".into())), "Blinn-Phong");
        assert_eq!(label(&k("light.0.exponent"), &toml::Value::Float(8.0)), "L_exp = 8");
        assert_eq!(label(&k("object.0.segments"), &toml::Value::Integer(16)), "segments = 16");
        // Whole tables are named by what they are; other values by their path, cut when long.
        let table = |s: &str| toml::Value::Table(toml::from_str(s).unwrap());
        assert_eq!(label(&k("object.0"), &table("shape = \"torus\"\nmaterial = \"plastic\"")), "Torus");
        assert_eq!(label(&k("light.1"), &table("kind = \"spot\"\nposition = [0, 2, 0]")), "Spot");
        assert_eq!(label(&k("light.1"), &table("intensity = 2")), "light.1 = { intensity = 2 }");
        let long = label(&k("object.0.translate"), &toml::Value::String("x".repeat(100)));
        assert_eq!(long.chars().count(), "translate = ".len() + MAX_VALUE_CHARS);
        assert!(long.ends_with('…'));
    }
}
