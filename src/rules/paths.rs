//! Point-to-point path sets (docs/formulation.md §3.4): sample one vertex per part of the face
//! partition, and for every pair of adjacent parts enumerate the simple paths between their
//! vertices with at most (shortest + tolerance) edges. Enumeration is bounded in count and time,
//! and reports what it enumerated.

use crate::mesh::{EdgeId, Mesh, VertexId};
use crate::spec::{EdgeRole, Problem};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeSet, VecDeque};
use std::time::{Duration, Instant};

/// Time cap on the enumeration for one pair.
const PAIR_TIME_CAP: Duration = Duration::from_secs(5);

/// One enumerated path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Path {
    /// Its vertices, from the first part's vertex to the second's.
    pub vertices: Vec<VertexId>,
    /// Its edges, in order.
    pub edges: Vec<EdgeId>,
}

/// The paths of one pair of adjacent parts.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairPaths {
    /// The two parts.
    pub parts: (u32, u32),
    /// Their sampled vertices.
    pub ends: (VertexId, VertexId),
    /// Edges on a shortest path (None: not connected).
    pub shortest: Option<usize>,
    /// The enumerated paths.
    pub paths: Vec<Path>,
    /// Whether the count or time cap cut the enumeration short.
    pub truncated: bool,
}

/// Everything the enumeration produced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathSets {
    /// The sampled vertex of every part, by part number (parts with no usable vertex are
    /// absent).
    pub samples: Vec<(u32, VertexId)>,
    /// Paths per adjacent pair.
    pub pairs: Vec<PairPaths>,
    /// Total paths.
    pub total_paths: usize,
    /// Seconds spent.
    pub seconds: f64,
}

fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E3779B97F4A7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
    z ^ (z >> 31)
}

fn usable(mesh: &Mesh, roles: &[EdgeRole], v: VertexId) -> bool {
    mesh.incident_edges(v).any(|e| roles[e.index()] != EdgeRole::Excluded)
}

/// Samples the vertices and enumerates the path sets of a problem with point-to-point on.
pub fn enumerate_path_sets(p: &Problem) -> PathSets {
    let t0 = Instant::now();
    let mesh = &p.mesh;
    let pp = p.p2p.as_ref().expect("point-to-point is on");
    let part = &pp.face_part;
    // Vertices of each part; a vertex is interior to a part when all its faces are in it.
    let nparts = part.iter().filter(|&&x| x != u32::MAX).map(|&x| x + 1).max().unwrap_or(0) as usize;
    let mut members: Vec<BTreeSet<VertexId>> = vec![BTreeSet::new(); nparts];
    for f in mesh.faces() {
        if part[f.index()] != u32::MAX {
            members[part[f.index()] as usize].extend(mesh.face_vertices(f).iter().copied());
        }
    }
    let mut rng = pp.seed ^ 0x006E_6574_7370_6563; // "netspec"
    let mut samples = Vec::new();
    for (k, vs) in members.iter().enumerate() {
        let ok: Vec<VertexId> =
            vs.iter().copied().filter(|&v| usable(mesh, &p.roles, v) && !p.is_obstacle_vertex[v.index()]).collect();
        let interior: Vec<VertexId> = ok
            .iter()
            .copied()
            .filter(|&v| {
                !mesh.is_boundary_vertex(v)
                    && mesh.outgoing(v).iter().all(|&h| mesh.he_face(h).is_some_and(|f| part[f.index()] == k as u32))
            })
            .collect();
        let pool = if interior.is_empty() { ok } else { interior };
        if !pool.is_empty() {
            let pick = pool[(splitmix(&mut rng) % pool.len() as u64) as usize];
            samples.push((k as u32, pick));
        }
    }
    // Adjacent parts: an edge with faces in two different parts.
    let mut adjacent = BTreeSet::new();
    for e in mesh.edges() {
        if let [Some(a), Some(b)] = mesh.edge_faces(e) {
            let (pa, pb) = (part[a.index()], part[b.index()]);
            if pa != pb && pa != u32::MAX && pb != u32::MAX {
                adjacent.insert((pa.min(pb), pa.max(pb)));
            }
        }
    }
    let sample_of = |k: u32| samples.iter().find(|(p, _)| *p == k).map(|(_, v)| *v);
    let mut pairs = Vec::new();
    for (a, b) in adjacent {
        let (Some(va), Some(vb)) = (sample_of(a), sample_of(b)) else { continue };
        pairs.push(enumerate_pair(mesh, &p.roles, (a, b), va, vb, pp.tolerance, pp.max_paths));
    }
    let total_paths = pairs.iter().map(|p| p.paths.len()).sum();
    PathSets { samples, pairs, total_paths, seconds: t0.elapsed().as_secs_f64() }
}

/// Hop distances to `target` over non-excluded edges.
fn hops_to(mesh: &Mesh, roles: &[EdgeRole], target: VertexId) -> Vec<usize> {
    let mut d = vec![usize::MAX; mesh.num_vertices()];
    let mut q = VecDeque::new();
    d[target.index()] = 0;
    q.push_back(target);
    while let Some(v) = q.pop_front() {
        for &h in mesh.outgoing(v) {
            if roles[mesh.he_edge(h).index()] == EdgeRole::Excluded {
                continue;
            }
            let w = mesh.he_head(h);
            if d[w.index()] == usize::MAX {
                d[w.index()] = d[v.index()] + 1;
                q.push_back(w);
            }
        }
    }
    d
}

fn enumerate_pair(
    mesh: &Mesh,
    roles: &[EdgeRole],
    parts: (u32, u32),
    a: VertexId,
    b: VertexId,
    tol: usize,
    cap: usize,
) -> PairPaths {
    let dist = hops_to(mesh, roles, b);
    let mut out = PairPaths { parts, ends: (a, b), shortest: None, paths: Vec::new(), truncated: false };
    if dist[a.index()] == usize::MAX {
        return out;
    }
    let limit = dist[a.index()] + tol;
    out.shortest = Some(dist[a.index()]);
    let t0 = Instant::now();
    let mut on_path = vec![false; mesh.num_vertices()];
    let mut verts = vec![a];
    let mut edges = Vec::new();
    on_path[a.index()] = true;
    // Iterative DFS: a stack of (vertex, next outgoing index).
    let mut stack: Vec<(VertexId, usize)> = vec![(a, 0)];
    while let Some(top) = stack.last_mut() {
        if out.paths.len() >= cap || t0.elapsed() > PAIR_TIME_CAP {
            out.truncated = true;
            break;
        }
        let (v, idx) = *top;
        top.1 += 1;
        let out_hes = mesh.outgoing(v);
        if idx >= out_hes.len() {
            stack.pop();
            on_path[v.index()] = false;
            verts.pop();
            edges.pop();
            continue;
        }
        let h = out_hes[idx];
        let e = mesh.he_edge(h);
        let w = mesh.he_head(h);
        if roles[e.index()] == EdgeRole::Excluded || on_path[w.index()] || dist[w.index()] == usize::MAX {
            continue;
        }
        if edges.len() + 1 + dist[w.index()] > limit {
            continue;
        }
        if w == b {
            let mut vs = verts.clone();
            vs.push(w);
            let mut es = edges.clone();
            es.push(e);
            out.paths.push(Path { vertices: vs, edges: es });
            continue;
        }
        on_path[w.index()] = true;
        verts.push(w);
        edges.push(e);
        stack.push((w, 0));
    }
    out
}
