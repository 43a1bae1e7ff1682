//! `cargo xtask pipeline`: a thin driver over `cutcal run` for every project in
//! `fixtures/projects/`, writing `target/pipeline/<project>/` and one summary table.

use std::fs;

use anyhow::{bail, Context, Result};

use crate::flags::PipelineFlags;

/// Runs every project file (sorted by name) and prints a summary.
pub fn run(flags: &PipelineFlags) -> Result<()> {
    let mut projects: Vec<_> = fs::read_dir(&flags.projects)
        .with_context(|| format!("cannot read the projects directory {}", flags.projects.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    projects.sort();
    if projects.is_empty() {
        bail!("{}: no project files (*.toml)", flags.projects.display());
    }
    let mut summary = Vec::new();
    for p in &projects {
        let project = cutcal_cli::commands::run::load_project(p)?;
        let out = flags.out.join(&project.name);
        let report = cutcal_cli::commands::run::run_project(p, &out, flags.quiet)
            .with_context(|| format!("project {}", p.display()))?;
        summary.push(report);
    }
    if flags.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    println!(
        "{:<10} {:<10} {:>9} {:>9} {:>7} {:>8} {:>6} {:>7} {:>6}",
        "project", "model", "A [MPa]", "B [MPa]", "n", "C", "m", "RMS", "files"
    );
    for r in &summary {
        if r.identification.is_empty() {
            println!(
                "{:<10} {:<10} {:>9} {:>9} {:>7} {:>8} {:>6} {:>7} {:>6}",
                r.project,
                "-",
                "-",
                "-",
                "-",
                "-",
                "-",
                "-",
                r.files.len()
            );
        }
        for (k, i) in &r.identification {
            println!(
                "{:<10} {:<10} {:>9.1} {:>9.1} {:>7.3} {:>8.4} {:>6.3} {:>7.1} {:>6}",
                r.project,
                k,
                i.jc.a_mpa,
                i.jc.b_mpa,
                i.jc.n,
                i.jc.c,
                i.jc.m,
                i.rms_mpa,
                r.files.len()
            );
        }
    }
    println!("outputs in {}/<project>/", flags.out.display());
    Ok(())
}
