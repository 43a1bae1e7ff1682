//! Integration tests of the variable-projection identification (`cutcal_ident::varpro`, Golub and
//! Pereyra 1973): on zone data synthesised from random JC truths (the law of paper Eq 16 at the
//! strain, strain rate and temperature of the C38 test 3 zone, paper Tables 2, 3 and 6), the
//! projected solution equals the full 5-parameter LM solution of the same objective; the MLSL
//! sample filter of the default multistart reaches the minimum of the exhaustive multistart; and
//! the analytic Jacobian of the projected residual equals central finite differences.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use std::sync::OnceLock;

use cutcal_ident::dpzd_fit::{identify, ZoneFitProblem};
use cutcal_ident::multistart::{multistart, SampleFilter};
use cutcal_ident::{Bounds, JcBounds, JcConstants, MultistartOptions, Problem};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState, ZonePoint};
use cutcal_model::{JcParams, RateTerm};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

const CONST: JcConstants = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
const BOUNDS: JcBounds =
    JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 1.0], c: [1e-4, 0.5], m: [0.5, 1.5] };

/// The 51 interior points of the enhanced-DPZD zone of C38 test 3 (paper Tables 2 and 6).
fn zone_points() -> &'static [ZonePoint] {
    static PTS: OnceLock<Vec<ZonePoint>> = OnceLock::new();
    PTS.get_or_init(|| {
        let t = cutcal_model::reference::c38_test3();
        let s = ShearPlaneState::from_test(&t).unwrap();
        let cfg = DpzdConfig::new(1e-4, 4.0, DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }).unwrap();
        let z = dpzd::solve(&cutcal_model::reference::c38_table3(), &s, &cfg).unwrap();
        z.interior_points(51).unwrap()
    })
}

/// Zone points whose target is the law of `truth` times `1 + noise sin(1.7 k + phase)`.
fn synthetic(truth: &JcParams, rate: RateTerm, noise: f64, phase: f64) -> Vec<ZonePoint> {
    let mut pts = zone_points().to_vec();
    for (k, p) in pts.iter_mut().enumerate() {
        let f = truth.flow_stress_with(rate, p.strain, p.strain_rate_per_s, p.temperature_c);
        p.effective_stress_pa = f * (1.0 + noise * (1.7 * k as f64 + phase).sin());
    }
    pts
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-12)
}

fn config() -> ProptestConfig {
    let cases = std::env::var("CUTCAL_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(24);
    // A fixed seed: the CI run is deterministic (the project's rule); CUTCAL_FUZZ_CASES widens it.
    ProptestConfig { cases, rng_seed: proptest::test_runner::RngSeed::Fixed(11), ..ProptestConfig::default() }
}

proptest! {
    #![proptest_config(config())]

    /// The projected multistart reaches the minimum the full 5-parameter LM reaches: the same
    /// objective (1e-9 relative), and on exact data the same parameters, the truth (1e-6 relative,
    /// the project's acceptance bound). On noisy data the parameters agree to 1e-3: there the
    /// minimum lies in a flat n-m valley where the full LM's own starts differ by ~1e-4 (found by
    /// this test: A 1482, B 681, n 0.369, C 0.0109, m 0.808 with 1 % noise, where 7 of 8 full-LM
    /// starts stop at the 200-iteration cap along the valley).
    #[test]
    fn varpro_equals_the_full_lm_on_random_truths(
        a in 100.0..1500.0f64, b_over_a in 0.2..1.3f64, n in 0.1..0.6f64, c in 0.005..0.08f64, m in 0.7..1.3f64,
        clamped in any::<bool>(), noisy in any::<bool>(), phase in 0.0..6.0f64,
    ) {
        let b = a * b_over_a;
        let truth = JcParams::new(a * 1e6, b * 1e6, n, c, m, 1.0, 1460.0, 20.0).unwrap();
        let rate = if clamped { RateTerm::Clamped } else { RateTerm::Unclamped };
        let noise = if noisy { 0.01 } else { 0.0 };
        let pts = synthetic(&truth, rate, noise, phase);
        let problem = ZoneFitProblem::weighted(pts, &[1.0; 51], CONST, rate);
        // Every start searched on both sides: this test is about the projection, not the filter.
        let opts = MultistartOptions { sample_filter: SampleFilter::Off, ..MultistartOptions::new(16, 1) };
        let full = multistart(&problem, &BOUNDS.to_bounds().unwrap(), &opts).unwrap();
        let vp = match identify(&problem, &BOUNDS, &opts) {
            Ok(v) => v,
            // Typed non-convergence only where the full LM does not converge either.
            Err(e) => {
                prop_assert!(full.unconverged_starts == 16, "varpro: {}; full LM converged", e);
                return Ok(());
            }
        };
        let ssr_vp = vp.objective_mpa * vp.objective_mpa;
        // Exact data: both reach zero residual; scale by the target's size there.
        let scale = full.best.ssr.max(1e-18 * 51.0 * a * a);
        prop_assert!((ssr_vp - full.best.ssr).abs() <= 1e-9 * scale, "SSR {} vs {}", ssr_vp, full.best.ssr);
        let got = [vp.jc.a_pa / 1e6, vp.jc.b_pa / 1e6, vp.jc.n, vp.jc.c, vp.jc.m];
        let tol = if noisy { 1e-3 } else { 1e-6 };
        for (k, (g, w)) in got.iter().zip(full.best.params.iter()).enumerate() {
            prop_assert!(rel(*g, *w) <= tol, "parameter {}: varpro {} vs full LM {}", k, g, w);
        }
        if !noisy {
            // And both return the truth.
            for (g, t) in got.iter().zip([a, b, n, c, m]) {
                prop_assert!(rel(*g, t) <= 1e-6, "{} vs truth {}", g, t);
            }
        }
    }
}

proptest! {
    #![proptest_config(config())]

    /// The default multistart (MLSL sample filter with `MLSL_SIGMA`, and the basin rule) reaches
    /// the minimum of the exhaustive one (every start searched to convergence) at 16 and 32
    /// starts: on exact data the same parameters (the truth, 1e-6); on noisy data the same
    /// objective to 1e-3 relative. The noisy bound is the filter's measured limit: in a flat n-m
    /// valley a filtered sample point can lie in the basin of a minimum whose objective differs by
    /// 1e-4 (found with `CUTCAL_FUZZ_CASES=2000`: SSR 1490.50 vs 1490.22, m 0.727 vs 0.617).
    /// With `sigma = 4` this test fails (exact data, 16 starts: SSR 11 against 4e-26).
    #[test]
    fn the_mlsl_filter_reaches_the_exhaustive_minimum(
        a in 100.0..1500.0f64, b_over_a in 0.2..1.3f64, n in 0.1..0.6f64, c in 0.005..0.08f64, m in 0.7..1.3f64,
        clamped in any::<bool>(), noisy in any::<bool>(), phase in 0.0..6.0f64, many in any::<bool>(),
    ) {
        let truth = JcParams::new(a * 1e6, a * b_over_a * 1e6, n, c, m, 1.0, 1460.0, 20.0).unwrap();
        let rate = if clamped { RateTerm::Clamped } else { RateTerm::Unclamped };
        let noise = if noisy { 0.01 } else { 0.0 };
        let problem = ZoneFitProblem::weighted(synthetic(&truth, rate, noise, phase), &[1.0; 51], CONST, rate);
        let starts = if many { 32 } else { 16 };
        let filtered = MultistartOptions::new(starts, 1);
        let every = MultistartOptions {
            sample_filter: SampleFilter::Off,
            basin_stop: cutcal_ident::multistart::BasinStop::Off,
            ..filtered
        };
        let (Ok(f), Ok(e)) = (identify(&problem, &BOUNDS, &filtered), identify(&problem, &BOUNDS, &every)) else {
            // A typed non-convergence of either is not a miss of the filter.
            return Ok(());
        };
        prop_assert!(f.critical_distance.is_some() && f.filtered_starts + f.starts_at_best <= starts);
        let (sf, se) = (f.objective_mpa.powi(2), e.objective_mpa.powi(2));
        let scale = se.max(1e-18 * 51.0 * a * a);
        let tol = if noisy { 1e-3 } else { 1e-9 };
        prop_assert!(sf - se <= tol * scale, "filtered SSR {} vs exhaustive {} ({} of {} searched)",
            sf, se, starts - f.filtered_starts, starts);
    }
}

/// Central differences of the projected residuals (step 1e-6 of the box width).
fn finite_difference(p: &impl Problem, q: &DVector<f64>, bounds: &Bounds) -> DMatrix<f64> {
    let mut out = DMatrix::zeros(p.residual_count(), 3);
    let (mut rp, mut rm) = (DVector::zeros(p.residual_count()), DVector::zeros(p.residual_count()));
    for j in 0..3 {
        let h = 1e-6 * (bounds.upper[j] - bounds.lower[j]);
        let (mut up, mut dn) = (q.clone(), q.clone());
        up[j] += h;
        dn[j] -= h;
        p.residuals(&up, &mut rp).unwrap();
        p.residuals(&dn, &mut rm).unwrap();
        out.set_column(j, &((&rp - &rm) / (2.0 * h)));
    }
    out
}

#[test]
fn analytic_jacobian_equals_finite_differences_with_free_and_held_linear_parameters() {
    let truth = JcParams::new(600e6, 300e6, 0.18, 0.03, 1.0, 1.0, 1460.0, 20.0).unwrap();
    let bounds =
        Bounds::new(vec!["n".into(), "c".into(), "m".into()], vec![0.0, 1e-4, 0.5], vec![1.0, 0.5, 1.5]).unwrap();
    // Boxes of (A, B): both free; B held at 250 (below its optimum); A held at 700 and B at 250.
    let boxes = [([1.0, 2000.0], [1.0, 2000.0]), ([1.0, 2000.0], [1.0, 250.0]), ([700.0, 2000.0], [1.0, 250.0])];
    for rate in [RateTerm::Clamped, RateTerm::Unclamped] {
        let pts = synthetic(&truth, rate, 0.02, 0.3);
        let problem = ZoneFitProblem::weighted(pts, &[1.0; 51], CONST, rate);
        for (case, (a_box, b_box)) in boxes.into_iter().enumerate() {
            let vp = problem.projected(a_box, b_box);
            let mut held = 0;
            for q in [[0.1, 0.02, 0.8], [0.35, 0.06, 1.2], [0.25, 0.0688, 1.1]] {
                let q = DVector::from_row_slice(&q);
                let mut jac = DMatrix::zeros(51, 3);
                vp.jacobian(&q, &bounds, &mut jac).unwrap();
                let fd = finite_difference(&vp, &q, &bounds);
                for j in 0..3 {
                    let err = (jac.column(j) - fd.column(j)).norm();
                    let size = fd.column(j).norm();
                    assert!(
                        err <= 1e-6 * size,
                        "{rate:?} {a_box:?} {b_box:?} q {q:?} column {j}: {err:.3e} of {size:.3e}"
                    );
                }
                let l = vp.linear_solution(&q);
                held += usize::from(!l.a_free) + usize::from(!l.b_free);
            }
            // The narrowed boxes do hold a linear parameter at a bound at some q (the branch of
            // the Jacobian with a held parameter is exercised); the wide box holds none.
            if case == 0 {
                assert_eq!(held, 0, "{rate:?}");
            } else {
                assert!(held > 0, "{rate:?} {a_box:?} {b_box:?}");
            }
        }
    }
}
