//! MatML 3.1 XML (fe-cards.md §4), written with quick-xml.
//!
//! MatML has no notion of a Johnson-Cook law: the JC set is a `PropertyData` named
//! "Johnson Cook Strength" with the parameter names used by Ansys Engineering Data (fe-cards.md §4,
//! "confirm against a real Engineering Data export"); temperature tables are comma-separated
//! `Data` with a Temperature `ParameterValue`. The interface (Eq 17 or Coulomb, heat transfer) is
//! written as two further named properties of the workpiece. Units are SI with degC.

use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, BytesText, Event};
use quick_xml::Writer;

use crate::numfmt;
use crate::physics::{MaterialTables, Prepared};
use crate::{ExportError, ExportFile, ExportInput};

/// Significant digits of MatML numbers.
pub(crate) const SIG_MATML: usize = 9;

/// (id, name, unit or None for unitless) of every parameter.
const PARAMETERS: &[(&str, &str, Option<&str>)] = &[
    ("pa_temperature", "Temperature", Some("C")),
    ("pa_jc_a", "Initial Yield Stress", Some("Pa")),
    ("pa_jc_b", "Hardening Constant", Some("Pa")),
    ("pa_jc_n", "Hardening Exponent", None),
    ("pa_jc_c", "Strain Rate Constant", None),
    ("pa_jc_m", "Thermal Softening Exponent", None),
    ("pa_jc_tm", "Melting Temperature", Some("C")),
    ("pa_jc_tr", "Reference Temperature", Some("C")),
    ("pa_jc_eps0", "Reference Strain Rate (/sec)", Some("1/s")),
    ("pa_eq17_m0", "Friction Factor m0", None),
    ("pa_eq17_beta", "Pressure Coefficient beta", Some("1/Pa")),
    ("pa_eq17_k", "Shear Strength k", Some("Pa")),
    ("pa_mu", "Coulomb Friction Coefficient", None),
];

/// (id, name, unit or None) of every property.
const PROPERTIES: &[(&str, &str, Option<&str>)] = &[
    ("pr_jc", "Johnson Cook Strength", None),
    ("pr_density", "Density", Some("kg m^-3")),
    ("pr_cp", "Specific Heat", Some("J kg^-1 C^-1")),
    ("pr_k", "Thermal Conductivity", Some("W m^-1 C^-1")),
    ("pr_friction_eq17", "Pressure-Dependent Shear Friction (paper Eq 17)", None),
    ("pr_friction_coulomb", "Coulomb Friction", None),
    ("pr_htc", "Interface Heat Transfer Coefficient", Some("W m^-2 C^-1")),
];

type W = Writer<Vec<u8>>;

fn xml_err(e: impl std::fmt::Display) -> ExportError {
    ExportError::Xml(e.to_string())
}

fn num(field: &str, v: f64) -> Result<String, ExportError> {
    numfmt::real(v, SIG_MATML).map_err(|e| ExportError::NonFinite { field: field.to_string(), value: e.0 })
}

fn list(field: &str, v: &[f64]) -> Result<String, ExportError> {
    Ok(v.iter().map(|x| num(field, *x)).collect::<Result<Vec<_>, _>>()?.join(","))
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

fn scalar_param(w: &mut W, id: &str, value: f64) -> Result<(), ExportError> {
    start(w, "ParameterValue", &[("parameter", id), ("format", "float")])?;
    text_el(w, "Data", &[("format", "float")], &num(id, value)?)?;
    end(w, "ParameterValue")
}

/// A property with named scalar parameters (the JC set, friction).
fn scalar_property(w: &mut W, property: &str, params: &[(&str, f64)]) -> Result<(), ExportError> {
    start(w, "PropertyData", &[("property", property)])?;
    text_el(w, "Data", &[("format", "string")], "-")?;
    for (id, v) in params {
        scalar_param(w, id, *v)?;
    }
    end(w, "PropertyData")
}

/// A property tabulated against temperature (Ansys Engineering Data convention: Variable Type
/// qualifiers mark the dependent and independent columns).
fn table_property(w: &mut W, property: &str, temps_c: &[f64], values: &[f64]) -> Result<(), ExportError> {
    let dep = vec!["Dependent"; values.len()].join(",");
    let ind = vec!["Independent"; temps_c.len()].join(",");
    start(w, "PropertyData", &[("property", property)])?;
    text_el(w, "Data", &[("format", "float")], &list(property, values)?)?;
    text_el(w, "Qualifier", &[("name", "Variable Type")], &dep)?;
    start(w, "ParameterValue", &[("parameter", "pa_temperature"), ("format", "float")])?;
    text_el(w, "Data", &[("format", "float")], &list("temperature", temps_c)?)?;
    text_el(w, "Qualifier", &[("name", "Variable Type")], &ind)?;
    end(w, "ParameterValue")?;
    end(w, "PropertyData")
}

fn details(w: &mut W, element: &str, id: &str, name: &str, unit: Option<&str>) -> Result<(), ExportError> {
    start(w, element, &[("id", id)])?;
    text_el(w, "Name", &[], name)?;
    match unit {
        Some(u) => {
            start(w, "Units", &[])?;
            start(w, "Unit", &[])?;
            text_el(w, "Name", &[], u)?;
            end(w, "Unit")?;
            end(w, "Units")?;
        }
        None => w.write_event(Event::Empty(BytesStart::new("Unitless"))).map_err(xml_err)?,
    }
    end(w, element)
}

fn thermal(w: &mut W, t: &MaterialTables) -> Result<(), ExportError> {
    table_property(w, "pr_density", &t.temps_c, &t.density)?;
    table_property(w, "pr_cp", &t.temps_c, &t.specific_heat)?;
    table_property(w, "pr_k", &t.temps_c, &t.conductivity)
}

pub(crate) fn render(p: &Prepared, input: &ExportInput<'_>) -> Result<Vec<ExportFile>, ExportError> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None))).map_err(xml_err)?;
    let prov = input.provenance;
    let header = format!(
        " cutcal {}: MatML 3.1 export | source test: {} | model variant: {} | units: SI (Pa, kg, m, s, J, W) with \
         temperatures in degC | JC (paper Eq 16) as the named property Johnson Cook Strength; thermal tables \
         sample the paper Table 3 polynomials | interface: paper Sec 5.1; k = A/sqrt(3) of the JC set ",
        prov.cutcal_version, prov.source_test, prov.model_variant
    );
    // A comment must not contain "--"; nothing in it needs escaping.
    let header = header.replace("--", "- -");
    w.write_event(Event::Comment(BytesText::from_escaped(header))).map_err(xml_err)?;
    start(&mut w, "MatML_Doc", &[])?;

    start(&mut w, "Material", &[("id", "workpiece")])?;
    start(&mut w, "BulkDetails", &[])?;
    text_el(&mut w, "Name", &[], &p.wp.name)?;
    start(&mut w, "Class", &[])?;
    text_el(&mut w, "Name", &[], "workpiece")?;
    end(&mut w, "Class")?;
    let jc = &p.jc;
    scalar_property(
        &mut w,
        "pr_jc",
        &[
            ("pa_jc_a", jc.a_pa),
            ("pa_jc_b", jc.b_pa),
            ("pa_jc_n", jc.n),
            ("pa_jc_c", jc.c),
            ("pa_jc_m", jc.m),
            ("pa_jc_tm", jc.tm_c),
            ("pa_jc_tr", jc.tr_c),
            ("pa_jc_eps0", jc.eps0_per_s),
        ],
    )?;
    thermal(&mut w, &p.wp)?;
    if let Some(m) = &p.mu_table {
        scalar_property(
            &mut w,
            "pr_friction_eq17",
            &[("pa_eq17_m0", m.m0), ("pa_eq17_beta", m.beta_per_pa), ("pa_eq17_k", m.k_pa)],
        )?;
    }
    if let Some(mu) = p.coulomb_mu {
        scalar_property(&mut w, "pr_friction_coulomb", &[("pa_mu", mu)])?;
    }
    start(&mut w, "PropertyData", &[("property", "pr_htc")])?;
    text_el(&mut w, "Data", &[("format", "float")], &num("heat transfer", p.htc)?)?;
    end(&mut w, "PropertyData")?;
    text_el(
        &mut w,
        "Notes",
        &[],
        "Friction and heat transfer describe the tool-chip interface (paper Sec 5.1). Eq 17: tau_f = m0 (1 - \
         exp(-beta P)) k; k = A/sqrt(3) of the JC set.",
    )?;
    end(&mut w, "BulkDetails")?;
    end(&mut w, "Material")?;

    if let Some(t) = &p.tool {
        start(&mut w, "Material", &[("id", "tool")])?;
        start(&mut w, "BulkDetails", &[])?;
        text_el(&mut w, "Name", &[], &t.name)?;
        start(&mut w, "Class", &[])?;
        text_el(&mut w, "Name", &[], "tool")?;
        end(&mut w, "Class")?;
        thermal(&mut w, t)?;
        end(&mut w, "BulkDetails")?;
        end(&mut w, "Material")?;
    }

    start(&mut w, "Metadata", &[])?;
    for (id, name, unit) in PARAMETERS {
        details(&mut w, "ParameterDetails", id, name, *unit)?;
    }
    for (id, name, unit) in PROPERTIES {
        details(&mut w, "PropertyDetails", id, name, *unit)?;
    }
    end(&mut w, "Metadata")?;
    end(&mut w, "MatML_Doc")?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    let contents = String::from_utf8(bytes).map_err(xml_err)?;
    Ok(vec![ExportFile { name: format!("{}_matml.xml", p.stem), contents }])
}
