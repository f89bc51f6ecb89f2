//! A block's boundary by arc length: its corners (turns of at least 30° after a 1 m
//! Douglas–Peucker simplification, corners closer than a third of a parcel depth merged), its
//! sides' street flags, and the matching of a template's corners and sides onto them, ranked by
//! the distortion of the side lengths `Σ ln(len_block / len_template)²` (Yang et al. 2013 §4.1,
//! "Initialization").

use super::file::{CornerKind, SideKind};
use super::instance::{turn, Instance, CORNER_TURN};
use crate::geometry::{closest_on_segment, dist, P};
use crate::layout::parcels::StreetIndex;
use geo::Simplify;

/// A closed ring (counter-clockwise, not closed) by arc length.
#[derive(Clone, Debug)]
pub struct Ring {
    /// Its vertices.
    pub pts: Vec<P>,
    /// `cum[i]`: arc length at vertex `i`; `cum[n]` the perimeter.
    pub cum: Vec<f64>,
}

impl Ring {
    /// The ring.
    pub fn new(pts: Vec<P>) -> Ring {
        let n = pts.len();
        let mut cum = vec![0.0; n + 1];
        for i in 0..n {
            cum[i + 1] = cum[i] + dist(pts[i], pts[(i + 1) % n]);
        }
        Ring { pts, cum }
    }

    /// The perimeter.
    pub fn length(&self) -> f64 {
        self.cum[self.pts.len()]
    }

    fn wrap(&self, s: f64) -> f64 {
        s.rem_euclid(self.length())
    }

    /// The edge holding arc length `s` (wrapped) and the parameter along it.
    fn locate(&self, s: f64) -> (usize, f64) {
        let s = self.wrap(s);
        let n = self.pts.len();
        let i = self.cum.partition_point(|&c| c <= s).saturating_sub(1).min(n - 1);
        let len = self.cum[i + 1] - self.cum[i];
        (i, if len > 0.0 { (s - self.cum[i]) / len } else { 0.0 })
    }

    /// The point at arc length `s` (any real; wrapped).
    pub fn at(&self, s: f64) -> P {
        let (i, t) = self.locate(s);
        let (a, b) = (self.pts[i], self.pts[(i + 1) % self.pts.len()]);
        [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]
    }

    /// The ring's vertices strictly between arc lengths `s0 < s1` (unwrapped, `s1 − s0` less than
    /// the perimeter), in order.
    pub fn between(&self, s0: f64, s1: f64) -> Vec<P> {
        let l = self.length();
        let n = self.pts.len();
        let mut out = Vec::new();
        let base = (s0 / l).floor() * l;
        for lap in 0..2 {
            for i in 0..n {
                let s = base + lap as f64 * l + self.cum[i];
                if s > s0 + 1e-9 && s < s1 - 1e-9 {
                    out.push(self.pts[i]);
                }
            }
        }
        out
    }

    /// The arc length in `[s0, s1]` (unwrapped) of the point of that arc nearest `p`.
    pub fn project(&self, p: P, s0: f64, s1: f64) -> f64 {
        let mut best = (dist(p, self.at(s0)), s0);
        let end = dist(p, self.at(s1));
        if end < best.0 {
            best = (end, s1);
        }
        // Only the edges the arc spans, from the one holding s0.
        let n = self.pts.len();
        let (mut i, _) = self.locate(s0);
        let mut a = s0 - (self.wrap(s0) - self.cum[i]);
        for _ in 0..=2 * n {
            let b = a + (self.cum[i + 1] - self.cum[i]);
            let (lo, hi) = (a.max(s0), b.min(s1));
            if lo < hi {
                let (q, t) = closest_on_segment(p, self.at(lo), self.at(hi));
                let d = dist(p, q);
                if d < best.0 {
                    best = (d, lo + t * (hi - lo));
                }
            }
            if b >= s1 {
                break;
            }
            a = b;
            i = (i + 1) % n;
        }
        best.1
    }
}

/// A corner of a block: its arc length, kind and turn (degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockCorner {
    /// Arc length along the block's ring.
    pub s: f64,
    /// Convex or concave.
    pub kind: CornerKind,
    /// The turn (degrees, left positive).
    pub turn: f64,
}

/// The block's corners, in ring order; `merge` is the distance within which corners merge.
pub fn block_corners(ring: &Ring, merge: f64) -> Vec<BlockCorner> {
    let closed: Vec<(f64, f64)> = ring.pts.iter().chain(ring.pts.first()).map(|p| (p[0], p[1])).collect();
    let simple: Vec<P> = geo::LineString::from(closed).simplify(1.0).0.iter().map(|c| [c.x, c.y]).collect();
    let simple = &simple[..simple.len().saturating_sub(1)];
    let m = simple.len();
    if m < 3 {
        return vec![];
    }
    let mut raw: Vec<BlockCorner> = Vec::new();
    for i in 0..m {
        let a = turn(simple[(i + m - 1) % m], simple[i], simple[(i + 1) % m]);
        if a.abs() >= CORNER_TURN / 2.0 {
            let k = ring.pts.iter().position(|&p| p == simple[i]).unwrap_or(0);
            raw.push(BlockCorner { s: ring.cum[k], kind: CornerKind::None, turn: a });
        }
    }
    // Merge runs of corners closer than `merge` along the ring (a chamfer is one corner).
    let l = ring.length();
    let mut groups: Vec<Vec<BlockCorner>> = Vec::new();
    for c in raw {
        match groups.last_mut() {
            Some(g) if c.s - g[g.len() - 1].s < merge && (c.turn > 0.0) == (g[0].turn > 0.0) => g.push(c),
            _ => groups.push(vec![c]),
        }
    }
    if groups.len() > 1 {
        let (first, last) = (&groups[0], &groups[groups.len() - 1]);
        if first[0].s + l - last[last.len() - 1].s < merge && (first[0].turn > 0.0) == (last[0].turn > 0.0) {
            let last = groups.pop().unwrap_or_default();
            groups[0].splice(0..0, last);
        }
    }
    let mut out: Vec<BlockCorner> = groups
        .into_iter()
        .filter_map(|g| {
            let sum: f64 = g.iter().map(|c| c.turn).sum();
            let sharpest = g.iter().max_by(|a, b| a.turn.abs().total_cmp(&b.turn.abs()))?;
            let kind = if sum >= CORNER_TURN {
                CornerKind::Convex
            } else if sum <= -CORNER_TURN {
                CornerKind::Concave
            } else {
                return None;
            };
            Some(BlockCorner { s: sharpest.s, kind, turn: sum })
        })
        .collect();
    out.sort_by(|a, b| a.s.total_cmp(&b.s));
    out
}

/// Whether most of the arc `[s0, s1]` (by length) fronts a street.
pub fn side_is_street(ring: &Ring, s0: f64, s1: f64, streets: &StreetIndex) -> bool {
    let mut pts = vec![ring.at(s0)];
    pts.extend(ring.between(s0, s1));
    pts.push(ring.at(s1));
    let (mut on, mut all) = (0.0, 0.0);
    for w in pts.windows(2) {
        let len = dist(w[0], w[1]);
        let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
        all += len;
        if streets.fronts(&[mid]) {
            on += len;
        }
    }
    all > 0.0 && on >= 0.5 * all
}

/// A block prepared for matching: its ring, corners and their sides' street flags.
#[derive(Clone, Debug)]
pub struct Block {
    /// The ring.
    pub ring: Ring,
    /// Its corners.
    pub corners: Vec<BlockCorner>,
    /// Side `i` (corner `i` to `i + 1`) fronts a street.
    pub street: Vec<bool>,
    /// Its area (m²).
    pub area: f64,
}

impl Block {
    /// The block of a ring.
    pub fn new(pts: Vec<P>, streets: &StreetIndex, merge: f64) -> Block {
        let area = crate::geometry::ring_area2(&pts).abs() / 2.0;
        let ring = Ring::new(pts);
        let corners = block_corners(&ring, merge);
        let k = corners.len();
        let l = ring.length();
        let street = (0..k)
            .map(|i| {
                let (s0, mut s1) = (corners[i].s, corners[(i + 1) % k].s);
                if s1 <= s0 {
                    s1 += l;
                }
                side_is_street(&ring, s0, s1, streets)
            })
            .collect();
        Block { ring, corners, street, area }
    }
}

/// A match of a template's corners onto a block's: the block arc length of every template
/// corner (increasing, unwrapped) and the distortion of the side lengths.
#[derive(Clone, Debug, PartialEq)]
pub struct Match {
    /// Arc length of template corner `i` on the block (increasing; the last side ends at
    /// `s[0] + perimeter`).
    pub s: Vec<f64>,
    /// `Σ ln(len_block / len_template)²` over the sides.
    pub distortion: f64,
}

/// The template sides' lengths.
pub fn side_lengths(inst: &Instance) -> Vec<f64> {
    let n = inst.boundary.len();
    let k = inst.corners.len();
    (0..k)
        .map(|i| {
            let (a, b) = (inst.corners[i].0, inst.corners[(i + 1) % k].0);
            let steps = (b + n - a) % n;
            let steps = if steps == 0 { n } else { steps };
            (0..steps)
                .map(|j| dist(inst.verts[inst.boundary[(a + j) % n]], inst.verts[inst.boundary[(a + j + 1) % n]]))
                .sum()
        })
        .collect()
}

/// Every compatible match of the template onto the block, best (least distortion) first. A block
/// with more corners than the template may drop its gentlest ones (turns under 60°).
pub fn matches(inst: &Instance, block: &Block) -> Vec<Match> {
    let k = inst.corners.len();
    let m = block.corners.len();
    if m < k {
        return vec![];
    }
    let mut keep: Vec<usize> = (0..m).collect();
    if m > k {
        let mut by_turn = keep.clone();
        by_turn.sort_by(|&a, &b| block.corners[b].turn.abs().total_cmp(&block.corners[a].turn.abs()));
        if by_turn[k..].iter().any(|&i| block.corners[i].turn.abs() >= 2.0 * CORNER_TURN) {
            return vec![];
        }
        keep = by_turn[..k].to_vec();
        keep.sort_unstable();
    }
    let l = block.ring.length();
    let tl = side_lengths(inst);
    // A side of the reduced block: street when any of the original sides it spans is (by length).
    let street_of = |i: usize, j: usize| -> bool {
        let (a, b) = (keep[i], keep[j]);
        let (mut on, mut all) = (0.0, 0.0);
        let mut c = a;
        loop {
            let d = (c + 1) % m;
            let mut len = block.corners[d].s - block.corners[c].s;
            if len <= 0.0 {
                len += l;
            }
            all += len;
            if block.street[c] {
                on += len;
            }
            c = d;
            if c == b {
                break;
            }
        }
        on >= 0.5 * all
    };
    let mut out = Vec::new();
    for r in 0..k {
        let ok = (0..k).all(|i| {
            let bi = (i + r) % k;
            block.corners[keep[bi]].kind == inst.corners[i].1
                && match inst.sides[i] {
                    SideKind::Any => true,
                    SideKind::Street => street_of(bi, (bi + 1) % k),
                    SideKind::None => !street_of(bi, (bi + 1) % k),
                }
        });
        if !ok {
            continue;
        }
        let mut s: Vec<f64> = (0..k).map(|i| block.corners[keep[(i + r) % k]].s).collect();
        for i in 1..k {
            while s[i] <= s[i - 1] {
                s[i] += l;
            }
        }
        let distortion = (0..k)
            .map(|i| {
                let next = if i + 1 < k { s[i + 1] } else { s[0] + l };
                ((next - s[i]) / tl[i]).ln().powi(2)
            })
            .sum();
        out.push(Match { s, distortion });
    }
    out.sort_by(|a, b| a.distortion.total_cmp(&b.distortion));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_length_points_and_projection() {
        let r = Ring::new(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 5.0], [0.0, 5.0]]);
        assert_eq!(r.length(), 30.0);
        assert_eq!(r.at(12.5), [10.0, 2.5]);
        assert_eq!(r.at(32.0), [2.0, 0.0]);
        assert_eq!(r.between(8.0, 17.0), vec![[10.0, 0.0], [10.0, 5.0]]);
        assert_eq!(r.between(28.0, 32.0), vec![[0.0, 0.0]]);
        assert!((r.project([4.0, -1.0], 0.0, 10.0) - 4.0).abs() < 1e-12);
        // Restricted to the right side, the nearest point is its start.
        assert!((r.project([4.0, -1.0], 10.0, 15.0) - 10.0).abs() < 1e-12);
    }

    #[test]
    fn a_rectangle_block_has_four_corners_and_a_chamfer_merges() {
        let idx = StreetIndex::new(&[]);
        let b = Block::new(vec![[0.0, 0.0], [100.0, 0.0], [100.0, 60.0], [0.0, 60.0]], &idx, 9.0);
        assert_eq!(b.corners.len(), 4);
        assert!(b.corners.iter().all(|c| c.kind == CornerKind::Convex && (c.turn - 90.0).abs() < 1e-9));
        let c = Block::new(vec![[0.0, 0.0], [97.0, 0.0], [100.0, 3.0], [100.0, 60.0], [0.0, 60.0]], &idx, 9.0);
        assert_eq!(c.corners.len(), 4);
    }
}
