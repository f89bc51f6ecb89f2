//! Local configurations of the paper's (13)–(14) on a mesh, and coverage balls (5)–(6): which
//! edge sets a spec's local rules talk about. Both the formulations (to emit rows) and the
//! design code (to validate and measure) read these lists; neither owns them.

use crate::mesh::{EdgeId, HalfEdgeId, Mesh, VertexId};
use crate::spec::{CoverageModel, EdgeRole, Problem};

/// Whether the design decides a configuration: at least one of its edges is a candidate. A
/// configuration made only of existing roads (e.g. the staircase boundary of a clipped
/// sub-region, or earlier street levels) is given, not designed: it is neither forbidden nor
/// penalised, and the validator exempts it too.
pub fn designed(p: &Problem, edges: &[EdgeId]) -> bool {
    edges.iter().any(|e| p.roles[e.index()] == EdgeRole::Candidate)
}

/// The zig-zag configurations (13, k = 0) of the mesh: for every interior edge `b` with faces
/// `f1`, `f2`, the staircases `a, b, c` with `a` a side of `f1` at one end of `b` and `c` a side of
/// `f2` at the other end. Two per interior edge.
pub fn zigzag_configs(mesh: &Mesh) -> Vec<(String, Vec<EdgeId>)> {
    let mut out = Vec::new();
    for b in mesh.edges() {
        let [h1, h2] = mesh.edge_half_edges(b);
        let (Some(p1), Some(n1), Some(p2), Some(n2)) =
            (mesh.he_prev(h1), mesh.he_next(h1), mesh.he_prev(h2), mesh.he_next(h2))
        else {
            continue;
        };
        out.push((format!("e{}_0", b.0), vec![mesh.he_edge(p1), b, mesh.he_edge(p2)]));
        out.push((format!("e{}_1", b.0), vec![mesh.he_edge(n1), b, mesh.he_edge(n2)]));
    }
    out
}

/// The too-close configurations (13, k = 1): both pairs of opposite edges of every quad face.
pub fn too_close_configs(mesh: &Mesh) -> Vec<(String, Vec<EdgeId>)> {
    let mut out = Vec::new();
    for f in mesh.faces() {
        let es = mesh.face_edges(f);
        if es.len() == 4 {
            out.push((format!("f{}_0", f.0), vec![es[0], es[2]]));
            out.push((format!("f{}_1", f.0), vec![es[1], es[3]]));
        }
    }
    out
}

/// The T-junction configurations (14): for every half-edge into an interior valence-4 vertex,
/// its edge `E0` and the other three edges.
pub fn t_configs(mesh: &Mesh) -> Vec<(HalfEdgeId, VertexId, EdgeId, [EdgeId; 3])> {
    let mut out = Vec::new();
    for v in mesh.vertices() {
        if mesh.is_boundary_vertex(v) || mesh.valence(v) != 4 {
            continue;
        }
        let edges: Vec<EdgeId> = mesh.incident_edges(v).collect();
        for &g in mesh.outgoing(v) {
            let h = mesh.he_twin(g);
            let e0 = mesh.he_edge(h);
            let others: Vec<EdgeId> = edges.iter().copied().filter(|&e| e != e0).collect();
            out.push((h, v, e0, [others[0], others[1], others[2]]));
        }
    }
    out
}

/// The vertices within the coverage range of `v` (hops on the whole mesh graph, or Euclidean),
/// `v` included, in id order.
pub fn cover_set(p: &Problem, v: VertexId) -> Vec<VertexId> {
    let mesh = &p.mesh;
    let mut out: Vec<VertexId> = match p.coverage_model {
        CoverageModel::Hops => {
            mesh.hop_distances(v, p.coverage_range.floor() as usize).into_iter().map(|(u, _)| u).collect()
        }
        CoverageModel::Euclidean => {
            let pv = mesh.position(v);
            let r2 = p.coverage_range * p.coverage_range;
            mesh.vertices()
                .filter(|&u| {
                    let pu = mesh.position(u);
                    (pu[0] - pv[0]).powi(2) + (pu[1] - pv[1]).powi(2) <= r2 * (1.0 + 1e-12)
                })
                .collect()
        }
    };
    out.sort();
    out
}
