//! cutcal_io: cutcal's file edge as a library. Reading the input files (material and JC TOML, test
//! CSV, simulation CSV, raw signal CSV) into validated model types, and writing outputs atomically
//! ([`output`]). The CLI and the Python module both read and write through this crate.
//!
//! Every input error is an [`InputError`] naming the file, the line (where the format has lines),
//! the field and the value; every output error is an [`output::OutputError`] naming the path.
// Unit tests compare bit-identical results on purpose (determinism, warm against cold paths).
#![cfg_attr(test, allow(clippy::float_cmp))]
#![warn(missing_docs)]

#[cfg(test)]
mod fuzz;
pub mod jc_file;
pub mod material_file;
mod material_raw;
pub mod output;
pub mod signal_csv;
pub mod simulation_csv;
mod test_columns;
pub mod tests_csv;

use std::fmt;
use std::path::{Path, PathBuf};

/// A located input error: file, line (1-based, when known), field, offending value and reason.
#[derive(Debug, Clone, PartialEq)]
pub struct InputError {
    /// The file.
    pub file: PathBuf,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// 1-based character column in the line, when known (TOML syntax errors).
    pub column: Option<usize>,
    /// The field or column.
    pub field: String,
    /// The offending value as written (may be empty).
    pub value: String,
    /// Why it is rejected.
    pub reason: String,
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(l) = self.line {
            write!(f, ":{l}")?;
            if let Some(c) = self.column {
                write!(f, ":{c}")?;
            }
        }
        write!(f, ": field `{}`", self.field)?;
        if !self.value.is_empty() {
            write!(f, " = '{}'", self.value)?;
        }
        write!(f, ": {}", self.reason)
    }
}

impl std::error::Error for InputError {}

impl InputError {
    /// An error at `file`, `line`, `field` with the offending `value` and the `reason`.
    pub fn new(
        file: &Path,
        line: Option<usize>,
        field: &str,
        value: impl fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Self {
            file: file.to_path_buf(),
            line,
            column: None,
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}

/// Reads a whole file as UTF-8 text with a located error.
pub fn read_text(path: &Path) -> Result<String, InputError> {
    let bytes =
        std::fs::read(path).map_err(|e| InputError::new(path, None, "(file)", "", format!("cannot read: {e}")))?;
    decode_text(path, bytes)
}

/// Decodes file contents as UTF-8 (a leading byte-order mark is dropped) and rejects empty files.
///
/// Returns an error naming the line and byte of the first invalid UTF-8 sequence, or saying the
/// file is empty or blank.
pub fn decode_text(path: &Path, bytes: Vec<u8>) -> Result<String, InputError> {
    let text = String::from_utf8(bytes).map_err(|e| {
        let good = e.utf8_error().valid_up_to();
        let upto = &e.as_bytes()[..good];
        let line = upto.iter().filter(|b| **b == b'\n').count() + 1;
        // The prefix is valid UTF-8 by construction; count characters, not bytes, for the column.
        let valid = std::str::from_utf8(upto).unwrap_or_default();
        let column = valid.rsplit('\n').next().unwrap_or_default().chars().count() + 1;
        let bad = e.as_bytes()[good..].iter().take(4).map(|b| format!("{b:#04x}")).collect::<Vec<_>>().join(" ");
        InputError::new(path, Some(line), "(text)", bad, format!("not valid UTF-8 at byte {good} (column {column})"))
    })?;
    let text = match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => text,
    };
    if text.trim().is_empty() {
        return Err(InputError::new(path, None, "(file)", "", "the file is empty"));
    }
    Ok(text)
}

/// A number rounded to 6 significant digits, in exponent form when very large or very small
/// (messages must stay readable for `1e300` and for SI values like `2.5e-5` m).
pub(crate) fn short_number(v: f64) -> String {
    let rounded: f64 = format!("{v:.5e}").parse().unwrap_or(v);
    if rounded.is_finite() && rounded.abs() > 0.0 && (rounded.abs() >= 1e7 || rounded.abs() < 1e-4) {
        format!("{rounded:e}")
    } else {
        format!("{rounded}")
    }
}

/// The reason of a model validation error, with the rejected SI value shortened.
pub(crate) fn model_reason(e: &cutcal_model::ModelError) -> String {
    match e {
        cutcal_model::ModelError::OutOfRange { field, value, rule } => {
            format!("{field} = {} must satisfy {rule}", short_number(*value))
        }
        other => other.to_string(),
    }
}

/// 1-based line of a byte offset in `text`.
pub(crate) fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())].iter().filter(|b| **b == b'\n').count() + 1
}

/// 1-based line where a CSV record starts. The csv crate takes a record's position before it
/// consumes the `\n` of a CRLF line end, so with CRLF files (spreadsheet exports) its
/// `Position::line` is one short; the byte offset moved past line ends, blank lines and `#`
/// comments is exact for either line end.
pub(crate) fn record_line(text: &str, pos: &csv::Position) -> usize {
    let b = text.as_bytes();
    let mut o = usize::try_from(pos.byte()).unwrap_or(usize::MAX).min(b.len());
    loop {
        while o < b.len() && (b[o] == b'\r' || b[o] == b'\n') {
            o += 1;
        }
        let at_line_start = o == 0 || b[o - 1] == b'\n';
        if at_line_start && o < b.len() && b[o] == b'#' {
            while o < b.len() && b[o] != b'\n' {
                o += 1;
            }
        } else {
            break;
        }
    }
    line_of(text, o)
}

/// Finds the line where `key` is assigned in a TOML text (best effort, for located validation errors).
///
/// `key` may be a dotted path (`thermal.valid_to_c`, `bounds.n`, `yield_strength.coefficients`):
/// the key is then looked for under its `[table]` header, or as an inline table entry
/// (`density = { unit = ... }`) of its parent, or as the `[table]` header itself. A plain key is the
/// first line assigning it in any table.
pub fn toml_key_line(text: &str, key: &str) -> Option<usize> {
    let mut table = String::new();
    // Best match so far: (length of the matched path prefix, line).
    let mut best: Option<(usize, usize)> = None;
    let mut consider = |len: usize, line: usize| {
        if best.is_none_or(|(l, _)| len > l) {
            best = Some((len, line));
        }
    };
    for (i, raw) in text.lines().enumerate() {
        let t = raw.trim_start();
        if let Some(h) = t.strip_prefix('[') {
            let name = h.trim_start_matches('[').split(']').next().unwrap_or("").trim();
            table = name.to_string();
            if key == table || key.starts_with(&format!("{table}.")) {
                consider(table.len(), i + 1);
            }
            continue;
        }
        let Some((lhs, _)) = t.split_once('=') else { continue };
        let lhs = lhs.trim().trim_matches('"');
        if lhs.is_empty() || lhs.starts_with('#') {
            continue;
        }
        let full = if table.is_empty() { lhs.to_string() } else { format!("{table}.{lhs}") };
        if full == key || (!key.contains('.') && lhs == key) {
            return Some(i + 1);
        }
        if key.starts_with(&format!("{full}.")) {
            consider(full.len() + 1, i + 1);
        }
    }
    best.map(|(_, line)| line)
}

/// Parses TOML into `T` with a located error (line and column of the offending text).
pub fn parse_toml<T: serde::de::DeserializeOwned>(path: &Path, text: &str) -> Result<T, InputError> {
    toml::from_str(text).map_err(|e| {
        let span = e.span().map(|s| s.start.min(text.len())..s.end.min(text.len()));
        let line = span.as_ref().map(|s| line_of(text, s.start));
        let value = span.as_ref().map(|s| offending_text(text, s.clone())).unwrap_or_default();
        // The TOML reader gives some errors (e.g. a control character) an empty message.
        let reason = match e.message().trim() {
            "" => "invalid TOML at this position (a control character or a misplaced token)".to_string(),
            m => m.to_string(),
        };
        let mut err = InputError::new(path, line, "(toml)", printable(&value), reason);
        err.column = span.as_ref().map(|s| column_of(text, s.start));
        err
    })
}

/// The text an error span points at: the span if it is within one line, widened to the whole
/// token when the span is shorter (`1e400` where the reader points at `1`); empty for a span
/// over several lines (a missing key is reported against its whole table).
fn offending_text(text: &str, span: std::ops::Range<usize>) -> String {
    let Some(spanned) = text.get(span.clone()) else { return String::new() };
    if spanned.trim_end().contains('\n') {
        return String::new();
    }
    let rest = text.get(span.start..).unwrap_or("");
    let token: String = rest.chars().take_while(|c| !c.is_whitespace() && !",]}#".contains(*c)).collect();
    let best = if token.len() > spanned.trim().len() { token.as_str() } else { spanned.trim() };
    best.chars().take(80).collect()
}

/// `text` with control characters escaped (`\0`, `\u{1b}`), so a message never carries them raw.
fn printable(text: &str) -> String {
    text.chars().map(|c| if c.is_control() { c.escape_default().to_string() } else { c.to_string() }).collect()
}

/// 1-based character column of a byte offset in `text`.
pub(crate) fn column_of(text: &str, offset: usize) -> usize {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    text[start..offset].chars().count() + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    const MATERIAL: &str = "name = \"x\"\nroom_c = 20\n[thermal]\nvalid_to_c = 1\ndensity = { unit = \"g\" }\n\
                            [bounds]\nn = [0, 1]\n[yield_strength]\nunit = \"MPa\"\n";

    #[test]
    fn toml_key_line_follows_tables_and_inline_tables() {
        // Line numbers counted in MATERIAL above.
        assert_eq!(toml_key_line(MATERIAL, "room_c"), Some(2));
        assert_eq!(toml_key_line(MATERIAL, "thermal.valid_to_c"), Some(4));
        assert_eq!(toml_key_line(MATERIAL, "thermal.density.unit"), Some(5));
        assert_eq!(toml_key_line(MATERIAL, "bounds.n"), Some(7));
        assert_eq!(toml_key_line(MATERIAL, "yield_strength.coefficients"), Some(8));
        assert_eq!(toml_key_line(MATERIAL, "yield_strength.unit"), Some(9));
        assert_eq!(toml_key_line(MATERIAL, "elastic.poisson"), None);
    }

    #[test]
    fn decode_text_locates_bad_utf8_and_drops_a_bom() {
        let e = decode_text(Path::new("f"), b"ab\ncd\xe9f".to_vec()).unwrap_err();
        assert_eq!((e.line, e.value.as_str()), (Some(2), "0xe9 0x66"));
        assert!(e.reason.contains("byte 5 (column 3)"), "{e}");
        assert_eq!(decode_text(Path::new("f"), b"\xef\xbb\xbfx".to_vec()).unwrap(), "x");
        assert!(decode_text(Path::new("f"), b" \n\t".to_vec()).unwrap_err().reason.contains("empty"));
    }

    #[test]
    fn toml_syntax_errors_carry_line_and_column() {
        let e = parse_toml::<toml::Table>(Path::new("f.toml"), "a = 1\nb = = 2\n").unwrap_err();
        assert_eq!((e.line, e.column), (Some(2), Some(5)));
        assert!(e.to_string().starts_with("f.toml:2:5: field `(toml)`"), "{e}");
    }
}
