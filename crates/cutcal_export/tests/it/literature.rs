//! A JC set outside the literature box of its material class is never exported silently: every
//! card file's header (Abaqus, LS-DYNA, DEFORM-style, MatML notes) says which parameter is outside.
//! The Fortran VFRICTION source is the one file without the line (fixed-form comment width).

use cutcal_export::{render_all, render_cut2d};
use cutcal_model::CuttingTest;

use crate::common;

#[test]
fn a_set_outside_the_literature_box_is_flagged_in_every_header() {
    let mut case = common::cases().into_iter().find(|c| c.key == "c38").expect("c38 case");
    // The issue-15 AISI 1045 joint-fit set (n 0.60, C 0.003, m 0.70) on the C38 workpiece (a steel):
    // n above 0.432 and C below 0.008 (steel box from the published sets, cutcal_ident::literature).
    case.jc.n = 0.60;
    case.jc.c = 0.003;
    case.jc.m = 0.70;
    let prov = common::provenance(&case);
    let opts = common::options();
    let mut files = render_all(&common::input(&case, &prov, &opts)).expect("render");
    // The complete 2-D deck of a cut (C38 test 3: 240 m/min, 0.075 mm, 1.95 mm, rake 0) too.
    let test = CuttingTest::new("3", 4.0, 0.075e-3, 1.95e-3, 0.0).unwrap();
    files.push(render_cut2d(&common::input(&case, &prov, &opts), &test).expect("deck"));
    for f in &files {
        if f.name.ends_with(".f") {
            continue;
        }
        assert!(
            f.contents.contains("WARNING: JC n 0.6000 outside [0.1440, 0.4320]")
                && f.contents.contains("WARNING: JC C 0.0030 outside [0.0080, 0.1755]"),
            "{} has no literature warning",
            f.name
        );
    }
    // The paper's own C38 set (Table 5) is inside the box: no warning anywhere.
    let case = common::cases().into_iter().find(|c| c.key == "c38").expect("c38 case");
    let prov = common::provenance(&case);
    let files = render_all(&common::input(&case, &prov, &opts)).expect("render");
    assert!(files.iter().all(|f| !f.contents.contains("WARNING: JC")));
}
