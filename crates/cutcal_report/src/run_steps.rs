//! The optional steps of `cutcal run` around the identification (issue 13): a project that starts
//! from raw force signals (`signals = "dir"`: the recordings reduction turns them into the test
//! rows first) and one that ends with the discrepancy diagnosis (`diagnose = true`).
//!
//! Both reuse the subcommands' own functions ([`crate::recordings::reduce_signals`],
//! [`crate::diagnose::diagnose_files`]), so a project runs exactly what the commands run.

use std::path::{Path, PathBuf};

use cutcal_io::output::StagedDir;
use cutcal_io::signal_csv::ChannelMap;
use cutcal_io::tests_csv::{parse_tests_with_columns, Columns};
use cutcal_model::{CuttingTest, JcParams};
use serde::Serialize;

use crate::diagnose::{diagnose_files, DiagnoseRequest, ForwardModel};
use crate::error::{Context, Result};
use crate::recordings::{plot, reduce_signals, TestSummary};
use crate::Progress;

/// The rows of a signals project: the reduction's output CSV, parsed.
#[derive(Debug)]
pub struct SignalRows {
    /// The tests with the measured forces and their sd filled in.
    pub tests: Vec<CuttingTest>,
    /// Header of the written CSV.
    pub columns: Columns,
    /// Per-test reduction summaries (written to `recordings.json`).
    pub summaries: Vec<TestSummary>,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
}

/// Name of the rows CSV a signals project writes.
pub const MEASURED_TESTS: &str = "measured_tests.csv";

/// Reduces `<signals>/<test>.csv` for every row of the conditions file `tests` and writes the
/// rows (`measured_tests.csv`), the JSON summary (`recordings.json`) and one SVG per reduced test
/// (`recordings/<test>.svg`) into `staged`. Paths in the outputs are shown as the project file
/// writes them (`signals_rel`, `tests_rel`), never absolute.
pub fn signals_step(
    staged: &StagedDir,
    tests: &Path,
    tests_rel: &Path,
    signals: &Path,
    signals_rel: &Path,
    progress: &dyn Progress,
) -> Result<SignalRows> {
    let shown = |p: &Path| -> String {
        if p == tests {
            tests_rel.display().to_string()
        } else if let Ok(rest) = p.strip_prefix(signals) {
            signals_rel.join(rest).display().to_string()
        } else {
            signals_rel.display().to_string()
        }
    };
    let rec = reduce_signals(tests, signals, &ChannelMap::default(), None, progress, &shown)?;
    let mut files = Vec::new();
    staged.write(MEASURED_TESTS, rec.csv.as_bytes())?;
    files.push(MEASURED_TESTS.to_string());
    staged.write("recordings.json", (serde_json::to_string_pretty(&rec.summaries)? + "\n").as_bytes())?;
    files.push("recordings.json".to_string());
    for (s, f) in rec.summaries.iter().zip(&rec.files) {
        if let (Some(an), Some(f)) = (&s.analysis, f) {
            let name = format!("recordings/{}.svg", s.test);
            staged.write(&name, plot(s, an, f).as_bytes())?;
            files.push(name);
        }
    }
    let (tests, columns) = parse_tests_with_columns(Path::new(MEASURED_TESTS), &rec.csv)
        .context("the rows written by the recordings reduction")?;
    Ok(SignalRows { tests, columns, summaries: rec.summaries, files })
}

/// The diagnosis of a project, as the report carries it.
#[derive(Debug, Clone, Serialize)]
pub struct ProjectDiagnosis {
    /// The JC set held fixed and where it comes from.
    pub jc_source: String,
    /// The diagnosis report (`cutcal diagnose --json`).
    pub report: serde_json::Value,
    /// Its text form (`cutcal diagnose`).
    pub text: String,
}

/// Runs `cutcal diagnose` Mode B (extended Oxley, the JC set `jc` held fixed: the set the
/// project uses downstream) on the rows in `recordings` (a file), writing `diagnosis_jc.toml`,
/// `diagnosis.txt` and `diagnosis.json` into `staged`; returns the diagnosis and the files.
pub fn diagnosis_step(
    staged: &StagedDir,
    project: &str,
    material: PathBuf,
    recordings: PathBuf,
    jc: (&str, &JcParams),
) -> Result<(ProjectDiagnosis, Vec<String>)> {
    let source =
        format!("cutcal {} run {project}: JC set held fixed in the diagnosis ({})", env!("CARGO_PKG_VERSION"), jc.0);
    staged.write("diagnosis_jc.toml", crate::dpzd_report::jc_toml(jc.1, source)?.as_bytes())?;
    let args = DiagnoseRequest {
        recordings,
        simulation: None,
        material: Some(material),
        jc: Some(staged.path("diagnosis_jc.toml")),
        free_jc: false,
        model: ForwardModel::Oxley,
    };
    let report = diagnose_files(&args).context("diagnosis of the project's tests")?;
    let text = report.to_text();
    let json = serde_json::to_value(&report)?;
    staged.write("diagnosis.txt", text.as_bytes())?;
    staged.write("diagnosis.json", (serde_json::to_string_pretty(&json)? + "\n").as_bytes())?;
    let files = ["diagnosis_jc.toml", "diagnosis.txt", "diagnosis.json"].map(String::from).to_vec();
    Ok((ProjectDiagnosis { jc_source: jc.0.to_string(), report: json, text }, files))
}
