//! Networks given as street centrelines in metres (a `netspec layout` or `netspec grow` output):
//! the polylines are split where one street ends on another or two cross, so that junctions are
//! nodes, and their levels mapped to the hierarchy SUMO is given.

use super::road::{Provenance, Region, RoadEdge, RoadNetwork, RoadNode};
use super::{read, TrafficError, TrafficErrorKind};
use crate::geometry::index::SegmentIndex;
use crate::geometry::{clip_segment as clip, closest_on_segment, dist, polyline_length, segment_intersection, P};
use crate::grow::output::NetworkFile;
use crate::layout::Street;
use serde::Deserialize;
use std::path::Path;

/// Within this distance (metres) a street end lies on another street, and two nodes are one.
const SNAP: f64 = 0.5;

/// The part of `layout.json` a traffic evaluation reads.
#[derive(Deserialize)]
struct LayoutFile {
    name: String,
    outer: Vec<P>,
    #[serde(default)]
    origin: Option<[f64; 2]>,
    streets: Vec<Street>,
    violations: Vec<serde_json::Value>,
}

/// The network of a `netspec layout` output directory (`layout.json`): its streets as a graph
/// (level 0 — major roads and the boundary street — as major roads, the first split as
/// collectors, deeper splits as local streets), entrances where major roads meet the region's
/// boundary, demand drawn in the region's outer ring — the same region a `netspec city` on that
/// site has, so both meet the same trips.
pub fn from_layout(dir: &Path) -> Result<RoadNetwork, TrafficError> {
    let file = dir.join("layout.json");
    let text = read(&file)?;
    let layout: LayoutFile = serde_json::from_str(&text).map_err(|e| {
        TrafficError::new(&file, TrafficErrorKind::Parse { what: "a netspec layout", message: e.to_string() })
    })?;
    if !layout.violations.is_empty() {
        let n = layout.violations.len();
        return Err(TrafficError::new(&file, TrafficErrorKind::Invalid(format!("{n} violations in layout.json"))));
    }
    let lines: Vec<Line> = layout.streets.iter().map(|s| (s.polyline.clone(), level_of(s.level), None)).collect();
    let (nodes, edges) = graph(&lines, &layout.outer);
    if edges.is_empty() {
        return Err(TrafficError::new(&file, TrafficErrorKind::NoNetwork("the layout has no streets".into())));
    }
    Ok(RoadNetwork {
        name: layout.name,
        source: provenance("layout", &file, String::new()),
        metres_per_unit: 1.0,
        nodes,
        edges,
        region: Region { boundary: layout.outer.clone(), areas: vec![layout.outer] },
        origin: layout.origin,
    })
}

/// The network of a `netspec grow` output directory (`network.json`), inside `window`
/// (`[x0, y0, x1, y1]`, metres; default the whole map): major roads and bridges as major roads,
/// minor roads as local streets (harbour links are ferries, not roads), each segment clipped
/// to the window and carrying the traffic the growth model put on it (its predicted load);
/// entrances where major roads cross the window's edge; demand drawn in the window — so a
/// `netspec city` on the same window meets the same trips.
pub fn from_grow(dir: &Path, window: Option<[f64; 4]>) -> Result<RoadNetwork, TrafficError> {
    let file = dir.join("network.json");
    let text = read(&file)?;
    let bad =
        |message: String| TrafficError::new(&file, TrafficErrorKind::Parse { what: "a netspec grow network", message });
    let net = NetworkFile::from_json(&text).map_err(bad)?;
    let [x0, y0, x1, y1] = window.unwrap_or([0.0, 0.0, net.size[0], net.size[1]]);
    if !(x0 < x1 && y0 < y1 && [x0, y0, x1, y1].iter().all(|v| v.is_finite())) {
        return Err(TrafficError::new(
            &file,
            TrafficErrorKind::Invalid(format!("window {x0},{y0},{x1},{y1} is empty")),
        ));
    }
    let pos = net.positions();
    let mut lines = Vec::new();
    for (i, s) in net.segments.iter().enumerate() {
        let level = match s.class.as_str() {
            "major" | "bridge" => 1,
            "minor" => 3,
            "harbour" => continue,
            other => return Err(bad(format!("segments[{i}].class: unknown class `{other}`"))),
        };
        let (a, b) = net.segment_ends(&pos, i).map_err(bad)?;
        if let Some((a, b)) = clip(a, b, [x0, y0, x1, y1]) {
            lines.push((vec![a, b], level, s.traffic));
        }
    }
    let ring = vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    let (nodes, edges) = graph(&lines, &ring);
    if edges.is_empty() {
        return Err(TrafficError::new(&file, TrafficErrorKind::NoNetwork("no road inside the window".into())));
    }
    Ok(RoadNetwork {
        name: dir.file_name().map_or("grow".into(), |n| n.to_string_lossy().into_owned()),
        source: provenance("grow", &file, format!("window {x0},{y0},{x1},{y1}")),
        metres_per_unit: 1.0,
        nodes,
        edges,
        region: Region { boundary: ring.clone(), areas: vec![ring] },
        origin: net.origin,
    })
}

/// The network of a GeoJSON file of street centrelines in WGS 84: the real streets of
/// `netspec site` (a `map/` directory, `map/streets.geojson`) or any FeatureCollection of
/// LineStrings. A street's `level` property (1–4, default 3) is its level, `oneway: true` makes it
/// one-way. When every street names its end nodes (`u`, `v`, as `netspec site` writes OSM node
/// ids), streets meet only where they share a node (a bridge over a street is no junction);
/// otherwise they are noded where they end on or cross each other. A Polygon feature is the
/// region (demand is drawn in its outer ring); without one the streets' bounding box is. The
/// metres are a transverse Mercator centred on the region feature's `origin` property, else on the
/// centre of the region's (or the streets') bounding box. The network is not clipped to its
/// region (street counts at nodes near the edge need the streets beyond it); see
/// [`super::network::clip`].
pub fn from_geojson(path: &Path) -> Result<RoadNetwork, TrafficError> {
    let file = if path.is_dir() { path.join("streets.geojson") } else { path.to_path_buf() };
    let text = read(&file)?;
    let bad =
        |message: String| TrafficError::new(&file, TrafficErrorKind::Parse { what: "a GeoJSON of streets", message });
    let (region, lines) = geojson_streets(&text).map_err(bad)?;
    if lines.is_empty() {
        return Err(TrafficError::new(&file, TrafficErrorKind::NoNetwork("no LineString streets".into())));
    }
    let all: Vec<[f64; 2]> = lines.iter().flat_map(|l| l.lonlat.iter().copied()).collect();
    let ring = region.as_ref().map_or_else(|| bbox_ring(&all), |r| r.outer.clone());
    let [lo, hi] = crate::geometry::polygon::bounds(&ring);
    let origin = region.and_then(|r| r.origin).unwrap_or([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]);
    let proj = crate::geometry::site::Projection::new(origin).map_err(|e| bad(e.to_string()))?;
    let local = |ps: &[[f64; 2]]| {
        ps.iter().map(|&q| proj.to_local(q)).collect::<Result<Vec<P>, _>>().map_err(|e| bad(e.to_string()))
    };
    let mut outer = local(&ring)?;
    if outer.len() > 1 && outer.first() == outer.last() {
        outer.pop();
    }
    let (nodes, edges) = if lines.iter().all(|l| l.ends.is_some()) {
        let shapes = lines.iter().map(|l| local(&l.lonlat)).collect::<Result<Vec<_>, _>>()?;
        by_node_ids(&lines, shapes)
    } else {
        let ls: Vec<Line> =
            lines.iter().map(|l| Ok((local(&l.lonlat)?, l.level, None))).collect::<Result<_, TrafficError>>()?;
        graph(&ls, &outer)
    };
    Ok(RoadNetwork {
        name: path.file_stem().map_or("streets".into(), |n| n.to_string_lossy().into_owned()),
        source: provenance("streets", &file, String::new()),
        metres_per_unit: 1.0,
        nodes,
        edges,
        region: Region { boundary: outer.clone(), areas: vec![outer] },
        origin: Some(origin),
    })
}

/// A street of a GeoJSON file.
struct GeoStreet {
    lonlat: Vec<[f64; 2]>,
    level: u8,
    oneway: bool,
    ends: Option<(i64, i64)>,
}

/// The region feature of a GeoJSON file of streets.
struct GeoRegion {
    outer: Vec<[f64; 2]>,
    origin: Option<[f64; 2]>,
}

/// The region (the first Polygon) and the streets (LineStrings) of a GeoJSON text.
fn geojson_streets(text: &str) -> Result<(Option<GeoRegion>, Vec<GeoStreet>), String> {
    let gj: geojson::GeoJson = text.parse().map_err(|e: geojson::Error| e.to_string())?;
    let features = match gj {
        geojson::GeoJson::FeatureCollection(fc) => fc.features,
        geojson::GeoJson::Feature(f) => vec![f],
        geojson::GeoJson::Geometry(g) => vec![geojson::Feature { geometry: Some(g), ..Default::default() }],
    };
    let mut region = None;
    let mut lines = Vec::new();
    for (i, f) in features.iter().enumerate() {
        let Some(g) = &f.geometry else { continue };
        let props = f.properties.clone().unwrap_or_default();
        match &g.value {
            geojson::GeometryValue::Polygon { coordinates } if region.is_none() => {
                let origin =
                    match props.get("origin") {
                        None => None,
                        Some(v) => Some(serde_json::from_value::<[f64; 2]>(v.clone()).map_err(|_| {
                            format!("features[{i}].properties.origin: {v} is not [longitude, latitude]")
                        })?),
                    };
                let outer = coordinates.first().ok_or_else(|| format!("features[{i}]: a Polygon without rings"))?;
                region = Some(GeoRegion { outer: lonlat(i, outer)?, origin });
            }
            geojson::GeometryValue::LineString { coordinates } => {
                let level = match props.get("level") {
                    None => 3,
                    Some(v) => v
                        .as_u64()
                        .filter(|l| (1..=4).contains(l))
                        .ok_or_else(|| format!("features[{i}].properties.level: {v} is not a level 1–4"))?
                        as u8,
                };
                let id = |k: &str| props.get(k).and_then(serde_json::Value::as_i64);
                let lonlat = lonlat(i, coordinates)?;
                if lonlat.len() < 2 {
                    return Err(format!("features[{i}]: a street needs two positions"));
                }
                lines.push(GeoStreet {
                    lonlat,
                    level,
                    oneway: props.get("oneway").and_then(serde_json::Value::as_bool).unwrap_or(false),
                    ends: id("u").zip(id("v")),
                });
            }
            _ => {}
        }
    }
    Ok((region, lines))
}

/// Positions of feature `i` as WGS 84 longitude/latitude.
fn lonlat(i: usize, ps: &[geojson::Position]) -> Result<Vec<[f64; 2]>, String> {
    ps.iter()
        .enumerate()
        .map(|(k, p)| {
            let s = p.as_slice();
            match (s.first(), s.get(1)) {
                (Some(&x), Some(&y)) if x.is_finite() && y.is_finite() && x.abs() <= 180.0 && y.abs() < 90.0 => {
                    Ok([x, y])
                }
                _ => Err(format!("features[{i}] position {k}: not a WGS 84 longitude/latitude")),
            }
        })
        .collect()
}

/// The street graph of streets that name their end nodes: one node per id.
fn by_node_ids(lines: &[GeoStreet], shapes: Vec<Vec<P>>) -> (Vec<RoadNode>, Vec<RoadEdge>) {
    let mut index: std::collections::BTreeMap<i64, usize> = std::collections::BTreeMap::new();
    let mut nodes: Vec<RoadNode> = Vec::new();
    let mut edges = Vec::new();
    for (l, shape) in lines.iter().zip(shapes) {
        let (u, v) = l.ends.expect("every street names its ends");
        let mut at = |id: i64, p: P| {
            *index.entry(id).or_insert_with(|| {
                nodes.push(RoadNode { id: nodes.len() as u32, pos: p, entrance: false });
                nodes.len() - 1
            })
        };
        let (a, b) = (at(u, shape[0]), at(v, shape[shape.len() - 1]));
        edges.push(RoadEdge {
            id: edges.len() as u32,
            a,
            b,
            level: l.level,
            shape,
            local: l.level >= 2,
            predicted_load: None,
            oneway: l.oneway,
        });
    }
    (nodes, edges)
}

/// The bounding box of positions as a ring.
fn bbox_ring(ps: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let [lo, hi] = crate::geometry::polygon::bounds(ps);
    vec![[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]]
}

/// Where a network of centrelines was read from (the files carry no solver runs).
fn provenance(kind: &str, file: &Path, description: String) -> Provenance {
    Provenance {
        kind: kind.into(),
        path: file.display().to_string(),
        netspec_version: env!("CARGO_PKG_VERSION").into(),
        description,
        runs: Vec::new(),
    }
}

/// A layout level as a traffic level (1 major, 2 collector, 3 local).
fn level_of(level: usize) -> u8 {
    (level + 1).min(3) as u8
}

/// A street centreline in metres, its traffic level, and the load a generator predicted on it.
pub type Line = (Vec<P>, u8, Option<f64>);

/// The street graph of polylines with levels: nodes at street ends, at points where a street
/// ends on another, and at crossings; an edge per piece between nodes (with its line's
/// predicted load). Nodes of major roads on `outer` are entrances.
pub fn graph(lines: &[Line], outer: &[P]) -> (Vec<RoadNode>, Vec<RoadEdge>) {
    let mut nodes: Vec<RoadNode> = Vec::new();
    let mut cells = Cells::new();
    let mut edges: Vec<RoadEdge> = Vec::new();
    let lines: Vec<&Line> = lines.iter().filter(|(l, _, _)| l.len() >= 2 && polyline_length(l) > SNAP).collect();
    let ends = SegmentIndex::new(
        lines.iter().flat_map(|(l, _, _)| [(l[0], l[0]), (l[l.len() - 1], l[l.len() - 1])]).collect(),
        20.0,
    );
    let mut owner = Vec::new();
    let mut segments = Vec::new();
    for (i, (l, _, _)) in lines.iter().enumerate() {
        for w in l.windows(2) {
            owner.push(i);
            segments.push((w[0], w[1]));
        }
    }
    let index = Segments { index: SegmentIndex::new(segments, 20.0), owner };
    for (i, (line, level, load)) in lines.iter().enumerate() {
        let cuts = cut_points(i, line, &index, &ends);
        for piece in split_at(line, &cuts) {
            if polyline_length(&piece) <= SNAP {
                continue;
            }
            let a = node(&mut nodes, &mut cells, piece[0]);
            let b = node(&mut nodes, &mut cells, *piece.last().expect("a piece"));
            if a == b && piece.len() < 3 {
                continue;
            }
            edges.push(RoadEdge {
                id: edges.len() as u32,
                a,
                b,
                level: *level,
                shape: piece,
                local: *level >= 2,
                predicted_load: *load,
                oneway: false,
            });
        }
    }
    let on_outer = |p: P| {
        (0..outer.len()).any(|k| dist(p, closest_on_segment(p, outer[k], outer[(k + 1) % outer.len()]).0) <= SNAP)
    };
    for e in edges.iter().filter(|e| e.level == 1) {
        for n in [e.a, e.b] {
            if on_outer(nodes[n].pos) {
                nodes[n].entrance = true;
            }
        }
    }
    (nodes, edges)
}

/// Every street's segments, with the street each belongs to.
struct Segments {
    index: SegmentIndex,
    owner: Vec<usize>,
}

/// Nodes bucketed by grid cells of [`SNAP`] metres.
type Cells = std::collections::BTreeMap<(i64, i64), Vec<usize>>;

/// The node at `p`: an existing one within [`SNAP`] (the first made), else a new one.
fn node(nodes: &mut Vec<RoadNode>, cells: &mut Cells, p: P) -> usize {
    let cell = |x: f64| (x / SNAP).floor() as i64;
    let (cx, cy) = (cell(p[0]), cell(p[1]));
    let mut near: Vec<usize> = (cx - 1..=cx + 1)
        .flat_map(|x| (cy - 1..=cy + 1).map(move |y| (x, y)))
        .filter_map(|c| cells.get(&c))
        .flatten()
        .copied()
        .filter(|&k| dist(nodes[k].pos, p) <= SNAP)
        .collect();
    near.sort_unstable();
    if let Some(&k) = near.first() {
        return k;
    }
    nodes.push(RoadNode { id: nodes.len() as u32, pos: p, entrance: false });
    cells.entry((cx, cy)).or_default().push(nodes.len() - 1);
    nodes.len() - 1
}

/// Arc lengths along `line` (street `i`) where it must be split: other streets' ends on it and
/// crossings with other streets, sorted, without its own ends.
fn cut_points(i: usize, line: &[P], segments: &Segments, ends: &SegmentIndex) -> Vec<f64> {
    let total = polyline_length(line);
    let mut cuts = Vec::new();
    let mut run = 0.0;
    for w in line.windows(2) {
        let l = dist(w[0], w[1]);
        let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
        for k in ends.near(mid, l / 2.0 + SNAP) {
            let e = ends.segments()[k].0;
            let (q, t) = closest_on_segment(e, w[0], w[1]);
            if dist(q, e) <= SNAP {
                cuts.push(run + t * l);
            }
        }
        for k in segments.index.near(mid, l / 2.0) {
            if segments.owner[k] == i {
                continue;
            }
            let (a, b) = segments.index.segments()[k];
            if let Some((s, _)) = segment_intersection(w[0], w[1], a, b) {
                cuts.push(run + s * l);
            }
        }
        run += l;
    }
    cuts.retain(|&c| c > SNAP && c < total - SNAP);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() <= SNAP);
    cuts
}

/// `line` cut at the arc lengths `cuts` (ascending).
fn split_at(line: &[P], cuts: &[f64]) -> Vec<Vec<P>> {
    let mut out = Vec::new();
    let mut piece = vec![line[0]];
    let mut run = 0.0;
    let mut next = cuts.iter().peekable();
    for w in line.windows(2) {
        let l = dist(w[0], w[1]);
        while let Some(&&c) = next.peek() {
            if c > run + l {
                break;
            }
            let t = if l > 0.0 { (c - run) / l } else { 0.0 };
            let p = [w[0][0] + t * (w[1][0] - w[0][0]), w[0][1] + t * (w[1][1] - w[0][1])];
            piece.push(p);
            out.push(std::mem::replace(&mut piece, vec![p]));
            next.next();
        }
        if piece.last() != Some(&w[1]) {
            piece.push(w[1]);
        }
        run += l;
    }
    out.push(piece);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A boundary square, a road across it and a street ending on the road: the road splits at
    /// the junction and at the boundary; the road's ends on the boundary are entrances.
    #[test]
    fn junctions_and_crossings_become_nodes() {
        let outer = vec![[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]];
        let mut ring = outer.clone();
        ring.push(outer[0]);
        let lines = vec![
            (ring, 1u8, None),
            (vec![[0.0, 50.0], [100.0, 50.0]], 1, None),
            (vec![[40.0, 50.0], [40.0, 100.0]], 2, None),
            (vec![[70.0, 20.0], [70.0, 80.0]], 3, Some(4.0)),
        ];
        let (nodes, edges) = graph(&lines, &outer);
        // The ring: cut at the road's ends and the street's end → 4 pieces; the road: 3 pieces
        // (the street's end, the crossing); the street: 1; the crossing street: 2.
        assert_eq!(edges.len(), 4 + 3 + 1 + 2, "{edges:?}");
        let entrances: Vec<P> = nodes.iter().filter(|n| n.entrance).map(|n| n.pos).collect();
        assert!(entrances.contains(&[0.0, 50.0]) && entrances.contains(&[100.0, 50.0]));
        assert!(nodes.iter().any(|n| n.pos == [70.0, 50.0]), "the crossing is a node");
        let total: f64 = edges.iter().map(|e| e.length()).sum();
        assert!((total - (400.0 + 100.0 + 50.0 + 60.0)).abs() < 1e-9, "{total}");
    }

    /// A grown network clipped to a window: segments cut at its edge, harbours left out, the
    /// major road's crossing of the edge an entrance, demand in the window.
    #[test]
    fn a_grown_network_is_clipped_to_its_window() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let json = r#"{"size": [1000, 1000], "nodes": [{"id": 0, "x": 100, "y": 500}, {"id": 1, "x": 900, "y": 500},
            {"id": 2, "x": 500, "y": 500}, {"id": 3, "x": 500, "y": 700}, {"id": 4, "x": 500, "y": 300}],
            "segments": [{"a": 0, "b": 2, "class": "major"}, {"a": 2, "b": 1, "class": "bridge"},
            {"a": 2, "b": 3, "class": "minor"}, {"a": 2, "b": 4, "class": "harbour"}]}"#;
        std::fs::write(dir.path().join("network.json"), json).expect("written");
        let net = from_grow(dir.path(), Some([300.0, 200.0, 800.0, 800.0])).expect("a network");
        let total: f64 = net.edges.iter().map(|e| e.length()).sum();
        assert!((total - (200.0 + 300.0 + 200.0)).abs() < 1e-9, "{total}");
        let entrances: Vec<P> = net.nodes.iter().filter(|n| n.entrance).map(|n| n.pos).collect();
        assert_eq!(entrances, vec![[300.0, 500.0], [800.0, 500.0]]);
        assert_eq!(net.region.boundary[2], [800.0, 800.0]);
        let e = from_grow(dir.path(), Some([5.0, 5.0, 5.0, 9.0])).unwrap_err().to_string();
        assert!(e.contains("network.json") && e.contains("empty"), "{e}");
    }

    /// A grown network that failed its independent check is no design.
    #[test]
    fn a_grown_network_with_violations_is_refused() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        let json = r#"{"size": [100, 100], "nodes": [{"id": 0, "x": 0, "y": 0}, {"id": 1, "x": 50, "y": 0}],
            "segments": [{"a": 0, "b": 1, "class": "major"}],
            "violations": [{"kind": "missing_node", "segment": 3, "node": 9}]}"#;
        std::fs::write(dir.path().join("network.json"), json).expect("written");
        let e = from_grow(dir.path(), None).unwrap_err().to_string();
        assert!(e.contains("network.json") && e.contains("1 violations"), "{e}");
        let e = crate::grow::window::write(dir.path(), [0.0, 0.0, 50.0, 50.0], "w", &dir.path().join("w"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("network.json") && e.contains("1 violations"), "{e}");
    }
}
