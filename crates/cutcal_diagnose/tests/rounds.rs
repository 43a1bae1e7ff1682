//! Later rounds (`cutcal_diagnose::diagnose`): a second mechanism is claimed on top of the first
//! only when it is not one of the first's confounders in the library (`mechanism::info`).
//!
//! The recordings carry two real mechanisms of the full model: a 20 um edge (Waldorf, DeVor &
//! Kapoor 1998) and a Nix-Gao size effect of length 40 um (Nix & Gao 1998) on the flow stress.
//! Both raise the forces most at small h, so the library lists them as confounders: whatever is
//! left after the first claim could as well be the first mechanism's true form.

mod common;

use common::{design, external, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_model::CuttingTest;

/// Exactly one of the confounded pair `a`, `b` is selected, and the other passed its own checks in
/// the second round (p below the round's level) and was held back by the rule.
fn one_claimed_other_held_back(report: &cutcal_diagnose::Report, a: &str, b: &str) {
    let text = report.to_text();
    assert_eq!(report.selected.len(), 1, "{text}");
    let first = report.selected[0].as_str();
    assert!(first == a || first == b, "{text}");
    let other = if first == a { b } else { a };
    let held = report
        .mechanisms
        .iter()
        .find(|m| m.id == other && m.reason.contains("confounded with"))
        .unwrap_or_else(|| panic!("{other} is held back as a confounder of {first}:\n{text}"));
    assert!(held.p_value.is_some_and(|p| p < report.thresholds.per_mechanism_alpha / 4.0), "{text}");
}

#[test]
fn a_confounder_of_the_first_claim_is_not_claimed_second() {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    // Nix-Gao factor sqrt(1 + l/h) relative to h = 0.1 mm, l = 40 um.
    let both = |t: &CuttingTest| Hooks {
        edge_radius_m: 20e-6,
        flow_multiplier: ((1.0 + 40e-6 / t.uncut_chip_thickness_m) / (1.0 + 40e-6 / 0.1e-3)).sqrt(),
        ..Hooks::NEUTRAL
    };
    let rec = measured(&tests, &external(&tests, &both), &|_| 1.0);
    let report = run(&rec, &ext);
    let text = report.to_text();
    one_claimed_other_held_back(&report, "edge_ploughing", "size_effect");
    assert!(report.explanation.contains("also improves the fit on top of"), "{text}");
    // The "after" held-out error is that of the claim alone, not of a choice the decision refused.
    let claimed = report.mechanisms.iter().find(|m| m.accepted).expect("one claim");
    let after = report.fit.after.loco.as_ref().expect("15 conditions give a held-out error").all;
    assert!((after - claimed.heldout_rms_after.unwrap()).abs() < 1e-9, "{after}\n{text}");
}

/// A worn tool (a wear land growing with the run order, Smithey, Kapoor & DeVor 2001, VB to
/// 0.15 mm) measured through a dynamometer whose feed channel picks up 12 % of the cutting force.
/// The land's normal-to-shear stress ratio differs between wear-land models, so an Ft excess in
/// proportion to Fc left after a wear claim could as well be the land's true ratio: the library
/// lists wear and cross-talk as confounders, and the second is held back. With the wear's
/// running-in share `w_0` (which takes part of the cross-talk's offset) a friction factor then also
/// passed its checks in the second round (dAICc -4.7, p = 1e-3); it is not claimed, since the
/// held-back cross-talk explains that remainder far better (dAICc -126.6):
/// `verdict::outdone_by_held_back`.
#[test]
fn cross_talk_is_not_claimed_on_top_of_wear() {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let worn = |t: &CuttingTest| Hooks { wear_land_m: 0.15e-3 * f64::from(t.order.unwrap()) / 15.0, ..Hooks::NEUTRAL };
    let mut rec = measured(&tests, &external(&tests, &worn), &|_| 1.0);
    for t in &mut rec {
        let (fc, ft) = (t.measured.cutting_force_n_per_m.unwrap(), t.measured.feed_force_n_per_m.unwrap());
        *t = t.clone().with_forces(Some(fc), Some(ft + 0.12 * fc)).unwrap();
    }
    one_claimed_other_held_back(&run(&rec, &ext), "flank_wear", "force_crosstalk");
}
