//! A real solver runs the tabular Abaqus card: CalculiX 2.20 (`ccx`, Debian `calculix-ccx`),
//! two unconnected single C3D8 elements in uniaxial tension at two tabulated temperatures
//! (fe-cards.md §5.2 test 1). The flow stress the solver produces at every tabulated plastic
//! strain it passes must equal the JC law (paper Eq 16, evaluated independently with
//! `JcParams::flow_stress`) within 0.5 %; any `*WARNING` or `*ERROR` in CalculiX's output fails.
//!
//! The native `HARDENING=JOHNSON COOK` card is not run: CalculiX 2.20 silently reads it as
//! perfect plasticity (fe-cards.md §2.3); it is covered by snapshots and `roundtrip.rs`.

use std::collections::BTreeMap;
use std::process::Command;

use cutcal_export::{render, Dialect};

use crate::common;

/// One `*PLASTIC` block of the tabular card: temperature (K) and (stress MPa, plastic strain).
struct Block {
    temperature_k: f64,
    points: Vec<(f64, f64)>,
}

/// Our own parse of the tabular card's `*PLASTIC` data lines "stress, strain, temperature".
fn plastic_blocks(card: &str) -> Vec<Block> {
    let mut lines = card.lines().skip_while(|l| !l.eq_ignore_ascii_case("*PLASTIC")).skip(1);
    let mut blocks: Vec<Block> = Vec::new();
    for l in lines.by_ref() {
        if l.starts_with('*') {
            break;
        }
        let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
        assert_eq!(v.len(), 3, "{l}");
        match blocks.last_mut() {
            Some(b) if (b.temperature_k - v[2]).abs() < 1e-9 => b.points.push((v[0], v[1])),
            _ => blocks.push(Block { temperature_k: v[2], points: vec![(v[0], v[1])] }),
        }
    }
    blocks
}

fn deck(material_card: &str, material: &str, t1: f64, t2: f64) -> String {
    let mut s = String::from("*HEADING\ncutcal uniaxial check of the tabular card\n*NODE\n");
    let corners = [
        (0., 0., 0.),
        (1., 0., 0.),
        (1., 1., 0.),
        (0., 1., 0.),
        (0., 0., 1.),
        (1., 0., 1.),
        (1., 1., 1.),
        (0., 1., 1.),
    ];
    for (e, dx) in [(0usize, 0.0), (10, 3.0)] {
        for (i, (x, y, z)) in corners.iter().enumerate() {
            s.push_str(&format!("{}, {}, {}, {}\n", e + i + 1, x + dx, y, z));
        }
    }
    s.push_str("*ELEMENT, TYPE=C3D8, ELSET=E1\n1, 1, 2, 3, 4, 5, 6, 7, 8\n");
    s.push_str("*ELEMENT, TYPE=C3D8, ELSET=E2\n2, 11, 12, 13, 14, 15, 16, 17, 18\n");
    s.push_str("*ELSET, ELSET=EALL\nE1, E2\n");
    s.push_str("*NSET, NSET=BOT\n1, 2, 3, 4, 11, 12, 13, 14\n*NSET, NSET=TOP\n5, 6, 7, 8, 15, 16, 17, 18\n");
    s.push_str("*NSET, NSET=X0\n1, 4, 5, 8, 11, 14, 15, 18\n*NSET, NSET=Y0\n1, 2, 5, 6, 11, 12, 15, 16\n");
    s.push_str("*NSET, NSET=N1\n1, 2, 3, 4, 5, 6, 7, 8\n*NSET, NSET=N2\n11, 12, 13, 14, 15, 16, 17, 18\n");
    s.push_str(material_card);
    s.push_str(&format!("*SOLID SECTION, ELSET=EALL, MATERIAL={material}\n"));
    s.push_str("*BOUNDARY\nBOT, 3\nX0, 1\nY0, 2\n");
    s.push_str(&format!("*INITIAL CONDITIONS, TYPE=TEMPERATURE\nN1, {t1}\nN2, {t2}\n"));
    // Top face displaced to a logarithmic strain of 0.4 in 200 equal increments.
    s.push_str("*STEP, NLGEOM, INC=1000\n*STATIC, DIRECT\n0.005, 1.\n");
    s.push_str(&format!("*BOUNDARY\nTOP, 3, 3, {}\n", 0.4f64.exp() - 1.0));
    s.push_str(&format!("*TEMPERATURE\nN1, {t1}\nN2, {t2}\n"));
    s.push_str("*EL PRINT, ELSET=E1\nS, PEEQ\n*EL PRINT, ELSET=E2\nS, PEEQ\n*END STEP\n");
    s
}

/// Parses the `.dat` file: (set, time) -> (S33 mean over integration points, PEEQ mean).
fn parse_dat(text: &str) -> BTreeMap<String, Vec<(f64, f64, f64)>> {
    let mut stress: BTreeMap<(String, u64), Vec<f64>> = BTreeMap::new();
    let mut peeq: BTreeMap<(String, u64), Vec<f64>> = BTreeMap::new();
    let mut current: Option<(bool, String, u64)> = None;
    for line in text.lines() {
        if let Some(pos) = line.find("for set") {
            let rest: Vec<&str> = line[pos + 7..].split_whitespace().collect();
            // "for set E1 and time  0.5000000E-02"
            let set = rest[0].to_string();
            let time: f64 = rest[3].parse().unwrap();
            let is_stress = line.trim_start().starts_with("stresses");
            let is_peeq = line.trim_start().starts_with("equivalent plastic strain");
            current = (is_stress || is_peeq).then(|| (is_stress, set, time.to_bits()));
            continue;
        }
        let Some((is_stress, set, t)) = &current else { continue };
        let v: Vec<f64> = match line.split_whitespace().map(str::parse).collect::<Result<Vec<f64>, _>>() {
            Ok(v) if !v.is_empty() => v,
            _ => continue,
        };
        let key = (set.clone(), *t);
        if *is_stress {
            stress.entry(key).or_default().push(v[4]);
        } else {
            peeq.entry(key).or_default().push(v[2]);
        }
    }
    let mut out: BTreeMap<String, Vec<(f64, f64, f64)>> = BTreeMap::new();
    for ((set, t), s) in &stress {
        let p = &peeq[&(set.clone(), *t)];
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        out.entry(set.clone()).or_default().push((f64::from_bits(*t), mean(s), mean(p)));
    }
    for v in out.values_mut() {
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    out
}

#[test]
fn calculix_reproduces_jc_flow_stress_from_the_tabular_card() {
    let opts = common::options();
    for case in common::cases().into_iter().filter(|c| c.key != "42crmo4") {
        let prov = common::provenance(&case);
        let files = render(Dialect::Abaqus, &common::input(&case, &prov, &opts)).unwrap();
        let card = &files.iter().find(|f| f.name.ends_with("_abaqus_tabular.inp")).unwrap().contents;
        let material = format!("WP_{}", case.workpiece.name.to_ascii_uppercase());
        let blocks = plastic_blocks(card);
        assert!(blocks.len() >= 2, "{}: {} temperature blocks", case.key, blocks.len());
        let (b1, b2) = (&blocks[0], &blocks[blocks.len() / 2]);
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("uni.inp"), deck(card, &material, b1.temperature_k, b2.temperature_k)).unwrap();
        let out = Command::new("ccx")
            .args(["-i", "uni"])
            .current_dir(dir.path())
            .env("OMP_NUM_THREADS", "1")
            .output()
            .expect("CalculiX `ccx` not found: install it with `apt-get install -y calculix-ccx`");
        let log = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        assert!(out.status.success(), "{}: ccx failed:\n{log}", case.key);
        assert!(!log.contains("*WARNING") && !log.contains("*ERROR"), "{}: ccx reported:\n{log}", case.key);
        let results = parse_dat(&std::fs::read_to_string(dir.path().join("uni.dat")).unwrap());
        for (set, block) in [("E1", b1), ("E2", b2)] {
            let history = &results[set];
            assert!(history.len() >= 150, "{set}: {} increments", history.len());
            let temperature_c = block.temperature_k - 273.15;
            let mut checked = 0;
            for seg in block.points.windows(2) {
                let ((_, e0), (_, e1)) = (seg[0], seg[1]);
                let inside: Vec<&(f64, f64, f64)> =
                    history.iter().filter(|(_, _, p)| *p > e0 + 1e-6 && *p < e1 - 1e-6).collect();
                if inside.len() < 2 {
                    continue;
                }
                // The solver's flow curve is linear on each table segment: the line through its
                // first and last points there gives its flow stress at the tabulated strains.
                let (first, last) = (inside[0], inside[inside.len() - 1]);
                let slope = (last.1 - first.1) / (last.2 - first.2);
                for e in [e0, e1] {
                    let solver = first.1 + slope * (e - first.2);
                    let jc = case.jc.flow_stress(e, opts.tabular_strain_rate_per_s, temperature_c) * 1e-6;
                    let rel = (solver - jc).abs() / jc;
                    assert!(
                        rel < 0.005,
                        "{} {set} T = {temperature_c} degC, eps = {e}: ccx {solver} vs JC {jc}",
                        case.key
                    );
                    checked += 1;
                }
            }
            assert!(checked >= 10, "{} {set}: only {checked} tabulated points reached", case.key);
        }
    }
}
