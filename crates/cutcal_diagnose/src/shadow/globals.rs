//! The shadow's global fit (issue 10, item 1): bounded least squares of cutcal's extended Oxley
//! model (Oxley 1989; Lalwani, Mehta & Jain 2009) against the external simulation's `ln Fc, ln Ft,
//! ln t2`, over a flow-stress level and the JC n, C and m (weak priors), and, behind a gate
//! (`ShadowFit::try_global`), the tool-chip interface factor m_f and the shadow's own edge radius
//! (Waldorf, DeVor & Kapoor 1998 ploughing) (`ShadowSimulation::build`).

use cutcal_ident::lm::{minimise, Bounds, LmOptions, Problem};
use cutcal_ident::IdentError;
use cutcal_model::oxley::OxleyPrediction;
use cutcal_model::{CuttingTest, JcParams, Material};
use nalgebra::DVector;
use rayon::prelude::*;

use super::knobs::Shadow;
use crate::error::DiagnoseError;
use crate::simulator::Prediction;

/// Least squares of the shadow's globals `[ln level, n, C, m]`, and m_f when `with_friction`, against the
/// external numbers.
pub(super) struct ShadowFit<'a> {
    pub(super) material: &'a Material,
    pub(super) nominal: JcParams,
    pub(super) tests: &'a [CuttingTest],
    pub(super) external: &'a [Prediction],
    /// Warm starts per test: the solutions at the nominal set (fixed, so the fit is deterministic).
    pub(super) starts: Vec<OxleyPrediction>,
    /// Whether the interface factor m_f is a fifth global (else m_f = 1, Oxley's sticking).
    pub(super) with_friction: bool,
    /// Whether the edge radius (um) is a global after the others (else the shadow is sharp).
    pub(super) with_edge: bool,
}

impl ShadowFit<'_> {
    pub(super) fn jc(&self, p: &[f64]) -> JcParams {
        JcParams {
            a_pa: self.nominal.a_pa * p[0].exp(),
            b_pa: self.nominal.b_pa * p[0].exp(),
            n: p[1],
            c: p[2],
            m: p[3],
            ..self.nominal
        }
    }

    pub(super) fn friction(&self, p: &[f64]) -> f64 {
        if self.with_friction {
            p[4]
        } else {
            1.0
        }
    }

    /// The shadow's edge radius, m.
    pub(super) fn edge(&self, p: &[f64]) -> f64 {
        if self.with_edge {
            p[4 + usize::from(self.with_friction)] * 1e-6
        } else {
            0.0
        }
    }

    /// RMS of `ln(y_shadow / y_external)` (%) at `p` over the fitted tests, when every one solves.
    pub(super) fn rms_pct(&self, p: &[f64]) -> Option<f64> {
        let mut r = DVector::zeros(self.residual_count());
        Problem::residuals(self, &DVector::from_row_slice(p), &mut r).ok()?;
        let k = 3 * self.tests.len();
        let ms = r.rows(0, k).norm_squared() / k as f64;
        ms.is_finite().then(|| 100.0 * (ms.sqrt().exp() - 1.0))
    }

    /// Bounded least squares from `start`: the parameters and whether a tolerance was met.
    pub(super) fn run(&self, start: Vec<f64>) -> Result<(Vec<f64>, bool), DiagnoseError> {
        let (mut names, mut lo, mut hi) = (
            vec!["ln_level".to_string(), "n".into(), "C".into(), "m".into()],
            vec![-2.5, 0.05, 1e-4, 0.3],
            vec![2.5, 0.8, 0.2, 2.5],
        );
        if self.with_friction {
            names.push("m_f".into());
            lo.push(FRICTION_FACTOR_MIN);
            hi.push(1.0);
        }
        if self.with_edge {
            names.push("r_e_um".into());
            lo.push(0.0);
            hi.push(EDGE_RADIUS_MAX_UM);
        }
        let bounds = Bounds::new(names, lo, hi).map_err(|e| DiagnoseError::Fit(e.to_string()))?;
        let opts =
            LmOptions { max_iterations: 30, gradient_tolerance: 1e-6, cost_tolerance: 1e-6, step_tolerance: 1e-6 };
        Ok(match minimise(self, &bounds, &DVector::from_vec(start.clone()), &opts) {
            Ok(r) => {
                (r.params.iter().copied().collect(), r.termination != cutcal_ident::lm::Termination::MaxIterations)
            }
            Err(_) => (start, false),
        })
    }

    /// One more global after the fit `x` (switched on by `switch`, appended to the parameters and
    /// started at `start`), behind the gate: tried when `x` leaves more than
    /// [`FRICTION_TRY_RMS_PCT`] on at least three tests (nine numbers), kept only when the new fit
    /// brings the misfit below [`FRICTION_GATE`] times that and at most to `ceiling` (%). Returns
    /// the fit kept, and leaves the switch as that fit has it.
    pub(super) fn try_global(
        &mut self,
        x: Vec<f64>,
        converged: bool,
        switch: fn(&mut Self, bool),
        start: f64,
        ceiling: f64,
    ) -> Result<(Vec<f64>, bool), DiagnoseError> {
        let Some(before) = self.rms_pct(&x).filter(|&r| self.tests.len() >= 3 && r > FRICTION_TRY_RMS_PCT) else {
            return Ok((x, converged));
        };
        switch(self, true);
        let mut trial = x.clone();
        trial.push(start);
        let (xt, conv_t) = self.run(trial)?;
        if self.rms_pct(&xt).is_some_and(|r| r < FRICTION_GATE * before && r <= ceiling) {
            Ok((xt, conv_t))
        } else {
            switch(self, false);
            Ok((x, converged))
        }
    }
}

/// Lower bound of the shadow's interface factor m_f (tau_int = m_f k_chip).
const FRICTION_FACTOR_MIN: f64 = 0.3;
/// Upper bound of the shadow's own edge radius, um (honed and worn edges of practical tools).
const EDGE_RADIUS_MAX_UM: f64 = 60.0;
/// The shadow tries m_f only when the four globals leave more than this misfit (RMS, %).
pub(super) const FRICTION_TRY_RMS_PCT: f64 = 3.0;
/// m_f is kept only when it brings the misfit below this fraction of the four-global fit's: an
/// external contact unlike Oxley's sticking (an FE run's Coulomb or shear-factor law) then explains
/// most of it, while a modest gain means m_f only compensates for another difference.
pub(super) const FRICTION_GATE: f64 = 0.5;

impl Problem for ShadowFit<'_> {
    fn parameter_count(&self) -> usize {
        4 + usize::from(self.with_friction) + usize::from(self.with_edge)
    }
    fn residual_count(&self) -> usize {
        3 * self.tests.len() + 3
    }
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        let x: Vec<f64> = p.iter().copied().collect();
        let sh =
            Shadow { material: self.material, jc: self.jc(&x), friction: self.friction(&x), edge_m: self.edge(&x) };
        let ys: Vec<Result<[f64; 5], DiagnoseError>> = self
            .tests
            .par_iter()
            .zip(&self.starts)
            .map(|(t, s)| sh.eval_from(t, None, Some(s)).map(|(y, _)| y))
            .collect();
        for (i, (y, e)) in ys.into_iter().zip(self.external).enumerate() {
            let y = y.map_err(|e| match e {
                DiagnoseError::Model { source, .. } => IdentError::Model(source),
                other => IdentError::InvalidOptions(other.to_string()),
            })?;
            out[3 * i] = e.fc_n_per_m.ln() - y[0];
            out[3 * i + 1] = e.ft_n_per_m.ln() - y[1];
            out[3 * i + 2] = e.chip_m.ln() - y[2];
        }
        // Weak priors (pseudo-residuals in the same log units, one per 0.05 of noise): n +-0.1,
        // C +-0.01, m +-0.2 about the nominal set.
        let k = 3 * self.tests.len();
        out[k] = 0.05 * (x[1] - self.nominal.n) / 0.1;
        out[k + 1] = 0.05 * (x[2] - self.nominal.c) / 0.01;
        out[k + 2] = 0.05 * (x[3] - self.nominal.m) / 0.2;
        Ok(())
    }
}
