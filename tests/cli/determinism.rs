//! Determinism: two runs of `cutcal identify` give byte-identical stdout and output files.

use std::fs;

use super::{cutcal, stderr};

/// Runs `identify` writing into `dir`; returns stdout and the bytes of the two output files.
fn run_once(dir: &std::path::Path, extra: &[&str]) -> (Vec<u8>, Vec<u8>, Vec<u8>) {
    let jc = dir.join("jc.toml");
    let fields = dir.join("fields.csv");
    let mut args = vec![
        "identify",
        "--material",
        "fixtures/materials/c38.toml",
        "--tests",
        "fixtures/tests/c38.csv",
        "--json",
        "--out-jc",
        jc.to_str().expect("utf-8 temp path"),
        "--fields-csv",
        fields.to_str().expect("utf-8 temp path"),
    ];
    args.extend_from_slice(extra);
    let o = cutcal(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    (o.stdout, fs::read(&jc).expect("jc written"), fs::read(&fields).expect("fields written"))
}

#[test]
fn two_identify_runs_are_byte_identical() {
    let (a, b) = (tempfile::tempdir().expect("tempdir"), tempfile::tempdir().expect("tempdir"));
    let first = run_once(a.path(), &[]);
    let second = run_once(b.path(), &[]);
    assert!(first.0.len() > 100 && first.1.len() > 50, "outputs unexpectedly short");
    assert!(first.0 == second.0, "--json stdout differs between two runs");
    assert!(first.1 == second.1, "--out-jc files differ between two runs");
    assert!(first.2 == second.2, "--fields-csv files differ between two runs");
    // Nothing but the requested outputs is left in the directory (atomic writes clean up).
    let mut names: Vec<String> =
        fs::read_dir(a.path()).expect("dir").map(|e| e.expect("entry").file_name().to_string_lossy().into()).collect();
    names.sort();
    assert_eq!(names, ["fields.csv", "jc.toml"]);
}
