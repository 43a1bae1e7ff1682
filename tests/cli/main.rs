//! End-to-end tests of the `cutcal` binary: outputs, exit codes and located error messages.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

mod bootstrap;
mod card_law;
mod catalogue;
mod channel_gain;
mod determinism;
mod far;
mod hidden;
mod identify;
mod noise;
mod one_condition;
mod pipe;
mod predict;
mod real_cases;
mod recordings;
mod sharp_edge;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().expect("repository root")
}

/// Runs `cutcal` with `args` from the repository root.
pub fn cutcal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cutcal")).args(args).current_dir(root()).output().expect("run cutcal")
}

/// Runs `cutcal` with `args`, asserts success and parses its stdout as one JSON value.
pub fn json(args: &[&str]) -> serde_json::Value {
    let o = cutcal(args);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("one JSON value")
}

/// The `col` column of a CSV fixture, by test id.
pub fn column(path: &str, col: &str) -> Vec<(String, f64)> {
    let text = std::fs::read_to_string(root().join(path)).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let c = header.iter().position(|h| *h == col).unwrap();
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].to_string(), f[c].parse().unwrap())
        })
        .collect()
}

/// Stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}
