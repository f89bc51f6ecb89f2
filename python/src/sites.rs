//! Real sites and street statistics: `netspec site` and `netspec stats` as functions.

use crate::errors::{err, to_py};
use netspec::osm::areas::AreaClass;
use netspec::osm::site::{Area, SiteRequest};
use netspec::traffic::network::{LoadOptions, SiteRegion};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;

/// The major classes `netspec site` takes by default.
const MAJOR: [&str; 4] = ["motorway", "trunk", "primary", "secondary"];

/// A real site from an OpenStreetMap extract (`.osm.pbf` or `.osm`), as `netspec site` makes
/// it: `out/site.geojson`, `out/map/streets.geojson` (and `grow.toml`, `city.toml` when asked).
/// The region is a `bbox` (west, south, east, north; WGS 84) or a GeoJSON `polygon` file.
/// Returns what was made: areas, holes, roads, streets, the origin and the files written.
#[pyfunction]
#[pyo3(signature = (extract, out, bbox=None, polygon=None, holes=None, major=None, service=false, grow=false, city=false, largest=false, name=None, exclude=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn site(
    py: Python<'_>,
    extract: PathBuf,
    out: PathBuf,
    bbox: Option<[f64; 4]>,
    polygon: Option<PathBuf>,
    holes: Option<Vec<String>>,
    major: Option<Vec<String>>,
    service: bool,
    grow: bool,
    city: bool,
    largest: bool,
    name: Option<String>,
    exclude: Option<Vec<i64>>,
) -> PyResult<PyObject> {
    let area = match (bbox, polygon) {
        (Some(b), None) => Area::Bbox(b),
        (None, Some(p)) => Area::Polygon(p),
        _ => return Err(PyValueError::new_err("give the region as exactly one of bbox or polygon")),
    };
    let holes = holes
        .unwrap_or_else(|| vec!["water".into()])
        .iter()
        .map(|h| {
            AreaClass::parse(h).ok_or_else(|| PyValueError::new_err(format!("holes: `{h}` is not water, park or rail")))
        })
        .collect::<PyResult<_>>()?;
    let req = SiteRequest {
        extract,
        area,
        out,
        holes,
        major: major.unwrap_or_else(|| MAJOR.iter().map(|s| s.to_string()).collect()),
        service,
        grow,
        city,
        largest,
        name,
        exclude: exclude.unwrap_or_default().into_iter().collect(),
    };
    let summary = py.allow_threads(|| netspec::osm::site::run(&req)).map_err(err)?;
    to_py(py, &summary)
}

/// Street statistics of designs (layout, grow, city or solve outputs, a site's `map/`, a GeoJSON
/// of streets) as `netspec stats --json` gives them, one dict per design: OSMnx's statistics,
/// orientation, blocks, parcels, and the distance to the reference (the first site `map/` given,
/// or `reference`). With `region` (a `site.geojson`), every design is judged on that site; with
/// `out`, `stats.json` and the pictures are written there.
#[pyfunction]
#[pyo3(signature = (designs, labels=None, region=None, reference=None, clean_int_tol=netspec::stats::CLEAN_INT_TOL, metres_per_unit=None, window=None, out=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn stats(
    py: Python<'_>,
    designs: Vec<PathBuf>,
    labels: Option<Vec<String>>,
    region: Option<PathBuf>,
    reference: Option<String>,
    clean_int_tol: f64,
    metres_per_unit: Option<f64>,
    window: Option<[f64; 4]>,
    out: Option<PathBuf>,
) -> PyResult<Vec<PyObject>> {
    if !(clean_int_tol >= 0.0 && clean_int_tol.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "clean_int_tol must be a non-negative number of metres, got {clean_int_tol}"
        )));
    }
    if designs.is_empty() {
        return Err(PyValueError::new_err("designs: give at least one"));
    }
    let region = region.as_deref().map(SiteRegion::load).transpose().map_err(err)?;
    let req = netspec::measure::StatsRequest {
        designs,
        labels: labels.unwrap_or_default(),
        load: LoadOptions { metres_per_unit, level: None, window, region },
        settings: netspec::stats::Settings { clean_int_tol },
        reference,
    };
    let measured = py
        .allow_threads(|| -> Result<_, netspec::measure::MeasureError> {
            let designs = netspec::measure::run(&req)?;
            if let Some(dir) = &out {
                netspec::measure::write(dir, &designs)?;
            }
            Ok(designs)
        })
        .map_err(err)?;
    measured.iter().map(|d| to_py(py, d)).collect()
}
