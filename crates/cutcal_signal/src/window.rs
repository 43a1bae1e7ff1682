//! Steady-cutting window on the decimated cutting-force envelope.
//!
//! 1. Cutting blocks: the plateau level `L` is the median of the block means above half the 98th
//!    percentile of `|mean|`; blocks with `|mean| > L / 2` are cutting. Gaps (dropouts, non-cutting
//!    blocks) of at most `max_gap_fraction` of the record inside a cut are bridged and their blocks,
//!    with one neighbour each side, excluded from the statistics; the longest cut is kept.
//! 2. Transients: on each end of the cut, a two-phase regression change point (Hinkley 1969,
//!    "Inference about the intersection in two-phase regression", Biometrika 56(3):495-504) is
//!    searched in the outer 40 % and accepted by the Schwarz (1978) information criterion with the
//!    sample size reduced to its AR(1) effective value; the window starts/ends at the accepted change
//!    point plus a margin of `margin_fraction` of the cut. A line (not a constant) is fitted on
//!    each side so that a wear drift across the steady part is not mistaken for a transient.

use crate::error::SignalError;

/// Tuning of the window search (fractions of the record or of the cut).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowConfig {
    /// Longest gap bridged inside one cut, as a fraction of the record's blocks.
    pub max_gap_fraction: f64,
    /// Margin added inside each detected change point, as a fraction of the cut's blocks.
    pub margin_fraction: f64,
}

impl Default for WindowConfig {
    fn default() -> Self {
        WindowConfig { max_gap_fraction: 0.02, margin_fraction: 0.02 }
    }
}

/// The detected window in block indices `[start, end)` and the blocks inside it to use.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockWindow {
    /// First block of the window.
    pub start: usize,
    /// One past the last block.
    pub end: usize,
    /// `use_block[k - start]`: false for dropout/gap blocks inside the window.
    pub use_block: Vec<bool>,
    /// Plateau level of the cutting channel (block-mean units).
    pub level: f64,
}

/// Prefix sums for least-squares lines over index ranges, skipping excluded blocks.
struct Prefix {
    n: Vec<f64>,
    x: Vec<f64>,
    xx: Vec<f64>,
    y: Vec<f64>,
    xy: Vec<f64>,
    yy: Vec<f64>,
}

impl Prefix {
    fn new(y: &[f64], used: &[bool], centre: f64) -> Prefix {
        let len = y.len() + 1;
        let mut p = Prefix {
            n: vec![0.0; len],
            x: vec![0.0; len],
            xx: vec![0.0; len],
            y: vec![0.0; len],
            xy: vec![0.0; len],
            yy: vec![0.0; len],
        };
        for (k, (&v, &u)) in y.iter().zip(used).enumerate() {
            let w = if u { 1.0 } else { 0.0 };
            let (x, v) = (k as f64, v - centre);
            p.n[k + 1] = p.n[k] + w;
            p.x[k + 1] = p.x[k] + w * x;
            p.xx[k + 1] = p.xx[k] + w * x * x;
            p.y[k + 1] = p.y[k] + w * v;
            p.xy[k + 1] = p.xy[k] + w * x * v;
            p.yy[k + 1] = p.yy[k] + w * v * v;
        }
        p
    }

    /// Residual sum of squares of the least-squares line over `[a, b)`.
    fn sse(&self, a: usize, b: usize) -> f64 {
        let n = self.n[b] - self.n[a];
        if n < 3.0 {
            return 0.0;
        }
        let sx = self.x[b] - self.x[a];
        let sy = self.y[b] - self.y[a];
        let sxx = self.xx[b] - self.xx[a] - sx * sx / n;
        let sxy = self.xy[b] - self.xy[a] - sx * sy / n;
        let syy = self.yy[b] - self.yy[a] - sy * sy / n;
        if sxx <= 0.0 {
            return syy.max(0.0);
        }
        (syy - sxy * sxy / sxx).max(0.0)
    }

    fn line(&self, a: usize, b: usize) -> (f64, f64) {
        let n = (self.n[b] - self.n[a]).max(1.0);
        let sx = self.x[b] - self.x[a];
        let sy = self.y[b] - self.y[a];
        let sxx = self.xx[b] - self.xx[a] - sx * sx / n;
        let sxy = self.xy[b] - self.xy[a] - sx * sy / n;
        let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
        (sy / n - slope * sx / n, slope)
    }
}

/// Lag-1 autocorrelation of the residuals of lines on `[a, c)` and `[c, b)`.
fn residual_rho1(y: &[f64], used: &[bool], p: &Prefix, centre: f64, a: usize, c: usize, b: usize) -> f64 {
    let mut res = Vec::with_capacity(b - a);
    for (lo, hi) in [(a, c), (c, b)] {
        let (i0, s) = p.line(lo, hi);
        for k in lo..hi {
            if used[k] {
                res.push(y[k] - centre - i0 - s * k as f64);
            }
        }
    }
    let c0: f64 = res.iter().map(|r| r * r).sum();
    if c0 <= 0.0 || res.len() < 3 {
        return 0.0;
    }
    let c1: f64 = res.windows(2).map(|w| w[0] * w[1]).sum();
    (c1 / c0).clamp(-0.99, 0.99)
}

/// Best change point in `[a, b)` searched over `cands`; `Some(c)` when the Schwarz criterion
/// (penalty 3 ln n for the change point and the second line) accepts it.
fn change_point(
    y: &[f64],
    used: &[bool],
    p: &Prefix,
    centre: f64,
    a: usize,
    b: usize,
    cands: std::ops::Range<usize>,
) -> Option<usize> {
    let sse1 = p.sse(a, b);
    let (mut best, mut best_c) = (f64::INFINITY, None);
    for c in cands {
        let s = p.sse(a, c) + p.sse(c, b);
        if s < best {
            best = s;
            best_c = Some(c);
        }
    }
    let c = best_c?;
    let n = p.n[b] - p.n[a];
    if n < 8.0 || sse1 <= 0.0 {
        return None;
    }
    if best <= 0.0 {
        return Some(c);
    }
    let rho = residual_rho1(y, used, p, centre, a, c, b).max(0.0);
    let n_eff = n * (1.0 - rho) / (1.0 + rho);
    (n_eff * (sse1 / best).ln() > 3.0 * n.ln()).then_some(c)
}

/// Find the steady window on block means `y` of the cutting channel; `finite[k]` is false for
/// blocks without samples.
pub fn detect(y: &[f64], finite: &[bool], cfg: &WindowConfig) -> Result<BlockWindow, SignalError> {
    let m = y.len();
    let mut abs: Vec<f64> = y.iter().zip(finite).filter(|(_, &f)| f).map(|(v, _)| v.abs()).collect();
    if abs.len() < 16 {
        return Err(SignalError::TooShort { samples: abs.len() as u64, needed: 16 });
    }
    abs.sort_by(f64::total_cmp);
    let p98 = abs[(abs.len() as f64 * 0.98) as usize - 1];
    if !(p98 > 0.0) {
        return Err(SignalError::NoCut("the cutting-force channel is zero throughout".into()));
    }
    let upper: Vec<f64> = abs.iter().copied().filter(|v| *v > 0.5 * p98).collect();
    let level = upper.get(upper.len() / 2).copied().unwrap_or(p98);
    if !(level > 0.0) {
        return Err(SignalError::NoCut("the cutting-force channel is zero throughout".into()));
    }
    let cutting: Vec<bool> = (0..m).map(|k| finite[k] && y[k].abs() > 0.5 * level).collect();
    // Runs of cutting blocks, bridging short gaps.
    let max_gap = ((m as f64 * cfg.max_gap_fraction) as usize).max(1);
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut k = 0;
    while k < m {
        if !cutting[k] {
            k += 1;
            continue;
        }
        let s = k;
        let mut e = k;
        while e < m {
            if cutting[e] {
                e += 1;
                continue;
            }
            let gap_end = (e..m).find(|&j| cutting[j]).unwrap_or(m);
            if gap_end < m && gap_end - e <= max_gap {
                e = gap_end;
            } else {
                break;
            }
        }
        runs.push((s, e));
        k = e;
    }
    let (a, b) = runs
        .iter()
        .copied()
        .max_by_key(|&(s, e)| (s..e).filter(|&j| cutting[j]).count())
        .ok_or_else(|| SignalError::NoCut("no block above half the plateau level".into()))?;
    // Blocks to use: cutting, and not next to a gap.
    let mut used: Vec<bool> = cutting.clone();
    for j in a..b {
        if !cutting[j] {
            if j > a {
                used[j - 1] = false;
            }
            if j + 1 < b {
                used[j + 1] = false;
            }
        }
    }
    let len = b - a;
    let centre = level.copysign(y[a..b].iter().sum::<f64>());
    let p = Prefix::new(y, &used, centre);
    let margin = ((len as f64 * cfg.margin_fraction).ceil() as usize).max(1);
    let outer = (len as f64 * 0.4) as usize;
    let half = a + len / 2;
    let mut start = a + margin;
    let mut end = b.saturating_sub(margin);
    if outer >= 4 {
        if let Some(c) = change_point(y, &used, &p, centre, a, half, a + 2..a + outer) {
            start = c + margin;
        }
        if let Some(c) = change_point(y, &used, &p, centre, half, b, b - outer..b - 2) {
            end = c.saturating_sub(margin);
        }
    }
    if end <= start + 8 {
        return Err(SignalError::WindowTooShort {
            t0_s: 0.0,
            t1_s: 0.0,
            blocks: end.saturating_sub(start),
            needed: 8,
            why: "the transients cover nearly the whole cut".into(),
        });
    }
    Ok(BlockWindow { start, end, use_block: used[start..end].to_vec(), level })
}
