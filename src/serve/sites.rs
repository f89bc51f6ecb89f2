//! Real sites in the browser: the OpenStreetMap extracts and sites under the root, an extract's
//! features in the map's view (streets by class, water, parks, railways), a site made from a box
//! or polygon drawn on it (`osm::site`, into `ROOT/sites/<name>/`), the urban methods run on a
//! site as runs of their own, and the site's designs compared with its real streets
//! (`measure`).
//!
//! A method runs as the `netspec` binary in a child process (`netspec layout|grow|city|traffic`,
//! output into the run's `out/`), so that Cancel ends it at once, a failing method cannot take the
//! server down, and a killed server takes its children with it (the child dies with its parent).
//! Its output lines stream to the page.

use super::error::ApiError;
use super::runs::{RunHandle, RunState};
use crate::geometry::{site::Projection, Polygon, P};
use crate::osm::read::{self, Extract};
use crate::osm::{areas::AreaClass, ways};
use serde::Deserialize;
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::SystemTime;

/// The folder of sites under the root.
pub const SITES: &str = "sites";
/// The folder uploads go to under the root.
pub const UPLOADS: &str = "uploads";
/// The largest site, km².
pub const MAX_KM2: f64 = 25.0;
/// The largest upload, bytes.
pub const MAX_UPLOAD: usize = 200 << 20;
/// The most features one view request returns (the largest first).
pub const MAX_FEATURES: usize = 30_000;

/// A feature of an extract as the map draws it: WGS 84 positions and the class it is drawn by.
#[derive(Clone, Debug)]
struct Drawn {
    /// `street`, `water`, `park` or `rail`.
    layer: &'static str,
    /// The `highway` class of a street, else the layer.
    class: String,
    /// The way's OSM id.
    id: i64,
    /// A street's netspec level (1–4).
    level: u8,
    /// A polygon (closed) or a line.
    area: bool,
    positions: Vec<[f64; 2]>,
    bbox: [f64; 4],
}

/// An extract read once, with what the map draws of it.
pub struct Layers {
    /// The extract.
    pub extract: Extract,
    drawn: Vec<Drawn>,
    /// The extent of its streets (of its nodes when it has none), W, S, E, N.
    pub extent: [f64; 4],
}

impl Layers {
    fn new(extract: Extract) -> Layers {
        let mut drawn = Vec::new();
        for w in &extract.ways {
            let Some(positions) = extract.positions(w) else { continue };
            if positions.len() < 2 {
                continue;
            }
            let (layer, class, level, area) = if let Some(level) = ways::level(&w.tags, true) {
                ("street", w.tag("highway").unwrap_or_default().to_string(), level, false)
            } else if w.is_closed() {
                match AreaClass::of(&w.tags) {
                    Some(c) => (layer_name(c), c.name().to_string(), 0, true),
                    None => continue,
                }
            } else if w.tag("natural") == Some("coastline") {
                ("water", "coastline".to_string(), 0, false)
            } else {
                continue;
            };
            let [lo, hi] = crate::geometry::polygon::bounds(&positions);
            drawn.push(Drawn { layer, class, id: w.id, level, area, positions, bbox: [lo[0], lo[1], hi[0], hi[1]] });
        }
        // The streets' extent (an extract's nodes may reach far beyond: ferry lines).
        let streets = drawn.iter().filter(|d| d.layer == "street").map(|d| d.bbox);
        let extent = streets
            .reduce(|a, b| [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])])
            .or_else(|| extract.extent())
            .unwrap_or([0.0; 4]);
        Layers { extract, drawn, extent }
    }

    /// The features whose box meets `view` (W, S, E, N) as GeoJSON, at most [`MAX_FEATURES`]
    /// (areas and major streets first), and whether some were left out.
    pub fn features(&self, view: [f64; 4]) -> Value {
        let meets = |b: &[f64; 4]| b[0] <= view[2] && b[2] >= view[0] && b[1] <= view[3] && b[3] >= view[1];
        let mut hits: Vec<&Drawn> = self.drawn.iter().filter(|d| meets(&d.bbox)).collect();
        hits.sort_by_key(|d| (if d.area { 0 } else { d.level.max(1) }, d.id));
        let left_out = hits.len().saturating_sub(MAX_FEATURES);
        hits.truncate(MAX_FEATURES);
        let features: Vec<Value> = hits
            .iter()
            .map(|d| {
                let geometry = if d.area {
                    json!({"type": "Polygon", "coordinates": [d.positions]})
                } else {
                    json!({"type": "LineString", "coordinates": d.positions})
                };
                json!({"type": "Feature", "id": d.id,
                       "properties": {"layer": d.layer, "class": d.class, "level": d.level, "osm_id": d.id,
                                      "major": d.layer == "street" && ways::MAJOR.contains(&d.class.as_str())},
                       "geometry": geometry})
            })
            .collect();
        json!({"type": "FeatureCollection", "features": features, "left_out": left_out,
               "attribution": crate::osm::ATTRIBUTION})
    }
}

fn layer_name(c: AreaClass) -> &'static str {
    match c {
        AreaClass::Water => "water",
        AreaClass::Park => "park",
        AreaClass::Rail => "rail",
    }
}

/// An extract read: its path, modification time and layers.
type Cached = (PathBuf, Option<SystemTime>, Arc<Layers>);

/// The last two extracts read, by path and modification time.
#[derive(Default)]
pub struct ExtractCache {
    entries: Mutex<Vec<Cached>>,
}

impl ExtractCache {
    /// The extract at `path` (read, or from the cache when unchanged).
    pub fn get(&self, path: &Path, shown: &str) -> Result<Arc<Layers>, ApiError> {
        let modified = std::fs::metadata(path).and_then(|m| m.modified()).ok();
        {
            let e = self.entries.lock().unwrap_or_else(|e| e.into_inner());
            if let Some((_, _, l)) = e.iter().find(|(p, m, _)| p == path && *m == modified) {
                return Ok(l.clone());
            }
        }
        let extract = read::read(path)
            .map_err(|e| ApiError::invalid(Some("path".into()), shorten(&e.to_string(), path, shown)))?;
        let layers = Arc::new(Layers::new(extract));
        let mut e = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        e.retain(|(p, _, _)| p != path);
        e.insert(0, (path.to_path_buf(), modified, layers.clone()));
        e.truncate(2);
        Ok(layers)
    }
}

/// A message with the absolute path replaced by the path under the root.
fn shorten(message: &str, path: &Path, shown: &str) -> String {
    message.replace(&path.display().to_string(), shown)
}

/// Whether a file under the root is an extract (by name: `.osm`, `.osm.pbf`, `.pbf`).
pub fn is_extract(name: &str) -> bool {
    name.ends_with(".osm") || name.ends_with(".osm.pbf") || name.ends_with(".pbf")
}

/// Extracts under the root (four folders deep, runs and sites left out), and the sites made.
pub fn list(root: &Path) -> Value {
    let mut extracts = Vec::new();
    walk(root, root, 0, &mut extracts);
    extracts.sort();
    let mut sites = Vec::new();
    if let Ok(entries) = std::fs::read_dir(root.join(SITES)) {
        for e in entries.flatten() {
            if e.path().join("site.geojson").is_file() {
                sites.push(e.file_name().to_string_lossy().into_owned());
            }
        }
    }
    sites.sort();
    let extracts: Vec<Value> = extracts
        .into_iter()
        .map(|rel| {
            let bytes = std::fs::metadata(root.join(&rel)).map_or(0, |m| m.len());
            json!({"path": rel, "bytes": bytes})
        })
        .collect();
    json!({"extracts": extracts, "sites": sites})
}

fn walk(root: &Path, dir: &Path, depth: usize, out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let Ok(kind) = e.file_type() else { continue };
        let p = e.path();
        let name = e.file_name().to_string_lossy().into_owned();
        if kind.is_dir() && depth < 4 && name != super::specs::RUNS && name != SITES && !name.starts_with('.') {
            walk(root, &p, depth + 1, out);
        } else if kind.is_file() && is_extract(&name) {
            if let Ok(rel) = p.strip_prefix(root) {
                out.push(rel.to_string_lossy().into_owned());
            }
        }
    }
}

/// A site asked for by the page.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SiteBody {
    /// The extract, a path under the root.
    pub extract: String,
    /// The site's name (a folder under `ROOT/sites/`).
    pub name: String,
    /// A box, W, S, E, N.
    #[serde(default)]
    pub bbox: Option<[f64; 4]>,
    /// Or a polygon, `[lon, lat]` points.
    #[serde(default)]
    pub polygon: Option<Vec<[f64; 2]>>,
    /// Which areas become holes (`water`, `park`, `rail`).
    #[serde(default = "water")]
    pub holes: Vec<String>,
    /// The major road classes.
    #[serde(default = "major")]
    pub major: Vec<String>,
    /// OSM ids of major-road ways left out.
    #[serde(default)]
    pub exclude: Vec<i64>,
}

fn water() -> Vec<String> {
    vec!["water".into()]
}

fn major() -> Vec<String> {
    ways::MAJOR.iter().map(|s| s.to_string()).collect()
}

/// A name that is one safe path component.
pub fn check_name(name: &str) -> Result<(), ApiError> {
    let ok = !name.is_empty()
        && name.len() <= 64
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        && !name.starts_with('-');
    if ok {
        Ok(())
    } else {
        Err(ApiError::bad("name", format!("`{name}`: a site's name is 1–64 letters, digits, `-` and `_`")))
    }
}

/// The ring of a drawn region, checked: at least three points, no self-crossing, an area of at
/// most [`MAX_KM2`].
fn check_region(ring: &[[f64; 2]], field: &str) -> Result<(), ApiError> {
    let bad = |m: String| ApiError::invalid(Some(field.into()), m);
    if ring.len() < 3
        || ring.iter().any(|p| !(p[0].is_finite() && p[1].is_finite() && p[0].abs() <= 180.0 && p[1].abs() < 90.0))
    {
        return Err(bad("a region needs three or more WGS 84 positions".into()));
    }
    let [lo, hi] = crate::geometry::polygon::bounds(ring);
    let proj = Projection::new([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]).map_err(|e| bad(e.to_string()))?;
    let local: Vec<P> =
        ring.iter().map(|&q| proj.to_local(q)).collect::<Result<_, _>>().map_err(|e| bad(e.to_string()))?;
    let polygon = Polygon::new(local, vec![]).map_err(|e| bad(format!("the region: {e}")))?;
    let km2 = polygon.area() / 1e6;
    if km2 > MAX_KM2 {
        return Err(bad(format!("the region is {km2:.1} km²; a site is at most {MAX_KM2} km²")));
    }
    Ok(())
}

/// Makes a site from a page's request: checked, then `osm::site` with grow and city specs into
/// `ROOT/sites/<name>/`. Returns what it made.
pub fn make(root: &Path, cache: &ExtractCache, b: SiteBody) -> Result<Value, ApiError> {
    check_name(&b.name)?;
    let dir = root.join(SITES).join(&b.name);
    if dir.exists() {
        return Err(ApiError::invalid(Some("name".into()), format!("a site named `{}` exists", b.name)));
    }
    let path = super::specs::under_root(root, &b.extract, "extract")?;
    if !path.is_file() {
        return Err(ApiError::not_found("extract", format!("no extract `{}` under --root", b.extract)));
    }
    let area = match (b.bbox, b.polygon) {
        (Some(bb), None) => {
            let [w, s, e, n] = bb;
            check_region(&[[w, s], [e, s], [e, n], [w, n]], "bbox")?;
            crate::osm::site::Area::Bbox(bb)
        }
        (None, Some(ring)) => {
            check_region(&ring, "polygon")?;
            crate::osm::site::Area::Ring(ring)
        }
        _ => return Err(ApiError::bad("bbox", "give either `bbox` or `polygon`".into())),
    };
    let holes = b
        .holes
        .iter()
        .map(|h| AreaClass::parse(h).ok_or_else(|| ApiError::bad("holes", format!("`{h}` is not water, park or rail"))))
        .collect::<Result<_, _>>()?;
    let layers = cache.get(&path, &b.extract)?;
    let req = crate::osm::site::SiteRequest {
        extract: path.clone(),
        area,
        out: dir.clone(),
        holes,
        major: b.major,
        service: false,
        grow: true,
        city: true,
        largest: false,
        name: Some(b.name.clone()),
        exclude: b.exclude.into_iter().collect(),
    };
    let s = crate::osm::site::run_on(&layers.extract, &req)
        .map_err(|e| ApiError::invalid(None, shorten(&e.to_string(), &path, &b.extract)))?;
    Ok(json!({"name": s.name, "region_km2": s.region_km2, "land_km2": s.land_km2, "holes": s.holes,
              "roads": s.roads.0, "streets": s.streets.0, "outside_share": s.outside_share,
              "attribution": crate::osm::ATTRIBUTION}))
}

/// A site's files for the page: its region and roads, its real streets, and its comparison.
pub fn open(root: &Path, name: &str) -> Result<Value, ApiError> {
    check_name(name)?;
    let dir = root.join(SITES).join(name);
    let read = |f: &str| -> Result<Value, ApiError> {
        let text = std::fs::read_to_string(dir.join(f))
            .map_err(|_| ApiError::not_found("name", format!("no site `{name}` (no {f})")))?;
        serde_json::from_str(&text).map_err(|e| ApiError::invalid(None, format!("{f}: {e}")))
    };
    let compare = read("compare.json").ok();
    Ok(json!({"name": name, "site": read("site.geojson")?, "map": read("map/streets.geojson")?, "compare": compare}))
}

/// The urban methods a site runs.
pub const METHODS: &[&str] = &["layout", "grow", "city", "traffic"];

/// A method's run asked for by the page, with its settings.
#[derive(Clone, Debug, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct MethodBody {
    /// `layout`, `grow`, `city` or `traffic`.
    pub method: String,
    /// Seed (layout, grow).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Layout: the cross field (`distance` or `smooth`).
    #[serde(default)]
    pub field: Option<String>,
    /// Layout: variations.
    #[serde(default)]
    pub variations: Option<u64>,
    /// Grow: steps.
    #[serde(default)]
    pub steps: Option<u32>,
    /// City: time limit per level, seconds.
    #[serde(default)]
    pub time_limit: Option<f64>,
    /// City: the backend.
    #[serde(default)]
    pub solver: Option<String>,
    /// Traffic: seconds of departures.
    #[serde(default)]
    pub duration: Option<f64>,
}

/// The command line of a method's run on site `dir`, its output in `out`; `designs` are the
/// site's finished designs (label, output folder), which traffic simulates with the real streets.
pub fn command(dir: &Path, out: &Path, m: &MethodBody, designs: &[(String, PathBuf)]) -> Result<Vec<String>, ApiError> {
    let s = |p: &Path| p.display().to_string();
    let bad = |f: &str, m: String| ApiError::invalid(Some(f.into()), m);
    let mut args: Vec<String> = Vec::new();
    match m.method.as_str() {
        "layout" => {
            args.extend(["layout".into(), s(&dir.join("site.geojson"))]);
            if let Some(f) = &m.field {
                if !["distance", "smooth"].contains(&f.as_str()) {
                    return Err(bad("field", format!("`{f}`: distance or smooth")));
                }
                args.extend(["--field".into(), f.clone()]);
            }
            if let Some(v) = m.variations {
                if !(1..=20).contains(&v) {
                    return Err(bad("variations", format!("{v}: 1 to 20 on this server")));
                }
                args.extend(["--variations".into(), v.to_string()]);
            }
        }
        "grow" => {
            args.extend(["grow".into(), s(&dir.join("grow.toml"))]);
            if let Some(n) = m.steps {
                if !(1..=200).contains(&n) {
                    return Err(bad("steps", format!("{n}: 1 to 200 on this server")));
                }
                args.extend(["--steps".into(), n.to_string()]);
            }
        }
        "city" => {
            args.extend(["city".into(), s(&dir.join("city.toml"))]);
            let t = m.time_limit.unwrap_or(20.0);
            if !(t > 0.0 && t <= 600.0) {
                return Err(bad("time_limit", format!("{t}: more than 0 and at most 600 s per level")));
            }
            args.extend(["--time-limit".into(), t.to_string()]);
            if let Some(k) = &m.solver {
                k.parse::<crate::solvers::SolverKind>().map_err(|e| bad("solver", e.to_string()))?;
                args.extend(["--solver".into(), k.clone()]);
            }
        }
        "traffic" => {
            args.push("traffic".into());
            let mut labels = vec!["map".to_string()];
            args.push(s(&dir.join("map")));
            for (label, path) in designs {
                labels.push(label.clone());
                args.push(s(path));
            }
            args.extend(["--labels".into(), labels.join(","), "--region".into(), s(&dir.join("site.geojson"))]);
            let d = m.duration.unwrap_or(3600.0);
            if !(d > 0.0 && d <= 7200.0) {
                return Err(bad("duration", format!("{d}: more than 0 and at most 7200 s")));
            }
            args.extend(["--duration".into(), d.to_string()]);
        }
        other => return Err(bad("method", format!("`{other}`: one of {}", METHODS.join(", ")))),
    }
    if let Some(seed) = m.seed {
        if matches!(m.method.as_str(), "layout" | "grow") {
            args.extend(["--seed".into(), seed.to_string()]);
        }
    }
    args.extend(["--out".into(), s(out)]);
    Ok(args)
}

/// Runs the method's command as a child process, streaming its lines, until it ends or the run
/// is stopped; then records how it ended and, for a design, measures the site again.
pub fn execute(h: &Arc<RunHandle>, bin: &Path, args: &[String], site_dir: &Path, root: &Path) {
    use std::io::BufRead;
    use std::process::{Command, Stdio};
    h.update(|r| {
        r.state = RunState::Running;
        r.error = None;
    });
    h.push(json!({ "kind": "started", "command": format!("netspec {}", args.join(" ")) }));
    let mut cmd = Command::new(bin);
    cmd.args(args).stdout(Stdio::piped()).stderr(Stdio::piped()).env("NO_COLOR", "1");
    crate::compare::child::die_with_parent(&mut cmd);
    let mut child = match cmd.spawn() {
        Ok(c) => c,
        Err(e) => return failed(h, format!("could not start {}: {e}", bin.display())),
    };
    let tail: Arc<Mutex<Vec<String>>> = Arc::default();
    let mut readers = Vec::new();
    for pipe in [
        child.stdout.take().map(|p| Box::new(p) as Box<dyn std::io::Read + Send>),
        child.stderr.take().map(|p| Box::new(p) as _),
    ]
    .into_iter()
    .flatten()
    {
        let (h, tail) = (h.clone(), tail.clone());
        readers.push(std::thread::spawn(move || {
            for line in std::io::BufReader::new(pipe).split(b'\n').map_while(Result::ok) {
                let text = String::from_utf8_lossy(&line).split('\r').next_back().unwrap_or("").trim_end().to_string();
                if text.is_empty() {
                    continue;
                }
                h.push(json!({ "kind": "line", "text": text }));
                let mut t = tail.lock().unwrap_or_else(|e| e.into_inner());
                t.push(text);
                let n = t.len();
                if n > 8 {
                    t.drain(..n - 8);
                }
            }
        }));
    }
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None) if h.interrupt.is_triggered() => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(std::time::Duration::from_millis(100)),
            Err(e) => return failed(h, e.to_string()),
        }
    };
    for r in readers {
        let _ = r.join();
    }
    let Some(status) = status else {
        h.update(|r| {
            r.state = RunState::Interrupted;
            r.error = Some("cancelled".into());
        });
        h.push(json!({ "kind": "done", "state": "interrupted", "error": "cancelled" }));
        return;
    };
    // city: 4 means some level ended without a network; the rest is designed.
    let city_partial = args.first().is_some_and(|a| a == "city") && status.code() == Some(4);
    if !status.success() && !city_partial {
        let t = tail.lock().unwrap_or_else(|e| e.into_inner()).join("\n");
        return failed(h, format!("{} ({status})", if t.is_empty() { "the method failed".into() } else { t }));
    }
    // Finished first: the comparison takes the site's finished designs.
    h.update(|r| r.state = RunState::Finished);
    let compare = remeasure(root, site_dir);
    if let Err(e) = &compare {
        h.update(|r| r.error = Some(format!("the comparison: {e}")));
    }
    h.push(json!({ "kind": "done", "state": "finished", "compare": compare.is_ok() }));
}

fn failed(h: &Arc<RunHandle>, message: String) {
    h.update(|r| {
        r.state = RunState::Failed;
        r.error = Some(message.clone());
    });
    h.push(json!({ "kind": "failed", "error": message }));
}

/// The site's finished designs: (label, output folder), one per finished method run, newest
/// first per method (a label is the method, and the run id when a method ran more than once).
pub fn designs(root: &Path, site: &str) -> Vec<(String, PathBuf)> {
    let mut by_method: BTreeMap<String, Vec<(String, PathBuf)>> = BTreeMap::new();
    for h in super::runs::load_records(&root.join(super::specs::RUNS)) {
        let (rec, dir) = h;
        if rec.settings["kind"] != "urban" || rec.settings["site"] != site || rec.state != RunState::Finished {
            continue;
        }
        let method = rec.settings["method"].as_str().unwrap_or_default().to_string();
        if method == "traffic" {
            continue;
        }
        by_method.entry(method).or_default().push((rec.id.clone(), dir.join("out")));
    }
    let mut out = Vec::new();
    for (method, mut runs) in by_method {
        runs.sort();
        let label = if method == "grow" { "grown".to_string() } else { method.clone() };
        let n = runs.len();
        for (id, dir) in runs.into_iter().rev() {
            out.push((if n == 1 { label.clone() } else { format!("{label}-{id}") }, dir));
        }
    }
    out
}

/// Measures the real streets and every finished design of the site on its outline and writes
/// `compare.json`: per design its statistics, distance to the real streets, parcels, and its
/// streets in WGS 84 (clipped to the site) for the linked maps; SUMO's numbers when a traffic run
/// has finished.
pub fn remeasure(root: &Path, site_dir: &Path) -> Result<Value, String> {
    let name = site_dir.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let region =
        crate::traffic::network::SiteRegion::load(&site_dir.join("site.geojson")).map_err(|e| e.to_string())?;
    let found = designs(root, &name);
    let mut paths = vec![site_dir.join("map")];
    let mut labels = vec!["map".to_string()];
    for (l, p) in &found {
        labels.push(l.clone());
        paths.push(p.clone());
    }
    let req = crate::measure::StatsRequest {
        designs: paths,
        labels,
        load: crate::traffic::network::LoadOptions { region: Some(region.clone()), ..Default::default() },
        ..Default::default()
    };
    let measured = crate::measure::run(&req).map_err(|e| e.to_string())?;
    let traffic = latest_traffic(root, &name);
    let designs: Vec<Value> = measured
        .iter()
        .map(|d| {
            let streets = d.network.as_ref().map(|(net, poly)| streets_geojson(net, poly.as_ref(), &region.projection));
            let sumo = traffic.as_ref().and_then(|t| t.get(&d.label).cloned());
            json!({"label": d.label, "path": d.path, "kind": d.kind, "stats": d.stats, "parcels": d.parcels,
                   "distance": d.distance, "streets": streets, "traffic": sumo})
        })
        .collect();
    let out = json!({"site": name, "designs": designs, "attribution": crate::osm::ATTRIBUTION});
    let text = serde_json::to_string(&out).map_err(|e| e.to_string())? + "\n";
    crate::run::write_atomic(&site_dir.join("compare.json"), text.as_bytes()).map_err(|e| e.to_string())?;
    Ok(out)
}

/// SUMO's numbers per design label of the site's newest finished traffic run.
fn latest_traffic(root: &Path, site: &str) -> Option<BTreeMap<String, Value>> {
    let mut runs: Vec<_> = super::runs::load_records(&root.join(super::specs::RUNS))
        .into_iter()
        .filter(|(r, _)| {
            r.settings["kind"] == "urban"
                && r.settings["site"] == site
                && r.settings["method"] == "traffic"
                && r.state == RunState::Finished
        })
        .collect();
    runs.sort_by(|a, b| a.0.id.cmp(&b.0.id));
    let (_, dir) = runs.pop()?;
    let text = std::fs::read_to_string(dir.join("out").join("comparison.json")).ok()?;
    let v: Value = serde_json::from_str(&text).ok()?;
    let mut out = BTreeMap::new();
    for d in v["designs"].as_array()? {
        let r = &d["report"];
        out.insert(
            d["label"].as_str()?.to_string(),
            json!({"arrived": r["vehicles"]["arrived"], "inserted": r["vehicles"]["inserted"],
                   "teleported": r["vehicles"]["teleported"], "travel_time_mean": r["all"]["travel_time_mean"],
                   "time_loss_mean": r["all"]["time_loss_mean"], "digest": r["demand"]["digest"]}),
        );
    }
    Some(out)
}

/// A network's streets, clipped to the site, as WGS 84 GeoJSON (degrees to 7 places; a piece
/// that cannot be projected is left out).
fn streets_geojson(net: &crate::traffic::RoadNetwork, poly: Option<&Polygon>, proj: &Projection) -> Value {
    let mut w = crate::geometry::geojson::GeoJsonWriter::new(proj).digits(7);
    for e in &net.edges {
        let pieces = match poly {
            Some(p) => p.clip_polyline(&e.shape, crate::stats::BOUNDARY_TOL),
            None => vec![e.shape.clone()],
        };
        for piece in pieces {
            // A piece off the projection's domain is no street of the picture.
            let _ = w.line(&piece, json!({"level": e.level}));
        }
    }
    w.into_value(Value::Null)
}

/// The comparison as CSV: a row per design, the statistics a reader compares first.
pub fn compare_csv(compare: &Value) -> String {
    let keys = [
        "street_density_km",
        "intersection_density_km",
        "clean_intersection_density_km",
        "dead_end_density_km",
        "streets_per_node_avg",
        "circuity_avg",
        "orientation_entropy",
        "orientation_order",
        "blocks_per_km2",
        "block_perimeter_mean",
        "area_km2",
    ];
    let mut out =
        format!("design,{},distance_to_map,parcels,undesirable_parcels,sumo_travel_time_mean\n", keys.join(","));
    let num = |v: &Value| v.as_f64().map_or(String::new(), |x| format!("{x}"));
    for d in compare["designs"].as_array().into_iter().flatten() {
        let cells: Vec<String> = keys.iter().map(|k| num(&d["stats"][k])).collect();
        out += &format!(
            "{},{},{},{},{},{}\n",
            d["label"].as_str().unwrap_or_default(),
            cells.join(","),
            num(&d["distance"]["mean"]),
            num(&d["parcels"]["parcels"]),
            num(&d["parcels"]["undesirable"]),
            num(&d["traffic"]["travel_time_mean"]),
        );
    }
    out
}
