//! The extended Oxley model against Lalwani, Mehta & Jain 2009 (their predictions) and Ivester et al.
//! 2000 (measurements) for AISI 1045 at 200 m/min, w = 1.6 mm (shared/data/aisi1045-orthogonal-200mpm.csv).

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};

use crate::support::{aisi1045, jc_aisi1045};

/// One row of the published table: conditions, Lalwani's predictions, Ivester's measurements.
struct Case {
    t1_mm: f64,
    rake_deg: f64,
    // Lalwani et al. 2009 predictions: delta, C0, t2 (mm), T_AB, T_int (degC), Fc, Ft (N).
    lalwani: [f64; 7],
    // Ivester et al. 2000 measurements: Fc, Ft (N), T_int (degC).
    measured: [f64; 3],
}

const CASES: [Case; 4] = [
    Case {
        t1_mm: 0.15,
        rake_deg: -7.0,
        lalwani: [0.040, 5.8, 0.43, 385.0, 942.0, 576.0, 364.0],
        measured: [610.0, 450.0, 1130.0],
    },
    Case {
        t1_mm: 0.15,
        rake_deg: 5.0,
        lalwani: [0.055, 4.2, 0.31, 301.0, 861.0, 433.0, 171.0],
        measured: [585.0, 385.0, 1240.0],
    },
    Case {
        t1_mm: 0.30,
        rake_deg: -7.0,
        lalwani: [0.025, 5.5, 0.72, 367.0, 1042.0, 1007.0, 533.0],
        measured: [1150.0, 600.0, 1120.0],
    },
    Case {
        t1_mm: 0.30,
        rake_deg: 5.0,
        lalwani: [0.030, 3.8, 0.54, 294.0, 984.0, 773.0, 233.0],
        measured: [920.0, 450.0, 1240.0],
    },
];

#[test]
fn fc_within_5_percent_of_lalwani_2009_for_the_four_aisi1045_cases() {
    let m = aisi1045();
    let jc = jc_aisi1045();
    let opts = OxleyOptions::wide();
    println!("case | Fc ours/Lalwani/meas N | Ft ours/Lalwani/meas N | t2 ours/Lalwani mm | T_AB ours/Lalwani C | T_int ours/Lalwani/meas C | delta ours/Lalwani | C0 ours/Lalwani | phi deg | flags");
    for (k, c) in CASES.iter().enumerate() {
        // 200 m/min, w = 1.6 mm, work temperature 25 degC (Lalwani et al. 2009).
        let cond = CuttingConditions::new(200.0 / 60.0, c.t1_mm * 1e-3, 1.6e-3, c.rake_deg.to_radians(), 25.0).unwrap();
        let p = oxley::predict(&m, &jc, &cond, &opts, &Physics::baseline()).unwrap();
        let l = c.lalwani;
        println!(
            "{} | {:.0}/{:.0}/{:.0} | {:.0}/{:.0}/{:.0} | {:.3}/{:.2} | {:.0}/{:.0} | {:.0}/{:.0}/{:.0} | {:.4}/{:.3} | {:.2}/{:.1} | {:.2} | {:?} evals {}",
            k + 1,
            p.cutting_force_n, l[5], c.measured[0],
            p.feed_force_n, l[6], c.measured[1],
            p.chip_thickness_m * 1e3, l[2],
            p.temperature_ab_c, l[3],
            p.temperature_int_c, l[4], c.measured[2],
            p.delta, l[0],
            p.c0, l[1],
            p.phi_rad.to_degrees(),
            p.flags, p.evaluations
        );
        let err = p.cutting_force_n / l[5] - 1.0;
        assert!(
            err.abs() < 0.05,
            "case {}: Fc {:.1} N vs Lalwani {} N ({:+.1} %)",
            k + 1,
            p.cutting_force_n,
            l[5],
            100.0 * err
        );
        assert!(p.residual_shear.abs() < opts.residual_tolerance && p.residual_normal.abs() < opts.residual_tolerance);
    }
}
