//! Python classes: `Material`, `JcParams`, `CuttingTest` and `IdentifyResult`, each holding the
//! library's type and converting it to Python values with units in the attribute names.

use std::path::PathBuf;
use std::sync::Arc;

use cutcal_io::jc_file::JcFile;
use cutcal_io::material_file::MaterialFile;
use cutcal_model::CuttingTest;
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyInt, PyList, PyTuple};

use super::{json_to_py, to_py};
use crate::identify::IdentifyOutput;
use crate::types::{self, NamedJc, TestColumns};

/// A workpiece material (the paper's Table 3 polynomials, bounds, interface), read by the CLI's
/// material reader.
#[pyclass(name = "Material", module = "cutcal", frozen)]
pub struct PyMaterial {
    pub(crate) inner: Arc<MaterialFile>,
}

#[pymethods]
impl PyMaterial {
    /// Material(toml_text=None, source="<Material>", **keys): a material from TOML text in the
    /// format of fixtures/materials/*.toml, or from that format's keys as keywords
    /// (`Material(name="C38", melting_c=1460.0, thermal={...}, yield_strength={...}, ...)`: the
    /// values of the file's keys as Python dicts, lists, numbers and strings), read by the same
    /// reader as `Material.from_toml`; `source` names it in errors and is the base of the
    /// `[interface].tool` file.
    #[new]
    #[pyo3(signature = (toml_text = None, source = "<Material>", **keys))]
    fn new(toml_text: Option<&str>, source: &str, keys: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let keys = keys.filter(|k| !k.is_empty());
        let mf = match (toml_text, keys) {
            (Some(text), None) => types::material_from_text(text, source).map_err(to_py)?,
            (None, Some(k)) => types::material_from_table(&toml_table(k, "")?, source).map_err(to_py)?,
            (Some(_), Some(_)) => {
                return Err(PyValueError::new_err("Material(...) takes TOML text or the file's keys, not both"))
            }
            (None, None) => {
                return Err(PyValueError::new_err(
                    "Material(...) needs TOML text or the material file's keys (name=..., melting_c=..., ...)",
                ))
            }
        };
        Ok(Self { inner: Arc::new(mf) })
    }

    /// Material.from_toml(path): reads a material file.
    #[staticmethod]
    fn from_toml(path: PathBuf) -> PyResult<Self> {
        Ok(Self { inner: Arc::new(types::material_from_file(&path).map_err(to_py)?) })
    }

    /// Material name.
    #[getter]
    fn name(&self) -> String {
        self.inner.material.name.clone()
    }

    /// Melting temperature, degC.
    #[getter]
    fn melting_c(&self) -> f64 {
        self.inner.material.melting_c
    }

    /// Room (reference) temperature, degC.
    #[getter]
    fn room_c(&self) -> f64 {
        self.inner.material.room_c
    }

    /// The file (or source name) it was read from.
    #[getter]
    fn path(&self) -> String {
        self.inner.path.display().to_string()
    }

    fn __repr__(&self) -> String {
        format!("Material(name={:?}, path={:?})", self.inner.material.name, self.inner.path.display().to_string())
    }
}

/// A Python dict as a TOML table (`prefix` names nested keys in errors).
fn toml_table(d: &Bound<'_, PyDict>, prefix: &str) -> PyResult<toml::Table> {
    let mut t = toml::Table::new();
    for (k, v) in d.iter() {
        let key: String = k.extract().map_err(|_| PyValueError::new_err(format!("{prefix}keys must be strings")))?;
        let value = toml_value(&v, &format!("{prefix}{key}"))?;
        t.insert(key, value);
    }
    Ok(t)
}

/// A Python value as a TOML value: bool, int, float, str, list/tuple, dict (None has no TOML form:
/// leave the key out).
fn toml_value(v: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if let Ok(d) = v.downcast::<PyDict>() {
        return Ok(toml::Value::Table(toml_table(d, &format!("{key}."))?));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(v.extract()?));
    }
    if let Ok(x) = v.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    if let Ok(s) = v.extract::<String>() {
        return Ok(toml::Value::String(s));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'_, PyAny>> = v.try_iter()?.collect::<PyResult<_>>()?;
        return items.iter().map(|x| toml_value(x, key)).collect::<PyResult<Vec<_>>>().map(toml::Value::Array);
    }
    Err(PyValueError::new_err(format!(
        "Material keyword `{key}`: {} has no TOML form (numbers, strings, lists, dicts; leave a key out instead of None)",
        v.get_type().name()?
    )))
}

/// A Johnson-Cook set (paper Eqs 14, 16) in the JC file's units: A, B in MPa, temperatures degC.
#[pyclass(name = "JcParams", module = "cutcal", frozen)]
#[derive(Clone)]
pub struct PyJcParams {
    pub(crate) inner: NamedJc,
}

#[pymethods]
impl PyJcParams {
    /// JcParams(a_mpa, b_mpa, n, c, m, tm_c, tr_c=20.0, eps0_per_s=1.0): validated by the JC file
    /// reader (errors name the field as `<JcParams>:LINE: field ...`).
    #[new]
    #[pyo3(signature = (a_mpa, b_mpa, n, c, m, tm_c, tr_c = 20.0, eps0_per_s = 1.0))]
    #[allow(clippy::too_many_arguments)] // the eight JC constants, named at the call
    fn new(a_mpa: f64, b_mpa: f64, n: f64, c: f64, m: f64, tm_c: f64, tr_c: f64, eps0_per_s: f64) -> PyResult<Self> {
        let v = JcFile { source: None, a_mpa, b_mpa, n, c, m, eps0_per_s, tm_c, tr_c };
        let jc = types::jc_from_values(&v).map_err(to_py)?;
        Ok(Self { inner: NamedJc { jc, file_name: None } })
    }

    /// JcParams.from_toml(path): reads a JC file (fixtures/jc/*.toml).
    #[staticmethod]
    fn from_toml(path: PathBuf) -> PyResult<Self> {
        Ok(Self { inner: types::jc_from_file(&path).map_err(to_py)? })
    }

    #[getter]
    fn a_mpa(&self) -> f64 {
        self.inner.jc.a_pa / 1e6
    }
    #[getter]
    fn b_mpa(&self) -> f64 {
        self.inner.jc.b_pa / 1e6
    }
    #[getter]
    fn n(&self) -> f64 {
        self.inner.jc.n
    }
    #[getter]
    fn c(&self) -> f64 {
        self.inner.jc.c
    }
    #[getter]
    fn m(&self) -> f64 {
        self.inner.jc.m
    }
    #[getter]
    fn eps0_per_s(&self) -> f64 {
        self.inner.jc.eps0_per_s
    }
    #[getter]
    fn tm_c(&self) -> f64 {
        self.inner.jc.tm_c
    }
    #[getter]
    fn tr_c(&self) -> f64 {
        self.inner.jc.tr_c
    }

    /// Flow stress, MPa, at effective strain, strain rate (1/s) and temperature (degC): paper Eq 16.
    fn flow_stress_mpa(&self, strain: f64, strain_rate_per_s: f64, temperature_c: f64) -> f64 {
        self.inner.jc.flow_stress(strain, strain_rate_per_s, temperature_c) / 1e6
    }

    /// The set as a dict in the JC file's keys and units.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let v = types::jc_values(&self.inner.jc);
        let d = PyDict::new(py);
        for (k, x) in [
            ("a_mpa", v.a_mpa),
            ("b_mpa", v.b_mpa),
            ("n", v.n),
            ("c", v.c),
            ("m", v.m),
            ("eps0_per_s", v.eps0_per_s),
            ("tm_c", v.tm_c),
            ("tr_c", v.tr_c),
        ] {
            d.set_item(k, x)?;
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let v = types::jc_values(&self.inner.jc);
        format!(
            "JcParams(a_mpa={}, b_mpa={}, n={}, c={}, m={}, tm_c={}, tr_c={}, eps0_per_s={})",
            v.a_mpa, v.b_mpa, v.n, v.c, v.m, v.tm_c, v.tr_c, v.eps0_per_s
        )
    }
}

/// One orthogonal cutting test in the units of the test CSV columns.
#[pyclass(name = "CuttingTest", module = "cutcal", frozen)]
#[derive(Clone)]
pub struct PyCuttingTest {
    pub(crate) inner: CuttingTest,
}

#[pymethods]
impl PyCuttingTest {
    /// CuttingTest(test, speed_m_min, uncut_mm, width_mm, rake_deg, fc_n_per_mm=None, ...):
    /// validated and converted by the test CSV reader (errors read `<CuttingTest>:2: field ...`).
    #[new]
    #[pyo3(signature = (test, speed_m_min, uncut_mm, width_mm, rake_deg, fc_n_per_mm = None, ft_n_per_mm = None,
        chip_mm = None, t_int_c = None, edge_radius_um = None, flank_wear_mm = None, order = None))]
    #[allow(clippy::too_many_arguments)] // one argument per CSV column
    fn new(
        test: String,
        speed_m_min: f64,
        uncut_mm: f64,
        width_mm: f64,
        rake_deg: f64,
        fc_n_per_mm: Option<f64>,
        ft_n_per_mm: Option<f64>,
        chip_mm: Option<f64>,
        t_int_c: Option<f64>,
        edge_radius_um: Option<f64>,
        flank_wear_mm: Option<f64>,
        order: Option<f64>,
    ) -> PyResult<Self> {
        let c = TestColumns {
            test,
            speed_m_min,
            uncut_mm,
            width_mm,
            rake_deg,
            fc_n_per_mm,
            ft_n_per_mm,
            chip_mm,
            t_int_c,
            edge_radius_um,
            flank_wear_mm,
            order,
        };
        Ok(Self { inner: types::test_from_columns(&c).map_err(to_py)? })
    }

    /// The test as a dict of CSV columns (None where not measured).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = types::columns_of(&self.inner);
        let d = PyDict::new(py);
        d.set_item("test", &c.test)?;
        d.set_item("speed_m_min", c.speed_m_min)?;
        d.set_item("uncut_mm", c.uncut_mm)?;
        d.set_item("width_mm", c.width_mm)?;
        d.set_item("rake_deg", c.rake_deg)?;
        d.set_item("fc_n_per_mm", c.fc_n_per_mm)?;
        d.set_item("ft_n_per_mm", c.ft_n_per_mm)?;
        d.set_item("chip_mm", c.chip_mm)?;
        d.set_item("t_int_c", c.t_int_c)?;
        d.set_item("edge_radius_um", c.edge_radius_um)?;
        d.set_item("flank_wear_mm", c.flank_wear_mm)?;
        d.set_item("order", c.order)?;
        Ok(d)
    }

    /// Test id.
    #[getter]
    fn test(&self) -> String {
        self.inner.id.clone()
    }

    fn __repr__(&self) -> String {
        let c = types::columns_of(&self.inner);
        format!(
            "CuttingTest(test={:?}, speed_m_min={}, uncut_mm={}, width_mm={}, rake_deg={})",
            c.test, c.speed_m_min, c.uncut_mm, c.width_mm, c.rake_deg
        )
    }
}

/// The result of `identify`: the JC set, the zone fields of Fig 4, bounds and spread.
#[pyclass(name = "IdentifyResult", module = "cutcal", frozen)]
pub struct PyIdentifyResult {
    pub(crate) inner: IdentifyOutput,
}

#[pymethods]
impl PyIdentifyResult {
    /// The identified Johnson-Cook set.
    #[getter]
    fn jc(&self) -> PyJcParams {
        PyJcParams { inner: NamedJc { jc: self.inner.jc, file_name: None } }
    }

    /// Parameters that ended on a bound (`a_mpa`, `b_mpa`, `n`, `c`, `m`).
    #[getter]
    fn at_bounds(&self) -> Vec<String> {
        self.inner.at_bounds.clone()
    }

    /// The zone fields across the primary shear zone (paper Fig 4): a dict of 1-D float64 numpy
    /// arrays, one per quantity, named with their units (`x_mm`, `gamma`, `gamma_dot_per_s`, `eps`,
    /// `eps_dot_per_s`, `tau_mpa`, `sigma_eff_mpa`, `temperature_c`).
    #[getter]
    fn fields<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, v) in &self.inner.fields {
            d.set_item(*name, PyArray1::from_vec(py, v.clone()))?;
        }
        Ok(d)
    }

    /// The bootstrap spread (a dict, as the `bootstrap` key of the CLI's JSON), or None when
    /// `identify(..., bootstrap=0)`.
    #[getter]
    fn spread<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.inner.spread_json.as_deref().map(|s| json_to_py(py, s)).transpose()
    }

    /// The JSON document of `cutcal identify --json`, as text.
    #[getter]
    fn json(&self) -> String {
        self.inner.json.clone()
    }

    /// The JSON document of `cutcal identify --json`, as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &self.inner.json)
    }

    fn __repr__(&self) -> String {
        let v = types::jc_values(&self.inner.jc);
        format!(
            "IdentifyResult(a_mpa={:.2}, b_mpa={:.2}, n={:.4}, c={:.5}, m={:.4}, at_bounds={:?})",
            v.a_mpa, v.b_mpa, v.n, v.c, v.m, self.inner.at_bounds
        )
    }
}

/// Adds the classes to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMaterial>()?;
    m.add_class::<PyJcParams>()?;
    m.add_class::<PyCuttingTest>()?;
    m.add_class::<PyIdentifyResult>()?;
    Ok(())
}
