//! `netspec site` and `netspec stats` on an OpenStreetMap extract the test writes (OSM XML, a
//! made-up town near 48° N): a grid of residential streets, a primary road drawn as two ways, a
//! secondary road across a lake, the sea beyond a coastline in one corner, a park, a one-way
//! street, a service road, a footway and a building. The site's holes, outline, major roads
//! (merged, clipped, split at the water) and attribution; the real streets as a design; the grow
//! context and the city spec read back by their own readers; the site through `layout`, `grow`,
//! `city`, `stats` and `traffic`; and bad input named, nothing written.

use netspec::grow::context::Context;
use netspec::urban::CitySpec;
use serde_json::Value;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const LON0: f64 = 11.0;
const LAT0: f64 = 48.0;
/// The region of every test: about 1.19 × 1.11 km inside the extract.
pub const BBOX: &str = "11.002,48.001,11.018,48.011";

fn ll(x: f64, y: f64) -> (f64, f64) {
    (LON0 + x / (111_320.0 * LAT0.to_radians().cos()), LAT0 + y / 111_132.0)
}

/// Tags of a way.
type Tags = Vec<(&'static str, &'static str)>;

/// An OSM XML extract: nodes from points (metres), ways with tags.
#[derive(Default)]
struct Osm {
    nodes: Vec<(i64, f64, f64)>,
    ways: Vec<(i64, Vec<i64>, Tags)>,
}

impl Osm {
    fn node(&mut self, x: f64, y: f64) -> i64 {
        let id = self.nodes.len() as i64 + 1;
        self.nodes.push((id, x, y));
        id
    }

    fn way(&mut self, refs: Vec<i64>, tags: &[(&'static str, &'static str)]) {
        let id = 1000 + self.ways.len() as i64;
        self.ways.push((id, refs, tags.to_vec()));
    }

    fn line(&mut self, pts: &[(f64, f64)], tags: &[(&'static str, &'static str)]) {
        let refs = pts.iter().map(|&(x, y)| self.node(x, y)).collect();
        self.way(refs, tags);
    }

    fn ring(&mut self, pts: &[(f64, f64)], tags: &[(&'static str, &'static str)]) {
        let mut refs: Vec<i64> = pts.iter().map(|&(x, y)| self.node(x, y)).collect();
        refs.push(refs[0]);
        self.way(refs, tags);
    }

    fn xml(&self) -> String {
        let mut s =
            String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<osm version=\"0.6\" generator=\"test\">\n");
        for &(id, x, y) in &self.nodes {
            let (lon, lat) = ll(x, y);
            let _ = writeln!(s, r#"  <node id="{id}" lat="{lat:.8}" lon="{lon:.8}"/>"#);
        }
        for (id, refs, tags) in &self.ways {
            let _ = writeln!(s, r#"  <way id="{id}">"#);
            for r in refs {
                let _ = writeln!(s, r#"    <nd ref="{r}"/>"#);
            }
            for (k, v) in tags {
                let _ = writeln!(s, r#"    <tag k="{k}" v="{v}"/>"#);
            }
            s.push_str("  </way>\n");
        }
        s + "</osm>\n"
    }
}

/// The made-up town as OSM XML (for the browser's tests too).
pub fn town_xml() -> String {
    town().xml()
}

/// The made-up town (metres east and north of 11° E, 48° N; the region spans about 150–1340 ×
/// 110–1220).
fn town() -> Osm {
    let mut o = Osm::default();
    // The residential grid: streets every 150 m, nodes shared where they cross.
    let xs: Vec<f64> = (0..10).map(|i| 100.0 + 150.0 * i as f64).collect();
    let ys: Vec<f64> = (0..9).map(|j| 100.0 + 150.0 * j as f64).collect();
    let grid: Vec<Vec<i64>> = ys.iter().map(|&y| xs.iter().map(|&x| o.node(x, y)).collect()).collect();
    for row in &grid {
        o.way(row.clone(), &[("highway", "residential")]);
    }
    for i in 0..xs.len() {
        let col: Vec<i64> = grid.iter().map(|r| r[i]).collect();
        let tags: &[(&str, &str)] =
            if i == 1 { &[("highway", "residential"), ("oneway", "yes")] } else { &[("highway", "residential")] };
        o.way(col, tags);
    }
    // The primary road at y = 720, drawn as two ways meeting at x = 750.
    let mid = o.node(750.0, 720.0);
    let (w, e) = (o.node(0.0, 720.0), o.node(1500.0, 720.0));
    o.way(vec![w, mid], &[("highway", "primary"), ("name", "Main Street")]);
    o.way(vec![mid, e], &[("highway", "primary"), ("name", "Main Street")]);
    // A lake, and the secondary road across it at x = 610.
    o.ring(&[(520.0, 300.0), (700.0, 300.0), (700.0, 480.0), (520.0, 480.0)], &[("natural", "water")]);
    o.line(&[(610.0, 0.0), (610.0, 1330.0)], &[("highway", "secondary"), ("bridge", "yes")]);
    // The coastline: land on its left, the sea in the north-east corner.
    o.line(&[(1500.0, 900.0), (1100.0, 1330.0)], &[("natural", "coastline")]);
    // A park, a service road, a footway, a building.
    o.ring(&[(880.0, 160.0), (980.0, 160.0), (980.0, 240.0), (880.0, 240.0)], &[("leisure", "park")]);
    o.line(&[(175.0, 175.0), (225.0, 175.0)], &[("highway", "service")]);
    o.line(&[(170.0, 600.0), (230.0, 650.0)], &[("highway", "footway")]);
    o.ring(&[(300.0, 300.0), (320.0, 300.0), (320.0, 320.0)], &[("building", "yes")]);
    o
}

fn netspec(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_netspec")).args(args).output().expect("netspec runs")
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn extract(dir: &Path) -> PathBuf {
    let f = dir.join("town.osm");
    std::fs::write(&f, town().xml()).expect("written");
    f
}

fn json(p: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(p).expect("read")).expect("JSON")
}

fn features<'a>(v: &'a Value, geometry: &str) -> Vec<&'a Value> {
    v["features"].as_array().expect("features").iter().filter(|f| f["geometry"]["type"] == geometry).collect()
}

fn site(dir: &Path, extra: &[&str]) -> PathBuf {
    let out = dir.join("site");
    let f = extract(dir);
    let mut args = vec!["site", f.to_str().unwrap(), "--bbox", BBOX, "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    ok(&netspec(&args));
    out
}

#[test]
fn a_site_has_its_water_as_holes_or_outline_and_its_major_roads() {
    let dir = tempfile::tempdir().unwrap();
    let out = site(dir.path(), &["--grow", "--city"]);
    let s = json(&out.join("site.geojson"));
    assert!(s["attribution"].as_str().unwrap().contains("OpenStreetMap contributors"));
    let polys = features(&s, "Polygon");
    assert_eq!(polys.len(), 1, "one region");
    let rings = polys[0]["geometry"]["coordinates"].as_array().unwrap();
    assert_eq!(rings.len(), 2, "the outline and the lake (the park is no hole by default)");
    assert!(polys[0]["properties"]["attribution"].as_str().unwrap().contains("ODbL"));
    // The sea cuts the north-east corner: the outline has more than the box's four corners.
    assert!(rings[0].as_array().unwrap().len() > 5, "{}", rings[0]);
    let roads = features(&s, "LineString");
    let named = |n: &str| roads.iter().filter(|r| r["properties"]["name"] == n).count();
    assert_eq!(named("Main Street"), 1, "the primary's two ways merge into one road");
    let secondary = roads.iter().filter(|r| r["properties"]["highway"] == "secondary").count();
    assert_eq!(secondary, 2, "the secondary is split where it crosses the lake");
    assert!(roads.iter().all(|r| r["properties"]["kind"] == "road"));

    let m = json(&out.join("map/streets.geojson"));
    let streets = features(&m, "LineString");
    let highways: std::collections::BTreeSet<&str> =
        streets.iter().map(|f| f["properties"]["highway"].as_str().unwrap()).collect();
    assert_eq!(highways, ["primary", "residential", "secondary"].into(), "no service road, no footway");
    assert!(streets.iter().all(|f| f["properties"]["u"].is_i64() && f["properties"]["v"].is_i64()));
    assert!(streets.iter().any(|f| f["properties"]["oneway"] == true));
    let level =
        |h: &str| streets.iter().find(|f| f["properties"]["highway"] == h).unwrap()["properties"]["level"].clone();
    assert_eq!((level("primary"), level("residential")), (1.into(), 3.into()));
    assert_eq!(features(&m, "Polygon")[0]["properties"]["origin"], polys[0]["properties"]["origin"]);

    // The grow context and the city spec read back with their own readers.
    let ctx = Context::load(&out.join("grow.toml")).expect("a grow context");
    assert_eq!(ctx.road.len(), 2, "the primary, and the secondary whole across the lake");
    assert!(!ctx.water.is_empty() && ctx.neighbour.len() >= 3);
    let toml = std::fs::read_to_string(out.join("grow.toml")).unwrap();
    assert!(toml.contains("OpenStreetMap contributors"));
    let city = CitySpec::load(&out.join("city.toml")).expect("a city spec");
    assert_eq!(city.roads.len(), 3);
    let lvl = city.level(None, 2).expect("level 2");
    assert_eq!(lvl.user.obstacle_polygons.len(), 1, "the lake, clear of the roads");

    // Parks as holes too.
    let out2 = dir.path().join("site2");
    let f = dir.path().join("town.osm");
    ok(&netspec(&[
        "site",
        f.to_str().unwrap(),
        "--bbox",
        BBOX,
        "--holes",
        "water,park",
        "--out",
        out2.to_str().unwrap(),
    ]));
    let s2 = json(&out2.join("site.geojson"));
    assert_eq!(features(&s2, "Polygon")[0]["geometry"]["coordinates"].as_array().unwrap().len(), 3);
}

#[test]
fn bad_sites_are_named_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let f = extract(dir.path());
    let out = dir.path().join("out");
    let run = |args: &[&str]| {
        let mut a = vec!["site"];
        a.extend_from_slice(args);
        a.extend_from_slice(&["--out", out.to_str().unwrap()]);
        let o = netspec(&a);
        assert_eq!(o.status.code(), Some(1), "{a:?}");
        assert!(!out.exists(), "nothing written for {a:?}");
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let e = run(&[f.to_str().unwrap(), "--bbox", "12.0,49.0,12.01,49.01"]);
    assert!(e.contains("lies outside the extract") && e.contains("town.osm"), "{e}");
    let e = run(&[f.to_str().unwrap(), "--bbox", "11.01,48.01,11.0,48.0"]);
    assert!(e.contains("--bbox") && e.contains("west < east"), "{e}");
    let junk = dir.path().join("junk.osm.pbf");
    std::fs::write(&junk, "this is not OpenStreetMap").unwrap();
    let e = run(&[junk.to_str().unwrap(), "--bbox", BBOX]);
    assert!(e.contains("junk.osm.pbf") && e.contains("not an OpenStreetMap extract"), "{e}");
    let empty = dir.path().join("empty.osm");
    std::fs::write(&empty, "<osm version=\"0.6\"></osm>").unwrap();
    let e = run(&[empty.to_str().unwrap(), "--bbox", BBOX]);
    assert!(e.contains("empty.osm") && e.contains("empty"), "{e}");
    let flat = dir.path().join("flat.geojson");
    std::fs::write(&flat, r#"{"type": "Polygon", "coordinates": [[[11.005, 48.005], [11.01, 48.005], [11.015, 48.005], [11.005, 48.005]]]}"#).unwrap();
    let e = run(&[f.to_str().unwrap(), "--polygon", flat.to_str().unwrap()]);
    assert!(e.contains("flat.geojson"), "{e}");
    // A river across the whole region splits it: refused unless --largest.
    let mut o = town();
    o.ring(
        &[(0.0, 800.0), (1500.0, 800.0), (1500.0, 850.0), (0.0, 850.0)],
        &[("natural", "water"), ("water", "river")],
    );
    let split = dir.path().join("split.osm");
    std::fs::write(&split, o.xml()).unwrap();
    let e = run(&[split.to_str().unwrap(), "--bbox", BBOX]);
    assert!(e.contains("pieces") && e.contains("--largest"), "{e}");
    ok(&netspec(&["site", split.to_str().unwrap(), "--bbox", BBOX, "--largest", "--out", out.to_str().unwrap()]));
}

#[test]
fn a_site_through_layout_grow_city_and_stats() {
    let dir = tempfile::tempdir().unwrap();
    let out = site(dir.path(), &["--grow", "--city"]);
    let d = |n: &str| out.join(n).to_str().unwrap().to_string();
    ok(&netspec(&["layout", &d("site.geojson"), "--out", &d("layout")]));
    ok(&netspec(&["grow", &d("grow.toml"), "--steps", "4", "--out", &d("grown")]));
    let o = netspec(&["city", &d("city.toml"), "--time-limit", "1", "--out", &d("city")]);
    assert!(matches!(o.status.code(), Some(0 | 4)), "{}", String::from_utf8_lossy(&o.stderr));
    let table = ok(&netspec(&[
        "stats",
        &d("map"),
        &d("layout"),
        &d("grown"),
        &d("city"),
        "--region",
        &d("site.geojson"),
        "--out",
        &d("stats"),
    ]));
    assert!(table.contains("| map |") && table.contains("reference"), "{table}");
    let st = json(&out.join("stats/stats.json"));
    let designs = st["designs"].as_array().unwrap();
    assert_eq!(designs.len(), 4);
    let area = designs[0]["stats"]["area_km2"].as_f64().unwrap();
    for des in designs {
        // One region for all: the same area.
        assert!((des["stats"]["area_km2"].as_f64().unwrap() - area).abs() < 1e-9, "{}", des["label"]);
        assert!(des["stats"]["street_length_total"].as_f64().unwrap() > 1000.0, "{}", des["label"]);
    }
    assert!(designs[0]["distance"].is_null() && designs[1]["distance"]["mean"].as_f64().unwrap() > 0.0);
    assert_eq!(designs[1]["reference"], "map");
    assert!(designs[1]["parcels"]["parcels"].as_u64().unwrap() > 0, "the layout has parcels");
    for f in ["comparison.png", "orientation-map.svg", "orientation-layout.png"] {
        assert!(out.join("stats").join(f).is_file(), "{f}");
    }
    // The map alone, as JSON lines: its grid, clipped to the region, reads as a grid.
    let line = ok(&netspec(&["stats", &d("map"), "--json"]));
    let map: Value = serde_json::from_str(line.lines().next().unwrap()).unwrap();
    assert!(map["stats"]["orientation_order"].as_f64().unwrap() > 0.9, "{}", map["stats"]["orientation_order"]);
    // A design without a place on the map cannot be judged on a site.
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/specs/tiny_network.toml");
    ok(&netspec(&["solve", spec.to_str().unwrap(), "--time-limit", "10", "--out", &d("solve")]));
    let e = netspec(&["stats", &d("solve"), "--region", &d("site.geojson")]);
    assert_eq!(e.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&e.stderr).contains("no place on the map"));
}

#[test]
fn the_real_streets_and_a_layout_meet_the_same_demand_in_sumo() {
    crate::setup_part("sumo");
    let dir = tempfile::tempdir().unwrap();
    let out = site(dir.path(), &[]);
    let d = |n: &str| out.join(n).to_str().unwrap().to_string();
    ok(&netspec(&["layout", &d("site.geojson"), "--out", &d("layout")]));
    ok(&netspec(&[
        "traffic",
        &d("map"),
        &d("layout"),
        "--region",
        &d("site.geojson"),
        "--duration",
        "300",
        "--out",
        &d("traffic"),
    ]));
    let c = json(&out.join("traffic/comparison.json"));
    let designs = c["designs"].as_array().unwrap();
    let digests: std::collections::BTreeSet<&str> =
        designs.iter().map(|d| d["report"]["demand"]["digest"].as_str().unwrap()).collect();
    assert_eq!(digests.len(), 1, "the same trips for the real streets and the layout");
    for des in designs {
        assert!(des["report"]["vehicles"]["arrived"].as_u64().unwrap() > 0, "{}", des["label"]);
    }
}
