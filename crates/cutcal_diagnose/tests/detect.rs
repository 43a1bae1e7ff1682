//! Detection limits (`cutcal_diagnose::detect`) checked through the whole pipeline: an edge below
//! the limit the report states for these recordings stays unclaimed, and one well above it is
//! claimed, each by the same F-test the decision uses.
//!
//! The recordings are cutcal's Oxley model on C38 thermal data with a deterministic +-2 % scatter
//! (`common`), read in Mode A through the generic-steel shadow. The edge is cutcal's Waldorf
//! ploughing hook at a radius set from the stated limit: 0.4 of it (non-centrality 0.16 of the
//! limit's) and 2.5 of it (6.25 of the limit's).

mod common;

use common::{design, external, measured, run};
use cutcal_diagnose::hooks::Hooks;
use cutcal_diagnose::Report;

fn edge_limit_um(r: &Report) -> f64 {
    let e = r.mechanisms.iter().find(|m| m.id == "edge_ploughing").expect("the edge is refitted");
    let l = e.detection_limits.iter().find(|l| l.param == "r_e").expect("the edge has a limit");
    assert!(l.below.is_none() && l.note.contains("one-sided"), "{l:?}");
    l.above.expect("the edge is detectable within its range")
}

fn edge_p(r: &Report) -> f64 {
    r.mechanisms.iter().find(|m| m.id == "edge_ploughing").and_then(|m| m.p_value).expect("the edge's F-test")
}

#[test]
fn an_edge_below_the_stated_limit_goes_unclaimed_and_one_above_it_is_claimed() {
    let tests = design();
    let ext = external(&tests, &|_| Hooks::NEUTRAL);
    let null = run(&measured(&tests, &ext, &|_| 1.0), &ext);
    assert_eq!(null.verdict.as_str(), "none", "{}", null.to_text());
    let limit_um = edge_limit_um(&null);
    // The sentence of a `none` verdict names what could hide, or says that nothing of typical size could.
    assert!(null.explanation.contains("detect"), "{}", null.explanation);
    assert!((1.0..80.0).contains(&limit_um), "limit {limit_um} um");
    let with_edge = |factor: f64| {
        let r_m = factor * limit_um * 1e-6;
        let rec = measured(&tests, &external(&tests, &|_| Hooks { edge_radius_m: r_m, ..Hooks::NEUTRAL }), &|_| 1.0);
        run(&rec, &ext)
    };
    let small = with_edge(0.4);
    let level = small.thresholds.per_mechanism_alpha;
    assert!(edge_p(&small) > level, "p {} at 0.4 of the limit, level {level}: {}", edge_p(&small), small.to_text());
    assert!(!small.selected.contains(&"edge_ploughing".to_string()), "{}", small.to_text());
    let large = with_edge(2.5);
    let level = large.thresholds.per_mechanism_alpha;
    assert!(edge_p(&large) < level, "p {} at 2.5 of the limit, level {level}: {}", edge_p(&large), large.to_text());
    assert_eq!(large.selected, vec!["edge_ploughing".to_string()], "{}", large.to_text());
}
