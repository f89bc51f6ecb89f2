//! Street layouts (§5.1): a small two-region, two-level city on every backend (snapshot),
//! roads carried over between levels, a failing sub-region, resume after a kill, the outputs.

use crate::network::backends;
use netspec::mesh::Mesh;
use netspec::solvers::SolverKind;
use netspec::spec::{EdgeRole, Spec};
use netspec::urban::{run_city, CityResult, CityRunOptions, CitySpec};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/city/two-regions.toml")
}

fn options(kind: SolverKind) -> CityRunOptions {
    CityRunOptions {
        solver: kind,
        time_limit: Some(60.0),
        threads: 2,
        threads_per_solve: 1,
        gap: Some(0.0),
        seed: None,
        resume: true,
        observer: None,
        interrupt: None,
        only: None,
        reuse_only: false,
        deadline: None,
    }
}

fn run(text: &str, kind: SolverKind, out: &Path) -> CityResult {
    let spec = CitySpec::from_toml(text).unwrap();
    run_city(&spec, out, &options(kind)).unwrap()
}

#[derive(Serialize)]
struct LevelSnap {
    region: String,
    level: u8,
    state: String,
    termination: Option<String>,
    objective: Option<f64>,
    valid: Option<bool>,
    mesh: Option<[usize; 3]>,
    new_edges: Option<usize>,
}

fn snapshot(r: &CityResult) -> Vec<LevelSnap> {
    r.regions
        .iter()
        .flat_map(|reg| {
            reg.levels.iter().map(|l| LevelSnap {
                region: reg.name.clone(),
                level: l.level,
                state: l.state.clone(),
                termination: l.termination.clone(),
                objective: l.objective.map(|o| (o * 1e6).round() / 1e6),
                valid: l.valid,
                mesh: l.mesh,
                new_edges: l.new_edges,
            })
        })
        .collect()
}

/// Objectives per level and validity, the same on every backend; level-2 roads are existing
/// roads of level 3 and active in its network.
#[test]
fn two_region_city_on_every_backend() {
    let text = std::fs::read_to_string(fixture()).unwrap();
    type Objectives = Vec<(String, u8, Option<f64>)>;
    let mut first: Option<(SolverKind, Objectives)> = None;
    for kind in backends(false) {
        let dir = tempfile::tempdir().unwrap();
        let r = run(&text, kind, dir.path());
        assert!(r.complete && r.valid, "{kind}: {:#?}", r.regions);
        assert_eq!(r.regions.len(), 2);
        for reg in &r.regions {
            assert!(reg.levels.iter().all(|l| l.termination.as_deref() == Some("optimal")), "{kind}: {:?}", reg.levels);
            check_carried_over(dir.path(), reg);
        }
        let objs: Vec<_> = r
            .regions
            .iter()
            .flat_map(|g| {
                g.levels.iter().map(|l| (g.name.clone(), l.level, l.objective.map(|o| (o * 1e6).round() / 1e6)))
            })
            .collect();
        match &first {
            None => {
                insta::assert_yaml_snapshot!("city_two_regions", snapshot(&r));
                first = Some((kind, objs));
            }
            Some((k0, o0)) => assert_eq!(&objs, o0, "{kind} disagrees with {k0}"),
        }
    }
}

/// Level 3's spec lists every level-2 road (split in two by the subdivision) as an existing
/// edge; they are active in level 3's network.
fn check_carried_over(out: &Path, reg: &netspec::urban::RegionReport) {
    let dir = netspec::urban::city::region_dir(out, reg.index, &reg.name);
    let l3 = dir.join("L3");
    let spec = Spec::load(&l3.join("spec.json")).unwrap();
    let problem = spec.resolve(&l3).unwrap();
    let roads = reg.roads.as_ref().unwrap();
    let mesh: &Mesh = &roads.mesh;
    assert_eq!(mesh.num_edges(), problem.mesh.num_edges());
    let result: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(l3.join("result.json")).unwrap()).unwrap();
    let active: Vec<[u32; 2]> = serde_json::from_value(result["active_edges"].clone()).unwrap();
    let mut level2 = 0;
    for e in mesh.edges() {
        if roads.edge_level[e.index()] == 2 {
            level2 += 1;
            assert_eq!(
                problem.roles[e.index()],
                EdgeRole::Existing,
                "{}: level-2 edge {e:?} is not existing at level 3",
                reg.name
            );
            let (a, b) = mesh.edge_vertices(e);
            assert!(active.contains(&[a.0, b.0]), "{}: level-2 edge {a:?}-{b:?} inactive at level 3", reg.name);
            assert!(problem.is_sink[a.index()] && problem.is_sink[b.index()]);
        }
    }
    assert!(level2 > 0, "{}: level 2 built no road", reg.name);
    // Level 2's own network passed every check.
    let l2: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("L2/result.json")).unwrap()).unwrap();
    assert_eq!(l2["validity"]["valid"], serde_json::json!(true));
}

/// An infeasible sub-region is reported and skipped; the other one is still designed.
#[test]
fn infeasible_region_is_a_result() {
    let text = std::fs::read_to_string(fixture()).unwrap()
        + "\n[region.levels.2.sinks]\nall_boundary = false\npoints = [[8, 0]]\n[region.levels.3]\nboundary = \"wall\"\n";
    let text = text.replace("[region.levels.2]\n", "[region.levels.2]\nboundary = \"wall\"\n");
    let dir = tempfile::tempdir().unwrap();
    let r = run(&text, SolverKind::default_kind().unwrap(), dir.path());
    assert!(!r.complete);
    let east = r.regions.iter().find(|g| g.name == "east").unwrap();
    assert_eq!(east.levels[0].state, "no_network");
    assert_eq!(east.levels[0].termination.as_deref(), Some("infeasible"));
    assert_eq!(east.levels[1].state, "skipped");
    let west = r.regions.iter().find(|g| g.name != "east").unwrap();
    assert!(west.levels.iter().all(|l| l.state == "solved"), "{:?}", west.levels);
    assert!(dir.path().join("city.svg").exists() && dir.path().join("streets.geojson").exists());
}

/// The outputs: GeoJSON (WGS 84) with one line per snake at every level, metrics, smoothing
/// energy down; the picture draws the levels present, the obstacle and the given sinks, and says
/// which metrics are totals and which per km².
#[test]
fn outputs_and_metrics() {
    // An obstacle and an explicit sink at level 2 (as Fig. 8 has).
    let text = std::fs::read_to_string(fixture()).unwrap().replace(
        "[levels.2]\n",
        "[levels.2]\nuser = { obstacle_polygons = [[[0, 0], [1, 0], [1, 1], [0, 1]]] }\nsinks = { all_boundary = true, points = [[6, 2]] }\n",
    );
    let dir = tempfile::tempdir().unwrap();
    let r = run(&text, SolverKind::default_kind().unwrap(), dir.path());
    assert!(r.complete && r.valid, "{:#?}", r.regions);
    let geo: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("streets.geojson")).unwrap()).unwrap();
    assert_eq!(geo["type"], "FeatureCollection");
    // WGS 84 around the default origin (0°, 0°): the 8 × 4 units at 100 m span 800 m east and
    // 400 m north, about 0.0072° and 0.0036°.
    assert_eq!(geo["properties"]["geo_origin"], serde_json::json!([0.0, 0.0]));
    assert_eq!(geo["properties"]["geo_origin_is_default"], serde_json::json!(true));
    let mut points = Vec::new();
    collect_points(&geo["features"], &mut points);
    let (lo, hi) = points.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    });
    assert!(lo[0].abs() < 1e-12 && lo[1].abs() < 1e-12, "{lo:?}");
    // Through the one transverse Mercator, degrees to 1e-8 (about a millimetre).
    let proj = netspec::geometry::site::Projection::new([0.0, 0.0]).unwrap();
    let [x, y] = proj.to_local(hi).unwrap();
    assert!((x - 800.0).abs() < 2e-3 && (y - 400.0).abs() < 2e-3, "{hi:?} is ({x}, {y}) m");
    let features = geo["features"].as_array().unwrap();
    let streets: Vec<_> = features.iter().filter(|f| f["properties"]["kind"] == "street").collect();
    // Level 1 (as given) is one multi-line; every other street is one smoothed snake.
    assert_eq!(streets.iter().filter(|f| f["geometry"]["type"] == "MultiLineString").count(), 1);
    assert!(streets.len() <= r.smoothing.snakes + 1);
    for level in [1, 2, 3] {
        assert!(streets.iter().any(|f| f["properties"]["level"] == level), "no level-{level} street");
    }
    assert_eq!(features.iter().filter(|f| f["properties"]["kind"] == "sub-region").count(), 2);
    // 8 × 4 units at 100 m: 0.32 km².
    assert!((r.metrics.area_km2 - 0.32).abs() < 1e-9, "{:?}", r.metrics);
    // The layout metrics of `netspec layout`, parcels from its parceller on the city's blocks.
    let lm = r.layout_metrics.as_ref().expect("a rectangular domain is a polygon");
    assert!((lm.area_km2 - 0.32).abs() < 1e-9 && lm.parcels > 100 && lm.blocks >= 2, "{lm:?}");
    let lu = &lm.land_use;
    assert!((lu.streets + lu.residential + lu.parks + lu.other - 100.0).abs() < 1.0, "{lu:?}");
    assert!(r.smoothing.energy_after < r.smoothing.energy_before);
    let png = std::fs::read(dir.path().join("city.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let svg = std::fs::read_to_string(dir.path().join("city.svg")).unwrap();
    for level in 1..=3 {
        assert!(svg.contains(&format!("data-level=\"{level}\"")), "no level {level} in the picture");
    }
    // The legend lists what is drawn: levels 1–3, the obstacle and the given sink; no level 4.
    assert!(svg.contains(">level 3: local roads<") && !svg.contains("level 4"), "{svg}");
    assert_eq!(svg.matches(r#"class="obstacle""#).count(), 1, "{svg}");
    assert_eq!(svg.matches(r#"class="sink""#).count(), 1, "{svg}");
    assert!(svg.contains(">obstacle<") && svg.contains(">sink (given)<"), "{svg}");
    let totals = format!("totals over 0.320 km²: streets {:.2} km", r.metrics.street_length_km);
    assert!(svg.contains(&totals) && svg.contains(&format!("per km²: streets {:.1} km", r.metrics.sl)), "{svg}");
}

fn collect_points(v: &serde_json::Value, out: &mut Vec<[f64; 2]>) {
    match v {
        serde_json::Value::Array(a) if a.len() == 2 && a.iter().all(|x| x.is_f64()) => {
            out.push([a[0].as_f64().unwrap(), a[1].as_f64().unwrap()])
        }
        serde_json::Value::Array(a) => a.iter().for_each(|x| collect_points(x, out)),
        serde_json::Value::Object(o) => {
            if let Some(g) = o.get("geometry") {
                collect_points(&g["coordinates"], out);
            } else {
                o.values().for_each(|x| collect_points(x, out));
            }
        }
        _ => {}
    }
}

/// With `geo_origin`, points are degrees around it, through the one transverse Mercator: the
/// origin is the anchor, and a point's degrees lead back to its metres.
#[test]
fn wgs84_around_a_given_origin() {
    use netspec::design::streets::GeoAnchor;
    use netspec::geometry::geojson::GeoJsonWriter;
    let text = std::fs::read_to_string(fixture())
        .unwrap()
        .replace("metres_per_unit = 100", "metres_per_unit = 100\ngeo_origin = [4.35, 50.85]");
    let spec = CitySpec::from_toml(&text).unwrap();
    let anchor = GeoAnchor::of_city(&spec);
    let proj = anchor.projection().unwrap();
    let w = GeoJsonWriter::new(&proj).scaled(anchor.metres_per_unit);
    assert_eq!(w.lonlat([0.0, 0.0]).unwrap(), [4.35, 50.85]);
    let [x, y] = proj.to_local(w.lonlat([8.0, 4.0]).unwrap()).unwrap();
    assert!((x - 800.0).abs() < 2e-3 && (y - 400.0).abs() < 2e-3, "({x}, {y})");
    let plain = CitySpec::from_toml(&std::fs::read_to_string(fixture()).unwrap()).unwrap();
    assert_eq!(plain.origin_wgs84(), netspec::urban::DEFAULT_GEO_ORIGIN);
    let bad = text.replace("geo_origin = [4.35, 50.85]", "geo_origin = [4.35, 95]");
    assert!(CitySpec::from_toml(&bad).unwrap_err().to_string().contains("geo_origin"));
}

/// Kill the run after one sub-region has finished; the rerun reuses it (its files are not
/// touched) and solves only what is left.
#[test]
fn resume_after_kill() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let spec = dir.path().join("city.toml");
    // One region at a time (--threads 1): region 0 first, then region 1.
    let text = std::fs::read_to_string(fixture()).unwrap();
    std::fs::write(&spec, text).unwrap();
    let exe = env!("CARGO_BIN_EXE_netspec");
    let mut child = Command::new(exe)
        .args(["city", spec.to_str().unwrap(), "--threads", "1", "--out", out.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let first_done = out.join("regions/00-region-0/L3/state.json");
    let t0 = Instant::now();
    while !first_done.exists() {
        assert!(t0.elapsed() < Duration::from_secs(120), "region 0 never finished");
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the run ended ({status}) before region 0 finished");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let second_done_before = out.join("regions/01-east/L3/state.json").exists();
    let stamp = |p: &Path| std::fs::metadata(p).unwrap().modified().unwrap();
    let kept = ["L2/state.json", "L2/result.json", "L3/state.json", "L3/result.json"]
        .map(|f| out.join("regions/00-region-0").join(f));
    let before: Vec<_> = kept.iter().map(|p| stamp(p)).collect();

    let o = Command::new(exe)
        .args(["city", spec.to_str().unwrap(), "--threads", "1", "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let after: Vec<_> = kept.iter().map(|p| stamp(p)).collect();
    assert_eq!(before, after, "region 0's files were rewritten");
    let r: CityResult = serde_json::from_str(&std::fs::read_to_string(out.join("city.json")).unwrap()).unwrap();
    assert!(r.regions[0].levels.iter().all(|l| l.state == "reused"), "{:?}", r.regions[0].levels);
    if !second_done_before {
        assert!(r.regions[1].levels.iter().any(|l| l.state == "solved"), "{:?}", r.regions[1].levels);
    }
    assert!(r.complete && r.valid);
}

/// City spec errors name the file and field; a region point outside every sub-region too.
#[test]
fn bad_city_specs() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture()).unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, text.replace("at = [6, 2]", "at = [60, 2]")).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .args(["city", bad.to_str().unwrap(), "--out", dir.path().to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("bad.toml") && err.contains("region[0].at"), "{err}");
    std::fs::write(
        &bad,
        text.replace(
            "coverage = { range = 2 }\nweights = { length = 1 }",
            "coverage = { range = 2, far = 2 }\nweights = { length = 1 }",
        ),
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_netspec")).args(["city", bad.to_str().unwrap()]).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("levels.3") && err.contains("far"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// Every city example in models/city reads and its sub-regions mesh.
#[test]
fn city_examples_resolve() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/city");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let spec = CitySpec::load(&path).unwrap_or_else(|e| panic!("{e}"));
            let regions = netspec::urban::city::regions(&spec).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(!regions.is_empty());
            n += 1;
        }
    }
    assert!(n >= 9, "only {n} city examples");
}
