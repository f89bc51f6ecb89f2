//! The [`Mesh`] type: construction, validation and queries.

use super::error::{DegenerateReason, MeshError};
use super::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::geometry as geom;
use std::collections::VecDeque;
use std::f64::consts::TAU;

/// Largest element count accepted, so that every id (including half-edge `2e + 1`) fits in `u32`.
const MAX_ELEMENTS: usize = (u32::MAX / 4) as usize;

/// Two vertices closer than this are duplicates.
const DUPLICATE_TOLERANCE: f64 = 1e-12;

/// A validated 2D polygon mesh with a half-edge structure.
///
/// Built by [`Mesh::from_polygons`] (or the generators, [`subdivide`](fn@super::subdivide), OBJ and
/// JSON readers). Immutable. Invariants of a mesh built by `from_polygons`:
/// - every face is a simple polygon with non-negligible area, stored counter-clockwise;
/// - every edge has one or two faces, and two faces sharing an edge use it in opposite directions;
/// - every vertex is used by a face, no two vertices coincide, and the faces around every vertex
///   form a single fan (a full disk for interior vertices, a half-disk for boundary vertices)
///   whose corner angles add up to one turn (interior) or less (boundary).
///
/// Non-adjacent faces are not checked for overlap. A mesh may have several connected components
/// and holes.
///
/// See the [module docs](super) for the numbering of edges and half-edges and the order of
/// one-rings.
#[derive(Clone, PartialEq)]
pub struct Mesh {
    positions: Vec<[f64; 2]>,
    /// CSR offsets into `face_verts` / `face_hes`, length `F + 1`.
    face_offsets: Vec<usize>,
    /// Face loops, counter-clockwise.
    face_verts: Vec<VertexId>,
    /// `face_hes[k]` runs `face_verts[k] → face_verts[k + 1]` (cyclically within the face).
    face_hes: Vec<HalfEdgeId>,
    /// Tail vertex of each half-edge, length `2E`.
    he_tail: Vec<VertexId>,
    he_face: Vec<Option<FaceId>>,
    he_next: Vec<Option<HalfEdgeId>>,
    he_prev: Vec<Option<HalfEdgeId>>,
    /// CSR offsets into `out_hes`, length `V + 1`.
    out_offsets: Vec<usize>,
    /// Outgoing half-edges of each vertex, CCW, starting after the boundary gap.
    out_hes: Vec<HalfEdgeId>,
    boundary_vertex: Vec<bool>,
}

impl Mesh {
    /// Builds and validates a mesh from vertex positions and faces given as loops of vertex
    /// indices.
    ///
    /// Faces may be given all counter-clockwise or all clockwise; clockwise input is normalised
    /// by reversing every loop while keeping its first vertex (`[a, b, c, d]` becomes
    /// `[a, d, c, b]`). Vertex and face ids are the input indices; edges are numbered in order of
    /// first appearance along the normalised loops. See [`MeshError`] for everything checked.
    pub fn from_polygons(positions: Vec<[f64; 2]>, faces: Vec<Vec<u32>>) -> Result<Mesh, MeshError> {
        Self::build(positions, faces, true)
    }

    /// Builds a mesh. With `check_geometry == false` the loops must already be counter-clockwise
    /// and all geometric checks (finite and distinct positions, areas, simplicity, orientation,
    /// angle sums) are skipped; the combinatorial checks still run. Used by [`subdivide`], whose
    /// output is combinatorially valid by construction.
    ///
    /// [`subdivide`]: fn@super::subdivide
    pub(crate) fn build(
        positions: Vec<[f64; 2]>,
        mut faces: Vec<Vec<u32>>,
        check_geometry: bool,
    ) -> Result<Mesh, MeshError> {
        let nv = positions.len();
        let nf = faces.len();
        if nf == 0 {
            return Err(MeshError::Empty { reason: "no faces".into() });
        }
        let corners: usize = faces.iter().map(Vec::len).sum();
        if nv > MAX_ELEMENTS || nf > MAX_ELEMENTS || corners > MAX_ELEMENTS {
            return Err(MeshError::TooLarge { reason: format!("{nv} vertices, {nf} faces, {corners} face corners") });
        }

        if check_geometry {
            if let Some(v) = positions.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
                return Err(MeshError::NonFinitePosition { v: VertexId(v as u32) });
            }
            if let Some((a, b)) = first_duplicate(&positions) {
                return Err(MeshError::DuplicateVertex { a: VertexId(a as u32), b: VertexId(b as u32) });
            }
        }

        // Combinatorial face checks, face by face.
        let mut used = vec![false; nv];
        let mut seen_in_face: Vec<u32> = vec![u32::MAX; nv];
        for (f, lp) in faces.iter().enumerate() {
            let face = FaceId(f as u32);
            if let Some(&index) = lp.iter().find(|&&i| i as usize >= nv) {
                return Err(MeshError::BadIndex { face, index });
            }
            if lp.len() < 3 {
                return Err(MeshError::DegenerateFace { face, reason: DegenerateReason::TooFewVertices });
            }
            for &i in lp {
                if seen_in_face[i as usize] == f as u32 {
                    return Err(MeshError::DegenerateFace {
                        face,
                        reason: DegenerateReason::RepeatedVertex(VertexId(i)),
                    });
                }
                seen_in_face[i as usize] = f as u32;
                used[i as usize] = true;
            }
        }
        if let Some(v) = used.iter().position(|&u| !u) {
            return Err(MeshError::IsolatedVertex { v: VertexId(v as u32) });
        }

        // Geometric face checks and orientation.
        let mut clockwise = vec![false; nf];
        if check_geometry {
            let mut pts = Vec::new();
            for (f, lp) in faces.iter().enumerate() {
                pts.clear();
                pts.extend(lp.iter().map(|&i| positions[i as usize]));
                let face = FaceId(f as u32);
                if geom::is_area_degenerate(&pts) {
                    return Err(MeshError::DegenerateFace { face, reason: DegenerateReason::ZeroArea });
                }
                if !geom::is_simple(&pts) {
                    return Err(MeshError::DegenerateFace { face, reason: DegenerateReason::SelfIntersecting });
                }
                clockwise[f] = geom::signed_area(&pts) < 0.0;
            }
        }

        // Edges used by more than two faces (independent of orientation): report the edge whose
        // third use comes first in face-walk order.
        let mut groups = CornerGroups::new(&faces, nv);
        if let Some((a, b)) = groups.non_manifold {
            return Err(MeshError::NonManifoldEdge { a: VertexId(a), b: VertexId(b) });
        }

        if check_geometry {
            let n_cw = clockwise.iter().filter(|&&c| c).count();
            if n_cw == nf {
                for lp in &mut faces {
                    lp[1..].reverse();
                }
                groups = CornerGroups::new(&faces, nv);
            } else if n_cw > 0 {
                // The minority orientation is wrong; on a tie, the clockwise faces are.
                let wrong_is_cw = 2 * n_cw <= nf;
                let f = clockwise.iter().position(|&c| c == wrong_is_cw).unwrap_or(0);
                return Err(MeshError::InconsistentOrientation { face: FaceId(f as u32) });
            }
        }

        // Half-edges: a corner that first uses its edge creates it (half-edge 2e in its
        // direction); the other corner of the edge, if any, takes half-edge 2e + 1.
        let mut he_tail: Vec<VertexId> = Vec::with_capacity(corners + corners / 2);
        let mut he_face: Vec<Option<FaceId>> = Vec::with_capacity(corners + corners / 2);
        let mut face_offsets = Vec::with_capacity(nf + 1);
        let mut face_verts = Vec::with_capacity(corners);
        let mut face_hes: Vec<HalfEdgeId> = Vec::with_capacity(corners);
        face_offsets.push(0);
        for (f, lp) in faces.iter().enumerate() {
            let face = FaceId(f as u32);
            for k in 0..lp.len() {
                let c = face_verts.len();
                let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
                let first = groups.first[c] as usize;
                let h = if first == c {
                    let e = (he_tail.len() / 2) as u32;
                    he_tail.push(VertexId(a));
                    he_tail.push(VertexId(b));
                    he_face.push(Some(face));
                    he_face.push(None);
                    2 * e
                } else {
                    let h0 = face_hes[first];
                    if he_tail[h0.index()] == VertexId(a) {
                        return Err(MeshError::InconsistentOrientation { face });
                    }
                    he_face[h0.index() ^ 1] = Some(face);
                    h0.0 ^ 1
                };
                face_verts.push(VertexId(a));
                face_hes.push(HalfEdgeId(h));
            }
            face_offsets.push(face_verts.len());
        }
        drop(groups);
        let nh = he_tail.len();
        let mut he_next = vec![None; nh];
        let mut he_prev = vec![None; nh];
        for f in 0..nf {
            let hs = &face_hes[face_offsets[f]..face_offsets[f + 1]];
            for k in 0..hs.len() {
                let (h, n) = (hs[k], hs[(k + 1) % hs.len()]);
                he_next[h.index()] = Some(n);
                he_prev[n.index()] = Some(h);
            }
        }

        // One-rings.
        let mut out_offsets = vec![0usize; nv + 1];
        for t in &he_tail {
            out_offsets[t.index() + 1] += 1;
        }
        for v in 0..nv {
            out_offsets[v + 1] += out_offsets[v];
        }
        let mut unordered = vec![HalfEdgeId(0); nh];
        let mut fill = out_offsets.clone();
        for (h, t) in he_tail.iter().enumerate() {
            unordered[fill[t.index()]] = HalfEdgeId(h as u32);
            fill[t.index()] += 1;
        }
        let twin = |h: HalfEdgeId| HalfEdgeId(h.0 ^ 1);
        let mut out_hes = Vec::with_capacity(nh);
        let mut boundary_vertex = vec![false; nv];
        for v in 0..nv {
            let ring = &unordered[out_offsets[v]..out_offsets[v + 1]];
            let mut starts = ring.iter().filter(|&&h| he_face[twin(h).index()].is_none());
            let first = starts.next().copied();
            if starts.next().is_some() {
                return Err(MeshError::NonManifoldVertex { v: VertexId(v as u32) });
            }
            boundary_vertex[v] = first.is_some();
            // ring is in increasing id order, so ring[0] is the smallest id.
            let start = first.unwrap_or(ring[0]);
            let before = out_hes.len();
            let mut cur = start;
            loop {
                out_hes.push(cur);
                if out_hes.len() - before > ring.len() {
                    return Err(MeshError::NonManifoldVertex { v: VertexId(v as u32) });
                }
                // CCW successor: sweep across the face on the left of `cur`.
                let Some(p) = he_prev[cur.index()] else { break };
                let nxt = twin(p);
                if nxt == start {
                    break;
                }
                cur = nxt;
            }
            if out_hes.len() - before != ring.len() {
                return Err(MeshError::NonManifoldVertex { v: VertexId(v as u32) });
            }
        }

        let mesh = Mesh {
            positions,
            face_offsets,
            face_verts,
            face_hes,
            he_tail,
            he_face,
            he_next,
            he_prev,
            out_offsets,
            out_hes,
            boundary_vertex,
        };
        if check_geometry {
            mesh.check_angle_sums()?;
        }
        Ok(mesh)
    }

    /// Checks that the corner angles around every vertex add up to one turn (interior) or less
    /// than one turn (boundary).
    fn check_angle_sums(&self) -> Result<(), MeshError> {
        for v in self.vertices() {
            if !self.angle_sum_ok(v) {
                return Err(MeshError::OverlappingFaces { v });
            }
        }
        Ok(())
    }

    /// Sum of the corner angles of the faces around `v` is consistent with a planar fan.
    pub(crate) fn angle_sum_ok(&self, v: VertexId) -> bool {
        self.angle_sum_ok_at(v, &self.positions)
    }

    /// As [`angle_sum_ok`](Self::angle_sum_ok), with positions taken from `pos`.
    pub(crate) fn angle_sum_ok_at(&self, v: VertexId, pos: &[[f64; 2]]) -> bool {
        let mut sum = 0.0;
        for &h in self.outgoing(v) {
            if let Some(p) = self.he_prev[h.index()] {
                let prev = pos[self.he_tail(p).index()];
                let next = pos[self.he_head(h).index()];
                sum += geom::corner_angle(prev, pos[v.index()], next);
            }
        }
        if self.boundary_vertex[v.index()] {
            sum < TAU - 1e-9
        } else {
            (sum - TAU).abs() <= 1e-6
        }
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of (undirected) edges.
    pub fn num_edges(&self) -> usize {
        self.he_tail.len() / 2
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.face_offsets.len() - 1
    }

    /// Number of half-edges (twice the number of edges).
    pub fn num_half_edges(&self) -> usize {
        self.he_tail.len()
    }

    /// All vertex ids, in order.
    pub fn vertices(&self) -> impl Iterator<Item = VertexId> {
        (0..self.num_vertices() as u32).map(VertexId)
    }

    /// All edge ids, in order.
    pub fn edges(&self) -> impl Iterator<Item = EdgeId> {
        (0..self.num_edges() as u32).map(EdgeId)
    }

    /// All face ids, in order.
    pub fn faces(&self) -> impl Iterator<Item = FaceId> {
        (0..self.num_faces() as u32).map(FaceId)
    }

    /// All half-edge ids, in order.
    pub fn half_edges(&self) -> impl Iterator<Item = HalfEdgeId> {
        (0..self.num_half_edges() as u32).map(HalfEdgeId)
    }

    /// Position of a vertex.
    pub fn position(&self, v: VertexId) -> [f64; 2] {
        self.positions[v.index()]
    }

    /// All vertex positions, indexed by vertex id.
    pub fn positions(&self) -> &[[f64; 2]] {
        &self.positions
    }

    /// Endpoints `(a, b)` of an edge; half-edge `2e` runs `a → b`.
    pub fn edge_vertices(&self, e: EdgeId) -> (VertexId, VertexId) {
        (self.he_tail[2 * e.index()], self.he_tail[2 * e.index() + 1])
    }

    /// Euclidean length of an edge.
    pub fn edge_length(&self, e: EdgeId) -> f64 {
        let (a, b) = self.edge_vertices(e);
        geom::dist(self.position(a), self.position(b))
    }

    /// The two half-edges of an edge: `[a → b, b → a]`, i.e. `[2e, 2e + 1]`.
    pub fn edge_half_edges(&self, e: EdgeId) -> [HalfEdgeId; 2] {
        [HalfEdgeId(2 * e.0), HalfEdgeId(2 * e.0 + 1)]
    }

    /// The edge a half-edge belongs to (`h / 2`).
    pub fn he_edge(&self, h: HalfEdgeId) -> EdgeId {
        EdgeId(h.0 / 2)
    }

    /// Tail (start) vertex of a half-edge.
    pub fn he_tail(&self, h: HalfEdgeId) -> VertexId {
        self.he_tail[h.index()]
    }

    /// Head (end) vertex of a half-edge.
    pub fn he_head(&self, h: HalfEdgeId) -> VertexId {
        self.he_tail[h.index() ^ 1]
    }

    /// The opposite half-edge (`h ^ 1`).
    pub fn he_twin(&self, h: HalfEdgeId) -> HalfEdgeId {
        HalfEdgeId(h.0 ^ 1)
    }

    /// The face to the left of a half-edge (`None` on the boundary side).
    pub fn he_face(&self, h: HalfEdgeId) -> Option<FaceId> {
        self.he_face[h.index()]
    }

    /// The next half-edge counter-clockwise around `he_face(h)` (`None` if `h` has no face).
    pub fn he_next(&self, h: HalfEdgeId) -> Option<HalfEdgeId> {
        self.he_next[h.index()]
    }

    /// The previous half-edge around `he_face(h)` (`None` if `h` has no face).
    pub fn he_prev(&self, h: HalfEdgeId) -> Option<HalfEdgeId> {
        self.he_prev[h.index()]
    }

    /// Euclidean length of a half-edge (the length of its edge).
    pub fn he_length(&self, h: HalfEdgeId) -> f64 {
        self.edge_length(self.he_edge(h))
    }

    /// The half-edge `from → to`, if the two vertices are joined by an edge.
    pub fn half_edge_between(&self, from: VertexId, to: VertexId) -> Option<HalfEdgeId> {
        self.outgoing(from).iter().copied().find(|&h| self.he_head(h) == to)
    }

    /// Half-edges leaving `v`, in counter-clockwise angular order. An interior vertex's list
    /// starts at its smallest half-edge id; a boundary vertex's list starts right after the
    /// boundary gap (`outgoing[0]` and `outgoing[last]` are its boundary edges and
    /// `he_face(outgoing[last])` is `None`). In both cases `he_face(outgoing[i])` is the face
    /// between `outgoing[i]` and `outgoing[i + 1]`.
    pub fn outgoing(&self, v: VertexId) -> &[HalfEdgeId] {
        &self.out_hes[self.out_offsets[v.index()]..self.out_offsets[v.index() + 1]]
    }

    /// The one-ring `N_v`: heads of [`outgoing`](Self::outgoing), in the same order.
    pub fn neighbors(&self, v: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        self.outgoing(v).iter().map(move |&h| self.he_head(h))
    }

    /// Edges at `v`, in the order of [`outgoing`](Self::outgoing).
    pub fn incident_edges(&self, v: VertexId) -> impl Iterator<Item = EdgeId> + '_ {
        self.outgoing(v).iter().map(move |&h| self.he_edge(h))
    }

    /// Faces around `v`, counter-clockwise, in the order of [`outgoing`](Self::outgoing)
    /// (`valence − 1` faces at a boundary vertex, `valence` at an interior one).
    pub fn vertex_faces(&self, v: VertexId) -> impl Iterator<Item = FaceId> + '_ {
        self.outgoing(v).iter().filter_map(move |&h| self.he_face(h))
    }

    /// Number of edges at `v`.
    pub fn valence(&self, v: VertexId) -> usize {
        self.out_offsets[v.index() + 1] - self.out_offsets[v.index()]
    }

    /// Whether `v` lies on the mesh boundary (outer boundary or a hole).
    pub fn is_boundary_vertex(&self, v: VertexId) -> bool {
        self.boundary_vertex[v.index()]
    }

    /// Whether `e` has a face on one side only.
    pub fn is_boundary_edge(&self, e: EdgeId) -> bool {
        self.he_face[2 * e.index() + 1].is_none()
    }

    /// All boundary vertices, in id order.
    pub fn boundary_vertices(&self) -> Vec<VertexId> {
        self.vertices().filter(|&v| self.is_boundary_vertex(v)).collect()
    }

    /// All boundary edges, in id order.
    pub fn boundary_edges(&self) -> Vec<EdgeId> {
        self.edges().filter(|&e| self.is_boundary_edge(e)).collect()
    }

    /// The boundary as closed loops of faceless half-edges (each the `2e + 1` of a boundary edge).
    /// The mesh lies to the right of these half-edges: outer boundaries run clockwise, holes
    /// counter-clockwise. Loops are ordered by, and start at, their smallest half-edge id.
    pub fn boundary_loops(&self) -> Vec<Vec<HalfEdgeId>> {
        let mut done = vec![false; self.num_half_edges()];
        let mut loops = Vec::new();
        for e in self.edges() {
            let h0 = HalfEdgeId(2 * e.0 + 1);
            if self.he_face(h0).is_some() || done[h0.index()] {
                continue;
            }
            let mut lp = Vec::new();
            let mut h = h0;
            loop {
                done[h.index()] = true;
                lp.push(h);
                // The next faceless half-edge leaves head(h) as its last outgoing half-edge.
                let Some(&n) = self.outgoing(self.he_head(h)).last() else {
                    break;
                };
                if n == h0 || done[n.index()] || self.he_face(n).is_some() {
                    break;
                }
                h = n;
            }
            loops.push(lp);
        }
        loops
    }

    /// A face's vertices, counter-clockwise.
    pub fn face_vertices(&self, f: FaceId) -> &[VertexId] {
        &self.face_verts[self.face_offsets[f.index()]..self.face_offsets[f.index() + 1]]
    }

    /// A face's half-edges, counter-clockwise: `face_half_edges(f)[i]` runs
    /// `face_vertices(f)[i] → face_vertices(f)[i + 1]` (cyclically).
    pub fn face_half_edges(&self, f: FaceId) -> Vec<HalfEdgeId> {
        self.face_half_edges_slice(f).to_vec()
    }

    /// Slice form of [`face_half_edges`](Self::face_half_edges).
    pub fn face_half_edges_slice(&self, f: FaceId) -> &[HalfEdgeId] {
        &self.face_hes[self.face_offsets[f.index()]..self.face_offsets[f.index() + 1]]
    }

    /// A face's edges, in the order of [`face_half_edges`](Self::face_half_edges) (so in a quad,
    /// edges `i` and `i + 2` are opposite).
    pub fn face_edges(&self, f: FaceId) -> Vec<EdgeId> {
        self.face_half_edges_slice(f).iter().map(|&h| self.he_edge(h)).collect()
    }

    /// The faces on the two sides of an edge: `[left of 2e, left of 2e + 1]`. The first is always
    /// `Some`; the second is `None` for a boundary edge.
    pub fn edge_faces(&self, e: EdgeId) -> [Option<FaceId>; 2] {
        [self.he_face[2 * e.index()], self.he_face[2 * e.index() + 1]]
    }

    /// Number of vertices (= edges) of a face.
    pub fn face_size(&self, f: FaceId) -> usize {
        self.face_offsets[f.index() + 1] - self.face_offsets[f.index()]
    }

    fn face_points(&self, f: FaceId) -> Vec<[f64; 2]> {
        self.face_vertices(f).iter().map(|&v| self.position(v)).collect()
    }

    /// Area centroid of a face.
    pub fn face_centroid(&self, f: FaceId) -> [f64; 2] {
        geom::centroid(&self.face_points(f))
    }

    /// Area of a face (positive).
    pub fn face_area(&self, f: FaceId) -> f64 {
        geom::signed_area(&self.face_points(f)).abs()
    }

    /// Axis-aligned bounding box `(min, max)` of all vertices.
    pub fn bounding_box(&self) -> ([f64; 2], [f64; 2]) {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in &self.positions {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }

    /// The vertex closest to `p` (the smallest id on ties); `None` if `p` is not finite.
    pub fn nearest_vertex(&self, p: [f64; 2]) -> Option<VertexId> {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return None;
        }
        let mut best: Option<(f64, VertexId)> = None;
        for v in self.vertices() {
            let q = self.position(v);
            let d = (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
            if best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, v));
            }
        }
        best.map(|(_, v)| v)
    }

    /// Breadth-first search on the mesh graph from `from`: every vertex at most `max_hops` edges
    /// away (including `from` itself at 0), with its hop count, sorted by `(hops, id)`.
    pub fn hop_distances(&self, from: VertexId, max_hops: usize) -> Vec<(VertexId, usize)> {
        let mut dist = vec![usize::MAX; self.num_vertices()];
        let mut queue = VecDeque::new();
        dist[from.index()] = 0;
        queue.push_back(from);
        let mut out = Vec::new();
        while let Some(v) = queue.pop_front() {
            let d = dist[v.index()];
            out.push((v, d));
            if d == max_hops {
                continue;
            }
            for w in self.neighbors(v) {
                if dist[w.index()] == usize::MAX {
                    dist[w.index()] = d + 1;
                    queue.push_back(w);
                }
            }
        }
        out.sort_by_key(|&(v, d)| (d, v));
        out
    }

    /// The input form: positions and counter-clockwise face loops (what
    /// [`from_polygons`](Self::from_polygons) takes back to rebuild an equal mesh).
    pub fn to_polygons(&self) -> (Vec<[f64; 2]>, Vec<Vec<u32>>) {
        let faces = self.faces().map(|f| self.face_vertices(f).iter().map(|v| v.0).collect()).collect();
        (self.positions.clone(), faces)
    }
}

/// Corners (face sides, numbered in face-walk order) grouped by undirected edge.
struct CornerGroups {
    /// `first[c]`: the first corner (in walk order) on the same undirected edge as corner `c`.
    first: Vec<u32>,
    /// Endpoints `(min, max)` of the edge whose third corner comes first, if any edge has more
    /// than two.
    non_manifold: Option<(u32, u32)>,
}

impl CornerGroups {
    /// Buckets corners by their smaller endpoint, then sorts each bucket by the larger one.
    /// Indices must be valid.
    fn new(faces: &[Vec<u32>], nv: usize) -> CornerGroups {
        let corners: usize = faces.iter().map(Vec::len).sum();
        let key = |lp: &[u32], k: usize| {
            let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
            (a.min(b), a.max(b))
        };
        let mut offsets = vec![0usize; nv + 1];
        for lp in faces {
            for k in 0..lp.len() {
                offsets[key(lp, k).0 as usize + 1] += 1;
            }
        }
        for v in 0..nv {
            offsets[v + 1] += offsets[v];
        }
        // (larger endpoint, corner), filled in corner order.
        let mut entries = vec![(0u32, 0u32); corners];
        let mut fill = offsets.clone();
        let mut c = 0u32;
        for lp in faces {
            for k in 0..lp.len() {
                let (lo, hi) = key(lp, k);
                entries[fill[lo as usize]] = (hi, c);
                fill[lo as usize] += 1;
                c += 1;
            }
        }
        let mut first = vec![0u32; corners];
        let mut worst: Option<(u32, u32, u32)> = None; // (third corner, lo, hi)
        for lo in 0..nv {
            let bucket = &mut entries[offsets[lo]..offsets[lo + 1]];
            bucket.sort_unstable();
            let mut i = 0;
            while i < bucket.len() {
                let mut j = i;
                while j < bucket.len() && bucket[j].0 == bucket[i].0 {
                    first[bucket[j].1 as usize] = bucket[i].1;
                    j += 1;
                }
                if j - i > 2 && worst.is_none_or(|w| bucket[i + 2].1 < w.0) {
                    worst = Some((bucket[i + 2].1, lo as u32, bucket[i].0));
                }
                i = j;
            }
        }
        CornerGroups { first, non_manifold: worst.map(|(_, a, b)| (a, b)) }
    }
}

/// Counts, plus the positions and face loops for small meshes (≤ 32 faces).
impl std::fmt::Debug for Mesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("Mesh");
        d.field("num_vertices", &self.num_vertices())
            .field("num_edges", &self.num_edges())
            .field("num_faces", &self.num_faces());
        if self.num_faces() <= 32 {
            d.field("positions", &self.positions);
            d.field("faces", &self.faces().map(|f| self.face_vertices(f)).collect::<Vec<_>>());
        }
        d.finish_non_exhaustive()
    }
}

/// The lexicographically smallest pair `(a, b)`, `a < b`, of positions within the duplicate
/// tolerance, if any.
pub(crate) fn first_duplicate(positions: &[[f64; 2]]) -> Option<(usize, usize)> {
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by(|&i, &j| {
        // `+ 0.0` turns −0 into +0, so that the order agrees with `==` on runs of equal x.
        let (p, q) = (positions[i], positions[j]);
        (p[0] + 0.0).total_cmp(&(q[0] + 0.0)).then((p[1] + 0.0).total_cmp(&(q[1] + 0.0))).then(i.cmp(&j))
    });
    // run_end[k]: one past the last sorted position with the same x as sorted position k.
    let n = order.len();
    let mut run_end = vec![n; n];
    for k in (0..n.saturating_sub(1)).rev() {
        let same = positions[order[k]][0] == positions[order[k + 1]][0];
        run_end[k] = if same { run_end[k + 1] } else { k + 1 };
    }
    let mut best: Option<(usize, usize)> = None;
    for k in 0..n {
        let p = positions[order[k]];
        let mut l = k + 1;
        while l < n {
            let q = positions[order[l]];
            if q[0] - p[0] > DUPLICATE_TOLERANCE {
                break;
            }
            if q[1] - p[1] > DUPLICATE_TOLERANCE {
                // Sorted by y within a run of equal x: the rest of q's run is farther away.
                l = run_end[l];
                continue;
            }
            if geom::dist(p, q) <= DUPLICATE_TOLERANCE {
                let (i, j) = (order[k], order[l]);
                let pair = (i.min(j), i.max(j));
                if best.is_none_or(|b| pair < b) {
                    best = Some(pair);
                }
            }
            l += 1;
        }
    }
    best
}
