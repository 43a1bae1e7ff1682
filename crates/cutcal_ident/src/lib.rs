//! cutcal_ident: Johnson-Cook parameter identification. No file I/O.
//!
//! - [`lm`]: a bounded Levenberg-Marquardt solver on nalgebra (why our own: see the module);
//! - [`multistart`]: seeded Latin-hypercube multistart and fit statistics (covariance, correlation,
//!   parameters at bounds);
//! - [`zone_problem`]: the Eq 15 least-squares problem over a set of zone points;
//! - [`dpzd_fit`]: the paper's Eq 15 identification from one DPZD zone solution;
//! - [`varpro`]: the same objective with A and B eliminated (variable projection), the fast path
//!   of [`dpzd_fit::identify`];
//! - [`zone_rule`]: the adaptive Gauss-Kronrod rule of that integral ([`gauss_kronrod`] on each
//!   panel), started at the integrand's breakpoints;
//! - [`quadrature`]: the Eq 15 objective as a zone integral and the `converged` identification;
//! - [`joint`]: JC fitted jointly to several tests through the extended Oxley model, with
//!   [`literature`] boxes for n, C and m and an [`identifiability`] verdict;
//! - [`zone_thickness`]: the zone thickness h = l_AB / C0 of the forward model, made
//!   self-consistent with the identified set;
//! - [`bootstrap`]: parameter uncertainty by resampling the measurements (parallel, deterministic);
//! - [`monte_carlo`]: its per-sample identification, warm-started from the nominal fit.
//!
//! Data flow: `cutcal_model::dpzd::ZoneSolution` -> [`dpzd_fit::identify_from_zone`] ->
//! [`dpzd_fit::JcIdentification`].
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]
#![warn(missing_docs)]
// `!(x > 0.0)` is how the solvers reject NaN together with the out-of-range values: kept.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bootstrap;
pub mod dpzd_fit;
pub mod error;
pub mod fit_stats;
pub mod gauss_kronrod;
pub mod identifiability;
pub mod joint;
pub mod literature;
pub mod lm;
pub mod monte_carlo;
pub mod multistart;
pub mod quadrature;
pub mod start_filter;
pub mod stats;
pub mod varpro;
pub mod zone_problem;
pub mod zone_rule;
pub mod zone_thickness;

pub use dpzd_fit::{identify_from_zone, identify_from_zone_with, JcBounds, JcConstants, JcIdentification};
pub use error::IdentError;
pub use lm::{Bounds, LmOptions, Problem};
pub use multistart::{FitStatistics, MultistartOptions};
pub use quadrature::{identify_converged, ConvergedIdentification, ConvergedOptions};
