//! SUMO plain XML of a [`RoadNetwork`] (nodes, edges, one road type per level), for SUMO's own
//! `netconvert`; and the GeoJSON of a `solve` design through the city's street GeoJSON writer.
//!
//! Every design vertex with a street is one node `n<id>`; every street is two edges, `e<id>`
//! from its `a` to its `b` and `-e<id>` back (SUMO's convention for the opposite direction),
//! with the street's shape (reversed for `-e<id>`) and the type `L<level>`. Coordinates are
//! local metres, which is what SUMO wants.

use super::network::RoadNetwork;
use super::{write, TrafficError};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A SUMO road type: the lanes, speed limit and right-of-way priority of one level.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoadType {
    /// The level (1 major road … 4 cul-de-sac).
    pub level: u8,
    /// SUMO type id (`L<level>`).
    pub id: String,
    /// What it is.
    pub name: String,
    /// Lanes per direction.
    pub lanes: u32,
    /// Speed limit, m/s.
    pub speed: f64,
    /// Priority at junctions (higher has the right of way).
    pub priority: i32,
}

/// The road types: level 1 major roads (2 lanes per direction, 50 km/h), 2 collectors (1 lane,
/// 40 km/h), 3 local streets (1 lane, 30 km/h), 4 cul-de-sacs (1 lane, 20 km/h); priority
/// falls with the level.
pub fn road_types() -> Vec<RoadType> {
    let t = |level: u8, name: &str, lanes: u32, kmh: f64| RoadType {
        level,
        id: format!("L{level}"),
        name: name.into(),
        lanes,
        speed: kmh / 3.6,
        priority: 5 - level as i32,
    };
    vec![
        t(1, "major road", 2, 50.0),
        t(2, "collector", 1, 40.0),
        t(3, "local street", 1, 30.0),
        t(4, "cul-de-sac", 1, 20.0),
    ]
}

/// The SUMO type id of a level (levels outside 1–4 take the nearest).
pub fn type_id(level: u8) -> String {
    format!("L{}", level.clamp(1, 4))
}

/// SUMO's id of the edge of street `id` in one direction (`forward`: from its `a` to its `b`).
pub fn edge_id(id: u32, forward: bool) -> String {
    if forward {
        format!("e{id}")
    } else {
        format!("-e{id}")
    }
}

/// The street id and direction of a SUMO edge id written by [`edge_id`] (`None` for others,
/// such as internal edges).
pub fn parse_edge_id(s: &str) -> Option<(u32, bool)> {
    match s.strip_prefix("-e") {
        Some(r) => r.parse().ok().map(|id| (id, false)),
        None => s.strip_prefix('e')?.parse().ok().map(|id| (id, true)),
    }
}

/// SUMO's id of the node of design vertex `id`.
pub fn node_id(id: u32) -> String {
    format!("n{id}")
}

fn shape_attr(points: &[[f64; 2]]) -> String {
    let parts: Vec<String> = points.iter().map(|p| format!("{:.3},{:.3}", p[0], p[1])).collect();
    parts.join(" ")
}

/// The three plain XML files of one network.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlainFiles {
    /// `.nod.xml`.
    pub nodes: PathBuf,
    /// `.edg.xml`.
    pub edges: PathBuf,
    /// `.typ.xml`.
    pub types: PathBuf,
}

/// The node file's text.
pub fn nodes_xml(net: &RoadNetwork) -> String {
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<!-- netspec {}: {}, one node per design vertex with a street, metres -->",
        env!("CARGO_PKG_VERSION"),
        xml_comment(&net.name)
    );
    s.push_str("<nodes>\n");
    for n in &net.nodes {
        let _ = writeln!(s, r#"    <node id="{}" x="{:.3}" y="{:.3}"/>"#, node_id(n.id), n.pos[0], n.pos[1]);
    }
    s.push_str("</nodes>\n");
    s
}

/// The edge file's text.
pub fn edges_xml(net: &RoadNetwork) -> String {
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<!-- netspec {}: {}, two edges (one per direction) per designed street -->",
        env!("CARGO_PKG_VERSION"),
        xml_comment(&net.name)
    );
    s.push_str("<edges>\n");
    for e in &net.edges {
        let (a, b) = (node_id(net.nodes[e.a].id), node_id(net.nodes[e.b].id));
        let ty = type_id(e.level);
        let mut back = e.shape.clone();
        back.reverse();
        let directions = [(edge_id(e.id, true), &a, &b, &e.shape), (edge_id(e.id, false), &b, &a, &back)];
        for (id, from, to, shape) in directions.into_iter().take(if e.oneway { 1 } else { 2 }) {
            let shape = if shape.len() > 2 { format!(r#" shape="{}""#, shape_attr(shape)) } else { String::new() };
            let _ = writeln!(s, r#"    <edge id="{id}" from="{from}" to="{to}" type="{ty}"{shape}/>"#);
        }
    }
    s.push_str("</edges>\n");
    s
}

/// The type file's text.
pub fn types_xml() -> String {
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<types>\n");
    for t in road_types() {
        let _ = writeln!(
            s,
            r#"    <type id="{}" numLanes="{}" speed="{:.4}" priority="{}"/> <!-- {} -->"#,
            t.id, t.lanes, t.speed, t.priority, t.name
        );
    }
    s.push_str("</types>\n");
    s
}

fn xml_comment(t: &str) -> String {
    t.replace("--", "- -")
}

/// Writes `<stem>.nod.xml`, `<stem>.edg.xml` and `<stem>.typ.xml` into `dir`.
pub fn write_plain(net: &RoadNetwork, dir: &Path, stem: &str) -> Result<PlainFiles, TrafficError> {
    let files = PlainFiles {
        nodes: dir.join(format!("{stem}.nod.xml")),
        edges: dir.join(format!("{stem}.edg.xml")),
        types: dir.join(format!("{stem}.typ.xml")),
    };
    write(&files.nodes, &nodes_xml(net))?;
    write(&files.edges, &edges_xml(net))?;
    write(&files.types, &types_xml())?;
    Ok(files)
}
