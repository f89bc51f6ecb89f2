//! The design graph to simulate, in metres: read from a `netspec solve` output (`result.json`:
//! the mesh and the active edges) or a `netspec city` output (`city.json` and every region's
//! saved roads, merged and smoothed exactly as the city run did).
//!
//! Node ids are the design's own vertex ids (mesh vertices of a solve; vertices of the merged
//! street graph of a city) and edge ids the design's edge ids (mesh edges; street graph edges),
//! so every SUMO element traces back to the design.

use super::{read, TrafficError, TrafficErrorKind};
use crate::geometry as geom;
use crate::pipeline::DesignResult;
use crate::urban::city::saved_roads;
use crate::urban::output::street_graph;
use crate::urban::smooth::{self, StreetGraph};
use crate::urban::CityResult;
use std::collections::BTreeMap;
use std::path::Path;

/// Metres per model unit for a `solve` design when none is given (a spec has no scale; the
/// Fig. 7 city specs use 20).
pub const DEFAULT_METRES_PER_UNIT: f64 = 20.0;

pub use crate::design::streets::DEFAULT_SOLVE_LEVEL;

pub use super::road::{Provenance, Region, RoadEdge, RoadNetwork, RoadNode};

/// How to read a design.
#[derive(Clone, Debug, Default)]
pub struct LoadOptions {
    /// Metres per model unit (default: the city spec's, or [`DEFAULT_METRES_PER_UNIT`]).
    pub metres_per_unit: Option<f64>,
    /// The level of a `solve` design's streets (default [`DEFAULT_SOLVE_LEVEL`]).
    pub level: Option<u8>,
    /// The window `[x0, y0, x1, y1]` (metres) of a `netspec grow` network (default: its map).
    pub window: Option<[f64; 4]>,
    /// A site to judge the design on (`netspec site`'s `site.geojson`, or any GeoJSON region):
    /// the design is moved into the site's metres (through WGS 84, so it needs an origin of its
    /// own), its region becomes the site's outline, and it is clipped there.
    pub region: Option<SiteRegion>,
}

/// A region read from a GeoJSON site: the polygon (local metres) and its projection.
#[derive(Clone, Debug)]
pub struct SiteRegion {
    /// The file, for messages.
    pub path: std::path::PathBuf,
    /// The polygon, with its holes.
    pub polygon: crate::geometry::Polygon,
    /// WGS 84 ↔ the polygon's metres.
    pub projection: crate::geometry::site::Projection,
}

impl SiteRegion {
    /// Reads the region of a GeoJSON site file (its one Polygon feature).
    pub fn load(path: &Path) -> Result<SiteRegion, TrafficError> {
        let text = read(path)?;
        let site = crate::geometry::site::read_geojson(&text).map_err(|e| {
            TrafficError::new(path, TrafficErrorKind::Parse { what: "a GeoJSON site", message: e.to_string() })
        })?;
        Ok(SiteRegion { path: path.to_path_buf(), polygon: site.polygon, projection: site.projection })
    }
}

/// Reads a design as it is simulated: [`load_whole`], then moved onto `opts.region` when one is
/// given, and clipped to its region when it reaches beyond it (the real streets of a `map/`).
pub fn load(path: &Path, opts: &LoadOptions) -> Result<RoadNetwork, TrafficError> {
    let (net, region) = load_whole(path, opts)?;
    let polygon = match region {
        Some(r) => r,
        None if net.source.kind == "streets" => {
            match crate::geometry::Polygon::new(net.region.boundary.clone(), vec![]) {
                Ok(p) => p,
                Err(e) => return Err(TrafficError::new(path, TrafficErrorKind::Invalid(format!("its region: {e}")))),
            }
        }
        None => return Ok(net),
    };
    let clipped = clip(&net, &polygon);
    if clipped.edges.is_empty() {
        return Err(TrafficError::new(path, TrafficErrorKind::NoNetwork("no street inside the region".into())));
    }
    Ok(clipped)
}

/// Reads a design whole, and the polygon it is to be judged on when `opts.region` gives one (the
/// design then moved into the region's metres, its region the region's outline): a
/// `result.json` file, a directory with one (a `netspec solve` output or a city level's
/// directory), a `netspec city` output directory (with `city.json`), a `netspec layout` output
/// directory (with `layout.json`), a `netspec grow` output directory (with `network.json` and
/// `series.csv`), a `netspec site` map (a directory with `streets.geojson`) or a GeoJSON file of
/// streets.
pub fn load_whole(
    path: &Path,
    opts: &LoadOptions,
) -> Result<(RoadNetwork, Option<crate::geometry::Polygon>), TrafficError> {
    let net = load_design(path, opts)?;
    let Some(site) = &opts.region else { return Ok((net, None)) };
    let Some(origin) = net.origin else {
        return Err(TrafficError::new(
            path,
            TrafficErrorKind::Invalid(format!(
                "the design has no place on the map (no WGS 84 origin), so it cannot be judged on {}",
                site.path.display()
            )),
        ));
    };
    let mut net = reframe(&net, origin, &site.projection)
        .map_err(|e| TrafficError::new(path, TrafficErrorKind::Invalid(e.to_string())))?;
    let outer = site.polygon.outer().to_vec();
    net.region = Region { boundary: outer.clone(), areas: vec![outer] };
    Ok((net, Some(site.polygon.clone())))
}

/// The network moved from the metres around `from` (WGS 84) into those of `to`: through WGS 84,
/// point by point (the same network when the origins agree).
pub fn reframe(
    net: &RoadNetwork,
    from: [f64; 2],
    to: &crate::geometry::site::Projection,
) -> Result<RoadNetwork, crate::geometry::site::SiteError> {
    if from == to.origin() {
        return Ok(net.clone());
    }
    let src = crate::geometry::site::Projection::new(from)?;
    let mv = |p: [f64; 2]| -> Result<[f64; 2], crate::geometry::site::SiteError> { to.to_local(src.to_wgs84(p)?) };
    let mut out = net.clone();
    for n in &mut out.nodes {
        n.pos = mv(n.pos)?;
    }
    for e in &mut out.edges {
        e.shape = e.shape.iter().map(|&p| mv(p)).collect::<Result<_, _>>()?;
    }
    for ring in std::iter::once(&mut out.region.boundary).chain(out.region.areas.iter_mut()) {
        *ring = ring.iter().map(|&p| mv(p)).collect::<Result<_, _>>()?;
    }
    out.origin = Some(to.origin());
    Ok(out)
}

/// The network clipped to a polygon (its boundary included): a street leaving it ends at a new
/// node where it crosses the boundary, an entrance when the street is a major road (level 1).
/// Streets wholly inside keep their ends.
pub fn clip(net: &RoadNetwork, polygon: &crate::geometry::Polygon) -> RoadNetwork {
    let tol = crate::stats::BOUNDARY_TOL;
    let mut nodes: Vec<RoadNode> = Vec::new();
    let mut kept: BTreeMap<usize, usize> = BTreeMap::new();
    let mut next_id = net.nodes.iter().map(|n| n.id).max().map_or(0, |m| m + 1);
    let mut edges = Vec::new();
    let mut keep = |i: usize, nodes: &mut Vec<RoadNode>| {
        *kept.entry(i).or_insert_with(|| {
            nodes.push(net.nodes[i].clone());
            nodes.len() - 1
        })
    };
    for e in &net.edges {
        let pieces = polygon.clip_polyline(&e.shape, tol);
        for piece in pieces {
            let (p, q) = (piece[0], piece[piece.len() - 1]);
            let mut end = |at: P, original: usize, nodes: &mut Vec<RoadNode>| {
                if geom::dist(at, net.nodes[original].pos) <= tol {
                    keep(original, nodes)
                } else {
                    nodes.push(RoadNode { id: next_id, pos: at, entrance: e.level == 1 });
                    next_id += 1;
                    nodes.len() - 1
                }
            };
            let a = end(p, e.a, &mut nodes);
            let b = end(q, e.b, &mut nodes);
            edges.push(RoadEdge { id: edges.len() as u32, a, b, shape: piece, ..e.clone() });
        }
    }
    let outer = polygon.outer().to_vec();
    RoadNetwork { nodes, edges, region: Region { boundary: outer.clone(), areas: vec![outer] }, ..net.clone() }
}

type P = [f64; 2];

fn load_design(path: &Path, opts: &LoadOptions) -> Result<RoadNetwork, TrafficError> {
    let md = std::fs::metadata(path).map_err(|e| TrafficError::new(path, e.into()))?;
    let file = if md.is_dir() {
        if path.join("city.json").is_file() {
            return from_city(path, opts);
        }
        if path.join("layout.json").is_file() {
            return super::streets::from_layout(path);
        }
        if path.join("network.json").is_file() && path.join("series.csv").is_file() {
            return super::streets::from_grow(path, opts.window);
        }
        if path.join("streets.geojson").is_file() {
            return super::streets::from_geojson(path);
        }
        let f = path.join("result.json");
        if !f.is_file() {
            return Err(TrafficError::new(path, TrafficErrorKind::NoResult));
        }
        f
    } else if path.extension().is_some_and(|e| e == "geojson" || e == "json" && is_geojson(path)) {
        return super::streets::from_geojson(path);
    } else {
        path.to_path_buf()
    };
    let text = read(&file)?;
    let res: DesignResult = serde_json::from_str(&text).map_err(|e| {
        TrafficError::new(&file, TrafficErrorKind::Parse { what: "a netspec design result", message: e.to_string() })
    })?;
    from_design(&res, &file, opts)
}

/// Whether a `.json` file is GeoJSON (a FeatureCollection).
fn is_geojson(path: &Path) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| t.contains("\"FeatureCollection\""))
}

fn fmt_opt(v: Option<f64>, f: impl Fn(f64) -> String) -> String {
    v.map_or("-".into(), f)
}

/// The network of a design result (`path` is named in errors and the provenance).
pub fn from_design(res: &DesignResult, path: &Path, opts: &LoadOptions) -> Result<RoadNetwork, TrafficError> {
    let err = |kind| TrafficError::new(path, kind);
    let s = &res.solve;
    let Some(net) = &res.network else {
        return Err(err(TrafficErrorKind::NoNetwork(format!("solver {}: {}", s.solver, s.termination.label()))));
    };
    if !res.validity.valid {
        let n =
            res.validity.design_violations.len() + res.validity.milp_check.as_ref().map_or(0, |c| c.violations.len());
        return Err(err(TrafficErrorKind::Invalid(format!("{n} violations"))));
    }
    let m = opts.metres_per_unit.unwrap_or(DEFAULT_METRES_PER_UNIT);
    let level = opts.level.unwrap_or(DEFAULT_SOLVE_LEVEL);
    let mesh = &res.mesh;
    let mut is_sink = vec![false; mesh.num_vertices()];
    for &v in &res.sinks {
        if let Some(x) = is_sink.get_mut(v as usize) {
            *x = true;
        }
    }
    let scaled = |p: [f64; 2]| [p[0] * m, p[1] * m];
    let mut node_of = BTreeMap::new();
    let mut nodes = Vec::new();
    let mut edges = Vec::new();
    for e in net.active_edges() {
        let (va, vb) = mesh.edge_vertices(e);
        let mut ends = [0usize; 2];
        for (k, v) in [va, vb].into_iter().enumerate() {
            ends[k] = *node_of.entry(v.0).or_insert_with(|| {
                nodes.push(RoadNode { id: v.0, pos: scaled(mesh.position(v)), entrance: is_sink[v.index()] });
                nodes.len() - 1
            });
        }
        edges.push(RoadEdge {
            id: e.0,
            a: ends[0],
            b: ends[1],
            level,
            shape: vec![nodes[ends[0]].pos, nodes[ends[1]].pos],
            local: true,
            predicted_load: None,
            oneway: false,
        });
    }
    if edges.is_empty() {
        return Err(err(TrafficErrorKind::NoNetwork("no active edge".into())));
    }
    // The region: the mesh's outer boundary loop (largest area) and its faces.
    let loops: Vec<Vec<[f64; 2]>> = mesh
        .boundary_loops()
        .iter()
        .map(|l| l.iter().map(|&h| scaled(mesh.position(mesh.he_tail(h)))).collect())
        .collect();
    let boundary = loops
        .into_iter()
        .max_by(|a, b| geom::signed_area(a).abs().total_cmp(&geom::signed_area(b).abs()))
        .unwrap_or_default();
    let areas =
        mesh.faces().map(|f| mesh.face_vertices(f).iter().map(|&v| scaled(mesh.position(v))).collect()).collect();
    let run = format!(
        "{} {}: {}, objective {}, gap {}, {:.1} s, valid",
        s.solver,
        s.solver_version,
        s.termination.label(),
        fmt_opt(s.objective, |v| format!("{v:.4}")),
        fmt_opt(s.gap, |g| format!("{:.2}%", 100.0 * g)),
        s.wall_time
    );
    Ok(RoadNetwork {
        name: res.spec.name.clone(),
        source: Provenance {
            kind: "solve".into(),
            path: path.display().to_string(),
            netspec_version: res.netspec_version.clone(),
            description: res.spec.description.clone(),
            runs: vec![run],
        },
        metres_per_unit: m,
        nodes,
        edges,
        region: Region { boundary, areas },
        origin: None,
    })
}

/// The network of a `netspec city` output directory: every region's roads after its last
/// level with a network, merged into one street graph and smoothed as `city` does (the
/// snakes' ends are the graph's vertices; the snapping of street ends onto the major roads,
/// done for pictures only, is not applied).
pub fn from_city(dir: &Path, opts: &LoadOptions) -> Result<RoadNetwork, TrafficError> {
    let file = dir.join("city.json");
    let text = read(&file)?;
    let mut city: CityResult = serde_json::from_str(&text).map_err(|e| {
        TrafficError::new(&file, TrafficErrorKind::Parse { what: "a netspec city result", message: e.to_string() })
    })?;
    if !city.valid {
        return Err(TrafficError::new(&file, TrafficErrorKind::Invalid("city.json says valid = false".into())));
    }
    let spec = city.spec.clone();
    let m = opts.metres_per_unit.unwrap_or(spec.metres_per_unit);
    let mut runs = Vec::new();
    for r in &mut city.regions {
        r.roads = saved_roads(&spec, dir, r).map_err(|e| {
            TrafficError::new(dir, TrafficErrorKind::Parse { what: "the city's saved roads", message: e.to_string() })
        })?;
        for l in &r.levels {
            runs.push(format!(
                "{:02} {} L{}: {} {}, objective {}, gap {}, {} s{}",
                r.index,
                r.name,
                l.level,
                l.state,
                l.termination.as_deref().unwrap_or("-"),
                fmt_opt(l.objective, |v| format!("{v:.4}")),
                fmt_opt(l.gap, |g| format!("{:.2}%", 100.0 * g)),
                fmt_opt(l.wall_time, |t| format!("{t:.1}")),
                match l.valid {
                    Some(true) => ", valid".to_string(),
                    Some(false) => ", INVALID".to_string(),
                    None => l.message.as_ref().map_or(String::new(), |m| format!(" ({m})")),
                }
            ));
        }
    }
    runs.push(format!(
        "backend {}, threads {:?}, time limit override {}",
        city.solver,
        city.threads,
        fmt_opt(city.time_limit_override, |t| format!("{t} s"))
    ));
    let (graph, _, _) = street_graph(&city.regions, spec.mesh.spacing);
    let smoothed = smooth::by_method(&graph, spec.smoothing.method);
    let (positions, shapes) = smoothed_geometry(&graph, &smoothed.snakes);
    let scaled = |p: [f64; 2]| [p[0] * m, p[1] * m];
    let outer: Vec<[f64; 2]> = spec.domain.outer.iter().map(|&p| scaled(p)).collect();
    // The domain's boundary: mesh boundary edges of exactly one sub-region (a major road
    // between two sub-regions bounds both).
    let key = |p: [f64; 2]| {
        ((p[0] / spec.mesh.spacing * 1e3).round() as i64, (p[1] / spec.mesh.spacing * 1e3).round() as i64)
    };
    let edge_key = |p: [f64; 2], q: [f64; 2]| if key(p) <= key(q) { (key(p), key(q)) } else { (key(q), key(p)) };
    let mut bounding: BTreeMap<_, usize> = BTreeMap::new();
    for roads in city.regions.iter().filter_map(|r| r.roads.as_ref()) {
        for e in roads.mesh.boundary_edges() {
            let (a, b) = roads.mesh.edge_vertices(e);
            *bounding.entry(edge_key(roads.mesh.position(a), roads.mesh.position(b))).or_default() += 1;
        }
    }
    let mut node_of = BTreeMap::new();
    let mut nodes = Vec::new();
    let mut edges = Vec::new();
    for (k, e) in graph.edges.iter().enumerate() {
        let mut ends = [0usize; 2];
        for (j, v) in [e.a, e.b].into_iter().enumerate() {
            ends[j] = *node_of.entry(v).or_insert_with(|| {
                nodes.push(RoadNode { id: v, pos: scaled(positions[v as usize]), entrance: false });
                nodes.len() - 1
            });
        }
        let shape: Vec<[f64; 2]> = shapes[k].iter().map(|&p| scaled(p)).collect();
        // A major road along the domain's boundary: through traffic enters and leaves there.
        if e.level == 1
            && bounding.get(&edge_key(graph.positions[e.a as usize], graph.positions[e.b as usize])) == Some(&1)
        {
            nodes[ends[0]].entrance = true;
            nodes[ends[1]].entrance = true;
        }
        edges.push(RoadEdge {
            id: k as u32,
            a: ends[0],
            b: ends[1],
            level: e.level,
            shape,
            local: e.level >= 2,
            predicted_load: None,
            oneway: false,
        });
    }
    if edges.is_empty() {
        return Err(TrafficError::new(&file, TrafficErrorKind::NoNetwork("the city has no streets".into())));
    }
    Ok(RoadNetwork {
        name: spec.name.clone(),
        source: Provenance {
            kind: "city".into(),
            path: file.display().to_string(),
            netspec_version: city.netspec_version.clone(),
            description: spec.description.clone(),
            runs,
        },
        metres_per_unit: m,
        nodes,
        edges,
        region: Region { boundary: outer.clone(), areas: vec![outer] },
        origin: spec.geo_origin,
    })
}

/// The smoothed geometry of a street graph (model units): every vertex's position (snake ends
/// stay where they are; vertices inside a snake move with it) and every edge's piece of its
/// snake, oriented from its `a` to its `b` — the straight segment where the snakes do not cover
/// an edge evenly.
pub fn smoothed_geometry(graph: &StreetGraph, snakes: &[smooth::Snake]) -> (Vec<[f64; 2]>, Vec<Vec<[f64; 2]>>) {
    let mut positions = graph.positions.clone();
    let mut index = BTreeMap::new();
    for (k, e) in graph.edges.iter().enumerate() {
        index.entry((e.a.min(e.b), e.a.max(e.b))).or_insert(k);
    }
    let mut shapes: Vec<Vec<[f64; 2]>> =
        graph.edges.iter().map(|e| vec![graph.positions[e.a as usize], graph.positions[e.b as usize]]).collect();
    for s in snakes {
        let n = s.vertices.len();
        if n < 2 || s.points.len() < n || (s.points.len() - 1) % (n - 1) != 0 {
            continue;
        }
        let sub = (s.points.len() - 1) / (n - 1);
        for i in 0..n - 1 {
            let (u, v) = (s.vertices[i], s.vertices[i + 1]);
            let Some(&k) = index.get(&(u.min(v), u.max(v))) else { continue };
            let mut piece = s.points[i * sub..=(i + 1) * sub].to_vec();
            positions[u as usize] = piece[0];
            positions[v as usize] = piece[sub];
            if graph.edges[k].a != u {
                piece.reverse();
            }
            shapes[k] = piece;
        }
    }
    (positions, shapes)
}
