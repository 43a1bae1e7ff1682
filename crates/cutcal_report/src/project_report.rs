//! The project report of `cutcal run`: its JSON form (`report.json`, `cutcal run --json`) and its
//! markdown form (`report.md`).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use serde::Serialize;

use crate::dpzd::{DpzdIdentifyReport, JcReport};

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
    pub predictions: Vec<crate::predict::PredictRow>,
    /// Published forces of one test beside our predictions of it (the project's `[fe_check]`;
    /// the paper's Table 6 for C38 test 3).
    pub table6: Vec<FeComparison>,
    /// Heading of the `table6` section (the `[fe_check]` title; not part of the JSON).
    #[serde(skip)]
    pub table6_title: String,
    /// Joint Oxley identification, when run.
    pub joint: Option<cutcal_ident::joint::OxleyIdentification>,
    /// Per-test reduction of the raw signals, for a project that starts from signals.
    pub recordings: Option<Vec<crate::recordings::TestSummary>>,
    /// The discrepancy diagnosis, when the project asks for it.
    pub diagnosis: Option<crate::run_steps::ProjectDiagnosis>,
    /// Why the diagnosis asked for did not run.
    pub diagnosis_skipped: Option<String>,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
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
        let _ = writeln!(s, "| model | test | phi [deg] | tau_max | T_AB | T_EF | A | B | n | C | m | RMS | at bounds | local searches at best (sample points) |");
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
        for (k, i) in &r.identification {
            let _ = writeln!(
                s,
                "| {k} | {} | {:.2} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.3} | {:.4} | {:.3} | {:.1} | {} | {}/{} ({}) |",
                i.test, i.shear_angle_deg, i.tau_max_mpa, i.t_ab_c, i.t_ef_c, i.jc.a_mpa, i.jc.b_mpa, i.jc.n, i.jc.c, i.jc.m,
                i.rms_mpa, i.at_bounds.join(", "), i.starts_at_best, i.starts - i.filtered_starts, i.starts
            );
        }
        let _ = writeln!(s);
        for (k, i) in &r.identification {
            if let Some(corr) = &i.correlation {
                // No standard errors (issue 11): s^2 (J^T J)^-1 of deterministic model residuals
                // at arbitrary points has no statistical meaning; the spread is the Monte-Carlo's.
                let _ = writeln!(
                    s,
                    "{k}: free parameters {:?}; condition number {} (no standard errors: s^2 (J^T J)^-1 of \
                     deterministic model residuals has no statistical meaning; `cutcal identify --bootstrap N` \
                     gives a Monte-Carlo spread).",
                    i.free,
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
        let _ = writeln!(s, "## {}\n", r.table6_title);
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
        let _ = writeln!(s, "\nVerdict: {}.", crate::joint::verdict_line(&j.verdict));
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
