//! The solve of the extended Oxley model as root finding (after Pantale et al. 2022), using the
//! structure of the equations: C0 solves the normal-stress condition in closed form at each phi
//! (it does not depend on delta, `Context::c0_for_phi`), so at each delta only
//! `tau_int = m_f k_chip` is left, one equation in phi (a secant iteration warm-started from the last
//! solution, with a phi scan + Brent as the fallback). The primary zone (T_AB, k_AB, forces, T_C)
//! depends on phi only, and the interface is closed-form in delta at a fixed primary zone.
//! The search over delta for the least cutting force is in `minimum.rs`.

use crate::error::ModelError;

use super::equations::{Context, PrimaryZone, State};
use super::pool::Pool;
use super::roots::brent_root;

/// Largest phi step of the secant iteration, rad.
const MAX_PHI_STEP: f64 = 0.05;

/// A scan point (it only orders the scan and brackets the minimum; never an output) is accepted at
/// this shear residual when a point of the other sign within [`SCAN_BRACKET`] certifies the root or
/// the secant step to the root is below 1e-6 rad: its phi is then within about 1e-6 rad of the root,
/// so its Fc orders the scan points to about 1e-6. Outputs are always solved to the residual tolerance.
const SCAN_RESIDUAL: f64 = 1e-6;

/// Width of the certifying bracket of a scan point, rad.
const SCAN_BRACKET: f64 = 0.01;

/// Primary zones kept for reuse.
const RECENT: usize = 4;

/// Recent primary zones whose exact residuals seed the root search at a new delta.
const SEEDS: usize = 3;

/// Solver state across the delta search: evaluation count, the last solutions, flags.
pub(crate) struct Solver<'a> {
    pub ctx: Context<'a>,
    /// Primary-zone evaluations (each with its T_AB and T_C solves).
    pub evaluations: usize,
    /// Last phi solution (or the warm start).
    pub(super) last: Option<f64>,
    /// Last d residual_shear / d phi seen at a solution (a secant estimate), 1/rad.
    slope: Option<f64>,
    /// The last primary zones computed (a ring): reused exactly when phi is bit-identical, and
    /// their residuals at a new delta (closed-form) are the first points of the next root search.
    recent: [Option<PrimaryZone>; RECENT],
    next_slot: usize,
    /// The last solutions (ln delta, phi), oldest first: the starting point at a new delta is
    /// their Lagrange extrapolation in ln delta.
    history: [(f64, f64); 3],
    pub(super) n_history: usize,
    pub multiple_phi_roots: bool,
    /// The largest `(tau_int - m_f k_chip)/k_AB` over every phi and delta and where, (value, phi,
    /// delta), once [`Solver::rescue`] has looked for it.
    pub(super) best_residual: Option<(f64, f64, f64)>,
    /// How many phi of that search had no admissible state, and one reason.
    pub(super) inadmissible: Option<(usize, ModelError)>,
    /// While true (the continuous delta scan), [`Solver::secant`] accepts a certified bracket with
    /// a residual below [`SCAN_RESIDUAL`].
    pub(super) scanning: bool,
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

/// What the secant iteration in phi solves at each phi.
#[derive(Clone, Copy)]
pub(super) enum Target {
    /// `tau_int = m_f k_chip` at this delta.
    Delta(f64),
    /// `tau_int = m_f k_chip` at the delta where `d k_chip / d delta = 0` inside `(lo, hi)`.
    Stationary { lo: f64, hi: f64 },
}

impl<'a> Solver<'a> {
    pub fn new(ctx: Context<'a>, guess: Option<f64>) -> Self {
        Self {
            ctx,
            evaluations: 0,
            last: guess,
            slope: None,
            recent: [None; RECENT],
            next_slot: 0,
            history: [(f64::NAN, f64::NAN); 3],
            n_history: 0,
            multiple_phi_roots: false,
            best_residual: None,
            inadmissible: None,
            scanning: false,
        }
    }

    pub(super) fn primary(&mut self, phi: f64) -> Result<PrimaryZone, ModelError> {
        if let Some(p) = self.recent.iter().flatten().find(|p| p.phi_rad.to_bits() == phi.to_bits()) {
            return Ok(*p);
        }
        self.evaluations += 1;
        let p = self.ctx.primary(phi)?;
        self.recent[self.next_slot] = Some(p);
        self.next_slot = (self.next_slot + 1) % RECENT;
        Ok(p)
    }

    /// Puts a computed primary zone into the ring of recent ones (if not there).
    pub(super) fn keep(&mut self, p: PrimaryZone) {
        if self.recent.iter().flatten().all(|q| q.phi_rad.to_bits() != p.phi_rad.to_bits()) {
            self.recent[self.next_slot] = Some(p);
            self.next_slot = (self.next_slot + 1) % RECENT;
        }
    }

    /// phi at `delta` extrapolated (Lagrange, in ln delta) from the last solutions; `None` without
    /// history or when it moves more than 3 [`MAX_PHI_STEP`] from the last solution.
    fn predict_phi(&self, delta: f64) -> Option<f64> {
        let h = &self.history[3 - self.n_history..];
        let (x, last) = (delta.ln(), h.last()?.1);
        let mut phi = 0.0;
        for (i, &(xi, pi)) in h.iter().enumerate() {
            let mut w = 1.0;
            for (j, &(xj, _)) in h.iter().enumerate() {
                if i != j {
                    w *= (x - xj) / (xi - xj);
                }
            }
            phi += w * pi;
        }
        (phi.is_finite() && (phi - last).abs() <= 3.0 * MAX_PHI_STEP).then_some(phi)
    }

    pub(super) fn remember(&mut self, delta: f64, phi: f64) {
        let x = delta.ln();
        if self.history[3 - self.n_history..].iter().any(|h| h.0.to_bits() == x.to_bits()) {
            return;
        }
        self.history.rotate_left(1);
        self.history[2] = (x, phi);
        self.n_history = (self.n_history + 1).min(3);
    }

    /// The state at phi for a target: at its delta, or at the stationary delta of k_chip
    /// (`hint`: the last stationary delta, updated).
    fn eval(&mut self, phi: f64, target: Target, hint: &mut f64) -> Result<State, ModelError> {
        let p = self.primary(phi)?;
        self.state_for(p, target, hint)
    }

    /// The state of a computed primary zone for a target.
    pub(super) fn state_for(&self, p: PrimaryZone, target: Target, hint: &mut f64) -> Result<State, ModelError> {
        match target {
            Target::Delta(delta) => self.ctx.state_from(p, delta),
            Target::Stationary { lo, hi } => {
                let d = self.stationary_delta(&p, *hint, lo, hi)?;
                *hint = d;
                self.ctx.state_from(p, d)
            }
        }
    }

    /// delta in `(lo, hi)` with `d ln k_chip / d ln delta = 0` at a fixed primary zone: inverse
    /// quadratic interpolation / secant in ln(delta) from `hint` ([`Pool::next`]), else Brent on
    /// `[lo, hi]`.
    pub(super) fn stationary_delta(&self, p: &PrimaryZone, hint: f64, lo: f64, hi: f64) -> Result<f64, ModelError> {
        let g = |x: f64| -> Result<f64, ModelError> {
            let v = self.ctx.chip_log_slope(p, x.exp());
            if v.is_finite() {
                Ok(v)
            } else {
                Err(ModelError::out_of_range("d ln k_chip / d ln delta", v, "a finite number"))
            }
        };
        let (xlo, xhi) = (lo.ln(), hi.ln());
        let tol = 1e-11;
        let x0 = hint.ln().clamp(xlo, xhi);
        let mut pool = Pool::new();
        for x in [x0, if x0 + 1e-3 <= xhi { x0 + 1e-3 } else { x0 - 1e-3 }] {
            pool.push(x, g(x)?);
        }
        for _ in 0..self.ctx.options.max_bracket_iterations {
            let Some((xb, _)) = pool.best() else { break };
            let Some(x) = pool.next(0.5) else { break };
            if !(x >= xlo && x <= xhi) {
                break;
            }
            if (x - xb).abs() <= tol {
                return Ok(x.exp());
            }
            pool.push(x, g(x)?);
        }
        let (glo, ghi) = (g(xlo)?, g(xhi)?);
        Ok(brent_root(g, xlo, xhi, glo, ghi, tol, self.ctx.options.max_bracket_iterations, "stationary delta")?.exp())
    }

    /// Local root of `residual_shear` in phi near `phi0`: the recent primary zones within 0.15 rad of
    /// `phi0` ([`SEEDS`] at a fixed delta) give exact residuals at this target at no primary-zone
    /// cost; then inverse quadratic
    /// interpolation / secant steps ([`Pool::next`]), each limited to 0.1 rad and kept in the phi
    /// range. `None` when it leaves the admissible states, stops decreasing the residual or reaches
    /// the cap (the caller then brackets).
    pub(super) fn secant(&mut self, phi0: f64, target: Target, hint: &mut f64, trust_start: bool) -> Option<State> {
        let o = self.ctx.options;
        let [lo, hi] = o.phi_range_rad;
        let tol = o.residual_tolerance;
        let x0 = phi0.clamp(lo, hi);
        let mut pool = Pool::new();
        let mut found: Option<State> = None;
        // The most recent primary zones (the end of the last root searches): three at a fixed delta
        // (one interface state each), two at the stationary delta (a delta solve each).
        let seeds = if matches!(target, Target::Delta(_)) { SEEDS } else { 2 };
        for k in 1..=seeds {
            let Some(p) = self.recent[(self.next_slot + RECENT - k) % RECENT] else { continue };
            if (p.phi_rad - x0).abs() > 3.0 * MAX_PHI_STEP {
                continue;
            }
            if let Ok(s) = self.state_for(p, target, hint) {
                pool.push(p.phi_rad, s.residual_shear);
                if s.residual_norm() < tol && found.is_none_or(|f| s.residual_shear.abs() < f.residual_shear.abs()) {
                    found = Some(s);
                }
            }
        }
        if found.is_some() {
            return found;
        }
        // phi0 is evaluated when fewer than two cached points are near, or when it is a prediction
        // (`trust_start`) and fewer than three are: three exact residuals at this target give an
        // inverse quadratic step that is closer to the root than the extrapolated phi0.
        if pool.len() < 2 || (trust_start && pool.len() < 3) {
            if let Ok(s) = self.eval(x0, target, hint) {
                if s.residual_norm() < tol {
                    return Some(s);
                }
                pool.push(x0, s.residual_shear);
            }
        }
        if pool.len() == 1 {
            // One point: a second one from the last slope, else a forward difference.
            let (x, r) = pool.best()?;
            let x1 = match self.slope {
                Some(d) => x - (r / d).clamp(-MAX_PHI_STEP, MAX_PHI_STEP),
                None => x + if x + 1e-6 <= hi { 1e-6 } else { -1e-6 },
            };
            let s = self.eval(x1.clamp(lo, hi), target, hint).ok()?;
            if s.residual_norm() < tol {
                return Some(s);
            }
            pool.push(s.primary.phi_rad, s.residual_shear);
        }
        let mut stalls = 0;
        for _ in 0..o.max_newton_iterations {
            let (xb, rb) = pool.best()?;
            let x = pool.next(MAX_PHI_STEP)?.clamp(lo, hi);
            if x.to_bits() == xb.to_bits() {
                return None;
            }
            let s = self.eval(x, target, hint).ok()?;
            let slope_here = (s.residual_shear - rb) / (x - xb);
            let certified = self.scanning
                && s.residual_shear.abs() < SCAN_RESIDUAL
                && (pool.brackets(x, s.residual_shear, SCAN_BRACKET) || (s.residual_shear / slope_here).abs() < 1e-6);
            if s.residual_norm() < tol || certified {
                let slope = (s.residual_shear - rb) / (x - xb);
                if slope.is_finite() && slope != 0.0 {
                    self.slope = Some(slope);
                }
                return Some(s);
            }
            if s.residual_shear.abs() >= rb.abs() {
                stalls += 1;
                if stalls > 2 {
                    return None;
                }
            }
            pool.push(x, s.residual_shear);
        }
        None
    }

    /// phi solving `tau_int = m_f k_chip` at delta by bracketing: a grid scan for the first sign
    /// change from the low end of the phi range, then Brent.
    fn scan_root(&mut self, delta: f64) -> Result<State, ModelError> {
        let o = self.ctx.options;
        let [lo, hi] = o.phi_range_rad;
        let n = o.phi_scan_points;
        let target = Target::Delta(delta);
        let mut unused = delta;
        let mut prev: Option<(f64, f64)> = None;
        let mut found: Option<(f64, f64, f64, f64)> = None;
        let mut changes = 0;
        let (mut r_min, mut r_max) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut first_err = None;
        for i in 0..n {
            let phi = lo + (hi - lo) * i as f64 / (n - 1) as f64;
            let s = match self.eval(phi, target, &mut unused) {
                Ok(s) => s,
                Err(e) => {
                    first_err.get_or_insert(e);
                    prev = None;
                    continue;
                }
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
                what: format!("Oxley shear angle (tau_int = k_chip) at delta {delta:.4}"),
                low: lo.to_degrees(),
                high: hi.to_degrees(),
                detail: self.no_phi_reason(r_min, r_max, first_err),
            });
        };
        let phi = {
            let f = |phi: f64| -> Result<f64, ModelError> { Ok(self.eval(phi, target, &mut unused)?.residual_shear) };
            brent_root(f, a, b, fa, fb, 1e-12, o.max_bracket_iterations, "Oxley shear angle (tau_int = k_chip)")?
        };
        let s = self.eval(phi, target, &mut unused)?;
        if s.residual_norm() < o.residual_tolerance {
            return Ok(s);
        }
        // Brent stops on the bracket width; polish the residual with the secant from there.
        self.secant(phi, target, &mut unused, true).ok_or_else(|| ModelError::NoConvergence {
            what: format!("Oxley shear angle (tau_int = k_chip) at delta {delta:.4}"),
            iterations: o.max_newton_iterations,
            last_change: s.residual_norm(),
            tolerance: o.residual_tolerance,
        })
    }

    /// The physical reason why `tau_int = k_chip` has no root over the phi range, from the extreme
    /// residuals `(tau_int - k_chip)/k_AB` seen and the thermal number `R_T = rho Cp V t1 / K` at T_w.
    fn no_phi_reason(&self, r_min: f64, r_max: f64, first_err: Option<ModelError>) -> String {
        let c = self.ctx.conditions;
        let (rho_cp, k) = self.ctx.thermal(c.work_temperature_c);
        let rt = rho_cp * c.speed_m_per_s * c.uncut_chip_thickness_m / k;
        if !r_max.is_finite() {
            let e = first_err.map_or_else(String::new, |e| e.to_string());
            format!(
                "no admissible state at any phi, so tau_int = k_chip cannot be solved (thermal number R_T = {rt:.2}); \
                 first reason: {e}; phi range (deg)"
            )
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

    /// (phi, C0) at one delta: the secant from the last solution, else the bracketing scan.
    pub fn solve_at(&mut self, delta: f64) -> Result<State, ModelError> {
        // Cold start: phi = 22 deg + 0.8 alpha (a rough fit to Lalwani et al. 2009's AISI 1045
        // solutions; only a starting point).
        let alpha = self.ctx.conditions.rake_rad;
        let predicted = self.predict_phi(delta);
        let guess = predicted.or(self.last).unwrap_or(22f64.to_radians() + 0.8 * alpha);
        let mut unused = delta;
        let s = match self.secant(guess, Target::Delta(delta), &mut unused, predicted.is_some()) {
            Some(s) => s,
            None => self.scan_root(delta)?,
        };
        self.last = Some(s.primary.phi_rad);
        self.remember(delta, s.primary.phi_rad);
        Ok(s)
    }
}
