//! cutcal_report: the work behind cutcal's two faces (the `cutcal` CLI and the Python module), as
//! a library. Each face only parses its arguments, calls a function here and prints or converts
//! the result, so that both compute the same thing:
//!
//! - one DPZD identification (paper Eq 15): [`dpzd`] (settings, h from the forward model, the
//!   h-sensitivity table, the JSON report), [`dpzd_report`] (table, zone fields, JC file),
//!   [`bootstrap`] (Monte-Carlo spread), [`identify`] (the command's request and entry point);
//! - the joint Oxley identification over every measured test: [`joint`];
//! - predictions with the extended Oxley model: [`predict`], [`predict_rows`] (rows, JSON, table);
//! - FE cards: [`export`]; the discrepancy diagnosis: [`diagnose`]; raw force signals:
//!   [`recordings`];
//! - `cutcal run PROJECT.toml` as named stages: [`project`] (the project file and its
//!   `[[compare]]`/`[fe_check]` data), [`stages`] and [`stages_downstream`] (read inputs,
//!   identify, compare, choose the JC set, cards, predict, joint, diagnose, report),
//!   [`run_steps`] (signals and diagnosis steps), [`project_report`] (JSON and markdown);
//! - SVG plots: [`svg`], [`plots`].
//!
//! Errors are typed ([`Error`]); the library never prints: long work reports through
//! [`Progress`], which the CLI draws on stderr.
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]
#![warn(missing_docs)]

pub mod bootstrap;
pub mod diagnose;
mod diagnose_mode_a;
pub mod dpzd;
pub mod dpzd_report;
pub mod error;
pub mod export;
pub mod identify;
pub mod joint;
pub mod plots;
pub mod predict;
pub mod predict_rows;
pub mod project;
pub mod project_report;
pub mod recordings;
pub mod run_steps;
pub mod stages;
pub mod stages_downstream;
pub mod svg;

pub use error::{Context, Error, ErrorKind, Result};

/// Progress of long work, reported to the caller (the CLI draws it on stderr; a library user may
/// ignore it with [`Quiet`]).
pub trait Progress {
    /// A stage of the project `material` starts or ends, e.g. `rendering FE cards`.
    fn stage(&self, _material: &str, _message: &str) {}
    /// `done` of `total` items of the batch `what` (e.g. signal files reduced).
    fn items(&self, _what: &str, _done: usize, _total: usize) {}
}

/// No progress reports.
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl Progress for Quiet {}
