//! The urban methods: `netspec layout`, `field`, `grow` (and its window) and `traffic` as
//! functions, each calling the library entry point the command calls.

use crate::blocking::run_blocking_with;
use crate::drawn::drawn;
use crate::errors::{err_chain, new_spec_error, setting_error, to_py};
use netspec::grow::{GrowError, GrowRequest, Source};
use netspec::layout::field::FieldMethod;
use netspec::layout::run::{LayoutError, LayoutRequest};
use netspec::layout::split::Selection;
use netspec::traffic::network::{LoadOptions, SiteRegion};
use netspec::traffic::run::{TrafficRequest, TrafficRunError};
use netspec::traffic::DemandSettings;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;

fn layout_error(e: LayoutError) -> PyErr {
    match e {
        LayoutError::Setting(s) => setting_error(&s),
        e => err_chain(&e),
    }
}

fn grow_error(py: Python<'_>, e: GrowError) -> PyErr {
    match e {
        GrowError::Field { ref path, ref field, .. } => new_spec_error(py, e.to_string(), Some(field.clone()), path),
        GrowError::NotAContext { path } => PyValueError::new_err(format!(
            "context: {} is a directory: give a context file to grow, or a window to window a grown network",
            path.display()
        )),
        e => err_chain(&e),
    }
}

fn parse_field(name: &str, value: &str) -> PyResult<FieldMethod> {
    value.parse().map_err(|e| PyValueError::new_err(format!("{name}: {e}")))
}

/// Lays a region (a TOML region or a GeoJSON site) out by domain splitting, as `netspec layout`
/// does: `variations` layouts (the first by `mode`, `best` or `random`; the others drawn by
/// quality with seeds `seed + 1`, …), each checked independently. Returns one dict per layout,
/// what its `layout.json` holds (`violations` empty when valid). With `out`, writes the files
/// `netspec layout --out` writes (variation k ≥ 2 in `variation-k/`). `from_layout` and
/// `relayout` lay one part of an earlier layout out again. `on_progress(variation, share)` hears
/// which variation runs (from 0) and the share of its area settled; Ctrl-C stops before the
/// next variation and returns the layouts made.
#[pyfunction]
#[pyo3(signature = (region, out=None, seed=None, variations=1, field="distance", mode="best", optimise=0, from_layout=None, relayout=None, on_progress=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn layout(
    py: Python<'_>,
    region: PathBuf,
    out: Option<PathBuf>,
    seed: Option<u64>,
    variations: usize,
    field: &str,
    mode: &str,
    optimise: usize,
    from_layout: Option<PathBuf>,
    relayout: Option<String>,
    on_progress: Option<PyObject>,
) -> PyResult<Vec<PyObject>> {
    let field = parse_field("field", field)?;
    let selection: Selection = mode.parse().map_err(|e| PyValueError::new_err(format!("mode: {e}")))?;
    let relayout = match (from_layout, relayout) {
        (Some(f), Some(p)) => Some((f, p)),
        (None, None) => None,
        (Some(_), None) => {
            return Err(PyValueError::new_err("relayout: give the part to lay out again with from_layout"))
        }
        (None, Some(_)) => {
            return Err(PyValueError::new_err("from_layout: give the layout.json to relayout a part of"))
        }
    };
    let region_path = region.clone();
    let mut req =
        LayoutRequest { region, field, selection, seed, variations, optimise, out, relayout, interrupt: None };
    req.validate().map_err(|s| setting_error(&s))?;
    let layouts = run_blocking_with(
        py,
        on_progress,
        |py, cb, (k, f): (usize, f64)| cb.call1(py, (k, f)).map(drop),
        move |interrupt, report| {
            req.interrupt = Some(interrupt);
            netspec::layout::run::run(&req, &mut |k, f| {
                if let Some(r) = &report {
                    r((k, f));
                }
            })
        },
    )?
    .map_err(layout_error)?;
    let region = netspec::layout::region::read_region(&region_path).map_err(|e| err_chain(&e))?;
    layouts
        .iter()
        .map(|l| {
            let svg = netspec::render::layout::layout_svg(&netspec::layout::run::scene(&region, l));
            drawn(py, to_py(py, l)?, svg)
        })
        .collect()
}

/// The cross field of a region, as `netspec field` makes it: writes `field.json`, `field.svg`
/// and `field.png` into `out` and returns what `field.json` holds (`method`, `vertices`,
/// `singularities`, `field`). `method` is `smooth` or `distance`; `h` the triangle size in
/// metres (default: a third of the parcel depth). The GIL is released meanwhile (no interrupt:
/// a field takes seconds).
#[pyfunction]
#[pyo3(signature = (region, out, method="distance", h=None))]
pub(crate) fn field(py: Python<'_>, region: PathBuf, out: PathBuf, method: &str, h: Option<f64>) -> PyResult<PyObject> {
    let method = parse_field("method", method)?;
    netspec::layout::run::check_field_h(h).map_err(|s| setting_error(&s))?;
    let f = py.allow_threads(|| netspec::layout::run::field_command(&region, method, h, &out)).map_err(layout_error)?;
    to_py(py, &netspec::layout::field::field_json(&f))
}

/// Grows a road network from a context file, as `netspec grow` does, into `out` (`network.json`,
/// `series.csv`, the pictures; `every`, `all_streets` and `gallery` as the command's flags).
/// With `window` (metres: x0, y0, x1, y1) also writes the window's `city.toml` and
/// `trade.json`; with a grown output directory as `context`, only windows it. Returns
/// `{"summary": ..., "window": ...}`: the run's summary (seed, the last step's measures,
/// seconds, files, the independent check's `violations`; None when only windowing) and the
/// window's (None without one, or when the grown network failed its check, as the command).
/// `on_progress(step, steps)` hears each step; Ctrl-C stops after the current step and the
/// network grown so far is checked and written.
#[pyfunction]
#[pyo3(signature = (context, out, seed=None, steps=None, every=None, all_streets=false, gallery=None, window=None, on_progress=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn grow(
    py: Python<'_>,
    context: PathBuf,
    out: PathBuf,
    seed: Option<u64>,
    steps: Option<u32>,
    every: Option<u32>,
    all_streets: bool,
    gallery: Option<u32>,
    window: Option<[f64; 4]>,
    on_progress: Option<PyObject>,
) -> PyResult<PyObject> {
    if every == Some(0) {
        return Err(PyValueError::new_err("every: must be at least 1"));
    }
    if gallery == Some(0) {
        return Err(PyValueError::new_err("gallery: must be at least 1"));
    }
    let mut req = GrowRequest { context, out, seed, steps, every, all_streets, gallery, interrupt: None };
    let (grown, summary) = match req.source(window).map_err(|e| grow_error(py, e))? {
        Source::Grown(dir) => (Some(dir), None),
        Source::Context => {
            let out = req.out.clone();
            let summary = run_blocking_with(
                py,
                on_progress,
                |py, cb, (k, n): (u32, u32)| cb.call1(py, (k, n)).map(drop),
                |interrupt, report| {
                    req.interrupt = Some(interrupt);
                    netspec::grow::run(&req, &mut |k, n| {
                        if let Some(r) = &report {
                            r((k, n));
                        }
                    })
                },
            )?
            .map_err(|e| grow_error(py, e))?;
            // A network that fails its check is not windowed (the command exits with 3).
            (summary.violations.is_empty().then_some(out), Some(summary))
        }
    };
    let windowed = match (window, grown) {
        (Some(w), Some(dir)) => Some(
            py.allow_threads(|| netspec::grow::window::write(&dir, w, &req.window_name(), &req.out))
                .map_err(|e| grow_error(py, e))?,
        ),
        _ => None,
    };
    let d = pyo3::types::PyDict::new(py);
    d.set_item("summary", summary.as_ref().map(|s| to_py(py, s)).transpose()?)?;
    d.set_item("window", windowed.as_ref().map(|w| to_py(py, w)).transpose()?)?;
    // The network as `network.svg` draws it (written by a grow; a windowed directory has its own).
    let grown_dir = if summary.is_some() { &req.out } else { &req.context };
    match std::fs::read_to_string(grown_dir.join("network.svg")) {
        Ok(svg) => drawn(py, d.into_any().unbind(), svg),
        Err(_) => Ok(d.into_any().unbind()),
    }
}

/// Evaluates designs in SUMO under the same demand, as `netspec traffic` does: `netspec city`,
/// `solve`, `layout` or `grow` outputs (directories, or `result.json` files). Writes into `out`
/// (one design's files there; several designs' in sub-directories named by `labels`, with
/// `comparison.md`, `comparison.json` and its picture) and returns what `traffic.json` holds
/// for one design, or what `comparison.json` holds (`{"designs": [{"label", "report"}]}`) for
/// several. The keyword arguments are the command's flags; SUMO is found as the command finds
/// it (`sumo_home`, `$SUMO_HOME`, the copy `scripts/setup.sh sumo` installs, `PATH`). The GIL is
/// released meanwhile; there is no interrupt hook (SUMO runs as child processes, stopped by
/// `time_limit`).
#[pyfunction]
#[pyo3(signature = (designs, out=PathBuf::from("out/traffic"), labels=None, duration=3600.0, through_rate=300.0, local_rate=600.0, seed=1, metres_per_unit=None, level=None, window=None, region=None, trade=None, trade_rate=300.0, sumo_home=None, time_limit=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn traffic(
    py: Python<'_>,
    designs: Vec<PathBuf>,
    out: PathBuf,
    labels: Option<Vec<String>>,
    duration: f64,
    through_rate: f64,
    local_rate: f64,
    seed: u64,
    metres_per_unit: Option<f64>,
    level: Option<u8>,
    window: Option<[f64; 4]>,
    region: Option<PathBuf>,
    trade: Option<PathBuf>,
    trade_rate: f64,
    sumo_home: Option<PathBuf>,
    time_limit: Option<f64>,
) -> PyResult<PyObject> {
    if designs.is_empty() {
        return Err(PyValueError::new_err("designs: give at least one"));
    }
    if level.is_some_and(|l| !(1..=4).contains(&l)) {
        return Err(PyValueError::new_err(format!("level: must be 1 to 4, got {}", level.unwrap_or_default())));
    }
    let trade = match &trade {
        Some(f) => netspec::traffic::demand::TradeFile::load(f).map_err(|e| err_chain(&e))?.flows,
        None => Vec::new(),
    };
    let demand = DemandSettings {
        duration,
        through_per_hour: through_rate,
        local_per_hour: local_rate,
        seed,
        trade_per_hour: trade_rate,
        trade,
    };
    let region = region.as_deref().map(SiteRegion::load).transpose().map_err(|e| err_chain(&e))?;
    let command = format!(
        "netspec.traffic({})",
        designs.iter().map(|d| format!("{:?}", d.display().to_string())).collect::<Vec<_>>().join(", ")
    );
    let req = TrafficRequest {
        designs,
        labels: labels.unwrap_or_default(),
        demand,
        load: LoadOptions { metres_per_unit, level, window, region },
        sumo_home,
        out,
        time_limit,
        command,
    };
    let done = py.allow_threads(|| netspec::traffic::run::run(&req, &mut |_| {})).map_err(|e| match e {
        TrafficRunError::Setting(s) => setting_error(&s),
        e => err_chain(&e),
    })?;
    match done.as_slice() {
        [one] => to_py(py, &one.report),
        _ => to_py(py, &netspec::traffic::run::comparison_json(&done)),
    }
}
