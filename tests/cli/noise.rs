//! A stated interface-temperature uncertainty (`t_int_sd_c`, K per row) sets the noise the
//! diagnosis weighs the interface temperature by, as the force and chip sd columns do for theirs
//! (`cutcal_diagnose::noise`). Without it the report says the 10 % default was assumed, and a
//! verdict that claims nothing says how to state a better one.

use super::json as report;

const RECORDINGS: &str = "fixtures/diagnose/held_out_only_recordings.csv";
const SIMULATION: &str = "fixtures/diagnose/held_out_only_simulation.csv";

#[test]
fn a_stated_interface_temperature_sd_is_the_noise_the_diagnosis_uses() {
    let text = std::fs::read_to_string(super::root().join(RECORDINGS)).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "t_int_c").expect("the fixture records t_int_c");
    // Each row states 4 % of its rise above 20 degC, rounded to 0.1 K; the expected noise is the
    // median of the stated relative values (the upper middle one for an even count).
    let mut rows = vec![format!("{},t_int_sd_c", header.join(","))];
    let mut relative = Vec::new();
    for line in lines {
        let t: f64 = line.split(',').nth(col).unwrap().parse().unwrap();
        let sd = (0.04 * (t - 20.0) * 10.0).round() / 10.0;
        relative.push(sd / (t - 20.0));
        rows.push(format!("{line},{sd:.1}"));
    }
    relative.sort_by(f64::total_cmp);
    let expected_pct = 100.0 * relative[relative.len() / 2];
    let dir = tempfile::tempdir().unwrap();
    let stated = dir.path().join("recordings.csv");
    std::fs::write(&stated, rows.join("\n") + "\n").unwrap();

    let run =
        |recordings: &str| report(&["diagnose", "--recordings", recordings, "--simulation", SIMULATION, "--json"]);
    let with = run(stated.to_str().unwrap());
    let pct = with["noise_pct"][3].as_f64().unwrap();
    assert!((pct - expected_pct).abs() < 1e-9, "{pct} against {expected_pct}");
    let source = with["noise_source"][3].as_str().unwrap();
    assert!(source.starts_with("per-row sd columns"), "{source}");
    // The fixture's verdict claims nothing either way; only with the scatter assumed does the
    // explanation ask for it.
    assert_ne!(with["verdict"], "missing_physics", "{with}");
    assert!(!with["explanation"].as_str().unwrap().contains("t_int_sd_c"), "{with}");

    let without = run(RECORDINGS);
    let source = without["noise_source"][3].as_str().unwrap();
    assert!(!source.starts_with("per-row") && source.contains("10 %"), "{source}");
    assert_ne!(without["verdict"], "missing_physics", "{without}");
    let explanation = without["explanation"].as_str().unwrap();
    assert!(explanation.contains("assumed 10 % scatter") && explanation.contains("t_int_sd_c"), "{explanation}");
}
