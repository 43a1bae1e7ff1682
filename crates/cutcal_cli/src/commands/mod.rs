//! One module per `cutcal` subcommand: a clap `Args` struct and a `run` function.

pub mod bootstrap;
pub mod diagnose;
pub mod export;
pub mod identify;
pub mod identify_oxley;
pub mod predict;
pub mod recordings;
pub mod run;
pub mod run_steps;
