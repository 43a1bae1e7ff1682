//! The pyo3 glue of module `cutcal._cutcal` (feature `python`, built by maturin): exception
//! classes, the error mapping and the module table. The classes are in `classes`, the functions in
//! `functions`; both only convert between Python and the adapters of this crate.

mod classes;
mod functions;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use crate::errors::{ErrorKind, FaceError};

create_exception!(cutcal, CutcalError, PyException, "Base class of every cutcal error.");
create_exception!(
    cutcal,
    InputError,
    CutcalError,
    "A file or value is malformed or out of range; the message names the file, line, field and value."
);
create_exception!(cutcal, ModelError, CutcalError, "The physics refused a state or a model solve failed.");
create_exception!(cutcal, IdentError, CutcalError, "The identification (paper Eq 15 fit) failed.");
create_exception!(cutcal, ExportError, CutcalError, "An FE card could not be rendered or written.");
create_exception!(cutcal, DiagnoseError, CutcalError, "The discrepancy diagnosis failed.");

/// The Python exception of a classified error, carrying the CLI's message.
pub(crate) fn to_py(e: FaceError) -> PyErr {
    match e.kind {
        ErrorKind::Input => InputError::new_err(e.message),
        ErrorKind::Model => ModelError::new_err(e.message),
        ErrorKind::Ident => IdentError::new_err(e.message),
        ErrorKind::Export => ExportError::new_err(e.message),
        ErrorKind::Diagnose => DiagnoseError::new_err(e.message),
        ErrorKind::Other => CutcalError::new_err(e.message),
    }
}

/// Parses a JSON document produced by the library into Python objects (`json.loads`).
pub(crate) fn json_to_py<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// The native module `cutcal._cutcal`; the package `cutcal` re-exports it.
#[pymodule]
fn _cutcal(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("CutcalError", py.get_type::<CutcalError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("ModelError", py.get_type::<ModelError>())?;
    m.add("IdentError", py.get_type::<IdentError>())?;
    m.add("ExportError", py.get_type::<ExportError>())?;
    m.add("DiagnoseError", py.get_type::<DiagnoseError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    classes::register(m)?;
    functions::register(m)?;
    Ok(())
}
