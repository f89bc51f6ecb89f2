//! The input of `netspec layout` and `netspec field`: a region (outer polygon, holes, optional
//! major roads) with the street widths, the parcel size and a seed, from TOML (local metres) or
//! GeoJSON (WGS 84, projected to local metres by [`crate::geometry::site`]).

use super::settings::{self, BlockSize, BlockToml, Fit, FitToml, Weights};
use super::template::{library, Template, TemplateError};
use super::zone::{self, Zone, ZoneProblem};
use crate::geometry::polygon::{Polygon, PolygonError, Ring};
use crate::geometry::site::{self, Projection, SiteError};
use crate::geometry::P;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The parcel size every template and the parceller aim for (paper §8: 30 m deep, 18 m wide).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParcelSize {
    /// Depth from the street (metres).
    #[serde(default = "default_depth")]
    pub depth: f64,
    /// Frontage along the street (metres).
    #[serde(default = "default_width")]
    pub width: f64,
}

impl Default for ParcelSize {
    fn default() -> Self {
        ParcelSize { depth: default_depth(), width: default_width() }
    }
}

fn default_depth() -> f64 {
    30.0
}
fn default_width() -> f64 {
    18.0
}
fn default_widths() -> Vec<f64> {
    vec![15.0]
}

/// Whether the region's own boundary is a street (half of it inside the region) or a plain edge
/// (parcels reach it, without street access there).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Boundary {
    /// A street of level 0 runs along the boundary.
    #[default]
    Street,
    /// No street along the boundary.
    None,
}

/// The TOML form of a region (also the settings a GeoJSON region's properties may carry).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RegionToml {
    #[serde(default)]
    name: Option<String>,
    outer: Vec<[f64; 2]>,
    #[serde(default)]
    holes: Vec<Vec<[f64; 2]>>,
    #[serde(default)]
    roads: Vec<Vec<[f64; 2]>>,
    #[serde(default)]
    seed: u64,
    #[serde(default)]
    boundary: Boundary,
    #[serde(default = "default_widths")]
    street_widths: Vec<f64>,
    #[serde(default)]
    parcel: ParcelSize,
    #[serde(default)]
    origin: Option<[f64; 2]>,
    #[serde(default)]
    templates: Option<TemplatesToml>,
    #[serde(default)]
    block: BlockToml,
    #[serde(default)]
    fit: FitToml,
    #[serde(default)]
    weights: Weights,
    #[serde(default)]
    zone: Vec<ZoneToml>,
}

/// `[[zone]]`: land marked for a use.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ZoneToml {
    polygon: Vec<[f64; 2]>,
    #[serde(rename = "use")]
    use_: String,
}

/// `[templates]`: a directory of the user's template files (relative to the region file),
/// whether the built-in ones are used, and whether a part is matched against them before it is
/// cut (`first`, the paper's control loop) or only once it is small enough for a block.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TemplatesToml {
    #[serde(default)]
    dir: Option<PathBuf>,
    #[serde(default = "yes")]
    builtin: bool,
    #[serde(default = "yes")]
    first: bool,
    #[serde(default)]
    counts: std::collections::BTreeMap<String, CountToml>,
}

/// `[templates.counts] NAME = { min, max, probability }`: a template's counts and probability for
/// this region, over its file's.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CountToml {
    #[serde(default)]
    min: Option<usize>,
    #[serde(default)]
    max: Option<usize>,
    #[serde(default)]
    probability: Option<f64>,
}

fn yes() -> bool {
    true
}

/// A region, checked.
#[derive(Clone, Debug)]
pub struct Region {
    /// A name for pictures and records (the file stem unless given).
    pub name: String,
    /// The region, in metres.
    pub polygon: Polygon,
    /// Major roads, clipped to the region (level 0 streets).
    pub roads: Vec<Vec<P>>,
    /// Street width per level (level 0: major roads and the boundary street; a level beyond the
    /// list takes its last entry).
    pub street_widths: Vec<f64>,
    /// The boundary's kind.
    pub boundary: Boundary,
    /// The parcel size.
    pub parcel: ParcelSize,
    /// The seed of every random choice.
    pub seed: u64,
    /// WGS 84 ↔ local metres (GeoJSON regions, or a TOML `origin`); `None` writes no GeoJSON.
    pub projection: Option<Projection>,
    /// The block templates: the built-in library, with a TOML region's `[templates] dir` added.
    pub templates: Vec<Template>,
    /// Whether every part is matched against the templates before it is cut (the paper's
    /// control loop) rather than only once it passes the fit test.
    pub templates_first: bool,
    /// The block size.
    pub block: BlockSize,
    /// The fit thresholds.
    pub fit: Fit,
    /// The weights of the streamline scores.
    pub weights: Weights,
    /// Zones: land marked for a use, laid out around.
    pub zones: Vec<Zone>,
}

impl Region {
    /// A region with every setting at its default — streets 15 m wide, a boundary street,
    /// 30 × 18 m parcels, seed 0, the built-in templates — for a site given by another command
    /// (a city's domain).
    pub fn with_defaults(name: &str, polygon: Polygon, roads: Vec<Vec<P>>) -> Region {
        let parcel = ParcelSize::default();
        let street_widths = default_widths();
        Region {
            name: name.to_string(),
            polygon,
            roads,
            block: BlockToml::default().resolve(parcel.depth, parcel.width, street_widths[0]),
            street_widths,
            boundary: Boundary::Street,
            parcel,
            seed: 0,
            projection: None,
            templates: super::template::file::builtin(),
            templates_first: true,
            fit: FitToml::default().resolve(),
            weights: Weights::default(),
            zones: Vec::new(),
        }
    }

    /// The street width of a level.
    pub fn street_width(&self, level: usize) -> f64 {
        let w = &self.street_widths;
        w.get(level).or(w.last()).copied().unwrap_or(15.0)
    }

    /// The parcels a layout of this region makes, about (area / parcel area).
    pub fn parcel_estimate(&self) -> f64 {
        self.polygon.area() / (self.parcel.depth * self.parcel.width)
    }
}

/// The most parcels a region may hold (about 54 km² of the default 30 × 18 m parcels).
pub const MAX_PARCELS: f64 = 100_000.0;

/// Why a region was refused; every variant names the file and the field.
#[derive(Debug, Error)]
pub enum RegionError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Malformed TOML, a missing or unknown key (the message names the line and key).
    #[error("{path}: {message}")]
    Toml {
        /// The file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// A GeoJSON site problem (the message names the feature).
    #[error("{path}: {source}")]
    Site {
        /// The file.
        path: PathBuf,
        /// Why.
        source: SiteError,
    },
    /// A zone was refused.
    #[error("{path}: {zone}: {problem}")]
    Zone {
        /// The file.
        path: PathBuf,
        /// The zone (`zone[i]`, or `features[i]` in GeoJSON).
        zone: String,
        /// Why.
        problem: ZoneProblem,
    },
    /// An invalid polygon.
    #[error("{path}: {field}: {source}")]
    Polygon {
        /// The file.
        path: PathBuf,
        /// `outer` or `holes[i]`.
        field: String,
        /// Why.
        source: PolygonError,
    },
    /// A value out of range.
    #[error("{path}: {field} = {value}: {expected}")]
    Value {
        /// The file.
        path: PathBuf,
        /// The key.
        field: String,
        /// The value given.
        value: String,
        /// What is expected.
        expected: &'static str,
    },
    /// A template file was refused (the message names the file and the field).
    #[error(transparent)]
    Template(#[from] TemplateError),
    /// Refused up front: the layout would take too long.
    #[error(
        "{path}: the region ({area_km2:.1} km²) would hold about {parcels:.0} parcels of {depth} × {width} m; \
         at most {max:.0} are laid out (larger parcels, or split the region)"
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its area.
        area_km2: f64,
        /// The parcel estimate.
        parcels: f64,
        /// Parcel depth.
        depth: f64,
        /// Parcel width.
        width: f64,
        /// [`MAX_PARCELS`].
        max: f64,
    },
}

/// Reads a region: GeoJSON when the file name ends in `.geojson` or `.json`, TOML otherwise.
pub fn read_region(path: &Path) -> Result<Region, RegionError> {
    let text = std::fs::read_to_string(path).map_err(|source| RegionError::Io { path: path.into(), source })?;
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    if matches!(ext, "geojson" | "json") {
        region_from_geojson(&text, path, &stem)
    } else {
        region_from_toml(&text, path, &stem)
    }
}

/// A region from TOML text; `path` names it in errors and `stem` is its default name.
pub fn region_from_toml(text: &str, path: &Path, stem: &str) -> Result<Region, RegionError> {
    let t: RegionToml =
        toml::from_str(text).map_err(|e| RegionError::Toml { path: path.into(), message: e.to_string() })?;
    let polygon = Polygon::new(t.outer, t.holes).map_err(|source| {
        let field = match ring_of(&source) {
            Some(Ring::Hole(i)) => format!("holes[{i}]"),
            _ => "outer".to_string(),
        };
        RegionError::Polygon { path: path.into(), field, source }
    })?;
    let zone_err = |(zone, problem)| RegionError::Zone { path: path.into(), zone, problem };
    let zones = t
        .zone
        .iter()
        .enumerate()
        .map(|(i, z)| Zone::new(format!("zone[{i}]"), z.polygon.clone(), &z.use_))
        .collect::<Result<Vec<_>, _>>()
        .map_err(zone_err)?;
    zone::check(&polygon, &zones).map_err(zone_err)?;
    let mut roads = Vec::new();
    for (i, r) in t.roads.iter().enumerate() {
        let pieces = site::clip_road(&polygon, r, &format!("roads[{i}]"))
            .map_err(|source| RegionError::Site { path: path.into(), source })?;
        roads.extend(pieces);
    }
    let (dir, builtin, first, counts) = match t.templates {
        Some(d) => (d.dir.map(|d| path.parent().unwrap_or(Path::new("")).join(d)), d.builtin, d.first, d.counts),
        None => (None, true, true, Default::default()),
    };
    let street = t.street_widths.get(1).or(t.street_widths.last()).copied().unwrap_or(15.0);
    let mut templates = library(dir.as_deref(), builtin)?;
    set_counts(&mut templates, &counts, path)?;
    let projection =
        t.origin.map(Projection::new).transpose().map_err(|source| RegionError::Site { path: path.into(), source })?;
    let region = Region {
        name: t.name.unwrap_or_else(|| stem.to_string()),
        polygon,
        roads,
        block: t.block.resolve(t.parcel.depth, t.parcel.width, street),
        street_widths: t.street_widths,
        boundary: t.boundary,
        parcel: t.parcel,
        seed: t.seed,
        projection,
        templates,
        templates_first: first,
        fit: t.fit.resolve(),
        weights: t.weights,
        zones,
    };
    check(region, path)
}

/// A region from GeoJSON text (the polygon feature's properties may carry `name`, `seed`,
/// `boundary`, `street_widths`, `parcel_depth` and `parcel_width`; other properties are ignored,
/// as QGIS and OpenStreetMap add their own).
pub fn region_from_geojson(text: &str, path: &Path, stem: &str) -> Result<Region, RegionError> {
    let s = site::read_geojson(text).map_err(|source| RegionError::Site { path: path.into(), source })?;
    let p = &s.properties;
    let bad = |field: &str, value: &serde_json::Value, expected| RegionError::Value {
        path: path.into(),
        field: format!("properties.{field}"),
        value: value.to_string(),
        expected,
    };
    let num = |key: &str, default: f64| -> Result<f64, RegionError> {
        match p.get(key) {
            None => Ok(default),
            Some(v) => v.as_f64().ok_or_else(|| bad(key, v, "a number")),
        }
    };
    let seed = match p.get("seed") {
        None => 0,
        Some(v) => v.as_u64().ok_or_else(|| bad("seed", v, "a non-negative integer"))?,
    };
    let boundary = match p.get("boundary") {
        None => Boundary::Street,
        Some(v) => serde_json::from_value(v.clone()).map_err(|_| bad("boundary", v, "\"street\" or \"none\""))?,
    };
    let street_widths = match p.get("street_widths") {
        None => default_widths(),
        Some(v) => serde_json::from_value(v.clone()).map_err(|_| bad("street_widths", v, "a list of numbers"))?,
    };
    let opt = |key: &str| -> Result<Option<f64>, RegionError> {
        p.get(key).map(|v| v.as_f64().ok_or_else(|| bad(key, v, "a number"))).transpose()
    };
    let templates_first = match p.get("templates_first") {
        None => true,
        Some(v) => v.as_bool().ok_or_else(|| bad("templates_first", v, "true or false"))?,
    };
    let parcel =
        ParcelSize { depth: num("parcel_depth", default_depth())?, width: num("parcel_width", default_width())? };
    let street = street_widths.get(1).or(street_widths.last()).copied().unwrap_or(15.0);
    let block = BlockToml { width: opt("block_width")?, max_length: opt("block_length")? };
    let fit = FitToml { threshold: opt("fit_threshold")?, ..FitToml::default() };
    let zone_err = |(zone, problem)| RegionError::Zone { path: path.into(), zone, problem };
    let zones = s
        .zones
        .iter()
        .map(|z| Zone::new(format!("features[{}]", z.feature), z.ring.clone(), &z.use_))
        .collect::<Result<Vec<_>, _>>()
        .map_err(zone_err)?;
    zone::check(&s.polygon, &zones).map_err(zone_err)?;
    let region = Region {
        name: p.get("name").and_then(|v| v.as_str()).map_or_else(|| stem.to_string(), str::to_string),
        polygon: s.polygon,
        roads: s.roads,
        block: block.resolve(parcel.depth, parcel.width, street),
        street_widths,
        boundary,
        parcel,
        seed,
        projection: Some(s.projection),
        templates: super::template::file::builtin(),
        templates_first,
        fit: fit.resolve(),
        weights: Weights::default(),
        zones,
    };
    check(region, path)
}

/// Applies `[templates.counts]` to the library; refuses an unknown name, a minimum above the
/// maximum and a probability that is not positive, naming the field.
fn set_counts(
    templates: &mut [Template],
    counts: &std::collections::BTreeMap<String, CountToml>,
    path: &Path,
) -> Result<(), RegionError> {
    for (name, c) in counts {
        let field = format!("templates.counts.{name}");
        let bad =
            |field: String, value: String, expected| RegionError::Value { path: path.into(), field, value, expected };
        let Some(t) = templates.iter_mut().find(|t| &t.name == name) else {
            return Err(bad(field, name.clone(), "the name of a template of the library"));
        };
        t.min_uses = c.min.unwrap_or(t.min_uses);
        t.max_uses = c.max.or(t.max_uses);
        if let Some(max) = t.max_uses.filter(|&m| m < t.min_uses) {
            return Err(bad(format!("{field}.min"), format!("{} (max {max})", t.min_uses), "at most the maximum"));
        }
        if let Some(p) = c.probability {
            if !(p.is_finite() && p > 0.0) {
                return Err(bad(format!("{field}.probability"), p.to_string(), "a positive number"));
            }
            t.probability = p;
        }
    }
    Ok(())
}

fn ring_of(e: &PolygonError) -> Option<Ring> {
    match e {
        PolygonError::TooFewVertices { ring, .. }
        | PolygonError::NotFinite { ring, .. }
        | PolygonError::Degenerate { ring }
        | PolygonError::SelfIntersecting { ring, .. } => Some(*ring),
        PolygonError::HoleOutside { hole } | PolygonError::HoleCrossing { hole, .. } => Some(Ring::Hole(*hole)),
        PolygonError::HoleInHole { inner, .. } => Some(Ring::Hole(*inner)),
    }
}

fn check(region: Region, path: &Path) -> Result<Region, RegionError> {
    let positive = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(RegionError::Value {
                path: path.into(),
                field: field.into(),
                value: v.to_string(),
                expected: "a positive number",
            })
        }
    };
    positive("parcel.depth", region.parcel.depth)?;
    positive("parcel.width", region.parcel.width)?;
    if region.street_widths.is_empty() {
        return Err(RegionError::Value {
            path: path.into(),
            field: "street_widths".into(),
            value: "[]".into(),
            expected: "at least one width",
        });
    }
    for (i, &w) in region.street_widths.iter().enumerate() {
        positive(&format!("street_widths[{i}]"), w)?;
    }
    for (field, v) in settings::positive_fields(&region.block, &region.fit) {
        positive(field, v)?;
    }
    if let Some((field, v)) = settings::check_weights(&region.weights) {
        return Err(RegionError::Value {
            path: path.into(),
            field: field.into(),
            value: v.to_string(),
            expected: "weights of at least 0, one of them positive",
        });
    }
    let parcels = region.parcel_estimate();
    if parcels > MAX_PARCELS {
        return Err(RegionError::TooLarge {
            path: path.into(),
            area_km2: region.polygon.area() / 1e6,
            parcels,
            depth: region.parcel.depth,
            width: region.parcel.width,
            max: MAX_PARCELS,
        });
    }
    Ok(region)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toml(text: &str) -> Result<Region, RegionError> {
        region_from_toml(text, Path::new("r.toml"), "r")
    }

    #[test]
    fn a_toml_region_has_defaults_and_clipped_roads() {
        let r = toml("outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\nroads = [[[-50, 150], [450, 150]]]\n").unwrap();
        assert_eq!((r.name.as_str(), r.seed, r.boundary), ("r", 0, Boundary::Street));
        assert_eq!(r.parcel, ParcelSize { depth: 30.0, width: 18.0 });
        assert_eq!(r.street_width(3), 15.0);
        assert_eq!(r.roads.len(), 1);
        assert!(r.projection.is_none());
        assert!((r.parcel_estimate() - 120_000.0 / 540.0).abs() < 1e-9);
    }

    #[test]
    fn errors_name_the_field() {
        let e = toml("outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\nholes = [[[500, 0], [600, 0], [600, 50]]]\n");
        assert_eq!(e.unwrap_err().to_string(), "r.toml: holes[0]: hole 0 is not inside the outer ring");
        let e = toml("outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\n[parcel]\ndepth = -3\n").unwrap_err();
        assert!(e.to_string().contains("parcel.depth = -3"), "{e}");
        let e = toml("outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\ncolour = 3\n").unwrap_err();
        assert!(e.to_string().contains("colour"), "{e}");
        let e = toml("outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\nroads = [[[500, 0], [600, 0]]]\n").unwrap_err();
        assert_eq!(e.to_string(), "r.toml: roads[0]: the road lies outside the region");
        let e = toml("outer = [[0, 0], [1e5, 0], [1e5, 1e5], [0, 1e5]]\n").unwrap_err();
        assert!(matches!(e, RegionError::TooLarge { .. }) && e.to_string().contains("10000.0 km²"), "{e}");
        let e = toml("outer = [[0, 0], [4, 0], [4, 3], [0, 3]]\nstreet_widths = []\n").unwrap_err();
        assert!(e.to_string().contains("street_widths"), "{e}");
    }

    #[test]
    fn block_size_fit_and_weights_are_settings() {
        let square = "outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\nstreet_widths = [20, 12]\n";
        let r = toml(square).unwrap();
        // Defaults: a double-loaded block between first-split streets, 14 parcels long.
        assert_eq!((r.block.width, r.block.max_length), (72.0, 252.0));
        assert_eq!((r.fit.threshold, r.fit.max_width, r.fit.min_parcels), (0.02, 1.35, 4.0));
        assert!(r.templates_first && r.weights.as_array() == [1.0; 4]);
        let set = format!(
            "{square}[block]\nwidth = 80\nmax_length = 400\n[fit]\nthreshold = 0.01\n[weights]\ncontinuity = 2\n[templates]\nfirst = false\n"
        );
        let r = toml(&set).unwrap();
        assert_eq!((r.block.width, r.block.max_length, r.fit.threshold), (80.0, 400.0, 0.01));
        assert_eq!((r.weights.continuity, r.weights.divergence, r.templates_first), (2.0, 1.0, false));
        let e = toml(&format!("{square}[block]\nwidth = -1\n")).unwrap_err();
        assert!(e.to_string().contains("block.width = -1"), "{e}");
        let e = toml(&format!("{square}[fit]\nslack = 1\n")).unwrap_err();
        assert!(e.to_string().contains("slack"), "{e}");
        let zero = "[weights]\ndivergence = 0\nboundary = 0\nsingularities = 0\ncontinuity = 0\n";
        let e = toml(&format!("{square}{zero}")).unwrap_err();
        assert!(e.to_string().contains("weights"), "{e}");
    }

    #[test]
    fn zones_are_read_and_refused_with_the_file_and_zone_named() {
        let square = "outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\n";
        let park = "[[zone]]\npolygon = [[100, 100], [200, 100], [200, 200], [100, 200]]\nuse = \"park\"\n";
        let r = toml(&format!("{square}{park}")).unwrap();
        assert_eq!((r.zones.len(), r.zones[0].use_), (1, zone::ZoneUse::Park));
        let mall = park.replace("park", "mall");
        let e = toml(&format!("{square}{park}{mall}")).unwrap_err().to_string();
        assert_eq!(e, "r.toml: zone[1]: use = \"mall\" is not park, school, commercial or keep");
        let over = park.replace("[100, 100], [200, 100]", "[150, 150], [250, 150]");
        let e = toml(&format!("{square}{park}{over}")).unwrap_err().to_string();
        assert_eq!(e, "r.toml: zone[1]: overlaps zone[0]");
        let out = park.replace("[200, 100], [200, 200]", "[500, 100], [500, 200]");
        let e = toml(&format!("{square}{out}")).unwrap_err().to_string();
        assert!(e.starts_with("r.toml: zone[0]: crosses the region's outline"), "{e}");
    }

    #[test]
    fn template_counts_are_set_per_region() {
        let square = "outer = [[0, 0], [400, 0], [400, 300], [0, 300]]\n";
        let r = toml(&format!("{square}[templates.counts]\ntownhouses = {{ min = 2, max = 5, probability = 0.5 }}\n"))
            .unwrap();
        let t = r.templates.iter().find(|t| t.name == "townhouses").unwrap();
        assert_eq!((t.min_uses, t.max_uses, t.probability), (2, Some(5), 0.5));
        let e = toml(&format!("{square}[templates.counts]\nvillas = {{ min = 1 }}\n")).unwrap_err();
        assert!(e.to_string().contains("templates.counts.villas"), "{e}");
        let e = toml(&format!("{square}[templates.counts]\nspike = {{ min = 9 }}\n")).unwrap_err();
        assert!(e.to_string().contains("templates.counts.spike.min = 9 (max 6)"), "{e}");
    }
}
