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
use crate::input::material_file::{load_material, MaterialFile};
use crate::input::tests_csv::load_tests;
use crate::input::{parse_toml, read_text};
use crate::output::StagedDir;
use crate::report::plots;

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
    /// (ours - published)/published, %.
    pub diff_pct: f64,
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
                diff_pct: (ours - published) / published * 100.0,
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
    let tests = load_tests(&tests_path)?;
    let reference_jc =
        project.reference_jc.as_ref().map(|p| crate::input::jc_file::load_jc(&resolve(base, p))).transpose()?;
    let tables: Option<toml::Table> = project
        .paper_tables
        .as_ref()
        .map(|p| -> Result<toml::Table> {
            let path = resolve(base, p);
            Ok(parse_toml(&path, &read_text(&path)?)?)
        })
        .transpose()?;
    let staged = StagedDir::new(out)?;
    let mut files = Vec::new();
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
                    model: *model,
                    h_m: idc.h_mm * 1e-3,
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
            skipped = Some(format!(
                "test {} of {} has no measured Fc, Ft and tc in the shipped fixtures (the paper shows them only in its figures); the reference JC set is used downstream",
                test.id,
                tests_path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default()
            ));
        }
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

    let mut report = ProjectReport {
        project: project.name.clone(),
        material: label.clone(),
        cutcal_version: env!("CARGO_PKG_VERSION").into(),
        identification: outcomes.iter().map(|(k, o)| (k.clone(), o.report.clone())).collect(),
        identification_skipped: skipped,
        comparisons,
        jc_used: jc_used.as_ref().map(|(s, j)| (s.clone(), JcReport::from(j))),
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
                    "{k}: standard errors of the free parameters {:?} = {:?}; condition number {:.3e}.",
                    i.free,
                    se.iter().map(|v| (v * 1e4).round() / 1e4).collect::<Vec<_>>(),
                    i.condition_number.unwrap_or(f64::NAN)
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
                "| {} | {} | {:.4} | {} | {:+.1} % |",
                c.against, c.parameter, c.ours, c.published, c.diff_pct
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
