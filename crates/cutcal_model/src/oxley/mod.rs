//! Oxley's predictive machining theory extended to the Johnson-Cook law (Lalwani, Mehta & Jain
//! 2009), solved as root finding (after Pantale, Dawoua Kaoutoing & Houe Ngouna 2022).
//!
//! # API (stable)
//!
//! ```text
//! oxley::predict(material: &Material, jc: &JcParams, conditions: &CuttingConditions,
//!                options: &OxleyOptions, physics: &Physics) -> Result<OxleyPrediction, ModelError>
//! oxley::predict_from(..same.., start: Option<&OxleyPrediction>)   // warm start (identification loops)
//! oxley::predict_many(material, jc, &[CuttingConditions], options, physics) -> Vec<Result<..>>  // rayon batch
//! ```
//!
//! - [`CuttingConditions`]: V, t1, w, rake, work temperature (validated).
//! - [`OxleyOptions`]: eta, psi, search ranges of phi, C0, delta, tolerances and caps; build it with
//!   [`OxleyOptions::wide`] (recommended) or [`OxleyOptions::lalwani2009`] (the paper's ranges).
//! - [`Physics`]: extra physics, all off in [`Physics::baseline`]: edge ploughing by an edge radius
//!   ([`EdgePloughing`], Waldorf, DeVor & Kapoor 1998), the flank-wear land ([`FlankWear`], Smithey,
//!   Kapoor & DeVor 2001), fixed additive edge forces (M1), interface friction factor (M4),
//!   heat-partition scale (M6), thermal softening scale (M7). [`Physics::with_tool`] switches on the
//!   tool-condition models for a stated r_e / VB. The hooks act inside the solve (M4, M6, M7) or add
//!   to the forces (edge, wear, M1), each reported separately in [`OxleyPrediction`].
//! - [`OxleyPrediction`]: phi, C0, delta, forces (per unit width and total), chip thickness,
//!   contact length, T_AB, T_int, strains and strain rates, the residuals reached and flags.
//!
//! Material data (rho Cp(T), K(T)) come from [`Material`]; the JC reference and melting
//! temperatures are `JcParams::tr_c` / `tm_c` (degC). Nothing material-specific is a constant here.
//!
//! # Model (Oxley 1989, Ch. 4; Lalwani et al. 2009, Sec. 2)
//!
//! ```text
//! l_AB = t1/sin phi, V_s = V cos a/cos(phi-a), gamma_AB = cos a/(2 sin phi cos(phi-a)), eps_AB = gamma_AB/sqrt3
//! epsdot_AB = C0 V_s/(sqrt3 l_AB), T_AB = T_w + eta (1-beta) F_s cos a/(rho Cp t1 w cos(phi-a)), k_AB = sigma_JC/sqrt3
//! n_eq = n B eps^n/(A + B eps^n), tan theta = 1 + 2(pi/4 - phi) - C0 n_eq, lambda = theta - phi + a
//! F_s = k_AB l_AB w, R = F_s/cos theta, F_c = R cos(lambda-a), F_t = R sin(lambda-a)
//! h = t1 sin theta/(cos lambda sin phi) (1 + C0 n_eq/(3 tan theta)), t2 = t1 cos(phi-a)/sin phi
//! tau_int = F/(h w) = k_chip(eps_int, epsdot_int, T_int)     -> phi
//! sigma_N = N/(h w) = k_AB (1 + pi/2 - 2a - 2 C0 n_eq)        -> C0
//! min over delta of F_c                                       -> delta
//! ```
//!
//! # Failure contract
//!
//! Every loop is capped. Returns [`ModelError::NoSolution`] when no (phi, C0) solution exists at
//! any delta in the ranges (the message gives the largest `(tau_int - k_chip)/k_AB` over every phi
//! and delta in the ranges, where it is, the thermal number R_T, and why states are inadmissible),
//! [`ModelError::AboveMelting`] when T_AB or T_int reaches the melting temperature,
//! [`ModelError::NoConvergence`] when a capped iteration stops short, and
//! [`ModelError::OutOfRange`]/[`ModelError::Inconsistent`] for invalid inputs. Never a penalty value.
//!
//! # Example
//! ```
//! use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
//! use cutcal_model::{JcParams, Material, TempPolynomial, ThermalProperties};
//! // Lalwani et al. 2009: AISI 1045, rho 7862 kg/m3, Cp = 420 + 0.504 T, K = 52.61 - 0.0281 T.
//! let rho = TempPolynomial::constant(7862.0);
//! let material = Material {
//!     name: "AISI1045".into(),
//!     thermal: ThermalProperties {
//!         rho_cp: rho.product(&TempPolynomial::new(vec![420.0, 0.504]).unwrap()),
//!         density: rho,
//!         conductivity: TempPolynomial::new(vec![52.61, -0.0281]).unwrap(),
//!         valid_from_c: 0.0,
//!         valid_to_c: 1400.0,
//!     },
//!     yield_strength: None, melting_c: 1460.0, room_c: 25.0, elastic: None,
//! };
//! // Jaspers & Dautzenberg 2002.
//! let jc = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap();
//! // Case 1: 200 m/min, t1 0.15 mm, w 1.6 mm, rake -7 deg; Lalwani predicts Fc = 576 N.
//! let cond = CuttingConditions::new(200.0 / 60.0, 0.15e-3, 1.6e-3, (-7f64).to_radians(), 25.0).unwrap();
//! let p = oxley::predict(&material, &jc, &cond, &OxleyOptions::wide(), &Physics::baseline()).unwrap();
//! assert!((p.cutting_force_n / 576.0 - 1.0).abs() < 0.05);
//! ```

mod edge;
mod equations;
mod existence;
mod minimum;
mod options;
mod pool;
mod roots;
mod solve;
mod temperatures;

use serde::{Deserialize, Serialize};

use crate::error::ModelError;
use crate::jc::JcParams;
use crate::material::Material;

pub use edge::{waldorf_factors, EdgePloughing, FlankWear};
pub use options::{CuttingConditions, EdgeForce, OxleyOptions, Physics};

use equations::{Context, TemperatureHints};
use solve::Solver;

/// Flags describing how trustworthy a prediction is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct SolutionFlags {
    /// phi sits on a bound of its search range.
    pub phi_at_bound: bool,
    /// C0 sits on a bound of its search range.
    pub c0_at_bound: bool,
    /// The Fc minimum over delta sits on a bound of the delta range, or next to a delta without
    /// solution (the true minimum may lie outside what was searched).
    pub delta_at_bound: bool,
    /// Fc changes by less than `delta_flat_tolerance` over `delta*(1 -/+ delta_flat_band)`:
    /// delta is poorly determined (its value is not meaningful to more than about one digit).
    pub delta_poorly_determined: bool,
    /// `R_T tan(phi)` was below the 0.04 lower end of Boothroyd's heat-partition correlation at AB.
    pub heat_partition_extrapolated: bool,
    /// The phi scan of the bracketing fallback saw more than one root of `tau_int = k_chip`
    /// (the lowest was taken).
    pub multiple_phi_roots: bool,
}

/// The output of [`predict`]: everything per unit width in SI, totals over the width of cut.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OxleyPrediction {
    /// Shear angle phi, rad.
    pub phi_rad: f64,
    /// Primary-zone strain-rate constant C0.
    pub c0: f64,
    /// Secondary-zone thickness ratio delta.
    pub delta: f64,
    /// Cutting force per unit width including the additive hooks, N/m.
    pub cutting_force_n_per_m: f64,
    /// Feed (thrust) force per unit width including the additive hooks, N/m.
    pub feed_force_n_per_m: f64,
    /// Cutting force over the width, N.
    pub cutting_force_n: f64,
    /// Feed force over the width, N.
    pub feed_force_n: f64,
    /// Chip-formation cutting force per unit width (Oxley's force system alone), N/m.
    pub chip_cutting_force_n_per_m: f64,
    /// Chip-formation feed force per unit width, N/m.
    pub chip_feed_force_n_per_m: f64,
    /// Added cutting force per unit width from all additive terms (fixed edge forces, edge
    /// ploughing, wear land), N/m.
    pub hook_cutting_force_n_per_m: f64,
    /// Added feed force per unit width from all additive terms, N/m.
    pub hook_feed_force_n_per_m: f64,
    /// Edge radius of the edge-ploughing term, m (None: sharp edge).
    pub edge_radius_m: Option<f64>,
    /// Flank wear land of the wear term, m (None: no wear land).
    pub flank_wear_m: Option<f64>,
    /// Edge-ploughing cutting force per unit width (Waldorf et al. 1998; 0 for a sharp edge), N/m.
    pub edge_cutting_force_n_per_m: f64,
    /// Edge-ploughing feed force per unit width, N/m.
    pub edge_feed_force_n_per_m: f64,
    /// Flank-wear-land cutting force per unit width (Smithey et al. 2001; 0 without wear), N/m.
    pub wear_cutting_force_n_per_m: f64,
    /// Flank-wear-land feed force per unit width, N/m.
    pub wear_feed_force_n_per_m: f64,
    /// Shear force along AB per unit width, F_s = k_AB l_AB, N/m.
    pub shear_force_n_per_m: f64,
    /// Chip thickness t2, m.
    pub chip_thickness_m: f64,
    /// Tool-chip contact length h, m.
    pub contact_length_m: f64,
    /// Shear-plane length l_AB, m.
    pub shear_plane_length_m: f64,
    /// Temperature at AB, degC.
    pub temperature_ab_c: f64,
    /// Mean tool-chip interface temperature, degC.
    pub temperature_int_c: f64,
    /// Effective strain at AB.
    pub strain_ab: f64,
    /// Effective strain rate at AB, 1/s.
    pub strain_rate_ab_per_s: f64,
    /// Effective strain at the interface.
    pub strain_int: f64,
    /// Effective strain rate at the interface, 1/s.
    pub strain_rate_int_per_s: f64,
    /// Shear flow stress at AB, k_AB, Pa.
    pub shear_flow_stress_ab_pa: f64,
    /// Shear flow stress of the chip at the interface, k_chip, Pa.
    pub shear_flow_stress_int_pa: f64,
    /// Interface shear stress from the force system, tau_int = F/(h w), Pa.
    pub interface_shear_stress_pa: f64,
    /// Interface normal stress from the force system, sigma_N = N/(h w), Pa.
    pub interface_normal_stress_pa: f64,
    /// Normal stress at B from the stress distribution along AB, sigma_N', Pa.
    pub model_normal_stress_pa: f64,
    /// Equivalent hardening index n_eq.
    pub n_eq: f64,
    /// Angle theta between the resultant and AB, rad.
    pub theta_rad: f64,
    /// Friction angle lambda, rad.
    pub friction_angle_rad: f64,
    /// Heat partition into the work beta (after the M6 scale).
    pub heat_partition: f64,
    /// Residual `(tau_int - m_f k_chip)/k_AB` reached.
    pub residual_shear: f64,
    /// Residual `(sigma_N - sigma_N')/k_AB` reached.
    pub residual_normal: f64,
    /// Largest relative change of the chip-formation Fc at the flatness probes, if computed.
    pub fc_change_over_delta_band: Option<f64>,
    /// Share of the delta scan points with a (phi, C0) solution.
    pub delta_scan_converged_share: f64,
    /// Primary-zone evaluations used (each with its T_AB and T_C solves; interface states at a
    /// computed primary zone are closed-form in delta and not counted).
    pub evaluations: usize,
    /// Trust flags.
    pub flags: SolutionFlags,
}

/// Predicts one orthogonal cut with the extended Oxley model; see the module docs for the
/// equations, the failure contract and an example.
///
/// **Source:** Oxley 1989, Ch. 4; Lalwani, Mehta & Jain 2009, Sec. 2; solution strategy after
/// Pantale et al. 2022.
pub fn predict(
    material: &Material,
    jc: &JcParams,
    conditions: &CuttingConditions,
    options: &OxleyOptions,
    physics: &Physics,
) -> Result<OxleyPrediction, ModelError> {
    predict_from(material, jc, conditions, options, physics, None)
}

/// [`predict`] for many conditions in parallel (rayon), one result per condition in input order.
/// Each prediction is cold-started, so the results do not depend on the thread count or order.
///
/// **Source:** as [`predict`].
pub fn predict_many(
    material: &Material,
    jc: &JcParams,
    conditions: &[CuttingConditions],
    options: &OxleyOptions,
    physics: &Physics,
) -> Vec<Result<OxleyPrediction, ModelError>> {
    use rayon::prelude::*;
    conditions.par_iter().map(|c| predict(material, jc, c, options, physics)).collect()
}

/// As [`predict`], warm-started at the (phi, C0) of `start` (for loops over nearby parameters,
/// e.g. identification). The warm start changes the work done, not the definition of the solution.
pub fn predict_from(
    material: &Material,
    jc: &JcParams,
    conditions: &CuttingConditions,
    options: &OxleyOptions,
    physics: &Physics,
    start: Option<&OxleyPrediction>,
) -> Result<OxleyPrediction, ModelError> {
    jc.validate()?;
    options.validate()?;
    physics.validate()?;
    let tm = jc.tm_c.min(material.melting_c);
    if conditions.work_temperature_c >= tm {
        return Err(ModelError::AboveMelting {
            what: "work temperature".into(),
            temperature_c: conditions.work_temperature_c,
            melting_c: tm,
        });
    }
    let hints = TemperatureHints::none();
    let ctx = Context { material, jc, conditions, options, physics, hints: &hints };
    let mut solver = Solver::new(ctx, start.map(|p| p.phi_rad));
    let search = match solver.search_delta() {
        Ok(s) => s,
        // A warm start must not change whether a solution is found: retry cold.
        Err(_) if start.is_some() => {
            let spent = solver.evaluations;
            hints.reset();
            solver = Solver::new(ctx, None);
            solver.evaluations = spent;
            solver.search_delta()?
        }
        Err(e) => return Err(e),
    };
    let s = search.best.state;
    let (p, i) = (s.primary, s.interface);
    if i.temperature_c >= tm {
        return Err(ModelError::AboveMelting {
            what: "tool-chip interface temperature T_int".into(),
            temperature_c: i.temperature_c,
            melting_c: tm,
        });
    }
    let near = |x: f64, r: [f64; 2]| (x - r[0]).abs().min((r[1] - x).abs()) <= 1e-6 * (r[1] - r[0]);
    // Additive terms, per unit width, all scaled by the k_AB and phi of this solution:
    // fixed edge forces (M1 hook), edge ploughing (Waldorf et al. 1998), wear land (Smithey et al. 2001).
    let (fixed_c, fixed_t) = physics.edge_force.map_or((0.0, 0.0), |e| (e.cutting_n_per_m, e.feed_n_per_m));
    let (edge_c, edge_t) = physics
        .edge_ploughing
        .map_or((0.0, 0.0), |e| e.forces_n_per_m(p.shear_flow_stress_pa, p.phi_rad, conditions.uncut_chip_thickness_m));
    let (wear_c, wear_t) = physics.flank_wear.map_or((0.0, 0.0), |f| f.forces_n_per_m(p.shear_flow_stress_pa));
    let hook_c = fixed_c + edge_c + wear_c;
    let hook_t = fixed_t + edge_t + wear_t;
    let fc = p.cutting_force_n_per_m + hook_c;
    let ft = p.feed_force_n_per_m + hook_t;
    let w = conditions.width_m;
    Ok(OxleyPrediction {
        phi_rad: p.phi_rad,
        c0: p.c0,
        delta: i.delta,
        cutting_force_n_per_m: fc,
        feed_force_n_per_m: ft,
        cutting_force_n: fc * w,
        feed_force_n: ft * w,
        chip_cutting_force_n_per_m: p.cutting_force_n_per_m,
        chip_feed_force_n_per_m: p.feed_force_n_per_m,
        hook_cutting_force_n_per_m: hook_c,
        hook_feed_force_n_per_m: hook_t,
        edge_radius_m: physics.edge_ploughing.map(|e| e.edge_radius_m),
        flank_wear_m: physics.flank_wear.map(|f| f.land_m),
        edge_cutting_force_n_per_m: edge_c,
        edge_feed_force_n_per_m: edge_t,
        wear_cutting_force_n_per_m: wear_c,
        wear_feed_force_n_per_m: wear_t,
        shear_force_n_per_m: p.shear_force_n_per_m,
        chip_thickness_m: p.chip_thickness_m,
        contact_length_m: p.contact_length_m,
        shear_plane_length_m: p.shear_plane_length_m,
        temperature_ab_c: p.temperature_c,
        temperature_int_c: i.temperature_c,
        strain_ab: p.strain,
        strain_rate_ab_per_s: p.strain_rate_per_s,
        strain_int: i.strain,
        strain_rate_int_per_s: i.strain_rate_per_s,
        shear_flow_stress_ab_pa: p.shear_flow_stress_pa,
        shear_flow_stress_int_pa: i.shear_flow_stress_pa,
        interface_shear_stress_pa: i.shear_stress_pa,
        interface_normal_stress_pa: i.normal_stress_pa,
        model_normal_stress_pa: p.model_normal_stress_pa,
        n_eq: p.n_eq,
        theta_rad: p.theta_rad,
        friction_angle_rad: p.lambda_rad,
        heat_partition: p.heat_partition,
        residual_shear: s.residual_shear,
        residual_normal: s.residual_normal,
        fc_change_over_delta_band: search.fc_change_over_band,
        delta_scan_converged_share: search.converged_share,
        evaluations: solver.evaluations,
        flags: SolutionFlags {
            phi_at_bound: near(p.phi_rad, options.phi_range_rad),
            c0_at_bound: near(p.c0, options.c0_range),
            delta_at_bound: search.at_bound,
            delta_poorly_determined: search.poorly_determined,
            heat_partition_extrapolated: p.beta_outside_correlation,
            multiple_phi_roots: solver.multiple_phi_roots,
        },
    })
}
