//! The closed-form relations of the extended Oxley model at a given (phi, C0, delta), with the two
//! temperature fixed points solved by bracketed root finding (never an unbounded loop).
//!
//! Sources: Oxley, *Mechanics of Machining* (1989), Ch. 4 (the parallel-sided primary zone, the
//! tool-chip interface, the temperature models); Lalwani, Mehta & Jain 2009, Sec. 2 (the same
//! relations with the Johnson-Cook law and the equivalent hardening index n_eq). The equations are
//! cited by quantity and section; the symbols follow Lalwani et al. 2009.

use std::cell::Cell;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

use crate::error::ModelError;
use crate::jc::JcParams;
use crate::material::Material;

use super::options::{CuttingConditions, OxleyOptions, Physics};
use super::roots::brent_root;

const SQRT3: f64 = 1.732_050_807_568_877_2;

/// Lower end of Boothroyd's heat-partition correlation in `R_T tan(phi)` (Oxley 1989, Sec. 4.3).
const BETA_CORRELATION_LOW: f64 = 0.04;

/// Everything the relations need, borrowed.
#[derive(Clone, Copy)]
pub(crate) struct Context<'a> {
    pub material: &'a Material,
    pub jc: &'a JcParams,
    pub conditions: &'a CuttingConditions,
    pub options: &'a OxleyOptions,
    pub physics: &'a Physics,
    /// Last temperatures solved (NaN: none), used to try a narrow bracket first.
    pub hints: &'a TemperatureHints,
}

/// The last T_AB and T_int solved, degC (NaN when none). Only a search window: a narrow bracket
/// around the hint is tried first and the full bracket is used when it does not change sign.
#[derive(Debug)]
pub(crate) struct TemperatureHints {
    pub ab_c: Cell<f64>,
    pub int_c: Cell<f64>,
}

impl TemperatureHints {
    pub fn none() -> Self {
        Self { ab_c: Cell::new(f64::NAN), int_c: Cell::new(f64::NAN) }
    }
}

/// Secant iteration from a hint (and the hint + 1 degC), kept inside `[lo, hi]`; `None` if it leaves
/// the interval, stalls or does not converge in 12 steps (the caller then brackets the whole
/// interval with Brent). The residuals solved here are increasing and nearly linear in T, so the
/// secant converges in a few steps; the root is the same to `tol` whatever the hint.
fn try_hint<F>(mut f: F, hint: f64, lo: f64, hi: f64, tol: f64) -> Option<f64>
where
    F: FnMut(f64) -> Result<f64, ModelError>,
{
    if !hint.is_finite() || !(hi > lo) {
        return None;
    }
    let mut x0 = hint.clamp(lo, hi);
    let mut x1 = if x0 + 1.0 <= hi { x0 + 1.0 } else { x0 - 1.0 };
    let mut f0 = f(x0).ok()?;
    let mut f1 = f(x1).ok()?;
    for _ in 0..12 {
        let df = f1 - f0;
        if !(df.is_finite() && df != 0.0) {
            return None;
        }
        let x2 = x1 - f1 * (x1 - x0) / df;
        if !(x2 >= lo && x2 <= hi) {
            return None;
        }
        if (x2 - x1).abs() <= tol {
            return Some(x2);
        }
        (x0, f0) = (x1, f1);
        x1 = x2;
        f1 = f(x1).ok()?;
    }
    None
}

/// The primary zone and the force system at (phi, C0).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PrimaryZone {
    pub phi_rad: f64,
    pub c0: f64,
    pub shear_plane_length_m: f64,
    pub chip_velocity_m_per_s: f64,
    pub strain: f64,
    pub strain_rate_per_s: f64,
    pub temperature_c: f64,
    pub temperature_rise_sz_c: f64,
    pub shear_flow_stress_pa: f64,
    pub heat_partition: f64,
    pub beta_outside_correlation: bool,
    pub n_eq: f64,
    pub theta_rad: f64,
    pub lambda_rad: f64,
    pub shear_force_n_per_m: f64,
    pub cutting_force_n_per_m: f64,
    pub feed_force_n_per_m: f64,
    pub friction_force_n_per_m: f64,
    pub normal_force_n_per_m: f64,
    pub chip_thickness_m: f64,
    pub contact_length_m: f64,
    /// sigma_N' from the stress distribution along AB, Pa.
    pub model_normal_stress_pa: f64,
}

/// The secondary (tool-chip) zone at delta.
#[derive(Debug, Clone, Copy)]
pub(crate) struct InterfaceZone {
    pub delta: f64,
    pub strain: f64,
    pub strain_rate_per_s: f64,
    pub temperature_c: f64,
    pub shear_flow_stress_pa: f64,
    pub shear_stress_pa: f64,
    pub normal_stress_pa: f64,
}

/// A full state with the two normalised equilibrium residuals.
#[derive(Debug, Clone, Copy)]
pub(crate) struct State {
    pub primary: PrimaryZone,
    pub interface: InterfaceZone,
    /// `(tau_int - m_f k_chip) / k_AB` (Oxley 1989, Sec. 4.2: the phi condition).
    pub residual_shear: f64,
    /// `(sigma_N - sigma_N') / k_AB` (Oxley 1989, Sec. 4.2: the C0 condition).
    pub residual_normal: f64,
}

impl State {
    /// The larger absolute residual.
    pub fn residual_norm(&self) -> f64 {
        self.residual_shear.abs().max(self.residual_normal.abs())
    }
}

impl Context<'_> {
    /// Volumetric heat capacity and conductivity at `temperature_c`, evaluated with the temperature
    /// clamped to the material's stated validity range (the fits are not extrapolated).
    pub(crate) fn thermal(&self, temperature_c: f64) -> (f64, f64) {
        let th = &self.material.thermal;
        let t = temperature_c.clamp(th.valid_from_c, th.valid_to_c);
        (th.rho_cp.value(t), th.conductivity.value(t))
    }

    /// The JC softening term `1 - T*^m` at `T_w + kappa_T (T - T_w)` (the thermal-softening hook).
    fn softening(&self, temperature_c: f64) -> f64 {
        let tw = self.conditions.work_temperature_c;
        self.jc.softening(tw + self.physics.thermal_softening_scale * (temperature_c - tw))
    }

    /// Johnson-Cook flow stress with the thermal-softening hook: evaluated at
    /// `T_w + kappa_T (T - T_w)` (kappa_T = 1: Lalwani et al. 2009, Sec. 2).
    fn flow_stress_pa(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        let tw = self.conditions.work_temperature_c;
        let t = tw + self.physics.thermal_softening_scale * (temperature_c - tw);
        self.jc.flow_stress(strain, strain_rate_per_s, t)
    }

    /// Boothroyd's heat partition into the work (Oxley 1989, Sec. 4.3):
    /// `beta = 0.5 - 0.35 log10(R_T tan phi)` for `0.04 <= R_T tan phi <= 10`,
    /// `beta = 0.3 - 0.15 log10(R_T tan phi)` above 10, with the thermal number
    /// `R_T = rho Cp V t1 / K`. Below 0.04 the value at 0.04 is used and flagged.
    /// Takes `x = R_T tan(phi)`; returns `(beta scaled by the M6 hook and clamped to [0, 1],
    /// outside-correlation flag)`.
    fn heat_partition_tan(&self, x: f64) -> (f64, bool) {
        let (beta, outside) = if x < BETA_CORRELATION_LOW {
            (0.5 - 0.35 * BETA_CORRELATION_LOW.log10(), true)
        } else if x <= 10.0 {
            (0.5 - 0.35 * x.log10(), false)
        } else {
            (0.3 - 0.15 * x.log10(), false)
        };
        ((beta * self.physics.heat_partition_scale).clamp(0.0, 1.0), outside)
    }

    /// The primary zone and the force system at (phi, C0).
    ///
    /// Returns an error if the state is non-physical (a non-positive flow stress at the work
    /// temperature, a friction angle outside (0, 90) deg, a non-positive contact length) or the
    /// temperature at AB reaches melting with thermal softening switched off.
    pub fn primary(&self, phi_rad: f64, c0: f64) -> Result<PrimaryZone, ModelError> {
        let c = self.conditions;
        let (alpha, v, t1, tw) = (c.rake_rad, c.speed_m_per_s, c.uncut_chip_thickness_m, c.work_temperature_c);
        let sin_phi = phi_rad.sin();
        let cos_pa = (phi_rad - alpha).cos();
        // Shear-plane length l_AB = t1 / sin(phi) (Lalwani et al. 2009, Sec. 2).
        let l_ab = t1 / sin_phi;
        // Shear velocity V_s = V cos(alpha)/cos(phi - alpha); chip velocity V_c = V sin(phi)/cos(phi - alpha)
        // (Oxley 1989, Sec. 4.2, hodograph).
        let v_s = v * alpha.cos() / cos_pa;
        let v_c = v * sin_phi / cos_pa;
        // Strain and strain rate at AB: gamma_AB = cos(alpha) / (2 sin(phi) cos(phi - alpha)),
        // eps_AB = gamma_AB / sqrt(3); epsdot_AB = C0 V_s / (sqrt(3) l_AB) (Lalwani et al. 2009, Sec. 2).
        let gamma_ab = alpha.cos() / (2.0 * sin_phi * cos_pa);
        let strain = gamma_ab / SQRT3;
        let strain_rate = c0 * v_s / (SQRT3 * l_ab);
        // The athermal part (A + B eps^n)(1 + C ln epsdot) is fixed at (phi, C0): evaluated once.
        let athermal = self.jc.hardening(strain) * self.jc.rate_factor(strain_rate);
        let tan_phi = phi_rad.tan();
        let k_at_work = self.flow_stress_pa(strain, strain_rate, tw) / SQRT3;
        if !(k_at_work.is_finite() && k_at_work > 0.0) {
            return Err(ModelError::out_of_range(
                "primary-zone flow stress at the work temperature (Pa)",
                k_at_work * SQRT3,
                format!("a positive JC stress (strain {strain:.3}, strain rate {strain_rate:.3e} 1/s)"),
            ));
        }
        // T_AB = T_w + eta dT_SZ with dT_SZ = (1 - beta) F_s cos(alpha) / (rho Cp t1 w cos(phi - alpha))
        // and F_s = k_AB l_AB w (Oxley 1989, Sec. 4.3), solved for T_AB on [T_w, T_m].
        let eta = self.options.eta;
        let rise = |t: f64| -> (f64, f64, f64, bool) {
            let (rho_cp, cond) = self.thermal(t);
            let k = athermal * self.softening(t) / SQRT3;
            let rt = rho_cp * v * t1 / cond;
            let (beta, outside) = self.heat_partition_tan(rt * tan_phi);
            ((1.0 - beta) * k * alpha.cos() / (rho_cp * sin_phi * cos_pa), k, beta, outside)
        };
        let f = |t: f64| -> Result<f64, ModelError> { Ok(t - tw - eta * rise(t).0) };
        let tm = self.jc.tm_c.min(self.material.melting_c);
        let (tol, cap) = (self.options.temperature_tolerance_c, self.options.max_bracket_iterations);
        let what = "primary-zone temperature T_AB";
        let hint = self.hints.ab_c.get();
        let t_ab = match try_hint(f, if hint.is_finite() { hint } else { tw + 300.0 }, tw, tm, tol) {
            Some(t) => t,
            None => {
                let f_lo = f(tw)?;
                let f_hi = f(tm)?;
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
        self.hints.ab_c.set(t_ab);
        let (d_t_sz, k_ab, beta, beta_outside) = rise(t_ab);
        if !(k_ab > 0.0) {
            return Err(ModelError::AboveMelting {
                what: "primary-zone temperature T_AB".into(),
                temperature_c: t_ab,
                melting_c: tm,
            });
        }
        // Equivalent hardening index n_eq = n B eps^n / (A + B eps^n) (Lalwani et al. 2009, Sec. 2).
        let hard = self.jc.hardening(strain);
        let n_eq =
            if strain > 0.0 && hard > 0.0 { self.jc.n * self.jc.b_pa * strain.powf(self.jc.n) / hard } else { 0.0 };
        // Direction of the resultant: tan(theta) = 1 + 2 (pi/4 - phi) - C0 n_eq (Oxley 1989, Sec. 4.2).
        let tan_theta = 1.0 + 2.0 * (FRAC_PI_4 - phi_rad) - c0 * n_eq;
        let theta = tan_theta.atan();
        // Friction angle lambda = theta - phi + alpha (Oxley 1989, Sec. 4.2).
        let lambda = theta - phi_rad + alpha;
        if !(lambda > 0.0 && lambda < FRAC_PI_2) {
            return Err(ModelError::out_of_range(
                "friction angle lambda (deg)",
                lambda.to_degrees(),
                format!("0 < lambda < 90 deg at phi {:.3} deg, C0 {c0:.3}", phi_rad.to_degrees()),
            ));
        }
        // Forces per unit width: F_s = k_AB l_AB, R = F_s / cos(theta), F = R sin(lambda),
        // N = R cos(lambda), F_c = R cos(lambda - alpha), F_t = R sin(lambda - alpha) (Oxley 1989, Sec. 4.2).
        let f_s = k_ab * l_ab;
        let r = f_s / theta.cos();
        let (f_c, f_t) = (r * (lambda - alpha).cos(), r * (lambda - alpha).sin());
        let (fr, nr) = (r * lambda.sin(), r * lambda.cos());
        // Chip thickness t2 = t1 cos(phi - alpha) / sin(phi) (Oxley 1989, Sec. 4.2).
        let t2 = t1 * cos_pa / sin_phi;
        // Tool-chip contact length h = t1 sin(theta) / (cos(lambda) sin(phi)) [1 + C0 n_eq / (3 tan(theta))]
        // (Lalwani et al. 2009, Sec. 2; Oxley 1989, Sec. 4.2).
        let h = t1 * theta.sin() / (lambda.cos() * sin_phi) * (1.0 + c0 * n_eq / (3.0 * tan_theta));
        if !(h.is_finite() && h > 0.0) {
            return Err(ModelError::out_of_range(
                "tool-chip contact length h (m)",
                h,
                format!("h > 0 at phi {:.3} deg, C0 {c0:.3}", phi_rad.to_degrees()),
            ));
        }
        // Normal stress at B from the stress distribution along AB:
        // sigma_N' = k_AB (1 + pi/2 - 2 alpha - 2 C0 n_eq) (Lalwani et al. 2009, Sec. 2).
        let sigma_n_prime = k_ab * (1.0 + FRAC_PI_2 - 2.0 * alpha - 2.0 * c0 * n_eq);
        Ok(PrimaryZone {
            phi_rad,
            c0,
            shear_plane_length_m: l_ab,
            chip_velocity_m_per_s: v_c,
            strain,
            strain_rate_per_s: strain_rate,
            temperature_c: t_ab,
            temperature_rise_sz_c: d_t_sz,
            shear_flow_stress_pa: k_ab,
            heat_partition: beta,
            beta_outside_correlation: beta_outside,
            n_eq,
            theta_rad: theta,
            lambda_rad: lambda,
            shear_force_n_per_m: f_s,
            cutting_force_n_per_m: f_c,
            feed_force_n_per_m: f_t,
            friction_force_n_per_m: fr,
            normal_force_n_per_m: nr,
            chip_thickness_m: t2,
            contact_length_m: h,
            model_normal_stress_pa: sigma_n_prime,
        })
    }

    /// The tool-chip interface at `delta` for a given primary zone.
    ///
    /// Returns an error only if the bracketed T_C solve fails its iteration cap.
    pub fn interface(&self, p: &PrimaryZone, delta: f64) -> Result<InterfaceZone, ModelError> {
        let c = self.conditions;
        let (alpha, v, t1, tw) = (c.rake_rad, c.speed_m_per_s, c.uncut_chip_thickness_m, c.work_temperature_c);
        let (t2, h) = (p.chip_thickness_m, p.contact_length_m);
        let cos_pa = (p.phi_rad - alpha).cos();
        // Mean chip temperature T_C = T_w + dT_SZ + dT_C with dT_C = F sin(phi) / (rho Cp t1 w cos(phi - alpha))
        // and rho Cp at T_C (Oxley 1989, Sec. 4.3: the chip is heated by the whole primary-zone rise
        // and the mean secondary-zone rise), solved on [T_w + dT_SZ, top of the property range].
        // The function is increasing in T_C (rho Cp grows or is held), so the root is unique.
        let base = tw + p.temperature_rise_sz_c;
        let d_t_c_at = |t: f64| -> f64 {
            let (rho_cp, _) = self.thermal(t);
            p.friction_force_n_per_m * p.phi_rad.sin() / (rho_cp * t1 * cos_pa)
        };
        let g = |t: f64| -> Result<f64, ModelError> { Ok(t - base - d_t_c_at(t)) };
        let top = self.material.thermal.valid_to_c;
        let (tol, cap) = (self.options.temperature_tolerance_c, self.options.max_bracket_iterations);
        let what = "mean chip temperature T_C";
        let t_c = if top <= base {
            base + d_t_c_at(top)
        } else if let Some(t) = try_hint(g, self.hints.int_c.get(), base, top, tol) {
            t
        } else {
            let g_hi = g(top)?;
            if g_hi <= 0.0 {
                // Above the property range the properties are held constant: closed form.
                base + d_t_c_at(top)
            } else {
                let g_lo = g(base)?;
                brent_root(g, base, top, g_lo, g_hi, tol, cap, what)?
            }
        };
        self.hints.int_c.set(t_c);
        // Maximum interface rise log10(dT_M / dT_C) = 0.06 - 0.195 delta sqrt(R_T t2 / h) + 0.5 log10(R_T t2 / h),
        // with the thermal number R_T = rho Cp V t1 / K of the chip at T_C, and the mean interface
        // temperature T_int = T_w + dT_SZ + psi dT_M (Oxley 1989, Sec. 4.3; Lalwani et al. 2009, Sec. 2).
        // Evaluating rho Cp and K at T_C, not at T_int, is what the independent implementation
        // pantale/OxleyPython does and what reproduces Lalwani's delta and T_int (docs/oxley.md).
        let (rho_cp, cond) = self.thermal(t_c);
        let d_t_c = d_t_c_at(t_c);
        let rt = rho_cp * v * t1 / cond;
        let gr = rt * t2 / h;
        let d_t_m = d_t_c * 10f64.powf(0.06 - 0.195 * delta * gr.sqrt() + 0.5 * gr.log10());
        let t_int = base + self.options.psi * d_t_m;
        // Interface strain rate epsdot_int = V_c / (sqrt(3) delta t2) and strain
        // eps_int = 2 eps_AB + 0.5 h / (sqrt(3) delta t2) (Lalwani et al. 2009, Sec. 2).
        let strain_rate = p.chip_velocity_m_per_s / (SQRT3 * delta * t2);
        let strain = 2.0 * p.strain + 0.5 * h / (SQRT3 * delta * t2);
        let k_chip = (self.flow_stress_pa(strain, strain_rate, t_int) / SQRT3).max(0.0);
        Ok(InterfaceZone {
            delta,
            strain,
            strain_rate_per_s: strain_rate,
            temperature_c: t_int,
            shear_flow_stress_pa: k_chip,
            // Interface stresses from the force system: tau_int = F / (h w), sigma_N = N / (h w)
            // (Oxley 1989, Sec. 4.2).
            shear_stress_pa: p.friction_force_n_per_m / h,
            normal_stress_pa: p.normal_force_n_per_m / h,
        })
    }

    /// Full state at (phi, C0, delta) with the two residuals.
    pub fn state(&self, phi_rad: f64, c0: f64, delta: f64) -> Result<State, ModelError> {
        let primary = self.primary(phi_rad, c0)?;
        self.state_from(primary, delta)
    }

    /// Full state from an already computed primary zone.
    pub fn state_from(&self, primary: PrimaryZone, delta: f64) -> Result<State, ModelError> {
        let interface = self.interface(&primary, delta)?;
        let k_ab = primary.shear_flow_stress_pa;
        let m_f = self.physics.interface_friction_factor;
        let residual_shear = (interface.shear_stress_pa - m_f * interface.shear_flow_stress_pa) / k_ab;
        let residual_normal = (interface.normal_stress_pa - primary.model_normal_stress_pa) / k_ab;
        if !(residual_shear.is_finite() && residual_normal.is_finite()) {
            return Err(ModelError::out_of_range(
                "Oxley equilibrium residual",
                if residual_shear.is_finite() { residual_normal } else { residual_shear },
                "a finite number",
            ));
        }
        Ok(State { primary, interface, residual_shear, residual_normal })
    }
}
