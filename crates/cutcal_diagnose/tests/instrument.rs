//! Instrument explanations as competitors (`cutcal_diagnose::instrument`): a drift of both force
//! channels over the run order must not be named flank wear, while a real wear land (Smithey,
//! Kapoor & DeVor 2001: the land raises Ft relatively more than Fc) still is.
//!
//! The "external simulation" is cutcal's Oxley model on C38 thermal data (paper Table 3); the
//! shadow runs on generic steel (AISI 1045, Lalwani 2009), as in `mode_a.rs`.

mod common;

use common::{design, external, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_model::CuttingTest;

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
    // The next test rules the instrument out first, then names the candidate it stopped.
    assert!(report.next_test.starts_with("check the force channels with dead weights"), "{}", report.next_test);
    assert!(report.next_test.contains("repeat the first test at the end of the series"), "{}", report.next_test);
    assert!(report.next_test.contains("flank_wear is the candidate"), "{}", report.next_test);
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

/// The edge of radius `radius_m` in the external model, read through force channels `gain` times
/// too high, diagnosed against the sharp external simulation: the names selected and the text.
fn edge_read_with_gain(radius_m: f64, gain: f64) -> (Vec<String>, String) {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let edge = |_: &CuttingTest| Hooks { edge_radius_m: radius_m, ..Hooks::NEUTRAL };
    let report = run(&measured(&tests, &external(&tests, &edge), &|_| gain), &ext);
    (report.selected.clone(), report.to_text())
}

#[test]
fn an_edge_under_a_gain_error_is_still_named() {
    // An 8 um edge (Waldorf et al. 1998, in the full model) recorded through force channels that
    // read 12 % high, inside the gain artefact's 20 % bound. The gain alone explains the data about
    // as well as the edge alone, but it leaves the edge force's rise at small h in the residuals:
    // the nested test (edge on top of the gain, against the gain alone) keeps the claim. Before that
    // test, such a case was `unexplained`.
    let (selected, text) = edge_read_with_gain(8e-6, 1.12);
    assert_eq!(selected, vec!["edge_ploughing".to_string()], "{text}");
    assert!(text.contains("adds significantly on top of it"), "{text}");
}

#[test]
fn a_gain_on_its_bound_does_not_stop_a_claim() {
    // A 15 um edge read 20 % high: the gain that would explain it sits on its bound, ln 1.2,
    // beyond what a calibrated dynamometer can be off by, so it is no instrument explanation and
    // the report says so.
    let (selected, text) = edge_read_with_gain(15e-6, 1.2);
    assert_eq!(selected, vec!["edge_ploughing".to_string()], "{text}");
    assert!(text.contains("on its bound"), "{text}");
}
