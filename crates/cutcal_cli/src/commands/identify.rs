//! `cutcal identify`: Johnson-Cook parameters from one cutting test through the DPZD model
//! (paper Eq 15), original or enhanced.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use cutcal_ident::{
    identify_converged, identify_from_zone_with, ConvergedOptions, JcBounds, JcConstants, JcIdentification,
    MultistartOptions,
};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState, ZoneSolution};
use cutcal_model::{CuttingTest, RateTerm};
use serde::Serialize;

use cutcal_io::material_file::{load_material, MaterialFile};
use cutcal_io::output::write_atomic;
use cutcal_io::tests_csv::{load_tests_measuring, MeasuredColumn};

/// Which DPZD model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ModelChoice {
    /// Thermally uncoupled model (constant rho*Cp, tau0(Tr) at both boundaries).
    Original,
    /// Thermomechanically enhanced model (paper Sec 3.3-3.5).
    Enhanced,
}

/// Identification preset (issue 11; docs/identification.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Preset {
    /// Default: the Eq 15 objective as a zone integral (adaptive Gauss-Kronrod, converged in A,
    /// B, C), the solvers' JC law (rate term clamped at eps0, as the exported cards).
    Converged,
    /// Reproduces Table 4: N = 51 uniform points, h = 0.1 mm, rhoCp = 3.5325 J/(cm^3 K) for the
    /// original model and the unclamped rate term. Choices made to reproduce Table 4; the paper
    /// states none of them.
    Paper,
}

impl Preset {
    /// The sentence the report prints about the preset.
    #[must_use]
    pub fn note(self) -> &'static str {
        match self {
            Preset::Converged => "preset converged: Eq 15 as the zone integral (1/h) int (f-F)^2 dx by adaptive Gauss-Kronrod 7/15, converged in A, B, C; JC rate term clamped at eps0 (the law of the exported cards)",
            Preset::Paper => "preset paper: N = 51, h = 0.1 mm, rhoCp = 3.5325 J/(cm^3 K), unclamped rate term; choices made to reproduce Table 4 (the paper states none of them); the exported cards clamp the rate term, so this set is not the cards' law",
        }
    }
}

/// Identification method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
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
    /// Parameter uncertainty by bootstrap (issue 7; see `commands/bootstrap.rs`).
    #[command(flatten)]
    pub uncertainty: super::bootstrap::BootstrapArgs,
}

/// JC parameters in report units: the JC file form (MPa, degC), without a source in reports.
pub type JcReport = cutcal_io::jc_file::JcFile;

/// The machine-readable result of a DPZD identification.
#[derive(Debug, Clone, Serialize)]
pub struct DpzdIdentifyReport {
    /// Material name.
    pub material: String,
    /// Test id.
    pub test: String,
    /// Model variant.
    pub model: ModelChoice,
    /// Identification preset.
    pub preset: Preset,
    /// What the preset means (stated in every report).
    pub preset_note: String,
    /// Rate term of the identified law.
    pub rate_term: RateTerm,
    /// Quadrature nodes of the converged rule (`None` for the paper preset).
    pub quadrature_nodes: Option<usize>,
    /// Zone thickness, mm.
    pub h_mm: f64,
    /// Exponent r.
    pub r: f64,
    /// Fit points.
    pub points: usize,
    /// Shear angle from the chip ratio, deg.
    pub shear_angle_deg: f64,
    /// Maximum shear stress (Eq 9), MPa.
    pub tau_max_mpa: f64,
    /// Maximum effective strain 2 gamma_AB / sqrt(3).
    pub max_effective_strain: f64,
    /// Shear-plane strain rate (effective), 1/s.
    pub max_effective_strain_rate_per_s: f64,
    /// Shear-plane (AB) temperature, degC.
    pub t_ab_c: f64,
    /// Exit (EF) temperature, degC.
    pub t_ef_c: f64,
    /// Exit shear strength, MPa.
    pub tau0_ef_mpa: f64,
    /// Fixed-point iterations.
    pub iterations: usize,
    /// Identified JC set.
    pub jc: JcReport,
    /// Eq 15 objective, MPa.
    pub objective_mpa: f64,
    /// RMS residual, MPa.
    pub rms_mpa: f64,
    /// Parameters at a bound.
    pub at_bounds: Vec<String>,
    /// Free parameters (order of covariance/correlation).
    pub free: Vec<String>,
    /// Linearised `s^2 (J^T J)^-1` standard errors of the free parameters (A, B in MPa). Kept for
    /// the record only: the residuals are deterministic model misfit, not noise, so this is NOT an
    /// uncertainty (issue 11); the spread comes from the Monte-Carlo propagation.
    pub std_errors: Option<Vec<f64>>,
    /// Correlation matrix of the free parameters.
    pub correlation: Option<Vec<Vec<f64>>>,
    /// Covariance matrix of the free parameters.
    pub covariance: Option<Vec<Vec<f64>>>,
    /// Condition number of J^T J on the free set.
    pub condition_number: Option<f64>,
    /// Multistart starts.
    pub starts: usize,
    /// Starts reaching the best minimum.
    pub starts_at_best: usize,
    /// Index of the best start.
    pub best_start: usize,
    /// Starts that stopped at the LM iteration cap (excluded from the best; if every start does,
    /// the identification fails with a typed non-convergence).
    pub unconverged_starts: usize,
    /// Multistart seed.
    pub seed: u64,
    /// Residual field at the fit points: x (mm) and JC - DPZD stress (MPa).
    pub residual_field: Vec<[f64; 2]>,
    /// Where h comes from (user, paper preset, or the forward model's l_AB/C0).
    pub h_source: String,
    /// The h values of the forward-model fixed point, mm (one value when h was given).
    pub h_history_mm: Vec<f64>,
    /// A, B and C identified over h/2..2h around the h used.
    pub h_sensitivity: Vec<HSensitivityRow>,
}

/// Settings of one DPZD identification (resolved from CLI or project file).
#[derive(Debug, Clone)]
pub struct DpzdSettings {
    /// Model variant.
    pub model: ModelChoice,
    /// Identification preset.
    pub preset: Preset,
    /// Zone thickness, m (the start of the fixed point when `h_from_forward_model`).
    pub h_m: f64,
    /// Take h from the forward model (`l_AB / C0`, self-consistent with the identified set)
    /// instead of `h_m`.
    pub h_from_forward_model: bool,
    /// Exponent r.
    pub r: f64,
    /// Fit points.
    pub points: usize,
    /// Constant rho*Cp of the original model, J/(m^3 K).
    pub rho_cp_original_j_per_m3_k: f64,
    /// Fixed-point tolerance, K.
    pub tolerance_c: f64,
    /// Fixed-point cap.
    pub max_iterations: usize,
    /// Multistart options.
    pub multistart: MultistartOptions,
}

impl DpzdSettings {
    /// The DPZD configuration.
    pub fn config(&self) -> Result<DpzdConfig> {
        let variant = match self.model {
            ModelChoice::Original => DpzdVariant::Original { rho_cp_j_per_m3_k: self.rho_cp_original_j_per_m3_k },
            ModelChoice::Enhanced => {
                DpzdVariant::Enhanced { tolerance_c: self.tolerance_c, max_iterations: self.max_iterations }
            }
        };
        Ok(DpzdConfig::new(self.h_m, self.r, variant)?)
    }
}

impl DpzdOutcome {
    /// `settings` with h fixed at the value this outcome used (for the Monte-Carlo propagation,
    /// which varies the measurements at that h; h's own influence is the h-sensitivity table).
    #[must_use]
    pub fn settings_at_h_used(&self, settings: &DpzdSettings) -> DpzdSettings {
        DpzdSettings { h_m: self.report.h_mm * 1e-3, h_from_forward_model: false, ..settings.clone() }
    }
}

/// Everything a DPZD identification produced.
#[derive(Debug, Clone)]
pub struct DpzdOutcome {
    /// The solved zone.
    pub zone: ZoneSolution,
    /// The identification.
    pub identification: JcIdentification,
    /// The report.
    pub report: DpzdIdentifyReport,
}

/// Bounds of a material file as identification bounds.
pub fn jc_bounds(mf: &MaterialFile) -> Result<JcBounds> {
    let b = mf.bounds.with_context(|| {
        format!("{}: no [bounds] section (identification needs bounds on A, B, n, C, m)", mf.path.display())
    })?;
    Ok(JcBounds { a_mpa: b.a_mpa, b_mpa: b.b_mpa, n: b.n, c: b.c, m: b.m })
}

/// Relative tolerance and cap of the zone-thickness fixed point.
const H_FIXED_POINT: (f64, usize) = (1e-3, 30);
/// Factors of the h-sensitivity table around the h used.
const H_SENSITIVITY_FACTORS: [f64; 5] = [0.5, 0.707, 1.0, 1.414, 2.0];

/// Runs the DPZD identification of `test` (library entry point shared by the CLI and `cutcal run`):
/// h as given, or from the forward model (`cutcal_ident::zone_thickness`), and the h-sensitivity
/// table of A, B and C over h/2..2h.
pub fn identify_dpzd(mf: &MaterialFile, test: &CuttingTest, settings: &DpzdSettings) -> Result<DpzdOutcome> {
    let (mut out, source, history) = if settings.h_from_forward_model {
        let oxley = crate::commands::predict::oxley_options(mf.oxley.as_ref(), false, None, None, None, None, None)?;
        let fp = cutcal_ident::zone_thickness::self_consistent_h::<anyhow::Error>(
            settings.h_m,
            H_FIXED_POINT.0,
            H_FIXED_POINT.1,
            |h| {
                let o = identify_dpzd_at(mf, test, &DpzdSettings { h_m: h, ..settings.clone() })?;
                let z = cutcal_ident::zone_thickness::oxley_zone_thickness(
                    &mf.material,
                    test,
                    &o.identification.jc,
                    &oxley,
                    mf.material.room_c,
                )?;
                Ok(z.h_m)
            },
        );
        match fp {
            Ok(fp) => {
                let o = identify_dpzd_at(mf, test, &DpzdSettings { h_m: fp.h_m, ..settings.clone() })?;
                let history: Vec<f64> = fp.history_m.iter().map(|h| h * 1e3).collect();
                let source = if fp.converged {
                    format!(
                        "forward model: l_AB/C0 of the test's extended-Oxley solution with the identified set, self-consistent to {} in {} steps from {} mm",
                        H_FIXED_POINT.0,
                        fp.history_m.len() - 1,
                        settings.h_m * 1e3
                    )
                } else {
                    format!(
                        "forward model, NOT converged: the fixed point h = l_AB/C0(JC(h)) did not settle in {} steps (history in h_history_mm); the last value is used",
                        H_FIXED_POINT.1
                    )
                };
                (o, source, history)
            }
            Err(e) => {
                let o = identify_dpzd_at(mf, test, settings)?;
                let source =
                    format!("{} mm default: the forward model gave no zone thickness ({:#})", settings.h_m * 1e3, e);
                (o, source, vec![settings.h_m * 1e3])
            }
        }
    } else {
        let o = identify_dpzd_at(mf, test, settings)?;
        let source = match settings.preset {
            Preset::Paper => {
                "paper preset: 0.1 mm, the choice that reproduces Table 4 (the paper states no h)".to_string()
            }
            Preset::Converged => "given by the user (--h-mm)".to_string(),
        };
        (o, source, vec![settings.h_m * 1e3])
    };
    let h_used = out.report.h_mm * 1e-3;
    let mut rows = Vec::new();
    for f in H_SENSITIVITY_FACTORS {
        let row = match identify_dpzd_at(mf, test, &DpzdSettings { h_m: h_used * f, ..settings.clone() }) {
            Ok(o) => HSensitivityRow {
                h_mm: h_used * f * 1e3,
                a_mpa: Some(o.identification.jc.a_pa / 1e6),
                b_mpa: Some(o.identification.jc.b_pa / 1e6),
                c: Some(o.identification.jc.c),
                note: None,
            },
            Err(e) => HSensitivityRow {
                h_mm: h_used * f * 1e3,
                a_mpa: None,
                b_mpa: None,
                c: None,
                note: Some(format!("not available: {e:#}")),
            },
        };
        rows.push(row);
    }
    out.report.h_source = source;
    out.report.h_history_mm = history;
    out.report.h_sensitivity = rows;
    Ok(out)
}

/// One row of the h-sensitivity table.
#[derive(Debug, Clone, Serialize)]
pub struct HSensitivityRow {
    /// Zone thickness, mm.
    pub h_mm: f64,
    /// Identified A, MPa (`None`: not available, see `note`).
    pub a_mpa: Option<f64>,
    /// Identified B, MPa.
    pub b_mpa: Option<f64>,
    /// Identified C.
    pub c: Option<f64>,
    /// Why a value is not available.
    pub note: Option<String>,
}

/// One DPZD identification at the settings' h.
fn identify_dpzd_at(mf: &MaterialFile, test: &CuttingTest, settings: &DpzdSettings) -> Result<DpzdOutcome> {
    let state = ShearPlaneState::from_test(test).with_context(|| format!("test {}", test.id))?;
    let config = settings.config()?;
    let zone = dpzd::solve(&mf.material, &state, &config)
        .with_context(|| format!("DPZD {:?} solve of test {}", settings.model, test.id))?;
    let bounds = jc_bounds(mf)?;
    let constants = JcConstants { eps0_per_s: 1.0, tm_c: mf.material.melting_c, tr_c: mf.material.room_c };
    let ctx = || format!("JC identification from test {} (preset {:?})", test.id, settings.preset);
    let (id, nodes) = match settings.preset {
        Preset::Paper => (
            identify_from_zone_with(
                &zone,
                settings.points,
                RateTerm::Unclamped,
                &bounds,
                constants,
                &settings.multistart,
            )
            .with_context(ctx)?,
            None,
        ),
        Preset::Converged => {
            let c = identify_converged(&zone, &bounds, constants, &settings.multistart, &ConvergedOptions::default())
                .with_context(ctx)?;
            (c.identification, Some(c.nodes))
        }
    };
    let xs: Vec<f64> = id.fit_x_m.iter().map(|x| x * 1e3).collect();
    let s = &id.statistics;
    let report = DpzdIdentifyReport {
        material: mf.material.name.clone(),
        test: test.id.clone(),
        model: settings.model,
        preset: settings.preset,
        preset_note: settings.preset.note().to_string(),
        rate_term: id.rate_term,
        quadrature_nodes: nodes,
        h_mm: settings.h_m * 1e3,
        r: settings.r,
        points: settings.points,
        shear_angle_deg: state.shear_angle_rad.to_degrees(),
        tau_max_mpa: state.tau_max_pa / 1e6,
        max_effective_strain: 2.0 * zone.gamma_ab / 3f64.sqrt(),
        max_effective_strain_rate_per_s: zone.gamma_dot_ab_per_s / 3f64.sqrt(),
        t_ab_c: zone.t_ab_c,
        t_ef_c: zone.t_ef_c,
        tau0_ef_mpa: zone.tau0_ef_pa / 1e6,
        iterations: zone.iterations,
        jc: JcReport::from_params(&id.jc, None),
        objective_mpa: id.objective_mpa,
        rms_mpa: id.rms_mpa,
        at_bounds: s.at_bounds.clone(),
        free: s.free.clone(),
        std_errors: s.std_errors.clone(),
        correlation: s.correlation.clone(),
        covariance: s.covariance.clone(),
        condition_number: s.condition_number,
        starts: id.starts,
        starts_at_best: id.starts_at_best,
        best_start: id.best_start,
        unconverged_starts: id.unconverged_starts,
        seed: settings.multistart.seed,
        residual_field: xs.iter().zip(&id.residuals_mpa).map(|(x, r)| [*x, *r]).collect(),
        h_source: String::new(),
        h_history_mm: Vec::new(),
        h_sensitivity: Vec::new(),
    };
    Ok(DpzdOutcome { zone, identification: id, report })
}

/// The zone fields as CSV (the data behind the paper's Fig 4).
pub fn fields_csv(zone: &ZoneSolution, n: usize) -> Result<String> {
    let mut out = String::from("x_mm,gamma,gamma_dot_per_s,eps,eps_dot_per_s,tau_mpa,sigma_eff_mpa,temperature_c\n");
    for p in zone.profile(n)? {
        writeln!(
            out,
            "{:.6},{:.6},{:.6e},{:.6},{:.6e},{:.4},{:.4},{:.4}",
            p.x_m * 1e3,
            p.gamma,
            p.gamma_dot_per_s,
            p.strain,
            p.strain_rate_per_s,
            p.tau_pa / 1e6,
            p.effective_stress_pa / 1e6,
            p.temperature_c
        )?;
    }
    Ok(out)
}

/// A JC file (TOML) for an identified set.
pub fn jc_toml(jc: &cutcal_model::JcParams, source: String) -> Result<String> {
    Ok(toml::to_string(&cutcal_io::jc_file::JcFile::from_params(jc, Some(source)))?)
}

/// Resolves CLI arguments into settings for `mf`.
pub fn settings_from_args(args: &IdentifyArgs, mf: &MaterialFile) -> Result<DpzdSettings> {
    let r = match (args.r, &mf.dpzd) {
        (Some(r), _) => r,
        (None, Some(d)) => d.r,
        (None, None) => bail!("{}: no [dpzd] r given; pass --r", mf.path.display()),
    };
    let mut rho_cp = args.rho_cp_original.or(mf.dpzd.as_ref().map(|d| d.rho_cp_original_j_per_cm3_k)).unwrap_or(3.5325);
    let (h_mm, points) = match args.preset {
        Preset::Paper => {
            if args.h_mm.is_some_and(|h| h != 0.1) || args.points.is_some_and(|n| n != 51) {
                bail!("--preset paper fixes h = 0.1 mm and N = 51 (the choices that reproduce Table 4); use --preset converged for other values");
            }
            rho_cp = 3.5325;
            (0.1, 51)
        }
        Preset::Converged => {
            if args.points.is_some() {
                bail!("--points applies to --preset paper only: the converged preset integrates over the zone");
            }
            (args.h_mm.unwrap_or(0.1), 51)
        }
    };
    let h_from_forward_model = args.preset == Preset::Converged && args.h_mm.is_none();
    if !(h_mm.is_finite() && h_mm > 0.0) {
        bail!("--h-mm must be a positive number of mm, got {h_mm}");
    }
    Ok(DpzdSettings {
        model: args.model,
        preset: args.preset,
        h_m: h_mm * 1e-3,
        h_from_forward_model,
        r,
        points,
        rho_cp_original_j_per_m3_k: rho_cp * 1e6,
        tolerance_c: args.tolerance_c,
        max_iterations: args.max_iterations,
        multistart: MultistartOptions::new(args.starts.unwrap_or(32), args.seed),
    })
}

/// Finds test `id` (or the material's identification test) in `tests`.
pub fn pick_test<'a>(
    tests: &'a [CuttingTest],
    id: Option<&str>,
    mf: &MaterialFile,
    tests_path: &std::path::Path,
) -> Result<&'a CuttingTest> {
    let id = match id {
        Some(i) => i.to_string(),
        None => mf
            .dpzd
            .as_ref()
            .map(|d| d.identification_test.clone())
            .with_context(|| format!("{}: no [dpzd] identification_test; pass --test", mf.path.display()))?,
    };
    tests.iter().find(|t| t.id == id).with_context(|| {
        let ids: Vec<&str> = tests.iter().map(|t| t.id.as_str()).collect();
        format!("{}: field `test`: no test with id '{id}' (ids: {ids:?})", tests_path.display())
    })
}

/// Human-readable table of a report.
#[must_use]
pub fn render_table(r: &DpzdIdentifyReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "cutcal identify: {} test {} ({:?} DPZD, h = {:.4} mm, r = {})",
        r.material, r.test, r.model, r.h_mm, r.r
    );
    let _ = writeln!(s, "  {}", r.preset_note);
    match r.quadrature_nodes {
        Some(n) => {
            let _ = writeln!(s, "  quadrature nodes   {n:>10}");
        }
        None => {
            let _ = writeln!(s, "  fit points N       {:>10}", r.points);
        }
    }
    let _ = writeln!(s, "  shear angle        {:>10.2} deg", r.shear_angle_deg);
    let _ = writeln!(s, "  tau_max (Eq 9)     {:>10.1} MPa", r.tau_max_mpa);
    let _ = writeln!(s, "  max eff. strain    {:>10.3}", r.max_effective_strain);
    let _ = writeln!(s, "  max eff. rate      {:>10.3e} 1/s", r.max_effective_strain_rate_per_s);
    let _ = writeln!(s, "  T_AB               {:>10.1} degC", r.t_ab_c);
    let _ = writeln!(s, "  T_EF               {:>10.1} degC   ({} fixed-point iterations)", r.t_ef_c, r.iterations);
    let _ = writeln!(s, "  parameter      value   note");
    let note = |name: &str| if r.at_bounds.iter().any(|a| a == name) { "at bound" } else { "" };
    let _ = writeln!(s, "  A [MPa]     {:>10.2}   {}", r.jc.a_mpa, note("a_mpa"));
    let _ = writeln!(s, "  B [MPa]     {:>10.2}   {}", r.jc.b_mpa, note("b_mpa"));
    let _ = writeln!(s, "  n           {:>10.4}   {}", r.jc.n, note("n"));
    let _ = writeln!(s, "  C           {:>10.5}   {}", r.jc.c, note("c"));
    let _ = writeln!(s, "  m           {:>10.4}   {}", r.jc.m, note("m"));
    let _ = writeln!(
        s,
        "  (no std.err: s^2 (J^T J)^-1 of deterministic model residuals has no statistical meaning; use --bootstrap N for a Monte-Carlo spread)"
    );
    let _ = writeln!(s, "  eps0 = {} 1/s, Tm = {} degC, Tr = {} degC", r.jc.eps0_per_s, r.jc.tm_c, r.jc.tr_c);
    let _ = writeln!(s, "  h = {:.4} mm: {}", r.h_mm, r.h_source);
    if r.h_history_mm.len() > 1 {
        let steps: Vec<String> = r.h_history_mm.iter().map(|h| format!("{h:.4}")).collect();
        let _ = writeln!(s, "  h fixed point [mm]: {}", steps.join(" -> "));
    }
    if !r.h_sensitivity.is_empty() {
        let _ = writeln!(s, "  h sensitivity (A, B and C only reparametrise with h; n and m do not):");
        for row in &r.h_sensitivity {
            match (row.a_mpa, row.b_mpa, row.c) {
                (Some(a), Some(b), Some(c)) => {
                    let _ = writeln!(s, "    h {:>8.4} mm: A {:>8.2} MPa, B {:>8.2} MPa, C {:.5}", row.h_mm, a, b, c);
                }
                _ => {
                    let _ =
                        writeln!(s, "    h {:>8.4} mm: {}", row.h_mm, row.note.as_deref().unwrap_or("not available"));
                }
            }
        }
    }
    let _ = writeln!(
        s,
        "  objective (Eq 15) {:.2} MPa, RMS {:.2} MPa; {}/{} starts reached the best minimum (seed {})",
        r.objective_mpa, r.rms_mpa, r.starts_at_best, r.starts, r.seed
    );
    if r.unconverged_starts > 0 {
        let _ = writeln!(
            s,
            "  {} of {} starts stopped at the LM iteration cap and were excluded",
            r.unconverged_starts, r.starts
        );
    }
    if let Some(c) = &r.correlation {
        let _ = writeln!(s, "  correlation of free parameters {:?}:", r.free);
        for row in c {
            let cells: Vec<String> = row.iter().map(|v| format!("{v:>7.3}")).collect();
            let _ = writeln!(s, "    {}", cells.join(" "));
        }
    }
    s
}

/// Runs `cutcal identify` (DPZD method).
pub fn run(args: &IdentifyArgs) -> Result<()> {
    if args.method == Method::Oxley {
        return super::identify_oxley::run(&super::identify_oxley::IdentifyOxleyArgs {
            material: args.material.clone(),
            tests: args.tests.clone(),
            starts: args.starts.unwrap_or(4),
            seed: args.seed,
            json: args.json,
            work_temperature_c: None,
            no_chip: args.no_chip,
            sharp: args.sharp,
            class: args.class.clone(),
            fix: args.fix.clone(),
        });
    }
    let mf = load_material(&args.material)?;
    let tests = load_tests_measuring(
        &args.tests,
        &[MeasuredColumn::CuttingForce, MeasuredColumn::FeedForce, MeasuredColumn::ChipThickness],
        "the DPZD identification (paper Eq 15) needs the measured Fc, Ft and tc",
    )?;
    let test = pick_test(&tests, args.test.as_deref(), &mf, &args.tests)?;
    let settings = settings_from_args(args, &mf)?;
    let out = identify_dpzd(&mf, test, &settings)?;
    // Issue 7: bootstrap before any file is written, so a failed bootstrap leaves nothing behind.
    let boot = super::bootstrap::run_bootstrap(&args.uncertainty, &mf, test, &out.settings_at_h_used(&settings))?;
    if let Some(p) = &args.fields_csv {
        write_atomic(p, fields_csv(&out.zone, 201)?.as_bytes())?;
    }
    if let Some(p) = &args.out_jc {
        let src = format!(
            "cutcal {} identify: {} test {} ({:?} DPZD)",
            env!("CARGO_PKG_VERSION"),
            out.report.material,
            out.report.test,
            args.model
        );
        write_atomic(p, jc_toml(&out.identification.jc, src)?.as_bytes())?;
    }
    if args.json {
        println!("{}", super::bootstrap::report_json(&out.report, boot.as_ref())?);
    } else {
        print!("{}", render_table(&out.report));
        if let Some(b) = &boot {
            print!("{}", super::bootstrap::render_bootstrap(b));
        }
    }
    Ok(())
}
