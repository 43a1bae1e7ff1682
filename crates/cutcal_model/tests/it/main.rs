//! Integration tests of cutcal_model (one binary): each module checks one published or derived claim.
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

// Shared fixtures in code (the model crate does no file I/O): AISI 1045 and AA6082 data.
mod support;
// Extended Oxley vs Lalwani et al. 2009 on the four AISI 1045 cases (Ivester et al. 2000).
mod oxley_lalwani;
// Convergence map over >= 1000 conditions per material: converged share, typed errors, no NaN.
mod oxley_convergence;
// Property tests: Fc rises with t1, phi rises with rake, equilibrium recomputed from the outputs.
mod oxley_props;
// Edge ploughing (Waldorf et al. 1998) and wear land (Smithey et al. 2001) inside a prediction.
mod oxley_edge;
// Every output against the independent implementation pantale/OxleyPython (fixture with its command).
mod oxley_reference;
mod oxley_scan_density;
// The fast solve path against the stored predictions of the previous solver.
mod oxley_fast_path;
