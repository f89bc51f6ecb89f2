//! A solve of a spec: its result, its design, its picture, and `solve` itself.

use crate::blocking::run_blocking;
use crate::errors::{parse_method, parse_variant, py_bool, py_num, run_error, to_py, NetspecError};
use crate::spec::PySpec;
use netspec::formulations::Formulation;
use netspec::pipeline::settings::Settings;
use netspec::pipeline::Method;
use netspec::run::{Design, SolveRequest, StartChoice};
use netspec::spec::{Problem, Variant};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// A designed network: the active edges (vertex pairs), the vertices' coordinates and the
/// metrics.
#[pyclass(module = "netspec", name = "Design", frozen, get_all)]
pub(crate) struct PyDesign {
    /// Active edges as (vertex, vertex), existing edges included, in edge order.
    pub(crate) edges: Vec<(u32, u32)>,
    /// Every mesh vertex's (x, y).
    pub(crate) points: Vec<(f64, f64)>,
    /// The network's metrics (length, dead ends, junctions, travel, …).
    pub(crate) metrics: PyObject,
}

#[pymethods]
impl PyDesign {
    fn __repr__(&self) -> String {
        format!("Design(edges={})", self.edges.len())
    }
}

/// What `solve` found: the checked design (or why there is none).
#[pyclass(module = "netspec", name = "Result", frozen)]
pub(crate) struct PyResultObj {
    pub(crate) problem: Arc<Problem>,
    pub(crate) formulation: Arc<Formulation>,
    pub(crate) design: Arc<Design>,
    pub(crate) explanation: Option<Arc<netspec::explain::Explanation>>,
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
        self.design.objective()
    }

    /// The proven bound (None for the searches).
    #[getter]
    fn bound(&self) -> Option<f64> {
        self.design.outcome().dual_bound
    }

    /// The relative gap.
    #[getter]
    fn gap(&self) -> Option<f64> {
        self.design.outcome().gap
    }

    /// Wall time of the solve, seconds.
    #[getter]
    fn time(&self) -> f64 {
        self.design.outcome().wall_time
    }

    /// The backend's own time, seconds.
    #[getter]
    fn solver_time(&self) -> Option<f64> {
        self.design.outcome().solver_time
    }

    /// Branch-and-bound nodes.
    #[getter]
    fn nodes(&self) -> Option<u64> {
        self.design.outcome().nodes
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
        let d = &self.design;
        let metrics = to_py(py, &d.metrics())?;
        Ok(Some(PyDesign {
            edges: d.active_edges.iter().map(|&[a, b]| (a, b)).collect(),
            points: d.mesh.positions().iter().map(|p| (p[0], p[1])).collect(),
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
        to_py(py, &*self.design)
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
    fn to_geojson(&self) -> PyResult<Option<String>> {
        if self.design.network().is_none() {
            return Ok(None);
        }
        let d = &self.design;
        let level = netspec::design::streets::DEFAULT_SOLVE_LEVEL;
        netspec::design::streets::design_geojson(&d.mesh, &d.active_edges, &self.problem.spec.name, level)
            .map(Some)
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
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
pub(crate) fn spec_arg(py: Python<'_>, spec: &Bound<'_, PyAny>) -> PyResult<PySpec> {
    if let Ok(s) = spec.downcast::<PySpec>() {
        return Ok(s.get().clone());
    }
    let path: PathBuf = spec
        .extract()
        .map_err(|_| pyo3::exceptions::PyTypeError::new_err("spec: give a netspec.Spec or the path of a spec file"))?;
    PySpec::load_file(py, &path)
}

/// The settings of a `solve`-shaped call.
pub(crate) struct SolveArgs {
    pub(crate) solver: Option<Method>,
    pub(crate) variant: Option<Variant>,
    pub(crate) time_limit: Option<f64>,
    pub(crate) threads: Option<u32>,
    pub(crate) gap: Option<f64>,
    pub(crate) seed: Option<u64>,
    pub(crate) start: bool,
    pub(crate) explain: bool,
}

/// One solve of a spec, as `netspec solve` makes it but writing nothing; `on_progress` as in
/// [`run_blocking`].
pub(crate) fn solve_spec(
    py: Python<'_>,
    spec: &PySpec,
    a: &SolveArgs,
    on_progress: Option<PyObject>,
) -> PyResult<PyResultObj> {
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
pub(crate) fn solve(
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
