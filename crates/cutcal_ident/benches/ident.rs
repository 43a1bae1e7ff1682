//! Benchmarks: one 50-start enhanced-DPZD identification of C38 test 3 (paper Table 4): the
//! `paper` preset (N = 51, unclamped rate term), the clamped law at N = 51, and the `converged`
//! preset's final fit on its quadrature nodes; each by variable projection (what `identify`
//! runs) and, for comparison, by the full 5-parameter LM on the same problem; with the multistart
//! MLSL sample filter and the basin rule (the default, `_varpro`), with the basin rule only
//! (`_varpro_basin_rule_only`) and with every start searched to convergence
//! (`_varpro_all_starts`, the path before issue 11 item 4); and the whole `converged`
//! identification (51-point fit, rule, refits).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_ident::dpzd_fit::{identify, ZoneFitProblem};
use cutcal_ident::multistart::{multistart, BasinStop, SampleFilter};
use cutcal_ident::quadrature::{adaptive_rule, identify_converged, ConvergedOptions};
use cutcal_ident::{identify_from_zone, JcBounds, JcConstants, MultistartOptions};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
use cutcal_model::{Material, RateTerm};
use nalgebra::DVector;

fn c38() -> Material {
    cutcal_model::reference::c38_table3()
}

fn bench(c: &mut Criterion) {
    let m = c38();
    // C38 test 3, paper Tables 2 and 6 (tau_max from Eq 9 with the measured forces).
    let state = ShearPlaneState {
        speed_m_per_s: 4.0,
        rake_rad: 0.0,
        shear_angle_rad: (0.075f64 / 0.157).atan(),
        tau_max_pa: 700.9e6,
    };
    let cfg = DpzdConfig::new(1e-4, 4.0, DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }).unwrap();
    let z = dpzd::solve(&m, &state, &cfg).unwrap();
    let bounds = JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 0.25], c: [1e-4, 1.0], m: [0.9, 1.1] };
    let consts = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
    let opts = MultistartOptions::new(50, 1);
    c.bench_function("identify_enhanced_c38_test3_50_starts", |b| {
        b.iter(|| identify_from_zone(black_box(&z), 51, &bounds, consts, &opts).unwrap())
    });

    // The problems as the presets build them.
    let pts = z.interior_points(51).unwrap();
    let paper = ZoneFitProblem::weighted(pts.clone(), &vec![1.0; 51], consts, RateTerm::Unclamped);
    let conv = identify_converged(&z, &bounds, consts, &opts, &ConvergedOptions::default()).unwrap();
    let jc = conv.identification.jc;
    let p = DVector::from_vec(vec![jc.a_pa / 1e6, jc.b_pa / 1e6, jc.n, jc.c, jc.m]);
    let rule = adaptive_rule(&z, &p, consts, RateTerm::Clamped, &ConvergedOptions::default()).unwrap();
    let nodes = rule.points.len();
    let converged = ZoneFitProblem::weighted(rule.points, &rule.weights, consts, RateTerm::Clamped);
    let full_bounds = bounds.to_bounds().unwrap();
    // Every start searched to convergence (the path before issue 11 item 4), and every start
    // searched with the basin rule (the path before the MLSL filter).
    let all_starts = MultistartOptions { basin_stop: BasinStop::Off, sample_filter: SampleFilter::Off, ..opts };
    let no_filter = MultistartOptions { sample_filter: SampleFilter::Off, ..opts };
    let mut g = c.benchmark_group("identify_50_starts");
    for (name, o) in [("converged_end_to_end", &opts), ("converged_end_to_end_all_starts", &all_starts)] {
        g.bench_function(name, |b| {
            b.iter(|| identify_converged(black_box(&z), &bounds, consts, o, &ConvergedOptions::default()).unwrap())
        });
    }
    for (name, problem) in [("paper_n51".to_string(), &paper), (format!("converged_{nodes}_nodes"), &converged)] {
        g.bench_function(format!("{name}_varpro"), |b| {
            b.iter(|| identify(black_box(problem), &bounds, &opts).unwrap())
        });
        g.bench_function(format!("{name}_varpro_all_starts"), |b| {
            b.iter(|| identify(black_box(problem), &bounds, &all_starts).unwrap())
        });
        g.bench_function(format!("{name}_varpro_basin_rule_only"), |b| {
            b.iter(|| identify(black_box(problem), &bounds, &no_filter).unwrap())
        });
        g.bench_function(format!("{name}_full_lm"), |b| {
            b.iter(|| multistart(black_box(problem), &full_bounds, &opts).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
