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
    /// Independent concealed-physics benchmark of `cutcal diagnose` (issue 10, item 5).
    Concealed(ConcealedFlags),
    /// Write the SYNTHETIC signal set of the signals project (fixtures/signals/c38/).
    Signals(SignalsFlags),
}

/// Options of `cargo xtask signals`.
#[derive(Debug, clap::Args)]
pub struct SignalsFlags {
    /// Output directory.
    #[arg(long, default_value = "fixtures/signals/c38")]
    pub out: PathBuf,
}

/// Options of `cargo xtask concealed`.
#[derive(Debug, clap::Args)]
pub struct ConcealedFlags {
    /// Generator family: `a` (the detector may be tuned on it), `b`, `c` or `d` (never tuned on),
    /// `both` (a and b), `all` (a, b and c) or a comma list such as `a,b,c,d`.
    #[arg(long, default_value = "both")]
    pub family: String,
    /// Number of datasets per family.
    #[arg(long, default_value_t = 200)]
    pub datasets: usize,
    /// Seed of the generator.
    #[arg(long, default_value_t = 2024)]
    pub seed: u64,
    /// Output directory (data/, truth-*.json, outcomes-*.json, scores.json, summary.md).
    #[arg(long, default_value = "target/concealed")]
    pub out: PathBuf,
    /// Also write the page here (e.g. docs/concealed.md).
    #[arg(long)]
    pub markdown: Option<PathBuf>,
    /// Worker threads.
    #[arg(long, default_value_t = 2)]
    pub threads: usize,
    /// Material-spread check: force one work material on every dataset (AISI1045, AISI4340,
    /// Ti6Al4V, AA2024-T351, OFHC-Cu, Nickel200). The benchmark's figures use the default draw.
    #[arg(long)]
    pub material: Option<String>,
    /// Generate data/, truth-<family>.json and the generation-failure count only: no diagnosis, no
    /// outcomes, scores or page; a generation summary on stderr.
    #[arg(long)]
    pub generate_only: bool,
    /// Which constants each dataset's nuisance perturbs: `full` (eta and psi +-3 %, thermal
    /// constants and JC +-5 %; the benchmark's figures) or `eta-psi` (eta and psi +-3 % only, the
    /// nuisance the issue states for its own independent suite; a check, not the headline).
    #[arg(long, default_value = "full")]
    pub nuisance: String,
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
