//! The state one diagnosis works on: the observations, the condition groups, the fit of a model
//! spec and its leave-one-condition-out folds (design note Sec 3.5), and the candidate record the
//! screen and refit fill in.

use cutcal_model::CuttingTest;

use crate::diagnose::Config;
use crate::error::DiagnoseError;
use crate::fit::{self, observations, Fit, Obs, Spec};
use crate::mechanism::MechanismId;

use crate::report::*;
use crate::simulator::Simulator;

pub(crate) struct Candidate {
    pub(crate) id: MechanismId,
    pub(crate) spec: Spec,
    pub(crate) fit: Fit,
    pub(crate) p: f64,
    pub(crate) daicc: f64,
    pub(crate) explained: f64,
    pub(crate) absorption: f64,
    pub(crate) screen_p: f64,
    /// Estimate and 95 % interval per fitted parameter (`None` ends when not available).
    pub(crate) ci: Vec<(f64, Option<f64>, Option<f64>)>,
    /// Why the interval is not available (empty when it is).
    pub(crate) ci_note: String,
    pub(crate) ci_ok: bool,
    /// Why the refit, significant or not, is not the mechanism's physics (`ci_ok` is then false).
    pub(crate) conflict: Option<String>,
    pub(crate) change: Vec<f64>,
    /// Screening sensitivity of the first parameter (noise units per typical magnitude).
    pub(crate) sens: Vec<f64>,
    /// Detection limit per strength parameter, typical moves per unit root non-centrality
    /// (`crate::detect`).
    pub(crate) unit_limits: Vec<crate::detect::ColumnLimit>,
    pub(crate) loco_after: Option<Loco>,
    /// The held-out pass's worst fold: the left-out condition's first test id and the candidate's
    /// AICc change on that fold's training data (`crate::heldout::heldout_round`).
    pub(crate) worst_fold: Option<(String, f64)>,
    pub(crate) significant: bool,
    pub(crate) accepted: bool,
    pub(crate) reason: String,
    /// The instrument artefact that explains the mismatch at least as well and stopped the claim.
    pub(crate) stopped_by: Option<crate::instrument::Artefact>,
    /// The earlier claim this candidate was held back for as a confounder (it passed its checks).
    pub(crate) held_back_for: Option<MechanismId>,
}

#[cfg(test)]
impl Candidate {
    /// A first-round candidate of mechanism `id` at `daicc`, significant with a usable interval
    /// (unit tests of the decision rules).
    pub(crate) fn stub(id: MechanismId, daicc: f64, accepted: bool) -> Self {
        let fit = crate::fit::Fit {
            x: vec![],
            resid: vec![],
            rss: 0.0,
            penalty: 0.0,
            k: 0,
            preds: vec![],
            status: crate::fit::FitStatus::Converged,
        };
        let spec = Spec { mechanisms: vec![id], ctx: crate::context::Context::of(&[]) };
        Self {
            id,
            spec,
            fit,
            p: 1e-6,
            daicc,
            explained: 0.5,
            absorption: 0.0,
            screen_p: 1e-6,
            ci: vec![],
            ci_note: String::new(),
            ci_ok: true,
            conflict: None,
            change: vec![],
            sens: vec![],
            unit_limits: vec![],
            loco_after: None,
            worst_fold: None,
            significant: true,
            accepted,
            reason: String::new(),
            stopped_by: None,
            held_back_for: None,
        }
    }
}

/// Held-out residuals of a leave-one-condition-out pass, in observation order (noise units).
#[derive(Debug, Clone)]
pub(crate) struct Loco {
    pub(crate) resid: Vec<f64>,
    pub(crate) rss: f64,
}

/// Groups tests into conditions (same h, V and rake).
pub fn condition_groups(tests: &[CuttingTest]) -> Vec<Vec<usize>> {
    let key = |t: &CuttingTest| {
        (
            (t.uncut_chip_thickness_m * 1e9).round() as i64,
            (t.speed_m_per_s * 1e6).round() as i64,
            (t.rake_rad * 1e6).round() as i64,
        )
    };
    let mut groups: Vec<(_, Vec<usize>)> = Vec::new();
    for (i, t) in tests.iter().enumerate() {
        let k = key(t);
        match groups.iter_mut().find(|(g, _)| *g == k) {
            Some((_, v)) => v.push(i),
            None => groups.push((k, vec![i])),
        }
    }
    groups.into_iter().map(|(_, v)| v).collect()
}

pub(crate) struct Problem<'a> {
    pub(crate) sim: &'a dyn Simulator,
    pub(crate) tests: &'a [CuttingTest],
    pub(crate) obs: Vec<Obs>,
    pub(crate) groups: Vec<Vec<usize>>,
    pub(crate) cfg: &'a Config,
}

impl Problem<'_> {
    pub(crate) fn n(&self) -> usize {
        self.obs.len()
    }

    pub(crate) fn fit(&self, spec: &Spec, start: Option<&[f64]>) -> Result<Fit, DiagnoseError> {
        fit::fit(self.sim, self.tests, &self.obs, spec, &self.cfg.noise, start, self.cfg.max_iterations)
    }

    /// Fits on all conditions but one, for each condition, and returns the held-out residuals of
    /// each spec in `specs` (fits warm-started at `starts`). `None` when the design is too small.
    pub(crate) fn loco(&self, specs: &[(&Spec, &[f64])]) -> Result<Option<Vec<Vec<Fit>>>, DiagnoseError> {
        if self.groups.len() < 3 {
            return Ok(None);
        }
        let mut per_fold = Vec::new();
        for g in &self.groups {
            let train: Vec<usize> = (0..self.tests.len()).filter(|i| !g.contains(i)).collect();
            let tr_tests: Vec<CuttingTest> = train.iter().map(|&i| self.tests[i].clone()).collect();
            let tr_obs = observations(&tr_tests);
            let te_tests: Vec<CuttingTest> = g.iter().map(|&i| self.tests[i].clone()).collect();
            let te_obs = observations(&te_tests);
            let mut fits = Vec::new();
            for (spec, start) in specs {
                let k = start.len();
                if tr_obs.len() <= k {
                    return Ok(None);
                }
                let tr_spec = Spec { mechanisms: spec.mechanisms.clone(), ctx: spec.ctx.subset(&train) };
                let f = fit::fit(
                    self.sim,
                    &tr_tests,
                    &tr_obs,
                    &tr_spec,
                    &self.cfg.noise,
                    Some(start),
                    self.cfg.max_iterations,
                )?;
                let te_ctx = spec.ctx.subset(g);
                let preds = fit::predict(
                    self.sim,
                    &te_tests,
                    &Spec { mechanisms: spec.mechanisms.clone(), ctx: te_ctx.clone() },
                    &te_ctx,
                    &f.x,
                )?;
                let resid = fit::residuals(&te_obs, &preds, &self.cfg.noise);
                // Keep the training fit (rss, k) and the held-out residuals/predictions.
                fits.push(Fit { x: f.x, resid, rss: f.rss, penalty: f.penalty, k: f.k, preds, status: f.status });
            }
            per_fold.push(fits);
        }
        Ok(Some(per_fold))
    }
}

pub(crate) fn loco_of(per_fold: &[Vec<Fit>], which: usize) -> Loco {
    let resid: Vec<f64> = per_fold.iter().flat_map(|f| f[which].resid.iter().copied()).collect();
    let rss = resid.iter().map(|r| r * r).sum();
    Loco { resid, rss }
}

/// Relative-error RMS (%) per output from noise-unit residuals and their outputs.
pub(crate) fn rms_pct(resid: &[f64], outputs: &[usize], noise: &[f64; crate::fit::NOUT]) -> OutputRms {
    let mut acc = [(0.0, 0usize); crate::fit::NOUT];
    let mut all = (0.0, 0usize);
    for (r, &j) in resid.iter().zip(outputs) {
        let rel = 100.0 * ((r * noise[j]).exp() - 1.0);
        acc[j].0 += rel * rel;
        acc[j].1 += 1;
        // `all` pools the forces and the chip (comparable with or without a temperature column).
        if j < 3 {
            all.0 += rel * rel;
            all.1 += 1;
        }
    }
    let f = |(s, c): (f64, usize)| (c > 0).then(|| (s / c as f64).sqrt());
    OutputRms { fc: f(acc[0]), ft: f(acc[1]), tc: f(acc[2]), t_int: f(acc[3]), all: f(all).unwrap_or(0.0) }
}
