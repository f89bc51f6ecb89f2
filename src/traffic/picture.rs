//! The pictures of traffic evaluations: a [`RoadNetwork`] and its [`TrafficReport`] as the plain
//! scenes of [`crate::render::traffic`] (the network coloured by traffic volume per street, the
//! travel-time histogram, the comparison of several designs).

use super::report::TrafficReport;
use super::RoadNetwork;
use crate::render::traffic::{self as draw, TrafficNumbers, VolumeScene, VolumeStreet};

/// The numbers of `r` that the pictures show.
pub fn numbers(r: &TrafficReport) -> TrafficNumbers {
    let d = &r.demand.settings;
    TrafficNumbers {
        name: r.name.clone(),
        sumo_version: r.sumo_version.clone(),
        duration: d.duration,
        through_per_hour: d.through_per_hour,
        local_per_hour: d.local_per_hour,
        seed: d.seed,
        inserted: r.vehicles.inserted,
        arrived: r.vehicles.arrived,
        teleported: r.vehicles.teleported,
        travel_time_mean: r.all.travel_time_mean,
        travel_time_p95: r.all.travel_time_p95,
        waiting_time_mean: r.all.waiting_time_mean,
        through_travel_time_mean: r.through.travel_time_mean,
        local_travel_time_mean: r.local.travel_time_mean,
        through_local_distance_share: r.through_on_local.distance_share,
        through_km_by_level: r.through_on_local.km_by_level,
        travel_times: r.travel_times.clone(),
    }
}

/// The network and its traffic volume per street (both directions), framed around the region's
/// boundary and the nodes.
pub fn volume_scene(net: &RoadNetwork, r: &TrafficReport) -> VolumeScene {
    let pts = net.region.boundary.iter().chain(net.nodes.iter().map(|n| &n.pos));
    let bounds = pts.fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    });
    VolumeScene {
        numbers: numbers(r),
        bounds,
        boundary: net.region.boundary.clone(),
        streets: net.edges.iter().map(|e| VolumeStreet { id: e.id, level: e.level, shape: e.shape.clone() }).collect(),
        volumes: r.edge_volumes.iter().map(|v| v.forward + v.backward).collect(),
    }
}

/// The network, every street coloured by the vehicles that used it (both directions) and drawn
/// as wide as its level; the title gives the demand and the main results.
pub fn volume_svg(net: &RoadNetwork, r: &TrafficReport) -> String {
    draw::volume_svg(&volume_scene(net, r))
}

/// Travel times of the vehicles that arrived, through and local traffic stacked, with the mean
/// and the 95th percentile marked.
pub fn histogram_svg(r: &TrafficReport) -> String {
    draw::histogram_svg(&numbers(r))
}

/// Several designs under one demand: the travel-time distribution of each next to bars of key
/// numbers ([`crate::render::traffic::comparison_svg`]).
pub fn comparison_svg(rows: &[(String, &TrafficReport)]) -> String {
    let numbers: Vec<(String, TrafficNumbers)> = rows.iter().map(|(l, r)| (l.clone(), numbers(r))).collect();
    let rows: Vec<(String, &TrafficNumbers)> = numbers.iter().map(|(l, n)| (l.clone(), n)).collect();
    draw::comparison_svg(&rows)
}
