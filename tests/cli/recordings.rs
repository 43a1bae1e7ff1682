//! `cutcal recordings` end to end on synthetic signals with known truth (generator:
//! `cutcal_signal::synthetic`, labelled synthetic): rows written back with forces, sd and flags.

use std::fmt::Write as _;
use std::fs;

use cutcal_io::tests_csv::load_tests;
use cutcal_signal::synthetic::SyntheticSpec;

use super::cutcal;

#[test]
fn signals_become_rows_with_sd_and_flags() {
    let dir = tempfile::tempdir().unwrap();
    let sig = dir.path().join("signals");
    fs::create_dir(&sig).unwrap();
    // Test 1 plain; test 2 with an 8 % wear drift; test 3 with a 45 Hz, 8 % BUE oscillation.
    let specs = [
        SyntheticSpec::plain(1),
        SyntheticSpec { drift_relative: 0.08, ..SyntheticSpec::plain(2) },
        SyntheticSpec { oscillation: Some((45.0, 0.08)), ..SyntheticSpec::plain(3) },
    ];
    for (i, s) in specs.iter().enumerate() {
        let mut text = String::from("# synthetic (cutcal_signal::synthetic)\ntime_s,fc_n,ft_n,fp_n\n");
        for (t, v) in s.samples() {
            writeln!(text, "{t:.6},{:.4},{:.4},{:.4}", v[0], v[1], v[2]).unwrap();
        }
        fs::write(sig.join(format!("{}.csv", i + 1)), text).unwrap();
    }
    let tests = dir.path().join("t.csv");
    fs::write(
        &tests,
        "test,speed_m_min,uncut_mm,width_mm,rake_deg\n1,200,0.1,2,0\n2,200,0.1,2,0\n3,200,0.1,2,0\n4,300,0.1,2,0\n",
    )
    .unwrap();
    let out = dir.path().join("t_measured.csv");
    let o = cutcal(&[
        "recordings",
        "--tests",
        tests.to_str().unwrap(),
        "--signals",
        sig.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = load_tests(&out).unwrap();
    // Test 1: Fc 500 N over 2 mm = 250 N/mm = 250e3 N/m; sd 10 N / 2 mm = 5 N/mm.
    let fc = rows[0].measured.cutting_force_n_per_m.unwrap();
    assert!((fc / 250e3 - 1.0).abs() < 0.005, "{fc}");
    let sd = rows[0].measured.sd.cutting_force_n_per_m.unwrap();
    assert!((sd / 5e3 - 1.0).abs() < 0.1, "{sd}");
    let text = fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert!(lines[0].ends_with("wear_flag,bue_flag"), "{}", lines[0]);
    assert!(lines[1].ends_with(",0,0") && lines[2].ends_with(",1,0") && lines[3].ends_with(",0,1"), "{text}");
    // Test 4 has no signal: its row is kept unmeasured.
    assert!(rows[3].measured.cutting_force_n_per_m.is_none());
    assert!(out.with_extension("json").is_file());
}
