//! A finished city: the street graph of all sub-regions, smoothed; its metrics; and the files
//! (`city.json`, `streets.geojson`, `city.svg`, `city.png`).

use super::city::{self, CityError, CityRunOptions, RegionReport};
use super::smooth::{self, Snake, StreetEdge, StreetGraph};
use super::spec::{CitySpec, SmoothingMethod};
use crate::design::streets::{streets_geojson, GeoAnchor, GeoRegion};
use crate::geometry as geom;
use crate::geometry::planar::{PlanarGraph, Region};
use crate::render::city::{CityPicture, RegionShape};
use crate::stats::yang::{street_metrics, StreetMetrics};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Version of the city result schema (`city.json`).
pub const CITY_SCHEMA_VERSION: u32 = 1;

/// The smoothing step's summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SmoothingSummary {
    /// The smoother.
    pub method: SmoothingMethod,
    /// Snakes (chains between junctions, dead-ends and level changes).
    pub snakes: usize,
    /// Energy before.
    pub energy_before: f64,
    /// Energy after.
    pub energy_after: f64,
    /// Iterations.
    pub iterations: usize,
    /// Whether the energy change fell below the tolerance.
    pub converged: bool,
    /// Street length after smoothing, km.
    pub smoothed_length_km: f64,
}

/// Everything about a city run (`city.json`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CityResult {
    /// Always `netspec.city`.
    pub schema: String,
    /// [`CITY_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The netspec version.
    pub netspec_version: String,
    /// The city spec, echoed.
    pub spec: CitySpec,
    /// Backend.
    pub solver: String,
    /// Time limit override from the command line, if any.
    pub time_limit_override: Option<f64>,
    /// Thread budget and threads per solve.
    pub threads: [u32; 2],
    /// Sub-regions and their levels (the per-level design results are in
    /// `regions/NN-name/L<n>/result.json`).
    pub regions: Vec<RegionReport>,
    /// Every level of every sub-region produced a network.
    pub complete: bool,
    /// Every network produced passed every independent check.
    pub valid: bool,
    /// Street metrics of the mesh network (Yang et al. §7), per km².
    pub metrics: StreetMetrics,
    /// The layout metrics of `netspec layout` (Yang et al. §7, land use and parcel shape
    /// included) on the smoothed streets, every street 15 m wide, the blocks cut by the layout's
    /// parceller into 30 × 18 m parcels: IP streets and split streets measured on equal terms.
    /// `None` when the domain is not a simple polygon.
    #[serde(default)]
    pub layout_metrics: Option<crate::layout::metrics::Metrics>,
    /// Smoothing.
    pub smoothing: SmoothingSummary,
    /// Wall time of the run, seconds (levels reused from an earlier run count as 0).
    pub wall_time: f64,
}

/// The city's streets as one graph: sub-region meshes' roads with coincident vertices merged
/// ([`PlanarGraph::from_vertices_edges_mapped`]), each edge with its level (1 for sub-region
/// boundaries, the major roads; the lowest where regions share an edge); the same graph without
/// levels (for the metrics); and per merged vertex whether streets may join the major road there
/// (see [`super::city::RegionRoads::joins_major`]).
pub fn street_graph(regions: &[RegionReport], spacing: f64) -> (StreetGraph, PlanarGraph, Vec<bool>) {
    // Both ends of every road edge, each edge with its level, each end with whether it joins.
    let (mut ends, mut pairs, mut levels, mut joinable) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for roads in regions.iter().filter_map(|r| r.roads.as_ref()) {
        for e in roads.mesh.edges().filter(|e| roads.edge_level[e.index()] > 0) {
            let (va, vb) = roads.mesh.edge_vertices(e);
            let k = ends.len() as u32;
            for v in [va, vb] {
                ends.push(roads.mesh.position(v));
                joinable.push(roads.joins_major.get(v.index()).copied().unwrap_or(roads.joins_major.is_empty()));
            }
            pairs.push([k, k + 1]);
            levels.push(roads.edge_level[e.index()]);
        }
    }
    let (planar, map) = PlanarGraph::from_vertices_edges_mapped(&ends, &pairs, spacing * 1e-6);
    let mut level_of: std::collections::BTreeMap<[u32; 2], u8> = std::collections::BTreeMap::new();
    for (pair, level) in pairs.iter().zip(levels) {
        let (a, b) = (map[pair[0] as usize], map[pair[1] as usize]);
        let l = level_of.entry([a.min(b), a.max(b)]).or_insert(level);
        *l = (*l).min(level);
    }
    let mut joins = vec![false; planar.positions.len()];
    for (i, j) in joinable.into_iter().enumerate() {
        joins[map[i] as usize] |= j;
    }
    let edges = planar.edges.iter().map(|&[a, b]| StreetEdge { a, b, level: level_of[&[a, b]] }).collect();
    (StreetGraph { positions: planar.positions.clone(), edges }, planar, joins)
}

fn polyline_length(points: &[[f64; 2]]) -> f64 {
    points.windows(2).map(|w| geom::dist(w[0], w[1])).sum()
}

/// The layout metrics of a city's streets (see [`CityResult::layout_metrics`]): the domain and the
/// streets in metres, the major roads and the domain boundary as level-0 streets, parcels from
/// the built-in templates block by block and the row parceller where none is accepted.
pub fn layout_metrics(
    spec: &CitySpec,
    major: &[[[f64; 2]; 2]],
    streets: &[Snake],
) -> Option<crate::layout::metrics::Metrics> {
    use crate::layout::split::Selection;
    use crate::layout::template::parcellate_with_templates;
    use crate::layout::{metrics, parcels, Street};
    let m = spec.metres_per_unit;
    let scale = |pts: &[[f64; 2]]| pts.iter().map(|p| [p[0] * m, p[1] * m]).collect::<Vec<_>>();
    let polygon = crate::geometry::Polygon::new(scale(&spec.domain.outer), Vec::new()).ok()?;
    let region = crate::layout::region::Region::with_defaults(&spec.name, polygon, Vec::new());
    let width = region.street_width(0);
    let mut all: Vec<Street> = major
        .iter()
        .map(|g| Street::new(scale(g), width, 0))
        .chain(
            streets
                .iter()
                .filter(|s| s.points.len() >= 2)
                .map(|s| Street::new(scale(&s.points), width, s.level as usize)),
        )
        .collect();
    let blocks = parcels::blocks(&region.polygon, &all);
    let mut rng = <rand::rngs::Xoshiro256PlusPlus as rand::SeedableRng>::seed_from_u64(region.seed);
    let t = parcellate_with_templates(&blocks, &all, &region, &region.templates, Selection::Best, &mut rng);
    all.extend(t.streets);
    Some(metrics::metrics(&region.polygon, &all, &blocks, &t.parcels))
}

/// Runs a city end to end and writes every output under `out`.
pub fn run_city(spec: &CitySpec, out: &Path, opts: &CityRunOptions) -> Result<CityResult, CityError> {
    run_city_on(spec, city::regions(spec)?, out, opts)
}

/// [`run_city`] on sub-regions already computed with [`city::regions`] (the command line needs
/// them first, for its progress bars).
pub fn run_city_on(
    spec: &CitySpec,
    regs: Vec<(Region, Option<usize>)>,
    out: &Path,
    opts: &CityRunOptions,
) -> Result<CityResult, CityError> {
    let t0 = std::time::Instant::now();
    std::fs::create_dir_all(out).map_err(|source| CityError::Io { path: out.to_path_buf(), source })?;
    let regions = city::run_regions(spec, regs, out, opts)?;
    let (graph, planar, joins) = street_graph(&regions, spec.mesh.spacing);
    let metrics = street_metrics(&planar, spec.metres_per_unit, geom::signed_area(&spec.domain.outer).abs());
    let smoothed = smooth::by_method(&graph, spec.smoothing.method);
    let major = major_road_segments(&regions);
    let snakes = smoothed.snakes.len();
    let streets = snap_to_major_roads(&graph, &joins, smoothed.snakes, &major, 1.5 * spec.mesh.spacing);
    let smoothing = SmoothingSummary {
        method: spec.smoothing.method,
        snakes,
        energy_before: smoothed.energy_before,
        energy_after: smoothed.energy_after,
        iterations: smoothed.iterations,
        converged: smoothed.converged,
        smoothed_length_km: (streets.iter().map(|s| polyline_length(&s.points)).sum::<f64>()
            + major.iter().map(|g| polyline_length(g)).sum::<f64>())
            * spec.metres_per_unit
            / 1000.0,
    };
    let layout_metrics = layout_metrics(spec, &major, &streets);
    let levels = || regions.iter().flat_map(|r| r.levels.iter());
    let result = CityResult {
        schema: "netspec.city".into(),
        schema_version: CITY_SCHEMA_VERSION,
        netspec_version: env!("CARGO_PKG_VERSION").into(),
        spec: spec.clone(),
        solver: opts.solver.name().into(),
        time_limit_override: opts.time_limit,
        threads: [opts.threads, opts.threads_per_solve],
        complete: levels().all(|l| l.has_network()),
        valid: levels().filter(|l| l.has_network()).all(|l| l.valid == Some(true)),
        regions,
        metrics,
        layout_metrics,
        smoothing,
        wall_time: t0.elapsed().as_secs_f64(),
    };
    let write = |name: &str, text: String| -> Result<(), CityError> {
        let path = out.join(name);
        std::fs::write(&path, text).map_err(|source| CityError::Io { path, source })
    };
    write("city.json", serde_json::to_string_pretty(&result).expect("results serialise") + "\n")?;
    let geo = geojson(spec, &result.regions, &major, &streets)
        .map_err(|source| CityError::GeoJson { path: out.join("streets.geojson"), source })?;
    write("streets.geojson", geo)?;
    let svg = city_svg(spec, &result, &major, &streets);
    if let Ok(png) = crate::render::png(&svg) {
        let path = out.join("city.png");
        std::fs::write(&path, png).map_err(|source| CityError::Io { path, source })?;
    }
    write("city.svg", svg)?;
    Ok(result)
}

/// Level 1 as given: the sub-regions' polygons (the domain boundary and the major roads,
/// clipped and split by the arrangement), each shared side once.
pub fn major_road_segments(regions: &[RegionReport]) -> Vec<[[f64; 2]; 2]> {
    let key = |p: [f64; 2]| ((p[0] * 1e6).round() as i64, (p[1] * 1e6).round() as i64);
    let mut seen = IndexMap::new();
    for r in regions {
        for ring in std::iter::once(&r.outer).chain(&r.holes) {
            for i in 0..ring.len() {
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                let k = if key(a) <= key(b) { (key(a), key(b)) } else { (key(b), key(a)) };
                if k.0 != k.1 {
                    seen.entry(k).or_insert([a, b]);
                }
            }
        }
    }
    seen.into_values().collect()
}

fn nearest_on_segments(p: [f64; 2], segments: &[[[f64; 2]; 2]]) -> Option<[f64; 2]> {
    segments
        .iter()
        .map(|&[a, b]| geom::closest_on_segment(p, a, b).0)
        .min_by(|q, r| geom::dist(p, *q).total_cmp(&geom::dist(p, *r)))
}

/// The streets to draw: level-1 snakes are dropped (level 1 is drawn as given), and every end of
/// a level ≥ 2 snake that sits on the sub-region boundary (the staircase next to a major road)
/// where streets may join it (`joins`) is moved onto the major road itself, the move fading out linearly over `blend` of arc length,
/// so streets meet the roads they join.
pub fn snap_to_major_roads(
    g: &StreetGraph,
    joins: &[bool],
    snakes: Vec<Snake>,
    major: &[[[f64; 2]; 2]],
    blend: f64,
) -> Vec<Snake> {
    let mut on_major = vec![false; g.positions.len()];
    for e in g.edges.iter().filter(|e| e.level == 1) {
        for v in [e.a as usize, e.b as usize] {
            on_major[v] = joins.get(v).copied().unwrap_or(true);
        }
    }
    let mut out: Vec<Snake> = snakes.into_iter().filter(|s| s.level >= 2).collect();
    for s in &mut out {
        if s.closed || s.points.len() < 2 {
            continue;
        }
        for at_end in [false, true] {
            let v = if at_end { *s.vertices.last().expect("non-empty") } else { s.vertices[0] };
            if !on_major[v as usize] {
                continue;
            }
            if at_end {
                s.points.reverse();
            }
            let p0 = s.points[0];
            if let Some(q) = nearest_on_segments(p0, major) {
                let shift = [q[0] - p0[0], q[1] - p0[1]];
                let total = polyline_length(&s.points);
                let reach = blend.min(total / 2.0).max(1e-12);
                let mut arc = 0.0;
                for i in 0..s.points.len() {
                    if i > 0 {
                        arc += geom::dist(s.points[i], s.points[i - 1]);
                    }
                    let w = (1.0 - arc / reach).max(0.0);
                    if w == 0.0 {
                        break;
                    }
                    s.points[i] = [s.points[i][0] + w * shift[0], s.points[i][1] + w * shift[1]];
                }
            }
            if at_end {
                s.points.reverse();
            }
        }
    }
    out
}

impl GeoAnchor {
    /// A city's: its `geo_origin` (else the default origin) and its scale.
    pub fn of_city(spec: &CitySpec) -> GeoAnchor {
        GeoAnchor {
            origin: spec.origin_wgs84(),
            origin_is_default: spec.geo_origin.is_none(),
            metres_per_unit: spec.metres_per_unit,
        }
    }
}

/// The smoothed streets (and sub-regions) of a city as GeoJSON ([`streets_geojson`] around the
/// city's anchor, [`GeoAnchor::of_city`]: `geo_origin` or, without one,
/// [`super::spec::DEFAULT_GEO_ORIGIN`]).
pub fn geojson(
    spec: &CitySpec,
    regions: &[RegionReport],
    major: &[[[f64; 2]; 2]],
    snakes: &[Snake],
) -> Result<String, crate::geometry::site::SiteError> {
    let regions: Vec<GeoRegion> = regions
        .iter()
        .map(|r| GeoRegion {
            index: r.index,
            name: r.name.clone(),
            outer: r.outer.clone(),
            holes: r.holes.clone(),
            levels: r.levels.iter().map(|l| format!("L{}: {}", l.level, l.state)).collect(),
        })
        .collect();
    streets_geojson(&spec.name, &GeoAnchor::of_city(spec), &regions, major, snakes)
}

/// What the city picture shows ([`crate::render::city`]): sub-regions tinted, streets by level
/// (width and colour), the level-1 roads as given, the obstacle polygons and explicit sink points
/// of every level spec (e.g. Fig. 8's historic site and existing intersections), a legend of what
/// is drawn, and the metrics (totals and per km²).
pub fn city_picture(spec: &CitySpec, result: &CityResult, major: &[[[f64; 2]; 2]], snakes: &[Snake]) -> CityPicture {
    let (mut obstacles, mut sinks): (Vec<Vec<[f64; 2]>>, Vec<[f64; 2]>) = (Vec::new(), Vec::new());
    for r in &result.regions {
        for n in spec.region_levels(r.spec_entry) {
            let Ok(level) = spec.level(r.spec_entry, n) else { continue };
            for poly in level.user.obstacle_polygons {
                if !obstacles.contains(&poly) {
                    obstacles.push(poly);
                }
            }
            for p in level.sinks.points {
                if !sinks.contains(&p) {
                    sinks.push(p);
                }
            }
        }
    }
    CityPicture {
        title: format!(
            "{} — {} sub-regions, {}, {}{}",
            spec.name,
            result.regions.len(),
            super::city::levels_summary(&result.regions),
            result.solver,
            if result.valid { "; every network valid" } else { "; NOT EVERY NETWORK VALID" }
        ),
        subtitle: vec![
            format!("{}; {} m per unit", result.metrics.totals_line(), spec.metres_per_unit),
            result.metrics.density_line(),
        ],
        bounds: spec.domain_bounds(),
        regions: result
            .regions
            .iter()
            .map(|r| RegionShape {
                index: r.index,
                name: r.name.clone(),
                outer: r.outer.clone(),
                holes: r.holes.clone(),
                label_point: r.label_point,
                incomplete: r.levels.iter().any(|l| !l.has_network()),
            })
            .collect(),
        major: major.to_vec(),
        streets: snakes.iter().map(|sn| (sn.level, sn.points.clone())).collect(),
        obstacles,
        sinks,
    }
}

/// The city picture as SVG text ([`city_picture`] drawn by [`crate::render::city::city_svg`]).
pub fn city_svg(spec: &CitySpec, result: &CityResult, major: &[[[f64; 2]; 2]], snakes: &[Snake]) -> String {
    crate::render::city::city_svg(&city_picture(spec, result, major, snakes))
}
