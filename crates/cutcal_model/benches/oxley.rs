//! Benchmark: one extended Oxley prediction (Lalwani et al. 2009, AISI 1045 case 1), cold start.
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

criterion_group!(benches, bench);
criterion_main!(benches);
