//! The calibrated null (issue 10, item 4): the significance level of the mechanism tests is set on
//! the data's own null by a parametric bootstrap through the whole first-round pipeline.
//!
//! Each replicate draws recordings from the fitted baseline (nuisance included) with the noise
//! model (multiplicative lognormal, design note Sec 3.1), refits the baseline, screens every
//! testable mechanism, refits the candidates and records each candidate's F-test p-value (1 when
//! its interval check fails), i.e. the level at which that replicate would have produced a claim.
//!
//! The mechanisms' F-tests are not equally exact under this null. The nuisance absorbs most of what
//! a heat-partition or softening refit can do, so their p-values are far larger than uniform (in a
//! family of the concealed benchmark fewer than 1 % of replicates reach p < 0.1), while a size
//! effect with its wide length range is a little anti-conservative. A single level set on the
//! smallest p of each replicate is then spent almost entirely on the anti-conservative tests. The
//! level is therefore set on the smallest *rescaled* p-value, `c_j p_j`, the single-step min-P
//! adjustment of Westfall & Young 1993 (Sec 2.6) with each mechanism's marginal null tail taken as
//! linear: `c_j = (#{replicates with p_j < P_REF} + 1/2) / (B P_REF)` (the null's rate of small
//! p-values relative to a uniform one). The level used on the data is the 5 % quantile of the
//! replicates' `min_j c_j p_j` over the p-values below the family level (order statistic
//! `floor(0.05 (B + 1))`, Davison & Hinkley 1997 Sec 4.2), and mechanism j is significant at
//! `p_j < level / c_j`, never above the family level. The
//! family-wise false-positive rate of the screen-refit-select chain is then <= 5 % by construction
//! (up to the bootstrap's Monte-Carlo error), whatever the scales: they only share the 5 % among
//! the mechanisms in proportion to how often each claims under the null. The held-out checks that
//! follow only remove claims, so they keep the bound.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::fit::{self, observations, Fit, Spec};
use crate::mechanism::MechanismId;
use crate::problem::Problem;
use crate::screen::screen_and_refit;

/// Reference p-value at which each mechanism's null tail is counted (module docs).
const P_REF: f64 = 0.1;

/// Outcome of the calibration.
#[derive(Debug, Clone, PartialEq)]
pub struct NullCalibration {
    /// Level of a mechanism whose null p-values are uniform (`c_j` = 1); mechanism j's is
    /// [`NullCalibration::level_of`].
    pub alpha: f64,
    /// Family level: no mechanism's level exceeds it.
    pub family: f64,
    /// The level from which later rounds divide by 4 per round: the same quantile of the
    /// replicates' smallest unscaled p-value (the null scales were measured on the baseline, not on
    /// top of a claim).
    pub later_rounds: f64,
    /// Null scale `c_j` of each mechanism tested (module docs).
    pub scale: Vec<(MechanismId, f64)>,
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

impl NullCalibration {
    /// Null scale of `id` (1 when it was not calibrated).
    #[must_use]
    pub fn scale_of(&self, id: MechanismId) -> f64 {
        self.scale.iter().find(|(m, _)| *m == id).map_or(1.0, |(_, c)| *c)
    }

    /// First-round level of mechanism `id`: `alpha / c_id`, never above the family level.
    #[must_use]
    pub fn level_of(&self, id: MechanismId) -> f64 {
        (self.alpha / self.scale_of(id)).min(self.family)
    }
}

/// Each claim-capable candidate's p-value on one replicate (1 for a candidate whose interval check
/// fails or that was not refitted); `None` when the replicate's baseline or screen fails.
fn replicate_ps(pr: &Problem<'_>, base: &Fit, base_spec: &Spec, usable: &[MechanismId], seed: u64) -> Option<Vec<f64>> {
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
    Some(
        usable
            .iter()
            .map(|&m| cands.iter().find(|c| c.id == m && c.ci_ok && c.p.is_finite()).map_or(1.0, |c| c.p))
            .collect(),
    )
}

/// Null scales `c_j` from the replicates' p-values (`ps[r][j]`, failed replicates left out).
fn null_scales(ps: &[Vec<f64>], mechanisms: usize) -> Vec<f64> {
    let b = ps.len().max(1) as f64;
    (0..mechanisms).map(|j| (ps.iter().filter(|r| r[j] < P_REF).count() as f64 + 0.5) / (b * P_REF)).collect()
}

/// The unit-scale level: the 5 % quantile (order statistic `floor(family (B + 1))`) over the
/// replicates `runs` of the smallest rescaled p-value `min_j c_j p_j` among those with `p_j <
/// family` (a mechanism's level never exceeds `family`, so a larger p-value claims at no level), a
/// failed replicate (`None`) counting as a claim at 0; never above `family`, and `family` without
/// replicates. A replicate then claims at level `alpha` exactly when some `p_j < min(alpha / c_j,
/// family)`, the rule applied to the data.
fn min_p_level(runs: &[Option<Vec<f64>>], c: &[f64], family: f64) -> f64 {
    if runs.is_empty() {
        return family;
    }
    let mut m: Vec<f64> = runs
        .iter()
        .map(|r| {
            r.as_ref().map_or(0.0, |v| {
                v.iter().zip(c).filter(|(p, _)| **p < family).map(|(p, c)| p * c).fold(f64::INFINITY, f64::min)
            })
        })
        .collect();
    m.sort_by(f64::total_cmp);
    let k = ((family * (runs.len() + 1) as f64).floor() as usize).max(1);
    m[(k - 1).min(m.len() - 1)].min(family)
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
    let runs: Vec<Option<Vec<f64>>> = (0..replicates)
        .into_par_iter()
        .map(|r| replicate_ps(pr, base, base_spec, usable, seed.wrapping_add(r as u64).wrapping_mul(0x9E37_79B9)))
        .collect();
    let failed = runs.iter().filter(|m| m.is_none()).count();
    let ok: Vec<Vec<f64>> = runs.iter().flatten().cloned().collect();
    let c = null_scales(&ok, usable.len());
    let alpha = min_p_level(&runs, &c, family);
    let later_rounds = min_p_level(&runs, &vec![1.0; usable.len()], family);
    let claims_at_family_level =
        runs.iter().filter(|r| r.as_ref().is_none_or(|v| v.iter().any(|p| *p < family))).count();
    NullCalibration {
        alpha: alpha.max(1e-12),
        family,
        later_rounds: later_rounds.max(1e-12),
        scale: usable.iter().copied().zip(c).collect(),
        replicates,
        failed,
        claims_at_family_level,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn null_scales_count_small_p_values_against_a_uniform_null() {
        // Ten replicates: mechanism 0 has one p below 0.1, mechanism 1 none. With the half-count
        // c = (count + 1/2) / (B P_REF): (1 + 0.5) / (10 x 0.1) = 1.5 and 0.5 / 1 = 0.5.
        let ps: Vec<Vec<f64>> = (0..10).map(|r| vec![if r == 3 { 0.05 } else { 0.5 }, 0.3]).collect();
        let c = null_scales(&ps, 2);
        assert!((c[0] - 1.5).abs() < 1e-12 && (c[1] - 0.5).abs() < 1e-12, "{c:?}");
    }

    #[test]
    fn the_level_is_the_quantile_of_the_smallest_rescaled_p() {
        // 39 replicates at family 0.05: order statistic floor(0.05 x 40) = 2. Replicate r has
        // p = (r + 1) / 100 for mechanism 0 and 0.9 for mechanism 1; with scales (2, 0.5) the
        // rescaled minima are min(2 (r + 1) / 100, 0.45): 0.02, 0.04, ... so the level is 0.04.
        // A failed replicate counts as 0 and moves the quantile down one place, to 0.02.
        let runs: Vec<Option<Vec<f64>>> = (0..39).map(|r| Some(vec![f64::from(r + 1) / 100.0, 0.9])).collect();
        assert!((min_p_level(&runs, &[2.0, 0.5], 0.05) - 0.04).abs() < 1e-12);
        let mut with_failure = runs.clone();
        with_failure[38] = None;
        assert!((min_p_level(&with_failure, &[2.0, 0.5], 0.05) - 0.02).abs() < 1e-12);
        assert!((min_p_level(&[], &[], 0.05) - 0.05).abs() < 1e-12);
        // A conservative mechanism (scale 0.05) at p = 0.3 rescales to 0.015 but claims at no level
        // (0.3 is above the family level), so it does not pull the level down.
        let conservative: Vec<Option<Vec<f64>>> = (0..39).map(|r| Some(vec![f64::from(r + 1) / 100.0, 0.3])).collect();
        assert!((min_p_level(&conservative, &[2.0, 0.05], 0.05) - 0.04).abs() < 1e-12);
    }

    #[test]
    fn a_mechanism_level_is_the_unit_level_over_its_scale_capped_at_the_family_level() {
        // alpha 0.01: scale 2 gives 0.005; scale 0.1 gives 0.1, capped at 0.05; an unknown
        // mechanism keeps 0.01.
        let cal = NullCalibration {
            alpha: 0.01,
            family: 0.05,
            later_rounds: 0.01,
            scale: vec![(MechanismId::SizeEffect, 2.0), (MechanismId::HeatPartition, 0.1)],
            replicates: 10,
            failed: 0,
            claims_at_family_level: 0,
        };
        assert!((cal.level_of(MechanismId::SizeEffect) - 0.005).abs() < 1e-15);
        assert!((cal.level_of(MechanismId::HeatPartition) - 0.05).abs() < 1e-15);
        assert!((cal.level_of(MechanismId::FlankWear) - 0.01).abs() < 1e-15);
    }
}
