//! Runs the Python suite (`tests/python/`, pytest) against the `cutcal` wheel installed in the
//! virtual environment that `.ci/run` prepares (`target/py-venv`, or the interpreter named by
//! `CUTCAL_PYTHON`), with the CLI binary of this workspace (`target/debug/cutcal`, built by
//! `cargo test --workspace`; `CUTCAL_CLI` overrides) as the reference.
//!
//! Without that interpreter the test says so and passes, unless `CI` is `true` or
//! `CUTCAL_REQUIRE_TOOLS=1`, where a missing environment fails.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn required() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true") || std::env::var("CUTCAL_REQUIRE_TOOLS").is_ok_and(|v| v == "1")
}

fn python() -> Option<PathBuf> {
    let p = match std::env::var_os("CUTCAL_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => root().join("target/py-venv/bin/python"),
    };
    p.exists().then_some(p)
}

#[test]
fn python_suite_passes_against_the_cli() {
    let Some(py) = python() else {
        assert!(!required(), "no Python environment for cutcal: run .ci/run's Python block or set CUTCAL_PYTHON");
        eprintln!("skipped: no target/py-venv (build it with the Python block of .ci/run) and no CUTCAL_PYTHON");
        return;
    };
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root().join("target"), PathBuf::from);
    let cli = std::env::var_os("CUTCAL_CLI").map_or_else(|| target.join("debug/cutcal"), PathBuf::from);
    assert!(cli.exists(), "the CLI binary {} is missing: run `cargo build -p cutcal_cli`", cli.display());
    let out = Command::new(&py)
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
        .arg(root().join("crates/cutcal_py/tests/python"))
        .env("CUTCAL_CLI", &cli)
        .env("MPLBACKEND", "Agg")
        .current_dir(root())
        .output()
        .expect("cannot start the Python interpreter");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "pytest failed:\n{text}");
    // A suite that collected nothing has not tested anything.
    assert!(text.contains(" passed"), "pytest ran no test:\n{text}");
    eprintln!("{text}");
}
