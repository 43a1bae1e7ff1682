//! The handlebars registry: templates embedded from the top-level `templates/` directory with
//! `include_str!`, strict mode (a missing value is an error, never an empty field), no HTML
//! escaping, and the number helpers of [`crate::numfmt`] (style.md §13: number formatting is done
//! by Rust helpers with their own unit tests, never by template logic).
//!
//! Helpers (all take numbers or arrays of numbers; a JSON `null` — what serde makes of NaN — is an
//! error):
//! - `d10 v...`: one LS-DYNA card in 10-column fields, 6 significant digits, comma fallback;
//! - `d20 v...`: one LS-DYNA card in 20-column fields, 9 significant digits, comma fallback;
//! - `num v...`: free-format reals (Abaqus), 7 significant digits, joined by `", "`;
//! - `sci v...`: DEFORM-style `%.6E` reals right-justified in 15 columns;
//! - `int v...`: integers right-justified in 8 columns (DEFORM-style record headers).

use handlebars::{Context, Handlebars, Helper, HelperResult, Output, RenderContext, RenderError, RenderErrorReason};
use serde_json::Value;

use crate::numfmt::{self, Field};
use crate::ExportError;

/// Significant digits of 10-column LS-DYNA fields.
pub const SIG_D10: usize = 6;
/// Significant digits of 20-column LS-DYNA fields.
pub const SIG_D20: usize = 9;
/// Significant digits of free-format Abaqus numbers.
pub const SIG_FREE: usize = 7;
/// Decimals of DEFORM-style scientific numbers.
pub const SCI_DECIMALS: usize = 6;

/// Every template: (name, source).
const TEMPLATES: &[(&str, &str)] = &[
    ("abaqus_jc", include_str!("../../../templates/abaqus_jc.inp.hbs")),
    ("abaqus_tabular", include_str!("../../../templates/abaqus_tabular.inp.hbs")),
    ("abaqus_thermal", include_str!("../../../templates/abaqus_thermal.inp.hbs")),
    ("abaqus_vfriction", include_str!("../../../templates/abaqus_vfriction.f.hbs")),
    ("lsdyna", include_str!("../../../templates/lsdyna.k.hbs")),
    ("lsdyna_cut2d", include_str!("../../../templates/lsdyna_cut2d.k.hbs")),
    ("deform_key", include_str!("../../../templates/deform.key.hbs")),
    ("deform_sheet", include_str!("../../../templates/deform_sheet.txt.hbs")),
];

fn other(msg: String) -> RenderError {
    RenderErrorReason::Other(msg).into()
}

/// Flattens helper parameters into fields; `""` is a blank field.
fn fields(h: &Helper<'_>) -> Result<Vec<Field>, RenderError> {
    fn push(v: &Value, out: &mut Vec<Field>, name: &str) -> Result<(), RenderError> {
        match v {
            Value::Number(n) => {
                if n.is_f64() {
                    out.push(Field::Real(n.as_f64().unwrap_or(f64::NAN)));
                } else if let Some(i) = n.as_i64() {
                    out.push(Field::Int(i));
                } else {
                    return Err(other(format!("{name}: integer {n} does not fit i64")));
                }
            }
            Value::String(s) if s.is_empty() => out.push(Field::Blank),
            Value::Array(a) => {
                for x in a {
                    push(x, out, name)?;
                }
            }
            Value::Null => return Err(other(format!("{name}: null parameter (a non-finite or missing number)"))),
            other_value => return Err(other(format!("{name}: not a number: {other_value}"))),
        }
        Ok(())
    }
    let mut out = Vec::new();
    for p in h.params() {
        push(p.value(), &mut out, h.name())?;
    }
    if out.is_empty() {
        return Err(other(format!("{}: no parameters", h.name())));
    }
    Ok(out)
}

fn not_finite(helper: &str, v: numfmt::NotFinite) -> RenderError {
    other(format!("{helper}: value {} is not finite", v.0))
}

fn card_helper(
    width: usize,
    sig: usize,
) -> impl Fn(&Helper<'_>, &Handlebars<'_>, &Context, &mut RenderContext<'_, '_>, &mut dyn Output) -> HelperResult + Send + Sync
{
    move |h, _, _, _, out| {
        let f = fields(h)?;
        let line = numfmt::card(&f, width, sig).map_err(|e| not_finite(h.name(), e))?;
        out.write(&line)?;
        Ok(())
    }
}

fn num_helper(
    h: &Helper<'_>,
    _: &Handlebars<'_>,
    _: &Context,
    _: &mut RenderContext<'_, '_>,
    out: &mut dyn Output,
) -> HelperResult {
    let texts = fields(h)?
        .into_iter()
        .map(|f| match f {
            Field::Int(i) => Ok(i.to_string()),
            Field::Real(v) => numfmt::real(v, SIG_FREE).map_err(|e| not_finite("num", e)),
            Field::Blank => Ok(String::new()),
        })
        .collect::<Result<Vec<_>, _>>()?;
    out.write(&texts.join(", "))?;
    Ok(())
}

fn sci_helper(
    h: &Helper<'_>,
    _: &Handlebars<'_>,
    _: &Context,
    _: &mut RenderContext<'_, '_>,
    out: &mut dyn Output,
) -> HelperResult {
    let mut line = String::new();
    for f in fields(h)? {
        let t = match f {
            Field::Real(v) => numfmt::sci(v, SCI_DECIMALS).map_err(|e| not_finite("sci", e))?,
            Field::Int(i) => numfmt::sci(i as f64, SCI_DECIMALS).map_err(|e| not_finite("sci", e))?,
            Field::Blank => return Err(other("sci: blank field".into())),
        };
        line.push_str(&format!("{t:>15}"));
    }
    out.write(&line)?;
    Ok(())
}

fn int_helper(
    h: &Helper<'_>,
    _: &Handlebars<'_>,
    _: &Context,
    _: &mut RenderContext<'_, '_>,
    out: &mut dyn Output,
) -> HelperResult {
    let mut line = String::new();
    for f in fields(h)? {
        match f {
            Field::Int(i) => line.push_str(&format!("{i:>8}")),
            _ => return Err(other("int: expects integers".into())),
        }
    }
    out.write(&line)?;
    Ok(())
}

/// Builds the registry with every template and helper.
///
/// Returns an error if a template does not compile (caught by every snapshot test).
pub(crate) fn registry() -> Result<Handlebars<'static>, ExportError> {
    let mut hb = Handlebars::new();
    hb.set_strict_mode(true);
    hb.register_escape_fn(handlebars::no_escape);
    hb.register_helper("d10", Box::new(card_helper(10, SIG_D10)));
    hb.register_helper("d20", Box::new(card_helper(20, SIG_D20)));
    hb.register_helper("num", Box::new(num_helper));
    hb.register_helper("sci", Box::new(sci_helper));
    hb.register_helper("int", Box::new(int_helper));
    for (name, src) in TEMPLATES {
        hb.register_template_string(name, *src)
            .map_err(|e| ExportError::Template { template: (*name).to_string(), message: e.to_string() })?;
    }
    Ok(hb)
}

/// Renders `template` with `ctx`; a `null` anywhere in the context (serde's rendering of NaN or
/// infinity) is reported as [`ExportError::NonFinite`] before the engine runs.
pub(crate) fn render(hb: &Handlebars<'_>, template: &str, ctx: &Value) -> Result<String, ExportError> {
    if let Some(path) = find_null(ctx, String::new()) {
        return Err(ExportError::NonFinite { field: format!("{template}: {path}"), value: f64::NAN });
    }
    hb.render(template, ctx)
        .map_err(|e| ExportError::Template { template: template.to_string(), message: e.to_string() })
}

fn find_null(v: &Value, path: String) -> Option<String> {
    match v {
        Value::Null => Some(if path.is_empty() { "(root)".into() } else { path }),
        Value::Array(a) => a.iter().enumerate().find_map(|(i, x)| find_null(x, format!("{path}[{i}]"))),
        Value::Object(o) => o.iter().find_map(|(k, x)| find_null(x, format!("{path}.{k}"))),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn hb_with(src: &str) -> Handlebars<'static> {
        let mut hb = registry().unwrap();
        hb.register_template_string("t", src).unwrap();
        hb
    }

    #[test]
    fn d10_renders_fixed_card_and_blanks() {
        let hb = hb_with("{{d10 1 x \"\" 0}}");
        let s = render(&hb, "t", &json!({"x": 7.85e-9})).unwrap();
        assert_eq!(s, "         1  7.85E-09                   0");
    }

    #[test]
    fn d10_falls_back_to_commas_for_a_long_number() {
        let hb = hb_with("{{d10 1 x}}");
        let s = render(&hb, "t", &json!({"x": -1.234567e-123})).unwrap();
        assert_eq!(s, "1,-1.23457E-123");
    }

    #[test]
    fn strict_mode_rejects_a_missing_value() {
        let hb = hb_with("{{d10 1 missing}}");
        assert!(matches!(render(&hb, "t", &json!({})), Err(ExportError::Template { .. })));
        let hb = hb_with("{{num missing}}");
        assert!(render(&hb, "t", &json!({"other": 1})).is_err());
    }

    #[test]
    fn nan_in_the_context_is_an_error_not_an_empty_field() {
        // serde_json turns NaN into null; both the pre-check and the helper reject it.
        let hb = hb_with("{{num x}}");
        let ctx = serde_json::to_value(std::collections::BTreeMap::from([("x", f64::NAN)])).unwrap();
        assert!(matches!(render(&hb, "t", &ctx), Err(ExportError::NonFinite { .. })));
        assert!(hb.render("t", &ctx).is_err());
    }

    #[test]
    fn num_sci_int_format() {
        let hb = hb_with("{{num a b}}|{{sci a}}|{{int 3 12}}");
        let s = render(&hb, "t", &json!({"a": 589.0, "b": 0.0134})).unwrap();
        assert_eq!(s, "589., 0.0134|   5.890000E+02|       3      12");
    }

    #[test]
    fn no_html_escaping() {
        let hb = hb_with("{{s}}");
        assert_eq!(render(&hb, "t", &json!({"s": "rho*cp <T> & k"})).unwrap(), "rho*cp <T> & k");
    }
}
