//! Infeasibility explained: when a design spec has no solution, which of its requirements
//! conflict.
//!
//! The spec's requirements are listed at the level a user writes them: coverage, no dead-ends,
//! no branches, each forbidden configuration kind, each wall edge, each obstacle entry, each
//! forced edge and vertex, each through route, point-to-point, the room tiling, each room-type
//! count and the game level type ([`Requirement`]). A set of requirements is *kept*, the rest
//! *relaxed*: the spec is edited (the relaxed entries dropped, switches set to allow), resolved
//! on the same mesh, built with [`pipeline::build`], the objective set aside (every cost 0),
//! and solved with [`pipeline::solve_built`] on any backend under a short time limit:
//! infeasible, feasible (a solution that netspec's own checker accepts), or unknown (the limit
//! came first — reported as such, never guessed). Before building, what no design can use is
//! closed (edges in a component without a sink: every active edge leads to a sink), and rows
//! left without variables but violated are infeasible as built — so a sink or forced element cut
//! off by walls or obstacles needs no search. Coverage (6) is relaxed on the built model (its
//! rows, named `cov6_…`, and the rows derived from them, `covedge_…` and `covball_…`, made
//! free): the spec has no switch for it.
//!
//! A **deletion filter** finds one minimal conflicting set: family by family (all walls, all
//! obstacles, … at once), then element by element inside the families that remain, halving
//! chunks first. **Every conflict** is then found by Reiter's hitting-set tree: each node relaxes
//! one more requirement of a known conflict (the walls, or the obstacle entries, of a conflict
//! together: a fence is one contradiction, and its pieces would only give it again); a node that
//! is still infeasible yields a new conflict, a feasible one a *repair* (requirements whose
//! relaxation together makes the spec feasible). The search stops at its budget (time,
//! conflicts, depth) and says whether it finished.
//!
//! Checks are cached, and a set is known feasible when a superset was, infeasible when a subset
//! was (relaxing requirements only removes constraints). That holds here except for specs where
//! dropping an obstacle adds work: faces to tile with rooms, parts to join by point-to-point
//! paths; there the inference is off. Through routes keep the path they had in the full spec.

use crate::mesh::{EdgeId, VertexId};
use crate::milp::VarId;
use crate::pipeline;
use crate::solvers::{SolveOptions, SolverKind, Termination};
use crate::spec::{Allow, BoundaryRole, CoverageModel, EdgeRole, LevelType, Problem, Spec, WeightValue};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::time::Instant;

/// A forbidden local configuration kind (weight `"forbid"`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ForbiddenKind {
    /// `weights.zigzag = "forbid"`.
    Zigzag,
    /// `weights.too_close = "forbid"`.
    TooClose,
    /// `weights.t_junction = "forbid"`.
    TJunction,
}

impl ForbiddenKind {
    fn key(self) -> &'static str {
        match self {
            ForbiddenKind::Zigzag => "zigzag",
            ForbiddenKind::TooClose => "too_close",
            ForbiddenKind::TJunction => "t_junction",
        }
    }
}

/// One requirement of a spec that can be relaxed on its own.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Requirement {
    /// Coverage (6): every vertex near an active one.
    Coverage,
    /// No dead-ends at non-sinks (`features.dead_ends = "forbid"`).
    DeadEnds,
    /// No branches (`features.branches = "forbid"`).
    Branches,
    /// A forbidden configuration kind.
    Forbidden {
        /// Which.
        config: ForbiddenKind,
    },
    /// A boundary edge that is a wall (`boundary = "wall"`).
    Wall {
        /// The edge id.
        edge: u32,
    },
    /// `user.obstacle_vertices[index]`.
    ObstacleVertex {
        /// Index in the spec's list.
        index: usize,
    },
    /// `user.obstacle_edges[index]`.
    ObstacleEdge {
        /// Index in the spec's list.
        index: usize,
    },
    /// `user.obstacle_faces[index]`.
    ObstacleFace {
        /// Index in the spec's list.
        index: usize,
    },
    /// `user.obstacle_polygons[index]`.
    ObstaclePolygon {
        /// Index in the spec's list.
        index: usize,
    },
    /// `user.forced_edges[index]`.
    ForcedEdge {
        /// Index in the spec's list.
        index: usize,
    },
    /// `user.forced_vertices[index]`.
    ForcedVertex {
        /// Index in the spec's list.
        index: usize,
    },
    /// `user.through_routes[index]`.
    ThroughRoute {
        /// Index in the spec's list.
        index: usize,
    },
    /// Point-to-point paths between every pair of parts.
    PointToPoint,
    /// Rooms (or blocks) tile the footprint, with the corridor or traversal rules.
    RoomTiling,
    /// `rooms.templates[template]`'s count (`min`, `max` or `exact`).
    RoomCount {
        /// Template index.
        template: usize,
    },
    /// The game level type (`circular` or `linear`: no branches).
    LevelType,
}

/// The family a requirement belongs to (relaxed together in the first pass).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Family {
    Coverage,
    DeadEnds,
    Branches,
    Forbidden(ForbiddenKind),
    Walls,
    Obstacles,
    ForcedEdges,
    ForcedVertices,
    ThroughRoutes,
    PointToPoint,
    RoomTiling,
    RoomCounts,
    LevelType,
}

impl Requirement {
    fn family(self) -> Family {
        match self {
            Requirement::Coverage => Family::Coverage,
            Requirement::DeadEnds => Family::DeadEnds,
            Requirement::Branches => Family::Branches,
            Requirement::Forbidden { config } => Family::Forbidden(config),
            Requirement::Wall { .. } => Family::Walls,
            Requirement::ObstacleVertex { .. }
            | Requirement::ObstacleEdge { .. }
            | Requirement::ObstacleFace { .. }
            | Requirement::ObstaclePolygon { .. } => Family::Obstacles,
            Requirement::ForcedEdge { .. } => Family::ForcedEdges,
            Requirement::ForcedVertex { .. } => Family::ForcedVertices,
            Requirement::ThroughRoute { .. } => Family::ThroughRoutes,
            Requirement::PointToPoint => Family::PointToPoint,
            Requirement::RoomTiling => Family::RoomTiling,
            Requirement::RoomCount { .. } => Family::RoomCounts,
            Requirement::LevelType => Family::LevelType,
        }
    }
}

/// A requirement as reported: what it is, the spec field it comes from, a sentence, and the mesh
/// elements it concerns (for pictures).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RequirementInfo {
    /// The requirement.
    pub requirement: Requirement,
    /// The spec field (`coverage`, `user.forced_edges[2]`, …).
    pub field: String,
    /// What it asks, in words.
    pub text: String,
    /// Vertices it concerns.
    pub vertices: Vec<u32>,
    /// Edges it concerns, as vertex pairs.
    pub edges: Vec<[u32; 2]>,
    /// Faces it concerns.
    pub faces: Vec<u32>,
}

/// A set of requirements that cannot all hold.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Conflict {
    /// The requirements, in a fixed order.
    pub requirements: Vec<RequirementInfo>,
    /// Proven minimal: relaxing any one of them was shown feasible. `false` when a check on the
    /// way hit its time limit (the set still conflicts; it may hold more than it needs).
    pub minimal: bool,
}

/// How the explanation ended.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExplainStatus {
    /// At least one conflict found.
    Explained,
    /// With the objective set aside the spec has a solution: nothing to explain.
    Feasible,
    /// The spec could not be shown infeasible (or no conflict isolated) within the limits.
    Unknown,
    /// Infeasible even with every listed requirement relaxed: the cause is outside them (e.g.
    /// the sinks or existing roads themselves).
    Unexplained,
}

/// The explanation of an infeasible spec.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Explanation {
    /// How it ended.
    pub status: ExplainStatus,
    /// Minimal conflicting sets, in the order found.
    pub conflicts: Vec<Conflict>,
    /// Sets of requirements (their fields, see [`RequirementInfo::short`]) whose relaxation
    /// together makes the spec feasible, as the search found them (one requirement or group of
    /// each conflict; smallest first).
    pub repairs: Vec<Vec<String>>,
    /// The search finished: every conflict is listed (up to the depth and count limits).
    pub complete: bool,
    /// Requirements of the spec that were considered.
    pub requirements: usize,
    /// Feasibility checks solved (cached and inferred ones not counted).
    pub checks: usize,
    /// Checks that ended without an answer (time limit).
    pub unknown_checks: usize,
    /// Wall time, seconds.
    pub seconds: f64,
    /// The backend that ran the checks.
    pub solver: String,
    /// Time limit of each check, seconds.
    pub check_time_limit: f64,
}

/// Limits of the search.
#[derive(Clone, Debug)]
pub struct ExplainOptions {
    /// Time limit of each feasibility check, seconds.
    pub check_time_limit: f64,
    /// Total time budget, seconds.
    pub time_budget: f64,
    /// Stop after this many conflicts.
    pub max_conflicts: usize,
    /// Depth of the hitting-set tree (how many requirements — or groups of walls or obstacle
    /// entries — are relaxed at once to look for more conflicts).
    pub max_depth: usize,
    /// Threads per check.
    pub threads: Option<u32>,
    /// The full spec is already known infeasible (skip the first check).
    pub known_infeasible: bool,
}

impl Default for ExplainOptions {
    fn default() -> Self {
        ExplainOptions {
            check_time_limit: 5.0,
            time_budget: 60.0,
            max_conflicts: 10,
            max_depth: 3,
            threads: None,
            known_infeasible: false,
        }
    }
}

/// The answer of one feasibility check.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// A solution exists (one was found and checked).
    Feasible,
    /// Proven infeasible.
    Infeasible,
    /// Neither, within the limits.
    Unknown,
}

/// The deletion filter's inner loop, for any kind of requirement: `kept` is known infeasible
/// (`check` says whether a set can hold); the `members` of `kept` are dropped in chunks, halving
/// from half the list down to single elements, each drop kept when the rest is still infeasible.
/// On return `kept` has lost every member it could lose. Returns whether the result is proven
/// minimal among `members` (no single-element check came back unknown). The whole of `members`
/// is never dropped at once (the caller knows it is needed).
pub fn deletion_filter<T: Ord + Clone>(
    kept: &mut BTreeSet<T>,
    mut members: Vec<T>,
    mut check: impl FnMut(&BTreeSet<T>) -> Verdict,
) -> bool {
    let mut minimal = true;
    if members.len() < 2 {
        return minimal;
    }
    let mut chunk = members.len().div_ceil(2);
    loop {
        let mut i = 0;
        while i < members.len() {
            let end = (i + chunk).min(members.len());
            if end - i == members.len() {
                i = end; // the whole list: already known to be needed
                continue;
            }
            let without: BTreeSet<T> = kept.iter().filter(|r| !members[i..end].contains(r)).cloned().collect();
            match check(&without) {
                Verdict::Infeasible => {
                    *kept = without;
                    members.drain(i..end);
                }
                v => {
                    if v == Verdict::Unknown && chunk == 1 {
                        minimal = false;
                    }
                    i = end;
                }
            }
        }
        if chunk == 1 {
            break;
        }
        chunk = chunk.div_ceil(2);
    }
    minimal
}

type Set = BTreeSet<Requirement>;

/// Every requirement of a problem, in a fixed order.
pub fn requirements(p: &Problem) -> Vec<Requirement> {
    let s = &p.spec;
    let mut out = Vec::new();
    if p.rooms.is_none() {
        out.push(Requirement::Coverage);
    }
    if p.dead_ends == Allow::Forbid {
        out.push(Requirement::DeadEnds);
    }
    if s.features.branches == Allow::Forbid {
        out.push(Requirement::Branches);
    }
    for (config, w) in [
        (ForbiddenKind::Zigzag, p.w_zigzag),
        (ForbiddenKind::TooClose, p.w_too_close),
        (ForbiddenKind::TJunction, p.w_t_junction),
    ] {
        if w == crate::spec::Weight::Forbid {
            out.push(Requirement::Forbidden { config });
        }
    }
    if s.boundary == BoundaryRole::Wall {
        for e in p.mesh.edges() {
            if p.mesh.is_boundary_edge(e) && p.roles[e.index()] == EdgeRole::Excluded && !excluded_by_obstacle(p, e) {
                out.push(Requirement::Wall { edge: e.0 });
            }
        }
    }
    let u = &s.user;
    out.extend((0..u.obstacle_vertices.len()).map(|index| Requirement::ObstacleVertex { index }));
    out.extend((0..u.obstacle_edges.len()).map(|index| Requirement::ObstacleEdge { index }));
    out.extend((0..u.obstacle_faces.len()).map(|index| Requirement::ObstacleFace { index }));
    out.extend((0..u.obstacle_polygons.len()).map(|index| Requirement::ObstaclePolygon { index }));
    out.extend((0..u.forced_edges.len()).map(|index| Requirement::ForcedEdge { index }));
    out.extend((0..u.forced_vertices.len()).map(|index| Requirement::ForcedVertex { index }));
    out.extend((0..u.through_routes.len()).map(|index| Requirement::ThroughRoute { index }));
    if p.p2p.is_some() {
        out.push(Requirement::PointToPoint);
    }
    if let Some(r) = &p.rooms {
        out.push(Requirement::RoomTiling);
        for (template, &(lo, hi)) in r.counts.iter().enumerate() {
            if lo.is_some() || hi.is_some() {
                out.push(Requirement::RoomCount { template });
            }
        }
        if matches!(r.level, Some(LevelType::Circular | LevelType::Linear)) {
            out.push(Requirement::LevelType);
        }
    }
    out
}

/// Whether edge `e` is excluded by an obstacle (not only by the boundary's role).
fn excluded_by_obstacle(p: &Problem, e: EdgeId) -> bool {
    let mesh = &p.mesh;
    let (a, b) = mesh.edge_vertices(e);
    let face =
        mesh.edge_half_edges(e).into_iter().filter_map(|h| mesh.he_face(h)).any(|f| p.is_obstacle_face[f.index()]);
    face || p.is_obstacle_vertex[a.index()]
        || p.is_obstacle_vertex[b.index()]
        || p.spec.user.obstacle_edges.iter().any(|&[x, y]| (x, y) == (a.0, b.0) || (x, y) == (b.0, a.0))
}

/// Describes a requirement of problem `p`.
pub fn describe(p: &Problem, r: Requirement) -> RequirementInfo {
    let s = &p.spec;
    let mesh = &p.mesh;
    let pair = |e: EdgeId| {
        let (a, b) = mesh.edge_vertices(e);
        [a.0, b.0]
    };
    let mut info = RequirementInfo {
        requirement: r,
        field: String::new(),
        text: String::new(),
        vertices: Vec::new(),
        edges: Vec::new(),
        faces: Vec::new(),
    };
    let faces_in = |poly: &[[f64; 2]]| -> Vec<u32> {
        mesh.faces().filter(|&f| crate::geometry::ring_contains(poly, mesh.face_centroid(f))).map(|f| f.0).collect()
    };
    match r {
        Requirement::Coverage => {
            info.field = "coverage".into();
            let unit = match p.coverage_model {
                CoverageModel::Hops => "edges",
                CoverageModel::Euclidean => "length units",
            };
            info.text = format!("coverage: every vertex within {} {unit} of the network", p.coverage_range);
        }
        Requirement::DeadEnds => {
            info.field = "features.dead_ends".into();
            info.text = "no dead-ends away from sinks (features.dead_ends = \"forbid\")".into();
        }
        Requirement::Branches => {
            info.field = "features.branches".into();
            info.text = "no branches (features.branches = \"forbid\")".into();
        }
        Requirement::Forbidden { config } => {
            info.field = format!("weights.{}", config.key());
            let what = match config {
                ForbiddenKind::Zigzag => "no zig-zags",
                ForbiddenKind::TooClose => "no parallel streets one cell apart",
                ForbiddenKind::TJunction => "no T-junctions",
            };
            info.text = format!("{what} (weights.{} = \"forbid\")", config.key());
        }
        Requirement::Wall { edge } => {
            let e = EdgeId(edge);
            info.field = "boundary".into();
            let [a, b] = pair(e);
            info.text = format!("wall: boundary edge {a}–{b} is not a street (boundary = \"wall\")");
            info.edges = vec![[a, b]];
        }
        Requirement::ObstacleVertex { index } => {
            let v = s.user.obstacle_vertices[index];
            info.field = format!("user.obstacle_vertices[{index}]");
            info.text = format!("obstacle vertex {v}");
            info.vertices = vec![v];
        }
        Requirement::ObstacleEdge { index } => {
            let [a, b] = s.user.obstacle_edges[index];
            info.field = format!("user.obstacle_edges[{index}]");
            info.text = format!("obstacle edge {a}–{b}");
            info.edges = vec![[a, b]];
        }
        Requirement::ObstacleFace { index } => {
            let f = s.user.obstacle_faces[index];
            info.field = format!("user.obstacle_faces[{index}]");
            info.text = format!("obstacle face {f}");
            info.faces = vec![f];
        }
        Requirement::ObstaclePolygon { index } => {
            info.field = format!("user.obstacle_polygons[{index}]");
            info.faces = faces_in(&s.user.obstacle_polygons[index]);
            info.text = format!("obstacle polygon {index} ({} faces)", info.faces.len());
        }
        Requirement::ForcedEdge { index } => {
            let [a, b] = s.user.forced_edges[index];
            info.field = format!("user.forced_edges[{index}]");
            info.text = format!("forced edge {a}–{b}");
            info.edges = vec![[a, b]];
        }
        Requirement::ForcedVertex { index } => {
            let v = p.forced_vertices[index];
            info.field = format!("user.forced_vertices[{index}]");
            info.text = format!("forced vertex {}", v.0);
            info.vertices = vec![v.0];
        }
        Requirement::ThroughRoute { index } => {
            let route = &p.through_routes[index];
            info.field = format!("user.through_routes[{index}]");
            info.text = format!(
                "through route {}–{} ({} edges, no branch at its {} inner vertices)",
                route[0].0,
                route[route.len() - 1].0,
                route.len() - 1,
                route.len().saturating_sub(2)
            );
            info.vertices = route.iter().map(|v| v.0).collect();
            info.edges = route.windows(2).map(|w| [w[0].0, w[1].0]).collect();
        }
        Requirement::PointToPoint => {
            info.field = "point_to_point".into();
            let parts: BTreeSet<u32> =
                p.p2p.iter().flat_map(|q| q.face_part.iter().copied()).filter(|&x| x != u32::MAX).collect();
            info.text = format!("point-to-point: a short path between every pair of {} parts", parts.len());
        }
        Requirement::RoomTiling => {
            info.field = "rooms".into();
            let names: Vec<&str> = s.rooms.iter().flat_map(|r| r.templates.iter().map(|t| t.name.as_str())).collect();
            info.text = format!("rooms tile the footprint exactly ({})", names.join(", "));
            info.faces = mesh.faces().filter(|f| !p.is_obstacle_face[f.index()]).map(|f| f.0).collect();
        }
        Requirement::RoomCount { template } => {
            info.field = format!("rooms.templates[{template}]");
            let (name, (lo, hi)) = match &p.rooms {
                Some(r) => (r.templates[template].name.clone(), r.counts[template]),
                None => (String::new(), (None, None)),
            };
            let count = match (lo, hi) {
                (Some(a), Some(b)) if a == b => format!("exactly {a}"),
                (Some(a), Some(b)) => format!("{a} to {b}"),
                (Some(a), None) => format!("at least {a}"),
                (None, Some(b)) => format!("at most {b}"),
                (None, None) => "any number of".into(),
            };
            info.text = format!("{count} room(s) of type {name:?}");
        }
        Requirement::LevelType => {
            info.field = "rooms.level".into();
            let level = p.rooms.as_ref().and_then(|r| r.level);
            info.text = match level {
                Some(LevelType::Circular) => "circular level: no branches (one sink)".into(),
                Some(LevelType::Linear) => "linear level: no branches (two boundary sinks)".into(),
                _ => "level type".into(),
            };
        }
    }
    info
}

/// The search's state: the base problem, every requirement, the cache.
struct Search<'a> {
    base: &'a Problem,
    all: Vec<Requirement>,
    kind: SolverKind,
    opts: &'a ExplainOptions,
    start: Instant,
    cache: BTreeMap<Set, Verdict>,
    feasible: Vec<Set>,
    infeasible: Vec<Set>,
    monotone: bool,
    checks: usize,
    unknown: usize,
    out_of_time: bool,
}

impl Search<'_> {
    fn remaining(&self) -> f64 {
        self.opts.time_budget - self.start.elapsed().as_secs_f64()
    }

    /// Whether the requirements in `kept` (the others relaxed) can all hold.
    fn check(&mut self, kept: &Set) -> Verdict {
        if let Some(&v) = self.cache.get(kept) {
            return v;
        }
        if self.monotone {
            if self.feasible.iter().any(|f| kept.is_subset(f)) {
                return Verdict::Feasible;
            }
            if self.infeasible.iter().any(|i| i.is_subset(kept)) {
                return Verdict::Infeasible;
            }
        }
        let left = self.remaining();
        if left <= 0.05 {
            self.out_of_time = true;
            return Verdict::Unknown;
        }
        let v = self.solve(kept, left.min(self.opts.check_time_limit));
        self.checks += 1;
        match v {
            Verdict::Feasible => self.feasible.push(kept.clone()),
            Verdict::Infeasible => self.infeasible.push(kept.clone()),
            Verdict::Unknown => self.unknown += 1,
        }
        self.cache.insert(kept.clone(), v);
        v
    }

    fn solve(&self, kept: &Set, limit: f64) -> Verdict {
        let relaxed: Set = self.all.iter().copied().filter(|r| !kept.contains(r)).collect();
        let Ok(mut p) = relaxed_problem(self.base, &relaxed) else { return Verdict::Unknown };
        if !close_unreachable(&mut p) {
            return Verdict::Infeasible;
        }
        let mut built = pipeline::build(&p);
        let model = &mut built.model;
        // Coverage (6) is relaxed when asked, and always when the room tiling (which replaces
        // it) is dropped: coverage was no requirement of the spec then.
        let free_coverage = relaxed.contains(&Requirement::Coverage)
            || (relaxed.contains(&Requirement::RoomTiling) && self.base.rooms.is_some());
        if free_coverage {
            // (6) and the rows the strong coverage form derives from it (edge coverage, ball cuts).
            let rows: Vec<_> = model
                .rows()
                .filter(|r| ["cov6_", "covedge_", "covball_"].iter().any(|pre| r.name.starts_with(pre)))
                .map(|r| r.id)
                .collect();
            for id in rows {
                model.set_row_sides(id, f64::NEG_INFINITY, f64::INFINITY);
            }
            // So are the cover cutsets the strong recipe separates from it.
            if let Some(g) = built.cutsets.as_mut() {
                g.groups.clear();
            }
        }
        // Feasibility only: the objective is set aside.
        for j in 0..model.num_vars() {
            model.var_mut(VarId(j as u32)).obj = 0.0;
        }
        model.obj_constant = 0.0;
        // A row without variables that its constant violates: infeasible as built (no solver
        // needed, and not every backend notices).
        let (lhs, rhs) = model.row_sides();
        let (starts, _, _) = model.csr();
        if (0..model.num_rows()).any(|i| starts[i] == starts[i + 1] && (lhs[i] > 1e-9 || rhs[i] < -1e-9)) {
            return Verdict::Infeasible;
        }
        let options = SolveOptions { time_limit: Some(limit), threads: self.opts.threads, ..SolveOptions::default() };
        match pipeline::solve_built(&p, &built, self.kind, &options) {
            Ok(r) if r.solve.termination == Termination::Infeasible => Verdict::Infeasible,
            // A solution counts when netspec's own checker accepts it.
            Ok(r) if r.network.is_some() && r.validity.milp_check.as_ref().is_some_and(|c| c.is_feasible()) => {
                Verdict::Feasible
            }
            _ => Verdict::Unknown,
        }
    }

    /// A minimal subset `c` of `kept` with `c` infeasible, given that `kept` is. Returns the
    /// set and whether it is proven minimal.
    fn shrink(&mut self, kept: &Set) -> (Set, bool) {
        let mut k = kept.clone();
        let mut minimal = true;
        // Families first.
        let mut families: Vec<Family> = k.iter().map(|r| r.family()).collect();
        families.dedup();
        for f in families {
            let without: Set = k.iter().copied().filter(|r| r.family() != f).collect();
            match self.check(&without) {
                Verdict::Infeasible => k = without,
                Verdict::Feasible => {}
                Verdict::Unknown => minimal = false,
            }
        }
        // Then elements inside each family left, halving chunks down to single elements.
        let mut families: Vec<Family> = k.iter().map(|r| r.family()).collect();
        families.dedup();
        for f in families {
            let members: Vec<Requirement> = k.iter().copied().filter(|r| r.family() == f).collect();
            minimal &= deletion_filter(&mut k, members, |s| self.check(s));
        }
        (k, minimal && !self.out_of_time)
    }
}

/// A copy of `base` with the requirements in `relaxed` dropped: the spec edited and resolved on
/// the same mesh, walls reopened on the resolved problem, through routes on their original
/// paths.
fn relaxed_problem(base: &Problem, relaxed: &Set) -> Result<Problem, crate::spec::SpecErrorKind> {
    let mut s: Spec = base.spec.clone();
    let has = |r: Requirement| relaxed.contains(&r);
    if has(Requirement::DeadEnds) {
        s.features.dead_ends = Allow::Allow;
    }
    if has(Requirement::Branches) {
        s.features.branches = Allow::Allow;
    }
    for (config, w) in [
        (ForbiddenKind::Zigzag, &mut s.weights.zigzag),
        (ForbiddenKind::TooClose, &mut s.weights.too_close),
        (ForbiddenKind::TJunction, &mut s.weights.t_junction),
    ] {
        if has(Requirement::Forbidden { config }) {
            *w = WeightValue::Number(0.0);
        }
    }
    fn keep<T: Clone>(v: &[T], relaxed: impl Fn(usize) -> bool) -> Vec<T> {
        v.iter().enumerate().filter(|(i, _)| !relaxed(*i)).map(|(_, x)| x.clone()).collect()
    }
    let u = &mut s.user;
    u.obstacle_vertices = keep(&u.obstacle_vertices, |index| has(Requirement::ObstacleVertex { index }));
    u.obstacle_edges = keep(&u.obstacle_edges, |index| has(Requirement::ObstacleEdge { index }));
    u.obstacle_faces = keep(&u.obstacle_faces, |index| has(Requirement::ObstacleFace { index }));
    u.obstacle_polygons = keep(&u.obstacle_polygons, |index| has(Requirement::ObstaclePolygon { index }));
    u.forced_edges = keep(&u.forced_edges, |index| has(Requirement::ForcedEdge { index }));
    u.forced_vertices = keep(&u.forced_vertices, |index| has(Requirement::ForcedVertex { index }));
    let routes: Vec<usize> =
        (0..u.through_routes.len()).filter(|&index| !has(Requirement::ThroughRoute { index })).collect();
    u.through_routes = keep(&u.through_routes, |index| has(Requirement::ThroughRoute { index }));
    if has(Requirement::PointToPoint) {
        s.point_to_point = None;
    }
    if has(Requirement::RoomTiling) {
        s.rooms = None;
    }
    if let Some(rooms) = &mut s.rooms {
        for (template, t) in rooms.templates.iter_mut().enumerate() {
            if has(Requirement::RoomCount { template }) {
                (t.min, t.max, t.exact) = (None, None, None);
            }
        }
        if has(Requirement::LevelType) {
            rooms.level = None;
        }
    }
    let mut p = s.resolve_on_mesh(base.mesh.clone())?;
    // Walls reopened: candidate edges again, unless an obstacle (still kept) excludes them.
    for r in relaxed {
        if let Requirement::Wall { edge } = *r {
            let e = EdgeId(edge);
            if p.roles[e.index()] == EdgeRole::Excluded && !excluded_by_obstacle(&p, e) {
                p.roles[e.index()] = EdgeRole::Candidate;
            }
        }
    }
    // Through routes keep the paths of the full spec (dropping an obstacle must not move them).
    p.through_routes = routes.iter().map(|&i| base.through_routes[i].clone()).collect::<Vec<Vec<VertexId>>>();
    Ok(p)
}

/// The branches of a node of the hitting-set tree labelled with `conflict`: each requirement on
/// its own, except walls and obstacle entries, which are relaxed together per conflict (a
/// fence of obstacle edges, or the walls around a corner, is one contradiction; its subsets
/// would only give the same contradiction again with other pieces of the fence).
fn branches(conflict: &Set) -> Vec<Set> {
    let mut out: Vec<Set> = Vec::new();
    for f in [Family::Walls, Family::Obstacles] {
        let group: Set = conflict.iter().copied().filter(|r| r.family() == f).collect();
        if !group.is_empty() {
            out.push(group);
        }
    }
    out.extend(
        conflict.iter().filter(|r| !matches!(r.family(), Family::Walls | Family::Obstacles)).map(|&r| Set::from([r])),
    );
    out.sort();
    out
}

/// Closes what no design can use: every active edge leads to a sink (no islands), so an edge
/// whose component (over edges that are not excluded) has no sink is excluded. Returns `false`
/// when that leaves a forced edge or a through-route edge excluded (no design exists).
fn close_unreachable(p: &mut Problem) -> bool {
    let mesh = &p.mesh;
    let n = mesh.num_vertices();
    let mut reached = vec![false; n];
    let mut stack: Vec<VertexId> = mesh.vertices().filter(|v| p.is_sink[v.index()]).collect();
    for v in &stack {
        reached[v.index()] = true;
    }
    while let Some(v) = stack.pop() {
        for &h in mesh.outgoing(v) {
            let w = mesh.he_head(h);
            if p.roles[mesh.he_edge(h).index()] != EdgeRole::Excluded && !reached[w.index()] {
                reached[w.index()] = true;
                stack.push(w);
            }
        }
    }
    for e in mesh.edges() {
        let (a, _) = mesh.edge_vertices(e);
        if !reached[a.index()] {
            p.roles[e.index()] = EdgeRole::Excluded;
        }
    }
    let route_edges = p
        .through_routes
        .iter()
        .flat_map(|r| r.windows(2).filter_map(|w| mesh.half_edge_between(w[0], w[1])).map(|h| mesh.he_edge(h)));
    !p.forced_edges.iter().copied().chain(route_edges).any(|e| p.roles[e.index()] == EdgeRole::Excluded)
}

/// Explains why problem `p` has no solution, with feasibility checks on backend `kind`.
pub fn explain(p: &Problem, kind: SolverKind, opts: &ExplainOptions) -> Explanation {
    let all = requirements(p);
    let obstacles = {
        let u = &p.spec.user;
        !(u.obstacle_vertices.is_empty()
            && u.obstacle_edges.is_empty()
            && u.obstacle_faces.is_empty()
            && u.obstacle_polygons.is_empty())
    };
    let mut search = Search {
        base: p,
        all: all.clone(),
        kind,
        opts,
        start: Instant::now(),
        cache: BTreeMap::new(),
        feasible: Vec::new(),
        infeasible: Vec::new(),
        monotone: !(obstacles && (p.rooms.is_some() || p.p2p.is_some())),
        checks: 0,
        unknown: 0,
        out_of_time: false,
    };
    let everything: Set = all.iter().copied().collect();
    if opts.known_infeasible {
        search.cache.insert(everything.clone(), Verdict::Infeasible);
        search.infeasible.push(everything.clone());
    }
    let finish = |search: &Search, status, conflicts: Vec<(Set, bool)>, repairs: Vec<Set>, complete| {
        let order = |set: &Set| -> Vec<Requirement> { all.iter().copied().filter(|r| set.contains(r)).collect() };
        let mut repairs: Vec<Vec<Requirement>> = repairs.iter().map(order).collect();
        repairs.sort_by_key(|r| r.len());
        Explanation {
            status,
            conflicts: conflicts
                .iter()
                .map(|(c, minimal)| Conflict {
                    requirements: order(c).into_iter().map(|r| describe(p, r)).collect(),
                    minimal: *minimal,
                })
                .collect(),
            repairs: repairs.iter().map(|r| r.iter().map(|&q| describe(p, q).short()).collect()).collect(),
            complete,
            requirements: all.len(),
            checks: search.checks,
            unknown_checks: search.unknown,
            seconds: search.start.elapsed().as_secs_f64(),
            solver: kind.name().into(),
            check_time_limit: opts.check_time_limit,
        }
    };
    match search.check(&everything) {
        Verdict::Feasible => return finish(&search, ExplainStatus::Feasible, Vec::new(), Vec::new(), true),
        Verdict::Unknown => return finish(&search, ExplainStatus::Unknown, Vec::new(), Vec::new(), false),
        Verdict::Infeasible => {}
    }
    match search.check(&Set::new()) {
        Verdict::Feasible => {}
        Verdict::Infeasible => return finish(&search, ExplainStatus::Unexplained, Vec::new(), Vec::new(), true),
        Verdict::Unknown => return finish(&search, ExplainStatus::Unknown, Vec::new(), Vec::new(), false),
    }
    // Reiter's hitting-set tree: nodes are sets of relaxed requirements, breadth first.
    let mut conflicts: Vec<(Set, bool)> = Vec::new();
    let mut repairs: Vec<Set> = Vec::new();
    let mut complete = true;
    let mut seen: BTreeSet<Set> = BTreeSet::new();
    // (relaxed requirements, depth: how many groups were relaxed to get there)
    let mut queue: VecDeque<(Set, usize)> = VecDeque::from([(Set::new(), 0)]);
    while let Some((h, depth)) = queue.pop_front() {
        if search.out_of_time || search.remaining() <= 0.0 {
            complete = false;
            break;
        }
        if repairs.iter().any(|r| r.is_subset(&h)) {
            continue;
        }
        let label = match conflicts.iter().find(|(c, _)| c.is_disjoint(&h)) {
            Some((c, _)) => c.clone(),
            None => {
                let kept: Set = everything.difference(&h).copied().collect();
                match search.check(&kept) {
                    Verdict::Feasible => {
                        repairs.push(h);
                        continue;
                    }
                    Verdict::Unknown => {
                        complete = false;
                        continue;
                    }
                    Verdict::Infeasible => {
                        if conflicts.len() >= opts.max_conflicts {
                            complete = false;
                            break;
                        }
                        let (c, minimal) = search.shrink(&kept);
                        conflicts.push((c.clone(), minimal));
                        c
                    }
                }
            }
        };
        if depth >= opts.max_depth {
            complete = false;
            continue;
        }
        for group in branches(&label) {
            let mut child = h.clone();
            child.extend(group);
            if seen.insert(child.clone()) {
                queue.push_back((child, depth + 1));
            }
        }
    }
    let status = if conflicts.is_empty() { ExplainStatus::Unknown } else { ExplainStatus::Explained };
    finish(&search, status, conflicts, repairs, complete && !search.out_of_time)
}

impl RequirementInfo {
    /// The field, with the edge for a wall (`boundary[0–1]`): short enough for lists.
    pub fn short(&self) -> String {
        match (self.requirement, self.edges.first()) {
            (Requirement::Wall { .. }, Some([a, b])) => format!("boundary[{a}–{b}]"),
            _ => self.field.clone(),
        }
    }

    /// `field: text`, or the text alone when it already names the field.
    pub fn field_text(&self) -> String {
        if self.text.contains(&self.field) {
            self.text.clone()
        } else {
            format!("{}: {}", self.field, self.text)
        }
    }
}

impl Explanation {
    /// Console lines: the conflicts, the repairs, how the search went.
    pub fn lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        let how = format!(
            "{} requirements, {} feasibility checks with {} ({} s limit each{}), {:.2} s",
            self.requirements,
            self.checks,
            self.solver,
            (self.check_time_limit * 100.0).round() / 100.0,
            if self.unknown_checks > 0 {
                format!(", {} without an answer", self.unknown_checks)
            } else {
                String::new()
            },
            self.seconds
        );
        match self.status {
            ExplainStatus::Feasible => {
                out.push(format!("with the objective set aside the spec has a solution ({how})"))
            }
            ExplainStatus::Unknown => out.push(format!("no conflict isolated within the limits ({how})")),
            ExplainStatus::Unexplained => out.push(format!(
                "infeasible even with every requirement relaxed: sinks, existing roads or the mesh itself ({how})"
            )),
            ExplainStatus::Explained => {
                out.push(format!(
                    "{} conflicting set{} of requirements{} ({how}):",
                    self.conflicts.len(),
                    if self.conflicts.len() == 1 { "" } else { "s" },
                    if self.complete { "" } else { " found (the search stopped at its limits; there may be more)" }
                ));
                for (i, c) in self.conflicts.iter().enumerate() {
                    out.push(format!("  conflict {}{}:", i + 1, if c.minimal { "" } else { " (not proven minimal)" }));
                    for r in &c.requirements {
                        out.push(format!("    - {}", r.field_text()));
                    }
                }
                if !self.repairs.is_empty() {
                    out.push("  feasible once these are relaxed together:".into());
                    for r in self.repairs.iter().take(8) {
                        out.push(format!("    - {}", compact(r)));
                    }
                    if self.repairs.len() > 8 {
                        out.push(format!("    … and {} more", self.repairs.len() - 8));
                    }
                }
            }
        }
        out
    }
}

/// The picture of a spec without a solution: its mesh, obstacles, sinks, forced elements and
/// through routes ([`crate::design::picture::mesh_scene`]), with the elements of each
/// conflicting set of requirements highlighted in the conflict's colour and every requirement
/// listed in the legend ([`crate::render::network::conflict_svg`]).
pub fn conflict_svg(p: &Problem, explanation: &Explanation, caption: &crate::render::Caption) -> String {
    use crate::render::network::{ConflictMarks, ConflictScene, RequirementMarks};
    let conflicts = ConflictScene {
        conflicts: explanation
            .conflicts
            .iter()
            .map(|c| ConflictMarks {
                minimal: c.minimal,
                requirements: c
                    .requirements
                    .iter()
                    .map(|r| RequirementMarks {
                        text: r.field_text(),
                        vertices: r.vertices.clone(),
                        edges: r.edges.clone(),
                        faces: r.faces.clone(),
                    })
                    .collect(),
            })
            .collect(),
        complete: explanation.complete,
    };
    crate::render::network::conflict_svg(&crate::design::picture::mesh_scene(p), &conflicts, caption)
}

/// Fields in a short list, indices of one list merged: `user.obstacle_edges[0, 1, 2] +
/// user.forced_vertices[0]`.
fn compact(fields: &[String]) -> String {
    let mut groups: Vec<(String, Vec<String>)> = Vec::new();
    for f in fields {
        let (name, index) = match f.split_once('[') {
            Some((n, rest)) => (n.to_string(), Some(rest.trim_end_matches(']').to_string())),
            None => (f.clone(), None),
        };
        match (groups.iter_mut().find(|g| g.0 == name), index) {
            (Some(g), Some(i)) => g.1.push(i),
            (None, Some(i)) => groups.push((name, vec![i])),
            (_, None) => groups.push((name, Vec::new())),
        }
    }
    groups
        .iter()
        .map(|(n, is)| if is.is_empty() { n.clone() } else { format!("{n}[{}]", is.join(", ")) })
        .collect::<Vec<_>>()
        .join(" + ")
}
