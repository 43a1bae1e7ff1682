//! A flank wear land with a running-in jump (thirtieth session): the classical wear curve rises
//! fast in the first cut and then steadily (Taylor-type tool-life testing, ISO 3685:1993 Annex G),
//! so VB at the first test is already a share of its final value. The recordings carry Smithey,
//! Kapoor & DeVor 2001's land forces of the full model with VB = 0.15 mm (0.4 + 0.6 k / 15) at the
//! k-th test of 15: a constant part that an edge radius could also give, and a trend in the run
//! order that it could not.

mod common;

use common::{design, external, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_model::CuttingTest;

#[test]
fn a_running_in_wear_land_is_named_flank_wear_not_an_edge() {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let worn = |t: &CuttingTest| Hooks {
        wear_land_m: 0.15e-3 * (0.4 + 0.6 * f64::from(t.order.unwrap()) / 15.0),
        ..Hooks::NEUTRAL
    };
    let report = run(&measured(&tests, &external(&tests, &worn), &|_| 1.0), &ext);
    let text = report.to_text();
    assert_eq!(report.selected, vec!["flank_wear".to_string()], "{text}");
    let wear = report.mechanisms.iter().find(|m| m.accepted).expect("one claim");
    let (vb, w0) = (&wear.params["vb"], &wear.params["w_0"]);
    assert!(vb.ci_low.unwrap() <= 0.15 && 0.15 <= vb.ci_high.unwrap(), "{text}");
    assert!(w0.ci_low.unwrap() <= 0.4 && 0.4 <= w0.ci_high.unwrap(), "{text}");
}
