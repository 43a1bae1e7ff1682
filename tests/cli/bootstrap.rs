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
    let args = ["--json", "--bootstrap", "64", "--seed", "3", "--noise-only"];
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
    // n and m sit at their bounds in every sample (paper Table 4: n = 0.25, m = 1.1): no correlation,
    // and the samples at a bound are counted as such; A, B and C are free in every sample.
    assert_eq!(b["correlation"][2][0], serde_json::Value::Null);
    let at = &b["at_bounds"];
    for (k, name) in ["a_mpa", "b_mpa", "n", "c", "m"].iter().enumerate() {
        assert_eq!(at[k]["name"], *name);
        let upper = if k == 2 || k == 4 { 64 } else { 0 };
        assert_eq!((at[k]["at_lower"].as_u64(), at[k]["at_upper"].as_u64()), (Some(0), Some(upper)), "{name}");
    }
    assert_eq!(at[2]["bounds"][1], 0.25);
    assert_eq!(b["choices"], serde_json::Value::Null);
    // By default the unstated choices h (x 1/2..2) and r (+- 1) vary too: the spread of A grows
    // (C38 test 3 with 2000 samples: std 17 MPa from the noise alone, 56 MPa with the choices).
    let with: serde_json::Value =
        serde_json::from_slice(&run_with_threads(2, &["--json", "--bootstrap", "64", "--seed", "3"])).expect("JSON");
    let wb = &with["bootstrap"];
    assert_eq!(wb["choices"]["h_factor"][1], 2.0);
    assert_eq!(wb["choices"]["r_half_width"], 1.0);
    let std_with = wb["parameters"][0]["std"].as_f64().unwrap();
    assert!(std_with > 1.5 * std, "std of A with choices {std_with}, noise only {std}");
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

#[test]
fn bootstrap_takes_the_rows_own_uncertainty_and_says_so() {
    // Test 3 (paper Table 6: 224, 186 N/mm, 0.157 mm) with sd columns of 2 % (Fc: 4.48 N/mm),
    // 4 % (Ft: 7.44 N/mm) and 3 % (chip: 0.00471 mm): the resampling uses 4 % on the forces (the
    // larger channel) and 3 % on the chip, and the report names the row as the source. A flag wins.
    let dir = tempfile::tempdir().expect("tempdir");
    let csv = dir.path().join("t.csv");
    std::fs::write(
        &csv,
        "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,chip_mm,fc_sd_n_per_mm,ft_sd_n_per_mm,chip_sd_mm\n\
         3,240,0.075,1.95,0,224,186,0.157,4.48,7.44,0.00471\n",
    )
    .expect("write csv");
    let run = |extra: &[&str]| {
        let mut args = vec!["identify", "--material", "fixtures/materials/c38.toml", "--tests", csv.to_str().unwrap()];
        args.extend(["--json", "--bootstrap", "8", "--bootstrap-starts", "2"]);
        args.extend(extra);
        let o = cutcal(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
        v["bootstrap"].clone()
    };
    let b = run(&[]);
    assert!((b["uncertainty"]["force"].as_f64().unwrap() - 0.04).abs() < 1e-9, "{b}");
    assert!((b["uncertainty"]["chip_thickness"].as_f64().unwrap() - 0.03).abs() < 1e-9, "{b}");
    let src = b["source"].as_str().unwrap();
    assert!(src.contains("row's sd columns (Fc 2.00 %, Ft 4.00 %"), "{src}");
    let b = run(&["--force-uncertainty", "0.01"]);
    assert!((b["uncertainty"]["force"].as_f64().unwrap() - 0.01).abs() < 1e-12, "{b}");
    assert!(b["source"].as_str().unwrap().contains("forces: --force-uncertainty"), "{b}");
}
