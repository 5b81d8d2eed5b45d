//! `--set KEY=VALUE`: override any value of the lesson by dotted path.

use super::path::{KeyPath, Segment};
use toml::{Table, Value};

/// One parsed `--set` argument.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// The argument as given, for messages.
    pub arg: String,
    /// Where to write.
    pub path: KeyPath,
    /// The TOML value (a bare word that is not TOML is taken as a string).
    pub value: Value,
}

/// Why an override could not be written into the lesson.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApplyError {
    /// What is wrong.
    pub message: String,
    /// How to fix it.
    pub hint: Option<String>,
    /// The key the lesson does not have, when that is the cause (`lighht` in
    /// `lighht.0.intensity=2`): the caller can ask the schema whether it is a typo.
    pub absent: Option<KeyPath>,
}

impl Override {
    /// Parses `KEY=VALUE`; the value is TOML (`64`, `[1, 0, 0]`, `"a"`), or a bare word.
    /// KEY may quote segments as TOML does (`material."GGX r = 1".roughness=0.5`).
    ///
    /// # Errors
    /// A message when there is no `=`, the key is not a dotted path, or the value starts
    /// like a TOML array, inline table or string (`[`, `{`, `"`, `'`) but is not one.
    pub fn parse(arg: &str) -> Result<Override, String> {
        let (key, raw) =
            super::path::split_assignment(arg).ok_or_else(|| format!("`{arg}` is not KEY=VALUE (e.g. material.plastic.shininess=64)"))?;
        if key.trim().is_empty() {
            return Err(format!("`{arg}` has no key before `=` (e.g. material.plastic.shininess=64)"));
        }
        let path = KeyPath::parse(key.trim()).ok_or_else(|| {
            format!(
                "`{key}` is not a dotted key path (e.g. light.0.intensity; quote a name with spaces or dots: material.\"my name\".diffuse)"
            )
        })?;
        let value = parse_value(raw)?;
        Ok(Override { arg: arg.to_string(), path, value })
    }

    /// Writes the value into `root`, creating missing tables on the way.
    ///
    /// # Errors
    /// [`ApplyError`] when the path runs through a non-table, an array index that does
    /// not exist, or a key the lesson does not have followed by an index.
    pub fn apply(&self, root: &mut Table) -> Result<(), ApplyError> {
        let mut whole = Value::Table(std::mem::take(root));
        let result = self.apply_to(&mut whole);
        if let Value::Table(t) = whole {
            *root = t;
        }
        result
    }

    fn apply_to(&self, whole: &mut Value) -> Result<(), ApplyError> {
        let segs = &self.path.0;
        let (last, parents) = segs.split_last().ok_or_else(|| plain("empty key".into()))?;
        let mut cur = whole;
        for (i, seg) in parents.iter().enumerate() {
            cur = step(cur, seg, &KeyPath(segs[..i].to_vec()), &segs[i + 1])?;
        }
        let here = KeyPath(parents.to_vec());
        match (last, cur) {
            (Segment::Key(k), Value::Table(t)) => {
                t.insert(k.clone(), self.value.clone());
                Ok(())
            }
            (Segment::Index(n), Value::Array(a)) => match a.get_mut(*n) {
                Some(slot) => {
                    *slot = self.value.clone();
                    Ok(())
                }
                None => Err(no_entry(&here, a, *n)),
            },
            (last, cur) => Err(not_found(&here, last, cur)),
        }
    }
}

/// Reads a `--set` or `--vary` value: TOML (`64`, `[1, 0, 0]`, `"a b"`, `{ kind = "point" }`),
/// or a bare word taken as a string (`gouraud`).
///
/// # Errors
/// A message (with a `hint:` line) when the value starts like a TOML array, inline table
/// or string (`[`, `{`, `"`, `'`) but does not parse: taking `[1,2` as the text "[1,2"
/// would only move the error somewhere vaguer.
pub fn parse_value(raw: &str) -> Result<Value, String> {
    let raw = raw.trim();
    let e = match format!("v = {raw}").parse::<Table>() {
        Ok(mut t) => return Ok(t.remove("v").unwrap_or(Value::String(raw.to_string()))),
        Err(e) => e,
    };
    let (what, closer, example) = match raw.chars().next() {
        Some('[') => ("an array", "`]`", "[1, 0.5, 0]"),
        Some('{') => ("an inline table", "`}`", "{ kind = \"point\", position = [0, 2, 2] }"),
        Some('"') => ("a quoted string", "`\"`", "\"text\""),
        Some('\'') => ("a quoted string", "`'`", "'text'"),
        _ => return Ok(Value::String(raw.to_string())),
    };
    let why = e.message().trim().lines().next().unwrap_or("").trim_end_matches('.').to_string();
    Err(format!(
        "the value `{raw}` starts like {what} but is not valid TOML ({why})\n  hint: check the closing {closer}, the commas and the quotes, e.g. {example}; put the whole argument in single quotes for the shell"
    ))
}

/// One step down the path; `next` is the segment after `seg` (a missing key is created
/// as a table, unless `next` indexes into it: an array cannot be made up).
fn step<'a>(cur: &'a mut Value, seg: &Segment, here: &KeyPath, next: &Segment) -> Result<&'a mut Value, ApplyError> {
    match (seg, cur) {
        (Segment::Key(k), Value::Table(t)) => {
            if !t.contains_key(k) {
                if let Segment::Index(n) = next {
                    let absent = here.key(k);
                    return Err(ApplyError {
                        message: format!("the lesson has no `{absent}`, so there is no `{}`", absent.index(*n)),
                        hint: Some(ADD_IN_FILE.into()),
                        absent: Some(absent),
                    });
                }
                t.insert(k.clone(), Value::Table(Table::new()));
            }
            Ok(t.get_mut(k).expect("inserted above"))
        }
        (Segment::Index(n), Value::Array(a)) => {
            if *n >= a.len() {
                return Err(no_entry(here, a, *n));
            }
            Ok(&mut a[*n])
        }
        (seg, v) => Err(not_found(here, seg, v)),
    }
}

const ADD_IN_FILE: &str = "--set changes entries the lesson has, it cannot add one; add it to the lesson file";

fn plain(message: String) -> ApplyError {
    ApplyError { message, hint: None, absent: None }
}

/// `here` is the array `a` and `n` is not one of its indices.
fn no_entry(here: &KeyPath, a: &[Value], n: usize) -> ApplyError {
    let len = a.len();
    let has = match len {
        0 => "no entries".to_string(),
        1 => "1 entry (index 0)".to_string(),
        _ => format!("{len} entries (indices 0 to {})", len - 1),
    };
    ApplyError {
        message: format!("`{here}` has {has}, so there is no `{}`", here.index(n)),
        // Only lists of tables ([[light]]) grow by adding entries; a vector has its length.
        hint: a.iter().all(Value::is_table).then(|| ADD_IN_FILE.into()),
        absent: None,
    }
}

fn not_found(here: &KeyPath, seg: &Segment, v: &Value) -> ApplyError {
    let what = match seg {
        Segment::Key(k) => format!("key `{k}`"),
        Segment::Index(n) => format!("index {n}"),
    };
    let place = if here.0.is_empty() { "the lesson".to_string() } else { format!("`{here}`") };
    let want = match seg {
        Segment::Key(_) => "a table",
        Segment::Index(_) => "an array",
    };
    let ty = v.type_str();
    let article = if ty.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
    plain(format!("cannot set {what}: {place} is {article} {ty}, not {want}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sets_nested_values_and_creates_tables() {
        let mut t: Table = "[[light]]\nkind = \"point\"\n".parse().unwrap();
        Override::parse("light.0.intensity=2").unwrap().apply(&mut t).unwrap();
        Override::parse("render.interpolation=gouraud").unwrap().apply(&mut t).unwrap();
        assert_eq!(t["light"][0]["intensity"].as_integer(), Some(2));
        assert_eq!(t["render"]["interpolation"].as_str(), Some("gouraud"));
    }

    #[test]
    fn values_are_toml() {
        let o = Override::parse("camera.background=[1, 0.5, 0]").unwrap();
        assert_eq!(o.value.as_array().map(|a| a.len()), Some(3));
        assert_eq!(Override::parse("a.b=\"x y\"").unwrap().value.as_str(), Some("x y"));
    }

    #[test]
    fn broken_toml_values_are_errors_and_bare_words_strings() {
        for broken in ["[1,2", "{ kind = \"point\"", "\"open", "'open", "[1, 2]]"] {
            let e = parse_value(broken).unwrap_err();
            assert!(e.contains("is not valid TOML") && e.contains("hint:"), "{broken}: {e}");
        }
        assert_eq!(parse_value("gouraud").unwrap().as_str(), Some("gouraud"));
        assert_eq!(parse_value("1.5.2").unwrap().as_str(), Some("1.5.2"));
        assert_eq!(parse_value("[1, 2]").unwrap().as_array().map(Vec::len), Some(2));
        // A quoted key segment may hold `=`.
        let o = Override::parse("material.\"r = 1\".roughness=0.5").unwrap();
        assert_eq!(o.path.0[1], Segment::Key("r = 1".into()));
        assert_eq!(o.value.as_float(), Some(0.5));
    }

    #[test]
    fn missing_index_is_an_error() {
        let mut t: Table = "[[light]]\nkind = \"point\"\n".parse().unwrap();
        let e = Override::parse("light.3.intensity=2").unwrap().apply(&mut t).unwrap_err();
        assert_eq!(e.message, "`light` has 1 entry (index 0), so there is no `light.3`");
        let e = Override::parse("lihgt.0.intensity=2").unwrap().apply(&mut t).unwrap_err();
        assert_eq!(e.absent, KeyPath::parse("lihgt"));
        assert!(Override::parse("novalue").is_err());
        assert!(Override::parse("=3").unwrap_err().contains("no key"));
    }
}
