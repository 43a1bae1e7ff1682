//! The simulator abstraction the diagnosis runs on, and its two built-in implementations.
//!
//! - [`FixedSimulation`] (Mode A): an external simulation (e.g. an FE run) given per test; its only
//!   baseline parameter is a common force scale (the stress level the external JC set may have
//!   wrong), used when there are at least two conditions.
//! - [`LiteSimulator`] (Mode B before/without the full Oxley model): the [`crate::lite`] model with
//!   JC parameters as the baseline (free with weak priors, or fixed).

use cutcal_model::{CuttingTest, JcParams, Material};

use crate::error::DiagnoseError;
use crate::lite::{self, Hooks, LiteConstants};

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

/// In-model hooks a simulator may support; unsupported ones fall back to output-level corrections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hook {
    /// Interface friction factor m_f.
    FrictionFactor,
    /// Heat-partition scale.
    HeatPartition,
    /// Extra thermomechanical softening.
    ExtraSoftening,
    /// Rake-angle shift per test.
    RakeShift,
    /// Flow-stress multiplier per test.
    FlowMultiplier,
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

/// Mode B: the lite Oxley model with JC as the baseline.
#[derive(Debug, Clone)]
pub struct LiteSimulator {
    nominal: JcParams,
    constants: LiteConstants,
    params: Vec<ParamSpec>,
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

impl LiteSimulator {
    /// JC free (weak priors at `nominal`, bounds `bx`) when `free` is true, fixed otherwise.
    #[must_use]
    pub fn new(material: &Material, nominal: JcParams, bx: &JcBox, free: bool) -> Self {
        let params = if free { jc_param_specs(&nominal, bx) } else { Vec::new() };
        Self { nominal, constants: LiteConstants::oxley_defaults(material), params }
    }

    /// With explicit lite constants (the benchmark uses this to perturb nuisances).
    #[must_use]
    pub fn with_constants(nominal: JcParams, constants: LiteConstants, bx: &JcBox, free: bool) -> Self {
        let params = if free { jc_param_specs(&nominal, bx) } else { Vec::new() };
        Self { nominal, constants, params }
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

impl Simulator for LiteSimulator {
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
        tests
            .iter()
            .zip(hooks)
            .map(|(t, h)| {
                let s = lite::solve(t, &jc, &self.constants, h)?;
                Ok(Prediction {
                    fc_n_per_m: s.fc_n_per_m,
                    ft_n_per_m: s.ft_n_per_m,
                    chip_m: s.chip_m,
                    t_ab_c: Some(s.t_ab_c),
                    t_int_c: Some(s.t_int_c),
                    beta: Some(s.beta),
                })
            })
            .collect()
    }
    fn jc_at(&self, theta: &[f64]) -> Option<JcParams> {
        Some(self.jc(theta))
    }
}

/// Mode B with cutcal's full forward model: the extended Oxley model of `cutcal_model::oxley`
/// (Lalwani et al. 2009) with JC as the baseline.
///
/// In-model hooks used: interface friction factor (M4), heat-partition scale (M6) and the rake
/// angle (built-up edge). Its thermal-softening hook can only weaken softening (scale <= 1), so
/// extra softening (M7) and the flow-stress multiplier (M10) fall back to output-level corrections;
/// edge and flank forces are added on the outputs by the mechanism layer.
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
}

impl Simulator for OxleySimulator {
    fn baseline_params(&self) -> &[ParamSpec] {
        &self.params
    }
    fn supports(&self, hook: Hook) -> bool {
        matches!(hook, Hook::FrictionFactor | Hook::HeatPartition | Hook::RakeShift)
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
        use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
        let jc = if theta.len() >= 5 {
            JcParams {
                a_pa: theta[0].exp() * 1e6,
                b_pa: theta[1].exp() * 1e6,
                n: theta[2],
                c: theta[3],
                m: theta[4],
                ..self.nominal
            }
        } else {
            self.nominal
        };
        let options = OxleyOptions::wide();
        tests
            .iter()
            .zip(hooks)
            .map(|(t, h)| {
                let err = |e| DiagnoseError::Model { test: t.id.clone(), source: e };
                let cond = CuttingConditions::new(
                    t.speed_m_per_s,
                    t.uncut_chip_thickness_m,
                    t.width_m,
                    t.rake_rad + h.rake_shift_rad,
                    self.material.room_c,
                )
                .map_err(err)?;
                let physics = Physics {
                    interface_friction_factor: h.friction_factor.clamp(1e-3, 1.0),
                    heat_partition_scale: h.heat_partition_scale.clamp(1e-3, 3.0),
                    ..Physics::baseline()
                };
                let p = oxley::predict(&self.material, &jc, &cond, &options, &physics).map_err(err)?;
                Ok(Prediction {
                    fc_n_per_m: p.cutting_force_n_per_m + h.edge_fc_n_per_m,
                    ft_n_per_m: p.feed_force_n_per_m + h.edge_ft_n_per_m,
                    chip_m: p.chip_thickness_m,
                    t_ab_c: Some(p.temperature_ab_c),
                    t_int_c: Some(p.temperature_int_c),
                    beta: None,
                })
            })
            .collect()
    }
    fn jc_at(&self, theta: &[f64]) -> Option<JcParams> {
        if theta.len() >= 5 {
            Some(JcParams {
                a_pa: theta[0].exp() * 1e6,
                b_pa: theta[1].exp() * 1e6,
                n: theta[2],
                c: theta[3],
                m: theta[4],
                ..self.nominal
            })
        } else {
            Some(self.nominal)
        }
    }
}
