//! Published reference materials, for tests, benchmarks and examples (the fixtures in
//! `fixtures/materials/` carry the same numbers for the command line).

use crate::cutting_test::CuttingTest;
use crate::material::{Material, ThermalProperties};
use crate::poly::TempPolynomial;

fn law(coefficients: &[f64], scale: f64) -> TempPolynomial {
    // The coefficients below are finite literals, so construction cannot fail.
    TempPolynomial::new(coefficients.to_vec()).expect("finite literal coefficients").scaled(scale)
}

/// C38 with the temperature-dependent laws of the paper's Table 3 in SI (rho g/cm^3 x1e3,
/// Cp J/(g K) x1e3, sigma0 MPa x1e6), Tm 1460 degC (Table 4), Tr 20 degC, valid 20-1200 degC.
///
/// **Source:** paper Table 3 (C38/42CrMo4 rows), Table 4.
///
/// # Example
/// ```
/// let m = cutcal_model::reference::c38_table3();
/// // sigma0(20) = 773.007 - 32.6 + 1.52 - 0.024 = 741.90 MPa (Table 3).
/// assert!((m.yield_strength_pa(20.0).unwrap() / 1e6 - 741.903).abs() < 1e-3);
/// ```
#[must_use]
pub fn c38_table3() -> Material {
    let rho = law(&[7.866, -8.465e-4, 1.091e-6, -5.961e-10], 1e3);
    let cp = law(&[0.2306, 0.0025, -3.653e-6, 1.707e-9], 1e3);
    Material {
        name: "C38".into(),
        thermal: ThermalProperties {
            rho_cp: rho.product(&cp),
            density: rho,
            conductivity: law(&[45.1088, -0.0321, 1.645e-5], 1.0),
            valid_from_c: 20.0,
            valid_to_c: 1200.0,
        },
        yield_strength: Some(law(&[773.007, -1.630, 0.0038, -3.001e-6], 1e6)),
        melting_c: 1460.0,
        room_c: 20.0,
        elastic: None,
    }
}

/// AISI 1045 with Lalwani's thermal data: rho 7862 kg/m^3, Cp = 420 + 0.504 T J/(kg K),
/// K = 52.61 - 0.0281 T W/(m K), Tm 1460 degC, work temperature 25 degC.
///
/// **Source:** Lalwani, Mehta & Jain, J. Mater. Process. Technol. 209 (2009) 5305-5312.
#[must_use]
pub fn aisi1045_lalwani2009() -> Material {
    let rho = TempPolynomial::constant(7862.0);
    Material {
        name: "AISI1045".into(),
        thermal: ThermalProperties {
            rho_cp: rho.product(&law(&[420.0, 0.504], 1.0)),
            density: rho,
            conductivity: law(&[52.61, -0.0281], 1.0),
            valid_from_c: 0.0,
            valid_to_c: 1400.0,
        },
        yield_strength: None,
        melting_c: 1460.0,
        room_c: 25.0,
        elastic: None,
    }
}

/// C38 test 3 as recorded: 240 m/min (4 m/s), h 0.075 mm, width 1.95 mm, rake 0 deg; Fc 224 N/mm,
/// Ft 186 N/mm, chip 0.157 mm, all per unit width in SI.
///
/// **Source:** paper Tables 2 and 6.
#[must_use]
pub fn c38_test3() -> CuttingTest {
    // The numbers below are finite, positive literals, so construction cannot fail.
    CuttingTest::new("3", 4.0, 0.075e-3, 1.95e-3, 0.0)
        .and_then(|t| t.with_forces(Some(224e3), Some(186e3)))
        .and_then(|t| t.with_chip_thickness(Some(0.157e-3)))
        .expect("paper Table 2 literals are valid")
}
