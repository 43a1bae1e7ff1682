//! Benchmark: one extended Oxley prediction (Lalwani et al. 2009, AISI 1045 case 1), cold start.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
use cutcal_model::{JcParams, Material};

fn aisi1045() -> Material {
    cutcal_model::reference::aisi1045_lalwani2009()
}

fn bench(c: &mut Criterion) {
    let m = aisi1045();
    // Jaspers & Dautzenberg 2002.
    let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap();
    let cond = CuttingConditions::new(200.0 / 60.0, 0.15e-3, 1.6e-3, (-7f64).to_radians(), 25.0).unwrap();
    let opts = OxleyOptions::wide();
    let phys = Physics::baseline();
    c.bench_function("oxley_predict_aisi1045_case1", |b| {
        b.iter(|| oxley::predict(black_box(&m), black_box(&jc), black_box(&cond), &opts, &phys).unwrap())
    });
    let start = oxley::predict(&m, &jc, &cond, &opts, &phys).unwrap();
    c.bench_function("oxley_predict_aisi1045_case1_warm", |b| {
        b.iter(|| oxley::predict_from(black_box(&m), black_box(&jc), &cond, &opts, &phys, Some(&start)).unwrap())
    });
}

/// 125 cold predictions over the users' range of issue 15 (V 100-400 m/min, t1 0.1-0.3 mm, rake
/// -7..+10 deg, 5 x 5 x 5), one after the other: the mean cost per condition away from case 1.
fn bench_range(c: &mut Criterion) {
    let m = aisi1045();
    let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap();
    let lin = |lo: f64, hi: f64, i: usize| lo + (hi - lo) * i as f64 / 4.0;
    let mut conds = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            for k in 0..5 {
                let v = lin(100.0, 400.0, i) / 60.0;
                let t1 = lin(0.1e-3, 0.3e-3, j);
                let rake = lin(-7.0, 10.0, k).to_radians();
                conds.push(CuttingConditions::new(v, t1, 1e-3, rake, 25.0).unwrap());
            }
        }
    }
    let opts = OxleyOptions::wide();
    let phys = Physics::baseline();
    c.bench_function("oxley_predict_aisi1045_users_range_125", |b| {
        b.iter(|| {
            let mut fc = 0.0;
            for cond in &conds {
                fc += oxley::predict(black_box(&m), black_box(&jc), cond, &opts, &phys).unwrap().cutting_force_n_per_m;
            }
            fc
        })
    });
}

criterion_group!(benches, bench, bench_range);
criterion_main!(benches);
