//! cutcal_cli: the edge of cutcal. Reads input files into model types, runs the library crates,
//! writes outputs atomically. The `cutcal` binary is a thin wrapper over [`run`].
#![warn(missing_docs)]

pub mod input;
