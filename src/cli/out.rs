//! Standard output for every subcommand, in one place.
//!
//! `shadelab ... | head -1` closes the pipe after the first line; the next write then
//! fails with `BrokenPipe` (Rust ignores SIGPIPE, so `println!` would panic). As ripgrep
//! does, that is a quiet, successful end: [`CliError::StdoutClosed`] stops the command
//! and `main` exits with 0 without printing anything.

use super::CliError;
use std::fmt;
use std::io::Write;

/// Writes formatted text to stdout and flushes it.
///
/// # Errors
/// [`CliError::StdoutClosed`] when the reader has gone away; [`CliError::Internal`] for
/// any other write failure.
pub fn print(args: fmt::Arguments<'_>) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    // Text from lessons and file names reaches the terminal without its control characters.
    let text = args.as_str().map_or_else(|| args.to_string().into(), std::borrow::Cow::Borrowed);
    out.write_all(crate::output::terminal_safe(&text).as_bytes()).and_then(|()| out.flush()).map_err(stdout_error)
}

/// `eprintln!` for subcommands and `main`: the line without control characters but its line
/// feeds (see [`crate::output::terminal_safe`]).
pub fn eprint_line(args: fmt::Arguments<'_>) {
    let text = args.to_string();
    eprintln!("{}", crate::output::terminal_safe(&text));
}

/// The [`CliError`] for a failed write to stdout.
pub fn stdout_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::StdoutClosed
    } else {
        CliError::Internal(format!("cannot write to stdout: {e}"))
    }
}

/// A command's summary line: on stdout, or on stderr under `--format jsonl` (whose stdout
/// holds only diagnostics).
///
/// # Errors
/// As [`print`].
pub fn result_line(line: &str) -> Result<(), CliError> {
    if super::diagnostics::jsonl() {
        eprint_line(format_args!("{line}"));
        Ok(())
    } else {
        print(format_args!("{line}\n"))
    }
}
