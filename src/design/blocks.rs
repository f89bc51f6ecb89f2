//! The block connectivity graph of a game level (paper §5.3): blocks are adjacent when the
//! network passes between them through a shared vertex. Written as JSON and GraphViz DOT, and
//! classified as a tree, a cycle or a path to check against the requested level type.

use super::Network;
use crate::mesh::VertexId;
use crate::rules::placements::Placement;
use crate::spec::Problem;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::fmt::Write;

/// The shape of a connectivity graph.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GraphShape {
    /// A simple path (every node degree ≤ 2, connected, acyclic).
    Path,
    /// A single cycle (every node degree 2, connected).
    Cycle,
    /// A tree that is not a path.
    Tree,
    /// Connected, with cycles, not a single cycle.
    Cyclic,
    /// More than one component.
    Disconnected,
    /// No blocks.
    Empty,
}

/// The block connectivity graph.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BlockGraph {
    /// Nodes: the chosen placements' indices, with their template names.
    pub nodes: Vec<(usize, String)>,
    /// Edges between node positions (i < j), with a shared vertex the network passes through.
    pub edges: Vec<(usize, usize, VertexId)>,
    /// Its shape.
    pub shape: GraphShape,
}

/// Builds the graph: two chosen blocks are adjacent when they share a vertex that has an active
/// edge inside each of them (the network goes from one block into the other there).
pub fn block_graph(p: &Problem, net: &Network, placements: &[Placement]) -> BlockGraph {
    let mesh = &p.mesh;
    let names = |t: usize| p.rooms.as_ref().map_or(String::new(), |r| r.templates[t].name.clone());
    let nodes: Vec<(usize, String)> = net.rooms.iter().map(|&k| (k, names(placements[k].template))).collect();
    // Vertices touched by an active inner edge of each block.
    let entered: Vec<BTreeSet<VertexId>> = net
        .rooms
        .iter()
        .map(|&k| {
            let mut s = BTreeSet::new();
            for e in placements[k].inner_edges.iter().filter(|e| net.active[e.index()]) {
                let (a, b) = mesh.edge_vertices(*e);
                s.insert(a);
                s.insert(b);
            }
            s
        })
        .collect();
    let mut edges = Vec::new();
    for i in 0..nodes.len() {
        for j in i + 1..nodes.len() {
            if let Some(&v) = entered[i].intersection(&entered[j]).next() {
                edges.push((i, j, v));
            }
        }
    }
    let shape = classify(nodes.len(), &edges);
    BlockGraph { nodes, edges, shape }
}

fn classify(n: usize, edges: &[(usize, usize, VertexId)]) -> GraphShape {
    if n == 0 {
        return GraphShape::Empty;
    }
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], x: usize) -> usize {
        let mut r = x;
        while p[r] != r {
            r = p[r];
        }
        p[x] = r;
        r
    }
    let mut deg = vec![0usize; n];
    for &(a, b, _) in edges {
        deg[a] += 1;
        deg[b] += 1;
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        parent[ra] = rb;
    }
    let roots = (0..n).filter(|&x| find(&mut parent, x) == x).count();
    if roots > 1 {
        return GraphShape::Disconnected;
    }
    let m = edges.len();
    match (m + 1 == n, deg.iter().all(|&d| d <= 2)) {
        (true, true) => GraphShape::Path,
        (true, false) => GraphShape::Tree,
        (false, _) if m == n && deg.iter().all(|&d| d == 2) => GraphShape::Cycle,
        _ => GraphShape::Cyclic,
    }
}

impl BlockGraph {
    /// GraphViz DOT text.
    pub fn to_dot(&self, name: &str) -> String {
        let mut s = format!("graph \"{}\" {{\n  node [shape=box];\n", name.replace('"', "'"));
        for (i, (k, t)) in self.nodes.iter().enumerate() {
            let _ = writeln!(s, "  b{i} [label=\"{} #{k}\"];", t.replace('"', "'"));
        }
        for (a, b, v) in &self.edges {
            let _ = writeln!(s, "  b{a} -- b{b} [label=\"v{}\"];", v.0);
        }
        s.push_str("}\n");
        s
    }
}
