//! The independent validator: docs/formulation.md §6 items 1–5, in plain graph code over the problem
//! and a set of active edges. It never reads the MILP.

use super::Network;
use crate::mesh::{EdgeId, Mesh, VertexId};
use crate::rules::paths::PathSets;
use crate::rules::{designed, t_configs, too_close_configs, zigzag_configs};
use crate::spec::{Allow, CoverageModel, Problem, Weight};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// One way the network breaks its specification.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Violation {
    /// Item 1: a connected component of active edges with no sink.
    Island {
        /// Its edges.
        edges: Vec<EdgeId>,
    },
    /// Item 2: a vertex farther than the coverage range from every active vertex.
    Uncovered {
        /// The vertex.
        vertex: VertexId,
    },
    /// Item 3: an active non-sink vertex with exactly one active edge, dead-ends forbidden.
    DeadEnd {
        /// The vertex.
        vertex: VertexId,
    },
    /// Item 3: a vertex with three or more active edges, branches forbidden.
    Branch {
        /// The vertex.
        vertex: VertexId,
        /// Its active degree.
        degree: usize,
    },
    /// Item 3: a forbidden zig-zag.
    ZigZag {
        /// Its three edges.
        edges: Vec<EdgeId>,
    },
    /// Item 3: a forbidden too-close pair.
    TooClose {
        /// The two edges.
        edges: Vec<EdgeId>,
    },
    /// Item 3: a forbidden T-junction.
    TJunction {
        /// The vertex.
        vertex: VertexId,
    },
    /// Item 4: an active edge that is excluded (wall, obstacle).
    ExcludedActive {
        /// The edge.
        edge: EdgeId,
    },
    /// Item 4: a forced edge that is inactive.
    ForcedInactive {
        /// The edge.
        edge: EdgeId,
    },
    /// Item 4: a forced vertex with no active edge.
    ForcedVertexInactive {
        /// The vertex.
        vertex: VertexId,
    },
    /// Item 4: a through route with an inactive edge or an inner vertex of degree ≠ 2.
    ThroughRoute {
        /// Route index.
        route: usize,
        /// What is wrong.
        detail: String,
    },
    /// Item 5: a pair of adjacent parts with no fully active enumerated path.
    PointToPoint {
        /// The two parts.
        parts: (u32, u32),
    },
    /// Item 6: a non-obstacle face covered by no room, or by more than one.
    Cover {
        /// The face.
        face: crate::mesh::FaceId,
        /// How many chosen rooms cover it.
        rooms: usize,
    },
    /// Item 6: a room whose inner or boundary edges break the mode's rule.
    Room {
        /// Index of the placement.
        placement: usize,
        /// What is wrong.
        detail: String,
    },
    /// Item 6: a game level's block graph does not have the requested shape.
    LevelShape {
        /// The level type asked for.
        level: crate::spec::LevelType,
        /// The shape found.
        shape: super::GraphShape,
    },
    /// Item 6: a room-type count outside its bounds.
    RoomCount {
        /// Template index.
        template: usize,
        /// Rooms of that type.
        count: usize,
    },
}

impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ids = |es: &[EdgeId]| es.iter().map(|e| format!("e{}", e.0)).collect::<Vec<_>>().join(",");
        match self {
            Violation::Island { edges } => {
                write!(f, "island: {} active edges with no sink ({})", edges.len(), ids(edges))
            }
            Violation::Uncovered { vertex } => write!(f, "vertex v{} is not covered", vertex.0),
            Violation::DeadEnd { vertex } => write!(f, "dead-end at v{}", vertex.0),
            Violation::Branch { vertex, degree } => write!(f, "branch of degree {degree} at v{}", vertex.0),
            Violation::ZigZag { edges } => write!(f, "zig-zag {}", ids(edges)),
            Violation::TooClose { edges } => write!(f, "too-close pair {}", ids(edges)),
            Violation::TJunction { vertex } => write!(f, "T-junction at v{}", vertex.0),
            Violation::ExcludedActive { edge } => write!(f, "excluded edge e{} is active", edge.0),
            Violation::ForcedInactive { edge } => write!(f, "forced edge e{} is inactive", edge.0),
            Violation::ForcedVertexInactive { vertex } => write!(f, "forced vertex v{} is inactive", vertex.0),
            Violation::ThroughRoute { route, detail } => write!(f, "through route {route}: {detail}"),
            Violation::PointToPoint { parts } => {
                write!(f, "parts {} and {}: no enumerated path is fully active", parts.0, parts.1)
            }
            Violation::Cover { face, rooms } => write!(f, "face f{} is covered by {rooms} rooms", face.0),
            Violation::Room { placement, detail } => write!(f, "room {placement}: {detail}"),
            Violation::LevelShape { level, shape } => {
                write!(f, "a {level:?} level needs a matching block graph, found {shape:?}")
            }
            Violation::RoomCount { template, count } => {
                write!(f, "template {template}: {count} rooms, outside its bounds")
            }
        }
    }
}

/// Active degree of every vertex.
pub(crate) fn degrees(mesh: &Mesh, net: &Network) -> Vec<usize> {
    let mut d = vec![0; mesh.num_vertices()];
    for e in net.active_edges() {
        let (a, b) = mesh.edge_vertices(e);
        d[a.index()] += 1;
        d[b.index()] += 1;
    }
    d
}

/// Connected components of the active edges: a component id per vertex (`usize::MAX` when the
/// vertex has no active edge).
pub(crate) fn components(mesh: &Mesh, net: &Network) -> Vec<usize> {
    let mut comp = vec![usize::MAX; mesh.num_vertices()];
    let mut next = 0;
    for e in net.active_edges() {
        let (s, _) = mesh.edge_vertices(e);
        if comp[s.index()] != usize::MAX {
            continue;
        }
        let mut q = VecDeque::from([s]);
        comp[s.index()] = next;
        while let Some(v) = q.pop_front() {
            for &h in mesh.outgoing(v) {
                if net.active[mesh.he_edge(h).index()] {
                    let w = mesh.he_head(h);
                    if comp[w.index()] == usize::MAX {
                        comp[w.index()] = next;
                        q.push_back(w);
                    }
                }
            }
        }
        next += 1;
    }
    comp
}

/// Checks items 1–5 of docs/formulation.md §6. `paths` are the enumerated point-to-point path sets (the
/// enumeration is deterministic, so they are the ones the model used).
pub fn validate(p: &Problem, net: &Network, paths: Option<&PathSets>) -> Vec<Violation> {
    let mesh = &p.mesh;
    let mut out = Vec::new();
    let deg = degrees(mesh, net);
    let active_vertex: Vec<bool> = deg.iter().map(|&d| d > 0).collect();

    // 1. No islands.
    let comp = components(mesh, net);
    let ncomp = comp.iter().filter(|&&c| c != usize::MAX).max().map_or(0, |c| c + 1);
    let mut has_sink = vec![false; ncomp];
    for v in mesh.vertices() {
        if comp[v.index()] != usize::MAX && p.is_sink[v.index()] {
            has_sink[comp[v.index()]] = true;
        }
    }
    for (c, _) in has_sink.iter().enumerate().filter(|(_, &s)| !s) {
        let edges = net.active_edges().into_iter().filter(|&e| comp[mesh.edge_vertices(e).0.index()] == c).collect();
        out.push(Violation::Island { edges });
    }

    // 2. Coverage, by BFS from the active vertices (hops) or by distance (Euclidean). Room
    // tiling replaces coverage (docs/formulation.md §4).
    let r = if p.rooms.is_some() { f64::INFINITY } else { p.coverage_range };
    let covered: Vec<bool> = match p.coverage_model {
        CoverageModel::Hops => {
            let mut d = vec![usize::MAX; mesh.num_vertices()];
            let mut q = VecDeque::new();
            for v in mesh.vertices().filter(|v| active_vertex[v.index()]) {
                d[v.index()] = 0;
                q.push_back(v);
            }
            while let Some(v) = q.pop_front() {
                for w in mesh.neighbors(v) {
                    if d[w.index()] == usize::MAX {
                        d[w.index()] = d[v.index()] + 1;
                        q.push_back(w);
                    }
                }
            }
            d.iter().map(|&h| r.is_infinite() || (h != usize::MAX && h as f64 <= r.floor())).collect()
        }
        CoverageModel::Euclidean => {
            let act: Vec<[f64; 2]> =
                mesh.vertices().filter(|v| active_vertex[v.index()]).map(|v| mesh.position(v)).collect();
            mesh.vertices()
                .map(|v| {
                    let pv = mesh.position(v);
                    act.iter().any(|a| ((a[0] - pv[0]).powi(2) + (a[1] - pv[1]).powi(2)).sqrt() <= r * (1.0 + 1e-9))
                })
                .collect()
        }
    };
    for v in mesh.vertices() {
        if !p.is_obstacle_vertex[v.index()] && !covered[v.index()] {
            out.push(Violation::Uncovered { vertex: v });
        }
    }

    // 3. Forbidden features.
    if p.dead_ends == Allow::Forbid {
        for v in mesh.vertices() {
            if deg[v.index()] == 1 && !p.is_sink[v.index()] {
                out.push(Violation::DeadEnd { vertex: v });
            }
        }
    }
    if p.branches == Allow::Forbid {
        for v in mesh.vertices() {
            if deg[v.index()] >= 3 {
                out.push(Violation::Branch { vertex: v, degree: deg[v.index()] });
            }
        }
    }
    // Configurations made only of existing roads are given, not designed (see `designed`).
    let all_active = |es: &[EdgeId]| designed(p, es) && es.iter().all(|e| net.active[e.index()]);
    if p.w_zigzag == Weight::Forbid {
        for z in zigzag_configs(mesh) {
            if all_active(&z.edges) {
                out.push(Violation::ZigZag { edges: z.edges.to_vec() });
            }
        }
    }
    if p.w_too_close == Weight::Forbid {
        for t in too_close_configs(mesh) {
            if all_active(&t.edges) {
                out.push(Violation::TooClose { edges: t.edges.to_vec() });
            }
        }
    }
    if p.w_t_junction == Weight::Forbid {
        for (_, v, e0, others) in t_configs(mesh) {
            if !net.active[e0.index()]
                && designed(p, &[e0, others[0], others[1], others[2]])
                && others.iter().all(|e| net.active[e.index()])
            {
                out.push(Violation::TJunction { vertex: v });
            }
        }
    }

    // 4. Obstacles, forced elements, through routes.
    for e in mesh.edges() {
        if net.active[e.index()] && p.roles[e.index()] == crate::spec::EdgeRole::Excluded {
            out.push(Violation::ExcludedActive { edge: e });
        }
    }
    for &e in &p.forced_edges {
        if !net.active[e.index()] {
            out.push(Violation::ForcedInactive { edge: e });
        }
    }
    for &v in &p.forced_vertices {
        if deg[v.index()] == 0 {
            out.push(Violation::ForcedVertexInactive { vertex: v });
        }
    }
    for (r, route) in p.through_routes.iter().enumerate() {
        for w in route.windows(2) {
            let e = mesh.he_edge(mesh.half_edge_between(w[0], w[1]).expect("route on mesh edges"));
            if !net.active[e.index()] {
                out.push(Violation::ThroughRoute {
                    route: r,
                    detail: format!("edge v{}–v{} inactive", w[0].0, w[1].0),
                });
            }
        }
        for &v in &route[1..route.len() - 1] {
            if deg[v.index()] != 2 {
                out.push(Violation::ThroughRoute {
                    route: r,
                    detail: format!("inner vertex v{} has degree {}", v.0, deg[v.index()]),
                });
            }
        }
    }

    // 5. Point-to-point.
    if let Some(sets) = paths {
        for pair in &sets.pairs {
            if !pair.paths.iter().any(|path| all_active(&path.edges)) {
                out.push(Violation::PointToPoint { parts: pair.parts });
            }
        }
    }
    out
}

/// docs/formulation.md §6 item 6: exact cover, the mode's inner/boundary edge rules, room counts.
/// `chosen` are indices into `placements`.
pub fn validate_rooms(
    p: &Problem,
    net: &Network,
    placements: &[crate::rules::placements::Placement],
    chosen: &[usize],
) -> Vec<Violation> {
    let Some(rooms) = &p.rooms else { return Vec::new() };
    let mesh = &p.mesh;
    let mut out = Vec::new();
    let mut cover = vec![0usize; mesh.num_faces()];
    let mut count = vec![0usize; rooms.templates.len()];
    for &k in chosen {
        let pl = &placements[k];
        count[pl.template] += 1;
        for f in &pl.faces {
            cover[f.index()] += 1;
        }
        let inner_active = pl.inner_edges.iter().filter(|e| net.active[e.index()]).count();
        let bnd_active = pl.boundary_edges.iter().filter(|e| net.active[e.index()]).count();
        match rooms.mode {
            crate::spec::RoomMode::Floorplan => {
                if inner_active > 0 {
                    out.push(Violation::Room {
                        placement: k,
                        detail: format!("{inner_active} corridor edges inside the room"),
                    });
                }
                if bnd_active == 0 {
                    out.push(Violation::Room { placement: k, detail: "no corridor along the room".into() });
                }
            }
            crate::spec::RoomMode::Game => {
                if inner_active == 0 {
                    out.push(Violation::Room { placement: k, detail: "the block is not traversed".into() });
                }
                if bnd_active > 0 {
                    out.push(Violation::Room {
                        placement: k,
                        detail: format!("{bnd_active} edges run along the block's boundary"),
                    });
                }
            }
        }
    }
    for f in mesh.faces() {
        let c = cover[f.index()];
        if p.is_obstacle_face[f.index()] {
            if c != 0 {
                out.push(Violation::Cover { face: f, rooms: c });
            }
        } else if c != 1 {
            out.push(Violation::Cover { face: f, rooms: c });
        }
    }
    if let (crate::spec::RoomMode::Game, Some(level)) = (rooms.mode, rooms.level) {
        use super::GraphShape as G;
        let shape = super::block_graph(p, net, placements).shape;
        let ok = match level {
            crate::spec::LevelType::Circular => shape == G::Cycle || (chosen.len() == 1 && shape == G::Path),
            crate::spec::LevelType::Linear => shape == G::Path,
            crate::spec::LevelType::Branching => !matches!(shape, G::Disconnected),
        };
        if !ok {
            out.push(Violation::LevelShape { level, shape });
        }
    }
    for (t, &(lo, hi)) in rooms.counts.iter().enumerate() {
        let c = count[t] as u32;
        if lo.is_some_and(|lo| c < lo) || hi.is_some_and(|hi| c > hi) {
            out.push(Violation::RoomCount { template: t, count: count[t] });
        }
    }
    out
}
