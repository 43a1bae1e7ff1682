//! Reduce and analyse 10^7 samples x 3 channels streamed from the synthetic generator; run under
//! `/usr/bin/time -v` to read the peak memory (the issue-13 budget: <= 2 s, <= 100 MB).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::time::Instant;

use cutcal_signal::synthetic::SyntheticSpec;
use cutcal_signal::{analyse, AnalysisConfig, Reducer, DEFAULT_MAX_BLOCKS};

fn main() {
    let spec = SyntheticSpec {
        rate_hz: 100_000.0,
        duration_s: 100.0,
        entry_s: 5.0,
        exit_s: 95.0,
        ramp_s: 1.0,
        ..SyntheticSpec::plain(1)
    };
    // The generator fills a 65536-sample chunk (not timed, like a file reader would); the reduction
    // and the analysis are timed.
    let total = Instant::now();
    let mut reduce = std::time::Duration::ZERO;
    let mut r = Reducer::new(3, DEFAULT_MAX_BLOCKS).expect("valid reducer");
    let mut chunk: Vec<(f64, [f64; 3])> = Vec::with_capacity(1 << 16);
    let mut samples = spec.samples();
    loop {
        chunk.clear();
        chunk.extend(samples.by_ref().take(1 << 16));
        if chunk.is_empty() {
            break;
        }
        let t = Instant::now();
        for (ts, v) in &chunk {
            r.push(*ts, v).expect("increasing time");
        }
        reduce += t.elapsed();
    }
    let t = Instant::now();
    let a = analyse(&r.finish().expect("long record"), &AnalysisConfig::default(), None).expect("a cut");
    let analysis = t.elapsed();
    let secs = (reduce + analysis).as_secs_f64();
    let all = total.elapsed().as_secs_f64();
    #[allow(clippy::print_stdout)] // an example reports on stdout
    {
        println!(
            "samples {} x 3 channels, window {:.3}..{:.3} s, Fc {:.2} N",
            spec.len(),
            a.t0_s,
            a.t1_s,
            a.channels[0].mean
        );
        println!(
            "reduction + analysis {secs:.3} s (analysis alone {:.3} s); with the generator {all:.3} s",
            analysis.as_secs_f64()
        );
    }
}
