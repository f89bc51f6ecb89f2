//! Local search on a valid design: moves over *chains* (maximal runs of free active edges whose
//! inner vertices have degree 2 — a street between two junctions), each tried on the state's
//! incremental counts and undone unless the design stays valid and gets cheaper:
//!
//! - **drop** a chain (a street that coverage, rooms and connectivity do not need);
//! - **reroute** a chain: drop it and join its ends by the cheapest rule-aware path;
//! - **add** one edge between two active vertices (a shortcut; only when the objective has a
//!   distance or travel term, which shortcuts can lower);
//!
//! and, at a local optimum, a **kick**: drop a few random chains from the best design, repair it
//! with the construction's rule steps, and descend again (iterated local search), until the
//! deadline. Connectivity after a removal is checked from the removed edges' ends only.

use super::budget::{self, Deadline};
use super::build::Builder;
use super::paths::{apply, Query, Target};
use super::state::{Rules, State};
use crate::mesh::{EdgeId, VertexId};

/// A maximal run of free active edges through degree-2 vertices.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Chain {
    pub edges: Vec<EdgeId>,
    pub ends: (VertexId, VertexId),
}

/// Whether a chain stops at `v`.
fn stop(r: &Rules, s: &State, v: VertexId) -> bool {
    s.deg[v.index()] != 2
        || r.is_sink(v)
        || r.forced_vertex[v.index()]
        || r.route_inner[v.index()]
        || s.active_out(r.mesh, v).any(|h| r.fixed[r.mesh.he_edge(h).index()])
}

/// The chains of a state, in a deterministic order.
pub(crate) fn chains(r: &Rules, s: &State) -> Vec<Chain> {
    let mesh = r.mesh;
    budget::charge_tight((mesh.num_vertices() + mesh.num_edges()) as u64);
    let mut seen = vec![false; mesh.num_edges()];
    let mut out = Vec::new();
    let walk = |start: VertexId, first: crate::mesh::HalfEdgeId, seen: &mut Vec<bool>| -> Chain {
        let mut edges = Vec::new();
        let mut h = first;
        loop {
            let e = mesh.he_edge(h);
            seen[e.index()] = true;
            edges.push(e);
            let x = mesh.he_head(h);
            if x == start || stop(r, s, x) {
                return Chain { edges, ends: (start, x) };
            }
            match s.active_out(mesh, x).find(|&g| mesh.he_edge(g) != e) {
                Some(g) if r.free(mesh.he_edge(g)) && !seen[mesh.he_edge(g).index()] => h = g,
                _ => return Chain { edges, ends: (start, x) },
            }
        }
    };
    for v in mesh.vertices() {
        if s.deg[v.index()] == 0 || !stop(r, s, v) {
            continue;
        }
        for h in s.active_out(mesh, v).collect::<Vec<_>>() {
            let e = mesh.he_edge(h);
            if r.free(e) && !seen[e.index()] {
                out.push(walk(v, h, &mut seen));
            }
        }
    }
    // Cycles with no stop.
    for e in mesh.edges() {
        if s.active[e.index()] && r.free(e) && !seen[e.index()] {
            let h = mesh.edge_half_edges(e)[0];
            out.push(walk(mesh.he_tail(h), h, &mut seen));
        }
    }
    out
}

/// Counters of a local search.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct LocalStats {
    pub tried: u64,
    pub accepted: u64,
    pub kicks: u64,
}

/// The local search: a builder (for paths and repairs) around the current state.
pub(crate) struct LocalSearch<'r, 'a> {
    pub b: Builder<'r, 'a>,
    pub objective: f64,
    pub stats: LocalStats,
}

impl<'r, 'a> LocalSearch<'r, 'a> {
    /// Starts from a valid state.
    pub fn new(b: Builder<'r, 'a>) -> Self {
        let objective = b.s.objective(b.r);
        LocalSearch { b, objective, stats: LocalStats::default() }
    }

    /// Whether the current state is valid given that only `removed` edges were switched off
    /// (their ends are checked for a path to a sink); on success its objective.
    fn judge(&mut self, removed: &[EdgeId]) -> Option<f64> {
        let r = self.b.r;
        if self.b.s.counts.total() != 0 {
            return None;
        }
        for &e in removed {
            let (a, c) = r.mesh.edge_vertices(e);
            if !self.b.s.reaches_sink(r, a) || !self.b.s.reaches_sink(r, c) {
                return None;
            }
        }
        if !r.shape_ok(&self.b.s) {
            return None;
        }
        Some(self.b.s.objective(r))
    }

    fn set(&mut self, edges: &[EdgeId], on: bool) {
        for &e in edges {
            if self.b.s.active[e.index()] != on {
                self.b.s.toggle(self.b.r, e);
            }
        }
    }

    /// Tries to drop a chain; keeps the change if it improves the objective.
    pub fn try_drop(&mut self, c: &Chain) -> bool {
        self.stats.tried += 1;
        self.set(&c.edges, false);
        match self.judge(&c.edges) {
            Some(obj) if obj < self.objective - 1e-9 => {
                self.objective = obj;
                self.stats.accepted += 1;
                true
            }
            _ => {
                self.set(&c.edges, true);
                false
            }
        }
    }

    /// Tries to replace a chain by the cheapest rule-aware path between its ends.
    pub fn try_reroute(&mut self, c: &Chain) -> bool {
        let (a, z) = c.ends;
        if a == z {
            return false;
        }
        self.stats.tried += 1;
        self.set(&c.edges, false);
        let target = |w: VertexId| w == z;
        let mut q = Query::new(std::slice::from_ref(&a), Target::Vertex(&target));
        q.noise = self.b.noise;
        let r = self.b.r;
        let path = self.b.ps.find(r, &self.b.s, &q, &mut self.b.rng);
        let Some(path) = path else {
            self.set(&c.edges, true);
            return false;
        };
        let new: Vec<EdgeId> = path.iter().map(|&h| r.mesh.he_edge(h)).collect();
        if new.len() == c.edges.len() && new.iter().all(|e| c.edges.contains(e)) {
            self.set(&c.edges, true);
            return false;
        }
        apply(r, &mut self.b.s, &path);
        match self.judge(&c.edges) {
            Some(obj) if obj < self.objective - 1e-9 => {
                self.objective = obj;
                self.stats.accepted += 1;
                true
            }
            _ => {
                self.set(&new, false);
                self.set(&c.edges, true);
                false
            }
        }
    }

    /// Tries to add one free edge between two active vertices.
    pub fn try_add(&mut self, e: EdgeId) -> bool {
        let r = self.b.r;
        let (a, c) = r.mesh.edge_vertices(e);
        if self.b.s.active[e.index()] || !r.free(e) || self.b.s.deg[a.index()] == 0 || self.b.s.deg[c.index()] == 0 {
            return false;
        }
        self.stats.tried += 1;
        self.b.s.toggle(r, e);
        match self.judge(&[]) {
            Some(obj) if obj < self.objective - 1e-9 => {
                self.objective = obj;
                self.stats.accepted += 1;
                true
            }
            _ => {
                self.b.s.toggle(r, e);
                false
            }
        }
    }

    /// Descends with drops, reroutes and (for distance objectives) additions until no move
    /// improves or the deadline passes.
    pub fn descend(&mut self, deadline: Deadline) {
        loop {
            let mut improved = false;
            let mut cs = chains(self.b.r, &self.b.s);
            self.b.rng.shuffle(&mut cs);
            for c in &cs {
                if deadline.passed() {
                    return;
                }
                if c.edges.iter().any(|e| !self.b.s.active[e.index()]) {
                    continue; // changed by an earlier move of this sweep
                }
                if self.try_drop(c) || self.try_reroute(c) {
                    improved = true;
                }
            }
            if self.b.r.needs_paths() {
                let mut free: Vec<EdgeId> =
                    self.b.r.mesh.edges().filter(|&e| self.b.r.free(e) && !self.b.s.active[e.index()]).collect();
                self.b.rng.shuffle(&mut free);
                for e in free {
                    if deadline.passed() {
                        return;
                    }
                    improved |= self.try_add(e);
                }
            }
            if !improved {
                return;
            }
        }
    }

    /// Iterated local search until the deadline: descend, then kick the best design found and
    /// descend again. Returns the best valid state and its objective.
    pub fn run(mut self, deadline: Deadline, mut on_best: impl FnMut(f64)) -> (State, f64, LocalStats) {
        self.descend(deadline);
        let mut best = (self.b.s.clone(), self.objective);
        on_best(best.1);
        while !deadline.passed() {
            self.stats.kicks += 1;
            self.b.s = best.0.clone();
            let mut cs = chains(self.b.r, &self.b.s);
            if cs.is_empty() {
                break;
            }
            self.b.rng.shuffle(&mut cs);
            let k = 1 + self.b.rng.below(3.min(cs.len()));
            for c in cs.iter().take(k) {
                self.set(&c.edges, false);
            }
            self.b.deadline = Some(deadline);
            if !self.b.repair_all() || !self.b.s.feasible(self.b.r) || !self.b.r.shape_ok(&self.b.s) {
                continue;
            }
            self.objective = self.b.s.objective(self.b.r);
            self.descend(deadline);
            if self.objective < best.1 - 1e-9 {
                best = (self.b.s.clone(), self.objective);
                on_best(best.1);
            }
        }
        (best.0, best.1, self.stats)
    }
}
