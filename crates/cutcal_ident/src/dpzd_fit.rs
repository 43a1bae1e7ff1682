//! Johnson-Cook identification from one DPZD zone solution (paper Eq 15).
//!
//! The target at the `N` interior points is the DPZD effective stress `F_k = sqrt(3) tau_e(x_k)`
//! (Eq 8); the model is the JC stress (Eq 16) at the DPZD strain, strain rate and temperature of the
//! same point. Least squares in MPa over `[A, B, n, C, m]` within box bounds: unweighted at `N`
//! uniform points (the paper's discrete Eq 15), or weighted by a quadrature rule so that the sum
//! approximates the zone integral `(1/h) int (f - F)^2 dx` (see [`crate::quadrature`]).

use cutcal_model::dpzd::{ZonePoint, ZoneSolution};
use cutcal_model::{JcParams, RateTerm};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::error::IdentError;
use crate::lm::{Bounds, Problem};
use crate::multistart::{
    fit_statistics, multistart_from, FitStatistics, MultistartOptions, DPZD_BASIN_RADIUS, MLSL_SIGMA,
};
use crate::varpro::VarproProblem;

/// Parameter names in the order of the optimisation vector.
pub const JC_NAMES: [&str; 5] = ["a_mpa", "b_mpa", "n", "c", "m"];

/// Largest upper bounds accepted for `[A_MPa, B_MPa, n, C, m]` (A, B: 100 GPa; n <= 2 and
/// m <= 10 as in `JcParams::validate`; C <= 10).
pub const JC_UPPER_LIMITS: [f64; 5] = [1e5, 1e5, 2.0, 10.0, 10.0];

/// Box bounds of the JC identification (A and B in MPa).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JcBounds {
    /// A, MPa.
    pub a_mpa: [f64; 2],
    /// B, MPa.
    pub b_mpa: [f64; 2],
    /// n.
    pub n: [f64; 2],
    /// C.
    pub c: [f64; 2],
    /// m.
    pub m: [f64; 2],
}

impl JcBounds {
    /// The bounds as a validated [`Bounds`].
    pub fn to_bounds(&self) -> Result<Bounds, IdentError> {
        let pairs = [self.a_mpa, self.b_mpa, self.n, self.c, self.m];
        for (name, [lo, hi]) in JC_NAMES.iter().zip(pairs) {
            if !(lo.is_finite() && hi.is_finite() && lo <= hi && lo >= 0.0) {
                return Err(IdentError::InvalidBounds { parameter: (*name).into(), low: lo, high: hi });
            }
        }
        if self.m[0] <= 0.0 {
            return Err(IdentError::InvalidBounds { parameter: "m".into(), low: self.m[0], high: self.m[1] });
        }
        // Upper limits of a physical JC set (n and m as in `JcParams::validate`); beyond them the
        // residuals overflow (found by fuzzing: B <= 4.8e194 MPa gave an infinite objective).
        for (name, hi, cap) in [
            ("a_mpa", self.a_mpa[1], JC_UPPER_LIMITS[0]),
            ("b_mpa", self.b_mpa[1], JC_UPPER_LIMITS[1]),
            ("n", self.n[1], JC_UPPER_LIMITS[2]),
            ("c", self.c[1], JC_UPPER_LIMITS[3]),
            ("m", self.m[1], JC_UPPER_LIMITS[4]),
        ] {
            if hi > cap {
                let low = match name {
                    "a_mpa" => self.a_mpa[0],
                    "b_mpa" => self.b_mpa[0],
                    "n" => self.n[0],
                    "c" => self.c[0],
                    _ => self.m[0],
                };
                return Err(IdentError::InvalidBounds { parameter: name.into(), low, high: hi });
            }
        }
        Bounds::new(
            JC_NAMES.iter().map(|s| (*s).to_string()).collect(),
            pairs.iter().map(|p| p[0]).collect(),
            pairs.iter().map(|p| p[1]).collect(),
        )
    }
}

/// The constants of the JC law that are not identified.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JcConstants {
    /// Reference strain rate, 1/s.
    pub eps0_per_s: f64,
    /// Melting temperature, degC.
    pub tm_c: f64,
    /// Reference temperature, degC.
    pub tr_c: f64,
}

impl JcConstants {
    /// JC parameters from an optimisation vector `[A_MPa, B_MPa, n, C, m]`.
    #[must_use]
    pub fn params(&self, p: &DVector<f64>) -> JcParams {
        JcParams {
            a_pa: p[0] * 1e6,
            b_pa: p[1] * 1e6,
            n: p[2],
            c: p[3],
            m: p[4],
            eps0_per_s: self.eps0_per_s,
            tm_c: self.tm_c,
            tr_c: self.tr_c,
        }
    }
}

/// The Eq 15 least-squares problem over a set of zone points.
///
/// The logarithms that do not depend on the parameters (`ln eps`, `ln(epsdot/eps0)`,
/// `ln theta`) are computed once, so a residual costs two `exp` per point; the values equal
/// [`JcParams::flow_stress`] and [`JcParams::gradient`] (checked in the tests).
#[derive(Debug, Clone)]
pub struct ZoneFitProblem {
    points: Vec<ZonePoint>,
    constants: JcConstants,
    rate_term: RateTerm,
    weight_sum: f64,
    cached: Vec<CachedPoint>,
}

/// Parameter-independent parts of the JC law at one point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CachedPoint {
    /// `ln eps`, or `None` where eps = 0 (then eps^n = 0 for n > 0).
    pub(crate) ln_strain: Option<f64>,
    /// `ln(epsdot/eps0)` as it enters the law (clamped at 0 for [`RateTerm::Clamped`]).
    pub(crate) ln_rate: f64,
    /// Square root of the quadrature weight (1 for the uniform discrete objective).
    pub(crate) sqrt_weight: f64,
    /// `ln theta`, or `None` where the homologous temperature is 0 (no softening).
    pub(crate) ln_theta: Option<f64>,
    /// Target `sqrt(3) tau_e`, MPa.
    pub(crate) target_mpa: f64,
}

impl ZoneFitProblem {
    /// A problem over the given points, unit weights, the solvers' clamped law.
    #[must_use]
    pub fn new(points: Vec<ZonePoint>, constants: JcConstants) -> Self {
        let w = vec![1.0; points.len()];
        Self::weighted(points, &w, constants, RateTerm::Clamped)
    }

    /// A problem with quadrature weights `weights` (>= 0, one per point) and an explicit rate term.
    ///
    /// The residuals are `sqrt(w_k) (f_k - F_k)`, so the SSR is `sum w_k (f_k - F_k)^2`.
    #[must_use]
    pub fn weighted(points: Vec<ZonePoint>, weights: &[f64], constants: JcConstants, rate_term: RateTerm) -> Self {
        let probe = JcParams {
            a_pa: 0.0,
            b_pa: 0.0,
            n: 0.0,
            c: 0.0,
            m: 1.0,
            eps0_per_s: constants.eps0_per_s,
            tm_c: constants.tm_c,
            tr_c: constants.tr_c,
        };
        let cached = points
            .iter()
            .zip(weights)
            .map(|(p, w)| {
                let theta = probe.homologous(p.temperature_c);
                CachedPoint {
                    ln_strain: (p.strain > 0.0).then(|| p.strain.ln()),
                    ln_rate: rate_term.log_ratio(p.strain_rate_per_s, constants.eps0_per_s),
                    sqrt_weight: w.max(0.0).sqrt(),
                    ln_theta: (theta > 0.0).then(|| theta.ln()),
                    target_mpa: p.effective_stress_pa / 1e6,
                }
            })
            .collect();
        let weight_sum = weights.iter().map(|w| w.max(0.0)).sum();
        Self { points, constants, rate_term, weight_sum, cached }
    }

    /// The rate term of the law fitted.
    #[must_use]
    pub fn rate_term(&self) -> RateTerm {
        self.rate_term
    }

    /// Unweighted residuals `f_k - F_k` in MPa at `p` (A, B in MPa).
    #[must_use]
    pub fn raw_residuals(&self, p: &DVector<f64>) -> Vec<f64> {
        self.raw_residuals_iter(p).collect()
    }

    /// [`Self::raw_residuals`] without the allocation, paired with the targets `F_k` (MPa).
    pub(crate) fn raw_residuals_iter<'s>(&'s self, p: &'s DVector<f64>) -> impl Iterator<Item = f64> + 's {
        self.cached.iter().map(move |c| Self::eval(p, c).0 - c.target_mpa)
    }

    /// The targets `F_k = sqrt(3) tau_e` (MPa) of the points.
    pub(crate) fn targets_mpa(&self) -> impl Iterator<Item = f64> + '_ {
        self.cached.iter().map(|c| c.target_mpa)
    }

    /// One problem from parts with the same constants and rate term, each point's weight
    /// multiplied by the weight given with its part (one per point): a quadrature rule assembled
    /// from its panels without re-evaluating the zone points or their logarithms.
    pub(crate) fn from_weighted_parts<'p>(
        parts: impl IntoIterator<Item = (&'p ZoneFitProblem, &'p [f64])>,
        constants: JcConstants,
        rate_term: RateTerm,
    ) -> Self {
        let parts: Vec<_> = parts.into_iter().collect();
        let total = parts.iter().map(|(part, _)| part.points.len()).sum();
        let (mut points, mut cached, mut weight_sum) = (Vec::with_capacity(total), Vec::with_capacity(total), 0.0);
        for (part, weights) in parts {
            debug_assert!(part.rate_term == rate_term && part.constants == constants);
            points.extend_from_slice(&part.points);
            for (c, w) in part.cached.iter().zip(weights) {
                let w = w.max(0.0);
                weight_sum += c.sqrt_weight * c.sqrt_weight * w;
                cached.push(CachedPoint { sqrt_weight: c.sqrt_weight * w.sqrt(), ..*c });
            }
        }
        Self { points, constants, rate_term, weight_sum, cached }
    }

    /// The points.
    #[must_use]
    pub fn points(&self) -> &[ZonePoint] {
        &self.points
    }

    /// The same problem with A and B (MPa) eliminated by variable projection ([`crate::varpro`]).
    #[must_use]
    pub fn projected(&self, a_box_mpa: [f64; 2], b_box_mpa: [f64; 2]) -> VarproProblem<'_> {
        VarproProblem::new(&self.cached, a_box_mpa, b_box_mpa)
    }

    /// JC stress in MPa and its gradient w.r.t. `[A_MPa, B_MPa, n, C, m]` at one cached point.
    #[inline]
    fn eval(p: &DVector<f64>, c: &CachedPoint) -> (f64, [f64; 5]) {
        let (a, b, n, cc, m) = (p[0], p[1], p[2], p[3], p[4]);
        let (en, d_en_dn) = match c.ln_strain {
            Some(l) => {
                let e = (n * l).exp();
                (e, e * l)
            }
            None if n == 0.0 => (1.0, 0.0),
            None => (0.0, 0.0),
        };
        let h = a + b * en;
        let rf = 1.0 + cc * c.ln_rate;
        let (tm, d_tm_dm) = match c.ln_theta {
            Some(l) => {
                let t = (m * l).exp();
                (t, t * l)
            }
            None => (0.0, 0.0),
        };
        let g = 1.0 - tm;
        (h * rf * g, [rf * g, en * rf * g, b * d_en_dn * rf * g, h * c.ln_rate * g, -h * rf * d_tm_dm])
    }
}

impl Problem for ZoneFitProblem {
    fn parameter_count(&self) -> usize {
        5
    }

    fn residual_count(&self) -> usize {
        self.points.len()
    }

    /// `f_k(x) - F_k` in MPa (paper Eq 15).
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        for (o, c) in out.iter_mut().zip(&self.cached) {
            *o = c.sqrt_weight * (Self::eval(p, c).0 - c.target_mpa);
        }
        Ok(())
    }

    /// Analytic Jacobian (MPa per parameter unit; A and B are in MPa in the vector).
    fn jacobian(&self, p: &DVector<f64>, _bounds: &Bounds, out: &mut DMatrix<f64>) -> Result<(), IdentError> {
        for (i, c) in self.cached.iter().enumerate() {
            let g = Self::eval(p, c).1;
            for (k, gk) in g.iter().enumerate() {
                out[(i, k)] = c.sqrt_weight * *gk;
            }
        }
        Ok(())
    }
}

/// An identified JC set with the quality of the fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JcIdentification {
    /// The identified parameters.
    pub jc: JcParams,
    /// Eq 15 objective `sqrt(sum w_k (F - f)^2)`, MPa (w = 1 for the uniform points; for a
    /// quadrature rule the weights sum to 1, so this is the zone RMS).
    pub objective_mpa: f64,
    /// RMS residual, MPa.
    pub rms_mpa: f64,
    /// Rate term of the fitted law.
    pub rate_term: RateTerm,
    /// Positions of the fit points (uniform points or quadrature nodes), m.
    pub fit_x_m: Vec<f64>,
    /// Residual field `f_k - F_k` (unweighted) at the fit points, MPa.
    pub residuals_mpa: Vec<f64>,
    /// Fit statistics (at-bound parameters, covariance, correlation).
    pub statistics: FitStatistics,
    /// Starts run.
    pub starts: usize,
    /// Starts that reached the best minimum (including those stopped by the basin rule on
    /// joining it: `stopped_at_best`).
    pub starts_at_best: usize,
    /// Starts stopped by the multistart basin rule ([`crate::multistart`]) on entering the basin
    /// of a minimum an earlier start had converged to (0 when the rule is off).
    pub stopped_starts: usize,
    /// Of `stopped_starts`, those that joined the best minimum.
    pub stopped_at_best: usize,
    /// Start index of the best minimum.
    pub best_start: usize,
    /// Starts that failed.
    pub failed_starts: usize,
    /// LM iterations of the best start.
    pub iterations: usize,
    /// Why the best start's LM stopped (never the iteration cap: that is an error).
    pub termination: crate::lm::Termination,
    /// Starts that hit the LM iteration cap (excluded from the best).
    pub unconverged_starts: usize,
    /// Sample points from which no local search was started (MLSL's critical-distance filter,
    /// [`crate::multistart::SampleFilter`]); they never count in `starts_at_best`.
    pub filtered_starts: usize,
    /// The MLSL critical distance applied (unit box of `(n, C, m)`; `None`: no filter).
    pub critical_distance: Option<f64>,
}

/// Identifies JC from the `points` interior points of a zone solution (paper Eq 15).
///
/// **Source:** paper Sec 4.1, Eq 15 with Eqs 13-16.
///
/// Returns an error if the zone fields cannot be evaluated, the bounds are invalid or every start fails.
pub fn identify_from_zone(
    zone: &ZoneSolution,
    points: usize,
    bounds: &JcBounds,
    constants: JcConstants,
    options: &MultistartOptions,
) -> Result<JcIdentification, IdentError> {
    identify_from_zone_with(zone, points, RateTerm::Clamped, bounds, constants, options)
}

/// As [`identify_from_zone`] with an explicit rate term ([`RateTerm::Unclamped`] is the paper's
/// literal Eq 16, used by the `paper` preset only).
///
/// **Source:** paper Sec 4.1, Eq 15 with Eqs 13-16.
///
/// Returns an error as [`identify_from_zone`].
pub fn identify_from_zone_with(
    zone: &ZoneSolution,
    points: usize,
    rate_term: RateTerm,
    bounds: &JcBounds,
    constants: JcConstants,
    options: &MultistartOptions,
) -> Result<JcIdentification, IdentError> {
    if points < 6 {
        return Err(IdentError::InvalidOptions(format!("at least 6 fit points are needed, got {points}")));
    }
    let pts = zone.interior_points(points)?;
    let w = vec![1.0; pts.len()];
    let problem = ZoneFitProblem::weighted(pts, &w, constants, rate_term);
    identify(&problem, bounds, options)
}

/// Runs the multistart identification on an assembled problem.
///
/// The multistart runs over `(n, C, m)` on the variable-projection problem ([`crate::varpro`]):
/// A and B are solved exactly for each `(n, C, m)`, so the result is the minimum of the same
/// Eq 15 objective over `[A, B, n, C, m]`; the statistics use the full 5-parameter Jacobian.
/// Starts are stopped by the basin rule of [`crate::multistart`] with radius
/// [`DPZD_BASIN_RADIUS`] unless `options.basin_stop` says otherwise.
///
/// **Source:** paper Eq 15; Golub and Pereyra (1973) variable projection.
pub fn identify(
    problem: &ZoneFitProblem,
    bounds: &JcBounds,
    options: &MultistartOptions,
) -> Result<JcIdentification, IdentError> {
    identify_warm(problem, bounds, options, None)
}

/// [`identify`] with the first start at `warm` (`[A_MPa, B_MPa, n, C, m]`; only n, C and m are
/// used, A and B are solved exactly) instead of the centre of the box.
///
/// **Source:** paper Eq 15; Golub and Pereyra (1973) variable projection.
///
/// Returns an error as [`identify`].
pub fn identify_warm(
    problem: &ZoneFitProblem,
    bounds: &JcBounds,
    options: &MultistartOptions,
    warm: Option<&DVector<f64>>,
) -> Result<JcIdentification, IdentError> {
    identify_warm_with(problem, bounds, options, warm, true)
}

/// [`identify_warm`]; with `statistics` false the covariance, correlation, standard errors and
/// condition number are not computed (`None`; the Monte-Carlo samples, which keep only the set).
pub(crate) fn identify_warm_with(
    problem: &ZoneFitProblem,
    bounds: &JcBounds,
    options: &MultistartOptions,
    warm: Option<&DVector<f64>>,
    statistics: bool,
) -> Result<JcIdentification, IdentError> {
    let b = bounds.to_bounds()?;
    let projected = problem.projected(bounds.a_mpa, bounds.b_mpa);
    let nonlinear = Bounds::new(
        JC_NAMES[2..].iter().map(|s| (*s).to_string()).collect(),
        vec![bounds.n[0], bounds.c[0], bounds.m[0]],
        vec![bounds.n[1], bounds.c[1], bounds.m[1]],
    )?;
    let radius = options.basin_stop.radius(Some(DPZD_BASIN_RADIUS));
    if let Some(w) = warm.filter(|w| w.len() != 5) {
        return Err(IdentError::InvalidOptions(format!("a warm start needs [A, B, n, C, m], got {} values", w.len())));
    }
    let first = warm.map(|w| DVector::from_vec(vec![w[2], w[3], w[4]]));
    let sigma = options.sample_filter.sigma(Some(MLSL_SIGMA));
    let mut report = multistart_from(&projected, &nonlinear, options, radius, sigma, first.as_ref())?;
    report.best.params = projected.full_parameters(&report.best.params);
    if report.best.termination == crate::lm::Termination::MaxIterations {
        // Every projected start stopped at the cap (a flat n-m valley): continue the best one with
        // the full 5-parameter LM from where it stopped, and keep that if it converges.
        if let Ok(more) = crate::lm::minimise(problem, &b, &report.best.params, &options.lm) {
            if more.termination != crate::lm::Termination::MaxIterations && more.ssr <= report.best.ssr {
                let iterations = report.best.iterations + more.iterations;
                report.best = crate::lm::LmResult { iterations, ..more };
            }
        }
    }
    if report.best.termination == crate::lm::Termination::MaxIterations {
        return Err(IdentError::NotConverged {
            what: format!("Levenberg-Marquardt (all {} starts)", report.starts),
            iterations: report.best.iterations,
            detail: format!(
                "every start stopped at the iteration cap; the best objective was {:.4e} MPa^2 (raise the cap or check the bounds)",
                report.best.ssr
            ),
        });
    }
    if !report.best.ssr.is_finite() {
        return Err(IdentError::NonFinite {
            what: "objective".into(),
            params: report.best.params.iter().copied().collect(),
        });
    }
    let stats = if statistics {
        fit_statistics(problem, &b, &report.best.params, &report.best.residuals)?
    } else {
        FitStatistics::without_covariance(&b, &report.best.params, &report.best.residuals)
    };
    let jc = problem.constants.params(&report.best.params);
    Ok(JcIdentification {
        jc,
        objective_mpa: report.best.ssr.sqrt(),
        rms_mpa: (report.best.ssr / problem.weight_sum.max(f64::MIN_POSITIVE)).sqrt(),
        rate_term: problem.rate_term,
        fit_x_m: problem.points.iter().map(|p| p.x_m).collect(),
        residuals_mpa: problem.raw_residuals(&report.best.params),
        statistics: stats,
        starts: report.starts,
        starts_at_best: report.starts_at_best,
        stopped_starts: report.stopped_starts,
        stopped_at_best: report.stopped_at_best,
        best_start: report.best_start,
        failed_starts: report.failed_starts,
        iterations: report.best.iterations,
        termination: report.best.termination,
        unconverged_starts: report.unconverged_starts,
        filtered_starts: report.filtered_starts,
        critical_distance: report.critical_distance,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point(strain: f64, rate: f64, t: f64) -> ZonePoint {
        ZonePoint {
            x_m: 0.0,
            gamma: strain * 3f64.sqrt(),
            gamma_dot_per_s: rate * 3f64.sqrt(),
            strain,
            strain_rate_per_s: rate,
            tau_pa: 0.0,
            effective_stress_pa: 0.0,
            work_j_per_m3: 0.0,
            temperature_c: t,
        }
    }

    proptest! {
        // The cached evaluation equals JcParams::flow_stress / gradient (the reference law, Eq 16).
        #[test]
        fn cached_law_equals_reference(
            a in 100.0..1000.0f64, b in 0.0..1000.0f64, n in 0.0..0.7f64, c in 0.0..0.2f64, m in 0.7..1.3f64,
            eps in 0.0..3.0f64, lrate in 0.0..12.0f64, t in 0.0..1400.0f64,
        ) {
            let k = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };
            let prob = ZoneFitProblem::new(vec![point(eps, lrate.exp(), t)], k);
            let pv = DVector::from_vec(vec![a, b, n, c, m]);
            let (s, g) = ZoneFitProblem::eval(&pv, &prob.cached[0]);
            let jc = k.params(&pv);
            let want = jc.flow_stress(eps, lrate.exp(), t) / 1e6;
            prop_assert!((s - want).abs() <= 1e-9 * want.abs().max(1.0));
            let gr = jc.gradient(eps, lrate.exp(), t);
            let scale = [1.0, 1.0, 1e-6, 1e-6, 1e-6];
            for k in 0..5 {
                prop_assert!((g[k] - gr[k] * scale[k]).abs() <= 1e-9 * (gr[k] * scale[k]).abs().max(1e-9), "k {}", k);
            }
        }
    }
}
