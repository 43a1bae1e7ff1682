//! Benchmark: joint Oxley identification over the four AISI 1045 cases of Ivester et al. 2000
//! (Lalwani et al. 2009 table), 1 start (the box centre) and 4 starts.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_ident::joint::{identify_oxley, JointOptions};
use cutcal_ident::{JcBounds, JcConstants, MultistartOptions};
use cutcal_model::oxley::{OxleyOptions, Physics};
use cutcal_model::{CuttingTest, Material};

fn aisi1045() -> Material {
    cutcal_model::reference::aisi1045_lalwani2009()
}

fn bench(c: &mut Criterion) {
    let m = aisi1045();
    let tests: Vec<CuttingTest> =
        [(0.15, -7.0, 610.0, 450.0), (0.15, 5.0, 585.0, 385.0), (0.30, -7.0, 1150.0, 600.0), (0.30, 5.0, 920.0, 450.0)]
            .iter()
            .map(|&(t1, rake, fc, ft): &(f64, f64, f64, f64)| {
                CuttingTest::new("x", 200.0 / 60.0, t1 * 1e-3, 1.6e-3, rake.to_radians())
                    .unwrap()
                    .with_forces(Some(fc / 1.6e-3), Some(ft / 1.6e-3))
                    .unwrap()
            })
            .collect();
    // fixtures/materials/aisi1045.toml bounds.
    let bounds =
        JcBounds { a_mpa: [100.0, 1500.0], b_mpa: [50.0, 1500.0], n: [0.05, 0.6], c: [0.001, 0.1], m: [0.6, 1.4] };
    let constants = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 25.0 };
    let opts = JointOptions {
        oxley: OxleyOptions::wide(),
        physics: Physics::baseline(),
        work_temperature_c: 25.0,
        use_chip_thickness: true,
        tool_condition: false,
    };
    let mut g = c.benchmark_group("joint_oxley_aisi1045_4_cases");
    g.sample_size(10);
    for starts in [1usize, 4] {
        g.bench_function(format!("{starts}_starts"), |b| {
            b.iter(|| {
                identify_oxley(
                    black_box(&m),
                    &tests,
                    &bounds,
                    None,
                    constants,
                    &opts,
                    &MultistartOptions::new(starts, 3),
                )
                .unwrap()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
