//! Property tests of the extended Oxley model (AISI 1045, Jaspers & Dautzenberg JC).

use std::f64::consts::FRAC_PI_2;

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, OxleyPrediction, Physics};
use proptest::prelude::*;

use crate::support::{aisi1045, jc_aisi1045};

fn predict(v_m_min: f64, t1_mm: f64, rake_deg: f64) -> OxleyPrediction {
    let cond = CuttingConditions::new(v_m_min / 60.0, t1_mm * 1e-3, 1e-3, rake_deg.to_radians(), 25.0).unwrap();
    oxley::predict(&aisi1045(), &jc_aisi1045(), &cond, &OxleyOptions::wide(), &Physics::baseline()).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    // Fc rises with t1: a 20 % thicker cut needs more force (Oxley 1989, Fig. 4.x trend; forces
    // scale roughly with t1 since F_s = k_AB t1 w / sin phi).
    #[test]
    fn fc_rises_with_uncut_thickness(v in 100.0..400.0f64, t1 in 0.08..0.3f64, rake in -5.0..10.0f64) {
        let a = predict(v, t1, rake);
        let b = predict(v, t1 * 1.2, rake);
        prop_assert!(b.cutting_force_n_per_m > a.cutting_force_n_per_m, "{} !> {}", b.cutting_force_n_per_m, a.cutting_force_n_per_m);
    }

    // phi rises with rake (every shear-angle relation, Merchant 1945 to Oxley 1989).
    #[test]
    fn phi_rises_with_rake(v in 100.0..400.0f64, t1 in 0.08..0.3f64, rake in -6.0..10.0f64) {
        let a = predict(v, t1, rake);
        let b = predict(v, t1, rake + 4.0);
        prop_assert!(b.phi_rad > a.phi_rad, "{} !> {}", b.phi_rad.to_degrees(), a.phi_rad.to_degrees());
    }

    // The solution satisfies its own equilibrium, recomputed from the reported outputs only:
    // F_s = Fc cos phi - Ft sin phi = k_AB l_AB; F = Fc sin a + Ft cos a and N = Fc cos a - Ft sin a;
    // F/h = k_chip; N/h = k_AB (1 + pi/2 - 2a - 2 C0 n_eq) (Oxley 1989, Sec. 4.2).
    #[test]
    fn solution_satisfies_its_equilibrium(v in 60.0..500.0f64, t1 in 0.05..0.35f64, rake in -8.0..15.0f64) {
        let p = predict(v, t1, rake);
        let a = rake.to_radians();
        let (fc, ft, phi) = (p.cutting_force_n_per_m, p.feed_force_n_per_m, p.phi_rad);
        let k_ab = p.shear_flow_stress_ab_pa;
        let fs = fc * phi.cos() - ft * phi.sin();
        prop_assert!((fs / (k_ab * p.shear_plane_length_m) - 1.0).abs() < 1e-9);
        let f = fc * a.sin() + ft * a.cos();
        let n = fc * a.cos() - ft * a.sin();
        let tol = 1e-6;
        prop_assert!((f / p.contact_length_m - p.shear_flow_stress_int_pa).abs() / k_ab < tol);
        let sigma_n_prime = k_ab * (1.0 + FRAC_PI_2 - 2.0 * a - 2.0 * p.c0 * p.n_eq);
        prop_assert!((n / p.contact_length_m - sigma_n_prime).abs() / k_ab < tol);
        // Chip geometry: t2 = t1 cos(phi - a) / sin(phi).
        prop_assert!((p.chip_thickness_m - t1 * 1e-3 * (phi - a).cos() / phi.sin()).abs() < 1e-12);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    // The interface heat share s scales the maximum interface rise dT_M as psi does
    // (T_int = T_w + dT_SZ + psi s dT_M, Oxley 1989 Sec 4.3 with the tool's share of the frictional
    // heat, Loewen & Shaw 1954): psi 0.9 with share s is the model with psi 0.9 s and share 1, at
    // every share, and where one has no solution neither has the other. A share of 0.75 or more
    // gives a cooler interface than Oxley's all-to-the-chip. Below that the claim does not hold
    // everywhere, and the test does not make it: on slow, thin cuts with a positive rake the cooler
    // chip side raises k_chip, Oxley's tau_int = k_chip lowers phi, and the extra shear heats the
    // interface again (100 m/min, 0.08 mm, 8 deg, s = 0.5: phi 3.8 deg, T_int 932 against 659 degC;
    // at 9.3 deg and s = 0.5 no solution is left). Both were found by a 1000-seed audit of this
    // test. On a grid of this test's range (speeds 100-400 m/min, 0.08-0.3 mm, rakes -5 to 10 deg;
    // 150 conditions, the share in steps of 0.005) the largest share with an interface no cooler,
    // or no solution, is 0.645, at 100 m/min, 0.08 mm and 10 deg
    // (`cargo run -p cutcal_model --release --example interface_share_scan`).
    #[test]
    fn interface_heat_share_acts_as_psi(v in 100.0..400.0f64, t1 in 0.08..0.3f64, rake in -5.0..10.0f64, s in 0.5..0.95f64) {
        let cond = CuttingConditions::new(v / 60.0, t1 * 1e-3, 1e-3, rake.to_radians(), 25.0).unwrap();
        let with_share = |share: f64| {
            let shared = Physics { interface_heat_share: share, ..Physics::baseline() };
            oxley::predict(&aisi1045(), &jc_aisi1045(), &cond, &OxleyOptions::wide(), &shared)
        };
        let psi = OxleyOptions::wide().with_eta_psi(0.9, 0.9 * s).unwrap();
        match (with_share(s), oxley::predict(&aisi1045(), &jc_aisi1045(), &cond, &psi, &Physics::baseline())) {
            (Ok(a), Ok(b)) => {
                prop_assert!((a.cutting_force_n_per_m / b.cutting_force_n_per_m - 1.0).abs() < 1e-6);
                prop_assert!((a.temperature_int_c - b.temperature_int_c).abs() < 1e-3);
            }
            (Err(_), Err(_)) => {}
            (a, b) => prop_assert!(false, "share {s} and psi {}: one solves, the other not ({a:?} / {b:?})", 0.9 * s),
        }
        let cooler = with_share(s.max(0.75)).unwrap();
        let full = predict(v, t1, rake);
        prop_assert!(cooler.temperature_int_c < full.temperature_int_c, "{} !< {}", cooler.temperature_int_c, full.temperature_int_c);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    // A scale s on C0 (`Physics::c0_scale`, the Mode A shadow's emulation of another code's primary
    // zone) replaces Oxley's normal-stress condition by C0 = s C0_Oxley(phi). Checked from the
    // reported outputs only: C0 / s is a root of the condition's closed-form quadratic in
    // u = C0 n_eq (Oxley 1989 Sec. 4.2; derivation in docs/oxley.md)
    // 3 (A - u sin psi)^2 + (2u - K)(3 T0 - 2u) = 0, T0 = 1 + 2 (pi/4 - phi), psi = phi - a,
    // A = cos psi + T0 sin psi, K = 1 + pi/2 - 2a; the scaled C0 sets the resultant's direction
    // tan(theta) = T0 - C0 n_eq and the strain rate C0 V_s / (sqrt(3) l_AB); and the shear
    // equilibrium F_s = k_AB l_AB and F/h = k_chip still hold. Every case solves for s in
    // [0.02, 1] (a thicker zone than Oxley's); a thinner one (s > 1) can leave no admissible state.
    #[test]
    fn a_c0_scale_replaces_the_normal_stress_condition(v in 100.0..400.0f64, t1 in 0.08..0.3f64, rake in -5.0..10.0f64, s in 0.02..1.0f64) {
        let cond = CuttingConditions::new(v / 60.0, t1 * 1e-3, 1e-3, rake.to_radians(), 25.0).unwrap();
        let physics = Physics { c0_scale: s, ..Physics::baseline() };
        let p = oxley::predict(&aisi1045(), &jc_aisi1045(), &cond, &OxleyOptions::wide(), &physics).unwrap();
        let a = rake.to_radians();
        let phi = p.phi_rad;
        let (t0, psi) = (1.0 + 2.0 * (std::f64::consts::FRAC_PI_4 - phi), phi - a);
        let big_a = psi.cos() + t0 * psi.sin();
        let k = 1.0 + FRAC_PI_2 - 2.0 * a;
        let u = p.c0 / s * p.n_eq;
        let quad = 3.0 * (big_a - u * psi.sin()).powi(2) + (2.0 * u - k) * (3.0 * t0 - 2.0 * u);
        prop_assert!(quad.abs() < 1e-9, "quadratic residual {quad} at C0/s = {}", p.c0 / s);
        prop_assert!((p.theta_rad.tan() - (t0 - p.c0 * p.n_eq)).abs() < 1e-9);
        let v_s = v / 60.0 * a.cos() / (phi - a).cos();
        let rate = p.c0 * v_s / (3f64.sqrt() * p.shear_plane_length_m);
        prop_assert!((p.strain_rate_ab_per_s / rate - 1.0).abs() < 1e-9);
        let (fc, ft) = (p.cutting_force_n_per_m, p.feed_force_n_per_m);
        let k_ab = p.shear_flow_stress_ab_pa;
        prop_assert!(((fc * phi.cos() - ft * phi.sin()) / (k_ab * p.shear_plane_length_m) - 1.0).abs() < 1e-9);
        let f = fc * a.sin() + ft * a.cos();
        prop_assert!((f / p.contact_length_m - p.shear_flow_stress_int_pa).abs() / k_ab < 1e-6);
    }
}
