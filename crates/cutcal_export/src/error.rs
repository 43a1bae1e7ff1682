//! The exporter's error type.

use cutcal_model::ModelError;

/// Why a card could not be rendered. Nothing is ever rendered from invalid or non-finite data.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// The model data (material, JC set, friction) failed its own validation.
    #[error("invalid {what}: {source}")]
    InvalidInput {
        /// Which input (e.g. `workpiece C38`, `jc set`).
        what: String,
        /// The model's reason.
        source: ModelError,
    },
    /// A derived number is NaN or infinite.
    #[error("{field} is not finite ({value}): it would be rendered as garbage")]
    NonFinite {
        /// Where the number goes (context path or field).
        field: String,
        /// The offending value.
        value: f64,
    },
    /// An option is outside its allowed range.
    #[error("option {field} = {value} is invalid: {expected}")]
    BadOption {
        /// The option.
        field: String,
        /// Its value as text.
        value: String,
        /// What is allowed.
        expected: String,
    },
    /// A value a dialect needs is absent (e.g. elastic constants for LS-DYNA).
    #[error("{dialect} needs {what}")]
    Missing {
        /// The dialect.
        dialect: String,
        /// What is missing.
        what: String,
    },
    /// A name or title cannot be written into a card.
    #[error("name {name:?} cannot be written: {reason}")]
    BadName {
        /// The name.
        name: String,
        /// Why.
        reason: String,
    },
    /// The template engine failed (a missing value in strict mode, or a helper error).
    #[error("template {template}: {message}")]
    Template {
        /// The template name.
        template: String,
        /// The engine's message.
        message: String,
    },
    /// Writing the MatML XML failed.
    #[error("matml writer: {0}")]
    Xml(String),
}

impl ExportError {
    /// Wraps a model validation error with what was being validated.
    pub(crate) fn invalid(what: impl Into<String>, source: ModelError) -> Self {
        Self::InvalidInput { what: what.into(), source }
    }

    /// Fails unless `value` is finite.
    pub(crate) fn finite(field: &str, value: f64) -> Result<f64, Self> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(Self::NonFinite { field: field.to_string(), value })
        }
    }
}
