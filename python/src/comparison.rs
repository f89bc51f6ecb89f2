//! Comparisons: backends on specs, in process, with the records and CSV of `netspec compare`.

use crate::errors::{err, parse_method, parse_variant, to_py};
use crate::result::{solve_spec, spec_arg, PyResultObj, SolveArgs};
use netspec::compare::{Manifest, RunRecord, RunSettings};
use netspec::solvers::SolverKind;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyList;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The columns of `results.csv`, in order.
#[pyfunction]
pub(crate) fn csv_columns() -> Vec<String> {
    let csv = netspec::compare::csv(&[]);
    csv.lines().next().unwrap_or_default().split(',').map(str::to_string).collect()
}

/// `results.csv` of the records (dicts as `compare` returns them).
#[pyfunction]
pub(crate) fn records_csv(py: Python<'_>, records: &Bound<'_, PyList>) -> PyResult<String> {
    let text: String = py.import("json")?.call_method1("dumps", (records,))?.extract()?;
    let records: Vec<RunRecord> =
        serde_json::from_str(&text).map_err(|e| PyValueError::new_err(format!("records: {e}")))?;
    Ok(netspec::compare::csv(&records))
}

/// A record of a run that has not produced a result (yet): status `failed`.
pub(crate) fn empty_record(
    instance: &str,
    label: &str,
    seed: Option<u64>,
    limit: f64,
    settings: RunSettings,
) -> RunRecord {
    RunRecord { instance: instance.to_string(), settings: Some(settings), ..RunRecord::failed(label, seed, limit) }
}

/// The record of one in-process run, with the fields `netspec compare` takes from a run's
/// `result.json`.
pub(crate) fn fill_record(mut rec: RunRecord, r: &PyResultObj) -> RunRecord {
    let d = &r.design;
    rec.take_design(d.mesh.num_edges(), &d.model_stats, d.outcome(), d.validity().valid);
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
pub(crate) fn compare(
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
pub(crate) fn looks_like_spec(path: &Path) -> bool {
    std::fs::read_to_string(path).map(|t| !t.lines().any(|l| l.trim() == "[[row]]")).unwrap_or(false)
}
