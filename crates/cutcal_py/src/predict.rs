//! Predict face: the extended Oxley forward model (Oxley 1989; Lalwani et al. 2009) for a list of
//! tests (`cutcal predict --json`'s document) and, vectorised, for arrays of conditions.
//!
//! Both call `cutcal_model::oxley::predict`, the project's one forward model, with the options the
//! CLI resolves (`cutcal_report::predict::oxley_options`). `predict_many` runs the
//! conditions on rayon's pool; results are collected in index order, so they do not depend on the
//! thread count.

use cutcal_io::material_file::MaterialFile;
use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, OxleyPrediction, Physics};
use cutcal_model::{CuttingTest, JcParams};
use cutcal_report::predict::{oxley_options, predict_rows, PredictReport};
use cutcal_report::Context as _;
use rayon::prelude::*;

use crate::errors::{face, FaceResult};

/// Options of a prediction; the defaults are the CLI's (`cutcal predict --help`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PredictRequest {
    /// Work-material temperature, degC (default: the material's room temperature).
    pub work_temperature_c: Option<f64>,
    /// Lalwani et al. 2009's search ranges instead of the wide ones.
    pub lalwani_ranges: bool,
    /// Oxley's eta.
    pub eta: Option<f64>,
    /// Oxley's psi.
    pub psi: Option<f64>,
    /// Ignore stated edge radii and flank wear (the CLI's `--sharp`).
    pub sharp: bool,
}

/// The Oxley options and work temperature of a request, resolved as the CLI does.
pub fn resolve(mf: &MaterialFile, req: &PredictRequest) -> FaceResult<(OxleyOptions, f64)> {
    let options = oxley_options(mf.oxley.as_ref(), req.lalwani_ranges, req.eta, req.psi, None, None, None)
        .with_context(|| format!("Oxley options for {}", mf.path.display()))
        .map_err(face)?;
    Ok((options, req.work_temperature_c.unwrap_or(mf.material.room_c)))
}

/// Predicts every test: the document of `cutcal predict --json` (forces over the width in N, chip
/// thickness in mm, % errors against the measurements, the full SI prediction per row).
pub fn predict_tests(
    mf: &MaterialFile,
    jc: &JcParams,
    tests: &[CuttingTest],
    req: &PredictRequest,
) -> FaceResult<PredictReport> {
    let (options, work_c) = resolve(mf, req)?;
    let rows = predict_rows(&mf.material, jc, tests, &options, work_c, req.sharp);
    Ok(PredictReport {
        material: mf.material.name.clone(),
        options,
        work_temperature_c: work_c,
        sharp: req.sharp,
        rows,
    })
}

/// Conditions in the units of the test CSV columns, one entry per cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Condition {
    /// Cutting speed, m/min.
    pub speed_m_min: f64,
    /// Uncut chip thickness, mm.
    pub uncut_mm: f64,
    /// Width of cut, mm.
    pub width_mm: f64,
    /// Rake angle, deg.
    pub rake_deg: f64,
    /// Cutting-edge radius, um (None: sharp edge).
    pub edge_radius_um: Option<f64>,
    /// Flank wear land VB, mm (None: unworn).
    pub flank_wear_mm: Option<f64>,
}

/// Predicts each condition independently (in parallel), returning per condition the prediction
/// or the reason it is not available (an invalid condition or a solve that did not converge).
///
/// The tool terms are those of `cutcal predict`: baseline physics plus the stated edge radius and
/// flank wear (`Physics::with_tool`: Waldorf et al. 1998 ploughing, Smithey et al. 2001 wear land).
#[must_use]
pub fn predict_many(
    mf: &MaterialFile,
    jc: &JcParams,
    conditions: &[Condition],
    options: &OxleyOptions,
    work_temperature_c: f64,
) -> Vec<Result<OxleyPrediction, String>> {
    conditions
        .par_iter()
        .map(|c| {
            let physics = Physics::with_tool(c.edge_radius_um.map(|r| r * 1e-6), c.flank_wear_mm.map(|v| v * 1e-3))
                .map_err(|e| e.to_string())?;
            CuttingConditions::new(
                c.speed_m_min / 60.0,
                c.uncut_mm * 1e-3,
                c.width_mm * 1e-3,
                c.rake_deg.to_radians(),
                work_temperature_c,
            )
            .and_then(|cc| oxley::predict(&mf.material, jc, &cc, options, &physics))
            .map_err(|e| e.to_string())
        })
        .collect()
}

/// How a column of `predict_many` is read from a prediction.
pub type ColumnReader = fn(&OxleyPrediction) -> f64;

/// The columns `predict_many` returns, named with their units, and how each is read from a
/// prediction.
pub const MANY_COLUMNS: [(&str, ColumnReader); 10] = [
    ("fc_n", |p| p.cutting_force_n),
    ("ft_n", |p| p.feed_force_n),
    ("fc_n_per_mm", |p| p.cutting_force_n_per_m / 1e3),
    ("ft_n_per_mm", |p| p.feed_force_n_per_m / 1e3),
    ("tc_mm", |p| p.chip_thickness_m * 1e3),
    ("t_ab_c", |p| p.temperature_ab_c),
    ("t_int_c", |p| p.temperature_int_c),
    ("phi_deg", |p| p.phi_rad.to_degrees()),
    ("c0", |p| p.c0),
    ("delta", |p| p.delta),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::{jc_from_file, material_from_file, tests_from_file};
    use std::path::Path;

    #[test]
    fn predict_many_equals_the_per_test_prediction_and_reports_bad_rows() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        // AISI 1045 (Ivester/Lalwani, sharp) and C38 (paper Table 2, 25 um edge radius stated).
        for (material, jc, tests) in [("aisi1045", "aisi1045_jaspers2002", "aisi1045"), ("c38", "c38_table5", "c38")] {
            let mf = material_from_file(&root.join(format!("fixtures/materials/{material}.toml"))).unwrap();
            let jc = jc_from_file(&root.join(format!("fixtures/jc/{jc}.toml"))).unwrap().jc;
            let tests = tests_from_file(&root.join(format!("fixtures/tests/{tests}.csv"))).unwrap();
            let req = PredictRequest::default();
            let report = predict_tests(&mf, &jc, &tests, &req).unwrap();
            let (options, work_c) = resolve(&mf, &req).unwrap();
            let mut conds: Vec<Condition> = tests
                .iter()
                .map(|t| Condition {
                    speed_m_min: t.speed_m_per_s * 60.0,
                    uncut_mm: t.uncut_chip_thickness_m * 1e3,
                    width_mm: t.width_m * 1e3,
                    rake_deg: t.rake_rad.to_degrees(),
                    edge_radius_um: t.edge_radius_m.map(|r| r * 1e6),
                    flank_wear_mm: t.flank_wear_m.map(|v| v * 1e3),
                })
                .collect();
            conds.push(Condition { speed_m_min: -1.0, ..conds[0] });
            let many = predict_many(&mf, &jc, &conds, &options, work_c);
            for (row, got) in report.rows.iter().zip(&many) {
                // Only equality with the per-test path of `cutcal predict` is checked here.
                let (fc, ft) = (got.as_ref().unwrap().cutting_force_n, got.as_ref().unwrap().feed_force_n);
                assert!((fc / row.fc_n.unwrap() - 1.0).abs() < 1e-9, "{material} {}: {fc}", row.test);
                assert!((ft / row.ft_n.unwrap() - 1.0).abs() < 1e-9, "{material} {}: {ft}", row.test);
            }
            assert!(many.last().unwrap().as_ref().unwrap_err().contains("speed_m_per_s"));
        }
    }
}
