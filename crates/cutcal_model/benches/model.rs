//! Benchmarks of the model core: one enhanced DPZD solve (C38 test 3).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
use cutcal_model::Material;

fn c38() -> Material {
    cutcal_model::reference::c38_table3()
}

fn bench(c: &mut Criterion) {
    let m = c38();
    let state = ShearPlaneState {
        speed_m_per_s: 4.0,
        rake_rad: 0.0,
        shear_angle_rad: (0.075f64 / 0.157).atan(),
        tau_max_pa: 700.9e6,
    };
    let cfg = DpzdConfig::new(1e-4, 4.0, DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }).unwrap();
    c.bench_function("dpzd_enhanced_solve_c38_test3", |b| {
        b.iter(|| dpzd::solve(black_box(&m), black_box(&state), &cfg).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
