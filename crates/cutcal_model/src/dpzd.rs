//! The distributed primary zone deformation (DPZD) model, original and thermomechanically
//! enhanced (paper Sec 3, Eqs 2-12, Sec 3.5).
//!
//! Given the shear angle and the shear-plane stress of one cutting test, the model returns the
//! fields across the primary shear zone: shear strain and strain rate (Eqs 2, 5), the piecewise
//! linear shear stress (Eq 8) and the adiabatic temperature (Eqs 11-12). The enhanced model makes
//! the exit shear strength depend on the exit temperature and resolves the coupling by the fixed
//! point of Sec 3.5.

use serde::{Deserialize, Serialize};

use crate::cutting_test::CuttingTest;
use crate::error::ModelError;
use crate::heating::AdiabaticHeating;
use crate::kinematics;
use crate::material::Material;
use crate::poly::TempPolynomial;

/// Which DPZD model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "variant", rename_all = "snake_case")]
pub enum DpzdVariant {
    /// Thermally uncoupled model of Shi et al.: `tau0 = sigma0(Tr)/sqrt(3)` at CD and EF and a
    /// constant volumetric heat capacity.
    ///
    /// The paper does not print the constant; 3.5325e6 J/(m^3 K) (7.85 g/cm^3 x 0.45 J/(g K))
    /// reproduces Table 4. Reading it as rho(20) Cp(20) of Table 3 (2.19e6) drives C to 0 and B to
    /// ~1000 MPa and cannot give Table 4.
    Original {
        /// Constant rho*Cp, J/(m^3 K).
        rho_cp_j_per_m3_k: f64,
    },
    /// Thermomechanically enhanced model: `tau0(T)` at the entry (CD) and exit (EF) temperatures,
    /// rho(T) Cp(T) of Table 3, coupled by the fixed point of Sec 3.5.
    Enhanced {
        /// Convergence tolerance on the exit temperature, K.
        tolerance_c: f64,
        /// Iteration cap.
        max_iterations: usize,
    },
}

/// Zone geometry and model choice.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DpzdConfig {
    /// Primary shear zone thickness h, m.
    pub zone_thickness_m: f64,
    /// Strain-rate distribution exponent r (paper Eq 2).
    pub r: f64,
    /// Model variant.
    pub variant: DpzdVariant,
}

impl DpzdConfig {
    /// Validating constructor: `0 < h <= 1 mm`, `0 < r <= 20`, positive rho*Cp / tolerance, cap >= 1.
    pub fn new(zone_thickness_m: f64, r: f64, variant: DpzdVariant) -> Result<Self, ModelError> {
        crate::error::check_range("zone_thickness_m", zone_thickness_m, 0.0, 1e-3, "0 < h <= 1e-3 m")?;
        crate::error::check_range("r", r, 0.0, 20.0, "0 < r <= 20")?;
        match variant {
            DpzdVariant::Original { rho_cp_j_per_m3_k } => {
                crate::error::check_range(
                    "rho_cp_j_per_m3_k",
                    rho_cp_j_per_m3_k,
                    1e5,
                    1e8,
                    "1e5 < rho*Cp <= 1e8 J/(m^3 K)",
                )?;
            }
            DpzdVariant::Enhanced { tolerance_c, max_iterations } => {
                crate::error::check_range("tolerance_c", tolerance_c, 0.0, 10.0, "0 < tol <= 10 K")?;
                if max_iterations == 0 || max_iterations > 10_000 {
                    return Err(ModelError::out_of_range("max_iterations", max_iterations as f64, "1..=10000"));
                }
            }
        }
        Ok(Self { zone_thickness_m, r, variant })
    }
}

/// The measured state that drives the DPZD model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShearPlaneState {
    /// Cutting speed V, m/s.
    pub speed_m_per_s: f64,
    /// Rake angle alpha, rad.
    pub rake_rad: f64,
    /// Shear angle phi, rad.
    pub shear_angle_rad: f64,
    /// Maximum shear stress on AB, Pa (Eq 9).
    pub tau_max_pa: f64,
}

impl ShearPlaneState {
    /// From a test with measured forces and chip thickness (shear angle from the chip ratio, Eq 9).
    ///
    /// Returns an error if a measurement is missing or gives no admissible state.
    pub fn from_test(test: &CuttingTest) -> Result<Self, ModelError> {
        let missing = |what: &str| {
            ModelError::Inconsistent(format!("{what} is not measured (the DPZD model needs Fc, Ft and tc)"))
        };
        let fc = test.measured.cutting_force_n_per_m.ok_or_else(|| missing("cutting force"))?;
        let ft = test.measured.feed_force_n_per_m.ok_or_else(|| missing("feed force"))?;
        let tc = test.measured.chip_thickness_m.ok_or_else(|| missing("chip thickness"))?;
        let phi = kinematics::shear_angle_from_chip(test.uncut_chip_thickness_m, tc, test.rake_rad)?;
        let tau_max_pa = kinematics::tau_max_from_forces(fc, ft, phi, test.uncut_chip_thickness_m)?;
        Ok(Self { speed_m_per_s: test.speed_m_per_s, rake_rad: test.rake_rad, shear_angle_rad: phi, tau_max_pa })
    }

    /// Checks a state built by hand (the fields are public): `0 < V <= 200 m/s`,
    /// `-45 deg < alpha < 45 deg`, `0 < phi < 90 deg`, `tau_max > 0` finite.
    ///
    /// Returns an error naming the first field out of range (found by fuzzing: a denormal negative
    /// shear angle gave an exit temperature of -inf instead of an error).
    pub fn validate(&self) -> Result<(), ModelError> {
        crate::error::check_range("speed_m_per_s", self.speed_m_per_s, 0.0, 200.0, "0 < V <= 200 m/s")?;
        let lim = 45f64.to_radians();
        if !(self.rake_rad.is_finite() && self.rake_rad > -lim && self.rake_rad < lim) {
            return Err(ModelError::out_of_range("rake_rad", self.rake_rad, "-45 deg < alpha < 45 deg"));
        }
        let phi = self.shear_angle_rad;
        if !(phi.is_finite() && phi > 1e-6 && phi < std::f64::consts::FRAC_PI_2) {
            return Err(ModelError::out_of_range("shear_angle_rad", phi, "1e-6 < phi < pi/2 rad"));
        }
        crate::error::check_range("tau_max_pa", self.tau_max_pa, 0.0, 1e11, "0 < tau_max <= 1e11 Pa")?;
        Ok(())
    }
}

/// How the zone converts plastic work into temperature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
enum HeatCapacity {
    Constant {
        rho_cp_j_per_m3_k: f64,
    },
    Polynomial {
        rho_cp: TempPolynomial,
        /// Its inverse from room temperature (rebuilt on use when absent, after deserialising).
        #[serde(skip)]
        heating: Option<AdiabaticHeating>,
    },
}

/// One point of the zone fields.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ZonePoint {
    /// Position across the zone, m (EF at -h/2, AB at 0, CD at +h/2).
    pub x_m: f64,
    /// Shear strain gamma (Eq 5).
    pub gamma: f64,
    /// Shear strain rate, 1/s (Eq 2).
    pub gamma_dot_per_s: f64,
    /// Effective strain gamma/sqrt(3).
    pub strain: f64,
    /// Effective strain rate gammadot/sqrt(3), 1/s.
    pub strain_rate_per_s: f64,
    /// Shear stress tau_e, Pa (Eq 8).
    pub tau_pa: f64,
    /// Effective stress sqrt(3) tau_e, Pa (the identification target of Eq 15).
    pub effective_stress_pa: f64,
    /// Plastic work per unit volume accumulated from CD, J/m^3 (Eq 11).
    pub work_j_per_m3: f64,
    /// Temperature, degC (Eq 12).
    pub temperature_c: f64,
}

/// The solved primary shear zone of one test.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ZoneSolution {
    /// The configuration solved.
    pub config: DpzdConfig,
    /// The driving state.
    pub state: ShearPlaneState,
    /// Shear strain on AB (Eq 6).
    pub gamma_ab: f64,
    /// Shear strain rate on AB, 1/s (Eq 3).
    pub gamma_dot_ab_per_s: f64,
    /// Normal velocity V sin(phi), m/s.
    pub normal_velocity_m_per_s: f64,
    /// Shear strength at the entry CD, Pa.
    pub tau0_cd_pa: f64,
    /// Shear strength at the exit EF, Pa.
    pub tau0_ef_pa: f64,
    /// Entry (CD) temperature = room temperature, degC.
    pub t_cd_c: f64,
    /// Temperature on AB, degC.
    pub t_ab_c: f64,
    /// Exit (EF) temperature, degC.
    pub t_ef_c: f64,
    /// Fixed-point iterations (1 for the original model).
    pub iterations: usize,
    /// Exit temperature after each fixed-point iteration, degC.
    pub exit_temperature_history_c: Vec<f64>,
    heat: HeatCapacity,
    room_c: f64,
    melting_c: f64,
}

/// Solves the DPZD zone for one shear-plane state.
///
/// **Source:** paper Eqs 2-8, 11-12; enhanced fixed point Sec 3.5 (Fig 3).
///
/// Returns an error if the state is out of range ([`ShearPlaneState::validate`]), the material
/// has no yield law, `tau_max` does not exceed the entry shear
/// strength, a temperature reaches melting, or the fixed point does not converge within its cap.
pub fn solve(material: &Material, state: &ShearPlaneState, config: &DpzdConfig) -> Result<ZoneSolution, ModelError> {
    state.validate()?;
    let h = config.zone_thickness_m;
    let r = config.r;
    let phi = state.shear_angle_rad;
    let gamma_ab = kinematics::gamma_ab(phi, state.rake_rad);
    let gamma_dot_ab = kinematics::gamma_dot_ab(state.speed_m_per_s, h, r, phi, state.rake_rad);
    let vn = state.speed_m_per_s * phi.sin();
    let room = material.room_c;
    let tau0_cd = material.yield_strength_pa(room)? / 3f64.sqrt();
    if state.tau_max_pa <= tau0_cd {
        return Err(ModelError::Inconsistent(format!(
            "tau_max = {:.1} MPa from the forces does not exceed the entry shear strength sigma0(Tr)/sqrt(3) = {:.1} MPa: the DPZD stress field (Eq 8) needs its maximum on AB",
            state.tau_max_pa / 1e6,
            tau0_cd / 1e6
        )));
    }
    let heat = match config.variant {
        DpzdVariant::Original { rho_cp_j_per_m3_k } => HeatCapacity::Constant { rho_cp_j_per_m3_k },
        DpzdVariant::Enhanced { .. } => HeatCapacity::Polynomial {
            rho_cp: material.thermal.rho_cp.clone(),
            heating: Some(AdiabaticHeating::new(material.thermal.rho_cp.clone(), material.room_c, material.melting_c)),
        },
    };
    let mut sol = ZoneSolution {
        config: *config,
        state: *state,
        gamma_ab,
        gamma_dot_ab_per_s: gamma_dot_ab,
        normal_velocity_m_per_s: vn,
        tau0_cd_pa: tau0_cd,
        tau0_ef_pa: tau0_cd,
        t_cd_c: room,
        t_ab_c: room,
        t_ef_c: room,
        iterations: 1,
        exit_temperature_history_c: Vec::new(),
        heat,
        room_c: room,
        melting_c: material.melting_c,
    };
    match config.variant {
        DpzdVariant::Original { .. } => {
            sol.t_ef_c = sol.temperature_from_work(sol.total_work_j_per_m3(), "exit (EF) temperature")?;
            sol.exit_temperature_history_c.push(sol.t_ef_c);
        }
        DpzdVariant::Enhanced { tolerance_c, max_iterations } => {
            // Sec 3.5: start from T* = Tr, update tau0(T*) at EF, recompute T, repeat.
            let mut t_star = room;
            let mut converged = false;
            let mut last_change = f64::INFINITY;
            for it in 1..=max_iterations {
                sol.tau0_ef_pa = material.yield_strength_pa(t_star)? / 3f64.sqrt();
                let t_new = sol.temperature_from_work(sol.total_work_j_per_m3(), "exit (EF) temperature")?;
                sol.exit_temperature_history_c.push(t_new);
                last_change = (t_new - t_star).abs();
                t_star = t_new;
                sol.iterations = it;
                if last_change < tolerance_c {
                    converged = true;
                    break;
                }
            }
            if !converged {
                return Err(ModelError::NoConvergence {
                    what: "enhanced DPZD fixed point (Sec 3.5)".into(),
                    iterations: max_iterations,
                    last_change,
                    tolerance: tolerance_c,
                });
            }
            sol.tau0_ef_pa = material.yield_strength_pa(t_star)? / 3f64.sqrt();
            sol.t_ef_c = sol.temperature_from_work(sol.total_work_j_per_m3(), "exit (EF) temperature")?;
        }
    }
    sol.t_ab_c = sol.temperature_from_work(sol.work_j_per_m3(0.0), "shear-plane (AB) temperature")?;
    Ok(sol)
}

impl ZoneSolution {
    /// `K = (h/2) gammadot_AB / V_n = gamma_AB (r+1)`: converts the Eq 2 shape integrals into strain.
    fn strain_scale(&self) -> f64 {
        self.gamma_ab * (self.config.r + 1.0)
    }

    /// Shear stress at `x`, Pa (paper Eq 8).
    #[must_use]
    pub fn tau_pa(&self, x_m: f64) -> f64 {
        let u = kinematics::distance_to_boundary(x_m, self.config.zone_thickness_m);
        let tau0 = if x_m >= 0.0 { self.tau0_cd_pa } else { self.tau0_ef_pa };
        tau0 + (self.state.tau_max_pa - tau0) * u
    }

    /// Plastic work per unit volume `int tau dgamma` from CD to `x`, J/m^3, in closed form.
    ///
    /// **Source:** paper Eq 11 with Eqs 2 and 8 (exact integral of a linear stress times a power law).
    #[must_use]
    pub fn work_j_per_m3(&self, x_m: f64) -> f64 {
        let u = kinematics::distance_to_boundary(x_m, self.config.zone_thickness_m);
        self.work_from_power(x_m, u, u.powf(self.config.r + 1.0))
    }

    /// [`Self::work_j_per_m3`] from `u` and `u^(r+1)` (`u^(r+2) = u^(r+1) u`).
    ///
    /// **Source:** paper Eq 11 with Eqs 2 and 8 (as [`Self::work_j_per_m3`]).
    fn work_from_power(&self, x_m: f64, u: f64, u_r1: f64) -> f64 {
        let r = self.config.r;
        let k = self.strain_scale();
        let tm = self.state.tau_max_pa;
        // int_0^u of (tau0 + (tm - tau0) s) s^r ds, times K (the u = 1 case needs no power).
        let half = |tau0: f64, u: f64, u_r1: f64| k * u_r1 * (tau0 / (r + 1.0) + (tm - tau0) * u / (r + 2.0));
        if x_m >= 0.0 {
            half(self.tau0_cd_pa, u, u_r1)
        } else {
            half(self.tau0_cd_pa, 1.0, 1.0) + half(self.tau0_ef_pa, 1.0, 1.0) - half(self.tau0_ef_pa, u, u_r1)
        }
    }

    /// Plastic work per unit volume over the whole zone, J/m^3.
    #[must_use]
    pub fn total_work_j_per_m3(&self) -> f64 {
        self.work_j_per_m3(-self.config.zone_thickness_m / 2.0)
    }

    fn temperature_from_work(&self, work: f64, what: &str) -> Result<f64, ModelError> {
        let t = match &self.heat {
            HeatCapacity::Constant { rho_cp_j_per_m3_k } => self.room_c + work / rho_cp_j_per_m3_k,
            HeatCapacity::Polynomial { rho_cp, heating } => {
                let rebuilt;
                let heating = match heating {
                    Some(h) => h,
                    None => {
                        rebuilt = AdiabaticHeating::new(rho_cp.clone(), self.room_c, self.melting_c);
                        &rebuilt
                    }
                };
                heating.temperature(work).map_err(|e| match e {
                    ModelError::AboveMelting { temperature_c, melting_c, .. } => {
                        ModelError::AboveMelting { what: what.into(), temperature_c, melting_c }
                    }
                    other => other,
                })?
            }
        };
        if t >= self.melting_c || t.is_nan() {
            return Err(ModelError::AboveMelting { what: what.into(), temperature_c: t, melting_c: self.melting_c });
        }
        Ok(t)
    }

    /// All fields at `x` (m).
    ///
    /// Returns an error if the temperature there cannot be found (cannot happen below the exit
    /// temperature, which [`solve`] already checked).
    pub fn point(&self, x_m: f64) -> Result<ZonePoint, ModelError> {
        let h = self.config.zone_thickness_m;
        // One power for the three fields: u^r (Eq 2), u^(r+1) (Eqs 5 and 11), u^(r+2) (Eq 11).
        let u = kinematics::distance_to_boundary(x_m, h);
        let u_r = u.powf(self.config.r);
        let gamma = kinematics::gamma_from_power(x_m, u_r * u, self.gamma_ab);
        let gamma_dot = self.gamma_dot_ab_per_s * u_r;
        let tau = self.tau_pa(x_m);
        let work = self.work_from_power(x_m, u, u_r * u);
        let s3 = 3f64.sqrt();
        Ok(ZonePoint {
            x_m,
            gamma,
            gamma_dot_per_s: gamma_dot,
            strain: gamma / s3,
            strain_rate_per_s: gamma_dot / s3,
            tau_pa: tau,
            effective_stress_pa: s3 * tau,
            work_j_per_m3: work,
            temperature_c: self.temperature_from_work(work, "zone temperature")?,
        })
    }

    /// The `n` uniform interior points `x_k = -h/2 + k h/(n+1)`, `k = 1..n` (end points excluded:
    /// the strain rate vanishes there). These are the points of the Eq 15 objective.
    pub fn interior_points(&self, n: usize) -> Result<Vec<ZonePoint>, ModelError> {
        let h = self.config.zone_thickness_m;
        (1..=n).map(|k| self.point(-h / 2.0 + k as f64 * h / (n as f64 + 1.0))).collect()
    }

    /// `n` evenly spaced points including both ends (for plots and field CSVs).
    pub fn profile(&self, n: usize) -> Result<Vec<ZonePoint>, ModelError> {
        let h = self.config.zone_thickness_m;
        let n = n.max(2);
        (0..n).map(|k| self.point(-h / 2.0 + k as f64 * h / (n as f64 - 1.0))).collect()
    }
}

#[cfg(test)]
mod tests;
