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

/// A local configuration of (13): the edges that may not (or should not) all be active, and the
/// site it is named after. Its name is built only when asked for ([`LocalConfig::name`]): the
/// heuristics enumerate these lists once per room tiling and never need one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LocalConfig<const N: usize> {
    /// The configuration's edges.
    pub edges: [EdgeId; N],
    /// Its site: `'e'` and the middle edge's id (zig-zags), or `'f'` and the face's (too-close).
    site: (char, u32),
    /// Which of the site's two configurations it is (0 or 1).
    k: u8,
}

impl<const N: usize> LocalConfig<N> {
    /// Its name in a model: `e{edge}_{k}` for a zig-zag, `f{face}_{k}` for a too-close pair.
    pub fn name(&self) -> String {
        format!("{}{}_{}", self.site.0, self.site.1, self.k)
    }
}

/// The zig-zag configurations (13, k = 0) of the mesh: for every interior edge `b` with faces
/// `f1`, `f2`, the staircases `a, b, c` with `a` a side of `f1` at one end of `b` and `c` a side of
/// `f2` at the other end. Two per interior edge.
pub fn zigzag_configs(mesh: &Mesh) -> Vec<LocalConfig<3>> {
    let mut out = Vec::new();
    for b in mesh.edges() {
        let [h1, h2] = mesh.edge_half_edges(b);
        let (Some(p1), Some(n1), Some(p2), Some(n2)) =
            (mesh.he_prev(h1), mesh.he_next(h1), mesh.he_prev(h2), mesh.he_next(h2))
        else {
            continue;
        };
        let site = ('e', b.0);
        out.push(LocalConfig { edges: [mesh.he_edge(p1), b, mesh.he_edge(p2)], site, k: 0 });
        out.push(LocalConfig { edges: [mesh.he_edge(n1), b, mesh.he_edge(n2)], site, k: 1 });
    }
    out
}

/// The too-close configurations (13, k = 1): both pairs of opposite edges of every quad face.
pub fn too_close_configs(mesh: &Mesh) -> Vec<LocalConfig<2>> {
    let mut out = Vec::new();
    for f in mesh.faces() {
        let es = mesh.face_edges(f);
        if es.len() == 4 {
            let site = ('f', f.0);
            out.push(LocalConfig { edges: [es[0], es[2]], site, k: 0 });
            out.push(LocalConfig { edges: [es[1], es[3]], site, k: 1 });
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
