//! `cutcal run PROJECT.toml`: the whole chain for one material -- identification (DPZD, original and
//! enhanced), cards, forward predictions -- into one output directory with `report.md`,
//! `report.json` and SVG plots, written atomically.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use cutcal_model::JcParams;
use serde::{Deserialize, Serialize};

use super::identify::{identify_dpzd, pick_test, DpzdIdentifyReport, DpzdOutcome, DpzdSettings, JcReport, ModelChoice};
use crate::report::plots;
use cutcal_io::material_file::{load_material, MaterialFile};
use cutcal_io::output::StagedDir;
use cutcal_io::tests_csv::{parse_tests_with_columns, Columns, MeasuredColumn};
use cutcal_io::{parse_toml, read_text};

/// Arguments of `cutcal run`.
#[derive(Debug, Clone, clap::Args)]
pub struct RunArgs {
    /// Project file (TOML), e.g. fixtures/projects/c38.toml.
    pub project: PathBuf,
    /// Output directory (default: target/pipeline/<project name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print the report JSON to stdout.
    #[arg(long)]
    pub json: bool,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
}

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
    pub fix: std::collections::BTreeMap<String, f64>,
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
    /// Paper table row to compare with (`table4.original`/`table4.enhanced` are used for the C38
    /// test-3 identification, `table5.<key>` for the enhanced set).
    #[serde(default)]
    pub paper_table5_key: Option<String>,
    /// Paper reference tables (TOML), relative to the project file.
    #[serde(default)]
    pub paper_tables: Option<PathBuf>,
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
    pub fix: std::collections::BTreeMap<String, f64>,
}

/// The paper's FE result for a test beside cutcal's forward prediction (Table 6).
#[derive(Debug, Clone, Serialize)]
pub struct FeComparison {
    /// Row label.
    pub source: String,
    /// Cutting force, N/mm.
    pub fc_n_per_mm: Option<f64>,
    /// Feed force, N/mm.
    pub ft_n_per_mm: Option<f64>,
    /// Chip thickness, mm.
    pub chip_mm: Option<f64>,
}

/// One parameter compared with a published value.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// What is compared (e.g. `Table 4 enhanced`).
    pub against: String,
    /// Parameter.
    pub parameter: String,
    /// Ours.
    pub ours: f64,
    /// Published.
    pub published: f64,
    /// (ours - published)/published, %; `None` when the published value is zero (no relative
    /// difference exists).
    pub diff_pct: Option<f64>,
}

/// The machine-readable project report.
#[derive(Debug, Clone, Serialize)]
pub struct ProjectReport {
    /// Project name.
    pub project: String,
    /// Material name.
    pub material: String,
    /// cutcal version.
    pub cutcal_version: String,
    /// Identifications by model.
    pub identification: BTreeMap<String, DpzdIdentifyReport>,
    /// Why an identification was not run, if it was not.
    pub identification_skipped: Option<String>,
    /// Comparisons with the paper's tables.
    pub comparisons: Vec<Comparison>,
    /// The JC set used downstream (cards, predictions) and where it comes from.
    pub jc_used: Option<(String, JcReport)>,
    /// Forward predictions (extended Oxley) of every test with the JC set used.
    pub predictions: Vec<super::predict::PredictRow>,
    /// The paper's Table 6 FE results beside our predictions (C38 test 3).
    pub table6: Vec<FeComparison>,
    /// Joint Oxley identification, when run.
    pub joint: Option<cutcal_ident::joint::OxleyIdentification>,
    /// Per-test reduction of the raw signals, for a project that starts from signals.
    pub recordings: Option<Vec<super::recordings::TestSummary>>,
    /// The discrepancy diagnosis, when the project asks for it.
    pub diagnosis: Option<super::run_steps::ProjectDiagnosis>,
    /// Why the diagnosis asked for did not run.
    pub diagnosis_skipped: Option<String>,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
}

fn resolve(base: &Path, p: &Path) -> PathBuf {
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        base.join(p)
    }
}

fn table_value(tables: &toml::Table, key: &str, param: &str) -> Option<f64> {
    let mut v: &toml::Value = tables.get(key.split('.').next()?)?;
    for part in key.split('.').skip(1) {
        v = v.get(part)?;
    }
    v.get(param)?.as_float()
}

fn compare(against: &str, tables: &toml::Table, key: &str, jc: &JcReport) -> Vec<Comparison> {
    [("a_mpa", jc.a_mpa), ("b_mpa", jc.b_mpa), ("n", jc.n), ("c", jc.c), ("m", jc.m)]
        .iter()
        .filter_map(|(p, ours)| {
            table_value(tables, key, p).map(|published| Comparison {
                against: against.into(),
                parameter: (*p).into(),
                ours: *ours,
                published,
                diff_pct: Some((ours - published) / published * 100.0).filter(|d| d.is_finite()),
            })
        })
        .collect()
}

/// Loads a project file.
pub fn load_project(path: &Path) -> Result<ProjectFile> {
    let text = read_text(path)?;
    Ok(parse_toml(path, &text)?)
}

/// Runs a project into `out` (atomically) and returns its report.
pub fn run_project(project_path: &Path, out: &Path, quiet: bool) -> Result<ProjectReport> {
    let project = load_project(project_path)?;
    let base = project_path.parent().unwrap_or(Path::new("."));
    let mf: MaterialFile = load_material(&resolve(base, &project.material))?;
    let tests_path = resolve(base, &project.tests);
    let staged = StagedDir::new(out)?;
    // 0. A project that starts from signals reduces them into the test rows first.
    let (tests, columns, tests_name, recordings, mut files) = match &project.signals {
        Some(sig) => {
            let rows =
                super::run_steps::signals_step(&staged, &tests_path, &project.tests, &resolve(base, sig), sig, quiet)?;
            (rows.tests, rows.columns, super::run_steps::MEASURED_TESTS.to_string(), Some(rows.summaries), rows.files)
        }
        None => {
            let (tests, columns) = parse_tests_with_columns(&tests_path, &read_text(&tests_path)?)?;
            let name = tests_path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
            (tests, columns, name, None, Vec::new())
        }
    };
    let reference_jc =
        project.reference_jc.as_ref().map(|p| cutcal_io::jc_file::load_jc(&resolve(base, p))).transpose()?;
    let tables: Option<toml::Table> = project
        .paper_tables
        .as_ref()
        .map(|p| -> Result<toml::Table> {
            let path = resolve(base, p);
            Ok(parse_toml(&path, &read_text(&path)?)?)
        })
        .transpose()?;
    let mut write = |name: &str, contents: &str| -> Result<()> {
        staged.write(name, contents.as_bytes())?;
        files.push(name.to_string());
        Ok(())
    };
    let label = mf.material.name.clone();
    let progress = |msg: &str| {
        if !quiet {
            #[allow(clippy::print_stderr)] // progress goes to stderr, results to files/stdout
            {
                eprintln!("[{label}] {msg}");
            }
        }
    };

    // 1. Identification (paper Eq 15) on the paper's chosen test, when it is measured.
    let mut outcomes: BTreeMap<String, DpzdOutcome> = BTreeMap::new();
    let mut skipped = None;
    if let Some(idc) = &project.identify {
        let test = pick_test(&tests, idc.test.as_deref(), &mf, &tests_path)?;
        let m = &test.measured;
        if m.cutting_force_n_per_m.is_some() && m.feed_force_n_per_m.is_some() && m.chip_thickness_m.is_some() {
            let dp = mf.dpzd.as_ref().with_context(|| format!("{}: no [dpzd] section", mf.path.display()))?;
            for model in &idc.models {
                progress(&format!("identifying JC from test {} ({model:?} DPZD, {} starts)", test.id, idc.starts));
                let settings = DpzdSettings {
                    // The project file states h and N, so it runs the paper's discrete objective.
                    preset: super::identify::Preset::Paper,
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
                let o = identify_dpzd(&mf, test, &settings)?;
                let key = format!("{model:?}").to_lowercase();
                write(
                    &format!("jc_{key}.toml"),
                    &super::identify::jc_toml(
                        &o.identification.jc,
                        format!(
                            "cutcal {} run {}: test {} ({key} DPZD)",
                            env!("CARGO_PKG_VERSION"),
                            project.name,
                            test.id
                        ),
                    )?,
                )?;
                write(&format!("zone_{key}.csv"), &super::identify::fields_csv(&o.zone, 201)?)?;
                write(
                    &format!("fit_{key}.svg"),
                    &plots::fit_over_x(&o.zone, &o.identification.jc, &format!("{label} test {} ({key})", test.id))?,
                )?;
                outcomes.insert(key, o);
            }
            if let (Some(o), Some(e)) = (outcomes.get("original"), outcomes.get("enhanced")) {
                for (name, svg) in plots::zone_fields(&o.zone, &e.zone, &format!("{label} test {}", test.id))? {
                    write(&name, &svg)?;
                }
            }
        } else {
            skipped = Some(dpzd_skip_reason(&tests_name, &columns, Some(test), reference_jc.is_some()));
        }
    } else {
        skipped = Some(dpzd_skip_reason(&tests_name, &columns, None, reference_jc.is_some()));
    }

    // 2. Comparison with the paper's tables.
    let mut comparisons = Vec::new();
    if let Some(t) = &tables {
        let test_is_c38_3 = label == "C38";
        for (key, o) in &outcomes {
            if test_is_c38_3 {
                comparisons.extend(compare(&format!("Table 4 {key}"), t, &format!("table4.{key}"), &o.report.jc));
            }
        }
        if let (Some(k), Some(e)) = (&project.paper_table5_key, outcomes.get("enhanced")) {
            comparisons.extend(compare("Table 5", t, &format!("table5.{k}"), &e.report.jc));
        }
    }

    // 3. The JC set used downstream.
    let jc_used: Option<(String, JcParams)> = outcomes
        .get("enhanced")
        .map(|o| ("identified (enhanced DPZD)".to_string(), o.identification.jc))
        .or_else(|| reference_jc.map(|j| ("reference set".to_string(), j)));
    if let Some((src, jc)) = &jc_used {
        write(
            "flow_curves.svg",
            &plots::flow_curves(jc, &format!("{label} ({src})"), &[20.0, 400.0, 800.0], &[1e3, 1e5]),
        )?;
    }

    // 4. FE cards of every dialect for the JC set used (when the material has an interface).
    if let (Some((src, jc)), Some(_)) = (&jc_used, &mf.interface) {
        progress("rendering FE cards");
        let provenance = cutcal_export::Provenance {
            cutcal_version: env!("CARGO_PKG_VERSION").to_string(),
            source_test: format!("{} ({src})", project.name),
            model_variant: if outcomes.contains_key("enhanced") {
                "enhanced DPZD".into()
            } else {
                "reference JC set".into()
            },
        };
        for f in super::export::render_cards(&mf, jc, &provenance)? {
            write(&format!("cards/{}", f.name), &f.contents)?;
        }
    }

    // 5. Forward predictions of every test, the paper's Table 6 beside them, and the joint fit.
    let oxley_options = super::predict::oxley_options(mf.oxley.as_ref(), false, None, None, None, None, None)
        .with_context(|| format!("Oxley options for {}", mf.path.display()))?;
    let mut predictions = Vec::new();
    let mut table6 = Vec::new();
    if let (true, Some((_, jc))) = (project.predict, &jc_used) {
        progress(&format!("predicting {} tests (extended Oxley)", tests.len()));
        predictions = super::predict::predict_rows(&mf.material, jc, &tests, &oxley_options, mf.material.room_c, false);
        if let Some(t) = &tables {
            if label == "C38" {
                let row = |key: &str, src: &str| FeComparison {
                    source: src.into(),
                    fc_n_per_mm: table_value(t, key, "fc_n_per_mm"),
                    ft_n_per_mm: table_value(t, key, "ft_n_per_mm"),
                    chip_mm: table_value(t, key, "chip_mm"),
                };
                table6.push(row("table6.experiment", "experiment (paper Table 6)"));
                table6.push(row("table6.fe_original", "DEFORM FE, original-DPZD JC (paper Table 6)"));
                table6.push(row("table6.fe_enhanced", "DEFORM FE, enhanced-DPZD JC (paper Table 6)"));
                let mut add = |src: String, jc: &JcParams| {
                    let r = super::predict::predict_rows(
                        &mf.material,
                        jc,
                        &tests[..],
                        &oxley_options,
                        mf.material.room_c,
                        false,
                    );
                    if let Some(p) = r.iter().find(|r| r.test == "3").and_then(|r| r.prediction) {
                        table6.push(FeComparison {
                            source: src,
                            fc_n_per_mm: Some(p.cutting_force_n_per_m / 1e3),
                            ft_n_per_mm: Some(p.feed_force_n_per_m / 1e3),
                            chip_mm: Some(p.chip_thickness_m * 1e3),
                        });
                    }
                };
                if let Some(j) = &reference_jc {
                    add("cutcal extended Oxley, Table 5 JC".into(), j);
                }
                for (k, o) in &outcomes {
                    add(format!("cutcal extended Oxley, cutcal {k}-DPZD JC"), &o.identification.jc);
                }
            }
        }
        let measured: Vec<_> = predictions
            .iter()
            .filter_map(|r| {
                let p = r.prediction?;
                Some((r, p))
            })
            .collect();
        let pts = |f: &dyn Fn(&super::predict::PredictRow) -> Option<(f64, f64)>| -> Vec<(f64, f64)> {
            measured.iter().filter_map(|(r, _)| f(r)).collect()
        };
        let fc = pts(&|r| Some((r.fc_measured_n?, r.fc_n?)));
        let ft = pts(&|r| Some((r.ft_measured_n?, r.ft_n?)));
        if !fc.is_empty() || !ft.is_empty() {
            write(
                "predicted_vs_measured_forces.svg",
                &crate::report::svg::Plot {
                    title: format!("{label}: extended Oxley vs measured forces"),
                    x_label: "measured force [N]".into(),
                    y_label: "predicted force [N]".into(),
                    series: vec![
                        crate::report::svg::Series::markers("Fc", fc),
                        crate::report::svg::Series::markers("Ft", ft),
                    ],
                    diagonal: true,
                }
                .render(),
            )?;
        }
        let per_test = |f: &dyn Fn(&super::predict::PredictRow) -> Option<f64>| -> Vec<(f64, f64)> {
            predictions.iter().enumerate().filter_map(|(i, r)| f(r).map(|v| (i as f64 + 1.0, v))).collect()
        };
        write(
            "predictions_per_test.svg",
            &crate::report::svg::Plot {
                title: format!("{label}: predicted forces and chip thickness per test"),
                x_label: "test (row of the tests file)".into(),
                y_label: "Fc, Ft [N] ; tc [um]".into(),
                series: vec![
                    crate::report::svg::Series::line("Fc predicted", per_test(&|r| r.fc_n)),
                    crate::report::svg::Series::markers("Fc measured", per_test(&|r| r.fc_measured_n)),
                    crate::report::svg::Series::line("Ft predicted", per_test(&|r| r.ft_n)),
                    crate::report::svg::Series::markers("Ft measured", per_test(&|r| r.ft_measured_n)),
                    crate::report::svg::Series::dashed("tc predicted [um]", per_test(&|r| r.tc_mm.map(|v| v * 1e3))),
                    crate::report::svg::Series::markers(
                        "tc measured [um]",
                        per_test(&|r| r.tc_measured_mm.map(|v| v * 1e3)),
                    ),
                ],
                diagonal: false,
            }
            .render(),
        )?;
    }
    let mut joint = None;
    if let Some(jc_cfg) = &project.joint {
        let measured = tests.iter().filter(|t| t.measured.cutting_force_n_per_m.is_some()).count();
        if measured >= 2 {
            progress(&format!("joint Oxley identification over {measured} tests ({} starts)", jc_cfg.starts));
            let mut bounds = super::identify::jc_bounds(&mf)?;
            let fixes: Vec<(String, f64)> = jc_cfg.fix.iter().map(|(k, v)| (k.clone(), *v)).collect();
            super::identify_oxley::apply_fixes(&mut bounds, &fixes)
                .with_context(|| format!("[joint] fix of project {}", project.name))?;
            let options = cutcal_ident::joint::JointOptions {
                oxley: oxley_options.clone(),
                physics: cutcal_model::oxley::Physics::baseline(),
                work_temperature_c: mf.material.room_c,
                use_chip_thickness: true,
                tool_condition: true,
            };
            let constants =
                cutcal_ident::JcConstants { eps0_per_s: 1.0, tm_c: mf.material.melting_c, tr_c: mf.material.room_c };
            let class = super::identify_oxley::material_class(jc_cfg.class.as_deref(), &mf.material)
                .with_context(|| format!("[joint] class of {}", project.name))?;
            let id = cutcal_ident::joint::identify_oxley(
                &mf.material,
                &tests,
                &bounds,
                class,
                constants,
                &options,
                &cutcal_ident::MultistartOptions::new(jc_cfg.starts, jc_cfg.seed),
            )
            .with_context(|| format!("joint Oxley identification from {}", tests_path.display()))?;
            // Only a determined set is written as an identified JC file.
            if id.verdict.is_determined() {
                let mut source = format!("cutcal {} run {}: joint Oxley fit", env!("CARGO_PKG_VERSION"), project.name);
                if !id.outside_literature.is_empty() {
                    source.push_str(&format!("; outside the literature box: {}", id.outside_literature.join(", ")));
                }
                write("jc_joint_oxley.toml", &super::identify::jc_toml(&id.jc, source)?)?;
            }
            joint = Some(id);
        }
    }

    // 6. The discrepancy diagnosis of the measured tests with the JC set used.
    let (mut diagnosis, mut diagnosis_skipped) = (None, None);
    if project.diagnose {
        match &jc_used {
            Some((src, jc)) => {
                progress("diagnosing the model-measurement mismatch");
                let rows = match recordings {
                    Some(_) => staged.path(super::run_steps::MEASURED_TESTS),
                    None => tests_path.clone(),
                };
                let (d, names) =
                    super::run_steps::diagnosis_step(&staged, &project.name, mf.path.clone(), rows, (src, jc))?;
                files.extend(names);
                diagnosis = Some(d);
            }
            None => {
                diagnosis_skipped = Some("no JC set is available (nothing identified and no reference_jc)".to_string())
            }
        }
    }

    let mut report = ProjectReport {
        project: project.name.clone(),
        material: label.clone(),
        cutcal_version: env!("CARGO_PKG_VERSION").into(),
        identification: outcomes.iter().map(|(k, o)| (k.clone(), o.report.clone())).collect(),
        identification_skipped: skipped,
        comparisons,
        jc_used: jc_used.as_ref().map(|(s, j)| (s.clone(), JcReport::from_params(j, None))),
        predictions,
        table6,
        joint,
        recordings,
        diagnosis,
        diagnosis_skipped,
        files: Vec::new(),
    };
    files.push("report.md".into());
    files.push("report.json".into());
    files.sort();
    report.files = files;
    staged.write("report.md", render_markdown(&report).as_bytes())?;
    staged.write("report.json", (serde_json::to_string_pretty(&report)? + "\n").as_bytes())?;
    staged.commit()?;
    progress(&format!("wrote {} files to {}", report.files.len(), out.display()));
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

/// A condition number for the report, or why there is none.
fn condition_text(c: Option<f64>) -> String {
    match c.filter(|v| v.is_finite()) {
        Some(v) => format!("{v:.3e}"),
        None => "not available (J^T J is singular on the free parameters)".to_string(),
    }
}

/// A relative difference for the report, or why there is none.
fn diff_text(d: Option<f64>) -> String {
    d.map_or_else(|| "not available (published value is zero)".to_string(), |v| format!("{v:+.1} %"))
}

/// The human-readable report.
#[must_use]
pub fn render_markdown(r: &ProjectReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# cutcal report: {} ({})\n", r.project, r.material);
    let _ = writeln!(s, "cutcal {}. Units: MPa, degC, 1/s unless stated.\n", r.cutcal_version);
    let _ = writeln!(s, "## Identification (DPZD, paper Eq 15)\n");
    if let Some(why) = &r.identification_skipped {
        let _ = writeln!(s, "Not run: {why}.\n");
    }
    if !r.identification.is_empty() {
        let _ = writeln!(s, "| model | test | phi [deg] | tau_max | T_AB | T_EF | A | B | n | C | m | RMS | at bounds | starts at best |");
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
        for (k, i) in &r.identification {
            let _ = writeln!(
                s,
                "| {k} | {} | {:.2} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.3} | {:.4} | {:.3} | {:.1} | {} | {}/{} |",
                i.test, i.shear_angle_deg, i.tau_max_mpa, i.t_ab_c, i.t_ef_c, i.jc.a_mpa, i.jc.b_mpa, i.jc.n, i.jc.c, i.jc.m,
                i.rms_mpa, i.at_bounds.join(", "), i.starts_at_best, i.starts
            );
        }
        let _ = writeln!(s);
        for (k, i) in &r.identification {
            if let (Some(se), Some(corr)) = (&i.std_errors, &i.correlation) {
                let _ = writeln!(
                    s,
                    "{k}: standard errors of the free parameters {:?} = {:?}; condition number {}.",
                    i.free,
                    se.iter().map(|v| (v * 1e4).round() / 1e4).collect::<Vec<_>>(),
                    condition_text(i.condition_number)
                );
                let strong: Vec<String> = (0..i.free.len())
                    .flat_map(|a| (a + 1..i.free.len()).map(move |b| (a, b)))
                    .filter(|(a, b)| corr[*a][*b].abs() > 0.8)
                    .map(|(a, b)| format!("{}-{} ({:.2})", i.free[a], i.free[b], corr[a][b]))
                    .collect();
                if !strong.is_empty() {
                    let _ = writeln!(s, "Poorly separated (|correlation| > 0.8): {}.", strong.join(", "));
                }
                let _ = writeln!(s);
            }
        }
    }
    if !r.comparisons.is_empty() {
        let _ = writeln!(s, "## Against the paper\n");
        let _ = writeln!(s, "| against | parameter | cutcal | paper | difference |");
        let _ = writeln!(s, "|---|---|---|---|---|");
        for c in &r.comparisons {
            let _ = writeln!(
                s,
                "| {} | {} | {:.4} | {} | {} |",
                c.against,
                c.parameter,
                c.ours,
                c.published,
                diff_text(c.diff_pct)
            );
        }
        let _ = writeln!(s);
    }
    if let Some((src, jc)) = &r.jc_used {
        let _ = writeln!(s, "## JC set used for cards and predictions\n");
        let _ = writeln!(
            s,
            "{src}: A {:.2} MPa, B {:.2} MPa, n {:.4}, C {:.5}, m {:.4}, eps0 {} 1/s, Tm {} degC, Tr {} degC.\n",
            jc.a_mpa, jc.b_mpa, jc.n, jc.c, jc.m, jc.eps0_per_s, jc.tm_c, jc.tr_c
        );
    }
    if !r.predictions.is_empty() {
        let _ = writeln!(s, "## Forward predictions (extended Oxley, Lalwani 2009) with the JC set used\n");
        let _ = writeln!(s, "| test | Fc [N] | measured | err | Ft [N] | measured | err | tc [mm] | measured | err | T_AB | T_int | T_int meas. | note |");
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
        let c = |v: Option<f64>, d: usize| v.map_or_else(|| "-".to_string(), |x| format!("{x:.d$}"));
        let pc = |v: Option<f64>| v.map_or_else(|| "-".to_string(), |x| format!("{x:+.1} %"));
        for p in &r.predictions {
            let (tab, tint, note) = match (&p.prediction, &p.error) {
                (Some(q), _) => (
                    format!("{:.0}", q.temperature_ab_c),
                    format!("{:.0}", q.temperature_int_c),
                    [
                        p.tool_note(),
                        if q.flags.delta_poorly_determined {
                            "delta poorly determined".to_string()
                        } else {
                            String::new()
                        },
                    ]
                    .into_iter()
                    .filter(|x| !x.is_empty())
                    .collect::<Vec<_>>()
                    .join("; "),
                ),
                (None, Some(e)) => ("-".into(), "-".into(), format!("failed: {e}")),
                (None, None) => ("-".into(), "-".into(), String::new()),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {tab} | {tint} | {} | {note} |",
                p.test,
                c(p.fc_n, 1),
                c(p.fc_measured_n, 1),
                pc(p.fc_error_pct),
                c(p.ft_n, 1),
                c(p.ft_measured_n, 1),
                pc(p.ft_error_pct),
                c(p.tc_mm, 3),
                c(p.tc_measured_mm, 3),
                pc(p.tc_error_pct),
                c(p.t_int_measured_c, 0)
            );
        }
        let _ = writeln!(s);
    }
    if !r.table6.is_empty() {
        let _ = writeln!(s, "## C38 test 3: the paper's FE check (Table 6) beside cutcal's forward model\n");
        let _ = writeln!(s, "| source | Fc [N/mm] | Ft [N/mm] | tc [mm] |");
        let _ = writeln!(s, "|---|---|---|---|");
        let c = |v: Option<f64>, d: usize| v.map_or_else(|| "-".to_string(), |x| format!("{x:.d$}"));
        for t in &r.table6 {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} |",
                t.source,
                c(t.fc_n_per_mm, 1),
                c(t.ft_n_per_mm, 1),
                c(t.chip_mm, 3)
            );
        }
        let _ = writeln!(s);
    }
    if let Some(j) = &r.joint {
        let _ = writeln!(s, "## Joint identification (extended Oxley over every measured test)\n");
        let _ = writeln!(
            s,
            "A {:.1} MPa, B {:.1} MPa, n {:.3}, C {:.4}, m {:.3}; RMS relative error {:.1} % over {} residuals; at bounds: {}; {}/{} starts at the best minimum.",
            j.jc.a_pa / 1e6, j.jc.b_pa / 1e6, j.jc.n, j.jc.c, j.jc.m,
            100.0 * (j.relative_errors.iter().map(|e| e * e).sum::<f64>() / j.relative_errors.len().max(1) as f64).sqrt(),
            j.relative_errors.len(), if j.statistics.at_bounds.is_empty() { "none".to_string() } else { j.statistics.at_bounds.join(", ") },
            j.starts_at_best, j.starts
        );
        let _ = writeln!(s, "\nVerdict: {}.", super::identify_oxley::verdict_line(&j.verdict));
        if !j.verdict.is_determined() {
            let _ = writeln!(s, "\nNo `jc_joint_oxley.toml` is written: the set above is a best fit, not an identification. Fix the weakest parameters (for example n, C and m at a published set of the class) or add tests at other speeds and feeds.");
        }
        let _ = writeln!(s);
    }
    if let Some(rec) = &r.recordings {
        let _ = writeln!(s, "## Recordings (raw force signals reduced to the test rows)\n");
        let _ = writeln!(s, "| test | signal | window [s] | Fc [N] | sd | se | Ft [N] | sd | se | wear | BUE |");
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|");
        for t in rec {
            match &t.analysis {
                Some(a) => {
                    let (fc, ft) = (a.channels[0], a.channels[1]);
                    let _ = writeln!(
                        s,
                        "| {} | `{}` | {:.3}-{:.3} | {:.1} | {:.2} | {:.3} | {:.1} | {:.2} | {:.3} | {} | {} |",
                        t.test,
                        t.signal,
                        a.t0_s,
                        a.t1_s,
                        fc.mean,
                        fc.sd,
                        fc.se,
                        ft.mean,
                        ft.sd,
                        ft.se,
                        if a.possible_tool_wear { "flagged" } else { "no" },
                        if a.possible_built_up_edge { "flagged" } else { "no" }
                    );
                }
                None => {
                    let _ = writeln!(
                        s,
                        "| {} | `{}` | not available: {} | | | | | | | | |",
                        t.test,
                        t.signal,
                        t.not_available.as_deref().unwrap_or("no analysis")
                    );
                }
            }
        }
        let _ = writeln!(s);
    }
    if let Some(d) = &r.diagnosis {
        let _ = writeln!(s, "## Diagnosis (cutcal diagnose, Mode B, {} held fixed)\n", d.jc_source);
        let _ = writeln!(s, "```text\n{}```\n", d.text);
    }
    if let Some(why) = &r.diagnosis_skipped {
        let _ = writeln!(s, "## Diagnosis\n\nNot run: {why}.\n");
    }
    let _ = writeln!(s, "## Files\n");
    for f in &r.files {
        let _ = writeln!(s, "- `{f}`");
    }
    s
}

/// Runs `cutcal run`.
pub fn run(args: &RunArgs) -> Result<()> {
    let project = load_project(&args.project)?;
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("target/pipeline").join(&project.name));
    let report = run_project(&args.project, &out, args.quiet)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    }
    Ok(())
}
