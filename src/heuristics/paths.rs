//! Rule-aware shortest paths: Dijkstra over the allowed, inactive edges from a set of sources to
//! a target, refusing every step that would complete a forbidden configuration (with the
//! active edges or the path's own last edges), create a forbidden branch or T-junction where the
//! path attaches, or pass through an active vertex. Penalised configurations the step would
//! complete are added to its cost, so paths avoid zig-zags where they can; a small cost per
//! turn keeps streets straight; a seeded noise on edge costs varies the paths between restarts.

use super::budget;
use super::rng::Rng;
use super::state::{Rules, State};
use crate::mesh::paths::OrdF64;
use crate::mesh::{EdgeId, HalfEdgeId, VertexId};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// How many of the path's last edges the rule checks look back along.
const LOOKBACK: usize = 5;

/// Where a path may end.
pub(crate) enum Target<'q> {
    /// At a vertex for which the predicate holds (reached by at least one edge).
    Vertex(&'q dyn Fn(VertexId) -> bool),
}

/// One path query.
pub(crate) struct Query<'q> {
    /// Start vertices (active or not).
    pub sources: &'q [VertexId],
    /// Where it may end.
    pub target: Target<'q>,
    /// Extra restriction on the edges it may use.
    pub edge_ok: Option<&'q dyn Fn(EdgeId) -> bool>,
    /// Extra restriction on the vertices it may enter.
    pub vertex_ok: Option<&'q dyn Fn(VertexId) -> bool>,
    /// Relative noise on edge costs (0: deterministic).
    pub noise: f64,
    /// Cost of a turn, relative to the edge length.
    pub turn: f64,
}

impl<'q> Query<'q> {
    /// A query with no extra restriction, no noise, a small turn cost.
    pub fn new(sources: &'q [VertexId], target: Target<'q>) -> Query<'q> {
        Query { sources, target, edge_ok: None, vertex_ok: None, noise: 0.0, turn: 0.05 }
    }
}

/// Reusable buffers for path searches on one mesh.
pub(crate) struct PathSearch {
    dist: Vec<f64>,
    pred: Vec<u32>,
    done: Vec<bool>,
    touched: Vec<u32>,
    is_source: Vec<bool>,
}

const NONE: u32 = u32::MAX;

impl PathSearch {
    /// Buffers for a mesh with `nv` vertices.
    pub fn new(nv: usize) -> PathSearch {
        PathSearch {
            dist: vec![f64::INFINITY; nv],
            pred: vec![NONE; nv],
            done: vec![false; nv],
            touched: Vec::new(),
            is_source: vec![false; nv],
        }
    }

    fn reset(&mut self) {
        for &v in &self.touched {
            self.dist[v as usize] = f64::INFINITY;
            self.pred[v as usize] = NONE;
            self.done[v as usize] = false;
            self.is_source[v as usize] = false;
        }
        self.touched.clear();
    }

    /// The path's half-edges ending at `v` (most recent first), up to `LOOKBACK`.
    fn chain(&self, r: &Rules, mut v: VertexId, out: &mut Vec<EdgeId>) {
        out.clear();
        while out.len() < LOOKBACK {
            let h = self.pred[v.index()];
            if h == NONE {
                break;
            }
            let h = HalfEdgeId(h);
            out.push(r.mesh.he_edge(h));
            v = r.mesh.he_tail(h);
        }
    }

    /// The cheapest path for the query, as half-edges from a source to the end, or `None`.
    pub fn find(&mut self, r: &Rules, s: &State, q: &Query, rng: &mut Rng) -> Option<Vec<HalfEdgeId>> {
        self.reset();
        let mesh = r.mesh;
        let mut heap = BinaryHeap::new();
        for &v in q.sources {
            if !attach_ok(r, s, v, None) {
                continue;
            }
            if self.dist[v.index()] > 0.0 {
                self.dist[v.index()] = 0.0;
                self.touched.push(v.0);
                self.is_source[v.index()] = true;
                heap.push(Reverse((OrdF64(0.0), v.0)));
            }
        }
        let mut chain = Vec::with_capacity(LOOKBACK);
        let Target::Vertex(is_target) = q.target;
        // Work (module `budget`): a unit per vertex popped and per half-edge scanned.
        let mut work = 0u64;
        let found = loop {
            let Some(Reverse((OrdF64(d), vi))) = heap.pop() else { break None };
            work += 1;
            let v = VertexId(vi);
            if self.done[v.index()] || d > self.dist[v.index()] {
                continue;
            }
            self.done[v.index()] = true;
            let reached = self.pred[v.index()] != NONE;
            if reached {
                if is_target(v) {
                    break Some(self.path_to(r, v));
                }
                // An active vertex ends a path; it cannot be passed through.
                if s.deg[v.index()] > 0 {
                    continue;
                }
            }
            self.chain(r, v, &mut chain);
            let prev = chain.first().copied();
            work += mesh.outgoing(v).len() as u64;
            for &h in mesh.outgoing(v) {
                let e = mesh.he_edge(h);
                if !r.allowed[e.index()] || s.active[e.index()] || chain.contains(&e) {
                    continue;
                }
                if q.edge_ok.is_some_and(|f| !f(e)) {
                    continue;
                }
                let w = mesh.he_head(h);
                if self.done[w.index()] || q.vertex_ok.is_some_and(|f| !f(w)) {
                    continue;
                }
                // The tail gets this edge: at a source, check attaching there.
                if !reached && !attach_ok(r, s, v, Some(e)) {
                    continue;
                }
                if s.deg[w.index()] > 0 || self.is_source[w.index()] {
                    // Entering an active vertex (or a source) ends the path there.
                    if !is_target(w) || self.is_source[w.index()] || !attach_ok(r, s, w, Some(e)) {
                        continue;
                    }
                } else if r.route_inner[w.index()] {
                    continue;
                }
                let Some(extra) = step_cost(r, s, e, &chain) else { continue };
                let mut c = mesh.edge_length(e) * (1.0 + q.noise * rng.unit()) + extra;
                if let Some(pe) = prev {
                    if turns(r, pe, e) {
                        c += q.turn * mesh.edge_length(e);
                    }
                }
                let nd = d + c;
                if nd < self.dist[w.index()] {
                    if self.dist[w.index()].is_infinite() {
                        self.touched.push(w.0);
                    }
                    self.dist[w.index()] = nd;
                    self.pred[w.index()] = h.0;
                    heap.push(Reverse((OrdF64(nd), w.0)));
                }
            }
        };
        budget::charge(work);
        found
    }

    fn path_to(&self, r: &Rules, mut v: VertexId) -> Vec<HalfEdgeId> {
        let mut out = Vec::new();
        while self.pred[v.index()] != NONE {
            let h = HalfEdgeId(self.pred[v.index()]);
            out.push(h);
            v = r.mesh.he_tail(h);
        }
        out.reverse();
        out
    }
}

/// Whether two consecutive edges turn (are not opposite at their shared vertex). On a vertex of
/// even valence, the straight continuation is the edge half-way round.
fn turns(r: &Rules, a: EdgeId, b: EdgeId) -> bool {
    let mesh = r.mesh;
    let (a0, a1) = mesh.edge_vertices(a);
    let (b0, b1) = mesh.edge_vertices(b);
    let shared = if a0 == b0 || a0 == b1 { a0 } else { a1 };
    let out = mesh.outgoing(shared);
    let n = out.len();
    if n % 2 == 1 || mesh.is_boundary_vertex(shared) {
        return true;
    }
    let ia = out.iter().position(|&h| mesh.he_edge(h) == a);
    let ib = out.iter().position(|&h| mesh.he_edge(h) == b);
    match (ia, ib) {
        (Some(i), Some(j)) => (i + n / 2) % n != j,
        _ => true,
    }
}

/// The extra cost of activating `e` after the path's last edges `chain` (most recent first):
/// `None` when it would complete a forbidden configuration, else the penalties it completes.
fn step_cost(r: &Rules, s: &State, e: EdgeId, chain: &[EdgeId]) -> Option<f64> {
    let mut extra = 0.0;
    for &c in &r.edge_configs[e.index()] {
        let cfg = &r.configs[c as usize];
        if cfg.edges.iter().all(|&x| x == e || s.active[x.index()] || chain.contains(&x)) {
            if cfg.forbid {
                return None;
            }
            extra += cfg.weight;
        }
    }
    Some(extra)
}

/// Whether vertex `v` may get the new edge `e` (or, with `None`, may start a path at all): no
/// branch where branches are forbidden, no T-junction where they are forbidden (penalised ones
/// are allowed), not the inner vertex of a through route.
pub(crate) fn attach_ok(r: &Rules, s: &State, v: VertexId, e: Option<EdgeId>) -> bool {
    let d = s.deg[v.index()];
    if d == 0 {
        return true;
    }
    if r.route_inner[v.index()] {
        return false;
    }
    if r.branch_forbid && d >= 2 {
        return false;
    }
    if let Some(e) = e {
        for &t in &r.edge_tconfigs[e.index()] {
            let tc = &r.tconfigs[t as usize];
            if tc.vertex != v || !tc.forbid {
                continue;
            }
            let on = |x: EdgeId| x == e || s.active[x.index()];
            if !on(tc.e0) && tc.others.iter().all(|&x| on(x)) {
                return false;
            }
        }
    }
    true
}

/// Switches on the edges of a path.
pub(crate) fn apply(r: &Rules, s: &mut State, path: &[HalfEdgeId]) {
    for &h in path {
        let e = r.mesh.he_edge(h);
        if !s.active[e.index()] {
            s.toggle(r, e);
        }
    }
}
