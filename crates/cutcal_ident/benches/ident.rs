//! Benchmarks: one 50-start enhanced-DPZD identification of C38 test 3 (paper Table 4).
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_ident::{identify_from_zone, JcBounds, JcConstants, MultistartOptions};
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
    let z = dpzd::solve(&m, &state, &cfg).unwrap();
    let bounds = JcBounds { a_mpa: [1.0, 2000.0], b_mpa: [1.0, 2000.0], n: [0.0, 0.25], c: [1e-4, 1.0], m: [0.9, 1.1] };
    let consts = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
    let opts = MultistartOptions::new(50, 1);
    c.bench_function("identify_enhanced_c38_test3_50_starts", |b| {
        b.iter(|| identify_from_zone(black_box(&z), 51, &bounds, consts, &opts).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
