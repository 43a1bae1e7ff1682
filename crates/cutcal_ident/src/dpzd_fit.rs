//! Johnson-Cook identification from one DPZD zone solution (paper Eq 15).
//!
//! The target at the `N` interior points is the DPZD effective stress `F_k = sqrt(3) tau_e(x_k)`
//! (Eq 8); the model is the JC stress (Eq 16) at the DPZD strain, strain rate and temperature of the
//! same point. Unweighted least squares in MPa over `[A, B, n, C, m]` within box bounds.

use cutcal_model::dpzd::{ZonePoint, ZoneSolution};
use cutcal_model::JcParams;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::error::IdentError;
use crate::lm::{Bounds, Problem};
use crate::multistart::{fit_statistics, multistart, FitStatistics, MultistartOptions};

/// Parameter names in the order of the optimisation vector.
pub const JC_NAMES: [&str; 5] = ["a_mpa", "b_mpa", "n", "c", "m"];

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
#[derive(Debug, Clone)]
pub struct ZoneFitProblem {
    points: Vec<ZonePoint>,
    constants: JcConstants,
}

impl ZoneFitProblem {
    /// A problem over the given points.
    #[must_use]
    pub fn new(points: Vec<ZonePoint>, constants: JcConstants) -> Self {
        Self { points, constants }
    }

    /// The points.
    #[must_use]
    pub fn points(&self) -> &[ZonePoint] {
        &self.points
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
        let jc = self.constants.params(p);
        for (o, pt) in out.iter_mut().zip(&self.points) {
            *o = (jc.flow_stress(pt.strain, pt.strain_rate_per_s, pt.temperature_c) - pt.effective_stress_pa) / 1e6;
        }
        Ok(())
    }

    /// Analytic Jacobian from [`JcParams::gradient`] (MPa per parameter unit).
    fn jacobian(&self, p: &DVector<f64>, _bounds: &Bounds, out: &mut DMatrix<f64>) -> Result<(), IdentError> {
        let jc = self.constants.params(p);
        for (i, pt) in self.points.iter().enumerate() {
            let g = jc.gradient(pt.strain, pt.strain_rate_per_s, pt.temperature_c);
            // A and B are in MPa in the vector: d(sigma/1e6)/d(A_MPa) = dsigma/dA_Pa.
            out[(i, 0)] = g[0];
            out[(i, 1)] = g[1];
            out[(i, 2)] = g[2] / 1e6;
            out[(i, 3)] = g[3] / 1e6;
            out[(i, 4)] = g[4] / 1e6;
        }
        Ok(())
    }
}

/// An identified JC set with the quality of the fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JcIdentification {
    /// The identified parameters.
    pub jc: JcParams,
    /// Eq 15 objective `sqrt(sum (F - f)^2)`, MPa.
    pub objective_mpa: f64,
    /// RMS residual, MPa.
    pub rms_mpa: f64,
    /// Residual field `f_k - F_k` at the fit points, MPa.
    pub residuals_mpa: Vec<f64>,
    /// Fit statistics (at-bound parameters, covariance, correlation).
    pub statistics: FitStatistics,
    /// Starts run.
    pub starts: usize,
    /// Starts that reached the best minimum.
    pub starts_at_best: usize,
    /// Start index of the best minimum.
    pub best_start: usize,
    /// Starts that failed.
    pub failed_starts: usize,
    /// LM iterations of the best start.
    pub iterations: usize,
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
    if points < 6 {
        return Err(IdentError::InvalidOptions(format!("at least 6 fit points are needed, got {points}")));
    }
    let problem = ZoneFitProblem::new(zone.interior_points(points)?, constants);
    identify(&problem, bounds, options)
}

/// Runs the multistart identification on an assembled problem.
pub fn identify(
    problem: &ZoneFitProblem,
    bounds: &JcBounds,
    options: &MultistartOptions,
) -> Result<JcIdentification, IdentError> {
    let b = bounds.to_bounds()?;
    let report = multistart(problem, &b, options)?;
    let stats = fit_statistics(problem, &b, &report.best.params, &report.best.residuals)?;
    let jc = problem.constants.params(&report.best.params);
    Ok(JcIdentification {
        jc,
        objective_mpa: report.best.ssr.sqrt(),
        rms_mpa: stats.rms,
        residuals_mpa: report.best.residuals.iter().copied().collect(),
        statistics: stats,
        starts: report.starts,
        starts_at_best: report.starts_at_best,
        best_start: report.best_start,
        failed_starts: report.failed_starts,
        iterations: report.best.iterations,
    })
}
