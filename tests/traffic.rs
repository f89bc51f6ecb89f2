//! Traffic evaluation in SUMO: tiny designs through the real `netconvert`,
//! `duarouter` and `sumo` installed by `scripts/setup.sh sumo` (run by the tests that need them); the export checked against the design
//! graph; the demand; errors that name the file and the cause.

use netspec::pipeline::{self, DesignResult};
use netspec::solvers::{SolveOptions, SolverKind};
use netspec::spec::Spec;
use netspec::traffic::demand::{self, TripClass};
use netspec::traffic::export::{self, parse_edge_id};
use netspec::traffic::network::{self, LoadOptions, Region};
use netspec::traffic::report::percentile;
use netspec::traffic::{evaluate, DemandSettings, RoadNetwork, Sumo};
use netspec::urban::{run_city, CityRunOptions, CitySpec};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures").join(rel)
}

/// The tiny network (a 4 × 4 grid, wall boundary, every boundary vertex a sink) solved with the
/// default backend to optimality; `extra` is appended to the spec.
fn tiny_design(extra: &str) -> DesignResult {
    let text = std::fs::read_to_string(fixture("specs/tiny_network.toml")).unwrap() + extra;
    let p = Spec::from_toml(&text).unwrap().resolve(Path::new(".")).unwrap();
    let nm = pipeline::build(&p);
    let r = pipeline::solve_built(
        &p,
        &nm,
        SolverKind::default_kind().unwrap(),
        &SolveOptions { time_limit: Some(60.0), ..Default::default() },
    )
    .unwrap();
    assert!(r.validity.valid, "{:?}", r.solve.termination);
    r
}

/// Demand of `duration` seconds, `through` and `local` trips per hour, no trade.
fn demand_of(duration: f64, through: f64, local: f64, seed: u64) -> DemandSettings {
    DemandSettings { duration, through_per_hour: through, local_per_hour: local, seed, ..Default::default() }
}

fn sumo() -> Sumo {
    crate::setup_part("sumo");
    Sumo::locate(None).unwrap_or_else(|e| panic!("{e}"))
}

/// Every value of attribute `name` of the `<tag …>` elements of an XML file, read with plain
/// string search (independent of the library's parser).
fn attr_values(path: &Path, tag: &str, name: &str) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let open = format!("<{tag} ");
    let key = format!(" {name}=\"");
    let mut out = Vec::new();
    for (i, _) in text.match_indices(&open) {
        let end = i + text[i..].find('>').unwrap();
        let el = &text[i..end];
        if let Some(k) = el.find(&key) {
            let v = &el[k + key.len()..];
            out.push(v[..v.find('"').unwrap()].to_string());
        }
    }
    out
}

/// A tiny design through the real netconvert, duarouter and sumo: every vehicle inserted
/// arrives, and the report's travel times are exactly the tripinfo file's.
#[test]
fn tiny_design_through_netconvert_and_sumo() {
    let res = tiny_design("");
    let net = network::from_design(
        &res,
        Path::new("tiny/result.json"),
        &LoadOptions { metres_per_unit: Some(50.0), level: None, window: None, region: None },
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let settings = demand_of(600.0, 120.0, 240.0, 3);
    let r = evaluate(&net, &settings, &sumo(), dir.path()).unwrap_or_else(|e| panic!("{e}"));
    let v = &r.vehicles;
    assert!(r.demand.placed > 10, "{:?}", r.demand);
    assert_eq!(r.demand.routed, r.demand.placed);
    assert_eq!(v.loaded, r.demand.routed as u64);
    assert_eq!(v.inserted, v.loaded);
    assert_eq!(v.arrived, v.inserted, "{v:?}");
    assert_eq!((v.running_at_end, v.waiting_at_end), (0, 0));
    assert!(r.through.vehicles > 0 && r.local.vehicles > 0);
    // Every designed street is in the .net.xml, both ways.
    assert_eq!(r.network.streets, res.active_edges.len());
    assert_eq!(r.network.streets_in_net, r.network.streets);
    assert_eq!(r.network.sumo_edges, 2 * r.network.streets);

    // The travel times are the tripinfo file's durations, class by class.
    let tripinfo = dir.path().join("sumo/tripinfo.xml");
    let ids = attr_values(&tripinfo, "tripinfo", "id");
    let durations: Vec<f64> =
        attr_values(&tripinfo, "tripinfo", "duration").iter().map(|d| d.parse().unwrap()).collect();
    let lengths: Vec<f64> =
        attr_values(&tripinfo, "tripinfo", "routeLength").iter().map(|d| d.parse().unwrap()).collect();
    assert_eq!(ids.len() as u64, v.arrived);
    let mut from_report: Vec<f64> = r.travel_times.values().flatten().copied().collect();
    let mut from_file = durations.clone();
    from_report.sort_by(f64::total_cmp);
    from_file.sort_by(f64::total_cmp);
    assert_eq!(from_report, from_file);
    let through: Vec<f64> =
        ids.iter().zip(&durations).filter(|(id, _)| id.starts_with("through")).map(|(_, d)| *d).collect();
    let mut rt = r.travel_times["through"].clone();
    rt.sort_by(f64::total_cmp);
    let mut ft = through.clone();
    ft.sort_by(f64::total_cmp);
    assert_eq!(rt, ft);
    let mean = durations.iter().sum::<f64>() / durations.len() as f64;
    assert!((r.all.travel_time_mean.unwrap() - mean).abs() <= 1e-9 * mean, "{:?} vs {mean}", r.all.travel_time_mean);
    assert_eq!(r.all.travel_time_p95, Some(from_file[(0.95 * from_file.len() as f64).ceil() as usize - 1]));
    let mean_len = lengths.iter().sum::<f64>() / lengths.len() as f64;
    assert!((r.all.route_length_mean.unwrap() - mean_len).abs() <= 1e-9 * mean_len);
    // One level: every through vehicle drives only on "local" streets (level 3).
    assert_eq!(r.through_on_local.distance_share, Some(1.0));
    let km = r.through_on_local.km_by_level;
    assert!(km[2] > 0.0 && km[0] == 0.0 && km[1] == 0.0 && km[3] == 0.0, "{km:?}");
    // Volumes: every vehicle departs somewhere, so the departures over all streets add up.
    let edgedata = dir.path().join("sumo/edgedata.xml");
    let departed: f64 = attr_values(&edgedata, "edge", "departed").iter().map(|d| d.parse::<f64>().unwrap()).sum();
    assert_eq!(departed, v.inserted as f64);
    // The pictures render.
    let svg = netspec::traffic::picture::volume_svg(&net, &r);
    assert_eq!(svg.matches("data-street=").count(), net.edges.len());
    netspec::render::png(&svg).unwrap();
    netspec::render::png(&netspec::traffic::picture::histogram_svg(&r)).unwrap();
}

/// Parses a plain node or edge file into id → attributes.
fn elements(path: &Path, tag: &str) -> BTreeMap<String, BTreeMap<String, String>> {
    let mut out = BTreeMap::new();
    for name in ["id", "from", "to", "type", "x", "y"] {
        let ids = attr_values(path, tag, "id");
        let vals = attr_values(path, tag, name);
        if vals.len() == ids.len() {
            for (id, v) in ids.into_iter().zip(vals) {
                out.entry(id).or_insert_with(BTreeMap::new).insert(name.to_string(), v);
            }
        }
    }
    out
}

/// The nodes and edges written for a solve design are exactly its active edges and their ends.
#[test]
fn solve_export_is_exactly_the_design() {
    let res = tiny_design("");
    let net = network::from_design(
        &res,
        Path::new("result.json"),
        &LoadOptions { metres_per_unit: Some(10.0), level: Some(2), window: None, region: None },
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let files = export::write_plain(&net, dir.path(), "t").unwrap();
    let nodes = elements(&files.nodes, "node");
    let edges = elements(&files.edges, "edge");
    let ends: BTreeSet<u32> = res.active_edges.iter().flatten().copied().collect();
    assert_eq!(nodes.keys().cloned().collect::<BTreeSet<_>>(), ends.iter().map(|v| format!("n{v}")).collect());
    for v in &ends {
        let p = res.mesh.position(netspec::mesh::VertexId(*v));
        let n = &nodes[&format!("n{v}")];
        assert_eq!((n["x"].parse::<f64>().unwrap(), n["y"].parse::<f64>().unwrap()), (p[0] * 10.0, p[1] * 10.0));
    }
    assert_eq!(edges.len(), 2 * res.active_edges.len());
    let network = res.network.as_ref().unwrap();
    for e in network.active_edges() {
        let (a, b) = res.mesh.edge_vertices(e);
        for (id, from, to) in [(format!("e{}", e.0), a.0, b.0), (format!("-e{}", e.0), b.0, a.0)] {
            let x = &edges[&id];
            assert_eq!(
                (x["from"].as_str(), x["to"].as_str(), x["type"].as_str()),
                (format!("n{from}").as_str(), format!("n{to}").as_str(), "L2")
            );
        }
    }
    // Entrances are the sinks.
    for n in &net.nodes {
        assert_eq!(n.entrance, res.sinks.contains(&n.id));
    }
}

/// A two-region city: the exported streets are the city's street graph (count, level and ends
/// of every edge, read back from disk), and netconvert keeps every one of them.
#[test]
fn city_export_is_exactly_the_street_graph() {
    let spec = CitySpec::from_toml(&std::fs::read_to_string(fixture("city/two-regions.toml")).unwrap()).unwrap();
    let out = tempfile::tempdir().unwrap();
    let opts = CityRunOptions {
        solver: SolverKind::default_kind().unwrap(),
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
    };
    let city = run_city(&spec, out.path(), &opts).unwrap();
    assert!(city.complete && city.valid);
    // The design graph, from the run in memory.
    let (graph, _, _) = netspec::urban::output::street_graph(&city.regions, spec.mesh.spacing);
    let net: RoadNetwork = network::load(out.path(), &LoadOptions::default()).unwrap();
    assert_eq!(net.metres_per_unit, 100.0);
    let dir = tempfile::tempdir().unwrap();
    let files = export::write_plain(&net, dir.path(), "c").unwrap();
    let nodes = elements(&files.nodes, "node");
    let edges = elements(&files.edges, "edge");
    let used: BTreeSet<u32> = graph.edges.iter().flat_map(|e| [e.a, e.b]).collect();
    assert_eq!(nodes.len(), used.len());
    assert_eq!(edges.len(), 2 * graph.edges.len());
    let mut per_level = [0usize; 5];
    for (k, g) in graph.edges.iter().enumerate() {
        per_level[g.level as usize] += 1;
        for (id, from, to) in [(format!("e{k}"), g.a, g.b), (format!("-e{k}"), g.b, g.a)] {
            let x = &edges[&id];
            assert_eq!(
                (x["from"].clone(), x["to"].clone(), x["type"].clone()),
                (format!("n{from}"), format!("n{to}"), format!("L{}", g.level))
            );
            assert_eq!(parse_edge_id(&id), Some((k as u32, !id.starts_with('-'))));
        }
    }
    assert!(per_level[1] > 0 && per_level[2] > 0 && per_level[3] > 0, "{per_level:?}");
    // Snake ends are graph vertices: nodes where a street ends or branches stay where the design has them.
    for n in &net.nodes {
        let deg = graph.edges.iter().filter(|e| e.a == n.id || e.b == n.id).count();
        if deg != 2 {
            let p = graph.positions[n.id as usize];
            assert_eq!(n.pos, [p[0] * 100.0, p[1] * 100.0]);
        }
    }
    // Through traffic enters and leaves on the major roads of the domain's boundary.
    // (the 8 × 4 rectangle at level 3's half-unit spacing: 2 × (16 + 8) nodes)
    assert_eq!(net.nodes.iter().filter(|n| n.entrance).count(), 48);
    for (k, n) in net.nodes.iter().enumerate().filter(|(_, n)| n.entrance) {
        assert!(net.edges.iter().any(|e| e.level == 1 && (e.a == k || e.b == k)), "{n:?}");
        let p = graph.positions[n.id as usize];
        assert!(
            p[0].min(p[1]).abs() < 1e-9 || (p[0] - 8.0).abs() < 1e-9 || (p[1] - 4.0).abs() < 1e-9,
            "{n:?} is not on the domain boundary"
        );
    }
    // Shapes start and end at their nodes.
    for e in &net.edges {
        assert_eq!((e.shape[0], *e.shape.last().unwrap()), (net.nodes[e.a].pos, net.nodes[e.b].pos));
    }
    // netconvert keeps every designed street, both ways.
    let net_xml = dir.path().join("c.net.xml");
    sumo().netconvert(&files, &net_xml).unwrap_or_else(|e| panic!("{e}"));
    let sumo_net = netspec::traffic::parse::net(&net_xml).unwrap();
    assert_eq!(sumo_net.edges.len(), 2 * graph.edges.len());
    for (id, e) in &sumo_net.edges {
        let (k, _) = parse_edge_id(id).unwrap();
        assert_eq!(e.edge_type, format!("L{}", graph.edges[k as usize].level));
        assert_eq!(e.lanes, if graph.edges[k as usize].level == 1 { 2 } else { 1 });
    }
    // And it carries traffic: every vehicle inserted arrives; through traffic is measured.
    let settings = demand_of(300.0, 240.0, 240.0, 5);
    let r = evaluate(&net, &settings, &sumo(), dir.path()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.vehicles.inserted > 10, "{:?}", r.vehicles);
    assert_eq!(r.vehicles.arrived, r.vehicles.inserted);
    assert_eq!(r.through_on_local.vehicles, r.through.vehicles);
    assert_eq!(r.network.streets_per_level, [per_level[1], per_level[2], per_level[3], per_level[4]]);
}

/// Demand depends only on the region and the settings; rates and the through/local rules hold.
#[test]
fn demand_is_seeded_and_placed() {
    let square = vec![[0.0, 0.0], [400.0, 0.0], [400.0, 400.0], [0.0, 400.0]];
    let region = Region { boundary: square.clone(), areas: vec![square.clone()] };
    let s = demand_of(3600.0, 200.0, 400.0, 7);
    let a = demand::generate(&region, &s);
    assert_eq!(a, demand::generate(&region, &s));
    assert_ne!(a, demand::generate(&region, &DemandSettings { seed: 8, ..s.clone() }));
    let through: Vec<_> = a.iter().filter(|t| t.class == TripClass::Through).collect();
    let local = a.len() - through.len();
    // Poisson counts: within 4 standard deviations of the rate.
    assert!((through.len() as f64 - 200.0).abs() < 4.0 * 200f64.sqrt(), "{}", through.len());
    assert!((local as f64 - 400.0).abs() < 4.0 * 400f64.sqrt(), "{local}");
    assert!(a.windows(2).all(|w| w[0].depart <= w[1].depart) && a.iter().all(|t| (0.0..3600.0).contains(&t.depart)));
    let on_boundary = |p: [f64; 2]| {
        p[0].abs() < 1e-9 || p[1].abs() < 1e-9 || (p[0] - 400.0).abs() < 1e-9 || (p[1] - 400.0).abs() < 1e-9
    };
    for t in &through {
        assert!(on_boundary(t.from) && on_boundary(t.to), "{t:?}");
        // 30–70 % of the perimeter apart along the boundary: at least 480 m of boundary, so
        // never on the same side.
        assert!((t.from[0] - t.to[0]).abs() + (t.from[1] - t.to[1]).abs() > 1e-9);
    }
    for t in a.iter().filter(|t| t.class == TripClass::Local) {
        assert!(t.from.iter().chain(&t.to).all(|c| (0.0..=400.0).contains(c)));
    }
    // The same site written another way (clockwise, from another vertex, closed, a hair off)
    // meets the same trips.
    let mut other: Vec<[f64; 2]> = square.iter().rev().map(|p| [p[0] + 1e-7, p[1] - 1e-7]).collect();
    other.rotate_left(2);
    other.push(other[0]);
    assert_eq!(a, demand::generate(&Region { boundary: other.clone(), areas: vec![other] }, &s));
    // Trade flows add trips of their own, in proportion to the weights, and leave the others.
    let flows = vec![
        demand::TradeFlow { from: [0.0, 100.0], to: [400.0, 300.0], weight: 3.0 },
        demand::TradeFlow { from: [200.0, 0.0], to: [200.0, 400.0], weight: 1.0 },
    ];
    let t = demand::generate(&region, &DemandSettings { trade_per_hour: 400.0, trade: flows, ..s.clone() });
    let (trade, rest): (Vec<_>, Vec<_>) = t.into_iter().partition(|t| t.class == TripClass::Trade);
    assert_eq!(rest, a);
    let first = trade.iter().filter(|t| t.from == [0.0, 100.0] && t.to == [400.0, 300.0]).count();
    assert!((trade.len() as f64 - 400.0).abs() < 4.0 * 20.0, "{}", trade.len());
    assert!((first as f64 - 300.0).abs() < 4.0 * 300f64.sqrt(), "{first}");
    assert_eq!(netspec::traffic::report::spearman(&[1.0, 2.0, 3.0, 4.0], &[10.0, 20.0, 30.0, 40.0]), Some(1.0));
    assert_eq!(netspec::traffic::report::spearman(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]), Some(-1.0));
    let tied = netspec::traffic::report::spearman(&[1.0, 1.0, 2.0, 3.0], &[5.0, 6.0, 7.0, 8.0]).unwrap();
    assert!((tied - 0.9486832980505138).abs() < 1e-12, "{tied}");
    assert_eq!(netspec::traffic::report::spearman(&[1.0, 1.0, 1.0], &[1.0, 2.0, 3.0]), None);
    assert_eq!(percentile(&[3.0, 1.0, 2.0, 4.0], 0.95), Some(4.0));
    assert_eq!(percentile(&(1..=20).map(f64::from).collect::<Vec<_>>(), 0.95), Some(19.0));
    assert_eq!(percentile(&[], 0.95), None);
}

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

/// Bad input: a directory with no result, a result with no network, unreadable JSON, SUMO
/// failing, SUMO missing — each error names the file and the cause.
#[test]
fn bad_input_names_the_file_and_the_cause() {
    let empty = tempfile::tempdir().unwrap();
    let e = network::load(empty.path(), &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains(&empty.path().display().to_string()) && e.contains("no design here"), "{e}");

    // An infeasible spec's result has no network.
    let text = "name = \"infeasible\"\nboundary = \"wall\"\nformulation = \"tight\"\n[mesh]\ngrid = { width = 6, height = 6 }\n[sinks]\nvertices = [0]\n[coverage]\nrange = 1\n[features]\nbranches = \"forbid\"\n";
    let p = Spec::from_toml(text).unwrap().resolve(Path::new(".")).unwrap();
    let nm = pipeline::build(&p);
    let res = pipeline::solve_built(&p, &nm, SolverKind::default_kind().unwrap(), &SolveOptions::default()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("result.json");
    std::fs::write(&file, serde_json::to_string(&res).unwrap()).unwrap();
    let e = network::load(dir.path(), &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains(&file.display().to_string()) && e.contains("has no network") && e.contains("infeasible"), "{e}");

    std::fs::write(&file, "{ \"schema\": ").unwrap();
    let e = network::load(&file, &LoadOptions::default()).unwrap_err().to_string();
    assert!(e.contains(&file.display().to_string()) && e.contains("cannot read a netspec design result"), "{e}");

    // netconvert fails on an edge between nodes that do not exist.
    let good = tiny_design("");
    let net = network::from_design(&good, Path::new("result.json"), &LoadOptions::default()).unwrap();
    let files = export::write_plain(&net, dir.path(), "bad").unwrap();
    let edg = std::fs::read_to_string(&files.edges).unwrap().replacen("from=\"n", "from=\"nowhere", 1);
    std::fs::write(&files.edges, edg).unwrap();
    let e = sumo().netconvert(&files, &dir.path().join("bad.net.xml")).unwrap_err().to_string();
    assert!(
        e.contains(&files.edges.display().to_string())
            && e.contains("`netconvert` failed")
            && e.contains("nowhere")
            && e.contains("bad.net.log"),
        "{e}"
    );

    // A SUMO_HOME given by name must hold SUMO.
    let e = Sumo::locate(Some(&dir.path().join("not-sumo"))).unwrap_err().to_string();
    assert!(e.contains("not-sumo") && e.contains("SUMO not found") && e.contains("scripts/setup.sh"), "{e}");

    // No SUMO anywhere: the command names the setup script.
    std::fs::write(&file, serde_json::to_string(&good).unwrap()).unwrap();
    let out = netspec()
        .arg("traffic")
        .arg(dir.path())
        .arg("--out")
        .arg(dir.path().join("out"))
        .env("SUMO_HOME", dir.path().join("no-sumo"))
        .env("NETSPEC_DEPS", dir.path().join("no-deps"))
        .env("PATH", dir.path().join("no-bin"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("SUMO not found") && stderr.contains("scripts/setup.sh") && stderr.contains("no-sumo"),
        "{stderr}"
    );
}

/// `netspec traffic A B`: two designs of one mesh under the same demand, a comparison table and
/// plot; `netspec solve` writes the design's GeoJSON (every segment an active edge).
#[test]
fn cli_compares_designs_and_solve_writes_geojson() {
    crate::setup_part("sumo");
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [("short", ""), ("direct", "[weights]\nlength = 0\ndistance = 1\n")] {
        let spec = dir.path().join(format!("{name}.toml"));
        std::fs::write(&spec, std::fs::read_to_string(fixture("specs/tiny_network.toml")).unwrap() + extra).unwrap();
        let out = netspec().arg("solve").arg(&spec).arg("--out").arg(dir.path().join(name)).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    // GeoJSON: the chains' segments are exactly the active edges (in WGS 84, one model unit a
    // metre from the default origin, through the one writer).
    let res: DesignResult =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("short/result.json")).unwrap()).unwrap();
    let geo: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("short/network.geojson")).unwrap()).unwrap();
    let proj = netspec::design::streets::GeoAnchor::model_units().projection().unwrap();
    let writer = netspec::geometry::geojson::GeoJsonWriter::new(&proj);
    let pos: Vec<[f64; 2]> = res.mesh.positions().iter().map(|&q| writer.lonlat(q).unwrap()).collect();
    let vid = |p: &serde_json::Value| {
        let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        pos.iter().position(|q| (q[0] - x).abs() < 1e-12 && (q[1] - y).abs() < 1e-12).unwrap() as u32
    };
    let mut segs = BTreeSet::new();
    for f in geo["features"].as_array().unwrap().iter().filter(|f| f["geometry"]["type"] == "LineString") {
        let pts = f["geometry"]["coordinates"].as_array().unwrap();
        for w in pts.windows(2) {
            let (a, b) = (vid(&w[0]), vid(&w[1]));
            assert!(segs.insert((a.min(b), a.max(b))));
        }
    }
    let active: BTreeSet<(u32, u32)> = res.active_edges.iter().map(|&[a, b]| (a.min(b), a.max(b))).collect();
    assert_eq!(segs, active);

    let out_dir = dir.path().join("cmp");
    let out = netspec()
        .args(["traffic"])
        .arg(dir.path().join("short"))
        .arg(dir.path().join("direct"))
        .args(["--duration", "300", "--through-rate", "120", "--local-rate", "240", "--metres-per-unit", "50", "--out"])
        .arg(&out_dir)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    let md = std::fs::read_to_string(out_dir.join("comparison.md")).unwrap();
    assert!(md.contains("| short |") && md.contains("| direct |") && md.contains("the same trips"), "{md}");
    for f in [
        "comparison.svg",
        "comparison.png",
        "comparison.json",
        "short/traffic.json",
        "short/volume.png",
        "direct/traveltime.png",
    ] {
        assert!(out_dir.join(f).is_file(), "{f}");
    }
}

/// The version the library names is the one scripts/setup.sh installs (pinned in
/// scripts/requirements.txt).
#[test]
fn setup_installs_the_named_sumo_version() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let pins = std::fs::read_to_string(root.join("scripts/requirements.txt")).unwrap();
    let line = pins.lines().find(|l| l.starts_with("eclipse-sumo==")).unwrap();
    assert_eq!(line.trim_start_matches("eclipse-sumo==").trim(), netspec::traffic::sumo::SETUP_SUMO_VERSION);
    let setup = std::fs::read_to_string(root.join("scripts/setup.sh")).unwrap();
    assert!(setup.contains("SUMO_VERSION=$(pinned eclipse-sumo)"), "setup.sh reads the pin");
}

/// A `netspec layout` output is a design for traffic: its streets become one graph (every metre
/// of street in it, junctions as nodes), its region is the layout's outer ring — so a city on
/// the same site meets the same trips — and SUMO runs it with every street present.
#[test]
fn a_layout_is_simulated_on_its_own_region() {
    use netspec::layout::region::region_from_toml;
    use netspec::layout::run::{layout, write_layout, LayoutOptions};
    let text = "outer = [[0, 0], [320, 0], [320, 200], [0, 200]]\nroads = [[[160, 0], [160, 200]]]\n";
    let region = region_from_toml(text, Path::new("site.toml"), "site").unwrap();
    let opts = LayoutOptions {
        field: netspec::layout::field::FieldMethod::Distance,
        selection: netspec::layout::split::Selection::Best,
        seed: 1,
        optimise: 0,
    };
    let l = layout(&region, &opts).unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_layout(dir.path(), &region, &l).unwrap();
    let net = network::load(dir.path(), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let square = vec![[0.0, 0.0], [320.0, 0.0], [320.0, 200.0], [0.0, 200.0]];
    assert_eq!(net.region, Region { boundary: square.clone(), areas: vec![square] });
    let designed: f64 = l.streets.iter().map(|s| netspec::geometry::polyline_length(&s.polyline)).sum();
    let graph: f64 = net.edges.iter().map(|e| e.length()).sum();
    assert!((designed - graph).abs() < 1e-6 * designed, "{designed} m of street, {graph} m in the graph");
    assert!(net.nodes.iter().any(|n| n.entrance), "the major road's ends are entrances");
    let settings = demand_of(600.0, 120.0, 240.0, 3);
    let out = tempfile::tempdir().unwrap();
    let r = evaluate(&net, &settings, &sumo(), out.path()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.network.streets_in_net, r.network.streets);
    assert!(r.vehicles.inserted > 10 && r.vehicles.arrived == r.vehicles.inserted, "{:?}", r.vehicles);
}

/// A window of a grown network: `netspec grow --window` writes the trade flows across it, trade
/// trips drive between the entrances, and the growth model's loads are ranked against SUMO's.
#[test]
fn a_grown_window_meets_trade_and_its_loads_are_ranked() {
    let dir = tempfile::tempdir().unwrap();
    // Two major roads crossing at (500, 500) (trade 9 east–west, 3 north–south) and a grid of
    // minor streets (no trade) in the north-east quarter.
    let mut nodes = vec![(0, 0.0, 500.0), (1, 500.0, 500.0), (2, 1000.0, 500.0), (3, 500.0, 0.0), (4, 500.0, 1000.0)];
    let mut segs = vec![(0, 1, "major", 9.0), (1, 2, "major", 9.0), (3, 1, "major", 3.0), (1, 4, "major", 3.0)];
    let mut id = 5;
    for x in [650.0, 800.0] {
        nodes.push((id, x, 500.0));
        nodes.push((id + 1, x, 800.0));
        segs.push((id, id + 1, "minor", 0.0));
        id += 2;
    }
    // Split the east–west road at the minor streets' ends so the graph stays planar.
    segs.retain(|s| !(s.0 == 1 && s.1 == 2));
    segs.extend([(1, 5, "major", 9.0), (5, 7, "major", 9.0), (7, 2, "major", 9.0), (6, 8, "minor", 0.0)]);
    let nodes: Vec<String> = nodes.iter().map(|(i, x, y)| format!(r#"{{"id": {i}, "x": {x}, "y": {y}}}"#)).collect();
    let segments: Vec<String> = segs
        .iter()
        .map(|(a, b, c, t)| format!(r#"{{"a": {a}, "b": {b}, "class": "{c}", "width": 1, "step": 0, "traffic": {t}}}"#))
        .collect();
    let json = format!(
        r#"{{"size": [1000, 1000], "spacing": 20, "nodes": [{}], "segments": [{}], "water": [],
            "routes": [{{"traffic": 9, "nodes": [0, 1, 5, 7, 2]}}, {{"traffic": 3, "nodes": [3, 1, 4]}}]}}"#,
        nodes.join(", "),
        segments.join(", ")
    );
    std::fs::write(dir.path().join("network.json"), json).unwrap();
    std::fs::write(dir.path().join("series.csv"), "step\n0\n").unwrap();
    let window = [100.0, 100.0, 900.0, 900.0];
    let w =
        netspec::grow::window::write(dir.path(), window, "w", &dir.path().join("w")).unwrap_or_else(|e| panic!("{e}"));
    // Two minor streets (4.7 km/km²) leave even the north-east quarter unbuilt.
    assert_eq!((w.roads, w.regions, w.empty_regions, w.flows), (4, 4, 4, 2), "{w:?}");
    let trade = demand::TradeFile::load(&dir.path().join("w/trade.json")).unwrap();
    let net = network::load(dir.path(), &LoadOptions { window: Some(window), ..Default::default() }).unwrap();
    assert!(net.edges.iter().filter(|e| e.level == 1).all(|e| e.predicted_load.is_some_and(|l| l > 0.0)));
    let settings = DemandSettings {
        duration: 600.0,
        through_per_hour: 60.0,
        local_per_hour: 120.0,
        seed: 3,
        trade_per_hour: 240.0,
        trade: trade.flows,
    };
    let out = tempfile::tempdir().unwrap();
    let r = evaluate(&net, &settings, &sumo(), out.path()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.demand.trade_drawn > 10 && r.trade.vehicles > 10, "{:?} {:?}", r.demand, r.trade);
    let p = r.predicted_loads.expect("predicted loads are ranked");
    assert_eq!(p.streets, net.edges.len());
    assert_eq!(p.loaded_streets, net.edges.iter().filter(|e| e.level == 1).count());
    // Trade follows the loaded major roads: the busier road ranks above the minor streets.
    assert!(p.spearman_trade.is_some_and(|rho| rho > 0.5), "{p:?}");
}

/// The designs' labels: the given ones first, the rest their directory names (a `result.json`'s
/// parent's), repeats made distinct.
#[test]
fn labels_are_given_or_the_directory_names_and_distinct() {
    let dir = tempfile::tempdir().unwrap();
    let result = dir.path().join("solved/result.json");
    std::fs::create_dir_all(result.parent().unwrap()).unwrap();
    std::fs::write(&result, "{}").unwrap();
    let designs: Vec<PathBuf> = vec!["a/x".into(), "b/x".into(), result, "c/y".into()];
    let labels = netspec::traffic::run::labels(&designs, &["first".to_string()]);
    assert_eq!(labels, ["first", "x", "solved", "y"]);
    let labels = netspec::traffic::run::labels(&designs, &[]);
    assert_eq!(labels, ["x", "x-1", "solved", "y"]);
}
