//! The independent check of a layout: it shares no code with the parceller or the metrics
//! beyond the polygon type and `geo`'s booleans. A layout is valid when
//! * no two parcels overlap: the area of their union equals the sum of their areas within 0.1 %;
//! * streets and parcels cover the region: their areas sum to the region's within 1 %;
//! * every parcel lies in the region (vertices within 1 mm of it);
//! * every residential parcel fronts a street: one of its edges comes within the street's half
//!   width (plus 0.5 m) of its centreline, by exact segment–segment distance;
//! * no street crosses a hole: no centreline segment properly crosses a hole's edge, and no
//!   segment midpoint lies inside a hole.

use super::{Parcel, Street, Use};
use crate::geometry::polygon::geo_polygon;
use crate::geometry::{closest_on_segment, dist, ring_area2, ring_contains, segment_intersection, Polygon, P};
use geo::{Area, BooleanOps, Buffer};
use serde::Serialize;
use std::fmt;

/// A rule a layout breaks.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
pub enum Violation {
    /// Parcels overlap.
    Overlap {
        /// Sum of parcel areas (m²).
        sum: f64,
        /// Area of their union (m²).
        union: f64,
    },
    /// Streets and parcels do not cover the region.
    Coverage {
        /// Their area over the region's, in %.
        percent: f64,
    },
    /// A parcel leaves the region.
    Outside {
        /// The parcel.
        parcel: usize,
    },
    /// A residential parcel fronts no street.
    NoStreet {
        /// The parcel.
        parcel: usize,
    },
    /// A street crosses a hole.
    StreetInHole {
        /// The street.
        street: usize,
        /// The hole.
        hole: usize,
    },
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Violation::Overlap { sum, union } => {
                write!(f, "parcels overlap: areas sum to {sum:.1} m², their union is {union:.1} m²")
            }
            Violation::Coverage { percent } => write!(f, "streets and parcels cover {percent:.2} % of the region"),
            Violation::Outside { parcel } => write!(f, "parcel {parcel} leaves the region"),
            Violation::NoStreet { parcel } => write!(f, "residential parcel {parcel} fronts no street"),
            Violation::StreetInHole { street, hole } => write!(f, "street {street} crosses hole {hole}"),
        }
    }
}

/// Every rule the layout breaks (empty when valid).
pub fn validate(region: &Polygon, streets: &[Street], parcels: &[Parcel]) -> Vec<Violation> {
    let mut out = Vec::new();
    let polys: Vec<geo::Polygon<f64>> = parcels.iter().map(|p| geo_polygon(&p.polygon, &[])).collect();
    let sum: f64 = parcels.iter().map(|p| ring_area2(&p.polygon).abs() / 2.0).sum();
    let union = geo::unary_union(polys.iter()).unsigned_area();
    if (sum - union).abs() > 1e-3 * sum.max(1e-9) {
        out.push(Violation::Overlap { sum, union });
    }
    let street_area = streets_area(region, streets);
    let percent = 100.0 * (street_area + union) / region.area();
    if (percent - 100.0).abs() > 1.0 {
        out.push(Violation::Coverage { percent });
    }
    for (i, p) in parcels.iter().enumerate() {
        if p.polygon.iter().any(|&q| !region.contains(q) && region.boundary_distance(q) > 1e-3) {
            out.push(Violation::Outside { parcel: i });
        }
        if p.use_ == Use::Residential && !fronts(&p.polygon, streets) {
            out.push(Violation::NoStreet { parcel: i });
        }
    }
    for (s, street) in streets.iter().enumerate() {
        for (h, hole) in region.holes().iter().enumerate() {
            if crosses(&street.polyline, hole) {
                out.push(Violation::StreetInHole { street: s, hole: h });
            }
        }
    }
    out
}

/// The streets' area inside the region: each centreline buffered by half its width (mitred joins,
/// butt ends, as streets are drawn), computed here again so the check does not rest on the
/// parceller's own street area.
fn streets_area(region: &Polygon, streets: &[Street]) -> f64 {
    let bufs: Vec<geo::MultiPolygon<f64>> = streets
        .iter()
        .map(|s| {
            let line = geo::LineString::from(s.polyline.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>());
            let style = geo::algorithm::buffer::BufferStyle::new(s.width / 2.0)
                .line_cap(geo::algorithm::buffer::LineCap::Butt)
                .line_join(geo::algorithm::buffer::LineJoin::Miter(4.0));
            line.buffer_with_style(style)
        })
        .collect();
    region.to_geo().intersection(&geo::unary_union(bufs.iter())).unsigned_area()
}

fn segment_distance(a: P, b: P, c: P, d: P) -> f64 {
    if segment_intersection(a, b, c, d).is_some() {
        return 0.0;
    }
    [
        dist(a, closest_on_segment(a, c, d).0),
        dist(b, closest_on_segment(b, c, d).0),
        dist(c, closest_on_segment(c, a, b).0),
        dist(d, closest_on_segment(d, a, b).0),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

fn fronts(ring: &[P], streets: &[Street]) -> bool {
    let n = ring.len();
    streets.iter().any(|s| {
        let reach = s.width / 2.0 + 0.5;
        s.polyline.windows(2).any(|w| (0..n).any(|i| segment_distance(ring[i], ring[(i + 1) % n], w[0], w[1]) <= reach))
    })
}

/// Its own rule for a street crossing a hole, deliberately independent of the parceller's.
fn crosses(line: &[P], hole: &[P]) -> bool {
    let n = hole.len();
    line.windows(2).any(|w| {
        let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
        // A street may end on the hole's ring: within a millimetre of its end is a touch.
        let margin = TOUCH / dist(w[0], w[1]).max(TOUCH);
        ring_contains(hole, mid)
            || (0..n).any(|k| {
                segment_intersection(w[0], w[1], hole[k], hole[(k + 1) % n])
                    .is_some_and(|(s, t)| s > margin && s < 1.0 - margin && t > 1e-9 && t < 1.0 - 1e-9)
            })
    })
}

/// How far past a hole's ring a street's end may reach (metres): the outputs' precision.
const TOUCH: f64 = 1e-3;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::parcels::{blocks, parcellate, StreetIndex};

    fn setup() -> (Polygon, Vec<Street>, Vec<Parcel>) {
        let region = Polygon::new(
            vec![[0.0, 0.0], [300.0, 0.0], [300.0, 150.0], [0.0, 150.0]],
            vec![vec![[200.0, 100.0], [240.0, 100.0], [240.0, 130.0], [200.0, 130.0]]],
        )
        .unwrap();
        let streets = vec![
            Street::new(vec![[0.0, 0.0], [300.0, 0.0], [300.0, 150.0], [0.0, 150.0], [0.0, 0.0]], 15.0, 0),
            Street::new(vec![[150.0, 0.0], [150.0, 150.0]], 15.0, 1),
        ];
        let parcels = parcellate(&blocks(&region, &streets), &StreetIndex::new(&streets), 30.0, 18.0);
        (region, streets, parcels)
    }

    #[test]
    fn a_parcelled_layout_is_valid() {
        let (region, streets, parcels) = setup();
        assert_eq!(validate(&region, &streets, &parcels), vec![]);
    }

    #[test]
    fn each_rule_catches_its_break() {
        let (region, mut streets, mut parcels) = setup();
        let first = parcels.iter().position(|p| p.use_ == Use::Residential).unwrap();
        parcels.push(parcels[first].clone());
        let v = validate(&region, &streets, &parcels);
        assert!(matches!(v[0], Violation::Overlap { .. }), "{v:?}");
        parcels.pop();
        parcels.remove(first);
        assert!(matches!(validate(&region, &streets, &parcels)[..], [Violation::Coverage { .. }]));
        let (_, _, mut parcels) = setup();
        let park = parcels.iter().position(|p| p.use_ == Use::Residential).unwrap();
        streets.truncate(0);
        parcels.truncate(park + 1);
        assert!(validate(&region, &streets, &parcels).iter().any(|v| matches!(v, Violation::NoStreet { .. })));
        let into_hole = Street::new(vec![[220.0, 50.0], [220.0, 115.0]], 15.0, 2);
        assert!(validate(&region, &[into_hole], &[]).contains(&Violation::StreetInHole { street: 0, hole: 0 }));
        // A street ending on the hole's ring, half a millimetre past it, touches it; two past, it enters.
        let to_hole = |y: f64| Street::new(vec![[220.0, 50.0], [220.0, y]], 15.0, 2);
        assert!(!validate(&region, &[to_hole(100.0005)], &[])
            .iter()
            .any(|v| matches!(v, Violation::StreetInHole { .. })));
        assert!(validate(&region, &[to_hole(100.002)], &[]).contains(&Violation::StreetInHole { street: 0, hole: 0 }));
    }
}
