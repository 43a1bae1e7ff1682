//! Convergence map of the extended Oxley solve: V 30-600 m/min, t1 0.02-0.4 mm, rake -10..+20 deg,
//! 10 x 10 x 10 = 1000 conditions each for AISI 1045 (Jaspers & Dautzenberg JC) and AA6082 (Table 5 JC).
//!
//! Every condition either converges (both equilibrium residuals below the tolerance, inside the
//! ranges) or fails with a typed `NoSolution` that gives the largest `(tau_int - k_chip)/k_AB` over
//! every phi and delta in the ranges, which must be negative: the model has no solution there. That
//! claim is checked by a different search: the same condition with 4x denser phi and delta scans
//! (the scan-and-bracket path, not the residual maximisation that produced the message) must fail
//! too. So the solver converges at every condition of the map where a solution exists (100 %), and
//! the converged share of the whole map is what the physics allows (docs/oxley.md, "Convergence maps").
//! Over the range of the reference comparisons (V 100-400 m/min, t1 0.1-0.3 mm, rake -7..+10 deg)
//! every one of 1000 conditions per material converges.

use std::collections::BTreeMap;

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, OxleyPrediction, Physics};
use cutcal_model::{JcParams, Material, ModelError};

use crate::support::{aa6082, aisi1045, jc_aa6082, jc_aisi1045};

fn lin(lo: f64, hi: f64, i: usize, n: usize) -> f64 {
    lo + (hi - lo) * i as f64 / (n - 1) as f64
}

/// Every finite output of a prediction (flags excluded).
fn all_finite(p: &OxleyPrediction) -> bool {
    [
        p.phi_rad,
        p.c0,
        p.delta,
        p.cutting_force_n_per_m,
        p.feed_force_n_per_m,
        p.chip_thickness_m,
        p.contact_length_m,
        p.temperature_ab_c,
        p.temperature_int_c,
        p.strain_ab,
        p.strain_rate_ab_per_s,
        p.strain_int,
        p.strain_rate_int_per_s,
        p.residual_shear,
        p.residual_normal,
    ]
    .iter()
    .all(|v| v.is_finite())
}

/// The largest shear residual stated in a NoSolution message ("... delta in the range is X, at ...").
fn stated_largest_residual(msg: &str) -> Option<f64> {
    let tail = msg.split("every delta in the range is ").nth(1)?;
    tail.split(',').next()?.trim().parse().ok()
}

/// Ranges of a map: speed m/min, t1 mm, rake deg.
struct Ranges {
    speed_m_min: [f64; 2],
    t1_mm: [f64; 2],
    rake_deg: [f64; 2],
}

/// The wide map of the module header.
const WIDE: Ranges = Ranges { speed_m_min: [30.0, 600.0], t1_mm: [0.02, 0.4], rake_deg: [-10.0, 20.0] };

/// The range of issue 15 item 2 (the users' range of the reference comparisons): V 100-400 m/min,
/// t1 0.1-0.3 mm, rake -7..+10 deg.
const USERS: Ranges = Ranges { speed_m_min: [100.0, 400.0], t1_mm: [0.1, 0.3], rake_deg: [-7.0, 10.0] };

fn map(material: &Material, jc: &JcParams, work_c: f64, r: &Ranges) -> (usize, usize, BTreeMap<String, usize>) {
    let opts = OxleyOptions::wide();
    let n = 10;
    let (mut total, mut ok) = (0, 0);
    let mut errors: BTreeMap<String, usize> = BTreeMap::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let v = lin(r.speed_m_min[0], r.speed_m_min[1], i, n) / 60.0;
                let t1 = lin(r.t1_mm[0], r.t1_mm[1], j, n) * 1e-3;
                let rake = lin(r.rake_deg[0], r.rake_deg[1], k, n).to_radians();
                let cond = CuttingConditions::new(v, t1, 1e-3, rake, work_c).unwrap();
                total += 1;
                match oxley::predict(material, jc, &cond, &opts, &Physics::baseline()) {
                    Ok(p) => {
                        assert!(all_finite(&p), "non-finite output at V {v} t1 {t1} rake {rake}: {p:?}");
                        assert!(p.residual_shear.abs().max(p.residual_normal.abs()) < opts.residual_tolerance);
                        assert!(p.temperature_int_c < jc.tm_c && p.temperature_ab_c < jc.tm_c);
                        assert!(p.cutting_force_n_per_m > 0.0 && p.chip_thickness_m > 0.0);
                        ok += 1;
                    }
                    Err(e) => {
                        let kind = match e {
                            ModelError::NoSolution { .. } => "NoSolution",
                            ModelError::NoConvergence { .. } => "NoConvergence",
                            ModelError::AboveMelting { .. } => "AboveMelting",
                            ModelError::OutOfRange { .. } => "OutOfRange",
                            ModelError::Inconsistent(_) => "Inconsistent",
                            _ => "other",
                        };
                        // Every failure is typed and names its physical reason.
                        let msg = e.to_string();
                        assert!(
                            matches!(e, ModelError::NoSolution { .. } | ModelError::AboveMelting { .. }),
                            "untyped failure at V {v} t1 {t1} rake {rake}: {msg}"
                        );
                        if let ModelError::NoSolution { .. } = e {
                            assert!(msg.contains("tau_int") && msg.contains("R_T ="), "no physical reason: {msg}");
                            let r = stated_largest_residual(&msg);
                            assert!(
                                r.is_some_and(|r| r < 0.0),
                                "no stated negative largest residual at V {v} t1 {t1} rake {rake}: {msg}"
                            );
                            // An independent, denser search finds no solution either.
                            let mut dense = opts.clone();
                            dense.phi_scan_points *= 4;
                            dense.delta_scan_points *= 4;
                            let again = oxley::predict(material, jc, &cond, &dense, &Physics::baseline());
                            assert!(again.is_err(), "a solution exists at V {v} t1 {t1} rake {rake}: {again:?}");
                        }
                        *errors.entry(kind.to_string()).or_default() += 1;
                    }
                }
            }
        }
    }
    (total, ok, errors)
}

#[test]
fn convergence_map_aisi1045_1000_conditions() {
    let (total, ok, errors) = map(&aisi1045(), &jc_aisi1045(), 25.0, &WIDE);
    println!("AISI 1045: {ok}/{total} converged ({:.1} %), errors {errors:?}", 100.0 * ok as f64 / total as f64);
    assert_eq!(total, 1000);
    // Measured 977/1000. The other 23 have no solution in the ranges (checked in `map`): all at
    // 30-157 m/min with t1 <= 0.104 mm, most at positive rake. Issue 15 asks for 99 % of the map;
    // the physics of this map allows 97.7 % (docs/oxley.md).
    assert!(ok >= 977, "only {ok}/{total} converged: {errors:?}");
}

#[test]
fn convergence_map_aa6082_1000_conditions() {
    let (total, ok, errors) = map(&aa6082(), &jc_aa6082(), 20.0, &WIDE);
    println!("AA6082: {ok}/{total} converged ({:.1} %), errors {errors:?}", 100.0 * ok as f64 / total as f64);
    assert_eq!(total, 1000);
    // Measured 945/1000. The other 55 have no solution in the ranges (checked in `map`); for most the
    // least k_chip is at delta = 0.5, the top of the range (a secondary zone half the chip thick).
    assert!(ok >= 945, "only {ok}/{total} converged: {errors:?}");
}

#[test]
fn every_condition_of_the_users_range_converges() {
    // 1000 conditions per material over issue 15's range; measured 1000/1000 for both.
    for (name, m, jc, tw) in [("AISI 1045", aisi1045(), jc_aisi1045(), 25.0), ("AA6082", aa6082(), jc_aa6082(), 20.0)] {
        let (total, ok, errors) = map(&m, &jc, tw, &USERS);
        println!("{name}, users' range: {ok}/{total} converged, errors {errors:?}");
        assert_eq!((total, ok), (1000, 1000), "{name}: {errors:?}");
    }
}
