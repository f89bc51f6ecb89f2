//! Backends, game levels and cities.

use crate::blocking::run_blocking;
use crate::errors::{err, new_spec_error, parse_kind, to_py, NetspecError};
use netspec::pipeline::settings::Settings;
use netspec::pipeline::Method;
use netspec::solvers::SolverKind;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;

/// Every compiled backend: `{"name", "version", "capabilities": {...}, "summary"}`, as
/// `netspec solvers --json` lists them.
#[pyfunction]
pub(crate) fn solvers(py: Python<'_>) -> PyResult<Vec<PyObject>> {
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
pub(crate) fn level(
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
pub(crate) fn city(
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
