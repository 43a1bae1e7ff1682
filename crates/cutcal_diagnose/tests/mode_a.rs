//! Mode A end to end: the shadow of an external simulation, its signatures against direct runs of
//! the full model, and the nuisance rule of issue 10 (item 3).
//!
//! The "external simulation" here is cutcal's Oxley model on C38 thermal data (paper Table 3);
//! the shadow runs on generic steel (AISI 1045, Lalwani 2009), so the two differ in material.

use cutcal_diagnose::hooks::Hooks;
use cutcal_diagnose::simulator::oxley_with_hooks;
use cutcal_diagnose::{diagnose, Config, Prediction, ShadowSimulation, Simulator, Verdict};
use cutcal_model::oxley::OxleyOptions;
use cutcal_model::{CuttingTest, JcParams};

fn jaspers(room_c: f64) -> JcParams {
    JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, room_c).unwrap()
}

/// 3 feeds x 4 speeds at 0 deg rake, 2 mm wide.
fn design() -> Vec<CuttingTest> {
    let mut v = Vec::new();
    for (i, (h, s)) in [0.05, 0.1, 0.2].iter().flat_map(|h| [60.0, 120.0, 200.0, 300.0].map(|s| (*h, s))).enumerate() {
        v.push(CuttingTest::new(format!("{}", i + 1), s / 60.0, h * 1e-3, 2e-3, 0.0).unwrap());
    }
    v
}

fn external(tests: &[CuttingTest], options: &OxleyOptions, h: &Hooks) -> Vec<Prediction> {
    let c38 = cutcal_model::reference::c38_table3();
    tests.iter().map(|t| oxley_with_hooks(&c38, &jaspers(20.0), t, h, options).unwrap()).collect()
}

fn shadow(tests: &[CuttingTest], ext: &[Prediction]) -> ShadowSimulation {
    ShadowSimulation::build(&cutcal_model::reference::aisi1045_lalwani2009(), jaspers(25.0), tests, ext, true).unwrap()
}

#[test]
fn shadow_returns_the_external_numbers_with_everything_off() {
    let tests = design();
    let ext = external(&tests, &OxleyOptions::wide(), &Hooks::NEUTRAL);
    let sim = shadow(&tests, &ext);
    let theta: Vec<f64> = sim.baseline_params().iter().map(|p| p.start).collect();
    let p = sim.simulate(&tests, &theta, &vec![Hooks::NEUTRAL; tests.len()]).unwrap();
    for (a, b) in p.iter().zip(&ext) {
        assert!((a.fc_n_per_m / b.fc_n_per_m - 1.0).abs() < 1e-12);
        assert!((a.ft_n_per_m / b.ft_n_per_m - 1.0).abs() < 1e-12);
        assert!((a.chip_m / b.chip_m - 1.0).abs() < 1e-12);
    }
}

#[test]
fn shadow_signatures_match_direct_runs_of_the_full_model_between_nodes() {
    // The signature of a 12 um edge (between the 10 and 15 um nodes), of m_f = 0.75 (between
    // 0.7 and 0.8), of the softening's JC m scaled by e^0.4 (between the 0.3 and 0.5 nodes of
    // the JC-m knob) and of an interface heat share 0.78 (psi s = 0.702, between the 0.65 and 0.75
    // nodes of the psi knob) at each test must equal the ratio of two direct runs of the full model with
    // the shadow's fitted JC set, to the interpolation error (< 1 % of the force).
    let tests = design();
    let ext = external(&tests, &OxleyOptions::wide(), &Hooks::NEUTRAL);
    let sim = shadow(&tests, &ext);
    let jc = sim.summary().jc;
    let steel = cutcal_model::reference::aisi1045_lalwani2009();
    let theta: Vec<f64> = sim.baseline_params().iter().map(|p| p.start).collect();
    for h in [
        Hooks { edge_radius_m: 12e-6, ..Hooks::NEUTRAL },
        Hooks { friction_factor: 0.75, ..Hooks::NEUTRAL },
        Hooks { thermal_exponent_ln_scale: 0.4, ..Hooks::NEUTRAL },
        Hooks { interface_heat_share: 0.78, ..Hooks::NEUTRAL },
    ] {
        let via = sim.simulate(&tests, &theta, &vec![h; tests.len()]).unwrap();
        for ((t, v), e) in tests.iter().zip(&via).zip(&ext) {
            let o = OxleyOptions::wide();
            let on = oxley_with_hooks(&steel, &jc, t, &h, &o).unwrap();
            let off = oxley_with_hooks(&steel, &jc, t, &Hooks::NEUTRAL, &o).unwrap();
            for (got, want) in [
                (v.fc_n_per_m / e.fc_n_per_m, on.fc_n_per_m / off.fc_n_per_m),
                (v.ft_n_per_m / e.ft_n_per_m, on.ft_n_per_m / off.ft_n_per_m),
                (v.chip_m / e.chip_m, on.chip_m / off.chip_m),
            ] {
                assert!((got / want - 1.0).abs() < 0.01, "test {}: {got} vs {want} for {h:?}", t.id);
            }
        }
    }
}

#[test]
fn nuisance_alone_gives_no_claim() {
    // Recordings from the external model with eta +3 % and psi -3 % (Oxley's temperature factors,
    // 0.9 nominal) and a common flow-stress level +4 %, no mechanism and no noise: the shifts this
    // makes in Ft and tc must be absorbed by the baseline, and the verdict is `none`.
    let tests = design();
    let ext = external(&tests, &OxleyOptions::wide(), &Hooks::NEUTRAL);
    let o = OxleyOptions::wide().with_eta_psi(0.927, 0.873).unwrap();
    let rec = external(&tests, &o, &Hooks { flow_multiplier: 1.04, ..Hooks::NEUTRAL });
    let moved = rec.iter().zip(&ext).map(|(r, e)| (r.ft_n_per_m / e.ft_n_per_m - 1.0).abs()).fold(0.0, f64::max);
    assert!(moved > 0.02, "the nuisance must move Ft visibly: {moved}");
    let measured: Vec<CuttingTest> = tests
        .iter()
        .zip(&rec)
        .map(|(t, r)| {
            t.clone()
                .with_forces(Some(r.fc_n_per_m), Some(r.ft_n_per_m))
                .and_then(|t| t.with_chip_thickness(Some(r.chip_m)))
                .unwrap()
        })
        .collect();
    let report = diagnose(&shadow(&measured, &ext), &measured, &Config::standard("A")).unwrap();
    assert!(report.selected.is_empty(), "{}", report.to_text());
    assert_eq!(report.verdict, Verdict::None, "{}", report.to_text());
}

#[test]
fn a_concealed_edge_is_named_and_improves_held_out_prediction() {
    // Recordings with a 25 um edge (Waldorf et al. 1998) and +-2 % deterministic scatter.
    let tests = design();
    let ext = external(&tests, &OxleyOptions::wide(), &Hooks::NEUTRAL);
    let rec = external(&tests, &OxleyOptions::wide(), &Hooks { edge_radius_m: 25e-6, ..Hooks::NEUTRAL });
    let measured: Vec<CuttingTest> = tests
        .iter()
        .zip(&rec)
        .enumerate()
        .map(|(i, (t, r))| {
            let z = ((i * 7919) % 13) as f64 / 13.0 - 0.5;
            t.clone()
                .with_forces(Some(r.fc_n_per_m * (1.0 + 0.04 * z)), Some(r.ft_n_per_m * (1.0 - 0.04 * z)))
                .and_then(|t| t.with_chip_thickness(Some(r.chip_m * (1.0 + 0.04 * z * z))))
                .unwrap()
        })
        .collect();
    let report = diagnose(&shadow(&measured, &ext), &measured, &Config::standard("A")).unwrap();
    assert_eq!(report.selected, vec!["edge_ploughing".to_string()], "{}", report.to_text());
    let (b, a) = (report.fit.before.loco.as_ref().unwrap().all, report.fit.after.loco.as_ref().unwrap().all);
    assert!(a < 0.7 * b, "held-out RMS {b} -> {a}");
    let r_e = report.mechanisms.iter().find(|m| m.id == "edge_ploughing").unwrap().params["r_e"].value;
    assert!((15.0..40.0).contains(&r_e), "{r_e}");
    assert!(report.calibration.contains("null replicates"), "{}", report.calibration);
}
