//! The raw form of a material file as serde reads it (the units it is printed in) and the checks
//! and conversions of its laws to SI (`convert`, the yield-law range check, positivity and
//! finiteness), used by [`crate::material_file::parse_material`].

use std::path::Path;

use cutcal_model::{Material, TempPolynomial};
use serde::{Deserialize, Serialize};

use crate::{toml_key_line, InputError};

/// A polynomial law as written: unit, ascending coefficients in the unit, and its source.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLaw {
    /// Unit of the value (the argument is always T in degC).
    pub unit: String,
    /// Ascending coefficients (constant first).
    pub coefficients: Vec<f64>,
    /// Provenance.
    #[serde(default)]
    pub source: Option<String>,
}

/// The yield-strength law as written: a [`RawLaw`] with its own optional validity range (default:
/// the thermal range), over which it must be positive and non-increasing.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawYieldLaw {
    pub(crate) unit: String,
    pub(crate) coefficients: Vec<f64>,
    #[serde(default)]
    pub(crate) source: Option<String>,
    #[serde(default)]
    pub(crate) valid_from_c: Option<f64>,
    #[serde(default)]
    pub(crate) valid_to_c: Option<f64>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawThermal {
    pub(crate) valid_from_c: f64,
    pub(crate) valid_to_c: f64,
    #[serde(default)]
    pub(crate) density: Option<RawLaw>,
    #[serde(default)]
    pub(crate) specific_heat: Option<RawLaw>,
    #[serde(default)]
    pub(crate) rho_cp: Option<RawLaw>,
    pub(crate) conductivity: RawLaw,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawElastic {
    pub(crate) youngs_gpa: f64,
    pub(crate) poisson: f64,
    #[serde(default)]
    pub(crate) source: Option<String>,
}

/// DPZD settings of a material (paper Sec 4.2).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DpzdSection {
    /// The test the paper identifies from.
    pub identification_test: String,
    /// Strain-rate exponent r of Eq 2.
    pub r: f64,
    /// Constant rho*Cp of the original model, J/(cm^3 K).
    pub rho_cp_original_j_per_cm3_k: f64,
}

/// Identification bounds, `[low, high]` each (A, B in MPa).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundsSection {
    /// A, MPa.
    #[serde(deserialize_with = "pair")]
    pub a_mpa: [f64; 2],
    /// B, MPa.
    #[serde(deserialize_with = "pair")]
    pub b_mpa: [f64; 2],
    /// n.
    #[serde(deserialize_with = "pair")]
    pub n: [f64; 2],
    /// C.
    #[serde(deserialize_with = "pair")]
    pub c: [f64; 2],
    /// m.
    #[serde(deserialize_with = "pair")]
    pub m: [f64; 2],
}

/// Reads exactly two numbers: the TOML reader would otherwise drop a third one silently.
pub(crate) fn pair<'de, D: serde::Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
    let v = Vec::<f64>::deserialize(d)?;
    match v.as_slice() {
        [lo, hi] => Ok([*lo, *hi]),
        _ => Err(serde::de::Error::custom(format!("expected a bound pair [low, high], got {} numbers", v.len()))),
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub(crate) enum RawFriction {
    PressureDependentShear { m0: f64, beta_per_mpa: f64 },
    Coulomb { mu: f64 },
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawInterface {
    #[serde(default)]
    pub(crate) tool: Option<String>,
    pub(crate) friction: RawFriction,
    pub(crate) heat_transfer_kw_per_m2_k: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMaterial {
    pub(crate) name: String,
    pub(crate) melting_c: f64,
    pub(crate) room_c: f64,
    pub(crate) thermal: RawThermal,
    #[serde(default)]
    pub(crate) yield_strength: Option<RawYieldLaw>,
    #[serde(default)]
    pub(crate) elastic: Option<RawElastic>,
    #[serde(default)]
    pub(crate) dpzd: Option<DpzdSection>,
    #[serde(default)]
    pub(crate) bounds: Option<BoundsSection>,
    #[serde(default)]
    pub(crate) interface: Option<RawInterface>,
    #[serde(default)]
    pub(crate) oxley: Option<toml::Table>,
}

/// Room (reference) temperatures a material file can plausibly mean, degC: a conditioned shop
/// or laboratory, with a wide margin. Used only to decide which of `room_c` and `melting_c` an
/// inconsistent pair blames.
pub(crate) const ROOM_PLAUSIBLE_C: (f64, f64) = (-50.0, 100.0);

pub(crate) fn convert(
    path: &Path,
    text: &str,
    field: &str,
    law: &RawLaw,
    units: &[(&str, f64)],
) -> Result<TempPolynomial, InputError> {
    let line = toml_key_line(text, field);
    let factor = units.iter().find(|(u, _)| *u == law.unit).map(|(_, f)| *f).ok_or_else(|| {
        let allowed: Vec<&str> = units.iter().map(|(u, _)| *u).collect();
        InputError::new(
            path,
            line,
            &format!("{field}.unit"),
            &law.unit,
            format!("unknown unit; expected one of {allowed:?}"),
        )
    })?;
    let coefficients_line = toml_key_line(text, &format!("{field}.coefficients")).or(line);
    let poly = TempPolynomial::new(law.coefficients.clone()).map(|p| p.scaled(factor)).map_err(|e| {
        InputError::new(
            path,
            coefficients_line,
            &format!("{field}.coefficients"),
            format!("{:?}", law.coefficients),
            e.to_string(),
        )
    })?;
    // Huge but finite coefficients can still overflow once evaluated or scaled to SI.
    if let Some(bad) = poly.coefficients().iter().position(|c| !c.is_finite()) {
        return Err(InputError::new(
            path,
            coefficients_line,
            &format!("{field}.coefficients"),
            format!("{:?}", law.coefficients),
            format!("coefficient {bad} overflows when converted from {} to SI", law.unit),
        ));
    }
    Ok(poly)
}

/// Checks the yield-strength law over its validity range (`yield_strength.valid_from_c`,
/// `valid_to_c`, each defaulting to the thermal range's end): the range inside (-273.15 degC,
/// melting], and sigma0 positive and non-increasing over it
/// ([`Material::check_yield_strength`]), with the error at the coefficients.
pub(crate) fn check_yield_range(
    path: &Path,
    text: &str,
    material: &Material,
    y: &RawYieldLaw,
) -> Result<(), InputError> {
    let thermal = &material.thermal;
    let (from, to) = (y.valid_from_c.unwrap_or(thermal.valid_from_c), y.valid_to_c.unwrap_or(thermal.valid_to_c));
    for (key, given) in [("yield_strength.valid_from_c", y.valid_from_c), ("yield_strength.valid_to_c", y.valid_to_c)] {
        if let Some(v) = given {
            check_finite(path, text, key, v)?;
        }
    }
    if !(from > -273.15 && from < to && to <= material.melting_c) {
        let key = if y.valid_to_c.is_some() { "yield_strength.valid_to_c" } else { "yield_strength.valid_from_c" };
        return Err(InputError::new(
            path,
            toml_key_line(text, key).or_else(|| toml_key_line(text, "yield_strength")),
            key,
            format!("[{from}, {to}]"),
            format!(
                "the yield-strength range must satisfy -273.15 < from < to <= melting_c = {} degC",
                material.melting_c
            ),
        ));
    }
    material.check_yield_strength(from, to).map_err(|defect| {
        let range = if y.valid_from_c.is_some() || y.valid_to_c.is_some() {
            "its stated range".to_string()
        } else {
            "the thermal range (no yield_strength.valid_to_c given; state the range the fit holds for there)"
                .to_string()
        };
        InputError::new(
            path,
            toml_key_line(text, "yield_strength.coefficients").or_else(|| toml_key_line(text, "yield_strength")),
            "yield_strength.coefficients",
            format!("{:?}", y.coefficients),
            format!("{defect}: sigma0(T) must be positive and non-increasing over [{from}, {to}] degC, {range}"),
        )
    })
}

/// Checks that a law is finite and positive over `[from, to]` degC (sampled every 10 K, like
/// [`cutcal_model::ThermalProperties::validate`]), with the error located at the law.
pub(crate) fn check_positive(
    path: &Path,
    text: &str,
    field: &str,
    law: &TempPolynomial,
    unit: &str,
    (from, to): (f64, f64),
) -> Result<(), InputError> {
    let steps = ((to - from) / 10.0).ceil().clamp(1.0, 1e5) as usize;
    for i in 0..=steps {
        let t = from + (to - from) * i as f64 / steps as f64;
        let v = law.value(t);
        if !(v.is_finite() && v > 0.0) {
            return Err(InputError::new(
                path,
                toml_key_line(text, field),
                field,
                format!("{v:e} {unit} at {t:.1} degC"),
                format!("must be positive over the thermal range [{from}, {to}] degC"),
            ));
        }
    }
    Ok(())
}

/// Checks that a scalar read from TOML is finite (TOML allows `nan`, `inf` and overflowing literals).
pub(crate) fn check_finite(path: &Path, text: &str, field: &str, value: f64) -> Result<(), InputError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(InputError::new(path, toml_key_line(text, field), field, value, "must be a finite number"))
    }
}
