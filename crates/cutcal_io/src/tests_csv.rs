//! A cutting-test CSV (`fixtures/tests/*.csv`), one row per test; `#` lines are comments.
//!
//! Columns (header names are the contract):
//! - required: `test`, `speed_m_min`, `uncut_mm`, `width_mm`, `rake_deg`;
//! - forces, either per unit width `fc_n_per_mm`, `ft_n_per_mm` (N/mm) or totals over the width
//!   `fc_n`, `ft_n` (N) -- not both kinds in one file;
//! - optional: `chip_mm`, `edge_radius_um`, `flank_wear_mm`, `order`, `t_int_c`;
//! - optional per-row uncertainty (standard deviations, same units as the value columns):
//!   `fc_sd_n_per_mm`, `ft_sd_n_per_mm` with per-width forces or `fc_sd_n`, `ft_sd_n` with totals,
//!   `chip_sd_mm` and `t_int_sd_c` (K); they go to [`CuttingTest::with_measurement_sd`];
//! - optional covariates written by `cutcal recordings` (0/1): `wear_flag` (significant drift across
//!   the steady window, possible tool wear) and `bue_flag` (strong low-frequency oscillation,
//!   possible built-up edge); they are checked here and left to the diagnosis.
//!
//! An empty cell means "not measured". When a file has no sd column for a quantity, repeated tests
//! at one condition (same speed, uncut chip thickness, width, rake, edge radius and flank wear; two
//! or more rows measuring it) give it: the sample standard deviation of the repeats is set on each
//! of them ([`derive_sd_from_repeats`]).

use std::collections::HashSet;
use std::path::Path;

use cutcal_model::dpzd::ShearPlaneState;
use cutcal_model::{CuttingTest, MeasuredSd};

use super::{model_reason, read_text, InputError};
pub use crate::test_columns::{derive_sd_from_repeats, Columns, MeasuredColumn};

pub(crate) const REQUIRED: [&str; 5] = ["test", "speed_m_min", "uncut_mm", "width_mm", "rake_deg"];
pub(crate) const OPTIONAL: [&str; 18] = [
    "fc_n_per_mm",
    "ft_n_per_mm",
    "fc_n",
    "ft_n",
    "fc_sd_n_per_mm",
    "ft_sd_n_per_mm",
    "fc_sd_n",
    "ft_sd_n",
    "chip_sd_mm",
    "t_int_sd_c",
    "wear_flag",
    "bue_flag",
    "chip_mm",
    "edge_radius_um",
    "flank_wear_mm",
    "order",
    "t_int_c",
    "note",
];

/// Reads and validates a test CSV.
pub fn load_tests(path: &Path) -> Result<Vec<CuttingTest>, InputError> {
    let text = read_text(path)?;
    parse_tests(path, &text)
}

/// Reads a test CSV for a command that needs `needs` measured: as [`load_tests`], and a file with
/// no column for one of them is an error naming the file, the accepted column names and the
/// columns found (rather than a later "not measured" about one row).
pub fn load_tests_measuring(
    path: &Path,
    needs: &[MeasuredColumn],
    purpose: &str,
) -> Result<Vec<CuttingTest>, InputError> {
    let text = read_text(path)?;
    let (tests, columns) = parse_tests_with_columns(path, &text)?;
    columns.require(path, needs, purpose)?;
    Ok(tests)
}

/// Parses test CSV text (`path` is only used in messages).
///
/// Returns a located error (line, column name, value) for CSV structure (missing, unknown or
/// duplicate columns, ragged rows), empty or non-numeric cells, NaN/infinite or out-of-range values,
/// duplicate test ids, a chip ratio with no shear angle, and forces with no positive shear-plane
/// force (Eq 9) at the measured shear angle.
pub fn parse_tests(path: &Path, text: &str) -> Result<Vec<CuttingTest>, InputError> {
    parse_tests_with_columns(path, text).map(|(tests, _)| tests)
}

/// [`parse_tests`], also returning the header.
pub fn parse_tests_with_columns(path: &Path, text: &str) -> Result<(Vec<CuttingTest>, Columns), InputError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut rdr =
        csv::ReaderBuilder::new().comment(Some(b'#')).trim(csv::Trim::All).flexible(false).from_reader(text.as_bytes());
    let csv_err = |e: csv::Error| {
        let line = e.position().map(|p| crate::record_line(text, p));
        match e.kind() {
            csv::ErrorKind::UnequalLengths { expected_len, len, .. } => InputError::new(
                path,
                line,
                "(row)",
                format!("{len} cells"),
                format!("the header has {expected_len} columns; every row needs one cell per column"),
            ),
            _ => InputError::new(path, line, "(csv)", "", e.to_string()),
        }
    };
    let headers = rdr.headers().map_err(csv_err)?.clone();
    let header_line =
        text.lines().position(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty()).map(|i| i + 1);
    if headers.is_empty() {
        return Err(InputError::new(path, None, "(header)", "", "no header row (the file has only comments)"));
    }
    for (i, h) in headers.iter().enumerate() {
        if h.is_empty() {
            return Err(InputError::new(
                path,
                header_line,
                &format!("(column {})", i + 1),
                "",
                "empty column name (a trailing comma in the header?)",
            ));
        }
        if !REQUIRED.contains(&h) && !OPTIONAL.contains(&h) {
            let stem = h.split('_').next().unwrap_or(h);
            let hint = REQUIRED
                .iter()
                .chain(OPTIONAL.iter())
                .find(|k| k.split('_').next() == Some(stem))
                .map(|k| format!(" (did you mean `{k}`? units are part of the column name)"))
                .unwrap_or_default();
            return Err(InputError::new(
                path,
                header_line,
                h,
                "",
                format!("unknown column{hint}; expected {REQUIRED:?} and optionally {OPTIONAL:?}"),
            ));
        }
        if headers.iter().take(i).any(|earlier| earlier == h) {
            return Err(InputError::new(path, header_line, h, "", format!("duplicate column (column {})", i + 1)));
        }
    }
    for r in REQUIRED {
        if !headers.iter().any(|h| h == r) {
            return Err(InputError::new(path, header_line, r, "", "required column is missing"));
        }
    }
    let per_mm =
        headers.iter().any(|h| ["fc_n_per_mm", "ft_n_per_mm", "fc_sd_n_per_mm", "ft_sd_n_per_mm"].contains(&h));
    let totals = headers.iter().any(|h| ["fc_n", "ft_n", "fc_sd_n", "ft_sd_n"].contains(&h));
    if per_mm && totals {
        return Err(InputError::new(
            path,
            header_line,
            "fc_n",
            "",
            "give forces either per unit width (fc_n_per_mm, ft_n_per_mm, fc_sd_n_per_mm, ft_sd_n_per_mm) or as totals (fc_n, ft_n, fc_sd_n, ft_sd_n), not both",
        ));
    }
    let col = |name: &str| headers.iter().position(|h| h == name);
    let mut tests = Vec::new();
    let mut seen = HashSet::new();
    for rec in rdr.records() {
        let rec = rec.map_err(csv_err)?;
        let line = rec.position().map(|p| crate::record_line(text, p));
        let cell = |name: &str| col(name).and_then(|i| rec.get(i)).unwrap_or("");
        let num = |name: &str, required: bool| -> Result<Option<f64>, InputError> {
            let s = cell(name);
            if s.is_empty() {
                return if required {
                    Err(InputError::new(path, line, name, s, "a value is required"))
                } else {
                    Ok(None)
                };
            }
            let v: f64 = s.parse().map_err(|_| InputError::new(path, line, name, s, "not a number"))?;
            if !v.is_finite() {
                return Err(InputError::new(path, line, name, s, "must be a finite number"));
            }
            Ok(Some(v))
        };
        let id = cell("test").to_string();
        if id.is_empty() {
            return Err(InputError::new(path, line, "test", "", "a test id is required"));
        }
        if !seen.insert(id.clone()) {
            return Err(InputError::new(path, line, "test", &id, "duplicate test id"));
        }
        // The value is reported as written in the file, the rule in the model's SI units.
        let located = |field: &'static str| {
            let v = cell(field).to_string();
            move |e: cutcal_model::ModelError| InputError::new(path, line, field, &v, model_reason(&e))
        };
        let speed = num("speed_m_min", true)?.unwrap_or_default();
        let uncut = num("uncut_mm", true)?.unwrap_or_default();
        let width = num("width_mm", true)?.unwrap_or_default();
        let rake = num("rake_deg", true)?.unwrap_or_default();
        let mut t = CuttingTest::new(id, speed / 60.0, uncut * 1e-3, width * 1e-3, rake.to_radians()).map_err(|e| {
            let field = match &e {
                cutcal_model::ModelError::OutOfRange { field, .. } if field.starts_with("speed") => "speed_m_min",
                cutcal_model::ModelError::OutOfRange { field, .. } if field.starts_with("uncut") => "uncut_mm",
                cutcal_model::ModelError::OutOfRange { field, .. } if field.starts_with("width") => "width_mm",
                _ => "rake_deg",
            };
            InputError::new(path, line, field, cell(field), model_reason(&e))
        })?;
        let (fc, ft, fc_name, ft_name) = if totals {
            // Totals over the width: N / (w in m) = N/m.
            let w = t.width_m;
            (num("fc_n", false)?.map(|f| f / w), num("ft_n", false)?.map(|f| f / w), "fc_n", "ft_n")
        } else {
            (
                num("fc_n_per_mm", false)?.map(|f| f * 1e3),
                num("ft_n_per_mm", false)?.map(|f| f * 1e3),
                "fc_n_per_mm",
                "ft_n_per_mm",
            )
        };
        t = t.with_forces(fc, None).map_err(located(fc_name))?;
        t = t.with_forces(fc, ft).map_err(located(ft_name))?;
        let chip = num("chip_mm", false)?;
        t = t.with_chip_thickness(chip.map(|c| c * 1e-3)).map_err(located("chip_mm"))?;
        let tint = num("t_int_c", false)?;
        t = t.with_interface_temperature(tint).map_err(located("t_int_c"))?;
        let re = num("edge_radius_um", false)?;
        let vb = num("flank_wear_mm", false)?;
        t = t.with_tool_condition(re.map(|r| r * 1e-6), None).map_err(located("edge_radius_um"))?;
        t = t.with_tool_condition(re.map(|r| r * 1e-6), vb.map(|v| v * 1e-3)).map_err(located("flank_wear_mm"))?;
        let (fc_sd, ft_sd, fc_sd_name, ft_sd_name) = if totals {
            let w = t.width_m;
            (num("fc_sd_n", false)?.map(|f| f / w), num("ft_sd_n", false)?.map(|f| f / w), "fc_sd_n", "ft_sd_n")
        } else {
            (
                num("fc_sd_n_per_mm", false)?.map(|f| f * 1e3),
                num("ft_sd_n_per_mm", false)?.map(|f| f * 1e3),
                "fc_sd_n_per_mm",
                "ft_sd_n_per_mm",
            )
        };
        let chip_sd = num("chip_sd_mm", false)?.map(|c| c * 1e-3);
        let tint_sd = num("t_int_sd_c", false)?;
        for (name, v) in [(fc_sd_name, fc_sd), (ft_sd_name, ft_sd), ("chip_sd_mm", chip_sd), ("t_int_sd_c", tint_sd)] {
            if v.is_some_and(|x| x <= 0.0) {
                return Err(InputError::new(path, line, name, cell(name), "a standard deviation must be > 0"));
            }
        }
        t = t
            .with_measurement_sd(MeasuredSd {
                cutting_force_n_per_m: fc_sd,
                feed_force_n_per_m: ft_sd,
                chip_thickness_m: chip_sd,
                interface_temperature_c: tint_sd,
            })
            .map_err(|e| {
                let field = match &e {
                    cutcal_model::ModelError::OutOfRange { field, .. } if field.starts_with("feed") => ft_sd_name,
                    cutcal_model::ModelError::OutOfRange { field, .. } if field.starts_with("chip") => "chip_sd_mm",
                    cutcal_model::ModelError::OutOfRange { field, .. } if field.starts_with("interface") => {
                        "t_int_sd_c"
                    }
                    _ => fc_sd_name,
                };
                InputError::new(path, line, field, cell(field), model_reason(&e))
            })?;
        for flag in ["wear_flag", "bue_flag"] {
            if let Some(v) = num(flag, false)? {
                if v.abs() > 0.0 && (v - 1.0).abs() > 0.0 {
                    return Err(InputError::new(path, line, flag, cell(flag), "a flag is 0 or 1"));
                }
            }
        }
        if let Some(o) = num("order", false)? {
            if o < 0.0 || o.fract().abs() > 0.0 || o > 1e9 {
                return Err(InputError::new(path, line, "order", o, "must be a non-negative whole number"));
            }
            t.order = Some(o as u32);
        }
        if let (Some(_), Some(_), Some(_)) =
            (t.measured.cutting_force_n_per_m, t.measured.feed_force_n_per_m, t.measured.chip_thickness_m)
        {
            // Eq 9 needs a positive shear-plane force; say so here, at the row, not deep in a solve.
            if let Err(e) = ShearPlaneState::from_test(&t) {
                return Err(InputError::new(path, line, ft_name, cell(ft_name), model_reason(&e)));
            }
        }
        tests.push(t);
    }
    if tests.is_empty() {
        return Err(InputError::new(path, header_line, "(rows)", "", "no test rows"));
    }
    let has = |names: [&str; 2]| names.iter().any(|n| headers.iter().any(|h| h == *n));
    derive_sd_from_repeats(
        &mut tests,
        [!has(["fc_sd_n_per_mm", "fc_sd_n"]), !has(["ft_sd_n_per_mm", "ft_sd_n"]), !has(["chip_sd_mm", "chip_sd_mm"])],
    );
    let columns = Columns { names: headers.iter().map(str::to_string).collect(), line: header_line };
    Ok((tests, columns))
}

#[cfg(test)]
mod tests;
