//! The search over delta for the least chip-formation cutting force (Lalwani et al. 2009, Sec. 2:
//! delta is chosen to minimise Fc): a scan of the delta range, the minimum between the neighbours of
//! the best scan point from the stationarity condition of k_chip (Brent's minimiser as the
//! fallback), the existence search at a bound, and the flatness probes.

use crate::error::ModelError;

use super::roots::brent_min;
use super::solve::{DeltaPoint, DeltaSearch, Solver, Target};

impl Solver<'_> {
    /// delta minimising the chip-formation cutting force: a geometric scan of the delta range, the
    /// minimum between the neighbours of the best scan point, and the flatness probes at
    /// delta*(1 -/+ band).
    ///
    /// The minimum: Fc depends on phi only (through the primary zone), so `dFc/d delta =
    /// dFc/dphi dphi/d delta`, and with `tau_int/k_AB` independent of delta, `dphi/d delta = 0` exactly
    /// where `d k_chip / d delta = 0` at the solution. The minimum is therefore solved as one
    /// equation in phi, `tau_int = m_f k_chip` at the stationary delta of k_chip (the converged
    /// minimum, not one to a delta tolerance); it is accepted when it lies strictly between the
    /// neighbours and its Fc does not exceed the scan's best. Otherwise (e.g. dFc/dphi = 0) Brent's
    /// minimiser in ln(delta) is used as before (Brent 1973, Ch. 5).
    pub fn search_delta(&mut self) -> Result<DeltaSearch, ModelError> {
        let o = self.ctx.options;
        let [dlo, dhi] = o.delta_range;
        // Discrete choice (Lalwani et al. 2009): an arithmetic grid, no refinement; else geometric.
        let deltas: Vec<f64> = match o.delta_grid_step {
            Some(step) => {
                let k = ((dhi - dlo) / step + 1e-9).floor() as usize;
                (0..=k).map(|i| dlo + step * i as f64).collect()
            }
            None => {
                let n = o.delta_scan_points;
                (0..n).map(|i| dlo * (dhi / dlo).powf(i as f64 / (n - 1) as f64)).collect()
            }
        };
        let n = deltas.len();
        let mut grid: Vec<Option<DeltaPoint>> = Vec::with_capacity(n);
        let mut first_err = None;
        // Scan points only order the scan and bracket the minimum: certified brackets suffice
        // (continuous delta only; the lalwani preset returns a scan point as it is).
        self.scanning = o.delta_grid_step.is_none();
        for &delta in &deltas {
            match self.solve_at(delta) {
                Ok(state) => grid.push(Some(DeltaPoint { delta, state })),
                Err(e) => {
                    first_err.get_or_insert(e);
                    grid.push(None);
                }
            }
        }
        self.scanning = false;
        let ok = grid.iter().flatten().count();
        let fc = |p: &DeltaPoint| p.state.primary.cutting_force_n_per_m;
        let Some((ib, best)) =
            grid.iter().enumerate().filter_map(|(i, p)| p.map(|p| (i, p))).min_by(|a, b| fc(&a.1).total_cmp(&fc(&b.1)))
        else {
            // No scan point has a solution: the largest shear residual over every phi and delta
            // decides whether one exists between the scan points (then it is solved) or not at all.
            return match self.rescue()? {
                Some(best) => Ok(DeltaSearch {
                    best,
                    at_bound: true,
                    fc_change_over_band: None,
                    poorly_determined: false,
                    converged_share: 0.0,
                }),
                None => Err(ModelError::NoSolution {
                    what: "extended Oxley model: no (phi, C0) solution at any delta".into(),
                    low: dlo,
                    high: dhi,
                    detail: self.no_solution_reason(first_err),
                }),
            };
        };
        let left = if ib > 0 { grid[ib - 1] } else { None };
        let right = grid.get(ib + 1).copied().flatten();
        let mut at_bound = left.is_none() || right.is_none();
        let mut best = best;
        let mut refined = false;
        if at_bound && o.delta_grid_step.is_none() {
            // The minimum sits next to a delta without solution or on a bound of the range, where
            // which phi root the scan follows depends on its path (several roots at low V t1).
            // The feasible phi form an interval whose ends are the extremes of phi over every
            // solution (`Solver::rescue`); Fc depends on phi only, so the least Fc over every delta
            // is at one of them: take it when it is lower.
            if let Ok(Some(p)) = self.rescue() {
                if fc(&p) < fc(&best) {
                    best = p;
                    refined = true;
                    // Every phi and delta of the ranges was searched: only a range bound is a bound.
                    at_bound = p.delta <= dlo * (1.0 + 1e-9) || p.delta >= dhi * (1.0 - 1e-9);
                }
            }
        }
        if let (Some(l), Some(r), None, false) = (left, right, o.delta_grid_step, refined) {
            let mut hint = best.delta;
            let phi0 = best.state.primary.phi_rad;
            self.keep(best.state.primary);
            if let Some(s) = self.secant(phi0, Target::Stationary { lo: l.delta, hi: r.delta }, &mut hint, true) {
                let p = DeltaPoint { delta: s.interface.delta, state: s };
                // (1e-5: the scan point's Fc is known to about 1e-6, see solve.rs SCAN_RESIDUAL.)
                if p.delta > l.delta && p.delta < r.delta && fc(&p) <= fc(&best) * (1.0 + 1e-5) {
                    best = p;
                    refined = true;
                }
            }
        }
        if let (Some(l), Some(r), None, false) = (left, right, o.delta_grid_step, refined) {
            // Refine in ln(delta); infeasible points stop the refinement (the scan best is kept).
            let mut found = best;
            let res = {
                let found = &mut found;
                let f = |x: f64| -> Result<f64, ModelError> {
                    let delta = x.exp();
                    let state = self.solve_at(delta)?;
                    let p = DeltaPoint { delta, state };
                    if fc(&p) < fc(found) {
                        *found = p;
                    }
                    Ok(fc(&p))
                };
                brent_min(f, l.delta.ln(), r.delta.ln(), o.delta_tolerance, o.max_bracket_iterations, "Oxley delta")
            };
            if res.is_ok_and(|m| m.x.is_finite() && m.f.is_finite()) || fc(&found) < fc(&best) {
                best = found;
            }
        }
        // A scan point returned as the answer is solved to the residual tolerance.
        if best.state.residual_norm() >= o.residual_tolerance {
            // From the scan point itself (within about 1e-6 rad of the root), not an extrapolation
            // of the points solved after it.
            self.n_history = 0;
            self.keep(best.state.primary);
            self.last = Some(best.state.primary.phi_rad);
            best = DeltaPoint { delta: best.delta, state: self.solve_at(best.delta)? };
        }
        // Flatness: Fc at delta*(1 -/+ band) against Fc(delta*).
        let mut change: Option<f64> = None;
        // The probes start at the minimum (phi is stationary in delta there).
        self.n_history = 0;
        self.remember(best.delta, best.state.primary.phi_rad);
        self.keep(best.state.primary);
        for factor in [1.0 - o.delta_flat_band, 1.0 + o.delta_flat_band] {
            let d = best.delta * factor;
            if d < dlo || d > dhi {
                continue;
            }
            self.last = Some(best.state.primary.phi_rad);
            if let Ok(s) = self.solve_at(d) {
                let rel = (s.primary.cutting_force_n_per_m / fc(&best) - 1.0).abs();
                change = Some(change.map_or(rel, |c| c.max(rel)));
            }
        }
        let poorly_determined = change.is_some_and(|c| c < o.delta_flat_tolerance);
        Ok(DeltaSearch {
            best,
            at_bound,
            fc_change_over_band: change,
            poorly_determined,
            converged_share: ok as f64 / n as f64,
        })
    }
}
