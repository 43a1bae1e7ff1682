//! `cutcal run PROJECT.toml`: the whole chain for one material into one output directory
//! (`report.md`, `report.json`, JC files, cards, SVG plots), written atomically; the stages are
//! `cutcal_report::stages`.

use std::path::PathBuf;

use anyhow::Result;
use cutcal_report::project::load_project;
use cutcal_report::stages::run_project;

/// Arguments of `cutcal run`.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// Project file (TOML), e.g. fixtures/projects/c38.toml.
    pub project: PathBuf,
    /// Output directory (default: target/pipeline/<project name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the report JSON to stdout.
    #[arg(long)]
    pub json: bool,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs `cutcal run`.
pub fn run(args: &RunArgs) -> Result<()> {
    let project = load_project(&args.project)?;
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("target/pipeline").join(&project.name));
    let progress = crate::progress::Terminal::new(args.quiet);
    let report = run_project(&args.project, &out, &progress);
    progress.finish();
    let report = report?;
    if args.json {
        crate::output::emit_line(&serde_json::to_string_pretty(&report)?)?;
    }
    Ok(())
}
