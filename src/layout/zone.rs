//! Zones: land the designer marks (Yang et al. 2013 §3's key design elements — parks, schools,
//! commercial areas — and land kept as it is). A park, school or commercial zone is a part of its
//! own with a street along its outline (where that is not the region's boundary); templates of
//! its label fill it, and where none fits it is one parcel of its use. A `keep` zone is left as
//! it is: no street crosses or follows it, and it is one parcel of use `keep`. Every other part
//! of the region is laid out around the zones.

use super::Street;
use super::Use;
use crate::geometry::polygon::{Polygon, PolygonError};
use crate::geometry::{closest_on_segment, dist, lerp, ring_contains, segment_intersection, P};
use geo::{Area, BooleanOps};
use thiserror::Error;

/// What a zone is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ZoneUse {
    /// A park.
    Park,
    /// A school and its grounds.
    School,
    /// Shops and offices.
    Commercial,
    /// Land kept as it is.
    Keep,
}

impl ZoneUse {
    /// From its name in a region file.
    pub fn parse(s: &str) -> Option<ZoneUse> {
        match s {
            "park" => Some(ZoneUse::Park),
            "school" => Some(ZoneUse::School),
            "commercial" => Some(ZoneUse::Commercial),
            "keep" => Some(ZoneUse::Keep),
            _ => None,
        }
    }

    /// The label templates that fill it carry (`kind`), and the part's label in the tree.
    pub fn label(self) -> &'static str {
        match self {
            ZoneUse::Park => "park",
            ZoneUse::School => "school",
            ZoneUse::Commercial => "commercial",
            ZoneUse::Keep => "keep",
        }
    }

    /// The zone's label back to its use (`None` for `block`).
    pub fn from_label(label: &str) -> Option<ZoneUse> {
        ZoneUse::parse(label)
    }

    /// The use of its parcels when no template fills it.
    pub fn parcel_use(self) -> Use {
        match self {
            ZoneUse::Park => Use::Park,
            ZoneUse::School => Use::School,
            ZoneUse::Commercial => Use::Commercial,
            ZoneUse::Keep => Use::Keep,
        }
    }

    /// Whether a street runs along its outline.
    pub fn has_street(self) -> bool {
        self != ZoneUse::Keep
    }
}

/// A zone, checked on its own (its ring is a simple polygon, its use known).
#[derive(Clone, Debug, PartialEq)]
pub struct Zone {
    /// How errors name it: `zone[i]` (TOML) or `features[i]` (GeoJSON).
    pub name: String,
    /// Its ring, counter-clockwise, not closed.
    pub ring: Vec<P>,
    /// Its use.
    pub use_: ZoneUse,
}

/// What is wrong with a zone.
#[derive(Debug, Error, PartialEq)]
pub enum ZoneProblem {
    /// An unknown use.
    #[error("use = \"{0}\" is not park, school, commercial or keep")]
    UnknownUse(String),
    /// Its ring is not a simple polygon.
    #[error(transparent)]
    Polygon(PolygonError),
    /// It lies (partly) outside the region.
    #[error("crosses the region's outline near ({:.1}, {:.1})", .0[0], .0[1])]
    CrossesOutline(P),
    /// It crosses a hole, lies in one or holds one.
    #[error("crosses hole {0}")]
    CrossesHole(usize),
    /// It holds a hole.
    #[error("contains hole {0}")]
    ContainsHole(usize),
    /// It overlaps another zone.
    #[error("overlaps {0}")]
    Overlaps(String),
}

impl Zone {
    /// A zone from its ring and use name, checked on its own.
    pub fn new(name: String, ring: Vec<P>, use_: &str) -> Result<Zone, (String, ZoneProblem)> {
        let Some(u) = ZoneUse::parse(use_) else { return Err((name, ZoneProblem::UnknownUse(use_.to_string()))) };
        let poly = match Polygon::new(ring, Vec::new()) {
            Ok(p) => p,
            Err(e) => return Err((name, ZoneProblem::Polygon(e))),
        };
        Ok(Zone { name, ring: poly.outer().to_vec(), use_: u })
    }

    /// Its polygon.
    pub fn polygon(&self) -> Polygon {
        Polygon::new(self.ring.clone(), Vec::new()).expect("a zone's ring was checked")
    }

    fn edges(&self) -> impl Iterator<Item = (P, P)> + '_ {
        let n = self.ring.len();
        (0..n).map(move |i| (self.ring[i], self.ring[(i + 1) % n]))
    }
}

/// Within this distance (metres) a zone's edge lies on the region's boundary.
const ON_BOUNDARY: f64 = 0.5;

/// Checks the zones against the region and each other: inside the region (touching its outline
/// is fine), clear of its holes, apart from each other. The error names the zone.
pub fn check(region: &Polygon, zones: &[Zone]) -> Result<(), (String, ZoneProblem)> {
    let outer = region.outer();
    for z in zones {
        let err = |p| Err((z.name.clone(), p));
        for (a, b) in z.edges() {
            for p in [a, lerp(a, b, 0.5)] {
                if !region_covers(outer, p) {
                    return err(ZoneProblem::CrossesOutline(p));
                }
            }
            if let Some(at) = proper_crossing(a, b, outer) {
                return err(ZoneProblem::CrossesOutline(at));
            }
            for (k, h) in region.holes().iter().enumerate() {
                if proper_crossing(a, b, h).is_some() || (ring_contains(h, a) && !on_ring(h, a)) {
                    return err(ZoneProblem::CrossesHole(k));
                }
            }
        }
        for (k, h) in region.holes().iter().enumerate() {
            if h.iter().any(|&p| ring_contains(&z.ring, p) && !on_ring(&z.ring, p)) {
                return err(ZoneProblem::ContainsHole(k));
            }
        }
    }
    for (i, z) in zones.iter().enumerate() {
        for w in &zones[..i] {
            if z.polygon().to_geo().intersection(&w.polygon().to_geo()).unsigned_area() > 1e-6 {
                return Err((z.name.clone(), ZoneProblem::Overlaps(w.name.clone())));
            }
        }
    }
    Ok(())
}

fn region_covers(ring: &[P], p: P) -> bool {
    ring_contains(ring, p) || on_ring(ring, p)
}

fn on_ring(ring: &[P], p: P) -> bool {
    let n = ring.len();
    (0..n).any(|i| dist(p, closest_on_segment(p, ring[i], ring[(i + 1) % n]).0) <= 1e-6)
}

/// Where segment `a b` crosses the ring's edges in both their interiors, if it does.
fn proper_crossing(a: P, b: P, ring: &[P]) -> Option<P> {
    let n = ring.len();
    (0..n).find_map(|i| {
        let (s, t) = segment_intersection(a, b, ring[i], ring[(i + 1) % n])?;
        let inside = |x: f64| x > 1e-9 && x < 1.0 - 1e-9;
        (inside(s) && inside(t)).then(|| lerp(a, b, s))
    })
}

/// The streets along the zones that have one (level 0, `width`): each zone's outline less the
/// edges on the region's boundary, as polylines.
pub fn streets(region: &Polygon, zones: &[Zone], width: f64) -> Vec<Street> {
    let mut out = Vec::new();
    for z in zones.iter().filter(|z| z.use_.has_street()) {
        let n = z.ring.len();
        let keep: Vec<bool> = z.edges().map(|(a, b)| region.boundary_distance(lerp(a, b, 0.5)) > ON_BOUNDARY).collect();
        let Some(start) = (0..n).find(|&i| !keep[i]) else {
            let mut closed = z.ring.clone();
            closed.push(z.ring[0]);
            out.push(Street::new(closed, width, 0));
            continue;
        };
        let mut line: Vec<P> = Vec::new();
        for k in 1..=n {
            let i = (start + k) % n;
            if keep[i] {
                if line.is_empty() {
                    line.push(z.ring[i]);
                }
                line.push(z.ring[(i + 1) % n]);
            } else if line.len() >= 2 {
                out.push(Street::new(std::mem::take(&mut line), width, 0));
            }
        }
        if line.len() >= 2 {
            out.push(Street::new(line, width, 0));
        }
    }
    out
}

/// The region less its zones: the pieces left to lay out (a zone inside the region becomes a
/// hole of its piece).
pub fn carve(region: &Polygon, zones: &[Zone]) -> Vec<Polygon> {
    if zones.is_empty() {
        return vec![region.clone()];
    }
    let all: Vec<geo::Polygon<f64>> = zones.iter().map(|z| z.polygon().to_geo()).collect();
    let union = geo::unary_union(all.iter());
    let rest = region.to_geo().difference(&union);
    let ring = |l: &geo::LineString<f64>| l.0.iter().map(|c| [c.x, c.y]).collect::<Vec<P>>();
    rest.0
        .iter()
        .filter(|p| p.unsigned_area() > 1.0)
        .filter_map(|p| Polygon::new(ring(p.exterior()), p.interiors().iter().map(ring).collect()).ok())
        .collect()
}

/// Major roads with the pieces inside zones left out.
pub fn clip_roads(roads: &[Vec<P>], zones: &[Zone]) -> Vec<Vec<P>> {
    let mut pieces: Vec<Vec<P>> = roads.to_vec();
    for z in zones {
        let zone = z.polygon().to_geo();
        pieces = pieces
            .into_iter()
            .flat_map(|r| {
                let line = geo::MultiLineString::new(vec![geo::LineString::from(
                    r.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>(),
                )]);
                zone.clip(&line, true)
                    .0
                    .into_iter()
                    .map(|l| l.0.iter().map(|c| [c.x, c.y]).collect::<Vec<P>>())
                    .filter(|l| l.len() >= 2 && crate::geometry::polyline_length(l) > 1.0)
                    .collect::<Vec<_>>()
            })
            .collect();
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    fn region() -> Polygon {
        Polygon::new(
            vec![[0.0, 0.0], [400.0, 0.0], [400.0, 300.0], [0.0, 300.0]],
            vec![vec![[300.0, 200.0], [350.0, 200.0], [350.0, 250.0], [300.0, 250.0]]],
        )
        .unwrap()
    }

    fn zone(name: &str, ring: &[[f64; 2]], u: &str) -> Zone {
        Zone::new(name.into(), ring.to_vec(), u).unwrap()
    }

    #[test]
    fn zones_are_checked_against_the_region_and_each_other() {
        let r = region();
        let school = zone("zone[0]", &[[0.0, 0.0], [120.0, 0.0], [120.0, 100.0], [0.0, 100.0]], "school");
        let park = zone("zone[1]", &[[150.0, 50.0], [250.0, 50.0], [250.0, 150.0], [150.0, 150.0]], "park");
        assert_eq!(check(&r, &[school.clone(), park.clone()]), Ok(()));
        let over = zone("zone[2]", &[[100.0, 50.0], [200.0, 50.0], [200.0, 90.0]], "keep");
        assert_eq!(
            check(&r, &[school.clone(), over]).unwrap_err(),
            ("zone[2]".into(), ZoneProblem::Overlaps("zone[0]".into()))
        );
        let out = zone("zone[0]", &[[350.0, 10.0], [450.0, 10.0], [450.0, 60.0], [350.0, 60.0]], "park");
        assert!(matches!(check(&r, &[out]), Err((_, ZoneProblem::CrossesOutline(_)))));
        let hole = zone("zone[0]", &[[320.0, 180.0], [380.0, 180.0], [380.0, 220.0], [320.0, 220.0]], "park");
        assert_eq!(check(&r, &[hole]).unwrap_err().1, ZoneProblem::CrossesHole(0));
        let round = zone("zone[0]", &[[280.0, 180.0], [380.0, 180.0], [380.0, 280.0], [280.0, 280.0]], "park");
        assert_eq!(check(&r, &[round]).unwrap_err().1, ZoneProblem::ContainsHole(0));
        let e = Zone::new("zone[3]".into(), vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], "mall").unwrap_err();
        assert_eq!(e.1.to_string(), "use = \"mall\" is not park, school, commercial or keep");
    }

    #[test]
    fn a_zone_on_the_boundary_has_a_street_on_its_inner_sides_and_becomes_its_own_part() {
        let r = region();
        let school = zone("zone[0]", &[[0.0, 0.0], [120.0, 0.0], [120.0, 100.0], [0.0, 100.0]], "school");
        let s = streets(&r, std::slice::from_ref(&school), 15.0);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].polyline, vec![[120.0, 0.0], [120.0, 100.0], [0.0, 100.0]]);
        let park = zone("zone[1]", &[[150.0, 50.0], [250.0, 50.0], [250.0, 150.0], [150.0, 150.0]], "park");
        let s = streets(&r, std::slice::from_ref(&park), 15.0);
        assert_eq!((s.len(), s[0].polyline.len()), (1, 5), "a closed ring");
        let keep = zone("zone[2]", &[[150.0, 200.0], [250.0, 200.0], [250.0, 280.0]], "keep");
        assert!(streets(&r, std::slice::from_ref(&keep), 15.0).is_empty());
        let rest = carve(&r, &[school, park]);
        assert_eq!(rest.len(), 1);
        assert_eq!(rest[0].holes().len(), 2, "the lake and the park");
        assert!((rest[0].area() - (120_000.0 - 2_500.0 - 12_000.0 - 10_000.0)).abs() < 1e-6);
        let roads = clip_roads(&[vec![[0.0, 100.0], [400.0, 100.0]]], &rest_zones());
        assert_eq!(roads.len(), 2, "the road leaves the park out");
    }

    fn rest_zones() -> Vec<Zone> {
        vec![zone("zone[1]", &[[150.0, 50.0], [250.0, 50.0], [250.0, 150.0], [150.0, 150.0]], "park")]
    }
}
