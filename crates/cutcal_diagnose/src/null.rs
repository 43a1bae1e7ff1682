//! The calibrated null (issue 10, item 4): the significance level of the mechanism tests is set on
//! the data's own null by a parametric bootstrap through the whole first-round pipeline.
//!
//! Each replicate draws recordings from the fitted baseline (nuisance included) with the noise
//! model (multiplicative lognormal, design note Sec 3.1), refits the baseline, screens every
//! testable mechanism, refits the candidates and records the smallest F-test p-value among those
//! that pass the interval check, i.e. the level at which that replicate would have produced a
//! claim. The level used on the data is the 5 % quantile of those smallest p-values (order
//! statistic `floor(0.05 (B + 1))`, Davison & Hinkley 1997 Sec 4.2), never above the family level.
//! The family-wise false-positive rate of the screen-refit-select chain is then <= 5 % by
//! construction (up to the bootstrap's Monte-Carlo error), whatever the selection does. The
//! held-out checks that follow only remove claims, so they keep the bound.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::fit::{self, observations, Fit, Spec};
use crate::mechanism::MechanismId;
use crate::problem::Problem;
use crate::screen::screen_and_refit;

/// Outcome of the calibration.
#[derive(Debug, Clone, PartialEq)]
pub struct NullCalibration {
    /// Per-mechanism level used (the calibrated one, or the Bonferroni level when not calibrated).
    pub alpha: f64,
    /// Replicates run.
    pub replicates: usize,
    /// Replicates whose baseline refit failed (counted as a claim at p = 0: conservative).
    pub failed: usize,
    /// Replicates with a claim at the family level.
    pub claims_at_family_level: usize,
}

/// Standard normal draw (Box-Muller).
fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = rng.gen::<f64>().max(1e-300);
    let u2: f64 = rng.gen();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Smallest p-value of a claim-capable candidate on one replicate (1 when none).
fn replicate_min_p(pr: &Problem<'_>, base: &Fit, base_spec: &Spec, usable: &[MechanismId], seed: u64) -> Option<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = pr.cfg.noise;
    let mut tests = pr.tests.to_vec();
    for o in &pr.obs {
        let y = fit::output(&base.preds[o.test], o.output) * (noise[o.output] * normal(&mut rng)).exp();
        let m = &mut tests[o.test].measured;
        match o.output {
            0 => m.cutting_force_n_per_m = Some(y),
            1 => m.feed_force_n_per_m = Some(y),
            2 => m.chip_thickness_m = Some(y),
            _ => m.interface_temperature_c = Some(y + fit::T_REF_C),
        }
    }
    let obs = observations(&tests);
    let rp = Problem { sim: pr.sim, tests: &tests, obs, groups: pr.groups.clone(), cfg: pr.cfg };
    let b = rp.fit(base_spec, Some(&base.x)).ok()?;
    let (cands, _) = screen_and_refit(&rp, &b, base_spec, usable).ok()?;
    Some(cands.iter().filter(|c| c.ci_ok && c.p.is_finite()).map(|c| c.p).fold(1.0, f64::min))
}

/// Calibrates the per-mechanism level on `replicates` null replicates (seeded, parallel).
#[must_use]
pub(crate) fn calibrate(
    pr: &Problem<'_>,
    base: &Fit,
    base_spec: &Spec,
    usable: &[MechanismId],
    replicates: usize,
    seed: u64,
) -> NullCalibration {
    let family = pr.cfg.family_alpha;
    let mins: Vec<Option<f64>> = (0..replicates)
        .into_par_iter()
        .map(|r| replicate_min_p(pr, base, base_spec, usable, seed.wrapping_add(r as u64).wrapping_mul(0x9E37_79B9)))
        .collect();
    let failed = mins.iter().filter(|m| m.is_none()).count();
    let mut p: Vec<f64> = mins.iter().map(|m| m.unwrap_or(0.0)).collect();
    p.sort_by(f64::total_cmp);
    let claims_at_family_level = p.iter().filter(|v| **v < family).count();
    let k = ((family * (replicates + 1) as f64).floor() as usize).max(1);
    let alpha = if replicates == 0 { family } else { p[(k - 1).min(p.len() - 1)].min(family) };
    NullCalibration { alpha: alpha.max(1e-12), replicates, failed, claims_at_family_level }
}
