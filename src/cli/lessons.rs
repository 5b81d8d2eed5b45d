//! `shadelab lessons`: list lessons with their titles.

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab lessons`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  The bundled lessons (or ./lessons), with their summaries and figures:
    shadelab lessons
  The lessons of another folder:
    shadelab lessons lessons/")]
pub struct LessonsArgs {
    /// Folder of lessons (default: `lessons` in the current folder, else the lessons of the
    /// source tree this binary was built from).
    #[arg(value_name = "DIR")]
    pub dir: Option<PathBuf>,
}

/// The bundled lessons of the source tree this binary was built from.
const BUNDLED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/lessons");

/// Prints one line per lesson: file, title, figures, summary.
pub fn run(args: LessonsArgs, quiet: bool) -> Result<(), CliError> {
    let dir = match args.dir {
        Some(dir) => {
            if !dir.is_dir() {
                let shown = std::path::absolute(&dir).unwrap_or_else(|_| dir.clone());
                let what = if dir.exists() { "is not a folder" } else { "does not exist" };
                return Err(CliError::Input(format!(
                    "no lessons folder: {} {what}\n  hint: give the folder that holds the lessons: `shadelab lessons PATH`",
                    shown.display()
                )));
            }
            dir
        }
        None => default_dir()?,
    };
    let shown = std::path::absolute(&dir).unwrap_or_else(|_| dir.clone());
    let files = super::figures::lesson_files(std::slice::from_ref(&dir))?;
    if files.is_empty() {
        return Err(CliError::Input(format!(
            "no lessons in {}: it has no *.toml files\n  hint: give the folder that holds the lessons: `shadelab lessons PATH`",
            shown.display()
        )));
    }
    // The listing is the result: -q only checks that there are lessons to list.
    if quiet {
        return Ok(());
    }
    for path in files {
        let name = crate::output::shown_text(&path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default());
        match crate::lesson::load(&path, &[]) {
            Ok(l) => {
                let figs: Vec<&str> = l.figures.iter().map(|f| f.name.as_str()).collect();
                outln!("{name:<28} {}", crate::output::shown_text(&l.title))?;
                if !l.summary.is_empty() {
                    outln!("{:<28} {}", "", l.summary)?;
                }
                if !figs.is_empty() {
                    outln!("{:<28} figures: {}", "", figs.join(", "))?;
                }
            }
            Err(e) => outln!("{name:<28} (invalid: {})", e.message)?,
        }
    }
    Ok(())
}

/// `lessons` in the current folder, else the bundled lessons (said on stderr, so a listing
/// names where its files are).
fn default_dir() -> Result<PathBuf, CliError> {
    let here = PathBuf::from("lessons");
    if here.is_dir() {
        return Ok(here);
    }
    let bundled = PathBuf::from(BUNDLED);
    if bundled.is_dir() {
        super::out::eprint_line(format_args!("lessons in {}", bundled.display()));
        return Ok(bundled);
    }
    let shown = std::path::absolute(&here).unwrap_or(here);
    Err(CliError::Input(format!(
        "no lessons folder: {} does not exist, nor does the source tree's {BUNDLED}\n  hint: run `shadelab lessons` from the shadelab folder, or give the folder: `shadelab lessons PATH`",
        shown.display()
    )))
}
