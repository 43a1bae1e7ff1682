//! Number formatting for FE cards: significant-digit rounding, fixed-width fields and the
//! fall-back rules of fe-cards.md §1.1 (a value must lie entirely inside its column; if it cannot,
//! the card is written in comma free format, never truncated).
//!
//! Every helper returns the *shortest* text that parses back to the value rounded to the requested
//! number of significant digits, so "render -> parse -> same number to printed precision" holds by
//! construction and is checked by property tests below and in `tests/it/roundtrip.rs`.

/// A value that cannot be written (NaN or infinite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NotFinite(pub f64);

/// `v` rounded to `sig` significant digits (1 <= sig <= 17).
///
/// Returns an error if `v` is NaN or infinite.
pub fn round_sig(v: f64, sig: usize) -> Result<f64, NotFinite> {
    if !v.is_finite() {
        return Err(NotFinite(v));
    }
    let sig = sig.clamp(1, 17);
    let text = format!("{:.*e}", sig - 1, v);
    // The text is produced by `format!` from a finite f64, so it always parses; fall back to `v`.
    let r: f64 = text.parse().unwrap_or(v);
    // `+ 0.0` turns -0.0 into +0.0 so that zero is never written with a sign.
    Ok(r + 0.0)
}

/// The shortest text for `v` rounded to `sig` significant digits, always recognisable as a real:
/// it contains a decimal point or an exponent (`589.`, `7.85E-09`, `4.32E+08`, `0.`).
///
/// Returns an error if `v` is NaN or infinite.
///
/// # Example
/// ```
/// use cutcal_export::numfmt::real;
/// assert_eq!(real(7.85e-9, 6).unwrap(), "7.85E-09");
/// assert_eq!(real(589.0, 6).unwrap(), "589.");
/// assert_eq!(real(80769.23076923, 6).unwrap(), "80769.2");
/// ```
pub fn real(v: f64, sig: usize) -> Result<String, NotFinite> {
    let r = round_sig(v, sig)?;
    Ok(shortest_real(r))
}

/// Shortest real text of an already rounded, finite value.
fn shortest_real(r: f64) -> String {
    let [a, b] = real_forms(r);
    if b.len() < a.len() {
        b
    } else {
        a
    }
}

/// The plain (`123457000.`) and exponent (`1.23457E+08`) forms of a rounded, finite value; both
/// parse back to exactly `r`.
fn real_forms(r: f64) -> [String; 2] {
    let mut plain = format!("{r}");
    if !plain.contains('.') {
        plain.push('.');
    }
    let sci = format!("{r:e}");
    let sci = match sci.split_once('e') {
        Some((mantissa, exp)) => {
            let e: i32 = exp.parse().unwrap_or(0);
            let sign = if e < 0 { '-' } else { '+' };
            format!("{mantissa}E{sign}{:02}", e.unsigned_abs())
        }
        None => sci,
    };
    [plain, sci]
}

/// Every text of `v` rounded to `sig` digits, in order of preference: the shortest form, the
/// other form, then the exponent form with the shortest legal exponent.
fn real_candidates(v: f64, sig: usize) -> Result<Vec<String>, NotFinite> {
    let r = round_sig(v, sig)?;
    let [plain, sci] = real_forms(r);
    let compact = compact_exponent(&sci);
    Ok(if sci.len() < plain.len() { vec![sci, plain, compact] } else { vec![plain, sci, compact] })
}

/// `text` right-justified in a field of `width` characters with at least one leading blank, or
/// `None` if it does not fit (fe-cards.md §1.1: keep >= 1 leading blank).
#[must_use]
pub fn fixed(text: &str, width: usize) -> Option<String> {
    (text.len() < width).then(|| format!("{text:>width$}"))
}

/// The same number with the shortest legal exponent (`7.8495E-09` -> `7.8495E-9`,
/// `2.79152E+08` -> `2.79152E8`): Fortran and both LS-DYNA parsers read it; used only when the
/// padded form does not fit its column.
#[must_use]
pub fn compact_exponent(text: &str) -> String {
    match text.split_once('E') {
        Some((mantissa, exp)) => {
            let (sign, digits) = match exp.strip_prefix('-') {
                Some(d) => ("-", d),
                None => ("", exp.trim_start_matches('+')),
            };
            let digits = digits.trim_start_matches('0');
            format!("{mantissa}E{sign}{}", if digits.is_empty() { "0" } else { digits })
        }
        None => text.to_string(),
    }
}

/// One field of an LS-DYNA card.
#[derive(Debug, Clone, PartialEq)]
pub enum Field {
    /// An integer (ids, flags).
    Int(i64),
    /// A real, written with `sig` significant digits.
    Real(f64),
    /// Left blank (the keyword's default applies).
    Blank,
}

/// Renders one card of `fields` in fixed columns of `width`, or — if any value does not fit its
/// column — the whole card in comma free format (fe-cards.md §1.1; never truncated).
///
/// Returns an error if a real is NaN or infinite.
///
/// # Example
/// ```
/// use cutcal_export::numfmt::{card, Field};
/// let c = card(&[Field::Int(1), Field::Real(7.85e-9), Field::Blank], 10, 6).unwrap();
/// assert_eq!(c, "         1  7.85E-09          ");
/// let wide = card(&[Field::Int(1), Field::Real(1.234567e-100)], 10, 6).unwrap();
/// assert_eq!(wide, "1,1.23457E-100");
/// ```
pub fn card(fields: &[Field], width: usize, sig: usize) -> Result<String, NotFinite> {
    let candidates: Vec<Vec<String>> = fields
        .iter()
        .map(|f| match f {
            Field::Int(i) => Ok(vec![i.to_string()]),
            Field::Real(v) => real_candidates(*v, sig),
            Field::Blank => Ok(vec![String::new()]),
        })
        .collect::<Result<_, _>>()?;
    let fixed_parts: Option<Vec<String>> = candidates.iter().map(|c| c.iter().find_map(|t| fixed(t, width))).collect();
    Ok(match fixed_parts {
        Some(parts) => parts.concat(),
        None => {
            // Free format: the shortest text of each field; trailing blanks are dropped, inner
            // blanks stay as empty fields, and a one-field card keeps a comma so that it is
            // unmistakably free format.
            let texts: Vec<&str> = candidates.iter().map(|c| c[0].as_str()).collect();
            let last = texts.iter().rposition(|t| !t.is_empty()).map_or(0, |i| i + 1);
            let mut line = texts[..last].join(",");
            if !line.contains(',') {
                line.push(',');
            }
            line
        }
    })
}

/// Scientific text with `decimals` digits after the point and a two-digit signed exponent,
/// the `%.6E` style of the DEFORM-style KEY block (`1.234567E+02`).
///
/// Returns an error if `v` is NaN or infinite.
pub fn sci(v: f64, decimals: usize) -> Result<String, NotFinite> {
    if !v.is_finite() {
        return Err(NotFinite(v));
    }
    let s = format!("{:.*e}", decimals, v + 0.0);
    Ok(match s.split_once('e') {
        Some((mantissa, exp)) => {
            let e: i32 = exp.parse().unwrap_or(0);
            let sign = if e < 0 { '-' } else { '+' };
            format!("{mantissa}E{sign}{:02}", e.unsigned_abs())
        }
        None => s,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn reals_from_fe_cards_example_render_as_in_the_note() {
        // fe-cards.md §1.1 "Advice for the writer": `80769.`, `7.85E-09`, `4.32E+08`.
        assert_eq!(real(80769.0, 6).unwrap(), "80769.");
        assert_eq!(real(7.85e-9, 6).unwrap(), "7.85E-09");
        assert_eq!(real(4.32e8, 6).unwrap(), "4.32E+08");
        assert_eq!(real(0.0, 6).unwrap(), "0.");
        assert_eq!(real(-0.0, 6).unwrap(), "0.");
        assert_eq!(real(1e20, 6).unwrap(), "1E+20");
        assert_eq!(real(-1.96, 6).unwrap(), "-1.96");
        assert_eq!(real(0.0134, 6).unwrap(), "0.0134");
    }

    #[test]
    fn rounding_is_to_significant_digits() {
        // 2/3 to 6 significant digits is 0.666667 (rounded, not truncated to 0.666666).
        assert_eq!(real(2.0 / 3.0, 6).unwrap(), "0.666667");
        assert_eq!(real(123456789.0, 6).unwrap(), "123457000.");
    }

    #[test]
    fn non_finite_is_an_error() {
        assert!(real(f64::NAN, 6).is_err());
        assert!(real(f64::INFINITY, 6).is_err());
        assert!(sci(f64::NEG_INFINITY, 6).is_err());
        assert!(card(&[Field::Real(f64::NAN)], 10, 6).is_err());
    }

    #[test]
    fn fixed_keeps_a_leading_blank() {
        assert_eq!(fixed("123456789", 10).as_deref(), Some(" 123456789"));
        assert_eq!(fixed("1234567890", 10), None);
    }

    #[test]
    fn card_falls_back_to_comma_format_when_one_value_does_not_fit() {
        // -1.23457E-100 needs 13 characters: the whole card goes to free format.
        let c = card(&[Field::Int(7), Field::Blank, Field::Real(-1.234567e-100), Field::Blank], 10, 6).unwrap();
        assert_eq!(c, "7,,-1.23457E-100");
        let f = card(&[Field::Int(7), Field::Blank, Field::Real(2.5)], 10, 6).unwrap();
        assert_eq!(f, "         7                 2.5");
    }

    #[test]
    fn compact_exponent_is_used_only_when_needed() {
        assert_eq!(compact_exponent("7.8495E-09"), "7.8495E-9");
        assert_eq!(compact_exponent("2.79152E+08"), "2.79152E8");
        assert_eq!(compact_exponent("589."), "589.");
        // C38 density at 20 degC (Table 3: 7.849502 g/cm^3) in t/mm^3 and cp in mm^2/(s^2 K):
        let c = card(&[Field::Real(7.849502e-9), Field::Real(4.32e8), Field::Real(279152456.0)], 10, 6).unwrap();
        assert_eq!(c, " 7.8495E-9  4.32E+08 2.79152E8");
        // -0.0672958 needs 10 characters in every form: free format, with a comma.
        assert_eq!(card(&[Field::Real(-0.06729582)], 10, 6).unwrap(), "-0.0672958,");
    }

    #[test]
    fn sci_matches_key_style() {
        assert_eq!(sci(589.0, 6).unwrap(), "5.890000E+02");
        assert_eq!(sci(0.0, 6).unwrap(), "0.000000E+00");
        assert_eq!(sci(-4.5e-12, 3).unwrap(), "-4.500E-12");
    }

    proptest! {
        // render -> parse -> the value rounded to the printed precision (relative 0.5e-(sig-1)).
        #[test]
        fn real_round_trips_to_printed_precision(mant in -9.999..9.999f64, exp in -300i32..300, sig in 1usize..12) {
            let v = mant * 10f64.powi(exp);
            let text = real(v, sig).unwrap();
            prop_assert!(text.contains('.') || text.contains('E'), "{text}");
            let back: f64 = text.parse().unwrap();
            let tol = 0.5 * 10f64.powi(1 - sig as i32) * v.abs() * (1.0 + 1e-12);
            prop_assert!((back - v).abs() <= tol, "{v} -> {text}");
        }

        // No field ever overflows its column: a fixed card is exactly n*width wide and every
        // window parses on its own; otherwise the card is comma separated.
        #[test]
        fn card_fields_never_overflow(vals in proptest::collection::vec((-9.999..9.999f64, -40i32..40), 1..8)) {
            let fields: Vec<Field> = vals.iter().map(|(m, e)| Field::Real(m * 10f64.powi(*e))).collect();
            let line = card(&fields, 10, 6).unwrap();
            if line.contains(',') {
                let parts: Vec<&str> = line.split(',').collect();
                prop_assert_eq!(parts.len(), fields.len().max(2));
                for (p, f) in parts.iter().zip(&fields) {
                    let back: f64 = p.parse().unwrap();
                    if let Field::Real(v) = f {
                        prop_assert!((back - v).abs() <= 0.5e-5 * v.abs() * (1.0 + 1e-12));
                    }
                }
            } else {
                prop_assert_eq!(line.len(), 10 * fields.len());
                for (i, f) in fields.iter().enumerate() {
                    let window = &line[10 * i..10 * i + 10];
                    prop_assert!(window.starts_with(' '));
                    let back: f64 = window.trim().parse().unwrap();
                    if let Field::Real(v) = f {
                        prop_assert!((back - v).abs() <= 0.5e-5 * v.abs() * (1.0 + 1e-12));
                    }
                }
            }
        }
    }
}
