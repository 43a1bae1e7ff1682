//! The per-test values of the mechanism hooks a simulator is asked to switch on.
//!
//! A mechanism sets these from its parameters (`mechanism::set_hooks`); a simulator turns them into
//! physics of cutcal's extended Oxley model (`cutcal_model::oxley::Physics`, the JC flow stress, the
//! rake angle). The neutral values switch every mechanism off.

/// Mechanism hooks for one test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hooks {
    /// Interface friction factor m_f: `tau_int = m_f k_chip` (1 = Oxley's full sticking; M4).
    pub friction_factor: f64,
    /// Scale on the Boothroyd heat partition beta (1 = Oxley; M6).
    pub heat_partition_scale: f64,
    /// Share of the tool-chip frictional heat that enters the chip (1 = Oxley's all; M6's interface
    /// part). It rides on the heat-partition hook (a simulator that supports
    /// [`Hook::HeatPartition`] supports both).
    pub interface_heat_share: f64,
    /// Extra thermomechanical coupling k: the flow stress sees `T_w + (1 + k)(T - T_w)` (0 = off;
    /// negative = weaker softening than the JC law's; M7).
    pub extra_softening: f64,
    /// ln of a scale on the JC thermal exponent m beyond the nuisance's (0 = off; M7's second
    /// form: a thermal exponent fitted at other temperatures). It rides on the extra-softening hook
    /// (a simulator that supports [`Hook::ExtraSoftening`] supports both).
    pub thermal_exponent_ln_scale: f64,
    /// Rake-angle shift, rad (built-up edge: positive = larger effective rake; M9).
    pub rake_shift_rad: f64,
    /// Flow-stress multiplier in both zones (size effect M10), 1 = off.
    pub flow_multiplier: f64,
    /// Cutting-edge radius, m, of the Waldorf et al. 1998 ploughing forces (0 = sharp; M1).
    pub edge_radius_m: f64,
    /// Flank wear land VB, m, of the Smithey et al. 2001 wear-land forces (0 = fresh tool; M3).
    pub wear_land_m: f64,
    /// Scale on Oxley's strain-rate constant C0 (`cutcal_model::oxley::Physics::c0_scale`; 1 =
    /// Oxley). Not a mechanism hook: the Mode A shadow's own global, with which it emulates an
    /// external simulation whose primary zone is not Oxley's (`crate::shadow`).
    pub c0_scale: f64,
}

impl Hooks {
    /// Every mechanism off.
    pub const NEUTRAL: Hooks = Hooks {
        friction_factor: 1.0,
        heat_partition_scale: 1.0,
        interface_heat_share: 1.0,
        extra_softening: 0.0,
        thermal_exponent_ln_scale: 0.0,
        rake_shift_rad: 0.0,
        flow_multiplier: 1.0,
        edge_radius_m: 0.0,
        wear_land_m: 0.0,
        c0_scale: 1.0,
    };
}

/// In-model hooks a simulator may support; a mechanism whose hook the simulator lacks is not
/// testable (there is no output-level stand-in).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Hook {
    /// Interface friction factor m_f.
    FrictionFactor,
    /// Heat-partition scale.
    HeatPartition,
    /// Extra thermomechanical softening.
    ExtraSoftening,
    /// Rake-angle shift per test.
    RakeShift,
    /// Flow-stress multiplier per test.
    FlowMultiplier,
    /// Cutting-edge radius (ploughing).
    EdgeRadius,
    /// Flank wear land.
    WearLand,
}

impl Hook {
    /// Every hook.
    pub const ALL: [Hook; 7] = [
        Hook::FrictionFactor,
        Hook::HeatPartition,
        Hook::ExtraSoftening,
        Hook::RakeShift,
        Hook::FlowMultiplier,
        Hook::EdgeRadius,
        Hook::WearLand,
    ];

    /// The value of this hook in `h`.
    #[must_use]
    pub fn value(self, h: &Hooks) -> f64 {
        match self {
            Hook::FrictionFactor => h.friction_factor,
            Hook::HeatPartition => h.heat_partition_scale,
            Hook::ExtraSoftening => h.extra_softening,
            Hook::RakeShift => h.rake_shift_rad,
            Hook::FlowMultiplier => h.flow_multiplier,
            Hook::EdgeRadius => h.edge_radius_m,
            Hook::WearLand => h.wear_land_m,
        }
    }

    /// `h` with this hook set to `v`.
    #[must_use]
    pub fn with(self, mut h: Hooks, v: f64) -> Hooks {
        match self {
            Hook::FrictionFactor => h.friction_factor = v,
            Hook::HeatPartition => h.heat_partition_scale = v,
            Hook::ExtraSoftening => h.extra_softening = v,
            Hook::RakeShift => h.rake_shift_rad = v,
            Hook::FlowMultiplier => h.flow_multiplier = v,
            Hook::EdgeRadius => h.edge_radius_m = v,
            Hook::WearLand => h.wear_land_m = v,
        }
        h
    }

    /// The value that switches the hook off.
    #[must_use]
    pub fn off(self) -> f64 {
        self.value(&Hooks::NEUTRAL)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_and_value_round_trip_and_off_is_neutral() {
        for h in Hook::ALL {
            let x = h.with(Hooks::NEUTRAL, 0.123);
            assert_eq!(h.value(&x), 0.123);
            assert_eq!(h.with(x, h.off()), Hooks::NEUTRAL);
        }
    }
}
