//! Instrument explanations as competitors (`cutcal_diagnose::instrument`): a drift of both force
//! channels over the run order must not be named flank wear, while a real wear land (Smithey,
//! Kapoor & DeVor 2001: the land raises Ft relatively more than Fc) still is.
//!
//! The "external simulation" is cutcal's Oxley model on C38 thermal data (paper Table 3); the
//! shadow runs on generic steel (AISI 1045, Lalwani 2009), as in `mode_a.rs`.

use cutcal_diagnose::hooks::Hooks;
use cutcal_diagnose::simulator::oxley_with_hooks;
use cutcal_diagnose::{diagnose, Config, Prediction, ShadowSimulation};
use cutcal_model::oxley::OxleyOptions;
use cutcal_model::{CuttingTest, JcParams};

fn jaspers(room_c: f64) -> JcParams {
    JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, room_c).unwrap()
}

/// 3 feeds x 5 speeds at 0 deg rake, 2 mm wide; run order a fixed permutation (7 i mod 15) so that
/// it is not aligned with feed or speed.
fn design() -> Vec<CuttingTest> {
    let mut v = Vec::new();
    for (i, (h, s)) in
        [0.05, 0.1, 0.2].iter().flat_map(|h| [60.0, 100.0, 150.0, 220.0, 300.0].map(|s| (*h, s))).enumerate()
    {
        let mut t = CuttingTest::new(format!("{}", i + 1), s / 60.0, h * 1e-3, 2e-3, 0.0).unwrap();
        t.order = Some(((7 * i) % 15 + 1) as u32);
        v.push(t);
    }
    v
}

fn external(tests: &[CuttingTest], h: &dyn Fn(&CuttingTest) -> Hooks) -> Vec<Prediction> {
    let c38 = cutcal_model::reference::c38_table3();
    tests.iter().map(|t| oxley_with_hooks(&c38, &jaspers(20.0), t, &h(t), &OxleyOptions::wide()).unwrap()).collect()
}

/// Recordings from `rec` with both forces multiplied by `gain(test)` and a deterministic +-2 %
/// scatter (no random numbers: the test does not depend on a generator).
fn measured(tests: &[CuttingTest], rec: &[Prediction], gain: &dyn Fn(&CuttingTest) -> f64) -> Vec<CuttingTest> {
    tests
        .iter()
        .zip(rec)
        .enumerate()
        .map(|(i, (t, r))| {
            let z = ((i * 7919) % 13) as f64 / 13.0 - 0.5;
            let g = gain(t);
            t.clone()
                .with_forces(Some(r.fc_n_per_m * g * (1.0 + 0.04 * z)), Some(r.ft_n_per_m * g * (1.0 - 0.04 * z)))
                .and_then(|t| t.with_chip_thickness(Some(r.chip_m * (1.0 + 0.04 * z * z))))
                .unwrap()
        })
        .collect()
}

fn run(rec: &[CuttingTest], ext: &[Prediction]) -> cutcal_diagnose::Report {
    let sim = ShadowSimulation::build(&cutcal_model::reference::aisi1045_lalwani2009(), jaspers(25.0), rec, ext, true)
        .unwrap();
    diagnose(&sim, rec, &Config::standard("A")).unwrap()
}

#[test]
fn a_force_drift_over_the_run_order_is_not_named_flank_wear() {
    // Both force channels drift up by 15 % from the first to the last test (a charge-amplifier
    // drift); the chip is untouched.
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let rec = measured(&tests, &ext, &|t| 1.0 + 0.15 * f64::from(t.order.unwrap() - 1) / 14.0);
    let report = run(&rec, &ext);
    assert!(report.selected.is_empty(), "{}", report.to_text());
    // Flank wear passes its own checks here; the drift competitor is what stops the claim.
    let wear = report.mechanisms.iter().find(|m| m.id == "flank_wear").expect("flank wear is refitted");
    assert!(wear.p_value.is_some_and(|p| p < report.thresholds.per_mechanism_alpha), "{}", report.to_text());
    assert!(wear.reason.contains("drift of both force channels"), "{}", report.to_text());
}

#[test]
fn a_wear_land_growing_with_the_run_order_is_still_named() {
    // VB grows linearly to 0.2 mm at the last test (the Smithey et al. 2001 land in the full model);
    // the drift competitor must not take the claim away.
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let wear = |t: &CuttingTest| Hooks { wear_land_m: 0.2e-3 * f64::from(t.order.unwrap()) / 15.0, ..Hooks::NEUTRAL };
    let rec = measured(&tests, &external(&tests, &wear), &|_| 1.0);
    let report = run(&rec, &ext);
    assert_eq!(report.selected, vec!["flank_wear".to_string()], "{}", report.to_text());
}

#[test]
fn a_common_force_gain_is_not_named_physics() {
    // Both force channels read 12 % high at every test (a charge-amplifier calibration error); the
    // chip is untouched. Whatever mechanism fits a level best must lose to the one-parameter gain.
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let rec = measured(&tests, &ext, &|_| 1.12);
    let report = run(&rec, &ext);
    assert!(report.selected.is_empty(), "{}", report.to_text());
}

#[test]
fn an_edge_under_a_gain_error_is_still_named() {
    // A 15 um edge (Waldorf et al. 1998, in the full model) recorded through force channels that
    // read 20 % high, the gain artefact's bound. The gain alone then explains the data better than
    // the edge alone (dAICc -85 against -72 here), but it leaves the edge force's rise at small h in
    // the residuals: the nested test (edge on top of the gain, against the gain alone) keeps the
    // claim. Before that test, this case was `unexplained`.
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let edge = |_: &CuttingTest| Hooks { edge_radius_m: 15e-6, ..Hooks::NEUTRAL };
    let rec = measured(&tests, &external(&tests, &edge), &|_| 1.2);
    let report = run(&rec, &ext);
    assert_eq!(report.selected, vec!["edge_ploughing".to_string()], "{}", report.to_text());
    assert!(report.to_text().contains("adds significantly on top of it"), "{}", report.to_text());
}
