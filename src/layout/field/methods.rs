//! The two field constructions, both returning per-vertex power values `u` (`[re, im]`).
//!
//! **Boundary data** (both methods): a boundary vertex gets `τ⁴`, `τ` its unit boundary tangent.
//! At a corner whose two edge tangents' fourth powers disagree (an interior angle not a multiple
//! of 90°) it gets their normalised mean — the midpoint of the shorter arc between them — so
//! the field turns by half the corner's mismatch on each side of the corner vertex, and a
//! corner of interior angle `θ_c` counts as `k_c = round(θ_c / 90°)` quarter turns in
//! Poincaré–Hopf: `Σ interior indices = χ − Σ_c (2 − k_c)/4`. Only when the two are exactly
//! opposed (an interior angle an odd multiple of 45°, where `k_c` itself is a tie) is the vertex
//! left free, and the solve decides.

use super::solve::{self, Screen, Weights};
use super::{pow4, C};
use crate::geometry::cdt::Mesh;
use crate::geometry::{self, Polygon, P};

/// The screened smoothing of the distance field diffuses over about this many edge lengths.
pub const DISTANCE_SMOOTHING: f64 = 2.0;

/// The smooth field: `min Σ w_ij |u_i − u_j|²` (cotangent weights, clamped at 0) with the
/// boundary data fixed — a harmonic `u`, two real solves with one matrix.
pub fn smooth(mesh: &Mesh) -> Vec<C> {
    let weights = cotan_weights(mesh);
    solve::solve(mesh.vertices.len(), &weights, &boundary_data(mesh), None)
}

/// The distance field ("D-field"): at an inner vertex `x`, the cross of `∇d(x)`, `d` the exact
/// distance to the boundary (outer ring and holes) — the unit vector from `x`'s nearest boundary
/// point, the inward normal of the nearest edge. Where the nearest point is a corner (the fan of
/// a reflex corner, where `∇d` turns with the circle around it), the nearer of the two edges'
/// normals is used instead, so the field keeps the corner convention of the boundary data
/// (a 270° corner is a quarter turn, not a singularity). Then `(M + tL) u = M u₀` with the
/// boundary fixed and `t = (2h)²` rounds the kinks at the medial axis (where `∇d` jumps).
///
/// `∇d` is taken exactly at the vertices rather than from a piecewise-linear `d` per triangle:
/// on a triangle straddling the medial axis the linear gradient is a blend of the two sides
/// (45° on a square's diagonal, the wrong cross), and averaging such blends to vertices puts
/// spurious singularities along the medial axis.
pub fn distance(mesh: &Mesh, region: &Polygon, h: f64) -> Vec<C> {
    let fixed = boundary_data(mesh);
    let edges = boundary_edges(region);
    let tree = edge_tree(&edges);
    let data: Vec<C> = mesh
        .vertices
        .iter()
        .zip(&fixed)
        .map(|(&x, f)| f.unwrap_or_else(|| pow4(distance_gradient(&edges, &tree, x))))
        .collect();
    let weights = cotan_weights(mesh);
    let mass = lumped_mass(mesh);
    let t = (DISTANCE_SMOOTHING * h).powi(2);
    solve::solve(mesh.vertices.len(), &weights, &fixed, Some(&Screen { mass: &mass, t, data: &data }))
}

/// The boundary data: `τ⁴` on boundary vertices (the normalised mean at corners), `None`
/// elsewhere.
pub fn boundary_data(mesh: &Mesh) -> Vec<Option<C>> {
    mesh.tangents
        .iter()
        .map(|t| {
            let [a, b] = t.as_ref()?.map(pow4);
            let m = [a[0] + b[0], a[1] + b[1]];
            let r = m[0].hypot(m[1]);
            (r > 1e-9).then(|| [m[0] / r, m[1] / r])
        })
        .collect()
}

/// A boundary edge with its neighbours' normals: `(a, b, n, n_prev, n_next)`, `n` the inward
/// unit normal of `ab`, `n_prev` that of the edge ending at `a`, `n_next` that of the edge
/// starting at `b`.
type Edge = (P, P, P, P, P);

fn boundary_edges(region: &Polygon) -> Vec<Edge> {
    let normal = |a: P, b: P| {
        let d = geometry::sub(b, a);
        let l = geometry::norm(d);
        [-d[1] / l, d[0] / l]
    };
    let mut out = Vec::new();
    for ring in region.rings() {
        let n = ring.len();
        for i in 0..n {
            let (p, a, b, q) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n], ring[(i + 2) % n]);
            out.push((a, b, normal(a, b), normal(p, a), normal(b, q)));
        }
    }
    out
}

/// The boundary edges in an R-tree, for nearest-edge queries in `O(log n)`.
type EdgeTree = rstar::RTree<rstar::primitives::GeomWithData<rstar::primitives::Line<P>, usize>>;

fn edge_tree(edges: &[Edge]) -> EdgeTree {
    let items = edges
        .iter()
        .enumerate()
        .map(|(i, e)| rstar::primitives::GeomWithData::new(rstar::primitives::Line::new(e.0, e.1), i));
    rstar::RTree::bulk_load(items.collect())
}

/// The unit gradient of the distance to the boundary at `x`: the inward normal of the nearest
/// edge; at a corner, the normal of whichever of its two edges faces `x` more.
fn distance_gradient(edges: &[Edge], tree: &EdgeTree, x: P) -> P {
    let Some(nearest) = tree.nearest_neighbor(&x) else { return [1.0, 0.0] };
    let (a, b, n, n_prev, n_next) = edges[nearest.data];
    let (q, t) = geometry::closest_on_segment(x, a, b);
    let r = geometry::sub(x, q);
    if t <= 0.0 {
        nearer(r, n_prev, n)
    } else if t >= 1.0 {
        nearer(r, n, n_next)
    } else {
        n
    }
}

/// Of two unit normals, the one with the larger dot product with `r` (the first on ties).
fn nearer(r: P, m: P, n: P) -> P {
    if geometry::dot(r, n) > geometry::dot(r, m) {
        n
    } else {
        m
    }
}

/// Cotangent weights `(cot α + cot β)/2` per edge, clamped at 0 (from below by a tiny positive
/// weight, so no vertex is cut off), edges sorted.
pub fn cotan_weights(mesh: &Mesh) -> Weights {
    let mut half: Vec<(usize, usize, f64)> = Vec::with_capacity(3 * mesh.triangles.len());
    for tri in &mesh.triangles {
        for k in 0..3 {
            let (i, j, o) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let (u, v) =
                (geometry::sub(mesh.vertices[i], mesh.vertices[o]), geometry::sub(mesh.vertices[j], mesh.vertices[o]));
            let cot = geometry::dot(u, v) / geometry::cross(u, v).abs().max(f64::MIN_POSITIVE);
            half.push((i.min(j), i.max(j), 0.5 * cot));
        }
    }
    half.sort_by_key(|e| (e.0, e.1));
    let mut out: Weights = Vec::with_capacity(half.len() / 2 + 1);
    for (i, j, w) in half {
        match out.last_mut() {
            Some(last) if (last.0, last.1) == (i, j) => last.2 += w,
            _ => out.push((i, j, w)),
        }
    }
    for e in &mut out {
        e.2 = e.2.max(1e-6);
    }
    out
}

/// Lumped vertex areas: a third of each incident triangle's area.
pub fn lumped_mass(mesh: &Mesh) -> Vec<f64> {
    let mut m = vec![0.0; mesh.vertices.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let a = mesh.area2(t) / 6.0;
        for &v in tri {
            m[v] += a;
        }
    }
    m
}
