//! cutcal_model: the physics of orthogonal cutting used by cutcal. No file I/O.
//!
//! Principal types:
//! - [`Material`] with the temperature-dependent properties of the paper's Table 3 ([`TempPolynomial`]),
//! - [`JcParams`], the Johnson-Cook flow stress (paper Eqs 14, 16),
//! - [`CuttingTest`], conditions and measurements of one orthogonal test,
//! - [`dpzd`], the distributed primary zone deformation model, original and enhanced (paper Sec 3),
//!   returning a [`dpzd::ZoneSolution`].
//!
//! Data flow: fixtures (read by the CLI) -> `Material`, `CuttingTest` -> `dpzd::solve` ->
//! `ZoneSolution` -> identification (crate `cutcal_ident`).
//!
//! Units: SI inside (Pa, m, s, J), temperatures in degC.
//!
//! ```text
//! sigma = (A + B eps^n)(1 + C ln(epsdot/eps0)) (1 - ((T - Tr)/(Tm - Tr))^m)      (Eq 16, Eq 14)
//! ```
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]
#![warn(missing_docs)]
// `!(x > 0.0)` is how the solvers reject NaN together with the out-of-range values: kept.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod cutting_test;
pub mod dpzd;
pub mod error;
pub(crate) mod heating;
pub mod jc;
pub mod kinematics;
pub mod material;
pub mod oxley;
pub mod poly;
pub mod reference;

pub use cutting_test::{CuttingTest, Measured, MeasuredSd};
pub use error::ModelError;
pub use jc::{JcParams, RateTerm};
pub use material::{Elastic, Friction, Interface, Material, ThermalProperties, YieldStrengthDefect};
pub use poly::TempPolynomial;
