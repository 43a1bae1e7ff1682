//! Joint identification of Johnson-Cook parameters from several orthogonal cutting tests through the
//! extended Oxley model (OXCUT-style inverse use of Oxley's theory).
//!
//! Residuals, relative-error weighted (dimensionless), for every test `i` with the measurement:
//!
//! ```text
//! r = (Fc_pred,i - Fc_meas,i) / Fc_meas,i,   (Ft_pred,i - Ft_meas,i) / Ft_meas,i,   (t2_pred,i - tc_meas,i) / tc_meas,i
//! ```
//!
//! Forces are per unit width (N/m) on both sides (the CLI converts totals with the width); the chip
//! thickness term is used only where measured and when [`JointOptions::use_chip_thickness`] is set.
//! The bounded LM with seeded multistart of [`crate::multistart`] minimises `|r|^2` over
//! `[A_MPa, B_MPa, n, C, m]`; covariance and at-bound flags come from [`crate::multistart::fit_statistics`].
//!
//! **Source:** the inverse use of Oxley's model follows the OXCUT approach (Oxley 1989, Ch. 7 uses the
//! forward model for machinability data); the forward model is [`cutcal_model::oxley`].

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, OxleyPrediction, Physics};
use cutcal_model::{CuttingTest, Material};

use crate::dpzd_fit::{JcBounds, JcConstants};
use crate::error::IdentError;
use crate::identifiability::{assess, Identifiability};
use crate::literature::{LiteratureBox, MaterialClass};
use crate::lm::{Bounds, Problem, Termination};
use crate::multistart::{fit_statistics, multistart, FitStatistics, MultistartOptions};

/// Relative standard deviations used where a test states none: Fc 3 %, Ft 5 %, chip thickness 5 %
/// (the project's documented default noise model, as in the diagnosis).
pub const DEFAULT_RELATIVE_SD: [f64; 3] = [0.03, 0.05, 0.05];

/// Level of the goodness-of-fit test (chi-square of the sd-weighted residuals) below which a
/// determined set is called a misfit.
pub const MISFIT_LEVEL: f64 = 0.01;

/// Settings of the joint fit besides the bounds and the multistart.
#[derive(Debug, Clone, PartialEq)]
pub struct JointOptions {
    /// Forward-model options.
    pub oxley: OxleyOptions,
    /// Extra physics in the forward model (usually [`Physics::baseline`]).
    pub physics: Physics,
    /// Initial work temperature, degC (usually the material's room temperature).
    pub work_temperature_c: f64,
    /// Fit the measured chip thickness where a test has it.
    pub use_chip_thickness: bool,
    /// Add each test's stated edge radius and flank wear to `physics` (edge ploughing, Waldorf et
    /// al. 1998; wear land, Smithey et al. 2001; see `cutcal_model::oxley::Physics::with_tool`).
    pub tool_condition: bool,
}

/// Which measured quantity a residual compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Cutting force.
    CuttingForce,
    /// Feed force.
    FeedForce,
    /// Chip thickness.
    ChipThickness,
}

/// One residual: its test, quantity and measured value (SI: N/m or m).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Observation {
    /// Index of the test in the input slice.
    pub test: usize,
    /// The quantity.
    pub quantity: Quantity,
    /// Measured value, N/m or m.
    pub measured: f64,
    /// Relative standard deviation of the measurement: the test's stated sd over the value, or
    /// [`DEFAULT_RELATIVE_SD`].
    pub relative_sd: f64,
}

/// The least-squares problem: one cold forward prediction per test per evaluation, so the forward
/// map is a pure function of the parameters (no warm start, no memoisation, no path dependence).
pub struct JointOxleyProblem<'a> {
    material: &'a Material,
    conditions: Vec<CuttingConditions>,
    physics: Vec<Physics>,
    observations: Vec<Observation>,
    constants: JcConstants,
    options: &'a JointOptions,
}

impl<'a> JointOxleyProblem<'a> {
    /// Assembles the problem from the tests' measurements.
    ///
    /// Returns an error if a test's conditions are invalid or no test has a measured force.
    pub fn new(
        material: &'a Material,
        tests: &[CuttingTest],
        constants: JcConstants,
        options: &'a JointOptions,
    ) -> Result<Self, IdentError> {
        let mut conditions = Vec::with_capacity(tests.len());
        let mut physics = Vec::with_capacity(tests.len());
        let mut observations = Vec::new();
        for (i, t) in tests.iter().enumerate() {
            conditions.push(CuttingConditions::from_test(t, options.work_temperature_c)?);
            let mut ph = options.physics;
            if options.tool_condition {
                let tool = Physics::with_tool(t.edge_radius_m, t.flank_wear_m)?;
                ph.edge_ploughing = tool.edge_ploughing.or(ph.edge_ploughing);
                ph.flank_wear = tool.flank_wear.or(ph.flank_wear);
            }
            physics.push(ph);
            let m = &t.measured;
            let rel = |v: f64, sd: Option<f64>, default: f64| match sd {
                Some(s) if s > 0.0 && s.is_finite() => s / v.abs(),
                _ => default,
            };
            let [d_fc, d_ft, d_tc] = DEFAULT_RELATIVE_SD;
            if let Some(v) = m.cutting_force_n_per_m {
                let relative_sd = rel(v, m.sd.cutting_force_n_per_m, d_fc);
                observations.push(Observation { test: i, quantity: Quantity::CuttingForce, measured: v, relative_sd });
            }
            if let Some(v) = m.feed_force_n_per_m {
                let relative_sd = rel(v, m.sd.feed_force_n_per_m, d_ft);
                observations.push(Observation { test: i, quantity: Quantity::FeedForce, measured: v, relative_sd });
            }
            if options.use_chip_thickness {
                if let Some(v) = m.chip_thickness_m {
                    let relative_sd = rel(v, m.sd.chip_thickness_m, d_tc);
                    observations.push(Observation {
                        test: i,
                        quantity: Quantity::ChipThickness,
                        measured: v,
                        relative_sd,
                    });
                }
            }
        }
        if observations.is_empty() {
            return Err(IdentError::InvalidOptions("no test has a measured cutting or feed force".into()));
        }
        Ok(Self { material, physics, conditions, observations, constants, options })
    }

    /// The observations, in residual order.
    #[must_use]
    pub fn observations(&self) -> &[Observation] {
        &self.observations
    }

    /// Forward predictions of every test at parameters `p = [A_MPa, B_MPa, n, C, m]`: each a cold
    /// [`oxley::predict`], so the same `p` gives the same predictions whatever was evaluated before.
    pub fn predictions(&self, p: &DVector<f64>) -> Result<Vec<OxleyPrediction>, IdentError> {
        let jc = self.constants.params(p);
        self.conditions
            .iter()
            .zip(&self.physics)
            .map(|(c, ph)| Ok(oxley::predict(self.material, &jc, c, &self.options.oxley, ph)?))
            .collect()
    }
}

impl Problem for JointOxleyProblem<'_> {
    fn parameter_count(&self) -> usize {
        5
    }

    fn residual_count(&self) -> usize {
        self.observations.len()
    }

    fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
        let preds = self.predictions(p)?;
        for (k, o) in self.observations.iter().enumerate() {
            let pr = &preds[o.test];
            let v = match o.quantity {
                Quantity::CuttingForce => pr.cutting_force_n_per_m,
                Quantity::FeedForce => pr.feed_force_n_per_m,
                Quantity::ChipThickness => pr.chip_thickness_m,
            };
            out[k] = (v - o.measured) / o.measured;
        }
        Ok(())
    }

    fn jacobian(&self, p: &DVector<f64>, bounds: &Bounds, out: &mut DMatrix<f64>) -> Result<(), IdentError> {
        crate::lm::jacobian_with_fresh_base(self, p, bounds, out)
    }

    /// Forward differences from the residuals `r0` at `p` (one forward solve set per parameter,
    /// half the cost of central ones); the step is 1e-5 of the bound width, inward at the upper bound.
    fn jacobian_at(
        &self,
        p: &DVector<f64>,
        r0: &DVector<f64>,
        bounds: &Bounds,
        out: &mut DMatrix<f64>,
    ) -> Result<(), IdentError> {
        let m = self.residual_count();
        let mut r1 = DVector::zeros(m);
        for k in 0..5 {
            let width = bounds.upper[k] - bounds.lower[k];
            if width <= 0.0 {
                // A fixed parameter: no solves, a zero column.
                for i in 0..m {
                    out[(i, k)] = 0.0;
                }
                continue;
            }
            let mut h = 1e-5 * width.max(p[k].abs() * 1e-2).max(1e-12);
            if p[k] + h > bounds.upper[k] {
                h = -h;
            }
            let mut q = p.clone();
            q[k] += h;
            self.residuals(&q, &mut r1)?;
            for i in 0..m {
                out[(i, k)] = (r1[i] - r0[i]) / h;
            }
        }
        Ok(())
    }
}

/// The outcome of a joint identification.
#[derive(Debug, Clone, Serialize)]
pub struct OxleyIdentification {
    /// Identified JC parameters.
    pub jc: cutcal_model::JcParams,
    /// The residuals (relative errors) at the solution, in observation order.
    pub relative_errors: Vec<f64>,
    /// What each residual compares.
    pub observations: Vec<Observation>,
    /// Forward predictions at the solution, one per test.
    pub predictions: Vec<OxleyPrediction>,
    /// Fit statistics: covariance, correlation, parameters at bounds.
    pub statistics: FitStatistics,
    /// Starts run.
    pub starts: usize,
    /// Starts reaching the best minimum.
    pub starts_at_best: usize,
    /// Index of the best start.
    pub best_start: usize,
    /// Starts that failed.
    pub failed_starts: usize,
    /// LM iterations of the best start.
    pub iterations: usize,
    /// Why the best start's LM stopped.
    pub termination: Termination,
    /// Starts that hit the LM iteration cap (excluded from the best while any start converged).
    pub unconverged_starts: usize,
    /// The bounds the fit used (the user's A and B; n, C and m intersected with the literature box).
    pub bounds_used: JcBounds,
    /// The literature box of the material class, when the class is known.
    pub literature: Option<LiteratureBox>,
    /// Parameters of the identified set outside the literature box (empty when inside or no box).
    pub outside_literature: Vec<String>,
    /// What the data determine at the solution; `None` if the Jacobian there failed.
    pub identifiability: Option<Identifiability>,
    /// Whether the set may be exported.
    pub verdict: JointVerdict,
}

/// The decision on a joint identification.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum JointVerdict {
    /// The LM converged and the data determine every free parameter direction.
    Determined,
    /// The data do not determine the set (the reason names the rank and condition number, and
    /// the parameters of the weakest direction). Callers must not export it as an identification.
    Undetermined {
        /// Why, in one sentence.
        reason: String,
    },
    /// The data determine the set, but no set in the box fits them within their stated noise
    /// (chi-square test at the 1 % level): the forward model leaves out physics these tests contain.
    Misfit {
        /// Why, in one sentence.
        reason: String,
    },
    /// The best start hit the LM iteration cap.
    NotConverged {
        /// Why, in one sentence.
        reason: String,
    },
}

impl JointVerdict {
    /// Whether the set may be exported as an identified set.
    #[must_use]
    pub fn is_determined(&self) -> bool {
        matches!(self, JointVerdict::Determined)
    }
}

/// Fixes one parameter (`a_mpa`, `b_mpa`, `n`, `c` or `m`; `A`, `B`, `C` accepted) at `value` by
/// giving it a zero-width box.
///
/// Returns an error for an unknown name or a value that is not finite and non-negative.
pub fn fix_parameter(bounds: &mut JcBounds, name: &str, value: f64) -> Result<(), IdentError> {
    if !(value.is_finite() && value >= 0.0) {
        return Err(IdentError::InvalidOptions(format!("fixed {name} = {value}: must be finite and >= 0")));
    }
    let slot = match name.trim().to_ascii_lowercase().as_str() {
        "a" | "a_mpa" => &mut bounds.a_mpa,
        "b" | "b_mpa" => &mut bounds.b_mpa,
        "n" => &mut bounds.n,
        "c" => &mut bounds.c,
        "m" => &mut bounds.m,
        other => {
            return Err(IdentError::InvalidOptions(format!(
                "cannot fix {other:?}: expected one of a_mpa, b_mpa, n, c, m"
            )))
        }
    };
    *slot = [value, value];
    Ok(())
}

/// The bounds of the joint fit: the user's A and B bounds; the n, C and m bounds intersected with
/// the literature box of `class` (the literature box alone where they do not overlap). Returns the
/// bounds and the box used (`None` without a class).
#[must_use]
pub fn plausible_bounds(user: &JcBounds, class: Option<MaterialClass>) -> (JcBounds, Option<LiteratureBox>) {
    let Some(class) = class else { return (*user, None) };
    let lit = LiteratureBox::of(class);
    let meet = |u: [f64; 2], l: [f64; 2]| {
        let (lo, hi) = (u[0].max(l[0]), u[1].min(l[1]));
        if u[1] <= u[0] {
            // A fixed parameter stays as the user fixed it (reported if outside the box).
            u
        } else if lo <= hi {
            [lo, hi]
        } else {
            l
        }
    };
    let b = JcBounds {
        a_mpa: user.a_mpa,
        b_mpa: user.b_mpa,
        n: meet(user.n, lit.n),
        c: meet(user.c, lit.c),
        m: meet(user.m, lit.m),
    };
    (b, Some(lit))
}

/// Fits JC jointly to the measured forces (and chip thickness) of `tests` through the extended
/// Oxley model, within `bounds`, from a seeded multistart.
///
/// Returns an error if the tests or bounds are invalid, or every start fails.
///
/// `class` selects the literature box for n, C and m ([`plausible_bounds`]); `None` keeps `bounds`
/// as given. The outcome's [`JointVerdict`] says whether the data determine the set
/// ([`crate::identifiability`]) and whether the LM converged.
pub fn identify_oxley(
    material: &Material,
    tests: &[CuttingTest],
    bounds: &JcBounds,
    class: Option<MaterialClass>,
    constants: JcConstants,
    options: &JointOptions,
    multistart_options: &MultistartOptions,
) -> Result<OxleyIdentification, IdentError> {
    let problem = JointOxleyProblem::new(material, tests, constants, options)?;
    let (bounds_used, literature) = plausible_bounds(bounds, class);
    let b = bounds_used.to_bounds()?;
    let report = multistart(&problem, &b, multistart_options)?;
    let predictions = problem.predictions(&report.best.params)?;
    // The covariance needs a Jacobian at the solution; if a perturbed forward solve fails there,
    // report the fit without covariance rather than failing the identification.
    let stats = fit_statistics(&problem, &b, &report.best.params, &report.best.residuals)
        .unwrap_or_else(|_| FitStatistics::without_covariance(&b, &report.best.params, &report.best.residuals));
    let identifiability = identifiability(&problem, &b, &report.best.params);
    let p = &report.best.params;
    let outside_literature = literature.as_ref().map_or_else(Vec::new, |l| l.outside(p[2], p[3], p[4]));
    let verdict = if report.best.termination == Termination::MaxIterations {
        JointVerdict::NotConverged {
            reason: format!(
                "every start stopped at the LM iteration cap ({} iterations) without meeting a tolerance",
                report.best.iterations
            ),
        }
    } else {
        let chi2: f64 =
            report.best.residuals.iter().zip(&problem.observations).map(|(r, o)| (r / o.relative_sd).powi(2)).sum();
        let free = (0..5).filter(|&k| b.upper[k] > b.lower[k]).count();
        let dof = problem.observations.len().saturating_sub(free);
        let p_fit = (dof > 0).then(|| crate::stats::chi2_sf(chi2, dof as f64));
        match &identifiability {
            Some(a) if a.determined && p_fit.is_some_and(|p| p < MISFIT_LEVEL) => JointVerdict::Misfit {
                reason: format!(
                    "chi-square {chi2:.1} on {dof} degrees of freedom (p = {:.1e}) with the stated measurement sd: no set in the box reproduces these tests; the forward model leaves out physics they contain (try `cutcal diagnose`)",
                    p_fit.unwrap_or(0.0)
                ),
            },
            Some(a) if a.determined => JointVerdict::Determined,
            Some(a) => JointVerdict::Undetermined {
                reason: format!(
                    "the data determine {} of {} parameter directions (condition number {}); the weakest, {}, is uncertain by {} of its box width at 1 sd",
                    a.effective_rank,
                    a.parameters.len(),
                    a.condition_number.map_or_else(|| "infinite".to_string(), |c| format!("{c:.3e}")),
                    a.weakest_direction.iter().take(3).map(|(n, v)| format!("{v:+.2} {n}")).collect::<Vec<_>>().join(" "),
                    a.weakest_uncertainty_in_box_widths.map_or_else(|| "an unbounded amount".to_string(), |u| format!("{u:.2}")),
                ),
            },
            None => JointVerdict::Undetermined {
                reason: "the Jacobian at the solution could not be evaluated (a perturbed forward solve failed)".into(),
            },
        }
    };
    Ok(OxleyIdentification {
        jc: constants.params(&report.best.params),
        relative_errors: report.best.residuals.iter().copied().collect(),
        observations: problem.observations.clone(),
        predictions,
        statistics: stats,
        starts: report.starts,
        starts_at_best: report.starts_at_best,
        best_start: report.best_start,
        failed_starts: report.failed_starts,
        iterations: report.best.iterations,
        termination: report.best.termination,
        unconverged_starts: report.unconverged_starts,
        bounds_used,
        literature,
        outside_literature,
        identifiability,
        verdict,
    })
}

/// [`assess`] of the joint problem at `p`: rows weighted by each observation's relative sd, columns
/// scaled by the bound widths.
fn identifiability(problem: &JointOxleyProblem<'_>, b: &Bounds, p: &DVector<f64>) -> Option<Identifiability> {
    let mut jac = DMatrix::zeros(problem.residual_count(), 5);
    problem.jacobian(p, b, &mut jac).ok()?;
    let sd: Vec<f64> = problem.observations.iter().map(|o| o.relative_sd).collect();
    let widths: Vec<f64> = (0..5).map(|k| b.upper[k] - b.lower[k]).collect();
    assess(&jac, &sd, &widths, &b.names)
}

#[cfg(test)]
mod tests;
