//! City specs: the domain, the major roads, the level hierarchy's functional specs (defaults and
//! per-region overrides), the mesh resolution, solver budgets and smoothing.
//!
//! A level's spec is an ordinary functional spec ([`Spec`]) without its mesh, so every key of
//! `docs/spec.md` means the same here. Per-region overrides are merged key by key into the
//! defaults (tables recursively, everything else replaced) before the result is read, so an
//! override only names what differs.

use crate::solvers::SolverKind;
use crate::spec::{
    BoundaryRole, CoverageSpec, FeatureSpec, FormulationSpec, MeshSpec, PointToPointSpec, SinkSpec, SolverSpec, Spec,
    UserSpec, WeightSpec,
};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// A city spec (the content of a city TOML file).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CitySpec {
    /// A short name (titles, output directory).
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// Metres per model unit (for the street metrics and GeoJSON).
    #[serde(default = "default_scale")]
    pub metres_per_unit: f64,
    /// Geographic anchor `[longitude, latitude]` (WGS 84 degrees) of the model origin, the
    /// centre of the transverse Mercator every netspec file shares. GeoJSON is always WGS 84
    /// (RFC 7946); without an anchor the origin is [`DEFAULT_GEO_ORIGIN`].
    #[serde(default)]
    pub geo_origin: Option<[f64; 2]>,
    /// The domain polygon.
    pub domain: DomainSpec,
    /// Major roads (level 1): polylines that split the domain into sub-regions.
    #[serde(default, rename = "road")]
    pub roads: Vec<RoadSpec>,
    /// Where further major roads come from (`[major] method = "streamlines"`); expanded into
    /// `roads` when the spec is read, so it is `None` in a read spec.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub major: Option<MajorSpec>,
    /// Mesh resolution for every sub-region.
    pub mesh: CityMeshSpec,
    /// Default spec per level (`"2"`, `"3"`, `"4"`); a level that is absent is not run.
    pub levels: IndexMap<String, toml::Table>,
    /// Per-region names and overrides.
    #[serde(default, rename = "region")]
    pub regions: Vec<RegionSpec>,
    /// Solver and budgets.
    #[serde(default)]
    pub solver: CitySolverSpec,
    /// Street smoothing.
    #[serde(default)]
    pub smoothing: SmoothingSpec,
}

fn default_scale() -> f64 {
    1.0
}

pub use crate::design::streets::DEFAULT_GEO_ORIGIN;

impl CitySpec {
    /// The model origin's `[longitude, latitude]`: `geo_origin`, else [`DEFAULT_GEO_ORIGIN`].
    pub fn origin_wgs84(&self) -> [f64; 2] {
        self.geo_origin.unwrap_or(DEFAULT_GEO_ORIGIN)
    }
}

/// Fig. 7a's levels 2–4 (collectors on the grid, local roads on the subdivided mesh,
/// cul-de-sacs), the levels of a city on a site that has no spec of its own; `obstacles` (city
/// units) become every level's `user.obstacle_polygons`.
pub fn fig7a_levels(obstacles: &[Vec<[f64; 2]>]) -> IndexMap<String, toml::Table> {
    const LEVELS: &str = r#"
[2]
time_limit = 1000
coverage = { range = 3 }
weights = { length = 1, distance = 1e-4, zigzag = "forbid", too_close = "forbid" }
features = { dead_ends = "forbid" }

[3]
subdivide = true
time_limit = 1200
coverage = { range = 3 }
weights = { length = 1, distance = 1e-4, zigzag = "forbid", too_close = "forbid" }
features = { dead_ends = "forbid" }

[4]
time_limit = 100
coverage = { range = 2 }
weights = { length = 1, distance = 1e-4, zigzag = "forbid", too_close = "forbid" }
features = { dead_ends = "allow" }
"#;
    let mut levels: IndexMap<String, toml::Table> = toml::from_str(LEVELS).expect("the built-in levels are TOML");
    if !obstacles.is_empty() {
        let polys = toml::Value::try_from(obstacles).expect("points are TOML");
        for t in levels.values_mut() {
            let mut user = toml::Table::new();
            user.insert("obstacle_polygons".into(), polys.clone());
            t.insert("user".into(), toml::Value::Table(user));
        }
    }
    levels
}

/// The domain.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DomainSpec {
    /// Its boundary polygon (either orientation).
    pub outer: Vec<[f64; 2]>,
}

/// A major road.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoadSpec {
    /// Its name (for messages).
    #[serde(default)]
    pub name: String,
    /// The polyline.
    pub points: Vec<[f64; 2]>,
}

/// How sub-regions are meshed: a grid clipped to each region, on one lattice for the city.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CityMeshSpec {
    /// Cell size of the level-2 mesh.
    pub spacing: f64,
}

/// A sub-region's name and overrides. It is found by a point inside it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// A point inside the sub-region.
    pub at: [f64; 2],
    /// Its name.
    pub name: String,
    /// Which levels to run here (default: every level of `levels`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub run_levels: Option<Vec<u8>>,
    /// Overrides per level, merged into the defaults.
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub levels: IndexMap<String, toml::Table>,
}

/// Solver settings for the whole city.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CitySolverSpec {
    /// Backend (default: the embedded default backend).
    #[serde(default)]
    pub name: Option<SolverKind>,
    /// Total thread budget for the city: `threads / threads_per_solve` sub-regions run at once.
    #[serde(default = "two_threads")]
    pub threads: u32,
    /// Threads given to each solve.
    #[serde(default = "one_thread")]
    pub threads_per_solve: u32,
    /// Relative gap.
    #[serde(default)]
    pub gap: Option<f64>,
    /// Seed.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Every level's solve starts with a large-neighbourhood search, or none does (`[solver] lns`
    /// of a spec); unset, each level's model decides by its size
    /// (`pipeline::strategy::LNS_FROM_NONZEROS`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lns: Option<bool>,
}

fn two_threads() -> u32 {
    2
}
fn one_thread() -> u32 {
    1
}

impl Default for CitySolverSpec {
    fn default() -> Self {
        CitySolverSpec { name: None, threads: 2, threads_per_solve: 1, gap: None, seed: None, lns: None }
    }
}

/// Which smoother draws the streets.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum SmoothingMethod {
    /// The paper's snakes (tension, stiffness, inertia; gradient descent).
    #[default]
    Snake,
    /// Yang et al.'s fairing (fairness + closeness, one linear solve per iteration).
    Fair,
    /// No smoothing: the mesh network as is.
    None,
}

/// Smoothing settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SmoothingSpec {
    /// The smoother.
    #[serde(default)]
    pub method: SmoothingMethod,
}

/// One level's functional spec: a [`Spec`] without mesh, rooms and solver, plus the level's own
/// switches.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LevelSpec {
    /// Subdivide the previous level's mesh (Catmull–Clark without moving vertices) first.
    #[serde(default)]
    pub subdivide: bool,
    /// Time limit of this level's solve, seconds.
    #[serde(default)]
    pub time_limit: Option<f64>,
    /// Role of the sub-region's boundary (default: an existing road).
    #[serde(default = "road")]
    pub boundary: BoundaryRole,
    /// Sinks (default: every boundary vertex). Vertices of earlier levels' roads are always sinks.
    #[serde(default = "boundary_sinks")]
    pub sinks: SinkSpec,
    /// Coverage.
    #[serde(default)]
    pub coverage: CoverageSpec,
    /// Weights.
    #[serde(default)]
    pub weights: WeightSpec,
    /// Dead-ends and branches.
    #[serde(default)]
    pub features: FeatureSpec,
    /// Point-to-point.
    #[serde(default)]
    pub point_to_point: Option<PointToPointSpec>,
    /// Obstacles, forced elements, through routes (give places as points: vertex ids change
    /// between levels).
    #[serde(default)]
    pub user: UserSpec,
    /// Formulation variant.
    #[serde(default)]
    pub formulation: FormulationSpec,
}

fn road() -> BoundaryRole {
    BoundaryRole::Road
}
fn boundary_sinks() -> SinkSpec {
    SinkSpec { all_boundary: true, ..SinkSpec::default() }
}

impl LevelSpec {
    /// The equivalent functional spec (its mesh section names `mesh.json`, which is where
    /// exported level specs keep the mesh).
    pub fn to_spec(&self, name: String, description: String) -> Spec {
        Spec {
            name,
            description,
            mesh: MeshSpec { grid: None, clipped: None, file: Some(PathBuf::from("mesh.json")), jitter: None },
            boundary: self.boundary,
            sinks: self.sinks.clone(),
            coverage: self.coverage.clone(),
            weights: self.weights.clone(),
            features: self.features.clone(),
            point_to_point: self.point_to_point.clone(),
            user: self.user.clone(),
            rooms: None,
            formulation: self.formulation.clone(),
            solver: SolverSpec { time_limit: self.time_limit, ..SolverSpec::default() },
        }
    }
}

/// Why a city spec cannot be used.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", path.display())]
pub struct CitySpecError {
    /// The city spec file.
    pub path: PathBuf,
    /// What is wrong.
    #[source]
    pub kind: CitySpecErrorKind,
}

/// What is wrong with a city spec.
#[derive(Debug, thiserror::Error)]
pub enum CitySpecErrorKind {
    /// The file could not be read.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// TOML syntax or schema error (the message names the line and key).
    #[error("{0}")]
    Toml(String),
    /// A field's value is unusable.
    #[error("field `{field}`: {message}")]
    Field {
        /// Dotted path, e.g. `region[2].levels.3.coverage.range`.
        field: String,
        /// What is wrong.
        message: String,
    },
}

fn field(field: impl Into<String>, message: impl Into<String>) -> CitySpecErrorKind {
    CitySpecErrorKind::Field { field: field.into(), message: message.into() }
}

/// Merges `over` into `base`: tables recursively, other values replaced.
pub fn merge_tables(base: &mut toml::Table, over: &toml::Table) {
    for (k, v) in over {
        match (base.get_mut(k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge_tables(b, o),
            _ => {
                base.insert(k.clone(), v.clone());
            }
        }
    }
}

/// Where a city's major roads come from (`[major]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MajorSpec {
    /// `given` (the `[[road]]` entries only) or `streamlines` (those, plus cuts of the split).
    pub method: MajorMethod,
    /// How many split depths become major roads: 1 keeps the first cut of the domain (and of
    /// each part the given roads make), 2 also the cuts of the halves, ….
    #[serde(default = "one")]
    pub depth: usize,
    /// The cross field the streamlines follow.
    #[serde(default = "distance")]
    pub field: crate::layout::field::FieldMethod,
    /// The seed of the split.
    #[serde(default)]
    pub seed: u64,
}

fn one() -> usize {
    1
}
fn distance() -> crate::layout::field::FieldMethod {
    crate::layout::field::FieldMethod::Distance
}

/// How major roads are made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MajorMethod {
    /// Drawn by hand: the `[[road]]` entries.
    Given,
    /// Streamlines of the domain's cross field, chosen as `netspec layout` chooses its cuts.
    Streamlines,
}

/// The level numbers a city can run.
pub const LEVELS: [u8; 3] = [2, 3, 4];

impl CitySpec {
    /// Parses TOML text and checks it, leaving `[major]` as written: [`CitySpec::from_toml`]
    /// (in `urban::load`) also expands it into roads.
    pub fn parse_toml(text: &str) -> Result<CitySpec, CitySpecErrorKind> {
        let spec: CitySpec = toml::from_str(text).map_err(|e| CitySpecErrorKind::Toml(e.to_string()))?;
        spec.check()?;
        Ok(spec)
    }

    fn check(&self) -> Result<(), CitySpecErrorKind> {
        if !(self.metres_per_unit > 0.0 && self.metres_per_unit.is_finite()) {
            return Err(field("metres_per_unit", format!("must be a positive number, got {}", self.metres_per_unit)));
        }
        if let Some(origin) = self.geo_origin {
            crate::geometry::site::Projection::new(origin).map_err(|e| field("geo_origin", e.to_string()))?;
        }
        if !(self.mesh.spacing > 0.0 && self.mesh.spacing.is_finite()) {
            return Err(field("mesh.spacing", format!("must be a positive number, got {}", self.mesh.spacing)));
        }
        if self.solver.threads == 0 || self.solver.threads_per_solve == 0 {
            return Err(field("solver.threads", "threads and threads_per_solve must be at least 1"));
        }
        for key in self.levels.keys() {
            level_number(&format!("levels.{key}"), key)?;
        }
        if self.levels.is_empty() {
            return Err(field("levels", "give at least level 2 (e.g. [levels.2])"));
        }
        for (i, r) in self.regions.iter().enumerate() {
            for key in r.levels.keys() {
                let n = level_number(&format!("region[{i}].levels.{key}"), key)?;
                if !self.levels.contains_key(key) {
                    return Err(field(
                        format!("region[{i}].levels.{key}"),
                        format!("level {n} has no default in [levels.{n}]"),
                    ));
                }
            }
            for &n in r.run_levels.iter().flatten() {
                if !self.levels.contains_key(&n.to_string()) {
                    return Err(field(
                        format!("region[{i}].run_levels"),
                        format!("level {n} has no default in [levels.{n}]"),
                    ));
                }
            }
        }
        // Every level of every region must read.
        for n in self.level_numbers() {
            self.level(None, n)?;
            for i in 0..self.regions.len() {
                self.level(Some(i), n)?;
            }
        }
        Ok(())
    }

    /// The levels with defaults, ascending.
    pub fn level_numbers(&self) -> Vec<u8> {
        let mut v: Vec<u8> = self.levels.keys().filter_map(|k| k.parse().ok()).collect();
        v.sort_unstable();
        v
    }

    /// The levels run in a region (`None`: a region without a `[[region]]` entry).
    pub fn region_levels(&self, region: Option<usize>) -> Vec<u8> {
        let all = self.level_numbers();
        match region.and_then(|i| self.regions[i].run_levels.as_ref()) {
            Some(run) => all.into_iter().filter(|n| run.contains(n)).collect(),
            None => all,
        }
    }

    /// An upper bound on the cells of a level's mesh: the grid over the domain's bounding box,
    /// times 4 for each level that subdivides.
    pub fn estimated_cells(&self) -> f64 {
        let (lo, hi) = self.domain_bounds();
        let cells = ((hi[0] - lo[0]) / self.mesh.spacing).ceil().max(0.0)
            * ((hi[1] - lo[1]) / self.mesh.spacing).ceil().max(0.0);
        // Each level that subdivides the mesh quadruples its faces.
        let subdivisions =
            self.levels.values().filter(|l| l.get("subdivide").and_then(|v| v.as_bool()) == Some(true)).count() as i32;
        cells * 4f64.powi(subdivisions)
    }

    /// The bounding box of the domain's outer polygon.
    pub fn domain_bounds(&self) -> ([f64; 2], [f64; 2]) {
        self.domain.outer.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
            ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
        })
    }

    /// A sub-region's name: its `[[region]]` entry's, else `region-<index>`.
    pub fn region_name(&self, index: usize, entry: Option<usize>) -> String {
        entry.map_or_else(|| format!("region-{index}"), |i| self.regions[i].name.clone())
    }

    /// Level `n`'s spec for a region (`None`: the defaults), overrides merged.
    pub fn level(&self, region: Option<usize>, n: u8) -> Result<LevelSpec, CitySpecErrorKind> {
        let key = n.to_string();
        let mut table =
            self.levels.get(&key).cloned().ok_or_else(|| field("levels", format!("level {n} has no default")))?;
        let mut at = format!("levels.{n}");
        if let Some(i) = region {
            if let Some(over) = self.regions[i].levels.get(&key) {
                merge_tables(&mut table, over);
                at = format!("region[{i}].levels.{n} (merged with levels.{n})");
            }
        }
        table.try_into::<LevelSpec>().map_err(|e| field(at, e.to_string().trim_end().to_string()))
    }
}

fn level_number(at: &str, key: &str) -> Result<u8, CitySpecErrorKind> {
    match key.parse::<u8>() {
        Ok(n) if LEVELS.contains(&n) => Ok(n),
        _ => Err(field(at, format!("levels are 2, 3 and 4 (level 1, the major roads, is given), got {key:?}"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CITY: &str = r#"
name = "two"
metres_per_unit = 20
domain = { outer = [[0, 0], [8, 0], [8, 4], [0, 4]] }
mesh = { spacing = 1 }
[[road]]
points = [[4, -1], [4, 5]]
[levels.2]
coverage = { range = 2 }
weights = { length = 1, zigzag = 5 }
[levels.3]
subdivide = true
coverage = { range = 3 }
[[region]]
at = [6, 2]
name = "east"
[region.levels.2]
coverage = { range = 1 }
features = { dead_ends = "allow" }
"#;

    #[test]
    fn overrides_merge_key_by_key() {
        let c = CitySpec::from_toml(CITY).unwrap();
        assert_eq!(c.level_numbers(), vec![2, 3]);
        let d = c.level(None, 2).unwrap();
        assert_eq!(d.coverage.range, 2.0);
        let e = c.level(Some(0), 2).unwrap();
        assert_eq!(e.coverage.range, 1.0);
        assert_eq!(e.features.dead_ends, crate::spec::Allow::Allow);
        // Untouched keys come from the defaults.
        assert_eq!(e.weights, d.weights);
        assert!(c.level(Some(0), 3).unwrap().subdivide);
    }

    #[test]
    fn errors_name_the_field() {
        let bad = CITY.replace("range = 1 }", "rnage = 1 }");
        let msg = CitySpec::from_toml(&bad).unwrap_err().to_string();
        assert!(msg.contains("region[0].levels.2") && msg.contains("rnage"), "{msg}");
        let bad = CITY.replace("[levels.3]", "[levels.5]");
        let msg = CitySpec::from_toml(&bad).unwrap_err().to_string();
        assert!(msg.contains("levels.5"), "{msg}");
        let bad = CITY.replace("spacing = 1", "spacing = 0");
        assert!(CitySpec::from_toml(&bad).unwrap_err().to_string().contains("mesh.spacing"));
    }
}
