//! A stated interface-temperature uncertainty (`t_int_sd_c`, K per row) sets the noise the
//! diagnosis weighs the interface temperature by, as the force and chip sd columns do for theirs
//! (`cutcal_diagnose::noise`). Without it, and with too few conditions (the fixture has 5) to read it
//! from neighbouring ones, the report says the 10 % default was assumed, and a verdict that claims
//! nothing says how to state a better one.

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

/// Without repeats or a stated sd, the interface temperature's scatter is read from neighbouring
/// conditions (`cutcal_diagnose::noise`, Munk et al. 2005). The fixture (8 conditions, a far
/// condition at test 1) gives it; the test computes it again from the two CSVs: `r = ln((T_rec -
/// 20) / (T_sim - 20))` per test, each test's nearest neighbour in (ln V, ln h, rake) scaled by
/// their ranges (the first on a tie), and the root of the mean of `(r_i - r_j)^2 / 2` over the
/// distinct pairs. It is used only above the 10 % default (the default also stands for the shadow's
/// thermal form error, which a difference estimate cannot see); the far condition makes it large
/// (14 %), as a difference estimate that is biased upwards by what is not smooth should be.
#[test]
fn the_interface_temperature_scatter_is_read_from_neighbouring_conditions() {
    let rec = |col: &str| super::column("fixtures/diagnose/far_condition_recordings.csv", col);
    let sim = super::column("fixtures/diagnose/far_condition_simulation.csv", "t_int_c");
    let (v, h, rake, t_rec) = (rec("speed_m_min"), rec("uncut_mm"), rec("rake_deg"), rec("t_int_c"));
    let pts: Vec<([f64; 3], f64)> = (0..t_rec.len())
        .map(|i| {
            let t_sim = sim.iter().find(|(id, _)| *id == t_rec[i].0).unwrap().1;
            let x = [v[i].1.ln(), h[i].1.ln(), rake[i].1.to_radians()];
            (x, ((t_rec[i].1 - 20.0) / (t_sim - 20.0)).ln())
        })
        .collect();
    let range: Vec<f64> = (0..3)
        .map(|k| {
            let v: Vec<f64> = pts.iter().map(|p| p.0[k]).collect();
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max) - v.iter().copied().fold(f64::INFINITY, f64::min)
        })
        .collect();
    let dist = |a: &[f64; 3], b: &[f64; 3]| -> f64 {
        (0..3).filter(|&k| range[k] > 0.0).map(|k| ((a[k] - b[k]) / range[k]).powi(2)).sum()
    };
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for i in 0..pts.len() {
        let mut best = None::<(usize, f64)>;
        for j in (0..pts.len()).filter(|&j| j != i) {
            let d = dist(&pts[i].0, &pts[j].0);
            if best.is_none_or(|(_, b)| d < b) {
                best = Some((j, d));
            }
        }
        let j = best.unwrap().0;
        if !pairs.contains(&(i.min(j), i.max(j))) {
            pairs.push((i.min(j), i.max(j)));
        }
    }
    let mean: f64 = pairs.iter().map(|&(i, j)| 0.5 * (pts[i].1 - pts[j].1).powi(2)).sum::<f64>() / pairs.len() as f64;
    let expected_pct = 100.0 * mean.sqrt();
    assert!(expected_pct > 10.0, "the far condition should inflate the estimate above the default: {expected_pct}");

    let out = report(&[
        "diagnose",
        "--recordings",
        "fixtures/diagnose/far_condition_recordings.csv",
        "--simulation",
        "fixtures/diagnose/far_condition_simulation.csv",
        "--json",
    ]);
    let pct = out["noise_pct"][3].as_f64().unwrap();
    assert!((pct - expected_pct).abs() < 1e-9, "{pct} against {expected_pct}");
    let source = out["noise_source"][3].as_str().unwrap();
    let df = pts.len() / 2;
    assert!(
        source.starts_with("neighbouring conditions") && source.contains(&format!("{} pairs, df = {df}", pairs.len())),
        "{source}"
    );
    // Not assumed, so the explanation does not ask for the column.
    assert!(!out["explanation"].as_str().unwrap().contains("t_int_sd_c"), "{out}");
}
