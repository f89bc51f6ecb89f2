//! Tests of construction, validation, JSON and the shared invariant checker.

use super::*;
use crate::geometry as geom;
use proptest::prelude::*;
use std::f64::consts::TAU;

fn angle(m: &Mesh, h: HalfEdgeId) -> f64 {
    let a = m.position(m.he_tail(h));
    let b = m.position(m.he_head(h));
    (b[1] - a[1]).atan2(b[0] - a[0])
}

/// Checks the structural invariants every mesh must satisfy (used by all mesh tests).
pub(crate) fn check_invariants(m: &Mesh) {
    for h in m.half_edges() {
        assert_eq!(m.he_twin(m.he_twin(h)), h);
        assert_eq!(m.he_head(h), m.he_tail(m.he_twin(h)));
        assert_eq!(m.he_edge(h).0, h.0 / 2);
        match m.he_face(h) {
            Some(f) => {
                let n = m.he_next(h).unwrap();
                assert_eq!(m.he_tail(n), m.he_head(h));
                assert_eq!(m.he_prev(n), Some(h));
                assert_eq!(m.he_face(n), Some(f));
            }
            None => {
                assert!(m.he_next(h).is_none() && m.he_prev(h).is_none());
                assert_eq!(h.0 % 2, 1, "half-edge 2e always has a face");
            }
        }
    }
    for v in m.vertices() {
        let out = m.outgoing(v);
        assert_eq!(out.len(), m.valence(v));
        assert!(out.iter().all(|&h| m.he_tail(h) == v));
        assert_eq!(m.neighbors(v).collect::<Vec<_>>(), out.iter().map(|&h| m.he_head(h)).collect::<Vec<_>>());
        assert_eq!(m.incident_edges(v).collect::<Vec<_>>(), out.iter().map(|&h| m.he_edge(h)).collect::<Vec<_>>());
        // CCW: angles relative to the first direction increase strictly within one turn.
        let a0 = angle(m, out[0]);
        let mut last = -1.0;
        for &h in out {
            let a = (angle(m, h) - a0).rem_euclid(TAU);
            assert!(a > last, "outgoing({v}) is not CCW");
            last = a;
        }
        if m.is_boundary_vertex(v) {
            assert!(m.he_face(m.he_twin(out[0])).is_none());
            assert!(m.he_face(*out.last().unwrap()).is_none());
            assert_eq!(m.vertex_faces(v).count(), out.len() - 1);
        } else {
            assert!(out.iter().all(|&h| m.he_face(h).is_some()));
            assert_eq!(out[0], *out.iter().min().unwrap());
        }
        for (k, &h) in out.iter().enumerate() {
            assert_eq!(m.half_edge_between(v, m.he_head(h)), Some(h));
            if let Some(f) = m.he_face(h) {
                // The face between out[k] and out[k + 1] has both edges.
                let next = out[(k + 1) % out.len()];
                let es = m.face_edges(f);
                assert!(es.contains(&m.he_edge(h)) && es.contains(&m.he_edge(next)));
            }
        }
        // Every face containing v appears exactly once in its single fan.
        let mut containing: Vec<FaceId> = m.faces().filter(|&f| m.face_vertices(f).contains(&v)).collect();
        let mut fan: Vec<FaceId> = m.vertex_faces(v).collect();
        containing.sort();
        fan.sort();
        assert_eq!(containing, fan, "fan of {v}");
    }
    for f in m.faces() {
        let vs = m.face_vertices(f);
        let hs = m.face_half_edges(f);
        assert_eq!(vs.len(), hs.len());
        assert_eq!(m.face_edges(f), hs.iter().map(|&h| m.he_edge(h)).collect::<Vec<_>>());
        for i in 0..vs.len() {
            assert_eq!(m.he_tail(hs[i]), vs[i]);
            assert_eq!(m.he_head(hs[i]), vs[(i + 1) % vs.len()]);
            assert_eq!(m.he_face(hs[i]), Some(f));
        }
        assert!(geom::signed_area(&vs.iter().map(|&v| m.position(v)).collect::<Vec<_>>()) > 0.0);
    }
    for e in m.edges() {
        let [h0, h1] = m.edge_half_edges(e);
        let (a, b) = m.edge_vertices(e);
        assert_eq!((m.he_tail(h0), m.he_head(h0), m.he_tail(h1)), (a, b, b));
        assert_eq!(m.edge_faces(e), [m.he_face(h0), m.he_face(h1)]);
        assert!(m.edge_faces(e)[0].is_some());
        assert_eq!(m.is_boundary_edge(e), m.edge_faces(e)[1].is_none());
    }
    let nb: usize = m.boundary_loops().iter().map(Vec::len).sum();
    assert_eq!(nb, m.boundary_edges().len());
    // Rebuilding from the polygons gives the same mesh.
    let (p, f) = m.to_polygons();
    assert_eq!(&Mesh::from_polygons(p, f).unwrap(), m);
}

fn square_pair() -> Vec<[f64; 2]> {
    // 3 — 4 — 5
    // |   |   |
    // 0 — 1 — 2
    vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0]]
}

fn build(p: Vec<[f64; 2]>, f: &[&[u32]]) -> Result<Mesh, MeshError> {
    Mesh::from_polygons(p, f.iter().map(|l| l.to_vec()).collect())
}

#[test]
fn clockwise_input_is_normalised() {
    let cw = build(square_pair(), &[&[0, 3, 4, 1], &[1, 4, 5, 2]]).unwrap();
    let ccw = build(square_pair(), &[&[0, 1, 4, 3], &[1, 2, 5, 4]]).unwrap();
    assert_eq!(cw, ccw);
    check_invariants(&cw);
}

#[test]
fn mixed_polygon_sizes_and_straight_corners() {
    // A pentagon whose corner 1 is straight (a hanging vertex shared with two triangles below).
    let p = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0], [1.0, -1.0]];
    let m = build(p, &[&[0, 1, 2, 3, 4], &[0, 5, 1], &[1, 5, 2]]).unwrap();
    check_invariants(&m);
    assert_eq!(m.valence(VertexId(1)), 3);
    assert!(!m.is_boundary_vertex(VertexId(1)));
}

#[test]
fn error_non_manifold_edge() {
    // Three triangles on edge 0–1.
    let p = vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.5, -1.0], [0.5, 2.0]];
    let e = build(p, &[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4]]).unwrap_err();
    assert_eq!(e, MeshError::NonManifoldEdge { a: VertexId(0), b: VertexId(1) });
    assert_eq!(e.to_string(), "edge (0, 1) is used by more than two faces");
}

#[test]
fn error_duplicate_vertex() {
    let mut p = square_pair();
    p.push([1.0, 1.0 + 1e-13]);
    let e = build(p, &[&[0, 1, 4, 3], &[1, 2, 5, 6]]).unwrap_err();
    assert_eq!(e, MeshError::DuplicateVertex { a: VertexId(4), b: VertexId(6) });
    assert!(e.to_string().contains("4") && e.to_string().contains("6"));
}

#[test]
fn error_degenerate_faces() {
    let deg = |f: &[&[u32]]| match build(square_pair(), f) {
        Err(MeshError::DegenerateFace { face, reason }) => (face, reason),
        other => panic!("{other:?}"),
    };
    assert_eq!(deg(&[&[0, 1, 4, 3], &[1, 2]]), (FaceId(1), DegenerateReason::TooFewVertices));
    assert_eq!(deg(&[&[0, 1, 4, 1, 3]]), (FaceId(0), DegenerateReason::RepeatedVertex(VertexId(1))));
    // Collinear triangle: zero area.
    let p = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
    assert!(matches!(
        build(p, &[&[0, 1, 2]]),
        Err(MeshError::DegenerateFace { reason: DegenerateReason::ZeroArea, .. })
    ));
    // Bow tie.
    assert_eq!(deg(&[&[0, 1, 3, 5], &[1, 2, 5, 4]]), (FaceId(0), DegenerateReason::SelfIntersecting));
    // Near-zero area (sliver).
    let p = vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1e-14]];
    assert!(matches!(
        build(p, &[&[0, 1, 2]]),
        Err(MeshError::DegenerateFace { reason: DegenerateReason::ZeroArea, .. })
    ));
    let e = MeshError::DegenerateFace { face: FaceId(7), reason: DegenerateReason::RepeatedVertex(VertexId(3)) };
    assert_eq!(e.to_string(), "face 7 is degenerate: vertex 3 appears twice");
}

#[test]
fn error_inconsistent_orientation() {
    let e = build(square_pair(), &[&[0, 1, 4, 3], &[1, 4, 5, 2]]).unwrap_err();
    assert_eq!(e, MeshError::InconsistentOrientation { face: FaceId(1) });
    // The minority is blamed, whichever face comes first.
    let p = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0], [3.0, 1.0]];
    let e = build(p, &[&[0, 4, 5, 1], &[1, 2, 6, 5], &[2, 3, 7, 6]]).unwrap_err();
    assert_eq!(e, MeshError::InconsistentOrientation { face: FaceId(0) });
    // Two CCW faces on the same side of an edge (overlap) use it in the same direction.
    let p = vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.5, 2.0]];
    let e = build(p, &[&[0, 1, 2], &[0, 1, 3]]).unwrap_err();
    assert_eq!(e, MeshError::InconsistentOrientation { face: FaceId(1) });
}

#[test]
fn error_isolated_vertex() {
    let mut p = square_pair();
    p.push([5.0, 5.0]);
    let e = build(p, &[&[0, 1, 4, 3], &[1, 2, 5, 4]]).unwrap_err();
    assert_eq!(e, MeshError::IsolatedVertex { v: VertexId(6) });
    assert_eq!(e.to_string(), "vertex 6 is isolated (used by no face)");
}

#[test]
fn error_bad_index_non_finite_empty() {
    let e = build(square_pair(), &[&[0, 1, 4, 3], &[1, 2, 9, 4]]).unwrap_err();
    assert_eq!(e, MeshError::BadIndex { face: FaceId(1), index: 9 });
    assert!(e.to_string().contains("face 1") && e.to_string().contains("9"));
    let mut p = square_pair();
    p[2] = [f64::NAN, 0.0];
    assert_eq!(build(p, &[&[0, 1, 4, 3]]).unwrap_err(), MeshError::NonFinitePosition { v: VertexId(2) });
    assert!(matches!(build(square_pair(), &[]), Err(MeshError::Empty { .. })));
    assert!(matches!(build(vec![], &[]), Err(MeshError::Empty { .. })));
}

#[test]
fn error_non_manifold_vertex() {
    // Two squares touching only at vertex 2.
    let p = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]];
    let e = build(p, &[&[0, 1, 2, 3], &[2, 4, 5, 6]]).unwrap_err();
    assert_eq!(e, MeshError::NonManifoldVertex { v: VertexId(2) });
    assert!(e.to_string().contains("vertex 2"));
}

#[test]
fn error_overlapping_faces() {
    // A fan of triangles around vertex 0 wrapping past a full turn at a boundary vertex.
    let mut p = vec![[0.0, 0.0]];
    let n = 7;
    for k in 0..n {
        let t = 1.25 * TAU * k as f64 / (n - 1) as f64;
        let r = 1.0 + 0.1 * k as f64;
        p.push([r * t.cos(), r * t.sin()]);
    }
    let faces: Vec<Vec<u32>> = (1..n as u32).map(|k| vec![0, k, k + 1]).collect();
    let e = Mesh::from_polygons(p, faces).unwrap_err();
    assert_eq!(e, MeshError::OverlappingFaces { v: VertexId(0) });
}

#[test]
fn json_round_trip_and_validation() {
    let m = jitter(&clipped_grid(&[[0.0, 0.0], [5.0, 0.0], [5.0, 3.0], [0.0, 4.0]], &[], 0.5).unwrap(), 0.2, 3);
    let text = serde_json::to_string(&m).unwrap();
    let back: Mesh = serde_json::from_str(&text).unwrap();
    // serde_json parses floats exactly only with its `float_roundtrip` feature; without it the
    // last bit may differ, so compare connectivity exactly and positions to a few ulps.
    let (p0, f0) = m.to_polygons();
    let (p1, f1) = back.to_polygons();
    assert_eq!(f0, f1);
    for (a, b) in p0.iter().zip(&p1) {
        for k in 0..2 {
            assert!((a[k] - b[k]).abs() <= 4.0 * f64::EPSILON * a[k].abs().max(1.0), "{a:?} vs {b:?}");
        }
    }
    // Exactly representable coordinates round-trip exactly.
    let g = clipped_grid(&[[0.0, 0.0], [5.0, 0.0], [5.0, 3.0], [0.0, 4.0]], &[], 0.25).unwrap();
    assert_eq!(serde_json::from_str::<Mesh>(&serde_json::to_string(&g).unwrap()).unwrap(), g);

    let fixture: Mesh = serde_json::from_str(include_str!("../../fixtures/mesh/grid_2x2.json")).unwrap();
    assert_eq!(fixture, grid(2, 2, 1.0));
    let v: serde_json::Value = serde_json::to_value(grid(1, 1, 2.0)).unwrap();
    assert_eq!(
        v,
        serde_json::json!({"vertices": [[0.0, 0.0], [2.0, 0.0], [0.0, 2.0], [2.0, 2.0]], "faces": [[0, 1, 3, 2]]})
    );

    let bad = r#"{"vertices": [[0,0],[1,0],[0,1],[9,9]], "faces": [[0,1,2]]}"#;
    let err = serde_json::from_str::<Mesh>(bad).unwrap_err();
    assert!(err.to_string().contains("vertex 3 is isolated"), "{err}");
    let unknown = r#"{"vertices": [[0,0],[1,0],[0,1]], "faces": [[0,1,2]], "extra": 1}"#;
    assert!(serde_json::from_str::<Mesh>(unknown).is_err());
}

#[test]
fn accessors_on_small_mesh() {
    let m = build(square_pair(), &[&[0, 1, 4, 3], &[1, 2, 5, 4]]).unwrap();
    assert_eq!((m.num_vertices(), m.num_edges(), m.num_faces(), m.num_half_edges()), (6, 7, 2, 14));
    let e = m.he_edge(m.half_edge_between(VertexId(1), VertexId(4)).unwrap());
    assert_eq!(e, EdgeId(1));
    assert_eq!(m.edge_faces(e), [Some(FaceId(0)), Some(FaceId(1))]);
    assert!(!m.is_boundary_edge(e));
    assert_eq!(m.edge_length(e), 1.0);
    assert_eq!(m.half_edge_between(VertexId(0), VertexId(5)), None);
    assert_eq!(m.boundary_vertices().len(), 6);
    assert_eq!(m.boundary_edges().len(), 6);
    // Vertex 1 (bottom middle): after the gap, east (2), north (4), west (0).
    assert_eq!(m.neighbors(VertexId(1)).collect::<Vec<_>>(), vec![VertexId(2), VertexId(4), VertexId(0)]);
    assert_eq!(m.vertex_faces(VertexId(1)).collect::<Vec<_>>(), vec![FaceId(1), FaceId(0)]);
    assert_eq!(m.face_area(FaceId(0)), 1.0);
    assert_eq!(m.boundary_loops().len(), 1);
    check_invariants(&m);
}

proptest! {
    /// from_polygons never panics on arbitrary small inputs, and accepted meshes are consistent.
    #[test]
    fn from_polygons_never_panics(
        pts in prop::collection::vec((0i32..4, 0i32..4), 0..10),
        faces in prop::collection::vec(prop::collection::vec(0u32..12, 0..6), 0..6),
    ) {
        let positions: Vec<[f64; 2]> = pts.iter().map(|&(x, y)| [x as f64, y as f64]).collect();
        if let Ok(m) = Mesh::from_polygons(positions, faces) {
            check_invariants(&m);
        }
    }

    /// Jitter keeps random clipped grids valid.
    #[test]
    fn jitter_stays_valid(seed in any::<u64>(), amount in 0.0f64..1.5, w in 1usize..6, h in 1usize..6) {
        let m = grid(w, h, 1.0);
        let j = jitter(&m, amount, seed);
        check_invariants(&j);
        prop_assert_eq!(j.boundary_vertices(), m.boundary_vertices());
    }
}

#[test]
fn duplicate_detection_is_exhaustive() {
    // Brute force against the sweep on small random-ish point sets with near duplicates.
    let mut state = 12345u64;
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 33) as i64
    };
    for _ in 0..300 {
        let n = 2 + (next() % 12) as usize;
        let pts: Vec<[f64; 2]> = (0..n)
            .map(|_| {
                let x = (next() % 3) as f64 * if next() % 2 == 0 { 1.0 } else { -1.0 } * 0.5;
                let y = (next() % 3) as f64 + if next() % 4 == 0 { 5e-13 } else { 0.0 };
                [x + 0.0 * (next() % 2) as f64, y]
            })
            .collect();
        let mut brute = None;
        for i in 0..n {
            for j in i + 1..n {
                if brute.is_none() && geom::dist(pts[i], pts[j]) <= 1e-12 {
                    brute = Some((i, j));
                }
            }
        }
        assert_eq!(super::halfedge::first_duplicate(&pts), brute, "{pts:?}");
    }
    // Signed zeros.
    let pts = vec![[-0.0, 0.0], [-0.0, 5.0], [0.0, 0.0]];
    assert_eq!(super::halfedge::first_duplicate(&pts), Some((0, 2)));
}

proptest! {
    /// Random sets of grid cells: accepted exactly when no two cells touch only at a corner,
    /// and accepted meshes satisfy every invariant (in both input orientations).
    #[test]
    fn random_cell_sets(mask in prop::collection::vec(any::<bool>(), 25), cw in any::<bool>()) {
        let n = 5usize;
        let kept = |i: isize, j: isize| i >= 0 && j >= 0 && i < n as isize && j < n as isize && mask[j as usize * n + i as usize];
        let mut id = vec![u32::MAX; (n + 1) * (n + 1)];
        let mut positions = Vec::new();
        let mut faces = Vec::new();
        for j in 0..n {
            for i in 0..n {
                if !mask[j * n + i] { continue; }
                let mut lp = Vec::new();
                for (di, dj) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
                    let g = (j + dj) * (n + 1) + i + di;
                    if id[g] == u32::MAX {
                        id[g] = positions.len() as u32;
                        positions.push([(i + di) as f64, (j + dj) as f64]);
                    }
                    lp.push(id[g]);
                }
                if cw { lp[1..].reverse(); }
                faces.push(lp);
            }
        }
        let pinch = (0..=n as isize).any(|i| (0..=n as isize).any(|j| {
            let (sw, se, ne, nw) = (kept(i - 1, j - 1), kept(i, j - 1), kept(i, j), kept(i - 1, j));
            (sw && ne && !se && !nw) || (se && nw && !sw && !ne)
        }));
        match Mesh::from_polygons(positions, faces.clone()) {
            Ok(m) => {
                prop_assert!(!pinch);
                check_invariants(&m);
                let s = subdivide(&m);
                check_invariants(&s.mesh);
            }
            Err(MeshError::NonManifoldVertex { .. }) => prop_assert!(pinch),
            Err(MeshError::Empty { .. }) => prop_assert!(faces.is_empty()),
            Err(e) => prop_assert!(false, "unexpected {e}"),
        }
    }
}
