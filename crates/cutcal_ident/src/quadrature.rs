//! The Eq 15 objective as an integral over the zone: adaptive Gauss-Kronrod quadrature and the
//! `converged` identification built on it.
//!
//! The paper sums `(f - F)^2` at `N` points it does not state. As `N` grows that sum approximates
//! `N/h int (f - F)^2 dx`, so the natural, `N`-free objective is the zone mean square
//! `J = (1/h) int_{-h/2}^{h/2} (f(x) - F(x))^2 dx`. Here `J` is evaluated with an adaptive
//! 7/15-point Gauss-Kronrod rule (Kronrod 1965; nodes and weights as in QUADPACK, Piessens et al.
//! 1983, routine QK15), bisecting the panel with the largest `|K15 - G7|` estimate until the total
//! estimate is below the tolerance. The rule depends on the integrand, hence on the parameters, so
//! the identification alternates: fit on the current rule, rebuild the rule at the fit, refit, until
//! A, B, n, C and m move by less than the parameter tolerance. Both loops are capped and end in a
//! typed [`IdentError::NotConverged`].

use std::collections::hash_map::{Entry, HashMap};

use cutcal_model::dpzd::{ZonePoint, ZoneSolution};
use cutcal_model::RateTerm;
use nalgebra::DVector;
use serde::Serialize;

use crate::dpzd_fit::{
    identify_from_zone_with, identify_warm_with, JcBounds, JcConstants, JcIdentification, ZoneFitProblem,
};
use crate::error::IdentError;
use crate::multistart::MultistartOptions;

/// Kronrod abscissae on [-1, 1] (non-negative half, descending), QUADPACK QK15.
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights matching [`XGK`], QUADPACK QK15.
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
/// Gauss weights of the embedded 7-point rule, at `XGK[1], XGK[3], XGK[5], XGK[7]`, QUADPACK QK15.
const WG: [f64; 4] =
    [0.129_484_966_168_869_7, 0.279_705_391_489_276_7, 0.381_830_050_505_118_9, 0.417_959_183_673_469_4];

/// The 15 Kronrod nodes of `[a, b]` with their Kronrod and (embedded) Gauss weights.
fn panel_nodes(a: f64, b: f64) -> [(f64, f64, f64); 15] {
    let c = 0.5 * (a + b);
    let hw = 0.5 * (b - a);
    let mut out = [(0.0, 0.0, 0.0); 15];
    let mut k = 0;
    for (j, (&x, &w)) in XGK.iter().zip(&WGK).enumerate() {
        let wg = if j % 2 == 1 { WG[j / 2] } else { 0.0 };
        if x == 0.0 {
            out[k] = (c, w * hw, wg * hw);
            k += 1;
        } else {
            out[k] = (c - hw * x, w * hw, wg * hw);
            out[k + 1] = (c + hw * x, w * hw, wg * hw);
            k += 2;
        }
    }
    out
}

/// `(K15, |K15 - G7|)` of `f` over `[a, b]`.
///
/// **Source:** Gauss-Kronrod 7/15 rule (Kronrod 1965; QUADPACK QK15, Piessens et al. 1983).
pub fn gauss_kronrod_15(f: impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let (mut k, mut g) = (0.0, 0.0);
    for (x, wk, wg) in panel_nodes(a, b) {
        let v = f(x);
        k += wk * v;
        g += wg * v;
    }
    (k, (k - g).abs())
}

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

/// A quadrature rule over the zone: points with weights summing to 1 (the `1/h` of the mean).
#[derive(Debug, Clone)]
pub struct ZoneRule {
    /// Zone points at the nodes.
    pub points: Vec<ZonePoint>,
    /// Weights (sum 1).
    pub weights: Vec<f64>,
    /// Panels used.
    pub panels: usize,
    /// Final error estimate relative to `int (f - F)^2`.
    pub rel_error: f64,
    /// Panel edges as fractions `x/h` of the zone thickness, ascending from -1/2 to 1/2.
    pub edges_rel: Vec<f64>,
}

/// Builds the adaptive rule for the integrand `(f - F)^2` at parameters `p` (A, B in MPa).
///
/// Panels start as `[-h/2, 0]` and `[0, h/2]` (the stress of Eq 8 has a kink on AB).
///
/// Returns [`IdentError::NotConverged`] if the error estimate is still above the tolerance at
/// `max_panels`, or a model error if a zone point cannot be evaluated.
pub fn adaptive_rule(
    zone: &ZoneSolution,
    p: &DVector<f64>,
    constants: JcConstants,
    rate_term: RateTerm,
    options: &ConvergedOptions,
) -> Result<ZoneRule, IdentError> {
    adaptive_rule_from(zone, p, constants, rate_term, options, &[-0.5, 0.0, 0.5])
}

/// [`adaptive_rule`] starting from the panels with edges `edges_rel` (fractions `x/h`, ascending
/// from -1/2 to 1/2, containing 0 for the kink on AB) instead of the two halves: a warm start
/// from the rule of a nearby problem (e.g. the nominal fit of a Monte-Carlo sample). Panels are
/// only bisected, never merged, so the rule meets the same tolerance with at least those panels.
///
/// Returns an error as [`adaptive_rule`], or if the edges are not such a partition.
pub fn adaptive_rule_from(
    zone: &ZoneSolution,
    p: &DVector<f64>,
    constants: JcConstants,
    rate_term: RateTerm,
    options: &ConvergedOptions,
    edges_rel: &[f64],
) -> Result<ZoneRule, IdentError> {
    rule_with_cache(zone, p, constants, rate_term, options, edges_rel, &mut PanelCache::default())
}

/// The zone points of the panels evaluated so far, as unit-weight fit problems keyed by the
/// panel's ends (bitwise). The zone fields do not depend on the JC parameters, so a rule rebuilt
/// at new parameters on the same zone re-uses them and only re-evaluates the residuals.
#[derive(Debug, Default)]
struct PanelCache {
    panels: HashMap<(u64, u64), ZoneFitProblem>,
}

impl PanelCache {
    /// The 15-node problem of panel `[a, b]` of `zone`.
    fn panel(
        &mut self,
        zone: &ZoneSolution,
        a: f64,
        b: f64,
        constants: JcConstants,
        rate_term: RateTerm,
    ) -> Result<&ZoneFitProblem, IdentError> {
        match self.panels.entry((a.to_bits(), b.to_bits())) {
            Entry::Occupied(e) => Ok(e.into_mut()),
            Entry::Vacant(e) => {
                let pts = panel_nodes(a, b).iter().map(|n| zone.point(n.0)).collect::<Result<Vec<_>, _>>()?;
                Ok(e.insert(ZoneFitProblem::weighted(pts, &[1.0; 15], constants, rate_term)))
            }
        }
    }
}

/// [`adaptive_rule_from`] with the zone points of `cache`.
fn rule_with_cache(
    zone: &ZoneSolution,
    p: &DVector<f64>,
    constants: JcConstants,
    rate_term: RateTerm,
    options: &ConvergedOptions,
    edges_rel: &[f64],
    cache: &mut PanelCache,
) -> Result<ZoneRule, IdentError> {
    let ok = edges_rel.len() >= 3
        && edges_rel.first() == Some(&-0.5)
        && edges_rel.last() == Some(&0.5)
        && edges_rel.contains(&0.0)
        && edges_rel.windows(2).all(|w| w[0] < w[1])
        && edges_rel.len() <= options.max_panels + 1;
    if !ok {
        return Err(IdentError::InvalidOptions(format!(
            "panel edges must ascend from -1/2 through 0 to 1/2 with at most {} panels, got {edges_rel:?}",
            options.max_panels
        )));
    }
    let h = zone.config.zone_thickness_m;
    let mut eval_panel = |a: f64, b: f64| -> Result<(f64, f64, f64), IdentError> {
        let nodes = panel_nodes(a, b);
        let prob = cache.panel(zone, a, b, constants, rate_term)?;
        let res = prob.raw_residuals(p);
        let (mut k, mut g, mut target) = (0.0, 0.0, 0.0);
        for ((node, r), pt) in nodes.iter().zip(&res).zip(prob.points()) {
            k += node.1 * r * r;
            g += node.2 * r * r;
            target += node.1 * (pt.effective_stress_pa / 1e6).powi(2);
        }
        Ok((k, (k - g).abs(), target))
    };
    let mut panels: Vec<(f64, f64, f64, f64, f64)> = Vec::new();
    for w in edges_rel.windows(2) {
        let (a, b) = (w[0] * h, w[1] * h);
        let (k, e, t) = eval_panel(a, b)?;
        panels.push((a, b, k, e, t));
    }
    let mut converged = false;
    let mut rel_error = f64::INFINITY;
    while panels.len() <= options.max_panels {
        let total: f64 = panels.iter().map(|q| q.2).sum();
        let err: f64 = panels.iter().map(|q| q.3).sum();
        let target: f64 = panels.iter().map(|q| q.4).sum();
        let scale = total.max(1e-6 * target).max(f64::MIN_POSITIVE);
        rel_error = err / scale;
        if rel_error <= options.quadrature_rel_tol {
            converged = true;
            break;
        }
        let (idx, _) = panels
            .iter()
            .enumerate()
            .fold((0, f64::NEG_INFINITY), |acc, (i, q)| if q.3 > acc.1 { (i, q.3) } else { acc });
        let (a, b, ..) = panels.swap_remove(idx);
        let mid = 0.5 * (a + b);
        for (lo, hi) in [(a, mid), (mid, b)] {
            let (k, e, t) = eval_panel(lo, hi)?;
            panels.push((lo, hi, k, e, t));
        }
    }
    if !converged {
        return Err(IdentError::NotConverged {
            what: "adaptive Gauss-Kronrod rule of the Eq 15 zone integral".into(),
            iterations: options.max_panels,
            detail: format!("relative error estimate {rel_error:.3e} > {:.1e}", options.quadrature_rel_tol),
        });
    }
    panels.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut edges_rel: Vec<f64> = panels.iter().map(|q| q.0 / h).collect();
    edges_rel.push(0.5);
    edges_rel[0] = -0.5;
    let mut points = Vec::with_capacity(15 * panels.len());
    let mut weights = Vec::with_capacity(15 * panels.len());
    for (a, b, ..) in &panels {
        points.extend_from_slice(cache.panel(zone, *a, *b, constants, rate_term)?.points());
        weights.extend(panel_nodes(*a, *b).iter().map(|n| n.1 / h));
    }
    Ok(ZoneRule { points, weights, panels: panels.len(), rel_error, edges_rel })
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
        (&[-0.5, 0.0, 0.5], None),
        &mut PanelCache::default(),
        true,
    )
}

/// A warm start for [`identify_converged_warm`]: a nearby converged identification (the nominal
/// fit of a Monte-Carlo propagation) and its rule's panel edges.
#[derive(Debug, Clone, PartialEq)]
pub struct WarmStart {
    /// The nearby solution (its n, C and m start the first local solve).
    pub jc: cutcal_model::JcParams,
    /// The panel edges of its final rule, fractions `x/h` ([`ZoneRule::edges_rel`]).
    pub edges_rel: Vec<f64>,
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
        Ok(Self { jc: identification.jc, edges_rel: rule.edges_rel })
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
    let mut cache = PanelCache::default();
    let rule = rule_with_cache(zone, &p, constants, RateTerm::Clamped, options, &warm.edges_rel, &mut cache)?;
    let problem = ZoneFitProblem::weighted(rule.points, &rule.weights, constants, RateTerm::Clamped);
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
        let rule = rule_with_cache(zone, &p, constants, rate, options, first_edges, cache)?;
        if last_edges.as_ref() == Some(&rule.edges_rel) {
            return Ok(ConvergedIdentification {
                identification: id,
                refits: refit - 1,
                panels: rule.panels,
                nodes: rule.points.len(),
                last_parameter_change: 0.0,
            });
        }
        let problem = ZoneFitProblem::weighted(rule.points, &rule.weights, constants, rate);
        let next = identify_warm_with(&problem, bounds, multistart, warm.then_some(&p), statistics)?;
        let q = vector(&next);
        last_change = p.iter().zip(q.iter()).map(|(a, b)| (a - b).abs() / a.abs().max(1e-12)).fold(0.0, f64::max);
        id = next;
        last_edges = Some(rule.edges_rel);
        if last_change < options.parameter_rel_tol {
            return Ok(ConvergedIdentification {
                identification: id,
                refits: refit,
                panels: rule.panels,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kronrod_rule_is_exact_to_degree_22_and_gauss_to_13() {
        // Independent check: int_{-1}^{1} x^k dx = 2/(k+1) for even k, 0 for odd k.
        for k in 0..=23 {
            let exact = if k % 2 == 0 { 2.0 / (k as f64 + 1.0) } else { 0.0 };
            let nodes = panel_nodes(-1.0, 1.0);
            let kr: f64 = nodes.iter().map(|n| n.1 * n.0.powi(k)).sum();
            let ga: f64 = nodes.iter().map(|n| n.2 * n.0.powi(k)).sum();
            if k <= 22 {
                assert!((kr - exact).abs() < 1e-14, "K15 degree {k}: {kr} vs {exact}");
            }
            if k <= 13 {
                assert!((ga - exact).abs() < 1e-14, "G7 degree {k}: {ga} vs {exact}");
            }
        }
        // G7 is not exact at degree 14 (it is a 7-point Gauss rule): the error estimate is live.
        let nodes = panel_nodes(-1.0, 1.0);
        let ga: f64 = nodes.iter().map(|n| n.2 * n.0.powi(14)).sum();
        assert!((ga - 2.0 / 15.0).abs() > 1e-6);
    }

    #[test]
    fn gauss_kronrod_integrates_a_smooth_function() {
        // int_0^1 exp(x) dx = e - 1.
        let (k, e) = gauss_kronrod_15(f64::exp, 0.0, 1.0);
        assert!((k - (std::f64::consts::E - 1.0)).abs() < 1e-15);
        assert!(e < 1e-12);
    }
}
