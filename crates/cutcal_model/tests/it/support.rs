//! Materials and JC sets used by the Oxley tests, built in code with their sources.

use cutcal_model::{JcParams, Material, TempPolynomial, ThermalProperties};

/// AISI 1045 with Lalwani et al. 2009's thermal data: rho = 7862 kg/m3, Cp = 420 + 0.504 T J/(kg K),
/// K = 52.61 - 0.0281 T W/(m K), T in degC; Tm 1460 degC, room 25 degC
/// (as in fixtures/materials/aisi1045.toml).
pub fn aisi1045() -> Material {
    cutcal_model::reference::aisi1045_lalwani2009()
}

/// Jaspers & Dautzenberg 2002 JC set for AISI 1045 (fixtures/jc/aisi1045_jaspers2002.toml).
pub fn jc_aisi1045() -> JcParams {
    JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap()
}

/// AA6082 as in fixtures/materials/aa6082.toml: rho*Cp = 2.4 + 0.0013 T - 7.17e-7 T^2 J/(cm3 K)
/// and K = 258.511 - 0.1116 T - 5e-5 T^2 W/(m K) (Ertürk et al. 2020, Table 3, ref [22]); rho 2.70 g/cm3;
/// Tm 582 degC, room 20 degC; properties valid 20-560 degC.
pub fn aa6082() -> Material {
    Material {
        name: "AA6082".into(),
        thermal: ThermalProperties {
            rho_cp: TempPolynomial::new(vec![2.4, 0.0013, -7.17e-7]).unwrap().scaled(1e6),
            density: TempPolynomial::constant(2700.0),
            conductivity: TempPolynomial::new(vec![258.511, -0.1116, -5e-5]).unwrap(),
            valid_from_c: 20.0,
            valid_to_c: 560.0,
        },
        yield_strength: None,
        melting_c: 582.0,
        room_c: 20.0,
        elastic: None,
    }
}

/// AA6082, Ertürk et al. 2020 Table 5 (fixtures/jc/aa6082_table5.toml).
pub fn jc_aa6082() -> JcParams {
    JcParams::new(250e6, 61e6, 0.43, 0.034, 1.067, 1.0, 582.0, 20.0).unwrap()
}
