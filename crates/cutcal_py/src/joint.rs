//! Joint face: JC fitted jointly to every measured test through the extended Oxley model (Oxley
//! 1989; Lalwani et al. 2009), n, C and m inside the literature box of the material class, with
//! the rank/condition verdict: `cutcal_report::joint::joint_fit`, the function
//! `cutcal identify --method oxley` calls. The set is returned only when the verdict says the data
//! determine it.

use std::path::Path;

use cutcal_io::material_file::MaterialFile;
use cutcal_model::{CuttingTest, JcParams};
use cutcal_report::joint::{joint_fit, verdict_line, JointRequest};
use cutcal_report::predict::oxley_options;
use cutcal_report::Context as _;

use crate::errors::{face, FaceResult};

/// Pseudo-file name of the tests of a joint fit given from Python (named in error messages).
pub const TESTS_SOURCE: &str = "<tests>";

/// What a joint identification returns to Python.
#[derive(Debug, Clone)]
pub struct JointOutput {
    /// The verdict in words (the CLI's `verdict:` line).
    pub verdict: String,
    /// `determined`, `undetermined`, `misfit` or `not_converged`.
    pub status: String,
    /// Whether the data determine the set.
    pub determined: bool,
    /// Effective rank of the scaled Jacobian (`None` when it could not be computed).
    pub effective_rank: Option<usize>,
    /// Number of free parameters (box width > 0; the CLI's "effective rank R of N").
    pub free_parameters: usize,
    /// Condition number of the scaled Jacobian (`None`: infinite or not computed).
    pub condition_number: Option<f64>,
    /// The identified set, only when determined.
    pub jc: Option<JcParams>,
    /// The best-fit set whatever the verdict (what the CLI prints; not an identification when
    /// undetermined).
    pub best_fit: JcParams,
    /// The JSON document of `cutcal identify --method oxley --json`.
    pub json: String,
}

/// The joint identification of `tests` (those with measured Fc and Ft take part) with the
/// material's bounds, the Oxley options of its `[oxley]` table, and `req`.
pub fn joint(mf: &MaterialFile, tests: &[CuttingTest], req: &JointRequest) -> FaceResult<JointOutput> {
    let oxley = oxley_options(mf.oxley.as_ref(), false, None, None, None, None, None)
        .with_context(|| format!("Oxley options for {}", mf.path.display()))
        .map_err(face)?;
    let id = joint_fit(mf, tests, Path::new(TESTS_SOURCE), oxley, req, None).map_err(face)?;
    let json = serde_json::to_string_pretty(&id).map_err(face)?;
    let status = serde_json::to_value(&id.verdict)
        .ok()
        .and_then(|v| v.get("status").and_then(|s| s.as_str()).map(str::to_string))
        .unwrap_or_default();
    let determined = id.verdict.is_determined();
    Ok(JointOutput {
        verdict: verdict_line(&id.verdict),
        status,
        determined,
        effective_rank: id.identifiability.as_ref().map(|a| a.effective_rank),
        free_parameters: id.identifiability.as_ref().map_or(id.statistics.free.len(), |a| a.parameters.len()),
        condition_number: id.identifiability.as_ref().and_then(|a| a.condition_number),
        jc: determined.then_some(id.jc),
        best_fit: id.jc,
        json,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::{material_from_file, tests_from_file};

    #[test]
    fn aisi1045_is_refused_as_undetermined_without_a_set() {
        // Ivester et al. 2000 via Lalwani 2009: four tests (Fc, Ft) cannot pin five parameters; the
        // pipeline report of fixtures/projects/aisi1045.toml says rank 2 of 5.
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mf = material_from_file(&root.join("fixtures/materials/aisi1045.toml")).unwrap();
        let tests = tests_from_file(&root.join("fixtures/tests/aisi1045.csv")).unwrap();
        let out = joint(&mf, &tests, &JointRequest { starts: 1, ..Default::default() }).unwrap();
        assert!(!out.determined && out.jc.is_none(), "{}", out.verdict);
        assert_eq!(out.status, "undetermined");
        assert!(out.effective_rank.is_some_and(|r| r < out.free_parameters), "{:?}", out.effective_rank);
        assert!(out.verdict.starts_with("REFUSED, not determined"), "{}", out.verdict);
        let bad = JointRequest { fix: vec![("q".into(), 1.0)], ..Default::default() };
        assert!(joint(&mf, &tests, &bad).unwrap_err().message.contains("--fix q=1"));
    }
}
