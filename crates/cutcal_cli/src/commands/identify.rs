//! `cutcal identify`: Johnson-Cook parameters from one cutting test through the DPZD model
//! (paper Eq 15), or jointly from every measured test through the extended Oxley model
//! (`--method oxley`). The work is `cutcal_report::{dpzd, bootstrap, joint}`; this module holds
//! the flags, writes the files asked for and prints.

use std::path::PathBuf;

use anyhow::Result;
use cutcal_io::output::write_atomic;
use cutcal_report::bootstrap::BootstrapRequest;
use cutcal_report::dpzd::{ModelChoice, Preset};
use cutcal_report::identify::{identify_test, DpzdRequest};
use cutcal_report::joint::{joint_files, parse_fix, JointRequest};

/// Identification method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// One test through the DPZD model (paper Eq 15).
    Dpzd,
    /// All measured tests at once through the extended Oxley forward model (OXCUT-style).
    Oxley,
}

/// Arguments of `cutcal identify`.
#[derive(Debug, Clone, clap::Args)]
pub struct IdentifyArgs {
    /// Material file (TOML), e.g. fixtures/materials/c38.toml.
    #[arg(long)]
    pub material: PathBuf,
    /// Test file (CSV), e.g. fixtures/tests/c38.csv.
    #[arg(long)]
    pub tests: PathBuf,
    /// Test id to identify from (default: the material's `dpzd.identification_test`).
    #[arg(long)]
    pub test: Option<String>,
    /// Identification method: `dpzd` (one test, paper Eq 15) or `oxley` (every measured test
    /// through the forward model; Fc, Ft and tc as relative errors).
    #[arg(long, value_enum, default_value_t = Method::Dpzd)]
    pub method: Method,
    /// Skip the chip thickness in the joint Oxley fit even where measured.
    #[arg(long)]
    pub no_chip: bool,
    /// Joint Oxley fit: ignore the tests' edge radius and flank wear (sharp, unworn tool).
    #[arg(long)]
    pub sharp: bool,
    /// Joint Oxley fit: material class of the literature box for n, C and m (steel, titanium,
    /// aluminium, none); default from the density.
    #[arg(long)]
    pub class: Option<String>,
    /// Joint Oxley fit: fix a parameter, NAME=VALUE (a_mpa, b_mpa, n, c, m; repeatable).
    #[arg(long = "fix", value_name = "NAME=VALUE")]
    pub fix: Vec<String>,
    /// DPZD model variant.
    #[arg(long, value_enum, default_value_t = ModelChoice::Enhanced)]
    pub model: ModelChoice,
    /// Identification preset: `converged` (default) or `paper` (reproduces Table 4).
    #[arg(long, value_enum, default_value_t = Preset::Converged)]
    pub preset: Preset,
    /// Primary shear zone thickness h, mm (the `paper` preset forces 0.1; default 0.1 otherwise).
    #[arg(long)]
    pub h_mm: Option<f64>,
    /// Number of uniform interior fit points N of Eq 15 (`paper` preset only; it forces 51).
    #[arg(long)]
    pub points: Option<usize>,
    /// Strain-rate exponent r of Eq 2 (default: the material's `dpzd.r`).
    #[arg(long)]
    pub r: Option<f64>,
    /// Multistart starts (default 32 for `dpzd`; 4 for `oxley`, whose starts take ~1 s each).
    #[arg(long)]
    pub starts: Option<usize>,
    /// Multistart seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Run a local search from every start point (`dpzd`): no MLSL filter of the start points
    /// (by default a point with a better one within the critical distance is not searched).
    #[arg(long)]
    pub every_start: bool,
    /// Constant rho*Cp of the original model, J/(cm^3 K) (default: the material's value, else 3.5325).
    #[arg(long)]
    pub rho_cp_original: Option<f64>,
    /// Enhanced fixed point tolerance on the exit temperature, K.
    #[arg(long, default_value_t = 1e-6)]
    pub tolerance_c: f64,
    /// Enhanced fixed point iteration cap.
    #[arg(long, default_value_t = 50)]
    pub max_iterations: usize,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write the zone fields (x, gamma, gammadot, eps, epsdot, tau, T) to this CSV.
    #[arg(long)]
    pub fields_csv: Option<PathBuf>,
    /// Write the identified JC set to this TOML (loadable by --jc).
    #[arg(long)]
    pub out_jc: Option<PathBuf>,
    /// Parameter uncertainty by bootstrap (issue 7; `cutcal_report::bootstrap`).
    #[command(flatten)]
    pub uncertainty: BootstrapArgs,
}

/// Bootstrap options of `cutcal identify`.
#[derive(Debug, Clone, clap::Args)]
pub struct BootstrapArgs {
    /// Resample the measured Fc, Ft and tc this many times and report the JC parameter spread (0: off).
    #[arg(long, default_value_t = 0)]
    pub bootstrap: usize,
    /// Relative standard uncertainty of the measured forces (0.03 = 3 %); default: the row's
    /// `fc_sd_n_per_mm` / `ft_sd_n_per_mm` when present, else 3 %.
    #[arg(long)]
    pub force_uncertainty: Option<f64>,
    /// Relative standard uncertainty of the measured chip thickness (0.05 = 5 %); default: the
    /// row's `chip_sd_mm` when present, else 5 %.
    #[arg(long)]
    pub chip_uncertainty: Option<f64>,
    /// Multistart starts per Monte-Carlo sample (the first at the nominal solution).
    #[arg(long, default_value_t = 2)]
    pub bootstrap_starts: usize,
    /// Vary only the measurements, not the unstated choices h and r.
    #[arg(long)]
    pub noise_only: bool,
    /// Range of the factor on h varied with the measurements (log-uniform): LOW HIGH.
    #[arg(long, num_args = 2, value_names = ["LOW", "HIGH"], default_values_t = [0.5, 2.0])]
    pub h_factor_range: Vec<f64>,
    /// Half-width of the uniform range of r varied with the measurements (nominal r +- this).
    #[arg(long, default_value_t = 1.0)]
    pub r_half_width: f64,
}

impl BootstrapArgs {
    fn request(&self) -> BootstrapRequest {
        BootstrapRequest {
            bootstrap: self.bootstrap,
            force_uncertainty: self.force_uncertainty,
            chip_uncertainty: self.chip_uncertainty,
            bootstrap_starts: self.bootstrap_starts,
            noise_only: self.noise_only,
            h_factor_range: self.h_factor_range.clone(),
            r_half_width: self.r_half_width,
        }
    }
}

impl IdentifyArgs {
    /// The DPZD request these flags stand for.
    #[must_use]
    pub fn dpzd_request(&self) -> DpzdRequest {
        DpzdRequest {
            model: self.model,
            preset: self.preset,
            h_mm: self.h_mm,
            points: self.points,
            r: self.r,
            starts: self.starts,
            seed: self.seed,
            every_start: self.every_start,
            rho_cp_original: self.rho_cp_original,
            tolerance_c: self.tolerance_c,
            max_iterations: self.max_iterations,
        }
    }
}

/// Runs `cutcal identify --method oxley`: the joint fit, printed.
fn run_joint(args: &IdentifyArgs) -> Result<()> {
    let req = JointRequest {
        starts: args.starts.unwrap_or(4),
        seed: args.seed,
        work_temperature_c: None,
        use_chip_thickness: !args.no_chip,
        tool_condition: !args.sharp,
        class: args.class.clone(),
        fix: args.fix.iter().map(|f| parse_fix(f)).collect::<Result<Vec<_>, _>>()?,
    };
    let (mf, id) = joint_files(&args.material, &args.tests, &req)?;
    if args.json {
        crate::output::emit_line(&serde_json::to_string_pretty(&id)?)?;
    } else {
        crate::output::emit(&cutcal_report::joint::table(&mf.material.name, &id))?;
    }
    Ok(())
}

/// Runs `cutcal identify`.
pub fn run(args: &IdentifyArgs) -> Result<()> {
    if args.method == Method::Oxley {
        return run_joint(args);
    }
    let run = identify_test(
        &args.material,
        &args.tests,
        args.test.as_deref(),
        &args.dpzd_request(),
        &args.uncertainty.request(),
    )?;
    if let Some(p) = &args.fields_csv {
        write_atomic(p, cutcal_report::dpzd_report::fields_csv(&run.outcome.zone, 201)?.as_bytes())?;
    }
    if let Some(p) = &args.out_jc {
        write_atomic(p, run.jc_toml()?.as_bytes())?;
    }
    if args.json {
        crate::output::emit_line(&run.json()?)?;
    } else {
        crate::output::emit(&run.text())?;
    }
    Ok(())
}
