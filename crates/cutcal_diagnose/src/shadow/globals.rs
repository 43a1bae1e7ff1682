//! The shadow's global fit (issue 10, item 1): bounded least squares of cutcal's extended Oxley
//! model (Oxley 1989; Lalwani, Mehta & Jain 2009) against the external simulation's `ln Fc, ln Ft,
//! ln t2`, over a flow-stress level and the JC n, C and m (weak priors), and, behind a gate
//! (`ShadowFit::select_gated`), a scale on Oxley's strain-rate constant C0
//! (`cutcal_model::oxley::Physics::c0_scale`), the tool-chip interface factor m_f and the shadow's
//! own edge radius (Waldorf, DeVor & Kapoor 1998 ploughing) (`FittedShadow::fit`).

use cutcal_ident::lm::{minimise, Bounds, LmOptions, Problem};
use cutcal_ident::IdentError;
use cutcal_model::oxley::OxleyPrediction;
use cutcal_model::{CuttingTest, JcParams, Material};
use nalgebra::DVector;
use rayon::prelude::*;

use super::knobs::Shadow;
use crate::error::DiagnoseError;
use crate::simulator::Prediction;

/// A gated global of the shadow, fitted after the four JC globals only where it halves the misfit
/// (`ShadowFit::select_gated`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Gated {
    /// The tool-chip interface factor m_f (tau_int = m_f k_chip; else 1, Oxley's sticking).
    Friction,
    /// The shadow's own edge radius, um (else sharp).
    Edge,
    /// ln of the scale on Oxley's strain-rate constant C0 (else Oxley's normal-stress condition).
    C0Scale,
}

/// The parameter of a gated global: its name, bounds, off value and start.
#[derive(Debug, Clone, Copy)]
struct GatedSpec {
    name: &'static str,
    lower: f64,
    upper: f64,
    /// The value that leaves the shadow as Oxley's (m_f = 1, sharp, ln s = 0).
    off: f64,
    /// The start of its fit (the edge starts inside its range: at its off value, on the bound, the
    /// fit's first step could not leave it).
    start: f64,
}

impl Gated {
    fn spec(self) -> GatedSpec {
        match self {
            Gated::Friction => GatedSpec { name: "m_f", lower: FRICTION_FACTOR_MIN, upper: 1.0, off: 1.0, start: 1.0 },
            Gated::Edge => GatedSpec { name: "r_e_um", lower: 0.0, upper: EDGE_RADIUS_MAX_UM, off: 0.0, start: 10.0 },
            Gated::C0Scale => GatedSpec {
                name: "ln_c0_scale",
                lower: C0_SCALE_MIN.ln(),
                upper: C0_SCALE_MAX.ln(),
                off: 0.0,
                start: 0.0,
            },
        }
    }
}

/// Least squares of the shadow's globals `[ln level, n, C, m]`, then the gated ones kept (in the
/// order they were added), against the external numbers.
#[derive(Clone)]
pub(super) struct ShadowFit<'a> {
    pub(super) material: &'a Material,
    pub(super) nominal: JcParams,
    pub(super) tests: &'a [CuttingTest],
    pub(super) external: &'a [Prediction],
    /// Warm starts per test: the solutions at the nominal set (fixed, so the fit is deterministic).
    pub(super) starts: Vec<OxleyPrediction>,
    /// The gated globals switched on, in parameter order after the four JC globals.
    pub(super) gated: Vec<Gated>,
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

    /// The value of gated global `g` at `p` (its off value when it is not switched on).
    fn gated_value(&self, g: Gated, p: &[f64]) -> f64 {
        self.gated.iter().position(|&h| h == g).map_or(g.spec().off, |k| p[4 + k])
    }

    /// The shadow's interface factor m_f.
    pub(super) fn friction(&self, p: &[f64]) -> f64 {
        self.gated_value(Gated::Friction, p)
    }

    /// The shadow's edge radius, m.
    pub(super) fn edge(&self, p: &[f64]) -> f64 {
        self.gated_value(Gated::Edge, p) * 1e-6
    }

    /// The shadow's scale on Oxley's C0.
    pub(super) fn c0_scale(&self, p: &[f64]) -> f64 {
        self.gated_value(Gated::C0Scale, p).exp()
    }

    /// The shadow at parameters `p`.
    pub(super) fn shadow(&self, p: &[f64]) -> Shadow<'_> {
        Shadow {
            material: self.material,
            jc: self.jc(p),
            friction: self.friction(p),
            edge_m: self.edge(p),
            c0_scale: self.c0_scale(p),
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
        for g in &self.gated {
            let spec = g.spec();
            names.push(spec.name.to_string());
            lo.push(spec.lower);
            hi.push(spec.upper);
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

    /// The gated globals after the fit `x`, by forward selection: while `x` leaves more than
    /// [`FRICTION_TRY_RMS_PCT`] on at least three tests (nine numbers), each remaining global of
    /// `candidates` (with its ceiling, %) is tried appended to the parameters at its start; those
    /// that bring the misfit below [`FRICTION_GATE`] times that and at most to their ceiling
    /// qualify, and the one that leaves the least is kept (ties: the first listed). The choice does
    /// not depend on the list's order except in ties: a global fitted first would otherwise take
    /// part of another's departure (a C0 scale part of an edge's ploughing) and leave less for it
    /// to halve. Returns the fit kept; `self.gated` then lists the globals kept, in order.
    pub(super) fn select_gated(
        &mut self,
        mut x: Vec<f64>,
        mut converged: bool,
        candidates: &[(Gated, f64)],
    ) -> Result<(Vec<f64>, bool), DiagnoseError> {
        let mut remaining = candidates.to_vec();
        while let Some(before) = self.rms_pct(&x).filter(|&r| self.tests.len() >= 3 && r > FRICTION_TRY_RMS_PCT) {
            // The trials of one round are independent: fitted in parallel, compared in list order.
            let trials: Vec<(Option<f64>, Vec<f64>, bool)> = remaining
                .par_iter()
                .map(|&(g, _)| {
                    let mut with = self.clone();
                    with.gated.push(g);
                    let mut trial = x.clone();
                    trial.push(g.spec().start);
                    let (xt, conv_t) = with.run(trial)?;
                    Ok((with.rms_pct(&xt), xt, conv_t))
                })
                .collect::<Result<_, DiagnoseError>>()?;
            let mut best: Option<(f64, usize)> = None;
            for (k, (&(_, ceiling), (after, _, _))) in remaining.iter().zip(&trials).enumerate() {
                if let Some(r) = after.filter(|&r| r < FRICTION_GATE * before && r <= ceiling) {
                    if best.is_none_or(|b| r < b.0) {
                        best = Some((r, k));
                    }
                }
            }
            let Some((_, k)) = best else { break };
            let Some((_, xt, conv_t)) = trials.into_iter().nth(k) else { break };
            self.gated.push(remaining.remove(k).0);
            x = xt;
            converged = conv_t;
        }
        Ok((x, converged))
    }
}

/// Lower bound of the shadow's interface factor m_f (tau_int = m_f k_chip).
const FRICTION_FACTOR_MIN: f64 = 0.3;
/// Upper bound of the shadow's own edge radius, um (honed and worn edges of practical tools).
const EDGE_RADIUS_MAX_UM: f64 = 60.0;
/// Range of the shadow's C0 scale: a primary zone from a tenth to 50 times as thick as Oxley's
/// closure puts it. On the concealed benchmark's minimum-energy family (`docs/concealed.md`, family
/// c, whose primary zone has a fixed C0 = 6) scales fell to the bound at 0.25 and still at 0.1: the
/// emulated closure wants the hardening term C0 n_eq of the resultant's direction nearly gone.
const C0_SCALE_MAX: f64 = 10.0;
/// Lower bound of the shadow's C0 scale (see [`C0_SCALE_MAX`]).
const C0_SCALE_MIN: f64 = 0.02;
/// The shadow tries its gated globals only while the fit leaves more than this misfit (RMS, %).
pub(super) const FRICTION_TRY_RMS_PCT: f64 = 3.0;
/// A gated global qualifies only when it brings the misfit below this fraction of what the fit
/// left before it (set for m_f in the thirteenth session and kept for the others): an
/// external contact unlike Oxley's sticking (an FE run's Coulomb or shear-factor law) then explains
/// most of it, while a modest gain means m_f only compensates for another difference.
pub(super) const FRICTION_GATE: f64 = 0.5;

impl Problem for ShadowFit<'_> {
    fn parameter_count(&self) -> usize {
        4 + self.gated.len()
    }
    fn residual_count(&self) -> usize {
        3 * self.tests.len() + 3
    }
    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        let x: Vec<f64> = p.iter().copied().collect();
        let sh = self.shadow(&x);
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
