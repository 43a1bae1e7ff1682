//! Per-channel statistics over the steady window and the wear / built-up-edge flags.

use serde::Serialize;

use crate::error::SignalError;
use crate::reduce::{Moments, Reduced};
use crate::spectrum::{self, Peak};
use crate::stats::{integrated_autocorrelation_time, trend};
use crate::window::{self, BlockWindow, WindowConfig};

/// Settings of the analysis, with documented defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisConfig {
    /// Window search tuning.
    pub window: WindowConfig,
    /// Channel whose envelope defines the window (the cutting force).
    pub window_channel: usize,
    /// Drift is significant when |z| exceeds this (3.29: two-sided p = 0.001) ...
    pub drift_z: f64,
    /// ... and the change across the window exceeds this fraction of the mean.
    pub drift_min_relative: f64,
    /// An oscillation is strong when its amplitude exceeds this fraction of the mean ...
    pub oscillation_min_relative: f64,
    /// ... and its line stands this many times above the median of the band.
    pub oscillation_min_prominence: f64,
    /// Oscillations at or below this frequency count as low-frequency (built-up edge), Hz.
    pub bue_max_hz: f64,
    /// Cycles the window must hold for a line to count as an oscillation (not a drift).
    pub min_cycles: f64,
}

impl Default for AnalysisConfig {
    fn default() -> Self {
        AnalysisConfig {
            window: WindowConfig::default(),
            window_channel: 0,
            drift_z: 3.29,
            drift_min_relative: 0.02,
            oscillation_min_relative: 0.03,
            oscillation_min_prominence: 8.0,
            bue_max_hz: 500.0,
            min_cycles: 3.0,
        }
    }
}

/// Statistics of one channel over the window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChannelStats {
    /// Mean over the window.
    pub mean: f64,
    /// Sample standard deviation of the samples in the window.
    pub sd: f64,
    /// Standard error of the mean with the autocorrelation taken into account.
    pub se: f64,
    /// Effective sample size `sd^2 / se^2`.
    pub effective_samples: f64,
    /// Integrated autocorrelation time of the batch means.
    pub batch_tau: f64,
    /// Drift slope across the window, units per second.
    pub drift_per_s: f64,
    /// Drift test statistic (slope over its autocorrelation-corrected standard error).
    pub drift_z: f64,
    /// Change across the window over the mean: `drift_per_s * duration / mean`.
    pub drift_relative: f64,
    /// Significant drift by both tests of [`AnalysisConfig`].
    pub drift_significant: bool,
    /// Dominant oscillation frequency, Hz (`None` when the window holds no resolvable band).
    pub oscillation_hz: Option<f64>,
    /// Its amplitude (half peak-to-peak), same unit as the channel.
    pub oscillation_amplitude: Option<f64>,
    /// Its prominence over the band's median.
    pub oscillation_prominence: Option<f64>,
    /// Strong oscillation at a low frequency (possible built-up edge).
    pub oscillation_strong: bool,
}

/// The result of analysing one recording.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Analysis {
    /// Window start, s.
    pub t0_s: f64,
    /// Window end, s.
    pub t1_s: f64,
    /// True when the window was given by the user, not detected.
    pub window_given: bool,
    /// Samples used in the window.
    pub samples_used: u64,
    /// Dropout samples in the whole record.
    pub samples_dropped: u64,
    /// Mean sample rate, Hz.
    pub sample_rate_hz: f64,
    /// Decimated block length, samples.
    pub block_len: u64,
    /// Highest oscillation frequency resolvable on the blocks, Hz.
    pub max_resolvable_hz: f64,
    /// Per channel statistics.
    pub channels: Vec<ChannelStats>,
    /// Significant drift on the window channel: possible tool wear.
    pub possible_tool_wear: bool,
    /// Strong low-frequency oscillation on the window channel: possible built-up edge.
    pub possible_built_up_edge: bool,
}

/// Analyse a reduced signal; `given` overrides the detected window with `[t0, t1]` seconds.
pub fn analyse(r: &Reduced, cfg: &AnalysisConfig, given: Option<(f64, f64)>) -> Result<Analysis, SignalError> {
    let ch = cfg.window_channel;
    if ch >= r.blocks.len() {
        return Err(SignalError::Config(format!("window channel {ch} is not among {} channel(s)", r.blocks.len())));
    }
    let finite: Vec<bool> = r.blocks[ch].iter().map(|b| b.moments.n > 0).collect();
    let w = match given {
        Some((t0, t1)) => {
            if !(t1 > t0) {
                return Err(SignalError::Config(format!("window {t0} s .. {t1} s is empty")));
            }
            let start = r.block_t0_s.iter().position(|&t| t >= t0).unwrap_or(r.len());
            let end =
                r.block_t0_s.iter().rposition(|&t| t + r.block_duration_s() <= t1 * (1.0 + 1e-12)).map_or(0, |k| k + 1);
            if end < start + 8 {
                return Err(SignalError::WindowTooShort {
                    t0_s: t0,
                    t1_s: t1,
                    blocks: end.saturating_sub(start),
                    needed: 8,
                    why: format!("the record spans {:.4} s .. {:.4} s", r.first_t_s, r.last_t_s),
                });
            }
            BlockWindow { start, end, use_block: finite[start..end].to_vec(), level: 0.0 }
        }
        None => window::detect(&r.blocks[ch].iter().map(|b| b.moments.mean).collect::<Vec<_>>(), &finite, &cfg.window)?,
    };
    let t0_s = r.block_t0_s[w.start];
    let t1_s = r.block_t0_s[w.end - 1] + r.block_duration_s();
    let idx: Vec<usize> = (w.start..w.end).filter(|&k| w.use_block[k - w.start] && finite[k]).collect();
    if idx.len() < 8 {
        return Err(SignalError::WindowTooShort {
            t0_s,
            t1_s,
            blocks: idx.len(),
            needed: 8,
            why: "too few blocks with samples".into(),
        });
    }
    let block_rate = 1.0 / r.block_duration_s();
    let duration = t1_s - t0_s;
    let max_resolvable_hz = 0.45 * block_rate;
    let channels =
        (0..r.blocks.len()).map(|c| channel_stats(r, c, &w, &idx, cfg, duration, block_rate)).collect::<Vec<_>>();
    let samples_used = idx.iter().map(|&k| r.blocks[ch][k].moments.n).sum();
    let main = channels[ch];
    Ok(Analysis {
        t0_s,
        t1_s,
        window_given: given.is_some(),
        samples_used,
        samples_dropped: r.dropped,
        sample_rate_hz: r.sample_rate_hz,
        block_len: r.block_len,
        max_resolvable_hz,
        possible_tool_wear: main.drift_significant,
        possible_built_up_edge: main.oscillation_strong,
        channels,
    })
}

fn channel_stats(
    r: &Reduced,
    c: usize,
    w: &BlockWindow,
    idx: &[usize],
    cfg: &AnalysisConfig,
    duration: f64,
    block_rate: f64,
) -> ChannelStats {
    let blocks = &r.blocks[c];
    let total = idx.iter().fold(Moments::default(), |a, &k| a.merge(blocks[k].moments));
    let sd = total.sd().unwrap_or(0.0);
    // Batch means: consecutive used blocks grouped so that at most 1024 batches remain.
    let g = idx.len().div_ceil(1024).max(1);
    let mut bt = Vec::new();
    let mut by = Vec::new();
    for chunk in idx.chunks(g) {
        let m = chunk.iter().fold(Moments::default(), |a, &k| a.merge(blocks[k].moments));
        let t = chunk.iter().map(|&k| r.block_mid_s(k)).sum::<f64>() / chunk.len() as f64;
        bt.push(t);
        by.push(m.mean);
    }
    let nb = by.len() as f64;
    let bmean = by.iter().sum::<f64>() / nb;
    let bvar = by.iter().map(|v| (v - bmean).powi(2)).sum::<f64>() / (nb - 1.0).max(1.0);
    let tau = integrated_autocorrelation_time(&by);
    // Var(grand mean) = Var(batch mean) * tau / batches (batch means, e.g. Flegal & Jones 2010).
    let iid_se = sd / (total.n as f64).sqrt();
    let se = (bvar * tau / nb).sqrt().max(iid_se);
    let effective_samples = if se > 0.0 { (sd / se).powi(2) } else { total.n as f64 };
    let tr = trend(&bt, &by);
    let (drift_per_s, drift_z) = tr.map_or((0.0, 0.0), |t| (t.slope, t.z));
    let drift_relative = if total.mean.abs() > 0.0 { drift_per_s * duration / total.mean.abs() } else { 0.0 };
    let drift_significant = drift_z.abs() > cfg.drift_z && drift_relative.abs() > cfg.drift_min_relative;
    // Oscillation on the detrended block means (excluded blocks set to the trend).
    let slope = tr.map_or(0.0, |t| t.slope);
    let tmid = bt.iter().sum::<f64>() / nb;
    let res: Vec<f64> = (w.start..w.end)
        .map(|k| {
            let fit = bmean + slope * (r.block_mid_s(k) - tmid);
            if w.use_block[k - w.start] && blocks[k].moments.n > 0 {
                blocks[k].moments.mean - fit
            } else {
                0.0
            }
        })
        .collect();
    let f_lo = cfg.min_cycles / duration.max(f64::MIN_POSITIVE);
    let peak: Option<Peak> = spectrum::dominant(&res, block_rate, f_lo, 0.45 * block_rate).map(|p| {
        // Block averaging attenuates a line at f by sinc(f / block_rate): undo it.
        let x = std::f64::consts::PI * p.frequency_hz / block_rate;
        let gain = if x > 0.0 { x.sin() / x } else { 1.0 };
        Peak { amplitude: p.amplitude / gain, ..p }
    });
    let oscillation_strong = peak.is_some_and(|p| {
        p.frequency_hz <= cfg.bue_max_hz
            && p.amplitude > cfg.oscillation_min_relative * total.mean.abs()
            && p.prominence > cfg.oscillation_min_prominence
    });
    ChannelStats {
        mean: total.mean,
        sd,
        se,
        effective_samples,
        batch_tau: tau,
        drift_per_s,
        drift_z,
        drift_relative,
        drift_significant,
        oscillation_hz: peak.map(|p| p.frequency_hz),
        oscillation_amplitude: peak.map(|p| p.amplitude),
        oscillation_prominence: peak.map(|p| p.prominence.min(1e12)),
        oscillation_strong,
    }
}
