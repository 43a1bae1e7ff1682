//! Every output of the `lalwani` preset against the independent implementation of Lalwani's
//! algorithm in pantale/OxleyPython (`ExtOxley_Lalwani.py`, run unmodified except for the cutting
//! conditions and rho = 7862 kg/m3), stored in `fixtures/reference/oxleypython-lalwani-grid.csv`
//! with the command that produced it. Tolerances (issue 15): Fc, Ft and t2 within 3 % (the
//! reference's grid steps, 0.1 deg in phi and 0.1 in C0, allow no closer); T_AB and T_int within
//! 5 % of their rise above the work temperature.

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, OxleyPrediction, Physics};
use cutcal_model::JcParams;

use crate::support::aisi1045;

const FIXTURE: &str = include_str!("../../../../fixtures/reference/oxleypython-lalwani-grid.csv");

/// The same reference with a second JC set (paper Table 5, 42CrMo4: C 0.117 and m 1.1, far from
/// Jaspers' C 0.0134 and m 1) in both implementations, on the script's AISI 1045 thermal data.
const FIXTURE_JC: &str = include_str!("../../../../fixtures/reference/oxleypython-jc-42crmo4.csv");

/// One reference row: conditions and the reference's outputs.
struct Row {
    speed_m_min: f64,
    t1_mm: f64,
    rake_deg: f64,
    delta: f64,
    fc_n: f64,
    ft_n: f64,
    chip_mm: f64,
    t_ab_c: f64,
    t_int_c: f64,
    res_shear: f64,
    res_normal: f64,
}

fn rows(fixture: &str) -> Vec<Row> {
    let mut out = Vec::new();
    let mut header = true;
    for line in fixture.lines().filter(|l| !l.starts_with('#') && !l.trim().is_empty()) {
        if header {
            assert!(line.starts_with("speed_m_min,uncut_mm,rake_deg,delta"), "{line}");
            header = false;
            continue;
        }
        let v: Vec<f64> = line.split(',').map(|x| x.trim().parse().unwrap()).collect();
        assert_eq!(v.len(), 14, "{line}");
        out.push(Row {
            speed_m_min: v[0],
            t1_mm: v[1],
            rake_deg: v[2],
            delta: v[3],
            fc_n: v[6],
            ft_n: v[7],
            chip_mm: v[8],
            t_ab_c: v[10],
            t_int_c: v[11],
            res_shear: v[12],
            res_normal: v[13],
        });
    }
    out
}

/// The reference's JC law: Jaspers & Dautzenberg 2002 with the reference temperature of the
/// script, T0 = 273.15 K = 0 degC (its `JohnsonCook` uses (T - T0)/(Tm - T0)).
fn jc_as_reference() -> JcParams {
    JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 0.0).unwrap()
}

/// Paper Table 5 for 42CrMo4 (fixtures/jc/42crmo4_table5.toml) with the script's T0 = 0 degC.
fn jc_42crmo4_as_reference() -> JcParams {
    JcParams::new(530e6, 153e6, 0.25, 0.117, 1.1, 1.0, 1460.0, 0.0).unwrap()
}

fn predict(r: &Row) -> OxleyPrediction {
    predict_with(r, &jc_as_reference(), &OxleyOptions::lalwani2009())
}

fn predict_with(r: &Row, jc: &JcParams, options: &OxleyOptions) -> OxleyPrediction {
    // w = 1.6 mm and T_w = 25 degC as in the script.
    let cond =
        CuttingConditions::new(r.speed_m_min / 60.0, r.t1_mm * 1e-3, 1.6e-3, r.rake_deg.to_radians(), 25.0).unwrap();
    oxley::predict(&aisi1045(), jc, &cond, options, &Physics::baseline())
        .unwrap_or_else(|e| panic!("{} m/min, {} mm, {} deg: {e}", r.speed_m_min, r.t1_mm, r.rake_deg))
}

#[test]
fn every_output_matches_the_independent_implementation_over_the_grid() {
    let rows = rows(FIXTURE);
    let failures = compare(&rows, &jc_as_reference(), &OxleyOptions::lalwani2009());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // 4 Lalwani cases + 21 grid conditions (the issue asks for >= 20).
    assert!(rows.len() >= 25, "4 Lalwani cases + 21 grid conditions, got {}", rows.len());
}

#[test]
fn every_output_matches_the_independent_implementation_with_another_jc_set() {
    let rows = rows(FIXTURE_JC);
    // This set needs C0 above Lalwani's 10 (as C38 does, `OxleyOptions::lalwani2009`): both
    // implementations search C0 up to 20.
    let mut options = OxleyOptions::lalwani2009();
    options.c0_range = [2.0, 20.0];
    let failures = compare(&rows, &jc_42crmo4_as_reference(), &options);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(rows.len() >= 6, "6 conditions, got {}", rows.len());
}

/// Every output of every row against the reference; the failures, one line each.
fn compare(rows: &[Row], jc: &JcParams, options: &OxleyOptions) -> Vec<String> {
    let mut failures = Vec::new();
    println!("V t1 rake | Fc ours/ref | Ft ours/ref | t2 ours/ref | T_AB ours/ref | T_int ours/ref | delta ours/ref");
    for r in rows {
        // The reference's grid point must itself be a solution (residuals within its grid step).
        assert!(
            r.res_shear.abs() < 0.05 && r.res_normal.abs() < 0.05,
            "reference not converged at {} {} {}",
            r.speed_m_min,
            r.t1_mm,
            r.rake_deg
        );
        let p = predict_with(r, jc, options);
        let rise = |t: f64| t - 25.0;
        let checks = [
            ("Fc", p.cutting_force_n / r.fc_n - 1.0, 0.03),
            ("Ft", p.feed_force_n / r.ft_n - 1.0, 0.03),
            ("t2", p.chip_thickness_m * 1e3 / r.chip_mm - 1.0, 0.03),
            ("T_AB", rise(p.temperature_ab_c) / rise(r.t_ab_c) - 1.0, 0.05),
            ("T_int", rise(p.temperature_int_c) / rise(r.t_int_c) - 1.0, 0.05),
        ];
        println!(
            "{} {} {} | {:.1}/{:.1} | {:.1}/{:.1} | {:.3}/{:.3} | {:.0}/{:.0} | {:.0}/{:.0} | {:.3}/{:.3}",
            r.speed_m_min,
            r.t1_mm,
            r.rake_deg,
            p.cutting_force_n,
            r.fc_n,
            p.feed_force_n,
            r.ft_n,
            p.chip_thickness_m * 1e3,
            r.chip_mm,
            p.temperature_ab_c,
            r.t_ab_c,
            p.temperature_int_c,
            r.t_int_c,
            p.delta,
            r.delta
        );
        for (name, err, tol) in checks {
            if !(err.abs() <= tol) {
                failures.push(format!(
                    "{name} at {} m/min, {} mm, {} deg: {:+.2} % (tolerance {} %)",
                    r.speed_m_min,
                    r.t1_mm,
                    r.rake_deg,
                    100.0 * err,
                    100.0 * tol
                ));
            }
        }
    }
    failures
}

/// Lalwani, Mehta & Jain 2009, Table (200 m/min, w = 1.6 mm): t1 (mm), rake (deg), Fc, Ft (N).
const LALWANI_TABLE: [(f64, f64, f64, f64); 4] =
    [(0.15, -7.0, 576.0, 364.0), (0.15, 5.0, 433.0, 171.0), (0.30, -7.0, 1007.0, 533.0), (0.30, 5.0, 773.0, 233.0)];

#[test]
fn lalwani_preset_is_within_5_percent_of_the_published_fc_and_ft() {
    // The JC reference temperature is the one of the independent implementation that reproduces
    // the table (0 degC); the paper's other inputs are in `support::aisi1045`.
    for (t1_mm, rake_deg, fc, ft) in LALWANI_TABLE {
        let r = Row {
            speed_m_min: 200.0,
            t1_mm,
            rake_deg,
            delta: 0.0,
            fc_n: fc,
            ft_n: ft,
            chip_mm: 0.0,
            t_ab_c: 0.0,
            t_int_c: 0.0,
            res_shear: 0.0,
            res_normal: 0.0,
        };
        let p = predict(&r);
        let (ec, et) = (p.cutting_force_n / fc - 1.0, p.feed_force_n / ft - 1.0);
        println!("{t1_mm} mm {rake_deg} deg: Fc {:+.2} %, Ft {:+.2} %", 100.0 * ec, 100.0 * et);
        assert!(ec.abs() < 0.05 && et.abs() < 0.05, "{t1_mm} mm {rake_deg} deg: Fc {ec:+.4}, Ft {et:+.4}");
    }
}

#[test]
fn outputs_move_the_right_way_with_speed_and_feed() {
    // Directions also shown by the reference fixture (e.g. 100 vs 250 vs 400 m/min rows): forces,
    // chip thickness and T_int rise with feed; Fc and t2 fall and T_int rises with speed. T_AB is
    // not asserted against speed: a lower heat partition beta and a larger phi act on it in
    // opposite directions (Oxley 1989, Sec. 4.3), and it is nearly flat.
    let at = |v: f64, t1: f64, rake: f64| {
        predict(&Row {
            speed_m_min: v,
            t1_mm: t1,
            rake_deg: rake,
            delta: 0.0,
            fc_n: 0.0,
            ft_n: 0.0,
            chip_mm: 0.0,
            t_ab_c: 0.0,
            t_int_c: 0.0,
            res_shear: 0.0,
            res_normal: 0.0,
        })
    };
    for rake in [-7.0, 0.0, 10.0] {
        for v in [100.0, 250.0, 400.0] {
            let ps: Vec<_> = [0.1, 0.15, 0.2, 0.25, 0.3].iter().map(|&t1| at(v, t1, rake)).collect();
            for w in ps.windows(2) {
                let (a, b) = (&w[0], &w[1]);
                assert!(b.cutting_force_n > a.cutting_force_n, "Fc with feed at {v} m/min, {rake} deg");
                assert!(b.feed_force_n > a.feed_force_n, "Ft with feed at {v} m/min, {rake} deg");
                assert!(b.chip_thickness_m > a.chip_thickness_m, "t2 with feed at {v} m/min, {rake} deg");
                assert!(b.temperature_int_c > a.temperature_int_c, "T_int with feed at {v} m/min, {rake} deg");
            }
        }
        for t1 in [0.1, 0.2, 0.3] {
            let ps: Vec<_> = [100.0, 150.0, 200.0, 250.0, 300.0, 400.0].iter().map(|&v| at(v, t1, rake)).collect();
            for w in ps.windows(2) {
                let (a, b) = (&w[0], &w[1]);
                assert!(b.cutting_force_n < a.cutting_force_n, "Fc with speed at {t1} mm, {rake} deg");
                assert!(b.chip_thickness_m < a.chip_thickness_m, "t2 with speed at {t1} mm, {rake} deg");
                assert!(b.temperature_int_c > a.temperature_int_c, "T_int with speed at {t1} mm, {rake} deg");
            }
        }
    }
}
