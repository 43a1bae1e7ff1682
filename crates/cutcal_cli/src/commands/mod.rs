//! One module per `cutcal` subcommand: a clap `Args` struct and a `run` function that calls
//! `cutcal_report` and prints.

pub mod diagnose;
pub mod export;
pub mod identify;
pub mod predict;
pub mod recordings;
pub mod run;
