//! A material file (`fixtures/materials/*.toml`): Table 3 laws in the units they are printed in,
//! converted to SI here (the only place units are converted).

use std::path::{Path, PathBuf};

use cutcal_model::{Elastic, Friction, Interface, Material, TempPolynomial, ThermalProperties};
use serde::{Deserialize, Serialize};

use super::{parse_toml, read_text, toml_key_line, InputError};

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

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawThermal {
    valid_from_c: f64,
    valid_to_c: f64,
    #[serde(default)]
    density: Option<RawLaw>,
    #[serde(default)]
    specific_heat: Option<RawLaw>,
    #[serde(default)]
    rho_cp: Option<RawLaw>,
    conductivity: RawLaw,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawElastic {
    youngs_gpa: f64,
    poisson: f64,
    #[serde(default)]
    source: Option<String>,
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
    pub a_mpa: [f64; 2],
    /// B, MPa.
    pub b_mpa: [f64; 2],
    /// n.
    pub n: [f64; 2],
    /// C.
    pub c: [f64; 2],
    /// m.
    pub m: [f64; 2],
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
enum RawFriction {
    PressureDependentShear { m0: f64, beta_per_mpa: f64 },
    Coulomb { mu: f64 },
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInterface {
    #[serde(default)]
    tool: Option<String>,
    friction: RawFriction,
    heat_transfer_kw_per_m2_k: f64,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    name: String,
    melting_c: f64,
    room_c: f64,
    thermal: RawThermal,
    #[serde(default)]
    yield_strength: Option<RawLaw>,
    #[serde(default)]
    elastic: Option<RawElastic>,
    #[serde(default)]
    dpzd: Option<DpzdSection>,
    #[serde(default)]
    bounds: Option<BoundsSection>,
    #[serde(default)]
    interface: Option<RawInterface>,
    #[serde(default)]
    oxley: Option<toml::Table>,
}

/// The tool-chip interface of a workpiece file.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceSection {
    /// Tool material name (a file `<tool>.toml` beside this one).
    pub tool: Option<String>,
    /// Friction and heat transfer in SI.
    pub interface: Interface,
}

/// A loaded, validated material file.
#[derive(Debug, Clone)]
pub struct MaterialFile {
    /// Where it was read from.
    pub path: PathBuf,
    /// The material in SI.
    pub material: Material,
    /// DPZD settings, when given.
    pub dpzd: Option<DpzdSection>,
    /// Identification bounds, when given.
    pub bounds: Option<BoundsSection>,
    /// Interface data, when given.
    pub interface: Option<InterfaceSection>,
    /// Forward-model settings table, passed through to the forward model's own reader.
    pub oxley: Option<toml::Table>,
}

fn convert(
    path: &Path,
    text: &str,
    field: &str,
    law: &RawLaw,
    units: &[(&str, f64)],
) -> Result<TempPolynomial, InputError> {
    let line = toml_key_line(text, field.rsplit('.').next().unwrap_or(field));
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
    TempPolynomial::new(law.coefficients.clone()).map(|p| p.scaled(factor)).map_err(|e| {
        InputError::new(path, line, &format!("{field}.coefficients"), format!("{:?}", law.coefficients), e.to_string())
    })
}

/// Reads and validates a material file.
///
/// Returns a located error for TOML syntax, unknown fields or units, and non-physical values.
pub fn load_material(path: &Path) -> Result<MaterialFile, InputError> {
    let text = read_text(path)?;
    let raw: RawMaterial = parse_toml(path, &text)?;
    let t = &raw.thermal;
    let k = convert(path, &text, "thermal.conductivity", &t.conductivity, &[("W/(m K)", 1.0)])?;
    let density_units = [("g/cm^3", 1e3), ("kg/m^3", 1.0)];
    let (rho_cp, density) = match (&t.rho_cp, &t.density, &t.specific_heat) {
        (Some(rc), Some(d), None) => (
            convert(path, &text, "thermal.rho_cp", rc, &[("J/(cm^3 K)", 1e6), ("J/(m^3 K)", 1.0)])?,
            convert(path, &text, "thermal.density", d, &density_units)?,
        ),
        (None, Some(d), Some(cp)) => {
            let d = convert(path, &text, "thermal.density", d, &density_units)?;
            let cp = convert(path, &text, "thermal.specific_heat", cp, &[("J/(g K)", 1e3), ("J/(kg K)", 1.0)])?;
            (d.product(&cp), d)
        }
        _ => {
            return Err(InputError::new(
                path,
                None,
                "thermal",
                "",
                "give either density and specific_heat, or rho_cp and density",
            ))
        }
    };
    let yield_strength = raw
        .yield_strength
        .as_ref()
        .map(|y| convert(path, &text, "yield_strength", y, &[("MPa", 1e6), ("Pa", 1.0)]))
        .transpose()?;
    let material = Material {
        name: raw.name.clone(),
        thermal: ThermalProperties {
            rho_cp,
            density,
            conductivity: k,
            valid_from_c: t.valid_from_c,
            valid_to_c: t.valid_to_c,
        },
        yield_strength,
        melting_c: raw.melting_c,
        room_c: raw.room_c,
        elastic: raw.elastic.as_ref().map(|e| Elastic { youngs_pa: e.youngs_gpa * 1e9, poisson: e.poisson }),
    };
    material.validate().map_err(|e| {
        let field = match &e {
            cutcal_model::ModelError::OutOfRange { field, .. } => field.clone(),
            _ => "material".into(),
        };
        InputError::new(path, toml_key_line(&text, &field), &field, "", e.to_string())
    })?;
    if material.room_c >= material.thermal.valid_to_c || material.thermal.valid_to_c > material.melting_c {
        return Err(InputError::new(
            path,
            toml_key_line(&text, "valid_to_c"),
            "thermal.valid_to_c",
            material.thermal.valid_to_c,
            format!("must lie in (room_c = {}, melting_c = {}] degC", material.room_c, material.melting_c),
        ));
    }
    if let Some(d) = &raw.dpzd {
        if !(d.r.is_finite() && d.r > 0.0 && d.r <= 20.0) {
            return Err(InputError::new(path, toml_key_line(&text, "r"), "dpzd.r", d.r, "must satisfy 0 < r <= 20"));
        }
        if !(d.rho_cp_original_j_per_cm3_k.is_finite()
            && d.rho_cp_original_j_per_cm3_k > 0.1
            && d.rho_cp_original_j_per_cm3_k < 100.0)
        {
            return Err(InputError::new(
                path,
                toml_key_line(&text, "rho_cp_original_j_per_cm3_k"),
                "dpzd.rho_cp_original_j_per_cm3_k",
                d.rho_cp_original_j_per_cm3_k,
                "must satisfy 0.1 < rho*Cp < 100 J/(cm^3 K)",
            ));
        }
    }
    if let Some(b) = &raw.bounds {
        for (name, [lo, hi]) in [("a_mpa", b.a_mpa), ("b_mpa", b.b_mpa), ("n", b.n), ("c", b.c), ("m", b.m)] {
            if !(lo.is_finite() && hi.is_finite() && lo <= hi && lo >= 0.0) {
                return Err(InputError::new(
                    path,
                    toml_key_line(&text, name),
                    &format!("bounds.{name}"),
                    format!("[{lo}, {hi}]"),
                    "bounds must be finite, non-negative and ordered low <= high",
                ));
            }
        }
    }
    let interface = raw
        .interface
        .as_ref()
        .map(|i| {
            let friction = match i.friction {
                RawFriction::PressureDependentShear { m0, beta_per_mpa } => {
                    Friction::PressureDependentShear { m0, beta_per_pa: beta_per_mpa * 1e-6 }
                }
                RawFriction::Coulomb { mu } => Friction::Coulomb { mu },
            };
            friction.validate().map_err(|e| {
                InputError::new(path, toml_key_line(&text, "friction"), "interface.friction", "", e.to_string())
            })?;
            let h = i.heat_transfer_kw_per_m2_k;
            if !(h.is_finite() && h > 0.0) {
                return Err(InputError::new(
                    path,
                    toml_key_line(&text, "heat_transfer_kw_per_m2_k"),
                    "interface.heat_transfer_kw_per_m2_k",
                    h,
                    "must be a positive number of kW/(m^2 K)",
                ));
            }
            Ok(InterfaceSection {
                tool: i.tool.clone(),
                interface: Interface { friction, heat_transfer_w_per_m2_k: h * 1e3 },
            })
        })
        .transpose()?;
    Ok(MaterialFile {
        path: path.to_path_buf(),
        material,
        dpzd: raw.dpzd,
        bounds: raw.bounds,
        interface,
        oxley: raw.oxley,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixture(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/materials").join(name)
    }

    #[test]
    fn loads_every_material_fixture() {
        for f in ["c38.toml", "42crmo4.toml", "aa6082.toml", "h13a.toml", "aisi1045.toml"] {
            load_material(&fixture(f)).unwrap_or_else(|e| panic!("{e}"));
        }
    }

    #[test]
    fn c38_units_converted_to_si() {
        let m = load_material(&fixture("c38.toml")).unwrap();
        // Table 3: rho(20) = 7.866 - 0.01693 + 0.0004364 - 0.0000047688 = 7.8495016 g/cm^3.
        assert!((m.material.thermal.density.value(20.0) - 7849.5016).abs() < 0.001);
        // sigma0(20) = 773.007 - 32.6 + 1.52 - 0.024008 = 741.90 MPa.
        assert!((m.material.yield_strength_pa(20.0).unwrap() - 741.902992e6).abs() < 1.0);
        match m.interface.unwrap().interface.friction {
            Friction::PressureDependentShear { beta_per_pa, .. } => {
                assert!((beta_per_pa - 0.0045e-6).abs() < 1e-18)
            }
            Friction::Coulomb { .. } => panic!("C38 uses Eq 17"),
        }
    }
}
