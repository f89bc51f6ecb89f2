//! Functional specifications: what the network must do, as a TOML or JSON file.
//!
//! A [`Spec`] is the file's content (serde, unknown keys rejected). [`Spec::resolve`] turns it
//! into a [`Problem`]: the mesh, every edge's role, the sinks, and the switches in plain form,
//! checking ids, ranges and contradictions with errors that name the field.

mod formulation;
mod resolve;
mod symmetry;
mod template;

pub use formulation::{
    parse_on_off, switch, BigMForm, ConnectivityForm, CoverageForm, DeadEndForm, DistanceForm, FormulationParts,
    FormulationSpec, PathForm, RecipeName, Switch, Variant, STRATEGY_KEYS, SWITCHES,
};

pub use resolve::{EdgeRole, PointToPoint, Problem, Rooms, Weight, DEFAULT_MAX_CELLS};
pub use symmetry::{symmetries, Symmetry};
pub use template::Template;

use crate::solvers::SolverKind;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A functional specification (the content of a spec file).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// A short name (used in titles and file names).
    pub name: String,
    /// Free text (e.g. which figure of the paper this reconstructs).
    #[serde(default)]
    pub description: String,
    /// The domain.
    pub mesh: MeshSpec,
    /// What boundary edges are: `road` (existing), `wall` (excluded) or `candidate`.
    #[serde(default = "default_boundary")]
    pub boundary: BoundaryRole,
    /// Where the network leads.
    pub sinks: SinkSpec,
    /// How dense the network must be.
    #[serde(default)]
    pub coverage: CoverageSpec,
    /// Objective weights and forbidden features.
    #[serde(default)]
    pub weights: WeightSpec,
    /// Dead-ends and branches.
    #[serde(default)]
    pub features: FeatureSpec,
    /// Point-to-point path sets (§3.4), off when absent.
    #[serde(default)]
    pub point_to_point: Option<PointToPointSpec>,
    /// Obstacles, forced elements and through routes.
    #[serde(default)]
    pub user: UserSpec,
    /// Room tiling (floor plans §5.2, game levels §5.3), off when absent.
    #[serde(default)]
    pub rooms: Option<RoomsSpec>,
    /// The formulation recipe (`paper`, `tight`, `strong`) or a table of its parts.
    #[serde(default)]
    pub formulation: FormulationSpec,
    /// Solver settings (the command line overrides them).
    #[serde(default)]
    pub solver: SolverSpec,
}

fn default_boundary() -> BoundaryRole {
    BoundaryRole::Wall
}

/// The domain mesh: a generator or a file, optionally jittered.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// A `width × height` grid of square cells.
    #[serde(default)]
    pub grid: Option<GridSpec>,
    /// A grid clipped to a polygon with holes.
    #[serde(default)]
    pub clipped: Option<ClippedSpec>,
    /// A Wavefront OBJ or JSON mesh file, relative to the spec file.
    #[serde(default)]
    pub file: Option<PathBuf>,
    /// Random jitter of interior vertices.
    #[serde(default)]
    pub jitter: Option<JitterSpec>,
}

/// A rectangular grid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// Cells along x.
    pub width: usize,
    /// Cells along y.
    pub height: usize,
    /// Cell size.
    #[serde(default = "one")]
    pub spacing: f64,
}

fn one() -> f64 {
    1.0
}

/// A grid clipped to a polygon.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClippedSpec {
    /// The outer polygon.
    pub outer: Vec<[f64; 2]>,
    /// Holes.
    #[serde(default)]
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Cell size.
    #[serde(default = "one")]
    pub spacing: f64,
}

/// Vertex jitter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JitterSpec {
    /// Fraction of the shortest incident edge.
    pub amount: f64,
    /// Seed.
    #[serde(default)]
    pub seed: u64,
}

/// Role of the mesh boundary's edges (docs/formulation.md §1).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BoundaryRole {
    /// Existing roads: fixed active, every boundary vertex must be a sink.
    Road,
    /// Walls: fixed inactive.
    Wall,
    /// Ordinary candidate edges.
    Candidate,
}

/// Which vertices are sinks.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SinkSpec {
    /// Every boundary vertex.
    #[serde(default)]
    pub all_boundary: bool,
    /// Vertex ids.
    #[serde(default)]
    pub vertices: Vec<u32>,
    /// The nearest vertex to each point.
    #[serde(default)]
    pub points: Vec<[f64; 2]>,
}

/// How coverage distance is measured.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum CoverageModel {
    /// Edges on the mesh graph (the paper's "two edges wide").
    #[default]
    Hops,
    /// Straight-line distance between vertices.
    Euclidean,
}

/// Coverage (5)–(6).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CoverageSpec {
    /// The range `r` (in edges for `hops`, in length units for `euclidean`); at least 1.
    #[serde(default = "default_range")]
    pub range: f64,
    /// The distance model.
    #[serde(default)]
    pub model: CoverageModel,
}

fn default_range() -> f64 {
    2.0
}

impl Default for CoverageSpec {
    fn default() -> Self {
        CoverageSpec { range: 2.0, model: CoverageModel::Hops }
    }
}

/// A weight: a non-negative number, or `"forbid"` (the paper's `inf`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum WeightValue {
    /// A weight.
    Number(f64),
    /// `"forbid"`.
    Word(String),
}

impl WeightValue {
    /// The value as written: `1`, `0.0001`, `forbid`.
    pub fn describe(&self) -> String {
        match self {
            WeightValue::Number(x) => format!("{x}"),
            WeightValue::Word(s) => s.clone(),
        }
    }
}

impl Default for WeightValue {
    fn default() -> Self {
        WeightValue::Number(0.0)
    }
}

/// Objective weights (15).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WeightSpec {
    /// λL, on total length.
    #[serde(default = "wnum1")]
    pub length: WeightValue,
    /// λD, on the paper's travel-distance term `Σ D(i→j)` (at an optimum: over active edges,
    /// the smaller of the two ends' label distances; docs/formulation.md §8).
    #[serde(default)]
    pub distance: WeightValue,
    /// On total travel: the sum over active non-sink vertices of the network distance to the
    /// nearest sink (a per-vertex term, not the paper's; modelled by a flow in every recipe).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub travel: WeightValue,
    /// λZ0, on zig-zags.
    #[serde(default)]
    pub zigzag: WeightValue,
    /// λZ1, on too-close parallel edges.
    #[serde(default)]
    pub too_close: WeightValue,
    /// λT, on T-junctions.
    #[serde(default)]
    pub t_junction: WeightValue,
}

fn is_zero(w: &WeightValue) -> bool {
    *w == WeightValue::Number(0.0)
}

fn wnum1() -> WeightValue {
    WeightValue::Number(1.0)
}

impl Default for WeightSpec {
    fn default() -> Self {
        WeightSpec {
            length: wnum1(),
            distance: WeightValue::default(),
            travel: WeightValue::default(),
            zigzag: WeightValue::default(),
            too_close: WeightValue::default(),
            t_junction: WeightValue::default(),
        }
    }
}

/// `allow` or `forbid`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Allow {
    /// Allowed.
    Allow,
    /// Forbidden by constraints.
    Forbid,
}

/// Dead-ends and branches.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeatureSpec {
    /// Dead-ends (10)–(11).
    #[serde(default = "forbid")]
    pub dead_ends: Allow,
    /// Branches (12).
    #[serde(default = "allow")]
    pub branches: Allow,
}

fn forbid() -> Allow {
    Allow::Forbid
}
fn allow() -> Allow {
    Allow::Allow
}

impl Default for FeatureSpec {
    fn default() -> Self {
        FeatureSpec { dead_ends: Allow::Forbid, branches: Allow::Allow }
    }
}

/// Point-to-point path sets (8)–(9).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointToPointSpec {
    /// Partition the faces into `blocks × blocks` blocks by face centroid (grid-like meshes).
    #[serde(default)]
    pub blocks: Option<usize>,
    /// Or an explicit part number per face (one entry per face).
    #[serde(default)]
    pub parts: Option<Vec<u32>>,
    /// Extra edges allowed over the shortest path (default 2).
    #[serde(default = "two")]
    pub tolerance: usize,
    /// Seed for picking the vertex of each part.
    #[serde(default)]
    pub seed: u64,
    /// Cap on the paths enumerated per pair of parts.
    #[serde(default = "default_max_paths")]
    pub max_paths: usize,
}

fn two() -> usize {
    2
}
fn default_max_paths() -> usize {
    5000
}

/// A point or a vertex id.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Place {
    /// A vertex id.
    Vertex(u32),
    /// The nearest vertex to a point.
    Point([f64; 2]),
}

/// A through route: a shortest path between two places, forced active, no inner branches.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThroughRoute {
    /// One end.
    pub from: Place,
    /// The other end.
    pub to: Place,
}

/// User specifications: obstacles, forced elements, through routes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct UserSpec {
    /// Obstacle vertices (ids).
    #[serde(default)]
    pub obstacle_vertices: Vec<u32>,
    /// Obstacle edges, as pairs of vertex ids.
    #[serde(default)]
    pub obstacle_edges: Vec<[u32; 2]>,
    /// Obstacle faces (ids).
    #[serde(default)]
    pub obstacle_faces: Vec<u32>,
    /// Obstacle polygons: every face whose centroid is inside is an obstacle face.
    #[serde(default)]
    pub obstacle_polygons: Vec<Vec<[f64; 2]>>,
    /// Forced edges, as pairs of vertex ids.
    #[serde(default)]
    pub forced_edges: Vec<[u32; 2]>,
    /// Forced-active vertices (ids, or points: the nearest vertex).
    #[serde(default)]
    pub forced_vertices: Vec<Place>,
    /// Through routes.
    #[serde(default)]
    pub through_routes: Vec<ThroughRoute>,
    /// Existing roads inside the domain (pairs of vertex ids): fixed active, not variables, and
    /// their end vertices become sinks (docs/formulation.md §1). Street levels use this to carry the
    /// roads of earlier levels over.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub existing_edges: Vec<[u32; 2]>,
}

/// Floor plan or game level (docs/formulation.md §4–§5).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RoomMode {
    /// Corridors between rooms: (17) no corridor inside a room, (18) every room touches one.
    Floorplan,
    /// A traversal through blocks: (19) every block is traversed, (20) nothing runs along a
    /// block's boundary.
    Game,
}

/// A room template in a spec: a named shape or an explicit cell list.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TemplateSpec {
    /// The room type's name (also its legend entry).
    pub name: String,
    /// `"rect AxB"` or `"L AxB"`; or give `cells`.
    #[serde(default)]
    pub shape: Option<String>,
    /// Explicit unit cells `[x, y]`.
    #[serde(default)]
    pub cells: Option<Vec<[i32; 2]>>,
    /// Fill colour in pictures (any SVG colour).
    #[serde(default)]
    pub color: Option<String>,
    /// Allow the four rotations (default true).
    #[serde(default = "yes")]
    pub rotations: bool,
    /// Allow reflections (default true).
    #[serde(default = "yes")]
    pub reflections: bool,
    /// At least this many rooms of this type.
    #[serde(default)]
    pub min: Option<u32>,
    /// At most this many.
    #[serde(default)]
    pub max: Option<u32>,
    /// Exactly this many (e.g. the boss room once).
    #[serde(default)]
    pub exact: Option<u32>,
}

fn yes() -> bool {
    true
}

/// The kind of game level (paper §5.3).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LevelType {
    /// Branches allowed (block graph: any connected graph, e.g. a tree).
    Branching,
    /// No branches, one sink (block graph: a cycle).
    Circular,
    /// No branches, two sinks on the boundary (block graph: a path).
    Linear,
}

/// Room tiling settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoomsSpec {
    /// Floor plan or game level.
    pub mode: RoomMode,
    /// Game levels: the level type (sets `features.branches` and checks the sinks).
    #[serde(default)]
    pub level: Option<LevelType>,
    /// The templates.
    pub templates: Vec<TemplateSpec>,
    /// Cap on enumerated placements (reported when hit).
    #[serde(default = "default_max_placements")]
    pub max_placements: usize,
}

fn default_max_placements() -> usize {
    200_000
}

/// Solver settings in a spec (the command line overrides each).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Backend name.
    #[serde(default)]
    pub name: Option<SolverKind>,
    /// Time limit in seconds.
    #[serde(default)]
    pub time_limit: Option<f64>,
    /// Relative gap.
    #[serde(default)]
    pub gap: Option<f64>,
    /// Absolute gap.
    #[serde(default)]
    pub abs_gap: Option<f64>,
    /// Node limit.
    #[serde(default)]
    pub node_limit: Option<u64>,
    /// Threads.
    #[serde(default)]
    pub threads: Option<u32>,
    /// Seed.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Solve in two phases when the objective has two scales (`solvers::split`); the solve
    /// strategy's switches (this and the three below) change no row of the model, and each
    /// defaults to what was measured best for the recipe (`pipeline::Strategy`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split_objective: Option<bool>,
    /// Round the backend's bound up to the objective's lattice (`solvers::lattice`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objective_lattice: Option<bool>,
    /// Hand the backend the settings measured on the recipe's models (each backend's own
    /// `Solver::strategy_hints`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solver_tuning: Option<bool>,
    /// The backend's parallel tree search when the solve has two threads or more.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parallel_search: Option<bool>,
    /// A large-neighbourhood search from the start before the full MILP (`pipeline::lns`);
    /// unset, `strong` searches on models of `pipeline::strategy::LNS_FROM_NONZEROS` nonzeros
    /// or more.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lns: Option<bool>,
}

/// A text field without control characters (they break pictures and file formats later).
pub fn check_text(field: &str, text: &str) -> Result<(), SpecErrorKind> {
    match text.chars().find(|c| c.is_control()) {
        Some(c) => Err(SpecErrorKind::Field {
            field: field.into(),
            message: format!("contains the control character U+{:04X}", c as u32),
        }),
        None => Ok(()),
    }
}

/// Every coordinate of `points` finite.
pub fn check_points(field: &str, points: &[[f64; 2]]) -> Result<(), SpecErrorKind> {
    match points.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        Some(i) => Err(SpecErrorKind::Field {
            field: format!("{field}[{i}]"),
            message: format!("coordinates must be finite numbers, got [{}, {}]", points[i][0], points[i][1]),
        }),
        None => Ok(()),
    }
}

/// Why a spec file could not be used.
#[derive(Debug, thiserror::Error)]
pub enum SpecErrorKind {
    /// The file could not be read.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// TOML syntax or schema error (the message names the line and key).
    #[error("{0}")]
    Toml(String),
    /// JSON syntax or schema error.
    #[error("{0}")]
    Json(#[from] serde_json::Error),
    /// A field's value is unusable.
    #[error("field `{field}`: {message}")]
    Field {
        /// Dotted path of the field, e.g. `sinks.vertices[3]`.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// The mesh could not be built or read.
    #[error("field `mesh`: {0}")]
    Mesh(String),
}

impl SpecErrorKind {
    /// The field the error names, dotted (`sinks.vertices[3]`; `mesh` for the mesh), if it names
    /// one.
    pub fn field(&self) -> Option<String> {
        match self {
            SpecErrorKind::Field { field, .. } => Some(field.clone()),
            SpecErrorKind::Mesh(_) => Some("mesh".to_string()),
            _ => None,
        }
    }
}

/// The dotted field of a TOML spec a schema error is at (`mesh.grid.width`), found by reading
/// `text` again with the path tracked; `None` for valid text, a syntax error, or an error of the
/// whole document. ([`SpecErrorKind::Toml`]'s message names the line.)
pub fn toml_error_field(text: &str) -> Option<String> {
    let value: toml::Value = toml::from_str(text).ok()?;
    let e = serde_path_to_error::deserialize::<_, Spec>(value).err()?;
    let path = e.path().to_string();
    (path != ".").then_some(path)
}

/// A spec error, naming the file.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", path.display())]
pub struct SpecError {
    /// The spec file (or `<inline>`).
    pub path: PathBuf,
    /// What is wrong.
    #[source]
    pub kind: SpecErrorKind,
}

impl Spec {
    /// Reads a `.toml` or `.json` spec file.
    pub fn load(path: &Path) -> Result<Spec, SpecError> {
        let err = |kind| SpecError { path: path.to_path_buf(), kind };
        let text = crate::io::read_utf8(path).map_err(|e| err(e.into()))?;
        if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
            Spec::from_json(&text).map_err(err)
        } else {
            Spec::from_toml(&text).map_err(err)
        }
    }

    /// Parses TOML text and checks its values ([`Spec::check_values`]).
    pub fn from_toml(text: &str) -> Result<Spec, SpecErrorKind> {
        let spec: Spec = toml::from_str(text).map_err(|e| SpecErrorKind::Toml(e.to_string()))?;
        spec.check_values()?;
        Ok(spec)
    }

    /// Parses JSON text and checks its values ([`Spec::check_values`]).
    pub fn from_json(text: &str) -> Result<Spec, SpecErrorKind> {
        let spec: Spec = serde_json::from_str(text)?;
        spec.check_values()?;
        Ok(spec)
    }

    /// Checks every value where it is read, before any work: text without control characters
    /// (`name`, `description`, template names), every coordinate finite. Errors name the field.
    pub fn check_values(&self) -> Result<(), SpecErrorKind> {
        check_text("name", &self.name)?;
        check_text("description", &self.description)?;
        if let Some(c) = &self.mesh.clipped {
            check_points("mesh.clipped.outer", &c.outer)?;
            for (i, h) in c.holes.iter().enumerate() {
                check_points(&format!("mesh.clipped.holes[{i}]"), h)?;
            }
        }
        check_points("sinks.points", &self.sinks.points)?;
        for (i, poly) in self.user.obstacle_polygons.iter().enumerate() {
            check_points(&format!("user.obstacle_polygons[{i}]"), poly)?;
        }
        for (i, p) in self.user.forced_vertices.iter().enumerate() {
            if let Place::Point(pt) = p {
                check_points(&format!("user.forced_vertices[{i}]"), std::slice::from_ref(pt))?;
            }
        }
        for (i, r) in self.user.through_routes.iter().enumerate() {
            for (end, p) in [("from", &r.from), ("to", &r.to)] {
                if let Place::Point(pt) = p {
                    check_points(&format!("user.through_routes[{i}].{end}"), std::slice::from_ref(pt))?;
                }
            }
        }
        if let Some(rooms) = &self.rooms {
            for (i, t) in rooms.templates.iter().enumerate() {
                check_text(&format!("rooms.templates[{i}].name"), &t.name)?;
            }
        }
        Ok(())
    }
}

/// A setting refused before any run (a solve's, a layout's, a traffic run's): where it came from
/// and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{place} {reason}")]
pub struct SettingsError {
    /// The flag, or the file and field (`fig2b.toml: solver.gap`).
    pub place: String,
    /// What is wrong with it.
    pub reason: String,
}
