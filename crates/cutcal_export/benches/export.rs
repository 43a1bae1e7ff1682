//! Benchmark: rendering every card dialect (Abaqus x3, LS-DYNA, DEFORM-style x2, MatML) for C38 with
//! the paper's Table 5 JC set.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};

#[path = "../tests/it/common.rs"]
#[allow(dead_code)] // the bench uses one of the shared cases
mod common;

fn bench(c: &mut Criterion) {
    let case = common::cases().into_iter().find(|k| k.key == "c38").expect("the C38 case");
    let options = common::options();
    let provenance = common::provenance(&case);
    let input = common::input(&case, &provenance, &options);
    c.bench_function("export_render_all_c38", |b| b.iter(|| cutcal_export::render_all(black_box(&input)).unwrap()));
}

criterion_group!(benches, bench);
criterion_main!(benches);
