//! `netspec site`: a real site from an OpenStreetMap extract.
//!
//! The region (a box or a GeoJSON polygon) less its holes (water by default; parks and railway
//! land on request) is the site's land: water touching the region's edge cuts the outline, and
//! a region that the holes split into pieces is refused (or, with `largest`, its largest piece
//! kept). The major roads are merged into continuous lines and clipped to the land; a road that
//! crosses water on a bridge is split at the water (the bridge is not a street of a layout; the
//! grow context keeps it whole, for growth builds bridges). Everything is written in one local
//! frame: a transverse Mercator centred on the region's bounding box, whose origin every file
//! records, so the site, the real streets and every design of the site share their metres.
//!
//! Files: `site.geojson` (what `netspec layout` reads), `map/streets.geojson` (the real drivable
//! streets as a design, for `netspec stats` and `netspec traffic`), and on request `grow.toml`
//! (a `netspec grow` context) and `city.toml` (a `netspec city` spec). All are computed before
//! any is written.

use super::areas::{self, AreaClass};
use super::read::{self, Extract};
use super::ways::{self, StreetPiece};
use super::{OsmError, ATTRIBUTION};
use crate::geometry::geojson::GeoJsonWriter;
use crate::geometry::planar::polygon_label_point;
use crate::geometry::site::{Projection, SiteError};
use crate::geometry::{dist, polyline_length, Polygon, P};
use geo::{Area as _, BooleanOps, Simplify};
use serde::Serialize;
use serde_json::json;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Land pieces smaller than this (m²) are slivers: dropped without asking.
pub const MIN_PIECE: f64 = 10_000.0;
/// Holes smaller than this (m²) are dropped (fountains, ponds a street would not go round).
pub const MIN_HOLE: f64 = 1_000.0;
/// Major road pieces shorter than this (metres) are dropped.
pub const MIN_ROAD: f64 = 20.0;
/// The real streets are kept this far (metres) beyond the region, so that the statistics count
/// a node's streets in the whole extract and blocks across the region's edge close.
pub const MAP_MARGIN: f64 = 500.0;
/// Metres per unit of the city spec written (its mesh has one unit between vertices).
pub const CITY_METRES_PER_UNIT: f64 = 20.0;
/// Dry strip (metres) kept between the city's water obstacles and its roads and edge.
pub const CITY_CLEARANCE: f64 = 30.0;
/// Decimal places of the WGS 84 coordinates written (1e-7° is about a centimetre).
const DIGITS: i32 = 7;

/// Where the site is.
#[derive(Clone, Debug, PartialEq)]
pub enum Area {
    /// A box `[west, south, east, north]`, degrees.
    Bbox([f64; 4]),
    /// A GeoJSON file whose polygon is the region.
    Polygon(PathBuf),
    /// A ring of `[longitude, latitude]` points (a region drawn on a map).
    Ring(Vec<[f64; 2]>),
}

/// What `netspec site` is asked for.
#[derive(Clone, Debug)]
pub struct SiteRequest {
    /// The extract (`.osm.pbf` or `.osm`).
    pub extract: PathBuf,
    /// The region.
    pub area: Area,
    /// The output directory.
    pub out: PathBuf,
    /// Which areas become holes.
    pub holes: BTreeSet<AreaClass>,
    /// The `highway` classes that are major roads.
    pub major: Vec<String>,
    /// Service roads are part of the real streets (level 4).
    pub service: bool,
    /// Also write a grow context.
    pub grow: bool,
    /// Also write a city spec.
    pub city: bool,
    /// Keep the largest land piece when holes split the region.
    pub largest: bool,
    /// The site's name (default: the output directory's).
    pub name: Option<String>,
    /// OSM ids of ways of the major classes to leave out of the major roads.
    pub exclude: BTreeSet<i64>,
}

/// What was made.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SiteSummary {
    /// The site's name.
    pub name: String,
    /// The local frame's origin, `[lon, lat]`.
    pub origin: [f64; 2],
    /// The region's area (km²).
    pub region_km2: f64,
    /// The land's area (km²).
    pub land_km2: f64,
    /// Holes in the land.
    pub holes: usize,
    /// Land pieces dropped (slivers, or all but the largest), m² each.
    pub dropped: Vec<f64>,
    /// Areas skipped because the extract lacks some of their nodes.
    pub incomplete_areas: usize,
    /// Major road pieces, and their length (m).
    pub roads: (usize, f64),
    /// Real street pieces within the region, and their length inside it (m).
    pub streets: (usize, f64),
    /// Share of the region's box outside the extract's extent.
    pub outside_share: f64,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// The site before it is written: land, roads and streets in the local frame.
struct Site {
    projection: Projection,
    region: Polygon,
    land: Polygon,
    roads: Vec<(Vec<P>, ways::MajorRoad)>,
    whole_roads: Vec<Vec<P>>,
    streets: Vec<(Vec<P>, StreetPiece)>,
    water: geo::MultiPolygon<f64>,
    forbidden: geo::MultiPolygon<f64>,
    dropped: Vec<f64>,
    incomplete: usize,
}

/// Makes the site and writes its files (see the module documentation).
pub fn run(req: &SiteRequest) -> Result<SiteSummary, OsmError> {
    run_on(&read::read(&req.extract)?, req)
}

/// [`run`] on an extract already read (`req.extract` names it in messages).
pub fn run_on(ex: &Extract, req: &SiteRequest) -> Result<SiteSummary, OsmError> {
    let extent = ex.extent().ok_or(OsmError::Empty { path: req.extract.clone() })?;
    let (ring, what) = region_ring(req)?;
    let outside_share = outside_share(&ring, extent);
    if outside_share >= 1.0 {
        return Err(OsmError::Outside { what, path: req.extract.clone(), extent });
    }
    let site = build(ex, req, &ring)?;
    let name = req.name.clone().unwrap_or_else(|| {
        req.out.file_name().map_or_else(|| "site".to_string(), |n| n.to_string_lossy().into_owned())
    });
    let source = req.extract.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let mut files: Vec<(PathBuf, String)> = vec![
        (req.out.join("site.geojson"), site_geojson(&site, &name, &source, req)?),
        (req.out.join("map").join("streets.geojson"), map_geojson(&site, &name, &source)?),
    ];
    if req.grow {
        files.push((req.out.join("grow.toml"), grow_toml(&site, &name, &source)?));
    }
    if req.city {
        files.push((req.out.join("city.toml"), city_toml(&site, &name, &source)?));
    }
    for (path, text) in &files {
        let dir = path.parent().unwrap_or(Path::new("."));
        std::fs::create_dir_all(dir).map_err(|source| OsmError::Io { path: dir.to_path_buf(), source })?;
        std::fs::write(path, text).map_err(|source| OsmError::Io { path: path.clone(), source })?;
    }
    let inside: Vec<f64> = site
        .streets
        .iter()
        .map(|(l, _)| site.region.clip_polyline(l, 1e-6).iter().map(|p| polyline_length(p)).sum())
        .collect();
    Ok(SiteSummary {
        name,
        origin: site.projection.origin(),
        region_km2: site.region.area() / 1e6,
        land_km2: site.land.area() / 1e6,
        holes: site.land.holes().len(),
        dropped: site.dropped,
        incomplete_areas: site.incomplete,
        roads: (site.roads.len(), site.roads.iter().map(|(l, _)| polyline_length(l)).sum()),
        streets: (inside.iter().filter(|&&l| l > 0.0).count(), inside.iter().sum()),
        outside_share,
        files: files.into_iter().map(|(p, _)| p).collect(),
    })
}

/// The region's outer ring in WGS 84, and how to name it in errors.
fn region_ring(req: &SiteRequest) -> Result<(Vec<[f64; 2]>, String), OsmError> {
    match &req.area {
        Area::Bbox(b) => {
            let [w, s, e, n] = *b;
            let ok = b.iter().all(|v| v.is_finite())
                && w.abs() <= 180.0
                && e.abs() <= 180.0
                && s.abs() < 90.0
                && n.abs() < 90.0;
            if !ok {
                return Err(OsmError::Bbox(format!("{w},{s},{e},{n}: not WGS 84 longitudes and latitudes")));
            }
            if !(w < e && s < n) {
                return Err(OsmError::Bbox(format!("{w},{s},{e},{n}: a box needs west < east and south < north")));
            }
            Ok((vec![[w, s], [e, s], [e, n], [w, n]], format!("the box {w},{s},{e},{n}")))
        }
        Area::Polygon(path) => {
            let text = crate::io::read_utf8(path)
                .map_err(|e| OsmError::Region { path: path.clone(), message: e.to_string() })?;
            let site = crate::geometry::site::read_geojson(&text)
                .map_err(|e| OsmError::Region { path: path.clone(), message: e.to_string() })?;
            if !site.polygon.holes().is_empty() {
                return Err(OsmError::Region {
                    path: path.clone(),
                    message: "the region polygon has holes; give its outline (netspec site makes the holes)".into(),
                });
            }
            let ring =
                site.polygon.outer().iter().map(|&p| site.projection.to_wgs84(p)).collect::<Result<Vec<_>, _>>()?;
            Ok((ring, format!("the polygon of {}", path.display())))
        }
        Area::Ring(ring) => {
            let ok =
                ring.iter().all(|p| p[0].is_finite() && p[1].is_finite() && p[0].abs() <= 180.0 && p[1].abs() < 90.0);
            if !ok || ring.len() < 3 {
                return Err(OsmError::Drawn("a region needs three or more WGS 84 positions".into()));
            }
            Ok((ring.clone(), "the drawn region".into()))
        }
    }
}

/// The share of the ring's bounding box that lies outside `extent` (both W, S, E, N).
fn outside_share(ring: &[[f64; 2]], extent: [f64; 4]) -> f64 {
    let [lo, hi] = crate::geometry::polygon::bounds(ring);
    let area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    let ix = (hi[0].min(extent[2]) - lo[0].max(extent[0])).max(0.0);
    let iy = (hi[1].min(extent[3]) - lo[1].max(extent[1])).max(0.0);
    if area > 0.0 {
        1.0 - ix * iy / area
    } else {
        1.0
    }
}

/// A point through the written file: to WGS 84, rounded as written, and back.
fn through_file(proj: &Projection, p: P) -> Result<P, SiteError> {
    proj.to_local(writer(proj).lonlat(p)?)
}

fn build(ex: &Extract, req: &SiteRequest, ring: &[[f64; 2]]) -> Result<Site, OsmError> {
    let [lo, hi] = crate::geometry::polygon::bounds(ring);
    let projection = Projection::new([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])])?;
    let bad = |message: String| match &req.area {
        Area::Polygon(p) => OsmError::Region { path: p.clone(), message },
        Area::Bbox(_) => OsmError::Region { path: req.extract.clone(), message },
        Area::Ring(_) => OsmError::Drawn(message),
    };
    let local = ring.iter().map(|&q| projection.to_local(q)).collect::<Result<Vec<P>, _>>()?;
    let region = Polygon::new(local, vec![]).map_err(|e| bad(format!("the region: {e}")))?;
    let region_geo = region.to_geo();
    let (holes, incomplete) = areas::areas(ex, &req.holes, &projection, &region_geo);
    let (land_geo, dropped) = land(&region_geo, &holes, req.largest)?;
    let land = land_polygon(&land_geo, &projection).map_err(|e| bad(format!("the land: {e}")))?;
    let land_geo = land.to_geo();
    let project_run = |ids: &[i64]| -> Vec<Vec<P>> {
        let pts: Vec<Option<P>> =
            ids.iter().map(|id| ex.nodes.get(id).and_then(|&ll| projection.to_local(ll).ok())).collect();
        pts.split(Option::is_none)
            .map(|r| r.iter().flatten().copied().collect::<Vec<P>>())
            .filter(|r| r.len() >= 2)
            .collect()
    };
    let mut roads = Vec::new();
    let mut whole_roads = Vec::new();
    for road in
        ways::major_roads(ex, &req.major).into_iter().filter(|r| !r.ways.iter().any(|w| req.exclude.contains(w)))
    {
        for run in project_run(&road.refs) {
            let line = geo::MultiLineString::new(vec![run.iter().map(|p| (p[0], p[1])).collect()]);
            for piece in land_geo.clip(&line, false).0 {
                let pts: Vec<P> = piece.0.iter().map(|c| [c.x, c.y]).collect();
                if polyline_length(&pts) >= MIN_ROAD {
                    let pts = pts.iter().map(|&p| through_file(&projection, p)).collect::<Result<Vec<P>, _>>()?;
                    roads.push((pts, road.clone()));
                }
            }
            whole_roads.push(run);
        }
    }
    let margin = MAP_MARGIN / 111_320.0;
    let lat = 0.5 * (lo[1] + hi[1]);
    let (mx, my) = (margin / lat.to_radians().cos().max(0.01), margin);
    let near = |p: [f64; 2]| p[0] >= lo[0] - mx && p[0] <= hi[0] + mx && p[1] >= lo[1] - my && p[1] <= hi[1] + my;
    let streets = ways::street_pieces(ex, req.service, near)
        .into_iter()
        .map(|s| {
            let pts = s.points.iter().map(|&q| projection.to_local(q)).collect::<Result<Vec<P>, _>>()?;
            Ok((pts, s))
        })
        .collect::<Result<Vec<_>, SiteError>>()?;
    let water_class: BTreeSet<AreaClass> = [AreaClass::Water].into();
    let (water, _) = areas::areas(ex, &water_class, &projection, &region_geo);
    let others: BTreeSet<AreaClass> = req.holes.iter().copied().filter(|c| *c != AreaClass::Water).collect();
    let (forbidden, _) = areas::areas(ex, &others, &projection, &region_geo);
    Ok(Site { projection, region, land, roads, whole_roads, streets, water, forbidden, dropped, incomplete })
}

/// A ring's points, not closed, without spikes (a vertex where the ring runs back along itself,
/// as booleans leave where two boundaries nearly coincide).
fn ring_of(l: &geo::LineString<f64>) -> Vec<P> {
    let mut r: Vec<P> = l.coords().map(|c| [c.x, c.y]).collect();
    if r.len() > 1 && r.first() == r.last() {
        r.pop();
    }
    drop_spikes(r)
}

/// Removes vertices where a ring turns back on itself (within a centimetre), until none is left.
fn drop_spikes(mut r: Vec<P>) -> Vec<P> {
    use crate::geometry::{closest_on_segment, cross, dot, sub};
    let mut changed = true;
    while changed && r.len() > 3 {
        changed = false;
        let n = r.len();
        for i in 0..n {
            let (a, b, c) = (r[(i + n - 1) % n], r[i], r[(i + 1) % n]);
            let (u, v) = (sub(b, a), sub(c, b));
            let back =
                dot(u, v) < 0.0 && cross(u, v).abs() <= 0.01 * crate::geometry::norm(u).max(crate::geometry::norm(v));
            let on = dist(c, closest_on_segment(c, a, b).0) <= 0.01 || dist(a, closest_on_segment(a, b, c).0) <= 0.01;
            if dist(a, b) <= 1e-6 || (back && on) {
                r.remove(i);
                changed = true;
                break;
            }
        }
    }
    r
}

/// The region less its holes: one piece (slivers under [`MIN_PIECE`] dropped), the largest with
/// `largest`, else an error naming the pieces.
fn land(
    region: &geo::Polygon<f64>,
    holes: &geo::MultiPolygon<f64>,
    largest: bool,
) -> Result<(geo::Polygon<f64>, Vec<f64>), OsmError> {
    let land = geo::MultiPolygon::new(vec![region.clone()]).difference(holes);
    let mut pieces: Vec<geo::Polygon<f64>> = land.0;
    pieces.sort_by(|a, b| b.unsigned_area().total_cmp(&a.unsigned_area()));
    let mut dropped: Vec<f64> = Vec::new();
    while pieces.len() > 1 && pieces[pieces.len() - 1].unsigned_area() < MIN_PIECE {
        dropped.push(pieces.pop().map_or(0.0, |p| p.unsigned_area()));
    }
    if pieces.len() > 1 && !largest {
        return Err(OsmError::Islands { areas: pieces.iter().map(|p| p.unsigned_area()).collect() });
    }
    dropped.extend(pieces.iter().skip(1).map(|p| p.unsigned_area()));
    let first = pieces.into_iter().next().ok_or(OsmError::NoLand)?;
    if first.unsigned_area() <= 0.0 {
        return Err(OsmError::NoLand);
    }
    Ok((first, dropped))
}

/// The land as a checked polygon, as it reads back from the file: outline and holes simplified
/// within half a metre (Ramer–Douglas–Peucker; the exact rings if that breaks validity), holes
/// under [`MIN_HOLE`] dropped, every vertex through the written WGS 84 coordinates.
fn land_polygon(land: &geo::Polygon<f64>, proj: &Projection) -> Result<Polygon, String> {
    let make = |p: &geo::Polygon<f64>| -> Result<Polygon, String> {
        let file = |r: Vec<P>| r.into_iter().map(|q| through_file(proj, q)).collect::<Result<Vec<P>, _>>();
        let outer = file(ring_of(p.exterior())).map_err(|e| e.to_string())?;
        let holes = p
            .interiors()
            .iter()
            .filter(|h| geo::Polygon::new((*h).clone(), vec![]).unsigned_area() >= MIN_HOLE)
            .map(|h| file(ring_of(h)))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| e.to_string())?;
        Polygon::new(outer, holes).map_err(|e| e.to_string())
    };
    make(&land.simplify(0.5)).or_else(|_| make(land))
}

/// The GeoJSON writer of a site's files: degrees to [`DIGITS`] places.
fn writer(proj: &Projection) -> GeoJsonWriter<'_> {
    GeoJsonWriter::new(proj).digits(DIGITS)
}

fn site_geojson(site: &Site, name: &str, source: &str, req: &SiteRequest) -> Result<String, OsmError> {
    let proj = &site.projection;
    let holes: Vec<&str> = req.holes.iter().map(|c| c.name()).collect();
    let mut w = writer(proj);
    w.polygon(
        site.land.rings(),
        json!({"name": name, "origin": proj.origin(), "source": source, "holes": holes.join(","),
               "attribution": ATTRIBUTION}),
    )?;
    for (line, road) in &site.roads {
        w.line(line, json!({"kind": "road", "highway": road.highway, "name": road.name, "osm_ways": road.ways}))?;
    }
    Ok(w.to_json_pretty(json!({"attribution": ATTRIBUTION})))
}

fn map_geojson(site: &Site, name: &str, source: &str) -> Result<String, OsmError> {
    let proj = &site.projection;
    let mut w = writer(proj);
    w.polygon(
        site.land.rings(),
        json!({"kind": "region", "name": name, "origin": proj.origin(), "source": source, "attribution": ATTRIBUTION}),
    )?;
    for (line, s) in &site.streets {
        w.line(
            line,
            json!({"kind": "street", "highway": s.highway, "level": s.level, "oneway": s.oneway,
                   "u": s.u, "v": s.v, "osm_way": s.way, "name": s.name}),
        )?;
    }
    Ok(w.to_json_pretty(json!({"attribution": ATTRIBUTION})))
}

fn header(kind: &str, name: &str, source: &str) -> String {
    format!("# {kind} of the site `{name}`, written by `netspec site` from {source}.\n# Data {ATTRIBUTION}.\n\n")
}

/// A `netspec grow` context of the site (the keys docs/grow.md lists).
#[derive(Serialize)]
struct GrowFile {
    size: [f64; 2],
    origin: [f64; 2],
    seed: u64,
    steps: u32,
    center: GrowPoint,
    neighbour: Vec<GrowPoint>,
    water: Vec<GrowPolygon>,
    forbidden: Vec<GrowPolygon>,
    road: Vec<GrowRoad>,
}

#[derive(Serialize)]
struct GrowPoint {
    position: P,
}

#[derive(Serialize)]
struct GrowPolygon {
    polygon: Vec<P>,
}

#[derive(Serialize)]
struct GrowRoad {
    points: Vec<P>,
    class: &'static str,
    fixed: bool,
}

/// Steps a site's context grows by default.
pub const GROW_STEPS: u32 = 40;

fn mm(p: P) -> P {
    [(p[0] * 1000.0).round() / 1000.0 + 0.0, (p[1] * 1000.0).round() / 1000.0 + 0.0]
}

/// The grow context: the map is the region's bounding box (rounded up to the metre), its origin
/// `(0, 0)` the box's south-west corner (the context's `origin` is that corner in WGS 84); the
/// real water and the other holes (as forbidden land) on the map, the real major roads whole
/// (bridges included) clipped to the map and without ends on water, as existing roads; a
/// neighbouring city where each leaves the map; the centre at the land's label point.
fn grow_toml(site: &Site, name: &str, source: &str) -> Result<String, OsmError> {
    let [lo, hi] = site.region.bounds();
    let size = [(hi[0] - lo[0]).ceil(), (hi[1] - lo[1]).ceil()];
    let rect = [0.0, 0.0, size[0], size[1]];
    let to_map = |p: P| [p[0] - lo[0], p[1] - lo[1]];
    let map = geo::MultiPolygon::new(vec![crate::geometry::polygon::geo_polygon(
        &[lo, [lo[0] + size[0], lo[1]], [lo[0] + size[0], lo[1] + size[1]], [lo[0], lo[1] + size[1]]],
        &[],
    )]);
    let on_map = |m: &geo::MultiPolygon<f64>| -> Vec<Vec<P>> {
        let m = m.intersection(&map);
        let big = m.0.iter().filter(|p| p.unsigned_area() >= MIN_HOLE);
        big.map(|p| ring_of(p.exterior()).into_iter().map(|q| mm(to_map(q))).collect()).collect()
    };
    let (water, forbidden) = (on_map(&site.water), on_map(&site.forbidden));
    let mut roads = Vec::new();
    let mut exits: Vec<P> = Vec::new();
    for run in &site.whole_roads {
        let pts: Vec<P> = run.iter().map(|&p| to_map(p)).collect();
        for piece in clip_to_rect(&pts, rect).iter().filter_map(|p| trim_to_land(p, &water)) {
            for end in [piece[0], piece[piece.len() - 1]] {
                let on_edge = end[0] <= 1e-6 || end[1] <= 1e-6 || end[0] >= size[0] - 1e-6 || end[1] >= size[1] - 1e-6;
                if on_edge && !exits.iter().any(|&q| dist(q, end) < 200.0) {
                    exits.push(end);
                }
            }
            if polyline_length(&piece) >= MIN_ROAD {
                roads.push(GrowRoad { points: piece.iter().map(|&p| mm(p)).collect(), class: "major", fixed: false });
            }
        }
    }
    let polys = |rings: &[Vec<P>]| rings.iter().map(|r| GrowPolygon { polygon: r.clone() }).collect();
    let holes: Vec<Vec<P>> = site.land.holes().to_vec();
    let center = polygon_label_point(site.land.outer(), &holes).unwrap_or(site.land.outer()[0]);
    let file = GrowFile {
        size,
        origin: writer(&site.projection).lonlat(lo)?,
        seed: 1,
        steps: GROW_STEPS,
        center: GrowPoint { position: mm(to_map(center)) },
        neighbour: exits.iter().map(|&p| GrowPoint { position: mm(p) }).collect(),
        water: polys(&water),
        forbidden: polys(&forbidden),
        road: roads,
    };
    let text =
        toml::to_string(&file).map_err(|e| OsmError::Write { what: "grow.toml".into(), message: e.to_string() })?;
    Ok(header("The grow context", name, source) + &text)
}

/// A road without its ends on water (a bridge cut by the map's edge): from its first point on
/// land to its last (a point within half a metre of water's edge is wet), sampled every metre;
/// `None` when no point of it is on land.
fn trim_to_land(line: &[P], water: &[Vec<P>]) -> Option<Vec<P>> {
    let near = |p: P, r: &[P]| {
        (0..r.len()).any(|i| dist(p, crate::geometry::closest_on_segment(p, r[i], r[(i + 1) % r.len()]).0) <= 0.5)
    };
    let wet = |p: P| water.iter().any(|r| crate::geometry::ring_contains(r, p) || near(p, r));
    let total = polyline_length(line);
    let steps = total.ceil().max(1.0) as usize;
    let at = |k: usize| total * k as f64 / steps as f64;
    let first = (0..=steps).find(|&k| !wet(crate::geometry::point_at_length(line, at(k))))?;
    let last = (0..=steps).rev().find(|&k| !wet(crate::geometry::point_at_length(line, at(k))))?;
    if first == 0 && last == steps {
        return Some(line.to_vec());
    }
    let (s0, s1) = (at(first), at(last));
    let mut out = vec![crate::geometry::point_at_length(line, s0)];
    let mut run = 0.0;
    for w in line.windows(2) {
        run += dist(w[0], w[1]);
        if run > s0 && run < s1 {
            out.push(w[1]);
        }
    }
    out.push(crate::geometry::point_at_length(line, s1));
    out.dedup();
    (out.len() >= 2).then_some(out)
}

/// A polyline clipped to a rectangle `[x0, y0, x1, y1]`.
fn clip_to_rect(line: &[P], r: [f64; 4]) -> Vec<Vec<P>> {
    let mut out: Vec<Vec<P>> = Vec::new();
    let mut open = false;
    for w in line.windows(2) {
        let Some((a, b)) = crate::geometry::clip_segment(w[0], w[1], r) else {
            open = false;
            continue;
        };
        if open && out.last().is_some_and(|p| dist(p[p.len() - 1], a) < 1e-9) {
            out.last_mut().expect("a piece").push(b);
        } else {
            out.push(vec![a, b]);
        }
        open = dist(b, w[1]) < 1e-9;
    }
    out
}

/// The IP city spec: the land's outline as the domain (units of [`CITY_METRES_PER_UNIT`] in the
/// site's frame, `geo_origin` its origin), the major roads as roads, the holes less a dry strip
/// along the roads and the outline as obstacles of every level, Fig. 7a's levels 2–4.
fn city_toml(site: &Site, name: &str, source: &str) -> Result<String, OsmError> {
    use crate::urban::spec::{CityMeshSpec, CitySpec, DomainSpec, RoadSpec};
    let u = |p: P| {
        let q = [p[0] / CITY_METRES_PER_UNIT, p[1] / CITY_METRES_PER_UNIT];
        [(q[0] * 1e6).round() / 1e6 + 0.0, (q[1] * 1e6).round() / 1e6 + 0.0]
    };
    let roads: Vec<Vec<P>> = site.roads.iter().map(|(l, _)| l.clone()).collect();
    let obstacles = crate::geometry::polygon::dry(site.land.holes(), &roads, site.land.outer(), CITY_CLEARANCE);
    let obstacles: Vec<Vec<P>> = obstacles.iter().map(|r| r.iter().map(|&p| u(p)).collect()).collect();
    let spec = CitySpec {
        name: name.to_string(),
        description: format!("the real site {name} ({source}) with Fig. 7a's levels"),
        metres_per_unit: CITY_METRES_PER_UNIT,
        geo_origin: Some(site.projection.origin()),
        domain: DomainSpec { outer: site.land.outer().iter().map(|&p| u(p)).collect() },
        roads: site
            .roads
            .iter()
            .enumerate()
            .map(|(k, (l, r))| RoadSpec {
                name: r.name.clone().unwrap_or_else(|| format!("{} {k}", r.highway)),
                points: l.iter().map(|&p| u(p)).collect(),
            })
            .collect(),
        major: None,
        mesh: CityMeshSpec { spacing: 1.0 },
        levels: crate::urban::spec::fig7a_levels(&obstacles),
        regions: Vec::new(),
        solver: Default::default(),
        smoothing: Default::default(),
    };
    let text =
        toml::to_string(&spec).map_err(|e| OsmError::Write { what: "city.toml".into(), message: e.to_string() })?;
    Ok(header("The IP city spec", name, source) + &text)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::geo_polygon;

    #[test]
    fn holes_that_split_the_region_are_refused_or_the_largest_kept() {
        let square = geo_polygon(&[[0.0, 0.0], [1000.0, 0.0], [1000.0, 1000.0], [0.0, 1000.0]], &[]);
        let river = geo::MultiPolygon::new(vec![geo_polygon(
            &[[600.0, -10.0], [650.0, -10.0], [650.0, 1010.0], [600.0, 1010.0]],
            &[],
        )]);
        let e = land(&square, &river, false).unwrap_err();
        assert!(matches!(&e, OsmError::Islands { areas } if areas.len() == 2), "{e}");
        assert!(e.to_string().contains("60.00 ha, 35.00 ha"), "{e}");
        let (l, dropped) = land(&square, &river, true).unwrap();
        assert!((l.unsigned_area() - 600_000.0).abs() < 1.0);
        assert_eq!(dropped.len(), 1);
        // A strip of water 5 m from the edge leaves a 0.5 ha sliver: dropped without asking.
        let cut = geo::MultiPolygon::new(vec![geo_polygon(
            &[[-10.0, 5.0], [1010.0, 5.0], [1010.0, 10.0], [-10.0, 10.0]],
            &[],
        )]);
        let (l, dropped) = land(&square, &cut, false).unwrap();
        assert!((l.unsigned_area() - 990_000.0).abs() < 1.0);
        assert_eq!(dropped.len(), 1);
        let lake = vec![[40.0, -10.0], [60.0, -10.0], [60.0, 10.0], [40.0, 10.0]];
        let bridge = vec![[0.0, 0.0], [100.0, 0.0]];
        assert_eq!(
            trim_to_land(&bridge, std::slice::from_ref(&lake)),
            Some(bridge.clone()),
            "a bridge in the middle stays"
        );
        let t = trim_to_land(&[[50.0, 0.0], [100.0, 0.0]], &[lake]).unwrap();
        // Sampled every metre, the shore's half-metre counted wet: the road starts a metre inland.
        assert_eq!(t, vec![[61.0, 0.0], [100.0, 0.0]], "a road starting on water starts on the shore");
        let spike = drop_spikes(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [10.0, 5.0], [5.0, 5.0], [0.0, 5.0]]);
        assert_eq!(spike, vec![[0.0, 0.0], [10.0, 0.0], [10.0, 5.0], [5.0, 5.0], [0.0, 5.0]]);
        assert!(outside_share(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]], [1.0, 0.0, 3.0, 3.0]) - 0.5 < 1e-12);
    }
}
