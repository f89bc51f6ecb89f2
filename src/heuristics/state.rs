//! The search state: what a problem's rules are on its mesh, precomputed once ([`Rules`]), and a
//! set of active edges with every rule's violation count kept up to date edge by edge
//! ([`State`]). Toggling an edge costs time proportional to what touches it (its configurations,
//! the coverage balls of its ends, its paths and rooms), so a search can try a move, read the
//! counts, and undo it. Islands are the one rule that is not local: [`State::reaches_sink`]
//! answers it for the ends of removed edges.
//!
//! The counts mirror [`crate::design::validate`] and [`crate::design::validate_rooms`] rule for
//! rule; the validator stays the authority and judges every design a search returns.

use super::budget;
use crate::design::{label_distances, travel_distances, Network};
use crate::mesh::{EdgeId, HalfEdgeId, Mesh, VertexId};
use crate::rules::paths::PathSets;
use crate::rules::placements::Placement;
use crate::rules::{cover_set, designed, t_configs, too_close_configs, zigzag_configs};
use crate::spec::{Allow, EdgeRole, Problem, RoomMode, Weight};
use std::collections::VecDeque;

/// Work units per local configuration built by [`Rules::new`] (module `budget`): each is
/// enumerated and named, at the cost of a few hundred path-search steps.
const CONFIG_UNITS: usize = 40;

/// A local configuration (zig-zag or too-close pair): present when all its edges are active.
#[derive(Clone, Debug)]
pub(crate) struct Config {
    pub edges: Vec<EdgeId>,
    /// Forbidden (a violation) or penalised (`weight` in the objective).
    pub forbid: bool,
    pub weight: f64,
}

/// A T-junction configuration: present when `e0` is inactive and the three others active.
#[derive(Clone, Debug)]
pub(crate) struct TConfig {
    pub vertex: VertexId,
    pub e0: EdgeId,
    pub others: [EdgeId; 3],
    pub forbid: bool,
    pub weight: f64,
}

/// A room tiling fixed for the search: the chosen placements (indices into `placements`).
#[derive(Clone, Debug)]
pub(crate) struct Tiling {
    pub rooms: Vec<usize>,
}

/// Everything a problem's rules say about its mesh, precomputed for one tiling (or none).
pub(crate) struct Rules<'a> {
    pub p: &'a Problem,
    pub mesh: &'a Mesh,
    /// Whether an edge may be active at all (not excluded; not inside a floor-plan room; not on
    /// a game block's boundary).
    pub allowed: Vec<bool>,
    /// Edges that must stay active (existing roads, forced edges, through routes).
    pub fixed: Vec<bool>,
    /// Length of each candidate edge (0 for existing roads: they are not in the objective).
    pub cost_len: Vec<f64>,
    /// Coverage balls (empty when coverage is off, i.e. with rooms).
    pub balls: Vec<Vec<VertexId>>,
    /// Whether a vertex must be covered (non-obstacle, coverage on).
    pub needs_cover: Vec<bool>,
    pub configs: Vec<Config>,
    pub edge_configs: Vec<Vec<u32>>,
    pub tconfigs: Vec<TConfig>,
    pub edge_tconfigs: Vec<Vec<u32>>,
    pub dead_end_forbid: bool,
    pub branch_forbid: bool,
    /// Inner vertices of through routes (degree exactly 2).
    pub route_inner: Vec<bool>,
    pub forced_vertex: Vec<bool>,
    /// Point-to-point: per pair, its paths as edge lists.
    pub pairs: Vec<Vec<Vec<EdgeId>>>,
    /// Per edge: (pair, path) that contain it.
    pub edge_paths: Vec<Vec<(u32, u32)>>,
    /// Rooms: per chosen room, the edges of which at least one must be active (floor plans:
    /// its usable boundary edges; game levels: its inner edges).
    pub groups: Vec<Vec<EdgeId>>,
    pub edge_groups: Vec<Vec<u32>>,
    /// The tiling, when the problem has rooms.
    pub tiling: Option<Tiling>,
    /// Whether no design can exist with this tiling: a fixed edge is not allowed, or a room has
    /// no edge it could be touched (traversed) by.
    pub conflict: bool,
    /// The placements the tiling indexes (room problems).
    pub placements: Option<&'a [Placement]>,
}

/// Adds a local configuration of weight `w` to `configs` when the design decides it and every
/// edge of it may be active (otherwise it can never be complete).
fn keep_config(p: &Problem, allowed: &[bool], edges: &[EdgeId], w: Weight, configs: &mut Vec<Config>) {
    if designed(p, edges) && edges.iter().all(|e| allowed[e.index()]) {
        configs.push(Config { edges: edges.to_vec(), forbid: w == Weight::Forbid, weight: w.value() });
    }
}

impl<'a> Rules<'a> {
    /// Precomputes the rules of `p` (with `tiling` of `placements` when it has rooms).
    pub fn new(
        p: &'a Problem,
        paths: Option<&PathSets>,
        placements: Option<&'a [Placement]>,
        tiling: Option<Tiling>,
    ) -> Rules<'a> {
        Rules::build(p, paths, placements, tiling, false)
    }

    /// The rules of a floor plan's corridors before its rooms (`p` without rooms): corridors
    /// keep off the outer walls — an edge opposite a wall on the mesh boundary across a face
    /// would leave a strip one face wide that few rooms fit — and a vertex no usable vertex could cover needs
    /// no cover (the room it ends up in reaches a corridor instead).
    pub fn corridors(p: &'a Problem, paths: Option<&PathSets>) -> Rules<'a> {
        let mut r = Rules::build(p, paths, None, None, true);
        let usable: Vec<bool> = r
            .mesh
            .vertices()
            .map(|v| r.p.is_sink[v.index()] || r.mesh.incident_edges(v).filter(|e| r.allowed[e.index()]).count() >= 2)
            .collect();
        for v in r.mesh.vertices() {
            if r.needs_cover[v.index()] && !r.balls[v.index()].iter().any(|w| usable[w.index()]) {
                r.needs_cover[v.index()] = false;
            }
        }
        r
    }

    fn build(
        p: &'a Problem,
        paths: Option<&PathSets>,
        placements: Option<&'a [Placement]>,
        tiling: Option<Tiling>,
        off_walls: bool,
    ) -> Rules<'a> {
        let mesh = &p.mesh;
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        let mut allowed: Vec<bool> = p.roles.iter().map(|r| *r != EdgeRole::Excluded).collect();
        if off_walls {
            for f in mesh.faces() {
                let es = mesh.face_edges(f);
                if es.len() == 4 {
                    for k in 0..4 {
                        if mesh.is_boundary_edge(es[(k + 2) % 4])
                            && p.roles[es[(k + 2) % 4].index()] == EdgeRole::Excluded
                            && p.roles[es[k].index()] == EdgeRole::Candidate
                        {
                            allowed[es[k].index()] = false;
                        }
                    }
                }
            }
        }
        let mut fixed: Vec<bool> = p.roles.iter().map(|r| *r == EdgeRole::Existing).collect();
        for &e in &p.forced_edges {
            fixed[e.index()] = true;
        }
        let mut route_inner = vec![false; nv];
        for route in &p.through_routes {
            for w in route.windows(2) {
                if let Some(h) = mesh.half_edge_between(w[0], w[1]) {
                    fixed[mesh.he_edge(h).index()] = true;
                }
            }
            for &v in &route[1..route.len() - 1] {
                route_inner[v.index()] = true;
            }
        }
        let mut groups = Vec::new();
        if let (Some(t), Some(pl), Some(rooms)) = (&tiling, placements, &p.rooms) {
            for &k in &t.rooms {
                let room = &pl[k];
                match rooms.mode {
                    RoomMode::Floorplan => {
                        for e in &room.inner_edges {
                            allowed[e.index()] = false;
                        }
                        groups.push(room.boundary_edges.clone());
                    }
                    RoomMode::Game => {
                        for e in &room.boundary_edges {
                            allowed[e.index()] = false;
                        }
                        groups.push(room.inner_edges.clone());
                    }
                }
            }
            for g in &mut groups {
                g.retain(|e| allowed[e.index()]);
            }
        }
        if p.dead_ends == Allow::Forbid {
            peel(p, mesh, &mut allowed, &fixed);
            for g in &mut groups {
                g.retain(|e: &EdgeId| allowed[e.index()]);
            }
        }
        let conflict = (0..ne).any(|e| fixed[e] && !allowed[e]) || groups.iter().any(|g| g.is_empty());
        let mut edge_groups = vec![Vec::new(); ne];
        for (g, es) in groups.iter().enumerate() {
            for e in es {
                edge_groups[e.index()].push(g as u32);
            }
        }
        let cost_len = mesh
            .edges()
            .map(|e| if p.roles[e.index()] == EdgeRole::Candidate { mesh.edge_length(e) } else { 0.0 })
            .collect();
        let coverage = p.rooms.is_none();
        let needs_cover: Vec<bool> = mesh.vertices().map(|v| coverage && !p.is_obstacle_vertex[v.index()]).collect();
        let balls = if coverage { mesh.vertices().map(|v| cover_set(p, v)).collect() } else { Vec::new() };

        let mut configs = Vec::new();
        if p.w_zigzag != Weight::Off {
            for z in zigzag_configs(mesh) {
                keep_config(p, &allowed, &z.edges, p.w_zigzag, &mut configs);
            }
        }
        if p.w_too_close != Weight::Off {
            for t in too_close_configs(mesh) {
                keep_config(p, &allowed, &t.edges, p.w_too_close, &mut configs);
            }
        }
        let mut edge_configs = vec![Vec::new(); ne];
        for (i, c) in configs.iter().enumerate() {
            for e in &c.edges {
                edge_configs[e.index()].push(i as u32);
            }
        }
        let mut tconfigs = Vec::new();
        if p.w_t_junction != Weight::Off {
            for (_, v, e0, others) in t_configs(mesh) {
                if designed(p, &[e0, others[0], others[1], others[2]]) && others.iter().all(|e| allowed[e.index()]) {
                    tconfigs.push(TConfig {
                        vertex: v,
                        e0,
                        others,
                        forbid: p.w_t_junction == Weight::Forbid,
                        weight: p.w_t_junction.value(),
                    });
                }
            }
        }
        let mut edge_tconfigs = vec![Vec::new(); ne];
        for (i, t) in tconfigs.iter().enumerate() {
            edge_tconfigs[t.e0.index()].push(i as u32);
            for e in t.others {
                edge_tconfigs[e.index()].push(i as u32);
            }
        }
        let mut pairs = Vec::new();
        let mut edge_paths = vec![Vec::new(); ne];
        if let Some(sets) = paths {
            for (i, pair) in sets.pairs.iter().enumerate() {
                let list: Vec<Vec<EdgeId>> = pair.paths.iter().map(|path| path.edges.clone()).collect();
                for (j, path) in list.iter().enumerate() {
                    for e in path {
                        edge_paths[e.index()].push((i as u32, j as u32));
                    }
                }
                pairs.push(list);
            }
        }
        let mut forced_vertex = vec![false; nv];
        for &v in &p.forced_vertices {
            forced_vertex[v.index()] = true;
        }
        // Work (module `budget`): the rules' size; a configuration is enumerated (and named)
        // at the cost of many steps.
        let ball_size: usize = balls.iter().map(Vec::len).sum();
        budget::charge_tight((nv + ne + ball_size) as u64);
        budget::charge((CONFIG_UNITS * (configs.len() + tconfigs.len())) as u64);
        Rules {
            p,
            mesh,
            allowed,
            fixed,
            cost_len,
            balls,
            needs_cover,
            configs,
            edge_configs,
            tconfigs,
            edge_tconfigs,
            dead_end_forbid: p.dead_ends == Allow::Forbid,
            branch_forbid: p.branches == Allow::Forbid,
            route_inner,
            forced_vertex,
            pairs,
            edge_paths,
            groups,
            edge_groups,
            tiling,
            conflict,
            placements,
        }
    }

    /// Whether a vertex is a sink.
    pub fn is_sink(&self, v: VertexId) -> bool {
        self.p.is_sink[v.index()]
    }

    /// Whether an edge may be switched by a search (allowed and not fixed).
    pub fn free(&self, e: EdgeId) -> bool {
        self.allowed[e.index()] && !self.fixed[e.index()]
    }

    /// Whether a game level's block graph has the shape its level type asks for (always true
    /// for other problems). Checked like [`crate::design::validate_rooms`] does.
    pub fn shape_ok(&self, s: &State) -> bool {
        use crate::design::GraphShape as G;
        use crate::spec::LevelType;
        let (Some(rooms), Some(pl), Some(t)) = (&self.p.rooms, self.placements, &self.tiling) else { return true };
        let (RoomMode::Game, Some(level)) = (rooms.mode, rooms.level) else { return true };
        let net = s.network(self);
        let shape = crate::design::block_graph(self.p, &net, pl).shape;
        match level {
            LevelType::Circular => shape == G::Cycle || (t.rooms.len() == 1 && shape == G::Path),
            LevelType::Linear => shape == G::Path,
            LevelType::Branching => !matches!(shape, G::Disconnected),
        }
    }

    /// Whether the objective needs shortest paths (distance or travel terms).
    pub fn needs_paths(&self) -> bool {
        self.p.w_distance > 0.0 || self.p.w_travel > 0.0
    }
}

/// Where dead-ends are forbidden, every active non-sink vertex has two active edges or more, so
/// an edge is only usable inside the part of the graph that survives peeling: repeatedly drop
/// the usable edges of every non-sink vertex with fewer than two (fixed edges are never
/// dropped). What is dropped could only ever lead into a dead-end.
fn peel(p: &Problem, mesh: &Mesh, allowed: &mut [bool], fixed: &[bool]) {
    let mut deg: Vec<u32> =
        mesh.vertices().map(|v| mesh.incident_edges(v).filter(|e| allowed[e.index()]).count() as u32).collect();
    let mut stack: Vec<VertexId> = mesh.vertices().filter(|v| !p.is_sink[v.index()] && deg[v.index()] == 1).collect();
    while let Some(v) = stack.pop() {
        if deg[v.index()] != 1 {
            continue;
        }
        let Some(e) = mesh.incident_edges(v).find(|e| allowed[e.index()]) else { continue };
        if fixed[e.index()] {
            continue;
        }
        allowed[e.index()] = false;
        deg[v.index()] = 0;
        let (a, b) = mesh.edge_vertices(e);
        let w = if a == v { b } else { a };
        deg[w.index()] -= 1;
        if !p.is_sink[w.index()] && deg[w.index()] == 1 {
            stack.push(w);
        }
    }
}

/// Violation counts, one per rule.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Counts {
    pub uncovered: i64,
    pub dead_ends: i64,
    pub branches: i64,
    pub configs: i64,
    pub tjunctions: i64,
    pub routes: i64,
    pub forced_vertices: i64,
    pub forced_edges: i64,
    pub pairs: i64,
    pub groups: i64,
}

impl Counts {
    /// The total number of violations (islands not included).
    pub fn total(&self) -> i64 {
        self.uncovered
            + self.dead_ends
            + self.branches
            + self.configs
            + self.tjunctions
            + self.routes
            + self.forced_vertices
            + self.forced_edges
            + self.pairs
            + self.groups
    }
}

/// A set of active edges with its rule counts.
#[derive(Clone, Debug)]
pub(crate) struct State {
    pub active: Vec<bool>,
    pub deg: Vec<u32>,
    cover: Vec<u32>,
    config_count: Vec<u8>,
    t_count: Vec<u8>,
    path_count: Vec<Vec<u16>>,
    pair_full: Vec<u32>,
    group_count: Vec<u32>,
    pub counts: Counts,
    /// Length of the active candidate edges.
    pub length: f64,
    /// The weighted penalised features present.
    pub penalty: f64,
    /// Scratch for connectivity searches (a visit stamp per vertex).
    stamp: Vec<u32>,
    generation: u32,
}

impl State {
    /// Nothing active; then every fixed edge switched on.
    pub fn new(r: &Rules) -> State {
        let (nv, ne) = (r.mesh.num_vertices(), r.mesh.num_edges());
        let mut s = State {
            active: vec![false; ne],
            deg: vec![0; nv],
            cover: vec![0; nv],
            config_count: vec![0; r.configs.len()],
            t_count: vec![0; r.tconfigs.len()],
            path_count: r.pairs.iter().map(|ps| vec![0; ps.len()]).collect(),
            pair_full: vec![0; r.pairs.len()],
            group_count: vec![0; r.groups.len()],
            counts: Counts::default(),
            length: 0.0,
            penalty: 0.0,
            stamp: vec![0; nv],
            generation: 0,
        };
        // Counts of the empty network.
        s.counts.uncovered = r.needs_cover.iter().filter(|&&c| c).count() as i64;
        s.counts.routes = r.route_inner.iter().filter(|&&x| x).count() as i64;
        s.counts.forced_vertices = r.forced_vertex.iter().filter(|&&x| x).count() as i64;
        s.counts.forced_edges = r.p.forced_edges.len() as i64;
        s.counts.pairs = r.pairs.len() as i64;
        s.counts.groups = r.groups.len() as i64;
        for (i, t) in r.tconfigs.iter().enumerate() {
            let _ = (i, t); // a T needs three active edges: none in the empty network
        }
        for e in r.mesh.edges() {
            if r.fixed[e.index()] && r.allowed[e.index()] {
                s.toggle(r, e);
            }
        }
        s
    }

    /// A state with exactly the given edges active (fixed edges included whatever `active` says).
    pub fn from_active(r: &Rules, active: &[bool]) -> State {
        let mut s = State::new(r);
        for e in r.mesh.edges() {
            if active[e.index()] && !s.active[e.index()] {
                s.toggle(r, e);
            }
        }
        s
    }

    /// Switches one edge, updating every count.
    pub fn toggle(&mut self, r: &Rules, e: EdgeId) {
        let i = e.index();
        // Work (module `budget`): a unit, and a tight step per count this edge touches.
        let touched =
            r.edge_configs[i].len() + r.edge_tconfigs[i].len() + r.edge_paths[i].len() + r.edge_groups[i].len();
        budget::charge(1 + budget::tight(touched as u64));
        let on = !self.active[i];
        self.active[i] = on;
        let (a, b) = r.mesh.edge_vertices(e);
        for x in [a, b] {
            self.change_degree(r, x, on);
        }
        self.length += if on { r.cost_len[i] } else { -r.cost_len[i] };
        if r.p.forced_edges.contains(&e) {
            self.counts.forced_edges += if on { -1 } else { 1 };
        }
        for &c in &r.edge_configs[i] {
            let cfg = &r.configs[c as usize];
            let n = cfg.edges.len() as u8;
            let before = self.config_count[c as usize] == n;
            if on {
                self.config_count[c as usize] += 1;
            } else {
                self.config_count[c as usize] -= 1;
            }
            let after = self.config_count[c as usize] == n;
            if before != after {
                let d = if after { 1 } else { -1 };
                if cfg.forbid {
                    self.counts.configs += d;
                } else {
                    self.penalty += d as f64 * cfg.weight;
                }
            }
        }
        for &t in &r.edge_tconfigs[i] {
            let tc = &r.tconfigs[t as usize];
            let e0_on_after = self.active[tc.e0.index()];
            let e0_on_before = if tc.e0 == e { !on } else { e0_on_after };
            let before = !e0_on_before && self.t_count[t as usize] == 3;
            if tc.e0 != e {
                if on {
                    self.t_count[t as usize] += 1;
                } else {
                    self.t_count[t as usize] -= 1;
                }
            }
            let after = !e0_on_after && self.t_count[t as usize] == 3;
            if before != after {
                let d = if after { 1 } else { -1 };
                if tc.forbid {
                    self.counts.tjunctions += d;
                } else {
                    self.penalty += d as f64 * tc.weight;
                }
            }
        }
        for &(pair, path) in &r.edge_paths[i] {
            let n = r.pairs[pair as usize][path as usize].len() as u16;
            let cnt = &mut self.path_count[pair as usize][path as usize];
            let before = *cnt == n;
            if on {
                *cnt += 1;
            } else {
                *cnt -= 1;
            }
            let after = *cnt == n;
            if before != after {
                let full = &mut self.pair_full[pair as usize];
                let was = *full > 0;
                if after {
                    *full += 1;
                } else {
                    *full -= 1;
                }
                if was != (*full > 0) {
                    self.counts.pairs += if was { 1 } else { -1 };
                }
            }
        }
        for &g in &r.edge_groups[i] {
            let cnt = &mut self.group_count[g as usize];
            let was = *cnt > 0;
            if on {
                *cnt += 1;
            } else {
                *cnt -= 1;
            }
            if was != (*cnt > 0) {
                self.counts.groups += if was { 1 } else { -1 };
            }
        }
    }

    fn change_degree(&mut self, r: &Rules, x: VertexId, up: bool) {
        let xi = x.index();
        let before = self.deg[xi];
        let after = if up { before + 1 } else { before - 1 };
        let sink = r.p.is_sink[xi];
        let dead = |d: u32| r.dead_end_forbid && d == 1 && !sink;
        let branch = |d: u32| r.branch_forbid && d >= 3;
        let route = |d: u32| r.route_inner[xi] && d != 2;
        let forced = |d: u32| r.forced_vertex[xi] && d == 0;
        let diff = |f: &dyn Fn(u32) -> bool| f(after) as i64 - f(before) as i64;
        self.counts.dead_ends += diff(&dead);
        self.counts.branches += diff(&branch);
        self.counts.routes += diff(&route);
        self.counts.forced_vertices += diff(&forced);
        self.deg[xi] = after;
        if (before == 0) != (after == 0) && !r.balls.is_empty() {
            budget::charge_tight(r.balls[xi].len() as u64);
            for &y in &r.balls[xi] {
                let c = &mut self.cover[y.index()];
                if up {
                    *c += 1;
                    if *c == 1 && r.needs_cover[y.index()] {
                        self.counts.uncovered -= 1;
                    }
                } else {
                    *c -= 1;
                    if *c == 0 && r.needs_cover[y.index()] {
                        self.counts.uncovered += 1;
                    }
                }
            }
        }
    }

    /// Whether `v` is covered (some active vertex within range), or needs no cover.
    pub fn covered(&self, r: &Rules, v: VertexId) -> bool {
        !r.needs_cover[v.index()] || self.cover[v.index()] > 0
    }

    /// Whether group (room) `g` has an active edge.
    pub fn group_ok(&self, g: usize) -> bool {
        self.group_count[g] > 0
    }

    /// Whether point-to-point pair `k` has a fully active path.
    pub fn pair_ok(&self, k: usize) -> bool {
        self.pair_full[k] > 0
    }

    /// How many edges of a pair's path are active.
    pub fn path_active(&self, pair: usize, path: usize) -> usize {
        self.path_count[pair][path] as usize
    }

    /// Whether a configuration is present.
    pub fn config_present(&self, r: &Rules, c: usize) -> bool {
        self.config_count[c] as usize == r.configs[c].edges.len()
    }

    /// Whether a T configuration is present.
    pub fn t_present(&self, r: &Rules, t: usize) -> bool {
        !self.active[r.tconfigs[t].e0.index()] && self.t_count[t] == 3
    }

    /// Whether the active vertex `v` reaches a sink along active edges (true for inactive `v`).
    pub fn reaches_sink(&mut self, r: &Rules, v: VertexId) -> bool {
        if self.deg[v.index()] == 0 || r.p.is_sink[v.index()] {
            return true;
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.generation = 1;
        }
        let g = self.generation;
        let mut queue = VecDeque::from([v]);
        self.stamp[v.index()] = g;
        while let Some(x) = queue.pop_front() {
            budget::charge(1);
            for &h in r.mesh.outgoing(x) {
                if !self.active[r.mesh.he_edge(h).index()] {
                    continue;
                }
                let y = r.mesh.he_head(h);
                if self.stamp[y.index()] == g {
                    continue;
                }
                if r.p.is_sink[y.index()] {
                    return true;
                }
                self.stamp[y.index()] = g;
                queue.push_back(y);
            }
        }
        false
    }

    /// The components with no sink (islands), as vertex lists.
    pub fn islands(&self, r: &Rules) -> Vec<Vec<VertexId>> {
        let mesh = r.mesh;
        budget::charge_tight(mesh.num_vertices() as u64);
        let mut seen = vec![false; mesh.num_vertices()];
        let mut out = Vec::new();
        for v in mesh.vertices() {
            if seen[v.index()] || self.deg[v.index()] == 0 {
                continue;
            }
            let mut comp = vec![v];
            seen[v.index()] = true;
            let mut k = 0;
            let mut sink = false;
            while k < comp.len() {
                let x = comp[k];
                k += 1;
                sink |= r.p.is_sink[x.index()];
                for &h in mesh.outgoing(x) {
                    if self.active[mesh.he_edge(h).index()] {
                        let y = mesh.he_head(h);
                        if !seen[y.index()] {
                            seen[y.index()] = true;
                            comp.push(y);
                        }
                    }
                }
            }
            if !sink {
                out.push(comp);
            }
        }
        out
    }

    /// Whether every rule holds, islands included.
    pub fn feasible(&self, r: &Rules) -> bool {
        self.counts.total() == 0 && self.islands(r).is_empty()
    }

    /// The design this state stands for (rooms from the tiling).
    pub fn network(&self, r: &Rules) -> Network {
        Network {
            active: self.active.clone(),
            directions: Vec::new(),
            labels: Vec::new(),
            rooms: r.tiling.as_ref().map_or(Vec::new(), |t| t.rooms.clone()),
        }
    }

    /// The objective (15) of this state, computed as [`crate::design::Objective::of`] computes it
    /// (length and penalties from the counts; the distance and travel terms by shortest paths).
    pub fn objective(&self, r: &Rules) -> f64 {
        let p = r.p;
        let mut total = p.w_length * self.length + self.penalty;
        if r.needs_paths() {
            // Shortest paths over the network, per term (module `budget`).
            budget::charge(2 * r.mesh.num_edges() as u64);
            let net =
                Network { active: self.active.clone(), directions: Vec::new(), labels: Vec::new(), rooms: Vec::new() };
            let mesh = r.mesh;
            if p.w_distance > 0.0 {
                let h = label_distances(p, &net);
                let label_into = |v: VertexId, len: f64| if p.is_sink[v.index()] { 0.0 } else { len + h[v.index()] };
                let mut distance = 0.0;
                for e in mesh.edges() {
                    if self.active[e.index()] && p.roles[e.index()] == EdgeRole::Candidate {
                        let len = mesh.edge_length(e);
                        let (u, v) = mesh.edge_vertices(e);
                        let best = label_into(v, len).min(label_into(u, len));
                        if best.is_finite() {
                            distance += best;
                        }
                    }
                }
                total += p.w_distance * distance;
            }
            if p.w_travel > 0.0 {
                let d = travel_distances(mesh, &net, &p.is_sink);
                let travel: f64 = mesh
                    .vertices()
                    .filter(|v| self.deg[v.index()] > 0 && !p.is_sink[v.index()] && d[v.index()].is_finite())
                    .map(|v| d[v.index()])
                    .sum();
                total += p.w_travel * travel;
            }
        }
        total
    }

    /// The active half-edges out of `v`.
    pub fn active_out<'m>(&'m self, mesh: &'m Mesh, v: VertexId) -> impl Iterator<Item = HalfEdgeId> + 'm {
        mesh.outgoing(v).iter().copied().filter(move |&h| self.active[mesh.he_edge(h).index()])
    }
}
