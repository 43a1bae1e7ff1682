//! A rounded edge that acts on the chip's formation as well as by ploughing: the chip forms on the
//! edge's chord above the stagnation point, a lower effective rake than the tool's (Manjunathaiah &
//! Endres 2000; Kountanya & Endres 2001). The detector's edge carries it with its shape `w_rake`
//! near 1 instead of reading the thicker chip and higher Ft as softening or heat partition.
//!
//! The "external simulation" is cutcal's Oxley model on C38 thermal data (paper Table 3); the
//! shadow runs on generic steel (AISI 1045, Lalwani 2009), as in `mode_a.rs`. The recordings add an
//! edge of r = 30 um: its Waldorf ploughing forces and the chord effective rake, computed here from
//! the edge's coordinates (not by the library's function).

mod common;

use common::{design, external, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_model::CuttingTest;

const R_M: f64 = 30e-6;

/// Chord effective rake of a 0 deg tool, rad, by coordinates: edge centre (0, r), chip side at -x,
/// stagnation point at height 0.3 r on the arc (x_s = -sqrt(r^2 - (0.7 r)^2)); for h above the
/// arc's tangent point (height r at 0 deg rake) the free-surface point is on the rake face, x = -r.
fn chord_rake(h: f64) -> f64 {
    let (y_s, x_s) = (0.3 * R_M, -(R_M * R_M - (0.7 * R_M) * (0.7 * R_M)).sqrt());
    assert!(h > R_M, "the design's feeds are all above the tangent point");
    ((-R_M - x_s) / (h - y_s)).atan()
}

fn edge(t: &CuttingTest) -> Hooks {
    Hooks { edge_radius_m: R_M, rake_shift_rad: chord_rake(t.uncut_chip_thickness_m), ..Hooks::NEUTRAL }
}

#[test]
fn an_edge_that_also_lowers_the_effective_rake_is_named_with_its_shape() {
    // By hand: x_s = -21.4243 um; h = 0.05 mm: atan(-8.5757 / 41) = -11.81 deg; 0.2 mm: -2.57 deg.
    assert!((chord_rake(0.05e-3).to_degrees() + 11.813).abs() < 0.01);
    assert!((chord_rake(0.2e-3).to_degrees() + 2.572).abs() < 0.01);
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let rec = measured(&tests, &external(&tests, &edge), &|_| 1.0);
    let report = run(&rec, &ext);
    assert_eq!(report.selected, vec!["edge_ploughing".to_string()], "{}", report.to_text());
    let e = report.mechanisms.iter().find(|m| m.id == "edge_ploughing").unwrap();
    // The radius is recovered within its interval, and the rake part is seen: w_rake's interval
    // stays clear of 0 (ploughing forces alone).
    let r = &e.params["r_e"];
    assert!(r.ci_low.unwrap() < 30.0 && 30.0 < r.ci_high.unwrap(), "{}", report.to_text());
    let w = &e.params["w_rake"];
    assert!(w.ci_low.is_some_and(|lo| lo > 0.3), "w_rake = {}: {}", w.value, report.to_text());
}
