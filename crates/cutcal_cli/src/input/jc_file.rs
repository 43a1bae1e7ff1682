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
    #[serde(default)]
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
    let f: JcFile = parse_toml(path, &text)?;
    JcParams::new(f.a_mpa * 1e6, f.b_mpa * 1e6, f.n, f.c, f.m, f.eps0_per_s, f.tm_c, f.tr_c).map_err(|e| {
        let field = match &e {
            cutcal_model::ModelError::OutOfRange { field, .. } => field.replace("_pa", "_mpa"),
            _ => "tm_c".to_string(),
        };
        let value = match &e {
            cutcal_model::ModelError::OutOfRange { value, .. } if field.ends_with("_mpa") => {
                format!("{}", value / 1e6)
            }
            cutcal_model::ModelError::OutOfRange { value, .. } => format!("{value}"),
            _ => String::new(),
        };
        InputError::new(path, toml_key_line(&text, &field), &field, value, e.to_string())
    })
}
