//! The measures urban designers compare layouts by (Yang et al. 2013 §7, after Southworth and
//! Owens 1993): land use, blocks, streets and parcel shape. One function for every layout netspec
//! makes, whatever drew its streets.
//!
//! Definitions (where §7 leaves them open):
//! * land use: streets = the area of the union of the street buffers inside the region;
//!   residential, parks and other (commercial included) = the parcels' areas by use; `unassigned`
//!   = what is left (zero when blocks are fully parcelled; the validator bounds it);
//! * densities are per km² of the whole region; streets, intersections and dead ends as
//!   [`crate::stats::yang`] counts them (a street along the region's boundary with half its
//!   length; intersections where three or more street arms meet; dead ends street ends that meet
//!   nothing off the region's boundary);
//! * parcel corners are the vertices of the parcel simplified by Douglas–Peucker at 0.5 m whose
//!   turn is at least 20°; the corner deviation is |interior angle − 90°|; the area ratio is the
//!   minimum rotated rectangle's area over the parcel's; a parcel is undesirable when its own
//!   mean deviation exceeds 15° or its ratio 1.2;
//! * over the parcels templates made (the paper measures them "for our results only"):
//!   `p_similarity`, the mean registration distance of a parcel to its ideal (its template face
//!   registered onto it by a similarity, metres), and `p_ideal`, the mean of the larger of a
//!   parcel's area over its ideal area and the reverse;
//! * histograms (§7's panel): parcel areas (20 bins up to twice the median area), corner
//!   deviations (1.5° bins) and registration distances (0.25 m bins), the last bin open.

use super::parcels::street_area;
use super::{Parcel, Street, Use};
use crate::geometry::shape::outer_ring;
use crate::geometry::Shape;
use crate::geometry::{ring_area2, Polygon, P};
use crate::stats::yang::{block_perimeter, street_length, street_nodes};
use geo::{Area, MinimumRotatedRect, Simplify};
use serde::{Deserialize, Serialize};

/// A parcel is undesirable above this mean corner deviation (degrees).
pub const UNDESIRABLE_DEVIATION: f64 = 15.0;
/// … or above this area ratio to its minimum rotated rectangle.
pub const UNDESIRABLE_RATIO: f64 = 1.2;

/// Land use, in % of the region's area.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LandUse {
    /// Streets.
    pub streets: f64,
    /// Residential parcels.
    pub residential: f64,
    /// Parks.
    pub parks: f64,
    /// Other parcels (commercial included).
    pub other: f64,
    /// Neither street nor parcel.
    pub unassigned: f64,
}

/// The §7 metrics of a layout.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// The region's area (km²).
    pub area_km2: f64,
    /// Land use (%).
    pub land_use: LandUse,
    /// Blocks.
    pub blocks: usize,
    /// Blocks per km².
    pub blocks_per_km2: f64,
    /// Mean block perimeter (m).
    pub block_perimeter_mean: f64,
    /// Shortest block perimeter (m).
    pub block_perimeter_min: f64,
    /// Longest block perimeter (m).
    pub block_perimeter_max: f64,
    /// Street centreline length per km² (km/km²).
    pub street_km_per_km2: f64,
    /// Intersections per km².
    pub intersections_per_km2: f64,
    /// Dead ends per km².
    pub dead_ends_per_km2: f64,
    /// Parcels.
    pub parcels: usize,
    /// Parcels per km².
    pub parcels_per_km2: f64,
    /// Mean deviation of parcel corners from 90° (degrees).
    pub corner_deviation_mean: f64,
    /// Mean ratio of a parcel's minimum rotated rectangle to its area.
    pub area_ratio_mean: f64,
    /// Parcels with a mean corner deviation over 15° or an area ratio over 1.2.
    pub undesirable: usize,
    /// Parcels made by templates.
    #[serde(default)]
    pub template_parcels: usize,
    /// §7's `p_similarity`: the template parcels' mean registration distance to their ideal (m).
    #[serde(default)]
    pub similarity_mean: Option<f64>,
    /// §7's `p_ideal`: the template parcels' mean area distortion against their ideal (≥ 1).
    #[serde(default)]
    pub ideal_ratio_mean: Option<f64>,
    /// Histograms of the parcels.
    #[serde(default)]
    pub histograms: Histograms,
}

/// Counts of values in bins: `counts[i]` between `edges[i]` and `edges[i + 1]`, the last bin
/// open above.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Histogram {
    /// Bin edges.
    pub edges: Vec<f64>,
    /// Counts per bin.
    pub counts: Vec<usize>,
}

impl Histogram {
    /// `bins` bins of `width` from 0, the last open above.
    pub fn new(values: impl Iterator<Item = f64>, width: f64, bins: usize) -> Histogram {
        let r = |x: f64| (x * 1000.0).round() / 1000.0;
        let mut counts = vec![0; bins];
        for v in values.filter(|v| v.is_finite()) {
            let i = if width > 0.0 { (v.max(0.0) / width).floor() as usize } else { 0 };
            counts[i.min(bins - 1)] += 1;
        }
        Histogram { edges: (0..=bins).map(|i| r(i as f64 * width)).collect(), counts }
    }
}

/// The parcel histograms of §7's panel.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Histograms {
    /// Parcel areas (m²).
    pub area: Histogram,
    /// Each parcel's mean corner deviation (degrees).
    pub corner_deviation: Histogram,
    /// Template parcels' registration distances (m).
    pub registration: Histogram,
}

/// Bins per histogram.
const BINS: usize = 20;

/// One parcel's shape measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParcelShape {
    /// Sum of its corners' deviations from 90° (degrees).
    pub deviation_sum: f64,
    /// Its corners.
    pub corners: usize,
    /// Its minimum rotated rectangle's area over its area.
    pub area_ratio: f64,
}

impl ParcelShape {
    /// Whether the parcel is undesirable.
    pub fn undesirable(&self) -> bool {
        self.deviation_sum / self.corners.max(1) as f64 > UNDESIRABLE_DEVIATION || self.area_ratio > UNDESIRABLE_RATIO
    }
}

/// A parcel's shape measures.
pub fn parcel_shape(ring: &[P]) -> ParcelShape {
    let closed: Vec<(f64, f64)> = ring.iter().chain(ring.first()).map(|p| (p[0], p[1])).collect();
    let poly = geo::Polygon::new(geo::LineString::from(closed), vec![]);
    let simple = outer_ring(&poly.simplify(0.5));
    let n = simple.len();
    let (mut sum, mut corners) = (0.0, 0);
    for i in 0..n {
        let (a, b, c) = (simple[(i + n - 1) % n], simple[i], simple[(i + 1) % n]);
        let (d1, d2) = (crate::geometry::sub(b, a), crate::geometry::sub(c, b));
        let turn = crate::geometry::cross(d1, d2).atan2(crate::geometry::dot(d1, d2)).to_degrees();
        if turn.abs() >= 20.0 {
            // Interior angle of a counter-clockwise ring: 180° − turn.
            sum += (180.0 - turn - 90.0).abs();
            corners += 1;
        }
    }
    let area = poly.unsigned_area();
    let rect = poly.minimum_rotated_rect().map_or(area, |r| r.unsigned_area());
    ParcelShape { deviation_sum: sum, corners, area_ratio: if area > 0.0 { rect / area } else { f64::INFINITY } }
}

/// The metrics of a layout: its region, streets, blocks and parcels.
pub fn metrics(region: &Polygon, streets: &[Street], blocks: &[Shape], parcels: &[Parcel]) -> Metrics {
    let area = region.area();
    let km2 = area / 1e6;
    let pct = |a: f64| 100.0 * a / area;
    let street_pct = pct(street_area(region, streets).unsigned_area());
    let by_use = |u: &[Use]| {
        pct(parcels.iter().filter(|p| u.contains(&p.use_)).map(|p| ring_area2(&p.polygon).abs() / 2.0).sum())
    };
    let (residential, parks, other) = (
        by_use(&[Use::Residential]),
        by_use(&[Use::Park]),
        by_use(&[Use::Other, Use::Commercial, Use::School, Use::Keep]),
    );
    let perimeters: Vec<f64> = blocks
        .iter()
        .map(|b| {
            let rings = b.rings();
            block_perimeter(&rings.iter().map(Vec::as_slice).collect::<Vec<_>>())
        })
        .collect();
    let shapes: Vec<ParcelShape> = parcels.iter().map(|p| parcel_shape(&p.polygon)).collect();
    let corners: usize = shapes.iter().map(|s| s.corners).sum();
    let lines: Vec<&[P]> = streets.iter().map(|s| s.polyline.as_slice()).collect();
    let nodes = street_nodes(region, &lines);
    let (intersections, dead_ends) = (nodes.intersections, nodes.dead_ends);
    let length = street_length(region, &lines);
    Metrics {
        area_km2: km2,
        land_use: LandUse {
            streets: street_pct,
            residential,
            parks,
            other,
            unassigned: 100.0 - street_pct - residential - parks - other,
        },
        blocks: blocks.len(),
        blocks_per_km2: blocks.len() as f64 / km2,
        block_perimeter_mean: mean(&perimeters),
        block_perimeter_min: perimeters.iter().copied().fold(f64::INFINITY, f64::min).min(f64::MAX),
        block_perimeter_max: perimeters.iter().copied().fold(0.0, f64::max),
        street_km_per_km2: length / 1000.0 / km2,
        intersections_per_km2: intersections as f64 / km2,
        dead_ends_per_km2: dead_ends as f64 / km2,
        parcels: parcels.len(),
        parcels_per_km2: parcels.len() as f64 / km2,
        corner_deviation_mean: shapes.iter().map(|s| s.deviation_sum).sum::<f64>() / corners.max(1) as f64,
        area_ratio_mean: mean(&shapes.iter().map(|s| s.area_ratio).collect::<Vec<_>>()),
        undesirable: shapes.iter().filter(|s| s.undesirable()).count(),
        template_parcels: parcels.iter().filter(|p| p.registration.is_some()).count(),
        similarity_mean: mean_of(parcels.iter().filter_map(|p| p.registration)),
        ideal_ratio_mean: mean_of(parcels.iter().filter_map(|p| {
            let a = ring_area2(&p.polygon).abs() / 2.0;
            p.ideal.filter(|&i| i > 0.0 && a > 0.0).map(|i| (a / i).max(i / a))
        })),
        histograms: histograms(parcels, &shapes),
    }
}

fn mean_of(v: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    (n > 0).then(|| sum / n as f64)
}

fn histograms(parcels: &[Parcel], shapes: &[ParcelShape]) -> Histograms {
    let mut areas: Vec<f64> = parcels.iter().map(|p| ring_area2(&p.polygon).abs() / 2.0).collect();
    areas.sort_by(f64::total_cmp);
    let median = areas.get(areas.len() / 2).copied().unwrap_or(0.0);
    let width = (2.0 * median / BINS as f64).max(1e-9);
    Histograms {
        area: Histogram::new(areas.iter().copied(), (width * 100.0).round().max(1.0) / 100.0, BINS),
        corner_deviation: Histogram::new(shapes.iter().map(|s| s.deviation_sum / s.corners.max(1) as f64), 1.5, BINS),
        registration: Histogram::new(parcels.iter().filter_map(|p| p.registration), 0.25, BINS),
    }
}

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::parcels::{blocks, parcellate, StreetIndex};

    #[test]
    fn a_rectangle_has_right_corners_and_ratio_one() {
        let s = parcel_shape(&[[0.0, 0.0], [18.0, 0.0], [18.0, 30.0], [0.0, 30.0]]);
        assert_eq!((s.corners, s.deviation_sum), (4, 0.0));
        assert!((s.area_ratio - 1.0).abs() < 1e-9 && !s.undesirable());
        let t = parcel_shape(&[[0.0, 0.0], [30.0, 0.0], [0.0, 30.0]]);
        // 90°, 45°, 45°: deviations 0 + 45 + 45 over 3 corners; ratio 2.
        assert!((t.deviation_sum - 90.0).abs() < 1e-9 && (t.area_ratio - 2.0).abs() < 1e-9 && t.undesirable());
    }

    #[test]
    fn a_cross_of_streets_in_a_square() {
        let region = Polygon::new(vec![[0.0, 0.0], [300.0, 0.0], [300.0, 300.0], [0.0, 300.0]], vec![]).unwrap();
        let ring = vec![[0.0, 0.0], [300.0, 0.0], [300.0, 300.0], [0.0, 300.0], [0.0, 0.0]];
        let streets = vec![
            Street::new(ring, 15.0, 0),
            Street::new(vec![[150.0, 0.0], [150.0, 300.0]], 15.0, 1),
            Street::new(vec![[0.0, 150.0], [150.0, 150.0]], 15.0, 2),
            Street::new(vec![[150.0, 150.0], [300.0, 150.0]], 15.0, 2),
            Street::new(vec![[75.0, 150.0], [75.0, 100.0]], 15.0, 3),
        ];
        let b = blocks(&region, &streets);
        let parcels = parcellate(&b, &StreetIndex::new(&streets), 30.0, 18.0);
        let m = metrics(&region, &streets, &b, &parcels);
        // Four T-junctions on the boundary, the crossing, the stub's T; the stub's other end.
        assert_eq!(m.intersections_per_km2 * m.area_km2, 6.0);
        assert!((m.dead_ends_per_km2 * m.area_km2 - 1.0).abs() < 1e-9);
        assert_eq!(m.blocks, 4);
        let lu = &m.land_use;
        assert!(lu.unassigned.abs() < 0.01, "{lu:?}");
        // Boundary half-counted: 600 m; inner streets 600 m; stub 50 m.
        assert!((m.street_km_per_km2 * m.area_km2 - 1.25).abs() < 1e-9);
    }
}
