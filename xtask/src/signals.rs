//! `cargo xtask signals`: the SYNTHETIC signal set `fixtures/signals/c38/` of the signals project
//! (`fixtures/projects/c38_signals.toml`), written by its own seeded generator -- deliberately not
//! `cutcal_signal::synthetic`, so the reduction is not checked against its own twin.
//!
//! Each file is one simulated orthogonal cut of C38 test 3 (paper Table 2: 240 m/min, uncut chip
//! thickness 0.075 mm, width 1.95 mm, rake 0 deg) at 2 kHz for 1.6 s: idle, a linear entry ramp,
//! the steady cut at the paper's Table 6 measured means (Fc 224 N/mm, Ft 186 N/mm, times the
//! 1.95 mm width: 436.8 N, 362.7 N), a linear exit ramp, idle. Cutting noise is a Gaussian AR(1)
//! process (Box & Jenkins 1976, Time Series Analysis, Sec. 3.2.4) scaled by the engagement, with
//! Box-Muller normals (Box & Muller 1958, Ann. Math. Stat. 29:610) from a ChaCha8 stream, plus
//! white sensor noise. Three seeds give test 3 and two repeat runs at the same condition.

use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use anyhow::{Context, Result};
use rand::RngCore;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Sample rate, Hz.
const RATE_HZ: f64 = 2000.0;
/// Record length, s.
const DURATION_S: f64 = 1.6;
/// Start of the entry ramp, s.
const ENTRY_S: f64 = 0.25;
/// Ramp duration (tool engagement / disengagement), s.
const RAMP_S: f64 = 0.04;
/// Start of the exit ramp, s.
const EXIT_S: f64 = 1.30;
/// Steady levels (Fc, Ft), N: paper Table 6 measured means per width x 1.95 mm (Table 2).
const LEVEL_N: [f64; 2] = [224.0 * 1.95, 186.0 * 1.95];
/// Cutting-noise sd as a fraction of the level (Fc, Ft).
const NOISE_FRACTION: [f64; 2] = [0.025, 0.03];
/// AR(1) coefficient of the cutting noise.
const PHI: f64 = 0.5;
/// White sensor noise sd, N.
const SENSOR_SD_N: f64 = 1.0;

/// The files: (test id, seed).
pub const FILES: [(&str, u64); 3] = [("3", 1), ("3r2", 2), ("3r3", 3)];

/// Standard normal pairs by Box-Muller from a seeded ChaCha8 stream.
struct Normal {
    rng: ChaCha8Rng,
    spare: Option<f64>,
}

impl Normal {
    fn new(seed: u64) -> Self {
        Self { rng: ChaCha8Rng::seed_from_u64(seed), spare: None }
    }

    /// A uniform in (0, 1]: 53 random bits, never 0 (the logarithm below needs it).
    fn uniform(&mut self) -> f64 {
        ((self.rng.next_u64() >> 11) as f64 + 1.0) / (1u64 << 53) as f64
    }

    fn sample(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        let (u1, u2) = (self.uniform(), self.uniform());
        let r = (-2.0 * u1.ln()).sqrt();
        let a = 2.0 * std::f64::consts::PI * u2;
        self.spare = Some(r * a.sin());
        r * a.cos()
    }
}

/// Engagement in [0, 1]: 0 idle, linear ramps, 1 in the steady cut.
fn engagement(t: f64) -> f64 {
    ((t - ENTRY_S) / RAMP_S).clamp(0.0, 1.0) * ((EXIT_S + RAMP_S - t) / RAMP_S).clamp(0.0, 1.0)
}

/// The text of one signal file.
#[must_use]
pub fn signal_text(test: &str, seed: u64) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# SYNTHETIC dynamometer recording, not measured: `cargo xtask signals` (xtask/src/signals.rs), seed {seed}."
    );
    let _ = writeln!(
        s,
        "# C38 test {test}: 240 m/min, h 0.075 mm, w 1.95 mm (paper Table 2); steady Fc {:.1} N, Ft {:.1} N = paper Table 6 means x width.",
        LEVEL_N[0], LEVEL_N[1]
    );
    let _ = writeln!(
        s,
        "# {RATE_HZ} Hz, {DURATION_S} s: entry ramp {ENTRY_S}-{} s, steady cut, exit ramp {EXIT_S}-{} s; AR(1) noise phi {PHI}, sd {} % / {} % of the level; sensor noise {SENSOR_SD_N} N.",
        ENTRY_S + RAMP_S,
        EXIT_S + RAMP_S,
        NOISE_FRACTION[0] * 100.0,
        NOISE_FRACTION[1] * 100.0
    );
    s.push_str("time_s,fc_n,ft_n\n");
    let mut normal = Normal::new(seed);
    let innovation = (1.0 - PHI * PHI).sqrt();
    let mut ar = [normal.sample(), normal.sample()];
    let n = (RATE_HZ * DURATION_S).round() as usize;
    for i in 0..n {
        let t = i as f64 / RATE_HZ;
        let e = engagement(t);
        let mut f = [0.0; 2];
        for c in 0..2 {
            ar[c] = PHI * ar[c] + innovation * normal.sample();
            f[c] = e * LEVEL_N[c] * (1.0 + NOISE_FRACTION[c] * ar[c]) + SENSOR_SD_N * normal.sample();
        }
        let _ = writeln!(s, "{t:.4},{:.2},{:.2}", f[0], f[1]);
    }
    s
}

/// Writes the set into `dir` (`<test>.csv` per file).
pub fn run(dir: &Path) -> Result<()> {
    fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for (test, seed) in FILES {
        let p = dir.join(format!("{test}.csv"));
        cutcal_io::output::write_atomic(&p, signal_text(test, seed).as_bytes())?;
        println!("wrote {}", p.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_set_is_what_the_generator_writes() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/signals/c38");
        for (test, seed) in FILES {
            let p = dir.join(format!("{test}.csv"));
            let committed = fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(committed == signal_text(test, seed), "{} is stale: run `cargo xtask signals`", p.display());
        }
    }

    #[test]
    fn the_steady_cut_holds_the_published_means() {
        // Independent of the reduction: the plain mean over the truth's steady part
        // [entry + ramp, exit] is within 0.5 % of Table 6 x width (2.5-3 % noise over ~2000 samples).
        let text = signal_text("3", 1);
        let rows: Vec<Vec<f64>> = text
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with("time"))
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 3200);
        let steady: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] >= ENTRY_S + RAMP_S && r[0] < EXIT_S).collect();
        for (c, want) in [(1, 436.8), (2, 362.7)] {
            let mean = steady.iter().map(|r| r[c]).sum::<f64>() / steady.len() as f64;
            assert!((mean / want - 1.0).abs() < 0.005, "channel {c}: {mean} vs {want}");
        }
        // Idle parts carry only the sensor noise.
        assert!(rows.iter().filter(|r| r[0] < ENTRY_S).all(|r| r[1].abs() < 6.0 * SENSOR_SD_N));
    }
}
