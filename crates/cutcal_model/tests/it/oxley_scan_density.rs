//! The least-Fc solution does not depend on the delta scan density: over the maps of
//! `oxley_convergence.rs` (V 30-600 m/min, t1 0.02-0.4 mm, rake -10..+20 deg), here on a 14 x 14 x 14
//! grid per material, the default scan (`OxleyOptions::wide`, 5 geometric delta points) and a scan
//! 16x denser (80 points) give the same Fc to 1e-5 wherever neither answer is flagged
//! `delta_at_bound`, and they converge at the same conditions.
//!
//! Where the minimum is flagged at a bound, the answer is set by a search range, not by the model:
//! at positive rakes above about 13 deg and high V t1 (AISI 1045), Fc keeps falling toward the delta
//! at which C0 reaches the bottom of its range (1.2), and a denser scan gets closer to that bound
//! (Fc up to 13 % lower with 80 points). Those answers carry the flag; docs/oxley.md says so.

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
use cutcal_model::{JcParams, Material};

use crate::support::{aa6082, aisi1045, jc_aa6082, jc_aisi1045};

/// (compared, flagged at a bound, converged only by one of the two, largest relative Fc difference).
fn compare(material: &Material, jc: &JcParams, work_c: f64) -> (usize, usize, usize, f64) {
    let coarse = OxleyOptions::wide();
    let mut dense = coarse.clone();
    dense.delta_scan_points = 16 * coarse.delta_scan_points;
    let n = 14;
    let (mut compared, mut flagged, mut one_sided, mut worst) = (0, 0, 0, 0.0f64);
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let f = |lo: f64, hi: f64, i: usize| lo + (hi - lo) * i as f64 / (n - 1) as f64;
                let v = f(30.0, 600.0, i) / 60.0;
                let t1 = f(0.02e-3, 0.4e-3, j);
                let rake = f(-10.0, 20.0, k).to_radians();
                let c = CuttingConditions::new(v, t1, 1e-3, rake, work_c).unwrap();
                let a = oxley::predict(material, jc, &c, &coarse, &Physics::baseline());
                let b = oxley::predict(material, jc, &c, &dense, &Physics::baseline());
                match (a, b) {
                    (Ok(a), Ok(b)) if a.flags.delta_at_bound || b.flags.delta_at_bound => flagged += 1,
                    (Ok(a), Ok(b)) => {
                        compared += 1;
                        worst = worst.max((a.cutting_force_n_per_m / b.cutting_force_n_per_m - 1.0).abs());
                    }
                    (Err(_), Err(_)) => {}
                    _ => one_sided += 1,
                }
            }
        }
    }
    (compared, flagged, one_sided, worst)
}

#[test]
fn least_fc_does_not_depend_on_the_delta_scan_density() {
    for (name, m, jc, tw) in [("AISI 1045", aisi1045(), jc_aisi1045(), 25.0), ("AA6082", aa6082(), jc_aa6082(), 20.0)] {
        let (compared, flagged, one_sided, worst) = compare(&m, &jc, tw);
        println!("{name}: {compared} compared, {flagged} flagged delta_at_bound, {one_sided} one-sided, largest Fc difference {worst:.2e}");
        assert!(compared > 2000, "{name}: only {compared} unflagged conditions");
        assert_eq!(one_sided, 0, "{name}: the scan density decides whether a solution is found");
        assert!(worst < 1e-5, "{name}: Fc moves by {worst:.2e} with the scan density");
    }
}
