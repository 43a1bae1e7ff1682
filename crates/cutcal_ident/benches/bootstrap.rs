//! Benchmarks of the Monte-Carlo propagation of C38 test 3 (paper Tables 2 and 6) on rayon's
//! global pool:
//!
//! - `bootstrap_1000_identifications_c38_test3_4_starts`: the issue-7 bench (measurement noise
//!   only, 51-point clamped fit, 4 cold starts per sample);
//! - `monte_carlo_converged/...`: the issue-11 default, the `converged` objective with the
//!   measurements (3 %/5 %) and the unstated choices (h x [0.5, 2], r +- 1) drawn, h = 15 um (about
//!   the forward model's l_AB/C0), per sample either warm-started from the nominal fit with
//!   2 starts and the Monte-Carlo settings (`warm_2_starts`, [`cutcal_ident::monte_carlo`],
//!   `ConvergedOptions::monte_carlo`, what `cutcal identify --bootstrap` runs) or cold with 4 starts
//!   (`cold_4_starts`, what `cutcal identify --bootstrap` ran before); also 1 warm start, and the
//!   `paper` objective (51 points, h = 0.1 mm) warm-started. A few hundred samples per
//!   iteration; the 10^4 figure is extrapolated, and measured once when `CUTCAL_BENCH_MC_FULL=1`
//!   (printed to stderr).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use cutcal_ident::bootstrap::{bootstrap, BootstrapOptions, Measurement, RelativeUncertainty, Sample, UnstatedChoices};
use cutcal_ident::monte_carlo::{SampleObjective, WarmSampleIdentifier};
use cutcal_ident::quadrature::{identify_converged, ConvergedOptions};
use cutcal_ident::{identify_from_zone, IdentError, JcBounds, JcConstants, MultistartOptions};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
use cutcal_model::{CuttingTest, JcParams, Material};

fn c38() -> Material {
    cutcal_model::reference::c38_table3()
}

fn bench(c: &mut Criterion) {
    let material = c38();
    // Paper Tables 2 and 6: 240 m/min, 0.075 mm, 1.95 mm, 0 deg; Fc 224 N/mm, Ft 186 N/mm, tc 0.157 mm.
    let test = CuttingTest::new("3", 4.0, 0.075e-3, 1.95e-3, 0.0).unwrap();
    let nominal = Measurement { cutting_force_n_per_m: 224e3, feed_force_n_per_m: 186e3, chip_thickness_m: 0.157e-3 };
    let variant = DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 };
    let cfg = DpzdConfig::new(1e-4, 4.0, variant).unwrap();
    let bounds = JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 0.25], c: [1e-4, 1.0], m: [0.9, 1.1] };
    let consts = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
    let starts = MultistartOptions::new(4, 1);
    let identify = |s: &Sample| -> Result<JcParams, IdentError> {
        let m = &s.measurement;
        let t = test
            .clone()
            .with_forces(Some(m.cutting_force_n_per_m), Some(m.feed_force_n_per_m))?
            .with_chip_thickness(Some(m.chip_thickness_m))?;
        let zone = dpzd::solve(&material, &ShearPlaneState::from_test(&t)?, &cfg)?;
        Ok(identify_from_zone(&zone, 51, &bounds, consts, &starts)?.jc)
    };
    let options = BootstrapOptions {
        samples: 1000,
        seed: 1,
        uncertainty: RelativeUncertainty::new(0.03, 0.05).unwrap(),
        choices: None,
    };
    let mut group = c.benchmark_group("bootstrap");
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    group.bench_function("bootstrap_1000_identifications_c38_test3_4_starts", |b| {
        b.iter(|| bootstrap(black_box(&nominal), &options, identify).unwrap())
    });
    group.finish();

    // The issue-11 default: converged objective, choices drawn.
    let measured =
        test.clone().with_forces(Some(224e3), Some(186e3)).unwrap().with_chip_thickness(Some(0.157e-3)).unwrap();
    let cfg15 = DpzdConfig::new(1.5e-5, 4.0, variant).unwrap();
    let zone = dpzd::solve(&material, &ShearPlaneState::from_test(&measured).unwrap(), &cfg15).unwrap();
    let co = ConvergedOptions::default();
    let nominal_fit = identify_converged(&zone, &bounds, consts, &MultistartOptions::new(32, 1), &co).unwrap();
    let warm_with = |starts: usize| {
        WarmSampleIdentifier::new(
            &material,
            &measured,
            cfg15,
            bounds,
            consts,
            SampleObjective::Converged(ConvergedOptions::monte_carlo()),
            MultistartOptions::new(starts, 1),
            &zone,
            &nominal_fit.identification,
        )
        .unwrap()
    };
    let (warm, warm1) = (warm_with(2), warm_with(1));
    // The `paper` objective (51 uniform points, unclamped), h = 0.1 mm as that preset.
    let zone_paper = dpzd::solve(&material, &ShearPlaneState::from_test(&measured).unwrap(), &cfg).unwrap();
    let paper = SampleObjective::Uniform { points: 51, rate_term: cutcal_model::RateTerm::Unclamped };
    let nominal_paper = cutcal_ident::identify_from_zone_with(
        &zone_paper,
        51,
        cutcal_model::RateTerm::Unclamped,
        &bounds,
        consts,
        &MultistartOptions::new(32, 1),
    )
    .unwrap();
    let warm_paper = WarmSampleIdentifier::new(
        &material,
        &measured,
        cfg,
        bounds,
        consts,
        paper,
        MultistartOptions::new(2, 1),
        &zone_paper,
        &nominal_paper,
    )
    .unwrap();
    let cold_starts = MultistartOptions::new(4, 1);
    let cold = |s: &Sample| -> Result<JcParams, IdentError> {
        let z = warm.zone(s)?;
        Ok(identify_converged(&z, &bounds, consts, &cold_starts, &co)?.identification.jc)
    };
    let warm_fn = |s: &Sample| warm.identify(s);
    let warm1_fn = |s: &Sample| warm1.identify(s);
    let warm_paper_fn = |s: &Sample| warm_paper.identify(s);
    let mc = |samples: usize| BootstrapOptions {
        samples,
        seed: 1,
        uncertainty: RelativeUncertainty::new(0.03, 0.05).unwrap(),
        choices: Some(UnstatedChoices::new([0.5, 2.0], 1.0).unwrap()),
    };
    let mut group = c.benchmark_group("monte_carlo_converged");
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    group.bench_function("warm_2_starts_500_samples", |b| {
        b.iter(|| bootstrap(black_box(&nominal), &mc(500), warm_fn).unwrap())
    });
    group.bench_function("warm_1_start_500_samples", |b| {
        b.iter(|| bootstrap(black_box(&nominal), &mc(500), warm1_fn).unwrap())
    });
    group.bench_function("paper_objective_warm_2_starts_500_samples", |b| {
        b.iter(|| bootstrap(black_box(&nominal), &mc(500), warm_paper_fn).unwrap())
    });
    group.bench_function("cold_4_starts_100_samples", |b| {
        b.iter(|| bootstrap(black_box(&nominal), &mc(100), cold).unwrap())
    });
    group.finish();

    if std::env::var_os("CUTCAL_BENCH_MC_FULL").is_some() {
        for (name, f) in [
            (
                "converged objective, warm 2 starts",
                &warm_fn as &(dyn Fn(&Sample) -> Result<JcParams, IdentError> + Sync),
            ),
            ("paper objective, warm 2 starts", &warm_paper_fn),
        ] {
            let t0 = std::time::Instant::now();
            let r = bootstrap(&nominal, &mc(10_000), f).unwrap();
            eprintln!(
                "monte_carlo {name}, 10^4 samples: {:.3} s wall on {} rayon threads ({} failed)",
                t0.elapsed().as_secs_f64(),
                rayon::current_num_threads(),
                r.failed
            );
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
