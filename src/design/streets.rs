//! A design's streets: the network split into chains between junctions (the paper's snakes,
//! which `urban::smooth` smooths), and streets as GeoJSON in WGS 84.

use crate::geometry::dist;
use crate::geometry::geojson::GeoJsonWriter;
use crate::geometry::site::{Projection, SiteError};
use crate::mesh::Mesh;
use serde::{Deserialize, Serialize};
use serde_json::json;
use std::collections::BTreeSet;

/// Where a GeoJSON's origin sits when nothing anchors it: `[longitude, latitude]` `[0, 0]`.
pub const DEFAULT_GEO_ORIGIN: [f64; 2] = [0.0, 0.0];

/// The level of a `solve` design's streets in its GeoJSON and in a traffic evaluation: local
/// streets.
pub const DEFAULT_SOLVE_LEVEL: u8 = 3;

/// A street network drawn on a mesh: positions and undirected edges with a level (1 = major
/// roads, 2 = collector, 3 = local, 4 = cul-de-sacs).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StreetGraph {
    /// Vertex positions.
    pub positions: Vec<[f64; 2]>,
    /// Undirected edges. Self-loops and edges with unknown vertices are ignored; of duplicate
    /// edges (either orientation) only the first is kept.
    pub edges: Vec<StreetEdge>,
}

/// One street segment between two vertices of a [`StreetGraph`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct StreetEdge {
    /// One end.
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// Hierarchy level (1 = major road … 4 = cul-de-sac).
    pub level: u8,
}

/// A snake: a chain of edges of one level whose interior vertices have valence 2.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Snake {
    /// Level of all its edges.
    pub level: u8,
    /// Graph vertices along the chain, in order; closed loops repeat the first at the end.
    pub vertices: Vec<u32>,
    /// An isolated cycle (every vertex of valence 2, one level): only its first vertex is fixed.
    /// A loop hanging from a junction is an open snake whose two ends coincide.
    pub closed: bool,
    /// The polyline, starting and ending at the chain's end vertices: from [`decompose`] the
    /// vertex positions, from `urban::smooth` the subdivided, smoothed points.
    pub points: Vec<[f64; 2]>,
}

/// Deduplicated edges `(a, b, level)` in order of first occurrence, and adjacency lists
/// `(edge, other end)` in edge order.
pub(crate) struct Topology {
    pub(crate) edges: Vec<(u32, u32, u8)>,
    pub(crate) adj: Vec<Vec<(usize, u32)>>,
}

impl Topology {
    pub(crate) fn new(g: &StreetGraph) -> Self {
        let n = g.positions.len();
        let mut seen = BTreeSet::new();
        let mut edges = Vec::new();
        let mut adj = vec![Vec::new(); n];
        for e in &g.edges {
            let (a, b) = (e.a as usize, e.b as usize);
            if a == b || a >= n || b >= n || !seen.insert((a.min(b), a.max(b))) {
                continue;
            }
            adj[a].push((edges.len(), e.b));
            adj[b].push((edges.len(), e.a));
            edges.push((e.a, e.b, e.level));
        }
        Topology { edges, adj }
    }

    /// A chain cannot pass through `v`: valence ≠ 2, or a level change.
    pub(crate) fn is_break(&self, v: u32) -> bool {
        let adj = &self.adj[v as usize];
        adj.len() != 2 || self.edges[adj[0].0].2 != self.edges[adj[1].0].2
    }

    /// The vertices after `from` along edge `via` up to a break (or an already used edge).
    pub(crate) fn walk(&self, used: &mut [bool], from: u32, via: usize) -> Vec<u32> {
        let (a, b, _) = self.edges[via];
        let (mut cur, mut e) = (if a == from { b } else { a }, via);
        let mut out = vec![cur];
        while !self.is_break(cur) {
            let &(next, other) = self.adj[cur as usize].iter().find(|&&(x, _)| x != e).unwrap();
            if used[next] {
                break;
            }
            used[next] = true;
            (cur, e) = (other, next);
            out.push(cur);
        }
        out
    }

    /// Mean edge length, or 1 if that is not a positive number.
    pub(crate) fn length_scale(&self, g: &StreetGraph) -> f64 {
        let total: f64 =
            self.edges.iter().map(|&(a, b, _)| dist(g.positions[a as usize], g.positions[b as usize])).sum();
        let l = total / self.edges.len().max(1) as f64;
        if l.is_finite() && l > 0.0 {
            l
        } else {
            1.0
        }
    }
}

/// Splits the network into snakes (paper appendix): maximal chains between vertices of valence
/// ≠ 2, also split where the level changes at a valence-2 vertex; isolated cycles of one level
/// become one closed snake starting at their lowest vertex id. Every (deduplicated) edge lies in
/// exactly one snake. Snakes are ordered by their lowest edge index; an open snake runs from its
/// lower end vertex id to the higher. `points` are the vertex positions.
pub fn decompose(g: &StreetGraph) -> Vec<Snake> {
    chains(g, &Topology::new(g))
}

pub(crate) fn chains(g: &StreetGraph, t: &Topology) -> Vec<Snake> {
    let mut used = vec![false; t.edges.len()];
    let mut snakes = Vec::new();
    for e0 in 0..t.edges.len() {
        if used[e0] {
            continue;
        }
        used[e0] = true;
        let (a, b, level) = t.edges[e0];
        let fwd = t.walk(&mut used, a, e0);
        let bwd = t.walk(&mut used, b, e0);
        let mut vs: Vec<u32> = bwd.into_iter().rev().chain(fwd).collect();
        let n = vs.len();
        let closed = vs[0] == vs[n - 1] && !t.is_break(vs[0]);
        if closed {
            vs.pop();
            let start = (0..vs.len()).min_by_key(|&i| vs[i]).unwrap();
            vs.rotate_left(start);
            if vs[1] > vs[vs.len() - 1] {
                vs[1..].reverse();
            }
            vs.push(vs[0]);
        } else if vs[0] > vs[n - 1] || (vs[0] == vs[n - 1] && vs[1] > vs[n - 2]) {
            vs.reverse();
        }
        let points = vs.iter().map(|&v| g.positions[v as usize]).collect();
        snakes.push(Snake { level, vertices: vs, closed, points });
    }
    snakes
}

/// Where GeoJSON's model coordinates sit on the Earth: the WGS 84 `[longitude, latitude]` of
/// the model origin, and metres per model unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeoAnchor {
    /// The model origin's `[longitude, latitude]`.
    pub origin: [f64; 2],
    /// The origin is [`DEFAULT_GEO_ORIGIN`], not a given anchor.
    pub origin_is_default: bool,
    /// Metres per model unit.
    pub metres_per_unit: f64,
}

impl GeoAnchor {
    /// Model units as metres from [`DEFAULT_GEO_ORIGIN`] (a design spec has no
    /// scale).
    pub fn model_units() -> GeoAnchor {
        GeoAnchor { origin: DEFAULT_GEO_ORIGIN, origin_is_default: true, metres_per_unit: 1.0 }
    }

    /// The projection of this anchor: the one transverse Mercator of every netspec file
    /// ([`Projection`]) centred on `origin`; a model point is `metres_per_unit` metres per unit
    /// from it ([`GeoJsonWriter::scaled`]).
    pub fn projection(&self) -> Result<Projection, SiteError> {
        Projection::new(self.origin)
    }
}

/// A sub-region as a GeoJSON polygon feature.
#[derive(Clone, Debug, PartialEq)]
pub struct GeoRegion {
    /// Its index.
    pub index: usize,
    /// Its name.
    pub name: String,
    /// The outer ring (not closed).
    pub outer: Vec<[f64; 2]>,
    /// Holes (not closed).
    pub holes: Vec<Vec<[f64; 2]>>,
    /// One line per level (`L2: solved`).
    pub levels: Vec<String>,
}

/// Streets as GeoJSON (RFC 7946), always WGS 84 longitude and latitude through the anchor's
/// projection ([`GeoAnchor::projection`], written by [`GeoJsonWriter`]): the sub-regions (none
/// for a single design), level 1 (`major`, the major roads and the domain boundary, as given) as
/// one multi-line, then every street (a polyline with its level); the collection's `properties`
/// say which origin and scale were used.
pub fn streets_geojson(
    name: &str,
    anchor: &GeoAnchor,
    regions: &[GeoRegion],
    major: &[[[f64; 2]; 2]],
    streets: &[Snake],
) -> Result<String, SiteError> {
    let proj = anchor.projection()?;
    let mut w = GeoJsonWriter::new(&proj).scaled(anchor.metres_per_unit);
    for r in regions {
        let rings = std::iter::once(r.outer.as_slice()).chain(r.holes.iter().map(Vec::as_slice));
        w.polygon(rings, json!({ "kind": "sub-region", "index": r.index, "name": r.name, "levels": r.levels }))?;
    }
    w.lines(
        major.iter().map(|seg| &seg[..]),
        json!({ "kind": "street", "level": 1, "closed": false, "note": "major roads and the domain boundary, as given" }),
    )?;
    for s in streets {
        w.line(&s.points, json!({ "kind": "street", "level": s.level, "closed": s.closed }))?;
    }
    Ok(w.to_json(json!({
        "name": name,
        "properties": {
            "crs": "WGS 84 longitude, latitude (RFC 7946)",
            "projection": "transverse Mercator centred on geo_origin",
            "geo_origin": anchor.origin,
            "geo_origin_is_default": anchor.origin_is_default,
            "metres_per_unit": anchor.metres_per_unit,
        },
    })))
}

/// The GeoJSON of a `solve` design ([`streets_geojson`]): its active edges as streets of
/// `level`, in chains between junctions and ends, and the mesh boundary as the domain boundary.
/// A spec has no scale, so coordinates are model units as metres from the default origin
/// ([`GeoAnchor::model_units`]).
pub fn design_geojson(mesh: &Mesh, active_edges: &[[u32; 2]], name: &str, level: u8) -> Result<String, SiteError> {
    let edges = active_edges.iter().map(|&[a, b]| StreetEdge { a, b, level }).collect();
    let graph = StreetGraph { positions: mesh.positions().to_vec(), edges };
    let snakes = decompose(&graph);
    let boundary: Vec<[[f64; 2]; 2]> = mesh
        .boundary_edges()
        .into_iter()
        .map(|e| {
            let (a, b) = mesh.edge_vertices(e);
            [mesh.position(a), mesh.position(b)]
        })
        .collect();
    streets_geojson(name, &GeoAnchor::model_units(), &[], &boundary, &snakes)
}
