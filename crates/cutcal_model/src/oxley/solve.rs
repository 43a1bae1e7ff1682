//! The nested solve of the extended Oxley model as root finding (after Pantale et al. 2022):
//! at each delta, (phi, C0) solve `tau_int = m_f k_chip` and `sigma_N = sigma_N'` (damped Newton,
//! warm-started, with a bracketing fallback: phi by Brent at each C0 on a scanned bracket, C0 by
//! Brent on a scanned bracket); delta minimises the cutting force (scan, then Brent).

use crate::error::ModelError;

use super::equations::{Context, PrimaryZone, State};
use super::roots::{brent_min, brent_root};

/// Solver state across the delta search: evaluation count, the last (phi, C0) solution, flags.
pub(crate) struct Solver<'a> {
    pub ctx: Context<'a>,
    pub evaluations: usize,
    last: Option<(f64, f64)>,
    /// The primary zone last computed: (phi, C0) repeat across delta (warm starts), and the primary
    /// zone does not depend on delta, so it is reused exactly when (phi, C0) are bit-identical.
    primary_cache: Option<PrimaryZone>,
    pub multiple_phi_roots: bool,
}

/// One converged point of the delta search.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DeltaPoint {
    pub delta: f64,
    pub state: State,
}

/// What the delta search returns.
pub(crate) struct DeltaSearch {
    pub best: DeltaPoint,
    pub at_bound: bool,
    pub fc_change_over_band: Option<f64>,
    pub poorly_determined: bool,
    pub converged_share: f64,
}

impl<'a> Solver<'a> {
    pub fn new(ctx: Context<'a>, guess: Option<(f64, f64)>) -> Self {
        Self { ctx, evaluations: 0, last: guess, primary_cache: None, multiple_phi_roots: false }
    }

    fn eval(&mut self, phi: f64, c0: f64, delta: f64) -> Result<State, ModelError> {
        if let Some(p) = self.primary_cache {
            if p.phi_rad.to_bits() == phi.to_bits() && p.c0.to_bits() == c0.to_bits() {
                return self.ctx.state_from(p, delta);
            }
        }
        self.evaluations += 1;
        let p = self.ctx.primary(phi, c0)?;
        self.primary_cache = Some(p);
        self.ctx.state_from(p, delta)
    }

    /// Damped Newton on the two normalised residuals from `guess`, with a forward-difference
    /// Jacobian, steps limited to 0.1 rad and 20 % of the C0 range, projected onto the ranges,
    /// backtracking until the residual norm falls.
    fn newton(&mut self, delta: f64, guess: (f64, f64)) -> Result<State, ModelError> {
        let o = self.ctx.options;
        let [plo, phi_hi] = o.phi_range_rad;
        let [clo, chi] = o.c0_range;
        let tol = o.residual_tolerance;
        let (mut phi, mut c0) = (guess.0.clamp(plo, phi_hi), guess.1.clamp(clo, chi));
        let mut s = self.eval(phi, c0, delta)?;
        for _ in 0..o.max_newton_iterations {
            if s.residual_norm() < tol {
                return Ok(s);
            }
            let hp = 1e-7;
            let hc = 1e-7 * c0.max(1.0);
            let sp = self.eval(phi + hp, c0, delta)?;
            let sc = self.eval(phi, c0 + hc, delta)?;
            let j11 = (sp.residual_shear - s.residual_shear) / hp;
            let j21 = (sp.residual_normal - s.residual_normal) / hp;
            let j12 = (sc.residual_shear - s.residual_shear) / hc;
            let j22 = (sc.residual_normal - s.residual_normal) / hc;
            let det = j11 * j22 - j12 * j21;
            if !(det.is_finite() && det.abs() > 1e-14 * (j11.abs() + j12.abs()) * (j21.abs() + j22.abs())) {
                return Err(ModelError::NoConvergence {
                    what: format!("Oxley (phi, C0) Newton at delta {delta:.4} (singular Jacobian)"),
                    iterations: 0,
                    last_change: det,
                    tolerance: tol,
                });
            }
            let mut dp = -(j22 * s.residual_shear - j12 * s.residual_normal) / det;
            let mut dc = -(-j21 * s.residual_shear + j11 * s.residual_normal) / det;
            let scale = (dp.abs() / 0.1).max(dc.abs() / (0.2 * (chi - clo))).max(1.0);
            dp /= scale;
            dc /= scale;
            let norm0 = s.residual_norm();
            let mut accepted = None;
            let mut t = 1.0;
            for _ in 0..12 {
                let (pn, cn) = ((phi + t * dp).clamp(plo, phi_hi), (c0 + t * dc).clamp(clo, chi));
                if let Ok(sn) = self.eval(pn, cn, delta) {
                    if sn.residual_norm() < norm0 * (1.0 - 1e-4 * t) {
                        accepted = Some((pn, cn, sn));
                        break;
                    }
                }
                t *= 0.5;
            }
            match accepted {
                Some((pn, cn, sn)) => {
                    phi = pn;
                    c0 = cn;
                    s = sn;
                }
                None => {
                    return Err(ModelError::NoConvergence {
                        what: format!("Oxley (phi, C0) Newton at delta {delta:.4} (no descent step)"),
                        iterations: 0,
                        last_change: norm0,
                        tolerance: tol,
                    })
                }
            }
        }
        if s.residual_norm() < tol {
            return Ok(s);
        }
        Err(ModelError::NoConvergence {
            what: format!("Oxley (phi, C0) Newton at delta {delta:.4}"),
            iterations: o.max_newton_iterations,
            last_change: s.residual_norm(),
            tolerance: tol,
        })
    }

    /// phi solving `tau_int = m_f k_chip` at fixed (C0, delta): a grid scan for the first sign
    /// change from the low end of the range, then Brent.
    fn phi_root(&mut self, c0: f64, delta: f64) -> Result<State, ModelError> {
        let o = self.ctx.options;
        let [lo, hi] = o.phi_range_rad;
        let n = o.phi_scan_points;
        let mut prev: Option<(f64, f64)> = None;
        let mut found: Option<(f64, f64, f64, f64)> = None;
        let mut changes = 0;
        let (mut r_min, mut r_max) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..n {
            let phi = lo + (hi - lo) * i as f64 / (n - 1) as f64;
            let Ok(s) = self.eval(phi, c0, delta) else {
                prev = None;
                continue;
            };
            let r = s.residual_shear;
            r_min = r_min.min(r);
            r_max = r_max.max(r);
            if let Some((p0, r0)) = prev {
                if (r0 > 0.0) != (r > 0.0) {
                    changes += 1;
                    if found.is_none() {
                        found = Some((p0, phi, r0, r));
                    }
                }
            }
            prev = Some((phi, r));
        }
        if changes > 1 {
            self.multiple_phi_roots = true;
        }
        let Some((a, b, fa, fb)) = found else {
            return Err(ModelError::NoSolution {
                what: format!("Oxley shear angle (tau_int = k_chip) at C0 {c0:.3}, delta {delta:.4}"),
                low: lo.to_degrees(),
                high: hi.to_degrees(),
                detail: self.no_phi_reason(r_min, r_max),
            });
        };
        let xtol = 1e-12;
        let mut evals = 0;
        let phi = {
            let ctx = self.ctx;
            let f = |phi: f64| -> Result<f64, ModelError> {
                evals += 1;
                Ok(ctx.state(phi, c0, delta)?.residual_shear)
            };
            brent_root(f, a, b, fa, fb, xtol, o.max_bracket_iterations, "Oxley shear angle (tau_int = k_chip)")?
        };
        self.evaluations += evals;
        self.eval(phi, c0, delta)
    }

    /// The physical reason why `tau_int = k_chip` has no root over the phi range, from the extreme
    /// residuals `(tau_int - k_chip)/k_AB` seen and the thermal number `R_T = rho Cp V t1 / K` at T_w.
    fn no_phi_reason(&self, r_min: f64, r_max: f64) -> String {
        let c = self.ctx.conditions;
        let (rho_cp, k) = self.ctx.thermal(c.work_temperature_c);
        let rt = rho_cp * c.speed_m_per_s * c.uncut_chip_thickness_m / k;
        if !r_max.is_finite() {
            format!("no admissible state over the phi range (deg) (thermal number R_T = {rt:.2})")
        } else if r_max < 0.0 {
            format!(
                "tau_int < k_chip at every phi (largest (tau_int - k_chip)/k_AB = {r_max:.3}): the friction stress the \
                 force system carries stays below the chip's flow stress at the interface, which is too cold to \
                 soften at this thermal number R_T = {rt:.2} (low V t1); Oxley's sticking-interface condition has \
                 no solution here, phi range (deg)"
            )
        } else {
            format!(
                "tau_int > k_chip at every phi (smallest (tau_int - k_chip)/k_AB = {r_min:.3}): the chip at the \
                 interface is softer than any friction stress the force system carries (thermal number \
                 R_T = {rt:.2}); phi range (deg)"
            )
        }
    }

    /// (phi, C0) by nested bracketing: a C0 grid scan of `sigma_N - sigma_N'` (each point with its
    /// phi root), then Brent on the first sign change.
    fn bracketed(&mut self, delta: f64) -> Result<State, ModelError> {
        let o = self.ctx.options;
        let [lo, hi] = o.c0_range;
        let n = o.c0_scan_points;
        let mut prev: Option<(f64, f64)> = None;
        let mut found = None;
        let mut first_err = None;
        let (mut r_lo, mut r_hi) = (f64::NAN, f64::NAN);
        for i in 0..n {
            let c0 = lo + (hi - lo) * i as f64 / (n - 1) as f64;
            let s = match self.phi_root(c0, delta) {
                Ok(s) => s,
                Err(e) => {
                    first_err.get_or_insert(e);
                    prev = None;
                    continue;
                }
            };
            let r = s.residual_normal;
            if r_lo.is_nan() {
                r_lo = r;
            }
            r_hi = r;
            if let Some((c_prev, r_prev)) = prev {
                if (r_prev > 0.0) != (r > 0.0) {
                    found = Some((c_prev, c0, r_prev, r));
                    break;
                }
            }
            prev = Some((c0, r));
        }
        let Some((a, b, fa, fb)) = found else {
            let detail = if r_lo.is_nan() {
                format!("no shear angle at any C0: {}", first_err.map_or_else(String::new, |e| e.to_string()))
            } else {
                format!(
                    "no sign change of (sigma_N - sigma_N')/k_AB: {r_lo:.4} at the low end, {r_hi:.4} at the high end"
                )
            };
            return Err(ModelError::NoSolution {
                what: format!("Oxley strain-rate constant C0 (sigma_N = sigma_N') at delta {delta:.4}"),
                low: lo,
                high: hi,
                detail,
            });
        };
        let c0 = {
            let f = |c0: f64| -> Result<f64, ModelError> { Ok(self.phi_root(c0, delta)?.residual_normal) };
            brent_root(f, a, b, fa, fb, 1e-10, o.max_bracket_iterations, "Oxley strain-rate constant C0")?
        };
        self.phi_root(c0, delta)
    }

    /// (phi, C0) at one delta: warm-started Newton, else nested bracketing.
    pub fn solve_at(&mut self, delta: f64) -> Result<State, ModelError> {
        let tol = self.ctx.options.residual_tolerance;
        // Warm start from the last solution; on a cold start, from phi = 22 deg + 0.8 alpha and
        // C0 = 5 (a rough fit to Lalwani et al. 2009's AISI 1045 solutions; only a starting point).
        let alpha = self.ctx.conditions.rake_rad;
        let guess = self.last.unwrap_or((22f64.to_radians() + 0.8 * alpha, 5.0));
        if let Ok(s) = self.newton(delta, guess) {
            self.last = Some((s.primary.phi_rad, s.primary.c0));
            return Ok(s);
        }
        let s = self.bracketed(delta)?;
        if s.residual_norm() >= tol {
            // Brent stops on the bracket width; polish the residual with Newton from there.
            let s = self.newton(delta, (s.primary.phi_rad, s.primary.c0))?;
            self.last = Some((s.primary.phi_rad, s.primary.c0));
            return Ok(s);
        }
        self.last = Some((s.primary.phi_rad, s.primary.c0));
        Ok(s)
    }

    /// delta minimising the chip-formation cutting force: a geometric scan of the delta range,
    /// Brent's minimiser in ln(delta) between the neighbours of the best scan point, and the
    /// flatness probes at delta*(1 -/+ band).
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
        for &delta in &deltas {
            match self.solve_at(delta) {
                Ok(state) => grid.push(Some(DeltaPoint { delta, state })),
                Err(e) => {
                    first_err.get_or_insert(e);
                    grid.push(None);
                }
            }
        }
        let ok = grid.iter().flatten().count();
        let fc = |p: &DeltaPoint| p.state.primary.cutting_force_n_per_m;
        let Some((ib, best)) =
            grid.iter().enumerate().filter_map(|(i, p)| p.map(|p| (i, p))).min_by(|a, b| fc(&a.1).total_cmp(&fc(&b.1)))
        else {
            return Err(ModelError::NoSolution {
                what: "extended Oxley model: no (phi, C0) solution at any delta".into(),
                low: dlo,
                high: dhi,
                detail: first_err.map_or_else(|| "no delta tried".into(), |e| e.to_string()),
            });
        };
        let left = if ib > 0 { grid[ib - 1] } else { None };
        let right = grid.get(ib + 1).copied().flatten();
        let at_bound = left.is_none() || right.is_none();
        let mut best = best;
        if let (Some(l), Some(r), None) = (left, right, o.delta_grid_step) {
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
            if res.is_ok_and(|m| m.x.is_finite() && m.f.is_finite()) {
                best = found;
            } else if fc(&found) < fc(&best) {
                best = found;
            }
        }
        // Flatness: Fc at delta*(1 -/+ band) against Fc(delta*).
        let mut change: Option<f64> = None;
        for factor in [1.0 - o.delta_flat_band, 1.0 + o.delta_flat_band] {
            let d = best.delta * factor;
            if d < dlo || d > dhi {
                continue;
            }
            self.last = Some((best.state.primary.phi_rad, best.state.primary.c0));
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
