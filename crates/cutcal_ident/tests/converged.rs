//! Integration test: the default `converged` preset on C38 test 3 (paper Tables 2, 3 and 6):
//! the Eq 15 zone integral with the solvers' clamped JC law is converged in the quadrature, and
//! the uniform-N discrete objective of the same law tends to it as N grows.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use cutcal_ident::quadrature::{identify_converged, ConvergedOptions};
use cutcal_ident::{identify_from_zone_with, JcBounds, JcConstants, MultistartOptions};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState, ZoneSolution};
use cutcal_model::{JcParams, RateTerm};

const BOUNDS: JcBounds =
    JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 0.25], c: [1e-4, 1.0], m: [0.9, 1.1] };
const CONST: JcConstants = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
const ENHANCED: DpzdVariant = DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 };

fn zone(h_m: f64) -> ZoneSolution {
    // C38 test 3: paper Tables 2 and 6.
    let t = cutcal_model::reference::c38_test3();
    let s = ShearPlaneState::from_test(&t).unwrap();
    dpzd::solve(&cutcal_model::reference::c38_table3(), &s, &DpzdConfig::new(h_m, 4.0, ENHANCED).unwrap()).unwrap()
}

fn abc(jc: &JcParams) -> [f64; 3] {
    [jc.a_pa / 1e6, jc.b_pa / 1e6, jc.c]
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn quadrature_is_converged_and_independent_of_its_tolerance() {
    let z = zone(1e-4);
    let ms = MultistartOptions::new(8, 1);
    let base = identify_converged(&z, &BOUNDS, CONST, &ms, &ConvergedOptions::default()).unwrap();
    let fine = ConvergedOptions { quadrature_rel_tol: 1e-9, ..ConvergedOptions::default() };
    let tight = identify_converged(&z, &BOUNDS, CONST, &ms, &fine).unwrap();
    assert!(tight.nodes > base.nodes, "a tighter tolerance must refine the rule");
    for (x, y) in abc(&base.identification.jc).iter().zip(abc(&tight.identification.jc)) {
        assert!(rel(*x, y) < 1e-3, "{x} vs {y}");
    }
    // The fitted law is the clamped one.
    assert_eq!(base.identification.rate_term, RateTerm::Clamped);
}

#[test]
fn uniform_sum_of_the_clamped_law_tends_to_the_integral() {
    // The paper's discrete sum at N uniform interior points is a midpoint-type rule for the same
    // integral: with the clamped law its A, B, C approach the converged ones as N grows.
    let z = zone(1e-4);
    let ms = MultistartOptions::new(8, 1);
    let conv = identify_converged(&z, &BOUNDS, CONST, &ms, &ConvergedOptions::default()).unwrap();
    let want = abc(&conv.identification.jc);
    let mut errs = Vec::new();
    println!("N | A MPa | B MPa | C | max rel. dev. from converged");
    for n in [51usize, 201, 1001, 5001] {
        let id = identify_from_zone_with(&z, n, RateTerm::Clamped, &BOUNDS, CONST, &ms).unwrap();
        let got = abc(&id.jc);
        let e = got.iter().zip(&want).map(|(g, w)| rel(*g, *w)).fold(0.0, f64::max);
        println!("{n} | {:.2} | {:.2} | {:.5} | {e:.2e}", got[0], got[1], got[2]);
        errs.push(e);
    }
    println!("converged ({} nodes) | {:.2} | {:.2} | {:.5}", conv.nodes, want[0], want[1], want[2]);
    assert!(errs.windows(2).all(|w| w[1] < w[0]), "deviation must fall with N: {errs:?}");
    assert!(errs[3] < 2e-3, "N = 5001 within 0.2 % of the integral: {errs:?}");
}
