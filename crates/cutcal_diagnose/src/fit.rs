//! Joint least-squares fits of the baseline parameters and mechanism parameters, on the bounded
//! Levenberg-Marquardt of `cutcal_ident`.
//!
//! Residuals are log-ratios in noise units, `e = ln(y_measured / y_model) / s_j` (design note
//! Sec 3.1, multiplicative noise), followed by the weak-prior pseudo-residuals of the baseline.

use cutcal_ident::lm::{minimise, Bounds, LmOptions, Problem, Termination};
use cutcal_ident::IdentError;
use cutcal_model::CuttingTest;
use nalgebra::{DMatrix, DVector};

use crate::error::DiagnoseError;
use crate::hooks::Hooks;
use crate::mechanism::{self, Context, MechanismId};
use crate::simulator::{ParamSpec, Prediction, Simulator};

/// The outputs: Fc, Ft, chip thickness and, where measured, the interface temperature rise.
pub const OUTPUTS: [&str; NOUT] = ["fc", "ft", "tc", "t_int"];

/// Number of outputs.
pub const NOUT: usize = 4;

/// Reference temperature of the interface-temperature output, degC: the output is the rise
/// `T_int - 20` so that its residual, like the others, is a log-ratio.
pub const T_REF_C: f64 = 20.0;

/// One observation: test index, output index (0 Fc, 1 Ft, 2 tc, 3 interface temperature rise) and
/// the measured value (N/m, m or K).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obs {
    /// Index into the tests.
    pub test: usize,
    /// Output index.
    pub output: usize,
    /// Measured value.
    pub value: f64,
}

/// The observations of a set of tests.
#[must_use]
pub fn observations(tests: &[CuttingTest]) -> Vec<Obs> {
    let mut v = Vec::new();
    for (i, t) in tests.iter().enumerate() {
        let m = t.measured;
        let rise = m.interface_temperature_c.map(|t| t - T_REF_C);
        for (j, y) in [m.cutting_force_n_per_m, m.feed_force_n_per_m, m.chip_thickness_m, rise].into_iter().enumerate()
        {
            if let Some(y) = y.filter(|y| *y > 0.0) {
                v.push(Obs { test: i, output: j, value: y });
            }
        }
    }
    v
}

/// Value of output `j` of a prediction.
#[must_use]
pub fn output(p: &Prediction, j: usize) -> f64 {
    match j {
        0 => p.fc_n_per_m,
        1 => p.ft_n_per_m,
        2 => p.chip_m,
        _ => p.t_int_c.map_or(f64::NAN, |t| (t - T_REF_C).max(1.0)),
    }
}

/// A model: the simulator's baseline plus a list of mechanisms (parameter layout: baseline first,
/// then each mechanism's fitted parameters in order).
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// Mechanisms switched on.
    pub mechanisms: Vec<MechanismId>,
    /// Their context (wear state, BUE onset).
    pub ctx: Context,
}

/// Number of fitted parameters of a mechanism (the BUE onset is chosen on a grid, not fitted).
#[must_use]
pub fn fitted_len(id: MechanismId) -> usize {
    match id {
        MechanismId::BuiltUpEdge => 1,
        _ => mechanism::info(id).params.len(),
    }
}

/// Predictions of `spec` at parameters `x` for `tests`.
///
/// Returns an error if the simulator fails.
pub fn predict(
    sim: &dyn Simulator,
    tests: &[CuttingTest],
    spec: &Spec,
    ctx: &Context,
    x: &[f64],
) -> Result<Vec<Prediction>, DiagnoseError> {
    let p = sim.baseline_params().len();
    let mut hooks = vec![Hooks::NEUTRAL; tests.len()];
    let mut at = p;
    for id in &spec.mechanisms {
        let d = fitted_len(*id);
        mechanism::set_hooks(*id, &x[at..at + d], tests, ctx, sim, &mut hooks);
        at += d;
    }
    let mut preds = sim.simulate(tests, &x[..p], &hooks)?;
    let mut at = p;
    for id in &spec.mechanisms {
        let d = fitted_len(*id);
        mechanism::correct(*id, &x[at..at + d], &mut preds);
        at += d;
    }
    Ok(preds)
}

/// Noise-unit residuals `ln(y/yhat)/s_j` of `obs` against `preds`.
#[must_use]
pub fn residuals(obs: &[Obs], preds: &[Prediction], noise: &[f64; NOUT]) -> Vec<f64> {
    obs.iter().map(|o| (o.value / output(&preds[o.test], o.output)).ln() / noise[o.output]).collect()
}

/// The parameters of `spec` at `x` that can still move both ways (more than 1e-6 of their range
/// from either bound), with the forward-difference step of each (1e-4 of its range), for
/// [`data_jacobian`]: a parameter held at a bound cannot absorb a signature that needs it beyond.
#[must_use]
pub fn free_columns(sim: &dyn Simulator, spec: &Spec, x: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let (_, lo, hi, _) = layout(sim, spec);
    let cols: Vec<usize> =
        (0..x.len().min(lo.len())).filter(|&i| (x[i] - lo[i]).min(hi[i] - x[i]) > 1e-6 * (hi[i] - lo[i])).collect();
    let steps = cols.iter().map(|&i| 1e-4 * (hi[i] - lo[i]).max(1e-9)).collect();
    (cols, steps)
}

/// Bounds, start and names of the parameter vector of `spec`.
#[must_use]
pub fn layout(sim: &dyn Simulator, spec: &Spec) -> (Vec<String>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut names, mut lo, mut hi, mut start) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for ps in sim.baseline_params() {
        names.push(ps.name.clone());
        lo.push(ps.lower);
        hi.push(ps.upper);
        start.push(ps.start);
    }
    for id in &spec.mechanisms {
        for pi in mechanism::info(*id).params.iter().take(fitted_len(*id)) {
            names.push(format!("{}.{}", id.as_str(), pi.name));
            lo.push(pi.lower);
            hi.push(pi.upper);
            // Start half-way between off and typical: inside the box, on the physical side.
            start.push((0.5 * (pi.off + pi.typical)).clamp(pi.lower, pi.upper));
        }
    }
    (names, lo, hi, start)
}

struct FitProblem<'a> {
    sim: &'a dyn Simulator,
    tests: &'a [CuttingTest],
    obs: &'a [Obs],
    spec: &'a Spec,
    noise: [f64; NOUT],
}

impl Problem for FitProblem<'_> {
    /// Forward differences (half the model calls of the default central ones; the LM step only
    /// needs the Jacobian to first order). The step is 1e-6 of the bound width, taken inward at the
    /// upper bound.
    fn jacobian(&self, p: &DVector<f64>, bounds: &Bounds, out: &mut DMatrix<f64>) -> Result<(), IdentError> {
        cutcal_ident::lm::jacobian_with_fresh_base(self, p, bounds, out)
    }
    /// The forward differences of [`Self::jacobian`] from the residuals `r0` at `p` that the
    /// minimiser already holds.
    fn jacobian_at(
        &self,
        p: &DVector<f64>,
        r0: &DVector<f64>,
        bounds: &Bounds,
        out: &mut DMatrix<f64>,
    ) -> Result<(), IdentError> {
        let m = self.residual_count();
        let mut rp = DVector::zeros(m);
        for k in 0..self.parameter_count() {
            let h = 1e-6 * (bounds.upper[k] - bounds.lower[k]).max(p[k].abs() * 1e-3).max(1e-12);
            let h = if p[k] + h > bounds.upper[k] { -h } else { h };
            let mut q = p.clone();
            q[k] += h;
            self.residuals(&q, &mut rp)?;
            for i in 0..m {
                out[(i, k)] = (rp[i] - r0[i]) / h;
            }
        }
        Ok(())
    }
    fn parameter_count(&self) -> usize {
        self.sim.baseline_params().len() + self.spec.mechanisms.iter().map(|m| fitted_len(*m)).sum::<usize>()
    }
    fn residual_count(&self) -> usize {
        self.obs.len() + self.sim.baseline_params().iter().filter(|p| p.prior_sd.is_some()).count()
    }
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        let x: Vec<f64> = p.iter().copied().collect();
        let preds = predict(self.sim, self.tests, self.spec, &self.spec.ctx, &x).map_err(|e| match e {
            DiagnoseError::Model { source, .. } => IdentError::Model(source),
            other => IdentError::InvalidOptions(other.to_string()),
        })?;
        let r = residuals(self.obs, &preds, &self.noise);
        for (i, v) in r.iter().enumerate() {
            out[i] = *v;
        }
        let mut k = r.len();
        for (i, ps) in self.sim.baseline_params().iter().enumerate() {
            if let Some(sd) = ps.prior_sd {
                out[k] = (x[i] - ps.start) / sd;
                k += 1;
            }
        }
        Ok(())
    }
}

/// Sum of the squared prior pseudo-residuals `(x - x0) / sd` of the baseline's nuisance at `x`.
#[must_use]
pub fn prior_penalty(params: &[ParamSpec], x: &[f64]) -> f64 {
    params.iter().zip(x).filter_map(|(ps, v)| ps.prior_sd.map(|sd| ((v - ps.start) / sd).powi(2))).sum()
}

/// A fitted model.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// Parameters.
    pub x: Vec<f64>,
    /// Data residuals in noise units.
    pub resid: Vec<f64>,
    /// Sum of squared data residuals.
    pub rss: f64,
    /// Sum of squared prior pseudo-residuals of the nuisance (`(x - x0) / sd`): what the fit paid
    /// to move the nuisance off its stated values.
    pub penalty: f64,
    /// Number of parameters (baseline + mechanisms).
    pub k: usize,
    /// Predictions at `x`.
    pub preds: Vec<Prediction>,
    /// How the minimiser ended (reported, never hidden: a capped or unmoved fit is named as such).
    pub status: FitStatus,
}

/// How a fit ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitStatus {
    /// A tolerance was met (gradient, cost or step) or the damping stalled at a minimum.
    Converged,
    /// The iteration cap was reached before any tolerance was met.
    IterationCap(usize),
    /// Fewer numbers than free parameters: the start point was kept, nothing was fitted.
    Underdetermined,
    /// The full run failed away from the start; a short damped rerun of this many iterations stood.
    ShortRetry(usize),
    /// No free parameters.
    NothingToFit,
}

impl Fit {
    /// The minimised objective: data residuals plus the nuisance's prior penalty.
    #[must_use]
    pub fn objective(&self) -> f64 {
        self.rss + self.penalty
    }
}

impl FitStatus {
    /// Whether the parameters are a fitted minimum (converged or stopped by damping).
    #[must_use]
    pub fn is_fitted(self) -> bool {
        matches!(self, Self::Converged | Self::NothingToFit)
    }

    /// Whether a refit can be tested: something was fitted, and not only by the damped rerun of
    /// [`FitStatus::ShortRetry`] (an iteration cap is reported, not refused).
    #[must_use]
    pub fn is_usable(self) -> bool {
        !matches!(self, Self::Underdetermined | Self::ShortRetry(_))
    }

    /// A short description for reports, `None` when the fit converged.
    #[must_use]
    pub fn note(self) -> Option<String> {
        match self {
            Self::Converged | Self::NothingToFit => None,
            Self::IterationCap(n) => Some(format!("fit stopped at its iteration cap of {n}")),
            Self::Underdetermined => Some("fewer measured numbers than free parameters: nothing fitted".into()),
            Self::ShortRetry(n) => Some(format!(
                "full fit failed inside the model's unsolvable region; a damped {n}-iteration rerun stood"
            )),
        }
    }
}

/// Fits `spec` to `obs` from `start` (or the layout's start when `None`).
///
/// Returns an error if the model fails at the start point.
pub fn fit(
    sim: &dyn Simulator,
    tests: &[CuttingTest],
    obs: &[Obs],
    spec: &Spec,
    noise: &[f64; NOUT],
    start: Option<&[f64]>,
    max_iterations: usize,
) -> Result<Fit, DiagnoseError> {
    let (names, lo, hi, s0) = layout(sim, spec);
    let x0: Vec<f64> = match start {
        Some(s) if s.len() == s0.len() => s.iter().zip(lo.iter().zip(&hi)).map(|(v, (l, h))| v.clamp(*l, *h)).collect(),
        _ => s0,
    };
    let (x, status) = if names.is_empty() {
        (Vec::new(), FitStatus::NothingToFit)
    } else {
        let problem = FitProblem { sim, tests, obs, spec, noise: *noise };
        let bounds = Bounds::new(names, lo, hi).map_err(|e| DiagnoseError::Fit(e.to_string()))?;
        let opts = LmOptions { max_iterations, gradient_tolerance: 1e-8, cost_tolerance: 1e-10, step_tolerance: 1e-9 };
        match minimise(&problem, &bounds, &DVector::from_vec(x0.clone()), &opts) {
            Ok(r) => {
                let status = if r.termination == Termination::MaxIterations {
                    FitStatus::IterationCap(max_iterations)
                } else {
                    FitStatus::Converged
                };
                (r.params.iter().copied().collect(), status)
            }
            Err(IdentError::Underdetermined { .. }) => (x0, FitStatus::Underdetermined),
            // A failure away from the start (a finite-difference probe outside the model's solvable
            // region) is retried once with a short, heavily damped run; then the error stands.
            Err(e) => {
                let short = LmOptions { max_iterations: 5, ..opts };
                match minimise(&problem, &bounds, &DVector::from_vec(x0.clone()), &short) {
                    Ok(r) => (r.params.iter().copied().collect(), FitStatus::ShortRetry(short.max_iterations)),
                    Err(_) => return Err(DiagnoseError::Fit(e.to_string())),
                }
            }
        }
    };
    let preds = predict(sim, tests, spec, &spec.ctx, &x)?;
    let resid = residuals(obs, &preds, noise);
    let rss = resid.iter().map(|r| r * r).sum();
    let penalty = prior_penalty(sim.baseline_params(), &x);
    Ok(Fit { k: x.len(), x, resid, rss, penalty, preds, status })
}

/// Central-difference Jacobian of the data residuals (rows) with respect to the parameters
/// `cols` of `x` (columns), steps `steps`.
///
/// Returns an error if the model fails at a perturbed point.
#[allow(clippy::too_many_arguments)] // one call site per use; the arguments are one fit's state
pub fn data_jacobian(
    sim: &dyn Simulator,
    tests: &[CuttingTest],
    obs: &[Obs],
    spec: &Spec,
    noise: &[f64; NOUT],
    x: &[f64],
    cols: &[usize],
    steps: &[f64],
) -> Result<DMatrix<f64>, DiagnoseError> {
    let mut j = DMatrix::zeros(obs.len(), cols.len());
    for (c, (&k, &h)) in cols.iter().zip(steps).enumerate() {
        let mut xp = x.to_vec();
        xp[k] += h;
        let rp = residuals(obs, &predict(sim, tests, spec, &spec.ctx, &xp)?, noise);
        let mut xm = x.to_vec();
        xm[k] -= h;
        let rm = residuals(obs, &predict(sim, tests, spec, &spec.ctx, &xm)?, noise);
        for i in 0..obs.len() {
            j[(i, c)] = (rp[i] - rm[i]) / (2.0 * h);
        }
    }
    Ok(j)
}

/// The part of the columns of `s` orthogonal to the column space of `j`: `(I - J J+) S`.
#[must_use]
pub fn project_out(j: &DMatrix<f64>, s: &DMatrix<f64>) -> DMatrix<f64> {
    if j.ncols() == 0 {
        return s.clone();
    }
    let svd = j.clone().svd(true, false);
    let Some(u) = svd.u else { return s.clone() };
    let smax = svd.singular_values.iter().fold(0.0f64, |a, b| a.max(*b));
    let mut out = s.clone();
    for (c, sv) in svd.singular_values.iter().enumerate() {
        if *sv > 1e-9 * smax {
            let uc = u.column(c);
            for k in 0..s.ncols() {
                let coef = uc.dot(&s.column(k));
                let mut col = out.column_mut(k);
                col.axpy(-coef, &uc, 1.0);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_objective_adds_the_prior_penalty_of_the_nuisance_only() {
        // Two nuisance knobs with priors and a free flow-stress scale without one: eta at 0.9 + 1 sd
        // and psi at 0.9 - 2 sd add 1 + 4 = 5; the scale, however far it moves, adds nothing.
        let nuisance = |name: &str, sd: Option<f64>| ParamSpec {
            name: name.into(),
            unit: "-".into(),
            start: 0.9,
            lower: 0.0,
            upper: 2.0,
            prior_sd: sd,
        };
        let params = [nuisance("eta", Some(0.0135)), nuisance("psi", Some(0.0135)), nuisance("scale", None)];
        let x = [0.9 + 0.0135, 0.9 - 0.027, 1.7];
        let penalty = prior_penalty(&params, &x);
        assert!((penalty - 5.0).abs() < 1e-9, "{penalty}");
        let fit = Fit {
            x: x.to_vec(),
            resid: vec![1.0, -2.0],
            rss: 5.0,
            penalty,
            k: 3,
            preds: Vec::new(),
            status: FitStatus::Converged,
        };
        assert!((fit.objective() - 10.0).abs() < 1e-9);
    }
}
