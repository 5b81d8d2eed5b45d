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

impl Override {
    /// Parses `KEY=VALUE`; the value is TOML (`64`, `[1, 0, 0]`, `"a"`), or a bare word.
    ///
    /// # Errors
    /// A message when there is no `=` or the key is empty.
    pub fn parse(arg: &str) -> Result<Override, String> {
        let (key, raw) = arg
            .split_once('=')
            .ok_or_else(|| format!("`{arg}` is not KEY=VALUE (e.g. material.plastic.shininess=64)"))?;
        let path = KeyPath::parse(key.trim())
            .ok_or_else(|| format!("`{key}` is not a dotted key path (e.g. light.0.intensity)"))?;
        let raw = raw.trim();
        let value = match format!("v = {raw}").parse::<Table>() {
            Ok(mut t) => t.remove("v").unwrap_or(Value::String(raw.to_string())),
            Err(_) => Value::String(raw.to_string()),
        };
        Ok(Override { arg: arg.to_string(), path, value })
    }

    /// Writes the value into `root`, creating missing tables on the way.
    ///
    /// # Errors
    /// A message when the path runs through a non-table or an array index that does not exist.
    pub fn apply(&self, root: &mut Table) -> Result<(), String> {
        let mut whole = Value::Table(std::mem::take(root));
        let result = self.apply_to(&mut whole);
        if let Value::Table(t) = whole {
            *root = t;
        }
        result
    }

    fn apply_to(&self, whole: &mut Value) -> Result<(), String> {
        let segs = &self.path.0;
        let (last, parents) = segs.split_last().ok_or("empty key")?;
        let mut cur = whole;
        for (i, seg) in parents.iter().enumerate() {
            cur = step(cur, seg, &KeyPath(segs[..i].to_vec()))?;
        }
        match (last, cur) {
            (Segment::Key(k), Value::Table(t)) => {
                t.insert(k.clone(), self.value.clone());
                Ok(())
            }
            (Segment::Index(n), Value::Array(a)) if *n < a.len() => {
                a[*n] = self.value.clone();
                Ok(())
            }
            (last, cur) => Err(not_found(&KeyPath(parents.to_vec()), last, cur)),
        }
    }
}

fn step<'a>(cur: &'a mut Value, seg: &Segment, here: &KeyPath) -> Result<&'a mut Value, String> {
    match (seg, cur) {
        (Segment::Key(k), Value::Table(t)) => {
            if !t.contains_key(k) {
                t.insert(k.clone(), Value::Table(Table::new()));
            }
            Ok(t.get_mut(k).expect("inserted above"))
        }
        (Segment::Index(n), Value::Array(a)) => {
            let len = a.len();
            a.get_mut(*n)
                .ok_or_else(|| format!("`{here}` has {len} entries (indices 0..{}), there is no {n}", len.max(1) - 1))
        }
        (seg, v) => Err(not_found(here, seg, v)),
    }
}

fn not_found(here: &KeyPath, seg: &Segment, v: &Value) -> String {
    let what = match seg {
        Segment::Key(k) => format!("key `{k}`"),
        Segment::Index(n) => format!("index {n}"),
    };
    let place = if here.0.is_empty() { "the lesson".to_string() } else { format!("`{here}`") };
    format!("cannot set {what}: {place} is a {}, not a {}", v.type_str(), match seg {
        Segment::Key(_) => "table",
        Segment::Index(_) => "list",
    })
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
    fn missing_index_is_an_error() {
        let mut t: Table = "[[light]]\nkind = \"point\"\n".parse().unwrap();
        let e = Override::parse("light.3.intensity=2").unwrap().apply(&mut t).unwrap_err();
        assert!(e.contains("there is no 3"), "{e}");
        assert!(Override::parse("novalue").is_err());
    }
}
