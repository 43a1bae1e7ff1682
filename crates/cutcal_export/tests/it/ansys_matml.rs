//! `ansys-materials-manager` (PyPI; the MatML reader of Ansys' PyMaterials) reads every exported
//! MatML file unchanged with its `MatmlReader`, and the values it reads are compared with the
//! material data: density, specific heat and conductivity (values and temperatures), the JC set,
//! isotropic elasticity, the Eq 17 constants and k(T), the heat transfer coefficient
//! (issue 12, Build 3). Script: `tests/python/matml_read.py`.

use std::collections::BTreeMap;
use std::process::Command;

use cutcal_export::{render, Dialect};
use cutcal_model::{Friction, Material};
use serde_json::Value;

use crate::{common, pytools};

type Props = BTreeMap<String, BTreeMap<String, Vec<f64>>>;

fn close(got: f64, want: f64) -> bool {
    // 9 significant digits are written (matml::SIG_MATML).
    (got - want).abs() <= 1e-8 * want.abs().max(1e-300)
}

fn values<'a>(props: &'a Props, prop: &str, param: &str) -> &'a [f64] {
    props.get(prop).and_then(|p| p.get(param)).unwrap_or_else(|| panic!("{prop} / {param} not read: {props:?}"))
}

/// Density, specific heat, conductivity vs temperature and elasticity of `m` as read.
fn check_bulk(key: &str, m: &Material, props: &Props) {
    for (prop, param, law) in [
        ("Density", "Density", &(|t| m.thermal.density.value(t)) as &dyn Fn(f64) -> f64),
        ("Specific Heat", "Specific Heat", &|t| m.thermal.specific_heat(t)),
        ("Thermal Conductivity", "Thermal Conductivity", &|t| m.thermal.conductivity.value(t)),
    ] {
        let temps = values(props, prop, "Temperature");
        let vals = values(props, prop, param);
        assert_eq!(temps.len(), vals.len(), "{key} {}: {prop}", m.name);
        assert!(temps.len() >= 2, "{key} {prop}: {temps:?}");
        for (t, v) in temps.iter().zip(vals) {
            assert!(close(*v, law(*t)), "{key} {} {prop} at {t} degC: read {v}, material {}", m.name, law(*t));
        }
    }
    let e = m.elastic.expect("fixture materials have elastic constants");
    assert!(close(values(props, "Elasticity", "Young's Modulus")[0], e.youngs_pa));
    assert!(close(values(props, "Elasticity", "Poisson's Ratio")[0], e.poisson));
}

#[test]
fn ansys_materials_manager_reads_every_matml_file() {
    let Some(py) = pytools::python_with(
        "ansys.materials.manager.parsers.matml.matml_reader",
        "ansys-materials-manager ansys-units pydantic pyparsing",
    ) else {
        return;
    };
    let opts = common::options();
    let dir = tempfile::tempdir().unwrap();
    let mut cases = common::cases();
    cases.push(common::aisi1045());
    let mut paths = Vec::new();
    for case in &cases {
        let prov = common::provenance(case);
        let files = render(Dialect::MatMl, &common::input(case, &prov, &opts)).unwrap();
        let path = dir.path().join(&files[0].name);
        std::fs::write(&path, &files[0].contents).unwrap();
        paths.push(path);
    }
    let out = Command::new(&py)
        .arg(pytools::root().join("crates/cutcal_export/tests/python/matml_read.py"))
        .args(&paths)
        .output()
        .expect("cannot start python");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "MatmlReader failed:\n{stderr}");
    let read: Value = serde_json::from_slice(&out.stdout).expect("JSON from matml_read.py");

    for (case, path) in cases.iter().zip(&paths) {
        let file = &read[path.to_string_lossy().as_ref()];
        let mats: BTreeMap<String, Props> = serde_json::from_value(file.clone()).unwrap();
        let names: Vec<&String> = mats.keys().collect();
        assert_eq!(names.len(), 2, "{}: workpiece and tool expected, read {names:?}", case.key);
        let wp = &mats[&case.workpiece.name];
        check_bulk(case.key, &case.workpiece, wp);
        check_bulk(case.key, &case.tool, &mats[&case.tool.name]);

        let jc = &case.jc;
        for (param, want) in [
            ("Initial Yield Stress", jc.a_pa),
            ("Hardening Constant", jc.b_pa),
            ("Hardening Exponent", jc.n),
            ("Strain Rate Constant", jc.c),
            ("Thermal Softening Exponent", jc.m),
            ("Melting Temperature", jc.tm_c),
            ("Reference Temperature", jc.tr_c),
            ("Reference Strain Rate (/sec)", jc.eps0_per_s),
        ] {
            let got = values(wp, "Johnson Cook Strength", param)[0];
            assert!(close(got, want), "{} JC {param}: read {got}, set {want}", case.key);
        }
        // Paper Sec 5.1: 1e5 kW/(m^2 K).
        assert!(close(values(wp, "Interface Heat Transfer", "Heat Transfer Coefficient")[0], 1e8));
        match case.interface.friction {
            Friction::PressureDependentShear { m0, beta_per_pa } => {
                let eq17 = "Pressure-Dependent Shear Friction (paper Eq 17)";
                assert!(close(values(wp, eq17, "Friction Factor m0")[0], m0));
                assert!(close(values(wp, eq17, "Pressure Coefficient beta")[0], beta_per_pa));
                // k(T) = (A + B 2^n)(1 + C ln(1e4/eps0))(1 - T*^m)/sqrt(3) (paper Eq 16 at eps = 2,
                // epsdot = 1e4 1/s), written out here.
                let temps = values(wp, "Eq 17 Local Shear Strength", "Temperature");
                let ks = values(wp, "Eq 17 Local Shear Strength", "Local Shear Strength k");
                assert!(temps.len() >= 5, "{}: {temps:?}", case.key);
                for (t, k) in temps.iter().zip(ks) {
                    let ts = (t - jc.tr_c) / (jc.tm_c - jc.tr_c);
                    let want = (jc.a_pa + jc.b_pa * 2f64.powf(jc.n))
                        * (1.0 + jc.c * (1e4 / jc.eps0_per_s).ln())
                        * (1.0 - ts.powf(jc.m))
                        / 3f64.sqrt();
                    assert!(close(*k, want), "{} k({t}): read {k}, Eq 16 {want}", case.key);
                }
            }
            Friction::Coulomb { mu } => {
                assert!(close(values(wp, "Coulomb Friction", "Coulomb Friction Coefficient")[0], mu));
            }
        }
    }
}
