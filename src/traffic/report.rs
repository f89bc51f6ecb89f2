//! The result of one evaluation (`traffic.json`), its one-screen summary, and the comparison
//! table of several designs.
//!
//! Travel time is `tripinfo`'s `duration` (insertion to arrival) of every vehicle that
//! arrived; the 95th percentile is the nearest-rank one (the value at rank ⌈0.95·n⌉ of the
//! sorted times). Route length is `routeLength`, waiting time `waitingTime` (time standing).
//! The share of through traffic on local streets is measured on the routes as driven
//! (`vehroute` output) of through vehicles that arrived, over whole edges (`.net.xml` lane
//! lengths): the share of their distance on levels ≥ 3 (local streets and cul-de-sacs), and
//! the share of them that used any such street; trade vehicles count as through traffic there.
//! For a design whose streets carry a generator's predicted loads (a grown network), the
//! predictions are ranked against SUMO's volumes ([`spearman`]).

use super::demand::{Placement, Trip, TripClass};
use super::export::{parse_edge_id, road_types, RoadType};
use super::network::{Provenance, RoadNetwork};
use super::parse::{self, SumoNet};
use super::sumo::{SimOutputs, Sumo};
use super::{DemandSettings, TrafficError, TrafficErrorKind};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Version of the traffic report schema (`traffic.json`).
pub const TRAFFIC_SCHEMA_VERSION: u32 = 1;

/// Everything about one evaluation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrafficReport {
    /// Always `netspec.traffic`.
    pub schema: String,
    /// [`TRAFFIC_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The netspec version.
    pub netspec_version: String,
    /// The design's name.
    pub name: String,
    /// Which run produced the design.
    pub source: Provenance,
    /// `sumo --version`.
    pub sumo_version: String,
    /// The network as exported and as `netconvert` built it.
    pub network: NetworkSummary,
    /// The road type of each level.
    pub road_types: Vec<RoadType>,
    /// The demand.
    pub demand: DemandSummary,
    /// Vehicle counts.
    pub vehicles: VehicleCounts,
    /// Every vehicle that arrived.
    pub all: ClassStats,
    /// Through traffic.
    pub through: ClassStats,
    /// Local traffic.
    pub local: ClassStats,
    /// Trade traffic (none without trade flows).
    #[serde(default)]
    pub trade: ClassStats,
    /// How much through and trade traffic used local streets.
    pub through_on_local: LocalShare,
    /// How the loads a generator predicted (a grown network's segment traffic) rank against
    /// SUMO's; absent for designs without predictions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub predicted_loads: Option<PredictedLoads>,
    /// Vehicles per street and direction.
    pub edge_volumes: Vec<EdgeVolume>,
    /// Travel times of the vehicles that arrived, s, per class (for histograms).
    pub travel_times: BTreeMap<String, Vec<f64>>,
    /// Wall time of each step, s.
    pub timings: Timings,
}

/// Sizes of the network.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NetworkSummary {
    /// Nodes exported.
    pub nodes: usize,
    /// Streets exported (each two SUMO edges).
    pub streets: usize,
    /// Streets per level 1–4.
    pub streets_per_level: [usize; 4],
    /// Street length per level 1–4, km.
    pub km_per_level: [f64; 4],
    /// Streets whose two edges are both in the `.net.xml`.
    pub streets_in_net: usize,
    /// Normal edges in the `.net.xml`.
    pub sumo_edges: usize,
    /// Junctions in the `.net.xml`.
    pub sumo_junctions: usize,
    /// Area of the region served, km².
    #[serde(default)]
    pub area_km2: f64,
    /// Nodes where three or more streets meet.
    #[serde(default)]
    pub intersections: usize,
    /// Nodes with one street that are not entrances (dead ends).
    #[serde(default)]
    pub dead_ends: usize,
}

/// The demand as drawn and as routed.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DemandSummary {
    /// The settings.
    pub settings: DemandSettings,
    /// A digest of the drawn trips (places and times): equal digests, equal demand.
    pub digest: String,
    /// Through trips drawn.
    pub through_drawn: usize,
    /// Local trips drawn.
    pub local_drawn: usize,
    /// Trade trips drawn.
    #[serde(default)]
    pub trade_drawn: usize,
    /// Dropped: both ends at one street or junction.
    pub same_place: usize,
    /// Dropped: no street of the kind needed.
    pub no_street: usize,
    /// Trips placed on the design.
    pub placed: usize,
    /// Trips `duarouter` found a route for.
    pub routed: usize,
}

/// Vehicle counts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct VehicleCounts {
    /// Loaded from the routes.
    pub loaded: u64,
    /// Inserted into the network.
    pub inserted: u64,
    /// Arrived (a `tripinfo` each).
    pub arrived: u64,
    /// Teleports.
    pub teleported: u64,
    /// Still driving when the simulation ended.
    pub running_at_end: u64,
    /// Never inserted.
    pub waiting_at_end: u64,
}

/// Statistics of the vehicles of one class that arrived.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ClassStats {
    /// Vehicles.
    pub vehicles: usize,
    /// Mean travel time, s.
    pub travel_time_mean: Option<f64>,
    /// 95th-percentile travel time (nearest rank), s.
    pub travel_time_p95: Option<f64>,
    /// Mean route length, m.
    pub route_length_mean: Option<f64>,
    /// Mean waiting time, s.
    pub waiting_time_mean: Option<f64>,
    /// Mean time loss, s.
    pub time_loss_mean: Option<f64>,
}

/// Loads a generator predicted against SUMO's, per street: Spearman rank correlations over the
/// streets with a prediction (ties ranked by their mean rank).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PredictedLoads {
    /// Streets with a predicted load.
    pub streets: usize,
    /// Against every vehicle on the street (both directions).
    pub spearman_all: Option<f64>,
    /// Against the trade vehicles that drove on the street (the traffic the generator models).
    pub spearman_trade: Option<f64>,
    /// Streets with a positive prediction (the generator's loaded roads).
    #[serde(default)]
    pub loaded_streets: usize,
    /// Over those alone, against the trade vehicles: whether the generator ranks its own roads
    /// as SUMO loads them.
    #[serde(default)]
    pub spearman_loaded: Option<f64>,
}

/// Through and trade traffic on local streets (levels ≥ 3).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LocalShare {
    /// Through and trade vehicles measured (arrived, with a route).
    pub vehicles: usize,
    /// Their vehicle-kilometres on each level 1–4.
    pub km_by_level: [f64; 4],
    /// Share of their distance on local streets.
    pub distance_share: Option<f64>,
    /// Share of them that used a local street.
    pub vehicle_share: Option<f64>,
}

/// Vehicles that used one street, per direction (`departed + entered` of SUMO's edge data).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgeVolume {
    /// The street's design id.
    pub street: u32,
    /// Its level.
    pub level: u8,
    /// From its `a` to its `b`.
    pub forward: f64,
    /// Back.
    pub backward: f64,
}

/// Wall time per step, s.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Timings {
    /// Reading the design (and, for a city, merging and smoothing its streets), if the caller
    /// measured it.
    pub load: f64,
    /// Writing the plain XML.
    pub export: f64,
    /// `netconvert`.
    pub netconvert: f64,
    /// Drawing and placing the demand, `duarouter`.
    pub routing: f64,
    /// `sumo`.
    pub simulation: f64,
    /// Reading SUMO's outputs.
    pub parse: f64,
    /// The whole evaluation (with `load`).
    pub total: f64,
}

/// Mean of a list (`None` if empty).
pub fn mean(v: &[f64]) -> Option<f64> {
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// Nearest-rank percentile `q` ∈ (0, 1] of a list (`None` if empty).
pub fn percentile(v: &[f64], q: f64) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let rank = ((q * s.len() as f64).ceil() as usize).clamp(1, s.len());
    Some(s[rank - 1])
}

/// Statistics of a set of trips.
pub fn class_stats(trips: &[&parse::TripInfo]) -> ClassStats {
    let col = |f: fn(&parse::TripInfo) -> f64| trips.iter().map(|t| f(t)).collect::<Vec<f64>>();
    let tt = col(|t| t.duration);
    ClassStats {
        vehicles: trips.len(),
        travel_time_mean: mean(&tt),
        travel_time_p95: percentile(&tt, 0.95),
        route_length_mean: mean(&col(|t| t.route_length)),
        waiting_time_mean: mean(&col(|t| t.waiting_time)),
        time_loss_mean: mean(&col(|t| t.time_loss)),
    }
}

/// A digest of drawn trips.
pub fn demand_digest(trips: &[Trip]) -> String {
    crate::io::digest(&[serde_json::to_string(trips).expect("trips serialise").as_bytes()])
}

/// Reads SUMO's outputs and assembles the report (timings are the caller's).
#[allow(clippy::too_many_arguments)]
pub fn build(
    net: &RoadNetwork,
    settings: &DemandSettings,
    sumo: &Sumo,
    sumo_net: &SumoNet,
    trips: &[Trip],
    placed: &Placement,
    routed: usize,
    out: &SimOutputs,
) -> Result<TrafficReport, TrafficError> {
    let infos = parse::tripinfos(&out.tripinfo)?;
    let stats = parse::statistics(&out.statistics)?;
    let edata = parse::edgedata(&out.edgedata)?;
    let routes = parse::vehroutes(&out.vehroutes)?;
    let class_of: BTreeMap<&str, TripClass> = placed.trips.iter().map(|t| (t.id.as_str(), t.class)).collect();
    for t in &infos {
        if !class_of.contains_key(t.id.as_str()) {
            return Err(TrafficError::new(
                &out.tripinfo,
                TrafficErrorKind::Output(format!("vehicle {:?} is not one of the trips written", t.id)),
            ));
        }
    }
    let of = |c: Option<TripClass>| -> Vec<&parse::TripInfo> {
        infos.iter().filter(|t| c.is_none_or(|c| class_of[t.id.as_str()] == c)).collect()
    };

    let street_of: BTreeMap<u32, usize> = net.edges.iter().enumerate().map(|(k, e)| (e.id, k)).collect();
    let (mut local_m, mut total_m, mut used_local, mut measured) = (0.0, 0.0, 0usize, 0usize);
    let mut km_by_level = [0.0; 4];
    // Trade vehicles per street, for the predicted loads.
    let mut trade_count: BTreeMap<usize, f64> = BTreeMap::new();
    for t in infos.iter().filter(|t| class_of[t.id.as_str()] != TripClass::Local) {
        let Some(edges) = routes.get(&t.id) else { continue };
        let trade = class_of[t.id.as_str()] == TripClass::Trade;
        measured += 1;
        let mut any = false;
        for e in edges {
            let (Some((id, _)), Some(ne)) = (parse_edge_id(e), sumo_net.edges.get(e)) else { continue };
            let Some(&k) = street_of.get(&id) else { continue };
            if trade {
                *trade_count.entry(k).or_default() += 1.0;
            }
            total_m += ne.length;
            km_by_level[(net.edges[k].level.clamp(1, 4) - 1) as usize] += ne.length / 1000.0;
            if net.edges[k].level >= 3 {
                local_m += ne.length;
                any = true;
            }
        }
        used_local += usize::from(any);
    }
    let through_on_local = LocalShare {
        vehicles: measured,
        km_by_level,
        distance_share: (total_m > 0.0).then(|| local_m / total_m),
        vehicle_share: (measured > 0).then(|| used_local as f64 / measured as f64),
    };

    let mut summary = NetworkSummary {
        nodes: net.nodes.len(),
        streets: net.edges.len(),
        sumo_edges: sumo_net.edges.len(),
        sumo_junctions: sumo_net.junctions,
        area_km2: net.region.areas.iter().map(|a| crate::geometry::ring_area2(a).abs() / 2.0).sum::<f64>() / 1e6,
        ..Default::default()
    };
    let mut degree = vec![0usize; net.nodes.len()];
    for e in &net.edges {
        degree[e.a] += 1;
        degree[e.b] += 1;
    }
    let entrances: Vec<bool> = net.nodes.iter().map(|n| n.entrance).collect();
    let nodes = crate::stats::yang::valence_nodes(&degree, &entrances);
    (summary.intersections, summary.dead_ends) = (nodes.intersections, nodes.dead_ends);
    let vol = |id: String| edata.get(&id).map_or(0.0, |d| d.volume());
    let mut edge_volumes = Vec::new();
    for e in &net.edges {
        let l = (e.level.clamp(1, 4) - 1) as usize;
        summary.streets_per_level[l] += 1;
        summary.km_per_level[l] += e.length() / 1000.0;
        let (f, b) = (super::export::edge_id(e.id, true), super::export::edge_id(e.id, false));
        summary.streets_in_net +=
            usize::from(sumo_net.edges.contains_key(&f) && (e.oneway || sumo_net.edges.contains_key(&b)));
        edge_volumes.push(EdgeVolume { street: e.id, level: e.level, forward: vol(f), backward: vol(b) });
    }
    let predicted: Vec<(f64, f64, f64)> = net
        .edges
        .iter()
        .zip(&edge_volumes)
        .enumerate()
        .filter_map(|(k, (e, v))| {
            Some((e.predicted_load?, v.forward + v.backward, trade_count.get(&k).copied().unwrap_or(0.0)))
        })
        .collect();
    let predicted_loads = (!predicted.is_empty()).then(|| {
        let p: Vec<f64> = predicted.iter().map(|t| t.0).collect();
        let loaded: Vec<&(f64, f64, f64)> = predicted.iter().filter(|t| t.0 > 0.0).collect();
        PredictedLoads {
            streets: predicted.len(),
            spearman_all: spearman(&p, &predicted.iter().map(|t| t.1).collect::<Vec<_>>()),
            spearman_trade: spearman(&p, &predicted.iter().map(|t| t.2).collect::<Vec<_>>()),
            loaded_streets: loaded.len(),
            spearman_loaded: spearman(
                &loaded.iter().map(|t| t.0).collect::<Vec<_>>(),
                &loaded.iter().map(|t| t.2).collect::<Vec<_>>(),
            ),
        }
    });
    let mut travel_times = BTreeMap::new();
    for c in [TripClass::Through, TripClass::Local, TripClass::Trade] {
        travel_times.insert(c.name().to_string(), of(Some(c)).iter().map(|t| t.duration).collect());
    }
    let count = |c: TripClass| trips.iter().filter(|t| t.class == c).count();
    Ok(TrafficReport {
        schema: "netspec.traffic".into(),
        schema_version: TRAFFIC_SCHEMA_VERSION,
        netspec_version: env!("CARGO_PKG_VERSION").into(),
        name: net.name.clone(),
        source: net.source.clone(),
        sumo_version: sumo.version.clone(),
        network: summary,
        road_types: road_types(),
        demand: DemandSummary {
            settings: settings.clone(),
            digest: demand_digest(trips),
            through_drawn: count(TripClass::Through),
            local_drawn: count(TripClass::Local),
            trade_drawn: count(TripClass::Trade),
            same_place: placed.same_place,
            no_street: placed.no_street,
            placed: placed.trips.len(),
            routed,
        },
        vehicles: VehicleCounts {
            loaded: stats.loaded,
            inserted: stats.inserted,
            arrived: infos.len() as u64,
            teleported: stats.teleports,
            running_at_end: stats.running,
            waiting_at_end: stats.waiting,
        },
        all: class_stats(&of(None)),
        through: class_stats(&of(Some(TripClass::Through))),
        local: class_stats(&of(Some(TripClass::Local))),
        trade: class_stats(&of(Some(TripClass::Trade))),
        through_on_local,
        predicted_loads,
        edge_volumes,
        travel_times,
        timings: Timings::default(),
    })
}

/// Ranks with ties at their mean rank (1-based).
fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && v[order[j + 1]] == v[order[i]] {
            j += 1;
        }
        for &k in &order[i..=j] {
            r[k] = (i + j) as f64 / 2.0 + 1.0;
        }
        i = j + 1;
    }
    r
}

/// Spearman's rank correlation of `x` and `y` (Pearson's on tie-averaged ranks); `None` with
/// fewer than three values or when either is constant.
pub fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    if x.len() != y.len() || x.len() < 3 {
        return None;
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let mean = (x.len() as f64 + 1.0) / 2.0;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        sxy += (a - mean) * (b - mean);
        sxx += (a - mean) * (a - mean);
        syy += (b - mean) * (b - mean);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

fn num(v: Option<f64>, digits: usize) -> String {
    v.map_or("-".into(), |v| format!("{v:.digits$}"))
}

fn pct(v: Option<f64>) -> String {
    v.map_or("-".into(), |v| format!("{:.1}%", 100.0 * v))
}

impl TrafficReport {
    /// Writes the report as `dir/traffic.json`.
    pub fn write(&self, dir: &std::path::Path) -> Result<(), TrafficError> {
        super::write(
            &dir.join("traffic.json"),
            &(serde_json::to_string_pretty(self).expect("reports serialise") + "\n"),
        )
    }

    /// A few lines for the terminal.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        let n = &self.network;
        let d = &self.demand;
        let v = &self.vehicles;
        let _ = writeln!(s, "design     {} ({} {})", self.name, self.source.kind, self.source.path);
        let _ = writeln!(
            s,
            "network    {} nodes, {} streets (levels 1–4: {:?}), {:.2} km; netconvert: {} edges, {} junctions, {}/{} streets present",
            n.nodes,
            n.streets,
            n.streets_per_level,
            n.km_per_level.iter().sum::<f64>(),
            n.sumo_edges,
            n.sumo_junctions,
            n.streets_in_net,
            n.streets
        );
        let _ = writeln!(
            s,
            "demand     {:.0} s, {:.0} through + {:.0} local per hour, seed {} (digest {}): drawn {} + {}, dropped {} same place + {} no street, routed {}/{}",
            d.settings.duration, d.settings.through_per_hour, d.settings.local_per_hour, d.settings.seed, d.digest, d.through_drawn, d.local_drawn, d.same_place, d.no_street, d.routed, d.placed
        );
        let _ = writeln!(
            s,
            "vehicles   inserted {}, arrived {}, teleported {}, still running {}, never inserted {}",
            v.inserted, v.arrived, v.teleported, v.running_at_end, v.waiting_at_end
        );
        if d.trade_drawn > 0 {
            let _ = writeln!(
                s,
                "trade      {:.0} per hour over {} flows: drawn {}",
                d.settings.trade_per_hour,
                d.settings.trade.len(),
                d.trade_drawn
            );
        }
        let mut classes = vec![("all", &self.all), ("through", &self.through), ("local", &self.local)];
        if d.trade_drawn > 0 {
            classes.push(("trade", &self.trade));
        }
        for (label, c) in classes {
            let _ = writeln!(
                s,
                "{label:<10} {} vehicles: travel time mean {} s, p95 {} s; route {} m; waiting {} s",
                c.vehicles,
                num(c.travel_time_mean, 1),
                num(c.travel_time_p95, 1),
                num(c.route_length_mean, 0),
                num(c.waiting_time_mean, 1)
            );
        }
        let l = &self.through_on_local;
        let km: f64 = l.km_by_level.iter().sum();
        let share = |k: usize| pct((km > 0.0).then(|| l.km_by_level[k] / km));
        let _ = writeln!(
            s,
            "through    (and trade) on local streets: {} of the distance, {} of the vehicles ({} measured); distance by level 1–4: {} / {} / {} / {}",
            pct(l.distance_share),
            pct(l.vehicle_share),
            l.vehicles,
            share(0),
            share(1),
            share(2),
            share(3)
        );
        if let Some(p) = &self.predicted_loads {
            let _ = writeln!(
                s,
                "predicted  loads against SUMO's over {} streets: Spearman {} (all vehicles), {} (trade); over the {} loaded ones {} (trade)",
                p.streets,
                num(p.spearman_all, 2),
                num(p.spearman_trade, 2),
                p.loaded_streets,
                num(p.spearman_loaded, 2)
            );
        }
        let t = &self.timings;
        let _ = writeln!(
            s,
            "time       {:.2} s: load {:.2}, export {:.2}, netconvert {:.2}, demand + duarouter {:.2}, sumo {:.2}, parse {:.2} (SUMO {})",
            t.total, t.load, t.export, t.netconvert, t.routing, t.simulation, t.parse, self.sumo_version
        );
        s
    }
}

/// A Markdown table comparing designs (same demand where the digests agree).
pub fn comparison_markdown(rows: &[(String, &TrafficReport)]) -> String {
    let mut s = String::new();
    let digests: std::collections::BTreeSet<&str> = rows.iter().map(|(_, r)| r.demand.digest.as_str()).collect();
    if let Some((_, r)) = rows.first() {
        let d = &r.demand.settings;
        let _ = writeln!(
            s,
            "Demand: {:.0} s of departures, {:.0} through + {:.0} local trips per hour, seed {}; {}. SUMO {}.\n",
            d.duration,
            d.through_per_hour,
            d.local_per_hour,
            d.seed,
            if digests.len() == 1 {
                "the same trips (places and times) for every design".to_string()
            } else {
                format!("NOT the same trips: {} different demand digests (different regions)", digests.len())
            },
            r.sumo_version
        );
    }
    s.push_str("| design | streets (L1/L2/L3/L4) | km | inserted | arrived | teleported | travel time mean / p95 (s) | route mean (m) | waiting mean (s) | through: travel time mean (s) | through on collectors (distance) | through on local streets: distance / vehicles | local: travel time mean (s) | wall time (s) |\n");
    s.push_str("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (label, r) in rows {
        let n = &r.network;
        let _ = writeln!(
            s,
            "| {label} | {} ({}) | {:.2} | {} | {} | {} | {} / {} | {} | {} | {} | {} | {} / {} | {} | {:.1} |",
            n.streets,
            n.streets_per_level.iter().map(|c| c.to_string()).collect::<Vec<_>>().join("/"),
            n.km_per_level.iter().sum::<f64>(),
            r.vehicles.inserted,
            r.vehicles.arrived,
            r.vehicles.teleported,
            num(r.all.travel_time_mean, 1),
            num(r.all.travel_time_p95, 1),
            num(r.all.route_length_mean, 0),
            num(r.all.waiting_time_mean, 1),
            num(r.through.travel_time_mean, 1),
            pct({
                let k = &r.through_on_local.km_by_level;
                let total: f64 = k.iter().sum();
                (total > 0.0).then(|| k[1] / total)
            }),
            pct(r.through_on_local.distance_share),
            pct(r.through_on_local.vehicle_share),
            num(r.local.travel_time_mean, 1),
            r.timings.total
        );
    }
    s.push_str("\nWhich run produced each design:\n\n");
    for (label, r) in rows {
        let _ =
            writeln!(s, "- **{label}**: `{}` ({}, netspec {})", r.source.path, r.source.kind, r.source.netspec_version);
        for line in &r.source.runs {
            let _ = writeln!(s, "  - {line}");
        }
    }
    s
}
