//! The `identify` command's work (`cutcal identify`, Python's `identify`): the request of one DPZD
//! identification (paper Eq 15) as the flags and keywords give it, resolved against the material
//! file, and [`identify_test`], which reads the files, identifies the test and runs the bootstrap.

use std::path::Path;

use cutcal_ident::multistart::SampleFilter;
use cutcal_ident::MultistartOptions;
use cutcal_io::material_file::{load_material, MaterialFile};
use cutcal_io::tests_csv::{load_tests_measuring, MeasuredColumn};
use cutcal_model::CuttingTest;

use crate::bail;
use crate::dpzd::{identify_dpzd, pick_test, DpzdOutcome, DpzdSettings, ModelChoice, Preset};
use crate::dpzd_report::{jc_toml, render_table};
use crate::error::Result;

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
    /// Search from every start point: no MLSL sample filter (`cutcal_ident::multistart`).
    pub every_start: bool,
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
            every_start: false,
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
                if args.h_mm.is_some_and(|h| (h - 0.1).abs() > 1e-12) || args.points.is_some_and(|n| n != 51) {
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
            multistart: MultistartOptions {
                sample_filter: if args.every_start { SampleFilter::Off } else { SampleFilter::Auto },
                ..MultistartOptions::new(args.starts.unwrap_or(32), args.seed)
            },
        })
    }
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
    let bootstrap =
        crate::bootstrap::run_bootstrap(boot, &mf, &test, &outcome.settings_at_h_used(&settings), &outcome)?;
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
