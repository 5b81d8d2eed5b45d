//! Material parameters that may name a texture: `{ texture = "file" }` or
//! `{ checker = { scale, a, b } }`, split from the constants the shading material keeps.

use super::hints::suggest;
use super::{R, Validator};
use crate::lesson::kinds::ModelKind;
use crate::lesson::limits::MAX_CHECKER_SCALE;
use crate::lesson::path::KeyPath;
use crate::lesson::raw::{RawColor, RawParam};
use crate::lesson::spans::Target;
use crate::lesson::texture::{TextureRef, TextureSource};
use glam::Vec3;

/// The keys of a texture table.
const TABLE_KEYS: [&str; 3] = ["texture", "checker", "channel"];
/// The keys of a `checker` table.
const CHECKER_KEYS: [&str; 3] = ["scale", "a", "b"];

/// The material keys of `kind` that may take a texture (besides `normal_map`).
pub(super) fn textured_keys(kind: ModelKind) -> &'static [&'static str] {
    match kind {
        ModelKind::Mirror | ModelKind::Glass => &[],
        ModelKind::CookTorrance => &["diffuse", "roughness"],
        ModelKind::Principled => &["base_color", "roughness", "metallic"],
        _ => &["diffuse"],
    }
}

impl Validator<'_> {
    /// A parameter split into its constant and its texture: a texture table is allowed only
    /// on the keys [`textured_keys`] lists for `kind`; `scalar` keys take one number.
    pub(super) fn param(
        &self,
        p: &KeyPath,
        kind: ModelKind,
        key: &'static str,
        v: &Option<RawParam>,
    ) -> R<(Option<RawColor>, Option<TextureRef>)> {
        match v {
            None => Ok((None, None)),
            Some(RawParam::Constant(c)) => Ok((Some(c.clone()), None)),
            Some(RawParam::Map(table)) => {
                let allowed = textured_keys(kind);
                if !allowed.contains(&key) {
                    let takes = if allowed.is_empty() { "none of its keys".to_string() } else { format!("`{}`", allowed.join("`, `")) };
                    return Err(self.err(
                        &p.key(key),
                        Target::Value,
                        format!("`{key}` cannot take a texture (with model `{}`)", kind.name()),
                        Some(format!("give a constant; textures go on {takes} and `normal_map`")),
                    ));
                }
                let mut source = self.texture_table(&p.key(key), table)?;
                if let Some(c) = table.get("channel") {
                    let cp = p.key(key).key("channel");
                    let data = matches!(key, "roughness" | "metallic");
                    let channel = match c.as_str() {
                        Some("r") => 0,
                        Some("g") => 1,
                        Some("b") => 2,
                        _ => {
                            return Err(self.err(
                                &cp,
                                Target::Value,
                                "`channel` is \"r\", \"g\" or \"b\"",
                                Some("glTF packs roughness in \"g\" and metallic in \"b\"".into()),
                            ));
                        }
                    };
                    match &mut source {
                        TextureSource::File { channel: c, .. } if data => *c = channel,
                        TextureSource::File { .. } => {
                            return Err(self.err(
                                &cp,
                                Target::Key,
                                format!("`{key}` is a colour: it reads all three channels"),
                                Some("remove `channel`; it picks the channel of `roughness` and `metallic` textures".into()),
                            ));
                        }
                        TextureSource::Checker { .. } => {
                            return Err(self.err(
                                &cp,
                                Target::Key,
                                "`channel` goes with `texture`, not `checker`",
                                Some("remove `channel`".into()),
                            ));
                        }
                    }
                }
                Ok((None, Some(TextureRef { key, source })))
            }
        }
    }

    /// `{ texture = "file" }` or `{ checker = { scale, a, b } }`.
    fn texture_table(&self, p: &KeyPath, table: &toml::Table) -> R<TextureSource> {
        for k in table.keys() {
            if !TABLE_KEYS.contains(&k.as_str()) {
                let hint = match suggest(k, &TABLE_KEYS) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None => "a texture table has `texture = \"file.png\"` or `checker = { scale = 8, a = 0.9, b = 0.1 }`".into(),
                };
                return Err(self.err(&p.key(k), Target::Key, format!("unknown key `{k}` in a texture table"), Some(hint)));
            }
        }
        match (table.get("texture"), table.get("checker")) {
            (Some(toml::Value::String(written)), None) => {
                let path = self.asset_path(&p.key("texture"), written)?;
                Ok(TextureSource::File { path, written: written.clone(), channel: 0 })
            }
            (Some(_), None) => Err(self.err(
                &p.key("texture"),
                Target::Value,
                "`texture` is a file name",
                Some("e.g. `texture = \"textures/wood.png\"`, relative to the lesson's folder".into()),
            )),
            (None, Some(toml::Value::Table(c))) => self.checker(&p.key("checker"), c),
            (None, Some(_)) => Err(self.err(
                &p.key("checker"),
                Target::Value,
                "`checker` is a table",
                Some("e.g. `checker = { scale = 8, a = 0.9, b = 0.1 }`".into()),
            )),
            _ => Err(self.err(
                p,
                Target::Value,
                "a texture table needs exactly one of `texture` and `checker`",
                Some("e.g. `{ texture = \"wood.png\" }` or `{ checker = { scale = 8 } }`".into()),
            )),
        }
    }

    /// `checker = { scale = 8, a = 0.9, b = 0.1 }`: squares per unit of uv and the two colours.
    fn checker(&self, p: &KeyPath, c: &toml::Table) -> R<TextureSource> {
        for k in c.keys() {
            if !CHECKER_KEYS.contains(&k.as_str()) {
                let hint =
                    suggest(k, &CHECKER_KEYS).map_or("a checker has `scale`, `a` and `b`".into(), |s| format!("did you mean `{s}`?"));
                return Err(self.err(&p.key(k), Target::Key, format!("unknown key `{k}` in `checker`"), Some(hint)));
            }
        }
        let scale = match c.get("scale") {
            None => 8,
            Some(toml::Value::Integer(n)) if (1..=MAX_CHECKER_SCALE).contains(n) => *n as u32,
            Some(_) => {
                return Err(self.err(
                    &p.key("scale"),
                    Target::Value,
                    format!("`scale` is a whole number of squares per unit of uv, 1 to {MAX_CHECKER_SCALE}"),
                    Some("e.g. `scale = 8`".into()),
                ));
            }
        };
        let colour = |key: &str, default: f32| -> R<Vec3> {
            let Some(v) = c.get(key) else { return Ok(Vec3::splat(default)) };
            let raw = v.clone().try_into::<RawColor>().map_err(|_| {
                self.err(
                    &p.key(key),
                    Target::Value,
                    format!("`{key}` is a number, [r, g, b] or a colour name"),
                    Some(format!("e.g. `{key} = 0.9`")),
                )
            })?;
            self.color(&p.key(key), &raw, 0.0, 1.0)
        };
        Ok(TextureSource::Checker { scale, a: colour("a", 0.9)?, b: colour("b", 0.1)? })
    }

    /// `key = "file"` (`normal_map`, `occlusion_map`): a map read whole from one file, confined
    /// like every file a lesson names; mirror and glass refuse it, saying `why` (what the map
    /// acts on that they lack).
    pub(super) fn file_map(&self, p: &KeyPath, kind: ModelKind, key: &'static str, v: &Option<String>, why: &str) -> R<Option<TextureRef>> {
        let Some(written) = v else { return Ok(None) };
        if matches!(kind, ModelKind::Mirror | ModelKind::Glass) {
            self.unused(p, key, v, &format!("by `{}` ({why})", kind.name()))?;
        }
        let path = self.asset_path(&p.key(key), written)?;
        Ok(Some(TextureRef { key, source: TextureSource::File { path, written: written.clone(), channel: 0 } }))
    }
}
