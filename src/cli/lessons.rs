//! `shadelab lessons`: list lessons with their titles.

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab lessons`.
#[derive(Debug, clap::Args)]
pub struct LessonsArgs {
    /// Folder of lessons (default: `lessons` in the current folder).
    #[arg(value_name = "DIR", default_value = "lessons")]
    pub dir: PathBuf,
}

/// Prints one line per lesson: file, title, figures, summary.
pub fn run(args: LessonsArgs) -> Result<(), CliError> {
    let shown = std::path::absolute(&args.dir).unwrap_or_else(|_| args.dir.clone());
    if !args.dir.is_dir() {
        let what = if args.dir.exists() { "is not a folder" } else { "does not exist" };
        let default = if args.dir.as_os_str() == "lessons" { " (the default: `lessons` in the current folder)" } else { "" };
        return Err(CliError::Input(format!(
            "no lessons folder: {} {what}{default}\n  hint: run `shadelab lessons` from the shadelab folder, or give the folder: `shadelab lessons PATH`",
            shown.display()
        )));
    }
    let files = super::figures::lesson_files(std::slice::from_ref(&args.dir))?;
    if files.is_empty() {
        return Err(CliError::Input(format!(
            "no lessons in {}: it has no *.toml files\n  hint: give the folder that holds the lessons: `shadelab lessons PATH`",
            shown.display()
        )));
    }
    for path in files {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        match crate::lesson::load(&path, &[]) {
            Ok(l) => {
                let figs: Vec<&str> = l.figures.iter().map(|f| f.name.as_str()).collect();
                outln!("{name:<28} {}", l.title)?;
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
