//! The `cutcal` binary: parse arguments, run, print the error chain, exit non-zero on failure.

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = cutcal_cli::Cli::parse();
    match cutcal_cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            #[allow(clippy::print_stderr)] // the binary reports the error chain
            {
                eprintln!("error: {e:#}");
            }
            ExitCode::FAILURE
        }
    }
}
