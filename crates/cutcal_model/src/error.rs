//! The one error type of the model crate: every variant names the quantity, its value and the rule it broke.

/// Errors raised by validating constructors and by the model solves.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A scalar input is outside its physical range (or NaN/infinite).
    #[error("{field} must satisfy {rule}, got {value}")]
    OutOfRange {
        /// Name of the field with its unit, e.g. `uncut_chip_thickness_m`.
        field: String,
        /// The rejected value.
        value: f64,
        /// The rule it broke, e.g. `0 < h <= 1e-3 m`.
        rule: String,
    },
    /// An input is inconsistent with another one (e.g. inverted bounds).
    #[error("{0}")]
    Inconsistent(String),
    /// A temperature reached or exceeded the melting temperature.
    #[error(
        "temperature {what} reached {temperature_c:.1} degC, at or above the melting temperature {melting_c:.1} degC"
    )]
    AboveMelting {
        /// Which temperature (e.g. `exit (EF) temperature`).
        what: String,
        /// The temperature reached, degC.
        temperature_c: f64,
        /// The melting temperature, degC.
        melting_c: f64,
    },
    /// An iteration hit its cap without meeting its tolerance.
    #[error(
        "{what} did not converge in {iterations} iterations (last change {last_change:e}, tolerance {tolerance:e})"
    )]
    NoConvergence {
        /// Which loop.
        what: String,
        /// Iterations done.
        iterations: usize,
        /// The last change / residual.
        last_change: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },
    /// A root-finding problem has no root in its admissible bracket.
    #[error("{what}: no solution in [{low}, {high}] ({detail})")]
    NoSolution {
        /// Which equation.
        what: String,
        /// Lower end of the searched range.
        low: f64,
        /// Upper end of the searched range.
        high: f64,
        /// Why (signs at the ends, etc.).
        detail: String,
    },
    /// Oxley's normal-stress condition has no admissible strain-rate constant C0 at a trial shear
    /// angle. The shear-angle searches probe many angles where this holds and discard the error,
    /// so it keeps its numbers and writes its message only when shown (the same text as
    /// [`ModelError::NoSolution`]'s).
    #[error(
        "Oxley strain-rate constant C0 (sigma_N = sigma_N') at phi {phi_deg:.3} deg: no solution in [{low}, {high}] ({})",
        .why.detail()
    )]
    NoAdmissibleC0 {
        /// The trial shear angle, deg.
        phi_deg: f64,
        /// Lower end of the C0 range.
        low: f64,
        /// Upper end of the C0 range.
        high: f64,
        /// Why no C0 is admissible.
        why: NoC0,
    },
}

/// Why Oxley's normal-stress condition has no admissible C0 at a shear angle
/// ([`ModelError::NoAdmissibleC0`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoC0 {
    /// No strain hardening (n_eq = 0): the balance does not depend on C0.
    NoHardening,
    /// The balance's quadratic in C0 n_eq has no real root.
    NoRealRoot,
    /// The closed-form roots (C0; NaN where a root does not exist) lie outside the range or give
    /// an inadmissible geometry.
    Inadmissible([f64; 2]),
}

impl NoC0 {
    /// The reason in words.
    #[must_use]
    pub fn detail(&self) -> String {
        match self {
            NoC0::NoHardening => {
                "n_eq = 0: the normal-stress balance does not depend on C0 (no strain hardening)".into()
            }
            NoC0::NoRealRoot => "the normal-stress balance has no real root in C0 n_eq at this phi".into(),
            NoC0::Inadmissible(roots) => {
                let shown: Vec<String> = roots.iter().filter(|c| !c.is_nan()).map(|c| format!("{c:.3}")).collect();
                format!(
                    "the balance needs C0 = {} (closed form), outside the range or inadmissible",
                    shown.join(" or ")
                )
            }
        }
    }
}

impl ModelError {
    /// Shorthand for [`ModelError::OutOfRange`].
    pub fn out_of_range(field: impl Into<String>, value: f64, rule: impl Into<String>) -> Self {
        Self::OutOfRange { field: field.into(), value, rule: rule.into() }
    }
}

/// Checks that `value` is finite and `lo < value <= hi` (open at `lo` when `open_lo`).
pub(crate) fn check_range(field: &str, value: f64, lo: f64, hi: f64, rule: &str) -> Result<f64, ModelError> {
    if value.is_finite() && value > lo && value <= hi {
        Ok(value)
    } else {
        Err(ModelError::out_of_range(field, value, rule))
    }
}

/// Checks that `value` is finite.
pub(crate) fn check_finite(field: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ModelError::out_of_range(field, value, "a finite number"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_inadmissible_c0_is_worded_as_a_missing_solution_only_when_shown() {
        let e = |why| ModelError::NoAdmissibleC0 { phi_deg: 12.3456, low: 2.0, high: 10.0, why };
        // The text the search's probes gave as `NoSolution` before they kept their numbers instead.
        let head = "Oxley strain-rate constant C0 (sigma_N = sigma_N') at phi 12.346 deg: no solution in [2, 10]";
        assert_eq!(
            e(NoC0::Inadmissible([1.23456, f64::NAN])).to_string(),
            format!("{head} (the balance needs C0 = 1.235 (closed form), outside the range or inadmissible)")
        );
        assert_eq!(
            e(NoC0::Inadmissible([0.5, 11.0])).to_string(),
            format!("{head} (the balance needs C0 = 0.500 or 11.000 (closed form), outside the range or inadmissible)")
        );
        assert_eq!(
            e(NoC0::NoRealRoot).to_string(),
            format!("{head} (the normal-stress balance has no real root in C0 n_eq at this phi)")
        );
        assert!(e(NoC0::NoHardening).to_string().ends_with("(no strain hardening))"));
    }
}
