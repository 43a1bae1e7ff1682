//! A size effect of the primary shear zone alone (Joshi & Melkote 2004 apply the strain gradient to
//! the primary zone, whose thickness scales with h): the detector's size effect carries it with
//! its shape `w_chip` near 0 instead of reading the thinner chip as a lower interface friction.
//!
//! The "external simulation" is cutcal's Oxley model on C38 thermal data (paper Table 3); the
//! shadow runs on generic steel (AISI 1045, Lalwani 2009), as in `mode_a.rs`. The recordings
//! strengthen the primary zone by F = sqrt(1 + l/h), l = 30 um (Nix & Gao 1998): in Oxley's
//! closure k_chip enters only tau_int = m_f k_chip, so that is every flow stress times F with the
//! interface factor 1/F (F = 1.26 at h = 0.05 mm, 1.07 at 0.2 mm).

mod common;

use common::{design, external, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_model::CuttingTest;

fn primary_only(t: &CuttingTest) -> Hooks {
    let f = (1.0 + 30e-6 / t.uncut_chip_thickness_m).sqrt();
    Hooks { flow_multiplier: f, friction_factor: 1.0 / f, ..Hooks::NEUTRAL }
}

#[test]
fn a_size_effect_of_the_primary_zone_alone_is_named_with_its_shape() {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let rec = measured(&tests, &external(&tests, &primary_only), &|_| 1.0);
    let report = run(&rec, &ext);
    assert_eq!(report.selected, vec!["size_effect".to_string()], "{}", report.to_text());
    let size = report.mechanisms.iter().find(|m| m.id == "size_effect").unwrap();
    // The strength is recovered (its interval holds the 30 um put in), and the shape is the
    // primary zone's: w_chip's interval stays clear of 1 (every flow stress). It is not 0 here:
    // the shadow's thermal data (AISI 1045) are not the simulation's (C38).
    let l = &size.params["l_um"];
    assert!(l.ci_low.unwrap() < 30.0 && 30.0 < l.ci_high.unwrap(), "{}", report.to_text());
    let w = &size.params["w_chip"];
    assert!(w.ci_high.is_some_and(|hi| hi < 0.8), "w_chip = {}: {}", w.value, report.to_text());
}

/// A bulk size effect: every flow stress times 1 + l/h, l = 40 um (the linear form of Backer,
/// Marshall & Shaw 1952, not the detector's Nix-Gao square root), on a simulation whose flow stress
/// is the bulk material's. The factor is 1.8, 1.4 and 1.2 at h = 0.05, 0.1 and 0.2 mm: a force level
/// of about 40 % at the design's mean thickness, far beyond the 6.9 % the baseline may absorb
/// (`nuisance::level_bound`). The detector's size effect carries the level with its reference share
/// `w_ref` below 1 (strengthening at every thickness). With the size effect relative to the mean
/// thickness alone (before the thirty-second session) the level went to a second claim, thermal
/// softening.
#[test]
fn a_bulk_size_effect_with_its_level_is_named_with_its_reference_share() {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let bulk = |t: &CuttingTest| Hooks { flow_multiplier: 1.0 + 40e-6 / t.uncut_chip_thickness_m, ..Hooks::NEUTRAL };
    let rec = measured(&tests, &external(&tests, &bulk), &|_| 1.0);
    let report = run(&rec, &ext);
    assert_eq!(report.selected, vec!["size_effect".to_string()], "{}", report.to_text());
    let size = report.mechanisms.iter().find(|m| m.id == "size_effect").unwrap();
    let w = &size.params["w_ref"];
    assert!(w.value < 0.5, "w_ref = {}: {}", w.value, report.to_text());
}
