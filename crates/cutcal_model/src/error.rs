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
