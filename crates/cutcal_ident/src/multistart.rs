//! Seeded, deterministic multistart around the bounded LM solver, and fit statistics
//! (covariance and correlation of the free parameters from the Jacobian).

use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::error::IdentError;
use crate::lm::{minimise, Bounds, LmOptions, LmResult, Problem, Termination};

/// Multistart settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MultistartOptions {
    /// Number of starts (>= 1). Start 0 is the centre of the box; the others a Latin hypercube.
    pub starts: usize,
    /// Seed of the ChaCha8 generator of the Latin hypercube.
    pub seed: u64,
    /// Local solver settings.
    pub lm: LmOptions,
    /// Two minima are "the same" when their SSR differ by less than this relative amount.
    pub same_minimum_rel_tol: f64,
}

impl MultistartOptions {
    /// `starts` starts from `seed` with precise local solves.
    #[must_use]
    pub fn new(starts: usize, seed: u64) -> Self {
        Self { starts, seed, lm: LmOptions::precise(), same_minimum_rel_tol: 1e-6 }
    }
}

/// The outcome of a multistart run.
#[derive(Debug, Clone, PartialEq)]
pub struct MultistartReport {
    /// The best local solution.
    pub best: LmResult,
    /// Which start gave it (0-based).
    pub best_start: usize,
    /// Starts run.
    pub starts: usize,
    /// Starts whose solve failed.
    pub failed_starts: usize,
    /// Starts that reached the best minimum (within `same_minimum_rel_tol`).
    pub starts_at_best: usize,
    /// SSR reached from each start (`None` where it failed).
    pub start_ssr: Vec<Option<f64>>,
    /// Starts that stopped at the LM iteration cap without meeting a tolerance. They are not
    /// chosen as the best while any start converged; when none did, `best.termination` is
    /// [`Termination::MaxIterations`] and callers must report it (a typed non-convergence).
    pub unconverged_starts: usize,
}

/// The start points in unit-box coordinates: the centre, then a Latin hypercube of `starts - 1`.
#[must_use]
pub fn start_points(dim: usize, starts: usize, seed: u64) -> Vec<DVector<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut pts = vec![DVector::from_element(dim, 0.5)];
    let k = starts.saturating_sub(1);
    if k == 0 {
        return pts;
    }
    let mut columns: Vec<Vec<f64>> = Vec::with_capacity(dim);
    for _ in 0..dim {
        let mut strata: Vec<f64> = (0..k).map(|i| (i as f64 + rng.gen::<f64>()) / k as f64).collect();
        // Fisher-Yates with the same generator: deterministic for a seed.
        for i in (1..k).rev() {
            let j = rng.gen_range(0..=i);
            strata.swap(i, j);
        }
        columns.push(strata);
    }
    for s in 0..k {
        pts.push(DVector::from_iterator(dim, columns.iter().map(|c| c[s])));
    }
    pts
}

/// Runs the bounded LM from every start and keeps the best.
///
/// Returns an error if the options are invalid or every start fails.
pub fn multistart<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    options: &MultistartOptions,
) -> Result<MultistartReport, IdentError> {
    if options.starts == 0 || options.starts > 100_000 {
        return Err(IdentError::InvalidOptions(format!("starts must be in 1..=100000, got {}", options.starts)));
    }
    // The best converged start, and the best of all (used only when no start converged).
    let mut best: Option<(usize, LmResult)> = None;
    let mut best_capped: Option<(usize, LmResult)> = None;
    let mut unconverged_starts = 0;
    let mut start_ssr = Vec::with_capacity(options.starts);
    let mut first_error = None;
    for (i, z0) in start_points(bounds.len(), options.starts, options.seed).into_iter().enumerate() {
        let p0 = bounds.from_unit(&z0);
        match minimise(problem, bounds, &p0, &options.lm) {
            Ok(res) => {
                start_ssr.push(Some(res.ssr));
                let slot = if res.termination == Termination::MaxIterations {
                    unconverged_starts += 1;
                    &mut best_capped
                } else {
                    &mut best
                };
                if slot.as_ref().map_or(true, |(_, b)| res.ssr < b.ssr) {
                    *slot = Some((i, res));
                }
            }
            Err(e) => {
                start_ssr.push(None);
                first_error.get_or_insert(e.to_string());
            }
        }
    }
    let (best_start, best) = best.or(best_capped).ok_or_else(|| IdentError::AllStartsFailed {
        starts: options.starts,
        first: first_error.clone().unwrap_or_default(),
    })?;
    let tol = options.same_minimum_rel_tol * best.ssr.max(f64::MIN_POSITIVE) + 1e-300;
    let starts_at_best = start_ssr.iter().flatten().filter(|s| (**s - best.ssr).abs() <= tol).count();
    let failed_starts = start_ssr.iter().filter(|s| s.is_none()).count();
    Ok(MultistartReport {
        best,
        best_start,
        starts: options.starts,
        failed_starts,
        starts_at_best,
        start_ssr,
        unconverged_starts,
    })
}

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

#[cfg(test)]
mod tests {
    use super::*;

    use crate::lm::tests::Rosen;

    #[test]
    fn capped_starts_are_counted_and_never_preferred_to_a_converged_one() {
        let b = Bounds::new(vec!["x".into(), "y".into()], vec![-2.0, -1.0], vec![2.0, 3.0]).unwrap();
        // A cap of 12 iterations: with seed 5, 3 of 9 starts stop at the cap and 6 converge.
        let mut o = MultistartOptions::new(9, 5);
        o.lm.max_iterations = 12;
        let r = multistart(&Rosen, &b, &o).unwrap();
        println!("unconverged {} of 9, best {:?}", r.unconverged_starts, r.best.termination);
        assert!(r.unconverged_starts > 0 && r.unconverged_starts < 9, "{}", r.unconverged_starts);
        assert_ne!(r.best.termination, Termination::MaxIterations);
        // A cap of 1: no start converges; the best says MaxIterations for the caller to report.
        o.lm.max_iterations = 1;
        let r = multistart(&Rosen, &b, &o).unwrap();
        assert_eq!(r.unconverged_starts, 9);
        assert_eq!(r.best.termination, Termination::MaxIterations);
    }

    #[test]
    fn start_points_are_a_latin_hypercube_and_deterministic() {
        let a = start_points(3, 11, 7);
        let b = start_points(3, 11, 7);
        assert_eq!(a, b);
        assert_eq!(a.len(), 11);
        // Each of the 10 strata of every coordinate holds exactly one point.
        for d in 0..3 {
            let mut hit = [0usize; 10];
            for p in &a[1..] {
                hit[(p[d] * 10.0).floor() as usize] += 1;
            }
            assert!(hit.iter().all(|h| *h == 1), "{hit:?}");
        }
        assert_ne!(start_points(3, 11, 8), a);
    }
}
