//! Streamline candidates through a cross field (Yang et al. 2013 §5, "Streamline Candidate
//! Generation"): seeds are the inner vertices of the field's triangulation, each with its two
//! cross lines flagged active; in a seeded random order, an active line is traced both ways by
//! fourth-order Runge–Kutta until it meets the region's boundary, where it ends exactly; every
//! seed within the separation `dε` of a kept streamline loses the line closest to it, and a
//! traced seed loses its own line whether the streamline is kept or not.
//!
//! At every Runge–Kutta stage the cross branch nearest the current travel direction is taken
//! (the four directions `θ + kπ/2` of a cross are otherwise ambiguous). A streamline is discarded
//! when it reaches a singularity (enters a singular triangle, or the interpolated `|u|` falls below
//! [`TraceOptions::min_magnitude`] — small, since a smooth field's `|u|` decays like `r⁴` towards
//! the centre of a disc without being singular there),
//! crosses itself, leaves the triangulation without meeting the boundary, or grows longer than
//! [`TraceOptions::max_length`] (a spiral or a closed orbit).

use super::field::CrossField;
use crate::geometry::index::SegmentIndex;
use crate::geometry::{add, dist, dot, norm, polyline_length, scale, segment_intersection, sub, Polygon, P};
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;

/// How streamlines are traced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceOptions {
    /// `dε`: seeds this close to a kept streamline lose their nearest line (paper: 0.3 × the
    /// parcel depth).
    pub separation: f64,
    /// The Runge–Kutta step (metres).
    pub step: f64,
    /// Below this `|u|` the field is singular and the streamline is discarded.
    pub min_magnitude: f64,
    /// Longer streamlines are discarded.
    pub max_length: f64,
}

/// Where a streamline meets the boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryHit {
    /// The ring (0: outer, `1 + i`: hole `i`).
    pub ring: usize,
    /// The ring's edge (from vertex `edge` to `edge + 1`).
    pub edge: usize,
    /// The parameter along the edge.
    pub t: f64,
    /// The point.
    pub at: P,
    /// The unit travel direction arriving there.
    pub direction: P,
}

/// A traced streamline, from boundary to boundary.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// Its points, from `ends[0].at` to `ends[1].at`.
    pub points: Vec<P>,
    /// Its ends.
    pub ends: [BoundaryHit; 2],
    /// `∫ |∇·f| ds` of the traced branch along it.
    pub divergence: f64,
    /// Its length.
    pub length: f64,
}

/// The region's boundary edges, indexed, with their ring and edge numbers.
pub struct BoundaryIndex {
    index: SegmentIndex,
    ids: Vec<(usize, usize)>,
}

impl BoundaryIndex {
    /// The index of a polygon's rings.
    pub fn new(region: &Polygon) -> BoundaryIndex {
        let mut segs = Vec::new();
        let mut ids = Vec::new();
        for (r, ring) in region.rings().enumerate() {
            for e in 0..ring.len() {
                segs.push((ring[e], ring[(e + 1) % ring.len()]));
                ids.push((r, e));
            }
        }
        let [lo, hi] = region.bounds();
        let cell = ((hi[0] - lo[0]).max(hi[1] - lo[1]) / 64.0).max(1.0);
        BoundaryIndex { index: SegmentIndex::new(segs, cell), ids }
    }

    /// The first boundary crossing of segment `a → b` (smallest parameter along it).
    pub fn first_hit(&self, a: P, b: P) -> Option<(f64, usize, usize, f64)> {
        let mid = scale(add(a, b), 0.5);
        let r = dist(a, b) / 2.0 + 1e-9;
        self.index
            .near(mid, r)
            .into_iter()
            .filter_map(|k| {
                let (c, d) = self.index.segments()[k];
                segment_intersection(a, b, c, d).map(|(s, t)| (s, self.ids[k].0, self.ids[k].1, t))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
    }

    /// The distance from `p` along the ray `p + s·d` (`d` unit) to the boundary, if it meets it
    /// within `reach`.
    pub fn ray(&self, p: P, d: P, reach: f64) -> Option<f64> {
        self.first_hit(p, add(p, scale(d, reach))).map(|h| h.0 * reach)
    }
}

/// Every candidate streamline of a region's field, in the order traced.
pub fn candidates(
    field: &CrossField,
    region: &Polygon,
    opts: &TraceOptions,
    rng: &mut Xoshiro256PlusPlus,
) -> Vec<Candidate> {
    let boundary = BoundaryIndex::new(region);
    let verts = field.vertices();
    let mut seeds: Vec<usize> = field.inner_vertices().collect();
    // Fisher–Yates with the seeded generator.
    for i in (1..seeds.len()).rev() {
        let j = ((rng.random::<f64>() * (i + 1) as f64) as usize).min(i);
        seeds.swap(i, j);
    }
    let seed_index = SegmentIndex::new(seeds.iter().map(|&v| (verts[v], verts[v])).collect(), opts.separation.max(1.0));
    let mut active = vec![[true; 2]; seeds.len()];
    let mut out = Vec::new();
    for k in 0..seeds.len() {
        for o in 0..2 {
            if !active[k][o] {
                continue;
            }
            active[k][o] = false;
            let theta = field.theta(seeds[k]) + o as f64 * std::f64::consts::FRAC_PI_2;
            match trace(field, &boundary, verts[seeds[k]], [theta.cos(), theta.sin()], opts) {
                Ok(c) => {
                    deactivate(field, &seed_index, &seeds, &mut active, &c.points, opts.separation);
                    out.push(c);
                }
                // Seeds on a discarded streamline would trace the same curve: their line is off.
                Err(points) => deactivate(field, &seed_index, &seeds, &mut active, &points, opts.separation / 2.0),
            }
        }
    }
    out
}

/// Turns off, on every seed within `sep` of the streamline, the cross line closest to its
/// tangent there.
fn deactivate(
    field: &CrossField,
    index: &SegmentIndex,
    seeds: &[usize],
    active: &mut [[bool; 2]],
    line: &[P],
    sep: f64,
) {
    let mut last: Option<P> = None;
    for w in line.windows(2) {
        if last.is_some_and(|q| dist(q, w[0]) < sep / 2.0) {
            continue;
        }
        last = Some(w[0]);
        let t = sub(w[1], w[0]);
        let l = norm(t);
        if l <= 0.0 {
            continue;
        }
        let t = scale(t, 1.0 / l);
        for k in index.near(w[0], sep) {
            let p = field.vertices()[seeds[k]];
            if dist(p, w[0]) > sep {
                continue;
            }
            let th = field.theta(seeds[k]);
            let along = dot([th.cos(), th.sin()], t).abs();
            let across = dot([-th.sin(), th.cos()], t).abs();
            active[k][usize::from(across > along)] = false;
        }
    }
}

/// Traces from `p` both ways along the cross line nearest `d`; a discarded streamline gives the
/// points traced before it was discarded.
pub fn trace(
    field: &CrossField,
    boundary: &BoundaryIndex,
    p: P,
    d: P,
    opts: &TraceOptions,
) -> Result<Candidate, Vec<P>> {
    let (fwd, end1, div1) = half(field, boundary, p, d, opts)?;
    let (bwd, end0, div0) = half(field, boundary, p, scale(d, -1.0), opts).map_err(|mut b| {
        b.extend(fwd.iter().copied());
        b
    })?;
    let mut points: Vec<P> = bwd.into_iter().rev().collect();
    points.pop();
    points.extend(fwd);
    let length = polyline_length(&points);
    if length > opts.max_length || self_crossing(&points) {
        return Err(points);
    }
    Ok(Candidate { points, ends: [end0, end1], divergence: div0 + div1, length })
}

/// One direction: points from `p` to the boundary, the hit, and `∫|∇·f|`; or the points traced
/// before a singularity, a closed orbit, the length limit or the triangulation's edge stopped it.
fn half(
    field: &CrossField,
    boundary: &BoundaryIndex,
    p: P,
    d: P,
    opts: &TraceOptions,
) -> Result<(Vec<P>, BoundaryHit, f64), Vec<P>> {
    let h = opts.step;
    let mut x = p;
    let Some(mut dir) = field.direction(x, d) else { return Err(vec![p]) };
    let mut pts = vec![x];
    let (mut length, mut div) = (0.0, 0.0);
    while length <= opts.max_length {
        let singular = |t: usize| field.singularities().iter().any(|s| s.triangle == t);
        let Some(s) = field.sample(x).filter(|s| s.magnitude >= opts.min_magnitude && !singular(s.triangle)) else {
            return Err(pts);
        };
        if length > 4.0 * h && dist(x, p) < h {
            // Back at the start: a closed orbit.
            return Err(pts);
        }
        let y = rk4(field, x, dir, h).unwrap_or_else(|| add(x, scale(dir, h)));
        if let Some((s_hit, ring, edge, t)) = boundary.first_hit(x, y) {
            let at = add(x, scale(sub(y, x), s_hit));
            let step = sub(y, x);
            let direction = scale(step, 1.0 / norm(step).max(1e-300));
            if dist(at, x) > 0.0 {
                pts.push(at);
            }
            div += field.divergence(s.triangle, direction).abs() * dist(at, x);
            return Ok((pts, BoundaryHit { ring, edge, t, at, direction }, div));
        }
        let step = sub(y, x);
        let l = norm(step);
        if l <= 1e-9 * h {
            return Err(pts);
        }
        dir = scale(step, 1.0 / l);
        div += field.divergence(s.triangle, dir).abs() * l;
        length += l;
        x = y;
        pts.push(x);
    }
    Err(pts)
}

/// One Runge–Kutta step of length `h` from `x`, each stage on the branch nearest the previous.
fn rk4(field: &CrossField, x: P, d: P, h: f64) -> Option<P> {
    let k1 = field.direction(x, d)?;
    let k2 = field.direction(add(x, scale(k1, h / 2.0)), k1)?;
    let k3 = field.direction(add(x, scale(k2, h / 2.0)), k2)?;
    let k4 = field.direction(add(x, scale(k3, h)), k3)?;
    let sum = add(add(k1, scale(k2, 2.0)), add(scale(k3, 2.0), k4));
    Some(add(x, scale(sum, h / 6.0)))
}

/// Whether a polyline crosses itself (segments at least three apart; checked on every point, with
/// a bounding-box sweep).
fn self_crossing(points: &[P]) -> bool {
    let n = points.len();
    if n < 5 {
        return false;
    }
    let segs: Vec<(P, P)> = points.windows(2).map(|w| (w[0], w[1])).collect();
    let step = segs.iter().map(|s| dist(s.0, s.1)).fold(0.0, f64::max);
    let index = SegmentIndex::new(segs.clone(), (step * 4.0).max(1e-6));
    segs.iter().enumerate().any(|(i, s)| {
        let mid = scale(add(s.0, s.1), 0.5);
        index
            .near(mid, dist(s.0, s.1) / 2.0 + 1e-9)
            .into_iter()
            .any(|j| j > i + 2 && segment_intersection(s.0, s.1, segs[j].0, segs[j].1).is_some())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::field::{FieldMethod, FieldOptions};
    use rand::SeedableRng;

    #[test]
    fn a_rectangle_gives_straight_streamlines_ending_on_its_boundary() {
        let region = Polygon::new(vec![[0.0, 0.0], [200.0, 0.0], [200.0, 100.0], [0.0, 100.0]], vec![]).unwrap();
        for method in [FieldMethod::Smooth, FieldMethod::Distance] {
            let field = CrossField::new(&region, &FieldOptions { method, h: 10.0 }).unwrap();
            let opts = TraceOptions { separation: 9.0, step: 2.0, min_magnitude: 1e-4, max_length: 600.0 };
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
            let cs = candidates(&field, &region, &opts, &mut rng);
            assert!(cs.len() >= 10, "{method:?}: {} candidates", cs.len());
            for c in &cs {
                for e in &c.ends {
                    assert!(region.boundary_distance(e.at) < 1e-9);
                }
                // Straight across: length is the chord between its ends, within 1 %.
                assert!(c.length <= 1.01 * dist(c.ends[0].at, c.ends[1].at), "{method:?}: {c:?}");
            }
            let across = cs.iter().filter(|c| (c.points[0][0] - c.points[c.points.len() - 1][0]).abs() < 1.0).count();
            assert!(across > 0 && across < cs.len(), "{method:?}: both families");
        }
    }

    #[test]
    fn self_crossing_is_detected() {
        let loop_ = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [5.0, 10.0], [5.0, -5.0]];
        assert!(self_crossing(&loop_));
        assert!(!self_crossing(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 1.0], [4.0, 2.0]]));
    }
}
