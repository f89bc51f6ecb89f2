//! Construction and repair of networks: from any set of active edges (the fixed ones alone, a
//! solver's disconnected incumbent, a design after a move) to one that breaks no rule, by rule
//! steps in a fixed order, repeated until nothing is left to fix:
//!
//! 1. islands are joined to a sink by a path, or dropped when no path exists;
//! 2. point-to-point pairs get their cheapest enumerated path;
//! 3. forced vertices are joined to the network;
//! 4. rooms no corridor touches (floor plans) get a path to one of their walls;
//! 5. coverage, greedily: the uncovered vertex farthest from the network is joined by a path,
//!    and where dead-ends are forbidden the path continues back to the network (so the network
//!    grows by through-streets, not stubs);
//! 6. dead-ends are extended to the network, or pruned back to the last junction;
//! 7. forbidden configurations, branches and through-route degrees are broken by dropping one
//!    of their free edges (steps 5–6 then mend what that breaks).
//!
//! Every path is rule-aware ([`super::paths`]): it never completes a forbidden configuration.

use super::budget::Deadline;
use super::paths::{apply, PathSearch, Query, Target};
use super::rng::Rng;
use super::state::{Rules, State};
use crate::mesh::{EdgeId, HalfEdgeId, VertexId};
use std::collections::VecDeque;

/// How many rounds of the rule steps before giving up.
const MAX_ROUNDS: usize = 40;

/// A state being built or repaired.
pub(crate) struct Builder<'r, 'a> {
    pub r: &'r Rules<'a>,
    pub s: State,
    pub ps: PathSearch,
    pub rng: Rng,
    /// Relative noise on path costs (varies the design between restarts).
    pub noise: f64,
    pub deadline: Option<Deadline>,
    /// Coverage joins the ball vertex nearest the network (the shortest arm) first, instead of
    /// the one nearest the uncovered vertex: spurs from the sinks rather than streets through
    /// the uncovered area (what a distance objective with dead-ends allowed rewards).
    pub short_arms: bool,
}

impl<'r, 'a> Builder<'r, 'a> {
    /// A builder starting from `s`.
    pub fn new(r: &'r Rules<'a>, s: State, rng: Rng, noise: f64, deadline: Option<Deadline>) -> Self {
        Builder { r, s, ps: PathSearch::new(r.mesh.num_vertices()), rng, noise, deadline, short_arms: false }
    }

    fn out_of_time(&self) -> bool {
        self.deadline.is_some_and(|d| d.passed())
    }

    /// Runs the rule steps until every rule holds; `false` when it cannot get there.
    pub fn repair_all(&mut self) -> bool {
        if self.r.conflict {
            return false;
        }
        for _ in 0..MAX_ROUNDS {
            if self.out_of_time() {
                return false;
            }
            self.join_islands();
            self.join_pairs();
            self.join_forced_vertices();
            self.touch_groups();
            self.cover();
            self.fix_dead_ends();
            if self.s.counts.total() == 0 && self.s.islands(self.r).is_empty() {
                return true;
            }
            self.break_local_violations();
        }
        false
    }

    /// The other construction: every allowed edge on, islands dropped, then every forbidden
    /// configuration (and branch) broken by dropping one of its free edges and pruning the
    /// dead-ends that leaves — each break kept only if no room, pair or forced vertex loses its
    /// last edge and no vertex is uncovered. Suits floor plans, whose corridors are a sparse
    /// choice among the walls. `false` when some configuration cannot be broken that way.
    pub fn everything_then_prune(&mut self) -> bool {
        let r = self.r;
        for e in r.mesh.edges() {
            if r.allowed[e.index()] && !self.s.active[e.index()] {
                self.s.toggle(r, e);
            }
        }
        for island in self.s.islands(r) {
            for v in island {
                for &h in r.mesh.outgoing(v) {
                    let e = r.mesh.he_edge(h);
                    if self.s.active[e.index()] && !r.fixed[e.index()] {
                        self.s.toggle(r, e);
                    }
                }
            }
        }
        for _ in 0..r.mesh.num_edges() {
            if self.out_of_time() {
                return false;
            }
            let Some(mut options) = self.some_local_violation() else {
                return true;
            };
            self.rng.shuffle(&mut options);
            // The break that loses the fewest rooms, pairs, forced vertices and covered vertices
            // (none, ideally); the rule steps afterwards mend what a forced loss leaves.
            let mut best: Option<(i64, EdgeId)> = None;
            for &e in &options {
                let before = self.s.counts;
                let log = self.break_at(e);
                let after = self.s.counts;
                let mut loss = (after.groups - before.groups)
                    + (after.pairs - before.pairs)
                    + (after.forced_vertices - before.forced_vertices)
                    + (after.uncovered - before.uncovered)
                    + (after.dead_ends - before.dead_ends).max(0);
                if log.iter().any(|&e| {
                    let (a, b) = r.mesh.edge_vertices(e);
                    !self.s.reaches_sink(r, a) || !self.s.reaches_sink(r, b)
                }) {
                    loss += 1000;
                }
                self.undo_off(&log);
                if best.is_none_or(|(l, _)| loss < l) {
                    best = Some((loss, e));
                }
                if loss <= 0 {
                    break;
                }
            }
            let Some((_, e)) = best else {
                return false;
            };
            self.break_at(e);
            self.join_islands();
        }
        false
    }

    /// Switches `e` off and prunes the dead-ends that leaves; the edges switched off.
    fn break_at(&mut self, e: EdgeId) -> Vec<EdgeId> {
        let r = self.r;
        let mut log = vec![e];
        self.s.toggle(r, e);
        let (a, b) = r.mesh.edge_vertices(e);
        for x in [a, b] {
            if r.dead_end_forbid && self.s.deg[x.index()] == 1 && !r.is_sink(x) {
                if let Some(more) = self.prune_logged(x) {
                    log.extend(more);
                }
            }
        }
        log
    }

    /// The free edges of one present forbidden configuration, T-junction or branch, if any.
    fn some_local_violation(&self) -> Option<Vec<EdgeId>> {
        let r = self.r;
        for c in 0..r.configs.len() {
            if r.configs[c].forbid && self.s.config_present(r, c) {
                return Some(r.configs[c].edges.iter().copied().filter(|&e| r.free(e)).collect());
            }
        }
        for t in 0..r.tconfigs.len() {
            if r.tconfigs[t].forbid && self.s.t_present(r, t) {
                return Some(r.tconfigs[t].others.iter().copied().filter(|&e| r.free(e)).collect());
            }
        }
        if r.branch_forbid {
            if let Some(v) = r.mesh.vertices().find(|v| self.s.deg[v.index()] >= 3) {
                return Some(self.s.active_out(r.mesh, v).map(|h| r.mesh.he_edge(h)).filter(|&e| r.free(e)).collect());
            }
        }
        None
    }

    /// Switches back on edges switched off.
    fn undo_off(&mut self, edges: &[EdgeId]) {
        for &e in edges {
            if !self.s.active[e.index()] {
                self.s.toggle(self.r, e);
            }
        }
    }

    /// Prunes the dead-end `v` back to a junction (no checks); the edges it switched off, or
    /// `None` (nothing switched) when the chain ends in a fixed edge.
    fn prune_logged(&mut self, v: VertexId) -> Option<Vec<EdgeId>> {
        let r = self.r;
        let mut chain = Vec::new();
        let mut x = v;
        loop {
            let Some(h) = self.s.active_out(r.mesh, x).next() else { break };
            let e = r.mesh.he_edge(h);
            if r.fixed[e.index()] {
                self.undo_off(&chain);
                return None;
            }
            self.s.toggle(r, e);
            chain.push(e);
            x = r.mesh.he_head(h);
            if self.s.deg[x.index()] != 1 || r.is_sink(x) {
                break;
            }
        }
        Some(chain)
    }

    /// Whether `v` is part of the network that reaches a sink, or a sink (a path may end there).
    fn sink_reached(&self) -> Vec<bool> {
        let mesh = self.r.mesh;
        let mut seen: Vec<bool> = mesh.vertices().map(|v| self.r.is_sink(v)).collect();
        let mut queue: VecDeque<VertexId> = mesh.vertices().filter(|v| self.r.is_sink(*v)).collect();
        while let Some(x) = queue.pop_front() {
            for h in self.s.active_out(mesh, x) {
                let y = mesh.he_head(h);
                if !seen[y.index()] {
                    seen[y.index()] = true;
                    queue.push_back(y);
                }
            }
        }
        seen
    }

    fn find(&mut self, q: &Query) -> Option<Vec<HalfEdgeId>> {
        self.ps.find(self.r, &self.s, q, &mut self.rng)
    }

    /// Switches on a path; returns the edges it switched.
    fn take(&mut self, path: &[HalfEdgeId]) -> Vec<EdgeId> {
        let edges: Vec<EdgeId> =
            path.iter().map(|&h| self.r.mesh.he_edge(h)).filter(|e| !self.s.active[e.index()]).collect();
        apply(self.r, &mut self.s, path);
        edges
    }

    fn undo(&mut self, edges: &[EdgeId]) {
        for &e in edges {
            if self.s.active[e.index()] {
                self.s.toggle(self.r, e);
            }
        }
    }

    /// Step 1: joins every island to the sink-reached network, or drops its free edges.
    pub fn join_islands(&mut self) {
        loop {
            let islands = self.s.islands(self.r);
            let Some(island) = islands.into_iter().next() else { return };
            let reached = self.sink_reached();
            let noise = self.noise;
            let target = |w: VertexId| reached[w.index()];
            let mut q = Query::new(&island, Target::Vertex(&target));
            q.noise = noise;
            let path = self.find(&q);
            match path {
                Some(path) => {
                    self.take(&path);
                    let end = self.r.mesh.he_head(*path.last().expect("a path has an edge"));
                    let _ = end;
                }
                None => {
                    // No way out: drop what can be dropped; a fixed island is beyond repair.
                    let mut dropped = false;
                    for &v in &island {
                        for &h in self.r.mesh.outgoing(v) {
                            let e = self.r.mesh.he_edge(h);
                            if self.s.active[e.index()] && !self.r.fixed[e.index()] {
                                self.s.toggle(self.r, e);
                                dropped = true;
                            }
                        }
                    }
                    if !dropped {
                        return;
                    }
                }
            }
        }
    }

    /// Step 2: every point-to-point pair without a fully active path gets the path that needs
    /// the fewest new edges and completes no forbidden configuration (if there is one).
    pub fn join_pairs(&mut self) {
        let r = self.r;
        for k in 0..r.pairs.len() {
            if self.s.pair_ok(k) {
                continue;
            }
            let mut order: Vec<usize> = (0..r.pairs[k].len()).collect();
            order.sort_by_key(|&j| (r.pairs[k][j].len() - self.s.path_active(k, j), j));
            let mut best: Option<(i64, usize)> = None;
            for &j in order.iter().take(200) {
                if r.pairs[k][j].iter().any(|e| !r.allowed[e.index()]) {
                    continue;
                }
                let before = self.s.counts.configs + self.s.counts.tjunctions + self.s.counts.branches;
                let on: Vec<EdgeId> = r.pairs[k][j].iter().copied().filter(|e| !self.s.active[e.index()]).collect();
                for &e in &on {
                    self.s.toggle(r, e);
                }
                let worse = self.s.counts.configs + self.s.counts.tjunctions + self.s.counts.branches - before;
                self.undo(&on);
                if best.is_none_or(|(w, _)| worse < w) {
                    best = Some((worse, j));
                }
                if worse <= 0 {
                    break;
                }
            }
            if let Some((_, j)) = best {
                for e in r.pairs[k][j].clone() {
                    if !self.s.active[e.index()] {
                        self.s.toggle(r, e);
                    }
                }
            }
        }
    }

    /// Step 3: a forced vertex with no active edge is joined to the network (passed through
    /// where dead-ends are forbidden).
    pub fn join_forced_vertices(&mut self) {
        let r = self.r;
        for &v in &r.p.forced_vertices {
            if self.s.deg[v.index()] == 0 {
                self.through(v);
            }
        }
    }

    /// Step 4: every room no corridor touches (every block no traversal enters) gets one of its
    /// edges, joined to the network at both ends where dead-ends are forbidden; the edges
    /// nearest the network are tried first.
    pub fn touch_groups(&mut self) {
        let r = self.r;
        let mut order: Vec<usize> = (0..r.groups.len()).collect();
        self.rng.shuffle(&mut order);
        for g in order {
            if self.s.group_ok(g) || self.out_of_time() {
                continue;
            }
            let hops = self.hops_from_network();
            let candidates: Vec<EdgeId> = r.groups[g]
                .iter()
                .copied()
                .filter(|&e| {
                    let (a, b) = r.mesh.edge_vertices(e);
                    !self.s.active[e.index()] && r.free(e) && !self.needs_way_on(a) && !self.needs_way_on(b)
                })
                .collect();
            let mut edges: Vec<(u32, u64, EdgeId)> = candidates
                .into_iter()
                .map(|e| {
                    let (a, b) = r.mesh.edge_vertices(e);
                    (hops[a.index()].min(hops[b.index()]), self.rng.next_u64(), e)
                })
                .collect();
            edges.sort_unstable();
            for &(_, _, e) in edges.iter().take(8) {
                if self.bridge(e) {
                    break;
                }
            }
        }
    }

    /// Switches `e` on and joins it to the network: an arm from an inactive end, and where
    /// dead-ends are forbidden an extension from the other end. Undone when that fails or when
    /// `e` completes a forbidden configuration.
    fn bridge(&mut self, e: EdgeId) -> bool {
        let r = self.r;
        let before = self.s.counts;
        self.s.toggle(r, e);
        let worse = self.s.counts.configs > before.configs
            || self.s.counts.tjunctions > before.tjunctions
            || self.s.counts.branches > before.branches
            || self.s.counts.routes > before.routes;
        if worse {
            self.s.toggle(r, e);
            return false;
        }
        let (a, b) = r.mesh.edge_vertices(e);
        let mut taken = vec![e];
        let reached = self.sink_reached();
        if !reached[a.index()] && !reached[b.index()] {
            let mut joined = false;
            for (x, y) in [(a, b), (b, a)] {
                let target = |w: VertexId| w != x && w != y && reached[w.index()];
                let mut q = Query::new(std::slice::from_ref(&x), Target::Vertex(&target));
                q.noise = self.noise;
                if let Some(arm) = self.ps.find(r, &self.s, &q, &mut self.rng) {
                    taken.extend(self.take(&arm));
                    joined = true;
                    break;
                }
            }
            if !joined {
                self.undo(&taken);
                return false;
            }
        }
        for x in [a, b] {
            if self.needs_extension(x) {
                match self.extension(x) {
                    Some(more) => taken.extend(more),
                    None => {
                        self.undo(&taken);
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Whether a path ending at the inactive vertex `w` would leave a dead-end there that no
    /// further path could extend (a non-sink with one usable edge, dead-ends forbidden).
    fn needs_way_on(&self, w: VertexId) -> bool {
        let r = self.r;
        r.dead_end_forbid
            && !r.is_sink(w)
            && self.s.deg[w.index()] == 0
            && r.mesh.incident_edges(w).filter(|e| r.allowed[e.index()]).count() < 2
    }

    fn needs_extension(&self, v: VertexId) -> bool {
        self.r.dead_end_forbid && self.s.deg[v.index()] == 1 && !self.r.is_sink(v)
    }

    /// Extends the dead-end `v` by a path to the network (or a sink).
    pub fn extend(&mut self, v: VertexId) -> bool {
        self.extension(v).is_some()
    }

    /// [`Self::extend`], returning the edges it switched on.
    fn extension(&mut self, v: VertexId) -> Option<Vec<EdgeId>> {
        let reached = self.sink_reached();
        let deg = &self.s.deg;
        let target = |w: VertexId| w != v && (reached[w.index()] || deg[w.index()] > 0);
        let mut q = Query::new(std::slice::from_ref(&v), Target::Vertex(&target));
        q.noise = self.noise;
        let path = self.ps.find(self.r, &self.s, &q, &mut self.rng)?;
        Some(self.take(&path))
    }

    /// Hop distances over allowed edges from the network and the sinks.
    fn hops_from_network(&self) -> Vec<u32> {
        let mesh = self.r.mesh;
        let mut d = vec![u32::MAX; mesh.num_vertices()];
        let mut queue = VecDeque::new();
        for v in mesh.vertices() {
            if self.s.deg[v.index()] > 0 || self.r.is_sink(v) {
                d[v.index()] = 0;
                queue.push_back(v);
            }
        }
        while let Some(x) = queue.pop_front() {
            for &h in mesh.outgoing(x) {
                if !self.r.allowed[mesh.he_edge(h).index()] {
                    continue;
                }
                let y = mesh.he_head(h);
                if d[y.index()] == u32::MAX {
                    d[y.index()] = d[x.index()] + 1;
                    queue.push_back(y);
                }
            }
        }
        d
    }

    /// Step 5: coverage. Repeatedly takes the uncovered vertex farthest from the network and
    /// joins it (or, failing that, a vertex of its coverage ball) by a path from the network,
    /// continued back to the network where dead-ends are forbidden.
    pub fn cover(&mut self) {
        let r = self.r;
        if r.balls.is_empty() {
            return;
        }
        let mut failed = vec![false; r.mesh.num_vertices()];
        // Vertices few others can cover (corners behind walls) go first.
        let coverers: Vec<usize> = r
            .mesh
            .vertices()
            .map(|v| {
                r.balls[v.index()]
                    .iter()
                    .filter(|&&w| !self.needs_way_on(w) && r.mesh.incident_edges(w).any(|e| r.allowed[e.index()]))
                    .count()
            })
            .collect();
        while self.s.counts.uncovered > 0 && !self.out_of_time() {
            let hops = self.hops_from_network();
            let mut best: Vec<VertexId> = Vec::new();
            let mut best_d = 0u32;
            for v in r.mesh.vertices() {
                if failed[v.index()] || self.s.covered(r, v) {
                    continue;
                }
                let d = hops[v.index()];
                let d = if d == u32::MAX { 0 } else { d + 1 };
                let d = if coverers[v.index()] <= 2 { d + 1_000_000 } else { d };
                if best.is_empty() || d > best_d {
                    best.clear();
                    best_d = d;
                }
                if d == best_d {
                    best.push(v);
                }
            }
            if best.is_empty() {
                return;
            }
            let u = best[self.rng.below(best.len())];
            if !self.cover_vertex(u, &hops) {
                failed[u.index()] = true;
            }
        }
    }

    /// Covers `u` by making a vertex of its ball active: `u` itself if it can be, else the
    /// others nearest `u` first — with `short_arms`, those nearest the network first (`hops`:
    /// each vertex's hop distance from it). The vertex gets a path (an *arm*) to the network, and where
    /// dead-ends are forbidden a second arm, so the network passes through it; when the second
    /// arm cannot be found, the first is tried again leaving the vertex another way.
    fn cover_vertex(&mut self, u: VertexId, hops: &[u32]) -> bool {
        let r = self.r;
        let short_arms = self.short_arms;
        let mut ball: Vec<(u32, usize, VertexId)> = r
            .mesh
            .hop_distances(u, r.balls[u.index()].len())
            .into_iter()
            .filter(|(w, _)| r.balls[u.index()].binary_search(w).is_ok())
            .map(|(w, d)| (if short_arms { hops[w.index()] } else { 0 }, d, w))
            .collect();
        ball.sort_unstable();
        let mut tried = 0;
        for (_, _, t) in ball {
            if tried >= 6 || self.out_of_time() {
                break;
            }
            if self.s.deg[t.index()] > 0
                || self.needs_way_on(t)
                || r.mesh.incident_edges(t).all(|e| !r.allowed[e.index()])
            {
                continue;
            }
            tried += 1;
            if self.through(t) {
                return true;
            }
        }
        false
    }

    /// Joins the inactive vertex `t` to the network by one arm (two where dead-ends are
    /// forbidden and `t` is not a sink).
    fn through(&mut self, t: VertexId) -> bool {
        let r = self.r;
        let two = r.dead_end_forbid && !r.is_sink(t);
        let mut banned: Vec<EdgeId> = Vec::new();
        for _ in 0..4 {
            let reached = self.sink_reached();
            let target = |w: VertexId| w != t && reached[w.index()];
            let edge_ok = |e: EdgeId| !banned.contains(&e);
            let mut q = Query::new(std::slice::from_ref(&t), Target::Vertex(&target));
            q.noise = self.noise;
            q.edge_ok = Some(&edge_ok);
            let Some(arm) = self.ps.find(r, &self.s, &q, &mut self.rng) else {
                return false;
            };
            let first = r.mesh.he_edge(arm[0]);
            let new = self.take(&arm);
            if !two || self.extend(t) {
                return true;
            }
            self.undo(&new);
            banned.push(first);
        }
        false
    }

    /// Step 6: every dead-end is extended to the network, or pruned back to a junction.
    pub fn fix_dead_ends(&mut self) {
        let r = self.r;
        if !r.dead_end_forbid {
            return;
        }
        for _ in 0..4 {
            let leaves: Vec<VertexId> = r.mesh.vertices().filter(|&v| self.needs_extension(v)).collect();
            if leaves.is_empty() {
                return;
            }
            for v in leaves {
                if !self.needs_extension(v) {
                    continue;
                }
                if !self.extend(v) {
                    self.prune(v);
                }
            }
        }
    }

    /// Drops the chain from the dead-end `v` back to the first vertex that is a junction, a
    /// sink or the end of a fixed edge, unless that uncovers a vertex or breaks a requirement.
    pub fn prune(&mut self, v: VertexId) -> bool {
        let r = self.r;
        let mut chain = Vec::new();
        let mut x = v;
        let mut from: Option<EdgeId> = None;
        loop {
            let next = self.s.active_out(r.mesh, x).find(|&h| Some(r.mesh.he_edge(h)) != from);
            let Some(h) = next else { break };
            let e = r.mesh.he_edge(h);
            if r.fixed[e.index()] {
                break;
            }
            chain.push(e);
            from = Some(e);
            x = r.mesh.he_head(h);
            if self.s.deg[x.index()] != 2
                || r.is_sink(x)
                || r.forced_vertex[x.index()]
                || chain.len() > r.mesh.num_edges()
            {
                break;
            }
        }
        if chain.is_empty() {
            return false;
        }
        let before = self.s.counts;
        for &e in &chain {
            self.s.toggle(r, e);
        }
        let after = self.s.counts;
        let worse = after.uncovered > before.uncovered
            || after.groups > before.groups
            || after.forced_vertices > before.forced_vertices
            || after.pairs > before.pairs;
        if worse {
            for &e in &chain {
                self.s.toggle(r, e);
            }
            return false;
        }
        true
    }

    /// Step 7: drops one free edge of every present forbidden configuration, branch, T-junction
    /// or bad through-route vertex.
    pub fn break_local_violations(&mut self) {
        let r = self.r;
        let mut drop: Vec<EdgeId> = Vec::new();
        for c in 0..r.configs.len() {
            if r.configs[c].forbid && self.s.config_present(r, c) {
                let free: Vec<EdgeId> = r.configs[c].edges.iter().copied().filter(|&e| r.free(e)).collect();
                if !free.is_empty() {
                    drop.push(free[self.rng.below(free.len())]);
                }
            }
        }
        for t in 0..r.tconfigs.len() {
            if r.tconfigs[t].forbid && self.s.t_present(r, t) {
                let free: Vec<EdgeId> = r.tconfigs[t].others.iter().copied().filter(|&e| r.free(e)).collect();
                if !free.is_empty() {
                    drop.push(free[self.rng.below(free.len())]);
                }
            }
        }
        for v in r.mesh.vertices() {
            let d = self.s.deg[v.index()];
            if (r.branch_forbid && d >= 3) || (r.route_inner[v.index()] && d > 2) {
                let free: Vec<EdgeId> =
                    self.s.active_out(r.mesh, v).map(|h| r.mesh.he_edge(h)).filter(|&e| r.free(e)).collect();
                if !free.is_empty() {
                    drop.push(free[self.rng.below(free.len())]);
                }
            }
        }
        for e in drop {
            if self.s.active[e.index()] {
                self.s.toggle(r, e);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::Spec;
    use std::path::Path;

    /// A 6×1 strip, the sink at its left end (vertex 0; the bottom row is 0..=6, the top row
    /// 7..=13), dead-ends allowed, coverage one hop.
    fn strip() -> crate::spec::Problem {
        let text = "name = \"strip\"\nboundary = \"candidate\"\n[mesh]\ngrid = { width = 6, height = 1 }\n[sinks]\nvertices = [0]\n[coverage]\nrange = 1\n[features]\ndead_ends = \"allow\"\n";
        Spec::from_toml(text).unwrap().resolve(Path::new(".")).unwrap()
    }

    #[test]
    fn short_arms_cover_from_the_ball_vertex_nearest_the_network() {
        let p = strip();
        let r = Rules::new(&p, None, None, None);
        let far = VertexId(6);
        for (short_arms, arm) in [(false, 6), (true, 5)] {
            let mut b = Builder::new(&r, State::new(&r), Rng::new(0), 0.0, None);
            b.short_arms = short_arms;
            let hops = b.hops_from_network();
            assert!(b.cover_vertex(far, &hops));
            // Vertex 6 is covered either by itself (an arm of six edges along the bottom row) or,
            // with short arms, by its neighbour 5 (five edges), which leaves 6 itself inactive.
            assert_eq!(b.s.deg[6] > 0, !short_arms, "degrees {:?}", b.s.deg);
            assert_eq!(b.s.deg[5], if short_arms { 1 } else { 2 });
            assert!(b.s.covered(&r, far));
            assert_eq!(b.s.active.iter().filter(|&&a| a).count(), arm);
        }
    }
}
