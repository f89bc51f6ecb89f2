//! A window of a grown network as the input of netspec's other designs: a **city spec** whose
//! major roads are the grown major chains (bridges included) clipped to the window and smoothed,
//! whose water is an obstacle of every level, and whose sub-regions that the growth left unbuilt
//! (or too small for a street) run no level; and the **trade flows** that cross the window (where the grown trade routes
//! enter and leave it, weighted by their traffic), the demand `netspec traffic --trade` adds
//! for every design of the window.
//!
//! Reads `network.json` only, so a grown map can be windowed many times without growing again.

use super::output::{write as write_file, NetworkFile, WaterRecord};
use super::GrowError;
use crate::design::streets::{decompose, StreetEdge, StreetGraph};
use crate::geometry::polygon::bounds;
use crate::geometry::{clip_segment as clip, dist, lerp, polyline_length, P};
use crate::urban::spec::CitySpec;
use geo::{ChaikinSmoothing, Simplify};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Metres per city unit of the spec written (the city mesh has one unit between vertices).
pub const METRES_PER_UNIT: f64 = 20.0;

/// Metres of dry strip kept along the window's edge and the roads in obstacle polygons (a cell
/// and a half).
const CLEARANCE: f64 = 1.5 * METRES_PER_UNIT;

/// Sub-regions smaller than this many mesh cells (3 × 3: 60 × 60 m) hold no street of their own
/// and run no level (slivers between grown roads that run side by side).
const MIN_CELLS: f64 = 9.0;

/// Sub-regions with less grown minor street than this (km per km²) are unbuilt and run no level
/// (a grown settlement has 40–50 km/km²; a few streets reaching into open land do not make it
/// built up).
const MIN_KM_PER_KM2: f64 = 10.0;

/// Trade across a region: trips from one point to another (each end at the nearest entrance),
/// as many as the flow's share of the weights.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TradeFlow {
    /// Where the trade enters, metres.
    pub from: [f64; 2],
    /// Where it leaves, metres.
    pub to: [f64; 2],
    /// Its weight (a grown network's route traffic).
    pub weight: f64,
}

/// A `trade.json` file: the trade flows across a window of a grown map.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TradeFile {
    /// The window `[x0, y0, x1, y1]`, metres.
    pub window: [f64; 4],
    /// The flows, in order of their end points.
    pub flows: Vec<TradeFlow>,
}

impl TradeFile {
    /// Reads and checks a trade file: finite points, weights ≥ 0.
    pub fn load(path: &Path) -> Result<TradeFile, GrowError> {
        let text = std::fs::read_to_string(path).map_err(|source| GrowError::Io { path: path.into(), source })?;
        let f: TradeFile = serde_json::from_str(&text)
            .map_err(|e| GrowError::Toml { path: path.into(), message: format!("not a trade file: {e}") })?;
        for (i, t) in f.flows.iter().enumerate() {
            if !(t.from.iter().chain(&t.to).all(|v| v.is_finite()) && t.weight.is_finite() && t.weight >= 0.0) {
                return Err(GrowError::Field {
                    path: path.into(),
                    field: format!("flows[{i}]"),
                    message: "points must be finite and the weight a number ≥ 0".into(),
                });
            }
        }
        Ok(f)
    }
}

/// What [`write`] made.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WindowSummary {
    /// Major chains in the window (the city's `[[road]]` entries).
    pub roads: usize,
    /// Their length, metres.
    pub road_m: f64,
    /// Sub-regions of the city.
    pub regions: usize,
    /// Sub-regions that run no level (under 10 km of grown minor street per km², or smaller than 3 × 3 cells).
    pub empty_regions: usize,
    /// Water bodies that reach into the window (obstacles).
    pub obstacles: usize,
    /// Trade flows across the window.
    pub flows: usize,
    /// Routes that reach into the window but start or end inside it (not a flow across it).
    pub routes_ending_inside: usize,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// A window `[x0, y0, x1, y1]` of the grown network in `dir` (`network.json`) written into `out`
/// as `city.toml` (named `name`) and `trade.json`.
pub fn write(dir: &Path, window: [f64; 4], name: &str, out: &Path) -> Result<WindowSummary, GrowError> {
    let file = dir.join("network.json");
    let text = std::fs::read_to_string(&file).map_err(|source| GrowError::Io { path: file.clone(), source })?;
    let field = |field: &str, message: String| GrowError::Field { path: file.clone(), field: field.into(), message };
    let bad = |message: String| GrowError::Toml { path: file.clone(), message };
    let net = NetworkFile::from_json(&text).map_err(bad)?;
    check_window(window, net.size).map_err(|m| field("window", m))?;
    let (major, minor) = clipped_roads(&net, window).map_err(bad)?;
    let chains: Vec<Vec<P>> = chains(&major)
        .into_iter()
        .map(|c| smooth(&c, net.spacing))
        .filter(|c| polyline_length(c) > net.spacing)
        .collect();
    let water: Vec<Vec<P>> = net.water.iter().filter_map(water_polygon).filter(|p| overlaps(p, window)).collect();
    let obstacles = clear_of_roads(&water, &chains, window);
    let (flows, inside) = trade_flows(&route_lines(&net).map_err(bad)?, window);
    let city = |empty: &[P]| -> Result<(String, CitySpec), GrowError> {
        let text = city_toml(&city_spec(name, window, net.origin, &chains, &obstacles, empty), window)
            .map_err(|m| field("window", m))?;
        let parsed = CitySpec::from_toml(&text)
            .map_err(|e| field("window", format!("the window's city spec is unusable: {e}")))?;
        Ok((text, parsed))
    };
    let (_, parsed) = city(&[])?;
    let regions =
        crate::urban::city::regions(&parsed).map_err(|e| field("window", format!("the window's major roads: {e}")))?;
    let empty: Vec<P> = regions.iter().filter(|(r, _)| unbuilt(r, &minor)).map(|(r, _)| r.label_point).collect();
    let (spec, _) = city(&empty)?;
    std::fs::create_dir_all(out).map_err(|source| GrowError::Io { path: out.to_path_buf(), source })?;
    let trade = TradeFile { window, flows };
    let json = serde_json::to_string_pretty(&trade).expect("trade flows serialise") + "\n";
    let files = vec![write_file(out, "city.toml", spec.as_bytes())?, write_file(out, "trade.json", json.as_bytes())?];
    Ok(WindowSummary {
        roads: chains.len(),
        road_m: chains.iter().map(|c| polyline_length(c)).sum(),
        regions: regions.len(),
        empty_regions: empty.len(),
        obstacles: water.len(),
        flows: trade.flows.len(),
        routes_ending_inside: inside,
        files,
    })
}

/// Why a window cannot be used on a map of `size`, if it cannot.
fn check_window(w: [f64; 4], size: [f64; 2]) -> Result<(), String> {
    let [x0, y0, x1, y1] = w;
    if !(w.iter().all(|v| v.is_finite()) && x0 < x1 && y0 < y1) {
        return Err(format!("{x0},{y0},{x1},{y1} is empty"));
    }
    if x1 <= 0.0 || y1 <= 0.0 || x0 >= size[0] || y0 >= size[1] {
        return Err(format!("{x0},{y0},{x1},{y1} is outside the map [0, {}] × [0, {}]", size[0], size[1]));
    }
    Ok(())
}

/// Segments as pairs of end points.
type Segments = Vec<(P, P)>;

/// The major roads (with bridges) and the minor roads, clipped to the window.
fn clipped_roads(net: &NetworkFile, w: [f64; 4]) -> Result<(Segments, Segments), String> {
    let pos = net.positions();
    let (mut major, mut minor) = (Vec::new(), Vec::new());
    for (i, s) in net.segments.iter().enumerate() {
        let (a, b) = net.segment_ends(&pos, i)?;
        match (s.class.as_str(), clip(a, b, w)) {
            ("major" | "bridge", Some(piece)) => major.push(piece),
            ("minor", Some(piece)) => minor.push(piece),
            _ => {}
        }
    }
    Ok((major, minor))
}

/// The trade routes as polylines with their traffic.
fn route_lines(net: &NetworkFile) -> Result<Vec<(Vec<P>, f64)>, String> {
    let pos = net.positions();
    let line = |i: usize, nodes: &[Option<usize>]| {
        nodes
            .iter()
            .map(|n| n.and_then(|n| pos.get(&n).copied()))
            .collect::<Option<Vec<P>>>()
            .ok_or_else(|| format!("routes[{i}].nodes: a node is not in `nodes`"))
    };
    net.routes.iter().enumerate().map(|(i, r)| Ok((line(i, &r.nodes)?, r.traffic))).collect()
}

/// Whether a sub-region (city units) is too small for a street or the growth left it unbuilt:
/// under [`MIN_KM_PER_KM2`] of the grown `minor` segments (metres) by their midpoints.
fn unbuilt(r: &crate::geometry::planar::Region, minor: &[(P, P)]) -> bool {
    let unit = |p: P| [p[0] / METRES_PER_UNIT, p[1] / METRES_PER_UNIT];
    let street: f64 = minor
        .iter()
        .filter(|&&(a, b)| crate::urban::city::point_in_region(unit(lerp(a, b, 0.5)), r))
        .map(|&(a, b)| dist(a, b))
        .sum();
    let km2 = r.area * METRES_PER_UNIT * METRES_PER_UNIT / 1e6;
    r.area < MIN_CELLS || street / 1000.0 < MIN_KM_PER_KM2 * km2
}

/// A point rounded to the millimetre.
type Key = (i64, i64);

/// Points within a millimetre are one.
fn key(p: P) -> Key {
    ((p[0] * 1000.0).round() as i64, (p[1] * 1000.0).round() as i64)
}

/// The segments joined into maximal chains between nodes whose degree is not 2 (ends,
/// junctions), a closed loop of degree-2 nodes one closed chain: the street graph's snakes
/// ([`decompose`]) over the segments' ends, one node per millimetre.
fn chains(segments: &[(P, P)]) -> Vec<Vec<P>> {
    let mut index: BTreeMap<Key, u32> = BTreeMap::new();
    let mut positions = Vec::new();
    let mut node = |p: P| {
        *index.entry(key(p)).or_insert_with(|| {
            positions.push(p);
            positions.len() as u32 - 1
        })
    };
    let edges: Vec<StreetEdge> =
        segments.iter().map(|&(a, b)| StreetEdge { a: node(a), b: node(b), level: 1 }).collect();
    decompose(&StreetGraph { positions, edges }).into_iter().map(|s| s.points).collect()
}

/// A grown chain as a city road: lattice zig-zags removed (Ramer–Douglas–Peucker within half the
/// lattice spacing), then two rounds of Chaikin corner cutting; both ends stay where they are.
fn smooth(chain: &[P], spacing: f64) -> Vec<P> {
    let closed = chain.len() > 2 && key(chain[0]) == key(chain[chain.len() - 1]);
    let line: geo::LineString<f64> = chain.iter().map(|p| geo::coord! { x: p[0], y: p[1] }).collect();
    let line = line.simplify(spacing / 2.0).chaikin_smoothing(2);
    let mut out: Vec<P> = line.coords().map(|c| [c.x, c.y]).collect();
    if !closed {
        // Chaikin keeps an open line's ends; restate them exactly (they are window or junction points).
        out[0] = chain[0];
        let n = out.len();
        out[n - 1] = chain[chain.len() - 1];
    }
    out.dedup_by(|a, b| dist(*a, *b) < 1e-3);
    out
}

/// A water body as a polygon: a lake or sea as it is, a river as its centre line buffered by half
/// its width (round joins).
fn water_polygon(w: &WaterRecord) -> Option<Vec<P>> {
    if let Some(p) = &w.polygon {
        return Some(p.clone());
    }
    let (r, width) = (w.river.as_ref()?, w.width?);
    use geo::Buffer;
    let line: geo::LineString<f64> = r.iter().map(|p| geo::coord! { x: p[0], y: p[1] }).collect();
    let poly = line.buffer(width / 2.0);
    let biggest = poly.0.into_iter().max_by(|a, b| {
        use geo::Area;
        a.unsigned_area().total_cmp(&b.unsigned_area())
    })?;
    Some(biggest.exterior().coords().map(|c| [c.x, c.y]).collect())
}

/// Water less a strip of [`CLEARANCE`] along the window's edge and every road: the water within
/// the window as obstacle polygons that no sub-region boundary runs through. (A boundary is a road
/// every level keeps; a vertex of it whose faces were all water would be an obstacle too, and
/// the level infeasible. Where a grown road crosses water it is a bridge, and the window's edge
/// is no road at all.)
fn clear_of_roads(water: &[Vec<P>], roads: &[Vec<P>], w: [f64; 4]) -> Vec<Vec<P>> {
    use geo::{Area, BooleanOps, Buffer};
    let line = |ps: &[P]| -> geo::LineString<f64> { ps.iter().map(|p| geo::coord! { x: p[0], y: p[1] }).collect() };
    let poly = |ps: &[P]| geo::Polygon::new(line(ps), vec![]);
    let [x0, y0, x1, y1] = w;
    let inner = [x0 + CLEARANCE, y0 + CLEARANCE, x1 - CLEARANCE, y1 - CLEARANCE];
    if inner[0] >= inner[2] || inner[1] >= inner[3] || water.is_empty() {
        return Vec::new();
    }
    let inside = geo::MultiPolygon::new(vec![poly(&[
        [inner[0], inner[1]],
        [inner[2], inner[1]],
        [inner[2], inner[3]],
        [inner[0], inner[3]],
    ])]);
    let strips = geo::MultiLineString::new(roads.iter().map(|r| line(r)).collect()).buffer(CLEARANCE);
    let mut out = Vec::new();
    for wp in water {
        let wet = geo::MultiPolygon::new(vec![poly(wp)]).intersection(&inside).difference(&strips);
        for p in wet.0.into_iter().filter(|p| p.unsigned_area() > CLEARANCE * CLEARANCE) {
            out.push(p.exterior().coords().map(|c| [c.x, c.y]).collect());
        }
    }
    out
}

/// Whether a polygon's bounding box meets the window.
fn overlaps(p: &[P], w: [f64; 4]) -> bool {
    let [lo, hi] = bounds(p);
    lo[0] < w[2] && hi[0] > w[0] && lo[1] < w[3] && hi[1] > w[1]
}

/// Whether `p` is on the window's edge (within a millimetre).
fn on_edge(p: P, w: [f64; 4]) -> bool {
    let e = 1e-3;
    (p[0] - w[0]).abs() <= e || (p[0] - w[2]).abs() <= e || (p[1] - w[1]).abs() <= e || (p[1] - w[3]).abs() <= e
}

/// The trade flows across the window: every piece of a route inside the window that enters and
/// leaves through the window's edge is a flow from its entry point to its exit point, weighted by
/// the route's traffic; flows between the same two points are summed. Pieces that start or end
/// inside (a city or a harbour in the window) are counted, not flows.
fn trade_flows(routes: &[(Vec<P>, f64)], w: [f64; 4]) -> (Vec<TradeFlow>, usize) {
    let mut sum: BTreeMap<(Key, Key), (P, P, f64)> = BTreeMap::new();
    let mut ending_inside = 0;
    for (line, traffic) in routes {
        if *traffic <= 0.0 {
            continue;
        }
        let mut pieces: Vec<Vec<P>> = Vec::new();
        let mut open = false;
        for s in line.windows(2) {
            let Some((a, b)) = clip(s[0], s[1], w) else {
                open = false;
                continue;
            };
            if open && pieces.last().is_some_and(|p| dist(*p.last().expect("a piece"), a) < 1e-6) {
                pieces.last_mut().expect("a piece").push(b);
            } else {
                pieces.push(vec![a, b]);
            }
            open = dist(b, s[1]) < 1e-9;
        }
        for p in pieces {
            let (a, b) = (p[0], p[p.len() - 1]);
            if !(on_edge(a, w) && on_edge(b, w)) {
                ending_inside += 1;
                continue;
            }
            if key(a) == key(b) {
                continue;
            }
            sum.entry((key(a), key(b))).or_insert((a, b, 0.0)).2 += traffic;
        }
    }
    let mm = |x: f64| (x * 1000.0).round() / 1000.0;
    let flows = sum
        .into_values()
        .map(|(a, b, t)| TradeFlow { from: [mm(a[0]), mm(a[1])], to: [mm(b[0]), mm(b[1])], weight: mm(t) })
        .collect();
    (flows, ending_inside)
}

/// Points in city units, to a thousandth.
fn units(ps: &[P]) -> Vec<P> {
    let u = |x: f64| (x / METRES_PER_UNIT * 1000.0).round() / 1000.0 + 0.0;
    ps.iter().map(|p| [u(p[0]), u(p[1])]).collect()
}

/// The city spec of a window: domain, major roads, water obstacles on every level (Fig. 7a's
/// levels 2–4, [`crate::urban::spec::fig7a_levels`]), and one `[[region]]` entry that runs no
/// level per point of `empty` (label points, city units already: they come from the spec's own
/// sub-regions). The city's units are the map's metres / [`METRES_PER_UNIT`] from the map's
/// origin, so `geo_origin` is the map's `origin`.
fn city_spec(
    name: &str,
    w: [f64; 4],
    origin: Option<P>,
    roads: &[Vec<P>],
    obstacles: &[Vec<P>],
    empty: &[P],
) -> CitySpec {
    use crate::urban::spec::{CityMeshSpec, DomainSpec, RegionSpec, RoadSpec};
    let [x0, y0, x1, y1] = w;
    let obstacles: Vec<Vec<P>> = obstacles.iter().map(|p| units(p)).collect();
    CitySpec {
        name: name.to_string(),
        description: format!("window {x0},{y0},{x1},{y1} of a grown network, streets by levels 2–4"),
        metres_per_unit: METRES_PER_UNIT,
        geo_origin: origin,
        domain: DomainSpec { outer: units(&[[x0, y0], [x1, y0], [x1, y1], [x0, y1]]) },
        roads: roads
            .iter()
            .enumerate()
            .map(|(k, r)| RoadSpec { name: format!("grown major {k}"), points: units(r) })
            .collect(),
        major: None,
        mesh: CityMeshSpec { spacing: 1.0 },
        levels: crate::urban::spec::fig7a_levels(&obstacles),
        regions: empty
            .iter()
            .map(|&at| RegionSpec {
                at,
                name: "unbuilt".into(),
                run_levels: Some(Vec::new()),
                levels: Default::default(),
            })
            .collect(),
        solver: Default::default(),
        smoothing: Default::default(),
    }
}

/// The window's `city.toml`: a comment saying where it comes from, then the spec.
fn city_toml(spec: &CitySpec, w: [f64; 4]) -> Result<String, String> {
    let [x0, y0, x1, y1] = w;
    let text = toml::to_string(spec).map_err(|e| format!("the window's city spec does not serialise: {e}"))?;
    Ok(format!(
        "# Written by `netspec grow … --window {x0},{y0},{x1},{y1}`: the grown major roads (smoothed) as\n\
         # `[[road]]` entries, the water as obstacles of every level, and the sub-regions without grown\n\
         # streets running no level. Coordinates are the grown map's metres / {METRES_PER_UNIT} from its\n\
         # origin (`geo_origin`), so `netspec traffic` draws the same demand for this city and for the\n\
         # grown window.\n\n{text}"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A road through the window, a junction, a loop: chains between junctions and ends.
    #[test]
    fn chains_run_between_junctions() {
        let segs = vec![
            ([0.0, 0.0], [10.0, 0.0]),
            ([10.0, 0.0], [20.0, 0.0]),
            ([20.0, 0.0], [30.0, 0.0]),
            ([20.0, 0.0], [20.0, 10.0]),
            ([50.0, 50.0], [60.0, 50.0]),
            ([60.0, 50.0], [60.0, 60.0]),
            ([60.0, 60.0], [50.0, 50.0]),
        ];
        let c = chains(&segs);
        let lens: Vec<f64> = c.iter().map(|l| polyline_length(l)).collect();
        assert_eq!(c.len(), 4, "{c:?}");
        assert!(lens.contains(&20.0) && lens.contains(&10.0), "{lens:?}");
        let total: f64 = lens.iter().sum();
        assert!((total - (30.0 + 10.0 + 20.0 + 200f64.sqrt())).abs() < 1e-9, "{total}");
    }

    /// A route crossing the window is a flow from its entry to its exit; one ending inside is not.
    #[test]
    fn routes_across_the_window_are_flows() {
        let w = [100.0, 100.0, 200.0, 200.0];
        let across = (vec![[0.0, 150.0], [150.0, 150.0], [150.0, 300.0]], 2.0);
        let same = (vec![[0.0, 150.0], [150.0, 150.0], [150.0, 300.0]], 1.0);
        let ending = (vec![[0.0, 120.0], [150.0, 120.0]], 5.0);
        let outside = (vec![[0.0, 0.0], [50.0, 50.0]], 5.0);
        let (flows, inside) = trade_flows(&[across, same, ending, outside], w);
        assert_eq!(inside, 1);
        assert_eq!(flows, vec![TradeFlow { from: [100.0, 150.0], to: [150.0, 200.0], weight: 3.0 }]);
    }

    /// A grown network: a major road with a bridge across a river, minor streets on one side.
    /// The city spec has the road, the river as an obstacle and the unbuilt side running no level.
    #[test]
    fn a_window_becomes_a_city_spec() {
        let dir = tempfile::tempdir().expect("a temporary directory");
        // North of the road: eight streets of 540 m (11 km/km² of the 0.4 km² sub-region).
        let (mut nodes, mut segments) = (String::new(), String::new());
        for k in 0..8 {
            let y = 1040 + 50 * k;
            nodes += &format!(
                r#", {{"id": {}, "x": 410, "y": {y}}}, {{"id": {}, "x": 950, "y": {y}}}"#,
                6 + 2 * k,
                7 + 2 * k
            );
            segments += &format!(r#", {{"a": {}, "b": {}, "class": "minor"}}"#, 6 + 2 * k, 7 + 2 * k);
        }
        let json = format!(
            r#"{{"size": [2000, 2000], "spacing": 20,
            "nodes": [{{"id": 0, "x": 0, "y": 1000}}, {{"id": 1, "x": 950, "y": 1000}}, {{"id": 2, "x": 1050, "y": 1000}},
                      {{"id": 3, "x": 2000, "y": 1000}}, {{"id": 4, "x": 600, "y": 1000}}, {{"id": 5, "x": 600, "y": 1030}}{nodes}],
            "segments": [{{"a": 0, "b": 4, "class": "major"}}, {{"a": 4, "b": 1, "class": "major"}},
                         {{"a": 1, "b": 2, "class": "bridge"}}, {{"a": 2, "b": 3, "class": "major"}},
                         {{"a": 4, "b": 5, "class": "minor"}}{segments}],
            "water": [{{"river": [[1000, 0], [1000, 2000]], "width": 60}}],
            "routes": [{{"traffic": 4, "nodes": [0, 4, 1, 2, 3]}}]}}"#
        );
        std::fs::write(dir.path().join("network.json"), json).expect("written");
        let out = dir.path().join("w");
        let s = write(dir.path(), [400.0, 600.0, 1400.0, 1400.0], "w", &out).expect("a window");
        assert_eq!((s.roads, s.regions, s.empty_regions, s.obstacles, s.flows), (1, 2, 1, 1, 1), "{s:?}");
        assert!((s.road_m - 1000.0).abs() < 1e-6, "{}", s.road_m);
        let spec = CitySpec::load(&out.join("city.toml")).expect("a city spec");
        assert_eq!(spec.roads.len(), 1);
        let regions = crate::urban::city::regions(&spec).expect("sub-regions");
        let runs: Vec<Vec<u8>> = regions.iter().map(|(_, e)| spec.region_levels(*e)).collect();
        assert!(runs.contains(&vec![]) && runs.contains(&vec![2, 3, 4]), "{runs:?}");
        let level = spec.level(None, 2).expect("level 2");
        // The river less a dry strip along the road that bridges it: two pieces.
        assert_eq!(level.user.obstacle_polygons.len(), 2);
        let trade: TradeFile = serde_json::from_str(&std::fs::read_to_string(out.join("trade.json")).unwrap()).unwrap();
        assert_eq!(trade.flows[0].from, [400.0, 1000.0]);
        assert_eq!(trade.flows[0].to, [1400.0, 1000.0]);
        let e = write(dir.path(), [5000.0, 0.0, 6000.0, 10.0], "w", &out).unwrap_err().to_string();
        assert!(e.contains("network.json") && e.contains("outside the map"), "{e}");
    }
}
