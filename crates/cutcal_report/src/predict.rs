//! Predictions (`cutcal predict`, `cutcal run`, Python's `predict`): forces, chip thickness and temperatures of every test of a CSV from a JC set
//! through the extended Oxley model (Lalwani et al. 2009), against the measurements where given.
//!
//! Tool condition: when a test states its edge radius (`edge_radius_um`) or flank wear
//! (`flank_wear_mm`), the prediction includes edge ploughing (Waldorf, DeVor & Kapoor 1998) and the
//! wear land (Smithey, Kapoor & DeVor 2001), scaled by the solution's k_AB (see
//! `cutcal_model::oxley::EdgePloughing`); their contributions are shown per test in the table and
//! the JSON. `--sharp` turns both off.
//!
//! Units of the report: forces in N over the test's width (the CSV may give totals `fc_n`/`ft_n`
//! with `width_mm`, or `fc_n_per_mm`/`ft_n_per_mm`; both are read as per-unit-width and multiplied
//! by the width here), chip thickness in mm, temperatures in degC, errors in % of the measurement.

use std::path::Path;

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
use cutcal_model::{CuttingTest, ModelError};

use cutcal_io::jc_file::load_jc;
use cutcal_io::material_file::load_material;
use cutcal_io::tests_csv::load_tests;

use crate::bail;
use crate::error::{Context, Result};
pub use crate::predict_rows::{row, table, PredictReport, PredictRow};

/// Options of a prediction (the CLI's `predict` flags, Python's keywords).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PredictRequest {
    /// Work-material temperature, degC (default: the material's room temperature).
    pub work_temperature_c: Option<f64>,
    /// Use Lalwani et al. 2009's search ranges instead of the wide ones.
    pub lalwani_ranges: bool,
    /// C0 search range: LOW HIGH.
    pub c0_range: Option<Vec<f64>>,
    /// Shear-angle search range, deg: LOW HIGH.
    pub phi_range_deg: Option<Vec<f64>>,
    /// Delta search range: LOW HIGH.
    pub delta_range: Option<Vec<f64>>,
    /// Oxley's eta (default 0.9, or the material's `[oxley] eta`).
    pub eta: Option<f64>,
    /// Oxley's psi (default 0.9, or the material's `[oxley] psi`).
    pub psi: Option<f64>,
    /// Ignore the tests' edge radius and flank wear (sharp, unworn tool).
    pub sharp: bool,
}

fn range2(v: &Option<Vec<f64>>, name: &str) -> Result<Option<[f64; 2]>> {
    match v.as_deref() {
        None => Ok(None),
        Some([a, b]) => Ok(Some([*a, *b])),
        Some(other) => bail!("--{name} takes two numbers, got {other:?}"),
    }
}

/// Reads a `[f64; 2]` or a number from the material's `[oxley]` table.
fn table_range(t: &toml::Table, key: &str) -> Result<Option<[f64; 2]>> {
    let Some(v) = t.get(key) else { return Ok(None) };
    let arr = v.as_array().with_context(|| format!("[oxley] {key} must be an array of two numbers"))?;
    let nums: Vec<f64> = arr
        .iter()
        .map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64)))
        .collect::<Option<_>>()
        .with_context(|| format!("[oxley] {key} must hold numbers"))?;
    match nums.as_slice() {
        [a, b] => Ok(Some([*a, *b])),
        _ => bail!("[oxley] {key} must have two entries, got {}", nums.len()),
    }
}

fn table_number(t: &toml::Table, key: &str) -> Result<Option<f64>> {
    match t.get(key) {
        None => Ok(None),
        Some(v) => Ok(Some(
            v.as_float()
                .or_else(|| v.as_integer().map(|i| i as f64))
                .with_context(|| format!("[oxley] {key} must be a number"))?,
        )),
    }
}

/// Oxley options from (in increasing precedence) the wide defaults or Lalwani's ranges, the
/// material's `[oxley]` table (`eta`, `psi`, `c0_range`, `phi_range_deg`, `delta_range`), the flags.
pub fn oxley_options(
    table: Option<&toml::Table>,
    lalwani: bool,
    eta: Option<f64>,
    psi: Option<f64>,
    c0: Option<[f64; 2]>,
    phi_deg: Option<[f64; 2]>,
    delta: Option<[f64; 2]>,
) -> Result<OxleyOptions> {
    let mut o = if lalwani { OxleyOptions::lalwani2009() } else { OxleyOptions::wide() };
    let (mut e, mut p) = (o.eta, o.psi);
    let (mut rc, mut rp, mut rd) = (o.c0_range, o.phi_range_rad, o.delta_range);
    if let Some(t) = table {
        for key in t.keys() {
            if !["eta", "psi", "c0_range", "phi_range_deg", "delta_range"].contains(&key.as_str()) {
                bail!("unknown key [oxley] {key} (known: eta, psi, c0_range, phi_range_deg, delta_range)");
            }
        }
        e = table_number(t, "eta")?.unwrap_or(e);
        p = table_number(t, "psi")?.unwrap_or(p);
        rc = table_range(t, "c0_range")?.unwrap_or(rc);
        rp = table_range(t, "phi_range_deg")?.map_or(rp, |r| r.map(f64::to_radians));
        rd = table_range(t, "delta_range")?.unwrap_or(rd);
    }
    e = eta.unwrap_or(e);
    p = psi.unwrap_or(p);
    rc = c0.unwrap_or(rc);
    rp = phi_deg.map_or(rp, |r| r.map(f64::to_radians));
    rd = delta.unwrap_or(rd);
    o = o.with_eta_psi(e, p)?.with_ranges(rp, rc, rd)?;
    Ok(o)
}

/// The physics of one test: baseline plus the stated edge radius and flank wear with the published
/// models ([`Physics::with_tool`]), or the baseline alone when `sharp`.
pub fn tool_physics(test: &CuttingTest, sharp: bool) -> Result<Physics, ModelError> {
    if sharp {
        Ok(Physics::baseline())
    } else {
        Physics::with_tool(test.edge_radius_m, test.flank_wear_m)
    }
}

/// Predicts every test with the baseline physics plus its stated tool condition
/// ([`tool_physics`]; none when `sharp`); a failed solve becomes a row with its error.
#[must_use]
pub fn predict_rows(
    material: &cutcal_model::Material,
    jc: &cutcal_model::JcParams,
    tests: &[CuttingTest],
    options: &OxleyOptions,
    work_temperature_c: f64,
    sharp: bool,
) -> Vec<PredictRow> {
    tests
        .iter()
        .map(|t| {
            let result = CuttingConditions::from_test(t, work_temperature_c)
                .and_then(|c| oxley::predict(material, jc, &c, options, &tool_physics(t, sharp)?))
                .map_err(|e| e.to_string());
            row(t, result)
        })
        .collect()
}

/// Loads the inputs and predicts every test: what `cutcal predict` computes before it prints.
///
/// Returns an error if a file is malformed (located) or an option is refused; a test whose solve
/// fails is a row with its error, not an error.
pub fn predict_files(material: &Path, jc: &Path, tests: &Path, args: &PredictRequest) -> Result<PredictReport> {
    let mf = load_material(material)?;
    let jc = load_jc(jc)?;
    let tests = load_tests(tests)?;
    let options = oxley_options(
        mf.oxley.as_ref(),
        args.lalwani_ranges,
        args.eta,
        args.psi,
        range2(&args.c0_range, "c0-range")?,
        range2(&args.phi_range_deg, "phi-range-deg")?,
        range2(&args.delta_range, "delta-range")?,
    )
    .with_context(|| format!("Oxley options for {}", material.display()))?;
    let work_c = args.work_temperature_c.unwrap_or(mf.material.room_c);
    let rows = predict_rows(&mf.material, &jc, &tests, &options, work_c, args.sharp);
    Ok(PredictReport {
        material: mf.material.name.clone(),
        options,
        work_temperature_c: work_c,
        sharp: args.sharp,
        rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::predict_rows::pct;

    fn fixture(rel: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel)
    }

    #[test]
    fn predicts_the_aisi1045_fixture_within_5_percent_of_lalwani() {
        // Lalwani et al. 2009 predictions for the four Ivester cases: Fc 576, 433, 1007, 773 N.
        let report = predict_files(
            &fixture("fixtures/materials/aisi1045.toml"),
            &fixture("fixtures/jc/aisi1045_jaspers2002.toml"),
            &fixture("fixtures/tests/aisi1045.csv"),
            &PredictRequest::default(),
        )
        .unwrap();
        let text = table(&report);
        for (r, lalwani) in report.rows.iter().zip([576.0, 433.0, 1007.0, 773.0]) {
            let fc = r.fc_n.unwrap();
            assert!((fc / lalwani - 1.0).abs() < 0.05, "test {}: {fc} N vs {lalwani} N", r.test);
            // Ivester et al. 2000 measured forces are present and compared (case 1: 610 N).
            assert!(r.fc_error_pct.is_some() && r.ft_error_pct.is_some());
        }
        assert!((report.rows[0].fc_measured_n.unwrap() - 610.0).abs() < 1e-6);
        assert!(text.contains("delta-flat"));
    }

    #[test]
    fn stated_edge_radius_is_used_by_default_and_sharp_turns_it_off() {
        // C38 tests state r_e = 25 um (paper Sec 2); test 3 has measured forces (Table 6).
        let report = |sharp| {
            predict_files(
                &fixture("fixtures/materials/c38.toml"),
                &fixture("fixtures/jc/c38_table5.toml"),
                &fixture("fixtures/tests/c38.csv"),
                &PredictRequest { sharp, ..Default::default() },
            )
            .unwrap()
        };
        let with = report(false);
        let sharp = report(true);
        for (a, b) in with.rows.iter().zip(&sharp.rows) {
            assert!((a.edge_radius_um.unwrap() - 25.0).abs() < 1e-9);
            assert_eq!(b.edge_radius_um, None);
            let (ec, et) = (a.edge_fc_n.unwrap(), a.edge_ft_n.unwrap());
            // The chip-formation solution is the same; the edge term is the whole difference.
            assert!((a.fc_n.unwrap() - b.fc_n.unwrap() - ec).abs() < 1e-9 * ec.max(1.0));
            assert!((a.ft_n.unwrap() - b.ft_n.unwrap() - et).abs() < 1e-9 * et.max(1.0));
            // Ploughing is thrust-dominant: P_t / P_c = 1 + pi/2 - 2 rho for m = 1 (Waldorf et al. 1998).
            assert!((et / ec - (1.0 + std::f64::consts::FRAC_PI_2 - 2.0 * 1.9f64.to_radians())).abs() < 1e-9);
        }
        let text = table(&with);
        assert!(text.contains("edge r_e 25 um (Waldorf 1998)"), "{text}");
        assert!(!table(&sharp).contains("edge r_e"));
        let json = serde_json::to_string(&with).unwrap();
        assert!(json.contains("\"edge_fc_n\"") && json.contains("\"edge_feed_force_n_per_m\""));
    }

    #[test]
    fn oxley_table_and_flags_override_in_order() {
        let t: toml::Table = toml::from_str("eta = 0.8\nc0_range = [2.0, 14]\n").unwrap();
        let o = oxley_options(Some(&t), false, None, Some(0.85), None, Some([5.0, 50.0]), None).unwrap();
        assert!((o.eta - 0.8).abs() < 1e-12 && (o.psi - 0.85).abs() < 1e-12);
        assert!((o.c0_range[1] - 14.0).abs() < 1e-12);
        assert!((o.phi_range_rad[1].to_degrees() - 50.0).abs() < 1e-9);
        let bad: toml::Table = toml::from_str("etta = 0.8\n").unwrap();
        let e = oxley_options(Some(&bad), false, None, None, None, None, None).unwrap_err();
        assert!(e.to_string().contains("etta"), "{e}");
    }

    #[test]
    fn row_converts_per_width_measurements_to_totals() {
        // Ivester et al. 2000 case 1: 610 N over 1.6 mm = 381250 N/m; a prediction of 576 N is -5.6 %.
        let t = CuttingTest::new("1", 200.0 / 60.0, 0.15e-3, 1.6e-3, (-7f64).to_radians())
            .unwrap()
            .with_forces(Some(610.0 / 1.6e-3), Some(450.0 / 1.6e-3))
            .unwrap();
        let r = row(&t, Err("x".into()));
        assert!((r.fc_measured_n.unwrap() - 610.0).abs() < 1e-9);
        assert_eq!(r.error.as_deref(), Some("x"));
        assert!((pct(576.0, Some(610.0)).unwrap() - (-5.573_770_491_803_279)).abs() < 1e-9);
    }
}
