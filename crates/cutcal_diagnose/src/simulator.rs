//! The simulator abstraction the diagnosis runs on, and its two built-in implementations.
//!
//! - [`FixedSimulation`] (Mode A): an external simulation (e.g. an FE run) given per test; its only
//!   baseline parameter is a common force scale (the stress level the external JC set may have
//!   wrong), used when there are at least two conditions.
//!   It supports no hook; Mode A uses it only when the shadow of [`crate::shadow`] cannot be built.
//! - [`OxleySimulator`] (Mode B): cutcal's extended Oxley model with JC as the baseline and every
//!   mechanism hook inside the model ([`oxley_with_hooks`]).

use cutcal_model::{CuttingTest, JcParams, Material};

use cutcal_model::oxley::{self, CuttingConditions, EdgePloughing, FlankWear, OxleyOptions, Physics};

use crate::error::DiagnoseError;
pub use crate::hooks::{Hook, Hooks};

/// Model outputs for one test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prediction {
    /// Cutting force per unit width, N/m.
    pub fc_n_per_m: f64,
    /// Feed force per unit width, N/m.
    pub ft_n_per_m: f64,
    /// Chip thickness, m.
    pub chip_m: f64,
    /// Shear-plane temperature, degC, when the simulator gives it.
    pub t_ab_c: Option<f64>,
    /// Interface temperature, degC, when known.
    pub t_int_c: Option<f64>,
    /// Boothroyd heat partition into the work, when known.
    pub beta: Option<f64>,
}

/// One baseline parameter: name with unit, start, bounds, weak prior width (`None`: no prior).
#[derive(Debug, Clone, PartialEq)]
pub struct ParamSpec {
    /// Name, e.g. `ln_A`.
    pub name: String,
    /// Unit for reports.
    pub unit: String,
    /// Start value (also the prior centre).
    pub start: f64,
    /// Lower bound.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
    /// Prior standard deviation (pseudo-residual `(x - start)/sd`), `None` for no prior.
    pub prior_sd: Option<f64>,
}

/// A forward model of the recordings with baseline parameters `theta` and mechanism hooks.
pub trait Simulator: Sync {
    /// The baseline parameters (JC, or a force scale in Mode A); may be empty.
    fn baseline_params(&self) -> &[ParamSpec];
    /// Whether the simulator implements `hook` inside the model.
    fn supports(&self, hook: Hook) -> bool;
    /// Whether it can predict conditions that were not simulated (for the next-test search).
    fn can_extrapolate(&self) -> bool;
    /// Predictions for `tests` at `theta` with one [`Hooks`] per test.
    ///
    /// Returns an error if a test cannot be simulated.
    fn simulate(&self, tests: &[CuttingTest], theta: &[f64], hooks: &[Hooks])
        -> Result<Vec<Prediction>, DiagnoseError>;
    /// JC parameters at `theta`, when the baseline is a JC set (for reports).
    fn jc_at(&self, _theta: &[f64]) -> Option<JcParams> {
        None
    }
}

/// Mode A: an external simulation, one [`Prediction`] per test id.
#[derive(Debug, Clone)]
pub struct FixedSimulation {
    entries: Vec<(String, Prediction)>,
    params: Vec<ParamSpec>,
}

impl FixedSimulation {
    /// Builds the simulation; `force_scale` adds the common force-scale baseline parameter `ln_s`.
    ///
    /// Returns an error if an id repeats or a value is not positive.
    pub fn new(entries: Vec<(String, Prediction)>, force_scale: bool) -> Result<Self, DiagnoseError> {
        for (i, (id, p)) in entries.iter().enumerate() {
            if entries[..i].iter().any(|(o, _)| o == id) {
                return Err(DiagnoseError::Inconsistent(format!("simulation test id `{id}` appears twice")));
            }
            for (name, v) in [("fc", p.fc_n_per_m), ("ft", p.ft_n_per_m), ("chip", p.chip_m)] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(DiagnoseError::Inconsistent(format!(
                        "simulation test `{id}`: {name} must be positive, got {v}"
                    )));
                }
            }
        }
        let params = if force_scale {
            vec![ParamSpec {
                name: "ln_force_scale".into(),
                unit: "-".into(),
                start: 0.0,
                lower: -0.7,
                upper: 0.7,
                prior_sd: None,
            }]
        } else {
            Vec::new()
        };
        Ok(Self { entries, params })
    }
}

impl Simulator for FixedSimulation {
    fn baseline_params(&self) -> &[ParamSpec] {
        &self.params
    }
    fn supports(&self, _hook: Hook) -> bool {
        false
    }
    fn can_extrapolate(&self) -> bool {
        false
    }
    fn simulate(
        &self,
        tests: &[CuttingTest],
        theta: &[f64],
        _hooks: &[Hooks],
    ) -> Result<Vec<Prediction>, DiagnoseError> {
        let scale = theta.first().map(|l| l.exp()).unwrap_or(1.0);
        tests
            .iter()
            .map(|t| {
                let (_, p) = self.entries.iter().find(|(id, _)| *id == t.id).ok_or_else(|| {
                    DiagnoseError::Inconsistent(format!(
                        "test `{}` is in the recordings but not in the simulation",
                        t.id
                    ))
                })?;
                Ok(Prediction { fc_n_per_m: p.fc_n_per_m * scale, ft_n_per_m: p.ft_n_per_m * scale, ..*p })
            })
            .collect()
    }
}

/// Bounds of the free JC parameters `[A MPa, B MPa, n, C, m]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JcBox {
    /// `(low, high)` per parameter, A and B in MPa.
    pub bounds: [(f64, f64); 5],
}

impl JcBox {
    /// The bounds of the design note's plausibility flags (Sec 3.2) widened for steels.
    #[must_use]
    pub fn wide() -> Self {
        Self { bounds: [(100.0, 2000.0), (20.0, 2000.0), (0.05, 0.7), (0.0005, 0.1), (0.5, 2.0)] }
    }
}

/// The JC baseline parameter vector `[ln A/MPa, ln B/MPa, n, C, m]` with weak priors at `nominal`.
///
/// Prior widths (one standard deviation): A x/÷ 1.35, B x/÷ 1.65, n 0.1, C 0.01, m 0.2: wide enough
/// for published JC scatter of one steel (design note Sec 4.2 lists sets differing by these amounts).
#[must_use]
pub fn jc_param_specs(nominal: &JcParams, bx: &JcBox) -> Vec<ParamSpec> {
    let c = |name: &str, unit: &str, v: f64, (lo, hi): (f64, f64), sd: f64| ParamSpec {
        name: name.into(),
        unit: unit.into(),
        start: v.clamp(lo, hi),
        lower: lo,
        upper: hi,
        prior_sd: Some(sd),
    };
    let b = bx.bounds;
    vec![
        c("ln_A", "ln MPa", (nominal.a_pa / 1e6).ln(), (b[0].0.ln(), b[0].1.ln()), 0.3),
        c("ln_B", "ln MPa", (nominal.b_pa.max(1e6) / 1e6).ln(), (b[1].0.ln(), b[1].1.ln()), 0.5),
        c("n", "-", nominal.n, b[2], 0.1),
        c("C", "-", nominal.c, b[3], 0.01),
        c("m", "-", nominal.m, b[4], 0.2),
    ]
}

/// Mode B with cutcal's full forward model: the extended Oxley model of `cutcal_model::oxley`
/// (Lalwani et al. 2009) with JC as the baseline; every mechanism hook is inside the model
/// ([`oxley_with_hooks`]).
#[derive(Debug, Clone)]
pub struct OxleySimulator {
    material: Material,
    nominal: JcParams,
    params: Vec<ParamSpec>,
}

impl OxleySimulator {
    /// JC free (weak priors at `nominal`, bounds `bx`) when `free`, fixed otherwise.
    #[must_use]
    pub fn new(material: &Material, nominal: JcParams, bx: &JcBox, free: bool) -> Self {
        let params = if free { jc_param_specs(&nominal, bx) } else { Vec::new() };
        Self { material: material.clone(), nominal, params }
    }

    fn jc(&self, theta: &[f64]) -> JcParams {
        if theta.len() < 5 {
            return self.nominal;
        }
        JcParams {
            a_pa: theta[0].exp() * 1e6,
            b_pa: theta[1].exp() * 1e6,
            n: theta[2],
            c: theta[3],
            m: theta[4],
            ..self.nominal
        }
    }
}

impl Simulator for OxleySimulator {
    fn baseline_params(&self) -> &[ParamSpec] {
        &self.params
    }
    fn supports(&self, _hook: Hook) -> bool {
        true
    }
    fn can_extrapolate(&self) -> bool {
        true
    }
    fn simulate(
        &self,
        tests: &[CuttingTest],
        theta: &[f64],
        hooks: &[Hooks],
    ) -> Result<Vec<Prediction>, DiagnoseError> {
        let jc = self.jc(theta);
        let options = OxleyOptions::wide();
        tests.iter().zip(hooks).map(|(t, h)| oxley_with_hooks(&self.material, &jc, t, h, &options)).collect()
    }
    fn jc_at(&self, theta: &[f64]) -> Option<JcParams> {
        Some(self.jc(theta))
    }
}

/// One prediction of cutcal's extended Oxley model (Oxley 1989; Lalwani et al. 2009) with the
/// mechanism hooks `h` switched on inside it:
/// - flow-stress multiplier: A and B of the JC law scaled (Eq 16 of the paper, both zones);
/// - rake shift: the effective rake angle;
/// - friction factor, heat-partition scale, extra softening: `oxley::Physics` (M4, M6, M7; the
///   softening hook evaluates the flow stress at `T_w + (1 + k)(T - T_w)`);
/// - thermal-exponent scale: the JC m multiplied by `exp(ln_m)` (M7's second form);
/// - edge radius: Waldorf, DeVor & Kapoor 1998 ploughing (`EdgePloughing::waldorf1998`);
/// - wear land: Smithey, Kapoor & DeVor 2001 (`FlankWear::smithey2001`).
///
/// Returns an error naming the test when a hook value is out of the model's range or the model
/// has no solution.
pub fn oxley_with_hooks(
    material: &Material,
    jc: &JcParams,
    t: &CuttingTest,
    h: &Hooks,
    options: &OxleyOptions,
) -> Result<Prediction, DiagnoseError> {
    oxley_with_hooks_from(material, jc, t, h, options, None).map(|(p, _)| p)
}

/// As [`oxley_with_hooks`], warm-started at a nearby solution (`oxley::predict_from`: the start
/// changes the work done, not the solution); also returns the full solution for the next start.
///
/// Returns an error naming the test when a hook value is out of range or there is no solution.
pub fn oxley_with_hooks_from(
    material: &Material,
    jc: &JcParams,
    t: &CuttingTest,
    h: &Hooks,
    options: &OxleyOptions,
    start: Option<&oxley::OxleyPrediction>,
) -> Result<(Prediction, oxley::OxleyPrediction), DiagnoseError> {
    let err = |e| DiagnoseError::Model { test: t.id.clone(), source: e };
    let cond = CuttingConditions::new(
        t.speed_m_per_s,
        t.uncut_chip_thickness_m,
        t.width_m,
        t.rake_rad + h.rake_shift_rad,
        material.room_c,
    )
    .map_err(err)?;
    let jc = JcParams {
        a_pa: jc.a_pa * h.flow_multiplier,
        b_pa: jc.b_pa * h.flow_multiplier,
        m: jc.m * h.thermal_exponent_ln_scale.clamp(-1.0, 1.0).exp(),
        ..*jc
    };
    let physics = Physics {
        interface_friction_factor: h.friction_factor.clamp(1e-3, 1.0),
        heat_partition_scale: h.heat_partition_scale.clamp(1e-3, 3.0),
        interface_heat_share: h.interface_heat_share.clamp(1e-3, 2.0),
        thermal_softening_scale: (1.0 + h.extra_softening).clamp(0.0, 3.0),
        edge_ploughing: if h.edge_radius_m > 0.0 {
            Some(EdgePloughing::waldorf1998(h.edge_radius_m.min(0.5e-3)).map_err(err)?)
        } else {
            None
        },
        flank_wear: if h.wear_land_m > 0.0 {
            Some(FlankWear::smithey2001(h.wear_land_m.min(2e-3)).map_err(err)?)
        } else {
            None
        },
        c0_scale: h.c0_scale.clamp(0.01, 10.0),
        ..Physics::baseline()
    };
    let p = oxley::predict_from(material, &jc, &cond, options, &physics, start).map_err(err)?;
    Ok((
        Prediction {
            fc_n_per_m: p.cutting_force_n_per_m,
            ft_n_per_m: p.feed_force_n_per_m,
            chip_m: p.chip_thickness_m,
            t_ab_c: Some(p.temperature_ab_c),
            t_int_c: Some(p.temperature_int_c),
            beta: Some(p.heat_partition),
        },
        p,
    ))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// AISI 1045, Jaspers & Dautzenberg 2002 (fixtures/jc/aisi1045_jaspers2002.toml).
    pub(crate) fn jaspers() -> JcParams {
        JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap()
    }

    #[test]
    fn hooks_move_the_full_model_in_their_documented_directions() {
        // Independent expectations from the physics, not from the code: a sharper-than-sticking
        // interface lowers Ft; ploughing and a wear land add force; a larger rake lowers Fc; a flow
        // multiplier of 1.1 raises Fc by close to 10 %.
        let m = cutcal_model::reference::aisi1045_lalwani2009();
        let t = CuttingTest::new("1", 200.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap();
        let o = OxleyOptions::wide();
        let at = |h: Hooks| oxley_with_hooks(&m, &jaspers(), &t, &h, &o).unwrap();
        let b = at(Hooks::NEUTRAL);
        assert!(at(Hooks { friction_factor: 0.7, ..Hooks::NEUTRAL }).ft_n_per_m < 0.9 * b.ft_n_per_m);
        let e = at(Hooks { edge_radius_m: 20e-6, ..Hooks::NEUTRAL });
        assert!(e.fc_n_per_m > b.fc_n_per_m && e.ft_n_per_m - b.ft_n_per_m > e.fc_n_per_m - b.fc_n_per_m);
        assert!(at(Hooks { wear_land_m: 0.2e-3, ..Hooks::NEUTRAL }).ft_n_per_m > 1.1 * b.ft_n_per_m);
        assert!(at(Hooks { rake_shift_rad: 0.1, ..Hooks::NEUTRAL }).fc_n_per_m < b.fc_n_per_m);
        let f = at(Hooks { flow_multiplier: 1.1, ..Hooks::NEUTRAL }).fc_n_per_m / b.fc_n_per_m;
        assert!((1.02..1.10).contains(&f), "{f}");
        assert!(at(Hooks { extra_softening: 0.5, ..Hooks::NEUTRAL }).fc_n_per_m < b.fc_n_per_m);
        // A larger JC m (less softening at T* < 1) raises the forces.
        assert!(at(Hooks { thermal_exponent_ln_scale: 0.3, ..Hooks::NEUTRAL }).fc_n_per_m > b.fc_n_per_m);
    }
}
