//! Plane geometry shared by the urban-layout methods: polygons with holes, their validity,
//! areas, distances and cuts. A leaf layer: it wraps well-kept crates (`geo` for validity,
//! booleans and rotated rectangles; `spade` for constrained Delaunay triangulations) and holds
//! the few primitives they lack. Coordinates are metres in a local plane.

pub mod cdt;
pub mod geojson;
pub mod index;
pub mod planar;
pub mod polygon;
pub mod site;
pub mod skeleton;
pub mod sparse;

pub use polygon::{Polygon, PolygonError};

/// A point (or vector) in the plane.
pub type P = [f64; 2];

/// `a − b`.
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
pub fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The 2-D cross product `a × b` (z of the 3-D one).
pub fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The Euclidean norm.
pub fn norm(a: P) -> f64 {
    a[0].hypot(a[1])
}

/// The distance between two points.
pub fn dist(a: P, b: P) -> f64 {
    norm(sub(a, b))
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

/// Twice the signed area of a ring (positive when counter-clockwise); the ring is implicitly
/// closed.
pub fn ring_area2(ring: &[P]) -> f64 {
    let n = ring.len();
    (0..n).map(|i| cross(ring[i], ring[(i + 1) % n])).sum()
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
