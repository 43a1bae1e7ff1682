//! The mechanism library: physics a primary-shear-zone model leaves out, each a 1-2 parameter
//! augmentation with units, bounds, the value that switches it off, its model (inside the forward
//! model through a [`Hook`]; only the dynamometer cross-talk acts on the outputs), the covariates it
//! needs and its confounders.
//!
//! **Source:** design note `discrepancy-discovery.md` Sec 2.2 (mechanisms M1, M3, M4 with the
//! speed dependence of M5, M6, M7, M9, M10, M11) and its signature matrix Sec 2.3. Every physical
//! mechanism is evaluated by cutcal's extended Oxley model at each test's own conditions (in Mode A
//! through the shadow of the external simulation, `crate::shadow`); there are no constant
//! sensitivities. A simulator that lacks a mechanism's hook makes that mechanism not testable.

use cutcal_model::CuttingTest;
use serde::{Deserialize, Serialize};

pub use crate::context::Context;
use crate::hooks::{Hook, Hooks};
use crate::simulator::{Prediction, Simulator};

mod bue;
mod friction;
mod library;
pub use bue::{bue_coordinates, bue_gate, bue_gates, bue_indicator, bue_onsets, BUE_SHARP_WIDTH, BUE_WIDTH};
pub(crate) use bue::{gate_alternatives, gate_class, GATE_CLASSES};
pub use friction::{friction_factor, hybrid_friction_factor};
pub use library::info;

/// Identifier of a library mechanism (the JSON/CLI spelling is snake_case).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MechanismId {
    /// M1 cutting-edge ploughing: additive edge forces.
    EdgePloughing,
    /// M3 flank wear land: additive forces growing with wear state.
    FlankWear,
    /// M4 tool-chip friction below full sticking, falling with cutting speed (M5).
    ToolChipFriction,
    /// M7 thermal softening / thermomechanical coupling stronger or weaker than the model's.
    ThermalSoftening,
    /// M6 heat partition into the work different from Boothroyd's.
    HeatPartition,
    /// M10 size effect: multiplicative strengthening at small h.
    SizeEffect,
    /// M9 built-up edge at low speed.
    BuiltUpEdge,
    /// M11 dynamometer cross-talk from Fc into Ft.
    ForceCrosstalk,
}

impl MechanismId {
    /// Every library mechanism.
    pub const ALL: [MechanismId; 8] = [
        MechanismId::EdgePloughing,
        MechanismId::FlankWear,
        MechanismId::ToolChipFriction,
        MechanismId::ThermalSoftening,
        MechanismId::HeatPartition,
        MechanismId::SizeEffect,
        MechanismId::BuiltUpEdge,
        MechanismId::ForceCrosstalk,
    ];

    /// The snake_case id.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            MechanismId::EdgePloughing => "edge_ploughing",
            MechanismId::FlankWear => "flank_wear",
            MechanismId::ToolChipFriction => "tool_chip_friction",
            MechanismId::ThermalSoftening => "thermal_softening",
            MechanismId::HeatPartition => "heat_partition",
            MechanismId::SizeEffect => "size_effect",
            MechanismId::BuiltUpEdge => "built_up_edge",
            MechanismId::ForceCrosstalk => "force_crosstalk",
        }
    }

    /// Parses a snake_case id.
    #[must_use]
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.as_str() == s)
    }
}

/// One mechanism parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamInfo {
    /// Name.
    pub name: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// Lower bound.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
    /// The value at which the mechanism is off.
    pub off: f64,
    /// A typical magnitude (for sensitivities and detectability).
    pub typical: f64,
}

/// Static description of a mechanism.
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismInfo {
    /// Id.
    pub id: MechanismId,
    /// Plain-language title.
    pub title: &'static str,
    /// Where the model comes from.
    pub source: &'static str,
    /// Parameters.
    pub params: Vec<ParamInfo>,
    /// The in-model hook, if the mechanism is in-model; `None`: additive on the outputs.
    pub hook: Option<Hook>,
    /// Expected residual signature (measured - model), for the narrative.
    pub signature: &'static str,
    /// Covariates it needs.
    pub covariates: &'static str,
    /// Mechanisms it is confounded with.
    pub confounders: &'static [MechanismId],
    /// What would separate it from its confounders (a test or a measurement).
    pub separate_by: &'static str,
}

/// Sets the in-model hooks of mechanism `id` with parameters `phi` (only where `sim` supports them).
pub fn set_hooks(
    id: MechanismId,
    phi: &[f64],
    tests: &[CuttingTest],
    ctx: &Context,
    sim: &dyn Simulator,
    hooks: &mut [Hooks],
) {
    let Some(hook) = info(id).hook else { return };
    if !sim.supports(hook) {
        return;
    }
    for (i, (t, h)) in tests.iter().zip(hooks.iter_mut()).enumerate() {
        match id {
            MechanismId::EdgePloughing => {
                let shape = ctx.edge_shape.as_ref().map_or(1.0, |s| s[i]);
                let r = phi[0] * 1e-6 * shape;
                h.edge_radius_m += r;
                if let Some(&w) = phi.get(1) {
                    h.rake_shift_rad += w * edge_rake_shift(r, t);
                }
            }
            MechanismId::FlankWear => {
                let w0 = phi.get(1).copied().unwrap_or(0.0);
                h.wear_land_m += phi[0] * 1e-3 * ctx.wear_state.as_ref().map_or(0.0, |w| w0 + (1.0 - w0) * w[i]);
            }
            MechanismId::ToolChipFriction => {
                let m = friction_factor(phi[0], phi[1], t.speed_m_per_s * 60.0, ctx.friction_v_ref_m_min);
                let load = ctx.friction_load.as_ref().map_or(1.0, |l| l[i]);
                h.friction_factor *= hybrid_friction_factor(m, load, f64::from(u8::from(ctx.friction_coulomb)));
            }
            MechanismId::ThermalSoftening => {
                h.extra_softening += phi[0];
                h.thermal_exponent_ln_scale += phi[1];
            }
            MechanismId::HeatPartition => {
                h.heat_partition_scale *= phi[0];
                h.interface_heat_share *= phi[1];
            }
            MechanismId::SizeEffect => {
                h.flow_multiplier *= size_factor(phi[0], phi.get(2).copied().unwrap_or(1.0), t, ctx.size_h_ref_m);
                h.friction_factor *= nix_gao(phi[0], t).powf(phi[1] - 1.0);
            }
            MechanismId::BuiltUpEdge => {
                h.rake_shift_rad += phi[0].to_radians()
                    * bue_gate(ctx.bue_coordinate(tests, i), ctx.bue_onset, ctx.bue_floor, ctx.bue_width())
            }
            _ => {}
        }
    }
}

/// Lowest effective rake, rad, an edge is given: the extended Oxley closure has no solution far
/// below it (nor does `CuttingConditions` accept -45 deg), and the shadow's rake table ends there.
const EDGE_RAKE_FLOOR_RAD: f64 = -40.0 * std::f64::consts::PI / 180.0;

/// The change of rake, rad, that an edge of radius `r_m` gives the chip at test `t`: its chord
/// effective rake (Manjunathaiah & Endres 2000; `EdgePloughing::effective_rake_rad`) less the
/// nominal rake, with the effective rake held at or above [`EDGE_RAKE_FLOOR_RAD`].
fn edge_rake_shift(r_m: f64, t: &CuttingTest) -> f64 {
    let Ok(edge) = cutcal_model::oxley::EdgePloughing::waldorf1998(r_m.clamp(0.0, 0.5e-3)) else { return 0.0 };
    let eff = edge.effective_rake_rad(t.uncut_chip_thickness_m, t.rake_rad);
    eff.max(EDGE_RAKE_FLOOR_RAD.min(t.rake_rad)) - t.rake_rad
}

/// Nix-Gao size factor `sqrt(1 + l/h) / (1 + l/h_ref)^(w_ref/2)` with `l` in um (Nix & Gao 1998).
/// `w_ref` is the share of the strengthening at the dataset's geometric-mean thickness `h_ref`
/// (`Context::size_h_ref_m`) that the simulation's flow stress already holds: 1 when its flow stress
/// was set at these thicknesses (the strengthening is then relative to `h_ref`, with no level of its
/// own there), 0 when it is the bulk material's (the absolute Nix-Gao factor, a strengthening at
/// every thickness).
fn size_factor(l_um: f64, w_ref: f64, t: &CuttingTest, h_ref_m: f64) -> f64 {
    nix_gao(l_um, t) / (1.0 + l_um.max(0.0) * 1e-6 / h_ref_m.max(1e-9)).powf(0.5 * w_ref.clamp(0.0, 1.0))
}

/// The absolute Nix-Gao factor `sqrt(1 + l/h)` (Nix & Gao 1998), at least 1.
fn nix_gao(l_um: f64, t: &CuttingTest) -> f64 {
    (1.0 + l_um.max(0.0) * 1e-6 / t.uncut_chip_thickness_m).sqrt()
}

/// Why a thermal-softening refit is not a softening change, when it is not.
///
/// M7 claims softening stronger, or weaker, than the model's: a flow-stress curve that lies below
/// (or above) the JC law's at every temperature. Each form alone is one-signed in that sense:
/// k_T > 0 lets the flow stress see a larger temperature rise (stronger) and ln_m > 0 a larger JC
/// exponent, whose factor 1 - T*^m is larger at every T* in (0, 1) (weaker; Johnson & Cook 1983).
/// When the data demand both forms (each 95 % interval `ci` excludes 0) in opposite directions,
/// the fitted curve crosses the model's: a change of the curve's shape with temperature, which the
/// two forms can draw for any trend with temperature (a built-up edge, a friction or a partition
/// that moves with speed), and not the mechanism claimed. `None` when the fit is one-signed, and
/// when either form sits on a bound of its range: that estimate is not free (the other form may be
/// making up for the range the bound cut off), and its Wald interval is not valid there.
#[must_use]
pub fn softening_conflict(ci: &[(f64, Option<f64>, Option<f64>)]) -> Option<String> {
    let params = info(MechanismId::ThermalSoftening).params;
    let demanded = |c: &(f64, Option<f64>, Option<f64>), p: &ParamInfo| match *c {
        (v, _, _) if (v - p.lower).min(p.upper - v) < 1e-3 * (p.upper - p.lower) => None,
        (v, Some(l), Some(h)) if l > 0.0 || h < 0.0 => Some(v),
        _ => None,
    };
    let (k_t, ln_m) = (demanded(ci.first()?, &params[0])?, demanded(ci.get(1)?, &params[1])?);
    // Stronger softening is k_T > 0 and ln_m < 0; a conflict is k_T and ln_m of one sign.
    (k_t * ln_m > 0.0).then(|| {
        let word = |stronger: bool| if stronger { "stronger" } else { "weaker" };
        format!(
            "both softening forms are demanded, in opposite directions (k_T = {k_t:+.3}: {}; ln_m = {ln_m:+.3}: {}): \
             the fitted flow-stress curve crosses the model's, a shape change with temperature rather than \
             softening stronger or weaker than the model's",
            word(k_t > 0.0),
            word(ln_m < 0.0)
        )
    })
}

/// Applies the output-level part of mechanism `id` to `preds`: only the dynamometer cross-talk
/// (M11, ISO 21612) acts on the recorded outputs; every other mechanism is inside the model.
pub fn correct(id: MechanismId, phi: &[f64], preds: &mut [Prediction]) {
    if id == MechanismId::ForceCrosstalk {
        for p in preds.iter_mut() {
            p.ft_n_per_m = (p.ft_n_per_m + phi[0] * p.fc_n_per_m).max(1.0);
        }
    }
}

/// Whether mechanism `id` can be tested on these tests (covariates present and varying).
///
/// Returns `Err(reason)` when it cannot.
pub fn testable(id: MechanismId, tests: &[CuttingTest], ctx: &Context, sim: &dyn Simulator) -> Result<(), String> {
    if let Some(hook) = info(id).hook {
        if !sim.supports(hook) {
            return Err(format!(
                "the simulation cannot switch it on (no {hook:?} hook; the shadow model was not built)"
            ));
        }
    }
    let distinct = |f: &dyn Fn(&CuttingTest) -> f64| {
        let mut v: Vec<f64> = tests.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs().max(1e-12));
        v.len()
    };
    match id {
        MechanismId::FlankWear => match &ctx.wear_state {
            Some(w) if w.iter().any(|x| *x > 0.0) && tests.len() >= 2 => Ok(()),
            _ => Err("needs the flank wear VB per test or the test order".into()),
        },
        MechanismId::SizeEffect if distinct(&|t| t.uncut_chip_thickness_m) < 2 => {
            Err("needs at least two uncut chip thicknesses".into())
        }
        MechanismId::BuiltUpEdge if ctx.bue_gate_c.is_none() && distinct(&|t| t.speed_m_per_s) < 3 => {
            Err("needs at least three speeds (or the interface temperature of the simulation)".into())
        }
        MechanismId::BuiltUpEdge if bue_onsets(tests, ctx).is_empty() => {
            Err("needs at least three distinct interface temperatures".into())
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_round_trip() {
        for m in MechanismId::ALL {
            assert_eq!(MechanismId::parse(m.as_str()), Some(m));
            assert_eq!(info(m).id, m);
        }
        assert_eq!(MechanismId::parse("gain_error"), None);
    }

    #[test]
    fn softening_conflicts_only_when_both_forms_are_demanded_against_each_other() {
        let c = |v: f64, l: f64, h: f64| (v, Some(l), Some(h));
        // Both stronger (k_T > 0, ln_m < 0) or both weaker: one-signed, no conflict.
        assert!(softening_conflict(&[c(0.2, 0.1, 0.3), c(-0.3, -0.4, -0.2)]).is_none());
        assert!(softening_conflict(&[c(-0.2, -0.3, -0.1), c(0.1, 0.02, 0.2)]).is_none());
        // One form not demanded (its interval spans 0), or not available: no conflict.
        assert!(softening_conflict(&[c(0.02, -0.08, 0.11), c(0.7, 0.26, 0.7)]).is_none());
        assert!(softening_conflict(&[(0.3, None, None), c(0.3, 0.1, 0.5)]).is_none());
        // ln_m on its upper bound 0.7 (not a free estimate): no conflict judged.
        assert!(softening_conflict(&[c(0.1, 0.04, 0.15), c(0.7, 0.45, 0.7)]).is_none());
        // k_T stronger and ln_m weaker, both demanded: a crossing curve.
        let why = softening_conflict(&[c(0.23, 0.16, 0.30), c(0.20, 0.07, 0.33)]).unwrap();
        assert!(why.contains("k_T = +0.230: stronger") && why.contains("ln_m = +0.200: weaker"), "{why}");
        assert!(softening_conflict(&[c(-0.25, -0.32, -0.18), c(-0.26, -0.44, -0.08)]).is_some());
    }

    #[test]
    fn recorded_edge_radii_keep_their_shape_and_wear_follows_the_order() {
        let mut a = CuttingTest::new("a", 2.0, 0.1e-3, 1e-3, 0.0).unwrap();
        let mut b = CuttingTest::new("b", 2.0, 0.2e-3, 1e-3, 0.0).unwrap();
        a.edge_radius_m = Some(10e-6);
        b.edge_radius_m = Some(30e-6);
        a.order = Some(1);
        b.order = Some(4);
        let tests = [a, b];
        let ctx = Context::of(&tests);
        let sim = crate::simulator::OxleySimulator::new(
            &cutcal_model::reference::aisi1045_lalwani2009(),
            crate::simulator::tests::jaspers(),
            &crate::simulator::JcBox::wide(),
            false,
        );
        let mut hooks = [Hooks::NEUTRAL; 2];
        // Mean recorded radius 20 um; r_e = 40 um doubles each: 20 and 60 um.
        set_hooks(MechanismId::EdgePloughing, &[40.0], &tests, &ctx, &sim, &mut hooks);
        assert!((hooks[0].edge_radius_m - 20e-6).abs() < 1e-12 && (hooks[1].edge_radius_m - 60e-6).abs() < 1e-12);
        // Order 1 and 4 of max 4: VB 0.05 and 0.2 mm for vb = 0.2 mm.
        set_hooks(MechanismId::FlankWear, &[0.2], &tests, &ctx, &sim, &mut hooks);
        assert!((hooks[0].wear_land_m - 0.05e-3).abs() < 1e-12 && (hooks[1].wear_land_m - 0.2e-3).abs() < 1e-12);
        // A running-in share w_0 = 0.4: VB = 0.2 (0.4 + 0.6 state) mm, 0.11 and 0.2 mm.
        let mut hooks = [Hooks::NEUTRAL; 2];
        set_hooks(MechanismId::FlankWear, &[0.2, 0.4], &tests, &ctx, &sim, &mut hooks);
        assert!((hooks[0].wear_land_m - 0.11e-3).abs() < 1e-12 && (hooks[1].wear_land_m - 0.2e-3).abs() < 1e-12);
    }

    #[test]
    fn row_order_is_the_run_order_only_for_an_unsorted_log() {
        // No `order` and no VB column: rows unsorted in h and V give the states (i + 1)/n; rows
        // sorted by feed give no run order (a wear trend over them is the feed's own effect).
        let t = |id: &str, v: f64, h: f64| CuttingTest::new(id, v / 60.0, h * 1e-3, 1e-3, 0.0).unwrap();
        let log = [t("a", 100.0, 0.2), t("b", 200.0, 0.1), t("c", 100.0, 0.1), t("d", 200.0, 0.2)];
        let ctx = Context::of(&log);
        assert_eq!(ctx.wear_state, Some(vec![0.25, 0.5, 0.75, 1.0]));
        assert!(ctx.order_from_rows);
        let sorted = [t("a", 100.0, 0.05), t("b", 200.0, 0.1), t("c", 100.0, 0.2), t("d", 200.0, 0.3)];
        let ctx = Context::of(&sorted);
        assert_eq!(ctx.wear_state, None);
        assert!(!ctx.order_from_rows);
    }

    #[test]
    fn size_effect_is_relative_to_the_geometric_mean_thickness_by_its_share_and_bue_follows_the_interface() {
        let t = |id: &str, v: f64, h: f64| CuttingTest::new(id, v / 60.0, h * 1e-3, 1e-3, 0.0).unwrap();
        let tests = [t("a", 100.0, 0.05), t("b", 100.0, 0.2), t("c", 100.0, 0.1)];
        let mut ctx = Context::of(&tests);
        // Geometric mean of 0.05, 0.2 and 0.1 mm: (0.001)^(1/3) = 0.1 mm.
        assert!((ctx.size_h_ref_m - 0.1e-3).abs() < 1e-12);
        // l = 100 um: at h = 0.05 mm sqrt(3 / 2), at h_ref 1, at 0.2 mm sqrt(1.5 / 2).
        assert!((size_factor(100.0, 1.0, &tests[0], ctx.size_h_ref_m) - 1.5f64.sqrt()).abs() < 1e-12);
        assert!((size_factor(100.0, 1.0, &tests[2], ctx.size_h_ref_m) - 1.0).abs() < 1e-12);
        assert!((size_factor(100.0, 1.0, &tests[1], ctx.size_h_ref_m) - 0.75f64.sqrt()).abs() < 1e-12);
        // w_ref = 0, the bulk material's flow stress: the absolute factor, sqrt(3) at 0.05 mm and
        // sqrt(2) at h_ref; w_ref = 1/2 divides it by 2^(1/4) at every thickness.
        assert!((size_factor(100.0, 0.0, &tests[0], ctx.size_h_ref_m) - 3f64.sqrt()).abs() < 1e-12);
        assert!((size_factor(100.0, 0.0, &tests[2], ctx.size_h_ref_m) - 2f64.sqrt()).abs() < 1e-12);
        assert!((size_factor(100.0, 0.5, &tests[2], ctx.size_h_ref_m) - 2f64.powf(0.25)).abs() < 1e-12);
        // One speed: no speed gate; with interface temperatures 400, 700, 550 degC the gate is the
        // temperature and the onset the geometric midpoint of the two coolest, sqrt(400 * 550).
        let sim = crate::simulator::OxleySimulator::new(
            &cutcal_model::reference::aisi1045_lalwani2009(),
            crate::simulator::tests::jaspers(),
            &crate::simulator::JcBox::wide(),
            false,
        );
        assert!(testable(MechanismId::BuiltUpEdge, &tests, &ctx, &sim).is_err());
        ctx.bue_gate_c = Some(vec![400.0, 700.0, 550.0]);
        assert_eq!(bue_onsets(&tests, &ctx), vec![(400.0f64 * 550.0).sqrt()]);
        assert!(testable(MechanismId::BuiltUpEdge, &tests, &ctx, &sim).is_ok());
    }
}
