//! The street and block measures of Yang et al. ("Urban pattern: layout design by hierarchical
//! domain splitting", 2013, §7), under their own names and definitions, as `netspec city`
//! ([`street_metrics`], which Peng et al. report for their urban layouts) and `netspec layout`
//! ([`StreetNodes`], [`street_length`]) report them.
//!
//! [`street_metrics`], on a street graph (model lengths are converted with `metres_per_unit`):
//! - **street length** `sl`: total edge length in km, per km² of the city domain;
//! - **intersections** `si`: vertices of valence ≥ 3, per km² (`si3`, `si4`: valence exactly
//!   3 and 4; valence ≥ 5 is only counted). Vertices of valence 2 are bends, not intersections.
//!   Whether the domain boundary belongs to the graph is up to the caller: if it does, a street
//!   ending at the boundary forms a 3-way intersection with the boundary road;
//! - **dead ends** `sd`: vertices of valence 1, per km²;
//! - **blocks** `bn`: bounded faces of the street graph, per km²; a block's boundary length is
//!   [`Face::perimeter`](crate::geometry::planar::Face::perimeter): the edges with the block on exactly one
//!   side, holes included, cul-de-sacs poking into the block excluded. `bmin`, `bavg`, `bmax`
//!   are the minimum, mean and maximum in metres.
//!
//! Vertices of valence 0 are ignored. Densities are 0 when the domain area is not positive.

use crate::geometry::planar::PlanarGraph;
use crate::geometry::{closest_on_segment, dist, polyline_length, Polygon, P};
use serde::{Deserialize, Serialize};

/// Street and block metrics of a street graph (see the module docs for the definitions).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StreetMetrics {
    /// Metres per model unit.
    pub metres_per_unit: f64,
    /// Area of the city domain in km².
    pub area_km2: f64,
    /// Total street length in km.
    pub street_length_km: f64,
    /// Street length density: km of street per km².
    pub sl: f64,
    /// Number of 3-way intersections (valence 3).
    pub intersections_3: usize,
    /// Number of 4-way intersections (valence 4).
    pub intersections_4: usize,
    /// Number of intersections of valence 5 or more.
    pub intersections_5plus: usize,
    /// Intersections (valence ≥ 3) per km².
    pub si: f64,
    /// 3-way intersections per km².
    pub si3: f64,
    /// 4-way intersections per km².
    pub si4: f64,
    /// Number of dead ends (valence-1 vertices).
    pub dead_ends: usize,
    /// Dead ends per km².
    pub sd: f64,
    /// Number of blocks (bounded faces).
    pub blocks: usize,
    /// Blocks per km².
    pub bn: f64,
    /// Smallest block boundary length in metres (`None` without blocks).
    pub bmin: Option<f64>,
    /// Mean block boundary length in metres (`None` without blocks).
    pub bavg: Option<f64>,
    /// Largest block boundary length in metres (`None` without blocks).
    pub bmax: Option<f64>,
}

/// Computes the [`StreetMetrics`] of the street graph `g` (model units, converted with
/// `metres_per_unit`) over a city domain of `area_units` model units². Blocks are the bounded
/// faces of [`PlanarGraph::faces`], so `g` should be planar (e.g. built by
/// [`PlanarGraph::from_segments`] or as a union of planar region graphs). Vertices at exactly
/// the same position are merged, and duplicate edges and self-loops dropped, first.
pub fn street_metrics(g: &PlanarGraph, metres_per_unit: f64, area_units: f64) -> StreetMetrics {
    // Merge exactly coincident vertices and drop duplicate edges and self-loops first.
    let g = &PlanarGraph::from_vertices_edges(&g.positions, &g.edges, 0.0);
    let km = metres_per_unit / 1000.0;
    let area_km2 = area_units * km * km;
    let per_km2 = |x: f64| if area_km2 > 0.0 { x / area_km2 } else { 0.0 };
    let street_length_km = (0..g.edges.len()).map(|e| g.edge_length(e)).sum::<f64>() * km;
    let valences = g.valences();
    let count = |f: &dyn Fn(usize) -> bool| valences.iter().filter(|&&d| f(d)).count();
    let (i3, i4, i5) = (count(&|d| d == 3), count(&|d| d == 4), count(&|d| d >= 5));
    let dead_ends = count(&|d| d == 1);
    let perimeters: Vec<f64> = g.faces().faces.iter().map(|f| f.perimeter * metres_per_unit).collect();
    let blocks = perimeters.len();
    let (bmin, bavg, bmax) = if blocks == 0 {
        (None, None, None)
    } else {
        (
            perimeters.iter().copied().reduce(f64::min),
            Some(perimeters.iter().sum::<f64>() / blocks as f64),
            perimeters.iter().copied().reduce(f64::max),
        )
    };
    StreetMetrics {
        metres_per_unit,
        area_km2,
        street_length_km,
        sl: per_km2(street_length_km),
        intersections_3: i3,
        intersections_4: i4,
        intersections_5plus: i5,
        si: per_km2((i3 + i4 + i5) as f64),
        si3: per_km2(i3 as f64),
        si4: per_km2(i4 as f64),
        dead_ends,
        sd: per_km2(dead_ends as f64),
        blocks,
        bn: per_km2(blocks as f64),
        bmin,
        bavg,
        bmax,
    }
}

impl StreetMetrics {
    /// The totals: `totals over 0.320 km²: streets 3.20 km, 12 intersections (3-way 8, 4-way 4),
    /// 0 dead-ends, 6 blocks`.
    pub fn totals_line(&self) -> String {
        format!(
            "totals over {:.3} km²: streets {:.2} km, {} intersections (3-way {}, 4-way {}), {} dead-ends, {} blocks",
            self.area_km2,
            self.street_length_km,
            self.intersections_3 + self.intersections_4 + self.intersections_5plus,
            self.intersections_3,
            self.intersections_4,
            self.dead_ends,
            self.blocks,
        )
    }

    /// The densities: `per km²: streets 10.0 km, 37.5 intersections (3-way 25.0, 4-way 12.5),
    /// 0.0 dead-ends, 18.8 blocks`.
    pub fn density_line(&self) -> String {
        format!(
            "per km²: streets {:.1} km, {:.1} intersections (3-way {:.1}, 4-way {:.1}), {:.1} dead-ends, {:.1} blocks",
            self.sl, self.si, self.si3, self.si4, self.sd, self.bn
        )
    }

    /// Both, in one line: which numbers are totals and which are per km².
    pub fn summary(&self) -> String {
        format!("{}; {}", self.totals_line(), self.density_line())
    }
}

/// Street ends closer than this meet, and points this close to the region's boundary are on it
/// (metres), for the layout measures.
pub const NODE_TOLERANCE: f64 = 0.5;

/// A layout's street nodes, counted at street ends: an end meets every other end within
/// [`NODE_TOLERANCE`] (one arm each) and every street passing through it (two arms); an
/// intersection has three or more arms, a dead end one arm and lies off the region's boundary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StreetNodes {
    /// Points where three or more street arms meet.
    pub intersections: usize,
    /// Street ends that meet nothing, off the region's boundary.
    pub dead_ends: usize,
}

/// The [`StreetNodes`] of a layout's street centrelines (metres) in `region`.
pub fn street_nodes(region: &Polygon, streets: &[&[P]]) -> StreetNodes {
    let ends: Vec<(usize, P)> = streets
        .iter()
        .enumerate()
        .filter(|(_, s)| s.len() >= 2 && s.first() != s.last())
        .flat_map(|(i, s)| [(i, s[0]), (i, s[s.len() - 1])])
        .collect();
    let segments: Vec<(usize, P, P)> =
        streets.iter().enumerate().flat_map(|(i, s)| s.windows(2).map(move |w| (i, w[0], w[1]))).collect();
    let index = crate::geometry::index::SegmentIndex::new(segments.iter().map(|s| (s.1, s.2)).collect(), 50.0);
    let mut seen: Vec<P> = Vec::new();
    let mut out = StreetNodes { intersections: 0, dead_ends: 0 };
    for &(_, p) in &ends {
        if seen.iter().any(|&q| dist(p, q) <= NODE_TOLERANCE) {
            continue;
        }
        seen.push(p);
        let end_arms = ends.iter().filter(|(_, q)| dist(p, *q) <= NODE_TOLERANCE).count();
        let mut through: Vec<usize> = index
            .near(p, NODE_TOLERANCE)
            .into_iter()
            .filter(|&k| {
                let (i, a, b) = segments[k];
                let s = streets[i];
                let is_end = dist(p, s[0]) <= NODE_TOLERANCE || dist(p, s[s.len() - 1]) <= NODE_TOLERANCE;
                let closed = s.first() == s.last();
                (closed || !is_end) && dist(p, closest_on_segment(p, a, b).0) <= NODE_TOLERANCE
            })
            .map(|k| segments[k].0)
            .collect();
        through.sort_unstable();
        through.dedup();
        let arms = end_arms + 2 * through.len();
        if arms >= 3 {
            out.intersections += 1;
        } else if arms == 1 && region.boundary_distance(p) > NODE_TOLERANCE {
            out.dead_ends += 1;
        }
    }
    out
}

/// Intersections (valence ≥ 3) and dead ends (valence 1, not `exempt` — a street leaving the
/// region there) of a graph given by its vertices' valences.
pub fn valence_nodes(valences: &[usize], exempt: &[bool]) -> StreetNodes {
    StreetNodes {
        intersections: valences.iter().filter(|&&d| d >= 3).count(),
        dead_ends: valences.iter().zip(exempt).filter(|(&d, &x)| d == 1 && !x).count(),
    }
}

/// The street length Yang et al. count: a street along the region's boundary (every vertex and
/// edge midpoint on it) counts with half its length, since it serves the region from one side.
pub fn street_length(region: &Polygon, streets: &[&[P]]) -> f64 {
    let on_boundary = |s: &[P]| {
        let mids = s.windows(2).map(|w| [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0]);
        s.iter().copied().chain(mids).all(|p| region.boundary_distance(p) <= NODE_TOLERANCE)
    };
    streets.iter().map(|s| polyline_length(s) * if on_boundary(s) { 0.5 } else { 1.0 }).sum()
}

/// The perimeter of a block given by its rings (outer and holes, each closed or not).
pub fn block_perimeter(rings: &[&[P]]) -> f64 {
    rings
        .iter()
        .map(|r| polyline_length(r) + if r.first() == r.last() { 0.0 } else { dist(r[r.len() - 1], r[0]) })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_with(roads: &[[[f64; 2]; 2]]) -> PlanarGraph {
        let sq = [[0.0, 0.0], [200.0, 0.0], [200.0, 200.0], [0.0, 200.0]];
        let mut segs: Vec<[[f64; 2]; 2]> = (0..4).map(|k| [sq[k], sq[(k + 1) % 4]]).collect();
        segs.extend_from_slice(roads);
        PlanarGraph::from_segments(&segs, 1e-9)
    }

    /// A 2 × 2 km square (200 units of 10 m) with a plus of roads through its centre.
    #[test]
    fn plus_in_a_square() {
        let g = square_with(&[[[100.0, 0.0], [100.0, 200.0]], [[0.0, 100.0], [200.0, 100.0]]]);
        let m = street_metrics(&g, 10.0, 200.0 * 200.0);
        let want = StreetMetrics {
            metres_per_unit: 10.0,
            area_km2: 4.0,
            street_length_km: 12.0, // 8 km boundary + 4 km plus
            sl: 3.0,
            intersections_3: 4, // where the plus meets the boundary
            intersections_4: 1, // the centre
            intersections_5plus: 0,
            si: 1.25,
            si3: 1.0,
            si4: 0.25,
            dead_ends: 0,
            sd: 0.0,
            blocks: 4,
            bn: 1.0,
            bmin: Some(4000.0),
            bavg: Some(4000.0),
            bmax: Some(4000.0),
        };
        assert_eq!(m, want);
        assert_eq!(
            m.summary(),
            "totals over 4.000 km²: streets 12.00 km, 5 intersections (3-way 4, 4-way 1), 0 dead-ends, 4 blocks; \
             per km²: streets 3.0 km, 1.2 intersections (3-way 1.0, 4-way 0.2), 0.0 dead-ends, 1.0 blocks"
        );
        // Serde round trip.
        let back: StreetMetrics = serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
        assert_eq!(back, m);
    }

    /// A cul-de-sac from the bottom midpoint to the centre, and a 5-way star elsewhere.
    #[test]
    fn dead_ends_and_stars() {
        let g = square_with(&[[[100.0, 0.0], [100.0, 100.0]]]);
        let m = street_metrics(&g, 10.0, 200.0 * 200.0);
        assert_eq!((m.intersections_3, m.intersections_4, m.dead_ends, m.blocks), (1, 0, 1, 1));
        assert_eq!(m.street_length_km, 9.0);
        assert_eq!((m.sd, m.si, m.si3), (0.25, 0.25, 0.25));
        // The cul-de-sac is not part of the block's boundary.
        assert_eq!((m.bmin, m.bavg, m.bmax), (Some(8000.0), Some(8000.0), Some(8000.0)));

        // Without the boundary: a lone star of 5 spokes has 5 dead ends and one 5-way centre.
        let spokes: Vec<[[f64; 2]; 2]> = (0..5)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 5.0;
                [[0.0, 0.0], [a.cos(), a.sin()]]
            })
            .collect();
        let m = street_metrics(&PlanarGraph::from_segments(&spokes, 1e-9), 1000.0, 4.0);
        assert_eq!((m.intersections_5plus, m.dead_ends, m.blocks), (1, 5, 0));
        assert_eq!((m.si, m.si3, m.sd), (0.25, 0.0, 1.25));
        assert!((m.street_length_km - 5.0).abs() < 1e-12);
        assert_eq!((m.bmin, m.bavg, m.bmax), (None, None, None));
        // Zero area: densities are 0, not NaN.
        assert_eq!(street_metrics(&PlanarGraph::default(), 1.0, 0.0).sl, 0.0);
    }
}
