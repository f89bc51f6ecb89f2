//! `netspec._netspec`: the Python extension module of netspec, wrapped by the package in
//! `python/netspec/`. Each function calls the library entry point the command line calls
//! (`netspec solve` → [`netspec::run::solve_loaded`], `compare`, `level`, `city`,
//! `solve-file`), with the solve's wait outside the GIL: other Python threads run meanwhile, a
//! Ctrl-C stops the backend and keeps its best design, and progress reaches a Python callback on
//! the calling thread.

use netspec::compare::{Manifest, RunRecord, RunSettings};
use netspec::formulations::Formulation;
use netspec::milp::{Model, Tolerances, VarKind};
use netspec::pipeline::settings::Settings;
use netspec::pipeline::Method;
use netspec::run::{Design, SolveRequest, StartChoice};
use netspec::solvers::{Interrupt, Progress, ProgressSink, SolveOptions, SolverKind};
use netspec::spec::{Problem, Spec, SpecError as LibSpecError, SpecErrorKind, Variant};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::sync::Arc;
use std::time::{Duration, Instant};

create_exception!(
    netspec,
    SpecError,
    PyValueError,
    "A spec that cannot be used: the message names the file and field, as `netspec solve` does; \
     `.field` is the dotted field (`sinks.vertices[3]`) or None, `.path` the file or `<inline>`."
);
create_exception!(
    netspec,
    NetspecError,
    PyRuntimeError,
    "A run that could not be made: a refused setting (named as the keyword argument), a backend \
     that cannot attempt the solve, a file that cannot be read or written."
);

/// How often the waiting thread looks for Ctrl-C and delivers progress.
const POLL: Duration = Duration::from_millis(25);

/// The name errors give a spec made from text or a dict.
const INLINE: &str = "<inline>";

fn spec_error(py: Python<'_>, path: &Path, kind: &SpecErrorKind, field: Option<String>) -> PyErr {
    // A field found by reading again is named in the message as the library names its own.
    let message = match (kind.field(), &field) {
        (None, Some(f)) => format!("{}: field `{f}`: {kind}", path.display()),
        _ => format!("{}: {kind}", path.display()),
    };
    new_spec_error(py, message, kind.field().or(field), path)
}

/// A `SpecError` with its `field` and `path` attributes.
fn new_spec_error(py: Python<'_>, message: String, field: Option<String>, path: &Path) -> PyErr {
    let err = SpecError::new_err(message);
    let value = err.value(py);
    // Attributes on a fresh exception instance cannot fail.
    let _ = value.setattr("field", field);
    let _ = value.setattr("path", path.display().to_string());
    err
}

fn lib_spec_error(py: Python<'_>, e: &LibSpecError) -> PyErr {
    // A TOML schema error names the line; the field is found by reading the file again.
    let field = match &e.kind {
        SpecErrorKind::Toml(_) => {
            std::fs::read_to_string(&e.path).ok().and_then(|t| netspec::spec::toml_error_field(&t))
        }
        _ => None,
    };
    spec_error(py, &e.path, &e.kind, field)
}

fn run_error(py: Python<'_>, e: netspec::run::RunError) -> PyErr {
    match e {
        netspec::run::RunError::Spec(s) => lib_spec_error(py, &s),
        // The flags are this function's keyword arguments.
        netspec::run::RunError::Settings(s) => {
            let place = s.place.trim_start_matches("--").replace('-', "_");
            NetspecError::new_err(format!("{place}: {}", s.reason))
        }
        other => NetspecError::new_err(other.to_string()),
    }
}

/// An optional number as Python writes it.
fn py_num(v: Option<f64>) -> String {
    v.map_or("None".to_string(), |v| format!("{v:?}"))
}

fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

fn err<E: std::fmt::Display>(e: E) -> PyErr {
    NetspecError::new_err(e.to_string())
}

/// A serialisable value as Python objects (through JSON: dicts, lists, numbers, strings, None).
fn to_py<T: Serialize>(py: Python<'_>, value: &T) -> PyResult<PyObject> {
    let text = serde_json::to_string(value).map_err(err)?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

fn parse_method(solver: Option<&str>) -> PyResult<Option<Method>> {
    solver.map(|s| s.parse::<Method>().map_err(|e| PyValueError::new_err(format!("solver: {e}")))).transpose()
}

fn parse_variant(formulation: Option<&str>) -> PyResult<Option<Variant>> {
    formulation
        .map(|f| f.parse::<Variant>().map_err(|e| PyValueError::new_err(format!("formulation: {e}"))))
        .transpose()
}

fn parse_kind(solver: &str) -> PyResult<SolverKind> {
    solver.parse::<SolverKind>().map_err(|e| PyValueError::new_err(format!("solver: {e}")))
}

/// A progress report of a running solve, as the backend gives it.
#[pyclass(module = "netspec", name = "Progress", frozen, get_all)]
#[derive(Clone)]
struct PyProgress {
    /// Seconds since the solver started.
    elapsed: f64,
    /// The best objective found so far (the incumbent), if any.
    incumbent: Option<f64>,
    /// The best proven bound so far, if any.
    bound: Option<f64>,
    /// Branch-and-bound nodes so far.
    nodes: u64,
}

#[pymethods]
impl PyProgress {
    fn __repr__(&self) -> String {
        format!(
            "Progress(elapsed={:.2}, incumbent={}, bound={}, nodes={})",
            self.elapsed,
            py_num(self.incumbent),
            py_num(self.bound),
            self.nodes
        )
    }
}

/// Runs `work` on a thread of its own with the GIL released, and waits for it: every [`POLL`]
/// the waiting (calling) thread takes the GIL to deliver progress reports to `on_progress` and
/// to look for a pending signal. A KeyboardInterrupt (Ctrl-C) triggers the run's interrupt (the
/// backend stops and keeps its best design, which `work` returns); an exception raised by
/// `on_progress` does too, and is raised once `work` has returned.
fn run_blocking<T: Send>(
    py: Python<'_>,
    on_progress: Option<PyObject>,
    work: impl FnOnce(Interrupt, Option<ProgressSink>) -> T + Send,
) -> PyResult<T> {
    /// What the waiting thread hears from the solving one.
    enum Heard {
        Progress(Progress),
        Done,
    }
    let interrupt = Interrupt::new();
    let (tx, rx) = mpsc::channel::<Heard>();
    let sink = on_progress.as_ref().map(|_| {
        let tx = tx.clone();
        ProgressSink(Arc::new(move |p: Progress| {
            let _ = tx.send(Heard::Progress(p));
        }))
    });
    let stop = interrupt.clone();
    let (out, raised) = py.allow_threads(move || {
        let mut raised: Option<PyErr> = None;
        let out = std::thread::scope(|scope| {
            let handle = scope.spawn(move || {
                let out = work(stop, sink);
                let _ = tx.send(Heard::Done);
                out
            });
            let mut finished = false;
            while !finished {
                // Blocks until a report, the end, or the next look for a signal. (A worker that
                // panicked drops its sender: disconnected is the end too.)
                let mut reports = Vec::new();
                let mut hear = |h: Result<Heard, ()>| match h {
                    Ok(Heard::Progress(p)) => reports.push(p),
                    Ok(Heard::Done) | Err(()) => finished = true,
                };
                match rx.recv_timeout(POLL) {
                    Ok(h) => hear(Ok(h)),
                    Err(mpsc::RecvTimeoutError::Timeout) => {}
                    Err(mpsc::RecvTimeoutError::Disconnected) => hear(Err(())),
                }
                rx.try_iter().for_each(|h| hear(Ok(h)));
                if finished && reports.is_empty() {
                    break;
                }
                Python::with_gil(|py| {
                    if let Some(cb) = &on_progress {
                        for p in reports {
                            let report =
                                PyProgress { elapsed: p.elapsed, incumbent: p.primal, bound: p.dual, nodes: p.nodes };
                            if let Err(e) = cb.call1(py, (report,)) {
                                raised.get_or_insert(e);
                                interrupt.trigger();
                            }
                        }
                    }
                    // Only the main thread sees signals; elsewhere this returns Ok.
                    if let Err(e) = py.check_signals() {
                        if !e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                            raised.get_or_insert(e);
                        }
                        interrupt.trigger();
                    }
                });
            }
            handle.join()
        });
        (out, raised)
    });
    match (out, raised) {
        (_, Some(e)) => Err(e),
        (Ok(v), None) => Ok(v),
        (Err(_), None) => Err(PyRuntimeError::new_err("the solve panicked")),
    }
}

// ---------------------------------------------------------------------------------------------
// Specs

/// A functional specification (a spec file's contents), not yet resolved against its mesh.
#[pyclass(module = "netspec", name = "Spec", frozen)]
#[derive(Clone)]
struct PySpec {
    spec: Spec,
    /// The file it was read from (`None`: text or a dict).
    path: Option<PathBuf>,
    /// Where a mesh file it names is looked up.
    base: PathBuf,
}

impl PySpec {
    fn origin(&self) -> PathBuf {
        self.path.clone().unwrap_or_else(|| PathBuf::from(INLINE))
    }

    /// The problem: the spec with `variant` applied, resolved against its mesh.
    fn problem(&self, py: Python<'_>, variant: Option<&Variant>, max_cells: Option<usize>) -> PyResult<Problem> {
        let mut spec = self.spec.clone();
        if let Some(v) = variant {
            v.apply(&mut spec.formulation, &mut spec.solver);
        }
        spec.resolve_within(&self.base, max_cells.unwrap_or(netspec::spec::DEFAULT_MAX_CELLS))
            .map_err(|kind| spec_error(py, &self.origin(), &kind, None))
    }

    fn load_file(py: Python<'_>, path: &Path) -> PyResult<PySpec> {
        let spec = Spec::load(path).map_err(|e| lib_spec_error(py, &e))?;
        let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        Ok(PySpec { spec, path: Some(path.to_path_buf()), base })
    }

    fn from_json_text(py: Python<'_>, text: &str, base: Option<PathBuf>) -> PyResult<PySpec> {
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
fn read_spec(py: Python<'_>, path: PathBuf) -> PyResult<PySpec> {
    PySpec::load_file(py, &path)
}

// ---------------------------------------------------------------------------------------------
// Models

/// A solver-neutral MILP: `min/max c·x + c0` subject to `lhs ≤ A x ≤ rhs`, bounds and
/// integrality.
#[pyclass(module = "netspec", name = "Model", frozen)]
struct PyModel {
    model: Arc<Model>,
    /// Whether the recipe separates rows during the solve, so that this is its complete
    /// equivalent (the cutset rows replaced by a single-commodity flow).
    compact: bool,
}

fn kind_name(k: VarKind) -> &'static str {
    match k {
        VarKind::Continuous => "continuous",
        VarKind::Integer => "integer",
        VarKind::Binary => "binary",
    }
}

/// A point as one value per column: a sequence in column order, or a dict by column name
/// (columns not named are 0).
fn point(model: &Model, values: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
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
fn model_options(
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
struct PyModelResult {
    report: netspec::report::SolveReport,
    model: Arc<Model>,
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
fn read_model(py: Python<'_>, path: PathBuf) -> PyResult<PyModel> {
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
fn check(py: Python<'_>, model: &PyModel, values: &Bound<'_, PyAny>) -> PyResult<PyObject> {
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

// ---------------------------------------------------------------------------------------------
// Designs

/// A designed network: the active edges (vertex pairs), the vertices' coordinates and the
/// metrics.
#[pyclass(module = "netspec", name = "Design", frozen, get_all)]
struct PyDesign {
    /// Active edges as (vertex, vertex), existing edges included, in edge order.
    edges: Vec<(u32, u32)>,
    /// Every mesh vertex's (x, y).
    points: Vec<(f64, f64)>,
    /// The network's metrics (length, dead ends, junctions, travel, …).
    metrics: PyObject,
}

#[pymethods]
impl PyDesign {
    fn __repr__(&self) -> String {
        format!("Design(edges={})", self.edges.len())
    }
}

/// What `solve` found: the checked design (or why there is none).
#[pyclass(module = "netspec", name = "Result", frozen)]
struct PyResultObj {
    problem: Arc<Problem>,
    formulation: Arc<Formulation>,
    design: Arc<Design>,
    explanation: Option<Arc<netspec::explain::Explanation>>,
}

impl PyResultObj {
    fn mesh_edges(&self) -> (&netspec::mesh::Mesh, &[[u32; 2]]) {
        match &*self.design {
            Design::Milp(r) => (&r.mesh, &r.active_edges),
            Design::Search(r) => (&r.mesh, &r.active_edges),
        }
    }
    fn solve_fields(&self) -> SolveFields {
        match &*self.design {
            Design::Milp(r) => {
                let s = &r.solve;
                SolveFields {
                    objective: s.objective,
                    bound: s.dual_bound,
                    gap: s.gap,
                    wall_time: s.wall_time,
                    solver_time: s.solver_time,
                    nodes: s.nodes,
                }
            }
            Design::Search(r) => {
                let s = &r.solve;
                SolveFields {
                    objective: s.objective,
                    bound: None,
                    gap: None,
                    wall_time: s.wall_time,
                    solver_time: s.solver_time,
                    nodes: None,
                }
            }
        }
    }
}

/// What a MILP solve and a search both report.
struct SolveFields {
    objective: Option<f64>,
    bound: Option<f64>,
    gap: Option<f64>,
    wall_time: f64,
    solver_time: Option<f64>,
    nodes: Option<u64>,
}

#[pymethods]
impl PyResultObj {
    /// The status line `netspec solve` prints: `optimal, design found (47 edges)`,
    /// `limit(time), design found (47 edges, gap 12 %)`, `infeasible, no design`.
    #[getter]
    fn status(&self) -> String {
        self.design.status_line()
    }

    /// Why the solve stopped: `optimal`, `infeasible`, `limit(time)`, `interrupted`, … (the
    /// `status` column of `results.csv`).
    #[getter]
    fn termination(&self) -> String {
        self.design.termination().label()
    }

    /// The objective.
    #[getter]
    fn objective(&self) -> Option<f64> {
        self.solve_fields().objective
    }

    /// The proven bound (None for the searches).
    #[getter]
    fn bound(&self) -> Option<f64> {
        self.solve_fields().bound
    }

    /// The relative gap.
    #[getter]
    fn gap(&self) -> Option<f64> {
        self.solve_fields().gap
    }

    /// Wall time of the solve, seconds.
    #[getter]
    fn time(&self) -> f64 {
        self.solve_fields().wall_time
    }

    /// The backend's own time, seconds.
    #[getter]
    fn solver_time(&self) -> Option<f64> {
        self.solve_fields().solver_time
    }

    /// Branch-and-bound nodes.
    #[getter]
    fn nodes(&self) -> Option<u64> {
        self.solve_fields().nodes
    }

    /// Whether a design exists and passed every independent check.
    #[getter]
    fn valid(&self) -> bool {
        self.design.network().is_some() && self.design.validity().valid
    }

    /// The design, or None.
    #[getter]
    fn design(&self, py: Python<'_>) -> PyResult<Option<PyDesign>> {
        if self.design.network().is_none() {
            return Ok(None);
        }
        let (mesh, edges) = self.mesh_edges();
        let metrics = match &*self.design {
            Design::Milp(r) => to_py(py, &r.metrics)?,
            Design::Search(r) => to_py(py, &r.metrics)?,
        };
        Ok(Some(PyDesign {
            edges: edges.iter().map(|&[a, b]| (a, b)).collect(),
            points: mesh.positions().iter().map(|p| (p[0], p[1])).collect(),
            metrics,
        }))
    }

    /// Which requirements conflict, when the spec was infeasible and `explain=True` (None
    /// otherwise).
    #[getter]
    fn explanation(&self, py: Python<'_>) -> PyResult<Option<PyObject>> {
        self.explanation.as_ref().map(|e| to_py(py, &**e)).transpose()
    }

    /// `result.json` as a dict.
    fn to_dict(&self, py: Python<'_>) -> PyResult<PyObject> {
        match &*self.design {
            Design::Milp(r) => to_py(py, &**r),
            Design::Search(r) => to_py(py, &**r),
        }
    }

    /// Writes the outputs `netspec solve` writes into the folder: `result.json`,
    /// `network.svg`/`.png`, `network.geojson`. Returns the folder.
    fn write(&self, py: Python<'_>, dir: PathBuf) -> PyResult<String> {
        let (p, f, d, e) = (&self.problem, &self.formulation, &self.design, &self.explanation);
        py.allow_threads(|| netspec::run::write_outputs(&dir, p, f, d, e.as_deref(), &mut |_| {}))
            .map_err(|e| run_error(py, e))?;
        Ok(dir.display().to_string())
    }

    /// The design as GeoJSON (WGS 84, one model unit a metre from the default origin), as
    /// `network.geojson`; None without a design.
    fn to_geojson(&self) -> Option<String> {
        self.design.network()?;
        let (mesh, edges) = self.mesh_edges();
        let level = netspec::design::streets::DEFAULT_SOLVE_LEVEL;
        Some(netspec::design::streets::design_geojson(mesh, edges, &self.problem.spec.name, level))
    }

    /// The picture `network.svg` holds (None without a design or an explanation).
    fn svg(&self) -> Option<String> {
        netspec::run::picture(&self.problem, &self.formulation, &self.design, self.explanation.as_deref())
    }

    fn _repr_svg_(&self) -> Option<String> {
        self.svg()
    }

    fn __repr__(&self) -> String {
        format!(
            "Result(status={:?}, objective={}, valid={})",
            self.design.status_line(),
            py_num(self.design.objective()),
            py_bool(self.valid())
        )
    }
}

/// A spec argument: a `Spec`, or the path of a spec file.
fn spec_arg(py: Python<'_>, spec: &Bound<'_, PyAny>) -> PyResult<PySpec> {
    if let Ok(s) = spec.downcast::<PySpec>() {
        return Ok(s.get().clone());
    }
    let path: PathBuf = spec
        .extract()
        .map_err(|_| pyo3::exceptions::PyTypeError::new_err("spec: give a netspec.Spec or the path of a spec file"))?;
    PySpec::load_file(py, &path)
}

/// The settings of a `solve`-shaped call.
struct SolveArgs {
    solver: Option<Method>,
    variant: Option<Variant>,
    time_limit: Option<f64>,
    threads: Option<u32>,
    gap: Option<f64>,
    seed: Option<u64>,
    start: bool,
    explain: bool,
}

/// One solve of a spec, as `netspec solve` makes it but writing nothing; `on_progress` as in
/// [`run_blocking`].
fn solve_spec(py: Python<'_>, spec: &PySpec, a: &SolveArgs, on_progress: Option<PyObject>) -> PyResult<PyResultObj> {
    let t0 = Instant::now();
    let problem = spec.problem(py, a.variant.as_ref(), None)?;
    let req = SolveRequest {
        spec: spec.origin(),
        variant: None,
        flags: Settings {
            method: a.solver,
            time_limit: a.time_limit,
            gap: a.gap,
            threads: a.threads,
            seed: a.seed,
            ..Settings::default()
        },
        explain: a.explain.then_some(netspec::run::ExplainBudget::Remaining),
        start: if a.start { StartChoice::Heuristic } else { StartChoice::Nothing },
        ..SolveRequest::default()
    };
    let problem = Arc::new(problem);
    let shared = problem.clone();
    let solved = run_blocking(py, on_progress, move |interrupt, sink| {
        let req = SolveRequest { interrupt: Some(interrupt), progress: sink, ..req };
        netspec::run::solve_loaded(&shared, &req, t0, None, &mut |_| {})
    })?;
    let (formulation, solved) = solved.map_err(|e| run_error(py, e))?;
    let design = solved.design.ok_or_else(|| NetspecError::new_err("nothing was solved"))?;
    Ok(PyResultObj {
        problem,
        formulation: Arc::new(formulation),
        design: Arc::new(design),
        explanation: solved.explanation.map(Arc::new),
    })
}

/// Designs a network from a spec (a `Spec` or a spec file's path), as `netspec solve` does.
#[pyfunction]
#[pyo3(signature = (spec, solver=None, formulation=None, time_limit=None, threads=None, gap=None, seed=None, start=true, explain=false, on_progress=None))]
#[allow(clippy::too_many_arguments)]
fn solve(
    py: Python<'_>,
    spec: &Bound<'_, PyAny>,
    solver: Option<&str>,
    formulation: Option<&str>,
    time_limit: Option<f64>,
    threads: Option<u32>,
    gap: Option<f64>,
    seed: Option<u64>,
    start: bool,
    explain: bool,
    on_progress: Option<PyObject>,
) -> PyResult<PyResultObj> {
    let spec = spec_arg(py, spec)?;
    let args = SolveArgs {
        solver: parse_method(solver)?,
        variant: parse_variant(formulation)?,
        time_limit,
        threads,
        gap,
        seed,
        start,
        explain,
    };
    solve_spec(py, &spec, &args, on_progress)
}

// ---------------------------------------------------------------------------------------------
// Comparisons

/// The columns of `results.csv`, in order.
#[pyfunction]
fn csv_columns() -> Vec<String> {
    let csv = netspec::compare::csv(&[]);
    csv.lines().next().unwrap_or_default().split(',').map(str::to_string).collect()
}

/// `results.csv` of the records (dicts as `compare` returns them).
#[pyfunction]
fn records_csv(py: Python<'_>, records: &Bound<'_, PyList>) -> PyResult<String> {
    let text: String = py.import("json")?.call_method1("dumps", (records,))?.extract()?;
    let records: Vec<RunRecord> =
        serde_json::from_str(&text).map_err(|e| PyValueError::new_err(format!("records: {e}")))?;
    Ok(netspec::compare::csv(&records))
}

/// A record of a run that has not produced a result (yet): status `failed`.
fn empty_record(instance: &str, label: &str, seed: Option<u64>, limit: f64, settings: RunSettings) -> RunRecord {
    RunRecord {
        instance: instance.to_string(),
        solver: label.to_string(),
        seed,
        edges: None,
        vars: None,
        rows: None,
        nonzeros: None,
        status: "failed".into(),
        objective: None,
        dual_bound: None,
        gap: None,
        nodes: None,
        solver_time: None,
        wall_time: 0.0,
        valid: false,
        killed: false,
        solver_version: None,
        exit_code: None,
        time_limit: Some(limit),
        error: None,
        settings: Some(settings),
        binary_digest: None,
        slurm_state: None,
    }
}

/// The record of one in-process run, with the fields `netspec compare` takes from a run's
/// `result.json`.
fn fill_record(mut rec: RunRecord, r: &PyResultObj) -> RunRecord {
    let (mesh, model_stats, status, version) = match &*r.design {
        Design::Milp(d) => (&d.mesh, &d.model_stats, d.solve.termination.label(), d.solve.solver_version.clone()),
        Design::Search(d) => (&d.mesh, &d.model_stats, d.solve.termination.label(), d.solve.solver_version.clone()),
    };
    let f = r.solve_fields();
    rec.edges = Some(mesh.num_edges());
    rec.vars = Some(model_stats.vars);
    rec.rows = Some(model_stats.rows);
    rec.nonzeros = Some(model_stats.nonzeros);
    rec.status = status;
    rec.objective = f.objective;
    rec.dual_bound = f.bound;
    rec.gap = f.gap;
    rec.nodes = f.nodes;
    rec.solver_time = f.solver_time;
    rec.valid = r.design.validity().valid;
    rec.solver_version = Some(version);
    rec.exit_code = Some(0);
    rec
}

/// Solves every spec (paths, or a manifest such as `models/table1.toml` with `rows` patterns)
/// on every backend (default: every compiled one) and formulation, as `netspec compare` does
/// but in this process, one run after the other. Returns the records (dicts with the fields of
/// `run.json`; `records_frame` makes a DataFrame of the `results.csv` columns). With `out`,
/// writes `results.csv` there. Ctrl-C stops the running solve (recorded as `interrupted`) and
/// skips the rest.
#[pyfunction]
#[pyo3(signature = (specs, solvers=None, formulations=None, time_limit=60.0, seeds=None, threads=None, start=true, rows=None, out=None))]
#[allow(clippy::too_many_arguments)]
fn compare(
    py: Python<'_>,
    specs: &Bound<'_, PyAny>,
    solvers: Option<Vec<String>>,
    formulations: Option<Vec<String>>,
    time_limit: f64,
    seeds: Option<Vec<u64>>,
    threads: Option<u32>,
    start: bool,
    rows: Option<Vec<String>>,
    out: Option<PathBuf>,
) -> PyResult<Vec<PyObject>> {
    if time_limit.is_nan() || time_limit <= 0.0 {
        return Err(PyValueError::new_err(format!(
            "time_limit must be a positive number of seconds, got {time_limit}"
        )));
    }
    let manifest = match specs.extract::<PathBuf>() {
        Ok(path) if path.extension().is_some_and(|e| e == "toml") && !looks_like_spec(&path) => {
            Manifest::load(&path).map_err(err)?
        }
        Ok(path) => Manifest::from_specs(&[path]),
        Err(_) => Manifest::from_specs(&specs.extract::<Vec<PathBuf>>()?),
    };
    let manifest = manifest.select(&rows.unwrap_or_default()).map_err(err)?;
    let solvers: Vec<String> = match solvers {
        Some(s) => s,
        None => SolverKind::compiled()
            .into_iter()
            .filter(|k| *k != SolverKind::GoodLp)
            .map(|k| k.name().to_string())
            .collect(),
    };
    let formulations = formulations.unwrap_or_default();
    let seeds: Vec<Option<u64>> = match seeds {
        Some(s) if !s.is_empty() => s.into_iter().map(Some).collect(),
        _ => vec![None],
    };
    let mut columns: Vec<(String, String, Option<String>)> = Vec::new();
    for s in &solvers {
        if formulations.is_empty() {
            columns.push((s.clone(), s.clone(), None));
        }
        for f in &formulations {
            columns.push((format!("{s}/{f}"), s.clone(), Some(f.clone())));
        }
    }
    let mut records = Vec::new();
    let mut stopped = false;
    for row in &manifest.row {
        let Some(path) = &row.spec else { continue };
        for (label, solver, formulation) in &columns {
            for seed in &seeds {
                if stopped {
                    break;
                }
                let mut settings = RunSettings::new(path, solver, *seed, threads, time_limit);
                settings.start = (!matches!(solver.as_str(), "heuristic" | "anneal"))
                    .then(|| if start { "heuristic" } else { "none" }.to_string());
                let args = SolveArgs {
                    solver: parse_method(Some(solver))?,
                    variant: parse_variant(formulation.as_deref())?,
                    time_limit: Some(time_limit),
                    threads,
                    gap: None,
                    seed: *seed,
                    start,
                    explain: false,
                };
                let t0 = Instant::now();
                let rec = empty_record(&row.name, label, *seed, time_limit, settings);
                let spec = spec_arg(py, &path.clone().into_pyobject(py)?.into_any());
                let mut r = match spec.and_then(|spec| solve_spec(py, &spec, &args, None)) {
                    Ok(res) => {
                        stopped = res.design.interrupted();
                        fill_record(rec, &res)
                    }
                    Err(e) => RunRecord { error: Some(e.to_string()), ..rec },
                };
                r.wall_time = t0.elapsed().as_secs_f64();
                records.push(r);
            }
        }
    }
    if let Some(dir) = &out {
        std::fs::create_dir_all(dir).map_err(err)?;
        netspec::run::write_atomic(&dir.join("results.csv"), netspec::compare::csv(&records).as_bytes())
            .map_err(err)?;
    }
    records.iter().map(|r| to_py(py, r)).collect()
}

/// Whether a `.toml` file is a spec rather than a manifest (a manifest has `[[row]]` tables).
fn looks_like_spec(path: &Path) -> bool {
    std::fs::read_to_string(path).map(|t| !t.lines().any(|l| l.trim() == "[[row]]")).unwrap_or(false)
}

// ---------------------------------------------------------------------------------------------
// Backends, levels, cities

/// Every compiled backend: `{"name", "version", "capabilities": {...}, "summary"}`, as
/// `netspec solvers --json` lists them.
#[pyfunction]
fn solvers(py: Python<'_>) -> PyResult<Vec<PyObject>> {
    netspec::report::solver_list()
        .iter()
        .map(|s| {
            let d = to_py(py, s)?;
            d.bind(py).set_item("summary", s.capability_summary())?;
            Ok(d)
        })
        .collect()
}

/// Lays out a game level from its connectivity graph, as `netspec level` does; returns what
/// it found (`status`: feasible, infeasible or unknown; the layouts; each method's report).
/// With `out`, writes the files `netspec level --out` writes.
#[pyfunction]
#[pyo3(signature = (spec, solver=None, method="both", time_limit=60.0, threads=None, seed=1, count=1, explain=true, out=None))]
#[allow(clippy::too_many_arguments)]
fn level(
    py: Python<'_>,
    spec: PathBuf,
    solver: Option<&str>,
    method: &str,
    time_limit: f64,
    threads: Option<u32>,
    seed: u64,
    count: usize,
    explain: bool,
    out: Option<PathBuf>,
) -> PyResult<PyObject> {
    let solver = match solver {
        Some(s) => parse_kind(s)?,
        None => SolverKind::default_kind().ok_or_else(|| NetspecError::new_err("no backend compiled in"))?,
    };
    let method = match method {
        "anneal" => netspec::levels::Method::Anneal,
        "milp" => netspec::levels::Method::Milp,
        "both" => netspec::levels::Method::Both,
        m => return Err(PyValueError::new_err(format!("method: `{m}` is not one of anneal, milp, both"))),
    };
    if !(time_limit > 0.0 && time_limit.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "time_limit must be a positive number of seconds, got {time_limit}"
        )));
    }
    if count == 0 {
        return Err(PyValueError::new_err("count must be at least 1"));
    }
    let req = netspec::levels::LevelRequest {
        spec,
        method,
        count,
        solver,
        time_limit,
        threads,
        out,
        explain,
        seed,
        export: None,
        seeds: 1,
    };
    let outcome = py.allow_threads(|| netspec::levels::run(&req)).map_err(err)?;
    to_py(py, &outcome)
}

/// Lays out a whole city from a city spec, as `netspec city` does: every sub-region's levels,
/// smoothed and assembled, written into `out` (default `out/<file stem>`; finished levels there
/// are reused unless `fresh`). Returns `city.json` as a dict. Ctrl-C stops the running levels
/// (each keeps its best network) and skips the rest.
#[pyfunction]
#[pyo3(signature = (spec, solver=None, time_limit=None, threads=None, threads_per_solve=None, gap=None, fresh=false, out=None, on_progress=None))]
#[allow(clippy::too_many_arguments)]
fn city(
    py: Python<'_>,
    spec: PathBuf,
    solver: Option<&str>,
    time_limit: Option<f64>,
    threads: Option<u32>,
    threads_per_solve: Option<u32>,
    gap: Option<f64>,
    fresh: bool,
    out: Option<PathBuf>,
    on_progress: Option<PyObject>,
) -> PyResult<PyObject> {
    let city = netspec::urban::CitySpec::load(&spec).map_err(|e| {
        let field = match &e.kind {
            netspec::urban::CitySpecErrorKind::Field { field, .. } => Some(field.clone()),
            _ => None,
        };
        new_spec_error(py, e.to_string(), field, &e.path)
    })?;
    let flags = Settings {
        method: solver.map(parse_kind).transpose()?.map(Method::Milp),
        time_limit,
        gap,
        ..Settings::default()
    };
    let mut opts = netspec::urban::CityRunOptions::resolve(
        &city,
        &spec,
        &flags,
        threads,
        threads_per_solve,
        netspec::spec::DEFAULT_MAX_CELLS,
    )
    .map_err(|s| {
        NetspecError::new_err(format!("{}: {}", s.place.trim_start_matches("--").replace('-', "_"), s.reason))
    })?;
    opts.resume = !fresh;
    let out = out.unwrap_or_else(|| netspec::run::default_out_dir(&spec));
    let result = run_blocking(py, on_progress, move |interrupt, sink| {
        opts.interrupt = Some(interrupt);
        if let Some(sink) = sink {
            opts.observer = Some(Arc::new(move |e: &netspec::urban::CityEvent| {
                if let netspec::urban::CityEvent::LevelProgress { progress, .. } = e {
                    (sink.0)(*progress);
                }
            }));
        }
        netspec::urban::run_city(&city, &out, &opts)
    })?;
    to_py(py, &result.map_err(err)?)
}

/// The version of the netspec library this module was built from.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

/// netspec: network design from functional specifications by integer programming, on
/// interchangeable MILP backends.
#[pymodule]
fn _netspec(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SpecError", py.get_type::<SpecError>())?;
    m.add("NetspecError", py.get_type::<NetspecError>())?;
    m.add_class::<PySpec>()?;
    m.add_class::<PyModel>()?;
    m.add_class::<PyModelResult>()?;
    m.add_class::<PyResultObj>()?;
    m.add_class::<PyDesign>()?;
    m.add_class::<PyProgress>()?;
    m.add_function(wrap_pyfunction!(read_spec, m)?)?;
    m.add_function(wrap_pyfunction!(read_model, m)?)?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(csv_columns, m)?)?;
    m.add_function(wrap_pyfunction!(records_csv, m)?)?;
    m.add_function(wrap_pyfunction!(solvers, m)?)?;
    m.add_function(wrap_pyfunction!(level, m)?)?;
    m.add_function(wrap_pyfunction!(city, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}
