//! Machine-readable diagnostics (`check --format jsonl`, `--annotations`): each error of a
//! run as one JSON object per line, as a GitHub workflow command on the lesson's line, or in
//! a GitLab code-quality report. Field by field in docs/cli.md, "Diagnostics for tools".

use crate::lesson::{LessonError, Location};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// One diagnostic: an error (or warning) at a place in a lesson.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// `error` or `warning`.
    pub level: &'static str,
    /// What kind: `lesson` (the file does not validate), `asset` (a file it names cannot be
    /// used), `figure` (a figure cannot be made), `budget` (a render over the budget).
    pub code: &'static str,
    /// What is wrong (one line, without the place).
    pub message: String,
    /// The lesson file.
    pub file: PathBuf,
    /// 1-based line and column in the file, when the place is in it.
    pub at: Option<(usize, usize)>,
    /// The `--set` (or `--vary`) flag the error is in, when it is in one.
    pub flag: Option<String>,
    /// How to fix it.
    pub hint: Option<String>,
    /// The dotted key path the error is about.
    pub key: Option<String>,
}

/// Every error `e` reports (itself and the others of its run), in its order.
pub fn of_lesson_error(e: &LessonError, code: &'static str) -> Vec<Diagnostic> {
    std::iter::once(e)
        .chain(e.others.iter())
        .map(|e| {
            let (at, flag) = match &e.location {
                Location::File { line, col } => (Some((*line, *col)), None),
                Location::Flag(f) => (None, Some(f.clone())),
                Location::Whole => (None, None),
            };
            Diagnostic {
                level: "error",
                code,
                message: e.message.clone(),
                file: e.file.clone(),
                at,
                flag,
                hint: e.hint.clone(),
                key: e.key.clone(),
            }
        })
        .collect()
}

/// An error known only as text about `file` (its first line the message, a `hint:` line the hint).
pub fn of_text(file: &Path, code: &'static str, text: &str) -> Diagnostic {
    let mut lines = text.lines();
    let first = lines.next().unwrap_or_default();
    // The text usually starts with the file's name: the message is what follows it.
    let shown = crate::output::shown_path(file);
    let message = first.strip_prefix(shown.as_str()).map_or(first, |m| m.trim_start_matches(':').trim_start()).to_string();
    let hint = lines.find_map(|l| l.trim_start().strip_prefix("hint: ")).map(str::to_string);
    Diagnostic { level: "error", code, message, file: file.to_path_buf(), at: None, flag: None, hint, key: None }
}

impl Diagnostic {
    /// The JSON object `--format jsonl` prints.
    pub fn json(&self) -> Value {
        json!({
            "level": self.level,
            "code": self.code,
            "message": self.message,
            "file": self.file.display().to_string(),
            "line": self.at.map(|a| a.0),
            "column": self.at.map(|a| a.1),
            // The validator locates a value's start; where it ends is not tracked.
            "end": Value::Null,
            "flag": self.flag,
            "hint": self.hint,
            "key": self.key,
        })
    }

    /// The GitHub Actions workflow command that puts the message on the lesson's line.
    pub fn github(&self) -> String {
        let mut props = format!("file={}", property(&self.file.display().to_string()));
        if let Some((line, col)) = self.at {
            props.push_str(&format!(",line={line},col={col}"));
        }
        props.push_str(&format!(",title={}", property(&format!("shadelab {}", self.code))));
        let mut text = match &self.key {
            Some(k) => format!("`{k}`: {}", self.message),
            None => self.message.clone(),
        };
        if let Some(flag) = &self.flag {
            text = format!("in {flag}: {text}");
        }
        if let Some(h) = &self.hint {
            text.push_str(&format!("\nhint: {h}"));
        }
        format!("::{} {props}::{}", self.level, data(&text))
    }

    /// The entry of a GitLab code-quality report.
    pub fn gitlab(&self) -> Value {
        let line = self.at.map_or(1, |a| a.0);
        let description = match &self.key {
            Some(k) => format!("`{k}`: {}", self.message),
            None => self.message.clone(),
        };
        // Stable across runs: the same error at the same place is the same issue.
        let fingerprint =
            blake3::hash(format!("{}:{line}:{}:{description}", self.file.display(), self.code).as_bytes()).to_hex()[..32].to_string();
        json!({
            "description": description,
            "check_name": format!("shadelab-{}", self.code),
            "fingerprint": fingerprint,
            "severity": if self.level == "error" { "major" } else { "minor" },
            "location": { "path": self.file.display().to_string(), "lines": { "begin": line } },
        })
    }
}

/// A workflow command's message: `%`, CR and LF escaped (GitHub's `escapeData`).
fn data(s: &str) -> String {
    s.replace('%', "%25").replace('\r', "%0D").replace('\n', "%0A")
}

/// A workflow command's property: as [`data`], and `:` and `,` too (GitHub's `escapeProperty`).
fn property(s: &str) -> String {
    data(s).replace(':', "%3A").replace(',', "%2C")
}

/// Where `--annotations` sends the diagnostics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Annotations {
    /// GitHub Actions workflow commands on stdout (also chosen by `GITHUB_ACTIONS=true`).
    Github,
    /// A GitLab code-quality report, `gl-code-quality-report.json` in the current folder.
    Gitlab,
    /// None, even under GitHub Actions.
    None,
}

/// The GitLab report's file name (the one GitLab's documentation uses).
pub const GITLAB_REPORT: &str = "gl-code-quality-report.json";

/// The annotations to make: the flag's, else GitHub's when running under GitHub Actions.
pub fn annotations(flag: Option<Annotations>) -> Annotations {
    flag.unwrap_or(if std::env::var("GITHUB_ACTIONS").is_ok_and(|v| v == "true") { Annotations::Github } else { Annotations::None })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Diagnostic {
        Diagnostic {
            level: "error",
            code: "lesson",
            message: "-0.2 is below 0, the smallest `roughness`: 50%, a, b".into(),
            file: "lessons/my,lesson.toml".into(),
            at: Some((12, 13)),
            flag: None,
            hint: Some("use 0 to 1".into()),
            key: Some("material.gold.roughness".into()),
        }
    }

    #[test]
    fn github_commands_escape_what_would_end_them() {
        let g = sample().github();
        assert_eq!(
            g,
            "::error file=lessons/my%2Clesson.toml,line=12,col=13,title=shadelab lesson::`material.gold.roughness`: -0.2 is below 0, the smallest `roughness`: 50%25, a, b%0Ahint: use 0 to 1"
        );
    }

    #[test]
    fn json_and_gitlab_carry_the_place() {
        let d = sample();
        let j = d.json();
        assert_eq!((j["line"].as_u64(), j["column"].as_u64()), (Some(12), Some(13)));
        assert_eq!(j["key"], "material.gold.roughness");
        let g = d.gitlab();
        assert_eq!(g["location"]["lines"]["begin"], 12);
        assert_eq!(g["fingerprint"].as_str().unwrap().len(), 32);
        assert_eq!(g["fingerprint"], sample().gitlab()["fingerprint"], "stable");
    }
}
