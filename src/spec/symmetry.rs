//! The symmetries of a problem: the rotations and reflections of the plane about the centre of
//! the mesh's bounding box (the dihedral group of a square, or of a rectangle) that map the
//! problem onto itself — vertices onto vertices, edges onto edges of the same role, sinks onto
//! sinks, obstacles onto obstacles.
//!
//! Every rule of a problem without the parts below is defined by the mesh's geometry and graph
//! alone (coverage balls by hops or by Euclidean distance, edge lengths, the angles of zig-zags,
//! too-close pairs and T-junctions, the distance to the nearest sink), so such a map carries
//! every design onto a design with the same objective. Problems with parts placed by id or by a
//! seed — forced edges or vertices, through routes, point-to-point pairs, room templates,
//! obstacle faces — are taken as having no symmetry (none is looked for).

use super::Problem;
use crate::mesh::{EdgeId, VertexId};
use std::collections::BTreeMap;

/// One symmetry of a problem (never the identity): where it sends each vertex and each edge.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symmetry {
    /// What the map is, as the matrix of `(dx, dy) ↦ (a·dx + b·dy, c·dx + d·dy)` about the
    /// bounding box's centre: `[a, b, c, d]`.
    pub matrix: [i8; 4],
    /// The image of every vertex, indexed by vertex id.
    pub vertex: Vec<VertexId>,
    /// The image of every edge, indexed by edge id.
    pub edge: Vec<EdgeId>,
}

/// The seven maps of the square's dihedral group other than the identity.
const MAPS: [[i8; 4]; 7] =
    [[-1, 0, 0, 1], [1, 0, 0, -1], [-1, 0, 0, -1], [0, 1, 1, 0], [0, -1, -1, 0], [0, -1, 1, 0], [0, 1, -1, 0]];

/// Coordinates are matched to this fraction of the bounding box's larger side.
const RELATIVE_TOLERANCE: f64 = 1e-7;

/// The problem's symmetries among the rotations and reflections about its bounding box's
/// centre, in a fixed order; empty when it has none or has a part placed by id or by a seed
/// (see the module's documentation). With the identity they form a group, whose order is
/// one more than the number returned (1, 2, 4 or 8).
pub fn symmetries(p: &Problem) -> Vec<Symmetry> {
    if !p.forced_edges.is_empty()
        || !p.forced_vertices.is_empty()
        || !p.through_routes.is_empty()
        || p.p2p.is_some()
        || p.rooms.is_some()
        || p.is_obstacle_face.iter().any(|&o| o)
    {
        return Vec::new();
    }
    let mesh = &p.mesh;
    let pos = mesh.positions();
    if pos.is_empty() {
        return Vec::new();
    }
    let (lo, hi) = mesh.bounding_box();
    let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let unit = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE) * RELATIVE_TOLERANCE;
    let key = |d: [f64; 2]| ((d[0] / unit).round() as i64, (d[1] / unit).round() as i64);
    let offset = |v: usize| [pos[v][0] - centre[0], pos[v][1] - centre[1]];
    let by_place: BTreeMap<(i64, i64), u32> = (0..pos.len()).map(|v| (key(offset(v)), v as u32)).collect();
    if by_place.len() != pos.len() {
        return Vec::new();
    }
    MAPS.iter().filter_map(|&m| map_onto_itself(p, m, &by_place, |v| key(apply(m, offset(v))))).collect()
}

/// `m` applied to the offset `d`.
fn apply(m: [i8; 4], d: [f64; 2]) -> [f64; 2] {
    [f64::from(m[0]) * d[0] + f64::from(m[1]) * d[1], f64::from(m[2]) * d[0] + f64::from(m[3]) * d[1]]
}

/// The symmetry `m`, if it maps every vertex onto a vertex and the problem onto itself.
fn map_onto_itself(
    p: &Problem,
    m: [i8; 4],
    by_place: &BTreeMap<(i64, i64), u32>,
    image_key: impl Fn(usize) -> (i64, i64),
) -> Option<Symmetry> {
    let mesh = &p.mesh;
    let vertex: Vec<VertexId> =
        (0..mesh.num_vertices()).map(|v| by_place.get(&image_key(v)).map(|&w| VertexId(w))).collect::<Option<_>>()?;
    let same_vertex = |v: usize, w: VertexId| {
        p.is_sink[v] == p.is_sink[w.index()] && p.is_obstacle_vertex[v] == p.is_obstacle_vertex[w.index()]
    };
    if !vertex.iter().enumerate().all(|(v, &w)| same_vertex(v, w)) {
        return None;
    }
    let edge: Vec<EdgeId> = mesh
        .edges()
        .map(|e| {
            let (a, b) = mesh.edge_vertices(e);
            let f = mesh.he_edge(mesh.half_edge_between(vertex[a.index()], vertex[b.index()])?);
            (p.roles[f.index()] == p.roles[e.index()]).then_some(f)
        })
        .collect::<Option<_>>()?;
    Some(Symmetry { matrix: m, vertex, edge })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::Spec;

    fn problem(toml: &str) -> Problem {
        Spec::from_toml(toml).unwrap().resolve(std::path::Path::new(".")).unwrap()
    }

    fn grid(width: u32, height: u32, sinks: &str) -> Problem {
        problem(&format!(
            "name = \"g\"\nboundary = \"wall\"\n[mesh]\ngrid = {{ width = {width}, height = {height}, spacing = 1.0 }}\n[sinks]\n{sinks}\n[coverage]\nrange = 2\n"
        ))
    }

    #[test]
    fn square_with_every_boundary_vertex_a_sink_has_the_whole_group() {
        let s = symmetries(&grid(4, 4, "all_boundary = true"));
        assert_eq!(s.len(), 7);
        for sym in &s {
            // A permutation of the vertices and of the edges.
            let mut v: Vec<u32> = sym.vertex.iter().map(|v| v.0).collect();
            v.sort_unstable();
            assert_eq!(v, (0..25).collect::<Vec<_>>());
            let mut e: Vec<u32> = sym.edge.iter().map(|e| e.0).collect();
            e.sort_unstable();
            assert_eq!(e, (0..40).collect::<Vec<_>>());
        }
    }

    #[test]
    fn a_rectangle_keeps_its_two_reflections_and_the_half_turn() {
        let s = symmetries(&grid(4, 2, "all_boundary = true"));
        let maps: Vec<[i8; 4]> = s.iter().map(|s| s.matrix).collect();
        assert_eq!(maps, vec![[-1, 0, 0, 1], [1, 0, 0, -1], [-1, 0, 0, -1]]);
    }

    #[test]
    fn sinks_decide_which_maps_remain() {
        // One sink at the corner (0, 0): only the diagonal reflection x ↔ y keeps it.
        let s = symmetries(&grid(4, 4, "vertices = [0]"));
        assert_eq!(s.iter().map(|s| s.matrix).collect::<Vec<_>>(), vec![[0, 1, 1, 0]]);
        // The top-middle vertex (2, 4) of a 4×4 grid: the reflection x ↦ 4 − x.
        let s = symmetries(&grid(4, 4, "vertices = [22]"));
        assert_eq!(s.iter().map(|s| s.matrix).collect::<Vec<_>>(), vec![[-1, 0, 0, 1]]);
        // Sinks at (1, 0) and (0, 3): none.
        assert!(symmetries(&grid(4, 4, "vertices = [1, 15]")).is_empty());
    }

    #[test]
    fn seeded_point_to_point_pairs_are_not_mapped() {
        let p = problem(
            "name = \"g\"\nboundary = \"wall\"\n[mesh]\ngrid = { width = 6, height = 6, spacing = 1.0 }\n[sinks]\nall_boundary = true\n[point_to_point]\nblocks = 2\ntolerance = 2\nseed = 1\n",
        );
        assert!(symmetries(&p).is_empty());
    }
}
