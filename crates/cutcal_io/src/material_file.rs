//! A material file (`fixtures/materials/*.toml`): Table 3 laws in the units they are printed in,
//! converted to SI here (the only place units are converted).

use std::path::{Path, PathBuf};

use cutcal_model::{Elastic, Friction, Interface, Material, ThermalProperties};

use super::{parse_toml, read_text, toml_key_line, InputError};
use crate::material_raw::{
    check_finite, check_positive, check_yield_range, convert, RawFriction, RawMaterial, ROOM_PLAUSIBLE_C,
};
pub use crate::material_raw::{BoundsSection, DpzdSection, RawLaw};

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

/// Reads and validates a material file.
///
/// Returns a located error for TOML syntax, unknown fields or units, and non-physical values.
pub fn load_material(path: &Path) -> Result<MaterialFile, InputError> {
    let text = read_text(path)?;
    parse_material(path, &text)
}

/// Parses and validates material TOML text (`path` is used in messages and kept in the result).
///
/// Returns a located error (line, dotted field, value) for TOML syntax, unknown fields or units,
/// NaN/infinite numbers, temperatures out of order (room below the validity range's top, which is
/// at most melting), thermal laws that are not positive over their range, inverted or negative
/// bounds, and out-of-range DPZD, elastic and interface settings.
pub fn parse_material(path: &Path, text: &str) -> Result<MaterialFile, InputError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let raw: RawMaterial = parse_toml(path, text)?;
    check_finite(path, text, "melting_c", raw.melting_c)?;
    check_finite(path, text, "room_c", raw.room_c)?;
    if raw.room_c <= -273.15 {
        return Err(InputError::new(
            path,
            toml_key_line(text, "room_c"),
            "room_c",
            raw.room_c,
            "must be above absolute zero (-273.15 degC)",
        ));
    }
    if raw.melting_c <= raw.room_c {
        // Which of the two is wrong: a room (reference) temperature outside the range any shop or
        // laboratory works at is the typo; otherwise the melting temperature is (no metal that is
        // cut melts at or below room temperature).
        let (field, value, other, other_value) = if (ROOM_PLAUSIBLE_C.0..=ROOM_PLAUSIBLE_C.1).contains(&raw.room_c) {
            ("melting_c", raw.melting_c, "room_c", raw.room_c)
        } else {
            ("room_c", raw.room_c, "melting_c", raw.melting_c)
        };
        let other_line = toml_key_line(text, other).map(|l| format!(" (line {l})")).unwrap_or_default();
        return Err(InputError::new(
            path,
            toml_key_line(text, field),
            field,
            value,
            format!(
                "{}: melting temperature {} degC must exceed room temperature {} degC; {other} = {other_value}{other_line} is taken as right",
                raw.name, raw.melting_c, raw.room_c
            ),
        ));
    }
    let t = &raw.thermal;
    check_finite(path, text, "thermal.valid_from_c", t.valid_from_c)?;
    check_finite(path, text, "thermal.valid_to_c", t.valid_to_c)?;
    if t.valid_from_c >= t.valid_to_c {
        return Err(InputError::new(
            path,
            toml_key_line(text, "thermal.valid_from_c"),
            "thermal.valid_from_c",
            t.valid_from_c,
            format!("must be below thermal.valid_to_c = {} degC", t.valid_to_c),
        ));
    }
    if raw.room_c >= t.valid_to_c || t.valid_to_c > raw.melting_c {
        return Err(InputError::new(
            path,
            toml_key_line(text, "thermal.valid_to_c"),
            "thermal.valid_to_c",
            t.valid_to_c,
            format!("must lie in (room_c = {}, melting_c = {}] degC", raw.room_c, raw.melting_c),
        ));
    }
    let range = (t.valid_from_c, t.valid_to_c);
    let k = convert(path, text, "thermal.conductivity", &t.conductivity, &[("W/(m K)", 1.0)])?;
    check_positive(path, text, "thermal.conductivity", &k, "W/(m K)", range)?;
    let density_units = [("g/cm^3", 1e3), ("kg/m^3", 1.0)];
    let (rho_cp, density) = match (&t.rho_cp, &t.density, &t.specific_heat) {
        (Some(rc), Some(d), None) => {
            let rc = convert(path, text, "thermal.rho_cp", rc, &[("J/(cm^3 K)", 1e6), ("J/(m^3 K)", 1.0)])?;
            let d = convert(path, text, "thermal.density", d, &density_units)?;
            check_positive(path, text, "thermal.rho_cp", &rc, "J/(m^3 K)", range)?;
            check_positive(path, text, "thermal.density", &d, "kg/m^3", range)?;
            (rc, d)
        }
        (None, Some(d), Some(cp)) => {
            let d = convert(path, text, "thermal.density", d, &density_units)?;
            let cp = convert(path, text, "thermal.specific_heat", cp, &[("J/(g K)", 1e3), ("J/(kg K)", 1.0)])?;
            check_positive(path, text, "thermal.density", &d, "kg/m^3", range)?;
            check_positive(path, text, "thermal.specific_heat", &cp, "J/(kg K)", range)?;
            (d.product(&cp), d)
        }
        _ => {
            return Err(InputError::new(
                path,
                toml_key_line(text, "thermal"),
                "thermal",
                "",
                "give either density and specific_heat, or rho_cp and density",
            ))
        }
    };
    let yield_strength = raw
        .yield_strength
        .as_ref()
        .map(|y| {
            let law = RawLaw { unit: y.unit.clone(), coefficients: y.coefficients.clone(), source: y.source.clone() };
            convert(path, text, "yield_strength", &law, &[("MPa", 1e6), ("Pa", 1.0)])
        })
        .transpose()?;
    if let Some(e) = &raw.elastic {
        if !(e.youngs_gpa.is_finite() && e.youngs_gpa > 0.0 && e.youngs_gpa <= 2000.0) {
            return Err(InputError::new(
                path,
                toml_key_line(text, "elastic.youngs_gpa"),
                "elastic.youngs_gpa",
                e.youngs_gpa,
                "must satisfy 0 < E <= 2000 GPa",
            ));
        }
        if !(e.poisson.is_finite() && e.poisson > -1.0 && e.poisson < 0.5) {
            return Err(InputError::new(
                path,
                toml_key_line(text, "elastic.poisson"),
                "elastic.poisson",
                e.poisson,
                "must satisfy -1 < nu < 0.5",
            ));
        }
    }
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
    // The checks above locate every rule of `Material::validate`; this is the model's own backstop.
    material.validate().map_err(|e| {
        let field = match &e {
            cutcal_model::ModelError::OutOfRange { field, .. } => field.clone(),
            _ => "material".into(),
        };
        InputError::new(path, toml_key_line(text, &field), &field, "", e.to_string())
    })?;
    if let Some(y) = &raw.yield_strength {
        check_yield_range(path, text, &material, y)?;
    }
    if let Some(d) = &raw.dpzd {
        if !(d.r.is_finite() && d.r > 0.0 && d.r <= 20.0) {
            return Err(InputError::new(
                path,
                toml_key_line(text, "dpzd.r"),
                "dpzd.r",
                d.r,
                "must satisfy 0 < r <= 20",
            ));
        }
        if !(d.rho_cp_original_j_per_cm3_k.is_finite()
            && d.rho_cp_original_j_per_cm3_k > 0.1
            && d.rho_cp_original_j_per_cm3_k < 100.0)
        {
            return Err(InputError::new(
                path,
                toml_key_line(text, "dpzd.rho_cp_original_j_per_cm3_k"),
                "dpzd.rho_cp_original_j_per_cm3_k",
                d.rho_cp_original_j_per_cm3_k,
                "must satisfy 0.1 < rho*Cp < 100 J/(cm^3 K)",
            ));
        }
        if d.identification_test.trim().is_empty() {
            return Err(InputError::new(
                path,
                toml_key_line(text, "dpzd.identification_test"),
                "dpzd.identification_test",
                "",
                "must name a test id of the tests CSV",
            ));
        }
    }
    if let Some(b) = &raw.bounds {
        for (name, [lo, hi]) in [("a_mpa", b.a_mpa), ("b_mpa", b.b_mpa), ("n", b.n), ("c", b.c), ("m", b.m)] {
            let field = format!("bounds.{name}");
            let line = toml_key_line(text, &field);
            if !(lo.is_finite() && hi.is_finite() && lo >= 0.0) {
                return Err(InputError::new(
                    path,
                    line,
                    &field,
                    format!("[{lo}, {hi}]"),
                    "bounds must be finite and non-negative",
                ));
            }
            let cap = cutcal_ident::dpzd_fit::JC_UPPER_LIMITS
                [["a_mpa", "b_mpa", "n", "c", "m"].iter().position(|k| *k == name).unwrap_or(0)];
            if hi > cap {
                return Err(InputError::new(
                    path,
                    line,
                    &field,
                    format!("[{lo}, {hi}]"),
                    format!("the upper bound must be at most {cap} (is the unit right?)"),
                ));
            }
            if lo > hi {
                return Err(InputError::new(
                    path,
                    line,
                    &field,
                    format!("[{lo}, {hi}]"),
                    "bounds are inverted: write [low, high] with low <= high",
                ));
            }
        }
        if b.m[0] <= 0.0 {
            return Err(InputError::new(
                path,
                toml_key_line(text, "bounds.m"),
                "bounds.m",
                format!("[{}, {}]", b.m[0], b.m[1]),
                "the lower bound of m must be positive (m = 0 removes thermal softening)",
            ));
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
                let value = match &e {
                    cutcal_model::ModelError::OutOfRange { field, value, .. } if field == "beta_per_pa" => {
                        format!("beta_per_mpa = {}", value * 1e6)
                    }
                    cutcal_model::ModelError::OutOfRange { field, value, .. } => format!("{field} = {value}"),
                    _ => String::new(),
                };
                InputError::new(
                    path,
                    toml_key_line(text, "interface.friction"),
                    "interface.friction",
                    value,
                    e.to_string(),
                )
            })?;
            let h = i.heat_transfer_kw_per_m2_k;
            if !(h.is_finite() && h > 0.0) {
                return Err(InputError::new(
                    path,
                    toml_key_line(text, "interface.heat_transfer_kw_per_m2_k"),
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
    fn an_inconsistent_melting_room_pair_blames_the_implausible_one() {
        let c38 = std::fs::read_to_string(fixture("c38.toml")).unwrap();
        // Line 5 of c38.toml is melting_c, line 6 room_c.
        let low_melting = c38.replace("melting_c = 1460.0", "melting_c = -5");
        let e = parse_material(Path::new("m.toml"), &low_melting).unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(5), "melting_c", "-5"), "{e}");
        assert!(e.reason.contains("room_c = 20 (line 6) is taken as right"), "{e}");
        let hot_room = c38.replace("room_c = 20.0", "room_c = 1500");
        let e = parse_material(Path::new("m.toml"), &hot_room).unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (Some(6), "room_c"), "{e}");
    }

    #[test]
    fn the_yield_law_is_checked_over_its_stated_range() {
        let c38 = std::fs::read_to_string(fixture("c38.toml")).unwrap();
        let stated = "valid_to_c = 980.0 ";
        assert!(c38.contains(stated));
        // Without the stated range the thermal range [20, 1200] degC applies, where the Table 3
        // cubic reaches zero at 980.2 degC (first non-positive 1 K sample: 981 degC).
        let e = parse_material(Path::new("m.toml"), &c38.replace(stated, "# ")).unwrap_err();
        assert_eq!(e.field, "yield_strength.coefficients");
        assert_eq!(e.line, toml_key_line(&c38, "yield_strength.coefficients"));
        assert!(e.reason.starts_with("sigma0(981 degC) = "), "{e}");
        assert!(e.reason.contains("over [20, 1200] degC, the thermal range"), "{e}");
        // A range reaching past melting is located at its key.
        let e = parse_material(Path::new("m.toml"), &c38.replace(stated, "valid_to_c = 1500.0 ")).unwrap_err();
        assert_eq!(e.field, "yield_strength.valid_to_c");
        assert_eq!(e.line, toml_key_line(&c38, "yield_strength.valid_to_c"));
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
