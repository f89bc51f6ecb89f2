//! Small subgraphs whose infeasibility proves a level infeasible: a layout of the level lays
//! out every induced subgraph (its nodes, the edges among them), so one subgraph without a
//! layout is a proof for the whole level, found at the cost of a small model.
//!
//! Candidates, smallest first: the shortest cycle through each edge, each node's closed
//! neighbourhood (the node, its neighbours), the biconnected components up to a size cap; each
//! as the subgraph its nodes induce, without repeats.

use super::super::spec::{shortest_cycle, Level, NodeId};
use serde::Serialize;
use std::collections::BTreeSet;

/// Where a candidate comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Origin {
    /// The shortest cycle through an edge.
    Cycle,
    /// A node and its neighbours.
    Neighbourhood,
    /// A biconnected component.
    Block,
}

/// A candidate subgraph: the nodes (ascending) whose induced subgraph is checked.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Candidate {
    /// Nodes, ascending.
    pub nodes: Vec<NodeId>,
    /// Edges among them.
    pub edges: usize,
    /// Where it comes from (the first origin that gave this node set).
    pub origin: Origin,
}

/// Node sets of the biconnected components (Hopcroft–Tarjan, iterative), each ascending; a
/// bridge is a component of two nodes.
pub fn biconnected_components(adj: &[Vec<NodeId>]) -> Vec<Vec<NodeId>> {
    let n = adj.len();
    let (mut disc, mut low) = (vec![usize::MAX; n], vec![0; n]);
    let mut out = Vec::new();
    let mut edges: Vec<(usize, usize)> = Vec::new();
    let mut time = 0;
    for root in 0..n {
        if disc[root] != usize::MAX {
            continue;
        }
        disc[root] = time;
        low[root] = time;
        time += 1;
        // (node, parent, next neighbour index)
        let mut stack: Vec<(usize, usize, usize)> = vec![(root, usize::MAX, 0)];
        while let Some(top) = stack.last_mut() {
            let (u, parent) = (top.0, top.1);
            if top.2 < adj[u].len() {
                let v = adj[u][top.2].0 as usize;
                top.2 += 1;
                if disc[v] == usize::MAX {
                    edges.push((u, v));
                    disc[v] = time;
                    low[v] = time;
                    time += 1;
                    stack.push((v, u, 0));
                } else if v != parent && disc[v] < disc[u] {
                    edges.push((u, v));
                    low[u] = low[u].min(disc[v]);
                }
                continue;
            }
            stack.pop();
            if parent == usize::MAX {
                continue;
            }
            low[parent] = low[parent].min(low[u]);
            if low[u] >= disc[parent] {
                let mut comp = BTreeSet::new();
                while let Some((x, y)) = edges.pop() {
                    comp.insert(x);
                    comp.insert(y);
                    if (x, y) == (parent, u) {
                        break;
                    }
                }
                out.push(comp.into_iter().map(|i| NodeId(i as u32)).collect());
            }
        }
    }
    out
}

/// Candidate subgraphs of `level`, smallest first (fewest nodes, then most edges, then origin
/// and nodes),
/// each node set once; sets of fewer than three nodes, of every node, and blocks of more than
/// `block_cap` nodes are left out (two nodes and an edge have a layout unless fixed nodes
/// forbid it, and the whole level is the whole model's to solve).
pub fn candidates(level: &Level, block_cap: usize) -> Vec<Candidate> {
    let adj = level.adjacency(&level.all_edges());
    let mut sets: Vec<(Vec<NodeId>, Origin)> = Vec::new();
    for &(a, b) in &level.edges {
        if let Some(c) = shortest_cycle(&adj, a, b) {
            sets.push((c, Origin::Cycle));
        }
    }
    for (i, nb) in adj.iter().enumerate() {
        let mut s = nb.clone();
        s.push(NodeId(i as u32));
        sets.push((s, Origin::Neighbourhood));
    }
    for c in biconnected_components(&adj) {
        if c.len() <= block_cap {
            sets.push((c, Origin::Block));
        }
    }
    let mut seen = BTreeSet::new();
    let mut out = Vec::new();
    for (mut nodes, origin) in sets {
        nodes.sort();
        nodes.dedup();
        if nodes.len() < 3 || nodes.len() >= level.nodes.len() || !seen.insert(nodes.clone()) {
            continue;
        }
        let edges = level
            .edges
            .iter()
            .filter(|(a, b)| nodes.binary_search(a).is_ok() && nodes.binary_search(b).is_ok())
            .count();
        out.push(Candidate { nodes, edges, origin });
    }
    // Fewest nodes first; among as many nodes, most edges first (the most constrained).
    let key = |c: &Candidate| (c.nodes.len(), std::cmp::Reverse(c.edges), c.origin, c.nodes.clone());
    out.sort_by_key(key);
    out
}

/// Candidates of at most this many nodes get a canonical form ([`shape`]).
pub const SHAPE_MAX_NODES: usize = 7;

/// The candidate's shape up to relabelling, when it has at most [`SHAPE_MAX_NODES`] nodes and
/// none of them is fixed: the least, over node orders, of the allowed blocks per node and the
/// adjacency matrix. Two candidates of one shape are the same level up to names (translations
/// aside), so one answer serves both.
pub fn shape(level: &Level, nodes: &[NodeId]) -> Option<Vec<u32>> {
    let n = nodes.len();
    if n > SHAPE_MAX_NODES || nodes.iter().any(|v| level.nodes[v.0 as usize].position.is_some()) {
        return None;
    }
    let mut adj = vec![vec![false; n]; n];
    for &(a, b) in &level.edges {
        if let (Ok(i), Ok(j)) = (nodes.binary_search(&a), nodes.binary_search(&b)) {
            adj[i][j] = true;
            adj[j][i] = true;
        }
    }
    let code = |order: &[usize]| -> Vec<u32> {
        let mut c: Vec<u32> = Vec::new();
        for &i in order {
            let blocks = &level.nodes[nodes[i].0 as usize].blocks;
            c.push(blocks.len() as u32);
            c.extend(blocks.iter().map(|b| b.0));
        }
        for (x, &i) in order.iter().enumerate() {
            for &j in &order[x + 1..] {
                c.push(u32::from(adj[i][j]));
            }
        }
        c
    };
    let mut order: Vec<usize> = (0..n).collect();
    let mut best = code(&order);
    // Heap's algorithm over every order.
    let mut k = vec![0usize; n];
    let mut i = 1;
    while i < n {
        if k[i] < i {
            order.swap(if i % 2 == 0 { 0 } else { k[i] }, i);
            best = best.min(code(&order));
            k[i] += 1;
            i = 1;
        } else {
            k[i] = 0;
            i += 1;
        }
    }
    best.push(n as u32);
    Some(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::generate::Generated;

    fn ids(v: &[u32]) -> Vec<NodeId> {
        v.iter().map(|&i| NodeId(i)).collect()
    }

    #[test]
    fn the_triangle_of_a_grid_comes_first() {
        let level = Generated::parse("grid:4x4+triangle").unwrap().level(0.55).unwrap();
        let c = candidates(&level, 12);
        // r0c0, r0c1, r1c1 are nodes 0, 1, 5.
        assert_eq!(c[0].nodes, ids(&[0, 1, 5]));
        assert_eq!((c[0].edges, c[0].origin), (3, Origin::Cycle));
        // The other triangle (r0c0, r1c0, r1c1), paths of three, then sets of four, the grid's
        // squares among them.
        assert_eq!(c[1].nodes, ids(&[0, 4, 5]));
        assert!(c.windows(2).all(|w| w[0].nodes.len() <= w[1].nodes.len()));
        let squares = c.iter().filter(|x| x.nodes.len() == 4 && x.edges == 4 && x.origin == Origin::Cycle).count();
        assert_eq!(squares, 8, "nine squares, the one with the diagonal split into triangles: {c:?}");
        let mut sets: Vec<&Vec<NodeId>> = c.iter().map(|x| &x.nodes).collect();
        sets.sort();
        sets.dedup();
        assert_eq!(sets.len(), c.len(), "no node set twice");
        // The whole grid is one block: left to the whole model.
        assert!(c.iter().all(|x| x.nodes.len() < 16));
    }

    #[test]
    fn stars_give_their_hub_neighbourhood_and_paths_nothing() {
        // A 5-leaf star with a tail on leaf 5: the hub's neighbourhood (6 nodes, 5 edges) and
        // leaf 5's (3 nodes).
        let mut t =
            String::from("door_width = 0.6\n[[block]]\nname = \"s\"\npolygon = [[0, 0], [1, 0], [1, 1], [0, 1]]\n");
        for i in 0..7 {
            t += &format!("[[node]]\nname = \"n{i}\"\n");
        }
        for (a, b) in [(0, 1), (0, 2), (0, 3), (0, 4), (0, 5), (5, 6)] {
            t += &format!("[[edge]]\nnodes = [\"n{a}\", \"n{b}\"]\n");
        }
        let level = Level::from_toml(&t).unwrap();
        let c = candidates(&level, 12);
        let got: Vec<(Vec<NodeId>, Origin)> = c.iter().map(|x| (x.nodes.clone(), x.origin)).collect();
        assert_eq!(
            got,
            vec![(ids(&[0, 5, 6]), Origin::Neighbourhood), (ids(&[0, 1, 2, 3, 4, 5]), Origin::Neighbourhood)]
        );
        let path = Generated::parse("path:6").unwrap().level(0.5).unwrap();
        assert!(candidates(&path, 12).iter().all(|x| x.nodes.len() == 3 && x.edges == 2));
    }

    #[test]
    fn shapes_match_up_to_relabelling() {
        let level = Generated::parse("grid:4x4").unwrap().level(0.5).unwrap();
        // Two squares of the grid, and two 3-paths, one bent the other way.
        let sq = |v: &[u32]| shape(&level, &ids(v)).unwrap();
        assert_eq!(sq(&[0, 1, 4, 5]), sq(&[10, 11, 14, 15]));
        assert_eq!(sq(&[0, 1, 2]), sq(&[1, 5, 9]));
        assert_ne!(sq(&[0, 1, 2]), sq(&[0, 1, 4, 5]));
        assert_ne!(sq(&[0, 1, 5]), sq(&[0, 1, 4, 5]));
        // A path of three and three nodes of which only two are joined differ.
        assert_ne!(sq(&[0, 1, 2]), sq(&[0, 1, 3]));
    }

    #[test]
    fn biconnected_components_of_two_cycles_and_a_bridge() {
        // Triangle 0-1-2, bridge 2-3, square 3-4-5-6.
        let edges = [(0, 1), (1, 2), (0, 2), (2, 3), (3, 4), (4, 5), (5, 6), (3, 6)];
        let mut adj = vec![Vec::new(); 7];
        for (a, b) in edges {
            adj[a].push(NodeId(b as u32));
            adj[b].push(NodeId(a as u32));
        }
        let mut comps = biconnected_components(&adj);
        comps.sort();
        assert_eq!(comps, vec![ids(&[0, 1, 2]), ids(&[2, 3]), ids(&[3, 4, 5, 6])]);
        assert_eq!(shortest_cycle(&adj, NodeId(3), NodeId(4)).map(|c| c.len()), Some(4));
        assert_eq!(shortest_cycle(&adj, NodeId(2), NodeId(3)), None);
    }
}
