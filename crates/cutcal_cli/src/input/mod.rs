//! Reading cutcal's input files (material and JC TOML, test CSV) into validated model types.
//!
//! Every error names the file, the line (where the format has lines), the field and the value.

pub mod jc_file;
pub mod material_file;
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
    pub(crate) fn new(
        file: &Path,
        line: Option<usize>,
        field: &str,
        value: impl fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Self {
            file: file.to_path_buf(),
            line,
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}

/// Reads a whole file as UTF-8 text with a located error.
pub(crate) fn read_text(path: &Path) -> Result<String, InputError> {
    let bytes =
        std::fs::read(path).map_err(|e| InputError::new(path, None, "(file)", "", format!("cannot read: {e}")))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let upto = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = upto.iter().filter(|b| **b == b'\n').count() + 1;
        InputError::new(
            path,
            Some(line),
            "(text)",
            "",
            format!("not valid UTF-8 (byte {})", e.utf8_error().valid_up_to()),
        )
    })?;
    if text.trim().is_empty() {
        return Err(InputError::new(path, None, "(file)", "", "the file is empty"));
    }
    Ok(text)
}

/// 1-based line of a byte offset in `text`.
pub(crate) fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())].iter().filter(|b| **b == b'\n').count() + 1
}

/// Finds the line where `key` is assigned in a TOML text (best effort, for located validation errors).
pub(crate) fn toml_key_line(text: &str, key: &str) -> Option<usize> {
    text.lines()
        .position(|l| {
            let t = l.trim_start();
            t.starts_with(key) && t[key.len()..].trim_start().starts_with('=')
        })
        .map(|i| i + 1)
}

/// Parses TOML into `T` with a located error.
pub(crate) fn parse_toml<T: serde::de::DeserializeOwned>(path: &Path, text: &str) -> Result<T, InputError> {
    toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| line_of(text, s.start));
        let value =
            e.span().map(|s| text[s.clone()].lines().next().unwrap_or("").trim().to_string()).unwrap_or_default();
        InputError::new(path, line, "(toml)", value, e.message().to_string())
    })
}
