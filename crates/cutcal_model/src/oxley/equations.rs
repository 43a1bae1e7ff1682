//! The closed-form relations of the extended Oxley model: the primary zone at a shear angle phi
//! (with C0 from the closed-form sigma_N balance, which does not depend on delta), its chip
//! temperature, and the tool-chip interface at any delta in closed form from them. The two
//! temperature fixed points are in `temperatures.rs`.
//!
//! Sources: Oxley, *Mechanics of Machining* (1989), Ch. 4 (the parallel-sided primary zone, the
//! tool-chip interface, the temperature models); Lalwani, Mehta & Jain 2009, Sec. 2 (the same
//! relations with the Johnson-Cook law and the equivalent hardening index n_eq). The equations are
//! cited by quantity and section; the symbols follow Lalwani et al. 2009.

use std::cell::Cell;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, LN_10};

use crate::error::{ModelError, NoC0};
use crate::jc::JcParams;
use crate::material::Material;

use super::options::{CuttingConditions, OxleyOptions, Physics};

pub(crate) const SQRT3: f64 = 1.732_050_807_568_877_2;

/// 10^0.06, the constant of Oxley's interface-temperature relation (Oxley 1989, Sec. 4.3).
const TEN_POW_0_06: f64 = 1.148_153_621_496_882_8;

/// Everything the relations need, borrowed.
#[derive(Clone, Copy)]
pub(crate) struct Context<'a> {
    pub material: &'a Material,
    pub jc: &'a JcParams,
    pub conditions: &'a CuttingConditions,
    pub options: &'a OxleyOptions,
    pub physics: &'a Physics,
    /// Last temperatures solved (NaN: none), the starting points of the Newton solves.
    pub hints: &'a TemperatureHints,
}

/// The last two T_AB and T_C solved with their phi, `(phi, T)` in rad and degC, newest last (NaN:
/// none). Only a starting point: the start at a new phi is their linear extrapolation in phi, and the
/// root is the same to the temperature tolerance whatever the start (the bracketing fallback covers
/// the whole interval).
#[derive(Debug)]
pub(crate) struct TemperatureHints {
    pub ab: Cell<[(f64, f64); 2]>,
    pub chip: Cell<[(f64, f64); 2]>,
}

impl TemperatureHints {
    pub fn none() -> Self {
        Self { ab: Cell::new([(f64::NAN, f64::NAN); 2]), chip: Cell::new([(f64::NAN, f64::NAN); 2]) }
    }

    /// Forgets every hint.
    pub fn reset(&self) {
        self.ab.set([(f64::NAN, f64::NAN); 2]);
        self.chip.set([(f64::NAN, f64::NAN); 2]);
    }

    /// The starting temperature at `phi` from a hint pair: linear extrapolation in phi, kept within
    /// 200 K of the newest; the newest alone if the pair is degenerate; `fallback` without hints.
    pub fn start(pair: [(f64, f64); 2], phi: f64, fallback: f64) -> f64 {
        let [(p0, t0), (p1, t1)] = pair;
        if !t1.is_finite() {
            return fallback;
        }
        let t = t1 + (t1 - t0) / (p1 - p0) * (phi - p1);
        if t.is_finite() && (t - t1).abs() <= 200.0 {
            t
        } else {
            t1
        }
    }

    /// Records a solved temperature at phi.
    pub fn push(cell: &Cell<[(f64, f64); 2]>, phi: f64, t: f64) {
        let [_, newest] = cell.get();
        if newest.0.to_bits() != phi.to_bits() {
            cell.set([newest, (phi, t)]);
        }
    }
}

/// The delta-independent part of the tool-chip interface, fixed by the primary zone:
/// `T_int(delta) = base + amplitude exp(-decay delta)`, `eps_int = 2 eps_AB + strain_coef/delta`,
/// `epsdot_int = rate_coef/delta`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChipHeat {
    /// T_w + dT_SZ, degC.
    pub base_c: f64,
    /// psi dT_C 10^0.06 sqrt(R_T t2/h), K.
    pub amplitude_c: f64,
    /// 0.195 ln(10) sqrt(R_T t2/h).
    pub decay: f64,
    /// 0.5 h / (sqrt3 t2).
    pub strain_coef: f64,
    /// V_c / (sqrt3 t2), 1/s.
    pub rate_coef_per_s: f64,
}

/// The primary zone and the force system at (phi, C0).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PrimaryZone {
    pub phi_rad: f64,
    pub c0: f64,
    pub shear_plane_length_m: f64,
    pub strain: f64,
    pub strain_rate_per_s: f64,
    pub temperature_c: f64,
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
    /// What the interface needs, fixed by this primary zone.
    pub chip: ChipHeat,
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
        let (rho_cp, _, k, _) = self.thermal_d(temperature_c);
        (rho_cp, k)
    }

    /// Johnson-Cook flow stress with the thermal-softening hook: evaluated at
    /// `T_w + kappa_T (T - T_w)` (kappa_T = 1: Lalwani et al. 2009, Sec. 2).
    fn flow_stress_pa(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        // (A + B eps^n)(1 + C ln(epsdot/eps0)) (paper Eq 16) times 1 - theta^m (Eq 14, with the
        // hook inside `softening_d`): the same as `JcParams::flow_stress` at the scaled temperature.
        self.jc.hardening(strain) * self.jc.rate_factor(strain_rate_per_s) * self.softening_d(temperature_c).0
    }

    /// C0 solving the normal-stress condition `sigma_N = N/(h w) = sigma_N'` at phi, in closed form.
    ///
    /// With `u = C0 n_eq`, `tan(theta) = T0 - u`, `T0 = 1 + 2 (pi/4 - phi)`, `psi = phi - a` and
    /// `K = 1 + pi/2 - 2a`, the relations of Oxley 1989 Sec. 4.2 / Lalwani et al. 2009 Sec. 2
    /// (N = k_AB l_AB cos(lambda)/cos(theta), h = t1 sin(theta)/(cos(lambda) sin(phi)) (1 + u/(3 tan theta)),
    /// sigma_N' = k_AB (K - 2u), lambda = theta - psi) give, with k_AB cancelling,
    /// `N/(h w k_AB) = 3 (cos psi + tan(theta) sin psi)^2 / (3 tan(theta) + u)`, so the condition is the
    /// quadratic `3 (A - u sin psi)^2 + (2u - K)(3 T0 - 2u) = 0`, `A = cos psi + T0 sin psi`
    /// (derivation in docs/oxley.md). It does not depend on delta or on any temperature.
    /// Of the roots with C0 in the range and an admissible geometry (0 < lambda < 90 deg, h > 0),
    /// the smaller C0 is returned.
    pub fn c0_for_phi(&self, phi_rad: f64, n_eq: f64, s_psi: f64, c_psi: f64) -> Result<f64, ModelError> {
        let alpha = self.conditions.rake_rad;
        let [clo, chi] = self.options.c0_range;
        let fail = |why: NoC0| ModelError::NoAdmissibleC0 { phi_deg: phi_rad.to_degrees(), low: clo, high: chi, why };
        if !(n_eq > 0.0) {
            return Err(fail(NoC0::NoHardening));
        }
        let t0 = 1.0 + 2.0 * (FRAC_PI_4 - phi_rad);
        let k = 1.0 + FRAC_PI_2 - 2.0 * alpha;
        let a = c_psi + t0 * s_psi;
        let (a2, a1, a0) =
            (3.0 * s_psi * s_psi - 4.0, 6.0 * t0 - 6.0 * a * s_psi + 2.0 * k, 3.0 * a * a - 3.0 * k * t0);
        let disc = a1 * a1 - 4.0 * a2 * a0;
        if !(disc >= 0.0) {
            return Err(fail(NoC0::NoRealRoot));
        }
        // Stable quadratic roots (a2 < 0 always, so the quadratic never degenerates).
        let q = -0.5 * (a1 + disc.sqrt().copysign(a1));
        let roots = [q / a2, if q == 0.0 { f64::NAN } else { a0 / q }];
        let admissible = |u: f64| -> bool {
            let c0 = u / n_eq;
            let tan_theta = t0 - u;
            // 0 < lambda = theta - psi < 90 deg without an arctangent: with cos(theta) > 0,
            // sin(lambda) = cos(theta) (tan(theta) cos psi - sin psi) and
            // cos(lambda) = cos(theta) (cos psi + tan(theta) sin psi) must both be positive
            // (lambda lies in (-225, 135) deg for phi in (0, 90) and |a| < 45 deg).
            let lambda_ok = tan_theta * c_psi - s_psi > 0.0 && c_psi + tan_theta * s_psi > 0.0;
            // h > 0: sin(theta) has the sign of tan(theta) and cos(lambda) > 0 here.
            let h_factor = (3.0 * tan_theta + u) / 3.0;
            c0 >= clo && c0 <= chi && lambda_ok && h_factor > 0.0
        };
        let best = roots.iter().copied().filter(|u| u.is_finite() && admissible(*u)).map(|u| u / n_eq).reduce(f64::min);
        best.ok_or_else(|| fail(NoC0::Inadmissible(roots.map(|u| if u.is_finite() { u / n_eq } else { f64::NAN }))))
    }

    /// The primary zone, the force system and the chip temperature at phi, with C0 from
    /// [`Context::c0_for_phi`] (the only C0 that satisfies the normal-stress condition there).
    ///
    /// Returns an error if no C0 in the range satisfies it, if the state is non-physical (a
    /// non-positive flow stress at the work temperature, a friction angle outside (0, 90) deg, a
    /// non-positive contact length) or the temperature at AB reaches melting with thermal softening
    /// switched off.
    pub fn primary(&self, phi_rad: f64) -> Result<PrimaryZone, ModelError> {
        let c = self.conditions;
        let (alpha, v, t1, tw) = (c.rake_rad, c.speed_m_per_s, c.uncut_chip_thickness_m, c.work_temperature_c);
        // sin/cos of phi, alpha and phi - alpha (angle addition; no repeated trigonometric calls).
        let (sin_phi, cos_phi) = phi_rad.sin_cos();
        let (sin_a, cos_a) = alpha.sin_cos();
        let cos_pa = cos_phi * cos_a + sin_phi * sin_a;
        let sin_pa = sin_phi * cos_a - cos_phi * sin_a;
        // Strain at AB: gamma_AB = cos(alpha) / (2 sin(phi) cos(phi - alpha)), eps_AB = gamma_AB / sqrt(3)
        // (Lalwani et al. 2009, Sec. 2).
        let gamma_ab = cos_a / (2.0 * sin_phi * cos_pa);
        let strain = gamma_ab / SQRT3;
        // Equivalent hardening index n_eq = n B eps^n / (A + B eps^n) (Lalwani et al. 2009, Sec. 2).
        let b_en = self.jc.b_pa * strain.powf(self.jc.n);
        let hard = self.jc.a_pa + b_en;
        let n_eq = if strain > 0.0 && hard > 0.0 { self.jc.n * b_en / hard } else { 0.0 };
        // C0 of the normal-stress condition, times the emulation scale (`Physics::c0_scale`, 1 = Oxley).
        let c0 = self.c0_for_phi(phi_rad, n_eq, sin_pa, cos_pa)? * self.physics.c0_scale;
        // Shear-plane length l_AB = t1 / sin(phi) (Lalwani et al. 2009, Sec. 2).
        let l_ab = t1 / sin_phi;
        // Shear velocity V_s = V cos(alpha)/cos(phi - alpha); chip velocity V_c = V sin(phi)/cos(phi - alpha)
        // (Oxley 1989, Sec. 4.2, hodograph).
        let v_s = v * cos_a / cos_pa;
        let v_c = v * sin_phi / cos_pa;
        // Strain rate at AB: epsdot_AB = C0 V_s / (sqrt(3) l_AB) (Lalwani et al. 2009, Sec. 2).
        let strain_rate = c0 * v_s / (SQRT3 * l_ab);
        // The athermal part (A + B eps^n)(1 + C ln epsdot) is fixed at (phi, C0): evaluated once.
        let athermal = hard * self.jc.rate_factor(strain_rate);
        let tan_phi = sin_phi / cos_phi;
        let k_at_work = athermal * self.softening_d(tw).0 / SQRT3;
        if !(k_at_work.is_finite() && k_at_work > 0.0) {
            return Err(ModelError::out_of_range(
                "primary-zone flow stress at the work temperature (Pa)",
                k_at_work * SQRT3,
                format!("a positive JC stress (strain {strain:.3}, strain rate {strain_rate:.3e} 1/s)"),
            ));
        }
        // T_AB = T_w + eta dT_SZ (Oxley 1989, Sec. 4.3), solved in temperatures.rs.
        let ab = self.solve_t_ab(phi_rad, athermal, cos_a / (sin_phi * cos_pa), tan_phi)?;
        let (t_ab, d_t_sz, k_ab) = (ab.t_ab_c, ab.rise_sz_c, ab.k_ab_pa);
        let tm = self.jc.tm_c.min(self.material.melting_c);
        if !(k_ab > 0.0) {
            return Err(ModelError::AboveMelting {
                what: "primary-zone temperature T_AB".into(),
                temperature_c: t_ab,
                melting_c: tm,
            });
        }
        // Direction of the resultant: tan(theta) = 1 + 2(pi/4 - phi) - C0 n_eq (Oxley 1989, Sec. 4.2).
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
        // Trigonometry of theta, lambda = theta - (phi - alpha) and lambda - alpha = theta - phi by
        // angle addition from tan(theta).
        let cos_theta = 1.0 / (1.0 + tan_theta * tan_theta).sqrt();
        let sin_theta = tan_theta * cos_theta;
        let r = f_s / cos_theta;
        let (sin_la, cos_la) = (sin_theta * cos_phi - cos_theta * sin_phi, cos_theta * cos_phi + sin_theta * sin_phi);
        let (sin_l, cos_l) = (sin_theta * cos_pa - cos_theta * sin_pa, cos_theta * cos_pa + sin_theta * sin_pa);
        let (f_c, f_t) = (r * cos_la, r * sin_la);
        let (fr, nr) = (r * sin_l, r * cos_l);
        // Chip thickness t2 = t1 cos(phi - alpha) / sin(phi) (Oxley 1989, Sec. 4.2).
        let t2 = t1 * cos_pa / sin_phi;
        // Tool-chip contact length h = t1 sin(theta) / (cos(lambda) sin(phi)) [1 + C0 n_eq / (3 tan(theta))]
        // (Lalwani et al. 2009, Sec. 2; Oxley 1989, Sec. 4.2).
        let h = t1 * sin_theta / (cos_l * sin_phi) * (1.0 + c0 * n_eq / (3.0 * tan_theta));
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
        // Mean chip temperature T_C = T_w + dT_SZ + dT_C, dT_C = F sin(phi) / (rho Cp(T_C) t1 cos(phi - a))
        // (Oxley 1989, Sec. 4.3), solved in temperatures.rs. It does not depend on delta.
        let base = tw + d_t_sz;
        let (t_c, d_t_c) = self.solve_t_c(phi_rad, base, fr * sin_phi / (t1 * cos_pa))?;
        // Maximum interface rise log10(dT_M / dT_C) = 0.06 - 0.195 delta sqrt(R_T t2 / h) + 0.5 log10(R_T t2 / h),
        // with the thermal number R_T = rho Cp V t1 / K of the chip at T_C (Oxley 1989, Sec. 4.3;
        // Lalwani et al. 2009, Sec. 2), written as dT_M = dT_C 10^0.06 sqrt(R_T t2/h) exp(-0.195 ln10 sqrt(R_T t2/h) delta).
        // Evaluating rho Cp and K at T_C, not at T_int, is what the independent implementation
        // pantale/OxleyPython does and what reproduces Lalwani's delta and T_int (docs/oxley.md).
        let (rho_cp, cond) = self.thermal(t_c);
        let gr_sqrt = (rho_cp * v * t1 / cond * t2 / h).sqrt();
        let chip = ChipHeat {
            base_c: base,
            amplitude_c: self.options.psi * self.physics.interface_heat_share * d_t_c * TEN_POW_0_06 * gr_sqrt,
            decay: 0.195 * LN_10 * gr_sqrt,
            strain_coef: 0.5 * h / (SQRT3 * t2),
            rate_coef_per_s: v_c / (SQRT3 * t2),
        };
        Ok(PrimaryZone {
            phi_rad,
            c0,
            shear_plane_length_m: l_ab,
            strain,
            strain_rate_per_s: strain_rate,
            temperature_c: t_ab,
            shear_flow_stress_pa: k_ab,
            heat_partition: ab.beta,
            beta_outside_correlation: ab.beta_outside,
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
            // With an emulation scale on C0 the normal-stress condition is replaced by
            // C0 = s_C0 C0_Oxley(phi), met by construction: sigma_N' is then reported as the
            // force system's sigma_N, so that the condition's residual is zero.
            model_normal_stress_pa: if (self.physics.c0_scale - 1.0).abs() < 1e-12 { sigma_n_prime } else { nr / h },
            chip,
        })
    }

    /// The tool-chip interface at `delta` for a given primary zone, in closed form (Oxley 1989,
    /// Sec. 4.3; Lalwani et al. 2009, Sec. 2): `T_int = T_w + dT_SZ + psi dT_M`,
    /// `epsdot_int = V_c/(sqrt3 delta t2)`, `eps_int = 2 eps_AB + 0.5 h/(sqrt3 delta t2)`,
    /// `k_chip = sigma_JC(eps_int, epsdot_int, T_int)/sqrt3`.
    pub fn interface(&self, p: &PrimaryZone, delta: f64) -> InterfaceZone {
        let ch = &p.chip;
        let t_int = ch.base_c + ch.amplitude_c * (-ch.decay * delta).exp();
        let strain_rate = ch.rate_coef_per_s / delta;
        let strain = 2.0 * p.strain + ch.strain_coef / delta;
        let k_chip = (self.flow_stress_pa(strain, strain_rate, t_int) / SQRT3).max(0.0);
        InterfaceZone {
            delta,
            strain,
            strain_rate_per_s: strain_rate,
            temperature_c: t_int,
            shear_flow_stress_pa: k_chip,
            // Interface stresses from the force system: tau_int = F / (h w), sigma_N = N / (h w)
            // (Oxley 1989, Sec. 4.2).
            shear_stress_pa: p.friction_force_n_per_m / p.contact_length_m,
            normal_stress_pa: p.normal_force_n_per_m / p.contact_length_m,
        }
    }

    /// `d ln k_chip / d ln delta` at fixed primary zone: the derivative of the closed form of
    /// [`Context::interface`] (JC law, paper Eqs 14 and 16, differentiated term by term; the rate term
    /// is 1 with zero slope at or below eps0). Zero where Fc(delta) is stationary (see minimum.rs).
    pub fn chip_log_slope(&self, p: &PrimaryZone, delta: f64) -> f64 {
        let (jc, ch) = (self.jc, &p.chip);
        let strain = 2.0 * p.strain + ch.strain_coef / delta;
        let en1 = strain.powf(jc.n - 1.0);
        let hard = jc.a_pa + jc.b_pa * en1 * strain;
        let d_hard = jc.b_pa * jc.n * en1 * (-ch.strain_coef / delta);
        let rate = ch.rate_coef_per_s / delta;
        let (rf, d_rf) =
            if rate > jc.eps0_per_s { (1.0 + jc.c * (rate / jc.eps0_per_s).ln(), -jc.c) } else { (1.0, 0.0) };
        let e = ch.amplitude_c * (-ch.decay * delta).exp();
        let (g, dg) = self.softening_d(ch.base_c + e);
        let d_t = -ch.decay * delta * e;
        d_hard / hard + d_rf / rf + dg * d_t / g
    }

    /// Full state from a primary zone at delta, with the two residuals.
    pub fn state_from(&self, primary: PrimaryZone, delta: f64) -> Result<State, ModelError> {
        let interface = self.interface(&primary, delta);
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
