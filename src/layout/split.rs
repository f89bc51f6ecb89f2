//! Streamline-based splitting (Yang et al. 2013 §5): a part's cross field, its streamline
//! candidates, their scores and the cut along the chosen one; the region's first cut along its
//! major roads; the fit test a part no template matches is settled by. The control loop that
//! calls them is [`super::tree`].
//!
//! **Scores** (§5, "Quality Score"): four costs per candidate, each min–max normalised over the
//! candidates to `ĉ ∈ [0, 1]`, combined as `qual = Σ λ_k (1 − ĉ_k)` with the region's weights
//! (`[weights]`, the paper's all 1):
//! * divergence: `∫|∇·f| ds / length^p` with `p = 1.1` (a cost; the paper's `p = 0.9` on the
//!   signed integral would favour short streamlines for a cost, so `p > 1` keeps its intent);
//! * distance to the boundary: along the streamline, the distances to the boundary on both sides
//!   along its normal, each compared with the nearest sum of block widths (a double-loaded block,
//!   `[block] width`, by default `2·depth + street`; where the boundary is not a street, also a
//!   single row, half that), the misfit over the narrowest width,
//!   capped at 1, averaged;
//! * distance to singularities: the smallest distance from the streamline to a singularity
//!   (near is good: cutting there removes singularities from the parts);
//! * continuity: 0 when both ends continue an earlier street end (within 4 m and 20° across the
//!   street), 0.5 for one, 1 for none.
//!
//! In comparison mode the best candidate is cut; in variation mode one is drawn with probability
//! proportional to its quality, from the seeded generator.

use super::field::{CrossField, FieldError, FieldMethod, FieldOptions};
use super::region::Region;
use super::streamline::{candidates, BoundaryHit, BoundaryIndex, Candidate, TraceOptions};
use super::Street;
use crate::geometry::{dist, dot, norm, scale, segment_intersection, sub, Polygon, P};
use geo::MinimumRotatedRect;
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;
use serde::{Deserialize, Serialize};

/// How a streamline is chosen among the candidates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Selection {
    /// The highest quality (the paper's comparison mode).
    Best,
    /// Drawn with probability proportional to quality (variation mode).
    Random,
}

impl std::str::FromStr for Selection {
    type Err = String;
    /// `best` or `random` (any case).
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "best" => Ok(Selection::Best),
            "random" => Ok(Selection::Random),
            _ => Err(format!("unknown streamline choice `{s}` (known: best, random)")),
        }
    }
}

/// What the control loop is run with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitOptions {
    /// The field construction.
    pub field: FieldMethod,
    /// The field's smallest triangle size (metres); a large part gets about 40 triangles across.
    pub h: f64,
    /// The streamline tracing.
    pub trace: TraceOptions,
    /// How the cut is chosen.
    pub selection: Selection,
    /// Parts longer than this (their minimum rotated rectangle's long side, metres) are split
    /// even when narrow enough for a block.
    pub max_block_length: f64,
    /// Centreline to centreline across a double-loaded block (metres).
    pub block_width: f64,
    /// A part is narrow enough for a block up to this many block widths (inscribed width).
    pub max_width: f64,
    /// Parts smaller than this many parcels are not cut.
    pub min_parcels: f64,
    /// The weights λ of the four scores (divergence, boundary, singularities, continuity).
    pub weights: [f64; 4],
    /// Whether a part round a hole that no streamline crosses is cut by two to the hole.
    pub round_holes: bool,
}

impl SplitOptions {
    /// The paper's settings for a region: `dε = 0.3 × depth`, triangles of about a third of the
    /// parcel depth, a step of a quarter of `dε`; the block size, fit thresholds and score
    /// weights from the region.
    pub fn for_region(region: &Region, field: FieldMethod, selection: Selection) -> SplitOptions {
        let d = region.parcel.depth;
        let [lo, hi] = region.polygon.bounds();
        let diameter = dist(lo, hi);
        SplitOptions {
            field,
            h: d / 3.0,
            trace: TraceOptions {
                separation: 0.3 * d,
                step: 0.075 * d,
                min_magnitude: 1e-4,
                max_length: 3.0 * diameter,
            },
            selection,
            max_block_length: region.block.max_length,
            block_width: region.block.width,
            max_width: region.fit.max_width,
            min_parcels: region.fit.min_parcels,
            weights: region.weights.as_array(),
            round_holes: region.fit.round_holes,
        }
    }
}

/// The result of the control loop without templates.
#[derive(Clone, Debug)]
pub struct Split {
    /// The parts left when nothing more is cut, in the order they were settled.
    pub parts: Vec<Polygon>,
    /// The streets: major roads (level 0) and every cut streamline (level = its depth + 1).
    pub streets: Vec<Street>,
    /// Candidates traced over the whole loop.
    pub candidates: usize,
    /// Cuts made along streamlines.
    pub cuts: usize,
}

/// Why the loop failed.
#[derive(Debug, thiserror::Error)]
pub enum SplitError {
    /// A field could not be built.
    #[error(transparent)]
    Field(#[from] FieldError),
}

/// One candidate's scores, each `1 − ĉ` (1 best), and their weighted sum (its quality).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CandidateScore {
    /// Divergence.
    pub divergence: f64,
    /// Fit of the distances to the boundary.
    pub boundary: f64,
    /// Nearness to a singularity.
    pub singularities: f64,
    /// Continuity with earlier street ends.
    pub continuity: f64,
    /// `Σ λ_k (1 − ĉ_k)`.
    pub quality: f64,
}

/// A part's cut: the chosen streamlines (simplified), its quality, the two parts, and every
/// candidate that cut the part with its scores (the chosen one at `chosen`).
#[derive(Clone, Debug)]
pub struct Cut {
    /// The streamlines, the new streets' centrelines: one across the part, or two from its outer
    /// ring to a hole (§5: a split may follow several streamlines).
    pub lines: Vec<Vec<P>>,
    /// Its quality.
    pub quality: f64,
    /// The part on its left, then the one on its right.
    pub parts: (Polygon, Polygon),
    /// The scores of every candidate that cut the part.
    pub scores: Vec<CandidateScore>,
    /// The chosen candidate's index in `scores`.
    pub chosen: usize,
    /// The candidates that cut the part, with their qualities and parts.
    pub scored: Vec<Scored>,
}

/// The cut of a part along its chosen streamline (the chosen field first; where none of its
/// streamlines cuts the part — a disc's distance field is all circles and radii — the other
/// construction), with the number of candidates traced; `None` when no candidate cuts it.
pub fn cut_part(
    poly: &Polygon,
    region: &Region,
    opts: &SplitOptions,
    ends: &[(P, P)],
    rng: &mut Xoshiro256PlusPlus,
) -> Result<(Option<Cut>, usize), SplitError> {
    // Triangles scale with the part (about 40 across), never finer than `opts.h`.
    let h = opts.h.max(poly.area().sqrt() / 40.0);
    let mut scored = Vec::new();
    let mut scores = Vec::new();
    let mut traced = 0;
    let mut fields = Vec::new();
    for method in [opts.field, other(opts.field)] {
        let field = CrossField::new(poly, &FieldOptions { method, h })?;
        let cands = candidates(&field, poly, &opts.trace, rng);
        traced += cands.len();
        (scored, scores) = score(&field, poly, region, opts, &cands, ends, Through::Across);
        if !scored.is_empty() {
            break;
        }
        fields.push((field, cands));
    }
    // No streamline crosses a part round a hole: two to the hole cut it, when the region asks.
    if scored.is_empty() && opts.round_holes && !poly.holes().is_empty() {
        for (field, cands) in &fields {
            (scored, scores) = score(field, poly, region, opts, cands, ends, Through::Hole);
            if !scored.is_empty() {
                break;
            }
        }
    }
    let Some(i) = choose(&scored, opts.selection, rng) else { return Ok((None, traced)) };
    let (cs, quality, parts) = (&scored[i].0, scored[i].1, scored[i].2.clone());
    let lines = cs.iter().map(|c| simplify(&c.points, 0.05)).collect();
    Ok((Some(Cut { lines, quality, parts, scores, chosen: i, scored }), traced))
}

fn other(m: FieldMethod) -> FieldMethod {
    match m {
        FieldMethod::Smooth => FieldMethod::Distance,
        FieldMethod::Distance => FieldMethod::Smooth,
    }
}

/// The region's first parts: the region less its zones, cut along its major roads (each split at
/// its crossings with earlier ones; the pieces inside zones left out), then the zones, each with
/// its use as its label. Returns the parts in the order they are worked on, and the level-0
/// streets: the boundary street first when the boundary is one, the streets along zones, the
/// major roads.
pub fn initial_parts(region: &Region) -> (Vec<(Polygon, String)>, Vec<Street>) {
    let w = region.street_width(0);
    let mut streets = Vec::new();
    if region.boundary == super::region::Boundary::Street {
        for ring in region.polygon.rings().take(1) {
            let mut closed = ring.to_vec();
            closed.push(ring[0]);
            streets.push(Street::new(closed, w, 0));
        }
    }
    streets.extend(super::zone::streets(&region.polygon, &region.zones, w));
    let mut parts = super::zone::carve(&region.polygon, &region.zones);
    let mut placed: Vec<Vec<P>> = Vec::new();
    for road in super::zone::clip_roads(&region.roads, &region.zones) {
        for piece in split_at_crossings(&road, &placed) {
            if let Some(k) = parts.iter().position(|p| p.contains(midpoint(&piece))) {
                if let Some((a, b)) = parts[k].cut(&piece, 1e-4) {
                    parts.splice(k..=k, [a, b]);
                }
            }
        }
        streets.push(Street::new(road.clone(), w, 0));
        placed.push(road);
    }
    let block = super::BLOCK.to_string();
    let mut out: Vec<(Polygon, String)> = parts.into_iter().map(|p| (p, block.clone())).collect();
    out.extend(region.zones.iter().map(|z| (z.polygon(), z.use_.label().to_string())));
    (out, streets)
}

fn midpoint(line: &[P]) -> P {
    crate::geometry::point_at_length(line, crate::geometry::polyline_length(line) / 2.0)
}

/// A road cut into pieces at its crossings with other roads.
fn split_at_crossings(road: &[P], others: &[Vec<P>]) -> Vec<Vec<P>> {
    let mut pieces = vec![vec![road[0]]];
    for w in road.windows(2) {
        let mut hits: Vec<f64> = others
            .iter()
            .flat_map(|o| o.windows(2).filter_map(|v| segment_intersection(w[0], w[1], v[0], v[1]).map(|h| h.0)))
            .filter(|&s| s > 1e-9 && s < 1.0 - 1e-9)
            .collect();
        hits.sort_by(f64::total_cmp);
        for s in hits {
            let p = [w[0][0] + s * (w[1][0] - w[0][0]), w[0][1] + s * (w[1][1] - w[0][1])];
            if let Some(last) = pieces.last_mut() {
                last.push(p);
            }
            pieces.push(vec![p]);
        }
        if let Some(last) = pieces.last_mut() {
            last.push(w[1]);
        }
    }
    pieces.retain(|p| p.len() >= 2 && crate::geometry::polyline_length(p) > 0.0);
    pieces
}

/// Whether a part is a block by the fit test: narrow enough for two rows of parcels back to back
/// (its inscribed width at most `max_width` block widths, so that a cut would leave parts narrower
/// than a block) and not longer than the longest block, or smaller than `min_parcels` parcels.
pub fn fits_block(poly: &Polygon, region: &Region, opts: &SplitOptions) -> bool {
    let parcel = region.parcel.depth * region.parcel.width;
    if poly.area() < opts.min_parcels * parcel {
        return true;
    }
    let long = poly.to_geo().minimum_rotated_rect().map_or(f64::INFINITY, |r| {
        let c = &r.exterior().0;
        let (a, b) = (dist([c[0].x, c[0].y], [c[1].x, c[1].y]), dist([c[1].x, c[1].y], [c[2].x, c[2].y]));
        a.max(b)
    });
    inscribed_width(poly, region.parcel.depth / 3.0) <= opts.max_width * opts.block_width
        && long <= opts.max_block_length
}

/// Twice the largest distance from an inside point to the boundary, sampled on a grid of `step`
/// (at most 200 × 200 points).
pub fn inscribed_width(poly: &Polygon, step: f64) -> f64 {
    let [lo, hi] = poly.bounds();
    let step = step.max((hi[0] - lo[0]).max(hi[1] - lo[1]) / 200.0);
    let mut best: f64 = 0.0;
    let mut y = lo[1] + step / 2.0;
    while y < hi[1] {
        let mut x = lo[0] + step / 2.0;
        while x < hi[0] {
            if poly.contains([x, y]) {
                best = best.max(poly.boundary_distance([x, y]));
            }
            x += step;
        }
        y += step;
    }
    2.0 * best
}

/// A street's ends with their outward directions.
pub fn street_ends(line: &[P]) -> Vec<(P, P)> {
    if line.len() < 2 || line.first() == line.last() {
        return Vec::new();
    }
    let n = line.len();
    let unit = |d: P| scale(d, 1.0 / norm(d).max(1e-300));
    vec![(line[0], unit(sub(line[0], line[1]))), (line[n - 1], unit(sub(line[n - 1], line[n - 2])))]
}

/// Douglas–Peucker simplification of an open polyline (ends kept).
pub fn simplify(line: &[P], tol: f64) -> Vec<P> {
    use geo::Simplify;
    let ls = geo::LineString::from(line.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>());
    ls.simplify(tol).0.iter().map(|c| [c.x, c.y]).collect()
}

/// A candidate cut — one streamline, or two to the same hole, each from the outer ring — its
/// quality, and the two parts.
pub type Scored = (Vec<Candidate>, f64, Parts);

/// The two parts of a cut.
pub type Parts = (Polygon, Polygon);

/// Which cuts [`score`] considers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Through {
    /// Single streamlines from the outer ring to the outer ring.
    Across,
    /// Pairs of streamlines from the outer ring to the same hole.
    Hole,
}

/// Scores the candidate cuts that leave two pieces at least a parcel deep — single streamlines
/// across the part, or pairs of streamlines from the outer ring to one hole (a pair's costs are
/// the means of its two streamlines') — returning the scored cuts and their scores, in the same
/// order.
fn score(
    field: &CrossField,
    poly: &Polygon,
    region: &Region,
    opts: &SplitOptions,
    cands: &[Candidate],
    ends: &[(P, P)],
    through: Through,
) -> (Vec<Scored>, Vec<CandidateScore>) {
    let depth = region.parcel.depth;
    let min_area = depth * region.parcel.width;
    // Between two streets a block is double-loaded; a single row backs onto a boundary without
    // a street.
    let mut widths = vec![opts.block_width];
    if region.boundary == super::region::Boundary::None {
        widths.push(opts.block_width / 2.0);
    }
    let boundary = BoundaryIndex::new(poly);
    let [lo, hi] = poly.bounds();
    let reach = 2.0 * dist(lo, hi);
    let costs = |c: &Candidate| -> Option<[f64; 4]> {
        let (db, median_gap) = boundary_fit(c, &boundary, &widths, reach);
        // Each side must hold at least a row of parcels and half a street.
        if median_gap < 0.9 * (depth + region.street_width(1) / 2.0) {
            return None;
        }
        let div = c.divergence / c.length.max(1e-9).powf(1.1);
        let ds = field.singularities().iter().map(|s| polyline_distance(s.at, &c.points)).fold(f64::INFINITY, f64::min);
        let ds = if ds.is_finite() { ds } else { 0.0 };
        let ct = 1.0 - 0.5 * c.ends.iter().filter(|e| continues(e.at, e.direction, ends)).count() as f64;
        Some([div, db, ds, ct])
    };
    let big_enough = |parts: &(Polygon, Polygon)| parts.0.area() >= min_area && parts.1.area() >= min_area;
    let mut rows: Vec<([f64; 4], Vec<Candidate>, Parts)> = Vec::new();
    match through {
        Through::Across => {
            for c in cands.iter().filter(|c| c.ends[0].ring == 0 && c.ends[1].ring == 0) {
                let Some(parts) = poly.cut(&c.points, 1e-6).filter(big_enough) else { continue };
                let Some(k) = costs(c) else { continue };
                rows.push((k, vec![c.clone()], parts));
            }
        }
        Through::Hole => {
            let to_holes: Vec<(Candidate, [f64; 4])> =
                cands.iter().filter_map(outer_to_hole).filter_map(|c| costs(&c).map(|k| (c, k))).collect();
            for (i, (a, ka)) in to_holes.iter().enumerate() {
                for (b, kb) in &to_holes[i + 1..] {
                    let hole = a.ends[1].ring;
                    if b.ends[1].ring != hole || dist(a.ends[1].at, b.ends[1].at) < depth {
                        continue;
                    }
                    let cut = poly.cut_round_hole(hole - 1, &a.points, &b.points, 1e-6);
                    let Some(parts) = cut.filter(big_enough) else { continue };
                    let k: [f64; 4] = std::array::from_fn(|m| (ka[m] + kb[m]) / 2.0);
                    rows.push((k, vec![a.clone(), b.clone()], parts));
                }
            }
        }
    }
    let mut lo_hi = [[f64::INFINITY, f64::NEG_INFINITY]; 4];
    for (costs, ..) in &rows {
        for k in 0..4 {
            lo_hi[k] = [lo_hi[k][0].min(costs[k]), lo_hi[k][1].max(costs[k])];
        }
    }
    rows.into_iter()
        .map(|(costs, cs, parts)| {
            let g: Vec<f64> = (0..4)
                .map(|k| {
                    let span = lo_hi[k][1] - lo_hi[k][0];
                    1.0 - if span > 0.0 { (costs[k] - lo_hi[k][0]) / span } else { 0.0 }
                })
                .collect();
            let q: f64 = (0..4).map(|k| opts.weights[k] * g[k]).sum();
            let s =
                CandidateScore { divergence: g[0], boundary: g[1], singularities: g[2], continuity: g[3], quality: q };
            ((cs, q, parts), s)
        })
        .unzip()
}

/// A candidate from the outer ring to a hole, turned to run from the outer ring; `None` for any
/// other.
fn outer_to_hole(c: &Candidate) -> Option<Candidate> {
    match (c.ends[0].ring, c.ends[1].ring) {
        (0, h) if h > 0 => Some(c.clone()),
        (h, 0) if h > 0 => {
            let mut r = c.clone();
            r.points.reverse();
            let [x, y] = c.ends;
            let back = |e: BoundaryHit| BoundaryHit { direction: scale(e.direction, -1.0), ..e };
            r.ends = [back(y), back(x)];
            Some(r)
        }
        _ => None,
    }
}

/// The mean misfit of the distances to the boundary on both sides with sums of block widths,
/// and the median over the streamline of the nearer side's distance.
fn boundary_fit(c: &Candidate, boundary: &BoundaryIndex, widths: &[f64], reach: f64) -> (f64, f64) {
    let wmin = widths.iter().copied().fold(f64::INFINITY, f64::min);
    let w0 = widths[0];
    let w1 = widths.get(1).copied().unwrap_or(w0);
    let opt = |y: f64| {
        // The nearest positive n·W₀ + m·W₁ to y.
        let mut best = f64::INFINITY;
        let mut a = 0.0;
        while a <= y + w0 {
            let rest = y - a;
            let m = (rest / w1).round().max(if a == 0.0 { 1.0 } else { 0.0 });
            best = best.min((rest - m * w1).abs());
            a += w0;
        }
        (best / wmin).min(1.0)
    };
    let (mut sum, mut n, mut gaps) = (0.0, 0, Vec::new());
    let spacing = (c.length / 20.0).max(1.0);
    let mut run = 0.0;
    for w in c.points.windows(2) {
        let l = dist(w[0], w[1]);
        run += l;
        if run < spacing || l <= 0.0 {
            continue;
        }
        run = 0.0;
        let t = scale(sub(w[1], w[0]), 1.0 / l);
        let nrm = [-t[1], t[0]];
        let mut gap = reach;
        for side in [nrm, scale(nrm, -1.0)] {
            let from = [w[0][0] + side[0] * 1e-6, w[0][1] + side[1] * 1e-6];
            let d = boundary.ray(from, side, reach);
            sum += d.map_or(1.0, opt);
            n += 1;
            gap = gap.min(d.unwrap_or(reach));
        }
        gaps.push(gap);
    }
    if n == 0 {
        return (1.0, 0.0);
    }
    gaps.sort_by(f64::total_cmp);
    (sum / n as f64, gaps[gaps.len() / 2])
}

fn polyline_distance(p: P, line: &[P]) -> f64 {
    line.windows(2).map(|w| dist(p, crate::geometry::closest_on_segment(p, w[0], w[1]).0)).fold(f64::INFINITY, f64::min)
}

/// Whether an end at `at`, travelling `dir`, continues an earlier street end across a street:
/// within 4 m of it and within 20° of its line.
fn continues(at: P, dir: P, ends: &[(P, P)]) -> bool {
    let cos20 = 20f64.to_radians().cos();
    ends.iter().any(|&(q, d)| dist(at, q) <= 4.0 + 1e-9 && dot(dir, d).abs() >= cos20)
}

/// The index of the chosen candidate.
fn choose(scored: &[Scored], selection: Selection, rng: &mut Xoshiro256PlusPlus) -> Option<usize> {
    if scored.is_empty() {
        return None;
    }
    match selection {
        Selection::Best => (0..scored.len()).max_by(|&a, &b| scored[a].1.total_cmp(&scored[b].1).then(b.cmp(&a))),
        Selection::Random => {
            let total: f64 = scored.iter().map(|s| s.1.max(0.0)).sum();
            let mut r = rng.random::<f64>() * total;
            for (i, s) in scored.iter().enumerate() {
                r -= s.1.max(0.0);
                if r <= 0.0 {
                    return Some(i);
                }
            }
            Some(scored.len() - 1)
        }
    }
}
