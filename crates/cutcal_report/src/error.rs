//! The typed error of the report library: every library error it passes on (located input
//! errors, output, model, identification, export, diagnosis), a refused request with its reason,
//! and a context line wrapped around an error, so that the CLI prints the same chain
//! (`context: cause: ...`) it printed when the chain was built with `anyhow`.
//!
//! The wrapped library errors are `transparent`: their text and their own source chain are kept,
//! and [`Error::kind`] tells a caller (the Python module) which library refused the work.

use std::fmt::Display;

/// An error of the report library.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A located input error (file, line, field, value, reason).
    #[error(transparent)]
    Input(#[from] cutcal_io::InputError),
    /// An output file or directory could not be written.
    #[error(transparent)]
    Output(#[from] cutcal_io::output::OutputError),
    /// The physics refused a value or a model solve failed.
    #[error(transparent)]
    Model(#[from] cutcal_model::ModelError),
    /// An identification failed (fit, multistart, bootstrap, zone thickness).
    #[error(transparent)]
    Ident(#[from] cutcal_ident::IdentError),
    /// A card could not be rendered.
    #[error(transparent)]
    Export(#[from] cutcal_export::ExportError),
    /// The diagnosis failed.
    #[error(transparent)]
    Diagnose(#[from] cutcal_diagnose::DiagnoseError),
    /// JSON serialisation failed.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    /// TOML serialisation failed.
    #[error(transparent)]
    Toml(#[from] toml::ser::Error),
    /// CSV reading or writing failed.
    #[error(transparent)]
    Csv(#[from] csv::Error),
    /// Text formatting failed.
    #[error(transparent)]
    Fmt(#[from] std::fmt::Error),
    /// Text was not UTF-8.
    #[error(transparent)]
    Utf8(#[from] std::string::FromUtf8Error),
    /// A number could not be parsed.
    #[error(transparent)]
    Number(#[from] std::num::ParseFloatError),
    /// A file could not be read.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// A request refused by the library (an option out of range, a missing section), with why.
    #[error("{0}")]
    Invalid(String),
    /// What was being done when `source` failed.
    #[error("{context}")]
    Context {
        /// The context line.
        context: String,
        /// The error it wraps.
        #[source]
        source: Box<Error>,
    },
}

/// Result of the report library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Which library an error comes from (the outermost typed cause under any context lines).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// Input files and values ([`Error::Input`]).
    Input,
    /// The model ([`Error::Model`]).
    Model,
    /// The identification ([`Error::Ident`]).
    Ident,
    /// The exporters ([`Error::Export`]).
    Export,
    /// The diagnosis ([`Error::Diagnose`]).
    Diagnose,
    /// Anything else (a refused request, output, serialisation).
    Other,
}

impl Error {
    /// A refused request with its reason.
    pub fn invalid(reason: impl Display) -> Self {
        Self::Invalid(reason.to_string())
    }

    /// The kind of the outermost typed cause, looking through context lines.
    #[must_use]
    pub fn kind(&self) -> ErrorKind {
        match self {
            Self::Context { source, .. } => source.kind(),
            Self::Input(_) => ErrorKind::Input,
            Self::Model(_) => ErrorKind::Model,
            Self::Ident(_) => ErrorKind::Ident,
            Self::Export(_) => ErrorKind::Export,
            Self::Diagnose(_) => ErrorKind::Diagnose,
            _ => ErrorKind::Other,
        }
    }

    /// The whole chain as one line, `context: cause: ...` (what `anyhow` prints with `{:#}`).
    #[must_use]
    pub fn chain_text(&self) -> String {
        let mut s = self.to_string();
        let mut cur: Option<&(dyn std::error::Error + 'static)> = std::error::Error::source(self);
        while let Some(e) = cur {
            s.push_str(": ");
            s.push_str(&e.to_string());
            cur = e.source();
        }
        s
    }
}

/// Adds a context line to an error (or turns a missing value into an error), as `anyhow` does.
pub trait Context<T> {
    /// Wraps the error with `context`.
    fn context<C: Display>(self, context: C) -> Result<T>;
    /// Wraps the error with the context `f` returns (evaluated only on error).
    fn with_context<C: Display, F: FnOnce() -> C>(self, f: F) -> Result<T>;
}

impl<T, E: Into<Error>> Context<T> for std::result::Result<T, E> {
    fn context<C: Display>(self, context: C) -> Result<T> {
        self.map_err(|e| Error::Context { context: context.to_string(), source: Box::new(e.into()) })
    }

    fn with_context<C: Display, F: FnOnce() -> C>(self, f: F) -> Result<T> {
        self.map_err(|e| Error::Context { context: f().to_string(), source: Box::new(e.into()) })
    }
}

impl<T> Context<T> for Option<T> {
    fn context<C: Display>(self, context: C) -> Result<T> {
        self.ok_or_else(|| Error::Invalid(context.to_string()))
    }

    fn with_context<C: Display, F: FnOnce() -> C>(self, f: F) -> Result<T> {
        self.ok_or_else(|| Error::Invalid(f().to_string()))
    }
}

/// Returns early with [`Error::Invalid`] and a formatted reason (the library's `bail!`).
#[macro_export]
macro_rules! bail {
    ($($arg:tt)*) => {
        return Err($crate::Error::Invalid(format!($($arg)*)))
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn context_keeps_the_chain_text_and_the_kind() {
        let model = cutcal_model::JcParams::new(-1.0, 1.0, 0.2, 0.01, 1.0, 1.0, 1400.0, 20.0).unwrap_err();
        let plain = model.to_string();
        let e = Err::<(), _>(model).context("JC set").context("project x").unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Model);
        assert_eq!(e.chain_text(), format!("project x: JC set: {plain}"));
        let none = None::<u8>.context("no [dpzd] section").unwrap_err();
        assert_eq!((none.kind(), none.chain_text().as_str()), (ErrorKind::Other, "no [dpzd] section"));
    }
}
