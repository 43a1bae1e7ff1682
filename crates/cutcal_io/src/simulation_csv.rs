//! A simulation CSV (e.g. from an FE run), one row per test; `#` lines are comments.
//!
//! Columns: required `test`, `fc_n_per_mm`, `ft_n_per_mm`, `chip_mm`; optional `t_ab_c`, `t_int_c`,
//! `shear_angle_deg`. Every error names the file, line, field and value.

use std::collections::HashSet;
use std::path::Path;

use super::{read_text, InputError};

const REQUIRED: [&str; 4] = ["test", "fc_n_per_mm", "ft_n_per_mm", "chip_mm"];
const OPTIONAL: [&str; 4] = ["t_ab_c", "t_int_c", "shear_angle_deg", "note"];

/// One simulated test, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulatedTest {
    /// Test id (matches the recordings).
    pub id: String,
    /// Cutting force per unit width, N/m.
    pub fc_n_per_m: f64,
    /// Feed force per unit width, N/m.
    pub ft_n_per_m: f64,
    /// Chip thickness, m.
    pub chip_m: f64,
    /// Shear-zone temperature, degC.
    pub t_ab_c: Option<f64>,
    /// Interface temperature, degC.
    pub t_int_c: Option<f64>,
    /// Shear angle, rad.
    pub shear_angle_rad: Option<f64>,
}

/// Reads and validates a simulation CSV.
pub fn load_simulation(path: &Path) -> Result<Vec<SimulatedTest>, InputError> {
    let text = read_text(path)?;
    parse_simulation(path, &text)
}

/// Parses simulation CSV text (`path` is only used in messages).
pub fn parse_simulation(path: &Path, text: &str) -> Result<Vec<SimulatedTest>, InputError> {
    let mut rdr =
        csv::ReaderBuilder::new().comment(Some(b'#')).trim(csv::Trim::All).flexible(false).from_reader(text.as_bytes());
    let csv_err = |e: csv::Error| {
        let line = e.position().map(|p| crate::record_line(text, p));
        InputError::new(path, line, "(csv)", "", e.to_string())
    };
    let headers = rdr.headers().map_err(csv_err)?.clone();
    let header_line =
        text.lines().position(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty()).map(|i| i + 1);
    for h in headers.iter() {
        if !REQUIRED.contains(&h) && !OPTIONAL.contains(&h) {
            return Err(InputError::new(
                path,
                header_line,
                h,
                "",
                format!("unknown column; expected {REQUIRED:?} and optionally {OPTIONAL:?}"),
            ));
        }
    }
    for r in REQUIRED {
        if !headers.iter().any(|h| h == r) {
            return Err(InputError::new(path, header_line, r, "", "required column is missing"));
        }
    }
    let col = |name: &str| headers.iter().position(|h| h == name);
    let mut out = Vec::new();
    let mut seen = HashSet::new();
    for rec in rdr.records() {
        let rec = rec.map_err(csv_err)?;
        let line = rec.position().map(|p| crate::record_line(text, p));
        let cell = |name: &str| col(name).and_then(|i| rec.get(i)).unwrap_or("");
        let num = |name: &str, lo: f64, hi: f64, rule: &str| -> Result<Option<f64>, InputError> {
            let s = cell(name);
            if s.is_empty() {
                return Ok(None);
            }
            let v: f64 = s.parse().map_err(|_| InputError::new(path, line, name, s, "not a number"))?;
            if !(v.is_finite() && v > lo && v <= hi) {
                return Err(InputError::new(path, line, name, s, format!("must satisfy {rule}")));
            }
            Ok(Some(v))
        };
        let required =
            |name: &str, v: Option<f64>| v.ok_or_else(|| InputError::new(path, line, name, "", "a value is required"));
        let id = cell("test").to_string();
        if id.is_empty() {
            return Err(InputError::new(path, line, "test", "", "a test id is required"));
        }
        if !seen.insert(id.clone()) {
            return Err(InputError::new(path, line, "test", &id, "duplicate test id"));
        }
        let fc = required("fc_n_per_mm", num("fc_n_per_mm", 0.0, 1e4, "0 < Fc <= 1e4 N/mm")?)?;
        let ft = required("ft_n_per_mm", num("ft_n_per_mm", 0.0, 1e4, "0 < Ft <= 1e4 N/mm")?)?;
        let tc = required("chip_mm", num("chip_mm", 0.0, 50.0, "0 < tc <= 50 mm")?)?;
        out.push(SimulatedTest {
            id,
            fc_n_per_m: fc * 1e3,
            ft_n_per_m: ft * 1e3,
            chip_m: tc * 1e-3,
            t_ab_c: num("t_ab_c", -273.15, 5000.0, "-273.15 < T <= 5000 degC")?,
            t_int_c: num("t_int_c", -273.15, 5000.0, "-273.15 < T <= 5000 degC")?,
            shear_angle_rad: num("shear_angle_deg", 0.0, 90.0, "0 < phi < 90 deg")?.map(f64::to_radians),
        });
    }
    if out.is_empty() {
        return Err(InputError::new(path, header_line, "(rows)", "", "no simulation rows"));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Vec<SimulatedTest>, InputError> {
        parse_simulation(Path::new("s.csv"), text)
    }

    #[test]
    fn reads_table6_enhanced_row_in_si() {
        // Paper Table 6, Sim. (JC-enhanced DPZD): 244 N/mm, 126.5 N/mm, 0.211 mm.
        let s = parse("test,fc_n_per_mm,ft_n_per_mm,chip_mm,shear_angle_deg\n3,244,126.5,0.211,25\n").unwrap();
        assert!((s[0].fc_n_per_m - 244e3).abs() < 1e-9 && (s[0].ft_n_per_m - 126.5e3).abs() < 1e-9);
        assert!((s[0].chip_m - 0.211e-3).abs() < 1e-15);
        assert!((s[0].shear_angle_rad.unwrap() - 25f64.to_radians()).abs() < 1e-15);
    }

    #[test]
    fn errors_are_located() {
        let e = parse("test,fc_n_per_mm,ft_n_per_mm,chip_mm\n3,244,-1,0.2\n").unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(2), "ft_n_per_mm", "-1"));
        let e = parse("test,fc_n_per_mm,ft_n_per_mm\n3,244,1\n").unwrap_err();
        assert_eq!(e.field, "chip_mm");
        let e = parse("test,fc_n_per_mm,ft_n_per_mm,chip_mm,t_ab_c\n3,244,1,0.2,abc\n").unwrap_err();
        assert_eq!((e.field.as_str(), e.value.as_str()), ("t_ab_c", "abc"));
        let e = parse("test,fc_n_per_mm,ft_n_per_mm,chip_mm\n3,244,1,0.2\n3,244,1,0.2\n").unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (Some(3), "test"));
        let e = parse("test,fc_n_per_mm,ft_n_per_mm,chip_mm\n3,,1,0.2\n").unwrap_err();
        assert_eq!(e.field, "fc_n_per_mm");
    }

    #[test]
    fn crlf_files_report_the_same_lines() {
        // A spreadsheet export ends its lines with CRLF: the bad row is on line 4 either way.
        for end in ["\n", "\r\n"] {
            let text = ["test,fc_n_per_mm,ft_n_per_mm,chip_mm", "1,244,1,0.2", "# note", "3,244,-1,0.2", ""].join(end);
            let e = parse(&text).unwrap_err();
            assert_eq!((e.line, e.field.as_str()), (Some(4), "ft_n_per_mm"), "{end:?}");
        }
    }
}
