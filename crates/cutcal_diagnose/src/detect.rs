//! Detection limits: how large a mechanism must be before this design, with its noise, would see
//! it. A `none` verdict says the data do not demand a mechanism; it does not say that none is
//! there. The limit says how much could hide.
//!
//! The limit is Baarda's (1968) minimal detectable bias, with the baseline's parameters (the
//! nuisance) profiled out under their priors:
//! - One strength parameter moves by delta typical magnitudes from its off value.
//! - The test's non-centrality is then `lambda = delta^2 left / s2`. Here `left` is the information
//!   left in the screen's sensitivity column `s` (noise units per typical move, `crate::screen`)
//!   once the baseline takes what it can: `|s|^2 - s^T J (J^T J + Lambda)^+ J^T s`, with `J` the
//!   baseline's Jacobian and `Lambda` its prior precisions (the Schur complement of the joint
//!   information, as in the refit's Wald covariance). `s2` is the residual variance in noise
//!   units, at least 1 (the stated noise).
//! - The limit is the delta at which `lambda` reaches `lambda_0(alpha, power)`: the non-centrality
//!   at which a one-degree-of-freedom test at level `alpha` rejects with that power. This is
//!   `(z_{1-alpha} + z_power)^2`, with `alpha / 2` when the parameter can move both ways (Baarda
//!   1968, NCG 2(5), Sec 2.3; Teunissen 2000, Testing theory, Sec 4.4).
//! - It is linearised at the screen's probe (a tenth of the typical move).
//!
//! Passing the significance test is necessary for a claim, not sufficient: the AICc, held-out,
//! ambiguity and instrument checks come after it.

use nalgebra::DMatrix;

use crate::fit::{self, Fit, Obs, Spec};
use crate::ftest::shape_params;
use crate::mechanism::{info, MechanismId};
use crate::problem::{Candidate, Problem};
use crate::report::DetectionLimit;
use crate::screen::nested_point;
use crate::separate::Recorded;
use crate::simulator::ParamSpec;
use crate::stats::normal_isf;

/// The power at which the limit is stated.
pub const POWER: f64 = 0.8;

/// Non-centrality at which a one-degree-of-freedom test at level `alpha` rejects with `power`
/// (Baarda 1968): `(z_{1-alpha'} + z_power)^2`, `alpha' = alpha / 2` when two-sided.
#[must_use]
pub fn noncentrality(alpha: f64, power: f64, two_sided: bool) -> f64 {
    let a = if two_sided { 0.5 * alpha } else { alpha };
    (normal_isf(a) + normal_isf(1.0 - power)).powi(2)
}

/// The prior precision `1 / sd^2` of each baseline parameter in `cols` (0 where it has none, and
/// for the parameters of mechanisms claimed in earlier rounds, which follow the baseline's).
pub(crate) fn precision(params: &[ParamSpec], cols: &[usize]) -> Vec<f64> {
    cols.iter().map(|&i| params.get(i).and_then(|p| p.prior_sd).map_or(0.0, |sd| 1.0 / (sd * sd))).collect()
}

/// One strength column's limit: typical moves per unit of `sqrt(lambda)`, and the share of the
/// column's signature the baseline absorbs with its priors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ColumnLimit {
    pub(crate) unit: f64,
    pub(crate) absorbed: f64,
}

/// The baseline's side of the profiling: its Jacobian `J` (noise units per unit of each free
/// parameter) and `(J^T J + Lambda)^+`, with `Lambda` the parameters' prior precisions (0: none).
/// It depends on the baseline alone, so one serves every mechanism and gate a screen scores.
pub(crate) struct BaselineInfo {
    j: DMatrix<f64>,
    /// `None` when there is no free column (the baseline then takes nothing).
    inverse: Option<DMatrix<f64>>,
    /// The Jacobian failed (no columns for the parameters free to move: `precision` and `j`
    /// disagree in length).
    failed: bool,
}

impl BaselineInfo {
    /// The information of the baseline columns `j` under prior precisions `precision`.
    pub(crate) fn new(j: DMatrix<f64>, precision: &[f64]) -> Self {
        let failed = precision.len() != j.ncols();
        let inverse = (!failed && j.ncols() > 0).then(|| {
            let mut info = j.transpose() * &j;
            for (i, p) in precision.iter().enumerate() {
                info[(i, i)] += p;
            }
            info.pseudo_inverse(1e-12).ok()
        });
        Self { j, inverse: inverse.flatten(), failed }
    }

    /// Per column of `s`, the part of `|s_c|^2` the baseline takes under its priors,
    /// `s_c^T J (J^T J + Lambda)^+ J^T s_c`; `None` when the Jacobian failed.
    fn taken(&self, s: &DMatrix<f64>) -> Option<Vec<f64>> {
        if self.failed {
            return None;
        }
        Some(
            (0..s.ncols())
                .map(|c| {
                    self.inverse.as_ref().map_or(0.0, |inv| {
                        let g = self.j.transpose() * s.column(c);
                        (g.transpose() * inv * &g)[(0, 0)]
                    })
                })
                .collect(),
        )
    }

    /// The limit per strength column of `s` (sensitivities, noise units per typical move) of
    /// mechanism `id`, with the baseline profiled out under its priors. The information left in a
    /// column is `|s|^2 - s^T J (J^T J + Lambda)^+ J^T s` (the Schur complement of the joint
    /// information, as in the refit's Wald covariance); the limit is `sqrt(max(s2, 1) / left)`,
    /// infinite where the baseline absorbs the column whole.
    pub(crate) fn unit_limits(&self, s: &DMatrix<f64>, s2: f64, id: MechanismId) -> Vec<ColumnLimit> {
        self.column_limits(s, s2, s.ncols().saturating_sub(shape_params(id)))
    }

    /// [`BaselineInfo::unit_limits`] of the first `strengths` columns of `s`.
    fn column_limits(&self, s: &DMatrix<f64>, s2: f64, strengths: usize) -> Vec<ColumnLimit> {
        // A baseline Jacobian that failed leaves no limit: one without the baseline's absorption
        // would understate what could hide.
        let Some(taken) = self.taken(s) else { return Vec::new() };
        (0..strengths.min(s.ncols()))
            .map(|c| {
                let total = s.column(c).norm_squared();
                let left = (total - taken[c]).max(0.0);
                let absorbed = if total > 0.0 { (taken[c] / total).clamp(0.0, 1.0) } else { 1.0 };
                let unit = if left > 1e-12 * total.max(1e-300) && left.is_finite() {
                    (s2.max(1.0) / left).sqrt()
                } else {
                    f64::INFINITY
                };
                ColumnLimit { unit, absorbed }
            })
            .collect()
    }

    /// The share of the signature `s` (all its columns) that the baseline can produce under its
    /// priors: `sum_c s_c^T J (J^T J + Lambda)^+ J^T s_c` over `sum_c |s_c|^2`, in [0, 1]. A
    /// Jacobian that failed takes nothing (0), as the screen's unprojected score test then assumes.
    pub(crate) fn absorbed_share(&self, s: &DMatrix<f64>) -> f64 {
        let total = s.norm_squared();
        match self.taken(s) {
            Some(taken) if total > 0.0 => (taken.iter().sum::<f64>() / total).clamp(0.0, 1.0),
            Some(_) => 1.0,
            None => 0.0,
        }
    }
}

/// The candidate's detection limits in its parameters' units, at level `alpha`.
pub(crate) fn limits(c: &Candidate, alpha: f64) -> Vec<DetectionLimit> {
    let inf = info(c.id);
    c.unit_limits
        .iter()
        .zip(&inf.params)
        .map(|(&ColumnLimit { unit, .. }, pi)| {
            let (down, up) = (pi.off > pi.lower, pi.off < pi.upper);
            let delta = unit * noncentrality(alpha, POWER, down && up).sqrt();
            let step = delta * (pi.typical - pi.off).abs();
            let below = (down && pi.off - step >= pi.lower).then_some(pi.off - step);
            let above = (up && pi.off + step <= pi.upper).then_some(pi.off + step);
            let mut notes = Vec::new();
            if !down || !up {
                notes.push("one-sided: the off value is a bound".to_string());
            }
            if (down && below.is_none()) || (up && above.is_none()) {
                notes.push(format!(
                    "on the open side no move within the modelled range [{}, {}] reaches the limit",
                    pi.lower, pi.upper
                ));
            }
            DetectionLimit {
                param: pi.name.into(),
                unit: pi.unit.into(),
                below: below.filter(|v| v.is_finite()),
                above: above.filter(|v| v.is_finite()),
                typical_units: delta.is_finite().then_some(delta),
                note: notes.join("; "),
            }
        })
        .collect()
}

/// The `none` verdict's sentence: which mechanisms of typical size these tests would not have
/// seen (their first strength parameter's limit beyond one typical magnitude), widest first.
pub(crate) fn unseen_sentence(cands: &[Candidate], alpha: f64) -> Option<String> {
    let mut hidden: Vec<(f64, String)> = Vec::new();
    let mut seen = 0;
    for c in cands {
        let Some(l) = limits(c, alpha).into_iter().next() else { continue };
        let t = l.typical_units.unwrap_or(f64::INFINITY);
        if t <= 1.0 {
            seen += 1;
            continue;
        }
        let unit = if l.unit == "-" { String::new() } else { format!(" {}", l.unit) };
        let range = match (l.below, l.above) {
            (Some(b), Some(a)) => format!("{} from {b:.3} to {a:.3}{unit}", l.param),
            (None, Some(a)) => format!("{} up to {a:.3}{unit}", l.param),
            (Some(b), None) => format!("{} down to {b:.3}{unit}", l.param),
            (None, None) => format!("{} anywhere in its modelled range", l.param),
        };
        let absorbed = c.unit_limits.first().map_or(0.0, |l| l.absorbed);
        let why = if absorbed > 0.9 {
            format!(", {:.1} % of whose signature the baseline's stated uncertainty also produces", 100.0 * absorbed)
        } else {
            String::new()
        };
        hidden.push((t, format!("{} ({range}){why}", c.id.as_str().replace('_', " "))));
    }
    let power = 100.0 * POWER;
    if hidden.is_empty() {
        return (seen > 0).then(|| {
            format!(
                "Each of the {seen} mechanisms tested would have been detected at its typical size ({power:.0} % \
                 power at the calibrated level)."
            )
        });
    }
    hidden.sort_by(|a, b| b.0.total_cmp(&a.0));
    let list: Vec<String> = hidden.into_iter().map(|(_, s)| s).collect();
    Some(format!(
        "A mechanism of typical size could still hide here, below what the significance test detects with \
         {power:.0} % power (`detection_limits`): {}.",
        list.join("; ")
    ))
}

/// The baseline's Jacobian (its free columns, as in the screen) on the observations `obs`, with the
/// columns' prior precisions. `None` where the model has no solution at a probe.
fn baseline_jacobian(pr: &Problem<'_>, obs: &[Obs], base: &Fit, base_spec: &Spec) -> Option<(DMatrix<f64>, Vec<f64>)> {
    let (cols, steps) = fit::free_columns(pr.sim, base_spec, &base.x);
    let j = fit::data_jacobian(pr.sim, pr.tests, obs, base_spec, &pr.cfg.noise, &base.x, &cols, &steps).ok()?;
    Some((j, precision(pr.sim.baseline_params(), &cols)))
}

/// The limit of `c`'s first strength parameter at the baseline fit, in typical moves per unit root
/// non-centrality at the stated noise (`s2` = 1), on the first `n` observations of `obs` and on all
/// of them (`jp`: the baseline's Jacobian on `obs` and its precisions). The sensitivity column is a
/// forward step of a tenth of the typical move, as in the screen. `None` where the model has no
/// solution at the probe or a limit is infinite.
fn first_limits(
    pr: &Problem<'_>,
    obs: &[Obs],
    n: usize,
    jp: &(DMatrix<f64>, Vec<f64>),
    base: &Fit,
    c: &Candidate,
) -> Option<(f64, f64)> {
    let noise = pr.cfg.noise;
    let pi = info(c.id).params[0];
    let x0 = nested_point(&base.x, c.id);
    let mut xp = x0.clone();
    xp[base.k] += 0.1 * (pi.typical - pi.off);
    let r0 = fit::residuals(obs, &fit::predict(pr.sim, pr.tests, &c.spec, &c.spec.ctx, &x0).ok()?, &noise);
    let rp = fit::residuals(obs, &fit::predict(pr.sim, pr.tests, &c.spec, &c.spec.ctx, &xp).ok()?, &noise);
    let s = DMatrix::from_iterator(obs.len(), 1, r0.iter().zip(&rp).map(|(a, b)| (b - a) / 0.1));
    let (j, prec) = jp;
    let unit =
        |j: DMatrix<f64>, s: DMatrix<f64>| BaselineInfo::new(j, prec).column_limits(&s, 1.0, 1).first().map(|l| l.unit);
    let now = unit(j.rows(0, n).into_owned(), s.rows(0, n).into_owned())?;
    let then = unit(j.clone(), s)?;
    (now.is_finite() && then.is_finite()).then_some((now, then))
}

/// For a `none` verdict on recordings without the tool-chip interface temperature: which hidden
/// mechanism recording it would expose most, and by how much its limit would narrow. Each test's
/// interface temperature rise is added at the baseline's prediction with the assumed scatter
/// (`Config::noise`, 10 % by default), and the limit of each mechanism that could hide at its
/// typical size is computed with and without it (at the stated noise, linearised as above).
pub(crate) fn interface_temperature_test(
    pr: &Problem<'_>,
    base: &Fit,
    base_spec: &Spec,
    cands: &[Candidate],
    alpha: f64,
) -> Option<String> {
    if Recorded::of(pr.tests).interface_temperature {
        return None;
    }
    let extra: Vec<Obs> = base
        .preds
        .iter()
        .enumerate()
        .map(|(i, p)| Obs { test: i, output: 3, value: fit::output(p, 3) })
        .filter(|o| o.value.is_finite() && o.value > 0.0)
        .collect();
    if extra.len() < pr.tests.len() {
        return None;
    }
    let with: Vec<Obs> = pr.obs.iter().copied().chain(extra).collect();
    let jp = baseline_jacobian(pr, &with, base, base_spec)?;
    let mut best: Option<(f64, &Candidate, f64, f64)> = None;
    for c in cands.iter().filter(|c| limits(c, alpha).first().is_some_and(|l| l.typical_units.is_none_or(|t| t > 1.0)))
    {
        let Some((now, then)) = first_limits(pr, &with, pr.obs.len(), &jp, base, c) else { continue };
        let gain = now / then;
        if gain > 1.5 && best.as_ref().is_none_or(|b| gain > b.0) {
            best = Some((gain, c, now, then));
        }
    }
    // The interval the report states (`limits`, at the screen's residual variance), and the same
    // narrowed by the ratio the two computations here give.
    let (_, c, now_here, then_here) = best?;
    let now = c.unit_limits.first()?.unit;
    let then = now * then_here / now_here;
    let pi = info(c.id).params[0];
    let both = pi.off > pi.lower && pi.off < pi.upper;
    let lambda = noncentrality(alpha, POWER, both).sqrt();
    let unit = if pi.unit == "-" { String::new() } else { format!(" {}", pi.unit) };
    // The interval of values that would hide, each end marked where it is the modelled range's.
    let range = |u: f64| {
        let step = u * lambda * (pi.typical - pi.off).abs();
        let end = |v: f64, bound: f64, open: bool| match (open, (v - bound) * (pi.off - bound) <= 0.0) {
            (false, _) => format!("{:.3}", pi.off),
            (true, true) => format!("{bound:.3} (bound)"),
            (true, false) => format!("{v:.3}"),
        };
        format!(
            "[{}, {}]{unit}",
            end(pi.off - step, pi.lower, pi.off > pi.lower),
            end(pi.off + step, pi.upper, pi.off < pi.upper)
        )
    };
    Some(format!(
        "none needed to explain these data; to see a {} of typical size, record the tool-chip interface temperature \
         (t_int_c) at these conditions: at {:.0} % scatter the values of {} that could hide would narrow from {} to {} \
         (80 % power, linearised)",
        c.id.as_str().replace('_', " "),
        100.0 * pr.cfg.noise[3],
        pi.name,
        range(now),
        range(then)
    ))
}

/// A mechanism's detection limits in one line of the text report: each parameter's detected
/// region, or that no move within its range is.
pub(crate) fn limits_text(limits: &[DetectionLimit]) -> String {
    let one = |l: &DetectionLimit| match (l.below, l.above) {
        (Some(b), Some(a)) => format!("{} <= {b:.4} or >= {a:.4}", l.param),
        (Some(b), None) => format!("{} <= {b:.4}", l.param),
        (None, Some(a)) => format!("{} >= {a:.4}", l.param),
        (None, None) => format!("{}: no move within its range", l.param),
    };
    limits.iter().map(one).collect::<Vec<_>>().join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::normal_sf;

    #[test]
    fn the_quantiles_and_baardas_noncentralities_are_the_published_ones() {
        // Standard normal table: z_0.975 = 1.959964, z_0.8 = 0.841621.
        assert!((normal_isf(0.025) - 1.959_964).abs() < 1e-6);
        assert!((normal_isf(0.2) - 0.841_621).abs() < 1e-6);
        // Baarda (1968): lambda_0 = 17.07 at alpha_0 = 0.001 and beta_0 = 0.80 (his standard
        // setting); 7.85 at alpha = 0.05 (Cohen 1988's power tables give the same).
        assert!((noncentrality(0.001, 0.8, true) - 17.07).abs() < 0.01);
        assert!((noncentrality(0.05, 0.8, true) - 7.85).abs() < 0.01);
        // One-sided: (z_0.95 + z_0.8)^2 = (1.644854 + 0.841621)^2 = 6.1826.
        assert!((noncentrality(0.05, 0.8, false) - 6.1826).abs() < 1e-3);
    }

    proptest::proptest! {
        /// The absorbed share lies in [0, 1]; with no prior it is the share the orthogonal
        /// projection onto the baseline's columns takes (`fit::project_out`, an SVD, computed
        /// independently of the pseudo-inverse used here); a tighter prior never lets the baseline
        /// take more.
        #[test]
        fn the_absorbed_share_is_the_projection_without_priors_and_falls_as_they_tighten(
            vals in proptest::collection::vec(-1.0f64..1.0, 7 * 5),
            prec in proptest::collection::vec(0.0f64..4.0, 3),
        ) {
            let j = DMatrix::from_column_slice(7, 3, &vals[..21]);
            let s = DMatrix::from_column_slice(7, 2, &vals[21..35]);
            proptest::prop_assume!(s.norm_squared() > 1e-6);
            let free = BaselineInfo::new(j.clone(), &[0.0; 3]).absorbed_share(&s);
            let projected = 1.0 - fit::project_out(&j, &s).norm_squared() / s.norm_squared();
            proptest::prop_assert!((free - projected).abs() < 1e-8, "{free} vs {projected}");
            let tied = BaselineInfo::new(j.clone(), &prec).absorbed_share(&s);
            let tighter: Vec<f64> = prec.iter().map(|p| 2.0 * p + 0.1).collect();
            let tightest = BaselineInfo::new(j.clone(), &tighter).absorbed_share(&s);
            proptest::prop_assert!((0.0..=1.0).contains(&tied) && (0.0..=1.0).contains(&tightest));
            proptest::prop_assert!(tied <= free + 1e-9 && tightest <= tied + 1e-9, "{free} {tied} {tightest}");
        }

        /// The quantile inverts the tail, and the non-centrality grows as the level tightens and as
        /// the power rises.
        #[test]
        fn the_quantile_inverts_the_tail_and_the_limit_moves_the_right_way(
            lp in -12.0f64..-0.01, a in 1e-4f64..0.2, pw in 0.5f64..0.99,
        ) {
            let p = 10f64.powf(lp);
            let z = normal_isf(p);
            proptest::prop_assert!((normal_sf(z) / p - 1.0).abs() < 1e-6);
            proptest::prop_assert!(noncentrality(0.5 * a, pw, true) > noncentrality(a, pw, true));
            proptest::prop_assert!(noncentrality(a, 0.5 * (pw + 1.0), true) > noncentrality(a, pw, true));
            proptest::prop_assert!(noncentrality(a, pw, true) > noncentrality(a, pw, false));
        }
    }

    #[test]
    fn the_information_left_is_the_schur_complement_worked_by_hand() {
        // Baseline column j = (1, 0, 0), mechanism columns s1 = (2, 0, 0) (all in j's direction)
        // and s2 = (3, 4, 0).
        let j = DMatrix::from_column_slice(3, 1, &[1.0, 0.0, 0.0]);
        let s = DMatrix::from_column_slice(3, 2, &[2.0, 0.0, 0.0, 3.0, 4.0, 0.0]);
        // No prior: the baseline takes s1 whole and the 3 of s2; 16 is left, the limit 1/4 (s2 below
        // the stated noise counts as 1).
        let free = BaselineInfo::new(j.clone(), &[0.0]).unit_limits(&s, 0.25, MechanismId::HeatPartition);
        assert!(free[0].unit.is_infinite() && (free[0].absorbed - 1.0).abs() < 1e-12);
        assert!((free[1].unit - 0.25).abs() < 1e-12 && (free[1].absorbed - 9.0 / 25.0).abs() < 1e-12);
        // A prior of precision 1: the baseline takes g^2 / (1 + 1) of each, g = j . s: 4 / 2 = 2 of
        // s1's 4 (limit 1 / sqrt(2)), 9 / 2 of s2's 25 (limit 1 / sqrt(20.5)).
        let tied = BaselineInfo::new(j.clone(), &[1.0]).unit_limits(&s, 1.0, MechanismId::HeatPartition);
        assert!((tied[0].unit - 0.5f64.sqrt()).abs() < 1e-12 && (tied[0].absorbed - 0.5).abs() < 1e-12);
        assert!((tied[1].unit - 1.0 / 20.5f64.sqrt()).abs() < 1e-12);
        // The signature's share the baseline produces, over both columns: without a prior 4 + 9 of
        // 29; with the prior 2 + 4.5 of 29; with a failed Jacobian (no columns) nothing.
        assert!((BaselineInfo::new(j.clone(), &[0.0]).absorbed_share(&s) - 13.0 / 29.0).abs() < 1e-12);
        assert!((BaselineInfo::new(j.clone(), &[1.0]).absorbed_share(&s) - 6.5 / 29.0).abs() < 1e-12);
        assert_eq!(BaselineInfo::new(DMatrix::zeros(3, 0), &[1.0]).absorbed_share(&s), 0.0);
    }
}
