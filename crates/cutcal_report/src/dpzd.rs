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

use crate::bail;
use crate::dpzd_report::{DpzdIdentifyReport, HSensitivityRow, JcReport};
use crate::error::{Context, Error, Result};

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

/// Options of one DPZD identification, as the CLI's `identify` flags and the Python keywords
/// give them; [`DpzdRequest::settings`] resolves them against a material file.
#[derive(Debug, Clone, PartialEq)]
pub struct DpzdRequest {
    /// DPZD model variant.
    pub model: ModelChoice,
    /// Identification preset.
    pub preset: Preset,
    /// Zone thickness h, mm (`None`: the forward model's for `converged`, 0.1 for `paper`).
    pub h_mm: Option<f64>,
    /// Uniform interior fit points N of Eq 15 (`paper` preset only; it forces 51).
    pub points: Option<usize>,
    /// Strain-rate exponent r of Eq 2 (default: the material's `dpzd.r`).
    pub r: Option<f64>,
    /// Multistart starts (default 32).
    pub starts: Option<usize>,
    /// Multistart seed.
    pub seed: u64,
    /// Constant rho*Cp of the original model, J/(cm^3 K) (default: the material's, else 3.5325).
    pub rho_cp_original: Option<f64>,
    /// Enhanced fixed point tolerance on the exit temperature, K.
    pub tolerance_c: f64,
    /// Enhanced fixed point iteration cap.
    pub max_iterations: usize,
}

impl Default for DpzdRequest {
    fn default() -> Self {
        Self {
            model: ModelChoice::Enhanced,
            preset: Preset::Converged,
            h_mm: None,
            points: None,
            r: None,
            starts: None,
            seed: 1,
            rho_cp_original: None,
            tolerance_c: 1e-6,
            max_iterations: 50,
        }
    }
}

impl DpzdRequest {
    /// Resolves the request into settings for `mf`.
    ///
    /// Returns an error if r is neither given nor in the material, if the `paper` preset is asked
    /// for other h or N than its own, or if h is not a positive number.
    pub fn settings(&self, mf: &MaterialFile) -> Result<DpzdSettings> {
        let args = self;
        let r = match (args.r, &mf.dpzd) {
            (Some(r), _) => r,
            (None, Some(d)) => d.r,
            (None, None) => bail!("{}: no [dpzd] r given; pass --r", mf.path.display()),
        };
        let mut rho_cp =
            args.rho_cp_original.or(mf.dpzd.as_ref().map(|d| d.rho_cp_original_j_per_cm3_k)).unwrap_or(3.5325);
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
