//! Property-based fuzzing of every input reader: random bytes, random CSV built from adversarial
//! cells, and the fixtures with random edits (the tests CSV, the material and JC TOML, and the
//! simulation CSV with its check against the recordings). Properties: no panic; an error names the
//! file, a line inside the file and a reason; an accepted input holds only finite, in-range values.
//!
//! `CUTCAL_FUZZ_CASES` scales the case count of every property (default: a bounded smoke run);
//! the documented long run is in `docs/fuzzing.md`.

use std::path::Path;

use proptest::prelude::*;

use super::jc_file::parse_jc;
use super::material_file::parse_material;
use super::simulation_csv::{check_against_recordings, parse_simulation, MAX_SIMULATION_FACTOR};
use super::tests_csv::{parse_tests, OPTIONAL, REQUIRED};
use super::{decode_text, InputError};

/// Cases per property: `CUTCAL_FUZZ_CASES` if set, else `smoke`.
fn cases(smoke: u32) -> u32 {
    std::env::var("CUTCAL_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(smoke)
}

fn config(smoke: u32) -> ProptestConfig {
    ProptestConfig { cases: cases(smoke), max_shrink_iters: 2000, ..ProptestConfig::default() }
}

const CSV_FIXTURE: &str = include_str!("../../../fixtures/tests/c38.csv");
const MATERIAL_FIXTURE: &str = include_str!("../../../fixtures/materials/c38.toml");
const JC_FIXTURE: &str = include_str!("../../../fixtures/jc/c38_table5.toml");
const SIM_FIXTURE: &str = include_str!("../../../fixtures/diagnose/five_conditions_simulation.csv");
const SIM_RECORDINGS: &str = include_str!("../../../fixtures/diagnose/five_conditions_recordings.csv");

/// Cells and tokens that have broken parsers before, or could.
const ADVERSARIAL: &[&str] = &[
    "",
    " ",
    "0",
    "-0",
    "-0.0",
    "1e-320",
    "5e-324",
    "1e308",
    "1e309",
    "1e999",
    "-1e999",
    "NaN",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "infinity",
    "+inf",
    "1_000",
    "0x10",
    "1,5",
    "\"",
    "\"\"",
    "'",
    "#",
    "[",
    "]",
    "{",
    "}",
    "=",
    "[1.0, 2.0, 3.0]",
    "[]",
    "true",
    "\"1460\"",
    "é",
    "\u{feff}",
    "\u{0}",
    "\r",
    "\n",
    "\t",
    "99999999999999999999",
    "-1",
    "1e-3",
    "0.157",
    "224",
    "-45",
    "45",
    "90",
    "1460",
    "-273.15",
    "3",
    "1.5",
];

/// A random cell: adversarial token, a random float in any form, or random printable text.
fn cell() -> impl Strategy<Value = String> {
    prop_oneof![
        proptest::sample::select(ADVERSARIAL).prop_map(str::to_string),
        any::<f64>().prop_map(|v| v.to_string()),
        (-1e4f64..1e4).prop_map(|v| format!("{v}")),
        "[ -~]{0,12}",
    ]
}

/// Column names: the reader's own (so that rows get parsed) and some impostors.
fn columns() -> Vec<&'static str> {
    let mut c: Vec<&'static str> = REQUIRED.iter().chain(OPTIONAL.iter()).copied().collect();
    c.extend(["speed_m_s", ""]);
    c
}

/// A CSV text: mostly the five required columns plus random others, with random rows.
fn csv_text() -> impl Strategy<Value = String> {
    let header = (proptest::collection::vec(proptest::sample::select(columns()), 0..6), any::<bool>()).prop_map(
        |(extra, with_required)| {
            let mut cols: Vec<&str> = if with_required { REQUIRED.to_vec() } else { vec![] };
            cols.extend(extra);
            cols
        },
    );
    header.prop_flat_map(|cols| {
        let width = cols.len().max(1);
        let row = proptest::collection::vec(cell(), width - 1..=width + 1);
        (Just(cols), proptest::collection::vec(row, 0..5)).prop_map(|(cols, rows)| {
            let mut s = cols.join(",");
            s.push('\n');
            for r in rows {
                s.push_str(&r.join(","));
                s.push('\n');
            }
            s
        })
    })
}

/// One random edit of a text: replace a byte range with a token, delete a line, duplicate a line.
#[derive(Debug, Clone)]
enum Edit {
    Replace { at: usize, len: usize, with: String },
    DeleteLine(usize),
    DuplicateLine(usize),
    ReplaceNumber { nth: usize, with: String },
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 0usize..8, cell()).prop_map(|(at, len, with)| Edit::Replace { at, len, with }),
        any::<usize>().prop_map(Edit::DeleteLine),
        any::<usize>().prop_map(Edit::DuplicateLine),
        (any::<usize>(), cell()).prop_map(|(nth, with)| Edit::ReplaceNumber { nth, with }),
    ]
}

/// Applies `edits` to `text` (positions taken modulo the current length, on char boundaries).
fn apply(text: &str, edits: &[Edit]) -> String {
    let mut s = text.to_string();
    for e in edits {
        match e {
            Edit::Replace { at, len, with } => {
                let mut a = at % (s.len() + 1);
                while !s.is_char_boundary(a) {
                    a -= 1;
                }
                let mut b = (a + len).min(s.len());
                while !s.is_char_boundary(b) {
                    b += 1;
                }
                s.replace_range(a..b, with);
            }
            Edit::DeleteLine(i) | Edit::DuplicateLine(i) => {
                let mut lines: Vec<String> = s.lines().map(str::to_string).collect();
                if !lines.is_empty() {
                    let k = i % lines.len();
                    if matches!(e, Edit::DeleteLine(_)) {
                        lines.remove(k);
                    } else {
                        lines.insert(k, lines[k].clone());
                    }
                }
                s = lines.join("\n");
            }
            Edit::ReplaceNumber { nth, with } => {
                let starts: Vec<usize> = s
                    .char_indices()
                    .filter(|(i, c)| {
                        c.is_ascii_digit()
                            && (*i == 0
                                || !(s.as_bytes()[i - 1].is_ascii_alphanumeric()
                                    || b"._".contains(&s.as_bytes()[i - 1])))
                    })
                    .map(|(i, _)| i)
                    .collect();
                if !starts.is_empty() {
                    let a = starts[nth % starts.len()];
                    let b = a + s[a..]
                        .find(|c: char| !(c.is_ascii_alphanumeric() || "+-.".contains(c)))
                        .unwrap_or(s.len() - a);
                    s.replace_range(a..b, with);
                }
            }
        }
    }
    s
}

/// The contract of every error: it names the file, a line inside the text (or none) and a reason.
fn check_error(e: &InputError, path: &Path, text: &str) -> Result<(), TestCaseError> {
    prop_assert_eq!(&e.file, path);
    prop_assert!(!e.reason.trim().is_empty(), "empty reason: {:?}", e);
    if let Some(l) = e.line {
        prop_assert!(l >= 1 && l <= text.lines().count().max(1) + 1, "line {} outside the text: {:?}", l, e);
    }
    let shown = e.to_string();
    prop_assert!(shown.starts_with(&path.display().to_string()), "{}", shown);
    Ok(())
}

fn check_csv(text: &str) -> Result<(), TestCaseError> {
    let path = Path::new("fuzz.csv");
    match parse_tests(path, text) {
        Ok(tests) => {
            prop_assert!(!tests.is_empty());
            for t in &tests {
                prop_assert!(t.speed_m_per_s.is_finite() && t.speed_m_per_s > 0.0);
                prop_assert!(t.uncut_chip_thickness_m > 0.0 && t.uncut_chip_thickness_m <= 5e-3);
                prop_assert!(t.width_m > 0.0 && t.width_m <= 1.0 && t.rake_rad.is_finite());
                let m = t.measured;
                for v in [m.cutting_force_n_per_m, m.feed_force_n_per_m, m.chip_thickness_m].into_iter().flatten() {
                    prop_assert!(v.is_finite() && v > 0.0, "{:?}", t);
                }
            }
        }
        Err(e) => check_error(&e, path, text)?,
    }
    Ok(())
}

fn check_material(text: &str) -> Result<(), TestCaseError> {
    let path = Path::new("fuzz.toml");
    match parse_material(path, text) {
        Ok(m) => {
            let mat = &m.material;
            prop_assert!(mat.melting_c.is_finite() && mat.room_c.is_finite() && mat.melting_c > mat.room_c);
            prop_assert!(mat.validate().is_ok());
            if let Some(b) = m.bounds {
                for [lo, hi] in [b.a_mpa, b.b_mpa, b.n, b.c, b.m] {
                    prop_assert!(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo <= hi);
                }
            }
        }
        Err(e) => check_error(&e, path, text)?,
    }
    Ok(())
}

fn check_jc(text: &str) -> Result<(), TestCaseError> {
    let path = Path::new("fuzz_jc.toml");
    match parse_jc(path, text) {
        Ok(jc) => prop_assert!(jc.validate().is_ok(), "{:?}", jc),
        Err(e) => check_error(&e, path, text)?,
    }
    Ok(())
}

/// A simulation CSV: an accepted one holds finite, in-range values, and its check against the
/// recordings of the same five cuts either passes, with every recorded test paired within
/// [`MAX_SIMULATION_FACTOR`], or names the simulation file.
fn check_simulation(text: &str) -> Result<(), TestCaseError> {
    let path = Path::new("fuzz_sim.csv");
    match parse_simulation(path, text) {
        Ok(sims) => {
            prop_assert!(!sims.is_empty());
            for s in &sims {
                prop_assert!(s.fc_n_per_m > 0.0 && s.ft_n_per_m > 0.0 && s.chip_m > 0.0, "{:?}", s);
                prop_assert!(s.fc_n_per_m.is_finite() && s.ft_n_per_m.is_finite() && s.chip_m.is_finite());
                for t in [s.t_ab_c, s.t_int_c, s.shear_angle_rad].into_iter().flatten() {
                    prop_assert!(t.is_finite(), "{:?}", s);
                }
            }
            let recs = parse_tests(Path::new("recordings.csv"), SIM_RECORDINGS).expect("the fixture's recordings");
            match check_against_recordings(path, &sims, &recs) {
                Ok(()) => {
                    for t in &recs {
                        let s = sims.iter().find(|s| s.id == t.id);
                        prop_assert!(s.is_some(), "test {} unpaired", t.id);
                        let (s, m) = (s.unwrap(), t.measured);
                        let pairs = [
                            (s.fc_n_per_m, m.cutting_force_n_per_m),
                            (s.ft_n_per_m, m.feed_force_n_per_m),
                            (s.chip_m, m.chip_thickness_m),
                        ];
                        for (a, b) in pairs {
                            if let Some(b) = b {
                                prop_assert!((a / b).max(b / a) <= MAX_SIMULATION_FACTOR);
                            }
                        }
                    }
                }
                Err(e) => check_error(&e, path, text)?,
            }
        }
        Err(e) => check_error(&e, path, text)?,
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn random_bytes_never_panic_any_reader(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        let path = Path::new("bytes.bin");
        match decode_text(path, bytes.clone()) {
            Ok(text) => {
                check_csv(&text)?;
                check_material(&text)?;
                check_jc(&text)?;
                check_simulation(&text)?;
            }
            Err(e) => check_error(&e, path, &String::from_utf8_lossy(&bytes))?,
        }
    }

    #[test]
    fn random_csv_never_panics(text in csv_text()) {
        check_csv(&text)?;
    }

    #[test]
    fn edited_csv_fixture_never_panics(edits in proptest::collection::vec(edit(), 1..4)) {
        check_csv(&apply(CSV_FIXTURE, &edits))?;
    }

    #[test]
    fn edited_material_fixture_never_panics(edits in proptest::collection::vec(edit(), 1..4)) {
        check_material(&apply(MATERIAL_FIXTURE, &edits))?;
    }

    #[test]
    fn edited_jc_fixture_never_panics(edits in proptest::collection::vec(edit(), 1..4)) {
        check_jc(&apply(JC_FIXTURE, &edits))?;
    }

    #[test]
    fn edited_simulation_fixture_never_panics(edits in proptest::collection::vec(edit(), 1..4)) {
        check_simulation(&apply(SIM_FIXTURE, &edits))?;
    }
}

#[test]
fn the_edit_helper_reaches_numbers_and_lines() {
    // A fuzzer whose mutations never land would pass vacuously: check that they do.
    let s = apply("a = 12.5\nb = 3\n", &[Edit::ReplaceNumber { nth: 1, with: "nan".into() }]);
    assert_eq!(s, "a = 12.5\nb = nan\n");
    let s = apply("x\ny\n", &[Edit::DuplicateLine(1)]);
    assert_eq!(s, "x\ny\ny");
    assert!(
        parse_jc(Path::new("j"), &apply(JC_FIXTURE, &[Edit::ReplaceNumber { nth: 3, with: "nan".into() }])).is_err()
    );
}
