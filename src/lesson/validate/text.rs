//! Lesson text in the course's two languages: every title, summary, note, caption and label
//! is a string, or `{ en = "...", ja = "..." }` of which `[lesson] lang` (or `--lang`) picks one.

use super::{R, Validator};
use crate::lesson::i18n::Lang;
use crate::lesson::path::KeyPath;
use crate::lesson::spans::Target;

/// The languages a text table may give.
const LANGS: [&str; 2] = ["en", "ja"];

impl Validator<'_> {
    /// A text at `p`: a string, or `{ en, ja }` read in the lesson's language (the other one
    /// when it gives only that one).
    pub(super) fn text(&self, p: &KeyPath, v: &toml::Value) -> R<String> {
        let bad = |at: &KeyPath, what: String| {
            self.err(at, Target::Value, what, Some("give a string, or both languages: `{ en = \"Shininess\", ja = \"光沢度\" }`".into()))
        };
        match v {
            toml::Value::String(s) => Ok(s.clone()),
            toml::Value::Table(t) => {
                for (k, v) in t {
                    if !LANGS.contains(&k.as_str()) {
                        return Err(self.err(
                            &p.key(k),
                            Target::Key,
                            format!("unknown language `{k}` in a text"),
                            Some("a text gives `en` and `ja`".into()),
                        ));
                    }
                    if !v.is_str() {
                        return Err(bad(&p.key(k), format!("`{k}` is the text in that language, a string")));
                    }
                }
                let want = match self.lang.get() {
                    Lang::Ja => ["ja", "en"],
                    _ => ["en", "ja"],
                };
                want.iter()
                    .find_map(|k| t.get(*k).and_then(toml::Value::as_str))
                    .map(str::to_string)
                    .ok_or_else(|| bad(p, "an empty text".into()))
            }
            _ => Err(bad(p, "a text is a string or `{ en, ja }`".into())),
        }
    }

    /// [`Validator::text`] of an optional key.
    pub(super) fn opt_text(&self, p: &KeyPath, v: Option<&toml::Value>) -> R<Option<String>> {
        v.map(|v| self.text(p, v)).transpose()
    }

    /// Each label of `labels` at `p` (`labels.0`, `labels.1`, ...).
    pub(super) fn texts(&self, p: &KeyPath, labels: Option<&Vec<toml::Value>>) -> R<Option<Vec<String>>> {
        labels.map(|l| l.iter().enumerate().map(|(i, v)| self.text(&p.index(i), v)).collect()).transpose()
    }
}

#[cfg(test)]
mod tests {
    use crate::lesson::{Override, parse};
    use std::path::Path;

    const LESSON: &str = r#"[lesson]
title = { en = "Shininess", ja = "光沢度" }
notes = "Plain text stays plain."

[camera]
position = [0, 0, 4]
size = [16, 16]

[[object]]
shape = "uv_sphere"
material = "m"

[material.m]
model = "blinn_phong"

[[light]]
kind = "directional"
direction = [0, 0, -1]

[[figure]]
name = "f"
kind = "sweep"
vary = "material.m.shininess"
values = [8, 64]
labels = [{ en = "soft", ja = "柔らかい" }, "sharp"]
caption = { ja = "日本語だけ" }
"#;

    #[test]
    fn the_lessons_language_picks_each_text() {
        let en = parse(LESSON, Path::new("t.toml"), &[]).unwrap();
        assert_eq!(en.title, "Shininess");
        assert_eq!(en.notes, "Plain text stays plain.");
        // A text given in one language only is shown in it.
        assert_eq!(en.figures[0].caption.as_deref(), Some("日本語だけ"));
        let labels = |l: &crate::lesson::Lesson| match &l.figures[0].body {
            crate::lesson::FigureBody::Sweep { cols, .. } => cols.labels.clone().unwrap(),
            other => panic!("{other:?}"),
        };
        assert_eq!(labels(&en), ["soft", "sharp"]);
        let ja = parse(LESSON, Path::new("t.toml"), &[Override::parse("lesson.lang=\"ja\"").unwrap()]).unwrap();
        assert_eq!(ja.title, "光沢度");
        assert_eq!(labels(&ja), ["柔らかい", "sharp"]);
    }

    #[test]
    fn a_text_table_names_its_languages() {
        let bad = LESSON.replace(r#"title = { en = "Shininess", ja = "光沢度" }"#, r#"title = { en = "Shininess", fr = "Brillance" }"#);
        let e = parse(&bad, Path::new("t.toml"), &[]).unwrap_err().to_string();
        assert!(e.contains("t.toml:2:") && e.contains("unknown language `fr`"), "{e}");
        let bad = LESSON.replace(r#"caption = { ja = "日本語だけ" }"#, "caption = { ja = 3 }");
        let e = parse(&bad, Path::new("t.toml"), &[]).unwrap_err().to_string();
        assert!(e.contains("figure.0.caption.ja") && e.contains("a string"), "{e}");
        let bad = LESSON.replace(r#"caption = { ja = "日本語だけ" }"#, "caption = {}");
        assert!(parse(&bad, Path::new("t.toml"), &[]).unwrap_err().to_string().contains("an empty text"));
        let bad = LESSON.replace(r#"notes = "Plain text stays plain.""#, "notes = 3");
        assert!(parse(&bad, Path::new("t.toml"), &[]).unwrap_err().to_string().contains("a text is a string"));
    }
}
