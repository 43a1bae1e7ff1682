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
    // heat, Loewen & Shaw 1954): psi 0.9 with share s is the model with psi 0.9 s and share 1, and a
    // share below 1 gives a cooler interface than Oxley's all-to-the-chip.
    #[test]
    fn interface_heat_share_acts_as_psi(v in 100.0..400.0f64, t1 in 0.08..0.3f64, rake in -5.0..10.0f64, s in 0.5..0.95f64) {
        let cond = CuttingConditions::new(v / 60.0, t1 * 1e-3, 1e-3, rake.to_radians(), 25.0).unwrap();
        let shared = Physics { interface_heat_share: s, ..Physics::baseline() };
        let a = oxley::predict(&aisi1045(), &jc_aisi1045(), &cond, &OxleyOptions::wide(), &shared).unwrap();
        let psi = OxleyOptions::wide().with_eta_psi(0.9, 0.9 * s).unwrap();
        let b = oxley::predict(&aisi1045(), &jc_aisi1045(), &cond, &psi, &Physics::baseline()).unwrap();
        prop_assert!((a.cutting_force_n_per_m / b.cutting_force_n_per_m - 1.0).abs() < 1e-6);
        prop_assert!((a.temperature_int_c - b.temperature_int_c).abs() < 1e-3);
        let full = predict(v, t1, rake);
        prop_assert!(a.temperature_int_c < full.temperature_int_c, "{} !< {}", a.temperature_int_c, full.temperature_int_c);
    }
}
