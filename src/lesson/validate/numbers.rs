//! Scalar checks: numbers, integers, vectors, colours and choices, each with its range in the message.

use super::hints::{key_help, last_key, suggest};
use super::{R, Validator};
use crate::lesson::CheckedValue;
use crate::lesson::error::LessonError;
use crate::lesson::path::KeyPath;
use crate::lesson::raw::RawColor;
use crate::lesson::spans::Target;
use glam::Vec3;

impl Validator<'_> {
    pub(super) fn number(&self, path: &KeyPath, v: f64, lo: f64, hi: f64) -> R<f32> {
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
        self.note(path, CheckedValue::Number { value: v, lo, hi, integer: false });
        Ok(v as f32)
    }

    pub(super) fn integer(&self, path: &KeyPath, v: i64, lo: i64, hi: i64) -> R<u32> {
        if v < lo || v > hi {
            let (lo_f, hi_f) = (lo as f64, hi as f64);
            return Err(self.err(
                path,
                Target::Value,
                format!("{v} is out of range: allowed {lo} to {hi}"),
                Some(range_hint(path, lo_f, hi_f)),
            ));
        }
        self.note(path, CheckedValue::Number { value: v as f64, lo: lo as f64, hi: hi as f64, integer: true });
        Ok(v as u32)
    }

    pub(super) fn vec3(&self, path: &KeyPath, v: [f64; 3], lo: f64, hi: f64) -> R<Vec3> {
        let mut out = [0.0f32; 3];
        for (i, x) in v.iter().enumerate() {
            // Located at the component, named by the whole vector.
            out[i] = self.number(&path.index(i), *x, lo, hi).map_err(|e| LessonError {
                key: Some(path.to_string()),
                message: format!("component {i}: {}", e.message),
                ..e
            })?;
        }
        self.note(path, CheckedValue::Vector { value: v, lo, hi });
        Ok(Vec3::from(out))
    }

    /// A colour: a grey, linear `[r, g, b]`, or text (sRGB hex, CSS name) decoded to linear.
    pub(super) fn color(&self, path: &KeyPath, c: &RawColor, lo: f64, hi: f64) -> R<Vec3> {
        let rgb = match c {
            RawColor::Text(text) => self.color_text(path, text),
            _ => self.triple(path, c, lo, hi),
        }?;
        self.note(path, CheckedValue::Colour { value: rgb.to_array().map(f64::from), lo, hi });
        Ok(rgb)
    }

    /// Three numbers that are not a colour (`scale`, a conductor's `eta` and `k`): no text.
    pub(super) fn triple(&self, path: &KeyPath, c: &RawColor, lo: f64, hi: f64) -> R<Vec3> {
        match c {
            RawColor::Scalar(s) => Ok(Vec3::splat(self.number(path, *s, lo, hi)?)),
            RawColor::Rgb(rgb) => self.vec3(path, *rgb, lo, hi),
            RawColor::Text(t) => Err(self.err(
                path,
                Target::Value,
                format!("`{t}` is text, and `{}` is not a colour", last_key(path).unwrap_or("this key")),
                Some(format!("give a number or three numbers, e.g. [{lo}, {lo}, {lo}]")),
            )),
        }
    }

    /// A colour written as text, decoded once with the sRGB EOTF (see [`crate::lesson::color`]).
    fn color_text(&self, path: &KeyPath, text: &str) -> R<Vec3> {
        use crate::lesson::color::{self, ColorTextError};
        color::parse(text).map_err(|e| {
            let (message, hint) = match e {
                ColorTextError::BadHex => (format!("`{text}` is not sRGB hex"), "write `#rgb` or `#rrggbb`, e.g. \"#cc1111\"".to_string()),
                ColorTextError::UnknownName(near) => (
                    format!("unknown colour name `{text}`"),
                    match near {
                        Some(n) => format!("did you mean `{n}`? (any of the 148 CSS colour names, sRGB hex, or linear [r, g, b])"),
                        None => "use a CSS colour name (e.g. \"steelblue\"), sRGB hex (\"#cc1111\") or linear [r, g, b]".to_string(),
                    },
                ),
            };
            self.err(path, Target::Value, message, Some(hint))
        })
    }

    pub(super) fn direction(&self, path: &KeyPath, v: [f64; 3]) -> R<Vec3> {
        let d = self.vec3(path, v, -1e6, 1e6)?;
        d.try_normalize().ok_or_else(|| {
            self.err(path, Target::Value, "a direction cannot be [0, 0, 0]", Some("give the way the light travels, e.g. [0, 0, -1]".into()))
        })
    }

    /// One of a closed set of names, in any case (`"Phong"` = `"phong"`) when that is unambiguous.
    pub(super) fn choice<T: Copy>(&self, path: &KeyPath, got: &str, options: &[(&str, T)]) -> R<T> {
        let exact = options.iter().find(|(name, _)| *name == got);
        let folded: Vec<_> = options.iter().filter(|(name, _)| name.eq_ignore_ascii_case(got)).collect();
        let found = exact.or(if folded.len() == 1 { Some(folded[0]) } else { None });
        if let Some((name, t)) = found {
            let names = options.iter().map(|(n, _)| n.to_string()).collect();
            self.note(path, CheckedValue::Choice { value: name.to_string(), names });
            return Ok(*t);
        }
        let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
        let hint = match suggest(got, &names) {
            Some(s) => format!("did you mean `{s}`? Allowed: {}", names.join(", ")),
            None => format!("allowed: {}", names.join(", ")),
        };
        Err(self.err(path, Target::Value, format!("unknown value `{got}`"), Some(hint)))
    }

    /// [`Validator::choice`] for a key that may be absent: `default` then, noted as checked
    /// (the live lab offers the choice whether or not the lesson wrote it).
    pub(super) fn choice_or<T: Copy + PartialEq>(&self, path: &KeyPath, got: &Option<String>, options: &[(&str, T)], default: T) -> R<T> {
        if let Some(s) = got {
            return self.choice(path, s, options);
        }
        if let Some((name, _)) = options.iter().find(|(_, t)| *t == default) {
            let names = options.iter().map(|(n, _)| n.to_string()).collect();
            self.note(path, CheckedValue::Choice { value: name.to_string(), names });
        }
        Ok(default)
    }

    /// [`Validator::integer`] for a key that may be absent: `default` then, noted as checked.
    pub(super) fn integer_or(&self, path: &KeyPath, got: Option<i64>, lo: i64, hi: i64, default: u32) -> R<u32> {
        match got {
            Some(v) => self.integer(path, v, lo, hi),
            None => {
                self.note(path, CheckedValue::Number { value: f64::from(default), lo: lo as f64, hi: hi as f64, integer: true });
                Ok(default)
            }
        }
    }

    /// Rejects a key that the chosen variant does not read (parameters nobody reads are errors).
    pub(super) fn unused<T>(&self, path: &KeyPath, key: &str, v: &Option<T>, why: &str) -> R<()> {
        match v {
            Some(_) => Err(self.err(&path.key(key), Target::Key, format!("`{key}` is not used {why}"), Some(format!("remove `{key}`")))),
            None => Ok(()),
        }
    }
}

/// The hint for a value out of range: what the key means, else the range again.
fn range_hint(path: &KeyPath, lo: f64, hi: f64) -> String {
    key_help(path).unwrap_or_else(|| {
        format!("use a value from {lo} to {hi} (see the `{}` row in docs/lesson-format.md)", last_key(path).unwrap_or("key"))
    })
}
