//! cutcal_py: the Python face of cutcal (module `cutcal`, an abi3 wheel built by maturin).
//!
//! One library, two thin faces: this crate adds no physics. Each module is an adapter for one
//! face of the Python API that converts types and calls the library (`cutcal_model`,
//! `cutcal_ident`, `cutcal_export`, `cutcal_diagnose`) through the same entry points the CLI uses
//! (`cutcal_io` for files, `cutcal_report` for the work):
//!
//! - [`types`]: `Material`, `JcParams`, `CuttingTest`, `read_tests` (the CLI's readers);
//! - [`identify`]: the DPZD identification of paper Eq 15 (Secs 3-4);
//! - [`joint`]: the joint Oxley identification over every measured test, with its verdict;
//! - [`predict`]: the extended Oxley model (Oxley 1989; Lalwani et al. 2009), per test and vectorised;
//! - [`export`]: FE cards;
//! - [`diagnose`]: discrepancy discovery;
//! - [`errors`]: the error chain sorted into Python exception classes with the CLI's message.
//!
//! The pyo3 glue (`python`, feature `python`) is compiled only by maturin, so that
//! `cargo test --workspace` needs no Python headers; the adapters are tested here in Rust and the
//! module end to end by `tests/python/` (pytest, run by `tests/pytest.rs`).
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]

pub mod diagnose;
pub mod errors;
pub mod export;
pub mod identify;
pub mod joint;
pub mod predict;
pub mod types;

#[cfg(feature = "python")]
mod python;
