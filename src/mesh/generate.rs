//! Mesh generators: regular grids, grids clipped to a polygon, and jittered meshes.

use super::error::MeshError;
use super::halfedge::Mesh;
use super::ids::VertexId;
use crate::geometry as geom;
use std::collections::VecDeque;

/// Most grid cells [`clipped_grid`] will scan.
const MAX_CLIP_CELLS: usize = 1 << 26;

/// A regular grid of `w × h` square quad cells with side `spacing`, bottom-left corner at the
/// origin.
///
/// Vertex `row * (w + 1) + col` is at `(col · spacing, row · spacing)`; face `row * w + col` is
/// the cell with that bottom-left vertex, as the loop `[bl, br, tr, tl]` (counter-clockwise). It
/// has `(w + 1)(h + 1)` vertices, `w(h + 1) + h(w + 1)` edges and `wh` faces.
///
/// # Panics
///
/// If the grid is not a valid mesh ([`try_grid`] says why): `w` or `h` 0, `spacing` not finite
/// and positive, or so large or small that positions overflow or coincide.
pub fn grid(w: usize, h: usize, spacing: f64) -> Mesh {
    try_grid(w, h, spacing).unwrap_or_else(|e| panic!("grid {w} × {h}, spacing {spacing}: {e}"))
}

/// [`grid`], or why it cannot be built: `w` or `h` 0, `spacing` not finite and positive, an
/// extent `max(w, h) · spacing` beyond f64, or a spacing so small that vertices coincide.
pub fn try_grid(w: usize, h: usize, spacing: f64) -> Result<Mesh, MeshError> {
    let invalid = |reason: String| Err(MeshError::InvalidInput { reason });
    if w == 0 || h == 0 {
        return invalid(format!("grid: w and h must be positive (got {w} × {h})"));
    }
    if !(spacing.is_finite() && spacing > 0.0) {
        return invalid(format!("grid: spacing must be finite and positive (got {spacing})"));
    }
    if !(w.max(h) as f64 * spacing).is_finite() {
        return invalid(format!("grid: {w} × {h} cells of side {spacing} reach beyond the largest number"));
    }
    let mut positions = Vec::with_capacity((w + 1) * (h + 1));
    for row in 0..=h {
        for col in 0..=w {
            positions.push([col as f64 * spacing, row as f64 * spacing]);
        }
    }
    let id = |row: usize, col: usize| (row * (w + 1) + col) as u32;
    let mut faces = Vec::with_capacity(w * h);
    for row in 0..h {
        for col in 0..w {
            faces.push(vec![id(row, col), id(row, col + 1), id(row + 1, col + 1), id(row + 1, col)]);
        }
    }
    Mesh::from_polygons(positions, faces)
}

/// The cells of a regular grid that lie inside a polygon with holes.
///
/// The grid has cell side `spacing` and its origin at the minimum corner of `outer`'s bounding
/// box, and covers that box. A cell is kept if its centre is inside `outer` and outside every
/// hole (even-odd rule, so polygon orientation does not matter; a centre exactly on a polygon
/// side is decided by the half-open crossing rule).
///
/// Where two kept cells touch only at a corner (a non-manifold vertex), one of them is removed:
/// the one with fewer kept edge-neighbours, and on a tie the one later in row-major order
/// (bottom row first). Removal repeats until no such corner remains.
///
/// Vertices are renumbered in row-major order of grid points (bottom row first, left to right)
/// and faces in row-major order of cells, each as `[bl, br, tr, tl]`. The result may have
/// several connected components (e.g. islands) and holes.
///
/// Errors: [`MeshError::InvalidInput`] for a non-positive or non-finite spacing, a polygon with
/// fewer than 3 points or non-finite coordinates; [`MeshError::TooLarge`] if the grid would have
/// more than 2^26 cells; [`MeshError::Empty`] if no cell remains.
pub fn clipped_grid(outer: &[[f64; 2]], holes: &[Vec<[f64; 2]>], spacing: f64) -> Result<Mesh, MeshError> {
    clipped_grid_impl(outer, holes, spacing, None)
}

/// [`clipped_grid`] on the lattice through `origin` (grid points at `origin + spacing·(i, j)`)
/// instead of the polygon's own bounding-box corner. Polygons that share a border and are meshed
/// on one lattice get complementary cells along it (every cell belongs to the polygon that
/// contains its centre), so their mesh boundaries coincide there — the sub-regions of a city.
pub fn clipped_grid_on_lattice(
    outer: &[[f64; 2]],
    holes: &[Vec<[f64; 2]>],
    spacing: f64,
    origin: [f64; 2],
) -> Result<Mesh, MeshError> {
    clipped_grid_impl(outer, holes, spacing, Some(origin))
}

fn clipped_grid_impl(
    outer: &[[f64; 2]],
    holes: &[Vec<[f64; 2]>],
    spacing: f64,
    origin: Option<[f64; 2]>,
) -> Result<Mesh, MeshError> {
    let invalid = |reason: String| Err(MeshError::InvalidInput { reason });
    if !(spacing.is_finite() && spacing > 0.0) {
        return invalid(format!("spacing must be finite and positive (got {spacing})"));
    }
    if outer.len() < 3 {
        return invalid(format!("the outer polygon has {} points (need at least 3)", outer.len()));
    }
    for (k, hole) in holes.iter().enumerate() {
        if hole.len() < 3 {
            return invalid(format!("hole {k} has {} points (need at least 3)", hole.len()));
        }
    }
    let finite = |p: &[f64; 2]| p[0].is_finite() && p[1].is_finite();
    if !outer.iter().all(finite) || !holes.iter().flatten().all(finite) {
        return invalid("polygon coordinates must be finite".into());
    }

    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in outer {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if let Some(o) = origin {
        if !(o[0].is_finite() && o[1].is_finite()) {
            return invalid("the lattice origin must be finite".into());
        }
        for k in 0..2 {
            lo[k] = o[k] + ((lo[k] - o[k]) / spacing).floor() * spacing;
        }
    }
    let cells_along = |k: usize| ((hi[k] - lo[k]) / spacing).ceil().max(1.0);
    let (fx, fy) = (cells_along(0), cells_along(1));
    if fx * fy > MAX_CLIP_CELLS as f64 {
        return Err(MeshError::TooLarge {
            reason: format!("clipped grid would scan {fx} × {fy} cells (limit {MAX_CLIP_CELLS})"),
        });
    }
    let (nx, ny) = (fx as usize, fy as usize);

    let mut keep = vec![false; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let c = [lo[0] + (i as f64 + 0.5) * spacing, lo[1] + (j as f64 + 0.5) * spacing];
            keep[j * nx + i] = geom::ring_contains(outer, c) && !holes.iter().any(|hole| geom::ring_contains(hole, c));
        }
    }
    remove_diagonal_contacts(&mut keep, nx, ny);

    // Renumber.
    let nvx = nx + 1;
    let mut vid = vec![u32::MAX; nvx * (ny + 1)];
    for j in 0..ny {
        for i in 0..nx {
            if keep[j * nx + i] {
                for (di, dj) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
                    vid[(j + dj) * nvx + i + di] = 0;
                }
            }
        }
    }
    let mut positions = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            if vid[j * nvx + i] == 0 {
                vid[j * nvx + i] = positions.len() as u32;
                positions.push([lo[0] + i as f64 * spacing, lo[1] + j as f64 * spacing]);
            }
        }
    }
    let mut faces = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            if keep[j * nx + i] {
                let v = |di: usize, dj: usize| vid[(j + dj) * nvx + i + di];
                faces.push(vec![v(0, 0), v(1, 0), v(1, 1), v(0, 1)]);
            }
        }
    }
    if faces.is_empty() {
        return Err(MeshError::Empty { reason: "no grid cell centre lies inside the polygon".into() });
    }
    Mesh::from_polygons(positions, faces)
}

/// Removes cells until no two kept cells touch only at a corner (see [`clipped_grid`]).
fn remove_diagonal_contacts(keep: &mut [bool], nx: usize, ny: usize) {
    let nvx = nx + 1;
    let cell = |keep: &[bool], i: isize, j: isize| -> bool {
        i >= 0 && j >= 0 && (i as usize) < nx && (j as usize) < ny && keep[j as usize * nx + i as usize]
    };
    let kept_neighbours = |keep: &[bool], c: usize| -> usize {
        let (i, j) = ((c % nx) as isize, (c / nx) as isize);
        [(-1, 0), (1, 0), (0, -1), (0, 1)].iter().filter(|(di, dj)| cell(keep, i + di, j + dj)).count()
    };
    let mut queued = vec![true; nvx * (ny + 1)];
    let mut queue: VecDeque<usize> = (0..nvx * (ny + 1)).collect();
    while let Some(g) = queue.pop_front() {
        queued[g] = false;
        let (i, j) = ((g % nvx) as isize, (g / nvx) as isize);
        // Cells around grid point (i, j).
        let sw = cell(keep, i - 1, j - 1);
        let se = cell(keep, i, j - 1);
        let ne = cell(keep, i, j);
        let nw = cell(keep, i - 1, j);
        let pair = if sw && ne && !se && !nw {
            Some(((i - 1, j - 1), (i, j)))
        } else if se && nw && !sw && !ne {
            Some(((i, j - 1), (i - 1, j)))
        } else {
            None
        };
        let Some((a, b)) = pair else { continue };
        let ca = a.1 as usize * nx + a.0 as usize;
        let cb = b.1 as usize * nx + b.0 as usize;
        let (na, nb) = (kept_neighbours(keep, ca), kept_neighbours(keep, cb));
        let victim = if na < nb || (na == nb && ca > cb) { ca } else { cb };
        keep[victim] = false;
        let (vi, vj) = (victim % nx, victim / nx);
        for (di, dj) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
            let corner = (vj + dj) * nvx + vi + di;
            if !queued[corner] {
                queued[corner] = true;
                queue.push_back(corner);
            }
        }
    }
}

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny deterministic generator.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[-1, 1)`.
    fn symmetric(&mut self) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        2.0 * unit - 1.0
    }
}

/// A copy of `mesh` with every interior vertex moved by a pseudo-random offset; ids,
/// connectivity and boundary vertices are unchanged.
///
/// Interior vertices are visited in id order; each draws an offset uniform in
/// `[-r, r] × [-r, r]` with `r = amount × (its shortest incident edge in the input mesh)`, from
/// one SplitMix64 stream seeded with `seed` (two draws per interior vertex). If the move would
/// make a face around the vertex degenerate, inverted or self-intersecting, or fold the faces
/// around it or its neighbours, the offset is halved (up to 8 times) and otherwise dropped, so
/// the result is always a valid mesh. `amount ≤ 0` or not finite returns an unchanged copy.
/// Deterministic for a given mesh, amount and seed.
pub fn jitter(mesh: &Mesh, amount: f64, seed: u64) -> Mesh {
    if !(amount.is_finite() && amount > 0.0) {
        return mesh.clone();
    }
    let mut rng = SplitMix64(seed);
    let mut pos = mesh.positions().to_vec();
    let mut pts = Vec::new();
    for v in mesh.vertices() {
        if mesh.is_boundary_vertex(v) {
            continue;
        }
        let shortest = mesh.incident_edges(v).map(|e| mesh.edge_length(e)).fold(f64::INFINITY, f64::min);
        let r = amount * shortest;
        let offset = [rng.symmetric() * r, rng.symmetric() * r];
        let origin = pos[v.index()];
        let mut scale = 1.0;
        let mut moved = false;
        for _ in 0..9 {
            pos[v.index()] = [origin[0] + scale * offset[0], origin[1] + scale * offset[1]];
            if move_is_valid(mesh, v, &pos, &mut pts) {
                moved = true;
                break;
            }
            scale *= 0.5;
        }
        if !moved {
            pos[v.index()] = origin;
        }
    }
    let (_, faces) = mesh.to_polygons();
    // The local checks make this valid; fall back to the input if a global check disagrees.
    Mesh::from_polygons(pos, faces).unwrap_or_else(|_| mesh.clone())
}

/// Whether the faces around `v` stay valid with positions `pos`.
fn move_is_valid(mesh: &Mesh, v: VertexId, pos: &[[f64; 2]], pts: &mut Vec<[f64; 2]>) -> bool {
    let p = pos[v.index()];
    if !(p[0].is_finite() && p[1].is_finite()) {
        return false;
    }
    for f in mesh.vertex_faces(v) {
        pts.clear();
        pts.extend(mesh.face_vertices(f).iter().map(|u| pos[u.index()]));
        if mesh.face_vertices(f).iter().any(|&u| u != v && geom::dist(pos[u.index()], p) <= 1e-9) {
            return false;
        }
        if geom::is_area_degenerate(pts) || geom::signed_area(pts) <= 0.0 || !geom::is_simple(pts) {
            return false;
        }
    }
    mesh.angle_sum_ok_at(v, pos) && mesh.neighbors(v).all(|u| mesh.angle_sum_ok_at(u, pos))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ids::{EdgeId, FaceId};
    use crate::mesh::tests::check_invariants;
    use std::f64::consts::TAU;

    fn has_diagonal_contact(m: &Mesh) -> bool {
        // In a valid mesh this cannot happen (NonManifoldVertex), but check the fan directly.
        m.vertices().any(|v| m.vertex_faces(v).count() + usize::from(m.is_boundary_vertex(v)) != m.valence(v))
    }

    #[test]
    fn grid_12x12_counts_and_one_rings() {
        let m = grid(12, 12, 1.0);
        assert_eq!((m.num_vertices(), m.num_edges(), m.num_faces(), m.num_half_edges()), (169, 312, 144, 624));
        assert_eq!(m.boundary_vertices().len(), 48);
        assert_eq!(m.boundary_edges().len(), 48);
        for v in m.vertices() {
            let (row, col) = (v.index() / 13, v.index() % 13);
            assert_eq!(m.position(v), [col as f64, row as f64]);
            let on_side = [row == 0, row == 12, col == 0, col == 12].iter().filter(|&&b| b).count();
            let expected = [4, 3, 2][on_side];
            assert_eq!(m.valence(v), expected, "valence of {v}");
            assert_eq!(m.is_boundary_vertex(v), on_side > 0);
        }
        check_invariants(&m);
        // Corner 0: boundary one-ring starts after the gap: first east (1), then north (13).
        assert_eq!(m.neighbors(VertexId(0)).collect::<Vec<_>>(), vec![VertexId(1), VertexId(13)]);
        // Bottom side vertex 5: east, north, west.
        assert_eq!(m.neighbors(VertexId(5)).collect::<Vec<_>>(), vec![VertexId(6), VertexId(18), VertexId(4)]);
        // Quads: edges i and i+2 are parallel.
        for f in m.faces() {
            let es = m.face_edges(f);
            assert_eq!(es.len(), 4);
            let dir = |e: EdgeId| {
                let (a, b) = m.edge_vertices(e);
                let (p, q) = (m.position(a), m.position(b));
                [q[0] - p[0], q[1] - p[1]]
            };
            for i in 0..2 {
                assert_eq!(geom::cross(dir(es[i]), dir(es[i + 2])), 0.0);
                assert_ne!(geom::cross(dir(es[i]), dir(es[i + 1])), 0.0);
            }
        }
        assert_eq!(m.face_centroid(FaceId(0)), [0.5, 0.5]);
        assert_eq!(m.bounding_box(), ([0.0, 0.0], [12.0, 12.0]));
        assert_eq!(m.boundary_loops().len(), 1);
        assert_eq!(m.boundary_loops()[0].len(), 48);
    }

    #[test]
    fn grid_edge_numbering_is_first_appearance() {
        let m = grid(2, 1, 1.0);
        // Face 0 = [0, 1, 4, 3]; face 1 = [1, 2, 5, 4].
        let ev: Vec<_> = m.edges().map(|e| m.edge_vertices(e)).map(|(a, b)| (a.0, b.0)).collect();
        assert_eq!(ev, vec![(0, 1), (1, 4), (4, 3), (3, 0), (1, 2), (2, 5), (5, 4)]);
        assert_eq!(m.edge_faces(EdgeId(1)), [Some(FaceId(0)), Some(FaceId(1))]);
    }

    #[test]
    fn hop_distances_and_nearest() {
        let m = grid(4, 4, 1.0);
        let d = m.hop_distances(VertexId(0), 2);
        assert_eq!(
            d,
            vec![
                (VertexId(0), 0),
                (VertexId(1), 1),
                (VertexId(5), 1),
                (VertexId(2), 2),
                (VertexId(6), 2),
                (VertexId(10), 2)
            ]
        );
        assert_eq!(m.nearest_vertex([1.1, 0.2]), Some(VertexId(1)));
        assert_eq!(m.nearest_vertex([f64::NAN, 0.0]), None);
        assert_eq!(m.hop_distances(VertexId(12), 100).len(), 25);
    }

    fn l_shape() -> Vec<[f64; 2]> {
        vec![[0.0, 0.0], [6.0, 0.0], [6.0, 3.0], [3.0, 3.0], [3.0, 6.0], [0.0, 6.0]]
    }

    #[test]
    fn clipped_grid_l_shape() {
        let m = clipped_grid(&l_shape(), &[], 1.0).unwrap();
        // 36 cells minus the 3×3 missing corner.
        assert_eq!(m.num_faces(), 27);
        assert_eq!(m.num_vertices(), 49 - 9);
        // Euler: V − E + F = 1 for a disk.
        assert_eq!(m.num_vertices() as i64 - m.num_edges() as i64 + m.num_faces() as i64, 1);
        assert_eq!(m.boundary_edges().len(), 24);
        check_invariants(&m);
        assert!(!has_diagonal_contact(&m));
        // Vertex 0 is the bottom-left corner; rows are numbered bottom-up.
        assert_eq!(m.position(VertexId(0)), [0.0, 0.0]);
        assert_eq!(m.position(VertexId(7)), [0.0, 1.0]);
    }

    #[test]
    fn clipped_grid_courtyard() {
        let outer = vec![[0.0, 0.0], [8.0, 0.0], [8.0, 8.0], [0.0, 8.0]];
        let hole = vec![[3.0, 3.0], [3.0, 5.0], [5.0, 5.0], [5.0, 3.0]];
        let m = clipped_grid(&outer, &[hole], 1.0).unwrap();
        assert_eq!(m.num_faces(), 64 - 4);
        assert_eq!(m.num_vertices(), 81 - 1);
        // Annulus: V − E + F = 0.
        assert_eq!(m.num_vertices() as i64 - m.num_edges() as i64 + m.num_faces() as i64, 0);
        assert_eq!(m.boundary_vertices().len(), 32 + 8);
        let loops = m.boundary_loops();
        assert_eq!(loops.iter().map(Vec::len).collect::<Vec<_>>(), vec![32, 8]);
        check_invariants(&m);
        assert!(!m.is_boundary_vertex(m.nearest_vertex([2.0, 2.0]).unwrap()));
        assert!(m.is_boundary_vertex(m.nearest_vertex([3.0, 4.0]).unwrap()));
    }

    #[test]
    fn clipped_grid_removes_diagonal_contacts() {
        // Two squares touching at (2, 2), plus a pinch on a diagonal staircase.
        let outer =
            vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [4.0, 2.0], [4.0, 4.0], [2.0, 4.0], [2.0, 2.0], [0.0, 2.0]];
        let m = clipped_grid(&outer, &[], 1.0).unwrap();
        check_invariants(&m);
        // One cell of the pinch is removed: the (tie) later one, cell (2, 2).
        assert_eq!(m.num_faces(), 7);
        assert!(m.nearest_vertex([3.0, 3.0]).is_some());
        let centroids: Vec<_> = m.faces().map(|f| m.face_centroid(f)).collect();
        assert!(centroids.contains(&[1.5, 1.5]));
        assert!(!centroids.contains(&[2.5, 2.5]));
        // A diagonal staircase of single cells collapses to cells without corner contacts.
        let stair = vec![[0.0, 0.0], [1.0, 0.0], [4.0, 3.0], [4.0, 4.0], [3.0, 4.0], [0.0, 1.0]];
        let s = clipped_grid(&stair, &[], 0.5).unwrap();
        check_invariants(&s);
    }

    /// A wiggly "coastline" with a bay, a peninsula and an offshore island (a separate component).
    #[test]
    fn clipped_grid_coastline() {
        let mut coast = Vec::new();
        let n = 64;
        for k in 0..n {
            let t = TAU * k as f64 / n as f64;
            let r = 10.0 + 2.5 * (3.0 * t).sin() + 1.2 * (7.0 * t + 0.4).cos() + 0.6 * (13.0 * t).sin();
            coast.push([r * t.cos(), r * t.sin()]);
        }
        let lake = vec![[-2.0, -2.0], [1.0, -2.5], [1.5, 1.0], [-1.0, 2.0]];
        let m = clipped_grid(&coast, std::slice::from_ref(&lake), 0.7).unwrap();
        check_invariants(&m);
        assert!(!has_diagonal_contact(&m));
        assert!(m.num_faces() > 300);
        for f in m.faces() {
            let c = m.face_centroid(f);
            assert!(geom::ring_contains(&coast, c) && !geom::ring_contains(&lake, c));
        }
        // Deterministic.
        assert_eq!(clipped_grid(&coast, &[lake], 0.7).unwrap(), m);
    }

    #[test]
    fn clipped_grid_errors() {
        let sq = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(matches!(clipped_grid(&sq, &[], 0.0), Err(MeshError::InvalidInput { .. })));
        assert!(matches!(clipped_grid(&sq[..2], &[], 1.0), Err(MeshError::InvalidInput { .. })));
        assert!(matches!(clipped_grid(&sq, std::slice::from_ref(&sq), 0.5), Err(MeshError::Empty { .. })));
        assert!(matches!(clipped_grid(&sq, &[], 1e-9), Err(MeshError::TooLarge { .. })));
        let thin = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 0.1]];
        assert!(matches!(clipped_grid(&thin, &[], 1.0), Err(MeshError::Empty { .. })));
    }

    #[test]
    fn jitter_valid_boundary_fixed_deterministic() {
        let m = grid(10, 8, 1.0);
        let j = jitter(&m, 0.3, 42);
        check_invariants(&j);
        assert_eq!(j, jitter(&m, 0.3, 42));
        assert_ne!(j, jitter(&m, 0.3, 43));
        let mut moved = 0;
        for v in m.vertices() {
            let (p, q) = (m.position(v), j.position(v));
            if m.is_boundary_vertex(v) {
                assert_eq!(p, q);
            } else {
                assert!((p[0] - q[0]).abs() <= 0.3 && (p[1] - q[1]).abs() <= 0.3);
                moved += usize::from(p != q);
            }
        }
        assert_eq!(moved, 9 * 7);
        // Same connectivity and numbering.
        for e in m.edges() {
            assert_eq!(m.edge_vertices(e), j.edge_vertices(e));
        }
        // Large amounts still give valid meshes.
        for seed in 0..20 {
            check_invariants(&jitter(&m, 2.0, seed));
        }
        assert_eq!(jitter(&m, 0.0, 1), m);
        assert_eq!(jitter(&m, f64::NAN, 1), m);
    }

    #[test]
    fn jitter_clipped_grid_with_hole() {
        let outer = vec![[0.0, 0.0], [8.0, 0.0], [8.0, 8.0], [0.0, 8.0]];
        let hole = vec![[3.0, 3.0], [3.0, 5.0], [5.0, 5.0], [5.0, 3.0]];
        let m = clipped_grid(&outer, &[hole], 1.0).unwrap();
        let j = jitter(&m, 0.45, 7);
        check_invariants(&j);
        assert_eq!(j.boundary_vertices(), m.boundary_vertices());
    }
}
