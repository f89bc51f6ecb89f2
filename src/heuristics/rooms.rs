//! Floor plans and game levels: an exact tiling by the room templates ([`super::tiling`]), then
//! the network the tiling allows.
//!
//! Before tiling, what the spec forces is turned into placements to avoid: an edge that must be
//! active (a forced edge; the only usable edge of a sole sink or of a forced vertex) cannot lie
//! inside a floor-plan room or on a game block's boundary, and a vertex that must be active
//! cannot be walled in by one room (floor plans) or sit on a block's corner where no block
//! edge reaches it (game levels). Rooms no corridor could touch, and blocks with no inner edge,
//! are avoided too.
//!
//! - **Floor plans** and **branching game levels**: the construction's rule steps
//!   ([`super::build`]) on the tiling's allowed edges, with "every room touched" (resp. "every
//!   block traversed") as a rule.
//! - **Circular and linear game levels**: the traversal visits every block once, so it is a
//!   Hamiltonian cycle (resp. path between the two sinks) of the blocks, two blocks being
//!   neighbours where they share a *portal* (a vertex both have an inner edge at). A
//!   depth-first search with Warnsdorff's order (fewest free neighbours first) and a degree
//!   check on the blocks left finds one; inside each block the route from its entry portal to
//!   its exit portal is the cheapest rule-aware path over its inner edges (local rules never
//!   reach across a block's boundary, so the routes combine).

use super::budget::{self, Deadline};
use super::build::Builder;
use super::paths::{PathSearch, Query, Target};
use super::rng::Rng;
use super::state::{Rules, State, Tiling};
use super::tiling::{tile, TilingProblem};
use crate::mesh::{EdgeId, VertexId};
use crate::rules::paths::PathSets;
use crate::rules::placements::Placement;
use crate::spec::{EdgeRole, LevelType, Problem, RoomMode};
use std::collections::HashMap;

/// Search nodes per tiling attempt.
const TILING_NODES: u64 = 200_000;
/// Search nodes per Hamiltonian attempt.
const HAM_NODES: u64 = 200_000;

/// Edges and vertices every design must have active.
fn musts(p: &Problem) -> (Vec<EdgeId>, Vec<VertexId>) {
    let mesh = &p.mesh;
    let mut edges: Vec<EdgeId> = p.forced_edges.clone();
    for route in &p.through_routes {
        for w in route.windows(2) {
            if let Some(h) = mesh.half_edge_between(w[0], w[1]) {
                edges.push(mesh.he_edge(h));
            }
        }
    }
    let mut vertices: Vec<VertexId> = p.forced_vertices.clone();
    let sinks: Vec<VertexId> = mesh.vertices().filter(|v| p.is_sink[v.index()]).collect();
    let linear = p.rooms.as_ref().is_some_and(|r| r.level == Some(LevelType::Linear));
    if sinks.len() == 1 || linear {
        vertices.extend(&sinks);
    }
    for &v in &vertices {
        let usable: Vec<EdgeId> = mesh.incident_edges(v).filter(|e| p.roles[e.index()] != EdgeRole::Excluded).collect();
        if usable.len() == 1
            || (usable.len() == 2 && p.dead_ends == crate::spec::Allow::Forbid && !p.is_sink[v.index()])
        {
            edges.extend(usable);
        }
    }
    edges.sort_unstable();
    edges.dedup();
    vertices.sort_unstable();
    vertices.dedup();
    (edges, vertices)
}

/// The tiling problem with the placements the spec rules out removed.
pub(crate) fn tiling_problem<'a>(p: &Problem, placements: &'a [Placement]) -> TilingProblem<'a> {
    let rooms = p.rooms.as_ref().expect("a room problem");
    let mesh = &p.mesh;
    let (must_edges, must_vertices) = musts(p);
    let usable_edge = |e: &EdgeId| p.roles[e.index()] != EdgeRole::Excluded;
    let usable = placements
        .iter()
        .map(|pl| match rooms.mode {
            RoomMode::Floorplan => {
                pl.boundary_edges.iter().any(usable_edge)
                    && !pl.inner_edges.iter().any(|e| must_edges.contains(e))
                    && !must_vertices.iter().any(|&v| {
                        let mut es = mesh.incident_edges(v).filter(usable_edge).peekable();
                        es.peek().is_some() && es.all(|e| pl.inner_edges.binary_search(&e).is_ok())
                    })
            }
            RoomMode::Game => {
                pl.inner_edges.iter().any(usable_edge)
                    && !pl.boundary_edges.iter().any(|e| must_edges.contains(e))
                    && !must_vertices.iter().any(|&v| {
                        let touches = mesh.vertex_faces(v).any(|f| pl.faces.binary_search(&f).is_ok());
                        touches && !mesh.incident_edges(v).any(|e| pl.inner_edges.binary_search(&e).is_ok())
                    })
            }
        })
        .collect();
    let portals = (rooms.mode == RoomMode::Game).then(|| {
        placements
            .iter()
            .map(|pl| {
                let border = pl.border_vertices(mesh);
                let mut vs: Vec<u32> = pl
                    .inner_edges
                    .iter()
                    .flat_map(|&e| {
                        let (a, b) = mesh.edge_vertices(e);
                        [a, b]
                    })
                    .filter(|v| border.binary_search(v).is_ok())
                    .map(|v| v.0)
                    .collect();
                vs.sort_unstable();
                vs.dedup();
                vs
            })
            .collect()
    });
    TilingProblem {
        placements,
        usable,
        cover: mesh.faces().map(|f| !p.is_obstacle_face[f.index()]).collect(),
        counts: rooms.counts.clone(),
        portals,
    }
}

/// One attempt: a seeded tiling and its network. `None` when this seed found no tiling or no
/// valid network on it. Floor plans alternate two orders: corridors first (even attempts: a
/// coverage network under the spec's rules, hop range 2 or 3, then a tiling whose rooms keep
/// those corridors on their walls and, every other time, touch one), and rooms first (odd attempts: a tiling, then
/// [`retile`] until no room is doomed, then the corridors).
pub(crate) fn construct<'a>(
    p: &'a Problem,
    placements: &'a [Placement],
    paths: Option<&PathSets>,
    rng: &mut Rng,
    noise: f64,
    deadline: Deadline,
    attempt: u64,
) -> Option<(Rules<'a>, State)> {
    let rooms_spec = p.rooms.as_ref()?;
    let mut tp = tiling_problem(p, placements);
    if rooms_spec.mode == RoomMode::Floorplan && attempt % 4 == 1 && p.w_too_close == crate::spec::Weight::Forbid {
        // Rooms one face wide somewhere would force a too-close pair wherever corridors run on
        // both their sides: leave them out this time (unless a count asks for them).
        for (k, pl) in placements.iter().enumerate() {
            if rooms_spec.counts[pl.template].0.unwrap_or(0) == 0 && one_wide(&p.mesh, pl) {
                tp.usable[k] = false;
            }
        }
    }
    let mut corridors: Option<Vec<bool>> = None;
    if rooms_spec.mode == RoomMode::Floorplan && attempt.is_multiple_of(2) {
        let range = [2.0, 3.0][(attempt / 2 % 2) as usize];
        // Every other time rooms need not touch a corridor yet (the rule steps add one).
        let touch = attempt % 8 < 4;
        let active = corridors_first(p, paths, range, rng, noise, deadline)?;
        for (k, pl) in placements.iter().enumerate() {
            tp.usable[k] = tp.usable[k]
                && !pl.inner_edges.iter().any(|e| active[e.index()])
                && (!touch || pl.boundary_edges.iter().any(|e| active[e.index()]));
        }
        corridors = Some(active);
    }
    let rooms = tile(&tp, rng.next_u64(), TILING_NODES);
    let mut rooms = rooms?;
    if rooms_spec.mode == RoomMode::Floorplan && corridors.is_none() && p.dead_ends == crate::spec::Allow::Forbid {
        rooms = retile(p, &tp, rooms, rng, deadline, &|rs: &[usize]| doomed(p, &tp, rs))?;
    }
    if let (RoomMode::Game, Some(level @ (LevelType::Circular | LevelType::Linear))) =
        (rooms_spec.mode, rooms_spec.level)
    {
        rooms = retile(p, &tp, rooms, rng, deadline, &|rs: &[usize]| doomed_blocks(p, &tp, rs, level))?;
    }
    let rules = Rules::new(p, paths, Some(placements), Some(Tiling { rooms }));
    if rules.conflict {
        return None;
    }
    let level = (rooms_spec.mode == RoomMode::Game).then_some(rooms_spec.level).flatten();
    let state = match (level, corridors) {
        (Some(LevelType::Circular) | Some(LevelType::Linear), _) => traverse(&rules, placements, rng, deadline)?,
        (_, start) => {
            let fresh = start.is_none();
            let s = match start {
                Some(active) => State::from_active(&rules, &active),
                None => State::new(&rules),
            };
            let mut b = Builder::new(&rules, s, rng.fork(), noise, Some(deadline));
            // Rooms first: every wall on, then pruned; the rule steps mend what is left.
            if fresh && rooms_spec.mode == RoomMode::Floorplan && !b.everything_then_prune() {
                b.s = State::new(&rules);
            }
            if !b.repair_all() {
                return None;
            }
            b.s
        }
    };
    (state.feasible(&rules) && rules.shape_ok(&state)).then_some((rules, state))
}

/// Blocks a circular (linear) traversal can never pass: fewer than two blocks they share a
/// portal with (one for the blocks holding a linear level's sinks).
fn doomed_blocks(p: &Problem, tp: &TilingProblem, rooms: &[usize], level: LevelType) -> Vec<usize> {
    let rules = Rules::new(p, None, Some(tp.placements), Some(Tiling { rooms: rooms.to_vec() }));
    let blocks = Blocks::new(&rules, tp.placements);
    let ends: Vec<usize> = match level {
        LevelType::Linear => p
            .mesh
            .vertices()
            .filter(|v| p.is_sink[v.index()])
            .flat_map(|v| blocks.portal_of[v.index()].clone())
            .collect(),
        _ => Vec::new(),
    };
    let neighbours = |b: usize| -> Vec<usize> {
        let mut ns: Vec<usize> = blocks.adj[b].iter().map(|&(y, _)| y).collect();
        ns.dedup();
        ns
    };
    let mut out: Vec<usize> =
        (0..rooms.len()).filter(|&b| neighbours(b).len() < if ends.contains(&b) { 1 } else { 2 }).collect();
    // A block whose only two neighbours include an end of the path must come right after
    // (before) that end: an end has room for one such block.
    for &e in &ends {
        let forced: Vec<usize> = (0..rooms.len())
            .filter(|&b| !ends.contains(&b) && neighbours(b).len() == 2 && neighbours(b).contains(&e))
            .collect();
        if forced.len() > 1 {
            out.extend(forced);
        }
    }
    out.sort_unstable();
    out.dedup();
    out.into_iter().map(|b| rooms[b]).collect()
}

/// Whether a placement has a face with two opposite sides on its boundary.
fn one_wide(mesh: &crate::mesh::Mesh, pl: &Placement) -> bool {
    pl.faces.iter().any(|&f| {
        let es = mesh.face_edges(f);
        es.len() == 4
            && (0..2).any(|k| {
                pl.boundary_edges.binary_search(&es[k]).is_ok() && pl.boundary_edges.binary_search(&es[k + 2]).is_ok()
            })
    })
}

/// Rooms no corridor can ever touch with this tiling, and rooms around a forced vertex that can
/// never get its two corridors: where dead-ends are forbidden, a corridor edge must survive
/// peeling (see the state's `peel`) of the walls the tiling leaves.
fn doomed(p: &Problem, tp: &TilingProblem, rooms: &[usize]) -> Vec<usize> {
    let mesh = &p.mesh;
    let tiling = Rules::new(p, None, Some(tp.placements), Some(Tiling { rooms: rooms.to_vec() }));
    // The walls a corridor from a sink can reach at all.
    let mut reach = vec![false; mesh.num_vertices()];
    let mut stack: Vec<crate::mesh::VertexId> = mesh.vertices().filter(|v| p.is_sink[v.index()]).collect();
    for v in &stack {
        reach[v.index()] = true;
    }
    while let Some(x) = stack.pop() {
        for &h in mesh.outgoing(x) {
            let y = mesh.he_head(h);
            if tiling.allowed[mesh.he_edge(h).index()] && !reach[y.index()] {
                reach[y.index()] = true;
                stack.push(y);
            }
        }
    }
    let edge_reached = |e: &EdgeId| {
        let (a, b) = mesh.edge_vertices(*e);
        reach[a.index()] && reach[b.index()]
    };
    let mut out: Vec<usize> =
        tiling.groups.iter().enumerate().filter(|(_, g)| !g.iter().any(edge_reached)).map(|(i, _)| rooms[i]).collect();
    for &v in &p.forced_vertices {
        let usable = mesh.incident_edges(v).filter(|e| tiling.allowed[e.index()] && edge_reached(e)).count();
        if usable < if p.is_sink[v.index()] { 1 } else { 2 } {
            for &k in rooms {
                if mesh.vertex_faces(v).any(|f| tp.placements[k].faces.binary_search(&f).is_ok()) {
                    out.push(k);
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// Re-places rooms until none is doomed (by `doomed`, e.g. [`doomed`] or
/// [`doomed_blocks`]): frees the rooms within two faces of a
/// doomed one and tiles the freed faces again (exact cover on them alone, counts adjusted),
/// keeping the new tiling when it has no more doomed rooms than the old one.
fn retile(
    p: &Problem,
    tp: &TilingProblem,
    mut rooms: Vec<usize>,
    rng: &mut Rng,
    deadline: Deadline,
    doomed: &dyn Fn(&[usize]) -> Vec<usize>,
) -> Option<Vec<usize>> {
    let mesh = &p.mesh;
    let nf = mesh.num_faces();
    let mut bad = doomed(&rooms);
    for _ in 0..300 {
        if bad.is_empty() {
            return Some(rooms);
        }
        if deadline.passed() {
            return None;
        }
        let b = bad[rng.below(bad.len())];
        // Faces within two steps of the doomed room.
        let mut near = vec![false; nf];
        let mut frontier: Vec<crate::mesh::FaceId> = tp.placements[b].faces.clone();
        for f in &frontier {
            near[f.index()] = true;
        }
        for _ in 0..2 {
            let mut next = Vec::new();
            for &f in &frontier {
                for e in mesh.face_edges(f) {
                    for g in mesh.edge_faces(e).into_iter().flatten() {
                        if !near[g.index()] {
                            near[g.index()] = true;
                            next.push(g);
                        }
                    }
                }
            }
            frontier = next;
        }
        let (freed, kept): (Vec<usize>, Vec<usize>) =
            rooms.iter().partition(|&&k| tp.placements[k].faces.iter().any(|f| near[f.index()]));
        let mut cover = vec![false; nf];
        for &k in &freed {
            for f in &tp.placements[k].faces {
                cover[f.index()] = true;
            }
        }
        let mut kept_count = vec![0u32; tp.counts.len()];
        for &k in &kept {
            kept_count[tp.placements[k].template] += 1;
        }
        let counts = tp
            .counts
            .iter()
            .zip(&kept_count)
            .map(|(&(lo, hi), &c)| (lo.map(|lo| lo.saturating_sub(c)), hi.map(|hi| hi.saturating_sub(c))))
            .collect();
        let usable = tp
            .usable
            .iter()
            .zip(tp.placements)
            .map(|(&u, pl)| u && pl.faces.iter().all(|f| cover[f.index()]))
            .collect();
        let sub = TilingProblem { placements: tp.placements, usable, cover, counts, portals: None };
        let Some(new) = tile(&sub, rng.next_u64(), 20_000) else { continue };
        let mut candidate = kept;
        candidate.extend(new);
        candidate.sort_unstable();
        let nb = doomed(&candidate);
        if nb.len() <= bad.len() {
            rooms = candidate;
            bad = nb;
        }
    }
    bad.is_empty().then_some(rooms)
}

/// A floor plan's corridors before its rooms: the network of the same spec without rooms and
/// with hop coverage `range` (every vertex within `range` edges of a corridor, so every face is
/// near one), built by the construction's rule steps.
fn corridors_first(
    p: &Problem,
    paths: Option<&PathSets>,
    range: f64,
    rng: &mut Rng,
    noise: f64,
    deadline: Deadline,
) -> Option<Vec<bool>> {
    let mut q = p.clone();
    q.rooms = None;
    q.coverage_range = range;
    q.coverage_model = crate::spec::CoverageModel::Hops;
    let rules = Rules::corridors(&q, paths);
    let mut b = Builder::new(&rules, State::new(&rules), rng.fork(), noise, Some(deadline));
    (b.repair_all() && b.s.feasible(&rules)).then_some(b.s.active)
}

/// A game level's blocks and their portals.
struct Blocks {
    /// Per block (position in the tiling): its placement's boundary vertices.
    boundary: Vec<Vec<VertexId>>,
    /// Per edge: the block it is an inner edge of.
    inner_of: Vec<Option<usize>>,
    /// Per block: (neighbour block, shared portal), sorted.
    adj: Vec<Vec<(usize, VertexId)>>,
    /// Per vertex: the blocks with an allowed inner edge at it.
    portal_of: Vec<Vec<usize>>,
}

impl Blocks {
    fn new(r: &Rules, placements: &[Placement]) -> Blocks {
        let mesh = r.mesh;
        let rooms = &r.tiling.as_ref().expect("tiled").rooms;
        let mut inner_of = vec![None; mesh.num_edges()];
        let mut boundary = Vec::new();
        for (b, &k) in rooms.iter().enumerate() {
            for e in &placements[k].inner_edges {
                if r.allowed[e.index()] {
                    inner_of[e.index()] = Some(b);
                }
            }
            boundary.push(placements[k].border_vertices(mesh));
        }
        let mut portal_of = vec![Vec::new(); mesh.num_vertices()];
        for v in mesh.vertices() {
            let mut bs: Vec<usize> = mesh.incident_edges(v).filter_map(|e| inner_of[e.index()]).collect();
            bs.sort_unstable();
            bs.dedup();
            portal_of[v.index()] = bs;
        }
        let mut adj = vec![Vec::new(); rooms.len()];
        for v in mesh.vertices() {
            let bs = &portal_of[v.index()];
            for i in 0..bs.len() {
                for j in 0..bs.len() {
                    if i != j && boundary[bs[i]].binary_search(&v).is_ok() && boundary[bs[j]].binary_search(&v).is_ok()
                    {
                        adj[bs[i]].push((bs[j], v));
                    }
                }
            }
        }
        for a in &mut adj {
            a.sort_unstable();
        }
        Blocks { boundary, inner_of, adj, portal_of }
    }
}

/// Cheapest routes inside one block, cached.
struct Routes<'r, 'a> {
    r: &'r Rules<'a>,
    blocks: &'r Blocks,
    scratch: State,
    ps: PathSearch,
    rng: Rng,
    cache: HashMap<RouteKey, Option<(f64, Vec<EdgeId>)>>,
}

/// A cached route: block, from, to, and the vertex it must avoid.
type RouteKey = (usize, VertexId, VertexId, Option<VertexId>);

impl Routes<'_, '_> {
    /// The route in block `b` from `a` to `z` (through `via` if given): its cost and edges.
    fn get(&mut self, b: usize, a: VertexId, z: VertexId, via: Option<VertexId>) -> Option<(f64, Vec<EdgeId>)> {
        if a == z {
            return None;
        }
        let key = (b, a, z, via);
        if let Some(v) = self.cache.get(&key) {
            return v.clone();
        }
        let out = self.compute(b, a, z, via);
        self.cache.insert(key, out.clone());
        out
    }

    fn leg(&mut self, b: usize, a: VertexId, z: VertexId, avoid: Option<VertexId>) -> Option<Vec<EdgeId>> {
        let blocks = self.blocks;
        let r = self.r;
        let edge_ok = |e: EdgeId| blocks.inner_of[e.index()] == Some(b);
        let vertex_ok = |w: VertexId| w == z || (Some(w) != avoid && blocks.boundary[b].binary_search(&w).is_err());
        let target = |w: VertexId| w == z;
        let mut q = Query::new(std::slice::from_ref(&a), Target::Vertex(&target));
        q.edge_ok = Some(&edge_ok);
        q.vertex_ok = Some(&vertex_ok);
        let path = self.ps.find(r, &self.scratch, &q, &mut self.rng)?;
        Some(path.iter().map(|&h| r.mesh.he_edge(h)).collect())
    }

    fn compute(&mut self, b: usize, a: VertexId, z: VertexId, via: Option<VertexId>) -> Option<(f64, Vec<EdgeId>)> {
        let r = self.r;
        let edges = match via {
            None => self.leg(b, a, z, None)?,
            Some(s) => {
                let first = self.leg(b, a, s, Some(z))?;
                for &e in &first {
                    self.scratch.toggle(r, e);
                }
                let second = self.leg(b, s, z, None);
                for &e in &first {
                    self.scratch.toggle(r, e);
                }
                let mut all = first;
                all.extend(second?);
                all
            }
        };
        // Its cost, and a last check that the whole route breaks no local rule.
        let (l0, p0, c0) = (self.scratch.length, self.scratch.penalty, self.scratch.counts);
        for &e in &edges {
            self.scratch.toggle(r, e);
        }
        let ok = self.scratch.counts.configs == c0.configs && self.scratch.counts.tjunctions == c0.tjunctions;
        let cost = r.p.w_length * (self.scratch.length - l0) + (self.scratch.penalty - p0);
        for &e in &edges {
            self.scratch.toggle(r, e);
        }
        ok.then_some((cost, edges))
    }
}

/// The Hamiltonian search over blocks.
struct Ham<'x, 'r, 'a> {
    blocks: &'x Blocks,
    routes: &'x mut Routes<'r, 'a>,
    n: usize,
    visited: Vec<bool>,
    used: HashMap<VertexId, bool>,
    /// (block, entry portal) in visiting order.
    order: Vec<(usize, Option<VertexId>)>,
    /// The exit portal chosen for the first block (closing case).
    first_exit: Option<VertexId>,
    start: usize,
    end: usize,
    end_exit: Option<VertexId>,
    /// Circular level with the sink inside the start block: the walk closes into it.
    closing: Option<VertexId>,
    nodes: u64,
    rng: Rng,
    /// Work units of one [`Ham::degrees_ok`] (module `budget`): a scan of the blocks and their
    /// neighbours, a step a few nanoseconds (measured: a sixteenth of a unit each).
    degree_check_units: u64,
}

impl Ham<'_, '_, '_> {
    fn free_neighbours(&self, y: usize) -> usize {
        let mut last = usize::MAX;
        let mut n = 0;
        for &(z, _) in &self.blocks.adj[y] {
            if z != last && !self.visited[z] {
                n += 1;
                last = z;
            }
        }
        n
    }

    /// Every block left can still be passed through (two usable neighbours; the end block one).
    fn degrees_ok(&self, y: usize) -> bool {
        budget::charge(self.degree_check_units);
        for z in 0..self.n {
            if self.visited[z] {
                continue;
            }
            let mut last = usize::MAX;
            let mut avail = 0;
            for &(w, _) in &self.blocks.adj[z] {
                if w != last && (!self.visited[w] || w == y || w == self.end) {
                    avail += 1;
                    last = w;
                }
            }
            let need = if z == self.end { 1 } else { 2 };
            if avail < need {
                return false;
            }
        }
        // The blocks left, with `y`, must be connected (and reach the end).
        let mut seen = vec![false; self.n];
        let mut stack = vec![y];
        seen[y] = true;
        let mut reached = 0;
        while let Some(x) = stack.pop() {
            for &(w, _) in &self.blocks.adj[x] {
                if !seen[w] && (!self.visited[w] || w == self.end) {
                    seen[w] = true;
                    if !self.visited[w] {
                        reached += 1;
                    }
                    stack.push(w);
                }
            }
        }
        let left = (0..self.n).filter(|&z| !self.visited[z]).count();
        reached == left && (self.closing.is_some() || left == 0 || seen[self.end])
    }

    fn dfs(&mut self, x: usize, entry: Option<VertexId>, count: usize) -> Option<bool> {
        self.nodes += 1;
        budget::charge(1);
        if self.nodes > HAM_NODES {
            return None;
        }
        if count == self.n {
            return Some(self.finish(x, entry));
        }
        let mut cands: Vec<(usize, u64, usize, VertexId)> = Vec::new();
        for &(y, q) in &self.blocks.adj[x] {
            if self.visited[y] || self.used.get(&q).copied().unwrap_or(false) {
                continue;
            }
            if y == self.end && self.closing.is_none() && count + 1 < self.n {
                continue;
            }
            cands.push((self.free_neighbours(y), self.rng.next_u64(), y, q));
        }
        cands.sort_unstable();
        for (_, _, y, q) in cands {
            match entry {
                Some(e) => {
                    if self.routes.get(x, e, q, None).is_none() {
                        continue;
                    }
                }
                None => self.first_exit = Some(q),
            }
            self.visited[y] = true;
            self.used.insert(q, true);
            self.order.push((y, Some(q)));
            if self.degrees_ok(y) {
                match self.dfs(y, Some(q), count + 1) {
                    Some(true) => return Some(true),
                    None => return None,
                    Some(false) => {}
                }
            }
            self.order.pop();
            self.used.insert(q, false);
            self.visited[y] = false;
        }
        Some(false)
    }

    fn finish(&mut self, x: usize, entry: Option<VertexId>) -> bool {
        let Some(e) = entry else { return false };
        match self.closing {
            Some(sink) => {
                let first_exit = self.first_exit.expect("the first block was left");
                let portals: Vec<VertexId> = self.blocks.adj[x]
                    .iter()
                    .filter(|&&(y, q)| y == self.start && !self.used.get(&q).copied().unwrap_or(false))
                    .map(|&(_, q)| q)
                    .collect();
                for q in portals {
                    if self.routes.get(x, e, q, None).is_some()
                        && self.routes.get(self.start, q, first_exit, Some(sink)).is_some()
                    {
                        self.order.push((self.start, Some(q)));
                        return true;
                    }
                }
                false
            }
            None => x == self.end && self.routes.get(x, e, self.end_exit.expect("an end portal"), None).is_some(),
        }
    }
}

/// A circular or linear level: a Hamiltonian walk over the blocks and the routes inside them.
fn traverse(r: &Rules, placements: &[Placement], rng: &mut Rng, deadline: Deadline) -> Option<State> {
    let p = r.p;
    let level = p.rooms.as_ref()?.level?;
    let blocks = Blocks::new(r, placements);
    let n = blocks.adj.len();
    let sinks: Vec<VertexId> = r.mesh.vertices().filter(|v| p.is_sink[v.index()]).collect();
    let block_with = |v: VertexId| -> Vec<usize> { blocks.portal_of[v.index()].clone() };
    let mut routes = Routes {
        r,
        blocks: &blocks,
        scratch: State::new(r),
        ps: PathSearch::new(r.mesh.num_vertices()),
        rng: rng.fork(),
        cache: HashMap::new(),
    };
    // Start, end and how the walk closes.
    let (start, start_entry, end, end_exit, closing) = match level {
        LevelType::Linear => {
            let (a, b) = (sinks.first().copied()?, sinks.get(1).copied()?);
            let (ba, bb) = (block_with(a), block_with(b));
            if ba.len() != 1 || bb.len() != 1 {
                return None;
            }
            (ba[0], Some(a), bb[0], Some(b), None)
        }
        LevelType::Circular => {
            let s = sinks.first().copied()?;
            let bs = block_with(s);
            match bs.len() {
                // The sink is a portal between two blocks: the walk leaves one through it and
                // comes back into it from the other.
                2 => (bs[1], Some(s), bs[0], Some(s), None),
                // The sink is inside one block: the walk closes into that block through it.
                1 if blocks.boundary[bs[0]].binary_search(&s).is_err() => (bs[0], None, bs[0], None, Some(s)),
                _ => {
                    return None;
                }
            }
        }
        LevelType::Branching => return None,
    };
    if deadline.passed() {
        return None;
    }
    let mut ham = Ham {
        blocks: &blocks,
        routes: &mut routes,
        n,
        visited: vec![false; n],
        used: HashMap::new(),
        order: vec![(start, start_entry)],
        first_exit: None,
        start,
        end,
        end_exit,
        closing,
        nodes: 0,
        degree_check_units: budget::tight((n + blocks.adj.iter().map(Vec::len).sum::<usize>()) as u64 / 2),
        rng: rng.fork(),
    };
    ham.visited[start] = true;
    if let Some(s) = start_entry {
        ham.used.insert(s, true);
    }
    if n == 1 {
        return None;
    }
    let res = ham.dfs(start, start_entry, 1);
    if res != Some(true) {
        return None;
    }
    let order = ham.order.clone();
    let first_exit = ham.first_exit;
    // Each block's route from its entry to its exit (the next block's entry).
    let mut state = State::new(r);
    for (i, &(b, entry)) in order.iter().enumerate() {
        let exit = match order.get(i + 1) {
            Some(&(_, q)) => q,
            None => end_exit,
        };
        let route = match (closing, i) {
            (Some(_), 0) => continue, // the start block is routed when the walk closes into it
            (Some(s), _) if i == order.len() - 1 => routes.get(b, entry?, first_exit?, Some(s))?,
            _ => routes.get(b, entry?, exit?, None)?,
        };
        for e in route.1 {
            if !state.active[e.index()] {
                state.toggle(r, e);
            }
        }
    }
    Some(state)
}
