//! Shortest paths on a mesh: the one Dijkstra every design measure and spec resolution uses
//! (the heap ordered by distance, then vertex id, so ties break the same way on every run).

use super::{HalfEdgeId, Mesh, VertexId};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A totally ordered f64 for heaps (no NaN ever enters).
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct OrdF64(pub f64);

impl Eq for OrdF64 {}

impl PartialOrd for OrdF64 {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for OrdF64 {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// Which half-edges a search may take, how much shorter a path must be to replace a label, and
/// where it may stop.
pub(crate) struct Search<F: Fn(HalfEdgeId) -> bool> {
    /// Whether a half-edge may be walked.
    pub usable: F,
    /// A label is replaced only by a path shorter by more than this (0 for strictly shorter).
    pub tolerance: f64,
    /// Stop once this vertex is settled.
    pub target: Option<VertexId>,
}

/// Dijkstra by edge length from `seeds` (each starts at its label in `dist`), over the
/// half-edges `search.usable` allows. `dist` holds the labels (∞ where unreached); labels of
/// vertices that are not seeds may be given too (a vertex already at 0 is never improved). The
/// result is every vertex's predecessor on its shortest path (`u32::MAX` for none).
pub(crate) fn dijkstra<F: Fn(HalfEdgeId) -> bool>(
    mesh: &Mesh,
    dist: &mut [f64],
    seeds: impl IntoIterator<Item = VertexId>,
    search: &Search<F>,
) -> Vec<u32> {
    let mut prev = vec![u32::MAX; mesh.num_vertices()];
    let mut heap: BinaryHeap<Reverse<(OrdF64, u32)>> =
        seeds.into_iter().map(|v| Reverse((OrdF64(dist[v.index()]), v.0))).collect();
    while let Some(Reverse((OrdF64(d), v))) = heap.pop() {
        if d > dist[v as usize] {
            continue;
        }
        if search.target.is_some_and(|t| t.0 == v) {
            break;
        }
        for &h in mesh.outgoing(VertexId(v)) {
            if !(search.usable)(h) {
                continue;
            }
            let (e, w) = (mesh.he_edge(h), mesh.he_head(h));
            let nd = d + mesh.edge_length(e);
            if nd < dist[w.index()] - search.tolerance {
                dist[w.index()] = nd;
                prev[w.index()] = v;
                heap.push(Reverse((OrdF64(nd), w.0)));
            }
        }
    }
    prev
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::grid;

    /// On a 2 × 2 grid of unit cells, the far corner is 4 away along the edges; a blocked
    /// half-edge is gone around, and a target stops the search once it is settled.
    #[test]
    fn distances_predecessors_blocked_edges_and_targets() {
        let m = grid(2, 2, 1.0);
        let far = m.vertices().max_by(|a, b| m.position(*a).partial_cmp(&m.position(*b)).unwrap()).unwrap();
        let start = m.vertices().min_by(|a, b| m.position(*a).partial_cmp(&m.position(*b)).unwrap()).unwrap();
        let mut dist = vec![f64::INFINITY; m.num_vertices()];
        dist[start.index()] = 0.0;
        let prev = dijkstra(&m, &mut dist, [start], &Search { usable: |_| true, tolerance: 0.0, target: None });
        assert_eq!(dist[far.index()], 4.0);
        assert!(dist.iter().all(|d| d.is_finite()));
        let mut v = far;
        let mut hops = 0;
        while v != start {
            v = VertexId(prev[v.index()]);
            hops += 1;
        }
        assert_eq!(hops, 4);
        // Nothing may be walked: only the seed is reached.
        let mut none = vec![f64::INFINITY; m.num_vertices()];
        none[start.index()] = 0.0;
        dijkstra(&m, &mut none, [start], &Search { usable: |_| false, tolerance: 0.0, target: None });
        assert_eq!(none.iter().filter(|d| d.is_finite()).count(), 1);
        // With a target, the search stops once it is settled: some vertex beyond stays unlabelled
        // or is labelled no shorter than the target.
        let mut to = vec![f64::INFINITY; m.num_vertices()];
        to[start.index()] = 0.0;
        let next = m.he_head(m.outgoing(start)[0]);
        dijkstra(&m, &mut to, [start], &Search { usable: |_| true, tolerance: 0.0, target: Some(next) });
        assert_eq!(to[next.index()], 1.0);
        assert!(!to[far.index()].is_finite());
    }
}
