//! `shadelab lessons`: list lessons with their titles.

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab lessons`.
#[derive(Debug, clap::Args)]
pub struct LessonsArgs {
    /// Folder of lessons.
    #[arg(value_name = "DIR", default_value = "lessons")]
    pub dir: PathBuf,
}

/// Prints one line per lesson: file, title, figures, summary.
pub fn run(args: LessonsArgs) -> Result<(), CliError> {
    if !args.dir.is_dir() {
        return Err(CliError::Input(format!(
            "{}: no such folder (run from the shadelab folder, or give the lessons folder)",
            args.dir.display()
        )));
    }
    let files = super::figures::lesson_files(std::slice::from_ref(&args.dir))?;
    for path in files {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        match crate::lesson::load(&path, &[]) {
            Ok(l) => {
                let figs: Vec<&str> = l.figures.iter().map(|f| f.name.as_str()).collect();
                println!("{name:<28} {}", l.title);
                if !l.summary.is_empty() {
                    println!("{:<28} {}", "", l.summary);
                }
                if !figs.is_empty() {
                    println!("{:<28} figures: {}", "", figs.join(", "));
                }
            }
            Err(e) => println!("{name:<28} (invalid: {})", e.message),
        }
    }
    Ok(())
}
