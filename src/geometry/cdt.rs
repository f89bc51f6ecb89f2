//! A quality constrained Delaunay triangulation of a [`Polygon`] (outer ring and holes), by
//! `spade`'s Ruppert–Chew refinement, returned as plain arrays: the mesh the cross fields of the
//! urban layouts live on.
//!
//! The rings are first split into pieces no longer than the target edge length `h`, so the
//! boundary is resolved at `h` whatever the refinement does; the refinement then bounds the
//! triangle area (about that of an equilateral triangle of side `h`) and the smallest angle
//! ([`MIN_ANGLE_DEG`]). Only triangles inside the polygon (not in a hole) are kept; vertices
//! are renumbered in `spade`'s insertion order, so the same polygon and `h` give the same mesh.

use super::{dist, Polygon, P};
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation as _};
use std::collections::HashSet;
use thiserror::Error;

/// The refinement's minimum angle (degrees); Ruppert's algorithm terminates for limits up to
/// about 30°, and 28° leaves it a margin.
pub const MIN_ANGLE_DEG: f64 = 28.0;

/// The most triangles a triangulation may have (estimated up front from the area and `h`).
pub const MAX_TRIANGLES: usize = 2_000_000;

/// The area of an equilateral triangle of side 1 (`√3/4`, rounded down): the estimate of a
/// refined triangle's area is `EQUILATERAL · h²`.
pub const EQUILATERAL: f64 = 0.43;

/// Why a polygon could not be triangulated.
#[derive(Debug, Error, PartialEq)]
pub enum CdtError {
    /// The target edge length is zero, negative or not finite.
    #[error("the target edge length must be a positive finite number of metres, not {0}")]
    BadEdgeLength(f64),
    /// The estimated triangle count (area / (0.43·h²)) is over [`MAX_TRIANGLES`].
    #[error("h = {h} m would give about {estimate} triangles (at most {limit}); use a larger h")]
    TooManyTriangles {
        /// The edge length asked for.
        h: f64,
        /// The estimate.
        estimate: f64,
        /// The limit.
        limit: usize,
    },
    /// `spade` refused a vertex (a coordinate too large or too small for its predicates).
    #[error("the triangulation refused vertex ({:.3}, {:.3}): {message}", at[0], at[1])]
    Insertion {
        /// The vertex.
        at: P,
        /// `spade`'s reason.
        message: String,
    },
    /// A boundary edge could not be made a constraint (it overlaps another boundary edge).
    #[error("boundary edge ({:.3}, {:.3})–({:.3}, {:.3}) overlaps another boundary edge", from[0], from[1], to[0], to[1])]
    Constraint {
        /// Where the edge starts.
        from: P,
        /// Where it ends.
        to: P,
    },
    /// The refinement ran out of vertices (very sharp input angles).
    #[error("the refinement did not finish within {limit} vertices (sharp corners?)")]
    Incomplete {
        /// The vertex budget.
        limit: usize,
    },
}

/// A triangulated polygon.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// The vertices.
    pub vertices: Vec<P>,
    /// The triangles (vertex indices, counter-clockwise).
    pub triangles: Vec<[usize; 3]>,
    /// Whether each vertex is on the boundary (outer ring or a hole).
    pub on_boundary: Vec<bool>,
    /// For a boundary vertex, the unit tangents of its incoming and outgoing boundary edges
    /// (the region on their left); equal away from corners. `None` inside.
    pub tangents: Vec<Option<[P; 2]>>,
}

impl Mesh {
    /// Twice the signed area of triangle `t` (positive: counter-clockwise).
    pub fn area2(&self, t: usize) -> f64 {
        let [a, b, c] = self.triangles[t].map(|i| self.vertices[i]);
        super::cross(super::sub(b, a), super::sub(c, a))
    }
}

/// The estimated triangle count of `polygon` at edge length `h`: `area / (0.43·h²)`.
pub fn estimate_triangles(polygon: &Polygon, h: f64) -> f64 {
    polygon.area() / (EQUILATERAL * h * h)
}

/// Triangulates `polygon` with edges of about `h` (metres) and angles of at least
/// [`MIN_ANGLE_DEG`] (except at sharper input corners).
pub fn triangulate(polygon: &Polygon, h: f64) -> Result<Mesh, CdtError> {
    if !(h.is_finite() && h > 0.0) {
        return Err(CdtError::BadEdgeLength(h));
    }
    let estimate = estimate_triangles(polygon, h);
    if estimate > MAX_TRIANGLES as f64 {
        return Err(CdtError::TooManyTriangles { h, estimate: estimate.round(), limit: MAX_TRIANGLES });
    }
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut boundary_vertices = 0;
    for ring in polygon.rings() {
        let points = split_ring(ring, h);
        boundary_vertices += points.len();
        let mut handles = Vec::with_capacity(points.len());
        for &p in &points {
            let handle = cdt
                .insert(Point2::new(p[0], p[1]))
                .map_err(|e| CdtError::Insertion { at: p, message: format!("{e:?}") })?;
            handles.push(handle);
        }
        for i in 0..handles.len() {
            let (a, b) = (handles[i], handles[(i + 1) % handles.len()]);
            if a != b && cdt.try_add_constraint(a, b).is_empty() && !cdt.exists_constraint(a, b) {
                return Err(CdtError::Constraint { from: points[i], to: points[(i + 1) % points.len()] });
            }
        }
    }
    let limit = (4.0 * estimate) as usize + 20 * boundary_vertices + 1000;
    let params = RefinementParameters::<f64>::new()
        .exclude_outer_faces(true)
        .with_angle_limit(AngleLimit::from_deg(MIN_ANGLE_DEG))
        .with_max_allowed_area(EQUILATERAL * h * h * AREA_FACTOR)
        .with_min_required_area(EQUILATERAL * h * h * 1e-3)
        .with_max_additional_vertices(limit);
    let result = cdt.refine(params);
    if !result.refinement_complete {
        return Err(CdtError::Incomplete { limit });
    }
    let outside: HashSet<_> = result.excluded_faces.into_iter().collect();
    Ok(extract(&cdt, &outside))
}

/// The refinement's area bound, in equilateral triangles of side `h`: refined triangles come out
/// between a quarter of the bound and the bound, so a bound above 1 gives edges of about `h`.
const AREA_FACTOR: f64 = 1.6;

/// The ring with each edge split into equal pieces no longer than `h`.
fn split_ring(ring: &[P], h: f64) -> Vec<P> {
    let mut out = Vec::new();
    for i in 0..ring.len() {
        let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
        let pieces = (dist(a, b) / h).ceil().max(1.0) as usize;
        for k in 0..pieces {
            let t = k as f64 / pieces as f64;
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// The inner triangles as plain arrays, vertices renumbered densely in `spade`'s order.
fn extract(cdt: &Cdt, outside: &HashSet<spade::handles::FixedFaceHandle<spade::handles::InnerTag>>) -> Mesh {
    let mut index = vec![usize::MAX; cdt.num_vertices()];
    let mut triangles = Vec::new();
    for face in cdt.inner_faces() {
        if outside.contains(&face.fix()) {
            continue;
        }
        let vs = face.vertices().map(|v| v.fix().index());
        triangles.push(vs);
        for v in vs {
            index[v] = 0;
        }
    }
    let mut vertices = Vec::new();
    for v in cdt.vertices() {
        let i = v.fix().index();
        if index[i] == 0 {
            index[i] = vertices.len();
            let p = v.position();
            vertices.push([p.x, p.y]);
        }
    }
    let mut mesh = Mesh {
        on_boundary: vec![false; vertices.len()],
        tangents: vec![None; vertices.len()],
        triangles: triangles.into_iter().map(|t| t.map(|v| index[v])).collect(),
        vertices,
    };
    for t in 0..mesh.triangles.len() {
        if mesh.area2(t) < 0.0 {
            mesh.triangles[t].swap(1, 2);
        }
    }
    boundary_tangents(&mut mesh);
    mesh
}

/// Marks the boundary (edges of one triangle only) and each boundary vertex's incoming and
/// outgoing edge tangents; triangles are counter-clockwise, so the region is on the left of
/// each directed boundary edge.
fn boundary_tangents(mesh: &mut Mesh) {
    let mut directed: Vec<(usize, usize)> =
        mesh.triangles.iter().flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]).collect();
    directed.sort_unstable();
    let has = |e: (usize, usize)| directed.binary_search(&e).is_ok();
    let boundary: Vec<(usize, usize)> = directed.iter().copied().filter(|&(a, b)| !has((b, a))).collect();
    let unit = |a: P, b: P| {
        let d = super::sub(b, a);
        super::scale(d, 1.0 / super::norm(d))
    };
    let mut incoming: Vec<Option<P>> = vec![None; mesh.vertices.len()];
    let mut outgoing: Vec<Option<P>> = vec![None; mesh.vertices.len()];
    for &(a, b) in &boundary {
        let t = unit(mesh.vertices[a], mesh.vertices[b]);
        outgoing[a].get_or_insert(t);
        incoming[b].get_or_insert(t);
    }
    for v in 0..mesh.vertices.len() {
        if let (Some(i), Some(o)) = (incoming[v], outgoing[v]) {
            mesh.on_boundary[v] = true;
            mesh.tangents[v] = Some([i, o]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{add, scale};
    use super::*;

    fn square(s: f64) -> Vec<P> {
        vec![[0.0, 0.0], [s, 0.0], [s, s], [0.0, s]]
    }

    fn area(mesh: &Mesh) -> f64 {
        (0..mesh.triangles.len()).map(|t| mesh.area2(t)).sum::<f64>() / 2.0
    }

    #[test]
    fn covers_the_polygon_without_its_holes() {
        let hole = vec![[4.0, 4.0], [6.0, 4.0], [6.0, 6.0], [4.0, 6.0]];
        let p = Polygon::new(square(10.0), vec![hole]).unwrap();
        let mesh = triangulate(&p, 0.5).unwrap();
        assert!((area(&mesh) - 96.0).abs() < 1e-9, "{}", area(&mesh));
        assert!((0..mesh.triangles.len()).all(|t| mesh.area2(t) > 0.0));
        for t in &mesh.triangles {
            let c = t.iter().fold([0.0; 2], |s, &v| add(s, scale(mesh.vertices[v], 1.0 / 3.0)));
            assert!(p.contains(c), "{c:?}");
        }
        // The boundary: every vertex on a ring is marked, tangents follow the rings.
        for (v, &q) in mesh.vertices.iter().enumerate() {
            let on = p.boundary_distance(q) < 1e-9;
            assert_eq!(on, mesh.on_boundary[v], "{q:?}");
        }
        let corner = mesh.vertices.iter().position(|&q| q == [10.0, 0.0]).unwrap();
        assert_eq!(mesh.tangents[corner], Some([[1.0, 0.0], [0.0, 1.0]]));
        let hole_corner = mesh.vertices.iter().position(|&q| q == [4.0, 4.0]).unwrap();
        // The hole is clockwise: into (4, 4) from (6, 4), out towards (4, 6).
        assert_eq!(mesh.tangents[hole_corner], Some([[-1.0, 0.0], [0.0, 1.0]]));
    }

    #[test]
    fn edges_are_about_h() {
        let p = Polygon::new(square(100.0), vec![]).unwrap();
        let mesh = triangulate(&p, 5.0).unwrap();
        let mut lengths = Vec::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                lengths.push(dist(mesh.vertices[t[k]], mesh.vertices[t[(k + 1) % 3]]));
            }
        }
        let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
        assert!((3.5..=6.0).contains(&mean), "mean edge {mean}");
        assert!(lengths.iter().all(|&l| l < 2.0 * 5.0), "{:?}", lengths.iter().fold(0.0f64, |a, &b| a.max(b)));
    }

    #[test]
    fn refuses_bad_or_huge_h() {
        let p = Polygon::new(square(1000.0), vec![]).unwrap();
        assert_eq!(triangulate(&p, 0.0), Err(CdtError::BadEdgeLength(0.0)));
        assert!(matches!(triangulate(&p, f64::NAN), Err(CdtError::BadEdgeLength(_))));
        assert!(matches!(triangulate(&p, 0.5), Err(CdtError::TooManyTriangles { .. })));
    }

    #[test]
    fn is_deterministic() {
        let p = Polygon::new(vec![[0.0, 0.0], [30.0, 0.0], [12.0, 25.0]], vec![]).unwrap();
        assert_eq!(triangulate(&p, 2.0).unwrap(), triangulate(&p, 2.0).unwrap());
    }
}
