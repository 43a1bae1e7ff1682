//! The project file of `cutcal run` (TOML): what to read, which steps to run, and which published
//! results to set beside cutcal's (`[[compare]]` of JC sets, `[fe_check]` of forces and chip
//! thickness), read and validated with located errors.
//!
//! Published results are data, not code: a `[[compare]]` entry names its row label, the dotted key
//! of the published set in `paper_tables` and the identification it is compared with; the runner
//! has no material-specific branch.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use cutcal_io::{parse_toml, read_text, toml_key_line, InputError};
use serde::{Deserialize, Serialize};

use crate::dpzd::ModelChoice;
use crate::error::Result;

/// Identification settings of a project.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectIdentify {
    /// DPZD variants to run.
    pub models: Vec<ModelChoice>,
    /// Test id (default: the material's `dpzd.identification_test`).
    #[serde(default)]
    pub test: Option<String>,
    /// Zone thickness, mm.
    pub h_mm: f64,
    /// Fit points.
    pub points: usize,
    /// Multistart starts.
    pub starts: usize,
    /// Seed.
    pub seed: u64,
    /// Material class of the literature box (steel, titanium, aluminium, none); default: from the
    /// density.
    #[serde(default)]
    pub class: Option<String>,
    /// Parameters fixed at a value (a_mpa, b_mpa, n, c, m), e.g. the n, C and m of a published set.
    #[serde(default)]
    pub fix: BTreeMap<String, f64>,
}

/// Joint (OXCUT-style) identification settings of a project.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectJoint {
    /// Multistart starts (each ~1 s).
    pub starts: usize,
    /// Seed.
    pub seed: u64,
    /// Material class of the literature box (steel, titanium, aluminium, none); default: from the
    /// density.
    #[serde(default)]
    pub class: Option<String>,
    /// Parameters fixed at a value (a_mpa, b_mpa, n, c, m), e.g. the n, C and m of a published set.
    #[serde(default)]
    pub fix: BTreeMap<String, f64>,
}

/// One published JC set to compare an identification with (`[[compare]]`).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareEntry {
    /// Row label in the report, e.g. `Table 4 enhanced`.
    pub name: String,
    /// Dotted key of the published set in `paper_tables`, e.g. `table4.enhanced`.
    pub table: String,
    /// The identification compared with it.
    pub model: ModelChoice,
}

/// One published row of a forward-model check (`[fe_check] published`).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PublishedRow {
    /// Dotted key in `paper_tables` with `fc_n_per_mm`, `ft_n_per_mm`, `chip_mm`.
    pub table: String,
    /// Row label, e.g. `experiment (paper Table 6)`.
    pub source: String,
}

/// Published forces and chip thickness of one test beside cutcal's forward predictions of it
/// with the reference set and every identified set (`[fe_check]`).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeCheck {
    /// Heading of the report section.
    pub title: String,
    /// The test (an id of the tests file).
    pub test: String,
    /// Published rows, in report order.
    pub published: Vec<PublishedRow>,
    /// How the reference set is named in its prediction row, e.g. `Table 5 JC`.
    pub reference_label: String,
}

/// A project file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectFile {
    /// Project name (output directory name).
    pub name: String,
    /// Material file, relative to the project file.
    pub material: PathBuf,
    /// Tests file, relative to the project file.
    pub tests: PathBuf,
    /// A published JC set for comparison and for the downstream steps when no test is measured.
    #[serde(default)]
    pub reference_jc: Option<PathBuf>,
    /// Published reference tables (TOML), relative to the project file.
    #[serde(default)]
    pub paper_tables: Option<PathBuf>,
    /// Published JC sets the identifications are compared with.
    #[serde(default)]
    pub compare: Vec<CompareEntry>,
    /// Published forces of one test beside the forward predictions.
    #[serde(default)]
    pub fe_check: Option<FeCheck>,
    /// Identification settings; absent: no DPZD identification.
    #[serde(default)]
    pub identify: Option<ProjectIdentify>,
    /// Joint Oxley identification over every measured test; absent: not run.
    #[serde(default)]
    pub joint: Option<ProjectJoint>,
    /// Forward predictions of every test with the JC set used (default true).
    #[serde(default = "yes")]
    pub predict: bool,
    /// Directory of raw force signals `<test>.csv`, relative to the project file (issue 13): the
    /// tests file then holds the conditions, and the `cutcal recordings` reduction fills in the
    /// forces and their standard deviations before anything else runs.
    #[serde(default)]
    pub signals: Option<PathBuf>,
    /// Run the discrepancy diagnosis (`cutcal diagnose` Mode B, extended Oxley, the JC set used
    /// held fixed) on the measured tests (default false).
    #[serde(default)]
    pub diagnose: bool,
}

fn yes() -> bool {
    true
}

/// `p` relative to the project directory `base` (an absolute `p` is kept).
#[must_use]
pub fn resolve(base: &Path, p: &Path) -> PathBuf {
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        base.join(p)
    }
}

/// The table at a dotted `key` (`table4.enhanced`) of the reference tables.
#[must_use]
pub fn table_at<'a>(tables: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut v: &toml::Value = tables.get(key.split('.').next()?)?;
    for part in key.split('.').skip(1) {
        v = v.get(part)?;
    }
    Some(v).filter(|v| v.is_table())
}

/// The number `param` of the table at `key`.
#[must_use]
pub fn table_value(tables: &toml::Table, key: &str, param: &str) -> Option<f64> {
    table_at(tables, key)?.get(param)?.as_float()
}

/// Loads a project file (parsed, not yet checked against its reference tables).
pub fn load_project(path: &Path) -> Result<ProjectFile> {
    let text = read_text(path)?;
    Ok(parse_toml(path, &text)?)
}

/// A project file with its reference tables, checked.
#[derive(Debug, Clone)]
pub struct CheckedProject {
    /// The project.
    pub project: ProjectFile,
    /// The reference tables, when the project names them.
    pub tables: Option<toml::Table>,
}

/// Loads a project file and its reference tables and checks that every `[[compare]]` and
/// `[fe_check]` entry names a table that exists and an identification the project runs.
///
/// Returns a located [`InputError`] (project file, line, field, value, reason) otherwise.
pub fn load_checked(path: &Path) -> Result<CheckedProject> {
    let text = read_text(path)?;
    let project: ProjectFile = parse_toml(path, &text)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let tables: Option<toml::Table> = match &project.paper_tables {
        Some(p) => {
            let tp = resolve(base, p);
            Some(parse_toml(&tp, &read_text(&tp)?)?)
        }
        None => None,
    };
    check(path, &text, &project, tables.as_ref())?;
    Ok(CheckedProject { project, tables })
}

/// Line of `key` in the `index`-th (0-based) `[[array]]` entry of a TOML text.
fn entry_key_line(text: &str, array: &str, index: usize, key: &str) -> Option<usize> {
    let header = format!("[[{array}]]");
    // Entries of `array` seen so far, and whether the current table is the `index`-th of them.
    let (mut count, mut inside) = (0usize, false);
    for (i, raw) in text.lines().enumerate() {
        let t = raw.trim();
        if t.starts_with('[') {
            inside = false;
            if t.starts_with(&header) {
                inside = count == index;
                count += 1;
            }
            continue;
        }
        if inside && t.split_once('=').map(|(l, _)| l.trim()) == Some(key) {
            return Some(i + 1);
        }
    }
    None
}

fn check(path: &Path, text: &str, p: &ProjectFile, tables: Option<&toml::Table>) -> Result<(), InputError> {
    let missing = |line: Option<usize>, field: &str, value: &str| {
        let why = match &p.paper_tables {
            Some(t) => format!("no such table in {}", t.display()),
            None => "the project names no paper_tables to read it from".to_string(),
        };
        InputError::new(path, line, field, value, why)
    };
    for (i, c) in p.compare.iter().enumerate() {
        if tables.and_then(|t| table_at(t, &c.table)).is_none() {
            return Err(missing(entry_key_line(text, "compare", i, "table"), "compare.table", &c.table));
        }
        if !p.identify.as_ref().is_some_and(|id| id.models.contains(&c.model)) {
            let value = format!("{:?}", c.model).to_lowercase();
            return Err(InputError::new(
                path,
                entry_key_line(text, "compare", i, "model"),
                "compare.model",
                value,
                "the project's [identify] models do not include it",
            ));
        }
    }
    if let Some(fe) = &p.fe_check {
        for r in &fe.published {
            if tables.and_then(|t| table_at(t, &r.table)).is_none() {
                return Err(missing(toml_key_line(text, "fe_check.published"), "fe_check.published.table", &r.table));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn project(extra: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        // Published values: paper Table 4 (enhanced DPZD, C38 test 3) and Table 6 (experiment).
        std::fs::write(
            dir.path().join("t.toml"),
            "[table4.enhanced]\na_mpa = 589.0\n[table6.experiment]\nfc_n_per_mm = 224.0\n",
        )
        .unwrap();
        let text = format!(
            "name = \"x\"\nmaterial = \"m.toml\"\ntests = \"t.csv\"\npaper_tables = \"t.toml\"\n{extra}\n\
             [identify]\nmodels = [\"enhanced\"]\nh_mm = 0.1\npoints = 51\nstarts = 4\nseed = 1\n"
        );
        let p = dir.path().join("p.toml");
        std::fs::write(&p, text).unwrap();
        (dir, p)
    }

    #[test]
    fn compare_entries_resolve_their_tables_and_models() {
        let (_d, p) =
            project("[[compare]]\nname = \"Table 4 enhanced\"\ntable = \"table4.enhanced\"\nmodel = \"enhanced\"");
        let c = load_checked(&p).unwrap();
        let t = c.tables.as_ref().unwrap();
        assert_eq!(table_value(t, &c.project.compare[0].table, "a_mpa"), Some(589.0));
        assert_eq!(table_value(t, "table4", "a_mpa"), None);
    }

    #[test]
    fn a_bad_compare_entry_is_located() {
        let entry = |table: &str, model: &str| {
            format!(
                "[[compare]]\nname = \"a\"\ntable = \"table4.enhanced\"\nmodel = \"enhanced\"\n\
                 [[compare]]\nname = \"b\"\ntable = \"{table}\"\nmodel = \"{model}\""
            )
        };
        // Lines 1-4 are the project header; the second entry's `table` is line 11, `model` line 12.
        let (_d, p) = project(&entry("table4.enhnced", "enhanced"));
        let e = load_checked(&p).unwrap_err().to_string();
        assert!(e.contains("p.toml:11: field `compare.table` = 'table4.enhnced': no such table in t.toml"), "{e}");
        let (_d, p) = project(&entry("table4.enhanced", "original"));
        let e = load_checked(&p).unwrap_err().to_string();
        assert!(e.contains("p.toml:12: field `compare.model` = 'original': the project's [identify]"), "{e}");
    }
}
