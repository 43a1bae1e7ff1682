//! A built-up edge in a band of the design rather than below an onset: the edge's height rises from
//! the slowest cuts to a peak and vanishes at high speed (Trent & Wright 2000, Metal Cutting, 4th
//! ed., Sec 5.3; Childs et al. 2000, Metal Machining, Sec 1.4), and the peak moves to lower speeds
//! as the feed grows.
//!
//! The recordings take the edge as a rake increase of 10 deg times a window in ln V,
//! `exp(-(ln(V / V_p))^2 / (2 w^2))` with `V_p = 150 m/min (h / 0.1 mm)^-1/2` and `w = 0.35`: a
//! log-normal window chosen here (as family d of `cargo xtask concealed` draws its own), not the
//! detector's logistic band on the interface temperature. Its share from the formula at h = 0.1 mm
//! is 0.032, 0.511, 1.000, 0.550 and 0.141 at 60, 100, 150, 220 and 300 m/min; the peak is near
//! 220 m/min at 0.05 mm and 100 m/min at 0.2 mm, and the slowest cut of each feed has at most 0.27
//! of the edge. With the one-sided gate alone (before the thirty-fourth session) the same
//! recordings came out `unexplained`. The setup is that of `mode_a.rs` (C38 simulation, AISI 1045
//! shadow).

mod common;

use common::{design, external, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_model::CuttingTest;

/// A log-normal window in the speed of test `t`: `exp(-(ln(V / V_p))^2 / (2 w^2))`, w = 0.35.
fn log_normal(t: &CuttingTest, v_peak_m_min: f64) -> f64 {
    let x = (t.speed_m_per_s * 60.0 / v_peak_m_min).ln();
    (-x * x / (2.0 * 0.35 * 0.35)).exp()
}

/// The window's share at test `t` (the formula of the module docs).
fn window(t: &CuttingTest) -> f64 {
    let h_mm = t.uncut_chip_thickness_m * 1e3;
    log_normal(t, 150.0 * (h_mm / 0.1).powf(-0.5))
}

/// Asserts `share` at 60, 100, 150, 220 and 300 m/min and thickness `h_m` against `want` (1e-3).
fn assert_shares(share: &dyn Fn(&CuttingTest) -> f64, h_m: f64, want: [f64; 5]) {
    let t = |v: f64| CuttingTest::new("w", v / 60.0, h_m, 2e-3, 0.0).unwrap();
    let got: Vec<f64> = [60.0, 100.0, 150.0, 220.0, 300.0].iter().map(|v| share(&t(*v))).collect();
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 1e-3, "{got:?}");
    }
}

/// The report on recordings of the C38 design whose rake is raised by 10 deg times `share`.
fn with_rake_increase(share: &dyn Fn(&CuttingTest) -> f64) -> cutcal_diagnose::Report {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let rec_pred = external(&tests, &|t| Hooks { rake_shift_rad: 10f64.to_radians() * share(t), ..Hooks::NEUTRAL });
    let rec = measured(&tests, &rec_pred, &|_| 1.0);
    run(&rec, &ext)
}

/// The built-up edge's first-round result in `report`.
fn edge_result(report: &cutcal_diagnose::Report) -> &cutcal_diagnose::report::MechanismResult {
    report.mechanisms.iter().find(|m| m.id == "built_up_edge").expect("the built-up edge is in the report")
}

#[test]
fn the_window_formula_gives_the_shares_in_the_docs() {
    assert_shares(&window, 0.1e-3, [0.032, 0.511, 1.0, 0.550, 0.141]);
}

#[test]
fn a_built_up_edge_in_a_band_of_speeds_is_named_with_a_floor() {
    let report = with_rake_increase(&window);
    assert_eq!(report.selected, vec!["built_up_edge".to_string()], "{}", report.to_text());
    let b = edge_result(&report);
    let (floor, onset) = (b.params["t_floor"].value, b.params["t_onset"].value);
    assert!(floor > 0.0 && floor < onset, "floor {floor}, onset {onset}: {}", report.to_text());
}

#[test]
fn a_built_up_edge_at_the_slowest_speeds_is_named_without_a_floor() {
    // The classical one-sided edge: a 10 deg rake increase that fades above 120 m/min as
    // 1 / (1 + (V / 120)^8) (a smooth step in speed chosen here, not the detector's logistic on
    // the interface temperature): 0.999 at 60, 0.82 at 100, 0.14 at 150 and under 0.01 from
    // 220 m/min. The band's floor would have to leave two of the coolest tests outside the edge,
    // which the recordings contradict; the one-sided gate is kept. A step in speed is not one in
    // the interface temperature at every feed: on the temperature alone (before the thirty-fifth
    // session) an edge radius was claimed after the built-up edge for what was left. With the
    // speed as a second gate coordinate the edge is gated by the speed and nothing is left.
    let step = |t: &CuttingTest| 1.0 / (1.0 + (t.speed_m_per_s * 60.0 / 120.0).powi(8));
    let report = with_rake_increase(&step);
    assert_eq!(report.selected.first().map(String::as_str), Some("built_up_edge"), "{}", report.to_text());
    let b = edge_result(&report);
    assert!(!b.params.contains_key("t_floor") && !b.params.contains_key("v_floor"), "{}", report.to_text());
    assert!(b.params.contains_key("v_onset"), "{}", report.to_text());
    assert_eq!(report.selected.len(), 1, "{}", report.to_text());
}

/// A window in ln V whose peak stays at `V_p = 100 m/min` at every feed (`w = 0.35`).
fn fixed_window(t: &CuttingTest) -> f64 {
    log_normal(t, 100.0)
}

#[test]
fn the_fixed_window_gives_its_shares_by_hand() {
    // exp(-(ln(V/100))^2 / 0.245): ln 0.6 = -0.5108 -> exp(-1.0651) = 0.345; 1 at 100;
    // ln 1.5 = 0.4055 -> exp(-0.6710) = 0.511; ln 2.2 = 0.7885 -> exp(-2.5375) = 0.079;
    // ln 3 = 1.0986 -> exp(-4.9263) = 0.007.
    assert_shares(&fixed_window, 0.05e-3, [0.345, 1.0, 0.511, 0.079, 0.007]);
}

#[test]
fn a_built_up_edge_charted_on_the_speed_alone_is_gated_by_the_speed() {
    // A 10 deg rake increase times `fixed_window`: an edge charted on the speed alone, as the BUE
    // maps of Trent & Wright 2000 (Sec 5.3) are, present from 60 to 150 m/min at every feed and
    // nearly gone from 220 m/min. The interface temperature rises with the feed as well as the
    // speed, so no gate of it holds the same tests; the screen's second coordinate, the speed, is
    // chosen, and the report gives the onset in m/min between 150 and 220. With the temperature
    // as the only coordinate (before the thirty-fifth session) these recordings came out
    // `unexplained`: the temperature gate fitted, but failed the held-out check (checked by
    // reverting the detector).
    let report = with_rake_increase(&fixed_window);
    assert_eq!(report.selected, vec!["built_up_edge".to_string()], "{}", report.to_text());
    let b = edge_result(&report);
    let onset = b.params.get("v_onset").map(|p| p.value);
    assert!(onset.is_some_and(|v| v > 150.0 && v < 220.0), "{}", report.to_text());
}

/// The rising side of an edge's band: a smooth rise in speed, `1 / (1 + (V / 120)^-8)`.
fn rising(t: &CuttingTest) -> f64 {
    1.0 / (1.0 + (t.speed_m_per_s * 60.0 / 120.0).powi(-8))
}

#[test]
fn the_rising_side_gives_its_shares_by_hand() {
    // (V/120)^-8: 256 at 60, 4.2998 at 100, 0.16777 at 150, 0.00784 at 220, 0.00066 at 300 m/min,
    // so 1/257, 1/5.2998, 1/1.16777, 1/1.00784 and 1/1.00066.
    assert_shares(&rising, 0.1e-3, [0.004, 0.189, 0.856, 0.992, 0.999]);
}

#[test]
fn a_built_up_edge_on_the_rising_side_of_its_band_is_named_with_a_floor_alone() {
    // A 10 deg rake increase times `rising`: the edge grows with the speed and the design stops
    // before it vanishes (Trent & Wright 2000, Sec 5.3: the edge's height rises from the lowest
    // speeds to a peak). Every onset of the detector's gates leaves a third of the tests above it
    // without the edge, which these recordings contradict; the rising gate (a floor, no onset)
    // holds them. Before the thirty-sixth session (no rising gate) these recordings were named
    // `tool_chip_friction`, a speed-dependent friction law (checked by reverting the detector).
    let report = with_rake_increase(&rising);
    assert_eq!(report.selected.first().map(String::as_str), Some("built_up_edge"), "{}", report.to_text());
    let b = edge_result(&report);
    assert!(!b.params.contains_key("t_onset") && !b.params.contains_key("v_onset"), "{}", report.to_text());
    let floor = b.params.get("t_floor").or_else(|| b.params.get("v_floor"));
    assert!(floor.is_some_and(|f| f.ci_note.contains("rising side")), "{}", report.to_text());
}
