//! Complete 2-D decks per cutting test (issue 12 Build 4): a named insta snapshot of one deck with
//! the mesh blocks shortened (the mesh itself is checked by the unit tests of
//! `cutcal_export::deck2d_mesh`), and PyDyna (`ansys-dyna-core` 0.12.1) on decks of tests with
//! different rake and edge radius: parses with no warning, nothing raw, every referenced ID
//! resolves (script `tests/python/dyna_check.py`, which also checks nodes, elements, node and part
//! sets, prescribed motion and the 2-D contact).

use std::process::Command;

use cutcal_export::{render_cut2d, ExportFile};
use cutcal_model::CuttingTest;

use crate::{common, pytools};

/// C38 test 1 (paper Table 2: 180 m/min, 0.075 mm, width 1.95 mm; rake 0 and edge radius 25 um,
/// paper Sec 2).
fn c38_test1() -> CuttingTest {
    let mut t = CuttingTest::new("1", 3.0, 0.075e-3, 1.95e-3, 0.0).unwrap();
    t.edge_radius_m = Some(25e-6);
    t
}

/// AA6082 test 2 (paper Table 2: 240 m/min, 0.2 mm, width 2 mm as fixtures/tests/aa6082.csv); a
/// rake of 6 deg and no stated edge radius (sharp) to exercise another tool geometry.
fn aa6082_test2() -> CuttingTest {
    CuttingTest::new("2", 4.0, 0.2e-3, 2.0e-3, 6f64.to_radians()).unwrap()
}

/// 42CrMo4 test 1 (paper Table 2: 300 m/min, 0.1 mm, 2.12 mm) with a -5 deg rake and a 10 um
/// radius: Coulomb friction (paper Sec 5.1: mu = 0.23).
fn crmo_test1() -> CuttingTest {
    let mut t = CuttingTest::new("1", 5.0, 0.1e-3, 2.12e-3, -5f64.to_radians()).unwrap();
    t.edge_radius_m = Some(10e-6);
    t
}

fn deck(key: &str, test: &CuttingTest) -> ExportFile {
    let case = common::cases().into_iter().find(|c| c.key == key).unwrap();
    let prov = common::provenance(&case);
    let opts = common::options();
    render_cut2d(&common::input(&case, &prov, &opts), test).unwrap()
}

/// The deck with every *NODE / *ELEMENT_SHELL / *SET_NODE_LIST data block cut to its first and
/// last 3 lines.
fn shortened(text: &str) -> String {
    let mut out = Vec::new();
    let mut block: Vec<&str> = Vec::new();
    let flush = |block: &mut Vec<&str>, out: &mut Vec<String>| {
        if block.len() > 8 {
            out.extend(block[..3].iter().map(|s| (*s).to_string()));
            out.push(format!("... {} lines ...", block.len() - 6));
            out.extend(block[block.len() - 3..].iter().map(|s| (*s).to_string()));
        } else {
            out.extend(block.iter().map(|s| (*s).to_string()));
        }
        block.clear();
    };
    for l in text.lines() {
        if l.starts_with('*') || l.starts_with('$') {
            flush(&mut block, &mut out);
            out.push(l.to_string());
        } else {
            block.push(l);
        }
    }
    flush(&mut block, &mut out);
    out.join("\n")
}

#[test]
fn snapshot_of_the_c38_test1_deck() {
    let f = deck("c38", &c38_test1());
    assert_eq!(f.name, "c38_cut2d_1.k");
    insta::assert_snapshot!("lsdyna_cut2d_c38_test1", shortened(&f.contents));
}

#[test]
fn deck_numbers_follow_the_test() {
    let f = deck("c38", &c38_test1());
    let c = &f.contents;
    // Paper Sec 5.1: H = 1e5 kW/m^2K = 1e8 W/m^2K; tonne-mm-s: x1e-3 -> 1e5 N/(s mm K).
    let h_line = c.lines().skip_while(|l| !l.starts_with("*CONTACT_2D")).nth(7).unwrap();
    let h: f64 = h_line[20..30].trim().parse().unwrap();
    assert_eq!(h, 1e5, "{h_line}");
    // Eq 17 asymptotes: FS = m0 k beta, VC = m0 k with k = k(Tc) of the cards (header value).
    let card = c.lines().skip_while(|l| !l.starts_with("*CONTACT_2D")).nth(3).unwrap();
    let fs: f64 = card[40..50].trim().parse().unwrap();
    let vc_line = c.lines().skip_while(|l| !l.starts_with("*CONTACT_2D")).nth(9).unwrap();
    let vc: f64 = vc_line[0..10].trim().parse().unwrap();
    // beta = 0.0045 /MPa (paper Sec 5.1), m0 = 1: FS / VC = beta.
    assert!((fs / vc - 0.0045).abs() < 1e-5 * 0.0045 * 10.0, "fs {fs} vc {vc}");
    // ENDTIM = (start gap + 8 mm) / V; the start gap is 0.5 t1 plus the rounded edge's offset of
    // its lowest point from its left-most point; for 0 rake, 25 um radius: r (1 - sin 7 deg)...
    // checked here only as 8 mm / V < ENDTIM < (8 mm + t1) / V.
    let end_line = c.lines().skip_while(|l| !l.starts_with("*CONTROL_TERMINATION")).nth(2).unwrap();
    let endtim: f64 = end_line[0..10].trim().parse().unwrap();
    assert!(endtim > 8e-3 / 3.0 && endtim < 8.075e-3 / 3.0, "{endtim}");
    // Workpiece elements (part 1) of *ELEMENT_SHELL = the count stated in the header = 2000
    // columns (10 mm / 5 um) x (30 fine rows (2 t1 / 5 um) + the graded rows).
    let wp_el = c
        .lines()
        .skip_while(|l| !l.starts_with("*ELEMENT_SHELL"))
        .filter(|l| !l.starts_with(['$', '*']) && l.get(8..16).is_some_and(|p| p.trim() == "1"))
        .count();
    assert_eq!(wp_el % 2000, 0);
    assert!(wp_el / 2000 > 30, "{wp_el}");
    assert!(c.contains(&format!("$   {wp_el} quads: 5. um columns")), "{wp_el}");

    // Coulomb (42CrMo4, paper Sec 5.1 mu = 0.23): FS = 0.23, VC = 0.
    let f = deck("42crmo4", &crmo_test1());
    let card = f.contents.lines().skip_while(|l| !l.starts_with("*CONTACT_2D")).nth(3).unwrap();
    assert_eq!(card[40..50].trim(), "0.23", "{card}");
}

#[test]
fn a_test_without_tool_or_with_a_bad_id_is_an_error() {
    let case = common::cases().into_iter().find(|c| c.key == "c38").unwrap();
    let prov = common::provenance(&case);
    let opts = common::options();
    let no_tool = cutcal_export::ExportInput { tool: None, ..common::input(&case, &prov, &opts) };
    assert!(render_cut2d(&no_tool, &c38_test1()).is_err());
    let mut t = c38_test1();
    t.id = "1,2".into();
    assert!(render_cut2d(&common::input(&case, &prov, &opts), &t).is_err());
}

#[test]
fn pydyna_parses_decks_of_different_tools_and_every_id_resolves() {
    let Some(py) = pytools::python_with("ansys.dyna.core", "ansys-dyna-core==0.12.1") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut paths = Vec::new();
    for (key, test) in [("c38", c38_test1()), ("aa6082", aa6082_test2()), ("42crmo4", crmo_test1())] {
        let f = deck(key, &test);
        let path = dir.path().join(&f.name);
        std::fs::write(&path, &f.contents).unwrap();
        paths.push(path);
    }
    let run = |paths: &[std::path::PathBuf]| {
        let out = Command::new(&py)
            .arg(pytools::root().join("crates/cutcal_export/tests/python/dyna_check.py"))
            .args(paths)
            .output()
            .expect("cannot start python");
        (
            out.status.success(),
            format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr)),
        )
    };
    let (ok, text) = run(&paths);
    assert!(ok, "PyDyna check failed:\n{text}");
    assert_eq!(text.lines().filter(|l| l.starts_with("ok ")).count(), paths.len(), "{text}");
    eprintln!("{text}");
    // The checker can fail: the same deck with the contact's SURFB naming part set 7 and the last
    // element naming node 99999999 is rejected with both errors.
    let good = std::fs::read_to_string(&paths[0]).unwrap();
    let bad = good.replacen("         1         2        1.        50", "         1         7        1.        50", 1);
    assert_ne!(bad, good);
    let last = bad.lines().rev().find(|l| !l.starts_with('*')).unwrap().to_string();
    let broken_last = format!("{}{:>8}", &last[..last.len() - 8], 99_999_999);
    let bad = bad.replace(&last, &broken_last);
    let bad_path = dir.path().join("broken.k");
    std::fs::write(&bad_path, bad).unwrap();
    let (ok, text) = run(&[bad_path]);
    assert!(!ok && text.contains("SURFB 7") && text.contains("undefined nodes"), "{text}");
}
