//! The two temperature fixed points of the extended Oxley model, solved by Newton's method with
//! analytic derivatives (each property polynomial and the JC softening evaluated once per
//! iterate), warm-started at the last solution, with Brent on the whole interval as the fallback.
//!
//! Sources: Oxley, *Mechanics of Machining* (1989), Sec. 4.3 (T_AB with Boothroyd's heat
//! partition; the mean chip temperature T_C); Lalwani, Mehta & Jain 2009, Sec. 2.

use std::f64::consts::LN_10;

use crate::error::ModelError;

use super::equations::{Context, TemperatureHints, SQRT3};
use super::roots::{brent_root, newton_1d};

/// Lower end of Boothroyd's heat-partition correlation in `R_T tan(phi)` (Oxley 1989, Sec. 4.3).
pub(crate) const BETA_CORRELATION_LOW: f64 = 0.04;

/// Newton iterations tried from the hint before the bracketing fallback.
const NEWTON_CAP: usize = 30;

/// The solved primary-zone temperature and what depends on it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AbTemperature {
    /// T_AB, degC.
    pub t_ab_c: f64,
    /// dT_SZ = (1 - beta) k_AB cos(a) / (rho Cp sin(phi) cos(phi - a)), K.
    pub rise_sz_c: f64,
    /// k_AB, Pa.
    pub k_ab_pa: f64,
    /// beta after the M6 scale.
    pub beta: f64,
    /// R_T tan(phi) below the correlation's range.
    pub beta_outside: bool,
}

/// Value and first derivative of `sum c_i T^i` in one Horner pass.
fn horner(coefficients: &[f64], t: f64) -> (f64, f64) {
    let (mut p, mut d) = (0.0, 0.0);
    for &c in coefficients.iter().rev() {
        d = d * t + p;
        p = p * t + c;
    }
    (p, d)
}

impl Context<'_> {
    /// rho Cp, d(rho Cp)/dT, K and dK/dT at `temperature_c`, clamped to the material's validity
    /// range (the fits are not extrapolated; outside it the derivatives are 0).
    pub(crate) fn thermal_d(&self, temperature_c: f64) -> (f64, f64, f64, f64) {
        let th = &self.material.thermal;
        let t = temperature_c.clamp(th.valid_from_c, th.valid_to_c);
        let inside = temperature_c > th.valid_from_c && temperature_c < th.valid_to_c;
        let (rho_cp, d_rho_cp) = horner(th.rho_cp.coefficients(), t);
        let (k, d_k) = horner(th.conductivity.coefficients(), t);
        if inside {
            (rho_cp, d_rho_cp, k, d_k)
        } else {
            (rho_cp, 0.0, k, 0.0)
        }
    }

    /// The JC softening `g = 1 - theta^m` at `T_w + kappa_T (T - T_w)` (the M7 hook) and dg/dT
    /// (paper Eq 14 and its derivative; 0 outside `(T_r, T_m)`).
    pub(crate) fn softening_d(&self, temperature_c: f64) -> (f64, f64) {
        let (jc, tw, kappa) = (self.jc, self.conditions.work_temperature_c, self.physics.thermal_softening_scale);
        let span = jc.tm_c - jc.tr_c;
        let theta = (tw + kappa * (temperature_c - tw) - jc.tr_c) / span;
        if theta <= 0.0 {
            (1.0, 0.0)
        } else if theta >= 1.0 {
            (0.0, 0.0)
        } else {
            // theta^1 = theta exactly: m = 1 (a common JC exponent) skips the power.
            #[allow(clippy::float_cmp)] // exactly 1: theta^1 = theta bit for bit
            let tm = if jc.m == 1.0 { theta } else { theta.powf(jc.m) };
            (1.0 - tm, -jc.m * tm / theta * kappa / span)
        }
    }

    /// Boothroyd's heat partition into the work (Oxley 1989, Sec. 4.3):
    /// `beta = 0.5 - 0.35 log10(R_T tan phi)` for `0.04 <= R_T tan phi <= 10`,
    /// `beta = 0.3 - 0.15 log10(R_T tan phi)` above 10, with the thermal number
    /// `R_T = rho Cp V t1 / K`. Below 0.04 the value at 0.04 is used and flagged.
    /// Takes `x = R_T tan(phi)`; returns `(beta scaled by the M6 hook and clamped to [0, 1],
    /// outside-correlation flag, d beta / d ln x)`.
    pub(crate) fn heat_partition_tan(&self, x: f64) -> (f64, bool, f64) {
        let (beta, outside, slope) = if x < BETA_CORRELATION_LOW {
            (0.5 - 0.35 * BETA_CORRELATION_LOW.log10(), true, 0.0)
        } else if x <= 10.0 {
            (0.5 - 0.35 / LN_10 * x.ln(), false, -0.35 / LN_10)
        } else {
            (0.3 - 0.15 / LN_10 * x.ln(), false, -0.15 / LN_10)
        };
        let s = self.physics.heat_partition_scale;
        let scaled = beta * s;
        if scaled <= 0.0 {
            (0.0, outside, 0.0)
        } else if scaled >= 1.0 {
            (1.0, outside, 0.0)
        } else {
            (scaled, outside, slope * s)
        }
    }

    /// T_AB = T_w + eta dT_SZ with dT_SZ = (1 - beta) k_AB cos(a) / (rho Cp sin(phi) cos(phi - a)),
    /// k_AB = athermal g(T_AB)/sqrt3, rho Cp, K and beta at T_AB (Oxley 1989, Sec. 4.3; Lalwani et al.
    /// 2009, Sec. 2), solved on [T_w, T_m]: Newton from the last T_AB, else Brent.
    /// `geo` is `cos(a) / (sin(phi) cos(phi - a))`.
    pub(crate) fn solve_t_ab(
        &self,
        phi_rad: f64,
        athermal_pa: f64,
        geo: f64,
        tan_phi: f64,
    ) -> Result<AbTemperature, ModelError> {
        let c = self.conditions;
        let (v, t1, tw, eta) = (c.speed_m_per_s, c.uncut_chip_thickness_m, c.work_temperature_c, self.options.eta);
        // Value of dT_SZ and its derivative in T, and the quantities reported.
        let rise = |t: f64| -> (f64, f64, f64, f64, bool) {
            let (rho_cp, d_rho_cp, cond, d_cond) = self.thermal_d(t);
            let (g, dg) = self.softening_d(t);
            let (k, dk) = (athermal_pa * g / SQRT3, athermal_pa * dg / SQRT3);
            let x = rho_cp * v * t1 / cond * tan_phi;
            let (beta, outside, dbeta_dlnx) = self.heat_partition_tan(x);
            let dbeta = dbeta_dlnx * (d_rho_cp / rho_cp - d_cond / cond);
            let value = (1.0 - beta) * k * geo / rho_cp;
            let deriv = geo * (-dbeta * k + (1.0 - beta) * dk - (1.0 - beta) * k * d_rho_cp / rho_cp) / rho_cp;
            (value, deriv, k, beta, outside)
        };
        let tm = self.jc.tm_c.min(self.material.melting_c);
        let (tol, cap) = (self.options.temperature_tolerance_c, self.options.max_bracket_iterations);
        // The last Newton iterate and its rise: Newton returns the evaluated point, reused below.
        let last = std::cell::Cell::new((f64::NAN, (0.0, 0.0, 0.0, 0.0, false)));
        let newton = |t: f64| -> Result<(f64, f64), ModelError> {
            let r = rise(t);
            last.set((t, r));
            Ok((t - tw - eta * r.0, 1.0 - eta * r.1))
        };
        let start = TemperatureHints::start(self.hints.ab.get(), phi_rad, tw + 300.0);
        let t_ab = match newton_1d(newton, start, tw, tm, tol, NEWTON_CAP) {
            Some(t) => t,
            None => {
                let what = "primary-zone temperature T_AB";
                let f = |t: f64| -> Result<f64, ModelError> { Ok(t - tw - eta * rise(t).0) };
                let (f_lo, f_hi) = (f(tw)?, f(tm)?);
                if f_hi < 0.0 {
                    return Err(ModelError::AboveMelting {
                        what: what.into(),
                        temperature_c: tm - f_hi,
                        melting_c: tm,
                    });
                }
                brent_root(f, tw, tm, f_lo, f_hi, tol, cap, what)?
            }
        };
        TemperatureHints::push(&self.hints.ab, phi_rad, t_ab);
        let (t_last, at_last) = last.get();
        let (rise_sz_c, _, k_ab_pa, beta, beta_outside) =
            if t_last.to_bits() == t_ab.to_bits() { at_last } else { rise(t_ab) };
        Ok(AbTemperature { t_ab_c: t_ab, rise_sz_c, k_ab_pa, beta, beta_outside })
    }

    /// Mean chip temperature T_C = T_w + dT_SZ + dT_C with dT_C = F sin(phi) / (rho Cp(T_C) t1 w cos(phi - a))
    /// (Oxley 1989, Sec. 4.3: the chip is heated by the whole primary-zone rise and the mean
    /// secondary-zone rise), solved on [T_w + dT_SZ, top of the property range]: Newton from the last
    /// T_C, else Brent; above the property range rho Cp is held, so the root is closed-form there.
    /// `heat_per_rho_cp` is `F sin(phi) / (t1 cos(phi - a))` (K times J/(m3 K)). Returns (T_C, dT_C).
    pub(crate) fn solve_t_c(&self, phi_rad: f64, base_c: f64, heat_per_rho_cp: f64) -> Result<(f64, f64), ModelError> {
        let d_t_c_at = |t: f64| heat_per_rho_cp / self.thermal_d(t).0;
        let top = self.material.thermal.valid_to_c;
        let (tol, cap) = (self.options.temperature_tolerance_c, self.options.max_bracket_iterations);
        let t_c = if top <= base_c {
            base_c + d_t_c_at(top)
        } else {
            let newton = |t: f64| -> Result<(f64, f64), ModelError> {
                let (rho_cp, d_rho_cp, ..) = self.thermal_d(t);
                let d = heat_per_rho_cp / rho_cp;
                Ok((t - base_c - d, 1.0 + d * d_rho_cp / rho_cp))
            };
            let start = TemperatureHints::start(self.hints.chip.get(), phi_rad, base_c + d_t_c_at(base_c));
            match newton_1d(newton, start, base_c, top, tol, NEWTON_CAP) {
                Some(t) => t,
                None => {
                    let g = |t: f64| -> Result<f64, ModelError> { Ok(t - base_c - d_t_c_at(t)) };
                    let g_hi = g(top)?;
                    if g_hi <= 0.0 {
                        base_c + d_t_c_at(top)
                    } else {
                        let g_lo = g(base_c)?;
                        brent_root(g, base_c, top, g_lo, g_hi, tol, cap, "mean chip temperature T_C")?
                    }
                }
            }
        };
        TemperatureHints::push(&self.hints.chip, phi_rad, t_c);
        Ok((t_c, d_t_c_at(t_c)))
    }
}
