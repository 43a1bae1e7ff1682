//! Integration tests of cutcal_model (one binary): each module checks one published or derived claim.

// Shared fixtures in code (the model crate does no file I/O): AISI 1045 and AA6082 data.
mod support;
// Extended Oxley vs Lalwani et al. 2009 on the four AISI 1045 cases (Ivester et al. 2000).
mod oxley_lalwani;
