//! The `shadelab` binary: parse arguments, run, map errors to exit codes.

use clap::Parser;

fn main() {
    let args = shadelab::cli::Args::parse();
    match shadelab::cli::run(args) {
        // `| head` closed the pipe: the reader has what it wanted (as ripgrep does).
        Ok(()) | Err(shadelab::cli::CliError::StdoutClosed) => {}
        Err(e) => {
            shadelab::cli::out::eprint_line(format_args!("error: {e}"));
            std::process::exit(e.exit_code());
        }
    }
}
