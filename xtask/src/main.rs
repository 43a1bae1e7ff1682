//! `cargo xtask <task>`: cutcal's automation in plain Rust (rust-analyzer style). This file only
//! dispatches; options live in `flags.rs`, each task in its own file.
// xtask is a command-line program: printing is its job.
#![allow(clippy::print_stdout, clippy::print_stderr)]

mod concealed;
mod flags;
mod pipeline;
mod signals;
mod tidy;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;

/// The repository root (xtask lives one level below it).
fn project_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("."))
}

fn main() -> ExitCode {
    let flags = flags::Xtask::parse();
    if let Err(e) = std::env::set_current_dir(project_root()) {
        eprintln!("error: cannot enter the project root: {e}");
        return ExitCode::FAILURE;
    }
    let result = match flags.task {
        flags::Task::Pipeline(f) => pipeline::run(&f),
        flags::Task::Signals(f) => signals::run(&f.out),
        flags::Task::Concealed(f) => {
            let parsed = concealed::Family::parse_list(&f.family)
                .and_then(|fams| concealed::NuisanceScope::parse(&f.nuisance).map(|n| (fams, n)));
            parsed.map_err(anyhow::Error::msg).and_then(|(families, nuisance)| {
                concealed::run(&concealed::ConcealedOptions {
                    families,
                    datasets: f.datasets,
                    seed: f.seed,
                    out: f.out,
                    markdown: f.markdown,
                    threads: f.threads,
                    material: f.material,
                    generate_only: f.generate_only,
                    nuisance,
                })
            })
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
