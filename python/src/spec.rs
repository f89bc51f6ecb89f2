//! Specs: read from a file, TOML or JSON text, or a dict; built into a model.

use crate::errors::{lib_spec_error, parse_variant, spec_error, to_py};
use crate::model::PyModel;
use netspec::spec::{Problem, Spec, SpecErrorKind, Variant};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The name errors give a spec made from text or a dict.
pub(crate) const INLINE: &str = "<inline>";

/// A functional specification (a spec file's contents), not yet resolved against its mesh.
#[pyclass(module = "netspec", name = "Spec", frozen)]
#[derive(Clone)]
pub(crate) struct PySpec {
    pub(crate) spec: Spec,
    /// The file it was read from (`None`: text or a dict).
    pub(crate) path: Option<PathBuf>,
    /// Where a mesh file it names is looked up.
    pub(crate) base: PathBuf,
}

impl PySpec {
    pub(crate) fn origin(&self) -> PathBuf {
        self.path.clone().unwrap_or_else(|| PathBuf::from(INLINE))
    }

    /// The problem: the spec with `variant` applied, resolved against its mesh.
    pub(crate) fn problem(
        &self,
        py: Python<'_>,
        variant: Option<&Variant>,
        max_cells: Option<usize>,
    ) -> PyResult<Problem> {
        let mut spec = self.spec.clone();
        if let Some(v) = variant {
            v.apply(&mut spec.formulation, &mut spec.solver);
        }
        spec.resolve_within(&self.base, max_cells.unwrap_or(netspec::spec::DEFAULT_MAX_CELLS))
            .map_err(|kind| spec_error(py, &self.origin(), &kind, None))
    }

    pub(crate) fn load_file(py: Python<'_>, path: &Path) -> PyResult<PySpec> {
        let spec = Spec::load(path).map_err(|e| lib_spec_error(py, &e))?;
        let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        Ok(PySpec { spec, path: Some(path.to_path_buf()), base })
    }

    pub(crate) fn from_json_text(py: Python<'_>, text: &str, base: Option<PathBuf>) -> PyResult<PySpec> {
        let origin = Path::new(INLINE);
        let mut de = serde_json::Deserializer::from_str(text);
        let spec: Spec = serde_path_to_error::deserialize(&mut de).map_err(|e| {
            let path = e.path().to_string();
            let field = (path != ".").then_some(path);
            spec_error(py, origin, &SpecErrorKind::Json(e.into_inner()), field)
        })?;
        spec.check_values().map_err(|k| spec_error(py, origin, &k, None))?;
        Ok(PySpec { spec, path: None, base: base.unwrap_or_else(|| PathBuf::from(".")) })
    }
}

#[pymethods]
impl PySpec {
    /// Parses a spec from TOML text (a spec file's contents); a mesh file it names is looked
    /// up under `base` (default: the current directory).
    #[staticmethod]
    #[pyo3(signature = (text, base=None))]
    fn from_toml(py: Python<'_>, text: &str, base: Option<PathBuf>) -> PyResult<PySpec> {
        let spec = Spec::from_toml(text)
            .map_err(|k| spec_error(py, Path::new(INLINE), &k, netspec::spec::toml_error_field(text)))?;
        Ok(PySpec { spec, path: None, base: base.unwrap_or_else(|| PathBuf::from(".")) })
    }

    /// Parses a spec from JSON text (the form `Spec.to_dict` and `result.json` give it).
    #[staticmethod]
    #[pyo3(signature = (text, base=None))]
    fn from_json(py: Python<'_>, text: &str, base: Option<PathBuf>) -> PyResult<PySpec> {
        PySpec::from_json_text(py, text, base)
    }

    /// A spec from a dict with the spec file's keys (nested dicts for its tables).
    #[staticmethod]
    #[pyo3(signature = (data, base=None))]
    fn from_dict(py: Python<'_>, data: &Bound<'_, PyDict>, base: Option<PathBuf>) -> PyResult<PySpec> {
        let text: String = py.import("json")?.call_method1("dumps", (data,))?.extract()?;
        PySpec::from_json_text(py, &text, base)
    }

    /// Reads a `.toml` or `.json` spec file.
    #[staticmethod]
    fn read(py: Python<'_>, path: PathBuf) -> PyResult<PySpec> {
        PySpec::load_file(py, &path)
    }

    /// The spec's name.
    #[getter]
    fn name(&self) -> String {
        self.spec.name.clone()
    }

    /// The spec's description.
    #[getter]
    fn description(&self) -> String {
        self.spec.description.clone()
    }

    /// The file it was read from, or None.
    #[getter]
    fn path(&self) -> Option<String> {
        self.path.as_ref().map(|p| p.display().to_string())
    }

    /// The spec as a dict (every field, defaults filled in; `Spec.from_dict` reads it back).
    fn to_dict(&self, py: Python<'_>) -> PyResult<PyObject> {
        to_py(py, &self.spec)
    }

    /// Resolves the spec against its mesh and builds its MILP with the formulation (a recipe
    /// such as `strong`, `tight:connectivity=flow`; default: the spec's own), as
    /// `netspec solve --export` does.
    #[pyo3(signature = (formulation=None, max_cells=None))]
    fn build(&self, py: Python<'_>, formulation: Option<&str>, max_cells: Option<usize>) -> PyResult<PyModel> {
        let variant = parse_variant(formulation)?;
        let problem = self.problem(py, variant.as_ref(), max_cells)?;
        // As `--export` writes it: a recipe whose cutset rows are separated during the solve
        // gives its complete equivalent (the single-commodity flow), the same optimum.
        let (model, compact) = py.allow_threads(|| {
            let f = netspec::pipeline::build(&problem);
            match f.is_complete() {
                true => (f.model, false),
                false => (netspec::formulations::build_compact(&problem).model, true),
            }
        });
        Ok(PyModel { model: Arc::new(model), compact })
    }

    fn __repr__(&self) -> String {
        let path = self.path.as_ref().map_or("None".to_string(), |p| format!("{:?}", p.display().to_string()));
        format!("Spec(name={:?}, path={path})", self.spec.name)
    }
}

/// Reads a spec file (`.toml` or `.json`).
#[pyfunction]
pub(crate) fn read_spec(py: Python<'_>, path: PathBuf) -> PyResult<PySpec> {
    PySpec::load_file(py, &path)
}
