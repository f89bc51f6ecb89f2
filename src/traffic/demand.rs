//! Seeded demand: trips drawn as points in the region, then placed on the nearest street of a
//! design. The points depend only on the region and the settings, so every design of one region
//! gets the same demand (the same places at the same times).
//!
//! * **Through traffic**: departures a Poisson process of `through_per_hour`; each trip starts
//!   at a uniformly random point of the region's boundary and ends 30–70 % of the perimeter
//!   further along it (the other side of the region), each end at the nearest *entrance* node
//!   (a node of a major road on the region's boundary; a sink of a `solve` design). Vehicles
//!   leave and reach these junctions in whichever direction their route needs (`duarouter
//!   --junction-taz`).
//! * **Local traffic**: a Poisson process of `local_per_hour`; both ends uniformly random
//!   points of the region, each on the nearest *local* street (level ≥ 2 in a city), at the
//!   point's projection, driving in a direction drawn with the trip (a car parked one way or
//!   the other: it may have to go round a block, as there are U-turns only at dead ends).
//!
//! * **Trade** (with `trade` flows, e.g. a `trade.json` of `netspec grow --window`): a Poisson
//!   process of `trade_per_hour`, shared among the flows by weight; each trip from the flow's
//!   entry point to its exit point, each end at the nearest entrance node.
//!
//! A trip whose two ends fall on the same street or junction is dropped (and counted). Routes
//! are `duarouter`'s.

use super::export::{edge_id, node_id};
use super::network::{Region, RoadNetwork};
use super::parse::SumoNet;
use crate::geometry as geom;
use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// How much traffic, for how long.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DemandSettings {
    /// Departures happen in `[0, duration)`, seconds.
    pub duration: f64,
    /// Through trips per hour.
    pub through_per_hour: f64,
    /// Local trips per hour.
    pub local_per_hour: f64,
    /// Seed of the demand (and of `duarouter` and `sumo`).
    pub seed: u64,
    /// Trade trips per hour, shared among the [`trade`](Self::trade) flows by weight.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub trade_per_hour: f64,
    /// Trade flows between points of the region's boundary (a `trade.json` of
    /// `netspec grow --window`); none by default.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub trade: Vec<TradeFlow>,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl Default for DemandSettings {
    /// One hour; 300 through and 600 local trips per hour; no trade; seed 1.
    fn default() -> Self {
        DemandSettings {
            duration: 3600.0,
            through_per_hour: 300.0,
            local_per_hour: 600.0,
            seed: 1,
            trade_per_hour: 0.0,
            trade: Vec::new(),
        }
    }
}

pub use crate::grow::window::{TradeFile, TradeFlow};

/// Through or local traffic (also the SUMO vehicle type of the trip).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TripClass {
    /// Across the region, boundary to boundary.
    Through,
    /// Between interior points.
    Local,
    /// Along a trade flow, entrance to entrance.
    Trade,
}

impl TripClass {
    /// `through` or `local`.
    pub fn name(self) -> &'static str {
        match self {
            TripClass::Through => "through",
            TripClass::Local => "local",
            TripClass::Trade => "trade",
        }
    }
}

/// A trip as drawn, before it is placed on a design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Trip {
    /// `through<k>` or `local<k>`.
    pub id: String,
    /// Its class.
    pub class: TripClass,
    /// Departure time, seconds.
    pub depart: f64,
    /// Origin, metres.
    pub from: [f64; 2],
    /// Destination, metres.
    pub to: [f64; 2],
    /// Which way to drive on the origin street and the destination street (`true`: from the
    /// street's `a` to its `b`).
    pub forward: [bool; 2],
}

/// Draws the trips of a region (sorted by departure). The region is first made canonical
/// ([`Region::canonical`]), so designs of one site from different methods — whose rings may
/// start elsewhere, run the other way or differ below a millimetre — meet the same trips.
pub fn generate(region: &Region, s: &DemandSettings) -> Vec<Trip> {
    let region = &region.canonical();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(s.seed);
    let mut trips = Vec::new();
    let perimeter = closed_length(&region.boundary);
    if perimeter > 0.0 {
        for (k, depart) in poisson(&mut rng, s.through_per_hour, s.duration).into_iter().enumerate() {
            let u = rng.random::<f64>() * perimeter;
            let v = u + perimeter * (0.3 + 0.4 * rng.random::<f64>());
            let forward = [rng.random::<bool>(), rng.random::<bool>()];
            trips.push(Trip {
                id: format!("through{k}"),
                class: TripClass::Through,
                depart,
                from: at_arc(&region.boundary, u),
                to: at_arc(&region.boundary, v),
                forward,
            });
        }
    }
    let (lo, hi) = bounds(region.areas.iter().flatten());
    if lo[0] < hi[0] && lo[1] < hi[1] {
        for (k, depart) in poisson(&mut rng, s.local_per_hour, s.duration).into_iter().enumerate() {
            // Rejection sampling in the bounding box (given up on an area of measure zero).
            let mut point = || {
                (0..10_000).find_map(|_| {
                    let p =
                        [lo[0] + rng.random::<f64>() * (hi[0] - lo[0]), lo[1] + rng.random::<f64>() * (hi[1] - lo[1])];
                    region.areas.iter().any(|a| geom::ring_contains(a, p)).then_some(p)
                })
            };
            let (Some(from), Some(to)) = (point(), point()) else { break };
            let forward = [rng.random::<bool>(), rng.random::<bool>()];
            trips.push(Trip { id: format!("local{k}"), class: TripClass::Local, depart, from, to, forward });
        }
    }
    trips.extend(trade(s));
    trips.sort_by(|a, b| a.depart.total_cmp(&b.depart).then(a.class.cmp(&b.class)));
    trips
}

/// The trade trips: per flow in order, a Poisson process of its share of `trade_per_hour`, from
/// a generator of its own (so adding trade leaves the through and local trips as they were).
fn trade(s: &DemandSettings) -> Vec<Trip> {
    let total: f64 = s.trade.iter().map(|f| f.weight.max(0.0)).sum();
    let mut trips = Vec::new();
    if total.is_nan() || total <= 0.0 {
        return trips;
    }
    // "trade" in ASCII, mixed into the seed.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(s.seed ^ 0x74_7261_6465);
    for f in &s.trade {
        for depart in poisson(&mut rng, s.trade_per_hour * f.weight.max(0.0) / total, s.duration) {
            let id = format!("trade{}", trips.len());
            trips.push(Trip { id, class: TripClass::Trade, depart, from: f.from, to: f.to, forward: [true, true] });
        }
    }
    trips
}

/// Departure times of a Poisson process of `per_hour` in `[0, duration)`.
fn poisson(rng: &mut Xoshiro256PlusPlus, per_hour: f64, duration: f64) -> Vec<f64> {
    let mut out = Vec::new();
    if per_hour.is_nan() || per_hour <= 0.0 {
        return out;
    }
    let mut t = 0.0;
    loop {
        t += -(1.0 - rng.random::<f64>()).ln() * 3600.0 / per_hour;
        if t >= duration {
            return out;
        }
        out.push(t);
    }
}

fn bounds<'a>(pts: impl Iterator<Item = &'a [f64; 2]>) -> ([f64; 2], [f64; 2]) {
    pts.fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    })
}

fn closed_length(poly: &[[f64; 2]]) -> f64 {
    (0..poly.len()).map(|i| geom::dist(poly[i], poly[(i + 1) % poly.len()])).sum()
}

/// The point at arc length `s` (modulo the perimeter) along a closed polygon.
fn at_arc(poly: &[[f64; 2]], s: f64) -> [f64; 2] {
    let total = closed_length(poly);
    let mut s = s.rem_euclid(total);
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let l = geom::dist(a, b);
        if s <= l && l > 0.0 {
            let t = s / l;
            return [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        }
        s -= l;
    }
    poly[0]
}

/// Where one end of a trip is on a design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgePlace {
    /// The street (index into [`RoadNetwork::edges`]).
    pub edge: usize,
    /// Direction (`true`: from the street's `a` to its `b`).
    pub forward: bool,
    /// SUMO's edge id.
    pub sumo_edge: String,
    /// Position along the SUMO edge, metres.
    pub pos: f64,
}

/// Where one end of a trip is on a design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Place {
    /// A junction (through traffic).
    Junction {
        /// The node (index into [`RoadNetwork::nodes`]).
        node: usize,
        /// SUMO's junction id.
        sumo_node: String,
    },
    /// A point on a street (local traffic).
    Street(EdgePlace),
}

impl Place {
    fn key(&self) -> (bool, usize) {
        match self {
            Place::Junction { node, .. } => (true, *node),
            Place::Street(e) => (false, e.edge),
        }
    }

    /// The trip-file attributes of this end: `prefix` is `from`/`to`, `pos` is
    /// `departPos`/`arrivalPos`.
    fn attrs(&self, prefix: &str, pos: &str) -> String {
        match self {
            Place::Junction { sumo_node, .. } => format!(r#"{prefix}Junction="{sumo_node}""#),
            Place::Street(e) => format!(r#"{prefix}="{}" {pos}="{:.2}""#, e.sumo_edge, e.pos),
        }
    }
}

/// A trip placed on a design.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlacedTrip {
    /// Index into the trips.
    pub trip: usize,
    /// The trip's id.
    pub id: String,
    /// Its class.
    pub class: TripClass,
    /// Departure, seconds.
    pub depart: f64,
    /// Origin.
    pub from: Place,
    /// Destination.
    pub to: Place,
}

/// The trips of a design.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Placement {
    /// Trips with their ends at different places.
    pub trips: Vec<PlacedTrip>,
    /// Trips dropped because both ends fell on the same street or junction.
    pub same_place: usize,
    /// Trips dropped because the design has no street of the kind they need.
    pub no_street: usize,
}

/// The nearest street among `candidates` to `p`, and the arc-length fraction of the projection
/// along its shape (from its `a`).
fn nearest(net: &RoadNetwork, candidates: &[usize], p: [f64; 2]) -> Option<(usize, f64)> {
    let mut best: Option<(f64, usize, f64)> = None;
    for &k in candidates {
        let shape = &net.edges[k].shape;
        let total: f64 = shape.windows(2).map(|w| geom::dist(w[0], w[1])).sum();
        let mut arc = 0.0;
        for w in shape.windows(2) {
            let l = geom::dist(w[0], w[1]);
            let q = geom::closest_on_segment(p, w[0], w[1]).0;
            let d = geom::dist(p, q);
            if best.is_none_or(|(bd, _, _)| d < bd) {
                let f = if total > 0.0 { (arc + geom::dist(w[0], q)) / total } else { 0.0 };
                best = Some((d, k, f));
            }
            arc += l;
        }
    }
    best.map(|(_, k, f)| (k, f))
}

/// Places the trips on a design, with positions on SUMO's edges (`sumo_net`'s lengths).
pub fn place(trips: &[Trip], net: &RoadNetwork, sumo_net: &SumoNet) -> Placement {
    let gates: Vec<usize> = (0..net.nodes.len()).filter(|&k| net.nodes[k].entrance).collect();
    let locals: Vec<usize> = (0..net.edges.len()).filter(|&k| net.edges[k].local).collect();
    let gate = |p: [f64; 2]| {
        let k = *gates
            .iter()
            .min_by(|&&a, &&b| geom::dist(p, net.nodes[a].pos).total_cmp(&geom::dist(p, net.nodes[b].pos)))?;
        Some(Place::Junction { node: k, sumo_node: node_id(net.nodes[k].id) })
    };
    let street = |p: [f64; 2], forward: bool| {
        let (k, f) = nearest(net, &locals, p)?;
        let id = edge_id(net.edges[k].id, forward);
        let len = sumo_net.edges.get(&id).map_or_else(|| net.edges[k].length(), |e| e.length);
        let frac = if forward { f } else { 1.0 - f };
        Some(Place::Street(EdgePlace {
            edge: k,
            forward,
            sumo_edge: id,
            pos: (frac * len).clamp(0.0, (len - 0.1).max(0.0)),
        }))
    };
    let mut out = Placement::default();
    for (i, t) in trips.iter().enumerate() {
        let ends = match t.class {
            TripClass::Through | TripClass::Trade => (gate(t.from), gate(t.to)),
            TripClass::Local => (street(t.from, t.forward[0]), street(t.to, t.forward[1])),
        };
        let (Some(from), Some(to)) = ends else {
            out.no_street += 1;
            continue;
        };
        if from.key() == to.key() {
            out.same_place += 1;
            continue;
        }
        out.trips.push(PlacedTrip { trip: i, id: t.id.clone(), class: t.class, depart: t.depart, from, to });
    }
    out
}

/// The trips as a SUMO trip file (vehicle types `through`, `local` and `trade`, all default passenger
/// cars), sorted by departure.
pub fn trips_xml(p: &Placement) -> String {
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<routes>\n");
    for c in [TripClass::Through, TripClass::Local, TripClass::Trade] {
        let _ = writeln!(s, r#"    <vType id="{}" vClass="passenger"/>"#, c.name());
    }
    for t in &p.trips {
        let _ = writeln!(
            s,
            r#"    <trip id="{}" type="{}" depart="{:.2}" {} {} departLane="best"/>"#,
            t.id,
            t.class.name(),
            t.depart,
            t.from.attrs("from", "departPos"),
            t.to.attrs("to", "arrivalPos")
        );
    }
    s.push_str("</routes>\n");
    s
}
