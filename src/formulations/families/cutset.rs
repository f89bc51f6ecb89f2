//! Cutset connectivity (docs/formulation.md §8): contract every sink into a root `r`; for every vertex
//! set `C` with `r ∉ C` and every `v ∈ C`, `Σ_{x∈δ(C)} E_x ≥ V_v`. The rows are exponentially
//! many, so none is written into the model: [`CutsetSeparator`] finds violated ones — by
//! connected components on integral points (exact), and by max-flow/min-cut from each vertex to
//! the root on fractional ones. With the distance flow's direction binaries the fractional rows
//! are directed, `Σ_{(a→b): a∈C, b∉C} E(a→b) ≥ V_v`: every active non-sink vertex has a path of
//! active half-edges to a sink, so a sink-free set holding one has an active half-edge leaving it.
//! Without them (`directed_cutsets`) the rows count the continuous parent arcs `P(a→b)` of the
//! out-arc rows the same way: a shortest-path forest into the sinks gives each active non-sink
//! vertex a path of parent arcs at 1, so `Σ_{(a→b): a∈C, b∉C} P(a→b) ≥ V_v` holds too.
//!
//! Beside them, the **cover cutsets** (this project's strengthening, valid cuts rather than lazy
//! rows): coverage (6) makes some vertex of a sink-free ball `cover(v)` active, and that vertex
//! reaches a sink, so every vertex set `S ⊇ cover(v)` without a sink is crossed:
//! `Σ_{x∈δ(S)} E_x ≥ 1` — the cut rows of a group Steiner tree with the balls as groups. They do
//! not weaken when the ball's activity is spread thinly over its vertices (the cutsets above
//! then ask only `≥ V_u` for the most active `u`), and are separated by max-flow from the
//! contracted ball to the root on fractional points.
//!
//! The max-flow is a small Dinic on the contracted mesh graph, kept here (rather than a general
//! graph crate) because it runs hundreds of times per separation round on the same graph with
//! new capacities and stops as soon as the flow reaches the vertex's activity.

use super::coverage::girth;
use crate::formulations::expr::Value;
use crate::formulations::family::{Ctx, Family};
use crate::mesh::VertexId;
use crate::milp::VarId;
use crate::solvers::{LazyRow, Lock, Separator};
use crate::spec::Allow;
use crate::spec::Problem;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// The contracted graph the cutsets live on: node 0 is the root (every sink), the other nodes
/// are the non-sink vertices with a candidate edge.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CutsetGraph {
    /// Number of nodes (root included).
    pub nodes: usize,
    /// Candidate edges as (node, node, `E_x`), both ends distinct.
    pub edges: Vec<(u32, u32, VarId)>,
    /// `V_v` of each node (`Const(1)` for the root).
    pub activity: Vec<Value>,
    /// The mesh vertex of each node (`u32::MAX` for the root).
    pub vertex: Vec<u32>,
    /// The cover groups: node sets some node of which every valid design makes active — each
    /// sink-free ball `cover(v)` of coverage (6) (inclusion-minimal, deterministic order).
    #[serde(default)]
    pub groups: Vec<CoverGroup>,
    /// The arcs of each edge in `edges`, `(a→b, b→a)`, when the recipe has them: the distance
    /// flow's direction binaries `E(a→b)`, or else the parent arcs `P(a→b)` of the out-arc rows
    /// (`directed_cutsets`). Either way each active non-sink vertex has a directed path of
    /// active arcs to a sink, and the cutsets count only the arcs leaving a set. An arc out of
    /// the root is `None` when the recipe has none (parent arcs leave only non-sinks); no cut
    /// counts it, since the root is never inside.
    #[serde(default)]
    pub arcs: Option<Vec<(Option<VarId>, Option<VarId>)>>,
    /// With dead-ends forbidden, the shortest cycle a design can hold (the cover cutsets are
    /// then lifted: one crossing leaves a cycle inside); `None` when dead-ends are allowed.
    #[serde(default)]
    pub girth: Option<f64>,
}

/// A vertex set some vertex of which every valid design makes active, as nodes of a
/// [`CutsetGraph`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CoverGroup {
    /// What asks for it (it names the group's rows).
    pub origin: GroupOrigin,
    /// Its non-root nodes, ascending.
    pub nodes: Vec<u32>,
}

/// What makes a [`CoverGroup`] hold an active vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum GroupOrigin {
    /// The ball `cover(v)` of coverage (6) of this mesh vertex `v`.
    Ball(u32),
}

impl std::fmt::Display for GroupOrigin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GroupOrigin::Ball(v) => write!(f, "v{v}"),
        }
    }
}

impl CutsetGraph {
    /// The graph of a problem, from its edge variables and vertex activities, and the arcs of
    /// its half-edges (direction binaries or parent arcs) when the recipe has them (see
    /// [`CutsetGraph::arcs`]). An arc may be missing only out of a sink; otherwise the graph
    /// gets no arcs.
    pub fn new(
        p: &Problem,
        edge: &[Option<VarId>],
        vertex: &[Value],
        directions: Option<&[Option<VarId>]>,
    ) -> CutsetGraph {
        let mesh = &p.mesh;
        let mut node = vec![u32::MAX; mesh.num_vertices()];
        let mut g = CutsetGraph {
            nodes: 1,
            edges: Vec::new(),
            activity: vec![Value::Const(1.0)],
            vertex: vec![u32::MAX],
            groups: Vec::new(),
            arcs: None,
            girth: None,
        };
        for v in mesh.vertices() {
            if p.is_sink[v.index()] {
                node[v.index()] = 0;
            } else if mesh.incident_edges(v).any(|e| edge[e.index()].is_some()) {
                node[v.index()] = g.nodes as u32;
                g.nodes += 1;
                g.activity.push(vertex[v.index()]);
                g.vertex.push(v.0);
            }
        }
        let mut arcs = directions.map(|_| Vec::new());
        for e in mesh.edges() {
            let Some(x) = edge[e.index()] else { continue };
            let (a, b) = mesh.edge_vertices(e);
            let (na, nb) = (node[a.index()], node[b.index()]);
            if na == nb {
                continue;
            }
            g.edges.push((na, nb, x));
            if let (Some(d), Some(list)) = (directions, arcs.as_mut()) {
                let [h0, h1] = mesh.edge_half_edges(e);
                let (ab, ba) = if mesh.he_tail(h0) == a { (h0, h1) } else { (h1, h0) };
                let (f, r) = (d[ab.index()], d[ba.index()]);
                if (f.is_some() || na == 0) && (r.is_some() || nb == 0) {
                    list.push((f, r));
                } else {
                    arcs = None;
                }
            }
        }
        g.arcs = arcs;
        g
    }

    /// Adds the cover groups of coverage (6): for every non-obstacle vertex `v` whose ball
    /// `cover(v)` holds no sink and no vertex active as a constant (`vertex`, as coverage
    /// reads it), the ball's nodes. Only inclusion-minimal groups are kept (a superset's
    /// cutsets are among its subset's).
    pub fn with_cover_groups(self, p: &Problem, vertex: &[Value], girth: Option<f64>) -> CutsetGraph {
        let balls = p
            .mesh
            .vertices()
            .filter(|v| !p.is_obstacle_vertex[v.index()])
            .map(|v| (GroupOrigin::Ball(v.0), crate::rules::cover_set(p, v)));
        self.with_groups(p, vertex, girth, balls)
    }

    /// Adds cover groups given as mesh vertex sets, each of which some valid design's active
    /// vertex lies in. A set holding a sink or a vertex active as a constant (`vertex`) gives
    /// no cut and is left out, as is every set that contains another (a superset's cutsets
    /// are among its subset's). `girth` as for [`CutsetGraph::with_cover_groups`].
    pub fn with_groups(
        mut self,
        p: &Problem,
        vertex: &[Value],
        girth: Option<f64>,
        sets: impl IntoIterator<Item = (GroupOrigin, Vec<VertexId>)>,
    ) -> CutsetGraph {
        self.girth = girth;
        let mut node = vec![u32::MAX; p.mesh.num_vertices()];
        for (k, &v) in self.vertex.iter().enumerate().skip(1) {
            node[v as usize] = k as u32;
        }
        let mut groups: Vec<CoverGroup> = Vec::new();
        for (origin, set) in sets {
            if set.iter().any(|u| p.is_sink[u.index()] || matches!(vertex[u.index()], Value::Const(c) if c > 0.0)) {
                continue;
            }
            let mut nodes: Vec<u32> = set.iter().map(|u| node[u.index()]).filter(|&k| k != u32::MAX).collect();
            nodes.sort_unstable();
            nodes.dedup();
            if !nodes.is_empty() {
                groups.push(CoverGroup { origin, nodes });
            }
        }
        let subset = |a: &[u32], b: &[u32]| a.len() <= b.len() && a.iter().all(|k| b.binary_search(k).is_ok());
        let keep: Vec<bool> = (0..groups.len())
            .map(|i| {
                !(0..groups.len()).any(|j| {
                    j != i
                        && subset(&groups[j].nodes, &groups[i].nodes)
                        && (groups[j].nodes.len() < groups[i].nodes.len() || j < i)
                })
            })
            .collect();
        self.groups = groups.into_iter().zip(keep).filter(|(_, k)| *k).map(|(g, _)| g).collect();
        self
    }
}

/// The cutsets as a family: no variable and no row in the model, only the graph their
/// separator works on ([`CutsetSeparator`]), with the cover groups of coverage (6). The
/// cutsets count the distance flow's direction binaries where the recipe has them, else the
/// parent arcs of the out-arc rows with the `directed_cutsets` switch.
pub struct Cutsets {
    graph: Option<CutsetGraph>,
}

impl Cutsets {
    /// When the plan separates cutsets lazily.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        c.plan.lazy_cutsets().then(|| Box::new(Cutsets { graph: None }) as Box<dyn Family>)
    }

    /// The graph the separator works on, once emitted.
    pub fn graph(&self) -> Option<&CutsetGraph> {
        self.graph.as_ref()
    }
}

impl Family for Cutsets {
    fn label(&self) -> String {
        "cutsets (§8, lazy)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let directions = if c.plan.distance_flow {
            Some(c.vars.half_edge.as_slice())
        } else {
            c.parent_cutsets().then_some(c.vars.parent.as_slice())
        };
        let g = CutsetGraph::new(p, &c.vars.edge, &c.vars.vertex, directions);
        let girth = (p.dead_ends == Allow::Forbid).then(|| girth(p));
        // Coverage (6) is in the model only without rooms; its balls give the cover cutsets.
        self.graph = Some(g.with_cover_groups(p, &c.vars.vertex, girth));
    }
}

/// Residual graph for Dinic's algorithm on an undirected graph: each edge is a pair of arcs,
/// each the other's reverse, both with the edge's capacity. Node `nodes` is an extra source
/// joined to every other non-root node, by arcs of capacity 0 unless a cover group is being
/// contracted into it.
struct FlowGraph {
    head: Vec<u32>,
    cap: Vec<f64>,
    adj_start: Vec<usize>,
    adj: Vec<u32>,
    level: Vec<i32>,
    iter: Vec<usize>,
    /// Number of graph edges (the source's arcs come after theirs).
    edges: usize,
}

impl FlowGraph {
    fn new(g: &CutsetGraph) -> FlowGraph {
        let n = g.nodes;
        let src = n as u32;
        let links: Vec<(u32, u32)> =
            g.edges.iter().map(|&(a, b, _)| (a, b)).chain((1..n as u32).map(|v| (src, v))).collect();
        let mut deg = vec![0usize; n + 2];
        for &(a, b) in &links {
            deg[a as usize] += 1;
            deg[b as usize] += 1;
        }
        let mut adj_start = vec![0usize; n + 2];
        for i in 0..=n {
            adj_start[i + 1] = adj_start[i] + deg[i];
        }
        let mut fill = adj_start.clone();
        let mut head = Vec::with_capacity(2 * links.len());
        let mut adj = vec![0u32; 2 * links.len()];
        for &(a, b) in &links {
            let k = head.len() as u32;
            head.push(b);
            head.push(a);
            adj[fill[a as usize]] = k;
            fill[a as usize] += 1;
            adj[fill[b as usize]] = k + 1;
            fill[b as usize] += 1;
        }
        FlowGraph {
            cap: vec![0.0; head.len()],
            head,
            adj_start,
            adj,
            level: vec![0; n + 1],
            iter: vec![0; n + 1],
            edges: g.edges.len(),
        }
    }

    /// Sets the edges' capacities; the extra source is cut off.
    fn set_capacities(&mut self, caps: &[f64]) {
        for (k, &c) in caps.iter().enumerate() {
            self.cap[2 * k] = c;
            self.cap[2 * k + 1] = c;
        }
        self.cap[2 * self.edges..].iter_mut().for_each(|c| *c = 0.0);
    }

    /// Sets the capacities of directed arcs: `forward[k]` from the first end of edge `k` to
    /// the second, `backward[k]` the other way (an antiparallel pair shares its residual arcs);
    /// the extra source is cut off.
    fn set_directed_capacities(&mut self, forward: &[f64], backward: &[f64]) {
        for (k, (&f, &b)) in forward.iter().zip(backward).enumerate() {
            self.cap[2 * k] = f;
            self.cap[2 * k + 1] = b;
        }
        self.cap[2 * self.edges..].iter_mut().for_each(|c| *c = 0.0);
    }

    /// Joins the extra source to `nodes` by arcs no cut will cross (contracts them into it).
    fn contract_into_source(&mut self, nodes: &[u32]) {
        for &v in nodes {
            let k = 2 * (self.edges + v as usize - 1);
            self.cap[k] = f64::INFINITY;
            self.cap[k + 1] = 0.0;
        }
    }

    fn bfs(&mut self, s: usize, t: usize) -> bool {
        self.level.iter_mut().for_each(|l| *l = -1);
        self.level[s] = 0;
        let mut q = VecDeque::from([s]);
        while let Some(v) = q.pop_front() {
            for &a in &self.adj[self.adj_start[v]..self.adj_start[v + 1]] {
                let w = self.head[a as usize] as usize;
                if self.cap[a as usize] > EPS && self.level[w] < 0 {
                    self.level[w] = self.level[v] + 1;
                    q.push_back(w);
                }
            }
        }
        self.level[t] >= 0
    }

    fn dfs(&mut self, v: usize, t: usize, f: f64) -> f64 {
        if v == t {
            return f;
        }
        while self.iter[v] < self.adj_start[v + 1] - self.adj_start[v] {
            let a = self.adj[self.adj_start[v] + self.iter[v]] as usize;
            let w = self.head[a] as usize;
            if self.cap[a] > EPS && self.level[w] == self.level[v] + 1 {
                let d = self.dfs(w, t, f.min(self.cap[a]));
                if d > EPS {
                    self.cap[a] -= d;
                    self.cap[a ^ 1] += d;
                    return d;
                }
            }
            self.iter[v] += 1;
        }
        0.0
    }

    /// Max-flow from `s` to `t`, stopping once it reaches `enough`.
    fn max_flow(&mut self, s: usize, t: usize, enough: f64) -> f64 {
        let mut flow = 0.0;
        while enough - flow > EPS && self.bfs(s, t) {
            self.iter.iter_mut().for_each(|i| *i = 0);
            let before = flow;
            while enough - flow > EPS {
                let f = self.dfs(s, t, enough - flow);
                if f <= EPS {
                    break;
                }
                flow += f;
            }
            if flow - before <= EPS {
                break; // only paths of negligible capacity are left
            }
        }
        flow
    }

    /// The nodes reachable from `s` in the residual graph (the source side of a min cut).
    fn source_side(&self, s: usize) -> Vec<bool> {
        let mut seen = vec![false; self.level.len()];
        seen[s] = true;
        let mut q = VecDeque::from([s]);
        while let Some(v) = q.pop_front() {
            for &a in &self.adj[self.adj_start[v]..self.adj_start[v + 1]] {
                let w = self.head[a as usize] as usize;
                if self.cap[a as usize] > EPS && !seen[w] {
                    seen[w] = true;
                    q.push_back(w);
                }
            }
        }
        seen
    }
}

const EPS: f64 = 1e-9;

/// How much a fractional cut must be violated to be returned.
const MIN_VIOLATION: f64 = 1e-3;

/// The kinds of cover cutset.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum CoverRow {
    /// `Σ_{x∈δ(S)} E_x ≥ 1`.
    Plain,
    /// `Σ_{(a→b): a∈S, b∉S} E(a→b) ≥ 1`.
    Directed,
    /// `Σ_{x∈δ(S)} E_x + (1/g)·Σ_{x∈E(S)} E_x ≥ 2`.
    Lifted,
}

/// Separates the cutset rows of a [`CutsetGraph`]. Rows are named `cut<n>_v<vertex>`.
pub struct CutsetSeparator<'a> {
    graph: CutsetGraph,
    flow: FlowGraph,
    /// Rows returned so far (for unique names).
    count: usize,
    /// Cap on the rows returned per fractional call.
    pub max_fractional_rows: usize,
    /// Cap on the cover cutsets returned per fractional call (beside the rows above).
    pub max_group_rows: usize,
    repair: Option<Repair<'a>>,
}

/// A function that turns a disconnected integral point into a feasible one, if it can.
pub type Repair<'a> = Box<dyn FnMut(&[f64]) -> Option<Vec<f64>> + 'a>;

impl<'a> CutsetSeparator<'a> {
    /// A separator over `graph`.
    pub fn new(graph: CutsetGraph) -> CutsetSeparator<'a> {
        let flow = FlowGraph::new(&graph);
        CutsetSeparator { graph, flow, count: 0, max_fractional_rows: 50, max_group_rows: 100, repair: None }
    }

    /// Sets the function that turns a disconnected integral point into a feasible one (used by
    /// the solve–cut–resolve loop for its next start).
    pub fn with_repair(mut self, f: Repair<'a>) -> Self {
        self.repair = Some(f);
        self
    }

    /// The graph.
    pub fn graph(&self) -> &CutsetGraph {
        &self.graph
    }

    /// The values of the arcs at `x` as capacities (forward, backward), when the graph has
    /// them (a missing arc out of the root: 0).
    fn directed_capacities(&self, x: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
        let at = |a: Option<VarId>| a.map_or(0.0, |a| x[a.index()].max(0.0));
        self.graph.arcs.as_ref().map(|arcs| arcs.iter().map(|&(f, b)| (at(f), at(b))).unzip())
    }

    /// The variable of edge `k` in a cut it crosses, its first end inside when `first_inside`:
    /// with `directed` and arcs, the arc leaving the inside; else `E_x` (also for an arc out of
    /// the root the recipe lacks, which no cut has inside).
    fn crossing_var(&self, k: usize, first_inside: bool, directed: bool) -> VarId {
        let arc = match (directed, self.graph.arcs.as_ref()) {
            (true, Some(arcs)) if first_inside => arcs[k].0,
            (true, Some(arcs)) => arcs[k].1,
            _ => None,
        };
        arc.unwrap_or(self.graph.edges[k].2)
    }

    fn activity(&self, node: usize, x: &[f64]) -> f64 {
        self.graph.activity[node].at(x)
    }

    /// The row `Σ_{x∈δ(C)} E_x − V_v ≥ 0` for the node set `inside` and node `v ∈ C`; with
    /// `directed` (the graph has direction binaries), `Σ_{(a→b): a∈C, b∉C} E(a→b) − V_v ≥ 0`,
    /// which implies it.
    fn row(&mut self, inside: &[bool], v: usize, directed: bool) -> LazyRow {
        let mut terms: Vec<(VarId, f64)> = Vec::new();
        for (k, &(a, b, _)) in self.graph.edges.iter().enumerate() {
            let ia = inside[a as usize];
            if ia != inside[b as usize] {
                terms.push((self.crossing_var(k, ia, directed), 1.0));
            }
        }
        let mut lhs = 0.0;
        match self.graph.activity[v] {
            Value::Var(y) => terms.push((y, -1.0)),
            Value::Const(c) => lhs = c,
        }
        self.count += 1;
        LazyRow { name: format!("cut{}_v{}", self.count, self.graph.vertex[v]), lhs, rhs: f64::INFINITY, terms }
    }

    /// The cover cutsets most violated by `x` (edge capacities `caps`): for each group a min
    /// cut `S` between the group, contracted, and the root, giving `Σ_{x∈δ(S)} E_x ≥ 1` — with
    /// direction binaries `Σ_{(a→b): a∈S, b∉S} E(a→b) ≥ 1`, which implies it — and, with a
    /// girth `g` (dead-ends forbidden), `Σ_{x∈δ(S)} E_x + (1/g)·Σ_{x∈E(S)} E_x ≥ 2`; at most
    /// [`CutsetSeparator::max_group_rows`] rows, the most violated first.
    fn separate_groups(&mut self, x: &[f64], caps: &[f64]) -> Vec<LazyRow> {
        let n = self.graph.nodes;
        let directed = self.directed_capacities(x);
        let mut found: Vec<(f64, GroupOrigin, CoverRow, Vec<bool>)> = Vec::new();
        let push = |found: &mut Vec<(f64, GroupOrigin, CoverRow, Vec<bool>)>,
                    violation: f64,
                    v: GroupOrigin,
                    kind: CoverRow,
                    inside: Vec<bool>| {
            if !found.iter().any(|(_, _, k, c)| *k == kind && *c == inside) {
                found.push((violation, v, kind, inside));
            }
        };
        for gi in 0..self.graph.groups.len() {
            let v = self.graph.groups[gi].origin;
            let plain = match &directed {
                Some((fw, bw)) => {
                    self.flow.set_directed_capacities(fw, bw);
                    CoverRow::Directed
                }
                None => {
                    self.flow.set_capacities(caps);
                    CoverRow::Plain
                }
            };
            self.flow.contract_into_source(&self.graph.groups[gi].nodes);
            let f = self.flow.max_flow(n, 0, 1.0);
            if f < 1.0 - MIN_VIOLATION {
                let mut inside = self.flow.source_side(n);
                inside.truncate(n);
                push(&mut found, 1.0 - f, v, plain, inside);
            }
            let Some(g) = self.graph.girth else { continue };
            self.flow.set_capacities(caps);
            self.flow.contract_into_source(&self.graph.groups[gi].nodes);
            let f = self.flow.max_flow(n, 0, 2.0);
            if f >= 2.0 - MIN_VIOLATION {
                continue;
            }
            let mut inside = self.flow.source_side(n);
            inside.truncate(n);
            let within: f64 = self
                .graph
                .edges
                .iter()
                .zip(caps)
                .filter(|(&(a, b, _), _)| inside[a as usize] && inside[b as usize])
                .map(|(_, &c)| c)
                .sum();
            let lhs = f + within / g;
            if lhs < 2.0 - MIN_VIOLATION {
                push(&mut found, 2.0 - lhs, v, CoverRow::Lifted, inside);
            }
        }
        found.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        found.truncate(self.max_group_rows);
        found.into_iter().map(|(_, v, kind, inside)| self.cover_row(v, kind, &inside)).collect()
    }

    /// The cover cutset of kind `kind` for the node set `inside`, asked for by group `v`.
    fn cover_row(&mut self, v: GroupOrigin, kind: CoverRow, inside: &[bool]) -> LazyRow {
        let g = self.graph.girth.unwrap_or(f64::INFINITY);
        let mut terms: Vec<(VarId, f64)> = Vec::new();
        for (k, &(a, b, e)) in self.graph.edges.iter().enumerate() {
            let (ia, ib) = (inside[a as usize], inside[b as usize]);
            match kind {
                CoverRow::Directed if ia != ib => terms.push((self.crossing_var(k, ia, true), 1.0)),
                CoverRow::Plain | CoverRow::Lifted if ia != ib => terms.push((e, 1.0)),
                CoverRow::Lifted if ia && ib => terms.push((e, 1.0 / g)),
                _ => {}
            }
        }
        self.count += 1;
        let (prefix, lhs) = match kind {
            CoverRow::Plain => ("gcut", 1.0),
            CoverRow::Directed => ("gcutd", 1.0),
            CoverRow::Lifted => ("gcut2_", 2.0),
        };
        LazyRow { name: format!("{prefix}{}_{v}", self.count), lhs, rhs: f64::INFINITY, terms }
    }

    /// Components of the edges with value above ½ that do not reach the root, as node masks with
    /// the node of largest activity in each.
    fn islands(&self, x: &[f64]) -> Vec<(Vec<bool>, usize)> {
        let n = self.graph.nodes;
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
        for &(a, b, e) in &self.graph.edges {
            if x[e.index()] > 0.5 {
                adj[a as usize].push(b);
                adj[b as usize].push(a);
            }
        }
        let mut comp = vec![usize::MAX; n];
        let mut next = 0;
        for s in 0..n {
            if comp[s] != usize::MAX {
                continue;
            }
            let mut q = VecDeque::from([s]);
            comp[s] = next;
            while let Some(v) = q.pop_front() {
                for &w in &adj[v] {
                    if comp[w as usize] == usize::MAX {
                        comp[w as usize] = next;
                        q.push_back(w as usize);
                    }
                }
            }
            next += 1;
        }
        let mut out = Vec::new();
        for c in 0..next {
            if c == comp[0] {
                continue;
            }
            let members: Vec<usize> = (0..n).filter(|&v| comp[v] == c).collect();
            let Some(&best) =
                members.iter().max_by(|&&a, &&b| self.activity(a, x).total_cmp(&self.activity(b, x)).then(b.cmp(&a)))
            else {
                continue;
            };
            if self.activity(best, x) > 0.5 || members.iter().any(|&v| !adj[v].is_empty()) {
                let mut inside = vec![false; n];
                for &v in &members {
                    inside[v] = true;
                }
                out.push((inside, best));
            }
        }
        out
    }
}

impl Separator for CutsetSeparator<'_> {
    fn name(&self) -> &str {
        "cutset"
    }

    fn separate_integral(&mut self, x: &[f64]) -> Vec<LazyRow> {
        let islands = self.islands(x);
        islands.into_iter().map(|(inside, v)| self.row(&inside, v, false)).collect()
    }

    fn separate_fractional(&mut self, x: &[f64]) -> Vec<LazyRow> {
        let caps: Vec<f64> = self.graph.edges.iter().map(|&(_, _, e)| x[e.index()].max(0.0)).collect();
        let directed = self.directed_capacities(x);
        let mut order: Vec<usize> = (1..self.graph.nodes).filter(|&v| self.activity(v, x) > MIN_VIOLATION).collect();
        order.sort_by(|&a, &b| self.activity(b, x).total_cmp(&self.activity(a, x)).then(a.cmp(&b)));
        let mut rows = Vec::new();
        let mut seen_cuts: Vec<Vec<bool>> = Vec::new();
        for v in order {
            if rows.len() >= self.max_fractional_rows {
                break;
            }
            let y = self.activity(v, x);
            match &directed {
                Some((fw, bw)) => self.flow.set_directed_capacities(fw, bw),
                None => self.flow.set_capacities(&caps),
            }
            let f = self.flow.max_flow(v, 0, y);
            if f >= y - MIN_VIOLATION {
                continue;
            }
            let inside = self.flow.source_side(v);
            if seen_cuts.contains(&inside) {
                continue;
            }
            // The most violated row of this cut is the one for its most active node.
            let best = (0..self.graph.nodes)
                .filter(|&u| inside[u])
                .max_by(|&a, &b| self.activity(a, x).total_cmp(&self.activity(b, x)).then(b.cmp(&a)))
                .unwrap_or(v);
            rows.push(self.row(&inside, best, directed.is_some()));
            seen_cuts.push(inside);
        }
        rows.extend(self.separate_groups(x, &caps));
        rows
    }

    fn repair(&mut self, x: &[f64]) -> Option<Vec<f64>> {
        self.repair.as_mut().and_then(|f| f(x))
    }

    fn locks(&self) -> Vec<(VarId, Lock)> {
        let mut out: Vec<(VarId, Lock)> = self.graph.edges.iter().map(|&(_, _, e)| (e, Lock::Down)).collect();
        out.extend(self.graph.activity.iter().filter_map(|a| match a {
            Value::Var(y) => Some((*y, Lock::Up)),
            Value::Const(_) => None,
        }));
        if let Some(arcs) = &self.graph.arcs {
            out.extend(arcs.iter().flat_map(|&(f, b)| [f, b]).flatten().map(|a| (a, Lock::Down)));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path r – 1 – 2 – 3 (node 0 is the root), edges E0 = r–1, E1 = 1–2, E2 = 2–3, with
    /// activities V1, V2, V3 as variables 3, 4, 5.
    fn path() -> CutsetSeparator<'static> {
        let g = CutsetGraph {
            nodes: 4,
            edges: vec![(0, 1, VarId(0)), (1, 2, VarId(1)), (2, 3, VarId(2))],
            activity: vec![Value::Const(1.0), Value::Var(VarId(3)), Value::Var(VarId(4)), Value::Var(VarId(5))],
            vertex: vec![u32::MAX, 10, 11, 12],
            groups: Vec::new(),
            arcs: None,
            girth: None,
        };
        CutsetSeparator::new(g)
    }

    #[test]
    fn integral_point_with_an_island() {
        let mut s = path();
        // r–1 inactive, 1–2 and 2–3 active: {1, 2, 3} is an island.
        let x = [0.0, 1.0, 1.0, 1.0, 1.0, 1.0];
        let rows = s.separate_integral(&x);
        assert_eq!(rows.len(), 1);
        let r = &rows[0];
        assert_eq!(r.lhs, 0.0);
        let mut terms = r.terms.clone();
        terms.sort_by_key(|t| t.0);
        // δ({1,2,3}) = {E0}; V of the most active node (ties: the first, node 1).
        assert_eq!(terms, vec![(VarId(0), 1.0), (VarId(3), -1.0)]);
        assert!(r.violation(&x) > 0.99);
        // Connected: nothing.
        assert!(s.separate_integral(&[1.0, 1.0, 1.0, 1.0, 1.0, 1.0]).is_empty());
        // Nothing active beyond the root: nothing.
        assert!(s.separate_integral(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]).is_empty());
    }

    #[test]
    fn fractional_min_cut_known_by_hand() {
        let mut s = path();
        // Capacities 0.3 (r–1), 0.9, 0.9; V3 = 0.8: max-flow 3 → r is 0.3, the min cut is
        // {1, 2, 3} | {r} with value 0.3, violated by 0.5 for V3 (the most active node).
        let x = [0.3, 0.9, 0.9, 0.2, 0.4, 0.8];
        let rows = s.separate_fractional(&x);
        assert_eq!(rows.len(), 1, "{rows:?}");
        let mut terms = rows[0].terms.clone();
        terms.sort_by_key(|t| t.0);
        assert_eq!(terms, vec![(VarId(0), 1.0), (VarId(5), -1.0)]);
        assert!((rows[0].violation(&x) - 0.5).abs() < 1e-9);
        // A point where every cut holds gives nothing.
        assert!(s.separate_fractional(&[0.9, 0.9, 0.9, 0.5, 0.5, 0.5]).is_empty());
    }

    #[test]
    fn cover_cutset_contracts_the_ball() {
        let mut s = path();
        s.graph.groups = vec![CoverGroup { origin: GroupOrigin::Ball(12), nodes: vec![2, 3] }];
        // r–1 at 0.3, the rest 0.9, activities 0.2 each: every cutset `≥ V_v` holds (the flow
        // from any one node is 0.3), but the ball {2, 3} sends only 0.3 to the root: the
        // cover cutset over δ({1, 2, 3}) = {E0} is violated by 0.7.
        let x = [0.3, 0.9, 0.9, 0.2, 0.2, 0.2];
        let rows = s.separate_fractional(&x);
        assert_eq!(rows.len(), 1, "{rows:?}");
        assert_eq!(rows[0].terms, vec![(VarId(0), 1.0)]);
        assert_eq!((rows[0].lhs, rows[0].name.as_str()), (1.0, "gcut1_v12"));
        assert!((rows[0].violation(&x) - 0.7).abs() < 1e-9);
        // With r–1 and 1–2 at 1 the ball sends a whole unit: nothing.
        assert!(s.separate_fractional(&[1.0, 1.0, 0.9, 0.2, 0.2, 0.2]).is_empty());
    }

    #[test]
    fn lifted_cover_cutset_counts_the_cycle_inside() {
        let mut s = path();
        s.graph.groups = vec![CoverGroup { origin: GroupOrigin::Ball(12), nodes: vec![2, 3] }];
        s.graph.girth = Some(4.0);
        // The ball {2, 3} sends 1 to the root (through 1–2): the plain cover cutset holds, but
        // one crossing needs a cycle inside, and the edges inside {2, 3} sum to 0.5:
        // E1 + ¼·E2 ≥ 2 is violated by 2 − (1 + 0.125).
        let x = [1.0, 1.0, 0.5, 0.2, 0.2, 0.2];
        let rows = s.separate_fractional(&x);
        assert_eq!(rows.len(), 1, "{rows:?}");
        assert_eq!(rows[0].terms, vec![(VarId(1), 1.0), (VarId(2), 0.25)]);
        assert_eq!((rows[0].lhs, rows[0].name.as_str()), (2.0, "gcut2_1_v12"));
        assert!((rows[0].violation(&x) - 0.875).abs() < 1e-9);
    }

    /// Separating `x` gives exactly one row, with these terms (in variable order) and violation.
    fn assert_one_directed_row(s: &mut CutsetSeparator<'_>, x: &[f64], terms: &[(VarId, f64)], violation: f64) {
        let rows = s.separate_fractional(x);
        assert_eq!(rows.len(), 1, "{rows:?}");
        let mut got = rows[0].terms.clone();
        got.sort_by_key(|t| t.0);
        assert_eq!(got, terms);
        assert!((rows[0].violation(x) - violation).abs() < 1e-9);
    }

    #[test]
    fn directed_cutset_counts_only_the_arcs_leaving() {
        let mut s = path();
        // Direction binaries: edge k's arc from its first end to its second is variable 6 + 2k,
        // the other way 7 + 2k (r→1 is 6, 1→r is 7, 1→2 is 8, 2→1 is 9, 2→3 is 10, 3→2 is 11).
        s.graph.arcs = Some(vec![
            (Some(VarId(6)), Some(VarId(7))),
            (Some(VarId(8)), Some(VarId(9))),
            (Some(VarId(10)), Some(VarId(11))),
        ]);
        // Every edge at 0.8, but r–1 points away from the root (r→1 at 0.8, 1→r at 0): the
        // undirected cutsets hold for V3 = 0.7, the directed one over the arcs leaving
        // {1, 2, 3} (just 1→r) is violated by 0.7.
        let mut x = vec![0.8, 0.8, 0.8, 0.7, 0.7, 0.7, 0.8, 0.0, 0.4, 0.4, 0.4, 0.4];
        assert_one_directed_row(&mut s, &x, &[(VarId(3), -1.0), (VarId(7), 1.0)], 0.7);
        // With every edge pointed at the root, nothing.
        x[6..].copy_from_slice(&[0.0, 0.8, 0.0, 0.8, 0.0, 0.8]);
        assert!(s.separate_fractional(&x).is_empty());
    }

    #[test]
    fn parent_arc_cutsets_lack_the_arcs_out_of_the_root() {
        let mut s = path();
        // Parent arcs (no arc leaves the root): r–1 has only P(1→r) = 6; 1→2 is 7, 2→1 is 8,
        // 2→3 is 9, 3→2 is 10.
        s.graph.arcs =
            Some(vec![(None, Some(VarId(6))), (Some(VarId(7)), Some(VarId(8))), (Some(VarId(9)), Some(VarId(10)))]);
        // Every edge at 0.8, V2 = 0 and V3 = 0.7, but the parent arc on 1–2 points away from
        // the root: the set {2, 3} has no arc leaving it (the undirected cutsets hold), and
        // its row counts 2→1 alone.
        let mut x = vec![0.8, 0.8, 0.8, 0.7, 0.0, 0.7, 0.8, 0.8, 0.0, 0.0, 0.8];
        assert_one_directed_row(&mut s, &x, &[(VarId(5), -1.0), (VarId(8), 1.0)], 0.7);
        // The missing arc is never locked or counted; pointed at the root, nothing is violated.
        assert_eq!(s.locks().iter().filter(|(v, _)| v.index() >= 6).count(), 5);
        x[6..].copy_from_slice(&[0.8, 0.0, 0.8, 0.0, 0.8]);
        assert!(s.separate_fractional(&x).is_empty());
    }

    #[test]
    fn fractional_cut_in_the_middle() {
        let mut s = path();
        // r–1 full, 1–2 at 0.2, V3 = 0.7: the cut {2, 3} (value 0.2) is the min cut for node 3.
        let x = [1.0, 0.2, 1.0, 0.7, 0.7, 0.7];
        let rows = s.separate_fractional(&x);
        assert!(!rows.is_empty());
        let mut terms = rows[0].terms.clone();
        terms.sort_by_key(|t| t.0);
        assert_eq!(terms[0], (VarId(1), 1.0));
        assert!((rows[0].violation(&x) - 0.5).abs() < 1e-9);
    }
}
