//! Python functions: `read_tests`, `identify`, `joint`, `predict`, `predict_many` (native part), `render`,
//! `export`, `diagnose`. Long work runs with the GIL released (`py.allow_threads`).

use std::path::PathBuf;
use std::time::Instant;

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use super::classes::{PyCuttingTest, PyIdentifyResult, PyJcParams, PyMaterial};
use super::{json_to_py, to_py};
use crate::diagnose::{diagnose_json, DiagnoseRequest};
use crate::export::{export_cards, render_cards, ExportRequest};
use crate::identify::{identify as identify_face, IdentifyRequest};
use crate::joint::joint as joint_face;
use crate::predict::{predict_many as many_face, predict_tests, resolve, Condition, PredictRequest, MANY_COLUMNS};
use crate::types;
use crate::types::NamedJc;
use cutcal_report::joint::JointRequest;

/// read_tests(path) -> list[CuttingTest]: the test CSV read by the CLI's reader.
#[pyfunction]
fn read_tests(path: PathBuf) -> PyResult<Vec<PyCuttingTest>> {
    let tests = types::tests_from_file(&path).map_err(to_py)?;
    Ok(tests.into_iter().map(|inner| PyCuttingTest { inner }).collect())
}

/// identify(material, test, model="enhanced", ...) -> IdentifyResult: JC from one test through
/// the DPZD zone model (paper Sec 3; enhanced fixed point Sec 3.5) by the Eq 15 fit.
#[pyfunction]
#[pyo3(signature = (material, test, model = "enhanced", starts = 32, seed = 1, preset = "converged", h_mm = None, points = None, r = None,
    rho_cp_original = None, tolerance_c = 1e-6, max_iterations = 50, bootstrap = 0, force_uncertainty = None,
    chip_uncertainty = None, bootstrap_starts = 2, field_points = 201, noise_only = false, every_start = false))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one keyword each
fn identify(
    py: Python<'_>,
    material: &PyMaterial,
    test: &PyCuttingTest,
    model: &str,
    starts: usize,
    seed: u64,
    preset: &str,
    h_mm: Option<f64>,
    points: Option<usize>,
    r: Option<f64>,
    rho_cp_original: Option<f64>,
    tolerance_c: f64,
    max_iterations: usize,
    bootstrap: usize,
    force_uncertainty: Option<f64>,
    chip_uncertainty: Option<f64>,
    bootstrap_starts: usize,
    field_points: usize,
    noise_only: bool,
    every_start: bool,
) -> PyResult<PyIdentifyResult> {
    let req = IdentifyRequest {
        model: model.to_string(),
        preset: preset.to_string(),
        h_mm,
        points,
        r,
        starts,
        seed,
        every_start,
        rho_cp_original,
        tolerance_c,
        max_iterations,
        bootstrap,
        force_uncertainty,
        chip_uncertainty,
        bootstrap_starts,
        noise_only,
        field_points,
    };
    let mf = material.inner.clone();
    let t = test.inner.clone();
    let out = py.allow_threads(move || identify_face(&mf, &t, &req)).map_err(to_py)?;
    Ok(PyIdentifyResult { inner: out })
}

/// predict(material, jc, tests, ...) -> dict: the document of `cutcal predict --json` (extended
/// Oxley model, Oxley 1989 / Lalwani et al. 2009) for a list of tests.
#[pyfunction]
#[pyo3(signature = (material, jc, tests, work_temperature_c = None, lalwani_ranges = false, eta = None, psi = None,
    sharp = false))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one keyword each
fn predict<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    jc: &PyJcParams,
    tests: Vec<PyCuttingTest>,
    work_temperature_c: Option<f64>,
    lalwani_ranges: bool,
    eta: Option<f64>,
    psi: Option<f64>,
    sharp: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let req = PredictRequest { work_temperature_c, lalwani_ranges, eta, psi, sharp };
    let mf = material.inner.clone();
    let j = jc.inner.jc;
    let tests: Vec<_> = tests.into_iter().map(|t| t.inner).collect();
    let json = py
        .allow_threads(move || {
            predict_tests(&mf, &j, &tests, &req)
                .and_then(|r| serde_json::to_string_pretty(&r).map_err(crate::errors::face))
        })
        .map_err(to_py)?;
    json_to_py(py, &json)
}

/// Native part of `cutcal.predict_many`: equal-length 1-D float64 arrays in; a dict of arrays, the
/// converged mask, the per-condition error (None where converged) and the seconds spent in Rust.
#[pyfunction]
#[pyo3(signature = (material, jc, speed_m_min, uncut_mm, width_mm, rake_deg, edge_radius_um = None,
    flank_wear_mm = None, work_temperature_c = None, lalwani_ranges = false))]
#[allow(clippy::too_many_arguments)] // one array per condition column
#[allow(clippy::type_complexity)] // the tuple is the documented return of the native helper
fn _predict_many<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    jc: &PyJcParams,
    speed_m_min: PyReadonlyArray1<'py, f64>,
    uncut_mm: PyReadonlyArray1<'py, f64>,
    width_mm: PyReadonlyArray1<'py, f64>,
    rake_deg: PyReadonlyArray1<'py, f64>,
    edge_radius_um: Option<PyReadonlyArray1<'py, f64>>,
    flank_wear_mm: Option<PyReadonlyArray1<'py, f64>>,
    work_temperature_c: Option<f64>,
    lalwani_ranges: bool,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyArray1<bool>>, Bound<'py, PyList>, f64)> {
    let cols = [speed_m_min.as_array(), uncut_mm.as_array(), width_mm.as_array(), rake_deg.as_array()];
    let n = cols[0].len();
    if cols.iter().any(|c| c.len() != n) {
        return Err(PyValueError::new_err("speed_m_min, uncut_mm, width_mm and rake_deg must have one length"));
    }
    let tool = [edge_radius_um.as_ref().map(|a| a.as_array()), flank_wear_mm.as_ref().map(|a| a.as_array())];
    if tool.iter().flatten().any(|c| c.len() != n) {
        return Err(PyValueError::new_err("edge_radius_um and flank_wear_mm must have the conditions' length"));
    }
    // NaN in a tool array means "not stated" for that condition (a sharp edge, no wear land).
    let stated = |k: usize, i: usize| tool[k].as_ref().map(|a| a[i]).filter(|v| !v.is_nan());
    let conds: Vec<Condition> = (0..n)
        .map(|i| Condition {
            speed_m_min: cols[0][i],
            uncut_mm: cols[1][i],
            width_mm: cols[2][i],
            rake_deg: cols[3][i],
            edge_radius_um: stated(0, i),
            flank_wear_mm: stated(1, i),
        })
        .collect();
    let req = PredictRequest { work_temperature_c, lalwani_ranges, ..Default::default() };
    let (options, work_c) = resolve(&material.inner, &req).map_err(to_py)?;
    let mf = material.inner.clone();
    let j = jc.inner.jc;
    let (results, seconds) = py.allow_threads(move || {
        let start = Instant::now();
        let r = many_face(&mf, &j, &conds, &options, work_c);
        (r, start.elapsed().as_secs_f64())
    });
    let out = PyDict::new(py);
    for (name, get) in MANY_COLUMNS {
        // A condition without a solution holds 0 here and is masked by `converged` (never NaN).
        let v: Vec<f64> = results.iter().map(|r| r.as_ref().map_or(0.0, get)).collect();
        out.set_item(name, PyArray1::from_vec(py, v))?;
    }
    let ok: Vec<bool> = results.iter().map(Result::is_ok).collect();
    let errors: Vec<Option<String>> = results.into_iter().map(|r| r.err()).collect();
    Ok((out, PyArray1::from_vec(py, ok), PyList::new(py, errors)?, seconds))
}

#[allow(clippy::too_many_arguments)] // the CLI's options, one keyword each
fn export_request(
    format: &str,
    units: &str,
    t_from_c: Option<f64>,
    t_to_c: Option<f64>,
    t_step_c: f64,
    strain_rate_per_s: f64,
    heat_fraction: f64,
    source_test: Option<String>,
    model_variant: &str,
    contact_temperature_c: Option<f64>,
    cutting_speed_m_per_min: Option<f64>,
) -> ExportRequest {
    ExportRequest {
        format: format.into(),
        units: units.into(),
        t_from_c,
        t_to_c,
        t_step_c,
        strain_rate_per_s,
        heat_fraction,
        source_test,
        model_variant: model_variant.into(),
        contact_temperature_c,
        cutting_speed_m_per_min,
    }
}

/// render(material, jc, format, ...) -> dict[str, str]: the card files (name -> text) of one
/// dialect (`abaqus` gives three files) or of `all`, exactly as `cutcal export` writes them.
#[pyfunction]
#[pyo3(signature = (material, jc, format, units = "tonne-mm-s", t_from_c = None, t_to_c = None, t_step_c = 100.0,
    strain_rate_per_s = 1e4, heat_fraction = 0.9, source_test = None, model_variant = "as identified in the JC file",
    contact_temperature_c = None, cutting_speed_m_per_min = None))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one keyword each
fn render<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    jc: &PyJcParams,
    format: &str,
    units: &str,
    t_from_c: Option<f64>,
    t_to_c: Option<f64>,
    t_step_c: f64,
    strain_rate_per_s: f64,
    heat_fraction: f64,
    source_test: Option<String>,
    model_variant: &str,
    contact_temperature_c: Option<f64>,
    cutting_speed_m_per_min: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let req = export_request(
        format,
        units,
        t_from_c,
        t_to_c,
        t_step_c,
        strain_rate_per_s,
        heat_fraction,
        source_test,
        model_variant,
        contact_temperature_c,
        cutting_speed_m_per_min,
    );
    let files = render_cards(&material.inner, &jc.inner, &req).map_err(to_py)?;
    let d = PyDict::new(py);
    for f in files {
        d.set_item(f.name, f.contents)?;
    }
    Ok(d)
}

/// export(material, jc, format="all", out=".", ...) -> list[str]: renders and writes the cards
/// atomically into `out`; returns the paths written.
#[pyfunction]
#[pyo3(signature = (material, jc, format = "all", out = PathBuf::from("."), units = "tonne-mm-s", t_from_c = None,
    t_to_c = None, t_step_c = 100.0, strain_rate_per_s = 1e4, heat_fraction = 0.9, source_test = None,
    model_variant = "as identified in the JC file", contact_temperature_c = None, cutting_speed_m_per_min = None))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one keyword each
fn export(
    material: &PyMaterial,
    jc: &PyJcParams,
    format: &str,
    out: PathBuf,
    units: &str,
    t_from_c: Option<f64>,
    t_to_c: Option<f64>,
    t_step_c: f64,
    strain_rate_per_s: f64,
    heat_fraction: f64,
    source_test: Option<String>,
    model_variant: &str,
    contact_temperature_c: Option<f64>,
    cutting_speed_m_per_min: Option<f64>,
) -> PyResult<Vec<String>> {
    let req = export_request(
        format,
        units,
        t_from_c,
        t_to_c,
        t_step_c,
        strain_rate_per_s,
        heat_fraction,
        source_test,
        model_variant,
        contact_temperature_c,
        cutting_speed_m_per_min,
    );
    let written = export_cards(&material.inner, &jc.inner, &req, &out).map_err(to_py)?;
    Ok(written.iter().map(|p| p.display().to_string()).collect())
}

/// diagnose(recordings, simulation=None, material=None, jc=None, free_jc=False, model="oxley")
/// -> dict: the document of `cutcal diagnose --json` (paths in, as the CLI takes them).
#[pyfunction]
#[pyo3(signature = (recordings, simulation = None, material = None, jc = None, free_jc = false, model = None))]
fn diagnose<'py>(
    py: Python<'py>,
    recordings: PathBuf,
    simulation: Option<PathBuf>,
    material: Option<PathBuf>,
    jc: Option<PathBuf>,
    free_jc: bool,
    model: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let req = DiagnoseRequest { recordings, simulation, material, jc, free_jc, model };
    let json = py.allow_threads(move || diagnose_json(&req)).map_err(to_py)?;
    json_to_py(py, &json)
}

/// joint(material, tests, starts=4, seed=1, use_chip_thickness=True, sharp=False,
/// material_class=None, fix=None, work_temperature_c=None) -> dict: JC fitted jointly to every
/// test with measured Fc and Ft through the extended Oxley model (Oxley 1989; Lalwani et al. 2009),
/// as `cutcal identify --method oxley`. Keys: `verdict` (the CLI's line), `status`, `determined`,
/// `effective_rank`, `free_parameters`, `condition_number`, `jc` (a JcParams only when the data
/// determine the set, else None), `best_fit` (the fitted set whatever the verdict) and `report`
/// (the CLI's `--json` document).
#[pyfunction]
#[pyo3(signature = (material, tests, starts = 4, seed = 1, use_chip_thickness = true, sharp = false,
    material_class = None, fix = None, work_temperature_c = None))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one keyword each
fn joint<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    tests: Vec<PyCuttingTest>,
    starts: usize,
    seed: u64,
    use_chip_thickness: bool,
    sharp: bool,
    material_class: Option<String>,
    fix: Option<std::collections::BTreeMap<String, f64>>,
    work_temperature_c: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let req = JointRequest {
        starts,
        seed,
        work_temperature_c,
        use_chip_thickness,
        tool_condition: !sharp,
        class: material_class,
        fix: fix.unwrap_or_default().into_iter().collect(),
    };
    let mf = material.inner.clone();
    let tests: Vec<_> = tests.into_iter().map(|t| t.inner).collect();
    let out = py.allow_threads(move || joint_face(&mf, &tests, &req)).map_err(to_py)?;
    let jc = |j| PyJcParams { inner: NamedJc { jc: j, file_name: None } };
    let d = PyDict::new(py);
    d.set_item("verdict", out.verdict)?;
    d.set_item("status", out.status)?;
    d.set_item("determined", out.determined)?;
    d.set_item("effective_rank", out.effective_rank)?;
    d.set_item("free_parameters", out.free_parameters)?;
    d.set_item("condition_number", out.condition_number)?;
    d.set_item("jc", out.jc.map(jc))?;
    d.set_item("best_fit", jc(out.best_fit))?;
    d.set_item("report", json_to_py(py, &out.json)?)?;
    Ok(d)
}

/// Adds the functions to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(read_tests, m)?)?;
    m.add_function(wrap_pyfunction!(identify, m)?)?;
    m.add_function(wrap_pyfunction!(joint, m)?)?;
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    m.add_function(wrap_pyfunction!(_predict_many, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(export, m)?)?;
    m.add_function(wrap_pyfunction!(diagnose, m)?)?;
    Ok(())
}
