//! The files of a grown network: `network.json` (metres), `series.csv` (one row per step),
//! `network.svg`/`.png`, `step-NNN.svg` snapshots and, with an `origin`, `network.geojson`
//! (WGS 84). Coordinates are rounded to the millimetre; the same seed gives the same bytes.

use super::graph::Class;
use super::step::Sim;
use super::validate::Violation;
use super::{mm, node_ids, GrowError};
use crate::geometry::geojson::GeoJsonWriter;
use crate::geometry::site::Projection;
use crate::geometry::P;
use crate::render::grow::{grow_svg, strip_svg, Bands, GrowScene, RoadLine};
use serde::Deserialize;
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn pt(p: P) -> [f64; 2] {
    [mm(p[0]), mm(p[1])]
}

/// `network.json`: nodes, road segments, waterways, water, settlements, cities, nuclei, the
/// trade routes (as node lists) and the `violations` an independent check found
/// ([`super::validate`]; empty when the network is valid).
pub fn network_json(sim: &Sim, violations: &[Violation]) -> Value {
    let ids = node_ids(sim);
    let g = &sim.graph;
    let nodes: Vec<Value> = g
        .nodes
        .iter()
        .enumerate()
        .filter_map(|(n, node)| ids[n].map(|id| json!({"id": id, "x": mm(node.pos[0]), "y": mm(node.pos[1])})))
        .collect();
    let seg = |s: &super::graph::Segment| {
        let mut v = json!({"a": ids[s.a as usize], "b": ids[s.b as usize], "class": s.class.name(), "width": s.width,
                           "step": s.born, "traffic": mm(s.load)});
        if s.fixed {
            v["fixed"] = json!(true);
        }
        v
    };
    let segments: Vec<Value> = g.segs.iter().filter(|s| s.class.is_road()).map(seg).collect();
    let waterways: Vec<Value> = g.segs.iter().filter(|s| s.class == Class::Water).map(seg).collect();
    let ctx = &sim.ctx;
    let water: Vec<Value> = ctx
        .water
        .iter()
        .map(|w| match (&w.polygon, &w.river) {
            (Some(p), _) => json!({"polygon": p.iter().map(|&q| pt(q)).collect::<Vec<_>>()}),
            (None, Some(r)) => json!({"river": r.iter().map(|&q| pt(q)).collect::<Vec<_>>(), "width": w.width}),
            _ => Value::Null,
        })
        .collect();
    let settlements: Vec<Value> = sim
        .blocks
        .settlements
        .iter()
        .map(|s| json!({"x": mm(s.center[0]), "y": mm(s.center[1]), "area": mm(s.area)}))
        .collect();
    let cities: Vec<Value> = sim
        .cities
        .iter()
        .map(|c| json!({"x": mm(c.pos[0]), "y": mm(c.pos[1]), "node": ids[c.node as usize], "water": c.water}))
        .collect();
    let nuclei: Vec<Value> = sim
        .nuclei
        .iter()
        .map(|q| json!({"x": mm(q.pos[0]), "y": mm(q.pos[1]), "strength": mm(q.strength), "step": q.born}))
        .collect();
    let routes: Vec<Value> = sim
        .traffic
        .routes
        .iter()
        .map(|r| {
            json!({"pair": sim.traffic.pairs[r.pair].cities, "traffic": mm(r.traffic), "step": r.born,
                   "nodes": r.nodes.iter().map(|&n| ids[n as usize]).collect::<Vec<_>>()})
        })
        .collect();
    let mut file = json!({
        "size": ctx.size,
        "spacing": ctx.spacing,
        "seed": sim.seed,
        "step": sim.step,
        "mu": mm(sim.mu),
        "b": mm(sim.b),
        "nodes": nodes,
        "segments": segments,
        "waterways": waterways,
        "water": water,
        "settlements": settlements,
        "cities": cities,
        "nuclei": nuclei,
        "routes": routes,
        "violations": violations,
    });
    if let Some(o) = ctx.origin {
        file["origin"] = json!(o);
    }
    file
}

/// `network.json` read back (by `netspec grow --window` and `netspec traffic`): the fields they
/// use, in metres.
#[derive(Clone, Debug, Deserialize)]
pub struct NetworkFile {
    /// The map's size.
    pub size: [f64; 2],
    /// The lattice spacing (the context's default if absent).
    #[serde(default = "default_spacing")]
    pub spacing: f64,
    /// The WGS 84 `[longitude, latitude]` of the map's `(0, 0)`, when the context has one.
    #[serde(default)]
    pub origin: Option<[f64; 2]>,
    /// Nodes with their ids.
    pub nodes: Vec<NodeRecord>,
    /// Road segments.
    pub segments: Vec<SegmentRecord>,
    /// The context's water.
    #[serde(default)]
    pub water: Vec<WaterRecord>,
    /// Trade routes as node lists.
    #[serde(default)]
    pub routes: Vec<RouteRecord>,
    /// What the independent check found (a network with any is not read as a design).
    #[serde(default)]
    pub violations: Vec<serde_json::Value>,
}

fn default_spacing() -> f64 {
    20.0
}

/// A node of `network.json`.
#[derive(Clone, Debug, Deserialize)]
pub struct NodeRecord {
    /// Its id.
    pub id: usize,
    /// x, metres.
    pub x: f64,
    /// y, metres.
    pub y: f64,
}

/// A road segment of `network.json`.
#[derive(Clone, Debug, Deserialize)]
pub struct SegmentRecord {
    /// One end's node id.
    pub a: usize,
    /// The other end's.
    pub b: usize,
    /// `major`, `minor`, `bridge` or `harbour`.
    pub class: String,
    /// The traffic the model put on it.
    #[serde(default)]
    pub traffic: Option<f64>,
}

/// A water body of `network.json`: a polygon, or a river line with its width.
#[derive(Clone, Debug, Deserialize)]
pub struct WaterRecord {
    /// A lake or sea outline.
    #[serde(default)]
    pub polygon: Option<Vec<P>>,
    /// A river's centre line.
    #[serde(default)]
    pub river: Option<Vec<P>>,
    /// The river's width.
    #[serde(default)]
    pub width: Option<f64>,
}

/// A trade route of `network.json`.
#[derive(Clone, Debug, Deserialize)]
pub struct RouteRecord {
    /// Its traffic.
    pub traffic: f64,
    /// Its nodes, in order.
    pub nodes: Vec<Option<usize>>,
}

impl NetworkFile {
    /// Parses `network.json`'s text; a network the independent check found violations in is
    /// refused (`Err` with the count).
    pub fn from_json(text: &str) -> Result<NetworkFile, String> {
        let net: NetworkFile = serde_json::from_str(text).map_err(|e| e.to_string())?;
        match net.violations.len() {
            0 => Ok(net),
            n => Err(format!("{n} violations of the network's invariants (`violations`)")),
        }
    }

    /// Node positions by id.
    pub fn positions(&self) -> BTreeMap<usize, P> {
        self.nodes.iter().map(|n| (n.id, [n.x, n.y])).collect()
    }

    /// The ends of segment `i`, or the message naming the field whose node is missing.
    pub fn segment_ends(&self, pos: &BTreeMap<usize, P>, i: usize) -> Result<(P, P), String> {
        let s = &self.segments[i];
        let at = |id: usize| pos.get(&id).copied().ok_or_else(|| format!("segments[{i}]: node {id} is not in `nodes`"));
        Ok((at(s.a)?, at(s.b)?))
    }
}

/// `series.csv`: a header and one row per step.
pub fn series_csv(sim: &Sim) -> String {
    let mut out = String::from(
        "step,settlements,built_up_ha,blocks,minor_km,major_km,nuclei,ports,bridges,trade_routes,new_routes,overflow,four_way_share,orientation_entropy,lane_km_added,lane_km,dead_end_share,block_median_m2\n",
    );
    for r in &sim.series {
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            r.step,
            r.settlements,
            r.built_up_ha,
            r.blocks,
            r.minor_km,
            r.major_km,
            r.nuclei,
            r.ports,
            r.bridges,
            r.trade_routes,
            r.new_routes,
            r.overflow,
            r.four_way_share,
            r.orientation_entropy,
            r.lane_km_added,
            r.lane_km,
            r.dead_end_share,
            r.block_median_m2
        ));
    }
    out
}

/// Minor-road segments that are stubs: dead-end streets, found by pruning minor segments with
/// an end no other road segment meets until none is left (what remains bounds a block or joins
/// other roads).
pub fn stubs(sim: &Sim) -> Vec<bool> {
    let g = &sim.graph;
    let mut stub = vec![false; g.segs.len()];
    let mut degree: Vec<usize> = (0..g.nodes.len() as u32).map(|n| g.road_degree(n)).collect();
    let mut leaves: Vec<u32> = (0..g.nodes.len() as u32).filter(|&n| degree[n as usize] == 1).collect();
    while let Some(n) = leaves.pop() {
        let Some(&s) = g.adj[n as usize].iter().find(|&&s| g.segs[s as usize].class.is_road() && !stub[s as usize])
        else {
            continue;
        };
        if g.segs[s as usize].class != Class::Minor || degree[n as usize] != 1 {
            continue;
        }
        stub[s as usize] = true;
        degree[n as usize] -= 1;
        let m = g.other(s, n);
        degree[m as usize] -= 1;
        if degree[m as usize] == 1 {
            leaves.push(m);
        }
    }
    stub
}

/// Straight pieces of the contour lines at `levels` of an elevation raster (`nx × ny` samples
/// `cell` metres apart, row 0 at y = 0), by marching squares.
fn contours(z: &[f64], nx: usize, ny: usize, cell: f64, levels: &[f64]) -> Vec<[P; 2]> {
    let mut out = Vec::new();
    for y in 0..ny.saturating_sub(1) {
        for x in 0..nx.saturating_sub(1) {
            // Corners counter-clockwise from the lower left, and the edges between them.
            let c = [(x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)];
            let v: Vec<f64> = c.iter().map(|&(i, j)| z[j * nx + i]).collect();
            for &level in levels {
                let mut pts = Vec::new();
                for e in 0..4 {
                    let (a, b) = (e, (e + 1) % 4);
                    if (v[a] > level) != (v[b] > level) {
                        let f = (level - v[a]) / (v[b] - v[a]);
                        let p = |k: usize| [c[k].0 as f64 * cell, c[k].1 as f64 * cell];
                        let (pa, pb) = (p(a), p(b));
                        pts.push([pa[0] + (pb[0] - pa[0]) * f, pa[1] + (pb[1] - pa[1]) * f]);
                    }
                }
                for pair in pts.chunks_exact(2) {
                    out.push([pair[0], pair[1]]);
                }
            }
        }
    }
    out
}

/// The picture's plain data; minor roads that are [`stubs`] are left out unless `all_streets`.
pub fn scene(sim: &Sim, all_streets: bool) -> GrowScene {
    let t = &sim.lattice.terrain;
    // Contour bands of 60 m would leave flat maps in one band: the band height is the larger of
    // 10 m and a sixth of the relief; contour lines run between the bands.
    let (lo, hi) = t.z.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), &z| (l.min(z), h.max(z)));
    let step = ((hi - lo) as f64 / 6.0).max(10.0);
    let k = (t.nx.max(t.ny) / 200).max(1);
    let (bx, by) = (t.nx.div_ceil(k), t.ny.div_ceil(k));
    let mut band = Vec::with_capacity(bx * by);
    let mut z = Vec::with_capacity(bx * by);
    for y in 0..by {
        for x in 0..bx {
            let h = t.z[(y * k).min(t.ny - 1) * t.nx + (x * k).min(t.nx - 1)];
            band.push((((h - lo) as f64 / step).floor() as u8).min(7));
            z.push(h as f64);
        }
    }
    let levels: Vec<f64> = (1..8).map(|i| lo as f64 + i as f64 * step).filter(|&l| l < hi as f64).collect();
    let cell = t.spacing * k as f64;
    let last = sim.step.max(1) as f64;
    let g = &sim.graph;
    let hidden = if all_streets { vec![false; g.segs.len()] } else { stubs(sim) };
    GrowScene {
        size: sim.ctx.size,
        bands: Bands { nx: bx, ny: by, cell, band },
        contours: contours(&z, bx, by, cell, &levels),
        water: sim.ctx.water.iter().filter_map(|w| w.polygon.clone()).collect(),
        rivers: sim.ctx.water.iter().filter_map(|w| Some((w.river.clone()?, w.width?))).collect(),
        forbidden: sim.ctx.forbidden.iter().map(|f| f.polygon.clone()).collect(),
        blocks: sim
            .blocks
            .faces
            .iter()
            .filter(|f| f.built_up)
            .map(|f| (f.ring.clone(), f.born as f64 / last))
            .collect(),
        roads: g
            .segs
            .iter()
            .enumerate()
            .filter(|&(s, _)| !hidden[s])
            .map(|(s, seg)| {
                let (a, b) = g.ends(s as u32);
                RoadLine { a, b, class: seg.class.name(), width: seg.width }
            })
            .collect(),
        cities: sim.cities.iter().map(|c| c.pos).collect(),
        nuclei: sim.nuclei.iter().map(|q| q.pos).collect(),
        caption: caption(sim),
    }
}

fn caption(sim: &Sim) -> String {
    let r = sim.series.last().expect("step 0 is always there");
    format!(
        "step {}: {} settlements, {:.0} ha built up, {} blocks, {:.1} km minor, {:.1} km major, {} ports, {} bridges, {} trade routes",
        r.step, r.settlements, r.built_up_ha, r.blocks, r.minor_km, r.major_km, r.ports, r.bridges, r.trade_routes
    )
}

/// Writes `bytes` to `dir/name`, naming the file on failure.
pub(crate) fn write(dir: &Path, name: &str, bytes: &[u8]) -> Result<PathBuf, GrowError> {
    let path = dir.join(name);
    std::fs::write(&path, bytes).map_err(|source| GrowError::Io { path: path.clone(), source })?;
    Ok(path)
}

/// Writes `step-NNN.svg` of a step's scene.
pub fn write_snapshot(dir: &Path, step: u32, scene: &GrowScene) -> Result<PathBuf, GrowError> {
    write(dir, &format!("step-{step:03}.svg"), grow_svg(scene).as_bytes())
}

/// Panels to a row in a strip of pictures.
pub const STRIP_COLUMNS: usize = 5;

/// Writes `NAME.svg` and `NAME.png`: the scenes side by side, [`STRIP_COLUMNS`] to a row.
pub fn write_strip(dir: &Path, name: &str, scenes: &[GrowScene]) -> Result<Vec<PathBuf>, GrowError> {
    let svg = strip_svg(scenes, STRIP_COLUMNS, 400.0);
    Ok(vec![
        write(dir, &format!("{name}.svg"), svg.as_bytes())?,
        write(dir, &format!("{name}.png"), &crate::render::png(&svg)?)?,
    ])
}

/// Writes `network.json` (with `violations`), `series.csv`, `network.svg`, `network.png` and
/// (with an origin) `network.geojson`; the pictures leave stubs out unless `all_streets`.
pub fn write_all(
    dir: &Path,
    sim: &Sim,
    violations: &[Violation],
    all_streets: bool,
) -> Result<Vec<PathBuf>, GrowError> {
    let mut files = Vec::new();
    let json = serde_json::to_string(&network_json(sim, violations)).expect("JSON serialises") + "\n";
    files.push(write(dir, "network.json", json.as_bytes())?);
    files.push(write(dir, "series.csv", series_csv(sim).as_bytes())?);
    let svg = grow_svg(&scene(sim, all_streets));
    files.push(write(dir, "network.svg", svg.as_bytes())?);
    files.push(write(dir, "network.png", &crate::render::png(&svg)?)?);
    if let Some(origin) = sim.ctx.origin {
        let geo = geojson(sim, &Projection::new(origin)?)?;
        files.push(write(dir, "network.geojson", geo.as_bytes())?);
    }
    Ok(files)
}

/// The network in WGS 84: road and waterway segments (`kind`, `class`, `width`, `step`), water,
/// cities and settlements; the map's origin `(0, 0)` is the context's `origin`.
pub fn geojson(sim: &Sim, proj: &Projection) -> Result<String, GrowError> {
    let mut w = GeoJsonWriter::new(proj);
    for (s, g) in sim.graph.segs.iter().enumerate() {
        let (a, b) = sim.graph.ends(s as u32);
        let kind = if g.class == Class::Water { "waterway" } else { "road" };
        let props =
            json!({"kind": kind, "class": g.class.name(), "width": g.width, "step": g.born, "traffic": mm(g.load)});
        w.line(&[a, b], props)?;
    }
    for wt in &sim.ctx.water {
        if let Some(poly) = &wt.polygon {
            w.polygon([poly.as_slice()], json!({"kind": "water"}))?;
        }
        if let (Some(line), Some(width)) = (&wt.river, wt.width) {
            w.line(line, json!({"kind": "river", "width": width}))?;
        }
    }
    for c in &sim.cities {
        w.point(c.pos, json!({"kind": "neighbour-city", "water": c.water}))?;
    }
    for s in &sim.blocks.settlements {
        w.point(s.center, json!({"kind": "settlement", "area": mm(s.area)}))?;
    }
    Ok(w.to_json(Value::Null))
}
