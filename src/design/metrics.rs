//! Network metrics: length, junctions, local features, and true travel distances (Dijkstra on
//! the active network, independent of the solver's labels).

use super::validate::degrees;
use super::Network;
use crate::mesh::paths::{dijkstra, Search};
use crate::mesh::{Mesh, VertexId};
use crate::rules::{t_configs, too_close_configs, zigzag_configs};
use crate::spec::{CoverageModel, Problem};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// Measurements of a decoded network.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Active edges (existing included).
    pub edges: usize,
    /// Their total length.
    pub length: f64,
    /// Vertices with an active edge.
    pub active_vertices: usize,
    /// Active non-sink vertices of degree 1.
    pub dead_ends: usize,
    /// Vertices of degree 3.
    pub junctions_3way: usize,
    /// Vertices of degree 4 or more.
    pub junctions_4way: usize,
    /// T-junctions (interior valence-4 vertex with exactly three active edges).
    pub t_junctions: usize,
    /// Too-close pairs present.
    pub too_close: usize,
    /// Zig-zags present.
    pub zigzags: usize,
    /// Mean network distance from active vertices to their nearest sink.
    pub mean_travel: f64,
    /// Largest such distance.
    pub max_travel: f64,
    /// Active vertices that cannot reach a sink (0 in a valid network).
    pub unreachable: usize,
    /// Coverage slack: the range minus the largest distance from a vertex to the nearest active
    /// vertex (≥ 0 when everything is covered).
    pub coverage_slack: f64,
}

/// Network distance from every vertex to its nearest sink along active edges (∞ if none).
pub fn travel_distances(mesh: &Mesh, net: &Network, is_sink: &[bool]) -> Vec<f64> {
    let mut dist = vec![f64::INFINITY; mesh.num_vertices()];
    let sinks: Vec<VertexId> = mesh.vertices().filter(|v| is_sink[v.index()]).collect();
    for v in &sinks {
        dist[v.index()] = 0.0;
    }
    let usable = |h| net.active[mesh.he_edge(h).index()];
    dijkstra(mesh, &mut dist, sinks, &Search { usable, tolerance: 0.0, target: None });
    dist
}

impl Metrics {
    /// Measures a network.
    pub fn of(p: &Problem, net: &Network) -> Metrics {
        let mesh = &p.mesh;
        let deg = degrees(mesh, net);
        let active = net.active_edges();
        let all = |es: &[crate::mesh::EdgeId]| es.iter().all(|e| net.active[e.index()]);
        let travel = travel_distances(mesh, net, &p.is_sink);
        let act: Vec<VertexId> = mesh.vertices().filter(|v| deg[v.index()] > 0).collect();
        let reach: Vec<f64> = act.iter().map(|v| travel[v.index()]).filter(|d| d.is_finite()).collect();
        let coverage_slack = match p.coverage_model {
            CoverageModel::Hops => {
                let mut d = vec![usize::MAX; mesh.num_vertices()];
                let mut q: VecDeque<VertexId> = act.iter().copied().collect();
                for v in &act {
                    d[v.index()] = 0;
                }
                while let Some(v) = q.pop_front() {
                    for w in mesh.neighbors(v) {
                        if d[w.index()] == usize::MAX {
                            d[w.index()] = d[v.index()] + 1;
                            q.push_back(w);
                        }
                    }
                }
                let worst = mesh
                    .vertices()
                    .filter(|v| !p.is_obstacle_vertex[v.index()])
                    .map(|v| d[v.index()])
                    .max()
                    .unwrap_or(0);
                if worst == usize::MAX {
                    f64::NEG_INFINITY
                } else {
                    p.coverage_range.floor() - worst as f64
                }
            }
            CoverageModel::Euclidean => {
                let worst = mesh
                    .vertices()
                    .filter(|v| !p.is_obstacle_vertex[v.index()])
                    .map(|v| {
                        let pv = mesh.position(v);
                        act.iter()
                            .map(|a| {
                                let pa = mesh.position(*a);
                                ((pa[0] - pv[0]).powi(2) + (pa[1] - pv[1]).powi(2)).sqrt()
                            })
                            .fold(f64::INFINITY, f64::min)
                    })
                    .fold(0.0, f64::max);
                p.coverage_range - worst
            }
        };
        Metrics {
            edges: active.len(),
            length: active.iter().map(|&e| mesh.edge_length(e)).sum(),
            active_vertices: act.len(),
            dead_ends: mesh.vertices().filter(|v| deg[v.index()] == 1 && !p.is_sink[v.index()]).count(),
            junctions_3way: deg.iter().filter(|&&d| d == 3).count(),
            junctions_4way: deg.iter().filter(|&&d| d >= 4).count(),
            t_junctions: t_configs(mesh).iter().filter(|(_, _, e0, o)| !net.active[e0.index()] && all(o)).count(),
            too_close: too_close_configs(mesh).iter().filter(|t| all(&t.edges)).count(),
            zigzags: zigzag_configs(mesh).iter().filter(|z| all(&z.edges)).count(),
            mean_travel: if reach.is_empty() { 0.0 } else { reach.iter().sum::<f64>() / reach.len() as f64 },
            max_travel: reach.iter().copied().fold(0.0, f64::max),
            unreachable: act.len() - reach.len(),
            coverage_slack,
        }
    }
}
