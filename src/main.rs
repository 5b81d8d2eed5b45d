//! The `shadelab` binary: parse arguments, run, map errors to exit codes.

use clap::Parser;

fn main() {
    let args = shadelab::cli::Args::parse();
    match shadelab::cli::run(args) {
        Ok(()) => {}
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(e.exit_code());
        }
    }
}
