//! Identify face: the DPZD identification of one test (paper Eq 15) through
//! `cutcal_report::dpzd::identify_dpzd`, with the settings resolved by the same
//! `DpzdRequest::settings` the CLI uses, so that a Python call and `cutcal identify --json` with
//! the same options give the same numbers.

use cutcal_io::material_file::MaterialFile;
use cutcal_model::{CuttingTest, JcParams};
use cutcal_report::bootstrap::{report_json, run_bootstrap, BootstrapRequest};
use cutcal_report::dpzd::{identify_dpzd, ModelChoice, Preset};
use cutcal_report::identify::DpzdRequest;

use crate::errors::{face, FaceResult};

/// Options of one identification; the defaults are the CLI's (`cutcal identify --help`).
#[derive(Debug, Clone, PartialEq)]
pub struct IdentifyRequest {
    /// `"original"` or `"enhanced"` (paper Sec 3.2 / 3.3-3.5).
    pub model: String,
    /// `"converged"` (default: Eq 15 as a zone integral with the solvers' JC law) or `"paper"`
    /// (Table 4's choices: N = 51, h = 0.1 mm, unclamped rate term).
    pub preset: String,
    /// Primary shear zone thickness h, mm (`None`: the preset's).
    pub h_mm: Option<f64>,
    /// Uniform interior fit points N of Eq 15 (`paper` preset only; `None`: the preset's).
    pub points: Option<usize>,
    /// Exponent r of Eq 2 (default: the material's `dpzd.r`).
    pub r: Option<f64>,
    /// Multistart starts.
    pub starts: usize,
    /// Multistart seed.
    pub seed: u64,
    /// A local search from every start point (no MLSL filter; the CLI's `--every-start`).
    pub every_start: bool,
    /// Constant rho*Cp of the original model, J/(cm^3 K).
    pub rho_cp_original: Option<f64>,
    /// Enhanced fixed point tolerance, K.
    pub tolerance_c: f64,
    /// Enhanced fixed point cap.
    pub max_iterations: usize,
    /// Bootstrap samples for the parameter spread (0: none).
    pub bootstrap: usize,
    /// Relative standard uncertainty of the measured forces (`None`: the test's sd, else 3 %).
    pub force_uncertainty: Option<f64>,
    /// Relative standard uncertainty of the measured chip thickness (`None`: the test's sd, else 5 %).
    pub chip_uncertainty: Option<f64>,
    /// Multistart starts per bootstrap sample.
    pub bootstrap_starts: usize,
    /// Vary only the measurements in the Monte-Carlo, not h and r (the CLI's `--noise-only`).
    pub noise_only: bool,
    /// Points of the returned zone fields (the CLI's `--fields-csv` writes 201).
    pub field_points: usize,
}

impl Default for IdentifyRequest {
    fn default() -> Self {
        Self {
            model: "enhanced".into(),
            preset: "converged".into(),
            h_mm: None,
            points: None,
            r: None,
            starts: 32,
            seed: 1,
            every_start: false,
            rho_cp_original: None,
            tolerance_c: 1e-6,
            max_iterations: 50,
            bootstrap: 0,
            force_uncertainty: None,
            chip_uncertainty: None,
            bootstrap_starts: 2,
            noise_only: false,
            field_points: 201,
        }
    }
}

/// The zone fields of the paper's Fig 4, one vector per quantity, named with their units (the
/// column names of the CLI's `--fields-csv`).
pub const FIELD_NAMES: [&str; 8] =
    ["x_mm", "gamma", "gamma_dot_per_s", "eps", "eps_dot_per_s", "tau_mpa", "sigma_eff_mpa", "temperature_c"];

/// What an identification returns to Python.
#[derive(Debug, Clone)]
pub struct IdentifyOutput {
    /// The identified JC set.
    pub jc: JcParams,
    /// Parameters on a bound (`a_mpa`, `b_mpa`, `n`, `c`, `m`).
    pub at_bounds: Vec<String>,
    /// The zone fields, in the order of [`FIELD_NAMES`].
    pub fields: Vec<(&'static str, Vec<f64>)>,
    /// The JSON document of `cutcal identify --json` (with `bootstrap` when asked).
    pub json: String,
    /// The bootstrap spread as JSON, when `bootstrap > 0`.
    pub spread_json: Option<String>,
}

fn preset_choice(name: &str) -> FaceResult<Preset> {
    match name {
        "converged" => Ok(Preset::Converged),
        "paper" => Ok(Preset::Paper),
        other => Err(face(anyhow::anyhow!("preset must be \"converged\" or \"paper\", got {other:?}"))),
    }
}

fn model_choice(name: &str) -> FaceResult<ModelChoice> {
    match name {
        "enhanced" => Ok(ModelChoice::Enhanced),
        "original" => Ok(ModelChoice::Original),
        other => Err(face(anyhow::anyhow!("model must be \"enhanced\" or \"original\", got {other:?}"))),
    }
}

/// The library requests this request stands for.
fn requests(req: &IdentifyRequest) -> FaceResult<(DpzdRequest, BootstrapRequest)> {
    let dpzd = DpzdRequest {
        model: model_choice(&req.model)?,
        preset: preset_choice(&req.preset)?,
        h_mm: req.h_mm,
        points: req.points,
        r: req.r,
        starts: Some(req.starts),
        seed: req.seed,
        every_start: req.every_start,
        rho_cp_original: req.rho_cp_original,
        tolerance_c: req.tolerance_c,
        max_iterations: req.max_iterations,
    };
    let boot = BootstrapRequest {
        bootstrap: req.bootstrap,
        force_uncertainty: req.force_uncertainty,
        chip_uncertainty: req.chip_uncertainty,
        bootstrap_starts: req.bootstrap_starts,
        noise_only: req.noise_only,
        ..BootstrapRequest::default()
    };
    Ok((dpzd, boot))
}

/// Identifies JC from `test` by the paper's Eq 15 (DPZD zone of Sec 3, enhanced fixed point of
/// Sec 3.5), exactly as `cutcal identify --json` does.
pub fn identify(mf: &MaterialFile, test: &CuttingTest, req: &IdentifyRequest) -> FaceResult<IdentifyOutput> {
    let (dpzd, boot) = requests(req)?;
    let settings = dpzd.settings(mf).map_err(face)?;
    let out = identify_dpzd(mf, test, &settings).map_err(face)?;
    let boot = run_bootstrap(&boot, mf, test, &out.settings_at_h_used(&settings), &out).map_err(face)?;
    let json = report_json(&out.report, boot.as_ref()).map_err(face)?;
    let spread_json = boot.as_ref().map(serde_json::to_string).transpose().map_err(face)?;
    let profile = out.zone.profile(req.field_points).map_err(face)?;
    let col = |f: fn(&cutcal_model::dpzd::ZonePoint) -> f64| profile.iter().map(f).collect::<Vec<f64>>();
    let fields = vec![
        (FIELD_NAMES[0], col(|p| p.x_m * 1e3)),
        (FIELD_NAMES[1], col(|p| p.gamma)),
        (FIELD_NAMES[2], col(|p| p.gamma_dot_per_s)),
        (FIELD_NAMES[3], col(|p| p.strain)),
        (FIELD_NAMES[4], col(|p| p.strain_rate_per_s)),
        (FIELD_NAMES[5], col(|p| p.tau_pa / 1e6)),
        (FIELD_NAMES[6], col(|p| p.effective_stress_pa / 1e6)),
        (FIELD_NAMES[7], col(|p| p.temperature_c)),
    ];
    Ok(IdentifyOutput { jc: out.identification.jc, at_bounds: out.report.at_bounds.clone(), fields, json, spread_json })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::{material_from_file, tests_from_file};
    use std::path::Path;

    #[test]
    fn c38_test_3_enhanced_gives_the_readme_figures_and_fig4_shapes() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mf = material_from_file(&root.join("fixtures/materials/c38.toml")).unwrap();
        let tests = tests_from_file(&root.join("fixtures/tests/c38.csv")).unwrap();
        let t3 = tests.iter().find(|t| t.id == "3").unwrap();
        let req = IdentifyRequest { starts: 8, field_points: 11, preset: "paper".into(), ..Default::default() };
        let out = identify(&mf, t3, &req).unwrap();
        // Paper Table 4 (with the paper preset, which reproduces it), enhanced: A = 589 MPa, C = 0.069 (cutcal within 1.5 %), n and m at bounds.
        assert!((out.jc.a_pa / 589e6 - 1.0).abs() < 0.015, "{}", out.jc.a_pa);
        assert!((out.jc.c / 0.069 - 1.0).abs() < 0.015, "{}", out.jc.c);
        assert_eq!(out.at_bounds, ["n", "m"]);
        assert!(out.fields.iter().all(|(_, v)| v.len() == 11));
        // x spans the zone -h/2 .. h/2 = -0.05 .. 0.05 mm (Sec 3, h = 0.1 mm).
        assert!((out.fields[0].1[0] + 0.05).abs() < 1e-12 && (out.fields[0].1[10] - 0.05).abs() < 1e-12);
        let v: serde_json::Value = serde_json::from_str(&out.json).unwrap();
        assert_eq!(v["starts"], 8);
        assert!(out.spread_json.is_none());
        let bad = IdentifyRequest { model: "enhancd".into(), ..Default::default() };
        assert!(identify(&mf, t3, &bad).unwrap_err().message.contains("enhancd"));
        let bad = IdentifyRequest { preset: "papr".into(), ..Default::default() };
        assert!(identify(&mf, t3, &bad).unwrap_err().message.contains("papr"));
    }
}
