//! Plane geometry shared by the urban-layout methods: polygons with holes, their validity,
//! areas, distances and cuts. A leaf layer: it wraps well-kept crates (`geo` for validity,
//! booleans and rotated rectangles; `spade` for constrained Delaunay triangulations) and holds
//! the few primitives they lack. Coordinates are metres in a local plane.

pub mod cdt;
pub mod convex;
pub mod geojson;
pub mod index;
pub mod planar;
pub mod polygon;
pub mod shape;
pub mod site;
pub mod skeleton;
pub mod sparse;

pub use polygon::{Polygon, PolygonError};
pub use shape::Shape;

/// A point (or vector) in the plane.
pub type P = [f64; 2];

/// `a − b`.
#[inline]
pub fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

/// `a + b`.
pub fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1]]
}

/// `s·a`.
pub fn scale(a: P, s: f64) -> P {
    [a[0] * s, a[1] * s]
}

/// The dot product.
#[inline]
pub fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The 2-D cross product `a × b` (z of the 3-D one).
#[inline]
pub fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The Euclidean norm.
pub fn norm(a: P) -> f64 {
    a[0].hypot(a[1])
}

/// The distance between two points.
#[inline]
pub fn dist(a: P, b: P) -> f64 {
    norm(sub(a, b))
}

/// Orientation of `c` relative to the directed line `a → b`: `(b − a) × (c − a)`, > 0 left,
/// < 0 right, 0 on it. Plain floating point, not an exact predicate: the crossing tests below
/// are built on it and their results (crossing points included) depend on its rounding.
#[inline]
pub fn orient(a: P, b: P, c: P) -> f64 {
    cross(sub(b, a), sub(c, a))
}

/// Parameter of the projection of `p` on the line `a → b` (0 at `a`, 1 at `b`; 0 for a
/// zero-length segment).
pub fn projection_param(p: P, a: P, b: P) -> f64 {
    let d = sub(b, a);
    let l2 = dot(d, d);
    if l2 > 0.0 {
        dot(sub(p, a), d) / l2
    } else {
        0.0
    }
}

/// The point of segment `ab` nearest to `p`, and its parameter `t ∈ [0, 1]`.
pub fn closest_on_segment(p: P, a: P, b: P) -> (P, f64) {
    let d = sub(b, a);
    let l2 = dot(d, d);
    let t = if l2 > 0.0 { (dot(sub(p, a), d) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (add(a, scale(d, t)), t)
}

/// The proper or touching intersection of segments `ab` and `cd`: the parameters `(s, t)` along
/// each (both in `[0, 1]`), or `None` when they are disjoint or parallel.
pub fn segment_intersection(a: P, b: P, c: P, d: P) -> Option<(f64, f64)> {
    let r = sub(b, a);
    let q = sub(d, c);
    let den = cross(r, q);
    if den.abs() <= 1e-15 * (norm(r) * norm(q)).max(f64::MIN_POSITIVE) {
        return None;
    }
    let ac = sub(c, a);
    let s = cross(ac, q) / den;
    let t = cross(ac, r) / den;
    ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t)).then_some((s, t))
}

/// Whether `x` and `y` have strictly opposite signs, beyond `tol` either side of zero.
#[inline]
fn straddle(x: f64, y: f64, tol: f64) -> bool {
    (x > tol && y < -tol) || (x < -tol && y > tol)
}

/// Where segments `ab` and `cd` cross properly (each one's ends strictly on both sides of the
/// other's line), if they do. Touching and collinear overlaps are not crossings.
pub fn proper_crossing(a: P, b: P, c: P, d: P) -> Option<P> {
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    if !(straddle(d1, d2, 0.0) && straddle(d3, d4, 0.0)) {
        return None;
    }
    let t = d1 / (d1 - d2);
    Some([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])])
}

/// Whether the closed segments `ab` and `cd` meet (touching counts), with lengths below `tol`
/// taken as zero: orientations within `tol²` of zero count as collinear, and a collinear end
/// within `tol` of the other segment's bounding box lies on it. `tol = 0` is the exact-zero test.
pub fn segments_meet(a: P, b: P, c: P, d: P, tol: f64) -> bool {
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    let tol2 = tol * tol;
    if straddle(d1, d2, tol2) && straddle(d3, d4, tol2) {
        return true;
    }
    (d1.abs() <= tol2 && in_box(c, d, a, tol))
        || (d2.abs() <= tol2 && in_box(c, d, b, tol))
        || (d3.abs() <= tol2 && in_box(a, b, c, tol))
        || (d4.abs() <= tol2 && in_box(a, b, d, tol))
}

/// Whether `p` lies in the bounding box of `a b` grown by `tol` (for a point collinear with the
/// segment: whether it is on it).
fn in_box(a: P, b: P, p: P, tol: f64) -> bool {
    p[0] >= a[0].min(b[0]) - tol
        && p[0] <= a[0].max(b[0]) + tol
        && p[1] >= a[1].min(b[1]) - tol
        && p[1] <= a[1].max(b[1]) + tol
}

/// Twice the signed area of a ring (positive when counter-clockwise); the ring is implicitly
/// closed.
pub fn ring_area2(ring: &[P]) -> f64 {
    let n = ring.len();
    (0..n).map(|i| cross(ring[i], ring[(i + 1) % n])).sum()
}

/// Signed area of a ring (positive if counter-clockwise); the ring is implicitly closed.
pub fn signed_area(ring: &[P]) -> f64 {
    let n = ring.len();
    let mut s = 0.0;
    for i in 0..n {
        s += cross(ring[i], ring[(i + 1) % n]);
    }
    0.5 * s
}

/// Perimeter of a ring.
pub fn perimeter(ring: &[P]) -> f64 {
    let n = ring.len();
    (0..n).map(|i| dist(ring[i], ring[(i + 1) % n])).sum()
}

/// Whether a ring's area is zero or negligible relative to its size.
pub fn is_area_degenerate(ring: &[P]) -> bool {
    let a = signed_area(ring);
    let p = perimeter(ring);
    a.abs() <= 1e-12 * p * p || a.is_nan()
}

/// Area centroid of a ring (the vertex average for zero area, the origin for no vertices).
pub fn centroid(ring: &[P]) -> P {
    let n = ring.len();
    let a = signed_area(ring);
    if n == 0 {
        return [0.0, 0.0];
    }
    // Shift to the first vertex for accuracy far from the origin.
    let o = ring[0];
    if a.abs() > 0.0 {
        let (mut cx, mut cy) = (0.0, 0.0);
        for i in 0..n {
            let p = sub(ring[i], o);
            let q = sub(ring[(i + 1) % n], o);
            let c = cross(p, q);
            cx += (p[0] + q[0]) * c;
            cy += (p[1] + q[1]) * c;
        }
        [o[0] + cx / (6.0 * a), o[1] + cy / (6.0 * a)]
    } else {
        let s = ring.iter().fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
        [s[0] / n as f64, s[1] / n as f64]
    }
}

/// Whether a ring is simple: no two non-adjacent sides meet, and no corner folds back onto its
/// incoming side (a 0° corner). Straight (180°) corners are allowed.
pub fn is_simple(ring: &[P]) -> bool {
    let n = ring.len();
    if n < 3 {
        return false;
    }
    let folds = (0..n).any(|i| {
        let u = sub(ring[(i + n - 1) % n], ring[i]);
        let w = sub(ring[(i + 1) % n], ring[i]);
        cross(u, w) == 0.0 && dot(u, w) > 0.0
    });
    if folds {
        return false;
    }
    n == 3 || first_meeting_sides(ring, 0.0).is_none()
}

/// The first pair `(i, j)`, `i < j`, of non-adjacent sides of a ring that meet (side `i` runs
/// from vertex `i`), lengths below `tol` taken as zero (see [`segments_meet`]).
pub fn first_meeting_sides(ring: &[P], tol: f64) -> Option<(usize, usize)> {
    let n = ring.len();
    (0..n).find_map(|i| {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        // Sides i and j are adjacent if j == i + 1 or (i == 0 and j == n - 1).
        (i + 2..n)
            .filter(|&j| !(i == 0 && j == n - 1))
            .find(|&j| segments_meet(a, b, ring[j], ring[(j + 1) % n], tol))
            .map(|j| (i, j))
    })
}

/// Interior angle, in `(0, 2π)`, at corner `v` of a counter-clockwise ring whose previous
/// corner is `p` and next corner is `n`: the counter-clockwise angle from `n − v` to `p − v`.
pub fn corner_angle(p: P, v: P, n: P) -> f64 {
    let a = sub(n, v);
    let b = sub(p, v);
    let ang = cross(a, b).atan2(dot(a, b));
    if ang < 0.0 {
        ang + std::f64::consts::TAU
    } else {
        ang
    }
}

/// Whether `p` is strictly inside the ring (even–odd rule; points on the ring may go either way).
pub fn ring_contains(ring: &[P], p: P) -> bool {
    let n = ring.len();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (ring[i], ring[j]);
        if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0] {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// Whether `p` is inside the ring or on it (even–odd rule, closed): [`ring_contains`] with the
/// points within `1e-9` (relative to the coordinates' size) of an edge counted in, so a polygon
/// drawn along a line of points (a map's edge) covers them whichever side of it they are on.
pub fn ring_covers(ring: &[P], p: P) -> bool {
    if ring_contains(ring, p) {
        return true;
    }
    let tol = 1e-9 * (1.0 + p[0].abs().max(p[1].abs()));
    let n = ring.len();
    (0..n).any(|i| dist(p, closest_on_segment(p, ring[i], ring[(i + 1) % n]).0) <= tol)
}

/// The length of an open polyline.
pub fn polyline_length(line: &[P]) -> f64 {
    line.windows(2).map(|w| dist(w[0], w[1])).sum()
}

/// The point at fraction `f` of the way from `a` to `b`.
pub fn lerp(a: P, b: P, f: f64) -> P {
    add(a, scale(sub(b, a), f))
}

/// The point at arc length `s` along a polyline (clamped to its ends).
pub fn point_at_length(line: &[P], s: f64) -> P {
    let mut left = s.max(0.0);
    for w in line.windows(2) {
        let l = dist(w[0], w[1]);
        if left <= l && l > 0.0 {
            return lerp(w[0], w[1], left / l);
        }
        left -= l;
    }
    *line.last().expect("a non-empty line")
}

/// Segment `ab` clipped to the rectangle `[x0, y0, x1, y1]` (Liang–Barsky), if any of it is in.
pub fn clip_segment(a: P, b: P, r: [f64; 4]) -> Option<(P, P)> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-d[0], a[0] - r[0]), (d[0], r[2] - a[0]), (-d[1], a[1] - r[1]), (d[1], r[3] - a[1])] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 < t1).then(|| (lerp(a, b, t0), lerp(a, b, t1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_cross_at_their_parameters() {
        let (s, t) = segment_intersection([0.0, 0.0], [2.0, 0.0], [1.0, -1.0], [1.0, 3.0]).unwrap();
        assert!((s - 0.5).abs() < 1e-12 && (t - 0.25).abs() < 1e-12);
        assert!(segment_intersection([0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]).is_none());
        assert!(segment_intersection([0.0, 0.0], [1.0, 0.0], [2.0, -1.0], [2.0, 1.0]).is_none());
    }

    #[test]
    fn rings_have_signed_areas_and_insides() {
        let sq = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        assert_eq!(ring_area2(&sq), 8.0);
        assert!(ring_contains(&sq, [1.0, 1.0]) && !ring_contains(&sq, [3.0, 1.0]));
        let (q, t) = closest_on_segment([1.0, 5.0], [0.0, 0.0], [4.0, 0.0]);
        assert_eq!((q, t), ([1.0, 0.0], 0.25));
    }
}
