//! The `shadelab` binary: parse arguments, run, map errors to exit codes.

use clap::Parser;

fn main() {
    let args = shadelab::cli::Args::try_parse().unwrap_or_else(|e| {
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
