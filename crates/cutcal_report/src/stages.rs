//! `cutcal run PROJECT.toml` as a sequence of named stages, each a function with typed input and
//! output: [`read_inputs`] (material, tests or raw signals, reference set, published tables),
//! [`identify`] (DPZD, paper Eq 15), [`compare`] (the project's `[[compare]]` entries),
//! [`choose_jc`] (the set used downstream), [`cards`], then `predict`, `joint` and `diagnose`
//! ([`crate::stages_downstream`]) and [`finish`] (report files, atomic commit). [`run_project`]
//! chains them; everything is written into a staged directory that is moved into place only when
//! every stage succeeded.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use cutcal_io::material_file::{load_material, MaterialFile};
use cutcal_io::output::StagedDir;
use cutcal_io::tests_csv::{parse_tests_with_columns, Columns, MeasuredColumn};
use cutcal_io::{read_text, toml_key_line, InputError};
use cutcal_model::{CuttingTest, JcParams};

use crate::dpzd::{identify_dpzd, pick_test, DpzdOutcome, DpzdSettings, JcReport, Preset};
use crate::dpzd_report::{fields_csv, jc_toml};
use crate::error::{Context, Result};
use crate::project::{load_checked, resolve, table_value, CheckedProject, ProjectFile};
use crate::project_report::{Comparison, ProjectReport};
use crate::recordings::TestSummary;
use crate::stages_downstream::{diagnose, joint, predict};
use crate::{plots, run_steps, Progress};

/// The files of a run, written into the staged output directory (names relative to it).
#[derive(Debug)]
pub struct Output<'a> {
    /// The staged directory.
    pub staged: &'a StagedDir,
    /// Files written so far.
    pub files: Vec<String>,
}

impl Output<'_> {
    /// Writes `name` into the staged directory and records it.
    pub fn write(&mut self, name: &str, contents: &str) -> Result<()> {
        self.staged.write(name, contents.as_bytes())?;
        self.files.push(name.to_string());
        Ok(())
    }
}

/// Stage 1's output: everything the later stages read.
#[derive(Debug, Clone)]
pub struct Inputs {
    /// The project file.
    pub project: ProjectFile,
    /// Its published reference tables.
    pub tables: Option<toml::Table>,
    /// The material file.
    pub mf: MaterialFile,
    /// The tests file as the project names it (resolved).
    pub tests_path: PathBuf,
    /// The test rows (reduced from the signals for a signals project).
    pub tests: Vec<CuttingTest>,
    /// Columns of the rows' file.
    pub columns: Columns,
    /// File name of the rows, for messages.
    pub tests_name: String,
    /// The per-test signal reduction of a signals project.
    pub recordings: Option<Vec<TestSummary>>,
    /// The reference JC set.
    pub reference_jc: Option<JcParams>,
}

impl Inputs {
    /// The material's name, the label of progress lines and plots.
    #[must_use]
    pub fn label(&self) -> &str {
        &self.mf.material.name
    }
}

/// Stage 1, read inputs: the material, the test rows (a signals project first reduces its raw
/// signals into them, writing the reduction's files), the reference set.
///
/// Returns a located error if an input is malformed or the `[fe_check]` test is not a row.
pub fn read_inputs(
    project_path: &Path,
    checked: CheckedProject,
    out: &mut Output<'_>,
    progress: &dyn Progress,
) -> Result<Inputs> {
    let CheckedProject { project, tables } = checked;
    let base = project_path.parent().unwrap_or(Path::new("."));
    let mf: MaterialFile = load_material(&resolve(base, &project.material))?;
    let tests_path = resolve(base, &project.tests);
    let (tests, columns, tests_name, recordings) = match &project.signals {
        Some(sig) => {
            let rows =
                run_steps::signals_step(out.staged, &tests_path, &project.tests, &resolve(base, sig), sig, progress)?;
            out.files.extend(rows.files);
            (rows.tests, rows.columns, run_steps::MEASURED_TESTS.to_string(), Some(rows.summaries))
        }
        None => {
            let (tests, columns) = parse_tests_with_columns(&tests_path, &read_text(&tests_path)?)?;
            let name = tests_path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
            (tests, columns, name, None)
        }
    };
    if let Some(fe) = project.fe_check.as_ref().filter(|fe| !tests.iter().any(|t| t.id == fe.test)) {
        let line = toml_key_line(&read_text(project_path)?, "fe_check.test");
        let why = format!("no test with this id in {tests_name}");
        return Err(InputError::new(project_path, line, "fe_check.test", &fe.test, why).into());
    }
    let reference_jc =
        project.reference_jc.as_ref().map(|p| cutcal_io::jc_file::load_jc(&resolve(base, p))).transpose()?;
    Ok(Inputs { project, tables, mf, tests_path, tests, columns, tests_name, recordings, reference_jc })
}

/// Stage 2's output: the identifications by model (`original`, `enhanced`), or why none ran.
#[derive(Debug, Clone, Default)]
pub struct Identified {
    /// Identifications by model name.
    pub outcomes: BTreeMap<String, DpzdOutcome>,
    /// Why the identification did not run.
    pub skipped: Option<String>,
}

/// Stage 2, identify: the DPZD identification (paper Eq 15, the project's h and N, i.e. the
/// paper's discrete objective) of the project's test with every model asked for, when the test
/// has Fc, Ft and tc; writes `jc_<model>.toml`, `zone_<model>.csv`, `fit_<model>.svg` and, with
/// both models, the Fig 4 field plots.
pub fn identify(inp: &Inputs, out: &mut Output<'_>, progress: &dyn Progress) -> Result<Identified> {
    let (mf, label) = (&inp.mf, inp.label());
    let reference = inp.reference_jc.is_some();
    let Some(idc) = &inp.project.identify else {
        let why = dpzd_skip_reason(&inp.tests_name, &inp.columns, None, reference);
        return Ok(Identified { outcomes: BTreeMap::new(), skipped: Some(why) });
    };
    let test = pick_test(&inp.tests, idc.test.as_deref(), mf, &inp.tests_path)?;
    let m = &test.measured;
    if !(m.cutting_force_n_per_m.is_some() && m.feed_force_n_per_m.is_some() && m.chip_thickness_m.is_some()) {
        let why = dpzd_skip_reason(&inp.tests_name, &inp.columns, Some(test), reference);
        return Ok(Identified { outcomes: BTreeMap::new(), skipped: Some(why) });
    }
    let dp = mf.dpzd.as_ref().with_context(|| format!("{}: no [dpzd] section", mf.path.display()))?;
    let mut outcomes = BTreeMap::new();
    for model in &idc.models {
        progress.stage(label, &format!("identifying JC from test {} ({model:?} DPZD, {} starts)", test.id, idc.starts));
        let settings = DpzdSettings {
            // The project file states h and N, so it runs the paper's discrete objective.
            preset: Preset::Paper,
            model: *model,
            h_m: idc.h_mm * 1e-3,
            h_from_forward_model: false,
            r: dp.r,
            points: idc.points,
            rho_cp_original_j_per_m3_k: dp.rho_cp_original_j_per_cm3_k * 1e6,
            tolerance_c: 1e-6,
            max_iterations: 50,
            multistart: cutcal_ident::MultistartOptions::new(idc.starts, idc.seed),
        };
        let o = identify_dpzd(mf, test, &settings)?;
        let key = format!("{model:?}").to_lowercase();
        let source =
            format!("cutcal {} run {}: test {} ({key} DPZD)", env!("CARGO_PKG_VERSION"), inp.project.name, test.id);
        out.write(&format!("jc_{key}.toml"), &jc_toml(&o.identification.jc, source)?)?;
        out.write(&format!("zone_{key}.csv"), &fields_csv(&o.zone, 201)?)?;
        let title = format!("{label} test {} ({key})", test.id);
        out.write(&format!("fit_{key}.svg"), &plots::fit_over_x(&o.zone, &o.identification.jc, &title)?)?;
        outcomes.insert(key, o);
    }
    if let (Some(o), Some(e)) = (outcomes.get("original"), outcomes.get("enhanced")) {
        for (name, svg) in plots::zone_fields(&o.zone, &e.zone, &format!("{label} test {}", test.id))? {
            out.write(&name, &svg)?;
        }
    }
    Ok(Identified { outcomes, skipped: None })
}

/// Stage 3, compare: every `[[compare]]` entry whose model was identified, parameter by
/// parameter against its published set (in the project file's order).
#[must_use]
pub fn compare(inp: &Inputs, id: &Identified) -> Vec<Comparison> {
    let Some(tables) = &inp.tables else { return Vec::new() };
    let mut rows = Vec::new();
    for c in &inp.project.compare {
        let Some(o) = id.outcomes.get(&format!("{:?}", c.model).to_lowercase()) else { continue };
        let jc = &o.report.jc;
        for (p, ours) in [("a_mpa", jc.a_mpa), ("b_mpa", jc.b_mpa), ("n", jc.n), ("c", jc.c), ("m", jc.m)] {
            if let Some(published) = table_value(tables, &c.table, p) {
                rows.push(Comparison {
                    against: c.name.clone(),
                    parameter: p.into(),
                    ours,
                    published,
                    diff_pct: Some((ours - published) / published * 100.0).filter(|d| d.is_finite()),
                });
            }
        }
    }
    rows
}

/// Stage 4, choose the JC set used downstream: the enhanced identification, else the reference
/// set; writes its flow curves.
pub fn choose_jc(inp: &Inputs, id: &Identified, out: &mut Output<'_>) -> Result<Option<(String, JcParams)>> {
    let used = id
        .outcomes
        .get("enhanced")
        .map(|o| ("identified (enhanced DPZD)".to_string(), o.identification.jc))
        .or_else(|| inp.reference_jc.map(|j| ("reference set".to_string(), j)));
    if let Some((src, jc)) = &used {
        let title = format!("{} ({src})", inp.label());
        out.write("flow_curves.svg", &plots::flow_curves(jc, &title, &[20.0, 400.0, 800.0], &[1e3, 1e5]))?;
    }
    Ok(used)
}

/// Stage 5, cards: FE cards of every dialect for the set used (when the material has an
/// `[interface]`), into `cards/`.
pub fn cards(
    inp: &Inputs,
    id: &Identified,
    jc_used: Option<&(String, JcParams)>,
    out: &mut Output<'_>,
    progress: &dyn Progress,
) -> Result<()> {
    let (Some((src, jc)), Some(_)) = (jc_used, &inp.mf.interface) else { return Ok(()) };
    progress.stage(inp.label(), "rendering FE cards");
    let provenance = cutcal_export::Provenance {
        cutcal_version: env!("CARGO_PKG_VERSION").to_string(),
        source_test: format!("{} ({src})", inp.project.name),
        model_variant: if id.outcomes.contains_key("enhanced") {
            "enhanced DPZD".into()
        } else {
            "reference JC set".into()
        },
    };
    for f in crate::export::render_cards(&inp.mf, jc, &provenance)? {
        out.write(&format!("cards/{}", f.name), &f.contents)?;
    }
    Ok(())
}

/// Runs a project into `out` (atomically) and returns its report.
///
/// Returns an error if the project file or an input is malformed (located), a stage fails, or
/// the output cannot be written; then nothing is left behind.
pub fn run_project(project_path: &Path, out: &Path, progress: &dyn Progress) -> Result<ProjectReport> {
    let checked = load_checked(project_path)?;
    let staged = StagedDir::new(out)?;
    let mut o = Output { staged: &staged, files: Vec::new() };
    let inp = read_inputs(project_path, checked, &mut o, progress)?;
    let id = identify(&inp, &mut o, progress)?;
    let comparisons = compare(&inp, &id);
    let jc_used = choose_jc(&inp, &id, &mut o)?;
    cards(&inp, &id, jc_used.as_ref(), &mut o, progress)?;
    let oxley = crate::predict::oxley_options(inp.mf.oxley.as_ref(), false, None, None, None, None, None)
        .with_context(|| format!("Oxley options for {}", inp.mf.path.display()))?;
    let predicted = predict(&inp, &id, jc_used.as_ref(), &oxley, &mut o, progress)?;
    let joint = joint(&inp, &oxley, &mut o, progress)?;
    let diagnosed = diagnose(&inp, jc_used.as_ref(), &mut o, progress)?;
    let report = ProjectReport {
        project: inp.project.name.clone(),
        material: inp.label().to_string(),
        cutcal_version: env!("CARGO_PKG_VERSION").into(),
        identification: id.outcomes.iter().map(|(k, o)| (k.clone(), o.report.clone())).collect(),
        identification_skipped: id.skipped,
        comparisons,
        jc_used: jc_used.as_ref().map(|(s, j)| (s.clone(), JcReport::from_params(j, None))),
        predictions: predicted.predictions,
        table6: predicted.table6,
        table6_title: inp.project.fe_check.as_ref().map(|f| f.title.clone()).unwrap_or_default(),
        joint,
        recordings: inp.recordings.clone(),
        diagnosis: diagnosed.diagnosis,
        diagnosis_skipped: diagnosed.skipped,
        files: Vec::new(),
    };
    let files = o.files;
    finish(report, files, staged, out, progress, inp.label())
}

/// Last stage, report: writes `report.md` and `report.json`, then moves the staged directory into
/// place.
pub fn finish(
    mut report: ProjectReport,
    mut files: Vec<String>,
    staged: StagedDir,
    out: &Path,
    progress: &dyn Progress,
    label: &str,
) -> Result<ProjectReport> {
    files.push("report.md".into());
    files.push("report.json".into());
    files.sort();
    report.files = files;
    staged.write("report.md", crate::project_report::render_markdown(&report).as_bytes())?;
    staged.write("report.json", (serde_json::to_string_pretty(&report)? + "\n").as_bytes())?;
    staged.commit()?;
    progress.stage(label, &format!("wrote {} files to {}", report.files.len(), out.display()));
    Ok(report)
}

/// Why the DPZD identification (paper Eq 15, which needs Fc, Ft and tc of one test) did not run:
/// the columns the tests file lacks, the quantities `test` lacks, or (no `test`) that the project
/// has no `[identify]` section; and what is used downstream instead.
fn dpzd_skip_reason(
    tests_name: &str,
    columns: &Columns,
    test: Option<&cutcal_model::CuttingTest>,
    reference: bool,
) -> String {
    let lacking: Vec<&str> = [
        (MeasuredColumn::CuttingForce, "Fc"),
        (MeasuredColumn::FeedForce, "Ft"),
        (MeasuredColumn::ChipThickness, "tc"),
    ]
    .into_iter()
    .filter(|(m, _)| !columns.has(*m))
    .map(|(_, n)| n)
    .collect();
    let mut why = if !lacking.is_empty() {
        format!(
            "the DPZD identification (paper Eq 15) needs the measured Fc, Ft and tc of one test, and {tests_name} has no {} column",
            lacking.join(", ")
        )
    } else if let Some(t) = test {
        let m = &t.measured;
        let absent: Vec<&str> = [
            (m.cutting_force_n_per_m.is_none(), "Fc"),
            (m.feed_force_n_per_m.is_none(), "Ft"),
            (m.chip_thickness_m.is_none(), "tc"),
        ]
        .into_iter()
        .filter(|(a, _)| *a)
        .map(|(_, n)| n)
        .collect();
        format!(
            "the DPZD identification (paper Eq 15) needs the measured Fc, Ft and tc of test {}, and its {} cells in {tests_name} are empty",
            t.id,
            absent.join(", ")
        )
    } else {
        "the project file has no [identify] section".to_string()
    };
    if test.is_none() && !lacking.is_empty() {
        why.push_str("; the project file has no [identify] section");
    }
    why.push_str(if reference {
        "; the reference JC set is used downstream"
    } else {
        "; no JC set is available downstream"
    });
    why
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_fe_check_of_a_missing_test_is_located_in_the_project_file() {
        let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
        let dir = tempfile::tempdir().unwrap();
        let project = dir.path().join("p.toml");
        // The C38 files (paper Tables 2, 3, 6); test 9 is not a row of c38.csv.
        let text = format!(
            "name = \"p\"\nmaterial = {:?}\ntests = {:?}\npaper_tables = {:?}\n\n[fe_check]\ntitle = \"t\"\n\
             test = \"9\"\nreference_label = \"r\"\npublished = [{{ table = \"table6.experiment\", source = \"e\" }}]\n",
            fixtures.join("materials/c38.toml"),
            fixtures.join("tests/c38.csv"),
            fixtures.join("reference/paper_tables.toml"),
        );
        std::fs::write(&project, text).unwrap();
        let staged = StagedDir::new(&dir.path().join("out")).unwrap();
        let mut out = Output { staged: &staged, files: Vec::new() };
        let checked = load_checked(&project).unwrap();
        let e = read_inputs(&project, checked, &mut out, &crate::Quiet).unwrap_err().to_string();
        assert!(e.ends_with("p.toml:8: field `fe_check.test` = '9': no test with this id in c38.csv"), "{e}");
    }
}
