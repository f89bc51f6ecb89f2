//! From a [`Spec`] to a [`Problem`]: the mesh, edge roles, sinks and switches, checked.

use super::Template;
use super::*;
use crate::mesh::paths::{dijkstra, Search};
use crate::mesh::{self, EdgeId, FaceId, Mesh, VertexId};

/// What an edge is in the model (docs/formulation.md §1).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EdgeRole {
    /// A decision variable.
    Candidate,
    /// Fixed active (an existing road); not a variable.
    Existing,
    /// Fixed inactive (wall, obstacle).
    Excluded,
}

/// A resolved weight.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase", tag = "mode", content = "value")]
pub enum Weight {
    /// Weight 0: nothing is emitted.
    Off,
    /// A positive weight: indicator variables and objective terms.
    Penalty(f64),
    /// Forbidden: constraints, no indicators.
    Forbid,
}

impl Weight {
    /// The objective weight (0 unless penalised).
    pub fn value(self) -> f64 {
        match self {
            Weight::Penalty(w) => w,
            _ => 0.0,
        }
    }
}

/// Resolved point-to-point settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointToPoint {
    /// Part number of every face (`u32::MAX` for obstacle faces).
    pub face_part: Vec<u32>,
    /// Extra edges over the shortest path.
    pub tolerance: usize,
    /// Seed for sampling.
    pub seed: u64,
    /// Cap on paths per pair.
    pub max_paths: usize,
}

/// Resolved room-tiling settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rooms {
    /// Floor plan or game level.
    pub mode: RoomMode,
    /// Game levels: the level type.
    pub level: Option<LevelType>,
    /// The templates, in spec order.
    pub templates: Vec<Template>,
    /// Per template: (min, max) count of rooms, if constrained.
    pub counts: Vec<(Option<u32>, Option<u32>)>,
    /// Fill colour per template.
    pub colors: Vec<String>,
    /// Cap on enumerated placements.
    pub max_placements: usize,
}

const PALETTE: [&str; 8] = ["#8dd3c7", "#ffffb3", "#bebada", "#fb8072", "#80b1d3", "#fdb462", "#b3de69", "#fccde5"];

fn parse_shape(field: &str, name: &str, shape: &str) -> Result<Template, SpecErrorKind> {
    let bad = || {
        SpecErrorKind::Field {
        field: field.to_string(),
        message: format!("expected \"rect AxB\", \"L AxB\" or \"T AxB\" (A, B between 1 and 20; L: A, B ≥ 2; T: A odd ≥ 3, B ≥ 2), got {shape:?}"),
    }
    };
    let mut parts = shape.split_whitespace();
    let (kind, dims) = (parts.next().ok_or_else(bad)?, parts.next().ok_or_else(bad)?);
    if parts.next().is_some() {
        return Err(bad());
    }
    let (a, b) = dims.split_once(['x', '×']).ok_or_else(bad)?;
    let (a, b): (i32, i32) = (a.parse().map_err(|_| bad())?, b.parse().map_err(|_| bad())?);
    if !(1..=20).contains(&a) || !(1..=20).contains(&b) {
        return Err(bad());
    }
    match kind.to_ascii_lowercase().as_str() {
        "rect" => Ok(Template::rect(name, a, b)),
        "l" if a >= 2 && b >= 2 => Ok(Template::l_shape(name, a, b)),
        "t" if a >= 3 && a % 2 == 1 && b >= 2 => {
            // A bar of A cells on top, a stem of B − 1 cells below its middle.
            let mut cells: Vec<(i32, i32)> = (0..a).map(|x| (x, b - 1)).chain((0..b - 1).map(|y| (a / 2, y))).collect();
            cells.sort();
            Ok(Template { name: name.to_string(), cells, rotations: true, reflections: true })
        }
        _ => Err(bad()),
    }
}

impl RoomsSpec {
    fn resolve(&self) -> Result<Rooms, SpecErrorKind> {
        if self.templates.is_empty() {
            return Err(field("rooms.templates", "give at least one template"));
        }
        let mut out = Rooms {
            mode: self.mode,
            level: self.level,
            templates: Vec::new(),
            counts: Vec::new(),
            colors: Vec::new(),
            max_placements: self.max_placements,
        };
        for (i, t) in self.templates.iter().enumerate() {
            let f = format!("rooms.templates[{i}]");
            let mut tpl = match (&t.shape, &t.cells) {
                (Some(s), None) => parse_shape(&format!("{f}.shape"), &t.name, s)?,
                (None, Some(cells)) => {
                    if cells.is_empty() || cells.iter().any(|c| c[0] < 0 || c[1] < 0 || c[0] > 50 || c[1] > 50) {
                        return Err(field(
                            format!("{f}.cells"),
                            "cells must be a non-empty list of [x, y] with 0 ≤ x, y ≤ 50",
                        ));
                    }
                    let mut cs: Vec<(i32, i32)> = cells.iter().map(|c| (c[0], c[1])).collect();
                    cs.sort();
                    if cs.windows(2).any(|w| w[0] == w[1]) {
                        return Err(field(format!("{f}.cells"), "a cell is listed twice"));
                    }
                    Template { name: t.name.clone(), cells: cs, rotations: true, reflections: true }
                }
                _ => return Err(field(&f, "give exactly one of `shape` or `cells`")),
            };
            tpl.rotations = t.rotations;
            tpl.reflections = t.reflections;
            let (lo, hi) = match (t.exact, t.min, t.max) {
                (Some(e), None, None) => (Some(e), Some(e)),
                (Some(_), _, _) => return Err(field(&f, "`exact` cannot be combined with `min` or `max`")),
                (None, lo, hi) => {
                    if let (Some(a), Some(b)) = (lo, hi) {
                        if a > b {
                            return Err(field(&f, format!("min {a} is above max {b}")));
                        }
                    }
                    (lo, hi)
                }
            };
            out.templates.push(tpl);
            out.counts.push((lo, hi));
            out.colors.push(t.color.clone().unwrap_or_else(|| PALETTE[i % PALETTE.len()].to_string()));
        }
        Ok(out)
    }
}

/// A specification resolved against its mesh: everything the formulation needs.
#[derive(Clone, Debug)]
pub struct Problem {
    /// The spec it came from.
    pub spec: Spec,
    /// The mesh.
    pub mesh: Mesh,
    /// Role of every edge.
    pub roles: Vec<EdgeRole>,
    /// Whether each vertex is a sink.
    pub is_sink: Vec<bool>,
    /// Whether each vertex is an obstacle (exempt from coverage, never active).
    pub is_obstacle_vertex: Vec<bool>,
    /// Whether each face is an obstacle.
    pub is_obstacle_face: Vec<bool>,
    /// Edges that must be active (candidate edges fixed to 1, plus through routes).
    pub forced_edges: Vec<EdgeId>,
    /// Vertices that must be active.
    pub forced_vertices: Vec<VertexId>,
    /// Through routes as vertex sequences (shortest paths).
    pub through_routes: Vec<Vec<VertexId>>,
    /// Coverage range.
    pub coverage_range: f64,
    /// Coverage model.
    pub coverage_model: CoverageModel,
    /// λL.
    pub w_length: f64,
    /// λD.
    pub w_distance: f64,
    /// λ of the per-vertex travel term (`weights.travel`).
    pub w_travel: f64,
    /// λZ0 (zig-zags).
    pub w_zigzag: Weight,
    /// λZ1 (too close).
    pub w_too_close: Weight,
    /// λT (T-junctions).
    pub w_t_junction: Weight,
    /// Dead-ends allowed?
    pub dead_ends: Allow,
    /// Branches allowed?
    pub branches: Allow,
    /// Point-to-point, if on.
    pub p2p: Option<PointToPoint>,
    /// The formulation recipe asked for (resolved into families by
    /// [`crate::formulations::Recipe::resolve`]).
    pub formulation: FormulationSpec,
    /// Room tiling, if on.
    pub rooms: Option<Rooms>,
}

fn field(field: impl Into<String>, message: impl Into<String>) -> SpecErrorKind {
    SpecErrorKind::Field { field: field.into(), message: message.into() }
}

fn weight(name: &str, w: &WeightValue, forbid_ok: bool) -> Result<Weight, SpecErrorKind> {
    match w {
        WeightValue::Number(x) if !x.is_finite() || *x < 0.0 => {
            Err(field(format!("weights.{name}"), format!("must be a non-negative number or \"forbid\", got {x}")))
        }
        WeightValue::Number(x) if *x == 0.0 => Ok(Weight::Off),
        WeightValue::Number(x) => Ok(Weight::Penalty(*x)),
        WeightValue::Word(s) if forbid_ok && (s == "forbid" || s == "inf") => Ok(Weight::Forbid),
        WeightValue::Word(s) => Err(field(
            format!("weights.{name}"),
            if forbid_ok {
                format!("expected a number or \"forbid\", got {s:?}")
            } else {
                format!("expected a number, got {s:?}")
            },
        )),
    }
}

impl Spec {
    /// Builds the mesh and resolves every field. `base` is the directory relative to which
    /// mesh files are found.
    pub fn resolve(&self, base: &Path) -> Result<Problem, SpecErrorKind> {
        self.resolve_within(base, DEFAULT_MAX_CELLS)
    }

    /// [`Spec::resolve`] with a cap on the mesh's size: a mesh whose cells (faces) would exceed
    /// `max_cells` is refused before it is built, with the estimate in the message.
    pub fn resolve_within(&self, base: &Path, max_cells: usize) -> Result<Problem, SpecErrorKind> {
        self.resolve_on_mesh(self.build_mesh(base, max_cells)?)
    }

    /// Resolves every field against a mesh built elsewhere (the spec's `mesh` section is not
    /// read): street levels use this for their generated and subdivided meshes.
    pub fn resolve_on_mesh(&self, mesh: Mesh) -> Result<Problem, SpecErrorKind> {
        let nv = mesh.num_vertices();
        let nf = mesh.num_faces();
        let vid = |f: String, v: u32| -> Result<VertexId, SpecErrorKind> {
            if (v as usize) < nv {
                Ok(VertexId(v))
            } else {
                Err(field(f, format!("vertex {v} does not exist (the mesh has {nv} vertices)")))
            }
        };
        let edge_of = |f: String, [a, b]: [u32; 2]| -> Result<EdgeId, SpecErrorKind> {
            let (va, vb) = (vid(f.clone(), a)?, vid(f.clone(), b)?);
            mesh.half_edge_between(va, vb)
                .map(|h| mesh.he_edge(h))
                .ok_or_else(|| field(f, format!("vertices {a} and {b} are not joined by a mesh edge")))
        };
        let place = |f: String, p: &Place| -> Result<VertexId, SpecErrorKind> {
            match p {
                Place::Vertex(v) => vid(f, *v),
                Place::Point(pt) => mesh.nearest_vertex(*pt).ok_or_else(|| field(f, "the mesh has no vertex")),
            }
        };

        // Roles from the boundary switch.
        let mut roles: Vec<EdgeRole> = mesh
            .edges()
            .map(|e| match (mesh.is_boundary_edge(e), self.boundary) {
                (true, BoundaryRole::Road) => EdgeRole::Existing,
                (true, BoundaryRole::Wall) => EdgeRole::Excluded,
                _ => EdgeRole::Candidate,
            })
            .collect();

        // Obstacles.
        let u = &self.user;
        let mut is_obstacle_face = vec![false; nf];
        for (i, &f) in u.obstacle_faces.iter().enumerate() {
            if f as usize >= nf {
                return Err(field(
                    format!("user.obstacle_faces[{i}]"),
                    format!("face {f} does not exist (the mesh has {nf} faces)"),
                ));
            }
            is_obstacle_face[f as usize] = true;
        }
        for (i, poly) in u.obstacle_polygons.iter().enumerate() {
            if poly.len() < 3 {
                return Err(field(format!("user.obstacle_polygons[{i}]"), "a polygon needs at least 3 points"));
            }
            for f in mesh.faces() {
                if crate::geometry::ring_contains(poly, mesh.face_centroid(f)) {
                    is_obstacle_face[f.index()] = true;
                }
            }
        }
        let mut is_obstacle_vertex = vec![false; nv];
        for (i, &v) in u.obstacle_vertices.iter().enumerate() {
            is_obstacle_vertex[vid(format!("user.obstacle_vertices[{i}]"), v)?.index()] = true;
        }
        // A vertex all of whose faces are obstacle faces lies inside the obstacle.
        for f in mesh.faces().filter(|f| is_obstacle_face[f.index()]) {
            for e in mesh.face_edges(f) {
                roles[e.index()] = EdgeRole::Excluded;
            }
            for &v in mesh.face_vertices(f) {
                let interior = mesh.outgoing(v).iter().all(|&h| {
                    let faces = [mesh.he_face(h), mesh.he_face(mesh.he_twin(h))];
                    faces.iter().all(|f| f.is_none_or(|f: FaceId| is_obstacle_face[f.index()]))
                });
                if interior && !mesh.is_boundary_vertex(v) {
                    is_obstacle_vertex[v.index()] = true;
                }
            }
        }
        for v in mesh.vertices().filter(|v| is_obstacle_vertex[v.index()]) {
            for e in mesh.incident_edges(v) {
                roles[e.index()] = EdgeRole::Excluded;
            }
        }
        for (i, &pair) in u.obstacle_edges.iter().enumerate() {
            let e = edge_of(format!("user.obstacle_edges[{i}]"), pair)?;
            roles[e.index()] = EdgeRole::Excluded;
        }
        let mut existing_ends = Vec::new();
        for (i, &pair) in u.existing_edges.iter().enumerate() {
            let f = format!("user.existing_edges[{i}]");
            let e = edge_of(f.clone(), pair)?;
            if roles[e.index()] == EdgeRole::Excluded {
                return Err(field(
                    f,
                    format!("edge {}–{} is an existing road but excluded (an obstacle or a wall)", pair[0], pair[1]),
                ));
            }
            roles[e.index()] = EdgeRole::Existing;
            existing_ends.extend(pair);
        }

        // Sinks.
        let mut is_sink = vec![false; nv];
        if self.sinks.all_boundary {
            for v in mesh.boundary_vertices() {
                is_sink[v.index()] = true;
            }
        }
        for (i, &v) in self.sinks.vertices.iter().enumerate() {
            is_sink[vid(format!("sinks.vertices[{i}]"), v)?.index()] = true;
        }
        for (i, p) in self.sinks.points.iter().enumerate() {
            is_sink[place(format!("sinks.points[{i}]"), &Place::Point(*p))?.index()] = true;
        }
        for v in existing_ends {
            is_sink[v as usize] = true;
        }
        if !is_sink.iter().any(|&s| s) {
            return Err(field("sinks", "no sink: set all_boundary, vertices or points"));
        }
        if let Some(v) = mesh.vertices().find(|v| is_sink[v.index()] && is_obstacle_vertex[v.index()]) {
            return Err(field("sinks", format!("vertex {} is both a sink and an obstacle", v.0)));
        }
        for e in mesh.edges().filter(|e| roles[e.index()] == EdgeRole::Existing) {
            let (a, b) = mesh.edge_vertices(e);
            for v in [a, b] {
                if !is_sink[v.index()] {
                    return Err(field(
                        "sinks",
                        format!("existing edge {}–{} touches vertex {}, which is not a sink (existing edges must join sinks; with boundary = \"road\" set sinks.all_boundary)", a.0, b.0, v.0),
                    ));
                }
            }
        }

        // Forced elements.
        let mut forced_edges = Vec::new();
        for (i, &pair) in u.forced_edges.iter().enumerate() {
            let f = format!("user.forced_edges[{i}]");
            let e = edge_of(f.clone(), pair)?;
            if roles[e.index()] == EdgeRole::Excluded {
                return Err(field(
                    f,
                    format!("edge {}–{} is forced but excluded (an obstacle or a wall)", pair[0], pair[1]),
                ));
            }
            forced_edges.push(e);
        }
        let mut forced_vertices = Vec::new();
        for (i, v) in u.forced_vertices.iter().enumerate() {
            let f = format!("user.forced_vertices[{i}]");
            let v = place(f.clone(), v)?;
            if is_obstacle_vertex[v.index()] || mesh.incident_edges(v).all(|e| roles[e.index()] == EdgeRole::Excluded) {
                return Err(field(f, format!("vertex {} is forced active but has no usable edge", v.0)));
            }
            forced_vertices.push(v);
        }
        let mut through_routes = Vec::new();
        for (i, r) in u.through_routes.iter().enumerate() {
            let f = format!("user.through_routes[{i}]");
            let (a, b) = (place(format!("{f}.from"), &r.from)?, place(format!("{f}.to"), &r.to)?);
            if a == b {
                return Err(field(f, "both ends are the same vertex"));
            }
            let path = shortest_path(&mesh, &roles, a, b).ok_or_else(|| {
                field(f.clone(), format!("no path from vertex {} to {} avoids walls and obstacles", a.0, b.0))
            })?;
            through_routes.push(path);
        }

        // Game level types fix the branch switch and the number of sinks.
        let mut branches = self.features.branches;
        if let Some(r) = &self.rooms {
            let sinks: Vec<VertexId> = mesh.vertices().filter(|v| is_sink[v.index()]).collect();
            match (r.mode, r.level) {
                (RoomMode::Floorplan, Some(_)) => {
                    return Err(field("rooms.level", "level types are for mode = \"game\""))
                }
                (RoomMode::Game, Some(LevelType::Branching)) => branches = Allow::Allow,
                (RoomMode::Game, Some(level @ (LevelType::Circular | LevelType::Linear)))
                    if self.features.dead_ends == Allow::Allow =>
                {
                    let what = if level == LevelType::Linear {
                        "a linear level is one path from one boundary sink to the other through every block"
                    } else {
                        "a circular level is one cycle through the sink and every block"
                    };
                    return Err(field(
                        "features.dead_ends",
                        format!("\"allow\" contradicts rooms.level = \"{}\": {what}, so it has no dead-ends (leave features.dead_ends at its default, \"forbid\")", if level == LevelType::Linear { "linear" } else { "circular" }),
                    ));
                }
                (RoomMode::Game, Some(LevelType::Circular)) => {
                    if sinks.len() != 1 {
                        return Err(field(
                            "sinks",
                            format!("a circular level has exactly one sink, the spec gives {}", sinks.len()),
                        ));
                    }
                    branches = Allow::Forbid;
                }
                (RoomMode::Game, Some(LevelType::Linear)) => {
                    if sinks.len() != 2 || sinks.iter().any(|&v| !mesh.is_boundary_vertex(v)) {
                        return Err(field("sinks", "a linear level has exactly two sinks, both on the boundary"));
                    }
                    branches = Allow::Forbid;
                }
                _ => {}
            }
        }

        // Switches.
        if !(self.coverage.range >= 1.0 && self.coverage.range.is_finite()) {
            return Err(field(
                "coverage.range",
                format!("must be a finite number of at least 1, got {}", self.coverage.range),
            ));
        }
        let w = &self.weights;
        let p2p = match &self.point_to_point {
            None => None,
            Some(p) => Some(PointToPoint {
                face_part: self.partition(&mesh, p, &is_obstacle_face)?,
                tolerance: p.tolerance,
                seed: p.seed,
                max_paths: p.max_paths.max(1),
            }),
        };
        Ok(Problem {
            spec: self.clone(),
            roles,
            is_sink,
            is_obstacle_vertex,
            is_obstacle_face,
            forced_edges,
            forced_vertices,
            through_routes,
            coverage_range: self.coverage.range,
            coverage_model: self.coverage.model,
            w_length: weight("length", &w.length, false)?.value(),
            w_distance: weight("distance", &w.distance, false)?.value(),
            w_travel: weight("travel", &w.travel, false)?.value(),
            w_zigzag: weight("zigzag", &w.zigzag, true)?,
            w_too_close: weight("too_close", &w.too_close, true)?,
            w_t_junction: weight("t_junction", &w.t_junction, true)?,
            dead_ends: self.features.dead_ends,
            branches,
            p2p,
            formulation: self.formulation.clone(),
            rooms: self.rooms.as_ref().map(RoomsSpec::resolve).transpose()?,
            mesh,
        })
    }

    fn build_mesh(&self, base: &Path, max_cells: usize) -> Result<Mesh, SpecErrorKind> {
        let too_big = |field: &str, cells: f64, what: String| {
            SpecErrorKind::Field {
                field: field.into(),
                message: format!(
                    "{what} gives about {cells:.0} cells, above the limit of {max_cells} (raise it with --max-cells if the machine can take it)"
                ),
            }
        };
        let m = &self.mesh;
        let given = [m.grid.is_some(), m.clipped.is_some(), m.file.is_some()].iter().filter(|&&b| b).count();
        if given != 1 {
            return Err(field("mesh", "give exactly one of `grid`, `clipped` or `file`"));
        }
        let mesh = if let Some(g) = &m.grid {
            if g.width == 0 || g.height == 0 {
                return Err(field("mesh.grid", format!("size {}×{} must be at least 1×1", g.width, g.height)));
            }
            let cells = g.width as f64 * g.height as f64;
            if cells > max_cells as f64 {
                return Err(too_big("mesh.grid", cells, format!("{}×{}", g.width, g.height)));
            }
            if !(g.spacing > 0.0 && g.spacing.is_finite()) {
                return Err(field("mesh.grid.spacing", "must be a positive number"));
            }
            mesh::try_grid(g.width, g.height, g.spacing).map_err(|e| field("mesh.grid", e.to_string()))?
        } else if let Some(c) = &m.clipped {
            if !(c.spacing > 0.0 && c.spacing.is_finite()) {
                return Err(field("mesh.clipped.spacing", "must be a positive number"));
            }
            // The cells of the grid over the outer polygon's bounding box: an upper bound.
            let span = |k: usize| {
                let (lo, hi) =
                    c.outer.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p[k]), hi.max(p[k])));
                if hi > lo {
                    ((hi - lo) / c.spacing).ceil()
                } else {
                    0.0
                }
            };
            let cells = span(0) * span(1);
            if cells > max_cells as f64 {
                return Err(too_big("mesh.clipped.spacing", cells, format!("spacing {}", c.spacing)));
            }
            mesh::clipped_grid(&c.outer, &c.holes, c.spacing).map_err(|e| SpecErrorKind::Mesh(e.to_string()))?
        } else {
            let path = base.join(m.file.as_ref().expect("one source"));
            let text =
                crate::io::read_utf8(&path).map_err(|e| SpecErrorKind::Mesh(format!("{}: {e}", path.display())))?;
            if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
                serde_json::from_str(&text).map_err(|e| SpecErrorKind::Mesh(format!("{}: {e}", path.display())))?
            } else {
                mesh::from_obj(&text).map_err(|e| SpecErrorKind::Mesh(format!("{}: {e}", path.display())))?
            }
        };
        if mesh.num_faces() > max_cells {
            return Err(too_big("mesh.file", mesh.num_faces() as f64, "the file".into()));
        }
        Ok(match &m.jitter {
            Some(j) if j.amount > 0.0 && j.amount < 0.5 => mesh::jitter(&mesh, j.amount, j.seed),
            Some(j) if j.amount == 0.0 => mesh,
            Some(j) => return Err(field("mesh.jitter.amount", format!("must be in [0, 0.5), got {}", j.amount))),
            None => mesh,
        })
    }

    fn partition(&self, mesh: &Mesh, p: &PointToPointSpec, obstacle: &[bool]) -> Result<Vec<u32>, SpecErrorKind> {
        let nf = mesh.num_faces();
        let mut parts = match (&p.blocks, &p.parts) {
            (Some(_), Some(_)) | (None, None) => {
                return Err(field("point_to_point", "give exactly one of `blocks` or `parts`"));
            }
            (Some(k), None) => {
                if *k < 2 {
                    return Err(field("point_to_point.blocks", "need at least 2 blocks per side"));
                }
                let (lo, hi) = mesh.bounding_box();
                mesh.faces()
                    .map(|f| {
                        let c = mesh.face_centroid(f);
                        let bx = (((c[0] - lo[0]) / (hi[0] - lo[0]) * *k as f64) as usize).min(k - 1);
                        let by = (((c[1] - lo[1]) / (hi[1] - lo[1]) * *k as f64) as usize).min(k - 1);
                        (by * k + bx) as u32
                    })
                    .collect::<Vec<u32>>()
            }
            (None, Some(parts)) => {
                if parts.len() != nf {
                    return Err(field(
                        "point_to_point.parts",
                        format!("has {} entries; the mesh has {nf} faces", parts.len()),
                    ));
                }
                parts.clone()
            }
        };
        for (f, part) in parts.iter_mut().enumerate() {
            if obstacle[f] {
                *part = u32::MAX;
            }
        }
        Ok(parts)
    }
}

/// Shortest path by length over non-excluded edges (Dijkstra; ties broken by vertex id, so
/// the route is deterministic).
pub(crate) fn shortest_path(mesh: &Mesh, roles: &[EdgeRole], a: VertexId, b: VertexId) -> Option<Vec<VertexId>> {
    let mut dist = vec![f64::INFINITY; mesh.num_vertices()];
    dist[a.index()] = 0.0;
    let usable = |h| roles[mesh.he_edge(h).index()] != EdgeRole::Excluded;
    let prev = dijkstra(mesh, &mut dist, [a], &Search { usable, tolerance: 1e-12, target: Some(b) });
    if !dist[b.index()].is_finite() {
        return None;
    }
    let mut path = vec![b];
    while let Some(&v) = path.last().filter(|&&v| v != a) {
        path.push(VertexId(prev[v.index()]));
    }
    path.reverse();
    Some(path)
}

/// The default cap on a mesh's cells (faces): 250,000, a 500 × 500 grid — far above the paper's
/// examples (the largest has a few thousand), below what makes a model too big for memory.
pub const DEFAULT_MAX_CELLS: usize = 250_000;
