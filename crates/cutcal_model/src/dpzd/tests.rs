//! Unit tests of `dpzd`.

use super::*;
use crate::material::tests_support::c38;

fn c38_test3() -> ShearPlaneState {
    // C38 test 3, paper Tables 2 and 6.
    let t = crate::reference::c38_test3();
    ShearPlaneState::from_test(&t).unwrap()
}

fn enhanced() -> DpzdConfig {
    DpzdConfig::new(1e-4, 4.0, DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }).unwrap()
}

fn original() -> DpzdConfig {
    DpzdConfig::new(1e-4, 4.0, DpzdVariant::Original { rho_cp_j_per_m3_k: 3.5325e6 }).unwrap()
}

#[test]
fn original_exit_temperature_matches_closed_form() {
    // Independent calculation: W = 2 gamma_AB (r+1) [tau0/(r+1) + (tau_max - tau0)/(r+2)],
    // T_EF = Tr + W / rho_cp with tau0 = sigma0(20)/sqrt(3).
    let s = c38_test3();
    let z = solve(&c38(), &s, &original()).unwrap();
    let sigma0 = 773.007 - 1.630 * 20.0 + 0.0038 * 400.0 - 3.001e-6 * 8000.0;
    let tau0 = sigma0 / 3f64.sqrt() * 1e6;
    let g = 1.0 / (2.0 * s.shear_angle_rad.sin() * s.shear_angle_rad.cos());
    let w = 2.0 * g * 5.0 * (tau0 / 5.0 + (s.tau_max_pa - tau0) / 6.0);
    assert!((z.t_ef_c - (20.0 + w / 3.5325e6)).abs() < 1e-9);
}

#[test]
fn enhanced_fixed_point_converges_fast_and_exits_cooler() {
    let s = c38_test3();
    let e = solve(&c38(), &s, &enhanced()).unwrap();
    let o = solve(&c38(), &s, &original()).unwrap();
    assert!(e.iterations <= 8, "{} iterations", e.iterations);
    assert!(e.t_ef_c < o.t_ef_c, "enhanced {} vs original {}", e.t_ef_c, o.t_ef_c);
    // Thermal softening at EF (Fig 4): exit strength well below the entry strength.
    assert!(e.tau0_ef_pa < 0.8 * e.tau0_cd_pa);
}

#[test]
fn energy_balance_closes_along_the_zone() {
    // int rho*Cp dT (Tr -> T(x)) equals int tau dgamma (trapezoid in gamma, 20001 points).
    let m = c38();
    let z = solve(&m, &c38_test3(), &enhanced()).unwrap();
    let pts = z.profile(20001).unwrap();
    let mut w = 0.0;
    for pair in pts.windows(2).rev() {
        let (a, b) = (pair[1], pair[0]);
        w += 0.5 * (a.tau_pa + b.tau_pa) * (b.gamma - a.gamma);
    }
    let ef = pts[0];
    let heat = m.heat_content_j_per_m3(20.0, ef.temperature_c);
    assert!((w - heat).abs() < 1e-6 * heat, "work {w} heat {heat}");
}

#[test]
fn stress_profile_hits_its_boundary_values() {
    let z = solve(&c38(), &c38_test3(), &enhanced()).unwrap();
    assert!((z.tau_pa(0.05e-3) - z.tau0_cd_pa).abs() < 1e-6);
    assert!((z.tau_pa(-0.05e-3) - z.tau0_ef_pa).abs() < 1e-6);
    assert!((z.tau_pa(0.0) - z.state.tau_max_pa).abs() < 1e-6);
}

#[test]
fn rejects_stress_below_entry_strength() {
    let mut s = c38_test3();
    s.tau_max_pa = 300e6;
    assert!(solve(&c38(), &s, &enhanced()).is_err());
}
