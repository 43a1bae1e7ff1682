//! Johnson-Cook identification from one DPZD zone solution (paper Eq 15).
//!
//! The target at the `N` interior points is the DPZD effective stress `F_k = sqrt(3) tau_e(x_k)`
//! (Eq 8); the model is the JC stress (Eq 16) at the DPZD strain, strain rate and temperature of the
//! same point. Least squares in MPa over `[A, B, n, C, m]` within box bounds: unweighted at `N`
//! uniform points (the paper's discrete Eq 15), or weighted by a quadrature rule so that the sum
//! approximates the zone integral `(1/h) int (f - F)^2 dx` (see [`crate::quadrature`]).

use cutcal_model::dpzd::ZoneSolution;
use cutcal_model::{JcParams, RateTerm};
use nalgebra::DVector;
use serde::Serialize;

use crate::error::IdentError;
use crate::lm::Bounds;
use crate::multistart::{
    fit_statistics, multistart_from, FitStatistics, MultistartOptions, DPZD_BASIN_RADIUS, MLSL_SIGMA,
};
pub use crate::zone_problem::{JcConstants, ZoneFitProblem};

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
        rate_term: problem.rate_term(),
        fit_x_m: problem.points().iter().map(|p| p.x_m).collect(),
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
