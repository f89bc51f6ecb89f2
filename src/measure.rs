//! `netspec stats`: the street statistics ([`crate::stats`]) of every design netspec makes or
//! reads — a layout, a grown map, a city, a solve, the real streets of a site (`map/`), a GeoJSON
//! of streets — on one region, each beside the real streets of the site: its distance to them
//! ([`crate::stats::distance`]), and the pictures (the designs side by side at one scale with
//! their orientation roses).

use crate::geometry::Polygon;
use crate::render::streets::{panels_svg, rose_svg, StreetPanel};
use crate::stats::{self, Distance, StreetStats};
use crate::traffic::network::{load_whole, LoadOptions, RoadNetwork};
use crate::traffic::TrafficError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What `netspec stats` is asked for.
#[derive(Clone, Debug, Default)]
pub struct StatsRequest {
    /// The designs.
    pub designs: Vec<PathBuf>,
    /// Their labels (default: directory names).
    pub labels: Vec<String>,
    /// How to read them (`region`: the site every design is judged on).
    pub load: LoadOptions,
    /// The statistics' settings.
    pub settings: stats::Settings,
    /// The label of the reference design the distances are taken to (default: the first real
    /// map, a `netspec site` `map/`).
    pub reference: Option<String>,
}

/// Yang et al.'s parcel measures, where a design has parcels (a layout's `metrics`, a city's
/// `layout_metrics`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParcelMeasures {
    /// Parcels.
    pub parcels: usize,
    /// Mean deviation of parcel corners from 90° (degrees).
    pub corner_deviation_mean: f64,
    /// Mean ratio of a parcel's minimum rotated rectangle to its area.
    pub area_ratio_mean: f64,
    /// Undesirable parcels.
    pub undesirable: usize,
}

/// One design measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DesignStats {
    /// Its label.
    pub label: String,
    /// The path given.
    pub path: String,
    /// What made it (`layout`, `grow`, `city`, `solve`, `streets`).
    pub kind: String,
    /// The statistics.
    pub stats: StreetStats,
    /// Parcel measures, where it has parcels.
    pub parcels: Option<ParcelMeasures>,
    /// Its distance to the reference, when there is one (and it is not the reference).
    pub distance: Option<Distance>,
    /// The reference's label.
    pub reference: Option<String>,
    /// The network as measured (for pictures).
    #[serde(skip)]
    pub network: Option<(RoadNetwork, Option<Polygon>)>,
}

/// Why the statistics could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum MeasureError {
    /// A design could not be read.
    #[error(transparent)]
    Design(#[from] TrafficError),
    /// A file could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A picture could not be made.
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// The reference is not one of the designs.
    #[error("--reference {0}: no design has that label")]
    Reference(String),
}

/// A label from a design's path: its directory name (`map` for a site's map).
pub fn default_label(p: &Path) -> String {
    let dir = if p.is_file() { p.parent().unwrap_or(p) } else { p };
    dir.file_name().map_or_else(|| "design".to_string(), |n| n.to_string_lossy().into_owned())
}

/// The statistics' input: a network's nodes and streets.
pub fn street_network(net: &RoadNetwork) -> stats::Network {
    stats::Network {
        nodes: net.nodes.iter().map(|n| n.pos).collect(),
        edges: net
            .edges
            .iter()
            .map(|e| stats::Edge { a: e.a, b: e.b, shape: e.shape.clone(), level: e.level, oneway: e.oneway })
            .collect(),
    }
}

/// Parcel measures of a layout or city output directory.
fn parcels(path: &Path) -> Option<ParcelMeasures> {
    let (file, key) = if path.join("layout.json").is_file() {
        (path.join("layout.json"), "metrics")
    } else if path.join("city.json").is_file() {
        (path.join("city.json"), "layout_metrics")
    } else {
        return None;
    };
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(file).ok()?).ok()?;
    serde_json::from_value(v.get(key)?.clone()).ok()
}

/// Measures every design (see the module documentation). Labels are made distinct.
pub fn run(req: &StatsRequest) -> Result<Vec<DesignStats>, MeasureError> {
    let mut out: Vec<DesignStats> = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    for (i, path) in req.designs.iter().enumerate() {
        let mut label = req.labels.get(i).cloned().unwrap_or_else(|| default_label(path));
        if !seen.insert(label.clone()) {
            label = format!("{label}-{i}");
            seen.insert(label.clone());
        }
        let (net, polygon) = load_whole(path, &req.load)?;
        let polygon = polygon.or_else(|| Polygon::new(net.region.boundary.clone(), vec![]).ok());
        let st = stats::measure(&street_network(&net), polygon.as_ref(), &req.settings);
        out.push(DesignStats {
            label,
            path: path.display().to_string(),
            kind: net.source.kind.clone(),
            stats: st,
            parcels: parcels(path),
            distance: None,
            reference: None,
            network: Some((net, polygon)),
        });
    }
    let reference = match &req.reference {
        Some(r) => Some(out.iter().position(|d| &d.label == r).ok_or_else(|| MeasureError::Reference(r.clone()))?),
        None => out.iter().position(|d| d.kind == "streets" && d.path_is_map()),
    };
    if let Some(k) = reference {
        let (label, reference) = (out[k].label.clone(), out[k].stats.clone());
        for (i, d) in out.iter_mut().enumerate() {
            if i != k {
                d.distance = Some(stats::distance(&d.stats, &reference));
                d.reference = Some(label.clone());
            }
        }
    }
    Ok(out)
}

impl DesignStats {
    /// Whether the design is a site's map (a directory with `streets.geojson`).
    fn path_is_map(&self) -> bool {
        Path::new(&self.path).join("streets.geojson").is_file()
    }
}

fn write_file(path: &Path, bytes: &[u8]) -> Result<(), MeasureError> {
    std::fs::write(path, bytes).map_err(|source| MeasureError::Io { path: path.to_path_buf(), source })
}

/// A file name made of a label.
fn stem(label: &str) -> String {
    label.chars().map(|c| if c.is_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect()
}

/// Writes `stats.json`, `orientation-<label>.svg/png` per design and `comparison.svg/png` (the
/// designs side by side at one scale, each with its rose) into `dir`; returns the files.
pub fn write(dir: &Path, designs: &[DesignStats]) -> Result<Vec<PathBuf>, MeasureError> {
    std::fs::create_dir_all(dir).map_err(|source| MeasureError::Io { path: dir.to_path_buf(), source })?;
    let mut files = Vec::new();
    let json = serde_json::json!({ "designs": designs });
    let path = dir.join("stats.json");
    write_file(&path, (serde_json::to_string_pretty(&json).expect("plain data") + "\n").as_bytes())?;
    files.push(path);
    let mut panels = Vec::new();
    let mut corners: Vec<[f64; 2]> = Vec::new();
    for d in designs {
        let svg = rose_svg(&d.label, &d.stats.orientation_bins);
        for (ext, bytes) in [("svg", svg.clone().into_bytes()), ("png", crate::render::png(&svg)?)] {
            let path = dir.join(format!("orientation-{}.{ext}", stem(&d.label)));
            write_file(&path, &bytes)?;
            files.push(path);
        }
        if let Some((net, polygon)) = &d.network {
            panels.push(panel(d, net, polygon.as_ref()));
            let ring = polygon.as_ref().map_or(net.region.boundary.as_slice(), |p| p.outer());
            corners.extend(crate::geometry::polygon::bounds(ring));
        }
    }
    if !panels.is_empty() {
        let [lo, hi] = crate::geometry::polygon::bounds(&corners);
        let svg = panels_svg(&panels, (lo, hi), 300.0);
        for (ext, bytes) in [("svg", svg.clone().into_bytes()), ("png", crate::render::png(&svg)?)] {
            let path = dir.join(format!("comparison.{ext}"));
            write_file(&path, &bytes)?;
            files.push(path);
        }
    }
    Ok(files)
}

/// A design's panel: its streets inside its region and the numbers a reader compares first.
fn panel(d: &DesignStats, net: &RoadNetwork, polygon: Option<&Polygon>) -> StreetPanel {
    let s = &d.stats;
    let f = |v: Option<f64>, k: f64| v.map_or("–".to_string(), |x| format!("{:.1}", x * k));
    let mut lines = vec![
        format!(
            "{} km/km² · {} intersections/km²",
            f(s.street_density_km, 1e-3),
            f(s.clean_intersection_density_km, 1.0)
        ),
        format!(
            "{} dead-ends/km² · φ {}",
            f(s.dead_end_density_km, 1.0),
            s.orientation_order.map_or("–".into(), |o| format!("{o:.2}"))
        ),
    ];
    if let Some(dist) = &d.distance {
        lines.push(format!(
            "distance to {}: {}",
            d.reference.as_deref().unwrap_or("map"),
            dist.mean.map_or("–".into(), |m| format!("{m:.2}"))
        ));
    }
    let streets = net
        .edges
        .iter()
        .flat_map(|e| {
            let pieces = match polygon {
                Some(p) => p.clip_polyline(&e.shape, stats::BOUNDARY_TOL),
                None => vec![e.shape.clone()],
            };
            pieces.into_iter().map(move |l| (e.level, l))
        })
        .collect();
    let region = match polygon {
        Some(p) => p.rings().map(<[_]>::to_vec).collect(),
        None => vec![net.region.boundary.clone()],
    };
    StreetPanel { title: d.label.clone(), lines, region, streets, bins: s.orientation_bins.clone() }
}

/// The table `netspec stats` prints: one row per design.
pub fn table(designs: &[DesignStats]) -> String {
    let f = |v: Option<f64>, k: f64, d: usize| v.map_or("–".to_string(), |x| format!("{:.*}", d, x * k));
    let mut out = String::from(
        "| design | nodes | street km/km² | intersections /km² (clean) | dead-ends /km² | 4-way share | circuity | entropy (nats) | order φ | blocks /km² | block perimeter (m) | distance to the map |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for d in designs {
        let s = &d.stats;
        out += &format!(
            "| {} | {} | {} | {} ({}) | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            d.label,
            s.n,
            f(s.street_density_km, 1e-3, 1),
            f(s.intersection_density_km, 1.0, 1),
            f(s.clean_intersection_density_km, 1.0, 1),
            f(s.dead_end_density_km, 1.0, 1),
            f(s.four_way_proportion(), 1.0, 2),
            f(s.circuity_avg, 1.0, 3),
            f(s.orientation_entropy, 1.0, 2),
            f(s.orientation_order, 1.0, 2),
            f(s.blocks_per_km2, 1.0, 1),
            f(s.block_perimeter_mean, 1.0, 0),
            match (&d.distance, &d.reference) {
                (Some(dist), _) => f(dist.mean, 1.0, 2),
                (None, None) if designs.iter().any(|o| o.reference.as_deref() == Some(&d.label)) => "reference".into(),
                _ => "–".into(),
            }
        );
    }
    out
}
