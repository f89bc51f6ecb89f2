//! A street network in metres, as every design is simulated and measured: nodes, streets with
//! their level, lanes and shape, the region they serve, and where they came from. The readers
//! are [`super::network`] (solve and city outputs) and [`super::streets`] (layout, grow and
//! GeoJSON streets).

use crate::geometry as geom;
use serde::{Deserialize, Serialize};

/// A street network in metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoadNetwork {
    /// Name (the spec's or the city's).
    pub name: String,
    /// Which run produced it.
    pub source: Provenance,
    /// The scale used to convert model units to metres.
    pub metres_per_unit: f64,
    /// Junctions and street ends.
    pub nodes: Vec<RoadNode>,
    /// Streets (undirected; each becomes one SUMO edge per direction).
    pub edges: Vec<RoadEdge>,
    /// The area the design serves (where demand is placed).
    pub region: Region,
    /// The WGS 84 `[longitude, latitude]` its metres are measured from (a transverse Mercator
    /// centred there), when the design is on the map.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin: Option<[f64; 2]>,
}

/// A node: a design vertex with at least one street.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoadNode {
    /// The design's vertex id.
    pub id: u32,
    /// Position, metres.
    pub pos: [f64; 2],
    /// Through traffic may start and end here: a node of a major road on the region's
    /// boundary (a city), a sink (a `solve` design).
    pub entrance: bool,
}

/// A street between two nodes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoadEdge {
    /// The design's edge id.
    pub id: u32,
    /// One end (index into [`RoadNetwork::nodes`]).
    pub a: usize,
    /// The other end.
    pub b: usize,
    /// Hierarchy level: 1 major road, 2 collector, 3 local street, 4 cul-de-sac.
    pub level: u8,
    /// Its geometry from `a` to `b`, metres (both ends included; the smoothed street where
    /// there is one, else the straight segment).
    pub shape: Vec<[f64; 2]>,
    /// Local traffic may start and end here (streets of levels ≥ 2 in a city; every street of
    /// a `solve` design).
    pub local: bool,
    /// The load its generator predicted (a grown network's segment traffic), if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub predicted_load: Option<f64>,
    /// Traffic runs only from `a` to `b` (a one-way street of a real map).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub oneway: bool,
}

impl RoadEdge {
    /// Length of the shape, metres.
    pub fn length(&self) -> f64 {
        self.shape.windows(2).map(|w| geom::dist(w[0], w[1])).sum()
    }
}

/// The area a design serves, metres: the same for every design of one region, so demand drawn
/// from it is the same too.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Region {
    /// The outer boundary (through traffic enters and leaves here).
    pub boundary: Vec<[f64; 2]>,
    /// Polygons whose union is the area (local traffic starts and ends here).
    pub areas: Vec<Vec<[f64; 2]>>,
}

impl Region {
    /// The same region written one way: coordinates rounded to the millimetre, every ring
    /// counter-clockwise and starting at its lowest vertex (smallest y, then x), without a
    /// repeated closing point.
    pub fn canonical(&self) -> Region {
        Region {
            boundary: canonical_ring(&self.boundary),
            areas: self.areas.iter().map(|a| canonical_ring(a)).collect(),
        }
    }
}

fn canonical_ring(ring: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mm = |x: f64| (x * 1000.0).round() / 1000.0;
    let mut r: Vec<[f64; 2]> = ring.iter().map(|p| [mm(p[0]), mm(p[1])]).collect();
    r.dedup();
    if r.len() > 1 && r.first() == r.last() {
        r.pop();
    }
    if geom::signed_area(&r) < 0.0 {
        r.reverse();
    }
    if let Some(k) = (0..r.len()).min_by(|&i, &j| (r[i][1], r[i][0]).partial_cmp(&(r[j][1], r[j][0])).expect("finite"))
    {
        r.rotate_left(k);
    }
    r
}

/// Which run produced a design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// `solve` or `city`.
    pub kind: String,
    /// The file read.
    pub path: String,
    /// The netspec version that wrote it.
    pub netspec_version: String,
    /// The spec's description.
    pub description: String,
    /// One line per solve: level, termination, objective, gap, time, validity, backend.
    pub runs: Vec<String>,
}
