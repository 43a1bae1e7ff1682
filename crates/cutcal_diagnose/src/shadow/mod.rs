//! Mode A: the *shadow* of an external simulation (issue 10, item 1).
//!
//! The user has an external simulation (an FE run, another code) per test and the recordings, and
//! often no cutcal material file. cutcal fits its own extended Oxley model (Oxley 1989; Lalwani,
//! Mehta & Jain 2009; `cutcal_model::oxley`) to the external numbers with a few global parameters
//! (a flow-stress level, the JC hardening exponent n and the rate and thermal sensitivities C and m;
//! then, each only where it halves the misfit left: a scale on Oxley's strain-rate constant C0,
//! where the simulation's primary zone is not Oxley's (another code's closure, an FE run's zone set
//! by its mesh); a tool-chip interface factor m_f, tau_int = m_f k_chip: an FE run's contact law is
//! rarely Oxley's full sticking; an edge radius of its own, where the simulation carries ploughing
//! forces: an FE run with the tool's real edge), on the given material's thermal properties or a
//! generic class's. The shadow's response to each
//! mechanism hook and to each nuisance knob, computed at every test's own conditions, is then the
//! signature laid on top of the external numbers:
//!
//! `ln y_i(theta, hooks) = ln y_ext,i + sum_k [S_ik(u_ik) - S_ik(u_k,off)]`
//!
//! with `S_ik` the shadow's `ln Fc, ln Ft, ln t2` (and temperatures) as a function of knob `k` at
//! test `i`, tabulated on a grid and interpolated by monotone cubic Hermite splines (Fritsch &
//! Carlson 1980). Knob effects combine additively in the logarithm (first order in the
//! interactions). Nothing is taken from constants measured at one reference condition.

mod fitted;
mod globals;
mod knobs;
mod memo;

use cutcal_model::{CuttingTest, JcParams, Material};

use crate::error::DiagnoseError;
use crate::hooks::{Hook, Hooks};
use crate::simulator::{ParamSpec, Prediction, Simulator};
use crate::spline::Table;
pub use fitted::FittedShadow;
use knobs::tables_at;

/// What the shadow fit found (for the report).
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowSummary {
    /// Material of the shadow (its thermal properties).
    pub material: String,
    /// The shadow's JC set after the fit.
    pub jc: JcParams,
    /// The shadow's tool-chip interface factor m_f (1 = Oxley's full sticking; fitted only where it
    /// halves the misfit).
    pub friction_factor: f64,
    /// The shadow's own edge radius, m (0 = sharp; fitted only where it halves the misfit and
    /// brings the shadow within [`SHADOW_CAUTION_RMS_PCT`]).
    pub edge_radius_m: f64,
    /// The shadow's scale on Oxley's strain-rate constant C0 (1 = Oxley's normal-stress condition;
    /// fitted only where it halves the misfit).
    pub c0_scale: f64,
    /// RMS of `ln(y_shadow / y_external)` over all outputs, %, after the fit.
    pub rms_pct: f64,
    /// Tests whose shadow had no solution (no signature; Mode A leaves them out), with the reason.
    pub unsolved: Vec<(String, String)>,
    /// Whether the shadow fit met a tolerance.
    pub converged: bool,
    /// Whether the fitted JC set was set aside for the nominal one at the start level (the fitted
    /// set left more tests without a solution).
    pub fit_discarded: bool,
}

/// Shadow RMS (%) above which the report cautions that the signatures are approximate. On the
/// concealed benchmark (`docs/concealed.md`) naming at ENR >= 2 was about 85 % where the shadow
/// reproduced family a's simulations within 3 % and about 65 % beyond 6 % (twelfth session). With
/// the seventeenth session's gated globals, families b, c and d name 69 % within 3 % and 73 %
/// beyond 6 %: the caution states the approximation, not a measured loss.
pub const SHADOW_CAUTION_RMS_PCT: f64 = 6.0;

impl ShadowSummary {
    /// A caution for the report when the shadow reproduces the external simulation poorly.
    #[must_use]
    pub fn fidelity_note(&self) -> Option<String> {
        (self.rms_pct > SHADOW_CAUTION_RMS_PCT).then(|| {
            format!(
                "the shadow reproduces the external simulation only to {:.1} % (RMS), beyond the \
                 {SHADOW_CAUTION_RMS_PCT:.0} % within which it is taken as close: its per-test signatures are \
                 approximate, so a named mechanism is less certain",
                self.rms_pct
            )
        })
    }
}

/// Mode A simulator: the external numbers, moved by the shadow's per-test signatures.
#[derive(Debug, Clone)]
pub struct ShadowSimulation {
    ids: Vec<String>,
    external: Vec<Prediction>,
    /// `tables[i][k]`: test i, knob k (order of `KNOBS`); `None` when the shadow has no solution.
    tables: Vec<Option<Vec<Table>>>,
    params: Vec<ParamSpec>,
    /// Whether `params` opens with the free flow-stress level.
    level_free: bool,
    /// Whether every id in `ids` is distinct (then a test found at its own position is the one
    /// a search would find).
    ids_distinct: bool,
    summary: ShadowSummary,
    /// Identity for the per-thread memo of knob deltas (`memo`); the tables never change after
    /// tabulation, so a clone may share it.
    memo_id: u64,
}

impl ShadowSimulation {
    /// Fits the shadow to `external` (one prediction per test of `tests`, same order) on
    /// `material` from the JC set `nominal` ([`FittedShadow::fit`]), then tabulates every knob at
    /// every test ([`ShadowSimulation::tabulate`]).
    ///
    /// `level_free`: whether the diagnosis baseline gets a free flow-stress level (use it with at
    /// least three conditions).
    ///
    /// Returns an error if the shadow has no solution at more than half of the tests.
    pub fn build(
        material: &Material,
        nominal: JcParams,
        tests: &[CuttingTest],
        external: &[Prediction],
        level_free: bool,
    ) -> Result<Self, DiagnoseError> {
        Ok(Self::tabulate(FittedShadow::fit(material, nominal, tests, external)?, tests, external, level_free))
    }

    /// Tabulates the fitted shadow's response to every knob at every test it solves (the tests
    /// and external numbers it was fitted to).
    #[must_use]
    pub fn tabulate(fitted: FittedShadow, tests: &[CuttingTest], external: &[Prediction], level_free: bool) -> Self {
        let built = tables_at(&fitted.shadow(), tests, &fitted.bases);
        let mut summary = fitted.summary;
        // A table fails only without a solved off node, which every solved test has; were one to
        // fail, its test is listed as unsolved rather than lost.
        let tables = built
            .into_iter()
            .zip(tests)
            .map(|(r, t)| match r? {
                Ok(v) => Some(v),
                Err(e) => {
                    summary.unsolved.push((t.id.clone(), e.to_string()));
                    None
                }
            })
            .collect();
        // Nuisance bounded by what its stated uncertainty produces (`crate::nuisance`).
        let params = crate::nuisance::mode_a_params(level_free);
        let ids: Vec<String> = tests.iter().map(|t| t.id.clone()).collect();
        let ids_distinct = ids.iter().collect::<std::collections::HashSet<_>>().len() == ids.len();
        Self {
            ids,
            ids_distinct,
            external: external.to_vec(),
            tables,
            params,
            level_free,
            summary,
            memo_id: memo::next_id(),
        }
    }

    /// What the shadow fit found.
    #[must_use]
    pub fn summary(&self) -> &ShadowSummary {
        &self.summary
    }

    /// Knob coordinates of test hooks `h` at baseline `theta`, in the order of `KNOBS`.
    fn coordinates(&self, theta: &[f64], h: &Hooks) -> [f64; 12] {
        let o = usize::from(self.level_free);
        let level = if self.level_free { theta.first().copied().unwrap_or(0.0) } else { 0.0 };
        let nuis = |k: usize, def: f64| theta.get(o + k).copied().unwrap_or(def);
        [
            h.friction_factor,
            h.heat_partition_scale,
            h.extra_softening,
            h.rake_shift_rad,
            level + h.flow_multiplier.max(1e-6).ln(),
            h.edge_radius_m,
            h.wear_land_m,
            nuis(0, 0.9),
            nuis(1, 0.9) * h.interface_heat_share,
            nuis(2, 0.0),
            nuis(3, 0.0),
            nuis(4, 0.0) + h.thermal_exponent_ln_scale,
        ]
    }
}

impl Simulator for ShadowSimulation {
    fn baseline_params(&self) -> &[ParamSpec] {
        &self.params
    }
    fn supports(&self, _hook: Hook) -> bool {
        true
    }
    fn can_extrapolate(&self) -> bool {
        false
    }
    fn simulate(
        &self,
        tests: &[CuttingTest],
        theta: &[f64],
        hooks: &[Hooks],
    ) -> Result<Vec<Prediction>, DiagnoseError> {
        let slots = self.tables.len() * knobs::KNOBS.len();
        memo::with_memo(self.memo_id, slots, |memo| {
            tests
                .iter()
                .zip(hooks)
                .enumerate()
                .map(|(j, (t, h))| {
                    // The tests usually come in the simulation's own order (a held-out fold drops
                    // some): look there first, then search (the first match, as ever).
                    let i = if self.ids_distinct && self.ids.get(j).is_some_and(|id| *id == t.id) {
                        j
                    } else {
                        self.ids.iter().position(|id| *id == t.id).ok_or_else(|| {
                            DiagnoseError::Inconsistent(format!(
                                "test `{}` is in the recordings but not in the simulation",
                                t.id
                            ))
                        })?
                    };
                    let e = self.external[i];
                    let Some(tabs) = &self.tables[i] else { return Ok(e) };
                    let u = self.coordinates(theta, h);
                    let mut d = [0.0; 5];
                    for (k, (tab, &uk)) in tabs.iter().zip(&u).enumerate() {
                        let dv = memo.delta(i * knobs::KNOBS.len() + k, tab, uk);
                        for j in 0..5 {
                            d[j] += dv[j];
                        }
                    }
                    // The flow-stress level's off value is 0: its table's value there is the shadow's own.
                    let base = tabs[4].at_off();
                    Ok(Prediction {
                        fc_n_per_m: e.fc_n_per_m * d[0].exp(),
                        ft_n_per_m: e.ft_n_per_m * d[1].exp(),
                        chip_m: e.chip_m * d[2].exp(),
                        t_ab_c: Some(e.t_ab_c.unwrap_or(base[3]) + d[3]),
                        t_int_c: Some(e.t_int_c.unwrap_or(base[4]) + d[4]),
                        beta: e.beta,
                    })
                })
                .collect()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::globals::FRICTION_TRY_RMS_PCT;
    use super::*;

    fn summary(rms_pct: f64) -> ShadowSummary {
        ShadowSummary {
            material: "AISI1045".into(),
            jc: crate::classes::MaterialClass::Steel.material().1,
            friction_factor: 1.0,
            edge_radius_m: 0.0,
            c0_scale: 1.0,
            rms_pct,
            unsolved: Vec::new(),
            converged: true,
            fit_discarded: false,
        }
    }

    fn steel_case(friction_factor: f64) -> (Material, JcParams, Vec<CuttingTest>, Vec<Prediction>) {
        steel_case_at(friction_factor, 1.1)
    }

    fn steel_case_at(friction_factor: f64, level: f64) -> (Material, JcParams, Vec<CuttingTest>, Vec<Prediction>) {
        steel_case_with(Hooks { friction_factor, ..Hooks::NEUTRAL }, level)
    }

    fn steel_case_with(hooks: Hooks, level: f64) -> (Material, JcParams, Vec<CuttingTest>, Vec<Prediction>) {
        use crate::simulator::oxley_with_hooks;
        use cutcal_model::oxley::OxleyOptions;
        let (m, jc) = crate::classes::MaterialClass::Steel.material();
        let tests: Vec<CuttingTest> =
            [(100.0, 0.05), (200.0, 0.1), (300.0, 0.2), (100.0, 0.2), (300.0, 0.05), (200.0, 0.15)]
                .iter()
                .enumerate()
                .map(|(i, (v, h))| {
                    CuttingTest::new(format!("{i}"), v / 60.0, h * 1e-3, 2e-3, 5f64.to_radians()).unwrap()
                })
                .collect();
        // The external simulation: the class's own model with the flow stress scaled by `level` and
        // the given hooks (interface factor, edge radius).
        let ext_jc = JcParams { a_pa: jc.a_pa * level, b_pa: jc.b_pa * level, ..jc };
        let ext =
            tests.iter().map(|t| oxley_with_hooks(&m, &ext_jc, t, &hooks, &OxleyOptions::wide()).unwrap()).collect();
        (m, jc, tests, ext)
    }

    #[test]
    fn an_external_contact_below_sticking_is_recovered_as_the_shadows_interface_factor() {
        // A simulation whose interface shear is 0.6 k_chip (an FE shear-factor contact): the four
        // globals cannot reproduce it; m_f halves the misfit, is kept and comes back near 0.6.
        let (m, jc, tests, ext) = steel_case(0.6);
        let sim = ShadowSimulation::build(&m, jc, &tests, &ext, true).unwrap();
        let sm = sim.summary();
        assert!((sm.friction_factor - 0.6).abs() < 0.05, "m_f {}", sm.friction_factor);
        assert!(sm.rms_pct < 1.0, "RMS {}", sm.rms_pct);
    }

    #[test]
    fn an_external_edge_is_recovered_as_the_shadows_edge_radius() {
        // A simulation with a 20 um edge (Waldorf ploughing forces on top of the chip's) at a 10 %
        // level: no flow-stress global reproduces forces that grow relatively as h falls; the
        // shadow's own edge radius halves the misfit, is kept and comes back near 20 um.
        let (m, jc, tests, ext) = steel_case_with(Hooks { edge_radius_m: 20e-6, ..Hooks::NEUTRAL }, 1.1);
        let sim = ShadowSimulation::build(&m, jc, &tests, &ext, true).unwrap();
        let sm = sim.summary();
        assert!((sm.edge_radius_m * 1e6 - 20.0).abs() < 2.0, "r_e {} um", sm.edge_radius_m * 1e6);
        assert!(sm.rms_pct < 1.0, "RMS {}", sm.rms_pct);
        // The edge is chosen over the other gated globals, which are then not needed.
        assert_eq!((sm.c0_scale, sm.friction_factor), (1.0, 1.0));
        // A sharp simulation keeps a sharp shadow.
        let (m, jc, tests, ext) = steel_case(1.0);
        assert_eq!(ShadowSimulation::build(&m, jc, &tests, &ext, true).unwrap().summary().edge_radius_m, 0.0);
    }

    #[test]
    fn another_codes_primary_zone_is_taken_up_by_the_c0_scale() {
        // A simulation whose primary zone is 1/0.3 times as thick as Oxley's closure puts it (C0
        // scaled by 0.3) at a 10 % level: the JC globals leave its chip and force ratio; the C0
        // scale halves the misfit, is kept and comes back near 0.3.
        let (m, jc, tests, ext) = steel_case_with(Hooks { c0_scale: 0.3, ..Hooks::NEUTRAL }, 1.1);
        let sim = ShadowSimulation::build(&m, jc, &tests, &ext, true).unwrap();
        let sm = sim.summary();
        assert!((sm.c0_scale - 0.3).abs() < 0.05, "C0 scale {}", sm.c0_scale);
        assert!(sm.rms_pct < 1.0, "RMS {}", sm.rms_pct);
        // Oxley's own closure keeps the scale at 1.
        let (m, jc, tests, ext) = steel_case(1.0);
        assert_eq!(ShadowSimulation::build(&m, jc, &tests, &ext, true).unwrap().summary().c0_scale, 1.0);
    }

    #[test]
    fn a_sticking_simulation_keeps_oxleys_contact() {
        let (m, jc, tests, ext) = steel_case(1.0);
        let sim = ShadowSimulation::build(&m, jc, &tests, &ext, true).unwrap();
        let sm = sim.summary();
        assert!((sm.friction_factor - 1.0).abs() < 1e-12, "m_f {}", sm.friction_factor);
        assert!(sm.rms_pct < FRICTION_TRY_RMS_PCT, "RMS {}", sm.rms_pct);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]
        /// Either the shadow recovers the simulation's interface factor, or the four other
        /// globals already reproduce it within the gate's 3 % and m_f stays at Oxley's 1. (Scan at a
        /// 10 % level: m_f 0.4-0.8 recovered exactly, 0.85-0.95 absorbed at RMS 3.0, 2.0, 1.0 %.)
        #[test]
        fn the_shadow_recovers_an_interface_factor_or_absorbs_it_within_the_gate(
            truth in 0.35f64..1.0,
            level in 0.9f64..1.15,
        ) {
            let (m, jc, tests, ext) = steel_case_at(truth, level);
            let sim = ShadowSimulation::build(&m, jc, &tests, &ext, true).unwrap();
            let sm = sim.summary();
            let recovered = (sm.friction_factor - truth).abs() < 0.02 && sm.rms_pct < 0.5;
            let absorbed = sm.friction_factor == 1.0 && sm.rms_pct <= FRICTION_TRY_RMS_PCT;
            proptest::prop_assert!(recovered || absorbed, "truth {truth}, level {level}: m_f {}, RMS {}", sm.friction_factor, sm.rms_pct);
        }
    }

    #[test]
    fn a_poor_shadow_is_flagged_and_a_close_one_is_not() {
        assert!(summary(2.5).fidelity_note().is_none());
        assert!(summary(SHADOW_CAUTION_RMS_PCT).fidelity_note().is_none());
        let note = summary(21.0).fidelity_note().expect("a 21 % shadow is flagged");
        assert!(note.contains("only to 21.0 %") && note.contains("less certain"), "{note}");
    }
}
