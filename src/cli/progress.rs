//! The progress bar and the one summary line of the multi-file commands.
//!
//! The bar is drawn on stderr only when stderr is a terminal (indicatif draws nothing to a
//! pipe or a file), and never under `-q`; lines printed while it runs go through
//! [`Progress::println`] so the bar does not tear them.

use super::CliError;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::Path;
use std::time::{Duration, Instant};

/// A bar of `len` steps with N of M and ETA, and the clock for the summary line.
pub struct Progress {
    bar: ProgressBar,
    start: Instant,
}

impl Progress {
    /// Starts a bar of `len` steps (hidden under `quiet` or when stderr is not a terminal).
    pub fn new(len: u64, quiet: bool) -> Self {
        let target = if quiet { ProgressDrawTarget::hidden() } else { ProgressDrawTarget::stderr() };
        let bar = ProgressBar::with_draw_target(Some(len), target);
        bar.set_style(ProgressStyle::with_template("{bar:30} {pos}/{len} ETA {eta} {wide_msg}").expect("valid template"));
        // Redrawn on a timer too, so the ETA moves during a long step.
        bar.enable_steady_tick(Duration::from_millis(250));
        Progress { bar, start: Instant::now() }
    }

    /// Says what runs now.
    pub fn message(&self, msg: String) {
        // Names come from files: no control character reaches the terminal.
        self.bar.set_message(crate::output::shown_text(&msg));
    }

    /// One step done.
    pub fn inc(&self) {
        self.bar.inc(1);
    }

    /// Moves the bar to `pos` steps done.
    pub fn set(&self, pos: u64) {
        self.bar.set_position(pos);
    }

    /// Steps done so far.
    pub fn position(&self) -> u64 {
        self.bar.position()
    }

    /// Prints a line on stdout with the bar out of the way.
    ///
    /// # Errors
    /// As [`super::out::print`].
    pub fn println(&self, line: std::fmt::Arguments<'_>) -> Result<(), CliError> {
        self.bar.suspend(|| super::out::print(format_args!("{line}\n")))
    }

    /// Removes the bar; returns the time since [`Progress::new`].
    pub fn finish(&self) -> Duration {
        self.bar.finish_and_clear();
        self.start.elapsed()
    }
}

/// The summary line: `40 figures in 15.3 s → out/` (`→ DIR/` only when files were written).
pub fn summary(count: usize, one: &str, many: &str, elapsed: Duration, dest: Option<&Path>) -> String {
    let noun = if count == 1 { one } else { many };
    let mut s = format!("{count} {noun} in {:.1} s", elapsed.as_secs_f64());
    if let Some(dir) = dest {
        let shown = dir.display().to_string();
        let slash = if shown.ends_with('/') { "" } else { "/" };
        s += &format!(" → {shown}{slash}");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_names_the_count_the_time_and_the_folder() {
        let t = Duration::from_millis(15_340);
        assert_eq!(summary(40, "figure", "figures", t, Some(Path::new("out"))), "40 figures in 15.3 s → out/");
        assert_eq!(summary(1, "figure", "figures", t, Some(Path::new("out/"))), "1 figure in 15.3 s → out/");
        assert_eq!(summary(3, "lesson", "lessons", t, None), "3 lessons in 15.3 s");
    }
}
