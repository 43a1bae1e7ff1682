//! Edge ploughing and the flank-wear land inside a prediction: the additive forces are scaled by the
//! k_AB and phi of the same solution, the chip-formation solution is unchanged, and the terms are
//! reported separately.

use cutcal_model::oxley::{self, waldorf_factors, CuttingConditions, OxleyOptions, Physics};

use crate::support::{aisi1045, jc_aisi1045};

#[test]
fn edge_and_wear_terms_add_to_the_chip_forces_with_the_solutions_k_ab() {
    let (m, jc) = (aisi1045(), jc_aisi1045());
    let opts = OxleyOptions::wide();
    // Lalwani et al. 2009 case 1 conditions with a 25 um edge and a 0.1 mm wear land.
    let cond = CuttingConditions::new(200.0 / 60.0, 0.15e-3, 1.6e-3, (-7f64).to_radians(), 25.0).unwrap();
    let sharp = oxley::predict(&m, &jc, &cond, &opts, &Physics::baseline()).unwrap();
    let tool = Physics::with_tool(Some(25e-6), Some(0.1e-3)).unwrap();
    let p = oxley::predict(&m, &jc, &cond, &opts, &tool).unwrap();
    assert_eq!(sharp.edge_cutting_force_n_per_m, 0.0);
    assert_eq!(sharp.wear_feed_force_n_per_m, 0.0);
    // The chip-formation solution does not depend on the additive terms.
    assert!((p.chip_cutting_force_n_per_m / sharp.chip_cutting_force_n_per_m - 1.0).abs() < 1e-9);
    // Edge: k_AB CA [P_c, P_t] with CA = r_e sqrt(1 - 0.7^2) (c_s = 0.3, t1 > 0.3 r_e) and the
    // factors evaluated at this solution's phi (Waldorf, DeVor & Kapoor 1998).
    let ca = 25e-6 * (1.0f64 - 0.49).sqrt();
    let [fc, ft] = waldorf_factors(p.phi_rad, 1.9f64.to_radians(), 1.0);
    let k = p.shear_flow_stress_ab_pa;
    assert!((p.edge_cutting_force_n_per_m / (k * ca * fc) - 1.0).abs() < 1e-12);
    assert!((p.edge_feed_force_n_per_m / (k * ca * ft) - 1.0).abs() < 1e-12);
    // Wear land, VB = 0.1 mm >= VB* = 0.05 mm: F_t = 2 k (VB - VB* + VB*/3), F_c = mu_w F_t with
    // mu_w 2 k = k (the cap is just reached) (Smithey, Kapoor & DeVor 2001).
    let ft_w = 2.0 * k * (0.1e-3 - 0.05e-3 + 0.05e-3 / 3.0);
    assert!((p.wear_feed_force_n_per_m / ft_w - 1.0).abs() < 1e-12);
    assert!((p.wear_cutting_force_n_per_m / (0.5 * ft_w) - 1.0).abs() < 1e-12);
    // Totals and magnitudes: ploughing is thrust-dominant (P_t/P_c = 1 + pi/2 - 2 rho ~ 2.5).
    let sum_c = p.chip_cutting_force_n_per_m + p.edge_cutting_force_n_per_m + p.wear_cutting_force_n_per_m;
    assert!((p.cutting_force_n_per_m / sum_c - 1.0).abs() < 1e-12);
    assert!(p.edge_feed_force_n_per_m > 2.0 * p.edge_cutting_force_n_per_m);
    assert!((p.cutting_force_n - p.cutting_force_n_per_m * 1.6e-3).abs() < 1e-9);
}

#[test]
fn edge_force_scales_with_radius_and_is_off_for_zero() {
    let (m, jc) = (aisi1045(), jc_aisi1045());
    let opts = OxleyOptions::wide();
    let cond = CuttingConditions::new(150.0 / 60.0, 0.1e-3, 1.0e-3, 0.0, 25.0).unwrap();
    let f = |r: f64| {
        oxley::predict(&m, &jc, &cond, &opts, &Physics::with_tool(Some(r), None).unwrap())
            .unwrap()
            .edge_feed_force_n_per_m
    };
    assert_eq!(f(0.0), 0.0);
    let (a, b) = (f(10e-6), f(40e-6));
    assert!((b / a - 4.0).abs() < 1e-9, "{a} {b}");
}

#[test]
fn predict_many_equals_predict_in_order() {
    let (m, jc) = (aisi1045(), jc_aisi1045());
    let opts = OxleyOptions::wide();
    let conds: Vec<_> = [(100.0, 0.1e-3, -7.0), (200.0, 0.15e-3, 5.0), (300.0, 0.3e-3, 0.0), (400.0, 0.2e-3, 10.0)]
        .iter()
        .map(|&(v, t1, r): &(f64, f64, f64)| {
            CuttingConditions::new(v / 60.0, t1, 1.6e-3, r.to_radians(), 25.0).unwrap()
        })
        .collect();
    let phys = Physics::with_tool(Some(20e-6), None).unwrap();
    let many = oxley::predict_many(&m, &jc, &conds, &opts, &phys);
    assert_eq!(many.len(), conds.len());
    for (c, p) in conds.iter().zip(many) {
        assert_eq!(p.unwrap(), oxley::predict(&m, &jc, c, &opts, &phys).unwrap());
    }
}
