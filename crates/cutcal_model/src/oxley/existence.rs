//! Whether the extended Oxley equations have a solution anywhere in the search ranges, when the
//! delta scan found none, and the solution if they do.
//!
//! At a fixed phi (C0 from the sigma_N balance) `tau_int/k_AB` does not depend on delta, so the
//! largest shear residual `(tau_int - m_f k_chip)/k_AB` over delta is at the delta where k_chip is
//! least (its stationary point, or a bound of the delta range). Maximising that over phi tells
//! whether any (phi, delta) satisfies `tau_int = m_f k_chip` (Oxley 1989, Sec. 4.2; Lalwani et al.
//! 2009, Sec. 2). If the maximum is negative there is no solution and the typed `NoSolution` says
//! by how much the interface condition is missed. If it is not, solutions exist in a window of
//! delta the scan stepped over: the feasible phi form an interval whose ends are the roots of that
//! maximum in phi, and since Fc depends on phi only, the Fc minimum over delta is at one of them.

use crate::error::ModelError;

use super::equations::{PrimaryZone, State};
use super::roots::{brent_min, brent_root};
use super::solve::{DeltaPoint, Solver};

impl Solver<'_> {
    /// The state at the delta of least k_chip in the delta range, for a primary zone.
    fn least_k_chip_state(&self, p: PrimaryZone) -> Result<State, ModelError> {
        let [lo, hi] = self.ctx.options.delta_range;
        let (g_lo, g_hi) = (self.ctx.chip_log_slope(&p, lo), self.ctx.chip_log_slope(&p, hi));
        let delta = if !(g_lo < 0.0) {
            lo
        } else if !(g_hi > 0.0) {
            hi
        } else {
            self.stationary_delta(&p, (lo * hi).sqrt(), lo, hi)?
        };
        self.ctx.state_from(p, delta)
    }

    /// The largest shear residual over delta at phi.
    fn envelope(&mut self, phi: f64) -> Result<State, ModelError> {
        let p = self.primary(phi)?;
        self.least_k_chip_state(p)
    }

    /// Looks for the largest shear residual over every phi and delta (a grid of 4x the phi scan
    /// points, refined by Brent's minimiser between the neighbours of the best), records it in
    /// `best_residual`, and returns the solution of least Fc when the maximum is not negative.
    pub(super) fn rescue(&mut self) -> Result<Option<DeltaPoint>, ModelError> {
        let o = self.ctx.options;
        let [lo, hi] = o.phi_range_rad;
        let n = 4 * o.phi_scan_points;
        let phis: Vec<f64> = (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect();
        let mut r: Vec<Option<f64>> = Vec::with_capacity(n);
        for &phi in &phis {
            match self.envelope(phi) {
                Ok(s) => r.push(Some(s.residual_shear)),
                Err(e) => {
                    // Keep the count and one reason, preferring a C0 outside its range (typed, and
                    // worded only if the model has no solution: most probes fail by design).
                    let c0 = |e: &ModelError| matches!(e, ModelError::NoAdmissibleC0 { .. });
                    self.inadmissible = Some(match self.inadmissible.take() {
                        Some((count, kept)) if !c0(&e) || c0(&kept) => (count + 1, kept),
                        Some((count, _)) => (count + 1, e),
                        None => (1, e),
                    });
                    r.push(None);
                }
            }
        }
        let Some((imax, rmax)) =
            r.iter().enumerate().filter_map(|(i, v)| v.map(|v| (i, v))).max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            return Ok(None);
        };
        // Refine the maximum between the neighbours (where admissible).
        let a = if imax > 0 && r[imax - 1].is_some() { phis[imax - 1] } else { phis[imax] };
        let b = if imax + 1 < n && r[imax + 1].is_some() { phis[imax + 1] } else { phis[imax] };
        let mut top = (rmax, phis[imax]);
        if b > a {
            let f = |phi: f64| -> Result<f64, ModelError> { Ok(-self.envelope(phi)?.residual_shear) };
            if let Ok(m) = brent_min(f, a, b, 1e-6, o.max_bracket_iterations, "largest Oxley shear residual") {
                if -m.f > top.0 {
                    top = (-m.f, m.x);
                }
            }
        }
        let at_top = self.envelope(top.1)?;
        self.best_residual = Some((top.0, top.1, at_top.interface.delta));
        if top.0 < 0.0 {
            return Ok(None);
        }
        // The ends of the feasible phi interval: the first negative grid point on each side.
        let right = (imax + 1..n).find(|&j| r[j].is_some_and(|v| v < 0.0));
        let left = (0..imax).rev().find(|&j| r[j].is_some_and(|v| v < 0.0));
        let mut best: Option<DeltaPoint> = None;
        for (x0, x1) in [left.map(|j| (phis[j], top.1)), right.map(|j| (top.1, phis[j]))].into_iter().flatten() {
            let mut f = |phi: f64| -> Result<f64, ModelError> { Ok(self.envelope(phi)?.residual_shear) };
            let (f0, f1) = (f(x0)?, f(x1)?);
            let Ok(phi) = brent_root(f, x0, x1, f0, f1, 1e-13, o.max_bracket_iterations, "Oxley shear angle") else {
                continue;
            };
            let s = self.envelope(phi)?;
            let fc = s.primary.cutting_force_n_per_m;
            if s.residual_norm() < o.residual_tolerance
                && best.is_none_or(|b| fc < b.state.primary.cutting_force_n_per_m)
            {
                best = Some(DeltaPoint { delta: s.interface.delta, state: s });
            }
        }
        Ok(best)
    }

    /// The physical reason why no (phi, C0, delta) in the ranges solves the model, from the largest
    /// shear residual found by [`Solver::rescue`] and the thermal number `R_T = rho Cp V t1 / K` at T_w.
    pub(super) fn no_solution_reason(&self, first_err: Option<ModelError>) -> String {
        let c = self.ctx.conditions;
        let (rho_cp, k) = self.ctx.thermal(c.work_temperature_c);
        let rt = rho_cp * c.speed_m_per_s * c.uncut_chip_thickness_m / k;
        let first = first_err.map_or_else(String::new, |e| e.to_string());
        let inadmissible = match &self.inadmissible {
            Some((count, e)) => format!(
                " At {count} of the {} phi grid points no state is admissible, e.g. {e}.",
                4 * self.ctx.options.phi_scan_points
            ),
            None => String::new(),
        };
        match self.best_residual {
            Some((r, phi, delta)) if r < 0.0 => {
                let [_, d_hi] = self.ctx.options.delta_range;
                let thick = if delta >= d_hi * (1.0 - 1e-9) {
                    format!(
                        " k_chip is least at the top of the delta range: only a secondary zone thicker than \
                         {d_hi} of the chip, outside the thin-zone assumption of the model, could soften it enough."
                    )
                } else {
                    String::new()
                };
                format!(
                    "tau_int < k_chip everywhere: the largest (tau_int - k_chip)/k_AB over every admissible phi in \
                     the range (C0 from sigma_N = sigma_N') and every delta in the range is {r:.4}, at phi {:.2} deg \
                     and delta {delta:.4}. The friction stress the force system carries stays below the chip's \
                     flow stress at the interface, which is too cold to soften at this thermal number \
                     R_T = {rt:.2}: Oxley's sticking-interface condition has no solution here.{thick}{inadmissible}",
                    phi.to_degrees()
                )
            }
            _ => format!(
                "no admissible state (phi, C0 from sigma_N = sigma_N') solves tau_int = k_chip at any delta \
                 (thermal number R_T = {rt:.2}).{inadmissible} First scan failure: {first}"
            ),
        }
    }
}
