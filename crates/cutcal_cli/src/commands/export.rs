//! `cutcal export`: FE cards (Abaqus, LS-DYNA, DEFORM-style, MatML) from a material file and a JC
//! file, rendered and written atomically by `cutcal_report::export` (issue 4; fe-cards.md).

use std::path::PathBuf;

use anyhow::Result;
use cutcal_report::export::{export_files, ExportRequest, FormatChoice, UnitsChoice};

/// Arguments of `cutcal export`.
#[derive(Debug, Clone, clap::Args)]
pub struct ExportArgs {
    /// Workpiece material file (TOML) with an [interface] section, e.g. fixtures/materials/c38.toml.
    #[arg(long)]
    pub material: PathBuf,
    /// Johnson-Cook file (TOML), e.g. fixtures/jc/c38_table5.toml.
    #[arg(long)]
    pub jc: PathBuf,
    /// Which cards to write.
    #[arg(long, value_enum)]
    pub format: FormatChoice,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Unit system of the Abaqus and LS-DYNA cards.
    #[arg(long, value_enum, default_value_t = UnitsChoice::TonneMmS)]
    pub units: UnitsChoice,
    /// Lowest table temperature, degC (default: the workpiece's validity range start).
    #[arg(long)]
    pub t_from_c: Option<f64>,
    /// Highest table temperature, degC (default: the workpiece's validity range end).
    #[arg(long)]
    pub t_to_c: Option<f64>,
    /// Table temperature step, degC.
    #[arg(long, default_value_t = 100.0)]
    pub t_step_c: f64,
    /// Strain rate of the tabular Abaqus *PLASTIC variant, 1/s.
    #[arg(long, default_value_t = 1e4)]
    pub strain_rate: f64,
    /// Fraction of plastic work converted to heat (Taylor-Quinney; not given in the paper).
    #[arg(long, default_value_t = 0.9)]
    pub heat_fraction: f64,
    /// Source test named in the headers (default: the JC file name).
    #[arg(long)]
    pub source_test: Option<String>,
    /// Model variant named in the headers.
    #[arg(long, default_value = "as identified in the JC file")]
    pub model_variant: String,
    /// Tool-chip contact temperature, degC, at which the LS-DYNA FS = 2 friction table evaluates
    /// k(T) (LS-DYNA cannot take k(T) there; docs/fe-cards.md). Default: the homologous
    /// temperature 0.5 of the JC set, stated in the deck. A measured interface temperature or the
    /// extended Oxley prediction (`cutcal predict`) is better.
    #[arg(long)]
    pub contact_temperature_c: Option<f64>,
    /// Cutting speed, m/min: the LS-DYNA deck then gets *CONTROL_TERMINATION for the paper's 8 mm
    /// cut (Sec 5.1). Without it no termination card is written (stated in the deck).
    #[arg(long)]
    pub cutting_speed_m_min: Option<f64>,
    /// Cutting tests (CSV, e.g. fixtures/tests/c38.csv): with `--format lsdyna` or `all`, one
    /// complete 2-D LS-DYNA deck per test is written beside the cards, `<material>_cut2d_<test>.k`
    /// (docs/fe-cards.md, "Complete 2-D decks").
    #[arg(long)]
    pub tests: Option<PathBuf>,
    /// Only this test of `--tests`.
    #[arg(long, requires = "tests")]
    pub test: Option<String>,
}

impl ExportArgs {
    /// The request these flags stand for.
    #[must_use]
    pub fn request(&self) -> ExportRequest {
        ExportRequest {
            format: self.format,
            units: self.units,
            t_from_c: self.t_from_c,
            t_to_c: self.t_to_c,
            t_step_c: self.t_step_c,
            strain_rate: self.strain_rate,
            heat_fraction: self.heat_fraction,
            source_test: self.source_test.clone(),
            model_variant: self.model_variant.clone(),
            contact_temperature_c: self.contact_temperature_c,
            cutting_speed_m_min: self.cutting_speed_m_min,
            tests: self.tests.clone(),
            test: self.test.clone(),
        }
    }
}

/// Runs `cutcal export`.
pub fn run(args: &ExportArgs) -> Result<()> {
    for p in export_files(&args.material, &args.jc, &args.out, &args.request())? {
        crate::output::emit_line(&format!("wrote {}", p.display()))?;
    }
    Ok(())
}
