//! Configuration spaces (Ma et al. 2014, §3.1): for a fixed block `A` and a moving block `B`, the
//! translations of `B` at which the two touch along a wall at least a door wide without their
//! interiors overlapping. It is a union of segments: for every pair of antiparallel edges, the
//! range over which `B`'s edge slides along `A`'s with an overlap of at least `w`, minus the
//! open stretches where some convex part of `B` enters some convex part of `A`.

use super::spec::{Block, BlockId, Level};
use crate::geometry::convex::{self, length, Facet, LEN_TOL};
use crate::geometry::{self, dot, scale, sub, P};
use serde::Serialize;

/// One segment of a configuration space: translations `a + t (b − a)`, `t ∈ [0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Segment {
    /// One end.
    pub a: P,
    /// The other end (equal to `a` for a single position).
    pub b: P,
}

impl Segment {
    /// Its length.
    pub fn len(&self) -> f64 {
        length(sub(self.b, self.a))
    }

    /// Whether it is a single point.
    pub fn is_empty(&self) -> bool {
        self.len() < LEN_TOL
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> P {
        geometry::add(self.a, scale(sub(self.b, self.a), t))
    }

    /// The parameter of the point of the segment nearest `p`, and the distance to it.
    pub fn project(&self, p: P) -> (f64, f64) {
        let d = sub(self.b, self.a);
        let l2 = dot(d, d);
        let t = if l2 < LEN_TOL * LEN_TOL { 0.0 } else { (dot(sub(p, self.a), d) / l2).clamp(0.0, 1.0) };
        (t, length(sub(p, self.at(t))))
    }
}

/// The convex parts' Minkowski differences of two blocks, as facet lists: `B + p` and `A`
/// have disjoint interiors exactly when, for every part pair, `p` satisfies `n · p ≥ h` for at
/// least one facet.
pub fn overlap_facets(a: &Block, b: &Block) -> Vec<Vec<Facet>> {
    a.parts
        .iter()
        .flat_map(|pa| b.parts.iter().map(move |pb| convex::facets(&convex::minkowski_difference(pa, pb))))
        .collect()
}

/// The open parameter interval of the line `p0 + u d` inside the convex region
/// `{n · p < h}` of every facet, if it is longer than [`LEN_TOL`] (a line along a facet,
/// within the tolerance, only touches).
fn inside_interval(p0: P, d: P, facets: &[Facet]) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for f in facets {
        let (c, s) = (f.h - dot(f.n, p0), dot(f.n, d));
        if s.abs() < 1e-12 {
            if c <= LEN_TOL {
                return None;
            }
        } else if s > 0.0 {
            hi = hi.min(c / s);
        } else {
            lo = lo.max(c / s);
        }
    }
    (hi - lo > LEN_TOL).then_some((lo, hi))
}

/// `[u0, u1]` minus the open intervals: the closed pieces left.
fn subtract(u0: f64, u1: f64, mut holes: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    holes.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut out = Vec::new();
    let mut start = u0;
    for (lo, hi) in holes {
        if hi <= start || lo >= u1 {
            continue;
        }
        if lo >= start {
            out.push((start, lo));
        }
        start = start.max(hi);
        if start > u1 {
            break;
        }
    }
    if start <= u1 {
        out.push((start, u1));
    }
    out
}

/// The configuration space of `b` moving around `a` for door width `w`.
pub fn contact_segments(a: &Block, b: &Block, w: f64) -> Vec<Segment> {
    let facets = overlap_facets(a, b);
    let (pa, pb) = (&a.polygon, &b.polygon);
    let mut out: Vec<Segment> = Vec::new();
    for i in 0..pa.len() {
        let (a0, a1) = (pa[i], pa[(i + 1) % pa.len()]);
        let la = length(sub(a1, a0));
        let d = scale(sub(a1, a0), 1.0 / la);
        let n = [d[1], -d[0]];
        for j in 0..pb.len() {
            let (b0, b1) = (pb[j], pb[(j + 1) % pb.len()]);
            let lb = length(sub(b1, b0));
            let e = scale(sub(b1, b0), 1.0 / lb);
            // Antiparallel edges only: B's edge runs against A's.
            if dot(d, e) > -1.0 + 1e-9 || la < w - LEN_TOL || lb < w - LEN_TOL {
                continue;
            }
            // B's edge on A's edge's line: n · (b0 + p) = n · a0. Along d, A's edge spans
            // [d·a0, d·a1] and B's [d·b1, d·b0] + u; they overlap by ≥ w for u in [u0, u1].
            let c = dot(n, sub(a0, b0));
            let (u0, u1) = (dot(d, a0) - dot(d, b0) + w, dot(d, a1) - dot(d, b1) - w);
            if u0 > u1 + LEN_TOL {
                continue;
            }
            let u1 = u1.max(u0);
            let p0 = scale(n, c);
            let holes: Vec<(f64, f64)> = facets.iter().filter_map(|f| inside_interval(p0, d, f)).collect();
            for (lo, hi) in subtract(u0, u1, holes) {
                let s = Segment { a: geometry::add(p0, scale(d, lo)), b: geometry::add(p0, scale(d, hi)) };
                let dup = out.iter().any(|t| {
                    (length(sub(t.a, s.a)) < LEN_TOL && length(sub(t.b, s.b)) < LEN_TOL)
                        || (length(sub(t.a, s.b)) < LEN_TOL && length(sub(t.b, s.a)) < LEN_TOL)
                });
                if !dup {
                    out.push(s);
                }
            }
        }
    }
    out
}

/// The pieces of segment `seg` (absolute positions of a block) at which the block stays out of
/// every convex region given by `facet_lists` (closed pieces; a single position is a piece too).
pub fn clip_out(seg: &Segment, facet_lists: &[Vec<Facet>]) -> Vec<Segment> {
    let len = seg.len();
    if len < LEN_TOL {
        let inside = facet_lists.iter().any(|fs| fs.iter().all(|f| f.h - dot(f.n, seg.a) > LEN_TOL));
        return if inside { Vec::new() } else { vec![*seg] };
    }
    let d = scale(sub(seg.b, seg.a), 1.0 / len);
    let holes: Vec<(f64, f64)> = facet_lists.iter().filter_map(|fs| inside_interval(seg.a, d, fs)).collect();
    subtract(0.0, len, holes).into_iter().map(|(lo, hi)| Segment { a: seg.at(lo / len), b: seg.at(hi / len) }).collect()
}

/// The configuration spaces of every ordered pair of block shapes of a level.
#[derive(Clone, Debug)]
pub struct CSpaces {
    n: usize,
    segments: Vec<Vec<Segment>>,
    facets: Vec<Vec<Vec<Facet>>>,
    obstacle_facets: Vec<Vec<Vec<Facet>>>,
    /// The largest coordinate of any segment end: one contact moves a block at most this far
    /// along either axis.
    pub reach: f64,
}

impl CSpaces {
    /// Computes every pair's segments and overlap facets.
    pub fn new(level: &Level) -> CSpaces {
        let n = level.blocks.len();
        let mut segments = Vec::with_capacity(n * n);
        let mut facets = Vec::with_capacity(n * n);
        for a in &level.blocks {
            for b in &level.blocks {
                segments.push(contact_segments(a, b, level.door_width));
                facets.push(overlap_facets(a, b));
            }
        }
        let reach = segments.iter().flatten().flat_map(|s| [s.a, s.b]).flatten().fold(0.0, |m: f64, v| m.max(v.abs()));
        let obstacle_facets = level
            .obstacles
            .iter()
            .flat_map(|o| {
                level.blocks.iter().map(|b| {
                    o.parts
                        .iter()
                        .flat_map(|po| {
                            b.parts.iter().map(move |pb| convex::facets(&convex::minkowski_difference(po, pb)))
                        })
                        .collect()
                })
            })
            .collect();
        CSpaces { n, segments, facets, obstacle_facets, reach }
    }

    /// Part-pair facet lists of block `b` against obstacle `o` (absolute coordinates): block `b`
    /// at position `p` clears the obstacle exactly when, for every list, `n · p ≥ h` holds for
    /// at least one facet.
    pub fn obstacle_facets(&self, o: usize, b: BlockId) -> &[Vec<Facet>] {
        &self.obstacle_facets[o * self.n + b.0 as usize]
    }

    /// Translations of `b` relative to `a` where they touch by a door.
    pub fn segments(&self, a: BlockId, b: BlockId) -> &[Segment] {
        &self.segments[a.0 as usize * self.n + b.0 as usize]
    }

    /// Part-pair facet lists of `b` relative to `a` ([`overlap_facets`]).
    pub fn facets(&self, a: BlockId, b: BlockId) -> &[Vec<Facet>] {
        &self.facets[a.0 as usize * self.n + b.0 as usize]
    }
}

/// The intersection of two segment sets (points where segments cross, overlaps of collinear
/// ones): positions in contact with two neighbours at once.
pub fn intersect(xs: &[Segment], ys: &[Segment]) -> Vec<Segment> {
    let mut out = Vec::new();
    for s in xs {
        for t in ys {
            if let Some(r) = intersect_one(s, t) {
                out.push(r);
            }
        }
    }
    out
}

fn intersect_one(s: &Segment, t: &Segment) -> Option<Segment> {
    let (r, q) = (sub(s.b, s.a), sub(t.b, t.a));
    let denom = geometry::cross(r, q);
    let w = sub(t.a, s.a);
    if s.is_empty() {
        return (t.project(s.a).1 < LEN_TOL).then_some(*s);
    }
    if t.is_empty() {
        return (s.project(t.a).1 < LEN_TOL).then_some(*t);
    }
    if denom.abs() < 1e-12 * length(r) * length(q) {
        // Parallel: collinear overlap, if any.
        if geometry::cross(w, r).abs() > LEN_TOL * length(r) {
            return None;
        }
        let l2 = dot(r, r);
        let (t0, t1) = (dot(sub(t.a, s.a), r) / l2, dot(sub(t.b, s.a), r) / l2);
        let (lo, hi) = (t0.min(t1).max(0.0), t0.max(t1).min(1.0));
        return (lo <= hi + LEN_TOL).then(|| Segment { a: s.at(lo), b: s.at(hi.max(lo)) });
    }
    let u = geometry::cross(w, q) / denom;
    let v = geometry::cross(w, r) / denom;
    let (eu, ev) = (LEN_TOL / length(r), LEN_TOL / length(q));
    (u >= -eu && u <= 1.0 + eu && v >= -ev && v <= 1.0 + ev).then(|| {
        let p = s.at(u.clamp(0.0, 1.0));
        Segment { a: p, b: p }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block(poly: &[P]) -> Block {
        Block { name: "b".into(), polygon: poly.to_vec(), parts: convex::convex_parts(poly), rotation_of: None }
    }

    const SQ: [P; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

    #[test]
    fn subtract_leaves_closed_pieces() {
        assert_eq!(subtract(0.0, 4.0, vec![(1.0, 2.0), (3.0, 5.0)]), vec![(0.0, 1.0), (2.0, 3.0)]);
        assert_eq!(subtract(0.0, 1.0, vec![(-1.0, 2.0)]), vec![]);
    }

    #[test]
    fn crossing_segments_meet_in_a_point() {
        let s = Segment { a: [0.0, 0.0], b: [2.0, 0.0] };
        let t = Segment { a: [1.0, -1.0], b: [1.0, 1.0] };
        let r = intersect(&[s], &[t]);
        assert_eq!(r.len(), 1);
        assert!(length(sub(r[0].a, [1.0, 0.0])) < 1e-12 && r[0].is_empty());
        let u = Segment { a: [1.5, 0.0], b: [3.0, 0.0] };
        let r = intersect(&[s], &[u]);
        assert!((r[0].len() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn square_against_square() {
        let s = contact_segments(&block(&SQ), &block(&SQ), 0.25);
        assert_eq!(s.len(), 4);
        assert!(s.iter().all(|x| (x.len() - 1.5).abs() < 1e-12));
    }
}
