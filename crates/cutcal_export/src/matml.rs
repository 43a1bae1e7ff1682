//! MatML 3.1 XML in the Ansys Engineering Data form (fe-cards.md §4), written with quick-xml.
//!
//! Layout, as Ansys Engineering Data and `ansys-materials-manager` (its `MatmlWriter`/`MatmlReader`)
//! write and read it: `EngineeringData` > `Notes`, `Materials` > `MatML_Doc` > `Material`* and
//! `Metadata`. Every `PropertyData` carries `<Data format="string">-</Data>` and its values in
//! `ParameterValue`s qualified `Variable Type` = `Dependent` (the property's values) or
//! `Independent` (the temperatures of a table). Ids are `pr<n>`/`pa<n>` as Ansys numbers them.
//!
//! MatML has no notion of a Johnson-Cook law: the JC set is the property "Johnson Cook Strength"
//! with the parameter names of Ansys' explicit-dynamics model (fe-cards.md §4). Elasticity is the
//! Ansys "Elasticity" property (Behavior Isotropic: Young's Modulus, Poisson's Ratio). The
//! interface (paper Sec 5.1) is written as further named properties of the workpiece: the Eq 17
//! constants, the local shear strength k(T) table, or the Coulomb coefficient, and the heat
//! transfer coefficient. Units are SI with temperatures in degC.

use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, BytesText, Event};
use quick_xml::Writer;

use crate::numfmt;
use crate::physics::{MaterialTables, Prepared, FRICTION_REFERENCE_STRAIN, FRICTION_REFERENCE_STRAIN_RATE_PER_S};
use crate::{ExportError, ExportFile, ExportInput};

/// Significant digits of MatML numbers.
pub(crate) const SIG_MATML: usize = 9;

/// A unit as Ansys writes it: (name, power) factors; empty = unitless.
type Unit = &'static [(&'static str, i32)];

/// (key, name, unit) of every parameter; the id is `pa<index>`.
const PARAMETERS: &[(&str, &str, Unit)] = &[
    ("temperature", "Temperature", &[("C", 1)]),
    ("density", "Density", &[("kg", 1), ("m", -3)]),
    ("cp", "Specific Heat", &[("J", 1), ("kg", -1), ("C", -1)]),
    ("k", "Thermal Conductivity", &[("W", 1), ("m", -1), ("C", -1)]),
    ("youngs", "Young's Modulus", &[("Pa", 1)]),
    ("poisson", "Poisson's Ratio", &[]),
    ("jc_a", "Initial Yield Stress", &[("Pa", 1)]),
    ("jc_b", "Hardening Constant", &[("Pa", 1)]),
    ("jc_n", "Hardening Exponent", &[]),
    ("jc_c", "Strain Rate Constant", &[]),
    ("jc_m", "Thermal Softening Exponent", &[]),
    ("jc_tm", "Melting Temperature", &[("C", 1)]),
    ("jc_tr", "Reference Temperature", &[("C", 1)]),
    ("jc_eps0", "Reference Strain Rate (/sec)", &[("s", -1)]),
    ("eq17_m0", "Friction Factor m0", &[]),
    ("eq17_beta", "Pressure Coefficient beta", &[("Pa", -1)]),
    ("eq17_k", "Local Shear Strength k", &[("Pa", 1)]),
    ("mu", "Coulomb Friction Coefficient", &[]),
    ("htc", "Heat Transfer Coefficient", &[("W", 1), ("m", -2), ("C", -1)]),
];

/// (key, name) of every property; the id is `pr<index>`. Properties carry no unit (Ansys writes
/// `Unitless`; the units are those of the parameters).
const PROPERTIES: &[(&str, &str)] = &[
    ("jc", "Johnson Cook Strength"),
    ("density", "Density"),
    ("cp", "Specific Heat"),
    ("k", "Thermal Conductivity"),
    ("elasticity", "Elasticity"),
    ("eq17", "Pressure-Dependent Shear Friction (paper Eq 17)"),
    ("eq17_k", "Eq 17 Local Shear Strength"),
    ("coulomb", "Coulomb Friction"),
    ("htc", "Interface Heat Transfer"),
];

fn id_of(list: &[&str], prefix: &str, key: &str) -> Result<String, ExportError> {
    list.iter()
        .position(|k| *k == key)
        .map(|i| format!("{prefix}{i}"))
        .ok_or_else(|| ExportError::Xml(format!("unknown MatML key {key}")))
}

fn pa(key: &str) -> Result<String, ExportError> {
    let keys: Vec<&str> = PARAMETERS.iter().map(|p| p.0).collect();
    id_of(&keys, "pa", key)
}

fn pr(key: &str) -> Result<String, ExportError> {
    let keys: Vec<&str> = PROPERTIES.iter().map(|p| p.0).collect();
    id_of(&keys, "pr", key)
}

type W = Writer<Vec<u8>>;

fn xml_err(e: impl std::fmt::Display) -> ExportError {
    ExportError::Xml(e.to_string())
}

fn num(field: &str, v: f64) -> Result<String, ExportError> {
    numfmt::real(v, SIG_MATML).map_err(|e| ExportError::NonFinite { field: field.to_string(), value: e.0 })
}

fn list(field: &str, v: &[f64]) -> Result<String, ExportError> {
    Ok(v.iter().map(|x| num(field, *x)).collect::<Result<Vec<_>, _>>()?.join(", "))
}

fn start(w: &mut W, name: &str, attrs: &[(&str, &str)]) -> Result<(), ExportError> {
    let mut e = BytesStart::new(name);
    for a in attrs {
        e.push_attribute(*a);
    }
    w.write_event(Event::Start(e)).map_err(xml_err)
}

fn end(w: &mut W, name: &str) -> Result<(), ExportError> {
    w.write_event(Event::End(BytesEnd::new(name))).map_err(xml_err)
}

fn text_el(w: &mut W, name: &str, attrs: &[(&str, &str)], text: &str) -> Result<(), ExportError> {
    start(w, name, attrs)?;
    w.write_event(Event::Text(BytesText::new(text))).map_err(xml_err)?;
    end(w, name)
}

/// One `ParameterValue`: comma-separated values with one Variable Type qualifier per value.
fn parameter(w: &mut W, key: &str, values: &[f64], independent: bool) -> Result<(), ExportError> {
    let kind = if independent { "Independent" } else { "Dependent" };
    start(w, "ParameterValue", &[("parameter", &pa(key)?), ("format", "float")])?;
    text_el(w, "Data", &[], &list(key, values)?)?;
    text_el(w, "Qualifier", &[("name", "Variable Type")], &vec![kind; values.len()].join(","))?;
    end(w, "ParameterValue")
}

/// A property with constant parameters (the JC set, elasticity, friction constants).
fn constant_property(
    w: &mut W,
    property: &str,
    qualifiers: &[(&str, &str)],
    params: &[(&str, f64)],
) -> Result<(), ExportError> {
    start(w, "PropertyData", &[("property", &pr(property)?)])?;
    text_el(w, "Data", &[("format", "string")], "-")?;
    for (name, value) in qualifiers {
        text_el(w, "Qualifier", &[("name", name)], value)?;
    }
    for (key, v) in params {
        parameter(w, key, &[*v], false)?;
    }
    end(w, "PropertyData")
}

/// A property tabulated against temperature.
fn table_property(
    w: &mut W,
    property: &str,
    qualifiers: &[(&str, &str)],
    key: &str,
    temps_c: &[f64],
    values: &[f64],
) -> Result<(), ExportError> {
    start(w, "PropertyData", &[("property", &pr(property)?)])?;
    text_el(w, "Data", &[("format", "string")], "-")?;
    for (name, value) in qualifiers {
        text_el(w, "Qualifier", &[("name", name)], value)?;
    }
    parameter(w, key, values, false)?;
    parameter(w, "temperature", temps_c, true)?;
    end(w, "PropertyData")
}

fn details(w: &mut W, element: &str, id: &str, name: &str, unit: Unit) -> Result<(), ExportError> {
    start(w, element, &[("id", id)])?;
    text_el(w, "Name", &[], name)?;
    if unit.is_empty() {
        w.write_event(Event::Empty(BytesStart::new("Unitless"))).map_err(xml_err)?;
    } else {
        start(w, "Units", &[])?;
        for (u, power) in unit {
            if *power == 1 {
                start(w, "Unit", &[])?;
            } else {
                start(w, "Unit", &[("power", &power.to_string())])?;
            }
            text_el(w, "Name", &[], u)?;
            end(w, "Unit")?;
        }
        end(w, "Units")?;
    }
    end(w, element)
}

/// Density, specific heat, conductivity and elasticity of one material.
fn bulk(w: &mut W, t: &MaterialTables) -> Result<(), ExportError> {
    table_property(w, "density", &[], "density", &t.temps_c, &t.density)?;
    table_property(w, "cp", &[("Definition", "Constant Pressure")], "cp", &t.temps_c, &t.specific_heat)?;
    table_property(w, "k", &[("Behavior", "Isotropic")], "k", &t.temps_c, &t.conductivity)?;
    if let Some((e, nu)) = t.elastic {
        constant_property(w, "elasticity", &[("Behavior", "Isotropic")], &[("youngs", e), ("poisson", nu)])?;
    }
    Ok(())
}

fn open_material(w: &mut W, name: &str, class: &str) -> Result<(), ExportError> {
    start(w, "Material", &[])?;
    start(w, "BulkDetails", &[])?;
    text_el(w, "Name", &[], name)?;
    start(w, "Class", &[])?;
    text_el(w, "Name", &[], class)?;
    end(w, "Class")
}

pub(crate) fn render(p: &Prepared, input: &ExportInput<'_>) -> Result<Vec<ExportFile>, ExportError> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None))).map_err(xml_err)?;
    let prov = input.provenance;
    let warnings: String = crate::literature_warnings(input).iter().map(|w| format!(" WARNING: {w}.")).collect();
    let notes = format!(
        "cutcal {}: Ansys Engineering Data (MatML 3.1) export. Source test: {}. Model variant: {}. Units: SI \
         (Pa, kg, m, s, J, W) with temperatures in degC. JC (paper Eq 16) as the property Johnson Cook \
         Strength; thermal tables sample the paper Table 3 polynomials; elastic constants from the material \
         file. Interface: paper Sec 5.1; Eq 17 tau_f = m0 (1 - exp(-beta P)) k(T) with k(T) = \
         sigma_JC({}, {} 1/s, T)/sqrt(3), the local shear flow stress (Eqs 14, 16), tabulated below Tm.{}",
        prov.cutcal_version,
        prov.source_test,
        prov.model_variant,
        FRICTION_REFERENCE_STRAIN,
        FRICTION_REFERENCE_STRAIN_RATE_PER_S,
        warnings
    );
    // The version attributes are those of the Engineering Data format that ansys-materials-manager
    // writes and reads (its MatmlWriter: 18.0.0.60).
    start(&mut w, "EngineeringData", &[("version", "18.0.0.60"), ("versiondate", "29.08.2016 15:02:00")])?;
    text_el(&mut w, "Notes", &[], &notes)?;
    start(&mut w, "Materials", &[])?;
    start(&mut w, "MatML_Doc", &[])?;

    open_material(&mut w, &p.wp.name, "workpiece")?;
    let jc = &p.jc;
    constant_property(
        &mut w,
        "jc",
        &[],
        &[
            ("jc_a", jc.a_pa),
            ("jc_b", jc.b_pa),
            ("jc_n", jc.n),
            ("jc_c", jc.c),
            ("jc_m", jc.m),
            ("jc_tm", jc.tm_c),
            ("jc_tr", jc.tr_c),
            ("jc_eps0", jc.eps0_per_s),
        ],
    )?;
    bulk(&mut w, &p.wp)?;
    if let Some(m) = &p.mu_table {
        constant_property(&mut w, "eq17", &[], &[("eq17_m0", m.m0), ("eq17_beta", m.beta_per_pa)])?;
        let temps: Vec<f64> = m.by_temperature.iter().map(|r| r.temp_c).collect();
        let ks: Vec<f64> = m.by_temperature.iter().map(|r| r.k_pa).collect();
        table_property(&mut w, "eq17_k", &[], "eq17_k", &temps, &ks)?;
    }
    if let Some(mu) = p.coulomb_mu {
        constant_property(&mut w, "coulomb", &[], &[("mu", mu)])?;
    }
    constant_property(&mut w, "htc", &[], &[("htc", p.htc)])?;
    text_el(
        &mut w,
        "Notes",
        &[],
        "Friction and heat transfer describe the tool-chip interface (paper Sec 5.1), not the bulk material.",
    )?;
    end(&mut w, "BulkDetails")?;
    end(&mut w, "Material")?;

    if let Some(t) = &p.tool {
        open_material(&mut w, &t.name, "tool")?;
        bulk(&mut w, t)?;
        end(&mut w, "BulkDetails")?;
        end(&mut w, "Material")?;
    }

    start(&mut w, "Metadata", &[])?;
    for (i, (_, name, unit)) in PARAMETERS.iter().enumerate() {
        details(&mut w, "ParameterDetails", &format!("pa{i}"), name, unit)?;
    }
    for (i, (_, name)) in PROPERTIES.iter().enumerate() {
        details(&mut w, "PropertyDetails", &format!("pr{i}"), name, &[])?;
    }
    end(&mut w, "Metadata")?;
    end(&mut w, "MatML_Doc")?;
    end(&mut w, "Materials")?;
    end(&mut w, "EngineeringData")?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    let contents = String::from_utf8(bytes).map_err(xml_err)?;
    Ok(vec![ExportFile { name: format!("{}_matml.xml", p.stem), contents }])
}
