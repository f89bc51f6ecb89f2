//! A design as a point of a formulation (a MIP start): every variable of the recipe set from
//! the active edges and rooms alone, each family setting its own ([`super::Family::encode`]).
//!
//! What several families need is computed once here ([`Encoding`]): directions point every
//! active edge toward its end with the smaller paper label (`0` at a sink, else `Δ + h`, see
//! [`crate::design::Objective`]); successors and the distance flow follow each vertex's best next
//! step; the travel and connectivity flows and the parent arcs follow a shortest-path tree. The
//! point is meant to be checked by the MILP checker before it is handed to a solver: a design
//! that breaks the spec gives a point that breaks rows, and the checker says which.

use super::vars::VarMap;
use super::Formulation;
use crate::design::{label_distances, travel_distances, Network};
use crate::mesh::{EdgeId, HalfEdgeId, VertexId};
use crate::milp::VarId;
use crate::rules::paths::PathSets;
use crate::spec::Problem;
use std::sync::OnceLock;

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

/// A design being encoded, with what the families compute from it once.
pub struct Encoding<'a> {
    /// The problem.
    pub p: &'a Problem,
    /// The design.
    pub net: &'a Network,
    /// The formulation's shared variables.
    pub vars: &'a VarMap,
    /// The formulation's point-to-point path sets, if any.
    pub path_sets: Option<&'a PathSets>,
    degree: Vec<usize>,
    labels: OnceLock<Vec<f64>>,
    next: OnceLock<Vec<Option<HalfEdgeId>>>,
    travel: OnceLock<Vec<f64>>,
}

impl<'a> Encoding<'a> {
    fn new(p: &'a Problem, net: &'a Network, f: &'a Formulation) -> Encoding<'a> {
        let mesh = &p.mesh;
        let mut degree = vec![0usize; mesh.num_vertices()];
        for e in net.active_edges() {
            let (a, b) = mesh.edge_vertices(e);
            degree[a.index()] += 1;
            degree[b.index()] += 1;
        }
        Encoding {
            p,
            net,
            vars: &f.vars,
            path_sets: f.path_sets.as_ref(),
            degree,
            labels: OnceLock::new(),
            next: OnceLock::new(),
            travel: OnceLock::new(),
        }
    }

    /// Whether edge `e` is active in the design.
    pub fn on(&self, e: EdgeId) -> bool {
        self.net.active[e.index()]
    }

    /// The active degree of `v`.
    pub fn degree(&self, v: VertexId) -> usize {
        self.degree[v.index()]
    }

    /// Whether `v` is an active non-sink vertex.
    pub fn active_non_sink(&self, v: VertexId) -> bool {
        !self.p.is_sink[v.index()] && self.degree(v) > 0
    }

    /// The paper's label of a half-edge of length `len` into `v`: 0 into a sink, else `len + h(v)`
    /// ([`label_distances`]).
    pub fn label_into(&self, v: VertexId, len: f64) -> f64 {
        if self.p.is_sink[v.index()] {
            0.0
        } else {
            len + self.labels.get_or_init(|| label_distances(self.p, self.net))[v.index()]
        }
    }

    /// The labels `h` of [`label_distances`], per vertex.
    pub fn labels(&self) -> &[f64] {
        self.labels.get_or_init(|| label_distances(self.p, self.net))
    }

    /// The best next step of every active non-sink vertex: the active half-edge out of it with
    /// the smallest label (ties: the first in the mesh's order); `None` where there is none.
    pub fn next(&self) -> &[Option<HalfEdgeId>] {
        self.next.get_or_init(|| {
            let mesh = &self.p.mesh;
            let mut next = vec![None; mesh.num_vertices()];
            for v in mesh.vertices().filter(|&v| self.active_non_sink(v)) {
                let mut best: Option<(f64, HalfEdgeId)> = None;
                for &g in mesh.outgoing(v) {
                    if self.on(mesh.he_edge(g)) {
                        let d = self.label_into(mesh.he_head(g), mesh.he_length(g));
                        if d.is_finite() && best.is_none_or(|(b, _)| d < b) {
                            best = Some((d, g));
                        }
                    }
                }
                next[v.index()] = best.map(|(_, g)| g);
            }
            next
        })
    }

    /// Sets the direction binaries `E(i→j)` (and, where the recipe has them, the labels
    /// `D(i→j)`): every active candidate edge toward its end with the smaller label. Fails when
    /// an active vertex cannot reach a sink.
    pub fn set_directions(&self, x: &mut [f64]) -> Result<(), EncodeError> {
        let mesh = &self.p.mesh;
        let next = self.next();
        if let Some(v) = mesh.vertices().find(|&v| self.active_non_sink(v) && next[v.index()].is_none()) {
            return Err(EncodeError::Unreachable(v.0));
        }
        for e in mesh.edges().filter(|&e| self.on(e) && self.vars.edge[e.index()].is_some()) {
            let [h0, h1] = mesh.edge_half_edges(e);
            let len = mesh.edge_length(e);
            let (d0, d1) = (self.label_into(mesh.he_head(h0), len), self.label_into(mesh.he_head(h1), len));
            if !d0.is_finite() && !d1.is_finite() {
                return Err(EncodeError::Unreachable(mesh.he_head(h0).0));
            }
            let chosen = if d0 <= d1 { h0 } else { h1 };
            set(x, self.vars.half_edge[chosen.index()], 1.0);
            set(x, self.vars.label[chosen.index()], self.label_into(mesh.he_head(chosen), len));
        }
        Ok(())
    }

    /// Whether the direction binary of `h` is on at `x`.
    pub fn direction_on(&self, x: &[f64], h: HalfEdgeId) -> bool {
        self.vars.half_edge[h.index()].is_some_and(|v| x[v.index()] > 0.5)
    }

    /// True network distances to the nearest sink ([`travel_distances`]).
    pub fn travel(&self) -> &[f64] {
        self.travel.get_or_init(|| travel_distances(&self.p.mesh, self.net, &self.p.is_sink))
    }

    /// A shortest-path tree into the sinks: each active non-sink vertex's step toward the
    /// nearest sink. Fails when an active vertex cannot reach one.
    pub fn tree(&self) -> Result<Vec<Option<HalfEdgeId>>, EncodeError> {
        let mesh = &self.p.mesh;
        let d = self.travel();
        let mut tree = vec![None; mesh.num_vertices()];
        for v in mesh.vertices().filter(|&v| self.active_non_sink(v)) {
            if !d[v.index()].is_finite() {
                return Err(EncodeError::Unreachable(v.0));
            }
            tree[v.index()] =
                mesh.outgoing(v).iter().copied().filter(|&g| self.on(mesh.he_edge(g))).min_by(|&a, &b| {
                    (mesh.he_length(a) + d[mesh.he_head(a).index()])
                        .total_cmp(&(mesh.he_length(b) + d[mesh.he_head(b).index()]))
                });
        }
        Ok(tree)
    }

    /// Sends every vertex's supply along `step` to a sink, accumulating the flow on each arc's
    /// variable in `flow`; vertices are processed from the farthest (largest `dist`) in, so
    /// each arc's flow is final when it is set.
    pub fn route(
        &self,
        x: &mut [f64],
        flow: &[Option<VarId>],
        supply: &mut [f64],
        step: &[Option<HalfEdgeId>],
        dist: &[f64],
    ) {
        let p = self.p;
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
}

/// Sets `v` to `val` in `x` when the variable exists.
pub fn set(x: &mut [f64], v: Option<VarId>, val: f64) {
    if let Some(v) = v {
        x[v.index()] = val;
    }
}

impl Formulation {
    /// The point of this formulation that stands for `net`: every variable at its lower bound
    /// (clamped into its bounds), then each family's own set from the design, in emission order.
    pub fn encode(&self, p: &Problem, net: &Network) -> Result<Vec<f64>, EncodeError> {
        if net.active.len() != p.mesh.num_edges() {
            return Err(EncodeError::WrongSize { got: net.active.len(), want: p.mesh.num_edges() });
        }
        let mut x: Vec<f64> = self.model.vars().iter().map(|v| v.lb.max(0.0).min(v.ub)).collect();
        let e = Encoding::new(p, net, self);
        for family in &self.parts {
            family.encode(&e, &mut x)?;
        }
        Ok(x)
    }
}
