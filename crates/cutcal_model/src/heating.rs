//! The adiabatic temperature of a material point: `T` from the heat it has taken up,
//! `integral_{from}^{T} rho*Cp(T) dT = heat` (paper Eq 12 integrated along the flow line), by a
//! safeguarded Newton iteration on the exact antiderivative of the rho*Cp polynomial, bracketed by
//! `[from, melting]` and capped at 100 steps. Used by the enhanced DPZD zone at every point
//! ([`crate::dpzd`]) and by [`crate::material::Material::temperature_after_heating`]; the tests
//! of the inversion are in [`crate::material`].

use crate::error::{check_finite, ModelError};
use crate::poly::TempPolynomial;

/// The inverse of the adiabatic heating from one start temperature: `T` with
/// `integral_{from}^{T} rho_cp dT = heat`, with the heat content at the start and at melting
/// evaluated once (a DPZD zone inverts it at every point).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct AdiabaticHeating {
    rho_cp: TempPolynomial,
    heat_content: TempPolynomial,
    from_c: f64,
    melting_c: f64,
    /// Heat content at `from_c`, J/m^3.
    h_from: f64,
    /// Heat from `from_c` to melting, J/m^3.
    h_to_melting: f64,
    /// `rho_cp` at `from_c`, J/(m^3 K).
    rho_cp_from: f64,
}

impl AdiabaticHeating {
    /// The heating of `rho_cp` from `from_c`, below `melting_c`.
    pub(crate) fn new(rho_cp: TempPolynomial, from_c: f64, melting_c: f64) -> Self {
        let heat_content = rho_cp.antiderivative_polynomial();
        let h_from = heat_content.value(from_c);
        let h_to_melting = heat_content.value(melting_c) - h_from;
        let rho_cp_from = rho_cp.value(from_c);
        Self { rho_cp, heat_content, from_c, melting_c, h_from, h_to_melting, rho_cp_from }
    }

    /// The temperature after taking up `heat_j_per_m3`, degC.
    ///
    /// **Source:** paper Eq 12 integrated along the flow line (adiabatic).
    ///
    /// Returns [`ModelError::AboveMelting`] if the heat would take the material to or past
    /// melting, and [`ModelError::NoConvergence`] at the cap.
    pub(crate) fn temperature(&self, heat_j_per_m3: f64) -> Result<f64, ModelError> {
        check_finite("heat_j_per_m3", heat_j_per_m3)?;
        if heat_j_per_m3 < 0.0 {
            return Err(ModelError::out_of_range("heat_j_per_m3", heat_j_per_m3, "heat >= 0 J/m^3"));
        }
        let (from_c, top, rho_cp) = (self.from_c, self.melting_c, &self.rho_cp);
        if heat_j_per_m3 >= self.h_to_melting {
            return Err(ModelError::AboveMelting {
                what: "adiabatic temperature".into(),
                temperature_c: top + (heat_j_per_m3 - self.h_to_melting) / rho_cp.value(top).max(1.0),
                melting_c: top,
            });
        }
        let (mut lo, mut hi) = (from_c, top);
        let mut t = (from_c + heat_j_per_m3 / self.rho_cp_from).clamp(lo, hi);
        for _ in 0..100 {
            let f = self.heat_content.value(t) - self.h_from - heat_j_per_m3;
            if f == 0.0 {
                // The root to rounding: a bisection from here would walk away from it and back.
                return Ok(t);
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let df = rho_cp.value(t);
            let mut next = t - f / df;
            if !(next >= lo && next <= hi) || df <= 0.0 {
                next = 0.5 * (lo + hi);
            }
            if (next - t).abs() < 1e-10 * (1.0 + t.abs()) || hi - lo < 1e-10 {
                return Ok(next);
            }
            t = next;
        }
        Err(ModelError::NoConvergence {
            what: "adiabatic temperature (Newton)".into(),
            iterations: 100,
            last_change: hi - lo,
            tolerance: 1e-10,
        })
    }
}
