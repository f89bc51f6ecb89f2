//! Small planar geometry helpers (private to the mesh module).

use std::f64::consts::TAU;

pub(crate) type P = [f64; 2];

/// `a − b`.
#[inline]
pub fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

/// The z component of the cross product.
#[inline]
pub fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The dot product.
#[inline]
pub fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

#[inline]
pub(crate) fn dist(a: P, b: P) -> f64 {
    let d = sub(a, b);
    d[0].hypot(d[1])
}

/// Orientation of `c` relative to the directed line `a → b`: > 0 left, < 0 right, 0 on it.
#[inline]
pub(crate) fn orient(a: P, b: P, c: P) -> f64 {
    cross(sub(b, a), sub(c, a))
}

/// Parameter of the projection of `p` on the line `a → b` (0 at `a`, 1 at `b`; 0 for a
/// zero-length segment).
pub(crate) fn projection_param(p: P, a: P, b: P) -> f64 {
    let d = sub(b, a);
    let l2 = dot(d, d);
    if l2 > 0.0 {
        dot(sub(p, a), d) / l2
    } else {
        0.0
    }
}

/// The point of segment `a b` closest to `p`.
pub(crate) fn closest_on_segment(p: P, a: P, b: P) -> P {
    let t = projection_param(p, a, b).clamp(0.0, 1.0);
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// Signed area of a closed polygon (positive if counter-clockwise).
pub fn signed_area(pts: &[P]) -> f64 {
    let n = pts.len();
    let mut s = 0.0;
    for i in 0..n {
        s += cross(pts[i], pts[(i + 1) % n]);
    }
    0.5 * s
}

/// Perimeter of a closed polygon.
pub(crate) fn perimeter(pts: &[P]) -> f64 {
    let n = pts.len();
    (0..n).map(|i| dist(pts[i], pts[(i + 1) % n])).sum()
}

/// Whether |area| is zero or negligible relative to the polygon's size.
pub(crate) fn is_area_degenerate(pts: &[P]) -> bool {
    let a = signed_area(pts);
    let p = perimeter(pts);
    a.abs() <= 1e-12 * p * p || a.is_nan()
}

/// Area centroid of a closed polygon (falls back to the vertex average for zero area).
pub fn centroid(pts: &[P]) -> P {
    let n = pts.len();
    let a = signed_area(pts);
    if n == 0 {
        return [0.0, 0.0];
    }
    // Shift to the first vertex for accuracy far from the origin.
    let o = pts[0];
    if a.abs() > 0.0 {
        let (mut cx, mut cy) = (0.0, 0.0);
        for i in 0..n {
            let p = sub(pts[i], o);
            let q = sub(pts[(i + 1) % n], o);
            let c = cross(p, q);
            cx += (p[0] + q[0]) * c;
            cy += (p[1] + q[1]) * c;
        }
        [o[0] + cx / (6.0 * a), o[1] + cy / (6.0 * a)]
    } else {
        let s = pts.iter().fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
        [s[0] / n as f64, s[1] / n as f64]
    }
}

/// Whether the closed segments `p1p2` and `q1q2` intersect (touching counts).
pub(crate) fn segments_intersect(p1: P, p2: P, q1: P, q2: P) -> bool {
    let d1 = orient(q1, q2, p1);
    let d2 = orient(q1, q2, p2);
    let d3 = orient(p1, p2, q1);
    let d4 = orient(p1, p2, q2);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    (d1 == 0.0 && on_segment(q1, q2, p1))
        || (d2 == 0.0 && on_segment(q1, q2, p2))
        || (d3 == 0.0 && on_segment(p1, p2, q1))
        || (d4 == 0.0 && on_segment(p1, p2, q2))
}

/// For a point `c` collinear with `a b`: whether it lies on the closed segment.
fn on_segment(a: P, b: P, c: P) -> bool {
    c[0] >= a[0].min(b[0]) && c[0] <= a[0].max(b[0]) && c[1] >= a[1].min(b[1]) && c[1] <= a[1].max(b[1])
}

/// Whether a closed polygon is simple: no two non-adjacent sides meet, and no corner folds back
/// onto its incoming side (a 0° corner). Straight (180°) corners are allowed.
pub(crate) fn is_simple(pts: &[P]) -> bool {
    let n = pts.len();
    if n < 3 {
        return false;
    }
    // Fold-back corners.
    for i in 0..n {
        let prev = pts[(i + n - 1) % n];
        let cur = pts[i];
        let next = pts[(i + 1) % n];
        let u = sub(prev, cur);
        let w = sub(next, cur);
        if cross(u, w) == 0.0 && dot(u, w) > 0.0 {
            return false;
        }
    }
    if n == 3 {
        return true;
    }
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        // Sides i and j are adjacent if j == i + 1 or (i == 0 and j == n - 1).
        for j in (i + 2)..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (c, d) = (pts[j], pts[(j + 1) % n]);
            if segments_intersect(a, b, c, d) {
                return false;
            }
        }
    }
    true
}

/// Interior angle, in `(0, 2π)`, at corner `v` of a counter-clockwise polygon whose previous
/// corner is `p` and next corner is `n`: the CCW angle from `n − v` to `p − v`.
pub(crate) fn corner_angle(p: P, v: P, n: P) -> f64 {
    let a = sub(n, v);
    let b = sub(p, v);
    let ang = cross(a, b).atan2(dot(a, b));
    if ang < 0.0 {
        ang + TAU
    } else {
        ang
    }
}

/// Even-odd point-in-polygon test (half-open crossing rule, deterministic on edges).
pub(crate) fn point_in_polygon(p: P, poly: &[P]) -> bool {
    let n = poly.len();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (poly[i], poly[j]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if p[0] < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}
