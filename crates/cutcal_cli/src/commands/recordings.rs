//! `cutcal recordings`: raw dynamometer force signals -> test rows with their own noise
//! (docs/recordings.md); the work is `cutcal_report::recordings`.

use std::path::PathBuf;

use anyhow::Result;
use cutcal_report::recordings::{record_files, table};

/// Arguments of `cutcal recordings`.
#[derive(Debug, Clone, clap::Args)]
pub struct RecordingsArgs {
    /// Tests CSV with the conditions (forces may be empty).
    #[arg(long)]
    pub tests: PathBuf,
    /// Directory with one signal file `<test>.csv` per test.
    #[arg(long)]
    pub signals: PathBuf,
    /// Output tests CSV (default: `<tests stem>_measured.csv` beside the input).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the JSON summary on stdout instead of the table (the `.json` file is written anyway).
    #[arg(long)]
    pub json: bool,
    /// Write one SVG per test into this directory.
    #[arg(long)]
    pub plots: Option<PathBuf>,
    /// Column names of the channels, e.g. `fc=Fz,ft=Fx,fp=Fy` (and `time=...`).
    #[arg(long)]
    pub channels: Option<String>,
    /// Use this window `t0,t1` (s) instead of detecting it.
    #[arg(long)]
    pub window: Option<String>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs `cutcal recordings`.
pub fn run(a: &RecordingsArgs) -> Result<()> {
    let progress = crate::progress::Terminal::new(a.quiet);
    let r = record_files(
        &a.tests,
        &a.signals,
        a.out.as_deref(),
        a.plots.as_deref(),
        a.channels.as_deref(),
        a.window.as_deref(),
        &progress,
    );
    progress.finish();
    let r = r?;
    if a.json {
        crate::output::emit_line(&r.json)?;
    } else {
        crate::output::emit(&table(&r))?;
    }
    Ok(())
}
