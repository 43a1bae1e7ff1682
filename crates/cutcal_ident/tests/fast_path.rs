//! Integration test (issue 11 item 4, speed by structure): the fast paths give the results of the
//! previous ones on C38 test 3 (paper Tables 2, 3 and 6), original and enhanced DPZD, `paper`
//! and `converged` presets.
//!
//! - The multistart basin rule and the MLSL sample filter (`cutcal_ident::multistart`) against
//!   every start run to convergence (`BasinStop::Off`, `SampleFilter::Off`, the previous path):
//!   the same set to 1e-8 relative; where every start of the previous path reached the best, so
//!   does every local search of the fast one; the stopped and filtered starts are reported.
//! - The warm-started Monte-Carlo sample (`cutcal_ident::monte_carlo`, 2 starts, the first at the
//!   nominal solution) against the cold 32-start identification `cutcal identify` runs, on seeded
//!   draws of the measurements (3 %/5 %) and of the unstated choices (h x [0.5, 2], r +- 1):
//!   the same minimum to 1e-8 for the uniform objective, to the `converged` preset's own 0.1 %
//!   for the zone integral (the warm quadrature rule is a different converged rule), with the
//!   default settings and with the Monte-Carlo ones (`ConvergedOptions::monte_carlo`).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use cutcal_ident::bootstrap::{sample, Measurement, RelativeUncertainty, UnstatedChoices};
use cutcal_ident::monte_carlo::{SampleObjective, WarmSampleIdentifier};
use cutcal_ident::multistart::{BasinStop, SampleFilter};
use cutcal_ident::quadrature::{identify_converged, ConvergedOptions};
use cutcal_ident::{identify_from_zone_with, JcBounds, JcConstants, JcIdentification, MultistartOptions};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState, ZoneSolution};
use cutcal_model::{CuttingTest, JcParams, Material, RateTerm};

const BOUNDS: JcBounds =
    JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 0.25], c: [1e-4, 1.0], m: [0.9, 1.1] };
const CONST: JcConstants = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
const ORIGINAL: DpzdVariant = DpzdVariant::Original { rho_cp_j_per_m3_k: 3.5325e6 };
const ENHANCED: DpzdVariant = DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 };
/// h of the `paper` preset (0.1 mm) and about the forward model's l_AB/C0 for C38 test 3 (15 um,
/// issue 11).
const H_M: [f64; 2] = [1e-4, 1.5e-5];

fn c38() -> Material {
    cutcal_model::reference::c38_table3()
}

fn test3() -> CuttingTest {
    // C38 test 3: paper Tables 2 and 6.
    cutcal_model::reference::c38_test3()
}

fn zone(variant: DpzdVariant, h_m: f64) -> ZoneSolution {
    let s = ShearPlaneState::from_test(&test3()).unwrap();
    dpzd::solve(&c38(), &s, &DpzdConfig::new(h_m, 4.0, variant).unwrap()).unwrap()
}

fn vector(jc: &JcParams) -> [f64; 5] {
    [jc.a_pa / 1e6, jc.b_pa / 1e6, jc.n, jc.c, jc.m]
}

fn max_rel(a: &JcParams, b: &JcParams) -> f64 {
    vector(a).iter().zip(vector(b)).map(|(x, y)| (x - y).abs() / y.abs().max(1e-12)).fold(0.0, f64::max)
}

/// 32 starts; `Off` turns both the basin rule and the MLSL filter off (the previous path), `Auto`
/// is the default (both on in the DPZD identification).
fn options(basin: BasinStop) -> MultistartOptions {
    let sample_filter = if basin == BasinStop::Off { SampleFilter::Off } else { SampleFilter::Auto };
    MultistartOptions { basin_stop: basin, sample_filter, ..MultistartOptions::new(32, 1) }
}

fn paper(z: &ZoneSolution, basin: BasinStop) -> JcIdentification {
    identify_from_zone_with(z, 51, RateTerm::Unclamped, &BOUNDS, CONST, &options(basin)).unwrap()
}

fn converged(z: &ZoneSolution, basin: BasinStop) -> JcIdentification {
    identify_converged(z, &BOUNDS, CONST, &options(basin), &ConvergedOptions::default()).unwrap().identification
}

#[test]
fn basin_rule_gives_the_previous_sets_both_models_both_presets() {
    for (name, variant) in [("original", ORIGINAL), ("enhanced", ENHANCED)] {
        for h in H_M {
            let z = zone(variant, h);
            for (preset, run) in
                [("paper", paper as fn(&ZoneSolution, BasinStop) -> JcIdentification), ("converged", converged)]
            {
                let previous = run(&z, BasinStop::Off);
                let fast = run(&z, BasinStop::Auto);
                let d = max_rel(&fast.jc, &previous.jc);
                let searched = fast.starts - fast.filtered_starts;
                println!(
                    "{name} h {h:e} {preset}: max rel. diff {d:.1e}, {searched} of {} searched (critical distance \
                     {:?}), stopped {} (at best {}), starts at best {} vs {}",
                    fast.starts,
                    fast.critical_distance,
                    fast.stopped_starts,
                    fast.stopped_at_best,
                    fast.starts_at_best,
                    previous.starts_at_best
                );
                assert!(d <= 1e-8, "{name} h {h} {preset}: {:?} vs {:?}", vector(&fast.jc), vector(&previous.jc));
                assert_eq!((previous.stopped_starts, previous.filtered_starts), (0, 0));
                assert_eq!(previous.critical_distance, None);
                // Every start of the previous path reached the best here, so every search of the
                // fast path must (a filtered start never counts as having reached it).
                assert_eq!(previous.starts_at_best, previous.starts, "{name} h {h} {preset}");
                assert_eq!(fast.starts_at_best, searched, "{name} h {h} {preset}");
                // The filter and the rule acted, and every skipped start is reported.
                assert!(fast.filtered_starts > 0 && searched > 1, "{name} h {h} {preset}");
                assert!(fast.stopped_starts > 0 && fast.stopped_starts < searched);
                assert!(fast.stopped_at_best <= fast.stopped_starts);
            }
        }
    }
}

/// Tests the filter was not chosen on: a grid of C38 measurements around test 3 (Fc 190-260 N/mm,
/// Ft 150-220 N/mm, tc 0.14-0.18 mm at 0.075 mm and 240 m/min; 18 of them), both models, the
/// `paper` problem and the `converged` preset, h = 0.1 mm and 15 um: the default multistart (MLSL
/// filter and basin rule) gives the set of the exhaustive one to 1e-6 (the project's acceptance
/// bound; the two reach the same minimum by different LM paths, which stop at the cost tolerance:
/// seen up to 1.7e-8) wherever both solve.
#[test]
fn the_filter_keeps_the_exhaustive_set_on_a_grid_of_measurements() {
    let (mut compared, mut worst) = (0, 0.0f64);
    for fc in [190e3, 224e3, 260e3] {
        for ft in [150e3, 186e3, 220e3] {
            for tc in [0.14e-3, 0.18e-3] {
                let t = CuttingTest::new("g", 4.0, 0.075e-3, 1.95e-3, 0.0)
                    .unwrap()
                    .with_forces(Some(fc), Some(ft))
                    .unwrap()
                    .with_chip_thickness(Some(tc))
                    .unwrap();
                let Ok(s) = ShearPlaneState::from_test(&t) else { continue };
                for variant in [ORIGINAL, ENHANCED] {
                    for h in H_M {
                        let Ok(z) = dpzd::solve(&c38(), &s, &DpzdConfig::new(h, 4.0, variant).unwrap()) else {
                            continue;
                        };
                        for run in [paper as fn(&ZoneSolution, BasinStop) -> JcIdentification, converged] {
                            let (fast, every) = (run(&z, BasinStop::Auto), run(&z, BasinStop::Off));
                            let d = max_rel(&fast.jc, &every.jc);
                            assert!(d <= 1e-6, "Fc {fc} Ft {ft} tc {tc} {variant:?} h {h}: {d:.1e}");
                            worst = worst.max(d);
                            assert!(fast.filtered_starts > 0);
                            compared += 1;
                        }
                    }
                }
            }
        }
    }
    println!("{compared} identifications compared, worst max rel. diff {worst:.1e}");
    assert!(compared >= 100, "{compared}");
}

#[test]
fn warm_started_samples_find_the_cold_multistart_minimum() {
    let (material, test) = (c38(), test3());
    let nominal = Measurement { cutting_force_n_per_m: 224e3, feed_force_n_per_m: 186e3, chip_thickness_m: 0.157e-3 };
    let u = RelativeUncertainty::new(0.03, 0.05).unwrap();
    let choices = UnstatedChoices::new([0.5, 2.0], 1.0).unwrap();
    let warm_starts = MultistartOptions::new(2, 1);
    for (variant, h) in [(ENHANCED, 1.5e-5), (ORIGINAL, 1e-4)] {
        let z = zone(variant, h);
        let cfg = DpzdConfig::new(h, 4.0, variant).unwrap();
        for (objective, tol) in [
            // The uniform objective is the same problem on both paths: the same minimum to 1e-8.
            (SampleObjective::Uniform { points: 51, rate_term: RateTerm::Unclamped }, 1e-8),
            // The warm rule is refined from the nominal panels, a different rule from the cold
            // one's that meets the same quadrature tolerance: the two minima agree to the
            // accuracy the `converged` preset states for itself, 0.1 % (issue 11; the tolerance
            // of `converged.rs`). Seen: up to 1.7e-8 since every rule starts at the integrand's
            // breakpoints (2.4e-4 before, original model, C).
            (SampleObjective::Converged(ConvergedOptions::default()), 1e-3),
            // The Monte-Carlo settings (quadrature and refits to 1e-4, what `cutcal identify
            // --bootstrap` uses) against the cold default: the same 0.1 %.
            (SampleObjective::Converged(ConvergedOptions::monte_carlo()), 1e-3),
        ] {
            let nominal_id = match objective {
                SampleObjective::Uniform { .. } => paper(&z, BasinStop::Auto),
                SampleObjective::Converged(_) => converged(&z, BasinStop::Auto),
            };
            let warm = WarmSampleIdentifier::new(
                &material,
                &test,
                cfg,
                BOUNDS,
                CONST,
                objective,
                warm_starts,
                &z,
                &nominal_id,
            )
            .unwrap();
            let mut worst: f64 = 0.0;
            for i in 0..6 {
                let s = sample(&nominal, &u, Some(&choices), 11, i);
                let zs = warm.zone(&s).unwrap();
                let cold = match objective {
                    SampleObjective::Uniform { .. } => paper(&zs, BasinStop::Off),
                    SampleObjective::Converged(_) => converged(&zs, BasinStop::Off),
                };
                let fast = warm.identify(&s).unwrap();
                let d = max_rel(&fast, &cold.jc);
                worst = worst.max(d);
                assert!(d <= tol, "sample {i} {objective:?}: {:?} vs {:?} ({d:.1e})", vector(&fast), vector(&cold.jc));
            }
            println!("{variant:?} h {h:e} {objective:?}: worst max rel. diff over 6 draws {worst:.1e}");
        }
    }
}

#[test]
fn a_rule_refined_from_its_own_panels_is_itself_and_bad_edges_are_rejected() {
    use cutcal_ident::quadrature::{adaptive_rule, adaptive_rule_from};
    let z = zone(ENHANCED, 1.5e-5);
    let id = converged(&z, BasinStop::Auto);
    let p = nalgebra::DVector::from_vec(vector(&id.jc).to_vec());
    let o = ConvergedOptions::default();
    let cold = adaptive_rule(&z, &p, CONST, RateTerm::Clamped, &o).unwrap();
    assert!(cold.panels > 2 && cold.edges_rel.len() == cold.panels + 1);
    // The cold rule already meets the tolerance on its panels: refining from them adds none.
    let warm = adaptive_rule_from(&z, &p, CONST, RateTerm::Clamped, &o, &cold.edges_rel).unwrap();
    assert_eq!(warm.edges_rel, cold.edges_rel);
    assert_eq!(warm.weights, cold.weights);
    for bad in [vec![-0.5, 0.5], vec![-0.5, 0.1, 0.5], vec![-0.4, 0.0, 0.5], vec![-0.5, 0.0, -0.1, 0.5]] {
        assert!(adaptive_rule_from(&z, &p, CONST, RateTerm::Clamped, &o, &bad).is_err(), "{bad:?}");
    }
}

#[test]
fn warm_monte_carlo_is_identical_for_any_thread_count() {
    use cutcal_ident::bootstrap::{bootstrap, BootstrapOptions, BootstrapReport};
    let (material, test) = (c38(), test3());
    let h = 1.5e-5;
    let z = zone(ENHANCED, h);
    let nominal_id = converged(&z, BasinStop::Auto);
    let cfg = DpzdConfig::new(h, 4.0, ENHANCED).unwrap();
    let objective = SampleObjective::Converged(ConvergedOptions::default());
    let warm = WarmSampleIdentifier::new(
        &material,
        &test,
        cfg,
        BOUNDS,
        CONST,
        objective,
        MultistartOptions::new(2, 1),
        &z,
        &nominal_id,
    )
    .unwrap();
    let options = BootstrapOptions {
        samples: 12,
        seed: 5,
        uncertainty: RelativeUncertainty::new(0.03, 0.05).unwrap(),
        choices: Some(UnstatedChoices::new([0.5, 2.0], 1.0).unwrap()),
    };
    let nominal = Measurement { cutting_force_n_per_m: 224e3, feed_force_n_per_m: 186e3, chip_thickness_m: 0.157e-3 };
    let run = |threads: usize| -> BootstrapReport {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| bootstrap(&nominal, &options, |s| warm.identify(s)).unwrap())
    };
    let bits = |r: &BootstrapReport| {
        r.parameters.iter().flat_map(|p| [p.mean, p.std, p.q025, p.q975]).map(f64::to_bits).collect::<Vec<_>>()
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.failed, 0, "{:?}", one.first_failure);
    assert_eq!(bits(&one), bits(&two));
}
