//! The result of a DPZD identification as the CLI prints it and `cutcal run` stores it: the JSON
//! report (`cutcal identify --json`), the readable table, the zone fields CSV (the data of the
//! paper's Fig 4) and the JC file of an identified set; and [`identify_test`], what
//! `cutcal identify` computes from its files before it prints.

use std::fmt::Write as _;
use std::path::Path;

use cutcal_io::material_file::{load_material, MaterialFile};
use cutcal_io::tests_csv::{load_tests_measuring, MeasuredColumn};
use cutcal_model::dpzd::ZoneSolution;
use cutcal_model::{CuttingTest, RateTerm};
use serde::Serialize;

use crate::dpzd::{identify_dpzd, pick_test, DpzdOutcome, DpzdRequest, DpzdSettings, ModelChoice, Preset};
use crate::error::Result;

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

/// A DPZD identification of one test of a tests file (what `cutcal identify` computes before it
/// prints), with the Monte-Carlo spread when the bootstrap request asks for it.
#[derive(Debug, Clone)]
pub struct IdentifiedTest {
    /// The material file.
    pub material: MaterialFile,
    /// The test identified from.
    pub test: CuttingTest,
    /// The resolved settings.
    pub settings: DpzdSettings,
    /// The identification.
    pub outcome: DpzdOutcome,
    /// The bootstrap, when asked for.
    pub bootstrap: Option<crate::bootstrap::BootstrapOutcome>,
}

/// Reads the material and the tests, picks the test (`test`, else the material's
/// `dpzd.identification_test`), identifies it and runs the bootstrap when `boot` asks for it
/// (before anything is written, so a failed bootstrap leaves nothing behind).
///
/// Returns an error if a file is malformed (located), the tests lack Fc, Ft or tc, the test is not
/// there, the request is refused, or the identification or the bootstrap fails.
pub fn identify_test(
    material: &Path,
    tests: &Path,
    test: Option<&str>,
    req: &DpzdRequest,
    boot: &crate::bootstrap::BootstrapRequest,
) -> Result<IdentifiedTest> {
    let mf = load_material(material)?;
    let all = load_tests_measuring(
        tests,
        &[MeasuredColumn::CuttingForce, MeasuredColumn::FeedForce, MeasuredColumn::ChipThickness],
        "the DPZD identification (paper Eq 15) needs the measured Fc, Ft and tc",
    )?;
    let test = pick_test(&all, test, &mf, tests)?.clone();
    let settings = req.settings(&mf)?;
    let outcome = identify_dpzd(&mf, &test, &settings)?;
    let bootstrap = crate::bootstrap::run_bootstrap(boot, &mf, &test, &outcome.settings_at_h_used(&settings))?;
    Ok(IdentifiedTest { material: mf, test, settings, outcome, bootstrap })
}

impl IdentifiedTest {
    /// The identified set as a JC file (TOML) whose `source` names the run.
    pub fn jc_toml(&self) -> Result<String> {
        let r = &self.outcome.report;
        let src = format!(
            "cutcal {} identify: {} test {} ({:?} DPZD)",
            env!("CARGO_PKG_VERSION"),
            r.material,
            r.test,
            self.settings.model
        );
        jc_toml(&self.outcome.identification.jc, src)
    }

    /// The JSON document of `cutcal identify --json` (with `bootstrap` when there is one).
    pub fn json(&self) -> Result<String> {
        crate::bootstrap::report_json(&self.outcome.report, self.bootstrap.as_ref())
    }

    /// The readable report of `cutcal identify` (with the bootstrap table when there is one).
    #[must_use]
    pub fn text(&self) -> String {
        let mut s = render_table(&self.outcome.report);
        if let Some(b) = &self.bootstrap {
            s.push_str(&crate::bootstrap::render_bootstrap(b));
        }
        s
    }
}
