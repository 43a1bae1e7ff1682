//! Parameter uncertainty by parametric bootstrap: the measured cutting force, feed force and chip
//! thickness are resampled within their stated relative uncertainties, the identification is re-run
//! on every sample, and the spread and correlation of the identified JC parameters are reported.
//!
//! Sampling: each measured value `q` becomes `q (1 + u z)` with `z` a standard normal deviate and
//! `u` the relative standard uncertainty (e.g. 3 % for forces, 5 % for chip thickness). A sample
//! whose identification fails (e.g. the perturbed forces melt the zone) is counted, not fatal.
//!
//! Determinism: sample `i` draws from a ChaCha8 stream `i` of the master seed, so every sample is
//! fixed by `(seed, i)` alone. Samples run in parallel with rayon and are collected in index order,
//! so the report is bit-identical for any number of threads.

use cutcal_model::JcParams;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;

use crate::dpzd_fit::JC_NAMES;
use crate::error::IdentError;

/// The measured quantities the DPZD identification depends on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measurement {
    /// Cutting force per unit width, N/m.
    pub cutting_force_n_per_m: f64,
    /// Feed (thrust) force per unit width, N/m.
    pub feed_force_n_per_m: f64,
    /// Chip thickness, m.
    pub chip_thickness_m: f64,
}

/// Relative standard uncertainties (one standard deviation, as a fraction: 0.03 = 3 %).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RelativeUncertainty {
    /// Of both forces.
    pub force: f64,
    /// Of the chip thickness.
    pub chip_thickness: f64,
}

impl RelativeUncertainty {
    /// Validating constructor.
    ///
    /// Returns an error unless both uncertainties are finite and in `[0, 0.25]` (beyond 25 % a
    /// normal perturbation makes non-positive measurements likely: 4 standard deviations).
    ///
    /// # Example
    /// ```
    /// use cutcal_ident::bootstrap::RelativeUncertainty;
    /// assert!(RelativeUncertainty::new(0.03, 0.05).is_ok());
    /// assert!(RelativeUncertainty::new(-0.03, 0.05).is_err());
    /// ```
    pub fn new(force: f64, chip_thickness: f64) -> Result<Self, IdentError> {
        for (name, u) in [("force", force), ("chip thickness", chip_thickness)] {
            if !(u.is_finite() && (0.0..=0.25).contains(&u)) {
                return Err(IdentError::InvalidOptions(format!(
                    "relative {name} uncertainty must satisfy 0 <= u <= 0.25, got {u}"
                )));
            }
        }
        Ok(Self { force, chip_thickness })
    }
}

/// The modelling choices the paper does not state, varied together with the measurements: the zone
/// thickness h (log-uniform over `h_factor` times the nominal h) and the strain-rate exponent r of
/// Eq 2 (uniform over nominal r +- `r_half_width`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct UnstatedChoices {
    /// Range of the factor on h, e.g. `[0.5, 2.0]`.
    pub h_factor: [f64; 2],
    /// Half-width of the uniform range of r, e.g. 1.
    pub r_half_width: f64,
}

impl UnstatedChoices {
    /// Validating constructor.
    ///
    /// Returns an error unless `0 < h_factor[0] <= 1 <= h_factor[1] <= 100` and
    /// `0 <= r_half_width <= 10`.
    pub fn new(h_factor: [f64; 2], r_half_width: f64) -> Result<Self, IdentError> {
        let [lo, hi] = h_factor;
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= 1.0 && (1.0..=100.0).contains(&hi)) {
            return Err(IdentError::InvalidOptions(format!(
                "the h factor range must satisfy 0 < low <= 1 <= high <= 100, got [{lo}, {hi}]"
            )));
        }
        if !(r_half_width.is_finite() && (0.0..=10.0).contains(&r_half_width)) {
            return Err(IdentError::InvalidOptions(format!("the r half-width must be in [0, 10], got {r_half_width}")));
        }
        Ok(Self { h_factor, r_half_width })
    }
}

/// One Monte-Carlo sample: the perturbed measurement and the drawn choices.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sample {
    /// The perturbed measurement.
    pub measurement: Measurement,
    /// Factor on the nominal h (1 when the choices are not varied).
    pub h_factor: f64,
    /// Offset added to the nominal r (0 when the choices are not varied).
    pub r_offset: f64,
}

/// Monte-Carlo settings (no `Default`: the sample count and uncertainties are choices to state).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BootstrapOptions {
    /// Number of resampled identifications (2..=1_000_000).
    pub samples: usize,
    /// Master seed; sample `i` uses ChaCha8 stream `i` of it.
    pub seed: u64,
    /// Measurement uncertainties.
    pub uncertainty: RelativeUncertainty,
    /// The unstated choices varied with the measurements; `None`: measurement noise only.
    pub choices: Option<UnstatedChoices>,
}

/// Spread of one identified parameter over the successful samples.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterSpread {
    /// Parameter name (`a_mpa`, `b_mpa`, `n`, `c`, `m`).
    pub name: String,
    /// Mean.
    pub mean: f64,
    /// Sample standard deviation (divisor `k - 1`).
    pub std: f64,
    /// 2.5 % quantile (linear interpolation between order statistics).
    pub q025: f64,
    /// 97.5 % quantile.
    pub q975: f64,
}

/// The outcome of a bootstrap.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BootstrapReport {
    /// Samples drawn.
    pub samples: usize,
    /// Samples whose identification succeeded (the statistics are over these).
    pub succeeded: usize,
    /// Samples whose identification failed.
    pub failed: usize,
    /// The first failure (lowest sample index), if any.
    pub first_failure: Option<String>,
    /// Master seed.
    pub seed: u64,
    /// The uncertainties sampled.
    pub uncertainty: RelativeUncertainty,
    /// The unstated choices varied (`None`: measurement noise only).
    pub choices: Option<UnstatedChoices>,
    /// Spread of A (MPa), B (MPa), n, C, m, in that order.
    pub parameters: Vec<ParameterSpread>,
    /// Pearson correlation matrix in the order of `parameters`; `None` where a parameter does not
    /// vary (e.g. pinned at a bound in every sample).
    pub correlation: Vec<Vec<Option<f64>>>,
}

/// Standard normal deviate by the Box-Muller transform (rand 0.8 without `rand_distr`).
fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    // 1 - U lies in (0, 1]: the logarithm is finite.
    let u1: f64 = 1.0 - rng.gen::<f64>();
    let u2: f64 = rng.gen::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// The measurement of sample `index`: each value times `1 + u z`, `z` standard normal, drawn from
/// ChaCha8 stream `index` of `seed` (forces first, then chip thickness).
#[must_use]
pub fn perturbed(nominal: &Measurement, uncertainty: &RelativeUncertainty, seed: u64, index: usize) -> Measurement {
    sample(nominal, uncertainty, None, seed, index).measurement
}

/// Sample `index`: the measurement of [`perturbed`], then (when `choices` is given) ln h factor
/// uniform over the log range and r offset uniform over +- the half-width, drawn after the
/// measurement from the same stream (so the measurements do not depend on whether choices vary).
#[must_use]
pub fn sample(
    nominal: &Measurement,
    uncertainty: &RelativeUncertainty,
    choices: Option<&UnstatedChoices>,
    seed: u64,
    index: usize,
) -> Sample {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index as u64);
    let measurement = measurement_draw(nominal, uncertainty, &mut rng);
    let (h_factor, r_offset) = match choices {
        Some(c) => {
            let (lo, hi) = (c.h_factor[0].ln(), c.h_factor[1].ln());
            let h = (lo + (hi - lo) * rng.gen::<f64>()).exp();
            let r = c.r_half_width * (2.0 * rng.gen::<f64>() - 1.0);
            (h, r)
        }
        None => (1.0, 0.0),
    };
    Sample { measurement, h_factor, r_offset }
}

fn measurement_draw(nominal: &Measurement, uncertainty: &RelativeUncertainty, rng: &mut ChaCha8Rng) -> Measurement {
    let fc = standard_normal(rng);
    let ft = standard_normal(rng);
    let tc = standard_normal(rng);
    Measurement {
        cutting_force_n_per_m: nominal.cutting_force_n_per_m * (1.0 + uncertainty.force * fc),
        feed_force_n_per_m: nominal.feed_force_n_per_m * (1.0 + uncertainty.force * ft),
        chip_thickness_m: nominal.chip_thickness_m * (1.0 + uncertainty.chip_thickness * tc),
    }
}

/// The five identified parameters in report units: A and B in MPa, then n, C, m.
fn report_vector(jc: &JcParams) -> [f64; 5] {
    [jc.a_pa / 1e6, jc.b_pa / 1e6, jc.n, jc.c, jc.m]
}

/// Runs `identify` on `options.samples` perturbed copies of `nominal` in parallel and summarises
/// the identified parameters.
///
/// `identify` maps a sample (measurement and drawn choices) to an identified JC set; it runs on rayon's pool, so it must be
/// `Sync` and should not itself spawn parallel work.
///
/// Returns an error if the options are invalid or fewer than two samples succeed (the first
/// failure is quoted).
pub fn bootstrap<F>(
    nominal: &Measurement,
    options: &BootstrapOptions,
    identify: F,
) -> Result<BootstrapReport, IdentError>
where
    F: Fn(&Sample) -> Result<JcParams, IdentError> + Sync,
{
    if !(2..=1_000_000).contains(&options.samples) {
        return Err(IdentError::InvalidOptions(format!(
            "bootstrap samples must be in 2..=1000000, got {}",
            options.samples
        )));
    }
    let u = RelativeUncertainty::new(options.uncertainty.force, options.uncertainty.chip_thickness)?;
    let results: Vec<Result<[f64; 5], String>> = (0..options.samples)
        .into_par_iter()
        .map(|i| {
            let m = sample(nominal, &u, options.choices.as_ref(), options.seed, i);
            match identify(&m) {
                Ok(jc) => {
                    let v = report_vector(&jc);
                    if v.iter().all(|x| x.is_finite()) {
                        Ok(v)
                    } else {
                        Err(format!("sample {i}: non-finite parameters {v:?}"))
                    }
                }
                Err(e) => Err(format!("sample {i}: {e}")),
            }
        })
        .collect();
    let ok: Vec<[f64; 5]> = results.iter().filter_map(|r| r.as_ref().ok().copied()).collect();
    let first_failure = results.iter().find_map(|r| r.as_ref().err().cloned());
    if ok.len() < 2 {
        return Err(IdentError::InvalidOptions(format!(
            "only {} of {} bootstrap samples could be identified; first failure: {}",
            ok.len(),
            options.samples,
            first_failure.unwrap_or_default()
        )));
    }
    let parameters: Vec<ParameterSpread> = (0..5)
        .map(|k| {
            let column: Vec<f64> = ok.iter().map(|v| v[k]).collect();
            let (mean, std) = mean_std(&column);
            ParameterSpread {
                name: JC_NAMES[k].to_string(),
                mean,
                std,
                q025: quantile(&column, 0.025),
                q975: quantile(&column, 0.975),
            }
        })
        .collect();
    let correlation = (0..5).map(|i| (0..5).map(|j| correlation(&ok, i, j, &parameters)).collect()).collect();
    Ok(BootstrapReport {
        samples: options.samples,
        succeeded: ok.len(),
        failed: options.samples - ok.len(),
        first_failure,
        seed: options.seed,
        uncertainty: u,
        choices: options.choices,
        parameters,
        correlation,
    })
}

/// Mean and sample standard deviation (at least two values).
fn mean_std(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.max(0.0).sqrt())
}

/// The `p` quantile with linear interpolation between order statistics (Hyndman-Fan type 7).
#[must_use]
pub fn quantile(x: &[f64], p: f64) -> f64 {
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    if s.is_empty() {
        return f64::NAN;
    }
    let h = (s.len() - 1) as f64 * p.clamp(0.0, 1.0);
    let lo = h.floor() as usize;
    let hi = (lo + 1).min(s.len() - 1);
    s[lo] + (h - lo as f64) * (s[hi] - s[lo])
}

/// Pearson correlation of parameters `i` and `j`; `None` when either does not vary.
fn correlation(rows: &[[f64; 5]], i: usize, j: usize, spread: &[ParameterSpread]) -> Option<f64> {
    let (si, sj) = (spread[i].std, spread[j].std);
    // A spread below 1e-12 of the mean is rounding, not variation.
    let varies = |s: f64, m: f64| s > 1e-12 * m.abs().max(1e-300);
    if !(varies(si, spread[i].mean) && varies(sj, spread[j].mean)) {
        return None;
    }
    let n = rows.len() as f64;
    let cov = rows.iter().map(|r| (r[i] - spread[i].mean) * (r[j] - spread[j].mean)).sum::<f64>() / (n - 1.0);
    Some((cov / (si * sj)).clamp(-1.0, 1.0))
}

#[cfg(test)]
mod tests;
