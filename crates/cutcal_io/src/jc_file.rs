//! A Johnson-Cook parameter file (`fixtures/jc/*.toml`): stresses in MPa, temperatures in degC.

use std::path::Path;

use cutcal_model::JcParams;
use serde::{Deserialize, Serialize};

use super::{parse_toml, read_text, toml_key_line, InputError};

/// The on-disk form of a JC parameter set.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JcFile {
    /// Where the numbers come from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
    /// A, MPa.
    pub a_mpa: f64,
    /// B, MPa.
    pub b_mpa: f64,
    /// n.
    pub n: f64,
    /// C.
    pub c: f64,
    /// m.
    pub m: f64,
    /// Reference strain rate, 1/s.
    pub eps0_per_s: f64,
    /// Melting temperature, degC.
    pub tm_c: f64,
    /// Reference temperature, degC.
    pub tr_c: f64,
}

impl JcFile {
    /// From model parameters.
    #[must_use]
    pub fn from_params(jc: &JcParams, source: Option<String>) -> Self {
        Self {
            source,
            a_mpa: jc.a_pa / 1e6,
            b_mpa: jc.b_pa / 1e6,
            n: jc.n,
            c: jc.c,
            m: jc.m,
            eps0_per_s: jc.eps0_per_s,
            tm_c: jc.tm_c,
            tr_c: jc.tr_c,
        }
    }
}

/// Reads and validates a JC file.
pub fn load_jc(path: &Path) -> Result<JcParams, InputError> {
    let text = read_text(path)?;
    parse_jc(path, &text)
}

/// Parses and validates JC TOML text (`path` is only used in messages).
///
/// Returns a located error (line, field in file units, value) for TOML syntax, unknown keys,
/// NaN/infinite numbers, values outside the ranges of [`JcParams::new`], and `tm_c <= tr_c`.
pub fn parse_jc(path: &Path, text: &str) -> Result<JcParams, InputError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let f: JcFile = parse_toml(path, text)?;
    for (field, v) in [
        ("a_mpa", f.a_mpa),
        ("b_mpa", f.b_mpa),
        ("n", f.n),
        ("c", f.c),
        ("m", f.m),
        ("eps0_per_s", f.eps0_per_s),
        ("tm_c", f.tm_c),
        ("tr_c", f.tr_c),
    ] {
        if !v.is_finite() {
            return Err(InputError::new(path, toml_key_line(text, field), field, v, "must be a finite number"));
        }
    }
    if !(f.a_mpa <= 1e5 && f.b_mpa <= 1e5) {
        let (field, v) = if f.a_mpa > 1e5 { ("a_mpa", f.a_mpa) } else { ("b_mpa", f.b_mpa) };
        return Err(InputError::new(
            path,
            toml_key_line(text, field),
            field,
            v,
            "must be at most 1e5 MPa (is the unit MPa, not Pa?)",
        ));
    }
    if f.tr_c <= -273.15 {
        return Err(InputError::new(
            path,
            toml_key_line(text, "tr_c"),
            "tr_c",
            f.tr_c,
            "must be above absolute zero (-273.15 degC)",
        ));
    }
    if f.tm_c <= f.tr_c {
        return Err(InputError::new(
            path,
            toml_key_line(text, "tm_c"),
            "tm_c",
            f.tm_c,
            format!("the melting temperature must exceed the reference temperature tr_c = {} degC", f.tr_c),
        ));
    }
    JcParams::new(f.a_mpa * 1e6, f.b_mpa * 1e6, f.n, f.c, f.m, f.eps0_per_s, f.tm_c, f.tr_c).map_err(|e| {
        let (field, value) = match &e {
            cutcal_model::ModelError::OutOfRange { field, value, .. } if field.ends_with("_pa") => {
                (field.replace("_pa", "_mpa"), format!("{}", value / 1e6))
            }
            cutcal_model::ModelError::OutOfRange { field, value, .. } => (field.clone(), format!("{value}")),
            _ => ("tm_c".to_string(), format!("{}", f.tm_c)),
        };
        InputError::new(path, toml_key_line(text, &field), &field, value, e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<JcParams, InputError> {
        parse_jc(Path::new("jc.toml"), text)
    }

    const C38: &str = "a_mpa = 589.0\nb_mpa = 145.0\nn = 0.25\nc = 0.069\nm = 1.1\n\
                       eps0_per_s = 1.0\ntm_c = 1460.0\ntr_c = 20.0\n";

    #[test]
    fn table5_c38_loads_in_pa() {
        // Paper Table 5, C38: A = 589 MPa.
        assert!((parse(C38).unwrap().a_pa - 589e6).abs() < 1e-6);
    }

    #[test]
    fn bad_values_are_located_in_file_units() {
        let e = parse(&C38.replace("b_mpa = 145.0", "b_mpa = -145.0")).unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(2), "b_mpa", "-145"));
        let e = parse(&C38.replace("tm_c = 1460.0", "tm_c = 15.0")).unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(7), "tm_c", "15"));
        let e = parse(&C38.replace("n = 0.25", "n = nan")).unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(3), "n", "NaN"));
        let e = parse(&C38.replace("a_mpa = 589.0", "a_mpa = 589e6")).unwrap_err();
        assert!(e.reason.contains("not Pa"), "{e}");
        let e = parse(&format!("{C38}d = 0.0\n")).unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (Some(9), "(toml)"));
    }
}
