//! The `shadelab` binary: parse arguments, run, map errors to exit codes.

use clap::FromArgMatches;

fn main() {
    let args = shadelab::cli::command().try_get_matches().and_then(|m| shadelab::cli::Args::from_arg_matches(&m)).unwrap_or_else(|e| {
        // A tool that asked for JSON Lines gets the usage error as one, too (exit 2).
        shadelab::cli::usage_error_json(&e, std::env::args_os());
        e.exit()
    });
    match shadelab::cli::run(args) {
        // `| head` closed the pipe: the reader has what it wanted (as ripgrep does).
        Ok(()) | Err(shadelab::cli::CliError::StdoutClosed) => {}
        Err(e) => {
            shadelab::cli::out::eprint_line(format_args!("error: {e}"));
            std::process::exit(e.exit_code());
        }
    }
}
