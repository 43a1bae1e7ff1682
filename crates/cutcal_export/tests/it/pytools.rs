//! The Python interpreter of the third-party readers (`ansys-materials-manager`, `ansys-dyna-core`):
//! `CUTCAL_PYTHON` (exported by `.ci/run`), else the workspace's `target/py-venv/bin/python`.
//! A test whose package is missing skips with a message, unless `CUTCAL_REQUIRE_TOOLS=1` (CI),
//! where it fails.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// True when a missing tool must fail the test (CI).
pub fn required() -> bool {
    std::env::var("CUTCAL_REQUIRE_TOOLS").is_ok_and(|v| v == "1")
}

/// An interpreter that imports `module`, or `None` (after a message) when the test may skip.
///
/// # Panics
/// When no such interpreter exists and [`required`] is true.
pub fn python_with(module: &str, pip_names: &str) -> Option<PathBuf> {
    let py = std::env::var_os("CUTCAL_PYTHON").map_or_else(|| root().join("target/py-venv/bin/python"), PathBuf::from);
    let ok = py.exists()
        && Command::new(&py).args(["-c", &format!("import {module}")]).output().is_ok_and(|o| o.status.success());
    if ok {
        return Some(py);
    }
    let msg = format!(
        "{} cannot import {module}: `pip install {pip_names}` into the venv of .ci/run (target/py-venv) \
         or set CUTCAL_PYTHON",
        py.display()
    );
    assert!(!required(), "{msg} (CUTCAL_REQUIRE_TOOLS=1)");
    eprintln!("skipped: {msg}");
    None
}
