//! The one error type of the signal crate: every variant says what was wrong and where.

/// Errors of the streaming reduction and the analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SignalError {
    /// A sample has a different number of channels than the reducer was built for.
    #[error("sample {index}: expected {expected} channel value(s), got {got}")]
    ChannelCount {
        /// Zero-based sample index.
        index: u64,
        /// Channels the reducer expects.
        expected: usize,
        /// Channels in the sample.
        got: usize,
    },
    /// The time stamps do not increase strictly (or are not finite).
    #[error("sample {index}: time {time_s} s does not increase after the previous sample ({previous_s} s)")]
    TimeNotIncreasing {
        /// Zero-based sample index.
        index: u64,
        /// The offending time stamp, s.
        time_s: f64,
        /// The previous time stamp, s.
        previous_s: f64,
    },
    /// A configuration value is out of its range.
    #[error("signal configuration: {0}")]
    Config(String),
    /// Too few samples to analyse.
    #[error("the signal has {samples} usable sample(s); at least {needed} are needed")]
    TooShort {
        /// Usable samples.
        samples: u64,
        /// Minimum needed.
        needed: u64,
    },
    /// No cutting (a force plateau clearly above zero) was found.
    #[error("no steady cut found: {0}")]
    NoCut(String),
    /// The steady window is too short for the statistics.
    #[error("the steady-cutting window {t0_s:.4} s .. {t1_s:.4} s holds {blocks} block(s); at least {needed} are needed ({why})")]
    WindowTooShort {
        /// Window start, s.
        t0_s: f64,
        /// Window end, s.
        t1_s: f64,
        /// Decimated blocks in the window.
        blocks: usize,
        /// Minimum needed.
        needed: usize,
        /// Why the window is short.
        why: String,
    },
}
