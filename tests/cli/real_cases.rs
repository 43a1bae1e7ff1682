//! The README's two real cases of `cutcal diagnose` ("Discrepancy discovery"), run through the
//! binary as a user runs them, so that what the README says of them stays true.

use super::json as report;

fn names(v: &serde_json::Value) -> Vec<&str> {
    v.as_array().expect("a list").iter().map(|s| s.as_str().expect("a name")).collect()
}

/// Paper Table 6, C38 test 3: DEFORM FE with the enhanced-DPZD JC against the measurement (Mode A,
/// no material file). One condition leaves nothing to check on held-out data: nothing is claimed,
/// and the answer is `ambiguous` between a cross-talk and an edge.
#[test]
fn c38_table6_is_ambiguous_between_cross_talk_and_an_edge() {
    let r = report(&[
        "diagnose",
        "--recordings",
        "fixtures/tests/c38.csv",
        "--simulation",
        "fixtures/diagnose/c38_table6_enhanced_sim.csv",
        "--json",
    ]);
    assert_eq!(r["verdict"], "ambiguous");
    assert!(names(&r["selected"]).is_empty());
    assert_eq!(names(&r["ambiguous_with"]), ["force_crosstalk", "edge_ploughing"]);
}

/// AISI 1045 (Ivester et al. 2000 via Lalwani 2009) against cutcal's own Oxley predictions (Mode B):
/// the edge is claimed. The size effect's reference share `w_ref` ends on its bound 0 there; a
/// shape parameter on its bound is not "the effect larger than the modelled range" (that note is
/// for a mechanism's strength, `screen::refit`).
#[test]
fn aisi1045_names_the_edge_and_a_shape_on_its_bound_is_not_a_far_bound() {
    let r = report(&[
        "diagnose",
        "--recordings",
        "fixtures/tests/aisi1045.csv",
        "--material",
        "fixtures/materials/aisi1045.toml",
        "--jc",
        "fixtures/jc/aisi1045_jaspers2002.toml",
        "--json",
    ]);
    assert_eq!(r["verdict"], "missing_physics");
    assert_eq!(names(&r["selected"]), ["edge_ploughing"]);
    let size =
        r["mechanisms"].as_array().unwrap().iter().find(|m| m["id"] == "size_effect").expect("size effect tried");
    let w_ref = &size["params"]["w_ref"];
    assert!(w_ref["value"].as_f64().unwrap() < 1e-3, "{w_ref}");
    assert!(!w_ref["ci_note"].as_str().unwrap().contains("far bound"), "{w_ref}");
}
