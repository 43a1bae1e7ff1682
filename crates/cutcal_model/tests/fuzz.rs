//! Property-based fuzzing of the model entry points with admissible and adversarial values
//! (NaN, infinities, zero, huge): `CuttingTest::new` and its setters, `JcParams::new` and
//! `flow_stress`, `ShearPlaneState::from_test` and `dpzd::solve`. Properties: no panic; whatever is
//! accepted is finite and in its stated range; a solved zone stays below melting.
//!
//! `CUTCAL_FUZZ_CASES` scales the case count (default: a bounded smoke run); see `docs/fuzzing.md`.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
use cutcal_model::{CuttingTest, JcParams, Material};
use proptest::prelude::*;

fn config(smoke: u32) -> ProptestConfig {
    let cases = std::env::var("CUTCAL_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(smoke);
    ProptestConfig { cases, ..ProptestConfig::default() }
}

/// Any f64 at all, with the special values over-represented.
fn wild() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => any::<f64>(),
        1 => proptest::sample::select(vec![
            0.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE, f64::MAX, f64::MIN, 1e-300, -1.0,
        ]),
    ]
}

/// A value near `scale` most of the time (to reach the solvers), anything otherwise.
fn near(scale: f64) -> impl Strategy<Value = f64> {
    prop_oneof![4 => (0.01f64..3.0).prop_map(move |k| k * scale), 1 => wild()]
}

/// C38 of the paper's Table 3, in SI.
fn c38() -> Material {
    cutcal_model::reference::c38_table3()
}

proptest! {
    #![proptest_config(config(512))]

    #[test]
    fn cutting_test_accepts_only_admissible_values(
        v in near(4.0), tu in near(1e-4), w in near(2e-3), rake in near(0.3),
        fc in near(2e5), ft in near(2e5), tc in near(2e-4), tint in near(500.0),
    ) {
        if let Ok(t) = CuttingTest::new("x", v, tu, w, rake) {
            prop_assert!(v > 0.0 && v <= 200.0 && tu > 0.0 && tu <= 5e-3 && w > 0.0 && w <= 1.0);
            prop_assert!(rake.abs() < 45f64.to_radians());
            if let Ok(t) = t.clone().with_forces(Some(fc), Some(ft)) {
                prop_assert!(fc.is_finite() && fc > 0.0 && ft.is_finite() && ft > 0.0);
                if let Ok(t) = t.with_chip_thickness(Some(tc)) {
                    // Whatever a test accepts, the shear-plane state either exists with finite
                    // numbers or is refused with an error.
                    if let Ok(s) = ShearPlaneState::from_test(&t) {
                        prop_assert!(s.shear_angle_rad > 0.0 && s.shear_angle_rad < std::f64::consts::FRAC_PI_2);
                        prop_assert!(s.tau_max_pa.is_finite() && s.tau_max_pa > 0.0);
                    }
                }
            }
            if t.with_interface_temperature(Some(tint)).is_ok() {
                prop_assert!(tint.is_finite() && tint > -273.15 && tint <= 5000.0);
            }
        }
    }

    #[test]
    fn jc_flow_stress_is_finite_for_accepted_physical_sets(
        a in near(5e8), b in near(3e8), n in near(0.3), c in near(0.05), m in near(1.0),
        eps0 in near(1.0), tm in near(1400.0), tr in near(20.0),
        strain in near(1.0), rate in near(1e4), temp in near(600.0),
    ) {
        if let Ok(jc) = JcParams::new(a, b, n, c, m, eps0, tm, tr) {
            let s = jc.flow_stress(strain, rate, temp);
            let g = jc.gradient(strain, rate, temp);
            let physical = a < 1e11 && b < 1e11 && c < 10.0 && eps0 > 1e-12 && eps0 < 1e12;
            let inputs = (0.0..1e3).contains(&strain) && rate.is_finite() && rate > 0.0
                && rate < 1e12 && temp.is_finite();
            if physical && inputs {
                prop_assert!(s.is_finite(), "sigma {} for {:?} at ({}, {}, {})", s, jc, strain, rate, temp);
                prop_assert!(g.iter().all(|d| d.is_finite()) || strain == 0.0, "{:?}", g);
            }
        }
    }

    #[test]
    fn dpzd_solve_never_panics_and_stays_below_melting(
        v in near(4.0), rake in near(0.1), phi in near(0.45), tau in near(7e8),
        h in near(1e-4), r in near(4.0), tol in near(1e-6), enhanced in any::<bool>(), rho_cp in near(3.5e6),
    ) {
        let material = c38();
        let variant = if enhanced {
            DpzdVariant::Enhanced { tolerance_c: tol, max_iterations: 50 }
        } else {
            DpzdVariant::Original { rho_cp_j_per_m3_k: rho_cp }
        };
        let state = ShearPlaneState { speed_m_per_s: v, rake_rad: rake, shear_angle_rad: phi, tau_max_pa: tau };
        if let Ok(cfg) = DpzdConfig::new(h, r, variant) {
            if let Ok(z) = dpzd::solve(&material, &state, &cfg) {
                for t in [z.t_ab_c, z.t_ef_c, z.t_cd_c] {
                    prop_assert!(t.is_finite() && t < material.melting_c, "{:?}", z);
                }
                if let Ok(points) = z.interior_points(11) {
                    for p in points {
                        prop_assert!(p.temperature_c.is_finite() && p.temperature_c < material.melting_c);
                    }
                }
            }
        }
    }
}
