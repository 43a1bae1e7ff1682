//! Error face: sorts an error chain of the library into the Python exception classes, keeping the
//! CLI's message (`cutcal ...` prints `error: {e:#}`; Python raises the text after `error: `).

use cutcal_io::InputError;

/// Which Python exception class an error becomes (all derive from `cutcal.CutcalError`): the
/// report library's own kind (`Input` -> `cutcal.InputError`, `Model` -> `cutcal.ModelError`,
/// `Ident` -> `cutcal.IdentError`, `Export` -> `cutcal.ExportError`, `Diagnose` ->
/// `cutcal.DiagnoseError`, `Other` -> `cutcal.CutcalError`).
pub use cutcal_report::ErrorKind;

/// An error ready for Python: its class and the CLI's message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceError {
    /// The exception class.
    pub kind: ErrorKind,
    /// The message, exactly as the CLI prints it after `error: `.
    pub message: String,
}

impl std::fmt::Display for FaceError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for FaceError {}

/// The kind of one error in a chain, if it is one of the library's typed errors.
fn kind_of(e: &(dyn std::error::Error + 'static)) -> Option<ErrorKind> {
    if let Some(r) = e.downcast_ref::<cutcal_report::Error>() {
        // The report library's error knows its typed cause under any context lines.
        return Some(r.kind()).filter(|k| *k != ErrorKind::Other);
    }
    if e.is::<InputError>() {
        Some(ErrorKind::Input)
    } else if e.is::<cutcal_ident::IdentError>() {
        Some(ErrorKind::Ident)
    } else if e.is::<cutcal_export::ExportError>() {
        Some(ErrorKind::Export)
    } else if e.is::<cutcal_diagnose::DiagnoseError>() {
        Some(ErrorKind::Diagnose)
    } else if e.is::<cutcal_model::ModelError>() {
        Some(ErrorKind::Model)
    } else {
        None
    }
}

/// Classifies an error by the outermost typed error of its chain (an identification that failed
/// because a model solve failed is an `IdentError`; a located reader error is an `InputError`),
/// and keeps the CLI's full message with its context chain.
#[must_use]
pub fn classify(e: &anyhow::Error) -> FaceError {
    let kind = e.chain().find_map(kind_of).unwrap_or(ErrorKind::Other);
    FaceError { kind, message: format!("{e:#}") }
}

/// Shorthand: a library result with its error classified.
pub type FaceResult<T> = Result<T, FaceError>;

/// Converts any error that anyhow accepts into a classified [`FaceError`].
pub fn face<E: Into<anyhow::Error>>(e: E) -> FaceError {
    classify(&e.into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn a_reader_error_keeps_its_location_and_class() {
        let e = cutcal_io::tests_csv::parse_tests(Path::new("t.csv"), "test,speed_m_min\n1,2\n").unwrap_err();
        let f = face(e);
        assert_eq!(f.kind, ErrorKind::Input);
        assert!(f.message.starts_with("t.csv:1: field `uncut_mm`"), "{}", f.message);
    }

    #[test]
    fn context_keeps_the_typed_class_and_the_chain_text() {
        let model = cutcal_model::JcParams::new(-1.0, 1.0, 0.2, 0.01, 1.0, 1.0, 1400.0, 20.0).unwrap_err();
        let e = anyhow::Error::new(model).context("JC set from Python");
        let f = classify(&e);
        assert_eq!(f.kind, ErrorKind::Model);
        assert!(f.message.starts_with("JC set from Python: "), "{}", f.message);
        assert_eq!(classify(&anyhow::anyhow!("plain")).kind, ErrorKind::Other);
    }
}
