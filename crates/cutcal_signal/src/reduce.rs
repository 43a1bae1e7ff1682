//! Streaming reduction of a multi-channel signal into a bounded number of equal-length blocks.
//!
//! Every sample updates running sums of the current block; a completed block stores, per channel,
//! its count, mean, centred sum of squares (M2), minimum and maximum. When the store is full,
//! neighbouring blocks are merged pairwise and the block length doubles, so memory is bounded by
//! `max_blocks` whatever the signal length. Block merging uses the pairwise update of Chan, Golub &
//! LeVeque (1979), "Updating formulae and a pairwise algorithm for computing sample variances",
//! Stanford CS report STAN-CS-79-773, which keeps mean and variance exact (no sample is lost).

use crate::error::SignalError;

/// Count, mean and centred sum of squares of a set of samples, merged exactly.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Moments {
    /// Number of samples.
    pub n: u64,
    /// Mean.
    pub mean: f64,
    /// Sum of squared deviations from the mean.
    pub m2: f64,
}

impl Moments {
    /// Merge two sets (Chan, Golub & LeVeque 1979, pairwise update).
    pub fn merge(self, o: Moments) -> Moments {
        if o.n == 0 {
            return self;
        }
        if self.n == 0 {
            return o;
        }
        let n = self.n + o.n;
        let (na, nb, nt) = (self.n as f64, o.n as f64, n as f64);
        let delta = o.mean - self.mean;
        Moments { n, mean: self.mean + delta * nb / nt, m2: self.m2 + o.m2 + delta * delta * na * nb / nt }
    }

    /// Sample standard deviation (n - 1 denominator); `None` below two samples.
    pub fn sd(&self) -> Option<f64> {
        (self.n >= 2).then(|| (self.m2.max(0.0) / (self.n - 1) as f64).sqrt())
    }
}

/// One decimated block of one channel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockStat {
    /// Count, mean and M2 of the finite samples in the block.
    pub moments: Moments,
    /// Smallest sample.
    pub min: f64,
    /// Largest sample.
    pub max: f64,
}

/// Running sums of the block being filled, shifted by its first value against cancellation.
#[derive(Debug, Clone, Copy)]
struct Open {
    shift: f64,
    s1: f64,
    s2: f64,
    min: f64,
    max: f64,
}

impl Open {
    const EMPTY: Open = Open { shift: f64::NAN, s1: 0.0, s2: 0.0, min: f64::INFINITY, max: f64::NEG_INFINITY };

    fn close(&self, n: u64) -> BlockStat {
        if n == 0 {
            return BlockStat { moments: Moments::default(), min: 0.0, max: 0.0 };
        }
        let nf = n as f64;
        let d = self.s1 / nf;
        let m2 = (self.s2 - self.s1 * d).max(0.0);
        BlockStat { moments: Moments { n, mean: self.shift + d, m2 }, min: self.min, max: self.max }
    }
}

/// Streaming reducer: push samples, then read the blocks. Memory is `O(max_blocks x channels)`.
#[derive(Debug, Clone)]
pub struct Reducer {
    channels: usize,
    max_blocks: usize,
    /// Sample positions (finite or dropped) per block.
    block_len: u64,
    /// Completed blocks, `blocks[c][k]`.
    blocks: Vec<Vec<BlockStat>>,
    /// Time of the first sample of each completed block, s.
    block_t0_s: Vec<f64>,
    open: Vec<Open>,
    open_positions: u64,
    open_finite: u64,
    open_t0_s: f64,
    positions: u64,
    dropped: u64,
    first_t_s: f64,
    last_t_s: f64,
}

impl Reducer {
    /// A reducer for `channels` channels keeping at most `max_blocks` blocks (a power of two >= 64).
    pub fn new(channels: usize, max_blocks: usize) -> Result<Self, SignalError> {
        if channels == 0 || channels > 16 {
            return Err(SignalError::Config(format!("channels must be 1..=16, got {channels}")));
        }
        if max_blocks < 64 || !max_blocks.is_power_of_two() {
            return Err(SignalError::Config(format!("max_blocks must be a power of two >= 64, got {max_blocks}")));
        }
        Ok(Reducer {
            channels,
            max_blocks,
            block_len: 1,
            blocks: vec![Vec::with_capacity(max_blocks); channels],
            block_t0_s: Vec::with_capacity(max_blocks),
            open: vec![Open::EMPTY; channels],
            open_positions: 0,
            open_finite: 0,
            open_t0_s: f64::NAN,
            positions: 0,
            dropped: 0,
            first_t_s: f64::NAN,
            last_t_s: f64::NAN,
        })
    }

    /// Add one sample at time `t_s`. A sample with any non-finite channel value is a dropout: it
    /// keeps its time slot but adds nothing to the statistics.
    pub fn push(&mut self, t_s: f64, values: &[f64]) -> Result<(), SignalError> {
        if values.len() != self.channels {
            return Err(SignalError::ChannelCount {
                index: self.positions,
                expected: self.channels,
                got: values.len(),
            });
        }
        if !t_s.is_finite() || (self.positions > 0 && t_s <= self.last_t_s) {
            return Err(SignalError::TimeNotIncreasing {
                index: self.positions,
                time_s: t_s,
                previous_s: self.last_t_s,
            });
        }
        if self.positions == 0 {
            self.first_t_s = t_s;
        }
        if self.open_positions == 0 {
            self.open_t0_s = t_s;
        }
        self.last_t_s = t_s;
        self.positions += 1;
        self.open_positions += 1;
        if values.iter().all(|v| v.is_finite()) {
            for (o, &x) in self.open.iter_mut().zip(values) {
                if self.open_finite == 0 {
                    o.shift = x;
                }
                let d = x - o.shift;
                o.s1 += d;
                o.s2 += d * d;
                o.min = o.min.min(x);
                o.max = o.max.max(x);
            }
            self.open_finite += 1;
        } else {
            self.dropped += 1;
        }
        if self.open_positions == self.block_len {
            self.close_open();
        }
        Ok(())
    }

    fn close_open(&mut self) {
        for c in 0..self.channels {
            let b = self.open[c].close(self.open_finite);
            self.blocks[c].push(b);
            self.open[c] = Open::EMPTY;
        }
        self.block_t0_s.push(self.open_t0_s);
        self.open_positions = 0;
        self.open_finite = 0;
        if self.block_t0_s.len() == self.max_blocks {
            self.halve();
        }
    }

    fn halve(&mut self) {
        for ch in &mut self.blocks {
            let merged: Vec<BlockStat> = ch
                .chunks(2)
                .map(|p| {
                    let (a, b) = (p[0], p[1]);
                    let (min, max) = match (a.moments.n, b.moments.n) {
                        (0, _) => (b.min, b.max),
                        (_, 0) => (a.min, a.max),
                        _ => (a.min.min(b.min), a.max.max(b.max)),
                    };
                    BlockStat { moments: a.moments.merge(b.moments), min, max }
                })
                .collect();
            *ch = merged;
        }
        self.block_t0_s = self.block_t0_s.iter().step_by(2).copied().collect();
        self.block_len *= 2;
    }

    /// Finish: the reduced signal (a partial last block is dropped from the blocks but its samples
    /// are counted; it is at most one block length at the very end of the record).
    pub fn finish(self) -> Result<Reduced, SignalError> {
        let usable = self.positions - self.dropped;
        if self.positions < 2 || self.block_t0_s.len() < 2 {
            return Err(SignalError::TooShort { samples: usable, needed: 128 });
        }
        let span = self.last_t_s - self.first_t_s;
        let sample_rate_hz = (self.positions - 1) as f64 / span;
        Ok(Reduced {
            block_len: self.block_len,
            blocks: self.blocks,
            block_t0_s: self.block_t0_s,
            sample_rate_hz,
            samples: self.positions,
            dropped: self.dropped,
            first_t_s: self.first_t_s,
            last_t_s: self.last_t_s,
        })
    }
}

/// A reduced signal: equal-length blocks per channel with exact moments.
#[derive(Debug, Clone)]
pub struct Reduced {
    /// Sample positions per block.
    pub block_len: u64,
    /// `blocks[channel][k]`.
    pub blocks: Vec<Vec<BlockStat>>,
    /// Start time of each block, s.
    pub block_t0_s: Vec<f64>,
    /// Mean sample rate over the record, Hz.
    pub sample_rate_hz: f64,
    /// Samples pushed (including dropouts).
    pub samples: u64,
    /// Dropout samples (a non-finite channel value).
    pub dropped: u64,
    /// Time of the first sample, s.
    pub first_t_s: f64,
    /// Time of the last sample, s.
    pub last_t_s: f64,
}

impl Reduced {
    /// Reduce a whole iterator of `(t_s, values)` samples.
    pub fn from_samples<I, V>(channels: usize, max_blocks: usize, samples: I) -> Result<Self, SignalError>
    where
        I: IntoIterator<Item = (f64, V)>,
        V: AsRef<[f64]>,
    {
        let mut r = Reducer::new(channels, max_blocks)?;
        for (t, v) in samples {
            r.push(t, v.as_ref())?;
        }
        r.finish()
    }

    /// Number of blocks.
    pub fn len(&self) -> usize {
        self.block_t0_s.len()
    }

    /// True when there are no blocks.
    pub fn is_empty(&self) -> bool {
        self.block_t0_s.is_empty()
    }

    /// Block duration, s.
    pub fn block_duration_s(&self) -> f64 {
        self.block_len as f64 / self.sample_rate_hz
    }

    /// Mid time of block `k`, s.
    pub fn block_mid_s(&self, k: usize) -> f64 {
        self.block_t0_s[k] + 0.5 * (self.block_len as f64 - 1.0) / self.sample_rate_hz
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merged_blocks_keep_exact_moments() {
        // 1000 samples of a known sequence: the merged moments equal the direct two-pass values.
        let xs: Vec<f64> = (0..1000).map(|i| 100.0 + ((i * 37) % 101) as f64 * 0.01).collect();
        let r = Reduced::from_samples(1, 64, xs.iter().enumerate().map(|(i, &x)| (i as f64 * 1e-3, [x]))).unwrap();
        assert_eq!(r.block_len, 16, "1000 samples in at most 64 blocks -> length 16");
        let used = (r.len() as u64 * r.block_len) as usize;
        let m = r.blocks[0].iter().fold(Moments::default(), |a, b| a.merge(b.moments));
        let direct_mean = xs[..used].iter().sum::<f64>() / used as f64;
        let direct_m2: f64 = xs[..used].iter().map(|x| (x - direct_mean).powi(2)).sum();
        assert_eq!(m.n as usize, used);
        assert!((m.mean - direct_mean).abs() < 1e-12);
        assert!((m.m2 - direct_m2).abs() < 1e-9 * direct_m2);
    }

    #[test]
    fn rejects_time_going_back_and_wrong_channel_count() {
        let mut r = Reducer::new(2, 64).unwrap();
        r.push(0.0, &[1.0, 2.0]).unwrap();
        assert!(matches!(r.push(0.0, &[1.0, 2.0]), Err(SignalError::TimeNotIncreasing { index: 1, .. })));
        assert!(matches!(r.push(1.0, &[1.0]), Err(SignalError::ChannelCount { index: 1, .. })));
    }
}
