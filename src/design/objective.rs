//! The objective (7)/(15) recomputed from a design alone: plain graph code over the problem and
//! the active edges, never the solver's labels, flows or indicators.
//!
//! **The paper's distance term.** At an optimum of the paper's model, a label into a sink is 0
//! and otherwise `D(i→j) = Δ(i→j) + D(j→k)` for the successor `j→k`; exactly one half-edge of an
//! active edge carries a label, pointing to the end whose label is smaller (docs/formulation.md §8). So
//! for a network the term is `Σ_{active candidate edges {u,v}} min(D(u→v), D(v→u))` with
//! `D(u→v) = 0` when `v` is a sink and `Δ(u,v) + h(v)` otherwise, where `h(v)` is the length of
//! the shortest network path from `v` to a sink **minus the length of its last edge** (0 when `v`
//! is next to a sink). On meshes with one edge length `Δ`, `Δ + h(v)` is the network distance
//! `d(v)`, so the term is `Σ min(d(u), d(v))` — a per-edge sum in which an edge touching a sink
//! costs 0. On other meshes the labels are only roughly distances (the paper says so); this is
//! what they measure exactly.
//!
//! **Travel** (the optional per-vertex term): `Σ_{active non-sink v} d(v)`.

use super::metrics::travel_distances;
use super::Network;
use crate::mesh::paths::{dijkstra, Search};
use crate::mesh::VertexId;
use crate::rules::{designed, t_configs, too_close_configs, zigzag_configs};
use crate::spec::{EdgeRole, Problem, Weight};
use serde::{Deserialize, Serialize};

/// The objective of a design, term by term, recomputed from its active edges.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Objective {
    /// Total length of the active candidate edges (the λL term; existing roads are not counted).
    pub length: f64,
    /// The paper's distance term `Σ D(i→j)` at its minimum for this network (the λD term).
    pub distance: f64,
    /// Total travel: `Σ` over active non-sink vertices of the network distance to the nearest
    /// sink (the `weights.travel` term).
    pub travel: f64,
    /// Zig-zags present (designed ones, i.e. with a candidate edge).
    pub zigzags: usize,
    /// Too-close pairs present (designed ones).
    pub too_close: usize,
    /// T-junctions present (designed ones).
    pub t_junctions: usize,
    /// Active vertices from which no sink can be reached (their edges are left out of
    /// `distance` and `travel`; 0 in a valid design).
    pub unreachable: usize,
    /// The weighted sum: `λL·length + λD·distance + λtravel·travel` plus each penalised
    /// feature's weight times its count.
    pub total: f64,
}

/// `h(v)` of the module docs for every vertex: the shortest network path from `v` to a sink
/// minus its last edge (`∞` when no sink is reachable; 0 at sinks by convention).
pub fn label_distances(p: &Problem, net: &Network) -> Vec<f64> {
    let mesh = &p.mesh;
    let mut h = vec![f64::INFINITY; mesh.num_vertices()];
    let mut seeds = Vec::new();
    for v in mesh.vertices() {
        if p.is_sink[v.index()] {
            h[v.index()] = 0.0;
            continue;
        }
        let next_to_sink =
            mesh.outgoing(v).iter().any(|&g| net.active[mesh.he_edge(g).index()] && p.is_sink[mesh.he_head(g).index()]);
        if next_to_sink {
            h[v.index()] = 0.0;
            seeds.push(v);
        }
    }
    let usable = |g| net.active[mesh.he_edge(g).index()] && !p.is_sink[mesh.he_head(g).index()];
    dijkstra(mesh, &mut h, seeds, &Search { usable, tolerance: 0.0, target: None });
    h
}

impl Objective {
    /// Recomputes every term of a design.
    pub fn of(p: &Problem, net: &Network) -> Objective {
        let mesh = &p.mesh;
        let h = label_distances(p, net);
        let d = travel_distances(mesh, net, &p.is_sink);
        let label_into = |v: VertexId, len: f64| if p.is_sink[v.index()] { 0.0 } else { len + h[v.index()] };
        let (mut length, mut distance) = (0.0, 0.0);
        for e in mesh.edges().filter(|e| net.active[e.index()] && p.roles[e.index()] == EdgeRole::Candidate) {
            let len = mesh.edge_length(e);
            length += len;
            let (u, v) = mesh.edge_vertices(e);
            let best = label_into(v, len).min(label_into(u, len));
            if best.is_finite() {
                distance += best;
            }
        }
        let mut active = vec![false; mesh.num_vertices()];
        for e in net.active_edges() {
            let (a, b) = mesh.edge_vertices(e);
            active[a.index()] = true;
            active[b.index()] = true;
        }
        let mut travel = 0.0;
        let mut unreachable = 0;
        for v in mesh.vertices().filter(|v| active[v.index()] && !p.is_sink[v.index()]) {
            if d[v.index()].is_finite() {
                travel += d[v.index()];
            } else {
                unreachable += 1;
            }
        }
        let present = |es: &[crate::mesh::EdgeId]| designed(p, es) && es.iter().all(|e| net.active[e.index()]);
        let zigzags = zigzag_configs(mesh).iter().filter(|z| present(&z.edges)).count();
        let too_close = too_close_configs(mesh).iter().filter(|t| present(&t.edges)).count();
        let t_junctions = t_configs(mesh)
            .iter()
            .filter(|(_, _, e0, o)| {
                !net.active[e0.index()]
                    && designed(p, &[*e0, o[0], o[1], o[2]])
                    && o.iter().all(|e| net.active[e.index()])
            })
            .count();
        let penalty = |w: Weight, n: usize| if let Weight::Penalty(l) = w { l * n as f64 } else { 0.0 };
        let total = p.w_length * length
            + p.w_distance * distance
            + p.w_travel * travel
            + penalty(p.w_zigzag, zigzags)
            + penalty(p.w_too_close, too_close)
            + penalty(p.w_t_junction, t_junctions);
        Objective { length, distance, travel, zigzags, too_close, t_junctions, unreachable, total }
    }
}
