//! Every xtask and its options, in one place.

use std::path::PathBuf;

/// cutcal's development tasks.
#[derive(Debug, clap::Parser)]
#[command(name = "cargo xtask")]
pub struct Xtask {
    /// The task.
    #[command(subcommand)]
    pub task: Task,
}

/// The tasks.
#[derive(Debug, clap::Subcommand)]
pub enum Task {
    /// Run every project in fixtures/projects through the whole chain into target/pipeline/.
    Pipeline(PipelineFlags),
}

/// Options of `cargo xtask pipeline`.
#[derive(Debug, clap::Args)]
pub struct PipelineFlags {
    /// Output root.
    #[arg(long, default_value = "target/pipeline")]
    pub out: PathBuf,
    /// Projects directory.
    #[arg(long, default_value = "fixtures/projects")]
    pub projects: PathBuf,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
    /// Print a JSON summary instead of the table.
    #[arg(long)]
    pub json: bool,
}
