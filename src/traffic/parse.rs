//! Reading SUMO's files: the `.net.xml` (edge lengths), the route file (vehicles routed),
//! `tripinfo`, `edgedata`, `vehroute` and `statistic` outputs. XML is parsed with `roxmltree`
//! (already in the build through `resvg`); every error names the file.

use super::{read, TrafficError, TrafficErrorKind};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;
use std::str::FromStr;

fn bad(path: &Path, what: &'static str, message: impl Into<String>) -> TrafficError {
    TrafficError::new(path, TrafficErrorKind::Parse { what, message: message.into() })
}

/// Parses `path` and hands the document to `f`.
fn with_doc<T>(
    path: &Path,
    what: &'static str,
    f: impl FnOnce(&roxmltree::Document) -> Result<T, String>,
) -> Result<T, TrafficError> {
    let text = read(path)?;
    let opts = roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() };
    let doc = roxmltree::Document::parse_with_options(&text, opts).map_err(|e| bad(path, what, e.to_string()))?;
    f(&doc).map_err(|m| bad(path, what, m))
}

fn attr<T: FromStr>(n: roxmltree::Node, name: &str) -> Result<T, String> {
    let v = n
        .attribute(name)
        .ok_or_else(|| format!("<{}> at byte {} has no `{name}`", n.tag_name().name(), n.range().start))?;
    v.parse()
        .map_err(|_| format!("<{}> at byte {}: `{name}` = {v:?} is not a number", n.tag_name().name(), n.range().start))
}

fn attr_or<T: FromStr>(n: roxmltree::Node, name: &str, default: T) -> Result<T, String> {
    if n.has_attribute(name) {
        attr(n, name)
    } else {
        Ok(default)
    }
}

fn elements<'a, 'i>(
    doc: &'a roxmltree::Document<'i>,
    tag: &'a str,
) -> impl Iterator<Item = roxmltree::Node<'a, 'i>> + 'a {
    doc.descendants().filter(move |n| n.is_element() && n.tag_name().name() == tag)
}

/// A `.net.xml`: its normal (non-internal) edges and its junctions.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SumoNet {
    /// Edge id → lanes, length, speed.
    pub edges: BTreeMap<String, NetEdge>,
    /// Junctions that are not internal.
    pub junctions: usize,
}

/// One edge of a `.net.xml`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NetEdge {
    /// `from` junction.
    pub from: String,
    /// `to` junction.
    pub to: String,
    /// Its type.
    pub edge_type: String,
    /// Lanes.
    pub lanes: usize,
    /// Length of its first lane, metres.
    pub length: f64,
    /// Speed limit of its first lane, m/s.
    pub speed: f64,
}

/// Reads a `.net.xml`.
pub fn net(path: &Path) -> Result<SumoNet, TrafficError> {
    with_doc(path, "a SUMO network", |doc| {
        let mut out = SumoNet::default();
        for e in elements(doc, "edge").filter(|e| e.attribute("function").is_none()) {
            let lanes: Vec<_> = e.children().filter(|c| c.is_element() && c.tag_name().name() == "lane").collect();
            let first = lanes.first().ok_or_else(|| format!("edge {:?} has no lane", e.attribute("id")))?;
            out.edges.insert(
                attr(e, "id")?,
                NetEdge {
                    from: attr(e, "from")?,
                    to: attr(e, "to")?,
                    edge_type: attr_or(e, "type", String::new())?,
                    lanes: lanes.len(),
                    length: attr(*first, "length")?,
                    speed: attr(*first, "speed")?,
                },
            );
        }
        out.junctions = elements(doc, "junction").filter(|j| j.attribute("type") != Some("internal")).count();
        Ok(out)
    })
}

/// Vehicles in a route file (`duarouter`'s output).
pub fn route_count(path: &Path) -> Result<usize, TrafficError> {
    with_doc(path, "a SUMO route file", |doc| Ok(elements(doc, "vehicle").count()))
}

/// One vehicle's `tripinfo` (written when it arrives).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TripInfo {
    /// Vehicle id.
    pub id: String,
    /// Vehicle type (`through` or `local`).
    pub vtype: String,
    /// Departure, s.
    pub depart: f64,
    /// Arrival, s.
    pub arrival: f64,
    /// Travel time, s.
    pub duration: f64,
    /// Distance driven, m.
    pub route_length: f64,
    /// Time spent standing (speed < 0.1 m/s), s.
    pub waiting_time: f64,
    /// Time lost against driving at the ideal speed, s.
    pub time_loss: f64,
    /// Delay between the planned departure and the insertion, s.
    pub depart_delay: f64,
}

/// Reads a `tripinfo` output.
pub fn tripinfos(path: &Path) -> Result<Vec<TripInfo>, TrafficError> {
    with_doc(path, "a SUMO tripinfo output", |doc| {
        elements(doc, "tripinfo")
            .map(|t| {
                Ok(TripInfo {
                    id: attr(t, "id")?,
                    vtype: attr_or(t, "vType", String::new())?,
                    depart: attr(t, "depart")?,
                    arrival: attr(t, "arrival")?,
                    duration: attr(t, "duration")?,
                    route_length: attr(t, "routeLength")?,
                    waiting_time: attr(t, "waitingTime")?,
                    time_loss: attr(t, "timeLoss")?,
                    depart_delay: attr_or(t, "departDelay", 0.0)?,
                })
            })
            .collect()
    })
}

/// Traffic on one edge (summed over the output's intervals).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EdgeData {
    /// Vehicles that started here.
    pub departed: f64,
    /// Vehicles that drove onto it.
    pub entered: f64,
    /// Vehicles that ended here.
    pub arrived: f64,
    /// Vehicle-seconds spent on it.
    pub sampled_seconds: f64,
}

impl EdgeData {
    /// Vehicles that used the edge: started on it or drove onto it.
    pub fn volume(&self) -> f64 {
        self.departed + self.entered
    }
}

/// Reads an `edgedata` output.
pub fn edgedata(path: &Path) -> Result<BTreeMap<String, EdgeData>, TrafficError> {
    with_doc(path, "a SUMO edgedata output", |doc| {
        let mut out: BTreeMap<String, EdgeData> = BTreeMap::new();
        for e in elements(doc, "edge") {
            let d = out.entry(attr(e, "id")?).or_default();
            d.departed += attr_or(e, "departed", 0.0)?;
            d.entered += attr_or(e, "entered", 0.0)?;
            d.arrived += attr_or(e, "arrived", 0.0)?;
            d.sampled_seconds += attr_or(e, "sampledSeconds", 0.0)?;
        }
        Ok(out)
    })
}

/// Reads a `vehroute` output: vehicle id → its (last) route's edges.
pub fn vehroutes(path: &Path) -> Result<BTreeMap<String, Vec<String>>, TrafficError> {
    with_doc(path, "a SUMO vehroute output", |doc| {
        let mut out = BTreeMap::new();
        for v in elements(doc, "vehicle") {
            let route = v
                .descendants()
                .rfind(|c| c.is_element() && c.tag_name().name() == "route")
                .ok_or_else(|| format!("vehicle {:?} has no route", v.attribute("id")))?;
            let edges: String = attr(route, "edges")?;
            out.insert(attr(v, "id")?, edges.split_whitespace().map(str::to_string).collect());
        }
        Ok(out)
    })
}

/// A `statistic-output`'s vehicle counts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Statistics {
    /// Vehicles loaded.
    pub loaded: u64,
    /// Vehicles inserted into the network.
    pub inserted: u64,
    /// Vehicles still driving when the simulation ended.
    pub running: u64,
    /// Vehicles still waiting to be inserted when it ended.
    pub waiting: u64,
    /// Teleports (a vehicle stuck for 300 s is moved ahead).
    pub teleports: u64,
}

/// Reads a `statistic-output`.
pub fn statistics(path: &Path) -> Result<Statistics, TrafficError> {
    with_doc(path, "a SUMO statistic output", |doc| {
        let v = elements(doc, "vehicles").next().ok_or("no <vehicles>")?;
        let t = elements(doc, "teleports").next().ok_or("no <teleports>")?;
        Ok(Statistics {
            loaded: attr(v, "loaded")?,
            inserted: attr(v, "inserted")?,
            running: attr(v, "running")?,
            waiting: attr(v, "waiting")?,
            teleports: attr(t, "total")?,
        })
    })
}
