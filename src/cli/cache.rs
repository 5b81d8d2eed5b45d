//! `shadelab cache`: where the on-disk cache is, how big it is, and emptying it.

use super::CliError;

/// Arguments of `shadelab cache`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Where the cache is and what it holds:
    shadelab cache
  Empty it (the next `figures` renders everything afresh and keeps it again):
    shadelab cache --clear
  The cache of a course's CI job, kept between its runs:
    shadelab --cache .shadelab-cache cache")]
pub struct CacheArgs {
    /// Remove every entry (results are recomputed on their next use).
    #[arg(long)]
    pub clear: bool,
}

/// Prints the folder, its entries and size; with `--clear`, empties it first.
pub fn run(args: CacheArgs, quiet: bool) -> Result<(), CliError> {
    let Some(dir) = crate::cache::dir() else {
        return outln!("the cache is off (--no-cache or $SHADELAB_NO_CACHE): nothing is kept between runs");
    };
    if args.clear {
        let removed = crate::cache::clear(&dir).map_err(|e| {
            CliError::Input(format!(
                "cannot clear the cache in {}: {}\n  hint: check the folder's permissions, or remove it by hand",
                dir.display(),
                crate::output::io_reason(&e)
            ))
        })?;
        if !quiet {
            outln!("removed {removed} file{} from {}", if removed == 1 { "" } else { "s" }, dir.display())?;
        }
    }
    let (entries, bytes) = crate::cache::usage(&dir);
    outln!("{}: {entries} entr{}, {:.1} MB", dir.display(), if entries == 1 { "y" } else { "ies" }, bytes as f64 / 1e6)
}
