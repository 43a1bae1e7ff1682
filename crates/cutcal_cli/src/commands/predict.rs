//! `cutcal predict`: forces, chip thickness and temperatures of every test of a CSV from a JC set
//! through the extended Oxley model (Lalwani et al. 2009); the work is `cutcal_report::predict`.

use std::path::PathBuf;

use anyhow::Result;
use cutcal_report::predict::{predict_files, table, PredictRequest};

/// Arguments of `cutcal predict`.
#[derive(Debug, Clone, clap::Args)]
pub struct PredictArgs {
    /// Material file (TOML) with K(T), rho*Cp(T); an `[oxley]` table may set eta, psi and ranges.
    #[arg(long)]
    pub material: PathBuf,
    /// Johnson-Cook set (TOML), e.g. fixtures/jc/aisi1045_jaspers2002.toml.
    #[arg(long)]
    pub jc: PathBuf,
    /// Tests (CSV), e.g. fixtures/tests/aisi1045.csv.
    #[arg(long)]
    pub tests: PathBuf,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Work-material temperature, degC (default: the material's room temperature).
    #[arg(long)]
    pub work_temperature_c: Option<f64>,
    /// Use Lalwani et al. 2009's search ranges (C0 2-10, phi 8-45 deg, delta 0.005-0.2) instead of the wide ones.
    #[arg(long)]
    pub lalwani_ranges: bool,
    /// Override the C0 search range: LOW HIGH.
    #[arg(long, num_args = 2, value_names = ["LOW", "HIGH"])]
    pub c0_range: Option<Vec<f64>>,
    /// Override the shear-angle search range, deg: LOW HIGH.
    #[arg(long, num_args = 2, value_names = ["LOW", "HIGH"])]
    pub phi_range_deg: Option<Vec<f64>>,
    /// Override the delta search range: LOW HIGH.
    #[arg(long, num_args = 2, value_names = ["LOW", "HIGH"])]
    pub delta_range: Option<Vec<f64>>,
    /// Oxley's eta (default 0.9, or the material's `[oxley] eta`).
    #[arg(long)]
    pub eta: Option<f64>,
    /// Oxley's psi (default 0.9, or the material's `[oxley] psi`).
    #[arg(long)]
    pub psi: Option<f64>,
    /// Ignore the tests' edge radius and flank wear (sharp, unworn tool: Oxley's chip forces only).
    #[arg(long)]
    pub sharp: bool,
}

impl PredictArgs {
    /// The request these flags stand for.
    #[must_use]
    pub fn request(&self) -> PredictRequest {
        PredictRequest {
            work_temperature_c: self.work_temperature_c,
            lalwani_ranges: self.lalwani_ranges,
            c0_range: self.c0_range.clone(),
            phi_range_deg: self.phi_range_deg.clone(),
            delta_range: self.delta_range.clone(),
            eta: self.eta,
            psi: self.psi,
            sharp: self.sharp,
        }
    }
}

/// Runs `cutcal predict`.
pub fn run(args: &PredictArgs) -> Result<()> {
    let report = predict_files(&args.material, &args.jc, &args.tests, &args.request())?;
    if args.json {
        crate::output::emit_line(&serde_json::to_string_pretty(&report)?)?;
    } else {
        crate::output::emit(&table(&report))?;
    }
    Ok(())
}
