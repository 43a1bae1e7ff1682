//! The adaptive quadrature rule of the Eq 15 zone integral ([`crate::quadrature`]): 7/15-point
//! Gauss-Kronrod panels (Kronrod 1965; nodes and weights as in QUADPACK, Piessens et al. 1983,
//! routine QK15), started at the integrand's breakpoints and bisected where `|K15 - G7|` is
//! largest until the total estimate is below the tolerance.
//!
//! The integrand `(f - F)^2` is smooth across the zone except at points known before any fit:
//! AB (`x = 0`), where the Eq 8 stress has a kink, and, for the solvers' clamped law, the two
//! points where the strain rate of Eq 2 crosses `eps0` and the rate term `1 + C ln(epsdot/eps0)`
//! turns to 1 ([`breakpoints`]). A panel edge at each keeps every panel's integrand smooth, so
//! the rule converges at its design rate instead of bisecting toward a kink (C38 test 3 at
//! h = 15 um and tolerance 1e-6: 20 panels, 8 of them closing in on the two clamp points, before
//! the clamp points were edges; `docs/identification-speed.md`).

use std::collections::hash_map::{Entry, HashMap};

use cutcal_model::dpzd::{ZonePoint, ZoneSolution};
use cutcal_model::RateTerm;
use nalgebra::DVector;

use crate::dpzd_fit::{JcConstants, ZoneFitProblem};
use crate::error::IdentError;
use crate::gauss_kronrod::panel_nodes;
use crate::quadrature::ConvergedOptions;

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

/// The breakpoints of the Eq 15 integrand as fractions `x/h`, ascending: the zone edges, AB
/// (`x = 0`) and, for [`RateTerm::Clamped`], the two points where the strain rate
/// `gammadot_AB u^r / sqrt(3)` (paper Eqs 2-3, `u = 1 - 2|x|/h`) equals `eps0`:
/// `u_c = (sqrt(3) eps0 / gammadot_AB)^(1/r)`, `x/h = -/+ (1 - u_c)/2`. There is no clamp point
/// when the whole zone is above `eps0` to rounding, or at or below it (`u_c >= 1`).
///
/// **Source:** paper Eqs 2, 3 and 16 (the clamp of Abaqus/LS-DYNA at `eps0`).
#[must_use]
pub fn breakpoints(zone: &ZoneSolution, constants: JcConstants, rate_term: RateTerm) -> Vec<f64> {
    if rate_term == RateTerm::Clamped {
        let u_c = (3f64.sqrt() * constants.eps0_per_s / zone.gamma_dot_ab_per_s).powf(1.0 / zone.config.r);
        let x = 0.5 * (1.0 - u_c);
        if x.is_finite() && x > 1e-9 && x < 0.5 - 1e-9 {
            return vec![-0.5, -x, 0.0, x, 0.5];
        }
    }
    vec![-0.5, 0.0, 0.5]
}

/// Panel edges `edges` (fractions `x/h`) of a nearby zone whose [`breakpoints`] are `from`,
/// carried to a zone whose breakpoints are `to`: every edge is mapped linearly between the two
/// breakpoints that enclose it, so breakpoints go to breakpoints and the panels keep their share of
/// each smooth piece. When the breakpoint lists differ in length (a clamp point in one zone only),
/// `to` alone is returned.
#[must_use]
pub fn map_edges(edges: &[f64], from: &[f64], to: &[f64]) -> Vec<f64> {
    if from.len() != to.len() || from.len() < 2 {
        return to.to_vec();
    }
    // A breakpoint is carried exactly (compared bitwise), not through the linear map.
    #[allow(clippy::float_cmp)]
    let mut out: Vec<f64> = edges
        .iter()
        .map(|&e| {
            let i = from.partition_point(|&b| b <= e).clamp(1, from.len() - 1);
            let (f0, f1, t0, t1) = (from[i - 1], from[i], to[i - 1], to[i]);
            if e == f0 {
                t0
            } else if e == f1 {
                t1
            } else {
                t0 + (e - f0) / (f1 - f0) * (t1 - t0)
            }
        })
        .collect();
    out.dedup();
    out
}

/// Builds the adaptive rule for the integrand `(f - F)^2` at parameters `p` (A, B in MPa).
///
/// Panels start at the integrand's [`breakpoints`].
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
/// from -1/2 to 1/2, containing 0) and the integrand's [`breakpoints`], instead of the
/// breakpoints alone: a warm start from the rule of a nearby problem (e.g. the nominal fit of a
/// Monte-Carlo sample, [`map_edges`]). Panels are only bisected, never merged, so the rule meets
/// the same tolerance with at least those panels.
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
    let mut cache = PanelCache::default();
    let built = build_rule(zone, p, constants, rate_term, options, edges_rel, &mut cache)?;
    let problem = built.problem(zone, constants, rate_term, &mut cache)?;
    let weights = built.weights(zone.config.zone_thickness_m).concat();
    Ok(ZoneRule {
        points: problem.points().to_vec(),
        weights,
        panels: built.panels.len(),
        rel_error: built.rel_error,
        edges_rel: built.edges_rel,
    })
}

/// The zone points of the panels evaluated so far, as unit-weight fit problems keyed by the
/// panel's ends (bitwise). The zone fields do not depend on the JC parameters, so a rule rebuilt
/// at new parameters on the same zone re-uses them and only re-evaluates the residuals.
#[derive(Debug, Default)]
pub(crate) struct PanelCache {
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

/// An adaptive rule's panels (ascending, m) before its fit problem is assembled.
#[derive(Debug, Clone)]
pub(crate) struct BuiltRule {
    /// Panels `[a, b]`, m, ascending.
    pub(crate) panels: Vec<(f64, f64)>,
    /// Panel edges as fractions `x/h`.
    pub(crate) edges_rel: Vec<f64>,
    /// Final error estimate relative to `int (f - F)^2`.
    pub(crate) rel_error: f64,
}

impl BuiltRule {
    /// The Kronrod weights of every panel's nodes divided by `h` (the rule's weights, sum 1).
    fn weights(&self, h: f64) -> Vec<[f64; 15]> {
        self.panels.iter().map(|&(a, b)| panel_nodes(a, b).map(|n| n.1 / h)).collect()
    }

    /// The weighted Eq 15 problem on the rule's nodes (weights `w_K15 / h`, summing to 1), from the
    /// cached panels.
    pub(crate) fn problem(
        &self,
        zone: &ZoneSolution,
        constants: JcConstants,
        rate_term: RateTerm,
        cache: &mut PanelCache,
    ) -> Result<ZoneFitProblem, IdentError> {
        for &(a, b) in &self.panels {
            cache.panel(zone, a, b, constants, rate_term)?;
        }
        let weights = self.weights(zone.config.zone_thickness_m);
        let parts = self.panels.iter().zip(&weights).map(|(&(a, b), w)| {
            let part = &cache.panels[&(a.to_bits(), b.to_bits())];
            (part, &w[..])
        });
        Ok(ZoneFitProblem::from_weighted_parts(parts, constants, rate_term))
    }
}

/// The edges `edges_rel` with the zone's `breaks` merged in (a break within `1e-12` of an edge is
/// that edge).
fn merge_breakpoints(edges_rel: &[f64], breaks: &[f64]) -> Vec<f64> {
    let mut out = edges_rel.to_vec();
    for &b in breaks {
        if out.iter().all(|e| (e - b).abs() > 1e-12) {
            let i = out.partition_point(|&e| e < b);
            out.insert(i, b);
        }
    }
    out
}

/// The adaptive rule from `edges_rel` and the zone's breakpoints, with the zone points of `cache`.
pub(crate) fn build_rule(
    zone: &ZoneSolution,
    p: &DVector<f64>,
    constants: JcConstants,
    rate_term: RateTerm,
    options: &ConvergedOptions,
    edges_rel: &[f64],
    cache: &mut PanelCache,
) -> Result<BuiltRule, IdentError> {
    let ok = edges_rel.len() >= 3
        && edges_rel.first() == Some(&-0.5)
        && edges_rel.last() == Some(&0.5)
        && edges_rel.contains(&0.0)
        && edges_rel.windows(2).all(|w| w[0] < w[1]);
    let edges_rel = merge_breakpoints(edges_rel, &breakpoints(zone, constants, rate_term));
    if !ok || edges_rel.len() > options.max_panels + 1 {
        return Err(IdentError::InvalidOptions(format!(
            "panel edges must ascend from -1/2 through 0 to 1/2 with at most {} panels (breakpoints included), got {edges_rel:?}",
            options.max_panels
        )));
    }
    let h = zone.config.zone_thickness_m;
    let mut eval_panel = |a: f64, b: f64| -> Result<(f64, f64, f64), IdentError> {
        let nodes = panel_nodes(a, b);
        let prob = cache.panel(zone, a, b, constants, rate_term)?;
        let (mut k, mut g, mut target) = (0.0, 0.0, 0.0);
        for ((node, r), y) in nodes.iter().zip(prob.raw_residuals_iter(p)).zip(prob.targets_mpa()) {
            k += node.1 * r * r;
            g += node.2 * r * r;
            target += node.1 * y * y;
        }
        Ok((k, (k - g).abs(), target))
    };
    let mut panels: Vec<(f64, f64, f64, f64, f64)> = Vec::with_capacity(edges_rel.len() + 8);
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
    Ok(BuiltRule { panels: panels.iter().map(|q| (q.0, q.1)).collect(), edges_rel, rel_error })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c38_test3_zone(h_m: f64) -> ZoneSolution {
        use cutcal_model::dpzd::{self, DpzdConfig, DpzdVariant, ShearPlaneState};
        // Paper Tables 2 and 6: 240 m/min, 0.075 mm, 1.95 mm, 0 deg; 224 N/mm, 186 N/mm, 0.157 mm.
        let t = cutcal_model::reference::c38_test3();
        let cfg = DpzdConfig::new(h_m, 4.0, DpzdVariant::Enhanced { tolerance_c: 1e-6, max_iterations: 50 }).unwrap();
        dpzd::solve(&cutcal_model::reference::c38_table3(), &ShearPlaneState::from_test(&t).unwrap(), &cfg).unwrap()
    }

    const CONST: JcConstants = JcConstants { eps0_per_s: 1.0, tm_c: 1460.0, tr_c: 20.0 };

    #[test]
    fn the_clamp_points_are_where_the_strain_rate_is_eps0() {
        let z = c38_test3_zone(1.5e-5);
        let b = breakpoints(&z, CONST, RateTerm::Clamped);
        assert_eq!(b.len(), 5, "{b:?}");
        assert_eq!((b[0], b[2], b[4]), (-0.5, 0.0, 0.5));
        assert_eq!(b[1], -b[3]);
        // Independent check: the zone's own strain rate (Eq 2 through ZoneSolution::point) at the
        // clamp points is eps0, and it is above eps0 just inside them and below just outside.
        let h = z.config.zone_thickness_m;
        for x in [b[1], b[3]] {
            let rate = |x_rel: f64| z.point(x_rel * h).unwrap().strain_rate_per_s;
            assert!((rate(x) - 1.0).abs() < 1e-9, "{}", rate(x));
            let inward = -x.signum() * 1e-6;
            assert!(rate(x + inward) > 1.0 && rate(x - inward) < 1.0);
        }
        // The paper's unclamped law has no clamp point.
        assert_eq!(breakpoints(&z, CONST, RateTerm::Unclamped), vec![-0.5, 0.0, 0.5]);
        // A reference rate above the whole zone's rate: every point is clamped, no clamp point.
        let slow = JcConstants { eps0_per_s: 1e12, ..CONST };
        assert_eq!(breakpoints(&z, slow, RateTerm::Clamped), vec![-0.5, 0.0, 0.5]);
    }

    proptest::proptest! {
        // Invariants of carrying a partition: the result ascends strictly from -1/2 to 1/2, every
        // breakpoint of `to` is in it, and each piece keeps its number of panels.
        #[test]
        fn carried_edges_stay_a_partition_with_the_new_breakpoints(
            k_from in 0.05..0.49f64, k_to in 0.05..0.49f64,
            fractions in proptest::collection::vec(0.01..0.99f64, 0..12),
        ) {
            let from = [-0.5, -k_from, 0.0, k_from, 0.5];
            let to = [-0.5, -k_to, 0.0, k_to, 0.5];
            // Edges: the breakpoints plus points inside the pieces of `from`.
            let mut edges = from.to_vec();
            for (i, f) in fractions.iter().enumerate() {
                let piece = i % 4;
                edges.push(from[piece] + f * (from[piece + 1] - from[piece]));
            }
            edges.sort_by(f64::total_cmp);
            edges.dedup();
            let out = map_edges(&edges, &from, &to);
            proptest::prop_assert_eq!(out.len(), edges.len());
            proptest::prop_assert!(out.windows(2).all(|w| w[0] < w[1]), "{:?}", out);
            for b in to {
                proptest::prop_assert!(out.contains(&b), "{} not in {:?}", b, out);
            }
            for piece in 0..4 {
                let count = |e: &[f64], lo: f64, hi: f64| e.iter().filter(|x| **x > lo && **x < hi).count();
                proptest::prop_assert_eq!(
                    count(&edges, from[piece], from[piece + 1]),
                    count(&out, to[piece], to[piece + 1])
                );
            }
        }
    }

    #[test]
    fn edges_are_carried_piecewise_linearly_between_breakpoints() {
        // By hand: [-0.5, -0.4] -> [-0.5, -0.45] halves offsets from -0.5 ... and [-0.4, 0] ->
        // [-0.45, 0] scales by 0.45/0.4 = 1.125 about 0.
        let from = [-0.5, -0.4, 0.0, 0.4, 0.5];
        let to = [-0.5, -0.45, 0.0, 0.45, 0.5];
        let edges = [-0.5, -0.45, -0.4, -0.2, 0.0, 0.2, 0.4, 0.45, 0.5];
        let want = [-0.5, -0.475, -0.45, -0.225, 0.0, 0.225, 0.45, 0.475, 0.5];
        let got = map_edges(&edges, &from, &to);
        assert_eq!(got.len(), want.len());
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-15, "{got:?}");
        }
        // A clamp point in one zone only: the other zone's breakpoints alone.
        assert_eq!(map_edges(&edges, &from, &[-0.5, 0.0, 0.5]), vec![-0.5, 0.0, 0.5]);
    }

    #[test]
    fn the_rule_integrates_the_clamped_objective_to_its_tolerance() {
        // Independent check of the whole rule: composite Simpson with 400 001 points on each
        // smooth piece (between the breakpoints) of (1/h) int (f - F)^2 dx, the JC law evaluated by
        // JcParams::flow_stress (not the fit problem's cached form).
        let z = c38_test3_zone(1.5e-5);
        let jc = cutcal_model::JcParams {
            a_pa: 536.6e6,
            b_pa: 103.6e6,
            n: 0.25,
            c: 0.0719,
            m: 1.0,
            eps0_per_s: 1.0,
            tm_c: 1460.0,
            tr_c: 20.0,
        };
        let p = DVector::from_vec(vec![536.6, 103.6, 0.25, 0.0719, 1.0]);
        let options = ConvergedOptions::default();
        let rule = adaptive_rule(&z, &p, CONST, RateTerm::Clamped, &options).unwrap();
        let quad: f64 = rule
            .points
            .iter()
            .zip(&rule.weights)
            .map(|(pt, w)| {
                let f = jc.flow_stress(pt.strain, pt.strain_rate_per_s, pt.temperature_c) / 1e6;
                w * (f - pt.effective_stress_pa / 1e6).powi(2)
            })
            .sum();
        let h = z.config.zone_thickness_m;
        let integrand = |x_rel: f64| {
            let pt = z.point(x_rel * h).unwrap();
            let f = jc.flow_stress(pt.strain, pt.strain_rate_per_s, pt.temperature_c) / 1e6;
            (f - pt.effective_stress_pa / 1e6).powi(2)
        };
        let mut simpson = 0.0;
        for w in breakpoints(&z, CONST, RateTerm::Clamped).windows(2) {
            let n = 400_000;
            let step = (w[1] - w[0]) / f64::from(n);
            let mut s = integrand(w[0]) + integrand(w[1]);
            for k in 1..n {
                s += if k % 2 == 1 { 4.0 } else { 2.0 } * integrand(w[0] + f64::from(k) * step);
            }
            simpson += s * step / 3.0;
        }
        let rel = (quad - simpson).abs() / simpson;
        assert!(rel < 1e-6, "rule {quad} vs Simpson {simpson} (rel {rel:.1e}, {} panels)", rule.panels);
        assert!(rule.rel_error <= options.quadrature_rel_tol);
    }
}
