//! The one error type of the diagnosis crate: every variant says what was wrong and with which value.

/// Errors raised while diagnosing a model-recording discrepancy.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DiagnoseError {
    /// The forward model failed for a test.
    #[error("forward model failed for test {test}: {source}")]
    Model {
        /// The test id.
        test: String,
        /// The model's error.
        source: cutcal_model::ModelError,
    },
    /// The recordings and the simulation do not line up (missing test, no outputs, ...).
    #[error("{0}")]
    Inconsistent(String),
    /// A parameter vector has the wrong length or a value outside its bounds.
    #[error("parameter `{name}` must satisfy {rule}, got {value}")]
    Parameter {
        /// Parameter name with its unit.
        name: String,
        /// The value given.
        value: f64,
        /// The rule it broke.
        rule: String,
    },
    /// A least-squares problem could not be solved (singular, non-finite residuals).
    #[error("least-squares fit failed: {0}")]
    Fit(String),
}
