//! Streaming reduction of dynamometer force recordings into cutting-test rows.
//!
//! Data flow: samples `(t, [fc, ft, fp])` are pushed one at a time into a [`Reducer`] (memory bounded
//! by its block count, independent of the record length), which yields a [`Reduced`] signal of
//! equal-length blocks with exact moments. [`analyse`] then finds the steady-cutting window on the
//! cutting-force envelope (or takes a given one), and reports per channel the mean, standard
//! deviation, autocorrelation-aware standard error, drift with its significance, and the dominant
//! oscillation, with the flags "possible tool wear" and "possible built-up edge". No file I/O here:
//! the CLI reads files and feeds the reducer. See docs/recordings.md for the methods and sources.
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]
// `!(x > 0.0)` is how the reducer rejects NaN together with the out-of-range values: kept.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod analyse;
mod error;
mod reduce;
pub mod spectrum;
pub mod stats;
pub mod synthetic;
pub mod window;

pub use analyse::{analyse, Analysis, AnalysisConfig, ChannelStats};
pub use error::SignalError;
pub use reduce::{BlockStat, Moments, Reduced, Reducer};

/// Default number of blocks kept by the reducer: 65536 x 3 channels x 32 bytes = 6 MB.
pub const DEFAULT_MAX_BLOCKS: usize = 1 << 16;
