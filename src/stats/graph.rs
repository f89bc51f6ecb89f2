//! The street graph the statistics are taken on: nodes in metres and the streets between them,
//! each a polyline with its level and whether it is one-way; and its simplification as
//! `osmnx.simplify_graph` does it (nodes only at street ends and junctions).

use crate::geometry::{polyline_length, P};
use serde::{Deserialize, Serialize};

/// A street network: nodes and the streets between them, in metres. Two streets meet only at a
/// node they share (a bridge over a street is no junction).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Network {
    /// Node positions.
    pub nodes: Vec<P>,
    /// Streets.
    pub edges: Vec<Edge>,
}

/// A street between two nodes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Edge {
    /// One end (index into [`Network::nodes`]).
    pub a: usize,
    /// The other end (equal to `a` for a loop).
    pub b: usize,
    /// Its polyline from `a` to `b`, both ends included.
    pub shape: Vec<P>,
    /// Its level (1 major … 4 cul-de-sac; what the design calls it).
    pub level: u8,
    /// Traffic runs only from `a` to `b`.
    pub oneway: bool,
}

impl Edge {
    /// Its length along the polyline.
    pub fn length(&self) -> f64 {
        polyline_length(&self.shape)
    }

    fn other(&self, v: usize) -> usize {
        if self.a == v {
            self.b
        } else {
            self.a
        }
    }
}

impl Network {
    /// Each node's streets: the number of edge ends at it, a loop counting twice (OSMnx's
    /// `count_streets_per_node` on the undirected graph).
    pub fn street_counts(&self) -> Vec<usize> {
        let mut count = vec![0; self.nodes.len()];
        for e in &self.edges {
            count[e.a] += 1;
            count[e.b] += 1;
        }
        count
    }

    /// The incident edges of every node, in edge order (a loop listed twice).
    fn incidence(&self) -> Vec<Vec<usize>> {
        let mut inc = vec![Vec::new(); self.nodes.len()];
        for (i, e) in self.edges.iter().enumerate() {
            inc[e.a].push(i);
            inc[e.b].push(i);
        }
        inc
    }

    /// Whether node `v` lies inside a street and is no junction: exactly two edge ends, to two
    /// different other nodes, no loop, both streets two-way or both one-way and chained (one in,
    /// one out). OSMnx keeps every other node.
    fn interstitial(&self, v: usize, inc: &[usize]) -> bool {
        let [e, f] = match inc {
            [e, f] => [&self.edges[*e], &self.edges[*f]],
            _ => return false,
        };
        if e.a == e.b || f.a == f.b || e.other(v) == f.other(v) || e.oneway != f.oneway {
            return false;
        }
        !e.oneway || ((e.b == v) != (f.b == v))
    }

    /// The network with every interstitial node merged away: each street runs from a junction or
    /// end to the next, its polyline the concatenation of its pieces, its level that of its
    /// longest piece. A ring of interstitial nodes (a closed street that meets nothing) is left
    /// out, as OSMnx does. Nodes keep their order; the result's nodes are the kept ones.
    pub fn simplified(&self) -> Network {
        let inc = self.incidence();
        let keep: Vec<bool> = (0..self.nodes.len()).map(|v| !self.interstitial(v, &inc[v])).collect();
        let mut done = vec![false; self.edges.len()];
        let mut paths: Vec<(usize, usize, Vec<usize>)> = Vec::new();
        for v in (0..self.nodes.len()).filter(|&v| keep[v]) {
            for &e in &inc[v] {
                if !done[e] {
                    paths.push(self.walk(v, e, &keep, &inc, &mut done));
                }
            }
        }
        // Rings without a junction are left out, as `simplify_graph(remove_rings=True)` does.
        let mut kept = keep;
        for &(a, b, _) in &paths {
            kept[a] = true;
            kept[b] = true;
        }
        let mut index = vec![usize::MAX; self.nodes.len()];
        let mut nodes = Vec::new();
        for v in (0..self.nodes.len()).filter(|&v| kept[v]) {
            index[v] = nodes.len();
            nodes.push(self.nodes[v]);
        }
        let edges = paths.into_iter().map(|(a, b, path)| self.merged(a, b, &path, &index)).collect();
        Network { nodes, edges }
    }

    /// Follows edge `e` from `v` through interstitial nodes to the next kept node.
    fn walk(
        &self,
        v: usize,
        e: usize,
        keep: &[bool],
        inc: &[Vec<usize>],
        done: &mut [bool],
    ) -> (usize, usize, Vec<usize>) {
        let mut path = vec![e];
        done[e] = true;
        let mut cur = self.edges[e].other(v);
        let mut last = e;
        while !keep[cur] {
            let Some(&next) = inc[cur].iter().find(|&&f| f != last && !done[f]) else { break };
            done[next] = true;
            path.push(next);
            cur = self.edges[next].other(cur);
            last = next;
        }
        (v, cur, path)
    }

    /// One street from the pieces `path`, walked from `a` to `b`.
    fn merged(&self, a: usize, b: usize, path: &[usize], index: &[usize]) -> Edge {
        let mut shape: Vec<P> = Vec::new();
        let mut at = a;
        let mut longest = (f64::NEG_INFINITY, 0u8);
        for &i in path {
            let e = &self.edges[i];
            let mut piece = e.shape.clone();
            if e.a != at {
                piece.reverse();
            }
            at = e.other(at);
            if !shape.is_empty() {
                piece.remove(0);
            }
            shape.extend(piece);
            let l = e.length();
            if l > longest.0 {
                longest = (l, e.level);
            }
        }
        // A one-way chain walked against its direction is turned round.
        let first = &self.edges[path[0]];
        let against = first.oneway && first.a != a;
        let (mut a, mut b) = (index[a], index[b]);
        if against {
            shape.reverse();
            std::mem::swap(&mut a, &mut b);
        }
        Edge { a, b, shape, level: longest.1, oneway: first.oneway }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge(a: usize, b: usize, nodes: &[P]) -> Edge {
        Edge { a, b, shape: vec![nodes[a], nodes[b]], level: 3, oneway: false }
    }

    #[test]
    fn a_street_of_three_pieces_becomes_one() {
        let nodes = vec![[0.0, 0.0], [10.0, 0.0], [20.0, 0.0], [30.0, 0.0], [20.0, 10.0]];
        let edges = vec![edge(0, 1, &nodes), edge(2, 1, &nodes), edge(2, 3, &nodes), edge(2, 4, &nodes)];
        let s = Network { nodes: nodes.clone(), edges }.simplified();
        // Node 1 is interstitial; node 2 is a T-junction.
        assert_eq!(s.nodes, vec![[0.0, 0.0], [20.0, 0.0], [30.0, 0.0], [20.0, 10.0]]);
        assert_eq!(s.edges.len(), 3);
        assert_eq!(s.edges[0].shape, vec![[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]]);
        assert_eq!(s.street_counts(), vec![1, 3, 1, 1]);
    }

    #[test]
    fn a_ring_is_left_out_and_one_way_chains_keep_their_direction() {
        let nodes = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]];
        let ring = vec![edge(0, 1, &nodes), edge(1, 2, &nodes), edge(2, 0, &nodes)];
        let s = Network { nodes: nodes.clone(), edges: ring }.simplified();
        assert_eq!((s.nodes.len(), s.edges.len()), (0, 0));
        // 2 → 1 → 0, one-way, given as 1→0 and 2→1.
        let one = |a: usize, b: usize| Edge { oneway: true, ..edge(a, b, &nodes) };
        let s = Network { nodes: nodes.clone(), edges: vec![one(1, 0), one(2, 1)] }.simplified();
        assert_eq!(s.edges.len(), 1);
        assert_eq!(s.edges[0].shape, vec![[10.0, 10.0], [10.0, 0.0], [0.0, 0.0]]);
        assert!(s.edges[0].oneway);
        // A one-way piece meeting a two-way piece keeps the node.
        let s = Network { nodes: nodes.clone(), edges: vec![one(0, 1), edge(1, 2, &nodes)] }.simplified();
        assert_eq!(s.edges.len(), 2);
    }
}
