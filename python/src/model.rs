//! Models: a solver-neutral MILP read, inspected, checked, written and solved.

use crate::blocking::run_blocking;
use crate::errors::{err, parse_method, py_bool, py_num, to_py, NetspecError};
use netspec::milp::{Model, Tolerances, VarKind};
use netspec::pipeline::settings::Settings;
use netspec::pipeline::Method;
use netspec::solvers::{SolveOptions, SolverKind};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::Arc;

/// A solver-neutral MILP: `min/max c·x + c0` subject to `lhs ≤ A x ≤ rhs`, bounds and
/// integrality.
#[pyclass(module = "netspec", name = "Model", frozen)]
pub(crate) struct PyModel {
    pub(crate) model: Arc<Model>,
    /// Whether the recipe separates rows during the solve, so that this is its complete
    /// equivalent (the cutset rows replaced by a single-commodity flow).
    pub(crate) compact: bool,
}

pub(crate) fn kind_name(k: VarKind) -> &'static str {
    match k {
        VarKind::Continuous => "continuous",
        VarKind::Integer => "integer",
        VarKind::Binary => "binary",
    }
}

/// A point as one value per column: a sequence in column order, or a dict by column name
/// (columns not named are 0).
pub(crate) fn point(model: &Model, values: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if let Ok(d) = values.downcast::<PyDict>() {
        let index: std::collections::HashMap<&str, usize> =
            model.vars().iter().enumerate().map(|(i, v)| (v.name.as_str(), i)).collect();
        let mut x = vec![0.0; model.num_vars()];
        for (k, v) in d.iter() {
            let name: String = k.extract()?;
            let i = *index.get(name.as_str()).ok_or_else(|| PyValueError::new_err(format!("no column `{name}`")))?;
            x[i] = v.extract()?;
        }
        return Ok(x);
    }
    let x: Vec<f64> = values.extract()?;
    if x.len() != model.num_vars() {
        return Err(PyValueError::new_err(format!(
            "the point has {} values, the model {} columns",
            x.len(),
            model.num_vars()
        )));
    }
    Ok(x)
}

/// The solve options of a model solve.
pub(crate) fn model_options(
    solver: Option<&str>,
    time_limit: Option<f64>,
    threads: Option<u32>,
    gap: Option<f64>,
    seed: Option<u64>,
) -> PyResult<(SolverKind, SolveOptions)> {
    let settings = Settings { method: parse_method(solver)?, time_limit, gap, threads, seed, ..Settings::default() };
    let (method, options) =
        netspec::pipeline::settings::resolve(&[(netspec::pipeline::settings::Origin::Flags, settings)]).map_err(
            |s| NetspecError::new_err(format!("{}: {}", s.place.trim_start_matches("--").replace('-', "_"), s.reason)),
        )?;
    match method {
        Method::Milp(k) => Ok((k, options)),
        m => Err(PyValueError::new_err(format!("solver: `{m}` is a design search, not a MILP backend"))),
    }
}

#[pymethods]
impl PyModel {
    /// The model's name.
    #[getter]
    fn name(&self) -> String {
        self.model.name.clone()
    }

    /// `minimize` or `maximize`.
    #[getter]
    fn sense(&self) -> &'static str {
        match self.model.sense {
            netspec::milp::Sense::Minimize => "minimize",
            netspec::milp::Sense::Maximize => "maximize",
        }
    }

    /// Columns (variables).
    #[getter]
    fn num_vars(&self) -> usize {
        self.model.num_vars()
    }

    /// Rows (constraints).
    #[getter]
    fn num_rows(&self) -> usize {
        self.model.num_rows()
    }

    /// Nonzero coefficients of the constraint matrix.
    #[getter]
    fn num_nonzeros(&self) -> usize {
        self.model.num_nonzeros()
    }

    /// Integer and binary columns.
    #[getter]
    fn num_integers(&self) -> usize {
        self.model.vars().iter().filter(|v| v.kind.is_integral()).count()
    }

    /// True when the spec's recipe separates its cutset rows during the solve, so that this
    /// model is its complete equivalent (a single-commodity flow in their place, the same
    /// optimum), as `netspec solve --export` writes it.
    #[getter]
    fn compact(&self) -> bool {
        self.compact
    }

    /// The column names, in column order.
    fn column_names(&self) -> Vec<String> {
        self.model.vars().iter().map(|v| v.name.clone()).collect()
    }

    /// The row names, in row order.
    fn row_names(&self) -> Vec<String> {
        self.model.rows().map(|r| r.name.to_string()).collect()
    }

    /// One column by name: `{"name", "kind", "lb", "ub", "obj"}`.
    fn column(&self, py: Python<'_>, name: &str) -> PyResult<PyObject> {
        let v = self
            .model
            .vars()
            .iter()
            .find(|v| v.name == name)
            .ok_or_else(|| pyo3::exceptions::PyKeyError::new_err(name.to_string()))?;
        let d = PyDict::new(py);
        d.set_item("name", &v.name)?;
        d.set_item("kind", kind_name(v.kind))?;
        d.set_item("lb", v.lb)?;
        d.set_item("ub", v.ub)?;
        d.set_item("obj", v.obj)?;
        Ok(d.into_any().unbind())
    }

    /// One row by name: `{"name", "lhs", "rhs", "terms"}`, terms a dict column name →
    /// coefficient (`lhs ≤ Σ terms ≤ rhs`, infinite sides for one-sided rows).
    fn row(&self, py: Python<'_>, name: &str) -> PyResult<PyObject> {
        let r = self
            .model
            .rows()
            .find(|r| r.name == name)
            .ok_or_else(|| pyo3::exceptions::PyKeyError::new_err(name.to_string()))?;
        let d = PyDict::new(py);
        d.set_item("name", r.name)?;
        d.set_item("lhs", r.lhs)?;
        d.set_item("rhs", r.rhs)?;
        let terms = PyDict::new(py);
        for (v, a) in r.terms() {
            terms.set_item(&self.model.var(v).name, a)?;
        }
        d.set_item("terms", terms)?;
        Ok(d.into_any().unbind())
    }

    /// The objective `c·x + c0` at a point (a sequence in column order, or a dict by name).
    fn objective_value(&self, values: &Bound<'_, PyAny>) -> PyResult<f64> {
        Ok(self.model.objective_value(&point(&self.model, values)?))
    }

    /// Writes the model: `.mps`, `.lp`, either with `.gz`, by the file's extension.
    fn write(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let model = self.model.clone();
        py.allow_threads(|| netspec::io::write_model_file(&model, &path)).map_err(err)?;
        Ok(())
    }

    /// Solves the model on a backend (default HiGHS) and checks the answer independently, as
    /// `netspec solve-file` does; `start` is a MIP start (a point, checked before it is handed
    /// over). Ctrl-C stops the backend and returns its best point.
    #[pyo3(signature = (solver=None, time_limit=None, threads=None, gap=None, seed=None, start=None, on_progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        solver: Option<&str>,
        time_limit: Option<f64>,
        threads: Option<u32>,
        gap: Option<f64>,
        seed: Option<u64>,
        start: Option<&Bound<'_, PyAny>>,
        on_progress: Option<PyObject>,
    ) -> PyResult<PyModelResult> {
        let (kind, mut options) = model_options(solver, time_limit, threads, gap, seed)?;
        options.mip_start = start.map(|s| point(&self.model, s)).transpose()?;
        let model = self.model.clone();
        let backend = kind.instance().map_err(err)?;
        if !backend.capabilities().reports_progress {
            options.progress = None;
        }
        let reports = on_progress.is_some() && backend.capabilities().reports_progress;
        let solved = run_blocking(py, on_progress.filter(|_| reports), move |interrupt, sink| {
            let mut o = options;
            o.interrupt = Some(interrupt);
            o.progress = sink;
            backend.solve(&model, &o).map(|r| (o, r))
        })?;
        let (options, result) = solved.map_err(err)?;
        let report = netspec::report::SolveReport::new(
            self.model.name.clone(),
            &self.model,
            SolveOptions { interrupt: None, progress: None, ..options },
            result,
            &Tolerances::default(),
        );
        Ok(PyModelResult { report, model: self.model.clone() })
    }

    fn __repr__(&self) -> String {
        format!(
            "Model(name={:?}, vars={}, rows={}, nonzeros={})",
            self.model.name,
            self.model.num_vars(),
            self.model.num_rows(),
            self.model.num_nonzeros()
        )
    }
}

/// What a model solve found, with the independent check of its point.
#[pyclass(module = "netspec", name = "ModelResult", frozen)]
pub(crate) struct PyModelResult {
    pub(crate) report: netspec::report::SolveReport,
    pub(crate) model: Arc<Model>,
}

#[pymethods]
impl PyModelResult {
    /// Why the backend stopped: `optimal`, `infeasible`, `limit(time)`, `interrupted`, …
    #[getter]
    fn termination(&self) -> String {
        self.report.result.termination.label()
    }

    /// The status line `netspec solve-file` prints.
    #[getter]
    fn status(&self) -> String {
        self.report.result.status_line()
    }

    /// The objective of the point found.
    #[getter]
    fn objective(&self) -> Option<f64> {
        self.report.result.objective
    }

    /// The proven bound.
    #[getter]
    fn bound(&self) -> Option<f64> {
        self.report.result.dual_bound
    }

    /// The relative gap.
    #[getter]
    fn gap(&self) -> Option<f64> {
        self.report.result.gap
    }

    /// Wall time of the solve, seconds.
    #[getter]
    fn time(&self) -> f64 {
        self.report.result.wall_time
    }

    /// Branch-and-bound nodes.
    #[getter]
    fn nodes(&self) -> Option<u64> {
        self.report.result.nodes
    }

    /// The backend.
    #[getter]
    fn solver(&self) -> String {
        self.report.result.solver.name().to_string()
    }

    /// Whether a point exists and passed the independent check.
    #[getter]
    fn valid(&self) -> bool {
        self.report.valid
    }

    /// The point, one value per column (None without one).
    #[getter]
    fn x(&self) -> Option<Vec<f64>> {
        self.report.result.primal.clone()
    }

    /// The point as a dict column name → value (None without one).
    fn values(&self, py: Python<'_>) -> PyResult<Option<PyObject>> {
        let Some(x) = &self.report.result.primal else { return Ok(None) };
        let d = PyDict::new(py);
        for (v, val) in self.model.vars().iter().zip(x) {
            d.set_item(&v.name, val)?;
        }
        Ok(Some(d.into_any().unbind()))
    }

    /// The JSON result `netspec solve-file --json` writes, as a dict.
    fn to_dict(&self, py: Python<'_>) -> PyResult<PyObject> {
        to_py(py, &self.report)
    }

    /// The one-screen summary `netspec solve-file` prints.
    fn summary(&self) -> String {
        self.report.summary()
    }

    fn __repr__(&self) -> String {
        format!(
            "ModelResult(solver={:?}, termination={:?}, objective={}, valid={})",
            self.report.result.solver.name(),
            self.report.result.termination.label(),
            py_num(self.report.result.objective),
            py_bool(self.report.valid)
        )
    }
}

/// Reads a model file: MPS (free or fixed) or LP, either gzipped, by its extension.
#[pyfunction]
pub(crate) fn read_model(py: Python<'_>, path: PathBuf) -> PyResult<PyModel> {
    let read = py.allow_threads(|| netspec::io::read_model_file(&path)).map_err(err)?;
    let warnings = py.import("warnings")?;
    for w in &read.warnings {
        warnings.call_method1("warn", (format!("{}: {w}", path.display()),))?;
    }
    Ok(PyModel { model: Arc::new(read.model), compact: false })
}

/// The independent checker: every bound, row and integrality requirement at a point (a
/// sequence in column order, or a dict by name), and the objective recomputed. Returns
/// `{"feasible", "objective", "max_bound_violation", "max_row_violation",
/// "max_integrality_violation", "violations"}` (violations as text).
#[pyfunction]
pub(crate) fn check(py: Python<'_>, model: &PyModel, values: &Bound<'_, PyAny>) -> PyResult<PyObject> {
    let x = point(&model.model, values)?;
    let report = netspec::milp::check_point(&model.model, &x, &Tolerances::default());
    let d = PyDict::new(py);
    d.set_item("feasible", report.is_feasible())?;
    d.set_item("objective", report.objective)?;
    d.set_item("max_bound_violation", report.max_bound_violation)?;
    d.set_item("max_row_violation", report.max_row_violation)?;
    d.set_item("max_integrality_violation", report.max_integrality_violation)?;
    let v: Vec<String> = report.violations.iter().map(|v| v.to_string()).collect();
    d.set_item("violations", PyList::new(py, v)?)?;
    Ok(d.into_any().unbind())
}
