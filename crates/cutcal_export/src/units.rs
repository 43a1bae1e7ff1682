//! Consistent unit systems for the Abaqus and LS-DYNA cards (fe-cards.md §1.1 table).
//!
//! The model is SI with temperatures in degC; cards get a stated consistent system with absolute
//! temperatures in K (LS-DYNA's thermal solver and radiation need an absolute scale; fe-cards.md §1.1).

use serde::Serialize;

/// A consistent unit system for Abaqus and LS-DYNA (neither has units of its own).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum UnitSystem {
    /// tonne, mm, s, N, MPa, mJ, K — the usual set for cutting (fe-cards.md §1.1).
    TonneMmSecondKelvin,
    /// kg, m, s, N, Pa, J, K (SI).
    SiKelvin,
}

/// Offset from degC to K.
pub const KELVIN_OFFSET: f64 = 273.15;

/// Multiplicative factors from SI to a [`UnitSystem`], plus labels for card headers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Factors {
    /// Stress and pressure (Pa ->).
    pub stress: f64,
    /// Density (kg/m^3 ->).
    pub density: f64,
    /// Specific heat (J/(kg K) ->).
    pub specific_heat: f64,
    /// Thermal conductivity (W/(m K) ->).
    pub conductivity: f64,
    /// Heat transfer coefficient (W/(m^2 K) ->).
    pub heat_transfer: f64,
    /// Length (m ->).
    pub length: f64,
    /// Velocity (m/s ->).
    pub velocity: f64,
}

impl UnitSystem {
    /// The SI-to-system factors (fe-cards.md §1.1 table: density x1e-12, stress x1e-6,
    /// specific heat x1e6, conductivity x1, heat transfer x1e-3 for t-mm-s).
    #[must_use]
    pub fn factors(self) -> Factors {
        match self {
            Self::TonneMmSecondKelvin => Factors {
                stress: 1e-6,
                density: 1e-12,
                specific_heat: 1e6,
                conductivity: 1.0,
                heat_transfer: 1e-3,
                length: 1e3,
                velocity: 1e3,
            },
            Self::SiKelvin => Factors {
                stress: 1.0,
                density: 1.0,
                specific_heat: 1.0,
                conductivity: 1.0,
                heat_transfer: 1.0,
                length: 1.0,
                velocity: 1.0,
            },
        }
    }

    /// A one-line statement of the system for card headers.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::TonneMmSecondKelvin => {
                "tonne, mm, s, N, MPa, mJ, K (density t/mm^3, specific heat mm^2/(s^2 K), conductivity \
                 N/(s K), heat transfer N/(s mm K))"
            }
            Self::SiKelvin => {
                "kg, m, s, N, Pa, J, K (density kg/m^3, specific heat J/(kg K), conductivity W/(m K), \
                 heat transfer W/(m^2 K))"
            }
        }
    }

    /// Stress unit name.
    #[must_use]
    pub fn stress_unit(self) -> &'static str {
        match self {
            Self::TonneMmSecondKelvin => "MPa",
            Self::SiKelvin => "Pa",
        }
    }
}

/// degC -> K.
#[must_use]
pub fn kelvin(temperature_c: f64) -> f64 {
    temperature_c + KELVIN_OFFSET
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tonne_mm_factors_reproduce_the_fe_cards_steel_example() {
        // fe-cards.md §1.1: 7850 kg/m^3 -> 7.85E-09, 432 J/(kg K) -> 4.32E+08, 1e4 W/(m^2 K) -> 10.
        let f = UnitSystem::TonneMmSecondKelvin.factors();
        assert!((7850.0 * f.density - 7.85e-9).abs() < 1e-22);
        assert!((432.0 * f.specific_heat - 4.32e8).abs() < 1e-3);
        assert!((1e4 * f.heat_transfer - 10.0).abs() < 1e-12);
        assert!((553.1e6 * f.stress - 553.1).abs() < 1e-9);
        assert!((kelvin(20.0) - 293.15).abs() < 1e-12);
    }
}
