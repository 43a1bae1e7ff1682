//! Deterministic synthetic dynamometer recordings with known truth, for tests, the benchmark and
//! the labelled-synthetic fixture set (never presented as measured data).
//!
//! Profile of each force channel
//! `F(t) = level * s(t) * (1 + drift * (t - t_steady0) / T_steady) + A sin(2 pi f t) * s(t) + noise`,
//! where `s(t)` rises linearly from 0 to 1 over the entry ramp,
//! is 1 in the steady cut and falls linearly to 0 over the exit ramp; the noise is a Gaussian AR(1)
//! process with the given marginal sd (Box & Jenkins 1976, Time Series Analysis, Sec. 3.2.4) drawn
//! with Box-Muller (Box & Muller 1958, Ann. Math. Stat. 29:610) from a SplitMix64 stream (Steele,
//! Lea & Flood 2014, OOPSLA), so a seed gives the same samples on every platform.

/// One synthetic recording; times in s, forces in N.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SyntheticSpec {
    /// Sample rate, Hz.
    pub rate_hz: f64,
    /// Record length, s.
    pub duration_s: f64,
    /// Start of the entry ramp, s.
    pub entry_s: f64,
    /// Duration of each ramp, s.
    pub ramp_s: f64,
    /// Start of the exit ramp, s.
    pub exit_s: f64,
    /// Steady levels per channel (fc, ft, fp), N.
    pub level_n: [f64; 3],
    /// Marginal noise sd per channel, N.
    pub noise_sd_n: [f64; 3],
    /// AR(1) coefficient of the noise (0 = white).
    pub noise_phi: f64,
    /// Relative change of the levels across the steady cut (wear drift).
    pub drift_relative: f64,
    /// Oscillation frequency, Hz, and amplitude as a fraction of each level (built-up edge).
    pub oscillation: Option<(f64, f64)>,
    /// Dropout `(start_s, duration_s)`: samples become NaN.
    pub dropout: Option<(f64, f64)>,
    /// Seed of the noise.
    pub seed: u64,
}

impl SyntheticSpec {
    /// A plain steady cut: 10 kHz, 2 s, entry 0.2 s, ramps 0.05 s, exit 1.7 s, Fc 500 N, Ft 300 N,
    /// Fp 50 N, 2 % white noise.
    pub fn plain(seed: u64) -> Self {
        SyntheticSpec {
            rate_hz: 10_000.0,
            duration_s: 2.0,
            entry_s: 0.2,
            ramp_s: 0.05,
            exit_s: 1.7,
            level_n: [500.0, 300.0, 50.0],
            noise_sd_n: [10.0, 6.0, 1.0],
            noise_phi: 0.0,
            drift_relative: 0.0,
            oscillation: None,
            dropout: None,
            seed,
        }
    }

    /// Steady window of the truth `[entry + ramp, exit]`, s.
    pub fn steady(&self) -> (f64, f64) {
        (self.entry_s + self.ramp_s, self.exit_s)
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        (self.duration_s * self.rate_hz).round() as usize
    }

    /// True when the record is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Noise-free value of channel `c` at time `t`.
    pub fn truth(&self, c: usize, t: f64) -> f64 {
        let (s0, s1) = self.steady();
        let s = if t < self.entry_s || t > s1 + self.ramp_s {
            0.0
        } else if t < s0 {
            (t - self.entry_s) / self.ramp_s
        } else if t <= s1 {
            1.0
        } else {
            1.0 - (t - s1) / self.ramp_s
        };
        let drift = 1.0 + self.drift_relative * ((t.clamp(s0, s1) - s0) / (s1 - s0));
        let osc = self.oscillation.map_or(0.0, |(f, a)| a * (2.0 * std::f64::consts::PI * f * t).sin());
        self.level_n[c] * s * (drift + osc)
    }

    /// The samples `(t_s, [fc, ft, fp])`.
    pub fn samples(&self) -> impl Iterator<Item = (f64, [f64; 3])> + '_ {
        let mut rng = SplitMix(self.seed);
        let mut ar = [0.0; 3];
        let innov = (1.0 - self.noise_phi * self.noise_phi).sqrt();
        (0..self.len()).map(move |i| {
            let t = i as f64 / self.rate_hz;
            let mut v = [0.0; 3];
            for c in 0..3 {
                ar[c] = if i == 0 { rng.normal() } else { self.noise_phi * ar[c] + innov * rng.normal() };
                v[c] = self.truth(c, t) + self.noise_sd_n[c] * ar[c];
            }
            if let Some((d0, dd)) = self.dropout {
                if t >= d0 && t < d0 + dd {
                    v = [f64::NAN; 3];
                }
            }
            (t, v)
        })
    }
}

/// SplitMix64 (Steele, Lea & Flood 2014) with Box-Muller normals.
struct SplitMix(u64);

impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    fn normal(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}
