//! The measurement that tells two near-equivalent mechanisms apart (the `next_test` of an
//! ambiguous verdict), from the physics in which their signatures differ in kind, and what to do
//! instead when the recordings already hold that measurement; likewise a single mechanism's own
//! confirmation, less what the recordings hold (`own_test`); and a claim's runner-up, the next
//! candidate in AICc, with the evidence ratio of the two (`runner_up`; Burnham & Anderson 2002,
//! Secs 2.6 and 2.9).
//!
//! Each mechanism's own `separate_by` (`mechanism::library`) says what confirms it against the
//! baseline. Two rivals that explain the same forces and chip need the quantity in which they
//! move apart, which is a property of the pair:
//!
//! - friction and heat partition: a lower interface friction lowers the frictional heat and with
//!   it the interface temperature rise, while a larger share of that heat into the chip raises it
//!   at the same lower feed force (Oxley 1989, the interface temperature rise `dT_M` of the
//!   frictional heat; Boothroyd 1963, Loewen & Shaw 1954 on its partition);
//! - softening and heat partition: a partition moves the temperatures themselves, a different
//!   softening moves the flow stress at nearly the model's temperatures;
//! - friction and built-up edge: the edge is gone once the interface is hot (Trent & Wright 2000,
//!   Sec 5.3), a lower friction is not;
//! - edge ploughing and size effect: the ploughing force follows the edge radius (Waldorf, DeVor
//!   & Kapoor 1998), a size effect the uncut chip thickness alone (Nix & Gao 1998);
//! - edge ploughing and flank wear: the land grows along the run order, the edge does not;
//! - cross-talk against an edge, a wear land or friction: a dead weight in the cutting direction
//!   reads on the feed channel only through cross-talk (ISO 21612:2021).

use cutcal_model::CuttingTest;

use crate::mechanism::{info, MechanismId};
use crate::problem::Candidate;

/// AICc distance beyond which a candidate has essentially no support beside the best (Burnham &
/// Anderson 2002, Sec 2.6: dAICc > 10): the report names the claim's runner-up only within it.
const RUNNER_UP_DAICC: f64 = 10.0;

/// AICc distance within which the next test also separates the claim from its runner-up: an
/// evidence ratio below e^2 = 7.4 (Burnham & Anderson 2002, Sec 2.6: beyond 4 a model has
/// considerably less support).
const NEXT_TEST_DAICC: f64 = 4.0;

/// Which optional measurements the recordings hold at every test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Recorded {
    /// The tool-chip interface temperature (`t_int_c`).
    pub(crate) interface_temperature: bool,
    /// The flank wear land VB (`flank_wear_mm`).
    pub(crate) flank_wear: bool,
    /// The chip thickness (`chip_mm`).
    pub(crate) chip: bool,
    /// The edge radius (`edge_radius_um`).
    pub(crate) edge_radius: bool,
}

impl Recorded {
    /// What every one of `tests` records (an empty set records nothing).
    pub(crate) fn of(tests: &[CuttingTest]) -> Self {
        let all = |f: &dyn Fn(&CuttingTest) -> bool| !tests.is_empty() && tests.iter().all(f);
        Self {
            interface_temperature: all(&|t| t.measured.interface_temperature_c.is_some()),
            flank_wear: all(&|t| t.flank_wear_m.is_some()),
            chip: all(&|t| t.measured.chip_thickness_m.is_some()),
            edge_radius: all(&|t| t.edge_radius_m.is_some()),
        }
    }
}

/// What would confirm mechanism `m` against the model: its library test (`separate_by`), less the
/// measurements the recordings already hold, which the diagnosis has used.
pub(crate) fn own_test(m: MechanismId, rec: Recorded) -> String {
    use MechanismId as M;
    let text = match m {
        M::EdgePloughing if rec.edge_radius => {
            "add a smaller and a larger feed: ploughing is additive, its relative share growing as r/h with the \
             recorded edge radius r"
        }
        M::FlankWear if rec.flank_wear => {
            "randomise the test order, so that the recorded wear land no longer follows the test conditions"
        }
        M::ToolChipFriction if rec.chip => {
            "measure the tool-chip contact length, which a lower friction shortens as it thins the chip; a \
             channel-gain error moves neither"
        }
        M::ThermalSoftening if rec.interface_temperature => "widen the speed range (x10)",
        M::HeatPartition if rec.interface_temperature => {
            "add the slowest and the fastest speed the tool allows: the recorded interface temperature then \
             spans the thermal numbers V h over which a partition changes most"
        }
        _ => return crate::mechanism::info(m).separate_by.to_string(),
    };
    text.to_string()
}

/// When no mechanism was claimed on recordings that hold the interface temperature but weighed it
/// at the assumed default scatter `sd` (`assumed`: `crate::noise::NoiseModel::assumed`): how to
/// weigh it by what the measurement is worth. A temperature known to 3-5 % instead of 10 % counts
/// (10/4)^2 = 6 times as much in the fit, and the temperature is what tells a heat partition or a
/// softening from a flow-stress level.
pub(crate) fn interface_noise_note(
    verdict: crate::report::Verdict,
    rec: Recorded,
    assumed: bool,
    sd: f64,
) -> Option<String> {
    (verdict != crate::report::Verdict::MissingPhysics && rec.interface_temperature && assumed).then(|| {
        format!(
            "The interface temperature was weighed at an assumed {:.0} % scatter of its rise (no t_int_sd_c column, \
             no repeated conditions): if the measurement is known to be better, state its standard deviation per \
             row in t_int_sd_c (K), and the temperature then weighs as much as it is worth.",
            100.0 * sd
        )
    })
}

/// The next measurement that separates mechanisms `a` and `b` (in either order), given what the
/// recordings hold; `None` for a pair without one (the mechanisms' own tests then stand).
pub(crate) fn separating_test(a: MechanismId, b: MechanismId, rec: Recorded) -> Option<String> {
    use MechanismId as M;
    let is = |x: M, y: M| (a == x && b == y) || (a == y && b == x);
    let dead_weights = "check the force channels with dead weights in each direction (ISO 21612): only cross-talk \
                        reads a feed force under a load in the cutting direction";
    let text = if is(M::ToolChipFriction, M::HeatPartition) {
        if rec.interface_temperature {
            "the interface temperature recorded here does not yet separate them: add the slowest and the \
             fastest speed the tool allows, between which the tool's share of the frictional heat \
             changes most (Loewen & Shaw 1954)"
        } else {
            "measure the tool-chip interface temperature: a lower friction lowers the frictional heat and \
             the interface temperature with it, while a larger share of that heat into the chip raises it"
        }
    } else if is(M::ThermalSoftening, M::HeatPartition) {
        if rec.interface_temperature {
            "the interface temperature recorded here does not yet separate them: widen the speed range \
             (x10), over which a different softening grows with the temperature while a different \
             partition is largest at the lowest V h"
        } else {
            "measure the tool-chip interface temperature: a different heat partition moves the temperature \
             itself, a different softening moves the forces at nearly the model's temperatures"
        }
    } else if is(M::ToolChipFriction, M::BuiltUpEdge) {
        "repeat the lowest-speed test and inspect the rake face for adhered material, and add a speed \
         above the fastest: a built-up edge is gone once the interface is hot (Trent & Wright 2000), a \
         lower friction is not"
    } else if is(M::EdgePloughing, M::SizeEffect) {
        "repeat the thinnest cut with a tool of another edge radius: the ploughing force changes with the \
         radius, a size effect does not"
    } else if is(M::EdgePloughing, M::FlankWear) {
        if rec.flank_wear {
            "measure the edge radius before and after the series: the recorded wear land does not yet \
             separate them, and an edge that stays as it was leaves the trend to the wear"
        } else {
            "measure VB after each test and randomise the test order: the land grows along the run \
             order, the edge does not"
        }
    } else if is(M::ForceCrosstalk, M::EdgePloughing)
        || is(M::ForceCrosstalk, M::FlankWear)
        || is(M::ForceCrosstalk, M::ToolChipFriction)
    {
        dead_weights
    } else {
        return None;
    };
    Some(text.to_string())
}

/// The claim `chosen`'s runner-up among the round's candidates `cands`: the one of least dAICc after
/// it that also passed its significance test with a usable interval, no conflict and no
/// instrument stop, within [`RUNNER_UP_DAICC`]; with its AICc distance behind the claim.
pub(crate) fn runner_up(cands: &[Candidate], chosen: MechanismId) -> Option<(&Candidate, f64)> {
    let claim = cands.iter().find(|c| c.id == chosen && c.accepted)?;
    cands
        .iter()
        .filter(|c| c.id != chosen && c.significant && c.ci_ok && c.conflict.is_none() && c.stopped_by.is_none())
        .map(|c| (c, c.daicc - claim.daicc))
        .filter(|(_, d)| d.is_finite() && (0.0..RUNNER_UP_DAICC).contains(d))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Whether the library lists `a` and `b` as confounded (either in the other's list).
fn confounded(a: MechanismId, b: MechanismId) -> bool {
    info(a).confounders.contains(&b) || info(b).confounders.contains(&a)
}

/// The explanation's sentence on the claim's runner-up: how strongly the data prefer the claim
/// (the evidence ratio of the two Akaike weights, exp(dAICc / 2); Burnham & Anderson 2002, Sec
/// 2.9), and for a confounded pair what would tell them apart.
pub(crate) fn runner_up_sentence(cands: &[Candidate], chosen: MechanismId, rec: Recorded) -> Option<String> {
    let (r, delta) = runner_up(cands, chosen)?;
    // Within 4 units the support for the runner-up is not much less than the claim's (Burnham &
    // Anderson 2002, Sec 2.6), and the sentence says so.
    let weak = if delta < NEXT_TEST_DAICC { " only" } else { "" };
    let mut s = format!(
        "Next to {}, {} also passes the significance test (dAICc {:.1} against {:.1}): the data favour {}{weak} by \
         an evidence ratio of {:.1} to 1 (Akaike weights, Burnham & Anderson 2002).",
        chosen.as_str(),
        r.id.as_str(),
        r.daicc,
        r.daicc - delta,
        chosen.as_str(),
        (0.5 * delta).exp()
    );
    if delta < NEXT_TEST_DAICC {
        s.push_str(" That is weak evidence: treat the claim as provisional until the two are told apart.");
    }
    if confounded(chosen, r.id) {
        let sep = separating_test(chosen, r.id, rec).unwrap_or_else(|| own_test(r.id, rec));
        s.push_str(&format!(" The library lists the two as confounded; to tell them apart, {sep}."));
    }
    Some(s)
}

/// The next test's part that separates the claim from a confounded runner-up within
/// [`NEXT_TEST_DAICC`], or `None`.
pub(crate) fn runner_up_test(cands: &[Candidate], chosen: MechanismId, rec: Recorded) -> Option<String> {
    let (r, delta) = runner_up(cands, chosen).filter(|(r, d)| *d < NEXT_TEST_DAICC && confounded(chosen, r.id))?;
    let sep = separating_test(chosen, r.id, rec).unwrap_or_else(|| own_test(r.id, rec));
    Some(format!(
        "to separate {} from {} (evidence ratio {:.1} to 1), {sep}",
        chosen.as_str(),
        r.id.as_str(),
        (0.5 * delta).exp()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use MechanismId as M;

    #[test]
    fn a_pair_is_separated_the_same_way_in_either_order() {
        let rec = Recorded::default();
        for &a in &M::ALL {
            for &b in &M::ALL {
                assert_eq!(separating_test(a, b, rec), separating_test(b, a, rec), "{a:?} {b:?}");
            }
        }
        // A mechanism is not its own rival.
        assert!(M::ALL.iter().all(|&m| separating_test(m, m, rec).is_none()));
    }

    #[test]
    fn friction_and_heat_partition_are_told_apart_by_the_interface_temperature_unless_it_is_recorded() {
        let none = Recorded::default();
        let t = separating_test(M::ToolChipFriction, M::HeatPartition, none).unwrap();
        assert!(t.starts_with("measure the tool-chip interface temperature"), "{t}");
        let with_t = Recorded { interface_temperature: true, ..none };
        let t = separating_test(M::HeatPartition, M::ToolChipFriction, with_t).unwrap();
        assert!(t.contains("recorded here does not yet separate them"), "{t}");
        assert!(!t.starts_with("measure the tool-chip interface temperature"), "{t}");
    }

    #[test]
    fn a_recorded_wear_land_asks_for_the_edge_radius_instead() {
        let t = separating_test(M::FlankWear, M::EdgePloughing, Recorded::default()).unwrap();
        assert!(t.starts_with("measure VB after each test"), "{t}");
        let t = separating_test(M::FlankWear, M::EdgePloughing, Recorded { flank_wear: true, ..Recorded::default() })
            .unwrap();
        assert!(t.starts_with("measure the edge radius"), "{t}");
    }

    #[test]
    fn a_mechanism_s_own_test_drops_what_the_recordings_hold() {
        let none = Recorded::default();
        for &m in &M::ALL {
            assert_eq!(own_test(m, none), crate::mechanism::info(m).separate_by, "{m:?}");
        }
        let all = Recorded { interface_temperature: true, flank_wear: true, chip: true, edge_radius: true };
        assert!(!own_test(M::ToolChipFriction, all).contains("chip thickness"));
        assert!(!own_test(M::ThermalSoftening, all).contains("interface temperature"));
        assert!(!own_test(M::HeatPartition, all).starts_with("measure"));
        assert!(!own_test(M::FlankWear, all).contains("measure VB"));
        assert!(!own_test(M::EdgePloughing, all).contains("measure the edge radius"));
        // Recorded chip only: friction no longer asks for it, the others are as in the library.
        let chip = Recorded { chip: true, ..none };
        assert!(own_test(M::ToolChipFriction, chip).starts_with("measure the tool-chip contact length"));
        assert_eq!(own_test(M::HeatPartition, chip), crate::mechanism::info(M::HeatPartition).separate_by);
    }

    #[test]
    fn only_the_measurements_recorded_at_every_test_count() {
        let mut a = CuttingTest::new("1", 2.0, 1e-4, 2e-3, 0.0).unwrap();
        let mut b = CuttingTest::new("2", 3.0, 1e-4, 2e-3, 0.0).unwrap();
        assert_eq!(Recorded::of(&[a.clone(), b.clone()]), Recorded::default());
        a.measured.interface_temperature_c = Some(600.0);
        a.flank_wear_m = Some(1e-4);
        assert_eq!(Recorded::of(&[a.clone(), b.clone()]), Recorded::default());
        b.measured.interface_temperature_c = Some(650.0);
        a.measured.chip_thickness_m = Some(2e-4);
        let rec = Recorded::of(&[a, b]);
        assert!(rec.interface_temperature && !rec.flank_wear && !rec.chip && !rec.edge_radius);
        assert_eq!(Recorded::of(&[]), Recorded::default());
        // The note on the interface temperature's scatter: only without a claim, with the
        // temperature recorded at every test, and with its scatter assumed.
        use crate::report::Verdict as V;
        let with_t = Recorded { interface_temperature: true, ..Recorded::default() };
        let note = interface_noise_note(V::Ambiguous, with_t, true, 0.1).unwrap();
        assert!(note.contains("assumed 10 %") && note.contains("t_int_sd_c"), "{note}");
        assert!(interface_noise_note(V::MissingPhysics, with_t, true, 0.1).is_none());
        assert!(interface_noise_note(V::None, Recorded::default(), true, 0.1).is_none());
        assert!(interface_noise_note(V::None, with_t, false, 0.04).is_none());
    }

    fn cand(id: M, daicc: f64, accepted: bool) -> Candidate {
        Candidate::stub(id, daicc, accepted)
    }

    #[test]
    fn the_runner_up_is_the_next_valid_candidate_within_ten_aicc_units() {
        let rec = Recorded::default();
        let mut cands = vec![
            cand(M::ThermalSoftening, -33.6, true),
            cand(M::HeatPartition, -30.6, false),
            cand(M::EdgePloughing, -31.0, false),
        ];
        // The edge is nearer (2.6 units) but not significant: heat partition, 3.0 behind, is next.
        cands[2].significant = false;
        let (r, d) = runner_up(&cands, M::ThermalSoftening).unwrap();
        assert_eq!(r.id, M::HeatPartition);
        assert!((d - 3.0).abs() < 1e-12);
        // Evidence ratio exp(3.0 / 2) = 4.48 (Burnham & Anderson 2002, Sec 2.9), and the pair's
        // separating measurement, since the library lists them as confounded.
        let s = runner_up_sentence(&cands, M::ThermalSoftening, rec).unwrap();
        assert!(s.starts_with("Next to thermal_softening, heat_partition also passes"), "{s}");
        assert!(s.contains("favour thermal_softening only by an evidence ratio of 4.5 to 1"), "{s}");
        assert!(s.contains("treat the claim as provisional"), "{s}");
        assert!(s.contains("to tell them apart, measure the tool-chip interface temperature"), "{s}");
        let t = runner_up_test(&cands, M::ThermalSoftening, rec).unwrap();
        assert!(t.starts_with("to separate thermal_softening from heat_partition (evidence ratio 4.5 to 1)"), "{t}");
        // 5 units behind: named in the explanation, not in the next test (beyond 4).
        cands[1].daicc = -28.6;
        let s = runner_up_sentence(&cands, M::ThermalSoftening, rec).unwrap();
        assert!(s.contains("favour thermal_softening by an evidence ratio of 12.2 to 1"), "{s}");
        assert!(!s.contains("provisional"), "{s}");
        assert!(runner_up_test(&cands, M::ThermalSoftening, rec).is_none());
        // 10 or more behind, or a crossing softening refit: no runner-up.
        cands[1].daicc = -23.6;
        assert!(runner_up(&cands, M::ThermalSoftening).is_none());
        cands[1].daicc = -30.6;
        cands[1].conflict = Some("crossing".into());
        assert!(runner_up(&cands, M::ThermalSoftening).is_none());
        // A runner-up the library does not pair with the claim gets no separating measurement.
        cands[1].conflict = None;
        cands[1].id = M::SizeEffect;
        let s = runner_up_sentence(&cands, M::ThermalSoftening, rec).unwrap();
        assert!(!s.contains("confounded"), "{s}");
        assert!(runner_up_test(&cands, M::ThermalSoftening, rec).is_none());
    }

    proptest::proptest! {
        /// Over any round of candidates: the runner-up is never the claim, is a valid candidate
        /// (significant, usable interval, no conflict, no instrument stop) 0-10 AICc units behind
        /// it, no valid candidate lies nearer behind, and the next test names it only within 4
        /// units and for a confounded pair.
        #[test]
        fn the_runner_up_is_the_nearest_valid_candidate_behind_the_claim(
            rows in proptest::collection::vec((0usize..8, -60.0f64..10.0, proptest::bool::ANY, proptest::bool::ANY), 1..8),
            claim_daicc in -60.0f64..0.0,
        ) {
            let rec = Recorded::default();
            let mut cands = vec![cand(M::ALL[0], claim_daicc, true)];
            for (k, d, sig, ok) in &rows {
                let mut c = cand(M::ALL[*k], *d, false);
                c.significant = *sig;
                c.ci_ok = *ok;
                cands.push(c);
            }
            let chosen = M::ALL[0];
            let valid = |c: &Candidate| c.id != chosen && c.significant && c.ci_ok;
            let behind = |c: &Candidate| c.daicc - claim_daicc;
            match runner_up(&cands, chosen) {
                Some((r, d)) => {
                    proptest::prop_assert!(valid(r));
                    proptest::prop_assert!((0.0..10.0).contains(&d) && (d - behind(r)).abs() < 1e-12);
                    for c in cands.iter().filter(|c| valid(c)) {
                        proptest::prop_assert!(!(0.0..d).contains(&behind(c)), "{:?} is nearer", c.id);
                    }
                    let named = runner_up_test(&cands, chosen, rec).is_some();
                    proptest::prop_assert_eq!(named, d < 4.0 && confounded(chosen, r.id));
                }
                None => {
                    for c in cands.iter().filter(|c| valid(c)) {
                        proptest::prop_assert!(!(0.0..10.0).contains(&behind(c)));
                    }
                    proptest::prop_assert!(runner_up_sentence(&cands, chosen, rec).is_none());
                }
            }
        }
    }
}
