//! Dotted key paths (`light.0.intensity`) shared by error spans and `--set` overrides.
//!
//! A segment is a bare key (letters, digits, `_`, `-`), an index (digits only), or a
//! quoted key as in TOML: `material."GGX r = 1 (α = 1)".roughness` (basic string, with
//! `\"` and `\\` escapes) or `material.'σ = 20°'.sigma_deg` (literal string).

use std::fmt;

/// One step of a key path: a table key or an array index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Segment {
    /// A key in a table.
    Key(String),
    /// An index into an array (of tables).
    Index(usize),
}

/// A path from the document root to a value.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct KeyPath(pub Vec<Segment>);

impl KeyPath {
    /// Parses `a.b.0.c`; all-digit segments are array indices, quoted segments
    /// (`"a.b"` or `'a b'`) are keys taken as written. `None` for an empty segment or
    /// an unclosed quote.
    pub fn parse(dotted: &str) -> Option<KeyPath> {
        let mut segs = Vec::new();
        let mut rest = dotted.trim();
        loop {
            let (seg, after) = segment(rest)?;
            segs.push(seg);
            let after = after.trim_start();
            match after.strip_prefix('.') {
                Some(next) => rest = next.trim_start(),
                None if after.is_empty() => return Some(KeyPath(segs)),
                None => return None,
            }
        }
    }

    /// This path with a key appended.
    pub fn key(&self, k: &str) -> KeyPath {
        let mut p = self.clone();
        p.0.push(Segment::Key(k.to_string()));
        p
    }

    /// This path with an index appended.
    pub fn index(&self, i: usize) -> KeyPath {
        let mut p = self.clone();
        p.0.push(Segment::Index(i));
        p
    }

    /// True when `self` starts with `prefix` (or equals it).
    pub fn starts_with(&self, prefix: &KeyPath) -> bool {
        self.0.len() >= prefix.0.len() && self.0[..prefix.0.len()] == prefix.0[..]
    }
}

/// The first segment of `s` and the text after it.
fn segment(s: &str) -> Option<(Segment, &str)> {
    if let Some(body) = s.strip_prefix('"') {
        let mut key = String::new();
        let mut chars = body.char_indices();
        while let Some((i, c)) = chars.next() {
            match c {
                '"' => return Some((Segment::Key(key), &body[i + 1..])),
                '\\' => match chars.next()? {
                    (_, 'n') => key.push('\n'),
                    (_, 't') => key.push('\t'),
                    (_, e @ ('"' | '\\')) => key.push(e),
                    _ => return None,
                },
                c => key.push(c),
            }
        }
        return None;
    }
    if let Some(body) = s.strip_prefix('\'') {
        let end = body.find('\'')?;
        return Some((Segment::Key(body[..end].to_string()), &body[end + 1..]));
    }
    let end = s.find('.').unwrap_or(s.len());
    let part = s[..end].trim();
    if part.is_empty() || part.contains(['"', '\'']) {
        return None;
    }
    let seg = match part.parse::<usize>() {
        Ok(i) if part.bytes().all(|b| b.is_ascii_digit()) => Segment::Index(i),
        _ => Segment::Key(part.to_string()),
    };
    Some((seg, &s[end..]))
}

/// Splits `KEY=VALUE` at the first `=` that is not inside a quoted key segment.
pub fn split_assignment(arg: &str) -> Option<(&str, &str)> {
    let mut quote: Option<char> = None;
    let mut escaped = false;
    for (i, c) in arg.char_indices() {
        match (quote, c) {
            (Some('"'), '\\') if !escaped => {
                escaped = true;
                continue;
            }
            (Some(q), c) if c == q && !escaped => quote = None,
            (None, '"' | '\'') => quote = Some(c),
            (None, '=') => return Some((&arg[..i], &arg[i + 1..])),
            _ => {}
        }
        escaped = false;
    }
    None
}

/// True when `k` can be written without quotes (and is not read back as an index).
fn is_bare(k: &str) -> bool {
    !k.is_empty() && k.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-') && !k.bytes().all(|b| b.is_ascii_digit())
}

impl fmt::Display for KeyPath {
    /// The path as it is typed: `material."GGX r = 1 (α = 1)".roughness` (keys that are
    /// not bare are quoted, so the text parses back to the same path).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, s) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(".")?;
            }
            match s {
                Segment::Key(k) if is_bare(k) => f.write_str(k)?,
                Segment::Key(k) => write!(f, "\"{}\"", k.replace('\\', "\\\\").replace('"', "\\\""))?,
                Segment::Index(n) => write!(f, "{n}")?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(p: &str) -> Vec<Segment> {
        KeyPath::parse(p).unwrap_or_else(|| panic!("{p} should parse")).0
    }

    #[test]
    fn bare_indices_and_quoted_segments() {
        assert_eq!(keys("light.0.intensity"), vec![Segment::Key("light".into()), Segment::Index(0), Segment::Key("intensity".into())]);
        assert_eq!(keys("material.\"GGX r = 1 (α = 1)\".roughness")[1], Segment::Key("GGX r = 1 (α = 1)".into()));
        assert_eq!(keys("material.'a.b'.x")[1], Segment::Key("a.b".into()));
        assert_eq!(keys("material.\"say \\\"hi\\\"\".x")[1], Segment::Key("say \"hi\"".into()));
        // A quoted number is a key, not an index.
        assert_eq!(keys("material.\"1\".model")[1], Segment::Key("1".into()));
        for bad in ["a..b", "", "a.", "material.\"open", "material.\"a\"b.c", "a.b\"c"] {
            assert_eq!(KeyPath::parse(bad), None, "{bad}");
        }
    }

    #[test]
    fn display_round_trips() {
        for p in ["light.0.intensity", "material.\"GGX r = 1 (α = 1)\".roughness", "material.\"1\".model", "material.\"a\\\"b\".x"] {
            let parsed = KeyPath::parse(p).unwrap();
            assert_eq!(parsed.to_string(), p);
            assert_eq!(KeyPath::parse(&parsed.to_string()), Some(parsed));
        }
        assert_eq!(KeyPath::parse("material.'a b'.x").unwrap().to_string(), "material.\"a b\".x");
    }

    #[test]
    fn assignment_splits_outside_quotes() {
        assert_eq!(split_assignment("material.\"r = 1\".roughness=0.5"), Some(("material.\"r = 1\".roughness", "0.5")));
        assert_eq!(split_assignment("material.'r = 1'.roughness=0.5"), Some(("material.'r = 1'.roughness", "0.5")));
        assert_eq!(split_assignment("a.b=\"x=y\""), Some(("a.b", "\"x=y\"")));
        assert_eq!(split_assignment("novalue"), None);
    }
}
