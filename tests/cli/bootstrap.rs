//! `cutcal identify --bootstrap N`: the spread report, its independence of the thread count, and
//! rejected options.

use std::process::Command;

use super::{cutcal, root, stderr};

const BASE: [&str; 5] = ["identify", "--material", "fixtures/materials/c38.toml", "--tests", "fixtures/tests/c38.csv"];

/// Runs identify with `extra` arguments on a rayon pool of `threads`; returns stdout.
fn run_with_threads(threads: usize, extra: &[&str]) -> Vec<u8> {
    let o = Command::new(env!("CARGO_BIN_EXE_cutcal"))
        .args(BASE)
        .args(extra)
        .env("RAYON_NUM_THREADS", threads.to_string())
        .current_dir(root())
        .output()
        .expect("run cutcal");
    assert!(o.status.success(), "{}", stderr(&o));
    o.stdout
}

#[test]
fn bootstrap_reports_spread_and_is_independent_of_threads() {
    let args = ["--json", "--bootstrap", "64", "--seed", "3"];
    let one = run_with_threads(1, &args);
    let two = run_with_threads(2, &args);
    assert!(one == two, "bootstrap output differs between 1 and 2 threads");
    let v: serde_json::Value = serde_json::from_slice(&one).expect("one JSON object");
    let b = &v["bootstrap"];
    assert_eq!(b["samples"], 64);
    assert_eq!(b["seed"], 3);
    let a = &b["parameters"][0];
    assert_eq!(a["name"], "a_mpa");
    let (mean, std) = (a["mean"].as_f64().unwrap(), a["std"].as_f64().unwrap());
    let nominal = v["jc"]["a_mpa"].as_f64().unwrap();
    // 3 % forces and 5 % chip move A by about 2 % (about 12 MPa, measured with 10^4 samples, see
    // docs/benchmarks.md); the mean of 64 samples lies within 1 % of the nominal fit.
    assert!(std > 3.0 && std < 30.0, "std of A {std}");
    assert!((mean - nominal).abs() < 0.01 * nominal, "mean {mean} nominal {nominal}");
    assert!(a["q025"].as_f64().unwrap() < mean && mean < a["q975"].as_f64().unwrap());
    // n and m sit at their bounds in every sample (paper Table 4: n = 0.25, m = 1.1): no correlation.
    assert_eq!(b["correlation"][2][0], serde_json::Value::Null);
    // Without --bootstrap the JSON has no bootstrap key.
    let plain: serde_json::Value = serde_json::from_slice(&run_with_threads(2, &["--json"])).expect("JSON");
    assert!(plain.get("bootstrap").is_none());
}

#[test]
fn bad_bootstrap_options_fail_and_write_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let jc = dir.path().join("jc.toml");
    let jc_arg = jc.to_str().expect("utf-8 path");
    let mut args = BASE.to_vec();
    args.extend(["--bootstrap", "10", "--force-uncertainty=-0.03", "--out-jc", jc_arg]);
    let o = cutcal(&args);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("relative force uncertainty must satisfy 0 <= u <= 0.25, got -0.03"), "{e}");
    assert!(!jc.exists(), "a failed run must leave no output file");
    let mut args = BASE.to_vec();
    args.extend(["--bootstrap", "1"]);
    let e = stderr(&cutcal(&args));
    assert!(e.contains("bootstrap samples must be in 2..=1000000, got 1"), "{e}");
}
