//! The one error type of the identification crate.

use cutcal_model::ModelError;

/// Errors raised by the optimiser and the identification problems.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IdentError {
    /// A bound pair is inverted, not finite, or has the wrong length.
    #[error("invalid bounds for {parameter}: [{low}, {high}]")]
    InvalidBounds {
        /// Parameter name.
        parameter: String,
        /// Lower bound.
        low: f64,
        /// Upper bound.
        high: f64,
    },
    /// The model failed where the optimiser needed a value.
    #[error("model evaluation failed: {0}")]
    Model(#[from] ModelError),
    /// A residual or Jacobian entry is NaN or infinite.
    #[error("non-finite {what} at parameters {params:?}")]
    NonFinite {
        /// Residuals or Jacobian.
        what: String,
        /// Where.
        params: Vec<f64>,
    },
    /// Every start of a multistart failed.
    #[error("all {starts} starts failed; first failure: {first}")]
    AllStartsFailed {
        /// Number of starts.
        starts: usize,
        /// The first failure.
        first: String,
    },
    /// Options out of range.
    #[error("{0}")]
    InvalidOptions(String),
    /// Too few data for the free parameters.
    #[error("{residuals} residuals cannot determine {parameters} free parameters")]
    Underdetermined {
        /// Residual count.
        residuals: usize,
        /// Free parameter count.
        parameters: usize,
    },
    /// A capped loop ended without meeting its tolerance (a typed non-convergence).
    #[error("{what} did not converge in {iterations} iterations: {detail}")]
    NotConverged {
        /// Which loop.
        what: String,
        /// Iterations (or panels) used.
        iterations: usize,
        /// Last state against the tolerance.
        detail: String,
    },
}
