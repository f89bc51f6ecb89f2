//! Planar straight-line graphs, their faces, and the arrangement of a city's major roads.
//!
//! [`PlanarGraph::from_segments`] turns a soup of segments into a planar graph (split at every
//! crossing, touch and overlap, snapped within a tolerance); [`PlanarGraph::faces`] traces its
//! faces with a rotation system, nesting disconnected components as holes; [`arrangement`]
//! splits a city domain into the sub-regions bounded by the domain boundary and the major roads.
//!
//! All outputs are deterministic: vertices are numbered in lexicographic (x, then y) order of
//! their positions, edges are sorted, and no hash-map iteration order leaks into a result.

use super::{closest_on_segment, dist, projection_param, proper_crossing, ring_contains, signed_area, sub, P};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap};

/// Distance from `p` to the segment `a b`.
fn seg_dist(p: P, a: P, b: P) -> f64 {
    dist(p, closest_on_segment(p, a, b).0)
}
/// Distance between two segments (0 if they cross).
fn seg_seg_dist(a: [P; 2], b: [P; 2]) -> f64 {
    if proper_crossing(a[0], a[1], b[0], b[1]).is_some() {
        return 0.0;
    }
    let d = [seg_dist(a[0], b[0], b[1]), seg_dist(a[1], b[0], b[1])];
    let e = [seg_dist(b[0], a[0], a[1]), seg_dist(b[1], a[0], a[1])];
    d[0].min(d[1]).min(e[0]).min(e[1])
}
fn finite(p: P) -> bool {
    p[0].is_finite() && p[1].is_finite()
}
/// Lexicographic (x, then y) order; `-0.0` is normalised to `0.0` by the callers.
fn cmp_xy(a: P, b: P) -> std::cmp::Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}
/// Lowest-left order (y, then x), used to pick canonical vertices.
fn cmp_yx(a: P, b: P) -> std::cmp::Ordering {
    a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]))
}

/// Clusters points deterministically: points are visited in lexicographic order and each joins
/// the nearest cluster representative (the cluster's first point) within `tol`, or starts a new
/// cluster. Returns the representatives (in lexicographic order) and each point's cluster.
fn snap(points: &[P], tol: f64) -> (Vec<P>, Vec<u32>) {
    let pts: Vec<P> = points.iter().map(|p| [p[0] + 0.0, p[1] + 0.0]).collect();
    let mut order: Vec<usize> = (0..pts.len()).collect();
    order.sort_by(|&a, &b| cmp_xy(pts[a], pts[b]).then(a.cmp(&b)));
    let mut reps: Vec<P> = Vec::new();
    let mut ids = vec![0u32; pts.len()];
    let mut grid: HashMap<(i64, i64), Vec<u32>> = HashMap::new();
    let cell = |p: P| ((p[0] / tol).floor() as i64, (p[1] / tol).floor() as i64);
    for i in order {
        let p = pts[i];
        let found = if tol > 0.0 {
            let (cx, cy) = cell(p);
            let mut best: Option<(f64, u32)> = None;
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for &r in grid.get(&(cx + dx, cy + dy)).map_or(&[][..], |v| v) {
                        let d = dist(p, reps[r as usize]);
                        if d <= tol && best.is_none_or(|(bd, br)| (d, r) < (bd, br)) {
                            best = Some((d, r));
                        }
                    }
                }
            }
            best.map(|b| b.1)
        } else {
            reps.last().filter(|&&r| r == p).map(|_| reps.len() as u32 - 1)
        };
        ids[i] = found.unwrap_or_else(|| {
            reps.push(p);
            let r = reps.len() as u32 - 1;
            if tol > 0.0 {
                grid.entry(cell(p)).or_default().push(r);
            }
            r
        });
    }
    (reps, ids)
}

/// Splits segments at all pairwise crossings, touches and overlaps, snaps within `tol`, and
/// returns the used vertex positions (lexicographic order) and the distinct edges (sorted),
/// each with the sorted indices of the input segments it lies on.
#[allow(clippy::type_complexity)]
fn split_segments(segs: &[[P; 2]], tol: f64) -> (Vec<P>, Vec<([u32; 2], Vec<usize>)>) {
    let tol = if tol.is_finite() && tol > 0.0 { tol } else { 0.0 };
    let ok: Vec<bool> = segs.iter().map(|s| finite(s[0]) && finite(s[1]) && s[0] != s[1]).collect();
    let mut on: Vec<Vec<P>> = segs.iter().zip(&ok).map(|(s, &ok)| if ok { vec![s[0], s[1]] } else { vec![] }).collect();
    let bbox = |s: &[P; 2]| {
        [s[0][0].min(s[1][0]) - tol, s[0][1].min(s[1][1]) - tol, s[0][0].max(s[1][0]) + tol, s[0][1].max(s[1][1]) + tol]
    };
    let boxes: Vec<[f64; 4]> = segs.iter().map(bbox).collect();
    // Sweep in x: only pairs whose bounding boxes overlap are tested.
    let mut by_x: Vec<usize> = (0..segs.len()).filter(|&i| ok[i]).collect();
    by_x.sort_by(|&a, &b| boxes[a][0].total_cmp(&boxes[b][0]).then(a.cmp(&b)));
    for (n, &i) in by_x.iter().enumerate() {
        for &j in by_x[n + 1..].iter().take_while(|&&j| boxes[j][0] <= boxes[i][2]) {
            if boxes[i][1] > boxes[j][3] || boxes[j][1] > boxes[i][3] {
                continue;
            }
            let (a, b) = (segs[i], segs[j]);
            let mut touched = false;
            for (s, t, k) in [(a, b, i), (b, a, j)] {
                for p in t {
                    if seg_dist(p, s[0], s[1]) <= tol {
                        on[k].push(p);
                        touched = true;
                    }
                }
            }
            if let Some(x) = proper_crossing(a[0], a[1], b[0], b[1]).filter(|_| !touched) {
                on[i].push(x);
                on[j].push(x);
            }
        }
    }
    let flat: Vec<P> = on.iter().flatten().copied().collect();
    let (reps, ids) = snap(&flat, tol);
    let mut edges: BTreeMap<[u32; 2], Vec<usize>> = BTreeMap::new();
    let mut k = 0;
    for (s, pts) in on.iter().enumerate() {
        let mut along: Vec<(f64, u32)> =
            pts.iter().enumerate().map(|(m, &p)| (projection_param(p, segs[s][0], segs[s][1]), ids[k + m])).collect();
        k += pts.len();
        along.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        for w in along.windows(2) {
            let (u, v) = (w[0].1, w[1].1);
            if u != v {
                edges.entry([u.min(v), u.max(v)]).or_default().push(s);
            }
        }
    }
    let (keys, sources): (Vec<[u32; 2]>, Vec<Vec<usize>>) = edges.into_iter().unzip();
    let g = compact(&reps, &keys);
    (g.positions, g.edges.into_iter().zip(sources).collect())
}

/// The graph without its isolated vertices (the order of vertices and edges is kept).
fn compact(positions: &[P], edges: &[[u32; 2]]) -> PlanarGraph {
    let mut map = vec![u32::MAX; positions.len()];
    for e in edges {
        map[e[0] as usize] = 0;
        map[e[1] as usize] = 0;
    }
    let mut kept = Vec::new();
    for (v, m) in map.iter_mut().enumerate().filter(|(_, m)| **m == 0) {
        *m = kept.len() as u32;
        kept.push(positions[v]);
    }
    PlanarGraph { positions: kept, edges: edges.iter().map(|e| [map[e[0] as usize], map[e[1] as usize]]).collect() }
}

/// An undirected planar straight-line graph: vertex positions and edges `[u, v]` with `u < v`.
///
/// The constructors guarantee no self-loops, no duplicate edges and sorted edges; planarity
/// (no crossing edges) is guaranteed by [`PlanarGraph::from_segments`] only.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PlanarGraph {
    /// Vertex positions.
    pub positions: Vec<[f64; 2]>,
    /// Edges as pairs of vertex indices.
    pub edges: Vec<[u32; 2]>,
}

/// A bounded face of a [`PlanarGraph`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Face {
    /// The closed boundary walk as a vertex cycle, counter-clockwise (the face on the left),
    /// first vertex not repeated at the end. An edge with this face on both sides (a dangling
    /// edge poking into the face) is walked there and back, so vertices may repeat.
    pub boundary: Vec<u32>,
    /// The outer walks of the components nested directly inside this face (only components
    /// with at least one cycle), clockwise (the face on the left).
    pub holes: Vec<Vec<u32>>,
    /// Area enclosed by `boundary` minus the areas enclosed by the holes.
    pub area: f64,
    /// Length of the edges of `boundary` and of the holes that have this face on exactly one
    /// side: dangling edges (cul-de-sacs, bridges, trees) inside the face do not count.
    pub perimeter: f64,
    /// Number of edges with this face on both sides (on the boundary walk, on the holes, or
    /// tree components floating inside the face).
    pub dangling_edges: usize,
    /// Total length of those dangling edges.
    pub dangling_length: f64,
}

/// The faces of a [`PlanarGraph`], see [`PlanarGraph::faces`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Faces {
    /// The bounded faces.
    pub faces: Vec<Face>,
    /// Per edge `[u, v]`: the face on the left of `u → v` and on the left of `v → u`
    /// (indices into `faces`; `None` is the unbounded face).
    pub edge_faces: Vec<[Option<u32>; 2]>,
}

impl PlanarGraph {
    /// Builds a planar graph from segments: splits them at all proper crossings, T-touches
    /// (an endpoint within `tol` of another segment) and collinear overlaps, snaps points
    /// closer than `tol` together (deterministically, see the module docs), and drops
    /// zero-length and duplicate edges and segments with non-finite coordinates. `O(n²)`.
    /// Use a small positive `tol` (e.g. 1e-9 × the extent); `tol <= 0` snaps exact matches only.
    pub fn from_segments(segments: &[[[f64; 2]; 2]], tol: f64) -> PlanarGraph {
        let (positions, edges) = split_segments(segments, tol);
        PlanarGraph { positions, edges: edges.into_iter().map(|e| e.0).collect() }
    }

    /// Builds a graph from positions and edges, merging vertices within `tol` of each other
    /// (no edge splitting), dropping self-loops and duplicate edges. See
    /// [`PlanarGraph::from_vertices_edges_mapped`] for the vertex map.
    pub fn from_vertices_edges(positions: &[[f64; 2]], edges: &[[u32; 2]], tol: f64) -> PlanarGraph {
        Self::from_vertices_edges_mapped(positions, edges, tol).0
    }

    /// Like [`PlanarGraph::from_vertices_edges`], also returning the new index of each input
    /// vertex. Vertices (isolated ones included) are renumbered in lexicographic order.
    /// Panics if an edge refers to a missing vertex.
    pub fn from_vertices_edges_mapped(positions: &[[f64; 2]], edges: &[[u32; 2]], tol: f64) -> (PlanarGraph, Vec<u32>) {
        let tol = if tol.is_finite() && tol > 0.0 { tol } else { 0.0 };
        let (reps, map) = snap(positions, tol);
        let mut es: Vec<[u32; 2]> = edges
            .iter()
            .map(|e| [map[e[0] as usize], map[e[1] as usize]])
            .filter(|e| e[0] != e[1])
            .map(|e| [e[0].min(e[1]), e[0].max(e[1])])
            .collect();
        es.sort_unstable();
        es.dedup();
        (PlanarGraph { positions: reps, edges: es }, map)
    }

    /// The union of several graphs (e.g. per-region street graphs sharing boundary vertices),
    /// merging vertices within `tol`, as [`PlanarGraph::from_vertices_edges`].
    pub fn union(graphs: &[PlanarGraph], tol: f64) -> PlanarGraph {
        let (mut positions, mut edges) = (Vec::new(), Vec::new());
        for g in graphs {
            let off = positions.len() as u32;
            positions.extend_from_slice(&g.positions);
            edges.extend(g.edges.iter().map(|e| [e[0] + off, e[1] + off]));
        }
        Self::from_vertices_edges(&positions, &edges, tol)
    }

    /// Number of edges at each vertex.
    pub fn valences(&self) -> Vec<usize> {
        let mut d = vec![0; self.positions.len()];
        for e in &self.edges {
            d[e[0] as usize] += 1;
            d[e[1] as usize] += 1;
        }
        d
    }

    /// Length of edge `e`.
    pub fn edge_length(&self, e: usize) -> f64 {
        let [u, v] = self.edges[e];
        dist(self.positions[u as usize], self.positions[v as usize])
    }

    /// Traces the faces with the rotation system ([`face_walks`]), so every face lies on the
    /// left of its walks. Each connected component has one
    /// outer walk (the one leaving its lowest-left vertex with the largest angle); all other
    /// walks are bounded faces. A component nested inside a bounded face of another component
    /// (by point-in-polygon of its lowest-left vertex) becomes a hole of the smallest such face.
    /// Assumes the graph is planar (e.g. built by [`PlanarGraph::from_segments`]).
    pub fn faces(&self) -> Faces {
        let nv = self.positions.len();
        let org = |h: usize| self.edges[h / 2][h % 2] as usize;
        let pos = |v: usize| self.positions[v];
        // Equal angles (overlapping edges, which a planar graph has none of) by far vertex.
        let FaceWalks { walks, walk_of, around: out } = face_walks(&self.positions, &self.edges, |h| org(h ^ 1) as u32);
        // Connected components (union-find) and their lowest-left vertices and outer walks.
        let mut parent: Vec<usize> = (0..nv).collect();
        fn find(p: &mut [usize], mut v: usize) -> usize {
            while p[v] != v {
                p[v] = p[p[v]];
                v = p[v];
            }
            v
        }
        for e in &self.edges {
            let (a, b) = (find(&mut parent, e[0] as usize), find(&mut parent, e[1] as usize));
            parent[a.max(b)] = a.min(b);
        }
        let comp: Vec<usize> = (0..nv).map(|v| find(&mut parent, v)).collect();
        let mut low: BTreeMap<usize, usize> = BTreeMap::new(); // component -> lowest-left vertex
        for v in (0..nv).filter(|&v| !out[v].is_empty()) {
            let l = low.entry(comp[v]).or_insert(v);
            if cmp_yx(pos(v), pos(*l)).is_lt() {
                *l = v;
            }
        }
        let outer_walk: BTreeMap<usize, usize> =
            low.iter().map(|(&r, &v)| (r, walk_of[*out[v].last().unwrap()])).collect();
        let ring = |w: usize| walks[w].iter().map(|&h| pos(org(h))).collect::<Vec<P>>();
        let mut walk_face: Vec<Option<u32>> = vec![None; walks.len()];
        let mut faces: Vec<Face> = Vec::new();
        let mut face_comp = Vec::new();
        for w in 0..walks.len() {
            let c = comp[org(walks[w][0])];
            if outer_walk[&c] != w {
                walk_face[w] = Some(faces.len() as u32);
                face_comp.push(c);
                let boundary = walks[w].iter().map(|&h| org(h) as u32).collect();
                let area = signed_area(&ring(w));
                faces.push(Face {
                    boundary,
                    holes: vec![],
                    area,
                    perimeter: 0.0,
                    dangling_edges: 0,
                    dangling_length: 0.0,
                });
            }
        }
        // Nesting: each component's outer walk lies in the smallest containing face, if any.
        let rings: Vec<Vec<P>> = faces.iter().map(|f| f.boundary.iter().map(|&v| pos(v as usize)).collect()).collect();
        let outer_area: Vec<f64> = faces.iter().map(|f| f.area).collect();
        let has_cycle: std::collections::BTreeSet<usize> = face_comp.iter().copied().collect();
        for (&r, &v) in &low {
            let p = pos(v);
            let container = (0..faces.len())
                .filter(|&f| face_comp[f] != r && ring_contains(&rings[f], p))
                .min_by(|&a, &b| outer_area[a].total_cmp(&outer_area[b]).then(a.cmp(&b)));
            let w = outer_walk[&r];
            walk_face[w] = container.map(|f| f as u32);
            if let (Some(f), true) = (container, has_cycle.contains(&r)) {
                faces[f].holes.push(walks[w].iter().map(|&h| org(h) as u32).collect());
                faces[f].area += signed_area(&ring(w)); // negative: clockwise
            }
        }
        // Perimeters and dangling edges.
        let mut edge_faces = Vec::with_capacity(self.edges.len());
        for e in 0..self.edges.len() {
            let (w0, w1) = (walk_of[2 * e], walk_of[2 * e + 1]);
            let (f0, f1) = (walk_face[w0], walk_face[w1]);
            edge_faces.push([f0, f1]);
            let len = self.edge_length(e);
            if w0 == w1 {
                if let Some(f) = f0 {
                    faces[f as usize].dangling_edges += 1;
                    faces[f as usize].dangling_length += len;
                }
            } else {
                for f in [f0, f1].into_iter().flatten() {
                    faces[f as usize].perimeter += len;
                }
            }
        }
        Faces { faces, edge_faces }
    }
}

/// The face walks of a plane straight-line graph, see [`face_walks`].
#[derive(Clone, Debug, PartialEq)]
pub struct FaceWalks {
    /// The walks as half-edge cycles, each from its smallest half-edge, in order of it.
    pub walks: Vec<Vec<usize>>,
    /// Per half-edge: its walk.
    pub walk_of: Vec<usize>,
    /// Per vertex: its outgoing half-edges in counter-clockwise order of angle.
    pub around: Vec<Vec<usize>>,
}

/// Traces the face walks of a plane straight-line graph with its rotation system: half-edge
/// `2e` runs `edges[e][0] → edges[e][1]` and `2e + 1` back. At each vertex the outgoing
/// half-edges are sorted by angle (`atan2`), equal angles by `tie` of the half-edge, and a walk
/// continues from `u → v` with the half-edge just clockwise of `v → u`, so every face lies on
/// the left of its walks: bounded faces counter-clockwise, each component's outer walk
/// clockwise. The one face tracer of the crate.
pub fn face_walks(positions: &[P], edges: &[[u32; 2]], tie: impl Fn(usize) -> u32) -> FaceWalks {
    let nh = 2 * edges.len();
    let org = |h: usize| edges[h / 2][h % 2] as usize;
    let angle = |h: usize| {
        let d = sub(positions[org(h ^ 1)], positions[org(h)]);
        d[1].atan2(d[0])
    };
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); positions.len()];
    for h in 0..nh {
        around[org(h)].push(h);
    }
    let mut rot = vec![0usize; nh];
    for hs in &mut around {
        hs.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)).then(tie(a).cmp(&tie(b))));
        for (k, &h) in hs.iter().enumerate() {
            rot[h] = k;
        }
    }
    let next = |h: usize| {
        let hs = &around[org(h ^ 1)];
        hs[(rot[h ^ 1] + hs.len() - 1) % hs.len()]
    };
    let mut walk_of = vec![usize::MAX; nh];
    let mut walks: Vec<Vec<usize>> = Vec::new();
    for h0 in 0..nh {
        if walk_of[h0] == usize::MAX {
            let (mut h, mut w) = (h0, Vec::new());
            while walk_of[h] == usize::MAX {
                walk_of[h] = walks.len();
                w.push(h);
                h = next(h);
            }
            walks.push(w);
        }
    }
    FaceWalks { walks, walk_of, around }
}

/// Why [`arrangement`] rejected its input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ArrangementError {
    /// The tolerance is negative or not finite.
    #[error("tolerance must be finite and non-negative, got {0}")]
    BadTolerance(f64),
    /// The domain polygon has fewer than 3 distinct points.
    #[error("domain polygon has {0} distinct point(s); at least 3 are needed")]
    DomainTooFewPoints(usize),
    /// A domain point has a non-finite coordinate.
    #[error("domain polygon point {index} is not finite: ({x}, {y})")]
    DomainNotFinite {
        /// Index of the point.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// Two edges of the domain polygon cross, touch or overlap.
    #[error("domain polygon is self-intersecting: edge {a} meets edge {b} (edge k joins distinct points k and k+1)")]
    DomainSelfIntersecting {
        /// One edge.
        a: usize,
        /// The other edge.
        b: usize,
    },
    /// The domain polygon encloses no area.
    #[error("domain polygon encloses (almost) no area")]
    DomainDegenerate,
    /// A road point has a non-finite coordinate.
    #[error("road {road}: point {index} is not finite: ({x}, {y})")]
    RoadNotFinite {
        /// Index of the road.
        road: usize,
        /// Index of the point in the road.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// A road has fewer than 2 distinct points.
    #[error("road {road} has {points} distinct point(s); a road polyline needs at least 2")]
    RoadTooFewPoints {
        /// Index of the road.
        road: usize,
        /// Number of distinct consecutive points.
        points: usize,
    },
    /// No part of a road of positive length lies inside (or on the boundary of) the domain.
    #[error("road {road} lies entirely outside the domain")]
    RoadOutsideDomain {
        /// Index of the road.
        road: usize,
    },
}

/// A sub-region of a city: a bounded face of the arrangement of the domain and the major roads.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Region {
    /// The outer boundary, counter-clockwise, starting at its lowest-left vertex (min y, then
    /// min x). Weakly simple: it may touch itself at a vertex (e.g. a road loop from one point).
    /// Vertices where a pruned dangling road attached are kept (as collinear vertices).
    pub outer: Vec<[f64; 2]>,
    /// Holes (rings of roads nested inside the region), clockwise.
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Area of `outer` minus the holes.
    pub area: f64,
    /// A point strictly inside the region and outside its holes.
    pub label_point: [f64; 2],
}

/// The result of [`arrangement`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Arrangement {
    /// The regions, sorted by the lowest-left vertex of `outer` (min y, then min x).
    pub regions: Vec<Region>,
    /// Per road (by index, ascending), the length inside the domain that was pruned because it
    /// separates no two regions: dead-end pieces, and bridges to rings of roads that thereby
    /// become holes. A piece shared by overlapping roads is reported for each of them.
    pub dangling: Vec<(usize, f64)>,
    /// The clipped and pruned arrangement graph whose bounded faces are `regions`.
    pub graph: PlanarGraph,
}

/// Removes consecutive points within `tol` (cyclically if `closed`).
fn dedup_points(pts: &[P], tol: f64, closed: bool) -> Vec<P> {
    let mut v: Vec<P> = Vec::new();
    for &p in pts {
        if v.last().is_none_or(|&q| dist(p, q) > tol) {
            v.push(p);
        }
    }
    while closed && v.len() > 1 && dist(v[0], v[v.len() - 1]) <= tol {
        v.pop();
    }
    v
}

/// Checks that a closed ring is simple (within `tol`).
fn check_simple(poly: &[P], tol: f64) -> Result<(), ArrangementError> {
    let n = poly.len();
    let edge = |k: usize| [poly[k], poly[(k + 1) % n]];
    for a in 0..n {
        for b in a + 1..n {
            let adjacent = b == a + 1 || (a == 0 && b == n - 1);
            let bad = if adjacent {
                // Adjacent edges share a vertex; they must not fold back onto each other.
                let (s, t) = if b == a + 1 { (edge(a), edge(b)) } else { (edge(b), edge(a)) };
                seg_dist(t[1], s[0], s[1]) <= tol || seg_dist(s[0], t[0], t[1]) <= tol
            } else {
                seg_seg_dist(edge(a), edge(b)) <= tol
            };
            if bad {
                return Err(ArrangementError::DomainSelfIntersecting { a, b });
            }
        }
    }
    Ok(())
}

/// A point strictly inside the polygon `outer` (any orientation, weakly simple) and outside all
/// `holes`: the midpoint of the widest inside interval along horizontal lines halfway between
/// consecutive distinct vertex heights, scored by min(width, slab height). `None` if the polygon
/// encloses no area.
pub fn polygon_label_point(outer: &[[f64; 2]], holes: &[Vec<[f64; 2]>]) -> Option<[f64; 2]> {
    let rings: Vec<&[P]> = std::iter::once(outer).chain(holes.iter().map(|h| h.as_slice())).collect();
    let mut ys: Vec<f64> = rings.iter().flat_map(|r| r.iter().map(|p| p[1])).collect();
    ys.sort_by(f64::total_cmp);
    ys.dedup();
    let mut best: Option<(f64, P)> = None;
    for w in ys.windows(2) {
        let (h, y) = (w[1] - w[0], 0.5 * (w[0] + w[1]));
        if !(h > 0.0 && y > w[0] && y < w[1]) {
            continue;
        }
        let mut xs: Vec<f64> = Vec::new();
        for r in &rings {
            for k in 0..r.len() {
                let (a, b) = (r[k], r[(k + 1) % r.len()]);
                if (a[1] < y) != (b[1] < y) {
                    xs.push(a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
                }
            }
        }
        xs.sort_by(f64::total_cmp);
        for iv in xs.chunks_exact(2) {
            let score = (iv[1] - iv[0]).min(h);
            if score > 0.0 && best.is_none_or(|b| score > b.0) {
                best = Some((score, [0.5 * (iv[0] + iv[1]), y]));
            }
        }
    }
    best.map(|b| b.1)
}

/// Splits a city domain into the sub-regions bounded by the domain boundary and the major
/// roads: the bounded faces of the planar arrangement of the boundary polygon (either
/// orientation, optionally closed by repeating the first point) and the road polylines.
///
/// Roads are split at all crossings, touches and overlaps (snapping within `tol`); pieces
/// outside the domain are clipped away (a road crossing out and back yields separate pieces);
/// pieces that separate no two regions (dead ends, bridges) are pruned and reported in
/// [`Arrangement::dangling`]. A ring of roads not connected to the boundary becomes a region and
/// a hole of the region around it.
pub fn arrangement(domain: &[[f64; 2]], roads: &[Vec<[f64; 2]>], tol: f64) -> Result<Arrangement, ArrangementError> {
    use ArrangementError as E;
    if !(tol.is_finite() && tol >= 0.0) {
        return Err(E::BadTolerance(tol));
    }
    if let Some((index, p)) = domain.iter().enumerate().find(|(_, p)| !finite(**p)) {
        return Err(E::DomainNotFinite { index, x: p[0], y: p[1] });
    }
    let poly = dedup_points(domain, tol, true);
    if poly.len() < 3 {
        return Err(E::DomainTooFewPoints(poly.len()));
    }
    check_simple(&poly, tol)?;
    let perimeter: f64 = (0..poly.len()).map(|k| dist(poly[k], poly[(k + 1) % poly.len()])).sum();
    if signed_area(&poly).abs() <= tol * perimeter {
        return Err(E::DomainDegenerate);
    }
    let nb = poly.len();
    let mut segs: Vec<[P; 2]> = (0..nb).map(|k| [poly[k], poly[(k + 1) % nb]]).collect();
    let mut seg_road: Vec<usize> = Vec::new();
    for (road, pts) in roads.iter().enumerate() {
        if let Some((index, p)) = pts.iter().enumerate().find(|(_, p)| !finite(**p)) {
            return Err(E::RoadNotFinite { road, index, x: p[0], y: p[1] });
        }
        let pts = dedup_points(pts, tol, false);
        if pts.len() < 2 {
            return Err(E::RoadTooFewPoints { road, points: pts.len() });
        }
        for w in pts.windows(2) {
            segs.push([w[0], w[1]]);
            seg_road.push(road);
        }
    }
    let (positions, split) = split_segments(&segs, tol);
    // Clip: keep boundary edges and road edges whose midpoint is inside the domain.
    let mut kept: Vec<([u32; 2], Vec<usize>)> = Vec::new();
    let mut inside_road = vec![false; roads.len()];
    for (e, src) in split {
        let (a, b) = (positions[e[0] as usize], positions[e[1] as usize]);
        let on_boundary = src.iter().any(|&s| s < nb);
        if on_boundary || ring_contains(&poly, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]) {
            let rs: Vec<usize> = src.iter().filter(|&&s| s >= nb).map(|&s| seg_road[s - nb]).collect();
            for &r in &rs {
                inside_road[r] = true;
            }
            kept.push((e, rs));
        }
    }
    if let Some(road) = inside_road.iter().position(|&b| !b) {
        return Err(E::RoadOutsideDomain { road });
    }
    let edges: Vec<[u32; 2]> = kept.iter().map(|k| k.0).collect();
    let full = PlanarGraph { positions, edges };
    let ef = full.faces().edge_faces;
    let mut pruned: BTreeMap<usize, f64> = BTreeMap::new();
    let mut keep = Vec::new();
    for (e, (_, rs)) in kept.iter().enumerate() {
        if ef[e][0] == ef[e][1] {
            for &r in rs {
                *pruned.entry(r).or_default() += full.edge_length(e);
            }
        } else {
            keep.push(full.edges[e]);
        }
    }
    let graph = compact(&full.positions, &keep);
    let pts = |vs: &[u32]| vs.iter().map(|&v| graph.positions[v as usize]).collect::<Vec<P>>();
    let mut regions: Vec<Region> = graph
        .faces()
        .faces
        .iter()
        .map(|f| {
            let mut outer = pts(&f.boundary);
            let start = (0..outer.len()).min_by(|&a, &b| cmp_yx(outer[a], outer[b]).then(a.cmp(&b))).unwrap_or(0);
            outer.rotate_left(start);
            let holes: Vec<Vec<P>> = f.holes.iter().map(|h| pts(h)).collect();
            let label_point = polygon_label_point(&outer, &holes).unwrap_or(outer[0]);
            Region { outer, holes, area: f.area, label_point }
        })
        .collect();
    regions.sort_by(|a, b| {
        cmp_yx(a.outer[0], b.outer[0]).then(cmp_yx(a.label_point, b.label_point)).then(a.area.total_cmp(&b.area))
    });
    Ok(Arrangement { regions, dangling: pruned.into_iter().collect(), graph })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQ: [P; 4] = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
    const TOL: f64 = 1e-9;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }
    fn areas(a: &Arrangement) -> Vec<f64> {
        a.regions.iter().map(|r| r.area).collect()
    }
    fn check_labels(a: &Arrangement) {
        for r in &a.regions {
            assert!(ring_contains(&r.outer, r.label_point), "{r:?}");
            assert!(r.holes.iter().all(|h| !ring_contains(h, r.label_point)), "{r:?}");
            assert!(signed_area(&r.outer) > 0.0);
            assert!(r.holes.iter().all(|h| signed_area(h) < 0.0));
        }
    }

    #[test]
    fn segments_cross_touch_overlap() {
        // A proper crossing: 5 vertices, 4 edges.
        let g = PlanarGraph::from_segments(&[[[0.0, 0.0], [2.0, 2.0]], [[0.0, 2.0], [2.0, 0.0]]], TOL);
        assert_eq!(g.positions.len(), 5);
        assert_eq!(g.edges.len(), 4);
        assert_eq!(g.positions[2], [1.0, 1.0]);
        // A T-touch and a collinear overlap, plus a near-miss within tol and a zero-length one.
        let g = PlanarGraph::from_segments(
            &[
                [[0.0, 0.0], [4.0, 0.0]],
                [[2.0, 0.0], [2.0, 3.0]],
                [[3.0, 0.0], [6.0, 0.0]],
                [[2.0, 3.0 + 1e-12], [5.0, 3.0]],
                [[9.0, 9.0], [9.0, 9.0]],
            ],
            TOL,
        );
        let want: Vec<P> = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 3.0], [3.0, 0.0], [4.0, 0.0], [5.0, 3.0], [6.0, 0.0]];
        assert_eq!(g.positions, want);
        assert_eq!(g.edges, vec![[0, 1], [1, 2], [1, 3], [2, 5], [3, 4], [4, 6]]);
        assert_eq!(g.valences(), vec![1, 3, 2, 2, 2, 1, 1]);
    }

    #[test]
    fn merge_vertices() {
        let a = PlanarGraph { positions: vec![[0.0, 0.0], [1.0, 0.0]], edges: vec![[0, 1]] };
        let b = PlanarGraph {
            positions: vec![[1.0 + 1e-12, 0.0], [1.0, 1.0], [1.0, 0.0]],
            edges: vec![[0, 1], [1, 2], [2, 0]],
        };
        let g = PlanarGraph::union(&[a, b], 1e-9);
        assert_eq!(g.positions, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
        assert_eq!(g.edges, vec![[0, 1], [1, 2]]);
        let (_, map) = PlanarGraph::from_vertices_edges_mapped(&[[5.0, 5.0], [0.0, 0.0], [5.0, 5.0]], &[], 0.0);
        assert_eq!(map, vec![1, 0, 1]);
    }

    #[test]
    fn faces_nesting_and_dangling() {
        let sq = |x: f64, y: f64, s: f64| {
            let p = [[x, y], [x + s, y], [x + s, y + s], [x, y + s]];
            (0..4).map(|k| [p[k], p[(k + 1) % 4]]).collect::<Vec<_>>()
        };
        // Two squares side by side: 2 faces, no holes.
        let g = PlanarGraph::from_segments(&[sq(0.0, 0.0, 1.0), sq(3.0, 0.0, 2.0)].concat(), TOL);
        let f = g.faces();
        assert_eq!(f.faces.len(), 2);
        assert!(f.faces.iter().all(|f| f.holes.is_empty()));
        let mut a: Vec<f64> = f.faces.iter().map(|f| f.area).collect();
        a.sort_by(f64::total_cmp);
        assert_eq!(a, vec![1.0, 4.0]);
        // A square in a square with a cul-de-sac into the ring, and a floating stick.
        let mut segs = [sq(0.0, 0.0, 10.0), sq(4.0, 4.0, 2.0)].concat();
        segs.push([[0.0, 5.0], [2.0, 5.0]]);
        segs.push([[7.0, 1.0], [8.0, 1.0]]);
        let g = PlanarGraph::from_segments(&segs, TOL);
        let f = g.faces();
        assert_eq!(f.faces.len(), 2);
        let big = f.faces.iter().find(|f| f.area > 50.0).unwrap();
        assert_eq!(big.holes.len(), 1);
        assert_eq!(big.holes[0].len(), 4);
        assert!(close(big.area, 96.0));
        assert!(close(big.perimeter, 48.0));
        assert_eq!(big.dangling_edges, 2);
        assert!(close(big.dangling_length, 3.0));
        let small = f.faces.iter().find(|f| f.area < 50.0).unwrap();
        assert!(close(small.area, 4.0) && close(small.perimeter, 8.0));
        // Every boundary walk is counter-clockwise.
        for face in &f.faces {
            let ring: Vec<P> = face.boundary.iter().map(|&v| g.positions[v as usize]).collect();
            assert!(signed_area(&ring) > 0.0);
        }
        // Edges on the outer boundary have the unbounded face on one side.
        let n_outer = f.edge_faces.iter().filter(|s| s.contains(&None)).count();
        assert_eq!(n_outer, 5); // bottom edge is split at nothing; left edge split at (0,5)
    }

    #[test]
    fn one_vertical_road() {
        let a = arrangement(&SQ, &[vec![[4.0, -1.0], [4.0, 11.0]]], TOL).unwrap();
        assert_eq!(areas(&a), vec![40.0, 60.0]);
        assert_eq!(a.regions[0].outer, vec![[0.0, 0.0], [4.0, 0.0], [4.0, 10.0], [0.0, 10.0]]);
        assert!(a.dangling.is_empty());
        check_labels(&a);
        // Either domain orientation gives the same result.
        let mut rev = SQ.to_vec();
        rev.reverse();
        assert_eq!(arrangement(&rev, &[vec![[4.0, -1.0], [4.0, 11.0]]], TOL).unwrap(), a);
    }

    #[test]
    fn plus_of_roads() {
        let roads = vec![vec![[5.0, 0.0], [5.0, 10.0]], vec![[-3.0, 5.0], [13.0, 5.0]]];
        let a = arrangement(&SQ, &roads, TOL).unwrap();
        assert_eq!(areas(&a), vec![25.0; 4]);
        let starts: Vec<P> = a.regions.iter().map(|r| r.outer[0]).collect();
        assert_eq!(starts, vec![[0.0, 0.0], [5.0, 0.0], [0.0, 5.0], [5.0, 5.0]]);
        check_labels(&a);
    }

    #[test]
    fn road_ending_inside_is_pruned() {
        let roads = vec![vec![[5.0, -2.0], [5.0, 5.0]], vec![[1.0, 1.0], [2.0, 2.0], [1.0, 2.0]]];
        let a = arrangement(&SQ, &roads, TOL).unwrap();
        assert_eq!(areas(&a), vec![100.0]);
        assert_eq!(a.dangling.len(), 2);
        assert_eq!(a.dangling[0], (0, 5.0));
        assert_eq!(a.dangling[1].0, 1);
        assert!(close(a.dangling[1].1, 2f64.sqrt() + 1.0));
        // The bottom edge stays split where the pruned road attached.
        assert_eq!(a.graph.edges.len(), 5);
        assert_eq!(a.regions[0].outer[1], [5.0, 0.0]);
        check_labels(&a);
    }

    #[test]
    fn road_crossing_out_and_back() {
        let road = vec![[-1.0, 2.0], [3.0, 2.0], [3.0, 12.0], [7.0, 12.0], [7.0, 2.0], [11.0, 2.0]];
        let a = arrangement(&SQ, &[road], TOL).unwrap();
        assert_eq!(areas(&a), vec![52.0, 24.0, 24.0]);
        assert!(a.dangling.is_empty());
        check_labels(&a);
    }

    #[test]
    fn road_overlapping_boundary() {
        let road = vec![[-2.0, 0.0], [5.0, 0.0], [5.0, 10.0], [5.0, 13.0]];
        let a = arrangement(&SQ, &[road], TOL).unwrap();
        assert_eq!(areas(&a), vec![50.0, 50.0]);
        assert!(a.dangling.is_empty());
        assert_eq!(a.graph.edges.len(), 7);
        // A road running only along the boundary is accepted and changes nothing.
        let a = arrangement(&SQ, &[vec![[0.0, 0.0], [10.0, 0.0]]], TOL).unwrap();
        assert_eq!(areas(&a), vec![100.0]);
    }

    #[test]
    fn ring_road_makes_a_hole() {
        let ring = vec![[3.0, 3.0], [7.0, 3.0], [7.0, 7.0], [3.0, 7.0], [3.0, 3.0]];
        let a = arrangement(&SQ, std::slice::from_ref(&ring), TOL).unwrap();
        assert_eq!(areas(&a), vec![84.0, 16.0]);
        assert_eq!(a.regions[0].holes.len(), 1);
        assert!(a.regions[1].holes.is_empty());
        check_labels(&a);
        // With a bridge from the boundary the bridge is reported and the regions are the same
        // (up to the vertices where the bridge attached).
        let b = arrangement(&SQ, &[ring, vec![[5.0, 0.0], [5.0, 3.0]]], TOL).unwrap();
        assert_eq!(areas(&b), areas(&a));
        assert_eq!(b.regions[0].holes.len(), 1);
        assert_eq!(b.regions[0].outer.len(), 5);
        assert_eq!(b.dangling, vec![(1, 3.0)]);
    }

    #[test]
    fn errors() {
        use ArrangementError as E;
        let road = vec![vec![[0.0, 5.0], [10.0, 5.0]]];
        assert_eq!(arrangement(&SQ[..2], &road, TOL), Err(E::DomainTooFewPoints(2)));
        let closed_pair = [[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]];
        assert_eq!(arrangement(&closed_pair, &road, TOL), Err(E::DomainTooFewPoints(2)));
        let nan = [[0.0, 0.0], [f64::NAN, 0.0], [1.0, 1.0]];
        assert!(matches!(arrangement(&nan, &road, TOL), Err(E::DomainNotFinite { index: 1, .. })));
        let bowtie = [[0.0, 0.0], [10.0, 10.0], [10.0, 0.0], [0.0, 10.0]];
        assert_eq!(arrangement(&bowtie, &road, TOL), Err(E::DomainSelfIntersecting { a: 0, b: 2 }));
        let flat = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert!(matches!(arrangement(&flat, &road, TOL), Err(E::DomainSelfIntersecting { .. })));
        let bad_roads = vec![road[0].clone(), vec![[1.0, 1.0]]];
        let e = arrangement(&SQ, &bad_roads, TOL).unwrap_err();
        assert_eq!(e, E::RoadTooFewPoints { road: 1, points: 1 });
        assert_eq!(e.to_string(), "road 1 has 1 distinct point(s); a road polyline needs at least 2");
        let bad_roads = vec![road[0].clone(), vec![[1.0, 1.0], [1.0, f64::INFINITY]]];
        assert!(matches!(arrangement(&SQ, &bad_roads, TOL), Err(E::RoadNotFinite { road: 1, index: 1, .. })));
        let outside = vec![road[0].clone(), vec![[11.0, 0.0], [20.0, 5.0]], vec![[10.0, 0.0], [12.0, 0.0]]];
        let e = arrangement(&SQ, &outside, TOL).unwrap_err();
        assert_eq!(e.to_string(), "road 1 lies entirely outside the domain");
        assert!(matches!(arrangement(&SQ, &road, -1.0), Err(E::BadTolerance(_))));
    }
    /// Pseudo-random roads: the regions partition the domain.
    #[test]
    fn regions_partition_the_domain() {
        let mut x = 12345u64;
        let mut rnd = move || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 * 14.0 - 2.0
        };
        let roads: Vec<Vec<P>> = (0..12).map(|_| (0..3).map(|_| [rnd(), rnd()]).collect()).collect();
        let a = arrangement(&SQ, &roads, TOL).unwrap();
        assert!(a.regions.len() > 10);
        assert!((a.regions.iter().map(|r| r.area).sum::<f64>() - 100.0).abs() < 1e-9);
        check_labels(&a);
        assert_eq!(arrangement(&SQ, &roads, TOL).unwrap(), a);
    }
}
