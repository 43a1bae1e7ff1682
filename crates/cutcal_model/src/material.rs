//! Materials: temperature-dependent properties (paper Table 3), melting and reference temperatures,
//! and the tool-chip interface laws (paper Eq 17).

use serde::{Deserialize, Serialize};

use crate::error::{check_finite, ModelError};
use crate::heating::AdiabaticHeating;
use crate::poly::TempPolynomial;

/// Temperature-dependent thermal properties in SI units, `T` in degC.
///
/// **Source:** paper Table 3 (C38/42CrMo4: rho(T) and Cp(T); AA6082 and H13A: rho*Cp(T) directly).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThermalProperties {
    /// Volumetric heat capacity rho(T) Cp(T), J/(m^3 K).
    pub rho_cp: TempPolynomial,
    /// Density, kg/m^3 (a constant polynomial where the source gives only rho*Cp).
    pub density: TempPolynomial,
    /// Thermal conductivity K(T), W/(m K).
    pub conductivity: TempPolynomial,
    /// Lowest temperature the fits are stated or used for, degC.
    pub valid_from_c: f64,
    /// Highest temperature the fits are stated or used for, degC.
    pub valid_to_c: f64,
}

impl ThermalProperties {
    /// Specific heat `Cp(T) = (rho Cp)(T) / rho(T)`, J/(kg K).
    #[must_use]
    pub fn specific_heat(&self, temperature_c: f64) -> f64 {
        self.rho_cp.value(temperature_c) / self.density.value(temperature_c)
    }

    /// Checks that rho*Cp, rho and K are positive over the stated range (sampled every 10 K).
    pub fn validate(&self, material: &str) -> Result<(), ModelError> {
        if !(self.valid_from_c.is_finite() && self.valid_to_c.is_finite() && self.valid_from_c < self.valid_to_c) {
            return Err(ModelError::Inconsistent(format!(
                "{material}: thermal validity range [{}, {}] degC is empty or not finite",
                self.valid_from_c, self.valid_to_c
            )));
        }
        let steps = ((self.valid_to_c - self.valid_from_c) / 10.0).ceil().max(1.0) as usize;
        for i in 0..=steps {
            let t = self.valid_from_c + (self.valid_to_c - self.valid_from_c) * i as f64 / steps as f64;
            for (name, v) in [
                ("rho_cp", self.rho_cp.value(t)),
                ("density", self.density.value(t)),
                ("conductivity", self.conductivity.value(t)),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(ModelError::Inconsistent(format!(
                        "{material}: {name} must be positive over [{}, {}] degC, got {v} at {t:.1} degC",
                        self.valid_from_c, self.valid_to_c
                    )));
                }
            }
        }
        Ok(())
    }
}

/// Isotropic linear elasticity (needed by FE cards, not by the cutting models).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Elastic {
    /// Young's modulus, Pa.
    pub youngs_pa: f64,
    /// Poisson's ratio.
    pub poisson: f64,
}

/// A workpiece or tool material.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Name, e.g. `C38`.
    pub name: String,
    /// Thermal properties.
    pub thermal: ThermalProperties,
    /// Temperature-dependent yield strength sigma0(T), Pa (workpieces; paper Table 3).
    pub yield_strength: Option<TempPolynomial>,
    /// Melting temperature Tm, degC.
    pub melting_c: f64,
    /// Room (reference) temperature Tr, degC.
    pub room_c: f64,
    /// Elastic constants, where known.
    pub elastic: Option<Elastic>,
}

impl Material {
    /// Validates the material: temperatures ordered and finite, thermal properties positive over
    /// their range, yield strength positive from Tr up to the thermal range's top.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_finite("melting_c", self.melting_c)?;
        check_finite("room_c", self.room_c)?;
        if self.melting_c <= self.room_c {
            return Err(ModelError::Inconsistent(format!(
                "{}: melting temperature {} degC must exceed room temperature {} degC",
                self.name, self.melting_c, self.room_c
            )));
        }
        self.thermal.validate(&self.name)?;
        if let Some(e) = self.elastic {
            if !(e.youngs_pa.is_finite() && e.youngs_pa > 0.0) {
                return Err(ModelError::out_of_range("youngs_pa", e.youngs_pa, "E > 0 Pa"));
            }
            if !(e.poisson.is_finite() && e.poisson > -1.0 && e.poisson < 0.5) {
                return Err(ModelError::out_of_range("poisson", e.poisson, "-1 < nu < 0.5"));
            }
        }
        Ok(())
    }

    /// Yield strength sigma0(T) in Pa (paper Table 3).
    ///
    /// Returns an error if the material has no yield-strength law, the temperature is at or
    /// above melting, or the law gives a non-positive value there.
    pub fn yield_strength_pa(&self, temperature_c: f64) -> Result<f64, ModelError> {
        let law = self.yield_strength.as_ref().ok_or_else(|| {
            ModelError::Inconsistent(format!("{}: no yield_strength law (needed by the DPZD model)", self.name))
        })?;
        self.check_below_melting("yield strength argument", temperature_c)?;
        let s = law.value(temperature_c);
        if s > 0.0 {
            Ok(s)
        } else {
            Err(ModelError::out_of_range(
                format!("{} yield strength at {temperature_c:.1} degC", self.name),
                s,
                "sigma0(T) > 0 Pa (the Table 3 fit is used outside its range)",
            ))
        }
    }

    /// Errors if `temperature_c` is NaN or at/above the melting temperature.
    pub fn check_below_melting(&self, what: &str, temperature_c: f64) -> Result<(), ModelError> {
        if temperature_c.is_nan() || temperature_c >= self.melting_c {
            return Err(ModelError::AboveMelting { what: what.to_string(), temperature_c, melting_c: self.melting_c });
        }
        Ok(())
    }

    /// Heat taken up per unit volume from `from_c` to `to_c`: the exact integral of rho*Cp(T), J/m^3.
    ///
    /// **Source:** integral form of paper Eq 12 (adiabatic energy balance).
    #[must_use]
    pub fn heat_content_j_per_m3(&self, from_c: f64, to_c: f64) -> f64 {
        self.thermal.rho_cp.integral(from_c, to_c)
    }

    /// Solves `integral_{from}^{T} rho*Cp dT = heat` for `T` with a safeguarded Newton iteration.
    ///
    /// **Source:** paper Eq 12 integrated along the flow line (adiabatic).
    ///
    /// Returns [`ModelError::AboveMelting`] if the heat would take the material to or past `Tm`.
    pub fn temperature_after_heating(&self, from_c: f64, heat_j_per_m3: f64) -> Result<f64, ModelError> {
        AdiabaticHeating::new(self.thermal.rho_cp.clone(), from_c, self.melting_c).temperature(heat_j_per_m3)
    }
}

/// Tool-chip friction law used by the FE cards.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum Friction {
    /// Pressure-dependent shear friction `tau_f = m0 (1 - exp(-beta P)) k` (paper Eq 17).
    PressureDependentShear {
        /// Friction factor m0, dimensionless (0 < m0 <= 1).
        m0: f64,
        /// Pressure coefficient beta, 1/Pa.
        beta_per_pa: f64,
    },
    /// Coulomb `tau = mu sigma` (paper Sec 5.1 for 42CrMo4).
    Coulomb {
        /// Friction coefficient mu.
        mu: f64,
    },
}

impl Friction {
    /// Interface shear stress in Pa at contact pressure `pressure_pa` for a workpiece of shear
    /// strength `shear_strength_pa` (paper Eq 17, or Coulomb).
    #[must_use]
    pub fn shear_stress_pa(&self, pressure_pa: f64, shear_strength_pa: f64) -> f64 {
        match *self {
            Self::PressureDependentShear { m0, beta_per_pa } => {
                m0 * (1.0 - (-beta_per_pa * pressure_pa).exp()) * shear_strength_pa
            }
            Self::Coulomb { mu } => mu * pressure_pa,
        }
    }

    /// Validates the coefficients.
    pub fn validate(&self) -> Result<(), ModelError> {
        match *self {
            Self::PressureDependentShear { m0, beta_per_pa } => {
                if !(m0.is_finite() && m0 > 0.0 && m0 <= 1.0) {
                    return Err(ModelError::out_of_range("m0", m0, "0 < m0 <= 1"));
                }
                if !(beta_per_pa.is_finite() && beta_per_pa > 0.0) {
                    return Err(ModelError::out_of_range("beta_per_pa", beta_per_pa, "beta > 0 1/Pa"));
                }
            }
            Self::Coulomb { mu } => {
                if !(mu.is_finite() && (0.0..=2.0).contains(&mu)) {
                    return Err(ModelError::out_of_range("mu", mu, "0 <= mu <= 2"));
                }
            }
        }
        Ok(())
    }
}

/// The tool-chip interface: friction and heat transfer (paper Sec 5.1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Interface {
    /// Friction law.
    pub friction: Friction,
    /// Heat transfer coefficient, W/(m^2 K) (paper: 10^5 kW/(m^2 K) = 1e8 W/(m^2 K)).
    pub heat_transfer_w_per_m2_k: f64,
}

/// Why a yield-strength law sigma0(T) is not usable over a temperature range (issue 11): the
/// paper's Table 3 cubics are fits with no stated range, and outside the range they were fitted
/// on they can reach zero (C38/42CrMo4 near 980 degC) or rise again after a minimum (AA6082 above
/// 405 degC), which no metal does between room temperature and melting.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum YieldStrengthDefect {
    /// sigma0 is zero or negative (or not finite) at `at_c`.
    NonPositive {
        /// First sampled temperature where it happens, degC.
        at_c: f64,
        /// sigma0 there, Pa.
        value_pa: f64,
    },
    /// sigma0 rises above its running minimum by more than 1 %.
    Rises {
        /// Temperature of the minimum, degC.
        minimum_c: f64,
        /// sigma0 at the minimum, Pa.
        minimum_pa: f64,
        /// First sampled temperature where sigma0 exceeds the minimum by more than 1 %, degC.
        at_c: f64,
        /// sigma0 there, Pa.
        value_pa: f64,
    },
}

/// Relative rise of sigma0 above its running minimum that [`Material::check_yield_strength`]
/// tolerates as fit scatter.
pub const RISE_TOLERANCE: f64 = 0.01;

impl std::fmt::Display for YieldStrengthDefect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::NonPositive { at_c, value_pa } => {
                write!(f, "sigma0({at_c} degC) = {:.2} MPa is not positive", value_pa / 1e6)
            }
            Self::Rises { minimum_c, minimum_pa, at_c, value_pa } => write!(
                f,
                "sigma0 falls to {:.2} MPa at {minimum_c} degC and rises again to {:.2} MPa at {at_c} degC (a yield strength does not increase with temperature)",
                minimum_pa / 1e6,
                value_pa / 1e6
            ),
        }
    }
}

impl Material {
    /// Checks that the yield-strength law sigma0(T) is positive and non-increasing over
    /// `[from_c, to_c]` degC, sampled every 1 K (both ends included); `Ok` if the material has no
    /// law. A rise counts when sigma0 exceeds its running minimum by more than 1 % of it: a smaller
    /// one is within a fit's scatter (the Table 3 AA6082 cubic rises 0.75 % from 256.63 MPa at
    /// 20 degC to 258.56 MPa at its local maximum, 39.3 degC, then falls).
    ///
    /// Ported from `Material::check_yield_strength` of the issue-11 branch (commit 930bda7), which
    /// compared the rise with the global minimum only; the running minimum also catches a bump
    /// before a lower minimum. The law is the paper's Table 3 polynomial.
    pub fn check_yield_strength(&self, from_c: f64, to_c: f64) -> Result<(), YieldStrengthDefect> {
        let Some(law) = self.yield_strength.as_ref() else { return Ok(()) };
        let steps = (to_c - from_c).max(0.0).ceil().min(1e6) as usize;
        let mut running: Option<(f64, f64)> = None;
        for i in 0..=steps {
            let t = if steps == 0 { from_c } else { from_c + (to_c - from_c) * i as f64 / steps as f64 };
            let v = law.value(t);
            if !(v.is_finite() && v > 0.0) {
                return Err(YieldStrengthDefect::NonPositive { at_c: t, value_pa: v });
            }
            match running {
                Some((tm, vm)) if v > vm * (1.0 + RISE_TOLERANCE) => {
                    return Err(YieldStrengthDefect::Rises { minimum_c: tm, minimum_pa: vm, at_c: t, value_pa: v })
                }
                Some((_, vm)) if v >= vm => {}
                _ => running = Some((t, v)),
            }
        }
        Ok(())
    }
}

/// Shared test data.
#[cfg(test)]
pub(crate) mod tests_support {
    use super::*;

    /// C38 thermal data of Table 3 (paper), in SI.
    pub(crate) fn c38() -> Material {
        let rho = TempPolynomial::new(vec![7.866, -8.465e-4, 1.091e-6, -5.961e-10]).unwrap().scaled(1e3);
        let cp = TempPolynomial::new(vec![0.2306, 0.0025, -3.653e-6, 1.707e-9]).unwrap().scaled(1e3);
        Material {
            name: "C38".into(),
            thermal: ThermalProperties {
                rho_cp: rho.product(&cp),
                density: rho,
                conductivity: TempPolynomial::new(vec![45.1088, -0.0321, 1.645e-5]).unwrap(),
                valid_from_c: 20.0,
                valid_to_c: 1200.0,
            },
            yield_strength: Some(TempPolynomial::new(vec![773.007, -1.630, 0.0038, -3.001e-6]).unwrap().scaled(1e6)),
            melting_c: 1460.0,
            room_c: 20.0,
            elastic: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::tests_support::c38;
    use super::*;

    #[test]
    fn temperature_inverts_heat_content() {
        let m = c38();
        m.validate().unwrap();
        for t in [25.0, 300.0, 700.0, 1100.0] {
            let q = m.heat_content_j_per_m3(20.0, t);
            let back = m.temperature_after_heating(20.0, q).unwrap();
            assert!((back - t).abs() < 1e-7, "{t} -> {back}");
        }
    }

    #[test]
    fn temperature_inverts_heat_content_to_rounding_at_every_degree() {
        // The Newton iteration may land on the root exactly (f = 0 to rounding); it must stop there,
        // not bisect away and back (at 700 degC that once returned 700.0000000575 after 36 steps).
        // Independent check: T -> heat by the exact integral -> T, at every degree 21..1400 degC.
        let m = c38();
        for k in 21..=1400 {
            let t = f64::from(k);
            let q = m.heat_content_j_per_m3(20.0, t);
            let back = m.temperature_after_heating(20.0, q).unwrap();
            assert!((back - t).abs() < 1e-9, "{t} -> {back}");
        }
    }

    #[test]
    fn heat_beyond_melting_is_an_error() {
        let m = c38();
        let q = m.heat_content_j_per_m3(20.0, 1460.0) * 1.01;
        assert!(matches!(m.temperature_after_heating(20.0, q), Err(ModelError::AboveMelting { .. })));
        assert!(m.temperature_after_heating(20.0, f64::NAN).is_err());
    }

    #[test]
    fn c38_sigma0_cubic_reaches_zero_inside_its_thermal_range() {
        // Table 3 C38 sigma0 = 773.007 - 1.630 T + 0.0038 T^2 - 3.001e-6 T^3 MPa has its one real
        // root at T = 980.22 degC (numpy.roots of the cubic); its derivative -1.630 + 0.0076 T -
        // 9.003e-6 T^2 has no real root (0.0076^2 < 4 * 9.003e-6 * 1.630), so it only falls.
        let m = c38();
        match m.check_yield_strength(20.0, 1200.0) {
            Err(YieldStrengthDefect::NonPositive { at_c, value_pa }) => {
                assert_eq!(at_c, 981.0);
                assert!(value_pa <= 0.0);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(m.check_yield_strength(20.0, 980.0), Ok(()));
    }

    #[test]
    fn aa6082_sigma0_cubic_rises_after_its_minimum() {
        // Table 3 AA6082 sigma0 = 250.258 + 0.437 T - 0.0061 T^2 + 9.155e-6 T^3 MPa: dsigma/dT = 0 at
        // T = (0.0122 + sqrt(0.0122^2 - 4*2.7465e-5*0.437)) / (2*2.7465e-5) = 405.0 degC, where
        // sigma0 = 34.86 MPa (hand evaluation; the issue-11 branch's test, commit 930bda7).
        let mut m = c38();
        m.yield_strength = Some(TempPolynomial::new(vec![250.258, 0.437, -0.0061, 9.155e-6]).unwrap().scaled(1e6));
        m.melting_c = 582.0;
        match m.check_yield_strength(20.0, 560.0) {
            Err(YieldStrengthDefect::Rises { minimum_c, minimum_pa, at_c, value_pa }) => {
                assert!((minimum_c - 405.0).abs() <= 1.0, "{minimum_c}");
                assert!((minimum_pa / 1e6 - 34.86).abs() < 0.01, "{minimum_pa}");
                assert!(at_c > minimum_c && value_pa > minimum_pa * 1.01, "{at_c} {value_pa}");
            }
            other => panic!("{other:?}"),
        }
        // Its 0.75 % rise from 20 to 39.3 degC (dsigma/dT = 0 at (0.0122 - sqrt(...)) / 5.493e-5)
        // is within the tolerance; a stricter one would flag it.
        assert_eq!(m.check_yield_strength(20.0, 400.0), Ok(()));
        let s20 = 250.258 + 0.437 * 20.0 - 0.0061 * 400.0 + 9.155e-6 * 8000.0;
        let t1 = (0.0122 - (0.0122f64.powi(2) - 4.0 * 2.7465e-5 * 0.437).sqrt()) / (2.0 * 2.7465e-5);
        let s1 = 250.258 + 0.437 * t1 - 0.0061 * t1 * t1 + 9.155e-6 * t1.powi(3);
        assert!((t1 - 39.3).abs() < 0.1 && (s1 / s20 - 1.0 - 0.0075).abs() < 0.0005, "{t1} {s20} {s1}");
        // sigma0 = 100 - 0.2 T + 0.002 T^2 MPa: d/dT = -0.2 + 0.004 T = 0 at 50 degC, inside [0, 100].
        m.yield_strength = Some(TempPolynomial::new(vec![100.0, -0.2, 0.002]).unwrap().scaled(1e6));
        assert!(matches!(m.check_yield_strength(0.0, 100.0), Err(YieldStrengthDefect::Rises { .. })));
    }

    #[test]
    fn eq17_saturates_at_m0_k() {
        // Eq 17 with m0 = 1, beta = 0.0045/MPa (paper Sec 5.1): at P = 2000 MPa, 1 - e^-9 = 0.99988.
        let f = Friction::PressureDependentShear { m0: 1.0, beta_per_pa: 0.0045e-6 };
        let tau = f.shear_stress_pa(2000e6, 400e6);
        assert!((tau / 400e6 - (1.0 - (-9.0f64).exp())).abs() < 1e-12);
    }
}
