//! Machine-readable diagnostics (`--format jsonl`, `--annotations` of `check`, `render`,
//! `figures` and `snapshot`): each error or warning of a run as one JSON object per line, as
//! a GitHub workflow command on the lesson's line, or in a GitLab code-quality report. Field
//! by field in docs/cli.md, "Diagnostics for tools".

use super::CliError;
use crate::lesson::{LessonError, Location};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

/// One diagnostic: an error (or warning) at a place in a lesson.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// `error`, `warning` or `note`.
    pub level: &'static str,
    /// What kind: `lesson` (the file does not validate), `asset` (a file it names cannot be
    /// used), `figure` (a figure cannot be made), `budget` (a render over the budget),
    /// `snapshot` (a figure differs from its blessed PNG), `render` (samples set to black),
    /// `mesh` (a mesh repaired), `input` (a command-line argument the command refused),
    /// `usage` (a command line that does not parse).
    pub code: &'static str,
    /// What is wrong (one line, without the place).
    pub message: String,
    /// The lesson file, when the diagnostic is about one.
    pub file: Option<PathBuf>,
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
                file: Some(e.file.clone()),
                at,
                flag,
                hint: e.hint.clone(),
                key: e.key.clone(),
            }
        })
        .collect()
}

/// An error known only as text about `file` (its first line the message, a `hint:` line the
/// hint). Without a file, a leading `PATH: ` that names an existing file is taken as it.
pub fn of_text(file: Option<&Path>, code: &'static str, text: &str) -> Diagnostic {
    let mut lines = text.lines();
    let first = lines.next().unwrap_or_default();
    let file = file.map(Path::to_path_buf).or_else(|| {
        let (head, _) = first.split_once(": ")?;
        Path::new(head).is_file().then(|| PathBuf::from(head))
    });
    // The text usually starts with the file's name: the message is what follows it.
    let message = file
        .as_ref()
        .and_then(|f| {
            [crate::output::shown_path(f), f.display().to_string()]
                .iter()
                .find_map(|shown| first.strip_prefix(shown.as_str()).map(|m| m.trim_start_matches(':').trim_start().to_string()))
        })
        .unwrap_or_else(|| first.to_string());
    // The rest (budget terms, several lines) stays in the hint's company: what a reader needs.
    let hint = lines.find_map(|l| l.trim_start().strip_prefix("hint: ")).map(str::to_string);
    Diagnostic { level: "error", code, message, file, at: None, flag: None, hint, key: None }
}

/// The diagnostics of a failed command's error: a lesson's errors each at its place, any
/// other error as one diagnostic (`code` `input` unless the text says more).
pub fn of_error(e: &CliError) -> Vec<Diagnostic> {
    match e {
        CliError::Lesson(e, code) => of_lesson_error(e, code),
        CliError::Input(text) => {
            let code = if text.contains("over its budget") { "budget" } else { "input" };
            vec![of_text(None, code, text)]
        }
        CliError::Internal(text) | CliError::Mismatch(text) => {
            vec![Diagnostic { code: "internal", ..of_text(None, "internal", text) }]
        }
        CliError::StdoutClosed => Vec::new(),
    }
}

impl Diagnostic {
    /// A warning about `file` (at `at`), with no hint or key.
    pub fn warning(code: &'static str, message: String, file: Option<PathBuf>, at: Option<(usize, usize)>) -> Diagnostic {
        Diagnostic { level: "warning", code, message, file, at, flag: None, hint: None, key: None }
    }

    /// The JSON object `--format jsonl` prints.
    pub fn json(&self) -> Value {
        json!({
            "level": self.level,
            "code": self.code,
            "message": self.message,
            "file": self.file.as_ref().map(|f| f.display().to_string()),
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
        let mut props = Vec::new();
        if let Some(file) = &self.file {
            props.push(format!("file={}", property(&file.display().to_string())));
        }
        if let Some((line, col)) = self.at {
            props.push(format!("line={line},col={col}"));
        }
        props.push(format!("title={}", property(&format!("shadelab {}", self.code))));
        let props = props.join(",");
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
        // GitHub has no `note` command: a note is a `notice`.
        let level = if self.level == "note" { "notice" } else { self.level };
        format!("::{level} {props}::{}", data(&text))
    }

    /// The entry of a GitLab code-quality report; `None` for a diagnostic about no file (a
    /// command-line argument), which has no place in the repository.
    pub fn gitlab(&self) -> Option<Value> {
        let file = self.file.as_ref()?;
        let line = self.at.map_or(1, |a| a.0);
        let description = match &self.key {
            Some(k) => format!("`{k}`: {}", self.message),
            None => self.message.clone(),
        };
        // Stable across runs: the same error at the same place is the same issue.
        let fingerprint =
            blake3::hash(format!("{}:{line}:{}:{description}", file.display(), self.code).as_bytes()).to_hex()[..32].to_string();
        let severity = match self.level {
            "error" => "major",
            "warning" => "minor",
            _ => "info",
        };
        Some(json!({
            "description": description,
            "check_name": format!("shadelab-{}", self.code),
            "fingerprint": fingerprint,
            "severity": severity,
            "location": { "path": file.display().to_string(), "lines": { "begin": line } },
        }))
    }
}

/// How this run reports diagnostics: set once by the command (`--format`, `--annotations`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sink {
    /// One JSON object per diagnostic on stdout (instead of text on stderr).
    pub jsonl: bool,
    /// Where else each goes.
    pub annotations: Annotations,
}

/// The run's sink; unset means text on stderr and no annotations.
static SINK: OnceLock<Sink> = OnceLock::new();
/// The GitLab report's entries, written by [`finish`].
static GITLAB: Mutex<Vec<Value>> = Mutex::new(Vec::new());
/// Errors reported so far: a command's final error that only counts them is not one more.
static ERRORS: AtomicUsize = AtomicUsize::new(0);

/// Sets how this run reports: `jsonl` for `--format jsonl`, and `--annotations` (else
/// GitHub's under GitHub Actions). One process runs one command: the first call wins.
pub fn configure(jsonl: bool, annotations: Option<Annotations>) -> Sink {
    *SINK.get_or_init(|| Sink { jsonl, annotations: self::annotations(annotations) })
}

/// The run's sink.
pub fn sink() -> Sink {
    SINK.get().copied().unwrap_or(Sink { jsonl: false, annotations: Annotations::None })
}

/// Whether stdout holds only JSON diagnostics in this run (so no other line goes there).
pub fn jsonl() -> bool {
    sink().jsonl
}

/// Reports `found`: as JSON on stdout under `--format jsonl` (the caller prints the text
/// form otherwise), and as annotations.
///
/// # Errors
/// [`CliError::StdoutClosed`] when stdout is gone.
pub fn emit(found: &[Diagnostic]) -> Result<(), CliError> {
    let sink = sink();
    ERRORS.fetch_add(found.iter().filter(|d| d.level == "error").count(), Ordering::Relaxed);
    for d in found {
        if sink.jsonl {
            outln!("{}", d.json())?;
        }
        match sink.annotations {
            Annotations::Github => outln!("{}", d.github())?,
            Annotations::Gitlab => GITLAB.lock().unwrap_or_else(std::sync::PoisonError::into_inner).extend(d.gitlab()),
            Annotations::None => {}
        }
    }
    Ok(())
}

/// A warning or note of the run (never fatal): `text` on stderr, or JSON under `--format
/// jsonl`; and as annotations.
pub fn warn(d: Diagnostic, text: std::fmt::Arguments<'_>) {
    if !jsonl() {
        super::out::eprint_line(text);
    }
    // A closed stdout ends the command elsewhere; a warning cannot fail it.
    let _ = emit(&[d]);
}

/// Ends the run's reporting: a failed command's error, if no error was reported as it
/// happened, becomes its diagnostics; then the GitLab report is written.
///
/// # Errors
/// The report cannot be written.
pub fn finish(result: &Result<(), CliError>) -> Result<(), CliError> {
    let sink = sink();
    if let Err(e) = result
        && (sink.jsonl || sink.annotations != Annotations::None)
        && ERRORS.load(Ordering::Relaxed) == 0
        && !matches!(e, CliError::Mismatch(_) | CliError::StdoutClosed)
    {
        emit(&of_error(e))?;
    }
    if sink.annotations == Annotations::Gitlab {
        let entries = std::mem::take(&mut *GITLAB.lock().unwrap_or_else(std::sync::PoisonError::into_inner));
        let text = serde_json::to_string_pretty(&Value::Array(entries)).expect("JSON values serialize");
        crate::output::write_atomic(Path::new(GITLAB_REPORT), |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
    }
    Ok(())
}

/// Several lessons' errors at once: a single one is returned as it is (reported at the end
/// like any error); several are each reported now and the run fails with their count.
pub fn each(mut errors: Vec<CliError>, total: usize) -> Option<CliError> {
    if errors.len() <= 1 {
        return errors.pop();
    }
    let n = errors.len();
    for e in &errors {
        if emit(&of_error(e)).is_err() {
            return Some(CliError::StdoutClosed);
        }
        if !jsonl() {
            super::out::eprint_line(format_args!("error: {e}"));
        }
    }
    Some(CliError::Input(super::check::invalid_line(n, total)))
}

/// A workflow command's message: `%`, CR and LF escaped (GitHub's `escapeData`).
fn data(s: &str) -> String {
    s.replace('%', "%25").replace('\r', "%0D").replace('\n', "%0A")
}

/// A workflow command's property: as [`data`], and `:` and `,` too (GitHub's `escapeProperty`).
fn property(s: &str) -> String {
    data(s).replace(':', "%3A").replace(',', "%2C")
}

/// `--format` and `--annotations` of `check`, `figures` and `snapshot` (flattened into each).
#[derive(Debug, Clone, clap::Args)]
pub struct ReportFlags {
    /// How errors and warnings are printed: text on stderr, or one JSON object each on
    /// stdout, which then holds nothing else (fields in docs/cli.md, "Diagnostics for tools").
    #[arg(long, value_enum, default_value = "text")]
    pub format: MessageFormat,
    /// Also report each error and warning where a CI shows it: `github` (workflow commands
    /// on the lesson's line; the default under GITHUB_ACTIONS=true), `gitlab` (a
    /// code-quality report, gl-code-quality-report.json), `none`.
    #[arg(long, value_enum, value_name = "WHERE")]
    pub annotations: Option<Annotations>,
}

impl ReportFlags {
    /// Sets the run's sink from the flags.
    pub fn configure(&self) -> Sink {
        configure(self.format == MessageFormat::Jsonl, self.annotations)
    }
}

/// `--format` of the commands whose main output is files: how their messages are printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MessageFormat {
    /// Text: `file:line:col: message` and a hint.
    Text,
    /// One JSON object per diagnostic.
    Jsonl,
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
            file: Some("lessons/my,lesson.toml".into()),
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
        let g = d.gitlab().expect("a diagnostic about a file");
        assert_eq!(g["location"]["lines"]["begin"], 12);
        assert_eq!(g["fingerprint"].as_str().unwrap().len(), 32);
        assert_eq!(g["fingerprint"], sample().gitlab().unwrap()["fingerprint"], "stable");
        let usage = Diagnostic { file: None, at: None, ..sample() };
        assert!(usage.gitlab().is_none(), "an argument error has no place in the repository");
        assert!(usage.github().starts_with("::error title=shadelab lesson::"), "{}", usage.github());
        assert_eq!(usage.json()["file"], Value::Null);
    }
}
