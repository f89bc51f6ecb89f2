//! Small simple polygons and their convex parts, kept fast for the level annealer's inner
//! loops: ear-clipping triangulation (blocks have tens of vertices; the meshes of the urban
//! methods use spade's constrained Delaunay triangulation in [`super::cdt`]), Hertel–Mehlhorn
//! convex parts, convex hulls, Minkowski differences, convex clipping and overlap areas.
//! Everything is `f64` with explicit tolerances.

use super::{add, cross, dot, scale, signed_area, sub, P};

/// Lengths below this are zero.
pub const LEN_TOL: f64 = 1e-7;
/// Areas above this are an overlap (the validator's threshold).
pub const AREA_TOL: f64 = 1e-9;

/// The Euclidean length as `√(a·a)`: cheaper than [`super::norm`] (which guards against
/// overflow, as coordinates here never need), and what the level code measures with; the two may
/// differ in the last bit.
#[inline]
pub fn length(a: P) -> f64 {
    dot(a, a).sqrt()
}

/// The polygon translated by `p`.
pub fn translate(poly: &[P], p: P) -> Vec<P> {
    poly.iter().map(|&q| add(q, p)).collect()
}

/// The polygon without repeated and collinear consecutive vertices.
pub fn simplify(poly: &[P]) -> Vec<P> {
    let mut v: Vec<P> = poly.to_vec();
    loop {
        let n = v.len();
        if n < 3 {
            return v;
        }
        let drop = (0..n).find(|&i| {
            let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
            length(sub(b, a)) < LEN_TOL || cross(sub(b, a), sub(c, b)).abs() < LEN_TOL * length(sub(c, a)).max(1.0)
        });
        match drop {
            Some(i) => {
                v.remove(i);
            }
            None => return v,
        }
    }
}

/// The first pair of non-adjacent edges that meet, if any (edge `i` runs from vertex `i`).
pub fn self_intersection(poly: &[P]) -> Option<(usize, usize)> {
    crate::geometry::first_meeting_sides(poly, LEN_TOL)
}

/// Whether `p` lies strictly inside the triangle `abc` (counter-clockwise) or on its boundary.
fn in_triangle(p: P, a: P, b: P, c: P) -> bool {
    let e = -LEN_TOL * LEN_TOL;
    cross(sub(b, a), sub(p, a)) >= e && cross(sub(c, b), sub(p, b)) >= e && cross(sub(a, c), sub(p, c)) >= e
}

/// Ear-clipping triangulation of a simple counter-clockwise polygon.
pub fn triangulate(poly: &[P]) -> Vec<[P; 3]> {
    let mut idx: Vec<usize> = (0..poly.len()).collect();
    let mut out = Vec::new();
    while idx.len() > 3 {
        let n = idx.len();
        let ear = (0..n).find(|&i| {
            let (a, b, c) = (poly[idx[(i + n - 1) % n]], poly[idx[i]], poly[idx[(i + 1) % n]]);
            if cross(sub(b, a), sub(c, b)) <= LEN_TOL * LEN_TOL {
                return false; // reflex or flat
            }
            (0..n)
                .filter(|&j| j != i && j != (i + n - 1) % n && j != (i + 1) % n)
                .all(|j| !in_triangle(poly[idx[j]], a, b, c))
        });
        // A simple polygon always has an ear; the fallback only guards against round-off.
        let i = ear.unwrap_or(0);
        out.push([poly[idx[(i + n - 1) % n]], poly[idx[i]], poly[idx[(i + 1) % n]]]);
        idx.remove(i);
    }
    if idx.len() == 3 {
        out.push([poly[idx[0]], poly[idx[1]], poly[idx[2]]]);
    }
    out
}

/// Whether a counter-clockwise polygon is convex (collinear vertices allowed).
pub fn is_convex(poly: &[P]) -> bool {
    let n = poly.len();
    (0..n).all(|i| cross(sub(poly[(i + 1) % n], poly[i]), sub(poly[(i + 2) % n], poly[(i + 1) % n])) >= -LEN_TOL)
}

/// The two polygons glued along an edge they share in opposite directions, if they share one.
fn glue(p: &[P], q: &[P]) -> Option<Vec<P>> {
    let same = |a: P, b: P| length(sub(a, b)) < LEN_TOL;
    for i in 0..p.len() {
        let (u, v) = (p[i], p[(i + 1) % p.len()]);
        for j in 0..q.len() {
            if same(q[j], v) && same(q[(j + 1) % q.len()], u) {
                // p from v round to u, then q from u round to v, the shared ends once.
                let mut out: Vec<P> = (0..p.len()).map(|k| p[(i + 1 + k) % p.len()]).collect();
                out.extend((1..q.len() - 1).map(|k| q[(j + 1 + k) % q.len()]));
                return Some(out);
            }
        }
    }
    None
}

/// Convex parts of a simple counter-clockwise polygon (Hertel–Mehlhorn: triangles merged while
/// the union stays convex). A convex polygon is its own single part.
pub fn convex_parts(poly: &[P]) -> Vec<Vec<P>> {
    if is_convex(poly) {
        return vec![poly.to_vec()];
    }
    let mut parts: Vec<Vec<P>> = triangulate(poly).into_iter().map(|t| t.to_vec()).collect();
    'outer: loop {
        for i in 0..parts.len() {
            for j in i + 1..parts.len() {
                if let Some(g) = glue(&parts[i], &parts[j]) {
                    if is_convex(&g) {
                        parts[i] = simplify(&g);
                        parts.remove(j);
                        continue 'outer;
                    }
                }
            }
        }
        return parts;
    }
}

/// The convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
pub fn convex_hull(points: &[P]) -> Vec<P> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup_by(|a, b| length(sub(*a, *b)) < LEN_TOL);
    if pts.len() < 3 {
        return pts;
    }
    let mut lower: Vec<P> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2
            && cross(sub(lower[lower.len() - 1], lower[lower.len() - 2]), sub(p, lower[lower.len() - 1]))
                <= LEN_TOL * LEN_TOL
        {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<P> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2
            && cross(sub(upper[upper.len() - 1], upper[upper.len() - 2]), sub(p, upper[upper.len() - 1]))
                <= LEN_TOL * LEN_TOL
        {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// `[xmin, xmax, ymin, ymax]` of a polygon.
pub fn bounding_box(poly: &[P]) -> [f64; 4] {
    poly.iter().fold([f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY], |b, p| {
        [b[0].min(p[0]), b[1].max(p[0]), b[2].min(p[1]), b[3].max(p[1])]
    })
}

/// Whether two boxes `[xmin, xmax, ymin, ymax]` are apart (touching counts as apart).
pub fn boxes_apart(a: [f64; 4], b: [f64; 4]) -> bool {
    a[1] <= b[0] || b[1] <= a[0] || a[3] <= b[2] || b[3] <= a[2]
}

/// A half-plane `n · p ≤ h` with unit outward normal `n`: one facet of a convex polygon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Facet {
    /// Unit outward normal.
    pub n: P,
    /// Offset.
    pub h: f64,
}

/// The facets of a convex counter-clockwise polygon.
pub fn facets(convex: &[P]) -> Vec<Facet> {
    let k = convex.len();
    (0..k)
        .map(|i| {
            let d = sub(convex[(i + 1) % k], convex[i]);
            let n = scale([d[1], -d[0]], 1.0 / length(d));
            Facet { n, h: dot(n, convex[i]) }
        })
        .collect()
}

/// The Minkowski difference `A ⊕ (−B)` of two convex polygons: the translations `p` of `B`
/// for which `B + p` meets `A`.
pub fn minkowski_difference(a: &[P], b: &[P]) -> Vec<P> {
    let pts: Vec<P> = a.iter().flat_map(|&p| b.iter().map(move |&q| sub(p, q))).collect();
    convex_hull(&pts)
}

/// The part of a convex polygon on the inner side of the line through `a`, `b` (left of `a→b`).
fn clip(poly: &[P], a: P, b: P) -> Vec<P> {
    let side = |p: P| cross(sub(b, a), sub(p, a));
    let mut out = Vec::new();
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            let t = sp / (sp - sq);
            out.push(add(p, scale(sub(q, p), t)));
        }
    }
    out
}

/// The area of the intersection of two convex counter-clockwise polygons.
pub fn convex_overlap_area(a: &[P], b: &[P]) -> f64 {
    let mut poly = a.to_vec();
    for i in 0..b.len() {
        if poly.len() < 3 {
            return 0.0;
        }
        poly = clip(&poly, b[i], b[(i + 1) % b.len()]);
    }
    if poly.len() < 3 {
        0.0
    } else {
        signed_area(&poly).max(0.0)
    }
}

/// The area of the intersection of two simple polygons given as triangulations.
pub fn overlap_area(a: &[[P; 3]], b: &[[P; 3]]) -> f64 {
    a.iter().flat_map(|s| b.iter().map(move |t| convex_overlap_area(s, t))).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: [P; 6] = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]];

    #[test]
    fn l_shape_parts_cover_its_area() {
        let parts = convex_parts(&L);
        assert_eq!(parts.len(), 2);
        let area: f64 = parts.iter().map(|p| signed_area(p)).sum();
        assert!((area - 3.0).abs() < 1e-12);
        assert!(parts.iter().all(|p| is_convex(p)));
        let tris = triangulate(&L);
        assert_eq!(tris.len(), 4);
        assert!((overlap_area(&tris, &tris) - 3.0).abs() < 1e-9);
    }

    #[test]
    fn bow_tie_self_intersects() {
        assert!(self_intersection(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]).is_some());
        assert!(self_intersection(&L).is_none());
    }

    #[test]
    fn minkowski_difference_of_unit_squares() {
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let m = minkowski_difference(&sq, &sq);
        assert_eq!(m.len(), 4);
        assert!((signed_area(&m) - 4.0).abs() < 1e-12);
    }
}
