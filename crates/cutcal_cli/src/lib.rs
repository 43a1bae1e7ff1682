//! cutcal_cli: the command-line face of cutcal. Parses arguments (clap), calls the libraries
//! (`cutcal_report` for the work, `cutcal_io` for files) and prints; the `cutcal` binary is a thin
//! wrapper over [`run`]. The Python module (`cutcal_py`) is the other face over the same calls.
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]
#![warn(missing_docs)]
// The CLI prints its results: that is its job.
#![allow(clippy::print_stdout)]

pub mod commands;
pub mod output;
pub mod progress;

use anyhow::Result;
use clap::{Parser, Subcommand};

/// cutcal: orthogonal cutting tests -> Johnson-Cook parameters -> FE cards and predictions.
#[derive(Debug, Parser)]
#[command(name = "cutcal", version, about)]
pub struct Cli {
    /// The job.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Identify Johnson-Cook parameters from a cutting test (DPZD, paper Eq 15).
    Identify(commands::identify::IdentifyArgs),
    /// Predict Fc, Ft, tc and temperatures with the extended Oxley model (Lalwani 2009).
    Predict(commands::predict::PredictArgs),
    /// Locate the mismatch between simulation and recordings and name the missing physics.
    Diagnose(commands::diagnose::DiagnoseArgs),
    /// Write FE cards (Abaqus, LS-DYNA, DEFORM-style, MatML) from a material and a JC file.
    Export(commands::export::ExportArgs),
    /// Run a whole project: identification, cards, predictions, report.
    Run(commands::run::RunArgs),
    /// Reduce raw dynamometer force signals to test rows with their own sd, drift and BUE flags.
    Recordings(commands::recordings::RecordingsArgs),
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Identify(a) => commands::identify::run(&a),
        Command::Run(a) => commands::run::run(&a),
        Command::Export(a) => commands::export::run(&a),
        Command::Predict(a) => commands::predict::run(&a),
        Command::Diagnose(a) => commands::diagnose::run(&a),
        Command::Recordings(a) => commands::recordings::run(&a),
    }
}
