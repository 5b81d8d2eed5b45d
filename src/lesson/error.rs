//! Lesson errors: where (file:line:col or a `--set` argument), which key, what, and a hint.

use std::fmt;
use std::path::PathBuf;

/// Where a lesson error was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Location {
    /// A position in the lesson file (1-based line and column, in characters).
    File {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
    },
    /// A command-line override with its flag: `--set KEY=VALUE` as given, or one value of a
    /// `--vary` of `compare` or `sweep` as `--vary KEY=VALUE`.
    Flag(String),
    /// The file as a whole (it could not be read).
    Whole,
}

/// A lesson that cannot be used: always the user's input, so the CLI exits with 2.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub struct LessonError {
    /// The lesson file.
    pub file: PathBuf,
    /// Where in it (or in which `--set`).
    pub location: Location,
    /// Dotted key path (`material.plastic.shininess`), when the error is about a key.
    pub key: Option<String>,
    /// What is wrong.
    pub message: String,
    /// How to fix it.
    pub hint: Option<String>,
    /// The other errors found in the same run, in file order after this one (validation
    /// reports up to [`crate::lesson::limits::MAX_ERRORS`] in all).
    pub others: Others,
}

/// The further errors of one run.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Others(Vec<LessonError>);

impl Others {
    /// The errors, in order.
    pub fn iter(&self) -> std::slice::Iter<'_, LessonError> {
        self.0.iter()
    }

    /// How many.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The last one, if any.
    pub fn last(&self) -> Option<&LessonError> {
        self.0.last()
    }
}

impl From<Vec<LessonError>> for Others {
    fn from(v: Vec<LessonError>) -> Self {
        Others(v)
    }
}

impl LessonError {
    /// One error and its others, sorted by place in the file (then `--set` flags, then the
    /// whole file), cut to [`crate::lesson::limits::MAX_ERRORS`]; `None` for no errors.
    pub fn combine(errors: Vec<LessonError>) -> Option<LessonError> {
        let mut all: Vec<LessonError> = Vec::new();
        for mut e in errors {
            let others = std::mem::take(&mut e.others);
            all.push(e);
            all.extend(others.iter().cloned());
        }
        let rank = |e: &LessonError| match &e.location {
            Location::File { line, col } => (0, *line, *col),
            Location::Flag(_) => (1, 0, 0),
            Location::Whole => (2, 0, 0),
        };
        all.sort_by_key(rank);
        all.dedup_by(|a, b| a.location == b.location && a.key == b.key && a.message == b.message);
        all.truncate(crate::lesson::limits::MAX_ERRORS);
        let mut all = all.into_iter();
        let mut first = all.next()?;
        first.others = all.collect::<Vec<_>>().into();
        Some(first)
    }

    /// How many errors this one reports (itself and its others).
    pub fn count(&self) -> usize {
        1 + self.others.len()
    }
}

impl fmt::Display for LessonError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let file = crate::output::shown_path(&self.file);
        match &self.location {
            Location::File { line, col } => write!(f, "{file}:{line}:{col}: ")?,
            Location::Flag(arg) => write!(f, "{file}: in {arg}: ")?,
            Location::Whole => write!(f, "{file}: ")?,
        }
        if let Some(key) = &self.key {
            write!(f, "`{key}`: ")?;
        }
        write!(f, "{}", self.message)?;
        if let Some(hint) = &self.hint {
            write!(f, "\n  hint: {hint}")?;
        }
        for other in self.others.iter() {
            write!(f, "\nerror: {other}")?;
        }
        Ok(())
    }
}
