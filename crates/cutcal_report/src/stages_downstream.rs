//! The downstream stages of `cutcal run` (see [`crate::stages`]): [`predict`] (extended Oxley
//! predictions of every test with the set used, the project's `[fe_check]` beside them, and their
//! plots), [`joint`] (the joint Oxley identification of a project's `[joint]`) and [`diagnose`]
//! (the discrepancy diagnosis of a project with `diagnose = true`).

use cutcal_ident::joint::OxleyIdentification;
use cutcal_model::oxley::OxleyOptions;
use cutcal_model::JcParams;

use crate::error::Result;
use crate::joint::{joint_fit, JointRequest};
use crate::predict::{predict_rows, PredictRow};
use crate::project::table_value;
use crate::project_report::FeComparison;
use crate::run_steps::{self, ProjectDiagnosis};
use crate::stages::Identified;
use crate::stages::{Inputs, Output};
use crate::svg::{Plot, Series};
use crate::Progress;

/// The predict stage's output.
#[derive(Debug, Clone, Default)]
pub struct Predicted {
    /// One row per test.
    pub predictions: Vec<PredictRow>,
    /// The `[fe_check]` rows: published, then cutcal's with the reference and identified sets.
    pub table6: Vec<FeComparison>,
}

/// Stage, predict: every test with the set used (when the project predicts and a set is
/// available), the `[fe_check]` rows, and the plots `predicted_vs_measured_forces.svg` (when any
/// force is measured) and `predictions_per_test.svg`.
pub fn predict(
    inp: &Inputs,
    id: &Identified,
    jc_used: Option<&(String, JcParams)>,
    oxley: &OxleyOptions,
    out: &mut Output<'_>,
    progress: &dyn Progress,
) -> Result<Predicted> {
    let (Some((_, jc)), true) = (jc_used, inp.project.predict) else { return Ok(Predicted::default()) };
    let (mf, label) = (&inp.mf, inp.label());
    progress.stage(label, &format!("predicting {} tests (extended Oxley)", inp.tests.len()));
    let predictions = predict_rows(&mf.material, jc, &inp.tests, oxley, mf.material.room_c, false);
    let table6 = fe_check(inp, id, oxley);
    let measured: Vec<&PredictRow> = predictions.iter().filter(|r| r.prediction.is_some()).collect();
    let pts = |f: &dyn Fn(&PredictRow) -> Option<(f64, f64)>| -> Vec<(f64, f64)> {
        measured.iter().filter_map(|r| f(r)).collect()
    };
    let fc = pts(&|r| Some((r.fc_measured_n?, r.fc_n?)));
    let ft = pts(&|r| Some((r.ft_measured_n?, r.ft_n?)));
    if !fc.is_empty() || !ft.is_empty() {
        let plot = Plot {
            title: format!("{label}: extended Oxley vs measured forces"),
            x_label: "measured force [N]".into(),
            y_label: "predicted force [N]".into(),
            series: vec![Series::markers("Fc", fc), Series::markers("Ft", ft)],
            diagonal: true,
        };
        out.write("predicted_vs_measured_forces.svg", &plot.render())?;
    }
    let per_test = |f: &dyn Fn(&PredictRow) -> Option<f64>| -> Vec<(f64, f64)> {
        predictions.iter().enumerate().filter_map(|(i, r)| f(r).map(|v| (i as f64 + 1.0, v))).collect()
    };
    let plot = Plot {
        title: format!("{label}: predicted forces and chip thickness per test"),
        x_label: "test (row of the tests file)".into(),
        y_label: "Fc, Ft [N] ; tc [um]".into(),
        series: vec![
            Series::line("Fc predicted", per_test(&|r| r.fc_n)),
            Series::markers("Fc measured", per_test(&|r| r.fc_measured_n)),
            Series::line("Ft predicted", per_test(&|r| r.ft_n)),
            Series::markers("Ft measured", per_test(&|r| r.ft_measured_n)),
            Series::dashed("tc predicted [um]", per_test(&|r| r.tc_mm.map(|v| v * 1e3))),
            Series::markers("tc measured [um]", per_test(&|r| r.tc_measured_mm.map(|v| v * 1e3))),
        ],
        diagonal: false,
    };
    out.write("predictions_per_test.svg", &plot.render())?;
    Ok(Predicted { predictions, table6 })
}

/// The `[fe_check]` rows: the published ones, then cutcal's prediction of the check's test with
/// the reference set and with every identified set (a set whose solve fails has no row).
fn fe_check(inp: &Inputs, id: &Identified, oxley: &OxleyOptions) -> Vec<FeComparison> {
    let (Some(fe), Some(tables)) = (&inp.project.fe_check, &inp.tables) else { return Vec::new() };
    let mut rows: Vec<FeComparison> = fe
        .published
        .iter()
        .map(|r| FeComparison {
            source: r.source.clone(),
            fc_n_per_mm: table_value(tables, &r.table, "fc_n_per_mm"),
            ft_n_per_mm: table_value(tables, &r.table, "ft_n_per_mm"),
            chip_mm: table_value(tables, &r.table, "chip_mm"),
        })
        .collect();
    let Some(test) = inp.tests.iter().find(|t| t.id == fe.test) else { return rows };
    let room_c = inp.mf.material.room_c;
    let mut add = |source: String, jc: &JcParams| {
        let r = predict_rows(&inp.mf.material, jc, std::slice::from_ref(test), oxley, room_c, false);
        if let Some(p) = r.first().and_then(|r| r.prediction) {
            rows.push(FeComparison {
                source,
                fc_n_per_mm: Some(p.cutting_force_n_per_m / 1e3),
                ft_n_per_mm: Some(p.feed_force_n_per_m / 1e3),
                chip_mm: Some(p.chip_thickness_m * 1e3),
            });
        }
    };
    if let Some(j) = &inp.reference_jc {
        add(format!("cutcal extended Oxley, {}", fe.reference_label), j);
    }
    for (k, o) in &id.outcomes {
        add(format!("cutcal extended Oxley, cutcal {k}-DPZD JC"), &o.identification.jc);
    }
    rows
}

/// Stage, joint: the joint Oxley identification of a project's `[joint]` over every test with a
/// measured Fc (at least two); writes `jc_joint_oxley.toml` only for a determined set.
pub fn joint(
    inp: &Inputs,
    oxley: &OxleyOptions,
    out: &mut Output<'_>,
    progress: &dyn Progress,
) -> Result<Option<OxleyIdentification>> {
    let Some(cfg) = &inp.project.joint else { return Ok(None) };
    let measured = inp.tests.iter().filter(|t| t.measured.cutting_force_n_per_m.is_some()).count();
    if measured < 2 {
        return Ok(None);
    }
    let name = &inp.project.name;
    progress.stage(inp.label(), &format!("joint Oxley identification over {measured} tests ({} starts)", cfg.starts));
    let req = JointRequest {
        starts: cfg.starts,
        seed: cfg.seed,
        class: cfg.class.clone(),
        fix: cfg.fix.iter().map(|(k, v)| (k.clone(), *v)).collect(),
        ..JointRequest::default()
    };
    let id = joint_fit(&inp.mf, &inp.tests, &inp.tests_path, oxley.clone(), &req, Some(name))?;
    // Only a determined set is written as an identified JC file.
    if id.verdict.is_determined() {
        let mut source = format!("cutcal {} run {name}: joint Oxley fit", env!("CARGO_PKG_VERSION"));
        if !id.outside_literature.is_empty() {
            source.push_str(&format!("; outside the literature box: {}", id.outside_literature.join(", ")));
        }
        out.write("jc_joint_oxley.toml", &crate::dpzd_report::jc_toml(&id.jc, source)?)?;
    }
    Ok(Some(id))
}

/// The diagnose stage's output.
#[derive(Debug, Clone, Default)]
pub struct Diagnosed {
    /// The diagnosis, when run.
    pub diagnosis: Option<ProjectDiagnosis>,
    /// Why the diagnosis asked for did not run.
    pub skipped: Option<String>,
}

/// Stage, diagnose: `cutcal diagnose` Mode B on the project's rows with the set used held fixed,
/// when the project asks for it.
pub fn diagnose(
    inp: &Inputs,
    jc_used: Option<&(String, JcParams)>,
    out: &mut Output<'_>,
    progress: &dyn Progress,
) -> Result<Diagnosed> {
    if !inp.project.diagnose {
        return Ok(Diagnosed::default());
    }
    let Some((src, jc)) = jc_used else {
        let why = "no JC set is available (nothing identified and no reference_jc)".to_string();
        return Ok(Diagnosed { diagnosis: None, skipped: Some(why) });
    };
    progress.stage(inp.label(), "diagnosing the model-measurement mismatch");
    let rows = match inp.recordings {
        Some(_) => out.staged.path(run_steps::MEASURED_TESTS),
        None => inp.tests_path.clone(),
    };
    let (d, names) = run_steps::diagnosis_step(out.staged, &inp.project.name, inp.mf.path.clone(), rows, (src, jc))?;
    out.files.extend(names);
    Ok(Diagnosed { diagnosis: Some(d), skipped: None })
}
