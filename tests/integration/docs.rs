//! The lesson file reference keeps up with the schema: every key of `src/lesson/raw.rs`
//! has a row in `docs/lesson-format.md`, and the complete example there is valid.

use crate::helpers::{lesson_file, shadelab};
use std::path::Path;

fn read(relative: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// `(struct, field)` for every `pub NAME:` inside a `pub struct Raw...` of `raw.rs`.
fn schema_keys(source: &str) -> Vec<(String, String)> {
    let mut keys = Vec::new();
    let mut current: Option<String> = None;
    for line in source.lines().map(str::trim) {
        if let Some(rest) = line.strip_prefix("pub struct Raw") {
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric()).collect();
            current = Some(format!("Raw{name}"));
        } else if line == "}" {
            current = None;
        } else if let (Some(s), Some(rest)) = (&current, line.strip_prefix("pub "))
            && let Some((field, _)) = rest.split_once(':')
        {
            keys.push((s.clone(), field.trim().to_string()));
        }
    }
    keys
}

#[test]
fn every_schema_key_has_a_row_in_the_reference() {
    let doc = read("docs/lesson-format.md");
    let keys = schema_keys(&read("src/lesson/raw.rs"));
    // Guard the scan itself: the schema has eight Raw structs and dozens of keys.
    let structs: std::collections::BTreeSet<&str> = keys.iter().map(|(s, _)| s.as_str()).collect();
    assert!(structs.len() >= 8 && keys.len() >= 40, "the scan of raw.rs found only {structs:?} / {} keys", keys.len());
    let missing: Vec<String> = keys
        .iter()
        .filter(|(_, field)| !doc.lines().any(|l| l.starts_with(&format!("| `{field}` |"))))
        .map(|(s, field)| format!("{s}.{field}"))
        .collect();
    assert!(missing.is_empty(), "docs/lesson-format.md has no row `| `KEY` | ...` for: {}", missing.join(", "));
}

#[test]
fn the_complete_example_is_a_valid_lesson() {
    let doc = read("docs/lesson-format.md");
    let (_, after) = doc.split_once("## A complete example").expect("the reference has a complete example");
    let (_, block) = after.split_once("```toml\n").expect("the example is a ```toml block");
    let (example, _) = block.split_once("```").expect("the block is closed");
    let (_dir, path) = lesson_file("example.toml", example);
    let out = shadelab().arg("check").arg(&path).output().expect("run shadelab");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "the example does not validate:\n{stderr}");
}

#[test]
fn the_glossary_page_lists_every_term_of_the_glossary() {
    let doc = read("docs/glossary.md");
    let mut missing = Vec::new();
    for t in shadelab::lesson::glossary::GLOSSARY {
        let row = format!("| {} | {} | {} |", t.en, t.ja, t.note).replace("|  |", "| |");
        if !doc.lines().any(|l| l.replace("|  |", "| |") == row) {
            missing.push(row);
        }
    }
    for topic in shadelab::lesson::glossary::topics() {
        assert!(doc.contains(&format!("## {topic}\n")), "no heading {topic}");
    }
    assert!(missing.is_empty(), "docs/glossary.md lacks (or has another spelling of) these rows:\n{}", missing.join("\n"));
}
