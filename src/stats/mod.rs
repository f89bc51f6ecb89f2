//! Street statistics: the one place netspec measures a street network, whatever made it (a
//! layout, a grown map, a city, a solve, the real streets of an OpenStreetMap extract).
//!
//! [`measure`] takes a [`Network`] in metres and the region it is judged on and returns
//! [`StreetStats`], under OSMnx's own names where OSMnx has the measure (Boeing,
//! "OSMnx: New methods for acquiring, constructing, analyzing, and visualizing complex street
//! networks", 2017; `osmnx.stats.basic_stats`), plus orientation order and blocks. Definitions
//! (docs/stats.md has them in full):
//! * the graph is simplified as `osmnx.simplify_graph` does ([`graph::Network::simplified`]);
//! * a node's street count is taken in the whole network, before clipping (OSMnx counts streets
//!   per node before truncating a graph to a polygon), so a street cut by the region's edge
//!   leaves no dead end; nodes count when they lie in the region (its boundary included);
//! * streets are clipped at the region's edge: lengths and orientations count the pieces
//!   inside; the points where the edge cuts a street are not nodes; an edge counts once per
//!   direction it can be driven (`m`, as OSMnx's directed graph has it);
//! * intersections are nodes with more than one street; clean intersections are the clusters of
//!   intersections whose discs of radius `clean_int_tol` overlap (`osmnx.consolidate_intersections(G, tolerance, rebuild_graph=False,
//!   dead_ends=False)`);
//! * orientation: the 36-bin histogram of chord bearings of every street piece and its reverse,
//!   weighted by length ([`orientation`]);
//! * blocks: the bounded faces of the street graph whose label point lies in the region
//!   ([`blocks`]).
//!
//! [`yang`] keeps the measures Yang et al. (2013, §7) and Peng et al. report, under their own
//! names and definitions.

pub mod blocks;
pub mod graph;
pub mod orientation;
pub mod yang;

pub use graph::{Edge, Network};

use crate::geometry::{dist, Polygon, P};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// OSMnx's `consolidate_intersections` tolerance the statistics use by default (metres).
pub const CLEAN_INT_TOL: f64 = 10.0;
/// Points within this distance (metres) of the region's boundary are on it.
pub const BOUNDARY_TOL: f64 = 0.01;

/// The statistics of one street network on one region. Lengths in metres, areas in km²;
/// OSMnx's keys keep OSMnx's units (`street_density_km` is metres of street per km²).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StreetStats {
    /// Nodes in the region.
    pub n: usize,
    /// Directed edges with a piece in the region (a two-way street counts twice).
    pub m: usize,
    /// Average node degree of the directed graph, 2m/n.
    pub k_avg: f64,
    /// Length of the directed edges' pieces in the region.
    pub edge_length_total: f64,
    /// `edge_length_total / m`.
    pub edge_length_avg: f64,
    /// Mean streets per node.
    pub streets_per_node_avg: f64,
    /// Nodes by their number of streets.
    pub streets_per_node_counts: BTreeMap<u32, usize>,
    /// The same as shares of `n`.
    pub streets_per_node_proportions: BTreeMap<u32, f64>,
    /// Nodes with more than one street.
    pub intersection_count: usize,
    /// Intersections after merging those within `2 × clean_int_tol` (see the module docs).
    pub clean_intersection_count: usize,
    /// Length of the streets' pieces in the region.
    pub street_length_total: f64,
    /// Streets with a piece in the region.
    pub street_segment_count: usize,
    /// `street_length_total / street_segment_count`.
    pub street_length_avg: f64,
    /// Street length over the straight distance between its ends, summed over streets.
    pub circuity_avg: Option<f64>,
    /// Share of streets that are loops.
    pub self_loop_proportion: f64,
    /// Dead ends: nodes in the region with one street.
    pub dead_end_count: usize,
    /// The region's area (km²), when there is a region.
    pub area_km2: Option<f64>,
    /// Nodes per km².
    pub node_density_km: Option<f64>,
    /// Intersections per km².
    pub intersection_density_km: Option<f64>,
    /// Clean intersections per km².
    pub clean_intersection_density_km: Option<f64>,
    /// Directed edge length per km² (m/km²).
    pub edge_density_km: Option<f64>,
    /// Street length per km² (m/km²).
    pub street_density_km: Option<f64>,
    /// Dead ends per km².
    pub dead_end_density_km: Option<f64>,
    /// Shannon entropy (nats) of the 36-bin length-weighted bearing histogram.
    pub orientation_entropy: Option<f64>,
    /// Boeing's order φ.
    pub orientation_order: Option<f64>,
    /// The histogram: metres of street per 10° bin, bin `k` centred on bearing `10 k`°.
    pub orientation_bins: Vec<f64>,
    /// Blocks whose label point is in the region.
    pub blocks: usize,
    /// Blocks per km².
    pub blocks_per_km2: Option<f64>,
    /// Mean block perimeter (m).
    pub block_perimeter_mean: Option<f64>,
    /// Shortest block perimeter (m).
    pub block_perimeter_min: Option<f64>,
    /// Longest block perimeter (m).
    pub block_perimeter_max: Option<f64>,
    /// Mean block area (m²).
    pub block_area_mean: Option<f64>,
    /// Smallest block area (m²).
    pub block_area_min: Option<f64>,
    /// Largest block area (m²).
    pub block_area_max: Option<f64>,
}

/// Settings of [`measure`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Radius of the discs that merge intersections (metres).
    pub clean_int_tol: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings { clean_int_tol: CLEAN_INT_TOL }
    }
}

/// A street's pieces in the region and their length.
struct Clipped {
    pieces: Vec<Vec<P>>,
    length: f64,
}

/// The statistics of `net` on `region` (the whole network when `None`: no densities).
pub fn measure(net: &Network, region: Option<&Polygon>, settings: &Settings) -> StreetStats {
    let g = net.simplified();
    let counts = g.street_counts();
    let inside_node = |p: P| region.is_none_or(|r| r.covers(p, BOUNDARY_TOL));
    let nodes: Vec<usize> = (0..g.nodes.len()).filter(|&v| inside_node(g.nodes[v])).collect();
    let clipped: Vec<Clipped> = g
        .edges
        .iter()
        .map(|e| {
            let pieces = match region {
                Some(r) => r.clip_polyline(&e.shape, BOUNDARY_TOL),
                None if e.shape.len() >= 2 => vec![e.shape.clone()],
                None => Vec::new(),
            };
            let length = pieces.iter().map(|p| crate::geometry::polyline_length(p)).sum();
            Clipped { pieces, length }
        })
        .collect();
    let used: Vec<usize> = (0..g.edges.len()).filter(|&i| !clipped[i].pieces.is_empty()).collect();
    let directions = |i: usize| if g.edges[i].oneway { 1 } else { 2 };
    let m: usize = used.iter().map(|&i| directions(i)).sum();
    let edge_length_total: f64 = used.iter().map(|&i| directions(i) as f64 * clipped[i].length).sum();
    let street_length_total: f64 = used.iter().map(|&i| clipped[i].length).sum();
    let chords: f64 = used.iter().flat_map(|&i| clipped[i].pieces.iter()).map(|p| dist(p[0], p[p.len() - 1])).sum();
    let loops = used.iter().filter(|&&i| g.edges[i].a == g.edges[i].b).count();
    let mut per_node: BTreeMap<u32, usize> = BTreeMap::new();
    for &v in &nodes {
        *per_node.entry(counts[v] as u32).or_default() += 1;
    }
    let n = nodes.len();
    let intersections = nodes.iter().filter(|&&v| counts[v] > 1).count();
    let dead_ends = nodes.iter().filter(|&&v| counts[v] == 1).count();
    let junctions: Vec<P> = nodes.iter().filter(|&&v| counts[v] > 1).map(|&v| g.nodes[v]).collect();
    let clean = clusters(&junctions, 2.0 * settings.clean_int_tol);
    let mut hist = orientation::Histogram::default();
    for &i in used.iter().filter(|&&i| g.edges[i].a != g.edges[i].b) {
        for p in &clipped[i].pieces {
            hist.add(p[0], p[p.len() - 1], crate::geometry::polyline_length(p));
        }
    }
    let entropy = hist.entropy();
    let blocks = blocks::blocks(net, region);
    let area_km2 = region.map(|r| r.area() / 1e6);
    let per_km2 = |x: f64| area_km2.filter(|&a| a > 0.0).map(|a| x / a);
    let ratio = |x: f64, d: usize| if d > 0 { x / d as f64 } else { 0.0 };
    let perimeters: Vec<f64> = blocks.iter().map(|b| b.perimeter).collect();
    let areas: Vec<f64> = blocks.iter().map(|b| b.area).collect();
    StreetStats {
        n,
        m,
        k_avg: ratio(2.0 * m as f64, n),
        edge_length_total,
        edge_length_avg: ratio(edge_length_total, m),
        streets_per_node_avg: ratio(nodes.iter().map(|&v| counts[v] as f64).sum(), n),
        streets_per_node_proportions: per_node.iter().map(|(&k, &c)| (k, ratio(c as f64, n))).collect(),
        streets_per_node_counts: per_node,
        intersection_count: intersections,
        clean_intersection_count: clean,
        street_length_total,
        street_segment_count: used.len(),
        street_length_avg: ratio(street_length_total, used.len()),
        circuity_avg: (chords > 0.0).then(|| street_length_total / chords),
        self_loop_proportion: ratio(loops as f64, used.len()),
        dead_end_count: dead_ends,
        area_km2,
        node_density_km: per_km2(n as f64),
        intersection_density_km: per_km2(intersections as f64),
        clean_intersection_density_km: per_km2(clean as f64),
        edge_density_km: per_km2(edge_length_total),
        street_density_km: per_km2(street_length_total),
        dead_end_density_km: per_km2(dead_ends as f64),
        orientation_entropy: entropy,
        orientation_order: entropy.map(orientation::order),
        orientation_bins: hist.bins.to_vec(),
        blocks: blocks.len(),
        blocks_per_km2: per_km2(blocks.len() as f64),
        block_perimeter_mean: mean(&perimeters),
        block_perimeter_min: perimeters.iter().copied().reduce(f64::min),
        block_perimeter_max: perimeters.iter().copied().reduce(f64::max),
        block_area_mean: mean(&areas),
        block_area_min: areas.iter().copied().reduce(f64::min),
        block_area_max: areas.iter().copied().reduce(f64::max),
    }
}

/// How far a design's statistics are from a reference's (the real streets of the same site):
/// per measure, the relative difference |design − reference| / reference, or for shares and
/// the order φ the absolute difference; and their mean. A relative measure whose reference is
/// zero, or a measure either lacks, is left out (and named in `missing`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Distance {
    /// Per measure (the [`DISTANCE_MEASURES`] names).
    pub measures: BTreeMap<String, f64>,
    /// Their mean.
    pub mean: Option<f64>,
    /// Measures that could not be compared.
    pub missing: Vec<String>,
}

/// The measures [`distance`] compares, each relative (`true`) or absolute (`false`): density and
/// grain (street km and clean intersections per km², mean street length, streets per node,
/// circuity, blocks per km² and their perimeter), and the node mix (shares of dead ends and of
/// four-way nodes); with the order φ (absolute). Dead ends enter as a share, not as a density: a
/// real map has few, and a relative difference of a small count says little.
pub const DISTANCE_MEASURES: [(&str, bool); 9] = [
    ("street_density_km", true),
    ("clean_intersection_density_km", true),
    ("street_length_avg", true),
    ("streets_per_node_avg", true),
    ("circuity_avg", true),
    ("blocks_per_km2", true),
    ("block_perimeter_mean", true),
    ("dead_end_proportion", false),
    ("four_way_proportion", false),
];

impl StreetStats {
    /// The share of nodes with one street.
    pub fn dead_end_proportion(&self) -> Option<f64> {
        (self.n > 0).then(|| self.dead_end_count as f64 / self.n as f64)
    }

    /// The share of nodes with four or more streets.
    pub fn four_way_proportion(&self) -> Option<f64> {
        (self.n > 0)
            .then(|| self.streets_per_node_counts.range(4..).map(|(_, &c)| c).sum::<usize>() as f64 / self.n as f64)
    }

    /// A measure by its [`DISTANCE_MEASURES`] name (or `orientation_order`).
    pub fn value(&self, name: &str) -> Option<f64> {
        match name {
            "street_density_km" => self.street_density_km,
            "intersection_density_km" => self.intersection_density_km,
            "clean_intersection_density_km" => self.clean_intersection_density_km,
            "dead_end_density_km" => self.dead_end_density_km,
            "street_length_avg" => Some(self.street_length_avg),
            "streets_per_node_avg" => Some(self.streets_per_node_avg),
            "circuity_avg" => self.circuity_avg,
            "blocks_per_km2" => self.blocks_per_km2,
            "block_perimeter_mean" => self.block_perimeter_mean,
            "dead_end_proportion" => self.dead_end_proportion(),
            "four_way_proportion" => self.four_way_proportion(),
            "orientation_order" => self.orientation_order,
            _ => None,
        }
    }
}

/// The [`Distance`] of `design` from `reference` over [`DISTANCE_MEASURES`] and the order φ.
pub fn distance(design: &StreetStats, reference: &StreetStats) -> Distance {
    let mut measures = BTreeMap::new();
    let mut missing = Vec::new();
    let all = DISTANCE_MEASURES.iter().copied().chain([("orientation_order", false)]);
    for (name, relative) in all {
        match (design.value(name), reference.value(name)) {
            (Some(d), Some(r)) if !relative => {
                measures.insert(name.to_string(), (d - r).abs());
            }
            (Some(d), Some(r)) if r > 0.0 => {
                measures.insert(name.to_string(), (d - r).abs() / r);
            }
            _ => missing.push(name.to_string()),
        }
    }
    let mean = (!measures.is_empty()).then(|| measures.values().sum::<f64>() / measures.len() as f64);
    Distance { measures, mean, missing }
}

fn mean(v: &[f64]) -> Option<f64> {
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// The number of clusters of points joined by chains of distances of at most `reach` (the
/// connected pieces of the union of discs of radius `reach / 2`).
pub fn clusters(points: &[P], reach: f64) -> usize {
    let mut parent: Vec<usize> = (0..points.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let cell = reach.max(f64::MIN_POSITIVE);
    let key = |p: P| ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64);
    let mut grid: BTreeMap<(i64, i64), Vec<usize>> = BTreeMap::new();
    for (i, &p) in points.iter().enumerate() {
        let (cx, cy) = key(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &j in grid.get(&(cx + dx, cy + dy)).map_or(&[][..], |v| v) {
                    if dist(p, points[j]) <= reach {
                        let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                        parent[a.max(b)] = a.min(b);
                    }
                }
            }
        }
        grid.entry((cx, cy)).or_default().push(i);
    }
    (0..points.len()).filter(|&i| root(&mut parent, i) == i).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `k × k` grid of two-way streets `s` metres apart, each block side one edge.
    fn grid(k: usize, s: f64) -> Network {
        let mut net = Network::default();
        for j in 0..k {
            for i in 0..k {
                net.nodes.push([i as f64 * s, j as f64 * s]);
            }
        }
        let id = |i: usize, j: usize| j * k + i;
        for j in 0..k {
            for i in 0..k {
                for (di, dj) in [(1, 0), (0, 1)] {
                    if i + di < k && j + dj < k {
                        let (a, b) = (id(i, j), id(i + di, j + dj));
                        net.edges.push(Edge { a, b, shape: vec![net.nodes[a], net.nodes[b]], level: 3, oneway: false });
                    }
                }
            }
        }
        net
    }

    #[test]
    fn a_grid_measured_whole() {
        let s = measure(&grid(4, 100.0), None, &Settings::default());
        // 16 nodes; the 4 corners have two streets to two neighbours, so OSMnx's simplification
        // merges them away: 12 nodes, 20 streets (the corners' two become one L).
        assert!((s.street_length_total - 2400.0).abs() < 1e-9);
        // 3,200 m of grid bearings (N, E, S, W: 800 each) and the four Ls' diagonal chords (400
        // each on the diagonals).
        let h = 2.0 / 3.0 * 6f64.ln() + 12f64.ln() / 3.0;
        assert!((s.orientation_entropy.unwrap() - h).abs() < 1e-12);
        assert_eq!(s.blocks, 9);
        assert_eq!(s.block_perimeter_mean, Some(400.0));
        assert_eq!(s.area_km2, None);
        // Circuity: 2,400 m over 16 chords of 100 m and 4 of 100√2 m.
        assert!((s.circuity_avg.unwrap() - 2400.0 / (1600.0 + 400.0 * 2f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn a_region_clips_streets_but_not_street_counts() {
        let net = grid(4, 100.0);
        // The region covers the lower-left 141 × 141 m: nodes (0,0)…(100,100).
        let region = Polygon::new(vec![[-1.0, -1.0], [140.0, -1.0], [140.0, 140.0], [-1.0, 140.0]], vec![]).unwrap();
        let s = measure(&net, Some(&region), &Settings::default());
        // Inside: (100,0) and (0,100) with 3 streets, (100,100) with 4; the corner was merged.
        assert_eq!(s.n, 3);
        assert_eq!(s.streets_per_node_counts, BTreeMap::from([(3, 2), (4, 1)]));
        assert_eq!(s.dead_end_count, 0, "streets cut by the edge make no dead end");
        assert!((s.area_km2.unwrap() - 0.141 * 0.141).abs() < 1e-12);
        // Inside length: the corner street (200 m), two 100 m streets to (100,100), and the
        // four stubs cut at 140 m (40 m each).
        assert!((s.street_length_total - 560.0).abs() < 1e-9, "{}", s.street_length_total);
        assert_eq!(s.blocks, 1);
        assert_eq!(clusters(&[[0.0, 0.0], [19.0, 0.0], [38.0, 0.0], [100.0, 0.0]], 20.0), 2);
    }

    #[test]
    fn distances_are_relative_or_absolute() {
        let map = measure(&grid(4, 100.0), None, &Settings::default());
        let region = Polygon::new(vec![[-1.0, -1.0], [301.0, -1.0], [301.0, 301.0], [-1.0, 301.0]], vec![]).unwrap();
        let a = measure(&grid(4, 100.0), Some(&region), &Settings::default());
        let b = measure(&grid(7, 50.0), Some(&region), &Settings::default());
        let same = distance(&a, &a);
        assert_eq!(same.mean, Some(0.0));
        // Without a region the reference has no densities: those are missing, not zero.
        assert!(distance(&a, &map).missing.contains(&"street_density_km".to_string()));
        let d = distance(&b, &a);
        // Twice the street density: relative difference 1.
        let sd = d.measures["street_density_km"];
        assert!((sd - (b.street_length_total / a.street_length_total - 1.0)).abs() < 1e-12, "{sd}");
        assert!(d.measures["orientation_order"] < 0.2, "both grids: {:?}", d.measures);
        assert!(d.mean.unwrap() > 0.0);
    }
}
