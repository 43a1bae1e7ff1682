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

/// The library entry of `id`.
#[must_use]
pub fn info(id: MechanismId) -> MechanismInfo {
    use MechanismId as M;
    let p = |name, unit, lower, upper, off, typical| ParamInfo { name, unit, lower, upper, off, typical };
    match id {
        M::EdgePloughing => MechanismInfo {
            id,
            title: "cutting-edge ploughing (edge radius rubbing the machined surface)",
            source: "Waldorf, DeVor & Kapoor 1998 slip-line ploughing (cutcal_model::oxley::edge); design note M1",
            // The effective edge radius; with `edge_radius_um` recorded, the per-test radius keeps the
            // recorded shape: r_i = r_e r_rec,i / mean(r_rec).
            params: vec![p("r_e", "um", 0.0, 80.0, 0.0, 15.0)],
            hook: Some(Hook::EdgeRadius),
            signature: "Fc +, Ft ++ (relative residual grows as r_e/h), chip thickness unchanged",
            covariates: "uncut chip thickness; edge radius helps",
            confounders: &[M::FlankWear, M::SizeEffect, M::ForceCrosstalk],
            separate_by: "add a smaller and a larger feed (ploughing is additive: its relative share grows as 1/h) and measure the edge radius",
        },
        M::FlankWear => MechanismInfo {
            id,
            title: "flank wear land contact",
            source: "Smithey, Kapoor & DeVor 2001 wear-land model (cutcal_model::oxley::edge); design note M3",
            // VB at the most worn test; VB_i = VB x wear state (measured VB / max, else order / max).
            params: vec![p("vb", "mm", 0.0, 0.4, 0.0, 0.1)],
            hook: Some(Hook::WearLand),
            signature: "Fc +, Ft ++ growing with test order / measured VB, chip thickness unchanged",
            covariates: "flank wear VB per test, or the test order",
            confounders: &[M::EdgePloughing],
            separate_by: "measure VB after each test and randomise the test order",
        },
        M::ToolChipFriction => MechanismInfo {
            id,
            title: "tool-chip friction below full sticking (sliding region), falling with speed",
            source: "Zorev 1963; Oxley 1989; Rech, Claudin & D'Eramo 2009; design note M4, M5",
            // m_f = m_f0 (V / V_ref)^(-p_v), V_ref the geometric mean test speed (note M5). The
            // lower bound 0.2 of m_f0 admits the mean Zorev interface shear of note M4 with a short
            // sticking zone (a sticking fraction 0.2 and mu = 0.25 under its sigma_n = sigma_max
            // (1 - x/l_c)^2.5 give about 0.28 k_chip); p_v <= 0.5 is note M5's range.
            params: vec![p("m_f0", "-", 0.2, 1.0, 1.0, 0.85), p("p_v", "-", 0.0, 0.5, 0.0, 0.15)],
            hook: Some(Hook::FrictionFactor),
            signature: "Fc - (mild), Ft --, chip thinner; Ft/Fc falling with ln V when p_v > 0",
            covariates: "none for m_f0; p_v needs at least two speeds",
            confounders: &[M::ThermalSoftening, M::ForceCrosstalk],
            separate_by: "measure the chip thickness (mass-based) and the contact length; a channel-gain error does not move the chip",
        },
        M::ThermalSoftening => MechanismInfo {
            id,
            title: "thermomechanical softening different from the model's (stronger or weaker)",
            source: "Ertuerk, Malakizadi & Larsson 2020 (coupling k_T); Johnson & Cook 1983 (exponent m); design note M7",
            // Two forms, both two-sided: k_T scales the temperature rise the flow stress sees
            // (k_T < 0 weaker softening, > 0 stronger); ln_m scales the JC thermal exponent m
            // beyond the nuisance's +-5 % (a thermal exponent fitted at other temperatures, the
            // commonest source of a wrong softening). Together they span softening that is more
            // level-like (ln_m) or more temperature-selective (k_T) than the JC law's.
            params: vec![p("k_T", "-", -0.5, 1.5, 0.0, 0.2), p("ln_m", "-", -0.7, 0.7, 0.0, 0.2)],
            hook: Some(Hook::ExtraSoftening),
            signature: "k_T: forces over-predicted increasingly with speed and feed, Ft most, chip thinner; ln_m: mostly a force level with a mild trend in temperature",
            covariates: "a speed range of about a decade",
            confounders: &[M::HeatPartition, M::ToolChipFriction],
            separate_by: "widen the speed range (x10) and measure the interface temperature",
        },
        M::HeatPartition => MechanismInfo {
            id,
            title: "heat partition different from Oxley's: into the workpiece at the shear plane, into the tool at the interface",
            source: "Boothroyd 1963; Oxley 1989; Loewen & Shaw 1954; Komanduri & Hou 2001; design note M6",
            // k_beta scales Boothroyd's shear-plane share into the work, up to 3 (beta itself capped
            // at 1): Boothroyd's correlation gives 0.1-0.3 at the thermal numbers of practical
            // cutting, and a partition from another heat-source model (e.g. Loewen & Shaw 1954's
            // shear-plane share) can differ from it by a factor; at 1.8 estimates were pinned at the
            // bound. s_int is the share of the tool-chip frictional heat that enters the chip, which
            // Oxley takes as 1: Loewen & Shaw 1954 and Komanduri & Hou 2001 give the tool 10-50 % of
            // it at low chip speeds (0.5-0.9); above 1 (to 1.5) covers a dT_M correlation that runs low.
            params: vec![p("k_beta", "-", 0.4, 3.0, 1.0, 1.3), p("s_int", "-", 0.3, 1.5, 1.0, 0.8)],
            hook: Some(Hook::HeatPartition),
            signature: "k_beta: force residual that follows the thermal number V h (largest at low V h); s_int: interface temperature and chip-side flow stress, so Ft and the chip",
            covariates: "temperature measurement to separate it from JC m",
            confounders: &[M::ThermalSoftening, M::ToolChipFriction],
            separate_by: "measure the tool-chip interface temperature",
        },
        M::SizeEffect => MechanismInfo {
            id,
            title: "size effect (strengthening at small uncut chip thickness)",
            source: "Nix & Gao 1998; Joshi & Melkote 2004; design note M10",
            // Up to 3000 um: with l >> h the factor tends to sqrt(l/h), so the same form also covers
            // power-law (Kienzle-type) size effects of exponent up to 1/2 over a feed range; the
            // local exponent 0.5 (l/h) / (1 + l/h) is 0.45 at l/h = 10, i.e. h = 0.3 mm (a bound
            // of 300 um capped it at 0.25 there, and left strong size effects unexplained).
            // w_chip is the share of the strengthening the chip's flow stress at the interface takes:
            // 1 = every flow stress (Nix & Gao 1998 applied to the material), 0 = the primary shear
            // zone only (Joshi & Melkote 2004 apply the strain gradient to the primary zone, whose
            // thickness scales with h). The common level is the baseline's (relative to h_ref), but
            // the primary zone's strengthening over the chip's is absolute: in Oxley's closure k_chip
            // enters only tau_int = m_f k_chip, so the primary zone alone strengthened by
            // F = sqrt(1 + l/h) is every flow stress times F with the interface factor times
            // F^(w_chip - 1) (at most 1).
            params: vec![p("l_um", "um", 0.0, 3000.0, 0.0, 5.0), p("w_chip", "-", 0.0, 1.0, 1.0, 0.0)],
            hook: Some(Hook::FlowMultiplier),
            signature: "Fc and Ft up by the same factor at small h, Ft/Fc and chip unchanged (w_chip = 1); with the primary zone alone (w_chip < 1) the chip also thins and Ft/Fc falls at small h",
            covariates: "at least three feeds",
            confounders: &[M::EdgePloughing, M::ToolChipFriction],
            separate_by: "add a second edge radius or a wider feed range: Ft/Fc stays flat for a size effect",
        },
        M::BuiltUpEdge => MechanismInfo {
            id,
            title: "built-up edge at low speed",
            source: "Trent & Wright 2000; Childs et al. 2000; design note M9",
            params: vec![p("d_alpha", "deg", 0.0, 25.0, 0.0, 8.0), p("v_onset", "m/min", 1.0, 1e4, 0.0, 100.0)],
            hook: Some(Hook::RakeShift),
            signature: "Fc -, Ft --, chip thinner, only at the lowest speeds",
            covariates: "at least three speeds, two of them in the low-speed regime",
            confounders: &[M::ToolChipFriction],
            separate_by: "repeat the lowest-speed test twice and inspect the edge for adhered material",
        },
        M::ForceCrosstalk => MechanismInfo {
            id,
            title: "dynamometer cross-talk from the cutting-force channel into the feed channel",
            source: "ISO 21612:2021; design note M11",
            // Up to +-0.2: beyond a calibrated instrument's own cross-talk of a few per cent, a
            // measuring axis turned by theta against the cutting direction (tool holder or
            // dynamometer mounting) gives c = sin theta, 0.2 at 11.5 deg. At +-0.08 (4.6 deg) a
            // larger cross-talk was pinned at the bound and a second, spurious mechanism (edge
            // ploughing, softening) was claimed to carry the rest.
            params: vec![p("c_tc", "-", -0.2, 0.2, 0.0, 0.02)],
            hook: None,
            signature: "Ft shifted in proportion to Fc (grows with h), chip unchanged",
            covariates: "a wide feed range",
            confounders: &[M::EdgePloughing],
            separate_by: "check the dynamometer with dead weights in each direction",
        },
    }
}

/// Smooth indicator of the built-up edge on its gate coordinate (interface temperature, degC, or
/// speed, m/min; `Context::bue_coordinate`): 1 well below the onset, 0 well above.
#[must_use]
pub fn bue_indicator(coordinate: f64, onset: f64) -> f64 {
    // Logistic in the log of the coordinate with a width of 10 % of the onset.
    1.0 / (1.0 + ((coordinate.max(1e-9) / onset.max(1e-9)).ln() / 0.1).exp())
}

/// Speed-dependent interface friction factor `m_f0 (V / V_ref)^(-p_v)` (design note M5, the power
/// law in V; Rech, Claudin & D'Eramo 2009 measured friction falling with sliding speed).
#[must_use]
pub fn friction_factor(m_f0: f64, p_v: f64, speed_m_min: f64, v_ref_m_min: f64) -> f64 {
    m_f0 * (speed_m_min / v_ref_m_min).powf(-p_v)
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
                h.edge_radius_m += phi[0] * 1e-6 * shape;
            }
            MechanismId::FlankWear => {
                h.wear_land_m += phi[0] * 1e-3 * ctx.wear_state.as_ref().map_or(0.0, |w| w[i]);
            }
            MechanismId::ToolChipFriction => {
                h.friction_factor *= friction_factor(phi[0], phi[1], t.speed_m_per_s * 60.0, ctx.friction_v_ref_m_min)
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
                h.flow_multiplier *= size_factor(phi[0], t, ctx.size_h_ref_m);
                h.friction_factor *= nix_gao(phi[0], t).powf(phi[1] - 1.0);
            }
            MechanismId::BuiltUpEdge => {
                h.rake_shift_rad += phi[0].to_radians() * bue_indicator(ctx.bue_coordinate(tests, i), ctx.bue_onset)
            }
            _ => {}
        }
    }
}

/// Nix-Gao-type size factor `sqrt((1 + l/h) / (1 + l/h_ref))` with `l` in um (Nix & Gao 1998): the
/// strengthening relative to the reference thickness `h_ref` at which the simulation's flow stress
/// holds (`Context::size_h_ref_m`).
fn size_factor(l_um: f64, t: &CuttingTest, h_ref_m: f64) -> f64 {
    let l = l_um * 1e-6;
    ((1.0 + l / t.uncut_chip_thickness_m) / (1.0 + l / h_ref_m.max(1e-9))).sqrt()
}

/// The absolute Nix-Gao factor `sqrt(1 + l/h)` (Nix & Gao 1998), at least 1.
fn nix_gao(l_um: f64, t: &CuttingTest) -> f64 {
    (1.0 + l_um.max(0.0) * 1e-6 / t.uncut_chip_thickness_m).sqrt()
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

/// Candidate built-up-edge onsets on the gate coordinate: geometric midpoints between its distinct
/// values that leave at least a third of them (and at least two) out of the BUE regime; at most 8,
/// evenly spread over the ranks. An edge over nearly every condition is a uniform rake change, which
/// friction or softening explains as well: the onset is identified only with conditions on both
/// sides (with two above it, friction and softening datasets were named `built_up_edge`).
#[must_use]
pub fn bue_onsets(tests: &[CuttingTest], ctx: &Context) -> Vec<f64> {
    let mut v: Vec<f64> = (0..tests.len()).map(|i| ctx.bue_coordinate(tests, i)).filter(|x| *x > 0.0).collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-3 * b.abs());
    if v.len() < 2 {
        return Vec::new();
    }
    let above = 2.max(v.len().div_ceil(3));
    let all: Vec<f64> = v.windows(2).map(|w| (w[0] * w[1]).sqrt()).take(v.len().saturating_sub(above).max(1)).collect();
    if all.len() <= 8 {
        return all;
    }
    (0..8).map(|k| all[k * (all.len() - 1) / 7]).collect()
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
    fn friction_factor_falls_with_speed_about_the_reference() {
        // m_f0 (V/V_ref)^(-p_v): equal to m_f0 at V_ref, 2^(-0.2) = 0.8706 of it at twice V_ref,
        // constant when p_v = 0; the context's V_ref is the geometric mean speed (80, 320 -> 160).
        assert!((friction_factor(0.7, 0.2, 150.0, 150.0) - 0.7).abs() < 1e-12);
        assert!((friction_factor(0.7, 0.2, 300.0, 150.0) - 0.7 * 0.870_550_563_3).abs() < 1e-9);
        assert!((friction_factor(0.7, 0.0, 37.0, 150.0) - 0.7).abs() < 1e-12);
        let tests = [
            CuttingTest::new("a", 80.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
            CuttingTest::new("b", 320.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
        ];
        assert!((Context::of(&tests).friction_v_ref_m_min - 160.0).abs() < 1e-9);
    }

    #[test]
    fn speed_exponent_moves_the_oxley_model_in_the_m5_direction() {
        // Note Sec 2.3, M5: with p_v > 0 the feed force falls with ln V relative to constant m_f.
        let m = cutcal_model::reference::aisi1045_lalwani2009();
        let jc = crate::simulator::tests::jaspers();
        let tests = [
            CuttingTest::new("lo", 100.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
            CuttingTest::new("hi", 400.0 / 60.0, 0.1e-3, 1e-3, 0.0).unwrap(),
        ];
        let ctx = Context::of(&tests);
        let sim = crate::simulator::OxleySimulator::new(&m, jc, &crate::simulator::JcBox::wide(), false);
        let ratio = |p_v: f64| {
            let mut hooks = [Hooks::NEUTRAL; 2];
            set_hooks(MechanismId::ToolChipFriction, &[0.7, p_v], &tests, &ctx, &sim, &mut hooks);
            let r = sim.simulate(&tests, &[], &hooks).unwrap();
            r[1].ft_n_per_m / r[0].ft_n_per_m
        };
        assert!(ratio(0.3) < 0.97 * ratio(0.0), "{} vs {}", ratio(0.3), ratio(0.0));
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
    fn bue_onsets_leave_a_third_of_the_gate_values_above() {
        // Nine interface temperatures 400, 450, ..., 800 degC: a third (3) must stay above the
        // onset, so the candidates are the 6 midpoints below the seventh value, the last one
        // sqrt(650 * 700); with three values, two stay above and one midpoint remains.
        let t = |i: usize| CuttingTest::new(format!("t{i}"), 2.0, 0.1e-3, 1e-3, 0.0).unwrap();
        let tests: Vec<CuttingTest> = (0..9).map(t).collect();
        let mut ctx = Context::of(&tests);
        ctx.bue_gate_c = Some((0..9).map(|i| 400.0 + 50.0 * i as f64).collect());
        let on = bue_onsets(&tests, &ctx);
        assert_eq!(on.len(), 6);
        assert!((on[5] - (650.0f64 * 700.0).sqrt()).abs() < 1e-9, "{on:?}");
        let tests3: Vec<CuttingTest> = (0..3).map(t).collect();
        let mut ctx3 = Context::of(&tests3);
        ctx3.bue_gate_c = Some(vec![400.0, 500.0, 600.0]);
        assert_eq!(bue_onsets(&tests3, &ctx3), vec![(400.0f64 * 500.0).sqrt()]);
    }

    #[test]
    fn bue_indicator_switches_at_onset() {
        // Logistic in ln V with width 0.1: at V = onset it is 1/2; at V = 2 onset it is 1/(1 + e^6.93).
        assert!((bue_indicator(80.0, 80.0) - 0.5).abs() < 1e-12);
        assert!(bue_indicator(160.0, 80.0) < 1e-3 && bue_indicator(40.0, 80.0) > 0.999);
    }

    #[test]
    fn size_effect_is_relative_to_the_geometric_mean_thickness_and_bue_follows_the_interface() {
        let t = |id: &str, v: f64, h: f64| CuttingTest::new(id, v / 60.0, h * 1e-3, 1e-3, 0.0).unwrap();
        let tests = [t("a", 100.0, 0.05), t("b", 100.0, 0.2), t("c", 100.0, 0.1)];
        let mut ctx = Context::of(&tests);
        // Geometric mean of 0.05, 0.2 and 0.1 mm: (0.001)^(1/3) = 0.1 mm.
        assert!((ctx.size_h_ref_m - 0.1e-3).abs() < 1e-12);
        // l = 100 um: at h = 0.05 mm sqrt(3 / 2), at h_ref 1, at 0.2 mm sqrt(1.5 / 2).
        assert!((size_factor(100.0, &tests[0], ctx.size_h_ref_m) - 1.5f64.sqrt()).abs() < 1e-12);
        assert!((size_factor(100.0, &tests[2], ctx.size_h_ref_m) - 1.0).abs() < 1e-12);
        assert!((size_factor(100.0, &tests[1], ctx.size_h_ref_m) - 0.75f64.sqrt()).abs() < 1e-12);
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
