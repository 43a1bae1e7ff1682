//! `cutcal predict` on the paper's C38 conditions with the Table 5 JC set: Lalwani's search
//! ranges hold no solution (C0 must exceed 10), the default wide ranges do.

use super::json;

fn predict(extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "predict",
        "--material",
        "fixtures/materials/c38.toml",
        "--jc",
        "fixtures/jc/c38_table5.toml",
        "--tests",
        "fixtures/tests/c38.csv",
        "--json",
    ];
    args.extend_from_slice(extra);
    json(&args)
}

#[test]
fn c38_table5_needs_c0_beyond_lalwanis_range() {
    // Issue 3: an independent implementation finds no solution for C38 with Table 5 unless C0 may
    // exceed Lalwani's [2, 10] (it needs C0 ~ 10.5-13.8).
    let narrow = predict(&["--lalwani-ranges"]);
    for row in narrow["rows"].as_array().unwrap() {
        let e = row["error"].as_str().unwrap_or_default();
        assert!(e.contains("no solution in [2, 10]"), "test {}: {e}", row["test"]);
    }
    let wide = predict(&[]);
    for row in wide["rows"].as_array().unwrap() {
        let p = &row["prediction"];
        let c0 = p["c0"].as_f64().unwrap_or_else(|| panic!("test {} failed: {}", row["test"], row["error"]));
        assert!(c0 > 10.0 && c0 < 20.0, "test {}: C0 = {c0}", row["test"]);
        assert_eq!(p["flags"]["c0_at_bound"], serde_json::json!(false));
    }
    // Test 3 is measured (paper Table 6): the chip thickness 0.157 mm is predicted within 10 %.
    let t3 = &wide["rows"].as_array().unwrap()[2];
    assert!(t3["tc_error_pct"].as_f64().unwrap().abs() < 10.0, "{}", t3["tc_error_pct"]);
}
