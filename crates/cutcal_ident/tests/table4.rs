//! Integration test: the paper's Table 4 from C38 test 3, original and enhanced DPZD, under the
//! `paper` preset: N = 51 uniform points, h = 0.1 mm, rhoCp = 3.5325e6 J/(m^3 K) for the original
//! model and the unclamped rate term of Eq 16. These are choices made to reproduce Table 4 (the
//! paper states none of them); the default `converged` preset is tested in `converged.rs`.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use cutcal_ident::{identify_from_zone_with, JcBounds, JcConstants, MultistartOptions};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
use cutcal_model::{Material, RateTerm};

fn c38() -> Material {
    cutcal_model::reference::c38_table3()
}

fn state() -> ShearPlaneState {
    // C38 test 3: paper Tables 2 and 6.
    let t = cutcal_model::reference::c38_test3();
    ShearPlaneState::from_test(&t).unwrap()
}

const BOUNDS: JcBounds =
    JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 0.25], c: [1e-4, 1.0], m: [0.9, 1.1] };
const CONST: JcConstants = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };

fn identify(variant: DpzdVariant, h_m: f64) -> (dpzd::ZoneSolution, cutcal_ident::JcIdentification) {
    let cfg = DpzdConfig::new(h_m, 4.0, variant).unwrap();
    let z = dpzd::solve(&c38(), &state(), &cfg).unwrap();
    let id =
        identify_from_zone_with(&z, 51, RateTerm::Unclamped, &BOUNDS, CONST, &MultistartOptions::new(32, 1)).unwrap();
    (z, id)
}

const ORIGINAL: DpzdVariant = DpzdVariant::Original { rho_cp_j_per_m3_k: 3.5325e6 };
const ENHANCED: DpzdVariant = DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 };

fn within(got: f64, want: f64, rel: f64) -> bool {
    (got - want).abs() <= rel * want.abs()
}

#[test]
fn original_dpzd_reproduces_table4() {
    let (_, id) = identify(ORIGINAL, 1e-4);
    let jc = id.jc;
    // Table 4, "Original": A 671, B 404, n 0.25, C 0.026, m 1.1; A, B, C within 2 %.
    assert!(within(jc.a_pa / 1e6, 671.0, 0.02), "A = {}", jc.a_pa / 1e6);
    assert!(within(jc.b_pa / 1e6, 404.0, 0.02), "B = {}", jc.b_pa / 1e6);
    assert!(within(jc.c, 0.026, 0.02), "C = {}", jc.c);
    assert_eq!(id.statistics.at_bounds, vec!["n".to_string(), "m".to_string()]);
    assert!((jc.n - 0.25).abs() < 1e-9 && (jc.m - 1.1).abs() < 1e-9);
    // Every local search reaches the same minimum (the problem is benign on this box); the sample
    // points the MLSL filter skipped never count as having reached it.
    assert!(id.filtered_starts > 0 && id.critical_distance.is_some());
    assert_eq!(id.starts_at_best, 32 - id.filtered_starts);
    // With the filter and the basin rule off, all 32 starts reach it and give the same set.
    let all = MultistartOptions {
        basin_stop: cutcal_ident::multistart::BasinStop::Off,
        sample_filter: cutcal_ident::multistart::SampleFilter::Off,
        ..MultistartOptions::new(32, 1)
    };
    let cfg = DpzdConfig::new(1e-4, 4.0, ORIGINAL).unwrap();
    let z = dpzd::solve(&c38(), &state(), &cfg).unwrap();
    let every = identify_from_zone_with(&z, 51, RateTerm::Unclamped, &BOUNDS, CONST, &all).unwrap();
    assert_eq!((every.starts_at_best, every.filtered_starts), (32, 0));
    assert!(within(every.jc.a_pa, jc.a_pa, 1e-8) && within(every.jc.c, jc.c, 1e-8));
}

#[test]
fn enhanced_dpzd_reproduces_table4_a_and_c() {
    let (z, id) = identify(ENHANCED, 1e-4);
    let jc = id.jc;
    // Table 4, "Enhanced": A 589, C 0.069 within 2 %; n and m at their upper bounds.
    assert!(within(jc.a_pa / 1e6, 589.0, 0.02), "A = {}", jc.a_pa / 1e6);
    assert!(within(jc.c, 0.069, 0.02), "C = {}", jc.c);
    assert_eq!(id.statistics.at_bounds, vec!["n".to_string(), "m".to_string()]);
    // B: Table 4 prints 145; an independent calculation (issue 2) gets ~116 under every choice it
    // tried, and so do we (115.9 MPa). Pinned to the independent value, not to the table.
    assert!(within(jc.b_pa / 1e6, 116.0, 0.02), "B = {}", jc.b_pa / 1e6);
    // The fixed point of Sec 3.5 converges to 1e-6 K in at most 8 iterations (5 here).
    assert!(z.iterations <= 8, "{}", z.iterations);
    assert_eq!(z.iterations, 5);
}

#[test]
fn zone_thickness_only_reparametrises_the_fit() {
    // gammadot ~ 1/h, so ln(epsdot) shifts by -ln(h): A/B, A C, B C and 1/C - ln h are invariant.
    for variant in [ORIGINAL, ENHANCED] {
        let (_, base) = identify(variant, 1e-4);
        for h in [0.05e-3, 0.2e-3] {
            let (_, other) = identify(variant, h);
            let (a0, b0, c0) = (base.jc.a_pa, base.jc.b_pa, base.jc.c);
            let (a1, b1, c1) = (other.jc.a_pa, other.jc.b_pa, other.jc.c);
            assert!(within(a1 / b1, a0 / b0, 1e-5), "A/B at h = {h}");
            assert!(within(a1 * c1, a0 * c0, 1e-5), "A C at h = {h}");
            assert!(within(b1 * c1, b0 * c0, 1e-5), "B C at h = {h}");
            assert!(within(1.0 / c1 - h.ln(), 1.0 / c0 - 1e-4f64.ln(), 1e-5), "1/C - ln h at h = {h}");
            assert!((other.rms_mpa - base.rms_mpa).abs() < 1e-6 * base.rms_mpa);
        }
    }
}

#[test]
fn identification_is_deterministic_for_a_seed() {
    let (_, a) = identify(ENHANCED, 1e-4);
    let (_, b) = identify(ENHANCED, 1e-4);
    assert_eq!(a.jc.a_pa.to_bits(), b.jc.a_pa.to_bits());
    assert_eq!(a.jc.c.to_bits(), b.jc.c.to_bits());
}

#[test]
fn recovers_known_parameters_from_synthetic_stresses() {
    // Replace the DPZD stresses with the JC stress of a known interior set at the same strain,
    // rate and temperature: the identification must return that set (zero residual).
    let (z, _) = identify(ENHANCED, 1e-4);
    let truth = cutcal_model::JcParams::new(600e6, 300e6, 0.18, 0.03, 1.0, 1.0, 1460.0, 20.0).unwrap();
    let mut pts = z.interior_points(51).unwrap();
    for p in &mut pts {
        p.effective_stress_pa = truth.flow_stress(p.strain, p.strain_rate_per_s, p.temperature_c);
    }
    let problem = cutcal_ident::dpzd_fit::ZoneFitProblem::new(pts, CONST);
    let id = cutcal_ident::dpzd_fit::identify(&problem, &BOUNDS, &MultistartOptions::new(16, 3)).unwrap();
    assert!(id.rms_mpa < 1e-6, "rms {}", id.rms_mpa);
    assert!(within(id.jc.a_pa, 600e6, 1e-6) && within(id.jc.b_pa, 300e6, 1e-6));
    assert!(within(id.jc.n, 0.18, 1e-6) && within(id.jc.c, 0.03, 1e-6) && within(id.jc.m, 1.0, 1e-6));
    assert!(id.statistics.at_bounds.is_empty());
}

/// `docs/table4-b.md`: the variants of the enhanced identification tried in search of Table 4's
/// B = 145. Each is computed here; none gives B = 145 (within 2 %) while A and C stay at Table 4
/// (589, 0.069 within 2 %), which is the finding the document states.
#[test]
fn table4_b_variants_none_reaches_145_with_a_and_c_at_table4() {
    use cutcal_ident::dpzd_fit::{identify, ZoneFitProblem};
    let fit = |state: &ShearPlaneState, strain_is_gamma: bool, rate_is_gammadot: bool| {
        let cfg = DpzdConfig::new(1e-4, 4.0, ENHANCED).unwrap();
        let z = dpzd::solve(&c38(), state, &cfg).unwrap();
        let mut pts = z.interior_points(51).unwrap();
        for p in &mut pts {
            if strain_is_gamma {
                p.strain = p.gamma;
            }
            if rate_is_gammadot {
                p.strain_rate_per_s = p.gamma_dot_per_s;
            }
        }
        let w = vec![1.0; pts.len()];
        let problem = ZoneFitProblem::weighted(pts, &w, CONST, RateTerm::Unclamped);
        identify(&problem, &BOUNDS, &MultistartOptions::new(16, 1)).unwrap().jc
    };
    let base = state();
    // The paper's printed shear angle 25.48 deg instead of atan(0.075/0.157) = 25.53 deg, with
    // tau_max recomputed from the measured forces at that angle (Eq 9).
    let phi = 25.48f64.to_radians();
    let tau = cutcal_model::kinematics::tau_max_from_forces(224e3, 186e3, phi, 0.075e-3).unwrap();
    let paper_phi = ShearPlaneState { shear_angle_rad: phi, tau_max_pa: tau, ..base };
    let variants = [
        ("as implemented", fit(&base, false, false)),
        ("shear angle 25.48 deg", fit(&paper_phi, false, false)),
        ("effective strain = gamma", fit(&base, true, false)),
        ("effective strain rate = gammadot", fit(&base, false, true)),
        ("both", fit(&base, true, true)),
    ];
    for (name, jc) in &variants {
        let (a, b, c) = (jc.a_pa / 1e6, jc.b_pa / 1e6, jc.c);
        println!("{name}: A {a:.1} B {b:.1} C {c:.4}");
        let at_table4 = within(a, 589.0, 0.02) && within(c, 0.069, 0.02);
        assert!(!(at_table4 && within(b, 145.0, 0.02)), "{name} reaches Table 4's B: A {a} B {b} C {c}");
    }
    // The implemented choice keeps A and C at Table 4 and B at the independent 116.
    let jc = &variants[0].1;
    assert!(within(jc.a_pa / 1e6, 589.0, 0.02) && within(jc.b_pa / 1e6, 116.0, 0.02));
}
