//! The level spec: blocks (polygons), a door width, the connectivity graph's nodes and edges.
//! Read from TOML, checked, and resolved to ids.

use super::LevelError;
use crate::geometry::convex;
use crate::geometry::{self, P};
use rustworkx_core::petgraph::graph::{NodeIndex, UnGraph};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::path::Path;

/// A block shape's index in [`Level::blocks`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct BlockId(pub u32);

/// A graph node's index in [`Level::nodes`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct NodeId(pub u32);

/// A graph edge's index in [`Level::edges`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct EdgeId(pub u32);

/// What the exact model minimises.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Objective {
    /// Nothing: any layout (the fastest proofs).
    #[default]
    None,
    /// The bounding box's width plus height.
    Bbox,
}

/// The level file as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LevelSpec {
    /// The door width `w`: every graph edge is a shared wall at least this long.
    pub door_width: f64,
    /// What the exact model minimises (default: nothing).
    #[serde(default)]
    pub objective: Objective,
    /// Block shapes.
    #[serde(default)]
    pub block: Vec<BlockSpec>,
    /// Graph nodes.
    #[serde(default)]
    pub node: Vec<NodeSpec>,
    /// Graph edges.
    #[serde(default)]
    pub edge: Vec<EdgeSpec>,
    /// Obstacles: fixed polygons no block may overlap.
    #[serde(default)]
    pub obstacle: Vec<ObstacleSpec>,
}

/// One obstacle: a polygon in absolute coordinates, fixed in place.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    /// Vertices, counter-clockwise.
    pub polygon: Vec<P>,
}

/// One block shape.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    /// Unique name.
    pub name: String,
    /// Vertices, counter-clockwise.
    pub polygon: Vec<P>,
    /// Rotations (degrees, counter-clockwise about the origin, multiples of 90) that become
    /// variant blocks named `name@angle`, allowed wherever the block is.
    #[serde(default)]
    pub rotations: Vec<i64>,
}

/// One graph node.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSpec {
    /// Unique name.
    pub name: String,
    /// Allowed blocks (every block when omitted).
    pub blocks: Option<Vec<String>>,
    /// A fixed position (the block's own coordinates are translated by it).
    pub position: Option<P>,
}

/// One graph edge.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeSpec {
    /// The two node names.
    pub nodes: [String; 2],
}

/// A checked block shape.
#[derive(Clone, Debug)]
pub struct Block {
    /// Its name.
    pub name: String,
    /// Vertices, counter-clockwise, without collinear repeats.
    pub polygon: Vec<P>,
    /// Convex parts covering it.
    pub parts: Vec<Vec<P>>,
    /// The block it is a rotation of, and the angle in degrees (`None` for a block as given).
    pub rotation_of: Option<(BlockId, i64)>,
}

/// A checked obstacle.
#[derive(Clone, Debug)]
pub struct Obstacle {
    /// Vertices, counter-clockwise, without collinear repeats (absolute coordinates).
    pub polygon: Vec<P>,
    /// Convex parts covering it.
    pub parts: Vec<Vec<P>>,
}

/// A checked node.
#[derive(Clone, Debug)]
pub struct Node {
    /// Its name.
    pub name: String,
    /// Allowed blocks, in block order.
    pub blocks: Vec<BlockId>,
    /// Fixed position, if any.
    pub position: Option<P>,
}

/// A checked level: ids resolved, polygons simple and counter-clockwise, graph connected.
#[derive(Clone, Debug)]
pub struct Level {
    /// Door width.
    pub door_width: f64,
    /// Objective of the exact model.
    pub objective: Objective,
    /// Block shapes.
    pub blocks: Vec<Block>,
    /// Nodes.
    pub nodes: Vec<Node>,
    /// Edges, each `(a, b)` with `a < b`, in file order.
    pub edges: Vec<(NodeId, NodeId)>,
    /// Obstacles, in file order.
    pub obstacles: Vec<Obstacle>,
}

fn field(name: impl Into<String>, reason: impl Into<String>) -> LevelError {
    LevelError::Field { field: name.into(), reason: reason.into() }
}

impl LevelSpec {
    /// Parses TOML text (errors give the parser's line and column).
    pub fn from_toml(text: &str) -> Result<LevelSpec, LevelError> {
        toml::from_str(text).map_err(|e| LevelError::Toml(e.to_string()))
    }

    /// Checks the spec and resolves names to ids.
    pub fn resolve(&self) -> Result<Level, LevelError> {
        let w = self.door_width;
        if !(w > 0.0 && w.is_finite()) {
            return Err(field("door_width", format!("must be a positive number, got {w}")));
        }
        let blocks = self.blocks()?;
        let longest =
            blocks.iter().flat_map(|b| (0..b.polygon.len()).map(|i| edge_len(&b.polygon, i))).fold(0.0, f64::max);
        if w > longest + convex::LEN_TOL {
            return Err(field("door_width", format!("{w} is wider than every wall (the longest is {longest})")));
        }
        let by_name: BTreeMap<&str, BlockId> =
            blocks.iter().enumerate().map(|(i, b)| (b.name.as_str(), BlockId(i as u32))).collect();
        let nodes = self.nodes(&blocks, &by_name)?;
        let edges = self.edges(&nodes)?;
        let obstacles = self.obstacles()?;
        let level = Level { door_width: w, objective: self.objective, blocks, nodes, edges, obstacles };
        level.check_connected()?;
        level.check_fixed_clear()?;
        Ok(level)
    }

    fn obstacles(&self) -> Result<Vec<Obstacle>, LevelError> {
        let mut out = Vec::new();
        for (i, o) in self.obstacle.iter().enumerate() {
            let polygon = checked_polygon(&format!("obstacle[{i}].polygon"), &o.polygon)?;
            let parts = convex::convex_parts(&polygon);
            out.push(Obstacle { polygon, parts });
        }
        Ok(out)
    }

    fn blocks(&self) -> Result<Vec<Block>, LevelError> {
        if self.block.is_empty() {
            return Err(field("block", "give at least one [[block]]"));
        }
        let mut seen = BTreeSet::new();
        let mut seen_variant = BTreeSet::new();
        let mut out: Vec<Block> = Vec::new();
        for (i, b) in self.block.iter().enumerate() {
            let at = format!("block[{i}] ({:?})", b.name);
            if !seen.insert(b.name.as_str()) {
                return Err(field(format!("{at}.name"), "duplicate block name"));
            }
            let poly = checked_polygon(&format!("{at}.polygon"), &b.polygon)?;
            let base = BlockId(out.len() as u32);
            let angles = rotations(&format!("{at}.rotations"), &b.rotations)?;
            let parts = convex::convex_parts(&poly);
            out.push(Block { name: b.name.clone(), polygon: poly.clone(), parts, rotation_of: None });
            for a in angles {
                let name = format!("{}@{a}", b.name);
                if !seen_variant.insert(name.clone()) {
                    return Err(field(format!("{at}.rotations"), format!("variant name {name:?} is taken")));
                }
                let polygon: Vec<P> = poly.iter().map(|&p| rotate(p, a)).collect();
                let parts = convex::convex_parts(&polygon);
                out.push(Block { name, polygon, parts, rotation_of: Some((base, a)) });
            }
        }
        if let Some(b) = out.iter().find(|b| b.rotation_of.is_some() && seen.contains(b.name.as_str())) {
            return Err(field("block", format!("variant name {:?} is also a block's name", b.name)));
        }
        Ok(out)
    }

    fn nodes(&self, blocks: &[Block], by_name: &BTreeMap<&str, BlockId>) -> Result<Vec<Node>, LevelError> {
        if self.node.is_empty() {
            return Err(field("node", "give at least one [[node]]"));
        }
        let mut seen = BTreeSet::new();
        let mut out = Vec::new();
        for (i, n) in self.node.iter().enumerate() {
            let at = format!("node[{i}] ({:?})", n.name);
            if !seen.insert(n.name.as_str()) {
                return Err(field(format!("{at}.name"), "duplicate node name"));
            }
            let blocks = match &n.blocks {
                None => (0..by_name.len() as u32).map(BlockId).collect(),
                Some(names) => {
                    let mut ids = BTreeSet::new();
                    for name in names {
                        let id = by_name
                            .get(name.as_str())
                            .ok_or_else(|| field(format!("{at}.blocks"), format!("no block named {name:?}")))?;
                        ids.insert(*id);
                        // A block brings its rotations.
                        let variants =
                            blocks.iter().enumerate().filter(|(_, b)| b.rotation_of.is_some_and(|r| r.0 == *id));
                        ids.extend(variants.map(|(k, _)| BlockId(k as u32)));
                    }
                    if ids.is_empty() {
                        return Err(field(format!("{at}.blocks"), "allow at least one block"));
                    }
                    ids.into_iter().collect()
                }
            };
            if n.position.is_some_and(|p| p.iter().any(|v| !v.is_finite())) {
                return Err(field(format!("{at}.position"), "coordinates must be finite"));
            }
            out.push(Node { name: n.name.clone(), blocks, position: n.position });
        }
        Ok(out)
    }

    fn edges(&self, nodes: &[Node]) -> Result<Vec<(NodeId, NodeId)>, LevelError> {
        let by_name: BTreeMap<&str, NodeId> =
            nodes.iter().enumerate().map(|(i, n)| (n.name.as_str(), NodeId(i as u32))).collect();
        let mut seen = BTreeSet::new();
        let mut out = Vec::new();
        for (i, e) in self.edge.iter().enumerate() {
            let at = format!("edge[{i}].nodes");
            let id = |name: &String| {
                by_name.get(name.as_str()).copied().ok_or_else(|| field(&at, format!("no node named {name:?}")))
            };
            let (a, b) = (id(&e.nodes[0])?, id(&e.nodes[1])?);
            if a == b {
                return Err(field(&at, "an edge joins two different nodes"));
            }
            let key = (a.min(b), a.max(b));
            if !seen.insert(key) {
                return Err(field(&at, "duplicate edge"));
            }
            out.push(key);
        }
        Ok(out)
    }
}

/// A polygon checked where read: finite, at least three non-collinear vertices, simple,
/// counter-clockwise; returned without collinear repeats.
fn checked_polygon(at: &str, polygon: &[P]) -> Result<Vec<P>, LevelError> {
    if polygon.iter().flatten().any(|v| !v.is_finite()) {
        return Err(field(at, "coordinates must be finite"));
    }
    let poly = convex::simplify(polygon);
    if poly.len() < 3 {
        return Err(field(at, "needs at least three non-collinear vertices"));
    }
    if let Some((e, f)) = convex::self_intersection(&poly) {
        return Err(field(at, format!("self-intersecting: edges {e} and {f} meet")));
    }
    if geometry::signed_area(&poly) <= 0.0 {
        return Err(field(at, "must be counter-clockwise (its signed area is negative)"));
    }
    Ok(poly)
}

/// The angles of a block's rotations, normalised to 90, 180 or 270, in the order given.
fn rotations(at: &str, angles: &[i64]) -> Result<Vec<i64>, LevelError> {
    let mut out = Vec::new();
    for &a in angles {
        let r = a.rem_euclid(360);
        if a % 90 != 0 {
            return Err(field(at, format!("{a} is not a multiple of 90 degrees")));
        }
        if r == 0 {
            return Err(field(at, format!("{a} degrees is the block itself")));
        }
        if out.contains(&r) {
            return Err(field(at, format!("{a} degrees is given twice")));
        }
        out.push(r);
    }
    Ok(out)
}

/// `p` rotated counter-clockwise about the origin by a multiple of 90 degrees (exact).
pub fn rotate(p: P, degrees: i64) -> P {
    match degrees.rem_euclid(360) {
        90 => [-p[1], p[0]],
        180 => [-p[0], -p[1]],
        270 => [p[1], -p[0]],
        _ => p,
    }
}

/// Length of edge `i` (from vertex `i`).
pub fn edge_len(poly: &[P], i: usize) -> f64 {
    convex::length(geometry::sub(poly[(i + 1) % poly.len()], poly[i]))
}

impl Level {
    /// Reads, parses and checks a level file; errors name the file.
    pub fn read(path: &Path) -> Result<Level, LevelError> {
        let name = path.display().to_string();
        let text =
            std::fs::read_to_string(path).map_err(|e| LevelError::Io { path: name.clone(), reason: e.to_string() })?;
        Self::from_toml(&text).map_err(|e| LevelError::InFile { path: name, source: Box::new(e) })
    }

    /// Parses and checks TOML text.
    pub fn from_toml(text: &str) -> Result<Level, LevelError> {
        LevelSpec::from_toml(text)?.resolve()
    }

    /// The name of a node.
    pub fn node_name(&self, n: NodeId) -> &str {
        &self.nodes[n.0 as usize].name
    }

    /// Neighbours of every node through the given edges, sorted.
    pub fn adjacency(&self, edges: &[EdgeId]) -> Vec<Vec<NodeId>> {
        let mut adj = vec![Vec::new(); self.nodes.len()];
        for e in edges {
            let (a, b) = self.edges[e.0 as usize];
            adj[a.0 as usize].push(b);
            adj[b.0 as usize].push(a);
        }
        for a in &mut adj {
            a.sort();
        }
        adj
    }

    /// Every edge id.
    pub fn all_edges(&self) -> Vec<EdgeId> {
        (0..self.edges.len() as u32).map(EdgeId).collect()
    }

    /// Hop distances from `from` through `edges` (`usize::MAX` when unreachable).
    pub fn hops(&self, from: NodeId, edges: &[EdgeId]) -> Vec<usize> {
        let adj = self.adjacency(edges);
        let mut d = vec![usize::MAX; self.nodes.len()];
        d[from.0 as usize] = 0;
        let mut q = VecDeque::from([from]);
        while let Some(u) = q.pop_front() {
            for &v in &adj[u.0 as usize] {
                if d[v.0 as usize] == usize::MAX {
                    d[v.0 as usize] = d[u.0 as usize] + 1;
                    q.push_back(v);
                }
            }
        }
        d
    }

    fn check_connected(&self) -> Result<(), LevelError> {
        let d = self.hops(NodeId(0), &self.all_edges());
        match d.iter().position(|&x| x == usize::MAX) {
            Some(i) => Err(field(
                "edge",
                format!(
                    "the graph must be connected: node {:?} is not reachable from {:?}",
                    self.nodes[i].name, self.nodes[0].name
                ),
            )),
            None => Ok(()),
        }
    }

    /// Whether some node has a fixed position (obstacles matter only then: otherwise a layout
    /// can be moved clear of them).
    pub fn has_fixed(&self) -> bool {
        self.nodes.iter().any(|n| n.position.is_some())
    }

    /// Each fixed node must have an allowed block that clears every obstacle at its position;
    /// the error names the first obstacle in the way.
    fn check_fixed_clear(&self) -> Result<(), LevelError> {
        if self.obstacles.is_empty() {
            return Ok(());
        }
        let tris: Vec<Vec<[P; 3]>> = self.obstacles.iter().map(|o| convex::triangulate(&o.polygon)).collect();
        for n in &self.nodes {
            let Some(p) = n.position else { continue };
            let first_hit = |b: &BlockId| {
                let placed = convex::triangulate(&convex::translate(&self.blocks[b.0 as usize].polygon, p));
                tris.iter().position(|t| convex::overlap_area(&placed, t) > convex::AREA_TOL)
            };
            let hits: Vec<Option<usize>> = n.blocks.iter().map(first_hit).collect();
            if let Some(Some(k)) = hits.iter().all(Option::is_some).then(|| hits[0]) {
                return Err(field(
                    format!("obstacle[{k}].polygon"),
                    format!("overlaps node {:?} at its fixed position whatever block it takes", n.name),
                ));
            }
        }
        Ok(())
    }

    /// Whether the graph is planar (the left-right planarity test of `rustworkx-core`).
    pub fn is_planar(&self) -> bool {
        let mut g = UnGraph::<(), ()>::with_capacity(self.nodes.len(), self.edges.len());
        let ids: Vec<NodeIndex> = self.nodes.iter().map(|_| g.add_node(())).collect();
        for &(a, b) in &self.edges {
            g.add_edge(ids[a.0 as usize], ids[b.0 as usize], ());
        }
        rustworkx_core::planar::is_planar(&g)
    }
}

/// The shortest cycle through edge `a`–`b` (its nodes), if the edge is on one.
pub fn shortest_cycle(adj: &[Vec<NodeId>], a: NodeId, b: NodeId) -> Option<Vec<NodeId>> {
    let mut prev: Vec<Option<NodeId>> = vec![None; adj.len()];
    prev[b.0 as usize] = Some(b);
    let mut q = VecDeque::from([b]);
    while let Some(u) = q.pop_front() {
        for &v in &adj[u.0 as usize] {
            if (u == b && v == a) || prev[v.0 as usize].is_some() {
                continue;
            }
            prev[v.0 as usize] = Some(u);
            if v == a {
                let mut path = vec![a];
                let mut x = a;
                while x != b {
                    x = prev[x.0 as usize]?;
                    path.push(x);
                }
                return Some(path);
            }
            q.push_back(v);
        }
    }
    None
}
