//! Shared test data: the paper's three workpieces with their Table 5 JC sets, the H13A tool, and
//! the export options used by the snapshots. Numbers are those of `fixtures/materials/*.toml` and
//! `fixtures/jc/*_table5.toml` (paper Tables 3 and 5, Sec 5.1), converted to SI exactly as
//! `cutcal_cli::input::material_file` does (g/cm^3 x1e3, J/(g K) x1e3, J/(cm^3 K) x1e6, MPa x1e6).

use cutcal_export::{
    ExportInput, ExportOptions, Provenance, TemperatureGrid, UnitSystem, STANDARD_CONTACT_PRESSURES_MPA,
    STANDARD_FLOW_STRAIN_RATES_PER_S, STANDARD_PLASTIC_STRAINS,
};
use cutcal_model::{Elastic, Friction, Interface, JcParams, Material, TempPolynomial, ThermalProperties};

/// One snapshot case: workpiece, JC, tool, interface.
pub struct Case {
    pub key: &'static str,
    pub workpiece: Material,
    pub jc: JcParams,
    pub tool: Material,
    pub interface: Interface,
}

fn poly(c: &[f64], scale: f64) -> TempPolynomial {
    TempPolynomial::new(c.to_vec()).unwrap().scaled(scale)
}

/// C38 / 42CrMo4 thermal laws: paper Table 3 (JMatPro), as in fixtures/materials/c38.toml.
fn steel(name: &str) -> Material {
    let rho = poly(&[7.866, -8.465e-4, 1.091e-6, -5.961e-10], 1e3);
    let cp = poly(&[0.2306, 0.0025, -3.653e-6, 1.707e-9], 1e3);
    Material {
        name: name.into(),
        thermal: ThermalProperties {
            rho_cp: rho.product(&cp),
            density: rho,
            conductivity: poly(&[45.1088, -0.0321, 1.645e-5], 1.0),
            valid_from_c: 20.0,
            valid_to_c: 1200.0,
        },
        yield_strength: Some(poly(&[773.007, -1.630, 0.0038, -3.001e-6], 1e6)),
        melting_c: 1460.0,
        room_c: 20.0,
        elastic: Some(Elastic { youngs_pa: 210e9, poisson: 0.3 }),
    }
}

/// AA6082: paper Table 3, fixtures/materials/aa6082.toml.
fn aa6082() -> Material {
    Material {
        name: "AA6082".into(),
        thermal: ThermalProperties {
            rho_cp: poly(&[2.4, 0.0013, -7.17e-7], 1e6),
            density: poly(&[2.70], 1e3),
            conductivity: poly(&[258.511, -0.1116, -5e-5], 1.0),
            valid_from_c: 20.0,
            valid_to_c: 560.0,
        },
        yield_strength: Some(poly(&[250.258, 0.437, -0.0061, 9.155e-6], 1e6)),
        melting_c: 582.0,
        room_c: 20.0,
        elastic: Some(Elastic { youngs_pa: 70e9, poisson: 0.33 }),
    }
}

/// H13A tool: paper Table 3, fixtures/materials/h13a.toml.
pub fn h13a() -> Material {
    Material {
        name: "H13A".into(),
        thermal: ThermalProperties {
            rho_cp: poly(&[2.8857, 0.0041, -5e-6, 3e-9], 1e6),
            density: poly(&[14.9], 1e3),
            conductivity: poly(&[92.584, 0.0419, -0.0003, 4e-7, -2e-10], 1.0),
            valid_from_c: 20.0,
            valid_to_c: 1000.0,
        },
        yield_strength: None,
        melting_c: 2800.0,
        room_c: 20.0,
        elastic: Some(Elastic { youngs_pa: 630e9, poisson: 0.22 }),
    }
}

/// Heat transfer coefficient of paper Sec 5.1: 1e5 kW/(m^2 K) = 1e8 W/(m^2 K).
const HTC: f64 = 1e8;

/// The three snapshot cases (paper Table 5 JC sets, Sec 5.1 interfaces).
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            key: "c38",
            workpiece: steel("C38"),
            jc: JcParams::new(589e6, 145e6, 0.25, 0.069, 1.1, 1.0, 1460.0, 20.0).unwrap(),
            tool: h13a(),
            interface: Interface {
                friction: Friction::PressureDependentShear { m0: 1.0, beta_per_pa: 0.0045e-6 },
                heat_transfer_w_per_m2_k: HTC,
            },
        },
        Case {
            key: "42crmo4",
            workpiece: steel("42CrMo4"),
            jc: jc_file("42crmo4"),
            tool: h13a(),
            interface: Interface { friction: Friction::Coulomb { mu: 0.23 }, heat_transfer_w_per_m2_k: HTC },
        },
        Case {
            key: "aa6082",
            workpiece: aa6082(),
            jc: JcParams::new(250e6, 61e6, 0.43, 0.034, 1.067, 1.0, 582.0, 20.0).unwrap(),
            tool: h13a(),
            interface: Interface {
                friction: Friction::PressureDependentShear { m0: 1.0, beta_per_pa: 0.012e-6 },
                heat_transfer_w_per_m2_k: HTC,
            },
        },
    ]
}

/// AISI 1045 of fixtures/materials/aisi1045.toml (Lalwani et al. 2009 thermal data, typical
/// elastic constants) with the Jaspers & Dautzenberg 2002 JC set of fixtures/jc/aisi1045_jaspers2002.toml
/// and the fixture's interface (Coulomb mu = 0.583, H13A tool, paper Sec 5.1 heat transfer).
pub fn aisi1045() -> Case {
    Case {
        key: "aisi1045",
        workpiece: Material {
            name: "AISI1045".into(),
            thermal: ThermalProperties {
                rho_cp: poly(&[7862.0], 1.0).product(&poly(&[420.0, 0.504], 1.0)),
                density: poly(&[7862.0], 1.0),
                conductivity: poly(&[52.61, -0.0281], 1.0),
                valid_from_c: 0.0,
                valid_to_c: 1400.0,
            },
            yield_strength: None,
            melting_c: 1460.0,
            room_c: 25.0,
            elastic: Some(Elastic { youngs_pa: 205e9, poisson: 0.29 }),
        },
        jc: JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap(),
        tool: h13a(),
        interface: Interface { friction: Friction::Coulomb { mu: 0.583 }, heat_transfer_w_per_m2_k: HTC },
    }
}

/// Reads a Table 5 JC fixture (`fixtures/jc/<key>_table5.toml`) with a minimal `key = value` reader,
/// so the tests follow the fixture rather than a copy of it.
pub fn jc_file(key: &str) -> JcParams {
    let path = format!("{}/../../fixtures/jc/{key}_table5.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    let get = |k: &str| -> f64 {
        text.lines()
            .filter_map(|l| l.split('#').next())
            .filter_map(|l| l.split_once('='))
            .find(|(name, _)| name.trim() == k)
            .map(|(_, v)| v.trim().parse().unwrap())
            .unwrap_or_else(|| panic!("{path}: no {k}"))
    };
    JcParams::new(
        get("a_mpa") * 1e6,
        get("b_mpa") * 1e6,
        get("n"),
        get("c"),
        get("m"),
        get("eps0_per_s"),
        get("tm_c"),
        get("tr_c"),
    )
    .unwrap()
}

/// Snapshot options: t-mm-s-K, 20..1200 degC every 100 K, tabular rate 1e4 1/s, Taylor-Quinney 0.9.
pub fn options() -> ExportOptions {
    ExportOptions {
        units: UnitSystem::TonneMmSecondKelvin,
        temperatures: TemperatureGrid { from_c: 20.0, to_c: 1200.0, step_c: 100.0 },
        plastic_strains: STANDARD_PLASTIC_STRAINS.to_vec(),
        tabular_strain_rate_per_s: 1e4,
        flow_strain_rates_per_s: STANDARD_FLOW_STRAIN_RATES_PER_S.to_vec(),
        contact_pressures_pa: STANDARD_CONTACT_PRESSURES_MPA.iter().map(|p| p * 1e6).collect(),
        inelastic_heat_fraction: 0.9,
        contact_temperature: None,
        cutting_speed_m_per_s: None,
    }
}

/// Snapshot provenance (the version is filtered in snapshots anyway).
pub fn provenance(case: &Case) -> Provenance {
    Provenance {
        cutcal_version: env!("CARGO_PKG_VERSION").into(),
        source_test: format!("{} paper Table 5 set", case.workpiece.name),
        model_variant: "enhanced DPZD".into(),
    }
}

/// Borrows a case as an export input.
pub fn input<'a>(case: &'a Case, prov: &'a Provenance, opts: &'a ExportOptions) -> ExportInput<'a> {
    ExportInput {
        workpiece: &case.workpiece,
        jc: &case.jc,
        tool: Some(&case.tool),
        interface: &case.interface,
        provenance: prov,
        options: opts,
    }
}
