//! Diagnose face: discrepancy discovery (issue 6, `cutcal_diagnose`) on files, through
//! `cutcal_report::diagnose::diagnose_files` (what `cutcal diagnose` calls), returning the JSON
//! document of `cutcal diagnose --json`.

use std::path::PathBuf;

use cutcal_report::diagnose::{diagnose_files, DiagnoseRequest as LibRequest, ForwardModel};

use crate::errors::{face, FaceResult};

/// Inputs of a diagnosis (the CLI's flags).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DiagnoseRequest {
    /// Recordings CSV (the test CSV format).
    pub recordings: PathBuf,
    /// Simulation CSV (Mode A), or none (Mode B: cutcal's forward model).
    pub simulation: Option<PathBuf>,
    /// Material TOML (required in Mode B).
    pub material: Option<PathBuf>,
    /// JC TOML fixing JC in Mode B.
    pub jc: Option<PathBuf>,
    /// Refit JC even though `jc` is given.
    pub free_jc: bool,
    /// `"oxley"` (default and only value: the project's one forward model).
    pub model: Option<String>,
}

/// Runs the diagnosis and returns the report as the CLI's pretty JSON.
pub fn diagnose_json(req: &DiagnoseRequest) -> FaceResult<String> {
    let model = match req.model.as_deref().unwrap_or("oxley") {
        "oxley" => ForwardModel::Oxley,
        other => return Err(face(anyhow::anyhow!("model must be \"oxley\", got {other:?}"))),
    };
    let args = LibRequest {
        recordings: req.recordings.clone(),
        simulation: req.simulation.clone(),
        material: req.material.clone(),
        jc: req.jc.clone(),
        free_jc: req.free_jc,
        model,
    };
    let report = diagnose_files(&args).map_err(face)?;
    serde_json::to_string_pretty(&report).map_err(face)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::errors::ErrorKind;

    #[test]
    fn a_missing_recordings_file_is_an_input_error_naming_it() {
        let req = DiagnoseRequest { recordings: "no/such.csv".into(), ..Default::default() };
        let e = diagnose_json(&req).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Input);
        assert!(e.message.starts_with("no/such.csv: field `(file)`"), "{}", e.message);
    }
}
