//! Fit statistics of a least-squares solution: SSR, RMS, the parameters at a bound, and the
//! covariance `s^2 (J^T J)^-1` with its correlation matrix and condition number (what the data
//! cannot pin down).

use nalgebra::{DMatrix, DVector};

use crate::error::IdentError;
use crate::lm::{Bounds, Problem};

/// Quality of a least-squares fit and what the data cannot pin down.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FitStatistics {
    /// Sum of squared residuals.
    pub ssr: f64,
    /// Root mean square residual.
    pub rms: f64,
    /// Names of parameters at a bound (or fixed).
    pub at_bounds: Vec<String>,
    /// Names of the free parameters, the order of the matrices below.
    pub free: Vec<String>,
    /// Covariance of the free parameters, `s^2 (J^T J)^-1`, `s^2 = SSR/(m - p)`; `None` if singular
    /// or if there are no degrees of freedom.
    pub covariance: Option<Vec<Vec<f64>>>,
    /// Correlation matrix of the free parameters.
    pub correlation: Option<Vec<Vec<f64>>>,
    /// Standard errors of the free parameters.
    pub std_errors: Option<Vec<f64>>,
    /// Condition number of `J^T J` on the free set (large: poorly determined combinations).
    pub condition_number: Option<f64>,
}

impl FitStatistics {
    /// SSR, RMS and the parameters at a bound, without the covariance and its relatives (`None`):
    /// for fits whose statistics are not reported (Monte-Carlo samples) or cannot be formed.
    #[must_use]
    pub fn without_covariance(bounds: &Bounds, params: &DVector<f64>, residuals: &DVector<f64>) -> Self {
        let ssr = residuals.norm_squared();
        let at = bounds.at_bounds(params, 1e-6);
        Self {
            ssr,
            rms: (ssr / residuals.len().max(1) as f64).sqrt(),
            at_bounds: at.iter().map(|&i| bounds.names[i].clone()).collect(),
            free: (0..bounds.len()).filter(|i| !at.contains(i)).map(|i| bounds.names[i].clone()).collect(),
            covariance: None,
            correlation: None,
            std_errors: None,
            condition_number: None,
        }
    }
}

/// Fit statistics at `params` (the Jacobian is evaluated there).
pub fn fit_statistics<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    params: &DVector<f64>,
    residuals: &DVector<f64>,
) -> Result<FitStatistics, IdentError> {
    let m = problem.residual_count();
    let n = problem.parameter_count();
    let ssr = residuals.norm_squared();
    let at = bounds.at_bounds(params, 1e-6);
    let free: Vec<usize> = (0..n).filter(|i| !at.contains(i)).collect();
    let mut jac = DMatrix::zeros(m, n);
    problem.jacobian(params, bounds, &mut jac)?;
    let jf = DMatrix::from_fn(m, free.len(), |i, k| jac[(i, free[k])]);
    let jtj = jf.transpose() * &jf;
    let dof = m as f64 - free.len() as f64;
    let (mut covariance, mut correlation, mut std_errors, mut condition_number) = (None, None, None, None);
    if !free.is_empty() {
        let sv = jtj.clone().symmetric_eigenvalues();
        let (mx, mn) = sv.iter().fold((0.0f64, f64::INFINITY), |(a, b), v| (a.max(*v), b.min(*v)));
        if mn > 0.0 {
            condition_number = Some(mx / mn);
        }
        if dof > 0.0 {
            if let Some(inv) = jtj.try_inverse() {
                let s2 = ssr / dof;
                let cov = inv * s2;
                let se: Vec<f64> = (0..free.len()).map(|i| cov[(i, i)].max(0.0).sqrt()).collect();
                let corr = (0..free.len())
                    .map(|i| (0..free.len()).map(|j| cov[(i, j)] / (se[i] * se[j]).max(f64::MIN_POSITIVE)).collect())
                    .collect();
                covariance = Some((0..free.len()).map(|i| (0..free.len()).map(|j| cov[(i, j)]).collect()).collect());
                correlation = Some(corr);
                std_errors = Some(se);
            }
        }
    }
    Ok(FitStatistics {
        ssr,
        rms: (ssr / m as f64).sqrt(),
        at_bounds: at.iter().map(|&i| bounds.names[i].clone()).collect(),
        free: free.iter().map(|&i| bounds.names[i].clone()).collect(),
        covariance,
        correlation,
        std_errors,
        condition_number,
    })
}
