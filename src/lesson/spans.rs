//! Byte spans of keys and values in the lesson text, for `file:line:col` messages.

use super::path::{KeyPath, Segment};
use std::ops::Range;
use toml::de::{DeTable, DeValue};

/// Whether an error is about the key itself (unknown key) or its value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Point at the key.
    Key,
    /// Point at the value.
    Value,
}

/// The span of `path` in `text`; when the path does not exist in the text, the span
/// of its deepest existing ancestor (a table header, or the start of the file).
pub fn find(text: &str, path: &KeyPath, target: Target) -> Range<usize> {
    walk(text, path, target).1
}

/// How many leading segments of `path` exist in `text` (`path.0.len()` when all do).
pub fn depth(text: &str, path: &KeyPath) -> usize {
    walk(text, path, Target::Value).0
}

/// Follows `path` as far as the text has it: (segments found, span of the deepest one).
fn walk(text: &str, path: &KeyPath, target: Target) -> (usize, Range<usize>) {
    let Ok(root) = DeTable::parse(text) else {
        return (0, 0..0);
    };
    let mut best = 0..0;
    let mut table: Option<&DeTable> = Some(root.get_ref());
    let mut array: Option<&[toml::Spanned<DeValue>]> = None;
    for (i, seg) in path.0.iter().enumerate() {
        let last = i + 1 == path.0.len();
        let value = match (seg, table, array) {
            (Segment::Key(k), Some(t), _) => {
                let Some((key, value)) = t.iter().find(|(key, _)| key.get_ref() == k) else {
                    return (i, best);
                };
                if last && target == Target::Key {
                    return (i + 1, key.span());
                }
                value
            }
            (Segment::Index(n), _, Some(a)) => match a.get(*n) {
                Some(v) => v,
                None => return (i, best),
            },
            _ => return (i, best),
        };
        best = value.span();
        table = value.get_ref().as_table();
        array = value.get_ref().as_array().map(|a| &a[..]);
    }
    (path.0.len(), best)
}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..text.floor_char_boundary(offset)];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = "[camera]\nposition = [0, 0, 4]\n\n[material.red]\nmodel = \"phong\"\nshininess = 32\n\n[[light]]\nkind = \"point\"\n\n[[light]]\nkind = \"spot\"\nintensity = 2\n";

    fn at(path: &str, target: Target) -> (usize, usize) {
        let span = find(DOC, &KeyPath::parse(path).unwrap(), target);
        line_col(DOC, span.start)
    }

    #[test]
    fn value_and_key_spans() {
        assert_eq!(at("material.red.shininess", Target::Value), (6, 13));
        assert_eq!(at("material.red.shininess", Target::Key), (6, 1));
        assert_eq!(at("light.1.intensity", Target::Value), (13, 13));
        assert_eq!(at("light.0.kind", Target::Key), (9, 1));
    }

    #[test]
    fn depth_counts_the_segments_the_text_has() {
        let depth = |p: &str| depth(DOC, &KeyPath::parse(p).unwrap());
        assert_eq!(depth("material.red.shininess"), 3);
        assert_eq!(depth("material.red.diffuse"), 2);
        assert_eq!(depth("material.blue.model"), 1);
        assert_eq!(depth("light.5.kind"), 1);
        assert_eq!(depth("render.aa"), 0);
    }

    #[test]
    fn missing_key_falls_back_to_its_table() {
        // `material.red.diffuse` is absent: point at the table it would go in.
        let (line, _) = at("material.red.diffuse", Target::Key);
        assert_eq!(line, 4);
    }
}
