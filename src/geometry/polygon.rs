//! Polygons with holes: checked on construction (finite, non-degenerate, simple, holes inside
//! and apart), normalised (outer ring counter-clockwise, holes clockwise, no closing repeat).

use super::{closest_on_segment, dist, ring_area2, ring_contains, segment_intersection, P};
use std::fmt;
use thiserror::Error;

/// Which ring of a polygon an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ring {
    /// The outer boundary.
    Outer,
    /// Hole `i` (0-based, in input order).
    Hole(usize),
}

impl fmt::Display for Ring {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Ring::Outer => write!(f, "the outer ring"),
            Ring::Hole(i) => write!(f, "hole {i}"),
        }
    }
}

/// Why a polygon was refused.
#[derive(Debug, Error, PartialEq)]
pub enum PolygonError {
    /// Fewer than three distinct vertices.
    #[error("{ring} has {count} distinct vertices; a polygon needs at least 3")]
    TooFewVertices {
        /// The ring.
        ring: Ring,
        /// Its distinct vertices.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("{ring}: vertex {vertex} is not finite")]
    NotFinite {
        /// The ring.
        ring: Ring,
        /// The vertex (0-based).
        vertex: usize,
    },
    /// The ring encloses no area.
    #[error("{ring} encloses no area (its vertices are collinear)")]
    Degenerate {
        /// The ring.
        ring: Ring,
    },
    /// Two non-adjacent edges of a ring meet.
    #[error("{ring} intersects itself near ({:.3}, {:.3}) (edges {} and {})", at[0], at[1], edges.0, edges.1)]
    SelfIntersecting {
        /// The ring.
        ring: Ring,
        /// Where.
        at: P,
        /// The two edges (edge `i` joins vertices `i` and `i + 1`).
        edges: (usize, usize),
    },
    /// A hole lies (partly) outside the outer ring.
    #[error("hole {hole} is not inside the outer ring")]
    HoleOutside {
        /// The hole.
        hole: usize,
    },
    /// A hole's boundary crosses another ring.
    #[error("hole {hole} crosses {other} near ({:.3}, {:.3})", at[0], at[1])]
    HoleCrossing {
        /// The hole.
        hole: usize,
        /// The ring it crosses.
        other: Ring,
        /// Where.
        at: P,
    },
    /// One hole lies inside another.
    #[error("hole {inner} lies inside hole {outer}")]
    HoleInHole {
        /// The enclosed hole.
        inner: usize,
        /// The enclosing hole.
        outer: usize,
    },
}

/// A polygon with holes, valid by construction.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    outer: Vec<P>,
    holes: Vec<Vec<P>>,
}

impl Polygon {
    /// Checks and normalises a polygon: rings may come in either orientation, with or without a
    /// closing vertex equal to the first; consecutive duplicates are dropped.
    pub fn new(outer: Vec<P>, holes: Vec<Vec<P>>) -> Result<Polygon, PolygonError> {
        let outer = clean_ring(outer, Ring::Outer, true)?;
        let holes = holes
            .into_iter()
            .enumerate()
            .map(|(i, h)| clean_ring(h, Ring::Hole(i), false))
            .collect::<Result<Vec<_>, _>>()?;
        let polygon = Polygon { outer, holes };
        polygon.check_holes()?;
        Ok(polygon)
    }

    /// The outer ring, counter-clockwise, not closed.
    pub fn outer(&self) -> &[P] {
        &self.outer
    }

    /// The holes, each clockwise, not closed.
    pub fn holes(&self) -> &[Vec<P>] {
        &self.holes
    }

    /// The outer ring followed by the holes.
    pub fn rings(&self) -> impl Iterator<Item = &[P]> {
        std::iter::once(self.outer.as_slice()).chain(self.holes.iter().map(Vec::as_slice))
    }

    /// Every boundary edge `(a, b)`, outer ring first, with the interior on the left.
    pub fn edges(&self) -> impl Iterator<Item = (P, P)> + '_ {
        self.rings().flat_map(|r| (0..r.len()).map(move |i| (r[i], r[(i + 1) % r.len()])))
    }

    /// The area (outer minus holes).
    pub fn area(&self) -> f64 {
        self.rings().map(ring_area2).sum::<f64>() / 2.0
    }

    /// The boundary length (outer ring and holes).
    pub fn perimeter(&self) -> f64 {
        self.edges().map(|(a, b)| dist(a, b)).sum()
    }

    /// Whether `p` is inside (not in a hole); points on the boundary may go either way.
    pub fn contains(&self, p: P) -> bool {
        ring_contains(&self.outer, p) && !self.holes.iter().any(|h| ring_contains(h, p))
    }

    /// The distance from `p` to the nearest boundary point (outer ring or hole).
    pub fn boundary_distance(&self, p: P) -> f64 {
        self.edges().map(|(a, b)| dist(p, closest_on_segment(p, a, b).0)).fold(f64::INFINITY, f64::min)
    }

    /// The bounding box `[min, max]`.
    pub fn bounds(&self) -> [P; 2] {
        bounds(&self.outer)
    }

    /// The polygon as a `geo` polygon (for booleans, buffers and rotated rectangles).
    pub fn to_geo(&self) -> geo::Polygon<f64> {
        geo_polygon(&self.outer, &self.holes)
    }

    /// Cuts the polygon along a polyline whose two ends lie on the outer ring (within `tol`) and
    /// whose inside avoids the boundary: the part on the line's left, then the part on its right.
    /// Holes go with the part that holds them. `None` when an end is off the outer ring, or a part
    /// is not a valid polygon (the line touches the boundary, or the cut leaves a sliver).
    pub fn cut(&self, line: &[P], tol: f64) -> Option<(Polygon, Polygon)> {
        let (a, b) = (*line.first()?, *line.last()?);
        let (ea, ta, da) = self.locate_on_outer(a);
        let (eb, tb, db) = self.locate_on_outer(b);
        if da > tol || db > tol || line.len() < 2 {
            return None;
        }
        let left = self.ring_walk((eb, tb), (ea, ta));
        let right = self.ring_walk((ea, ta), (eb, tb));
        // Left part: the line from a to b, then the ring from b back to a (counter-clockwise).
        let mut l: Vec<P> = line.to_vec();
        l.extend(left);
        let mut r: Vec<P> = line.iter().rev().copied().collect();
        r.extend(right);
        let (mut hl, mut hr) = (Vec::new(), Vec::new());
        for h in &self.holes {
            if ring_contains(&l, h[0]) {
                hl.push(h.clone());
            } else {
                hr.push(h.clone());
            }
        }
        Some((Polygon::new(l, hl).ok()?, Polygon::new(r, hr).ok()?))
    }

    /// Whether `p` is inside or within `tol` of the boundary (the closed polygon, with a margin).
    pub fn covers(&self, p: P, tol: f64) -> bool {
        self.contains(p) || self.boundary_distance(p) <= tol
    }

    /// A polyline clipped to the closed polygon: the pieces inside it or on its boundary (within
    /// `tol`), in order along the line. Unlike a boolean clip, a piece running along the boundary
    /// is kept, so a street on the region's edge counts as inside. Pieces shorter than `tol` are
    /// dropped.
    pub fn clip_polyline(&self, line: &[P], tol: f64) -> Vec<Vec<P>> {
        let [lo, hi] = self.bounds();
        let mut pieces: Vec<Vec<P>> = Vec::new();
        let mut current: Vec<P> = Vec::new();
        let flush = |current: &mut Vec<P>, pieces: &mut Vec<Vec<P>>| {
            if current.len() >= 2 && super::polyline_length(current) > tol {
                pieces.push(std::mem::take(current));
            }
            current.clear();
        };
        for w in line.windows(2) {
            let (a, b) = (w[0], w[1]);
            let outside_box = (a[0].max(b[0]) < lo[0] - tol)
                || (a[0].min(b[0]) > hi[0] + tol)
                || (a[1].max(b[1]) < lo[1] - tol)
                || (a[1].min(b[1]) > hi[1] + tol);
            if outside_box {
                flush(&mut current, &mut pieces);
                continue;
            }
            let mut ts: Vec<f64> = vec![0.0, 1.0];
            ts.extend(self.edges().filter_map(|(c, d)| segment_intersection(a, b, c, d).map(|(s, _)| s)));
            ts.sort_by(f64::total_cmp);
            ts.dedup();
            for k in ts.windows(2) {
                let at = |t: f64| {
                    if t <= 0.0 {
                        a
                    } else if t >= 1.0 {
                        b
                    } else {
                        super::lerp(a, b, t)
                    }
                };
                let (p, q) = (at(k[0]), at(k[1]));
                if dist(p, q) == 0.0 {
                    continue;
                }
                if self.covers(super::lerp(a, b, 0.5 * (k[0] + k[1])), tol) {
                    if current.last() != Some(&p) {
                        flush(&mut current, &mut pieces);
                        current.push(p);
                    }
                    current.push(q);
                } else {
                    flush(&mut current, &mut pieces);
                }
            }
        }
        flush(&mut current, &mut pieces);
        pieces
    }

    /// The outer edge nearest `p`: (edge, parameter, distance).
    fn locate_on_outer(&self, p: P) -> (usize, f64, f64) {
        locate(&self.outer, p)
    }

    /// The outer ring's vertices strictly between two positions, walking counter-clockwise.
    fn ring_walk(&self, from: (usize, f64), to: (usize, f64)) -> Vec<P> {
        ring_arc(&self.outer, from, to)
    }

    /// Cuts the polygon along two polylines, each from the outer ring to hole `hole` (their ends
    /// within `tol` of the rings, their insides clear of the boundary), into the two parts
    /// between them, neither holding that hole; each part's boundary follows the hole between
    /// the two lines' ends. Other holes go with the part that holds them. `None` when an end is
    /// off its ring or a part is not a valid polygon.
    pub fn cut_round_hole(&self, hole: usize, a: &[P], b: &[P], tol: f64) -> Option<(Polygon, Polygon)> {
        let ring = self.holes.get(hole)?;
        let (ha, hb) = (locate(ring, *a.last()?), locate(ring, *b.last()?));
        if ha.2 > tol || hb.2 > tol {
            return None;
        }
        let filled = Polygon {
            outer: self.outer.clone(),
            holes: self.holes.iter().enumerate().filter(|(i, _)| *i != hole).map(|(_, h)| h.clone()).collect(),
        };
        // Along the hole one way, then the other: each line is `a`, the arc, `b` reversed, and of
        // the two parts it cuts, the one without the hole is a part of the answer.
        let forward = ring_arc(ring, (ha.0, ha.1), (hb.0, hb.1));
        let backward = ring_arc(ring, (hb.0, hb.1), (ha.0, ha.1));
        let part = |arc: &[P], rest: &[P], rest_ends: (P, P)| -> Option<Polygon> {
            let mut line = a.to_vec();
            line.extend_from_slice(arc);
            line.extend(b.iter().rev());
            let (l, r) = filled.cut(&line, tol)?;
            // A point of the hole's ring off this line lies inside the part that holds the hole.
            let inside = rest.get(rest.len() / 2).copied().unwrap_or(super::lerp(rest_ends.0, rest_ends.1, 0.5));
            Some(if ring_contains(&l.outer, inside) { r } else { l })
        };
        let ends = (*a.last()?, *b.last()?);
        let one = part(&forward, &backward, ends)?;
        let back: Vec<P> = backward.iter().rev().copied().collect();
        let two = part(&back, &forward, ends)?;
        Some((one, two))
    }

    fn check_holes(&self) -> Result<(), PolygonError> {
        for (i, h) in self.holes.iter().enumerate() {
            if let Some((_, _, at)) = first_crossing(h, &self.outer) {
                return Err(PolygonError::HoleCrossing { hole: i, other: Ring::Outer, at });
            }
            if !ring_contains(&self.outer, h[0]) {
                return Err(PolygonError::HoleOutside { hole: i });
            }
            for (j, g) in self.holes.iter().enumerate().take(i) {
                if let Some((_, _, at)) = first_crossing(h, g) {
                    return Err(PolygonError::HoleCrossing { hole: i, other: Ring::Hole(j), at });
                }
                if ring_contains(g, h[0]) {
                    return Err(PolygonError::HoleInHole { inner: i, outer: j });
                }
                if ring_contains(h, g[0]) {
                    return Err(PolygonError::HoleInHole { inner: j, outer: i });
                }
            }
        }
        Ok(())
    }
}

/// Obstacles that keep clear of a domain's roads and edge: the parts of `areas` inside the
/// domain `outer` shrunk by `clearance`, less a strip of `clearance` along every road, each
/// piece larger than `clearance²` as its outer ring. (A domain's edge and its roads are streets
/// every level of a city keeps; an obstacle reaching them would make a level infeasible.)
pub fn dry(areas: &[Vec<P>], roads: &[Vec<P>], outer: &[P], clearance: f64) -> Vec<Vec<P>> {
    use geo::{Area, BooleanOps, Buffer};
    let line = |ps: &[P]| -> geo::LineString<f64> { ps.iter().map(|p| geo::coord! { x: p[0], y: p[1] }).collect() };
    let closed = |ps: &[P]| -> geo::LineString<f64> {
        ps.iter().chain(ps.first()).map(|p| geo::coord! { x: p[0], y: p[1] }).collect()
    };
    if areas.is_empty() {
        return Vec::new();
    }
    let inside = geo::Polygon::new(closed(outer), vec![]).buffer(-clearance);
    let strips = geo::MultiLineString::new(roads.iter().map(|r| line(r)).collect()).buffer(clearance);
    let mut out = Vec::new();
    for a in areas {
        let wet = geo::MultiPolygon::new(vec![geo::Polygon::new(closed(a), vec![])])
            .intersection(&inside)
            .difference(&strips);
        for p in wet.0.into_iter().filter(|p| p.unsigned_area() > clearance * clearance) {
            let mut r: Vec<P> = p.exterior().coords().map(|c| [c.x, c.y]).collect();
            if r.len() > 1 && r.first() == r.last() {
                r.pop();
            }
            out.push(r);
        }
    }
    out
}

/// The bounding box `[min, max]` of points.
pub fn bounds(points: &[P]) -> [P; 2] {
    let mut b = [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]];
    for p in points {
        for k in 0..2 {
            b[0][k] = b[0][k].min(p[k]);
            b[1][k] = b[1][k].max(p[k]);
        }
    }
    b
}

fn clean_ring(ring: Vec<P>, which: Ring, ccw: bool) -> Result<Vec<P>, PolygonError> {
    if let Some(vertex) = ring.iter().position(|p| !p[0].is_finite() || !p[1].is_finite()) {
        return Err(PolygonError::NotFinite { ring: which, vertex });
    }
    let mut r: Vec<P> = Vec::with_capacity(ring.len());
    for p in ring {
        if r.last() != Some(&p) {
            r.push(p);
        }
    }
    while r.len() > 1 && r.first() == r.last() {
        r.pop();
    }
    if r.len() < 3 {
        return Err(PolygonError::TooFewVertices { ring: which, count: r.len() });
    }
    if let Some((e, f, at)) = self_crossing(&r) {
        return Err(PolygonError::SelfIntersecting { ring: which, at, edges: (e, f) });
    }
    let a2 = ring_area2(&r);
    let [lo, hi] = bounds(&r);
    let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if a2.abs() <= 1e-12 * extent * extent {
        return Err(PolygonError::Degenerate { ring: which });
    }
    if (a2 > 0.0) != ccw {
        r.reverse();
    }
    Ok(r)
}

/// Edge boxes sorted by their left end, swept left to right: the pairs whose boxes overlap.
fn sweep_pairs(a: &[(P, P)], b: &[(P, P)], mut visit: impl FnMut(usize, usize) -> bool) {
    let key = |s: &(P, P)| s.0[0].min(s.1[0]);
    let right = |s: &(P, P)| s.0[0].max(s.1[0]);
    let mut all: Vec<(bool, usize)> = (0..a.len()).map(|i| (false, i)).chain((0..b.len()).map(|i| (true, i))).collect();
    let seg = |&(side, i): &(bool, usize)| if side { b[i] } else { a[i] };
    all.sort_by(|x, y| key(&seg(x)).total_cmp(&key(&seg(y))));
    let mut active: Vec<(bool, usize)> = Vec::new();
    for item in all {
        let s = seg(&item);
        active.retain(|o| right(&seg(o)) >= key(&s));
        for o in &active {
            if o.0 == item.0 {
                continue;
            }
            let t = seg(o);
            let (ylo, yhi) = (s.0[1].min(s.1[1]), s.0[1].max(s.1[1]));
            if t.0[1].max(t.1[1]) < ylo || t.0[1].min(t.1[1]) > yhi {
                continue;
            }
            let (i, j) = if item.0 { (o.1, item.1) } else { (item.1, o.1) };
            if visit(i, j) {
                return;
            }
        }
        active.push(item);
    }
}

/// A `geo` polygon from an outer ring and holes (not closed; each is closed here, orientations
/// kept): the one conversion to `geo`.
pub fn geo_polygon(outer: &[P], holes: &[Vec<P>]) -> geo::Polygon<f64> {
    let ring = |r: &[P]| geo::LineString::from(r.iter().chain(r.first()).map(|p| (p[0], p[1])).collect::<Vec<_>>());
    geo::Polygon::new(ring(outer), holes.iter().map(|h| ring(h)).collect())
}

fn ring_edges(r: &[P]) -> Vec<(P, P)> {
    (0..r.len()).map(|i| (r[i], r[(i + 1) % r.len()])).collect()
}

/// The first pair of non-adjacent edges of a ring that meet (lower index first), and where.
fn self_crossing(r: &[P]) -> Option<(usize, usize, P)> {
    let edges = ring_edges(r);
    let n = edges.len();
    let adjacent = |i: usize, j: usize| i == j || j == i + 1 || (i == 0 && j == n - 1);
    crossing(&edges, &edges, |i, j| adjacent(i.min(j), i.max(j))).map(|(i, j, at)| (i.min(j), i.max(j), at))
}

/// The first pair of edges, one from each ring, that meet.
fn first_crossing(r: &[P], s: &[P]) -> Option<(usize, usize, P)> {
    crossing(&ring_edges(r), &ring_edges(s), |_, _| false)
}

/// The first pair of edges `(a[i], b[j])` not skipped that meet, and where.
fn crossing(a: &[(P, P)], b: &[(P, P)], skip: impl Fn(usize, usize) -> bool) -> Option<(usize, usize, P)> {
    let mut found = None;
    sweep_pairs(a, b, |i, j| {
        if skip(i, j) {
            return false;
        }
        let ((p, q), (c, d)) = (a[i], b[j]);
        let Some((t, _)) = segment_intersection(p, q, c, d) else { return false };
        found = Some((i, j, [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]));
        true
    });
    found
}

/// The edge of `ring` nearest `p`: (edge, parameter, distance).
fn locate(ring: &[P], p: P) -> (usize, f64, f64) {
    let n = ring.len();
    (0..n)
        .map(|e| {
            let (q, t) = closest_on_segment(p, ring[e], ring[(e + 1) % n]);
            (e, t, dist(p, q))
        })
        .min_by(|x, y| x.2.total_cmp(&y.2))
        .unwrap_or((0, 0.0, f64::INFINITY))
}

/// The vertices of `ring` strictly between two positions (edge, parameter), walking forward
/// (in the ring's vertex order).
fn ring_arc(ring: &[P], from: (usize, f64), to: (usize, f64)) -> Vec<P> {
    let n = ring.len();
    let mut out = Vec::new();
    if from.0 == to.0 && from.1 < to.1 {
        return out;
    }
    let mut e = (from.0 + 1) % n;
    let mut first = true;
    loop {
        // Vertex e starts edge e; stop once edge `to.0` is reached (its start vertex included).
        out.push(ring[e]);
        if e == to.0 && !(first && from.0 == to.0 && from.1 < to.1) {
            break;
        }
        first = false;
        e = (e + 1) % n;
        if out.len() > n {
            break;
        }
    }
    // A position at the very start of its edge coincides with the vertex pushed last.
    if to.1 <= 0.0 {
        out.pop();
    }
    if from.1 >= 1.0 && !out.is_empty() {
        out.remove(0);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polylines_clip_to_the_closed_polygon() {
        let sq = Polygon::new(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]], vec![]).unwrap();
        // A bent line inside stays one piece, whatever its vertices' rounding.
        let bent = vec![[0.1, 0.3], [3.3, 7.7], [9.1, 0.7]];
        assert_eq!(sq.clip_polyline(&bent, 1e-6), vec![bent.clone()]);
        // A line through the square, and one along its edge (kept: the edge is inside).
        assert_eq!(sq.clip_polyline(&[[-5.0, 5.0], [15.0, 5.0]], 1e-6), vec![vec![[0.0, 5.0], [10.0, 5.0]]]);
        assert_eq!(sq.clip_polyline(&[[0.0, -5.0], [0.0, 15.0]], 1e-6), vec![vec![[0.0, 0.0], [0.0, 10.0]]]);
        // In, out and in again: two pieces.
        let zig = sq.clip_polyline(&[[5.0, 5.0], [15.0, 5.0], [15.0, 8.0], [5.0, 8.0]], 1e-6);
        assert_eq!(zig, vec![vec![[5.0, 5.0], [10.0, 5.0]], vec![[10.0, 8.0], [5.0, 8.0]]]);
    }

    fn square(x: f64, y: f64, s: f64) -> Vec<P> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    #[test]
    fn normalises_orientation_and_closing_vertex() {
        let mut cw = square(0.0, 0.0, 10.0);
        cw.reverse();
        cw.push(cw[0]);
        let mut hole = square(2.0, 2.0, 2.0);
        hole.push(hole[0]);
        let p = Polygon::new(cw, vec![hole]).unwrap();
        assert_eq!(p.outer().len(), 4);
        assert!(ring_area2(p.outer()) > 0.0 && ring_area2(&p.holes()[0]) < 0.0);
        assert_eq!(p.area(), 96.0);
        assert!(p.contains([1.0, 1.0]) && !p.contains([3.0, 3.0]));
        assert_eq!(p.boundary_distance([5.0, 1.0]), 1.0);
    }

    #[test]
    fn a_cut_splits_a_square_with_its_hole() {
        let p = Polygon::new(square(0.0, 0.0, 10.0), vec![square(6.0, 6.0, 2.0)]).unwrap();
        let (l, r) = p.cut(&[[5.0, 0.0], [5.0, 5.0], [5.0, 10.0]], 1e-9).unwrap();
        assert_eq!((l.area(), l.holes().len()), (50.0, 0));
        assert_eq!((r.area(), r.holes().len()), (46.0, 1));
        assert!(l.contains([2.0, 5.0]) && r.contains([9.0, 1.0]));
        // Across a corner: ends on adjacent edges.
        let (a, b) = p.cut(&[[8.0, 0.0], [10.0, 2.0]], 1e-9).unwrap();
        assert!((a.area() - 94.0).abs() < 1e-9 && (b.area() - 2.0).abs() < 1e-9, "{} {}", a.area(), b.area());
        // Both ends on one edge: a pocket.
        assert!(p
            .cut(&[[2.0, 0.0], [3.0, 1.0], [4.0, 0.0]], 1e-9)
            .is_some_and(|(x, y)| (x.area() - 1.0).abs() < 1e-9 || (y.area() - 1.0).abs() < 1e-9));
        assert!(p.cut(&[[5.0, 0.0], [5.0, 5.0]], 1e-9).is_none(), "an end inside");
    }

    #[test]
    fn two_lines_to_a_hole_split_the_land_round_it() {
        let p = Polygon::new(square(0.0, 0.0, 10.0), vec![square(4.0, 4.0, 2.0), square(8.0, 1.0, 1.0)]).unwrap();
        let (a, b) = ([[5.0, 0.0], [5.0, 2.0], [5.0, 4.0]], [[5.0, 10.0], [5.0, 6.0]]);
        let (x, y) = p.cut_round_hole(0, &a, &b, 1e-9).unwrap();
        let (left, right) = if x.contains([1.0, 5.0]) { (x, y) } else { (y, x) };
        // Each side keeps half the square less half the hole; the small hole goes right.
        assert_eq!((left.area(), left.holes().len()), (48.0, 0));
        assert_eq!((right.area(), right.holes().len()), (47.0, 1));
        assert!(!left.contains([5.5, 5.0]) && !right.contains([4.5, 5.0]) && right.contains([9.5, 5.0]));
        // Both lines to the same hole edge: a sliver between them and the rest.
        let (c, d) = ([[4.5, 0.0], [4.5, 4.0]], [[5.5, 0.0], [5.5, 4.0]]);
        let (x, y) = p.cut_round_hole(0, &c, &d, 1e-9).unwrap();
        let mut areas = [x.area(), y.area()];
        areas.sort_by(f64::total_cmp);
        assert_eq!(areas, [4.0, 91.0]);
        assert!(p.cut_round_hole(0, &[[5.0, 0.0], [5.0, 3.0]], &b, 1e-9).is_none(), "an end off the hole");
        assert!(p.cut_round_hole(2, &a, &b, 1e-9).is_none(), "no such hole");
    }

    #[test]
    fn refuses_bad_rings_by_name() {
        let bow = vec![[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
        assert!(matches!(Polygon::new(bow, vec![]), Err(PolygonError::SelfIntersecting { ring: Ring::Outer, .. })));
        let line = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert_eq!(Polygon::new(line, vec![]), Err(PolygonError::Degenerate { ring: Ring::Outer }));
        let nan = vec![[0.0, 0.0], [f64::NAN, 0.0], [2.0, 1.0]];
        assert_eq!(Polygon::new(nan, vec![]), Err(PolygonError::NotFinite { ring: Ring::Outer, vertex: 1 }));
        let out = square(20.0, 20.0, 1.0);
        assert_eq!(Polygon::new(square(0.0, 0.0, 10.0), vec![out]), Err(PolygonError::HoleOutside { hole: 0 }));
        let across = square(8.0, 2.0, 4.0);
        assert!(matches!(
            Polygon::new(square(0.0, 0.0, 10.0), vec![across]),
            Err(PolygonError::HoleCrossing { hole: 0, other: Ring::Outer, .. })
        ));
        let (a, b) = (square(1.0, 1.0, 4.0), square(2.0, 2.0, 1.0));
        assert_eq!(
            Polygon::new(square(0.0, 0.0, 10.0), vec![a, b]),
            Err(PolygonError::HoleInHole { inner: 1, outer: 0 })
        );
    }
}
