//! The DPZD identification of one test (paper Eq 15, Secs 3-4), original or enhanced: the
//! settings a request resolves to, h as given or from the forward model (`l_AB/C0`, made
//! self-consistent with the identified set), and the h-sensitivity table. The CLI's `identify`,
//! `cutcal run` and the Python module all call [`identify_dpzd`].

use cutcal_ident::{
    identify_converged, identify_from_zone_with, ConvergedOptions, JcBounds, JcConstants, JcIdentification,
    MultistartOptions,
};
use cutcal_io::material_file::MaterialFile;
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState, ZoneSolution};
use cutcal_model::{CuttingTest, RateTerm};
use serde::Serialize;

use crate::error::{Context, Error, Result};

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
    /// Starts reaching the best minimum (including those stopped on joining it).
    pub starts_at_best: usize,
    /// Starts stopped early by the multistart basin rule on joining a minimum an earlier start
    /// converged to (Rinnooy Kan & Timmer 1987; `cutcal_ident::multistart`).
    pub stopped_starts: usize,
    /// Of `stopped_starts`, those that joined the best minimum.
    pub stopped_at_best: usize,
    /// Sample points from which no local search was started: a sample point with a lower
    /// objective lay within the MLSL critical distance (Rinnooy Kan & Timmer 1987;
    /// `cutcal_ident::multistart`). They never count in `starts_at_best`.
    pub filtered_starts: usize,
    /// That critical distance (unit box of n, C, m); absent when no filter ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub critical_distance: Option<f64>,
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

/// Which DPZD model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum ModelChoice {
    /// Thermally uncoupled model (constant rho*Cp, tau0(Tr) at both boundaries).
    Original,
    /// Thermomechanically enhanced model (paper Sec 3.3-3.5).
    Enhanced,
}

/// Identification preset (issue 11; docs/identification.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
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
        let oxley = crate::predict::oxley_options(mf.oxley.as_ref(), false, None, None, None, None, None)?;
        let fp = cutcal_ident::zone_thickness::self_consistent_h::<Error>(
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
                let source = format!(
                    "{} mm default: the forward model gave no zone thickness ({})",
                    settings.h_m * 1e3,
                    e.chain_text()
                );
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
                note: Some(format!("not available: {}", e.chain_text())),
            },
        };
        rows.push(row);
    }
    out.report.h_source = source;
    out.report.h_history_mm = history;
    out.report.h_sensitivity = rows;
    Ok(out)
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
        stopped_starts: id.stopped_starts,
        stopped_at_best: id.stopped_at_best,
        filtered_starts: id.filtered_starts,
        critical_distance: id.critical_distance,
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
