//! cutcal_diagnose: discrepancy discovery between a simulation and cutting recordings. No file I/O.
//!
//! Locate the mismatch, name the physics that was left out, model it, refit jointly with the
//! baseline parameters and show the fit improve on held-out conditions, with a calibrated
//! false-positive rate (design note `discrepancy-discovery.md`, Sec 3).
#![warn(missing_docs)]
// Unit tests compare bit-identical results on purpose (round trips, held values).
#![cfg_attr(test, allow(clippy::float_cmp))]

pub mod classes;
mod context;
pub mod error;
pub mod far;
pub mod fit;
mod ftest;
mod heldout;
pub mod hooks;
mod instrument;
pub mod noise;
pub mod nuisance;
pub mod null;
pub mod shadow;
pub mod spline;
/// The statistics kernel lives in `cutcal_ident` (the joint fit uses it too).
pub use cutcal_ident::stats;

pub use error::DiagnoseError;
pub mod detect;
pub mod diagnose;
mod locate;
pub mod mechanism;
mod narrative;
mod next_test;
mod problem;
pub use problem::condition_groups;
pub mod report;
mod screen;
mod separate;
pub mod simulator;
mod verdict;

pub use diagnose::{diagnose, Config};
pub use mechanism::MechanismId;
pub use report::{Report, Verdict};
pub use shadow::ShadowSimulation;
pub use simulator::{FixedSimulation, OxleySimulator, Prediction, Simulator};
