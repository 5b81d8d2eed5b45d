//! `shadelab completions` and `shadelab man`: generated from the one clap definition
//! ([`super::Args`]), so they never disagree with `--help`.

use super::CliError;
use std::path::PathBuf;

/// Arguments of `shadelab completions`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  Bash (load it from ~/.bashrc, or put it in ~/.local/share/bash-completion/completions/shadelab):
    shadelab completions bash > shadelab.bash
  Zsh (a file named _shadelab in a folder of your $fpath):
    shadelab completions zsh > _shadelab
  Fish (~/.config/fish/completions/shadelab.fish) and PowerShell (dot-source it from $PROFILE):
    shadelab completions fish > shadelab.fish
    shadelab completions powershell > shadelab.ps1")]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum, value_name = "SHELL")]
    pub shell: clap_complete::Shell,
}

/// Arguments of `shadelab man`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  The main page (options and the list of subcommands), read with man:
    shadelab man > shadelab.1
  One page per subcommand too (shadelab-render.1, shadelab-brdf-lobe.1, ...) in man/:
    shadelab man -o man/")]
pub struct ManArgs {
    /// Folder to write shadelab.1 and one page per subcommand into, created if needed
    /// [default: the main page on stdout].
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
}

/// Prints the completion script for a shell.
pub fn run_completions(args: CompletionsArgs) -> Result<(), CliError> {
    let mut script = Vec::new();
    // Into memory first: clap_complete panics on a failed write, and `| head` is not a failure.
    clap_complete::generate(args.shell, &mut super::command(), "shadelab", &mut script);
    out!("{}", String::from_utf8_lossy(&script))
}

/// Every page of the man tree: the command's own, then its subcommands', depth first.
fn pages(cmd: &clap::Command, out: &mut Vec<(String, Vec<u8>)>) -> Result<(), CliError> {
    let man = clap_mangen::Man::new(cmd.clone());
    let mut roff = Vec::new();
    man.render(&mut roff).map_err(|e| CliError::Internal(format!("cannot render the man page: {e}")))?;
    out.push((man.get_filename(), roff));
    for sub in cmd.get_subcommands().filter(|s| !s.is_hide_set()) {
        pages(sub, out)?;
    }
    Ok(())
}

/// Prints the main man page, or writes every page into `-o DIR`.
pub fn run_man(args: ManArgs, quiet: bool) -> Result<(), CliError> {
    let mut cmd = super::command().disable_help_subcommand(true);
    // Built, each subcommand knows its full name (`shadelab-render`) for its page.
    cmd.build();
    let Some(dir) = args.output else {
        let mut roff = Vec::new();
        clap_mangen::Man::new(cmd).render(&mut roff).map_err(|e| CliError::Internal(format!("cannot render the man page: {e}")))?;
        return out!("{}", String::from_utf8_lossy(&roff));
    };
    crate::output::check_folder(&dir, &dir)?;
    let start = std::time::Instant::now();
    let mut all = Vec::new();
    pages(&cmd, &mut all)?;
    for (name, roff) in &all {
        crate::output::write_atomic(&dir.join(name), |w| w.write_all(roff).map_err(|e| e.to_string()))?;
        if !quiet {
            outln!("wrote {}", dir.join(name).display())?;
        }
    }
    outln!("{}", super::progress::summary(all.len(), "man page", "man pages", start.elapsed(), Some(&dir)))
}
