//! Decoding a solution into a network, measuring it, and validating it independently.
//!
//! The validator ([`validate`]) checks FORMULATION §6 items 1–5 in plain graph code that never
//! reads the MILP: it takes the problem and a set of active edges. Item 7 (every row and bound
//! holds; the objective recomputed from the design equals the solver's) is [`check_objective`]
//! together with the MILP checker.

mod blocks;
mod metrics;
mod validate;

pub use blocks::{block_graph, BlockGraph, GraphShape};
pub use metrics::{travel_distances, Metrics};
pub use validate::{validate, validate_rooms, Violation};

use crate::formulations::network::NetworkModel;
use crate::mesh::{EdgeId, VertexId};
use crate::spec::{EdgeRole, Problem};
use serde::{Deserialize, Serialize};

/// A decoded network.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Network {
    /// Whether each edge is active (existing edges included).
    pub active: Vec<bool>,
    /// Active half-edges (direction toward a sink), as (tail, head), from `E(i→j)`.
    pub directions: Vec<(VertexId, VertexId)>,
    /// Distance labels of active half-edges as the solver returned them: (tail, head, label).
    pub labels: Vec<(VertexId, VertexId, f64)>,
    /// Chosen room placements (indices into the model's placements), when tiling rooms.
    #[serde(default)]
    pub rooms: Vec<usize>,
}

impl Network {
    /// The active edges, in id order.
    pub fn active_edges(&self) -> Vec<EdgeId> {
        self.active.iter().enumerate().filter(|(_, &a)| a).map(|(i, _)| EdgeId(i as u32)).collect()
    }

    /// A network from a list of active edges (existing edges are added), for hand-built tests.
    pub fn from_edges(p: &Problem, edges: &[EdgeId]) -> Network {
        let mut active: Vec<bool> = p.roles.iter().map(|r| *r == EdgeRole::Existing).collect();
        for e in edges {
            active[e.index()] = true;
        }
        Network { active, directions: Vec::new(), labels: Vec::new(), rooms: Vec::new() }
    }
}

/// Decodes the solver's point (binaries rounded at 0.5).
pub fn decode(p: &Problem, nm: &NetworkModel, x: &[f64]) -> Network {
    let mesh = &p.mesh;
    let active = mesh
        .edges()
        .map(|e| match nm.edge_var[e.index()] {
            Some(v) => x[v.index()] > 0.5,
            None => p.roles[e.index()] == EdgeRole::Existing,
        })
        .collect();
    let mut directions = Vec::new();
    let mut labels = Vec::new();
    for e in mesh.edges() {
        for h in mesh.edge_half_edges(e) {
            if let Some(v) = nm.half_edge_var[h.index()] {
                if x[v.index()] > 0.5 {
                    directions.push((mesh.he_tail(h), mesh.he_head(h)));
                    let d = nm.label_var[h.index()].map_or(0.0, |d| x[d.index()]);
                    labels.push((mesh.he_tail(h), mesh.he_head(h), d));
                }
            }
        }
    }
    let rooms = nm.rooms.as_ref().map_or(Vec::new(), |rm| {
        rm.vars.iter().enumerate().filter(|(_, v)| x[v.index()] > 0.5).map(|(k, _)| k).collect()
    });
    Network { active, directions, labels, rooms }
}

/// FORMULATION §6 item 7, the design half: the objective recomputed from the decoded network
/// (λL × active candidate length + λD × Σ labels + λZ × configurations present + λT ×
/// T-junctions present) — using the solver's labels, which only (2) defines.
pub fn recompute_objective(p: &Problem, nm: &NetworkModel, net: &Network, x: &[f64]) -> f64 {
    let mesh = &p.mesh;
    let mut obj = 0.0;
    for e in mesh.edges() {
        if nm.edge_var[e.index()].is_some() && net.active[e.index()] {
            obj += p.w_length * mesh.edge_length(e);
        }
    }
    obj += p.w_distance * nm.label_var.iter().flatten().map(|d| x[d.index()]).sum::<f64>();
    for c in &nm.local_configs {
        if c.edges.iter().all(|e| net.active[e.index()]) {
            obj += if c.k == 0 { p.w_zigzag.value() } else { p.w_too_close.value() };
        }
    }
    for t in &nm.t_configs {
        if !net.active[t.e0.index()] && t.others.iter().all(|e| net.active[e.index()]) {
            obj += p.w_t_junction.value();
        }
    }
    obj
}
