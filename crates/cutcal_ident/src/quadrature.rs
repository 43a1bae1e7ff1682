//! The Eq 15 objective as an integral over the zone: adaptive Gauss-Kronrod quadrature and the
//! `converged` identification built on it.
//!
//! The paper sums `(f - F)^2` at `N` points it does not state. As `N` grows that sum approximates
//! `N/h int (f - F)^2 dx`, so the natural, `N`-free objective is the zone mean square
//! `J = (1/h) int_{-h/2}^{h/2} (f(x) - F(x))^2 dx`. Here `J` is evaluated with the adaptive
//! 7/15-point Gauss-Kronrod rule of [`crate::zone_rule`], whose panels start at the integrand's
//! breakpoints (AB and the two points where the strain rate crosses `eps0`). The rule depends on the integrand, hence on the parameters, so
//! the identification alternates: fit on the current rule, rebuild the rule at the fit, refit, until
//! A, B, n, C and m move by less than the parameter tolerance. Both loops are capped and end in a
//! typed [`IdentError::NotConverged`].

use cutcal_model::dpzd::ZoneSolution;
use cutcal_model::RateTerm;
use nalgebra::DVector;
use serde::Serialize;

use crate::dpzd_fit::{identify_from_zone_with, identify_warm_with, JcBounds, JcConstants, JcIdentification};
use crate::error::IdentError;
pub use crate::gauss_kronrod::gauss_kronrod_15;
use crate::multistart::MultistartOptions;
pub use crate::zone_rule::{adaptive_rule, adaptive_rule_from, breakpoints, map_edges, ZoneRule};
use crate::zone_rule::{build_rule, PanelCache};

/// Settings of the `converged` objective.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ConvergedOptions {
    /// Relative tolerance of the quadrature error estimate, on `int (f - F)^2` (floor:
    /// `rel_tol * 1e-6 int F^2`).
    pub quadrature_rel_tol: f64,
    /// Panel cap of the adaptive rule.
    pub max_panels: usize,
    /// Stop when every parameter moves by less than this relative amount between refits.
    pub parameter_rel_tol: f64,
    /// Refit cap.
    pub max_refits: usize,
}

impl Default for ConvergedOptions {
    /// Quadrature to 1e-6, parameters to 1e-5 (100 times below the 0.1 % target), 400 panels,
    /// 10 refits.
    fn default() -> Self {
        Self { quadrature_rel_tol: 1e-6, max_panels: 400, parameter_rel_tol: 1e-5, max_refits: 10 }
    }
}

impl ConvergedOptions {
    /// The settings of a Monte-Carlo sample ([`crate::monte_carlo`]): quadrature and parameters to
    /// 1e-4, still 10 times below the 0.1 % convergence target and far below the spread the samples
    /// estimate (C38 test 3: A +- 10 %); 400 panels, 10 refits. On C38 test 3 (10^4 samples) the
    /// reported spread equals the default's to 1e-5 relative (`tests/fast_path.rs` checks a seeded
    /// draw), at about 80 % of the cost.
    #[must_use]
    pub fn monte_carlo() -> Self {
        Self { quadrature_rel_tol: 1e-4, parameter_rel_tol: 1e-4, ..Self::default() }
    }
}

/// The `converged` identification and how it converged.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConvergedIdentification {
    /// The identification on the final rule (objective = zone RMS of `f - F`, MPa).
    pub identification: JcIdentification,
    /// Refits done.
    pub refits: usize,
    /// Panels of the final rule.
    pub panels: usize,
    /// Quadrature nodes of the final rule.
    pub nodes: usize,
    /// Largest relative parameter change at the last refit.
    pub last_parameter_change: f64,
}

/// Identifies JC by minimising the zone integral of Eq 15 with the solvers' clamped law.
///
/// **Source:** paper Sec 4.1, Eq 15 read as `(1/h) int (f - F)^2 dx` with Eqs 13-16; Gauss-Kronrod
/// 7/15 (QUADPACK QK15).
///
/// Returns [`IdentError::NotConverged`] if the rule or the refit loop does not converge within its
/// cap, or any error of the underlying multistart.
pub fn identify_converged(
    zone: &ZoneSolution,
    bounds: &JcBounds,
    constants: JcConstants,
    multistart: &MultistartOptions,
    options: &ConvergedOptions,
) -> Result<ConvergedIdentification, IdentError> {
    let rate = RateTerm::Clamped;
    // Start from the uniform 51-point fit of the same law.
    let id = identify_from_zone_with(zone, 51, rate, bounds, constants, multistart)?;
    refit_until_converged(
        zone,
        bounds,
        constants,
        multistart,
        options,
        id,
        (&breakpoints(zone, constants, rate), None),
        &mut PanelCache::default(),
        true,
    )
}

/// A warm start for [`identify_converged_warm`]: a nearby converged identification (the nominal
/// fit of a Monte-Carlo propagation), its rule's panel edges and its zone's breakpoints.
#[derive(Debug, Clone, PartialEq)]
pub struct WarmStart {
    /// The nearby solution (its n, C and m start the first local solve).
    pub jc: cutcal_model::JcParams,
    /// The panel edges of its final rule, fractions `x/h` ([`ZoneRule::edges_rel`]).
    pub edges_rel: Vec<f64>,
    /// The [`breakpoints`] of its zone (the edges are carried to another zone's with
    /// [`map_edges`]).
    pub breakpoints_rel: Vec<f64>,
}

impl WarmStart {
    /// The warm start of a converged identification on `zone` (its final rule is rebuilt there).
    ///
    /// Returns an error if the rule cannot be rebuilt (as [`adaptive_rule`]).
    pub fn from_identification(
        zone: &ZoneSolution,
        identification: &JcIdentification,
        constants: JcConstants,
        options: &ConvergedOptions,
    ) -> Result<Self, IdentError> {
        let p = vector(identification);
        let rule = adaptive_rule(zone, &p, constants, RateTerm::Clamped, options)?;
        let breakpoints_rel = breakpoints(zone, constants, RateTerm::Clamped);
        Ok(Self { jc: identification.jc, edges_rel: rule.edges_rel, breakpoints_rel })
    }
}

/// [`identify_converged`] warm-started: no uniform 51-point fit; the first rule is refined from
/// `warm`'s panels at `warm`'s parameters and the first start of every multistart is the
/// previous solution (`multistart.starts` starts in all, the others the same Latin hypercube).
///
/// The minimum is the same as [`identify_converged`]'s within the refit and quadrature
/// tolerances when `warm` lies in its basin (a Monte-Carlo sample near the nominal fit; checked on
/// C38 test 3 draws in `tests/fast_path.rs`); the rule can have more panels than a cold start's.
///
/// **Source:** as [`identify_converged`].
///
/// Returns an error as [`identify_converged`].
pub fn identify_converged_warm(
    zone: &ZoneSolution,
    bounds: &JcBounds,
    constants: JcConstants,
    multistart: &MultistartOptions,
    options: &ConvergedOptions,
    warm: &WarmStart,
) -> Result<ConvergedIdentification, IdentError> {
    identify_converged_warm_with(zone, bounds, constants, multistart, options, warm, true)
}

/// [`identify_converged_warm`]; with `statistics` false no fit along the way computes the
/// covariance and its relatives ([`crate::dpzd_fit::identify_warm`]): the Monte-Carlo samples.
pub(crate) fn identify_converged_warm_with(
    zone: &ZoneSolution,
    bounds: &JcBounds,
    constants: JcConstants,
    multistart: &MultistartOptions,
    options: &ConvergedOptions,
    warm: &WarmStart,
    statistics: bool,
) -> Result<ConvergedIdentification, IdentError> {
    let p = DVector::from_vec(vec![warm.jc.a_pa / 1e6, warm.jc.b_pa / 1e6, warm.jc.n, warm.jc.c, warm.jc.m]);
    let rate = RateTerm::Clamped;
    let mut cache = PanelCache::default();
    // The nominal panels carried to this zone's breakpoints (its clamp points move with the
    // drawn h, r and measurements).
    let start = map_edges(&warm.edges_rel, &warm.breakpoints_rel, &breakpoints(zone, constants, rate));
    let rule = build_rule(zone, &p, constants, rate, options, &start, &mut cache)?;
    let problem = rule.problem(zone, constants, rate, &mut cache)?;
    let id = identify_warm_with(&problem, bounds, multistart, Some(&p), statistics)?;
    // Later rules are refined from this sample's first rule (a superset of the nominal panels
    // where this zone needed more): when it still meets the tolerance at the fit, it is reused.
    let edges = rule.edges_rel;
    refit_until_converged(
        zone,
        bounds,
        constants,
        multistart,
        options,
        id,
        (&edges, Some(edges.clone())),
        &mut cache,
        statistics,
    )
}

/// The refit loop of [`identify_converged`]: rebuild the rule at the current fit, refit, until
/// the parameters move by less than the tolerance. A rebuilt rule with the same panels as the
/// previous one would give the same problem, hence (deterministic multistart) the same fit: the
/// loop then ends without the refit, with a change of 0. `first_edges` are the panels every rule
/// is refined from, `fitted_on` the panel set `id` was fitted on, when known (a warm start; then
/// the multistarts start at the previous solution).
#[allow(clippy::too_many_arguments)]
fn refit_until_converged(
    zone: &ZoneSolution,
    bounds: &JcBounds,
    constants: JcConstants,
    multistart: &MultistartOptions,
    options: &ConvergedOptions,
    mut id: JcIdentification,
    (first_edges, fitted_on): (&[f64], Option<Vec<f64>>),
    cache: &mut PanelCache,
    statistics: bool,
) -> Result<ConvergedIdentification, IdentError> {
    let rate = RateTerm::Clamped;
    let warm = fitted_on.is_some();
    let mut last_change = f64::INFINITY;
    let mut last_edges = fitted_on;
    for refit in 1..=options.max_refits {
        let p = vector(&id);
        let rule = build_rule(zone, &p, constants, rate, options, first_edges, cache)?;
        if last_edges.as_ref() == Some(&rule.edges_rel) {
            return Ok(ConvergedIdentification {
                identification: id,
                refits: refit - 1,
                panels: rule.panels.len(),
                nodes: 15 * rule.panels.len(),
                last_parameter_change: 0.0,
            });
        }
        let problem = rule.problem(zone, constants, rate, cache)?;
        let next = identify_warm_with(&problem, bounds, multistart, warm.then_some(&p), statistics)?;
        let q = vector(&next);
        last_change = p.iter().zip(q.iter()).map(|(a, b)| (a - b).abs() / a.abs().max(1e-12)).fold(0.0, f64::max);
        id = next;
        last_edges = Some(rule.edges_rel);
        if last_change < options.parameter_rel_tol {
            return Ok(ConvergedIdentification {
                identification: id,
                refits: refit,
                panels: rule.panels.len(),
                nodes: problem.points().len(),
                last_parameter_change: last_change,
            });
        }
    }
    Err(IdentError::NotConverged {
        what: "refits of the converged Eq 15 identification".into(),
        iterations: options.max_refits,
        detail: format!("largest relative parameter change {last_change:.3e} > {:.1e}", options.parameter_rel_tol),
    })
}

fn vector(id: &JcIdentification) -> DVector<f64> {
    DVector::from_vec(vec![id.jc.a_pa / 1e6, id.jc.b_pa / 1e6, id.jc.n, id.jc.c, id.jc.m])
}
