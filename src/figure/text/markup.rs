//! The sub- and superscript markup: source text → characters with their script, and back to
//! plain text with Unicode scripts. The rules are in the parent module's docs.

use super::{SCRIPT_SCALE, SUB_DROP, SUP_RISE};

/// Where a character sits: on the baseline, in a script, or in a script of a script.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Script {
    Normal,
    Sub,
    Sup,
    /// A subscript inside a superscript: `(R·V)^{K_shi}`.
    SupSub,
    /// A superscript inside a subscript: `L_{x^2}`.
    SubSup,
}

impl Script {
    /// The script a `_` or `^` opens from here, if it opens one.
    fn inner(self, marker: char) -> Option<Script> {
        match (self, marker) {
            (Script::Normal, '_') => Some(Script::Sub),
            (Script::Normal, '^') => Some(Script::Sup),
            (Script::Sup, '_') => Some(Script::SupSub),
            (Script::Sub, '^') => Some(Script::SubSup),
            _ => None,
        }
    }

    /// (size factor, baseline shift down in ems of the base size); each level scales its parent's shift.
    pub(super) fn placement(self) -> (f32, f32) {
        let s = SCRIPT_SCALE;
        match self {
            Script::Normal => (1.0, 0.0),
            Script::Sub => (s, SUB_DROP),
            Script::Sup => (s, -SUP_RISE),
            Script::SupSub => (s * s, -SUP_RISE + s * SUB_DROP),
            Script::SubSup => (s * s, SUB_DROP - s * SUP_RISE),
        }
    }
}

/// One character of parsed markup and where it came from in the source.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Token {
    pub(super) ch: char,
    pub(super) script: Script,
    /// Byte offset of the character (or its escaping backslash) in the source.
    pub(super) at: usize,
}

fn is_escapable(c: char) -> bool {
    matches!(c, '_' | '^' | '{' | '}' | '\\')
}

/// Markup → characters with their script (see the parent module's docs for the rules).
pub(super) fn parse(text: &str) -> Vec<Token> {
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    let mut out = Vec::with_capacity(chars.len());
    let mut i = 0;
    parse_run(&chars, &mut i, Script::Normal, false, &mut out);
    out
}

/// Parses `chars` from `*i` at `script` up to the end, or past the closing `}` when `braced`.
fn parse_run(chars: &[(usize, char)], i: &mut usize, script: Script, braced: bool, out: &mut Vec<Token>) {
    let next = |i: usize| chars.get(i).map(|&(_, c)| c);
    while let Some(&(at, c)) = chars.get(*i) {
        if braced && c == '}' {
            *i += 1;
            return;
        }
        if c == '\\' && next(*i + 1).is_some_and(is_escapable) {
            out.push(Token { ch: chars[*i + 1].1, script, at });
            *i += 2;
            continue;
        }
        if let Some(inner) = script.inner(c) {
            match next(*i + 1) {
                Some('{') => {
                    *i += 2;
                    parse_run(chars, i, inner, true, out);
                    continue;
                }
                Some(n) if n.is_alphanumeric() => {
                    *i += 1;
                    while let Some(&(at, c)) = chars.get(*i).filter(|(_, c)| c.is_alphanumeric()) {
                        out.push(Token { ch: c, script: inner, at });
                        *i += 1;
                    }
                    continue;
                }
                // A marker before anything else is just a character.
                _ => {}
            }
        }
        out.push(Token { ch: c, script, at });
        *i += 1;
    }
}

/// The Unicode subscript of `c`, if Unicode has one (digits, signs and some letters).
fn subscript(c: char) -> Option<char> {
    const FROM: &str = "0123456789+-=()aehijklmnoprstuvx";
    const TO: &str = "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ";
    FROM.chars().position(|f| f == c).and_then(|i| TO.chars().nth(i))
}

/// The Unicode superscript of `c`, if Unicode has one.
fn superscript(c: char) -> Option<char> {
    const FROM: &str = "0123456789+-=()in";
    const TO: &str = "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁼⁽⁾ⁱⁿ";
    FROM.chars().position(|f| f == c).and_then(|i| TO.chars().nth(i))
}

/// Markup as plain text, for renderers without it (chart legends and titles): a script run
/// becomes Unicode sub- or superscript characters when every one of its characters has
/// one (`K_shi` → `Kₛₕᵢ`, `r^2` → `r²`), and is otherwise written back in markup form
/// (`x_{y z}`), which still reads.
pub fn to_plain_text(text: &str) -> String {
    let tokens = parse(text);
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < tokens.len() {
        let script = tokens[i].script;
        let end = (i..tokens.len()).find(|&j| tokens[j].script != script).unwrap_or(tokens.len());
        let run: String = tokens[i..end].iter().map(|t| t.ch).collect();
        let map = match script {
            Script::Normal => None,
            Script::Sub | Script::SupSub => Some((subscript as fn(char) -> Option<char>, '_')),
            Script::Sup | Script::SubSup => Some((superscript as fn(char) -> Option<char>, '^')),
        };
        match map {
            None => out.push_str(&run),
            Some((f, marker)) => match run.chars().map(f).collect::<Option<String>>() {
                Some(mapped) => out.push_str(&mapped),
                None if run.chars().all(char::is_alphanumeric) => {
                    out.push(marker);
                    out.push_str(&run);
                }
                None => {
                    out.push(marker);
                    out.push('{');
                    out.push_str(&run);
                    out.push('}');
                }
            },
        }
        i = end;
    }
    out
}

/// Markup as HTML: each script run in `<sub>` or `<sup>` (a script of a script nested one
/// level), every run's text passed through `escape` (the caller's HTML escaping).
pub fn to_html(text: &str, escape: &dyn Fn(&str) -> String) -> String {
    let tokens = parse(text);
    let mut out = String::with_capacity(text.len());
    // The outer script element open now: a script of a script goes inside its parent's.
    let mut open: Option<&str> = None;
    let mut i = 0;
    while i < tokens.len() {
        let script = tokens[i].script;
        let end = (i..tokens.len()).find(|&j| tokens[j].script != script).unwrap_or(tokens.len());
        let run = escape(&tokens[i..end].iter().map(|t| t.ch).collect::<String>());
        let (outer, inner) = match script {
            Script::Normal => (None, None),
            Script::Sub => (Some("sub"), None),
            Script::Sup => (Some("sup"), None),
            Script::SupSub => (Some("sup"), Some("sub")),
            Script::SubSup => (Some("sub"), Some("sup")),
        };
        if open != outer {
            if let Some(tag) = open {
                out.push_str(&format!("</{tag}>"));
            }
            if let Some(tag) = outer {
                out.push_str(&format!("<{tag}>"));
            }
            open = outer;
        }
        match inner {
            Some(tag) => out.push_str(&format!("<{tag}>{run}</{tag}>")),
            None => out.push_str(&run),
        }
        i = end;
    }
    if let Some(tag) = open {
        out.push_str(&format!("</{tag}>"));
    }
    out
}

/// Escapes `literal` so it renders verbatim: `_`, `^` and `\` get a backslash.
pub fn escape(literal: &str) -> String {
    let mut out = String::with_capacity(literal.len());
    for c in literal.chars() {
        if matches!(c, '_' | '^' | '\\') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plain(tokens: &[Token]) -> String {
        tokens.iter().map(|t| t.ch).collect()
    }

    fn scripts(text: &str) -> Vec<(char, Script)> {
        parse(text).iter().map(|t| (t.ch, t.script)).collect()
    }

    #[test]
    fn markup_parses_scripts_and_escapes() {
        use Script::*;
        assert_eq!(
            scripts("K_shi = 5"),
            [('K', Normal), ('s', Sub), ('h', Sub), ('i', Sub), (' ', Normal), ('=', Normal), (' ', Normal), ('5', Normal)]
        );
        assert_eq!(scripts("L_{a b}x"), [('L', Normal), ('a', Sub), (' ', Sub), ('b', Sub), ('x', Normal)]);
        assert_eq!(scripts("r^2"), [('r', Normal), ('2', Sup)]);
        assert_eq!(scripts("x^{-1}"), [('x', Normal), ('-', Sup), ('1', Sup)]);
        assert_eq!(plain(&parse(r"blinn\_phong")), "blinn_phong");
        assert!(parse(r"blinn\_phong").iter().all(|t| t.script == Normal));
        // Lone markers and stray braces are literal; an unclosed brace runs to the end.
        assert_eq!(plain(&parse("a_ b^ _")), "a_ b^ _");
        assert_eq!(plain(&parse("{x}")), "{x}");
        assert_eq!(scripts("a_{bc"), [('a', Normal), ('b', Sub), ('c', Sub)]);
        // One level of alternating nesting, for exponents like the Phong term's.
        assert_eq!(
            scripts("V)^{K_shi}x"),
            [('V', Normal), (')', Normal), ('K', Sup), ('s', SupSub), ('h', SupSub), ('i', SupSub), ('x', Normal)]
        );
        assert_eq!(scripts("e^{-σ_{t} d}"), [('e', Normal), ('-', Sup), ('σ', Sup), ('t', SupSub), (' ', Sup), ('d', Sup)]);
        assert_eq!(scripts("L_{x^2}"), [('L', Normal), ('x', Sub), ('2', SubSup)]);
        assert_eq!(to_plain_text("K_shi = 1"), "Kₛₕᵢ = 1");
        assert_eq!(to_plain_text("r^2 and F_0"), "r² and F₀");
        assert_eq!(to_plain_text("L_{spot dir}"), "L_{spot dir}");
        assert_eq!(to_plain_text("K_diff"), "K_diff", "no subscript d exists: written back as markup");
        assert_eq!(to_plain_text("a\\_b"), "a_b");
        assert_eq!(scripts("_{a_b}"), [('a', Sub), ('_', Sub), ('b', Sub)]);
        assert_eq!(scripts("^{a^{b}}"), [('a', Sup), ('^', Sup), ('{', Sup), ('b', Sup), ('}', Normal)]);
        assert_eq!(plain(&parse(r"a\b\\")), r"a\b\");
        assert!(parse("").is_empty());
    }

    #[test]
    fn escape_round_trips_through_the_parser() {
        for s in ["blinn_phong", r"a\_b", "x^2_y", r"\", "_{}^"] {
            let tokens = parse(&escape(s));
            assert_eq!(plain(&tokens), s);
            assert!(tokens.iter().all(|t| t.script == Script::Normal), "{s}");
        }
    }
}
