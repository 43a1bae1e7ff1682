//! Types face: materials, JC sets and cutting tests for Python, built through the CLI's own
//! readers so that Python and the command line validate, convert units and word errors alike.
//!
//! A value given from Python (`JcParams(a_mpa=...)`, `CuttingTest(speed_m_min=...)`) is written as
//! the one-record file the CLI would read (TOML for a JC set, one CSV row for a test) and parsed by
//! `cutcal_io`; the pseudo-file name (`<JcParams>`, `<CuttingTest>`) stands in for the path
//! in a located error. No unit conversion or validation is written twice.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use cutcal_io::jc_file::{load_jc, parse_jc, JcFile};
use cutcal_io::material_file::{load_material, parse_material, MaterialFile};
use cutcal_io::tests_csv::{load_tests, parse_tests};
use cutcal_model::{CuttingTest, JcParams};

use crate::errors::{face, FaceResult};

/// Pseudo-file name of a JC set built from Python values.
pub const JC_SOURCE: &str = "<JcParams>";
/// Pseudo-file name of a cutting test built from Python values.
pub const TEST_SOURCE: &str = "<CuttingTest>";

/// Reads a material file (TOML) with the CLI's reader.
pub fn material_from_file(path: &Path) -> FaceResult<MaterialFile> {
    load_material(path).map_err(face)
}

/// Parses material TOML text; `source` names it in error messages (and is the directory base for
/// a tool material named by `[interface].tool`).
pub fn material_from_text(text: &str, source: &str) -> FaceResult<MaterialFile> {
    parse_material(Path::new(source), text).map_err(face)
}

/// A material from the values of a material file's keys (the keyword form of `Material(...)`),
/// written as the TOML text the file would hold and read by the same reader, so that it is
/// validated and converted exactly as [`material_from_file`] does; `source` names it in errors
/// (the generated text's lines) and is the base of a tool named by `[interface].tool`.
pub fn material_from_table(table: &toml::Table, source: &str) -> FaceResult<MaterialFile> {
    let text = toml::to_string(table).map_err(face)?;
    material_from_text(&text, source)
}

/// A JC set with the name of the file it came from (the CLI's `export` names that file in the
/// card headers, so Python keeps it to render byte-identical cards).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedJc {
    /// The parameters (SI inside).
    pub jc: JcParams,
    /// File name (without directory) of the JC file, when read from one.
    pub file_name: Option<String>,
}

/// Reads a JC file (TOML: MPa, degC) with the CLI's reader.
pub fn jc_from_file(path: &Path) -> FaceResult<NamedJc> {
    let jc = load_jc(path).map_err(face)?;
    Ok(NamedJc { jc, file_name: path.file_name().map(|n| n.to_string_lossy().into_owned()) })
}

/// A number as TOML writes it (`nan`, `inf` where Rust would write `NaN`, `inf`), so that a
/// non-finite value reaches the reader and is rejected there with its located message.
fn toml_number(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{v:?}")
    }
}

/// A JC set from values in the JC file's units (stresses MPa, temperatures degC), validated by
/// the JC file reader ([`parse_jc`]): errors read `<JcParams>:LINE: field `a_mpa` = '...': ...`.
pub fn jc_from_values(v: &JcFile) -> FaceResult<JcParams> {
    let mut text = String::new();
    for (key, value) in [
        ("a_mpa", v.a_mpa),
        ("b_mpa", v.b_mpa),
        ("n", v.n),
        ("c", v.c),
        ("m", v.m),
        ("eps0_per_s", v.eps0_per_s),
        ("tm_c", v.tm_c),
        ("tr_c", v.tr_c),
    ] {
        let _ = writeln!(text, "{key} = {}", toml_number(value));
    }
    parse_jc(Path::new(JC_SOURCE), &text).map_err(face)
}

/// The JC set in file units (MPa, degC), the form Python shows.
#[must_use]
pub fn jc_values(jc: &JcParams) -> JcFile {
    JcFile::from_params(jc, None)
}

/// One test in the units of the test CSV columns (the names carry the units).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TestColumns {
    /// Test id.
    pub test: String,
    /// Cutting speed, m/min.
    pub speed_m_min: f64,
    /// Uncut chip thickness, mm.
    pub uncut_mm: f64,
    /// Width of cut, mm.
    pub width_mm: f64,
    /// Rake angle, deg.
    pub rake_deg: f64,
    /// Measured cutting force per unit width, N/mm.
    pub fc_n_per_mm: Option<f64>,
    /// Measured feed force per unit width, N/mm.
    pub ft_n_per_mm: Option<f64>,
    /// Measured chip thickness, mm.
    pub chip_mm: Option<f64>,
    /// Measured interface temperature, degC.
    pub t_int_c: Option<f64>,
    /// Cutting-edge radius, um.
    pub edge_radius_um: Option<f64>,
    /// Flank wear land VB, mm.
    pub flank_wear_mm: Option<f64>,
    /// Run order.
    pub order: Option<f64>,
}

/// CSV cell of a number (full precision: `{:?}` reads back to the same f64).
fn cell(v: Option<f64>) -> String {
    v.map(|x| format!("{x:?}")).unwrap_or_default()
}

/// A test from column values, validated and converted by the test CSV reader ([`parse_tests`]):
/// errors read `<CuttingTest>:2: field `speed_m_min` = '...': ...`.
pub fn test_from_columns(c: &TestColumns) -> FaceResult<CuttingTest> {
    let header = "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,chip_mm,t_int_c,\
                  edge_radius_um,flank_wear_mm,order";
    let id = format!("\"{}\"", c.test.replace('"', "\"\""));
    let row = [
        id,
        cell(Some(c.speed_m_min)),
        cell(Some(c.uncut_mm)),
        cell(Some(c.width_mm)),
        cell(Some(c.rake_deg)),
        cell(c.fc_n_per_mm),
        cell(c.ft_n_per_mm),
        cell(c.chip_mm),
        cell(c.t_int_c),
        cell(c.edge_radius_um),
        cell(c.flank_wear_mm),
        cell(c.order),
    ]
    .join(",");
    let mut tests = parse_tests(Path::new(TEST_SOURCE), &format!("{header}\n{row}\n")).map_err(face)?;
    Ok(tests.remove(0))
}

/// The columns of a test (SI back to the CSV units), for Python's attributes and DataFrames.
#[must_use]
pub fn columns_of(t: &CuttingTest) -> TestColumns {
    let per_mm = |v: Option<f64>| v.map(|x| x / 1e3);
    TestColumns {
        test: t.id.clone(),
        speed_m_min: t.speed_m_per_s * 60.0,
        uncut_mm: t.uncut_chip_thickness_m * 1e3,
        width_mm: t.width_m * 1e3,
        rake_deg: t.rake_rad.to_degrees(),
        fc_n_per_mm: per_mm(t.measured.cutting_force_n_per_m),
        ft_n_per_mm: per_mm(t.measured.feed_force_n_per_m),
        chip_mm: t.measured.chip_thickness_m.map(|v| v * 1e3),
        t_int_c: t.measured.interface_temperature_c,
        edge_radius_um: t.edge_radius_m.map(|v| v * 1e6),
        flank_wear_mm: t.flank_wear_m.map(|v| v * 1e3),
        order: t.order.map(f64::from),
    }
}

/// Reads a test CSV with the CLI's reader.
pub fn tests_from_file(path: &Path) -> FaceResult<Vec<CuttingTest>> {
    load_tests(path).map_err(face)
}

/// A path given from Python, as the CLI would take it.
#[must_use]
pub fn path_of(p: &str) -> PathBuf {
    PathBuf::from(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::errors::ErrorKind;

    fn fixture(rel: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel)
    }

    #[test]
    fn a_material_from_its_keys_equals_the_file() {
        // The C38 file (paper Table 3 polynomials) read as a table of keys and rebuilt.
        let path = fixture("fixtures/materials/c38.toml");
        let table: toml::Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
        let from_file = material_from_file(&path).unwrap();
        let from_keys = material_from_table(&table, &path.display().to_string()).unwrap();
        assert_eq!(format!("{:?}", from_keys.material), format!("{:?}", from_file.material));
        assert_eq!(format!("{:?}", from_keys.bounds), format!("{:?}", from_file.bounds));
        assert_eq!(format!("{:?}", from_keys.interface), format!("{:?}", from_file.interface));
        let mut bad = table.clone();
        bad.insert("melting_c".into(), toml::Value::Float(-5.0));
        let e = material_from_table(&bad, "<Material>").unwrap_err();
        assert_eq!(e.kind, ErrorKind::Input);
        assert!(e.message.starts_with("<Material>:") && e.message.contains("melting_c"), "{}", e.message);
    }

    #[test]
    fn a_test_from_columns_equals_the_csv_row_bit_for_bit() {
        // Every row of the C38 file (paper Table 2/6) rebuilt from its columns is the same test.
        for t in tests_from_file(&fixture("fixtures/tests/c38.csv")).unwrap() {
            let back = test_from_columns(&columns_of(&t)).unwrap();
            assert_eq!(back.id, t.id);
            assert!((back.speed_m_per_s / t.speed_m_per_s - 1.0).abs() < 1e-15, "{}", t.id);
            assert!((back.uncut_chip_thickness_m / t.uncut_chip_thickness_m - 1.0).abs() < 1e-15);
            assert_eq!(back.measured.chip_thickness_m.is_some(), t.measured.chip_thickness_m.is_some());
        }
    }

    #[test]
    fn a_bad_column_is_located_under_the_pseudo_file() {
        let mut c =
            TestColumns { test: "#1, \"odd\"".into(), speed_m_min: 240.0, uncut_mm: 0.075, ..Default::default() };
        c.width_mm = 1.95;
        assert_eq!(test_from_columns(&c).unwrap().id, "#1, \"odd\"");
        c.speed_m_min = -240.0;
        let e = test_from_columns(&c).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Input);
        assert!(e.message.starts_with("<CuttingTest>:2: field `speed_m_min` = '-240.0'"), "{}", e.message);
    }

    #[test]
    fn jc_values_round_trip_and_reject_nan_with_the_field() {
        // Paper Table 5, C38: A = 589 MPa, B = 145 MPa, n = 0.25, C = 0.069, m = 1.1.
        let named = jc_from_file(&fixture("fixtures/jc/c38_table5.toml")).unwrap();
        assert_eq!(named.file_name.as_deref(), Some("c38_table5.toml"));
        let back = jc_from_values(&jc_values(&named.jc)).unwrap();
        assert!((back.a_pa - 589e6).abs() < 1e-6 && (back.c - 0.069).abs() < 1e-15);
        let mut v = jc_values(&named.jc);
        v.c = f64::NAN;
        let e = jc_from_values(&v).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Input);
        assert!(e.message.contains("<JcParams>:4: field `c`"), "{}", e.message);
    }
}
