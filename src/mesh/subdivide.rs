//! Catmull–Clark-style subdivision that keeps every vertex where it is.

use super::halfedge::Mesh;
use super::ids::{EdgeId, FaceId, VertexId};

/// The result of [`subdivide`]: the finer mesh and how its elements relate to the coarse one.
#[derive(Clone, Debug, PartialEq)]
pub struct Subdivision {
    /// The subdivided mesh (all faces quads).
    pub mesh: Mesh,
    /// `edge_children[e]` = the two new edges that make up old edge `e`; the first touches
    /// `edge_vertices(e).0`, the second `edge_vertices(e).1`.
    pub edge_children: Vec<[EdgeId; 2]>,
    /// `vertex_map[v]` = the new id of old vertex `v` (always `v` itself).
    pub vertex_map: Vec<VertexId>,
    /// `edge_midpoint[e]` = the new vertex at the midpoint of old edge `e` (id `V + e`).
    pub edge_midpoint: Vec<VertexId>,
    /// `face_center[f]` = the new vertex at the centroid of old face `f` (id `V + E + f`).
    pub face_center: Vec<VertexId>,
    /// `face_children[f][i]` = the new quad at corner `face_vertices(f)[i]` of old face `f`.
    /// The children of a face are consecutive ids, faces in old face order.
    pub face_children: Vec<Vec<FaceId>>,
}

/// Splits every n-gon into n quads without moving any vertex.
///
/// Vertices: the old vertices keep their ids and positions; then one new vertex at each edge
/// midpoint (ids `V + e`, in edge order); then one at each face's area centroid (ids
/// `V + E + f`). Each face `f` with corners `v_0 … v_{n−1}` becomes, for `i = 0 … n−1`, the
/// quad `[v_i, mid(v_i v_{i+1}), centre(f), mid(v_{i−1} v_i)]` (counter-clockwise), with ids in
/// that order. So `V' = V + E + F`, `E' = 2E + Σ|f|`, `F' = Σ|f|`. New edges are numbered by first
/// appearance like any mesh.
///
/// Unlike Catmull–Clark, positions are not smoothed: the subdivided mesh covers exactly the same
/// region. For convex faces every child quad is valid; a strongly non-convex face (whose centroid
/// does not see all its edge midpoints) can give inverted child quads, which are still returned
/// with the correct connectivity (the geometric checks of [`Mesh::from_polygons`] are skipped).
pub fn subdivide(mesh: &Mesh) -> Subdivision {
    let nv = mesh.num_vertices();
    let ne = mesh.num_edges();
    let mut positions = Vec::with_capacity(nv + ne + mesh.num_faces());
    positions.extend_from_slice(mesh.positions());
    for e in mesh.edges() {
        let (a, b) = mesh.edge_vertices(e);
        let (p, q) = (mesh.position(a), mesh.position(b));
        positions.push([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]);
    }
    for f in mesh.faces() {
        positions.push(mesh.face_centroid(f));
    }

    let mid = |e: EdgeId| (nv + e.index()) as u32;
    let mut faces = Vec::new();
    let mut face_children = Vec::with_capacity(mesh.num_faces());
    for f in mesh.faces() {
        let centre = (nv + ne + f.index()) as u32;
        let vs = mesh.face_vertices(f);
        let hs = mesh.face_half_edges_slice(f);
        let n = vs.len();
        let mut children = Vec::with_capacity(n);
        for i in 0..n {
            let prev = hs[(i + n - 1) % n];
            children.push(FaceId(faces.len() as u32));
            faces.push(vec![vs[i].0, mid(mesh.he_edge(hs[i])), centre, mid(mesh.he_edge(prev))]);
        }
        face_children.push(children);
    }

    let fine = Mesh::build(positions, faces, false).expect("subdivision of a valid mesh is combinatorially valid");
    let edge_children = mesh
        .edges()
        .map(|e| {
            let (a, b) = mesh.edge_vertices(e);
            let m = VertexId(mid(e));
            let child = |x: VertexId, y: VertexId| {
                fine.he_edge(fine.half_edge_between(x, y).expect("the halves of a subdivided edge exist"))
            };
            [child(a, m), child(m, b)]
        })
        .collect();
    Subdivision {
        edge_children,
        vertex_map: mesh.vertices().collect(),
        edge_midpoint: mesh.edges().map(|e| VertexId(mid(e))).collect(),
        face_center: mesh.faces().map(|f| VertexId((nv + ne + f.index()) as u32)).collect(),
        face_children,
        mesh: fine,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{clipped_grid, grid, jitter, Mesh};

    fn check(m: &Mesh) -> Subdivision {
        let s = subdivide(m);
        let (v, e, f) = (m.num_vertices(), m.num_edges(), m.num_faces());
        let corners: usize = m.faces().map(|f| m.face_size(f)).sum();
        assert_eq!(s.mesh.num_vertices(), v + e + f);
        assert_eq!(s.mesh.num_edges(), 2 * e + corners);
        assert_eq!(s.mesh.num_faces(), corners);
        assert!(s.mesh.faces().all(|f| s.mesh.face_size(f) == 4));
        // Geometrically valid too (for convex input faces): full validation accepts it.
        let (p, fs) = s.mesh.to_polygons();
        assert_eq!(Mesh::from_polygons(p, fs).unwrap(), s.mesh);
        for old in m.vertices() {
            assert_eq!(s.vertex_map[old.index()], old);
            assert_eq!(s.mesh.position(old), m.position(old));
            assert_eq!(s.mesh.is_boundary_vertex(old), m.is_boundary_vertex(old));
        }
        for old in m.edges() {
            let (a, b) = m.edge_vertices(old);
            let mid = s.edge_midpoint[old.index()];
            let [c0, c1] = s.edge_children[old.index()];
            let ends = |e: EdgeId| {
                let (x, y) = s.mesh.edge_vertices(e);
                (x.min(y), x.max(y))
            };
            assert_eq!(ends(c0), (a.min(mid), a.max(mid)));
            assert_eq!(ends(c1), (b.min(mid), b.max(mid)));
            let total = s.mesh.edge_length(c0) + s.mesh.edge_length(c1);
            assert!((total - m.edge_length(old)).abs() <= 1e-12 * m.edge_length(old).max(1.0));
            assert_eq!(s.mesh.is_boundary_edge(c0), m.is_boundary_edge(old));
            assert_eq!(s.mesh.valence(mid), if m.is_boundary_edge(old) { 3 } else { 4 });
        }
        for old in m.faces() {
            let c = s.face_center[old.index()];
            assert_eq!(s.mesh.position(c), m.face_centroid(old));
            assert_eq!(s.mesh.valence(c), m.face_size(old));
            let kids = &s.face_children[old.index()];
            for (i, &k) in kids.iter().enumerate() {
                assert_eq!(s.mesh.face_vertices(k)[0], m.face_vertices(old)[i]);
                assert!(s.mesh.face_vertices(k).contains(&c));
            }
            let area: f64 = kids.iter().map(|&k| s.mesh.face_area(k)).sum();
            assert!((area - m.face_area(old)).abs() <= 1e-9 * m.face_area(old));
        }
        s
    }

    #[test]
    fn subdivide_grid() {
        let s = check(&grid(3, 2, 1.0));
        assert_eq!(s.mesh.num_faces(), 24);
        // Subdividing a grid gives the grid at half the spacing, up to numbering.
        assert_eq!(s.mesh.num_edges(), grid(6, 4, 0.5).num_edges());
        assert_eq!(s.mesh.boundary_vertices().len(), grid(6, 4, 0.5).boundary_vertices().len());
    }

    #[test]
    fn subdivide_triangle_and_pentagon() {
        // A pentagon with a triangle on its top-right side and a quad below.
        let positions =
            vec![[0.0, 0.0], [2.0, 0.0], [2.6, 1.6], [1.0, 2.6], [-0.6, 1.6], [3.4, 3.0], [0.0, -1.5], [2.0, -1.5]];
        let faces = vec![vec![0, 1, 2, 3, 4], vec![2, 5, 3], vec![0, 6, 7, 1]];
        let m = Mesh::from_polygons(positions, faces).unwrap();
        let s = check(&m);
        assert_eq!(m.num_edges(), 10);
        assert_eq!(s.mesh.num_vertices(), 8 + 10 + 3);
        assert_eq!(s.mesh.num_faces(), 5 + 3 + 4);
        // Twice is fine as well.
        check(&s.mesh);
    }

    #[test]
    fn subdivide_clipped_and_jittered() {
        let outer = vec![[0.0, 0.0], [6.0, 0.0], [6.0, 3.0], [3.0, 3.0], [3.0, 6.0], [0.0, 6.0]];
        check(&jitter(&clipped_grid(&outer, &[], 1.0).unwrap(), 0.3, 5));
    }
}
