//! A design as a point of a formulation (a MIP start): every variable of the recipe set from
//! the active edges and rooms alone.
//!
//! Directions point every active edge toward its end with the smaller paper label
//! (`0` at a sink, else `Δ + h`, see [`crate::design::Objective`]); labels take those values;
//! successors and the distance flow follow each vertex's best next step; the travel and
//! connectivity flows and the parent arcs follow a shortest-path tree. The point is meant to be checked by the MILP
//! checker before it is handed to a solver: a design that breaks the spec gives a point that
//! breaks rows, and the checker says which.

use super::build::Formulation;
use super::expr::Value;
use crate::design::{label_distances, travel_distances, Network};
use crate::mesh::{HalfEdgeId, VertexId};
use crate::spec::{PathForm, Problem};

/// Why a design could not be turned into a point.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EncodeError {
    /// The network's edge list does not fit the mesh.
    #[error("the design has {got} edge flags for a mesh of {want} edges")]
    WrongSize {
        /// Flags given.
        got: usize,
        /// Edges in the mesh.
        want: usize,
    },
    /// An active vertex cannot reach a sink, so no direction or label exists for it.
    #[error("active vertex v{0} cannot reach a sink")]
    Unreachable(u32),
    /// A chosen room index is not a placement of the model.
    #[error("room {0} is not one of the model's placements")]
    UnknownRoom(usize),
}

impl Formulation {
    /// The point of this formulation that stands for `net`.
    pub fn encode(&self, p: &Problem, net: &Network) -> Result<Vec<f64>, EncodeError> {
        let mesh = &p.mesh;
        if net.active.len() != mesh.num_edges() {
            return Err(EncodeError::WrongSize { got: net.active.len(), want: mesh.num_edges() });
        }
        let mut x: Vec<f64> = self.model.vars().iter().map(|v| v.lb.max(0.0).min(v.ub)).collect();
        let set = |x: &mut Vec<f64>, v: Option<crate::milp::VarId>, val: f64| {
            if let Some(v) = v {
                x[v.index()] = val;
            }
        };
        let on = |e: crate::mesh::EdgeId| net.active[e.index()];
        for e in mesh.edges() {
            set(&mut x, self.vars.edge[e.index()], if on(e) { 1.0 } else { 0.0 });
        }
        let mut degree = vec![0usize; mesh.num_vertices()];
        for e in net.active_edges() {
            let (a, b) = mesh.edge_vertices(e);
            degree[a.index()] += 1;
            degree[b.index()] += 1;
        }
        for v in mesh.vertices() {
            if let Value::Var(y) = self.vars.vertex[v.index()] {
                x[y.index()] = if degree[v.index()] > 0 { 1.0 } else { 0.0 };
            }
        }

        // Labels and directions.
        let h = label_distances(p, net);
        let label_into = |v: VertexId, len: f64| if p.is_sink[v.index()] { 0.0 } else { len + h[v.index()] };
        // The best next step of every non-sink vertex: the active half-edge out of it with the
        // smallest label (ties: the first in the mesh's order).
        let mut next: Vec<Option<HalfEdgeId>> = vec![None; mesh.num_vertices()];
        for v in mesh.vertices() {
            if p.is_sink[v.index()] || degree[v.index()] == 0 {
                continue;
            }
            let mut best: Option<(f64, HalfEdgeId)> = None;
            for &g in mesh.outgoing(v) {
                if on(mesh.he_edge(g)) {
                    let d = label_into(mesh.he_head(g), mesh.he_length(g));
                    if d.is_finite() && best.is_none_or(|(b, _)| d < b) {
                        best = Some((d, g));
                    }
                }
            }
            match best {
                Some((_, g)) => next[v.index()] = Some(g),
                None if self.needs_directions() => return Err(EncodeError::Unreachable(v.0)),
                None => {}
            }
        }
        if self.needs_directions() {
            for e in mesh.edges().filter(|&e| on(e) && self.vars.edge[e.index()].is_some()) {
                let [h0, h1] = mesh.edge_half_edges(e);
                let len = mesh.edge_length(e);
                let (d0, d1) = (label_into(mesh.he_head(h0), len), label_into(mesh.he_head(h1), len));
                if !d0.is_finite() && !d1.is_finite() {
                    return Err(EncodeError::Unreachable(mesh.he_head(h0).0));
                }
                let chosen = if d0 <= d1 { h0 } else { h1 };
                set(&mut x, self.vars.half_edge[chosen.index()], 1.0);
                set(&mut x, self.vars.label[chosen.index()], label_into(mesh.he_head(chosen), len));
            }
            for s in &self.vars.successors {
                let j = mesh.he_head(s.from);
                let from_on = self.vars.half_edge[s.from.index()].is_some_and(|v| x[v.index()] > 0.5);
                x[s.var.index()] = if from_on && next[j.index()] == Some(s.to) { 1.0 } else { 0.0 };
            }
        }
        for nu in &self.vars.dead_end_indicators {
            let e = mesh.he_edge(nu.half_edge);
            let j = mesh.he_head(nu.half_edge);
            let others = mesh.incident_edges(j).filter(|&f| f != e && on(f)).count();
            x[nu.var.index()] = if others > 0 { 1.0 } else { 0.0 };
        }

        // Distance flow: each active half-edge into a non-sink supplies a unit at its head, which
        // follows the best next steps to a sink.
        if self.vars.distance_flow.iter().any(Option::is_some) {
            let mut supply = vec![0.0f64; mesh.num_vertices()];
            for e in mesh.edges() {
                for g in mesh.edge_half_edges(e) {
                    if self.vars.half_edge[g.index()].is_some_and(|v| x[v.index()] > 0.5)
                        && !p.is_sink[mesh.he_head(g).index()]
                    {
                        supply[mesh.he_head(g).index()] += 1.0;
                    }
                }
            }
            route(p, &mut x, &self.vars.distance_flow, &mut supply, &next, &h);
        }
        // Travel and connectivity flows: every active non-sink vertex supplies a unit along a
        // shortest-path tree (true distances).
        let parents = self.vars.parent.iter().any(Option::is_some);
        if parents
            || self.vars.travel_flow.iter().any(Option::is_some)
            || self.vars.connect_flow.iter().any(Option::is_some)
        {
            let d = travel_distances(mesh, net, &p.is_sink);
            let mut tree: Vec<Option<HalfEdgeId>> = vec![None; mesh.num_vertices()];
            for v in mesh.vertices() {
                if p.is_sink[v.index()] || degree[v.index()] == 0 {
                    continue;
                }
                if !d[v.index()].is_finite() {
                    return Err(EncodeError::Unreachable(v.0));
                }
                tree[v.index()] = mesh.outgoing(v).iter().copied().filter(|&g| on(mesh.he_edge(g))).min_by(|&a, &b| {
                    (mesh.he_length(a) + d[mesh.he_head(a).index()])
                        .total_cmp(&(mesh.he_length(b) + d[mesh.he_head(b).index()]))
                });
            }
            // Parent arcs: each active non-sink vertex owns the edge to its parent in the tree.
            for g in tree.iter().flatten() {
                set(&mut x, self.vars.parent[g.index()], 1.0);
            }
            for flow in [&self.vars.travel_flow, &self.vars.connect_flow] {
                if flow.iter().any(Option::is_some) {
                    let mut supply: Vec<f64> = mesh
                        .vertices()
                        .map(|v| if !p.is_sink[v.index()] && degree[v.index()] > 0 { 1.0 } else { 0.0 })
                        .collect();
                    route(p, &mut x, flow, &mut supply, &tree, &d);
                }
            }
        }

        // Point-to-point paths, local configurations, T-junctions, rooms.
        if let Some(sets) = &self.path_sets {
            // The `select` form chooses one path per pair (the first whole one); the others
            // mark every whole path.
            let one_per_pair = self.recipe.paths == PathForm::Select;
            for (pair, vars) in sets.pairs.iter().zip(&self.vars.paths) {
                let mut chosen = false;
                for (path, v) in pair.paths.iter().zip(vars) {
                    let whole = path.edges.iter().all(|&e| on(e)) && !(one_per_pair && chosen);
                    chosen |= whole && v.is_some();
                    set(&mut x, *v, if whole { 1.0 } else { 0.0 });
                }
            }
        }
        for c in &self.vars.local_configs {
            set(&mut x, c.indicator, if c.edges.iter().all(|&e| on(e)) { 1.0 } else { 0.0 });
        }
        for t in &self.vars.t_configs {
            set(&mut x, t.indicator, if !on(t.e0) && t.others.iter().all(|&e| on(e)) { 1.0 } else { 0.0 });
        }
        for &k in &net.rooms {
            let v = self.vars.rooms.get(k).ok_or(EncodeError::UnknownRoom(k))?;
            x[v.index()] = 1.0;
        }
        Ok(x)
    }

    /// Whether the recipe has direction binaries (labels or the distance flow).
    fn needs_directions(&self) -> bool {
        self.vars.half_edge.iter().any(Option::is_some)
    }
}

/// Sends every vertex's supply along `step` to a sink, accumulating the flow on each arc;
/// vertices are processed from the farthest (largest `dist`) in, so each arc's flow is final
/// when it is set.
fn route(
    p: &Problem,
    x: &mut [f64],
    flow: &[Option<crate::milp::VarId>],
    supply: &mut [f64],
    step: &[Option<HalfEdgeId>],
    dist: &[f64],
) {
    let mesh = &p.mesh;
    let mut order: Vec<VertexId> = mesh.vertices().filter(|v| step[v.index()].is_some()).collect();
    order.sort_by(|a, b| dist[b.index()].total_cmp(&dist[a.index()]).then(a.cmp(b)));
    for v in order {
        let g = step[v.index()].expect("filtered");
        let amount = supply[v.index()];
        if amount == 0.0 {
            continue;
        }
        if let Some(f) = flow[g.index()] {
            x[f.index()] += amount;
        }
        let w = mesh.he_head(g);
        if !p.is_sink[w.index()] {
            supply[w.index()] += amount;
        }
    }
}
