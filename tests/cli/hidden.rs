//! What a `none` verdict could hide (`cutcal_diagnose::detect`), through the binary. The pair is
//! family b dataset 21 of the concealed benchmark at seed 18181 (`fixtures/README.md`): a hidden
//! heat partition at ENR 2.6, of which the stated nuisance leaves 0.4 noise units, so the verdict
//! is `none`. The report must say that a heat partition of typical size could hide there, with the
//! same interval in its text as in its JSON, and that recording the interface temperature would
//! narrow it.

use super::json as report;

fn numbers_in(s: &str) -> Vec<f64> {
    s.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
        .filter_map(|w| w.trim_matches('-').parse::<f64>().ok())
        .collect()
}

#[test]
fn a_none_verdict_says_a_heat_partition_could_hide_and_how_the_interface_temperature_would_narrow_it() {
    let r = report(&[
        "diagnose",
        "--recordings",
        "fixtures/diagnose/unseen_heat_partition_recordings.csv",
        "--simulation",
        "fixtures/diagnose/unseen_heat_partition_simulation.csv",
        "--json",
    ]);
    assert_eq!(r["verdict"], "none", "{r}");
    let hp = r["mechanisms"].as_array().unwrap().iter().find(|m| m["id"] == "heat_partition").expect("refitted");
    let k_beta = hp["detection_limits"].as_array().unwrap().iter().find(|l| l["param"] == "k_beta").unwrap();
    let above = k_beta["above"].as_f64().expect("detectable above 1 within the range");
    // The lower side lies beyond the modelled range [0.4, 3]: no value there, and the note says why.
    assert!(k_beta["below"].is_null() && k_beta["note"].as_str().unwrap().contains("[0.4, 3]"), "{k_beta}");
    let explanation = r["explanation"].as_str().unwrap();
    assert!(explanation.contains(&format!("heat partition (k_beta up to {above:.3})")), "{explanation}");
    // Every limit in the JSON is a finite number or null with its note.
    for m in r["mechanisms"].as_array().unwrap() {
        for l in m["detection_limits"].as_array().unwrap() {
            for side in ["below", "above"] {
                assert!(l[side].is_null() || l[side].as_f64().is_some_and(f64::is_finite), "{l}");
            }
        }
    }
    // The next test asks for the interface temperature; the interval narrows from the reported
    // [0.4, above] to one inside it.
    let next = r["next_test"].as_str().unwrap();
    assert!(next.contains("t_int_c") && next.contains("heat partition"), "{next}");
    let tail = &next[next.find("narrow from").expect("the intervals")..];
    let v = numbers_in(tail);
    // [0.400 (bound), above] to [0.400 (bound), narrowed] (80 % power ...)
    assert_eq!(&v[..2], &[0.4, (above * 1000.0).round() / 1000.0], "{tail}");
    assert!(v[2] == 0.4 && v[3] > 1.0 && v[3] < v[1], "{tail}");
}
