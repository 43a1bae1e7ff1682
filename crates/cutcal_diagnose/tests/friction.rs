//! A hybrid Coulomb-Tresca interface, `tau_int = min(mu sigma_N, k_chip)` (Zorev 1963; the default
//! law of DEFORM and Abaqus, Oezel 2006, Int. J. Mach. Tools Manuf. 46, 518), in recordings of a
//! simulation that has Oxley's full sticking. The interface slides only where sticking needs more
//! than `mu`: the cool chips of the thin, slow cuts. Its reduction therefore falls as the interface
//! heats, the signature that a temperature-gated built-up edge also has.
//!
//! The recordings solve the law at each test to its fixed point: the friction factor
//! `m = min(1, mu sigma_N / k_chip)` is iterated, each time with `sigma_N` and `k_chip` of the
//! solution at the previous `m`, until it changes by less than 1e-5. The detector's hybrid form
//! takes the cap at the baseline's stresses (the first step) and from the forces (F/N), so the two
//! are different computations of the same law. With the shear-factor form alone (before the
//! thirty-third session) the same recordings were named a size effect. The setup is that of
//! `mode_a.rs` (C38 simulation, AISI 1045 shadow).

mod common;

use common::{design, jaspers, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_diagnose::simulator::oxley_with_hooks_from;
use cutcal_diagnose::Prediction;
use cutcal_model::oxley::OxleyOptions;
use cutcal_model::CuttingTest;

/// The test's solution under the hybrid law with coefficient `mu`, and its friction factor.
fn hybrid(t: &CuttingTest, mu: f64) -> (Prediction, f64) {
    let c38 = cutcal_model::reference::c38_table3();
    let mut m = 1.0;
    for _ in 0..200 {
        let h = Hooks { friction_factor: m, ..Hooks::NEUTRAL };
        let (p, full) = oxley_with_hooks_from(&c38, &jaspers(20.0), t, &h, &OxleyOptions::wide(), None).unwrap();
        let next = (mu * full.interface_normal_stress_pa / full.shear_flow_stress_int_pa).min(1.0);
        if (next - m).abs() < 1e-5 {
            return (p, m);
        }
        // Damped: the cap lowers T_int, which raises k_chip and so lowers the next cap.
        m = 0.5 * (m + next);
    }
    panic!("test {}: the hybrid law's fixed point did not converge", t.id);
}

#[test]
fn the_apparent_friction_from_the_forces_is_the_interface_stress_ratio() {
    // Merchant's force circle gives F/N = tan(alpha + atan(Ft/Fc)); Oxley's closure has tau_int =
    // k_chip and sigma_N = N / contact at its solution, so F/N = k_chip / sigma_N. The context's
    // friction load is built from the first; the model's interface stresses give the second.
    let c38 = cutcal_model::reference::c38_table3();
    for t in design() {
        let (p, full) =
            oxley_with_hooks_from(&c38, &jaspers(20.0), &t, &Hooks::NEUTRAL, &OxleyOptions::wide(), None).unwrap();
        let from_forces = (t.rake_rad + (p.ft_n_per_m / p.fc_n_per_m).atan()).tan();
        let from_stresses = full.shear_flow_stress_int_pa / full.interface_normal_stress_pa;
        assert!((from_forces / from_stresses - 1.0).abs() < 1e-3, "test {}: {from_forces} vs {from_stresses}", t.id);
    }
}

#[test]
fn a_hybrid_coulomb_tresca_interface_is_named_friction_in_its_hybrid_form() {
    let tests = design();
    let ext = common::external(&tests, &|_| Hooks::NEUTRAL);
    let c38 = cutcal_model::reference::c38_table3();
    // mu at 0.9 of the median apparent friction k_chip / sigma_N of the design (0.58): the cap
    // lowers the interface temperature and so raises k_chip, and 9 of 15 tests slide, with
    // friction factors from 0.74 (h = 0.05 mm, 60 m/min) to 1.
    let mut apparent: Vec<f64> = tests
        .iter()
        .map(|t| {
            let (_, full) =
                oxley_with_hooks_from(&c38, &jaspers(20.0), t, &Hooks::NEUTRAL, &OxleyOptions::wide(), None).unwrap();
            full.shear_flow_stress_int_pa / full.interface_normal_stress_pa
        })
        .collect();
    apparent.sort_by(f64::total_cmp);
    let mu = 0.9 * apparent[apparent.len() / 2];
    let solved: Vec<(Prediction, f64)> = tests.iter().map(|t| hybrid(t, mu)).collect();
    let sliding = solved.iter().filter(|(_, m)| *m < 0.999).count();
    assert!((6..=12).contains(&sliding), "{sliding} of 15 tests slide at mu = {mu}");
    let rec_pred: Vec<Prediction> = solved.into_iter().map(|(p, _)| p).collect();
    let rec = measured(&tests, &rec_pred, &|_| 1.0);
    let report = run(&rec, &ext);
    assert_eq!(report.selected, vec!["tool_chip_friction".to_string()], "{}", report.to_text());
    let f = report.mechanisms.iter().find(|m| m.id == "tool_chip_friction").unwrap();
    // The refit chose the hybrid form (reported as w_c = 1).
    let w = &f.params["w_c"];
    assert!((w.value - 1.0).abs() < 1e-12, "w_c = {}: {}", w.value, report.to_text());
}
