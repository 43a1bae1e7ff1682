//! `cutcal diagnose`: locate the mismatch between a simulation and the recordings, name the missing
//! physics, refit and show the held-out improvement (issue 6); the work is
//! `cutcal_report::diagnose`.

use std::path::PathBuf;

use anyhow::{Context, Result};
use cutcal_io::output::write_atomic;
use cutcal_report::diagnose::{diagnose_files, residual_plot, DiagnoseRequest, ForwardModel};

/// Arguments of `cutcal diagnose`.
#[derive(Debug, Clone, clap::Args)]
pub struct DiagnoseArgs {
    /// Recordings CSV: test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,chip_mm[,...].
    #[arg(long)]
    pub recordings: PathBuf,
    /// Simulation CSV (Mode A): test,fc_n_per_mm,ft_n_per_mm,chip_mm[,t_ab_c,t_int_c,shear_angle_deg].
    #[arg(long)]
    pub simulation: Option<PathBuf>,
    /// Material TOML (required in Mode B; in Mode A it gives the shadow model its thermal
    /// properties, else the generic class (steel, titanium, aluminium) that matches the simulation).
    #[arg(long)]
    pub material: Option<PathBuf>,
    /// JC TOML: fixes JC in Mode B (or sets the prior centre with --free-jc); in Mode A the shadow's
    /// starting JC set (else the class's nominal set or the material's bounds centre).
    #[arg(long)]
    pub jc: Option<PathBuf>,
    /// Refit JC jointly even though --jc is given (it becomes the prior centre).
    #[arg(long)]
    pub free_jc: bool,
    /// Forward model of Mode B.
    #[arg(long, value_enum, default_value_t = ForwardModel::Oxley)]
    pub model: ForwardModel,
    /// Print the JSON report instead of text.
    #[arg(long)]
    pub json: bool,
    /// Write an SVG plot of the residuals before and after.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

impl DiagnoseArgs {
    /// The request these flags stand for.
    #[must_use]
    pub fn request(&self) -> DiagnoseRequest {
        DiagnoseRequest {
            recordings: self.recordings.clone(),
            simulation: self.simulation.clone(),
            material: self.material.clone(),
            jc: self.jc.clone(),
            free_jc: self.free_jc,
            model: self.model,
        }
    }
}

/// Runs `cutcal diagnose`.
pub fn run(args: &DiagnoseArgs) -> Result<()> {
    let report = diagnose_files(&args.request())?;
    if let Some(p) = &args.plot {
        write_atomic(p, residual_plot(&report).as_bytes()).with_context(|| format!("writing {}", p.display()))?;
    }
    if args.json {
        crate::output::emit_line(&serde_json::to_string_pretty(&report)?)?;
    } else {
        crate::output::emit(&report.to_text())?;
    }
    Ok(())
}
