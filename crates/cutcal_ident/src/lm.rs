//! A bounded Levenberg-Marquardt least-squares solver on nalgebra.
//!
//! Why our own and not a crate: the `levenberg-marquardt` crate has no box constraints, argmin has
//! no bounded LM, and our problems are small (5-10 parameters, tens of residuals) with analytic
//! Jacobians. This is the projected LM with an active set: parameters are scaled to the unit box,
//! a parameter at a bound whose gradient points outward is held, the damped Gauss-Newton step is
//! solved on the free set (Cholesky of `J^T J + lambda diag(J^T J)`) and projected onto the box.
//! Deterministic: no randomness, fixed iteration caps.

use nalgebra::{DMatrix, DVector};

use crate::error::IdentError;

/// A nonlinear least-squares problem `min 1/2 |r(p)|^2` over physical parameters `p`.
pub trait Problem {
    /// Number of parameters.
    fn parameter_count(&self) -> usize;
    /// Number of residuals.
    fn residual_count(&self) -> usize;
    /// Residuals at `p`.
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError>;
    /// Jacobian `dr/dp` at `p` (rows: residuals). The default is a central difference with a
    /// step of 1e-6 of each parameter's bound width.
    fn jacobian(&self, p: &DVector<f64>, bounds: &Bounds, out: &mut DMatrix<f64>) -> Result<(), IdentError> {
        let m = self.residual_count();
        let mut rp = DVector::zeros(m);
        let mut rm = DVector::zeros(m);
        for k in 0..self.parameter_count() {
            let h = 1e-6 * (bounds.upper[k] - bounds.lower[k]).max(p[k].abs() * 1e-3).max(1e-12);
            let mut q = p.clone();
            let up = (q[k] + h).min(bounds.upper[k].max(q[k]));
            let dn = (q[k] - h).max(bounds.lower[k].min(q[k]));
            q[k] = up;
            self.residuals(&q, &mut rp)?;
            q[k] = dn;
            self.residuals(&q, &mut rm)?;
            let w = up - dn;
            for i in 0..m {
                out[(i, k)] = if w > 0.0 { (rp[i] - rm[i]) / w } else { 0.0 };
            }
        }
        Ok(())
    }
    /// Jacobian at `p` when the caller already holds the residuals `r` at `p` (the minimiser does:
    /// it evaluated them when it accepted the step). The default ignores `r` and calls
    /// [`Problem::jacobian`]; a forward-difference problem overrides it to take `r` as its base
    /// point instead of evaluating the model there again, with the same result bit for bit.
    fn jacobian_at(
        &self,
        p: &DVector<f64>,
        r: &DVector<f64>,
        bounds: &Bounds,
        out: &mut DMatrix<f64>,
    ) -> Result<(), IdentError> {
        let _ = r;
        self.jacobian(p, bounds, out)
    }
}

/// [`Problem::jacobian_at`] from residuals evaluated afresh at `p`: the `jacobian` of a problem
/// whose forward differences live in `jacobian_at`, for callers that hold no residuals at `p`.
///
/// Returns an error if the model fails at `p` or in the differences.
pub fn jacobian_with_fresh_base<P: Problem + ?Sized>(
    problem: &P,
    p: &DVector<f64>,
    bounds: &Bounds,
    out: &mut DMatrix<f64>,
) -> Result<(), IdentError> {
    let mut r = DVector::zeros(problem.residual_count());
    problem.residuals(p, &mut r)?;
    problem.jacobian_at(p, &r, bounds, out)
}

/// Box bounds `lower <= p <= upper` (a parameter with `lower == upper` is fixed).
#[derive(Debug, Clone, PartialEq)]
pub struct Bounds {
    /// Lower bounds.
    pub lower: DVector<f64>,
    /// Upper bounds.
    pub upper: DVector<f64>,
    /// Parameter names (for messages and reports).
    pub names: Vec<String>,
}

impl Bounds {
    /// Validating constructor: finite, ordered, equal lengths.
    pub fn new(names: Vec<String>, lower: Vec<f64>, upper: Vec<f64>) -> Result<Self, IdentError> {
        if names.len() != lower.len() || lower.len() != upper.len() || names.is_empty() {
            return Err(IdentError::InvalidOptions(format!(
                "bounds need one name, lower and upper per parameter (got {}, {}, {})",
                names.len(),
                lower.len(),
                upper.len()
            )));
        }
        for ((n, lo), hi) in names.iter().zip(&lower).zip(&upper) {
            if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                return Err(IdentError::InvalidBounds { parameter: n.clone(), low: *lo, high: *hi });
            }
        }
        Ok(Self { lower: DVector::from_vec(lower), upper: DVector::from_vec(upper), names })
    }

    /// Number of parameters.
    #[must_use]
    pub fn len(&self) -> usize {
        self.lower.len()
    }

    /// True when there are no parameters (never, for a validated instance).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.lower.is_empty()
    }

    /// Physical parameters from unit-box coordinates.
    #[must_use]
    pub fn from_unit(&self, z: &DVector<f64>) -> DVector<f64> {
        DVector::from_iterator(
            self.len(),
            // The clamp keeps `lower + z * w` inside the box despite rounding (found by the
            // identification fuzz: n = 0.21511837423046304 above an upper bound of 0.215118374230463).
            (0..self.len()).map(|i| {
                (self.lower[i] + z[i] * (self.upper[i] - self.lower[i])).max(self.lower[i]).min(self.upper[i])
            }),
        )
    }

    /// [`Bounds::from_unit`] written into `out` (no allocation).
    pub fn from_unit_into(&self, z: &DVector<f64>, out: &mut DVector<f64>) {
        for i in 0..self.len() {
            out[i] = (self.lower[i] + z[i] * (self.upper[i] - self.lower[i])).max(self.lower[i]).min(self.upper[i]);
        }
    }

    /// Unit-box coordinates of physical parameters (0 for fixed parameters).
    #[must_use]
    pub fn to_unit(&self, p: &DVector<f64>) -> DVector<f64> {
        DVector::from_iterator(
            self.len(),
            (0..self.len()).map(|i| {
                let w = self.upper[i] - self.lower[i];
                if w > 0.0 {
                    ((p[i] - self.lower[i]) / w).clamp(0.0, 1.0)
                } else {
                    0.0
                }
            }),
        )
    }

    /// Indices of parameters within `rel_tol` of a bound (relative to the bound width), and fixed ones.
    #[must_use]
    pub fn at_bounds(&self, p: &DVector<f64>, rel_tol: f64) -> Vec<usize> {
        let z = self.to_unit(p);
        (0..self.len())
            .filter(|&i| self.upper[i] <= self.lower[i] || z[i] <= rel_tol || z[i] >= 1.0 - rel_tol)
            .collect()
    }
}

/// Stopping rules and caps of the solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmOptions {
    /// Iteration cap.
    pub max_iterations: usize,
    /// Stop when the projected gradient (unit-box scaled) falls below this.
    pub gradient_tolerance: f64,
    /// Stop when the relative cost decrease of an accepted step falls below this.
    pub cost_tolerance: f64,
    /// Stop when the step (unit box) falls below this.
    pub step_tolerance: f64,
}

impl LmOptions {
    /// Tight tolerances suited to the small identification problems of cutcal.
    #[must_use]
    pub fn precise() -> Self {
        Self { max_iterations: 200, gradient_tolerance: 1e-10, cost_tolerance: 1e-14, step_tolerance: 1e-12 }
    }
}

/// Why the solver stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// Projected gradient below tolerance.
    Gradient,
    /// Relative cost change below tolerance.
    Cost,
    /// Step below tolerance.
    Step,
    /// Iteration cap reached.
    MaxIterations,
    /// Damping grew without finding a decrease (a boundary or flat minimum).
    Stalled,
    /// Ended by the caller's stop rule ([`minimise_until`]; the multistart basin rule), not a
    /// convergence: the point is where the run was stopped.
    Stopped,
}

/// The result of one bounded LM run.
#[derive(Debug, Clone, PartialEq)]
pub struct LmResult {
    /// Parameters (physical).
    pub params: DVector<f64>,
    /// Residuals at the solution.
    pub residuals: DVector<f64>,
    /// Sum of squared residuals.
    pub ssr: f64,
    /// Iterations done.
    pub iterations: usize,
    /// Why it stopped.
    pub termination: Termination,
}

fn checked_residuals<P: Problem + ?Sized>(
    problem: &P,
    p: &DVector<f64>,
    r: &mut DVector<f64>,
) -> Result<f64, IdentError> {
    problem.residuals(p, r)?;
    if r.iter().any(|v| !v.is_finite()) {
        return Err(IdentError::NonFinite { what: "residuals".into(), params: p.iter().copied().collect() });
    }
    Ok(r.norm_squared())
}

/// Minimises `|r(p)|^2` within `bounds` from `start` (clamped into the box).
///
/// Returns an error if the model fails or is non-finite at the start point; failures at trial
/// points only reject the step.
pub fn minimise<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    start: &DVector<f64>,
    options: &LmOptions,
) -> Result<LmResult, IdentError> {
    minimise_until(problem, bounds, start, options, |_, _| false)
}

/// As [`minimise`], with a stop rule: after every accepted step that did not end the run,
/// `stop(z, ssr)` is called with the unit-box point and its SSR; `true` ends the run with
/// [`Termination::Stopped`] (used by the multistart basin rule, [`crate::multistart`]).
///
/// Returns an error as [`minimise`].
pub fn minimise_until<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    start: &DVector<f64>,
    options: &LmOptions,
    mut stop: impl FnMut(&DVector<f64>, f64) -> bool,
) -> Result<LmResult, IdentError> {
    let n = problem.parameter_count();
    let m = problem.residual_count();
    if bounds.len() != n || start.len() != n {
        return Err(IdentError::InvalidOptions(format!(
            "problem has {n} parameters but bounds have {} and the start {}",
            bounds.len(),
            start.len()
        )));
    }
    let width: DVector<f64> = &bounds.upper - &bounds.lower;
    let free_dims: Vec<usize> = (0..n).filter(|&i| width[i] > 0.0).collect();
    if m < free_dims.len() {
        return Err(IdentError::Underdetermined { residuals: m, parameters: free_dims.len() });
    }
    let mut z = bounds.to_unit(start);
    let mut p = bounds.from_unit(&z);
    let mut r = DVector::zeros(m);
    let mut cost = checked_residuals(problem, &p, &mut r)?;
    let mut jac = DMatrix::zeros(m, n);
    let mut lambda = 1e-3;
    let mut r_trial = DVector::zeros(m);
    // Work space of the step, allocated once: the gradient, the free set, J^T J on it (row-major,
    // k x k for k free parameters), its damped copy and the step.
    let mut g = DVector::zeros(n);
    let mut free: Vec<usize> = Vec::with_capacity(n);
    let mut jtj = vec![0.0; n * n];
    let mut damped = vec![0.0; n * n];
    let mut step = vec![0.0; n];
    let mut z_trial = z.clone();
    let mut p_trial = p.clone();
    let mut termination = Termination::MaxIterations;
    let mut iterations = 0;
    'outer: for it in 1..=options.max_iterations {
        iterations = it;
        problem.jacobian_at(&p, &r, bounds, &mut jac)?;
        if jac.iter().any(|v| !v.is_finite()) {
            return Err(IdentError::NonFinite { what: "Jacobian".into(), params: p.iter().copied().collect() });
        }
        // Scale to the unit box: dr/dz = dr/dp * width.
        for (k, w) in width.iter().enumerate() {
            jac.column_mut(k).scale_mut(*w);
        }
        jac.tr_mul_to(&r, &mut g);
        // Active set: at a bound with the descent direction pointing out of the box.
        free.clear();
        free.extend(
            free_dims.iter().copied().filter(|&i| !((z[i] <= 0.0 && g[i] > 0.0) || (z[i] >= 1.0 && g[i] < 0.0))),
        );
        let pg = free.iter().map(|&i| g[i] * g[i]).sum::<f64>().sqrt();
        if free.is_empty() || pg <= options.gradient_tolerance * (1.0 + cost) {
            termination = Termination::Gradient;
            break;
        }
        let k_free = free.len();
        for (a, &i) in free.iter().enumerate() {
            for (b, &j) in free.iter().enumerate().skip(a) {
                let v = jac.column(i).dot(&jac.column(j));
                jtj[a * k_free + b] = v;
                jtj[b * k_free + a] = v;
            }
        }
        loop {
            damped[..k_free * k_free].copy_from_slice(&jtj[..k_free * k_free]);
            for k in 0..k_free {
                damped[k * k_free + k] += lambda * jtj[k * k_free + k].max(1e-12);
            }
            for (k, &i) in free.iter().enumerate() {
                step[k] = -g[i];
            }
            if !cholesky_solve(&mut damped[..k_free * k_free], &mut step[..k_free]) {
                lambda *= 10.0;
                if lambda > 1e16 {
                    termination = Termination::Stalled;
                    break 'outer;
                }
                continue;
            }
            z_trial.copy_from(&z);
            for (k, &i) in free.iter().enumerate() {
                z_trial[i] = (z[i] + step[k]).clamp(0.0, 1.0);
            }
            let dz = z_trial.iter().zip(z.iter()).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
            bounds.from_unit_into(&z_trial, &mut p_trial);
            let trial_cost = match checked_residuals(problem, &p_trial, &mut r_trial) {
                Ok(c) => c,
                Err(IdentError::Model(_)) | Err(IdentError::NonFinite { .. }) => f64::INFINITY,
                Err(e) => return Err(e),
            };
            if trial_cost < cost {
                let rel = (cost - trial_cost) / cost.max(f64::MIN_POSITIVE);
                std::mem::swap(&mut z, &mut z_trial);
                std::mem::swap(&mut p, &mut p_trial);
                std::mem::swap(&mut r, &mut r_trial);
                cost = trial_cost;
                lambda = (lambda / 3.0).max(1e-12);
                if rel < options.cost_tolerance {
                    termination = Termination::Cost;
                    break 'outer;
                }
                if dz < options.step_tolerance {
                    termination = Termination::Step;
                    break 'outer;
                }
                if stop(&z, cost) {
                    termination = Termination::Stopped;
                    break 'outer;
                }
                break;
            }
            lambda *= 4.0;
            if dz < options.step_tolerance || lambda > 1e16 {
                termination = if dz < options.step_tolerance { Termination::Step } else { Termination::Stalled };
                break 'outer;
            }
        }
    }
    Ok(LmResult { params: p, residuals: r, ssr: cost, iterations, termination })
}

/// Solves `A x = b` in place for a symmetric positive definite `A` (row-major `k x k`, `k^2 =
/// a.len()`, `k = b.len()`) by the Cholesky factorisation `A = L L^T` (Golub and Van Loan,
/// *Matrix Computations*, Alg. 4.2.1) and two triangular solves; `b` becomes `x`. Returns false
/// (leaving `a` and `b` overwritten) when a pivot is not positive: `A` is not positive definite.
fn cholesky_solve(a: &mut [f64], b: &mut [f64]) -> bool {
    let k = b.len();
    // L overwrites the lower triangle of `a`.
    for j in 0..k {
        let mut d = a[j * k + j];
        for l in 0..j {
            d -= a[j * k + l] * a[j * k + l];
        }
        if !(d > 0.0) {
            return false;
        }
        let d = d.sqrt();
        a[j * k + j] = d;
        for i in j + 1..k {
            let mut v = a[i * k + j];
            for l in 0..j {
                v -= a[i * k + l] * a[j * k + l];
            }
            a[i * k + j] = v / d;
        }
    }
    // L y = b, then L^T x = y.
    for i in 0..k {
        let mut v = b[i];
        for l in 0..i {
            v -= a[i * k + l] * b[l];
        }
        b[i] = v / a[i * k + i];
    }
    for i in (0..k).rev() {
        let mut v = b[i];
        for l in i + 1..k {
            v -= a[l * k + i] * b[l];
        }
        b[i] = v / a[i * k + i];
    }
    true
}

#[cfg(test)]
pub(crate) mod tests;
