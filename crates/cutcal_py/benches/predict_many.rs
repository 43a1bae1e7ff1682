//! Benchmark: the Rust side of `cutcal.predict_many`, the adapter's `predict_many` over 64 AISI 1045
//! conditions (150-250 m/min, t1 0.15 mm, w 1.6 mm, rake -7 deg; Jaspers & Dautzenberg 2002 JC):
//! the time per condition against which `benches/overhead.py` measures the Python call overhead.
//! Run with `RAYON_NUM_THREADS=1 cargo bench -p cutcal_py --bench predict_many` to compare one thread.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_py::predict::{predict_many, resolve, Condition, PredictRequest};
use cutcal_py::types::{jc_from_file, material_from_file};

fn bench(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mf = material_from_file(&root.join("fixtures/materials/aisi1045.toml")).unwrap();
    let jc = jc_from_file(&root.join("fixtures/jc/aisi1045_jaspers2002.toml")).unwrap().jc;
    let (options, work_c) = resolve(&mf, &PredictRequest::default()).unwrap();
    let n = 64;
    let conds: Vec<Condition> = (0..n)
        .map(|i| Condition {
            speed_m_min: 150.0 + 100.0 * i as f64 / (n - 1) as f64,
            uncut_mm: 0.15,
            width_mm: 1.6,
            rake_deg: -7.0,
            edge_radius_um: None,
            flank_wear_mm: None,
        })
        .collect();
    let mut group = c.benchmark_group("predict_many");
    group.sample_size(10);
    group.bench_function("aisi1045_64_conditions", |b| {
        b.iter(|| predict_many(black_box(&mf), black_box(&jc), black_box(&conds), &options, work_c))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
