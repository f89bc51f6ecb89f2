//! The global optimisation of the streets (Yang et al. 2013 §6): after the split, the street
//! network is faired and its blocks pulled towards strips bounded by a pair of offset curves, so
//! that rows of parcels fit them with less distortion.
//!
//! **The mesh.** Every street made by the split (level ≥ 1) is resampled at a uniform spacing;
//! its vertices are the unknowns. Streets are added in the order they were cut, so each street's
//! ends lie on the region's boundary, on a hole, on a given major road or on an earlier street:
//! an end on an earlier split street is merged with that street's nearest vertex (the paper's
//! short-edge collapse: no edge shorter than half the spacing at a junction), and the junction
//! is then one vertex shared by both streets. Given major roads (level 0) are input and stay
//! fixed.
//!
//! **The energy** (eq. 3) `F = w_s f_shape + w_f f_fair + w_c f_close` with the paper's weights
//! 1 / 0.8 / 0.2:
//! * `f_shape = Σ |v − v̄|²` (eq. 5): the blocks are the region minus the streets' areas; a block
//!   close to a quadrilateral (its area at least 3/4 of its minimum rotated rectangle's) is split
//!   at the ring points nearest the rectangle's corners into four sides; of the two pairs of
//!   opposite sides the one facing each other across the narrower gap is `(c₁, c₂)` (the strip
//!   runs along the block; the paper keeps the pair of smaller offset deviation, which on a
//!   tapering block picks its far-apart ends);
//!   both are sampled at the same arc-length parameters, their midpoints `mᵢ` make the midline,
//!   and the target strip is `mᵢ ± (l/2) nᵢ` with `l` the mean distance between them (Fig. 9),
//!   the two short sides straight between the strip's ends. A street vertex takes, from every
//!   block whose long side runs within its half width (plus 1 m), the displacement that brings
//!   the nearest point of that side to its target at the same arc-length parameter; `v̄` is `v`
//!   plus the mean of those displacements (eq. 4 with equal weights). The short sides and the
//!   outer 15 % of each long side give no target: there blocks meet at a junction, their
//!   targets disagree, and following them kinks the streets. Vertices with no target from any
//!   block have no shape term.
//! * `f_fair = Σ |v_{i−1} − 2vᵢ + v_{i+1}|²` along every split street (eq. 6);
//! * `f_close = Σ |v − v⁰|²` to the positions before the optimisation (eq. 7).
//!
//! **Constraints.** A street end on the region's boundary (or a hole's) or on a major road slides
//! along the boundary segment it lies on, never past that segment's ends (the paper's
//! intersections sliding on the boundary). The sliding is applied by solving with the end free
//! and projecting it back onto its segment — x and y then decouple, so each iteration is one
//! sparse symmetric positive definite matrix `w_s S + w_f DᵀD + w_c I` solved for x and y by
//! [`crate::geometry::sparse`]; the projection moves an end by at most the (small) normal part of
//! its step. The strips are re-fitted and the system solved again, 10 times.

use super::parcels::blocks;
use super::region::Region;
use super::Street;
use crate::geometry::index::SegmentIndex;
use crate::geometry::sparse::Csr;
use crate::geometry::{
    add, closest_on_segment, dist, dot, lerp, norm, point_at_length, polyline_length, scale, sub, P,
};
use geo::{Area, MinimumRotatedRect};

/// The optimisation's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OptimiseOptions {
    /// Iterations (strip fit, then one solve), 10 in the paper; 0 leaves the streets as they are.
    pub iterations: usize,
    /// Weight of strip fitting `w_s`.
    pub shape: f64,
    /// Weight of fairness `w_f`.
    pub fair: f64,
    /// Weight of closeness `w_c`.
    pub close: f64,
    /// The spacing street vertices are resampled at (metres).
    pub spacing: f64,
}

impl OptimiseOptions {
    /// The paper's weights and iterations, vertices a quarter of a parcel's width apart.
    pub fn for_region(region: &Region) -> OptimiseOptions {
        OptimiseOptions { iterations: 10, shape: 1.0, fair: 0.8, close: 0.2, spacing: region.parcel.width / 4.0 }
    }
}

/// How a vertex may move.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Free,
    Fixed,
    /// Along this segment, between its ends.
    Slide(P, P),
}

/// The street network as vertices and chains of vertices.
#[derive(Debug)]
struct Mesh {
    pos: Vec<P>,
    kind: Vec<Kind>,
    /// Per street: `Some(vertex ids)` for a split street, `None` for a fixed major road.
    chains: Vec<Option<Vec<usize>>>,
}

/// Fairs the split streets and pulls their blocks towards strips; returns the streets in the
/// same order, major roads unchanged.
pub fn optimise(region: &Region, streets: &[Street], opts: &OptimiseOptions) -> Vec<Street> {
    if opts.iterations == 0 || streets.iter().all(|s| s.level == 0) {
        return streets.to_vec();
    }
    let mut mesh = build(region, streets, opts.spacing);
    let start = mesh.pos.clone();
    let mut current = to_streets(&mesh, streets);
    for _ in 0..opts.iterations {
        let targets = shape_targets(region, &current, &mesh);
        solve(&mut mesh, &start, &targets, opts);
        current = to_streets(&mesh, streets);
    }
    current
}

fn to_streets(mesh: &Mesh, streets: &[Street]) -> Vec<Street> {
    streets
        .iter()
        .zip(&mesh.chains)
        .map(|(s, c)| match c {
            Some(ids) => Street { polyline: ids.iter().map(|&v| mesh.pos[v]).collect(), ..s.clone() },
            None => s.clone(),
        })
        .collect()
}

/// Within this distance (metres) a street end lies on the boundary or on another street.
const ON: f64 = 0.5;

fn build(region: &Region, streets: &[Street], spacing: f64) -> Mesh {
    let mut mesh = Mesh { pos: Vec::new(), kind: Vec::new(), chains: Vec::new() };
    let boundary: Vec<(P, P)> = region.polygon.edges().collect();
    for (k, s) in streets.iter().enumerate() {
        if s.level == 0 || s.polyline.len() < 2 {
            mesh.chains.push(None);
            continue;
        }
        let pts = resample(&s.polyline, spacing);
        let mut ids: Vec<usize> = Vec::with_capacity(pts.len());
        let last = pts.len() - 1;
        for (i, &p) in pts.iter().enumerate() {
            let id = if i == 0 || i == last { end_vertex(&mut mesh, p, &boundary, &streets[..k]) } else { None };
            ids.push(id.unwrap_or_else(|| push(&mut mesh, p, Kind::Free)));
        }
        ids.dedup();
        mesh.chains.push((ids.len() >= 2).then_some(ids));
    }
    mesh
}

fn push(mesh: &mut Mesh, p: P, kind: Kind) -> usize {
    mesh.pos.push(p);
    mesh.kind.push(kind);
    mesh.pos.len() - 1
}

/// The vertex a street end becomes: an earlier split street's nearest vertex, or a new vertex
/// sliding on the boundary or a major road; `None` for a free end.
fn end_vertex(mesh: &mut Mesh, p: P, boundary: &[(P, P)], earlier: &[Street]) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for chain in mesh.chains.iter().take(earlier.len()) {
        let Some(ids) = chain else { continue };
        let near = ids.windows(2).any(|w| dist(p, closest_on_segment(p, mesh.pos[w[0]], mesh.pos[w[1]]).0) <= ON);
        if !near {
            continue;
        }
        for &v in ids {
            let d = dist(p, mesh.pos[v]);
            if best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, v));
            }
        }
    }
    if let Some((_, v)) = best {
        return Some(v);
    }
    let majors = earlier.iter().filter(|s| s.level == 0).flat_map(|s| s.polyline.windows(2).map(|w| (w[0], w[1])));
    let on = boundary
        .iter()
        .copied()
        .chain(majors)
        .map(|(a, b)| (dist(p, closest_on_segment(p, a, b).0), a, b))
        .filter(|&(d, _, _)| d <= ON)
        .min_by(|x, y| x.0.total_cmp(&y.0));
    on.map(|(_, a, b)| {
        push(mesh, closest_on_segment(p, a, b).0, if dist(a, b) > 0.0 { Kind::Slide(a, b) } else { Kind::Fixed })
    })
}

/// `line` resampled at about `spacing`, both ends kept.
fn resample(line: &[P], spacing: f64) -> Vec<P> {
    let len = polyline_length(line);
    let n = ((len / spacing).round() as usize).max(1);
    (0..=n).map(|i| point_at_length(line, len * i as f64 / n as f64)).collect()
}

/// Per vertex, the target `v̄` of strip fitting, if any block gives one.
fn shape_targets(region: &Region, streets: &[Street], mesh: &Mesh) -> Vec<Option<P>> {
    let fits: Vec<Option<Strip>> = blocks(&region.polygon, streets).iter().map(|b| Strip::fit(b.geo())).collect();
    let mut segments = Vec::new();
    let mut owner = Vec::new();
    for (b, strip) in fits.iter().enumerate() {
        if let Some(s) = strip {
            for i in 0..s.ring.len() {
                segments.push((s.ring[i], s.ring[(i + 1) % s.ring.len()]));
                owner.push((b, i));
            }
        }
    }
    let reach = streets.iter().map(|s| s.width / 2.0).fold(0.0, f64::max) + 1.0;
    let index = SegmentIndex::new(segments, reach);
    let mut half = vec![0.0f64; mesh.pos.len()];
    for (s, chain) in streets.iter().zip(&mesh.chains) {
        for &v in chain.iter().flatten() {
            half[v] = half[v].max(s.width / 2.0);
        }
    }
    (0..mesh.pos.len())
        .map(|v| {
            if mesh.kind[v] == Kind::Fixed {
                return None;
            }
            let p = mesh.pos[v];
            // The nearest point of each block's ring within reach.
            let mut per_block: Vec<(usize, f64, usize, P)> = Vec::new();
            for k in index.near(p, half[v] + 1.0) {
                let (a, b) = index.segments()[k];
                let (q, _) = closest_on_segment(p, a, b);
                let d = dist(p, q);
                if d > half[v] + 1.0 {
                    continue;
                }
                let (blk, edge) = owner[k];
                match per_block.iter_mut().find(|e| e.0 == blk) {
                    Some(e) if d < e.1 => *e = (blk, d, edge, q),
                    Some(_) => {}
                    None => per_block.push((blk, d, edge, q)),
                }
            }
            let shifts: Vec<P> = per_block
                .iter()
                .filter_map(|&(blk, _, edge, q)| {
                    let strip = fits[blk].as_ref().expect("indexed blocks have strips");
                    strip.target(edge, q).map(|t| sub(t, q))
                })
                .collect();
            if shifts.is_empty() {
                return None;
            }
            let n = shifts.len() as f64;
            Some(add(p, shifts.iter().fold([0.0, 0.0], |acc, d| add(acc, scale(*d, 1.0 / n)))))
        })
        .collect()
}

/// A block fitted by a strip: its ring, the ring's arc length at every vertex, the four corner
/// positions along it, and the target sides.
struct Strip {
    ring: Vec<P>,
    /// `cum[i]` = arc length from vertex 0 to vertex i; `cum[n]` the perimeter.
    cum: Vec<f64>,
    /// Arc lengths of the four corners, ascending from the first.
    corners: [f64; 4],
    /// Which side (0..4, side k from corner k to corner k+1) is `c₁`; `c₂` is side `first + 2`.
    first: usize,
    /// The target curve of `c₁` (from its start to its end) and of `c₂` (from `c₁`'s start side to
    /// its end side, i.e. against `c₂`'s own direction).
    t1: Vec<P>,
    t2: Vec<P>,
}

/// The share of a long side at either end that gets no target: near a corner, where blocks
/// meet at a junction, the targets of neighbouring blocks disagree and would kink the streets.
const END_MARGIN: f64 = 0.15;

/// Samples per side of a strip.
const SAMPLES: usize = 24;

impl Strip {
    /// The strip of a near-quadrilateral block without holes, else `None`.
    fn fit(block: &geo::Polygon<f64>) -> Option<Strip> {
        if !block.interiors().is_empty() {
            return None;
        }
        let rect = block.minimum_rotated_rect()?;
        if block.unsigned_area() < 0.75 * rect.unsigned_area() {
            return None;
        }
        let ring = crate::geometry::shape::outer_ring(block);
        let n = ring.len();
        if n < 4 {
            return None;
        }
        let mut cum = vec![0.0];
        for i in 0..n {
            cum.push(cum[i] + dist(ring[i], ring[(i + 1) % n]));
        }
        let corners_xy: Vec<P> = rect.exterior().0.iter().take(4).map(|c| [c.x, c.y]).collect();
        let mut idx: Vec<usize> = corners_xy
            .iter()
            .map(|&c| (0..n).min_by(|&i, &j| dist(ring[i], c).total_cmp(&dist(ring[j], c))).expect("a ring"))
            .collect();
        idx.sort_unstable();
        idx.dedup();
        if idx.len() != 4 {
            return None;
        }
        let corners = [cum[idx[0]], cum[idx[1]], cum[idx[2]], cum[idx[3]]];
        let mut strip = Strip { ring, cum, corners, first: 0, t1: Vec::new(), t2: Vec::new() };
        let gap = |k: usize| {
            let (a, b) = strip.facing(k);
            a.iter().zip(&b).map(|(p, q)| dist(*p, *q)).sum::<f64>()
        };
        strip.first = if gap(1) < gap(0) { 1 } else { 0 };
        let (c1, c2) = strip.facing(strip.first);
        let mid: Vec<P> = c1.iter().zip(&c2).map(|(a, b)| scale(add(*a, *b), 0.5)).collect();
        let l = c1.iter().zip(&c2).map(|(a, b)| dist(*a, *b)).sum::<f64>() / c1.len() as f64;
        let m = mid.len();
        for i in 0..m {
            let t = sub(mid[(i + 1).min(m - 1)], mid[i.saturating_sub(1)]);
            let nt = norm(t);
            let mut nrm = if nt > 0.0 { [-t[1] / nt, t[0] / nt] } else { [0.0, 0.0] };
            if dot(nrm, sub(c1[i], mid[i])) < 0.0 {
                nrm = scale(nrm, -1.0);
            }
            strip.t1.push(add(mid[i], scale(nrm, l / 2.0)));
            strip.t2.push(sub(mid[i], scale(nrm, l / 2.0)));
        }
        Some(strip)
    }

    /// Sides `k` and `k + 2` sampled at the same parameters, the second against its direction.
    fn facing(&self, k: usize) -> (Vec<P>, Vec<P>) {
        let a: Vec<P> = (0..=SAMPLES).map(|i| self.point(self.side_at(k, i as f64 / SAMPLES as f64))).collect();
        let b: Vec<P> =
            (0..=SAMPLES).map(|i| self.point(self.side_at(k + 2, 1.0 - i as f64 / SAMPLES as f64))).collect();
        (a, b)
    }

    /// The arc lengths where side `k` (mod 4) starts and ends, the end past the perimeter for
    /// the side that wraps round vertex 0.
    fn span(&self, k: usize) -> (f64, f64) {
        let s0 = self.corners[k % 4];
        let s1 = self.corners[(k + 1) % 4];
        (s0, if s1 <= s0 { s1 + self.cum[self.ring.len()] } else { s1 })
    }

    /// The arc length of the point at fraction `f` of side `k` (mod 4).
    fn side_at(&self, k: usize, f: f64) -> f64 {
        let (s0, s1) = self.span(k);
        s0 + f * (s1 - s0)
    }

    /// The ring point at arc length `s` (mod the perimeter).
    fn point(&self, s: f64) -> P {
        let n = self.ring.len();
        let s = s.rem_euclid(self.cum[n]);
        let i = self.cum.partition_point(|&c| c <= s).saturating_sub(1).min(n - 1);
        let l = self.cum[i + 1] - self.cum[i];
        let f = if l > 0.0 { (s - self.cum[i]) / l } else { 0.0 };
        add(self.ring[i], scale(sub(self.ring[(i + 1) % n], self.ring[i]), f))
    }

    /// The target of ring point `q` on edge `edge`.
    fn target(&self, edge: usize, q: P) -> Option<P> {
        let per = self.cum[self.ring.len()];
        let s = self.cum[edge] + dist(self.ring[edge], q);
        // The side holding `s` and the fraction along it.
        let (mut side, mut f) = (0, 0.0);
        for k in 0..4 {
            let (s0, s1) = self.span(k);
            let mut t = s;
            if t < s0 {
                t += per;
            }
            if t >= s0 && t <= s1 {
                side = k;
                f = if s1 > s0 { (t - s0) / (s1 - s0) } else { 0.0 };
                break;
            }
        }
        let rel = (side + 4 - self.first) % 4;
        if !(END_MARGIN..=1.0 - END_MARGIN).contains(&f) {
            return None;
        }
        match rel {
            0 => Some(sample(&self.t1, f)),
            2 => Some(sample(&self.t2, 1.0 - f)),
            _ => None,
        }
    }
}

/// The point at fraction `f` of a polyline given by equally spaced parameter samples.
fn sample(points: &[P], f: f64) -> P {
    let x = f.clamp(0.0, 1.0) * (points.len() - 1) as f64;
    let i = (x.floor() as usize).min(points.len() - 2);
    lerp(points[i], points[i + 1], x - i as f64)
}

/// One iteration's solve: minimises the energy over the free and sliding vertices, then puts the
/// sliding ones back on their segments.
fn solve(mesh: &mut Mesh, start: &[P], targets: &[Option<P>], opts: &OptimiseOptions) {
    let n = mesh.pos.len();
    let mut slot = vec![usize::MAX; n];
    let mut unknowns = Vec::new();
    for (v, kind) in mesh.kind.iter().enumerate() {
        if *kind != Kind::Fixed {
            slot[v] = unknowns.len();
            unknowns.push(v);
        }
    }
    let m = unknowns.len();
    let mut entries: Vec<(usize, usize, f64)> = Vec::new();
    let mut rhs = vec![[0.0f64; 2]; m];
    for (k, &v) in unknowns.iter().enumerate() {
        let mut d = opts.close;
        rhs[k] = scale(start[v], opts.close);
        if let Some(t) = targets[v] {
            d += opts.shape;
            rhs[k] = add(rhs[k], scale(t, opts.shape));
        }
        entries.push((k, k, d));
    }
    // Fairness: each second difference `c = v_{i−1} − 2v_i + v_{i+1}` adds `w_f · c cᵀ`.
    for ids in mesh.chains.iter().flatten() {
        for w in ids.windows(3) {
            let terms = [(w[0], 1.0), (w[1], -2.0), (w[2], 1.0)];
            for &(a, ca) in &terms {
                if slot[a] == usize::MAX {
                    continue;
                }
                for &(b, cb) in &terms {
                    let c = opts.fair * ca * cb;
                    if slot[b] == usize::MAX {
                        rhs[slot[a]] = sub(rhs[slot[a]], scale(mesh.pos[b], c));
                    } else {
                        entries.push((slot[a], slot[b], c));
                    }
                }
            }
        }
    }
    let a = Csr::from_triplets(m, &entries);
    let (x, y) = rayon::join(
        || a.solve(&rhs.iter().map(|r| r[0]).collect::<Vec<_>>()),
        || a.solve(&rhs.iter().map(|r| r[1]).collect::<Vec<_>>()),
    );
    for (k, &v) in unknowns.iter().enumerate() {
        let p = [x[k], y[k]];
        mesh.pos[v] = match mesh.kind[v] {
            Kind::Slide(a, b) => closest_on_segment(p, a, b).0,
            _ => p,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::region::region_from_toml;
    use std::path::Path;

    fn square() -> Region {
        let text = r#"
outer = [[0, 0], [200, 0], [200, 120], [0, 120]]
"#;
        region_from_toml(text, Path::new("t.toml"), "t").expect("a region")
    }

    /// A wiggly street across a rectangle comes out straighter (fairness), still ending on the
    /// boundary, and its ends slide only along the boundary.
    #[test]
    fn fairs_a_wiggly_street_and_keeps_its_ends_on_the_boundary() {
        let region = square();
        let wiggle: Vec<P> = (0..=40).map(|i| [5.0 * i as f64, 60.0 + 3.0 * ((i as f64) * 1.3).sin()]).collect();
        let streets = vec![Street::new(wiggle.clone(), 12.0, 1)];
        let out = optimise(&region, &streets, &OptimiseOptions::for_region(&region));
        let bend = |l: &[P]| l.windows(3).map(|w| norm(add(sub(w[0], w[1]), sub(w[2], w[1])))).sum::<f64>();
        let before = bend(&resample(&wiggle, 4.5));
        let after = bend(&out[0].polyline);
        assert!(after < 0.5 * before, "bending {before} → {after}");
        let (a, b) = (out[0].polyline[0], *out[0].polyline.last().expect("points"));
        assert!(a[0].abs() < 1e-9 && (b[0] - 200.0).abs() < 1e-9, "ends {a:?} {b:?}");
    }

    /// A street ending on an earlier one shares its vertex, so the junction stays closed.
    #[test]
    fn a_junction_stays_closed() {
        let region = square();
        let main: Vec<P> = (0..=20).map(|i| [10.0 * i as f64, 60.0 + 2.0 * (i as f64).sin()]).collect();
        let at = main[8];
        let branch: Vec<P> = vec![at, [at[0] + 3.0, 90.0], [at[0], 120.0]];
        let streets = vec![Street::new(main, 12.0, 1), Street::new(branch, 10.0, 2)];
        let out = optimise(&region, &streets, &OptimiseOptions::for_region(&region));
        let end = out[1].polyline[0];
        assert!(out[0].polyline.contains(&end), "junction {end:?} not on the main street");
        assert!((out[1].polyline.last().expect("points")[1] - 120.0).abs() < 1e-9);
    }

    /// A block that is already a rectangular strip is its own target: nothing moves.
    #[test]
    fn a_rectangle_is_its_own_strip() {
        let block = geo::Polygon::new(
            geo::LineString::from(vec![(0.0, 0.0), (100.0, 0.0), (100.0, 40.0), (0.0, 40.0), (0.0, 0.0)]),
            vec![],
        );
        let s = Strip::fit(&block).expect("a strip");
        for (edge, q) in [(0, [30.0, 0.0]), (2, [70.0, 40.0])] {
            let t = s.target(edge, q).expect("a target");
            assert!(dist(t, q) < 1e-9, "{q:?} → {t:?}");
        }
        // The short sides and the ends of the long ones get none.
        assert_eq!(s.target(1, [100.0, 10.0]), None);
        assert_eq!(s.target(0, [5.0, 0.0]), None);
    }

    /// A trapezoid's long sides are pulled towards parallel offset curves.
    #[test]
    fn a_trapezoid_is_pulled_towards_parallel_sides() {
        let block = geo::Polygon::new(
            geo::LineString::from(vec![(0.0, 0.0), (100.0, 0.0), (100.0, 50.0), (0.0, 30.0), (0.0, 0.0)]),
            vec![],
        );
        let s = Strip::fit(&block).expect("a strip");
        let t: Vec<P> = [(0, [20.0, 0.0]), (2, [20.0, 34.0]), (0, [80.0, 0.0]), (2, [80.0, 46.0])]
            .iter()
            .map(|&(edge, q)| s.target(edge, q).expect("a target"))
            .collect();
        let (l, r) = (dist(t[0], t[1]), dist(t[2], t[3]));
        assert!((l - r).abs() < 1.0, "strip widths {l} and {r}");
    }
}
