//! A condition far from the rest (`cutcal_diagnose::far`): the fixture is a null of the concealed
//! benchmark whose recordings jump to another branch of Oxley's closure at test 1 alone. The report
//! names that test, and only it, with robust z values this test recomputes from the report's own
//! residuals against the baseline (median and 1.4826 MAD, floored at the output's noise).

use super::json as report;

const RECORDINGS: &str = "fixtures/diagnose/far_condition_recordings.csv";
const SIMULATION: &str = "fixtures/diagnose/far_condition_simulation.csv";

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

#[test]
fn a_condition_on_another_branch_is_named_as_far_from_the_rest() {
    // The raw data: at test 1 the recorded cutting force is 1.7 times the simulation's; at the
    // other seven, within 0.98-1.14 times.
    let rec = super::column(RECORDINGS, "fc_n_per_mm");
    let sim = super::column(SIMULATION, "fc_n_per_mm");
    for ((id, r), (id_s, s)) in rec.iter().zip(&sim) {
        assert_eq!(id, id_s);
        let ratio = r / s;
        if id == "1" {
            assert!(ratio > 1.6, "{id}: {ratio}");
        } else {
            assert!(ratio > 0.98 && ratio < 1.14, "{id}: {ratio}");
        }
    }

    let r = report(&["diagnose", "--recordings", RECORDINGS, "--simulation", SIMULATION, "--json"]);
    let far = r["far_conditions"].as_array().expect("far conditions reported");
    assert!(!far.is_empty() && far.iter().all(|f| f["test"] == "1"), "{far:?}");
    let names = ["fc", "ft", "tc", "t_int"];
    for f in far {
        let out = f["output"].as_str().unwrap();
        let j = names.iter().position(|n| *n == out).unwrap();
        let lr: Vec<f64> = r["residuals"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|x| x["output"] == out)
            .map(|x| (1.0 + x["before_pct"].as_f64().unwrap() / 100.0).ln())
            .collect();
        let m = median(&lr);
        let mad = median(&lr.iter().map(|x| (x - m).abs()).collect::<Vec<_>>());
        let scale = (1.4826 * mad).max(r["noise_pct"][j].as_f64().unwrap() / 100.0);
        let row = r["residuals"].as_array().unwrap().iter().find(|x| x["output"] == out && x["test"] == "1").unwrap();
        let z = ((1.0 + row["before_pct"].as_f64().unwrap() / 100.0).ln() - m) / scale;
        let got = f["robust_z"].as_f64().unwrap();
        assert!(z > 5.0 && (got - z).abs() < 1e-9, "{out}: {got} against {z}");
    }
    assert!(far.iter().any(|f| f["output"] == "fc"), "{far:?}");
    let text = r["explanation"].as_str().unwrap();
    assert!(text.contains("test 1 departs") && text.contains("repeat it"), "{text}");
}
