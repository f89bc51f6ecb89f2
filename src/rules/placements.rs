//! Room-template placements on quad meshes (docs/formulation.md §4, "Floor plans — room tiling").
//!
//! A [`Template`] is a polyomino of unit cells. [`enumerate_placements`] maps every symmetry
//! image of every template onto the mesh by walking face adjacency from each quad anchor face in
//! each of its 4 orientations, and returns the distinct [`Placement`]s (face sets with their
//! inner and boundary edges).
//!
//! # Walking
//!
//! A walk state is a quad face `f` and an orientation `k`: the half-edge
//! `face_half_edges(f)[k]` is the face's "+x" side, and the following half-edges (CCW) are
//! "+y", "−x" and "−y". Moving in direction `d` leaves `f` through side `k + d`, enters the
//! neighbour `g` through the twin half-edge (at index `j` of `g`'s loop), which is `g`'s side
//! `d + 2`; so `g`'s orientation is `j − (d + 2)` (mod 4). Every cell of a template image is
//! reached by a breadth-first walk over the image's cells, and every adjacency between two image
//! cells is checked from both sides: if a cell would be reached with a different face or a
//! different orientation, the walk is inconsistent (this happens around irregular vertices) and
//! the placement is rejected. Placements leaving the mesh, touching a non-quad face or a blocked
//! face, or visiting a face twice are rejected too. Rotations come from the 4 anchor
//! orientations (and from the images); reflections only from the images.
//!
//! Nothing here panics on any valid [`Mesh`]: a short `blocked_faces` slice counts missing
//! entries as unblocked.

use crate::mesh::{EdgeId, FaceId, Mesh, VertexId};
pub use crate::spec::Template;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashSet, VecDeque};
use std::time::{Duration, Instant};

/// Time cap on placement enumeration for a problem (its model and its heuristics use the same,
/// so both see the same list).
pub const PLACEMENT_TIME_CAP: Duration = Duration::from_secs(20);

/// The placements of a problem's room templates on its mesh, as its model and its heuristics
/// use them ([`enumerate_placements`] with the problem's obstacles and caps).
pub fn enumerate_for(p: &crate::spec::Problem, rooms: &crate::spec::Rooms) -> PlacementReport {
    enumerate_placements(&p.mesh, &rooms.templates, &p.is_obstacle_face, rooms.max_placements, PLACEMENT_TIME_CAP)
}

/// One placement of a template on the mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Placement {
    /// Index of the template in the slice given to [`enumerate_placements`].
    pub template: usize,
    /// The covered faces, sorted.
    pub faces: Vec<FaceId>,
    /// Edges with both faces in the placement, sorted.
    pub inner_edges: Vec<EdgeId>,
    /// Edges with exactly one face in the placement (including mesh-boundary edges of the
    /// placement's faces), sorted.
    pub boundary_edges: Vec<EdgeId>,
    /// Whether some boundary edge is a mesh boundary edge.
    pub touches_mesh_boundary: bool,
}

impl Placement {
    /// The vertices on the placement's boundary edges, sorted.
    pub fn border_vertices(&self, mesh: &Mesh) -> Vec<VertexId> {
        let mut border: Vec<VertexId> = self
            .boundary_edges
            .iter()
            .flat_map(|&e| {
                let (a, b) = mesh.edge_vertices(e);
                [a, b]
            })
            .collect();
        border.sort_unstable();
        border.dedup();
        border
    }
}

/// The result of [`enumerate_placements`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlacementReport {
    /// The placements, ordered by template, then anchor face, then anchor orientation, then
    /// image order (first occurrence of each face set).
    pub placements: Vec<Placement>,
    /// Number of placements per template (same length as the template slice).
    pub per_template: Vec<usize>,
    /// Whether enumeration stopped early at `max_placements` or the time cap.
    pub truncated: bool,
    /// Wall-clock seconds spent.
    pub seconds: f64,
}

/// Enumerates the distinct placements of `templates` on the quad faces of `mesh`, avoiding
/// `blocked_faces` (indexed by face id; missing entries mean unblocked). See the module docs
/// for the walk. Face sets are deduplicated per template. Stops (with `truncated`) when a new
/// placement would exceed `max_placements` or when `time_cap` has passed.
pub fn enumerate_placements(
    mesh: &Mesh,
    templates: &[Template],
    blocked_faces: &[bool],
    max_placements: usize,
    time_cap: Duration,
) -> PlacementReport {
    let start = Instant::now();
    let mut placements = Vec::new();
    let mut per_template = vec![0usize; templates.len()];
    let mut truncated = false;
    let usable =
        |f: FaceId| -> bool { mesh.face_size(f) == 4 && !blocked_faces.get(f.index()).copied().unwrap_or(false) };
    let mut checks = 0usize;

    'outer: for (ti, template) in templates.iter().enumerate() {
        let images = template.images();
        if images.is_empty() {
            continue;
        }
        let mut seen: HashSet<Vec<FaceId>> = HashSet::new();
        for f in mesh.faces() {
            if !usable(f) {
                continue;
            }
            for k in 0..4u8 {
                for image in &images {
                    checks += 1;
                    if checks.is_multiple_of(64) && start.elapsed() >= time_cap {
                        truncated = true;
                        break 'outer;
                    }
                    let Some(mut faces) = walk(mesh, image, f, k, &usable) else {
                        continue;
                    };
                    faces.sort_unstable();
                    if seen.contains(&faces) {
                        continue;
                    }
                    if placements.len() >= max_placements {
                        truncated = true;
                        break 'outer;
                    }
                    seen.insert(faces.clone());
                    placements.push(make_placement(mesh, ti, faces));
                    per_template[ti] += 1;
                }
            }
        }
    }
    PlacementReport { placements, per_template, truncated, seconds: start.elapsed().as_secs_f64() }
}

/// Direction offsets: +x, +y, −x, −y.
const DIRS: [(i32, i32); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];

/// Moves one step in direction `d` from state `(f, k)`; `None` if there is no usable neighbour.
fn step(mesh: &Mesh, f: FaceId, k: u8, d: u8, usable: &impl Fn(FaceId) -> bool) -> Option<(FaceId, u8)> {
    let hes = mesh.face_half_edges_slice(f);
    if hes.len() != 4 {
        return None;
    }
    let h = hes[((k + d) % 4) as usize];
    let t = mesh.he_twin(h);
    let g = mesh.he_face(t)?;
    if !usable(g) {
        return None;
    }
    let ghes = mesh.face_half_edges_slice(g);
    let j = ghes.iter().position(|&x| x == t)? as u8;
    // In g, the entry side `j` is direction d + 2: orientation k' with k' + d + 2 ≡ j.
    Some((g, (j + 8 - (d + 2)) % 4))
}

/// Maps the image's cells onto faces from anchor `(f, k)` (the anchor is the image's first,
/// i.e. smallest, cell). Returns the faces (in cell order) or `None` if the walk is rejected.
fn walk(mesh: &Mesh, image: &[(i32, i32)], f: FaceId, k: u8, usable: &impl Fn(FaceId) -> bool) -> Option<Vec<FaceId>> {
    let first = *image.first()?;
    let index: BTreeMap<(i32, i32), usize> = image.iter().enumerate().map(|(i, &c)| (c, i)).collect();
    let mut state: Vec<Option<(FaceId, u8)>> = vec![None; image.len()];
    state[0] = Some((f, k));
    let mut used: HashSet<FaceId> = HashSet::new();
    used.insert(f);
    let mut queue = VecDeque::new();
    queue.push_back(index[&first]);
    while let Some(ci) = queue.pop_front() {
        let (cf, ck) = state[ci]?;
        let (cx, cy) = image[ci];
        for (d, &(dx, dy)) in DIRS.iter().enumerate() {
            let (Some(nx), Some(ny)) = (cx.checked_add(dx), cy.checked_add(dy)) else {
                continue;
            };
            let Some(&ni) = index.get(&(nx, ny)) else {
                continue;
            };
            let next = step(mesh, cf, ck, d as u8, usable)?;
            match state[ni] {
                Some(s) => {
                    if s != next {
                        return None;
                    }
                }
                None => {
                    if !used.insert(next.0) {
                        return None; // the walk came back to a face already used
                    }
                    state[ni] = Some(next);
                    queue.push_back(ni);
                }
            }
        }
    }
    // A polyomino given with disconnected cells leaves some cells unreached: reject.
    state.into_iter().map(|s| s.map(|(face, _)| face)).collect()
}

fn make_placement(mesh: &Mesh, template: usize, faces: Vec<FaceId>) -> Placement {
    let in_set = |f: Option<FaceId>| f.is_some_and(|f| faces.binary_search(&f).is_ok());
    let mut inner = Vec::new();
    let mut boundary = Vec::new();
    let mut touches = false;
    for &f in &faces {
        for e in mesh.face_edges(f) {
            let [a, b] = mesh.edge_faces(e);
            if in_set(a) && in_set(b) {
                inner.push(e);
            } else {
                boundary.push(e);
                if b.is_none() {
                    touches = true;
                }
            }
        }
    }
    inner.sort_unstable();
    inner.dedup();
    boundary.sort_unstable();
    boundary.dedup();
    Placement { template, faces, inner_edges: inner, boundary_edges: boundary, touches_mesh_boundary: touches }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh;

    fn run(m: &Mesh, t: Template, blocked: &[bool]) -> PlacementReport {
        enumerate_placements(m, &[t], blocked, usize::MAX, Duration::from_secs(60))
    }

    fn check_invariants(m: &Mesh, templates: &[Template], r: &PlacementReport) {
        let mut seen = HashSet::new();
        for p in &r.placements {
            let n = templates[p.template].images()[0].len();
            assert_eq!(p.faces.len(), n);
            let mut f = p.faces.clone();
            f.dedup();
            assert_eq!(f.len(), n, "faces distinct");
            assert!(p.faces.windows(2).all(|w| w[0] < w[1]));
            assert!(p.faces.iter().all(|&f| m.face_size(f) == 4));
            assert!(seen.insert((p.template, p.faces.clone())), "dedup");
            assert!(p.inner_edges.windows(2).all(|w| w[0] < w[1]));
            assert!(p.boundary_edges.windows(2).all(|w| w[0] < w[1]));
            // each face contributes 4 edge sides: 2 per inner edge, 1 per boundary edge
            assert_eq!(2 * p.inner_edges.len() + p.boundary_edges.len(), 4 * n);
            assert_eq!(p.touches_mesh_boundary, p.boundary_edges.iter().any(|&e| m.is_boundary_edge(e)));
        }
        let mut counts = vec![0; templates.len()];
        for p in &r.placements {
            counts[p.template] += 1;
        }
        assert_eq!(counts, r.per_template);
    }

    #[test]
    fn images() {
        assert_eq!(Template::rect("a", 1, 1).images().len(), 1);
        assert_eq!(Template::rect("a", 2, 2).images().len(), 1);
        assert_eq!(Template::rect("a", 3, 2).images().len(), 2);
        assert_eq!(Template::l_shape("l", 2, 2).images().len(), 4);
        assert_eq!(Template::l_shape("l", 3, 2).images().len(), 8);
        assert_eq!(Template::l_shape("l", 2, 2).cells.len(), 3);
        let t = Template {
            name: "s".into(),
            cells: vec![(0, 0), (1, 0), (1, 1), (2, 1)],
            rotations: true,
            reflections: false,
        };
        assert_eq!(t.images().len(), 2);
        let t2 = Template { reflections: true, ..t.clone() };
        assert_eq!(t2.images().len(), 4);
        for img in t2.images() {
            assert_eq!(img.iter().map(|c| c.0).min(), Some(0));
            assert_eq!(img.iter().map(|c| c.1).min(), Some(0));
            assert!(img.windows(2).all(|w| w[0] < w[1]));
        }
        assert_eq!(t2.images(), t2.images());
        let empty = Template { cells: vec![], ..t };
        assert!(empty.images().is_empty());
    }

    #[test]
    fn grid_counts() {
        for m in [mesh::grid(4, 3, 1.0), mesh::jitter(&mesh::grid(4, 3, 1.0), 0.2, 7)] {
            let ts = [
                Template::rect("1x1", 1, 1),
                Template::rect("2x2", 2, 2),
                Template::rect("3x2", 3, 2),
                Template::l_shape("L3", 2, 2),
                Template::rect("1x4", 1, 4),
                Template::rect("5x1", 5, 1),
            ];
            let r = enumerate_placements(&m, &ts, &[], usize::MAX, Duration::from_secs(60));
            assert_eq!(r.per_template, vec![12, 6, 7, 24, 3, 0]);
            assert!(!r.truncated);
            check_invariants(&m, &ts, &r);
            // order: by template
            assert!(r.placements.windows(2).all(|w| w[0].template <= w[1].template));
        }
    }

    #[test]
    fn edges_of_2x2() {
        let m = mesh::grid(4, 3, 1.0);
        let r = run(&m, Template::rect("2x2", 2, 2), &[]);
        for p in &r.placements {
            assert_eq!(p.inner_edges.len(), 4);
            assert_eq!(p.boundary_edges.len(), 8);
            assert!(p.touches_mesh_boundary); // every 2x2 in a 4x3 grid touches the boundary
        }
        // The 1×1 at the centre-ish face 5 (row 1, col 1) does not touch the boundary.
        let r1 = run(&m, Template::rect("1x1", 1, 1), &[]);
        let p5 = r1.placements.iter().find(|p| p.faces == vec![FaceId(5)]).unwrap();
        assert!(!p5.touches_mesh_boundary);
        assert_eq!(p5.inner_edges.len(), 0);
        assert_eq!(p5.boundary_edges.len(), 4);
        // The 2x2 at bottom-left: faces 0, 1, 4, 5.
        let p = r.placements.iter().find(|p| p.faces == vec![FaceId(0), FaceId(1), FaceId(4), FaceId(5)]);
        assert!(p.is_some());
    }

    #[test]
    fn blocked_faces() {
        let m = mesh::grid(4, 3, 1.0);
        let mut blocked = vec![false; m.num_faces()];
        blocked[5] = true;
        let ts = [Template::rect("2x2", 2, 2), Template::rect("3x2", 3, 2), Template::l_shape("L", 2, 2)];
        let all = enumerate_placements(&m, &ts, &[], usize::MAX, Duration::from_secs(60));
        let some = enumerate_placements(&m, &ts, &blocked, usize::MAX, Duration::from_secs(60));
        let expected: Vec<_> = all.placements.iter().filter(|p| !p.faces.contains(&FaceId(5))).cloned().collect();
        assert_eq!(some.placements, expected);
        assert!(some.placements.len() < all.placements.len());
        // 2x2: of 6 blocks, those containing face 5 (row 1, col 1) are 4.
        assert_eq!(some.per_template[0], 2);
    }

    #[test]
    fn truncation() {
        let m = mesh::grid(4, 3, 1.0);
        let ts = [Template::rect("1x1", 1, 1)];
        let r = enumerate_placements(&m, &ts, &[], 5, Duration::from_secs(60));
        assert_eq!(r.placements.len(), 5);
        assert!(r.truncated);
        let r = enumerate_placements(&m, &ts, &[], 12, Duration::from_secs(60));
        assert_eq!(r.placements.len(), 12);
        assert!(!r.truncated);
        let big = mesh::grid(30, 30, 1.0);
        let r = enumerate_placements(&big, &[Template::rect("4x4", 4, 4)], &[], usize::MAX, Duration::ZERO);
        assert!(r.truncated);
    }

    /// A triangle split into 3 quads around a valence-3 interior vertex.
    fn tri3() -> Mesh {
        let pos = vec![[0.0, 0.0], [2.0, 0.0], [1.0, 2.0], [1.0, 0.0], [1.5, 1.0], [0.5, 1.0], [1.0, 0.7]];
        let faces = vec![vec![0, 3, 6, 5], vec![3, 1, 4, 6], vec![4, 2, 5, 6]];
        Mesh::from_polygons(pos, faces).unwrap()
    }

    #[test]
    fn irregular_vertex() {
        let m = tri3();
        let ts = [
            Template::rect("1x1", 1, 1),
            Template::rect("1x2", 1, 2),
            Template::rect("2x2", 2, 2),
            Template::l_shape("L", 2, 2),
            Template::rect("1x3", 1, 3),
        ];
        let r = enumerate_placements(&m, &ts, &[], usize::MAX, Duration::from_secs(60));
        check_invariants(&m, &ts, &r);
        assert_eq!(r.per_template[0], 3);
        assert_eq!(r.per_template[1], 3); // each pair of the 3 quads
        assert_eq!(r.per_template[2], 0); // 3 faces only
                                          // An L around the valence-3 vertex is all 3 faces, walked consistently (no cycle closes).
        assert_eq!(r.per_template[3], 1);
    }

    #[test]
    fn irregular_meshes_do_not_panic() {
        // A hexagon fanned into 6 triangles, subdivided: valence 6 centre, valence 3 vertices.
        let mut pos = vec![[0.0, 0.0]];
        for i in 0..6 {
            let a = i as f64 * std::f64::consts::PI / 3.0;
            pos.push([2.0 * a.cos(), 2.0 * a.sin()]);
        }
        let faces: Vec<Vec<u32>> = (0..6).map(|i| vec![0, 1 + i, 1 + (i + 1) % 6]).collect();
        let hex = Mesh::from_polygons(pos, faces).unwrap();
        let sub = mesh::subdivide(&hex).mesh;
        let sub2 = mesh::subdivide(&sub).mesh;
        let lshape = mesh::clipped_grid(
            &[[0.0, 0.0], [6.0, 0.0], [6.0, 3.0], [3.0, 3.0], [3.0, 6.0], [0.0, 6.0]],
            &[vec![[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]],
            1.0,
        )
        .unwrap();
        let ts = [
            Template::rect("1x1", 1, 1),
            Template::rect("2x2", 2, 2),
            Template::rect("3x2", 3, 2),
            Template::l_shape("L", 3, 2),
            Template::rect("1x5", 1, 5),
            Template { name: "odd".into(), cells: vec![(0, 0), (2, 0)], rotations: true, reflections: true },
        ];
        for m in [&hex, &sub, &sub2, &lshape, &tri3()] {
            let r = enumerate_placements(m, &ts, &[true], usize::MAX, Duration::from_secs(60));
            check_invariants(m, &ts, &r);
            assert_eq!(r.per_template[5], 0); // disconnected cells never place
            let r = enumerate_placements(m, &ts, &vec![true; 3 * m.num_faces()], 10, Duration::from_secs(60));
            assert!(r.placements.is_empty());
        }
        assert_eq!(enumerate_placements(&hex, &ts, &[], usize::MAX, Duration::from_secs(60)).placements.len(), 0);
        // The subdivided hexagon has one 2x2 block around each interior valence-4 vertex (the
        // spoke midpoints) and none around the valence-3 and valence-6 vertices.
        let r = enumerate_placements(&sub, &[Template::rect("2x2", 2, 2)], &[], usize::MAX, Duration::from_secs(60));
        assert_eq!(r.per_template[0], 6);
    }
}
