//! Benchmark: a bootstrap of 1000 enhanced-DPZD identifications of C38 test 3 (4 starts per
//! sample, as `cutcal identify --bootstrap` does by default) on rayon's global pool.
//!
//! The target is 10^4 identifications in <= 20 s on 2 cores; this bench times 10^3 per
//! iteration so that criterion's 10 samples stay short; `docs/benchmarks.md` has the 10^4 timing.
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use cutcal_ident::bootstrap::{bootstrap, BootstrapOptions, Measurement, RelativeUncertainty, Sample};
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
    let cfg = DpzdConfig::new(1e-4, 4.0, DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }).unwrap();
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
}

criterion_group!(benches, bench);
criterion_main!(benches);
