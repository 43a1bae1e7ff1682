//! Benchmark: 10^7 samples x 3 channels reduced and analysed (the issue-13 budget is <= 2 s).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use cutcal_signal::synthetic::SyntheticSpec;
use cutcal_signal::{analyse, AnalysisConfig, Reducer, DEFAULT_MAX_BLOCKS};

fn bench(c: &mut Criterion) {
    // 100 kHz x 100 s = 10^7 samples. Samples are generated on the fly (no buffer), so the time
    // includes the generator; the reduction alone is faster.
    let spec = SyntheticSpec {
        rate_hz: 100_000.0,
        duration_s: 100.0,
        entry_s: 5.0,
        exit_s: 95.0,
        ramp_s: 1.0,
        ..SyntheticSpec::plain(1)
    };
    let mut g = c.benchmark_group("signal");
    g.sample_size(10);
    g.bench_function("reduce_and_analyse_1e7x3", |b| {
        b.iter(|| {
            let mut r = Reducer::new(3, DEFAULT_MAX_BLOCKS).unwrap();
            for (t, v) in spec.samples() {
                r.push(t, &v).unwrap();
            }
            black_box(analyse(&r.finish().unwrap(), &AnalysisConfig::default(), None).unwrap())
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
