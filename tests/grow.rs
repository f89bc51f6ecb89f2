//! `netspec grow` on small maps (a 64 × 64 lattice with a straight river, a lake): the lattice
//! mask, water, connectivity, the traffic bookkeeping after every step, planarity by an
//! independent segment-intersection check, the library's own independent check
//! (`grow::validate`) finding nothing, a second harbour, determinism, context errors, and a
//! context's existing roads, nuclei and named centre (the town grows where the user puts it).

use netspec::grow::context::Context;
use netspec::grow::graph::Class;
use netspec::grow::lattice::directions;
use netspec::grow::step::Sim;
use netspec::grow::validate::{validate, Network};
use netspec::grow::{self, GrowRequest};
use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::path::{Path, PathBuf};

fn model(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("models/grow").join(name)
}

fn small(name: &str) -> Context {
    Context::load(&model(name)).unwrap()
}

type P = [f64; 2];

fn orient(a: P, b: P, c: P) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether closed segments `ab` and `cd` share a point (written for the test, independently of
/// the library's geometry).
fn meet(a: P, b: P, c: P, d: P) -> bool {
    let on = |p: P, q: P, r: P| {
        orient(p, q, r).abs() <= 1e-9 * (1.0 + (q[0] - p[0]).abs() + (q[1] - p[1]).abs())
            && r[0] >= p[0].min(q[0]) - 1e-9
            && r[0] <= p[0].max(q[0]) + 1e-9
            && r[1] >= p[1].min(q[1]) - 1e-9
            && r[1] <= p[1].max(q[1]) + 1e-9
    };
    let (d1, d2, d3, d4) = (orient(c, d, a), orient(c, d, b), orient(a, b, c), orient(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    on(c, d, a) || on(c, d, b) || on(a, b, c) || on(a, b, d)
}

/// Road segments that meet anywhere but at a shared node.
fn planarity_violations(sim: &Sim) -> Vec<(usize, usize)> {
    let g = &sim.graph;
    let roads: Vec<(usize, u32, u32, P, P)> = g
        .segs
        .iter()
        .enumerate()
        .filter(|(_, s)| s.class.is_road())
        .map(|(i, s)| (i, s.a, s.b, g.nodes[s.a as usize].pos, g.nodes[s.b as usize].pos))
        .collect();
    let mut bad = Vec::new();
    for (k, &(i, a, b, pa, pb)) in roads.iter().enumerate() {
        for &(j, c, d, pc, pd) in &roads[k + 1..] {
            let shared: Vec<u32> = [a, b].into_iter().filter(|n| *n == c || *n == d).collect();
            if shared.len() == 2 {
                bad.push((i, j)); // a duplicate segment
                continue;
            }
            if shared.len() == 1 {
                // Meeting at the shared node only: the far ends must not lie on the other segment.
                let n = shared[0];
                let far1 = if a == n { pb } else { pa };
                let far2 = if c == n { pd } else { pc };
                let (s1, s2) = if a == n { (pa, pb) } else { (pb, pa) };
                let (t1, t2) = if c == n { (pc, pd) } else { (pd, pc) };
                if meet(s1, s2, far2, far2) || meet(t1, t2, far1, far1) {
                    bad.push((i, j));
                }
                continue;
            }
            if meet(pa, pb, pc, pd) {
                bad.push((i, j));
            }
        }
    }
    bad
}

/// Checks the traffic bookkeeping: T(s) = Σ T(P) over the routes through s; each pair's routes
/// carry its demand; a segment over capacity only where some pair using it recorded overflow.
fn check_traffic(sim: &Sim) {
    let g = &sim.graph;
    let mut by_ends: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for (i, s) in g.segs.iter().enumerate() {
        by_ends.insert((s.a.min(s.b), s.a.max(s.b)), i);
    }
    let mut load = vec![0.0; g.segs.len()];
    let mut users: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); g.segs.len()];
    let demand = sim.demand(sim.step);
    for (p, pair) in sim.traffic.pairs.iter().enumerate() {
        let mut total = 0.0;
        for &r in &pair.routes {
            let route = &sim.traffic.routes[r];
            assert_eq!(route.pair, p);
            let ends = [sim.cities[pair.cities[0]].node, sim.cities[pair.cities[1]].node];
            assert_eq!([route.nodes[0], *route.nodes.last().unwrap()], ends, "route {r} runs between its cities");
            for w in route.nodes.windows(2) {
                let s = *by_ends
                    .get(&(w[0].min(w[1]), w[0].max(w[1])))
                    .unwrap_or_else(|| panic!("route {r} leaves the segments"));
                assert_ne!(g.segs[s].class, Class::Minor, "route {r} runs on a minor road");
                load[s] += route.traffic;
                users[s].insert(p);
            }
            assert!(route.traffic >= -1e-9);
            total += route.traffic;
        }
        assert!(
            (total - demand).abs() <= 1e-6 * demand.max(1.0),
            "step {}: pair {p} carries {total} of {demand}",
            sim.step
        );
    }
    for (i, s) in g.segs.iter().enumerate() {
        assert!(
            (s.load - load[i]).abs() <= 1e-6 * load[i].max(1.0),
            "segment {i}: T(s) {} ≠ Σ T(P) {}",
            s.load,
            load[i]
        );
        if s.class != Class::Water && load[i] > sim.traffic.per_lane * s.width + 1e-6 {
            assert!(
                users[i].iter().any(|&p| sim.traffic.pairs[p].overflow > 0.0),
                "step {}: segment {i} over capacity ({} > {}) without a recorded overflow",
                sim.step,
                load[i],
                sim.traffic.per_lane * s.width
            );
        }
    }
}

#[test]
fn mask_directions() {
    assert_eq!(directions(3).len(), 32);
    assert_eq!(directions(8).len(), 176);
}

#[test]
fn river_map_invariants_hold_every_step() {
    let ctx = small("small-river.toml");
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    let river = ctx.water[0].river.clone().unwrap();
    // Every city pair is connected after step 0 by trade segments.
    let g = &sim.graph;
    let mut adj: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    for s in g.segs.iter().filter(|s| s.class != Class::Minor) {
        adj.entry(s.a).or_default().push(s.b);
        adj.entry(s.b).or_default().push(s.a);
    }
    for pair in &sim.traffic.pairs {
        let (from, to) = (sim.cities[pair.cities[0]].node, sim.cities[pair.cities[1]].node);
        let mut seen = BTreeSet::from([from]);
        let mut queue = VecDeque::from([from]);
        while let Some(n) = queue.pop_front() {
            for &m in adj.get(&n).into_iter().flatten() {
                if seen.insert(m) {
                    queue.push_back(m);
                }
            }
        }
        assert!(seen.contains(&to), "cities {:?} are not connected after step 0", pair.cities);
    }
    assert!(sim.series[0].bridges + sim.series[0].ports >= 1, "the river is crossed");
    check_traffic(&sim);
    for _ in 0..ctx.steps {
        sim.step();
        check_traffic(&sim);
    }
    assert!(planarity_violations(&sim).is_empty(), "{:?}", &planarity_violations(&sim)[..]);
    let found = validate(&Network::of(&sim), &sim.ctx);
    assert!(found.is_empty(), "{found:?}");
    // No road crosses the river's centre line except bridges (and harbours, which end at it).
    for (i, s) in sim.graph.segs.iter().enumerate() {
        if matches!(s.class, Class::Major | Class::Minor) {
            let (a, b) = (sim.graph.nodes[s.a as usize].pos, sim.graph.nodes[s.b as usize].pos);
            for w in river.windows(2) {
                assert!(!meet(a, b, w[0], w[1]), "{:?} segment {i} crosses the river", s.class);
            }
        }
    }
    let last = sim.series.last().unwrap();
    assert!(last.minor_km > 1.0 && last.blocks > 10 && last.built_up_ha > sim.series[0].built_up_ha, "{last:?}");
}

#[test]
fn a_second_harbour_appears_when_the_first_saturates() {
    let ctx = small("small-lake.toml");
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    assert_eq!(sim.series[0].ports, 1, "one harbour in the initial network");
    let first = sim.graph.segs.iter().position(|s| s.class == Class::Harbour).unwrap();
    let mut second = None;
    for _ in 0..ctx.steps {
        sim.step();
        check_traffic(&sim);
        if second.is_none() && sim.series.last().unwrap().ports >= 2 {
            // Built in the step the first harbour's routes came to need more than it carries.
            let h = &sim.graph.segs[first];
            let users = sim
                .traffic
                .routes
                .iter()
                .filter(|r| {
                    r.born == 0
                        && r.nodes.windows(2).any(|w| (w[0].min(w[1]), w[0].max(w[1])) == (h.a.min(h.b), h.a.max(h.b)))
                })
                .count();
            let need = |t: u32| users as f64 * sim.demand(t);
            let cap = sim.traffic.per_lane * h.width;
            assert!(need(sim.step) > cap && need(sim.step - 1) <= cap, "step {}: {users} routes, {h:?}", sim.step);
            second = Some(sim.step);
        }
    }
    assert!(second.is_some(), "a second harbour appears: {:?}", sim.series);
    let harbours: Vec<u32> =
        (0..sim.graph.segs.len() as u32).filter(|&s| sim.graph.segs[s as usize].class == Class::Harbour).collect();
    let sites = sim.port_sites(&harbours);
    assert!(sites.len() >= 2 && dist(sites[0], sites[1]) > 200.0, "the second port is at another site: {sites:?}");
    assert!(planarity_violations(&sim).is_empty());
    let found = validate(&Network::of(&sim), &sim.ctx);
    assert!(found.is_empty(), "{found:?}");
}

fn run_to(dir: &Path, context: &Path, seed: Option<u64>) -> Vec<u8> {
    let req = GrowRequest {
        context: context.to_path_buf(),
        out: dir.to_path_buf(),
        seed,
        steps: Some(10),
        every: Some(5),
        all_streets: false,
        gallery: None,
        interrupt: None,
    };
    let summary = grow::run(&req, &mut |_, _| {}).unwrap();
    assert!(summary.violations.is_empty() && summary.snapshot_violations.is_empty(), "{:?}", summary.violations);
    for f in ["network.json", "series.csv", "network.svg", "network.png", "step-000.svg", "step-010.svg", "steps.png"] {
        assert!(dir.join(f).exists(), "{f}");
    }
    std::fs::read(dir.join("network.json")).unwrap()
}

#[test]
fn same_seed_same_bytes_another_seed_differs() {
    let tmp = tempfile::tempdir().unwrap();
    let ctx = model("small-river.toml");
    let a = run_to(&tmp.path().join("a"), &ctx, None);
    let b = run_to(&tmp.path().join("b"), &ctx, None);
    let c = run_to(&tmp.path().join("c"), &ctx, Some(99));
    assert!(a == b, "same seed, different network.json");
    assert!(a != c, "another seed, same network.json");
    let v: serde_json::Value = serde_json::from_slice(&a).unwrap();
    for k in ["nodes", "segments", "water", "settlements"] {
        assert!(v[k].is_array(), "{k}");
    }
    assert_eq!(v["violations"], serde_json::json!([]), "the independent check found violations");
    let classes: BTreeSet<&str> =
        v["segments"].as_array().unwrap().iter().map(|s| s["class"].as_str().unwrap()).collect();
    assert!(classes.is_subset(&BTreeSet::from(["major", "minor", "bridge", "harbour"])), "{classes:?}");
}

#[test]
fn bad_contexts_name_the_field() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        ("size = [1000, 1000]\n[[water]]\nriver = [[0, 0], [500, 0]]\nwidth = 20\n[[water]]\nriver = [[0, 0]]\nwidth = 5", "water[1].river"),
        ("size = [1000, 1000]\n[[water]]\npolygon = [[0, 0], [10, 0], [10, 10]]\nriver = [[0, 0], [1, 1]]", "water[0]"),
        ("size = [1000, 1000]\n[[neighbour]]\nposition = [0, 0]\n[[neighbour]]\nposition = [5000, 0]", "neighbour[1].position"),
        ("size = [1000, 1000]\n[center]\nposition = [1, 2]\nradius = 3", "center.radius"),
        ("size = [1000, 1000]\n[params]\nwidths = [[0, 1], [0, 2]]", "params.widths[1]"),
        ("size = [1000, 1000]\n[[pattern]]\nfrom = 0\nkind = \"spiral\"", "pattern[0].kind"),
        ("size = [400000, 400000]\nspacing = 2", "size"),
    ];
    for (i, (text, field)) in cases.iter().enumerate() {
        let path = tmp.path().join(format!("c{i}.toml"));
        std::fs::write(&path, text).unwrap();
        let req = GrowRequest {
            context: path.clone(),
            out: tmp.path().join("out"),
            seed: None,
            steps: Some(1),
            every: None,
            all_streets: false,
            gallery: None,
            interrupt: None,
        };
        let e = grow::run(&req, &mut |_, _| {}).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains(field), "case {i}: {msg}");
        assert!(msg.contains(&path.display().to_string()), "case {i} names the file: {msg}");
    }
    let e = Context::from_toml("size = [400000, 400000]\nspacing = 2").unwrap_err();
    assert!(e.to_string().contains("GiB"), "the memory estimate: {e}");
}

/// `netspec grow --window`: a grown map's window as a city spec and trade flows, the same from
/// the grown directory without growing again; a directory without `--window` is refused.
#[test]
fn a_window_is_a_city_spec_and_trade_flows() {
    let tmp = tempfile::tempdir().unwrap();
    let bin = env!("CARGO_BIN_EXE_netspec");
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let run = |args: &[&std::ffi::OsStr]| std::process::Command::new(bin).args(args).output().unwrap();
    let ctx = model("small-river.toml");
    let o = run(&[
        "grow".as_ref(),
        ctx.as_os_str(),
        "--steps".as_ref(),
        "10".as_ref(),
        "--window".as_ref(),
        "250,450,1000,1050".as_ref(),
        "--out".as_ref(),
        a.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let spec = netspec::urban::CitySpec::load(&a.join("city.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(!spec.roads.is_empty(), "the grown major roads are the city's roads");
    assert!(!spec.level(None, 2).unwrap().user.obstacle_polygons.is_empty(), "the river is an obstacle");
    let regions = netspec::urban::city::regions(&spec).unwrap();
    let running = regions.iter().filter(|(_, e)| !spec.region_levels(*e).is_empty()).count();
    assert!(running >= 1 && running < regions.len(), "built and unbuilt sub-regions: {running} of {}", regions.len());
    let trade = netspec::traffic::demand::TradeFile::load(&a.join("trade.json")).unwrap();
    assert!(!trade.flows.is_empty());
    let o = run(&[
        "grow".as_ref(),
        a.as_os_str(),
        "--window".as_ref(),
        "250,450,1000,1050".as_ref(),
        "--out".as_ref(),
        b.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = |d: &Path, f: &str| std::fs::read_to_string(d.join(f)).unwrap();
    // The same window of the same network: the same files but for the city's name.
    assert_eq!(text(&a, "city.toml").replace("\"a\"", "\"b\""), text(&b, "city.toml"));
    assert_eq!(text(&a, "trade.json"), text(&b, "trade.json"));
    let o = run(&["grow".as_ref(), a.as_os_str(), "--out".as_ref(), b.as_os_str()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--window"), "{err}");
    let o = run(&[
        "grow".as_ref(),
        a.as_os_str(),
        "--window".as_ref(),
        "5000,5000,6000,6000".as_ref(),
        "--out".as_ref(),
        b.as_os_str(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("network.json") && err.contains("outside the map"), "{err}");
}

/// The length-weighted centroid of the minor roads and their length (metres).
fn minor_centroid(sim: &Sim) -> (P, f64) {
    let g = &sim.graph;
    let (mut sx, mut sy, mut total) = (0.0, 0.0, 0.0);
    for s in g.segs.iter().filter(|s| s.class == Class::Minor) {
        let (a, b) = (g.nodes[s.a as usize].pos, g.nodes[s.b as usize].pos);
        let l = (b[0] - a[0]).hypot(b[1] - a[1]);
        sx += l * (a[0] + b[0]) / 2.0;
        sy += l * (a[1] + b[1]) / 2.0;
        total += l;
    }
    ([sx / total, sy / total], total)
}

/// Minor-road length (metres) with its midpoint within `r` of `p`.
fn minor_near(sim: &Sim, p: P, r: f64) -> f64 {
    let g = &sim.graph;
    g.segs
        .iter()
        .filter(|s| s.class == Class::Minor)
        .map(|s| (g.nodes[s.a as usize].pos, g.nodes[s.b as usize].pos))
        .filter(|(a, b)| ((a[0] + b[0]) / 2.0 - p[0]).hypot((a[1] + b[1]) / 2.0 - p[1]) <= r)
        .map(|(a, b)| (b[0] - a[0]).hypot(b[1] - a[1]))
        .sum()
}

fn dist(a: P, b: P) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Nodes reachable from `from` over trade segments (everything but minor roads).
fn trade_reach(sim: &Sim, from: u32) -> BTreeSet<u32> {
    let g = &sim.graph;
    let mut seen = BTreeSet::from([from]);
    let mut queue = VecDeque::from([from]);
    while let Some(n) = queue.pop_front() {
        for &s in &g.adj[n as usize] {
            let seg = &g.segs[s as usize];
            if seg.class != Class::Minor {
                let m = if seg.a == n { seg.b } else { seg.a };
                if seen.insert(m) {
                    queue.push_back(m);
                }
            }
        }
    }
    seen
}

/// `models/grow/lake-shore.toml`: a centre named on a lake's west shore and three neighbours
/// around (one across the lake). The initial network joins every neighbour to the centre, the
/// centre nucleus is there, and after the context's steps the minor roads' length-weighted
/// centroid is within 400 m of it.
#[test]
fn the_town_grows_at_the_named_centre() {
    let ctx = small("lake-shore.toml");
    let centre = ctx.center.as_ref().unwrap().position;
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    let node = sim.centre.expect("a named centre has a node");
    assert!(dist(sim.graph.nodes[node as usize].pos, centre) <= ctx.spacing, "the centre node is at the centre");
    assert!(dist(sim.nuclei[0].pos, centre) <= ctx.spacing && sim.nuclei[0].strength > 0.9, "{:?}", sim.nuclei[0]);
    let reach = trade_reach(&sim, node);
    for c in &sim.cities {
        assert!(reach.contains(&c.node), "city at {:?} is not joined to the centre", c.pos);
    }
    for _ in 0..ctx.steps {
        sim.step();
    }
    let (c, total) = minor_centroid(&sim);
    assert!(total > 5000.0, "{total} m of minor roads");
    assert!(dist(c, centre) <= 400.0, "the minor roads' centroid {c:?} is {:.0} m from the centre", dist(c, centre));
    assert!(validate(&Network::of(&sim), &sim.ctx).is_empty());
}

/// A small map with a bent existing major road from the south edge to the centre (fixed, one
/// lane), an old town of minor streets in the south-east with a nucleus, and a second nucleus
/// from step 8.
const ROADS: &str = r#"
size = [1260, 1260]
spacing = 20
radius = 4
seed = 7
steps = 20
[center]
position = [630, 700]
[[neighbour]]
position = [0, 900]
[[neighbour]]
position = [1260, 1000]
[[neighbour]]
position = [300, 0]
[[neighbour]]
position = [700, 1260]
[terrain]
relief = 10
scale = 800
[params]
growth = [[0, 6], [20, 12]]
demand = 1.5
widths = [[0, 1], [5, 2]]
"#;

const OLD_TOWN: &str = r#"
[[road]]
points = [[300, 0], [250, 350], [500, 650], [630, 700]]
fixed = true
lanes = 1
[[road]]
points = [[850, 250], [1050, 250], [1050, 400], [850, 400], [850, 250]]
class = "minor"
[[road]]
points = [[950, 250], [950, 400]]
class = "minor"
[[nucleus]]
position = [950, 330]
strength = 0.9
[[nucleus]]
position = [200, 1000]
strength = 1
from = 8
"#;

#[test]
fn existing_roads_and_nuclei_shape_the_growth() {
    let with = Context::from_toml(&format!("{ROADS}{OLD_TOWN}")).unwrap();
    let without = Context::from_toml(ROADS).unwrap();
    let mut a = Sim::new(&with, with.seed).unwrap();
    let mut b = Sim::new(&without, without.seed).unwrap();
    // The city at the road's end is the road's end; its trade follows the road's bends.
    let south = a.cities.iter().position(|c| c.pos == [300.0, 0.0]).expect("a city at the road's end");
    let bends: Vec<u32> = [[250.0, 350.0], [500.0, 650.0]]
        .iter()
        .map(|&p| a.graph.nodes.iter().position(|n| n.pos == p).expect("the road's points are nodes") as u32)
        .collect();
    let routes: Vec<&Vec<u32>> =
        a.traffic.routes.iter().filter(|r| a.traffic.pairs[r.pair].cities.contains(&south)).map(|r| &r.nodes).collect();
    assert!(routes.iter().all(|r| bends.iter().all(|n| r.contains(n))), "the south city's trade runs along the road");
    // The old town's streets are blocks from the start.
    assert!(a.series[0].blocks >= 2 && b.series[0].blocks == 0, "{:?} {:?}", a.series[0], b.series[0]);
    let given: Vec<usize> = (0..a.graph.segs.len()).filter(|&s| a.graph.segs[s].fixed).collect();
    assert!(!given.is_empty());
    let before = a.nuclei.len();
    for k in 1..=with.steps {
        a.step();
        b.step();
        let late = a.nuclei.iter().any(|q| q.pos == [200.0, 1000.0]);
        assert_eq!(late, k >= 8, "step {k}: the nucleus from step 8");
        check_traffic(&a);
    }
    assert!(a.nuclei.len() > before);
    // Saturation made the growth build or widen roads, but the fixed road kept its one lane.
    assert!(a.series.iter().any(|r| r.overflow > 0.0 || r.new_routes > 0 && r.step > 0), "{:?}", a.series);
    for &s in &given {
        let seg = &a.graph.segs[s];
        assert!(seg.width == 1.0 && seg.class == Class::Major, "fixed segment {s}: {seg:?}");
    }
    assert!(a.graph.segs.iter().any(|s| !s.fixed && s.width >= 2.0), "other roads were widened");
    // Streets grew in the old town and around the late nucleus, where without them there are
    // none or fewer.
    let old_town = [950.0, 330.0];
    let (ga, gb) = (minor_near(&a, old_town, 250.0), minor_near(&b, old_town, 250.0));
    assert!(ga > 1000.0 + gb, "old town: {ga:.0} m of minor roads with it, {gb:.0} m without");
    let (la, lb) = (minor_near(&a, [200.0, 1000.0], 200.0), minor_near(&b, [200.0, 1000.0], 200.0));
    assert!(la > lb + 300.0, "late nucleus: {la:.0} m with it, {lb:.0} m without");
    assert!(validate(&Network::of(&a), &a.ctx).is_empty());
    assert!(planarity_violations(&a).is_empty());
}

/// What a real site's context holds: major roads running to the map's edge with neighbours at
/// their ends, a road over a river on a bridge shorter than `bridge`, water touching the edge.
#[test]
fn a_site_like_context_is_accepted() {
    let ctx = Context::from_toml(
        r#"
size = [1260, 1260]
spacing = 20
radius = 4
steps = 5
[center]
position = [500, 800]
[[neighbour]]
position = [500, 1260]
[[neighbour]]
position = [420, 0]
[[neighbour]]
position = [0, 800]
[[road]]
points = [[500, 1260], [500, 800], [450, 300], [420, 0]]
[[road]]
points = [[0, 800.3], [500, 800]]
[[water]]
river = [[0, 500], [1260, 540]]
width = 60
[[water]]
polygon = [[1000, 0], [1260, 0], [1260, 1260], [1100, 1260]]
"#,
    )
    .unwrap();
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    assert!(sim.series[0].bridges >= 1, "the road crosses the river on a bridge");
    for (c, p) in sim.cities.iter().zip([[500.0, 1260.0], [420.0, 0.0], [0.0, 800.3]]) {
        assert_eq!(c.pos, p, "the city is the road's end");
    }
    for _ in 0..ctx.steps {
        sim.step();
    }
    let found = validate(&Network::of(&sim), &sim.ctx);
    assert!(found.is_empty(), "{found:?}");
}

#[test]
fn bad_roads_and_nuclei_name_the_field_and_nothing_is_grown() {
    let tmp = tempfile::tempdir().unwrap();
    let lake = "size = [1000, 1000]\n[[water]]\npolygon = [[300, 300], [700, 300], [700, 700], [300, 700]]\n";
    let cases = [
        ("[[road]]\npoints = [[10, 10]]", "road[0].points"),
        ("[[road]]\npoints = [[10, 10], [100, 10]]\n[[road]]\npoints = [[10, 10], [1200, 10]]", "road[1].points[1]"),
        ("[[road]]\npoints = [[100, 500], [500, 500]]", "road[0].points"),
        ("[[road]]\npoints = [[100, 500], [900, 500]]", "params.bridge"),
        ("[[road]]\npoints = [[100, 100], [200, 100]]\nclass = \"trunk\"", "road[0].class"),
        ("[[road]]\npoints = [[100, 100], [200, 100]]\nlanes = 0", "road[0].lanes"),
        ("[[nucleus]]\nposition = [-10, 100]\nstrength = 0.5", "nucleus[0].position"),
        ("[[nucleus]]\nposition = [500, 500]\nstrength = 0.5", "nucleus[0].position"),
        ("[[nucleus]]\nposition = [100, 100]\nstrength = 1.5", "nucleus[0].strength"),
        ("[center]\nposition = [500, 500]", "center.position"),
    ];
    for (i, (text, field)) in cases.iter().enumerate() {
        let path = tmp.path().join(format!("c{i}.toml"));
        std::fs::write(&path, format!("{lake}{text}")).unwrap();
        let out = tmp.path().join(format!("out{i}"));
        let req = GrowRequest {
            context: path.clone(),
            out: out.clone(),
            seed: None,
            steps: Some(1),
            every: None,
            all_streets: false,
            gallery: None,
            interrupt: None,
        };
        let e = grow::run(&req, &mut |_, _| {}).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains(field), "case {i}: {msg}");
        assert!(msg.contains(&path.display().to_string()), "case {i} names the file: {msg}");
        assert!(!out.exists(), "case {i}: nothing is grown");
    }
}

/// A sea drawn along the map's east, north and south edges covers them: the cities on its
/// border are reached by ship, and no road runs along the edge (the edge's vertices once stayed
/// land, a strip one vertex wide on the east and north edges).
#[test]
fn water_on_the_map_edge_leaves_no_land_strip() {
    let ctx = Context::from_toml(
        r#"
size = [1260, 1260]
spacing = 20
radius = 4
steps = 10
[center]
position = [400, 500]
[[neighbour]]
position = [0, 300]
[[neighbour]]
position = [500, 0]
[[neighbour]]
position = [1260, 600]
[[neighbour]]
position = [800, 1260]
[[water]]
polygon = [[900, 0], [1260, 0], [1260, 1260], [600, 1260], [650, 1000], [900, 700]]
"#,
    )
    .unwrap();
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    let t = &sim.lattice.terrain;
    for k in 0..t.ny {
        let s = k as f64 * ctx.spacing;
        assert_eq!(t.class_at([1260.0, s]), 1, "east edge at y = {s}");
        if s >= 920.0 {
            assert_eq!(t.class_at([s, 0.0]), 1, "south edge at x = {s}");
        }
        if s >= 620.0 {
            assert_eq!(t.class_at([s, 1260.0]), 1, "north edge at x = {s}");
        }
    }
    let water: Vec<bool> = sim.cities.iter().map(|c| c.water).collect();
    assert_eq!(water, [false, false, true, true], "the cities on the sea's edge are reached by ship");
    for _ in 0..ctx.steps {
        sim.step();
    }
    let g = &sim.graph;
    for s in g.segs.iter().filter(|s| matches!(s.class, Class::Major | Class::Minor)) {
        let (a, b) = (g.nodes[s.a as usize].pos, g.nodes[s.b as usize].pos);
        assert!(a[0].min(b[0]) < 1250.0, "a road along the east edge: {a:?}–{b:?}");
        assert!(a[1].min(b[1]) < 1250.0 || a[0].max(b[0]) < 600.0, "a road along the north edge: {a:?}–{b:?}");
    }
    let found = validate(&Network::of(&sim), &sim.ctx);
    assert!(found.is_empty(), "{found:?}");
}

/// One road between two cities on open land (every face too large to be a built-up block, so
/// the road stays extendible) and traffic growing from 10 to 100 units while a lane carries 30:
/// the road is widened as it saturates, its capacity follows its lanes, and no second road is
/// built.
#[test]
fn widening_relieves_a_saturated_road() {
    let ctx = Context::from_toml(
        r#"
size = [1260, 1260]
spacing = 20
radius = 4
steps = 30
[[neighbour]]
position = [0, 600]
[[neighbour]]
position = [1260, 640]
[terrain]
relief = 5
[params]
mu = 0.7
b = 1
demand = 5
growth = [[0, 2], [30, 20]]
widths = [[0, 1]]
block_area = 1
"#,
    )
    .unwrap();
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    assert_eq!(sim.traffic.routes.len(), 1);
    for _ in 0..ctx.steps {
        sim.step();
        check_traffic(&sim);
        let route = &sim.traffic.routes[0];
        for w in route.nodes.windows(2) {
            let s = &sim.graph.segs[sim.graph.find(w[0], w[1]).unwrap() as usize];
            let cap = netspec::grow::traffic::capacity(&sim.graph, sim.graph.find(w[0], w[1]).unwrap(), 30.0);
            assert_eq!(cap, 30.0 * s.width, "capacity follows lanes");
            assert!(s.load <= cap + 1e-9, "step {}: load {} over capacity {cap}", sim.step, s.load);
        }
    }
    let s = &sim.series;
    assert!(s.iter().all(|r| r.overflow == 0.0), "widening relieved every shortfall: {s:?}");
    assert_eq!(sim.traffic.routes.len(), 1, "no second road");
    let widest = sim.graph.segs.iter().filter(|g| g.class == Class::Major).map(|g| g.width).fold(0.0, f64::max);
    assert!(widest >= 4.0, "{widest} lanes for 100 units");
    assert!(s.last().unwrap().lane_km > 3.9 * s[0].lane_km, "{:?} → {:?}", s[0], s.last());
}

/// The pictures leave dead-end stubs out (every minor road shown bounds a block or joins roads:
/// no end of it is a dead end among the roads shown) unless all streets are asked for; the step
/// strip and the gallery put their pictures side by side.
#[test]
fn pictures_hide_stubs_and_come_in_strips() {
    let ctx = small("small-river.toml");
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    for _ in 0..15 {
        sim.step();
    }
    let (shown, all) = (grow::output::scene(&sim, false), grow::output::scene(&sim, true));
    let minor = |s: &netspec::render::grow::GrowScene| s.roads.iter().filter(|r| r.class == "minor").count();
    assert!(minor(&shown) < minor(&all) && minor(&shown) > minor(&all) / 2, "{} of {}", minor(&shown), minor(&all));
    let key = |p: P| ((p[0] * 1000.0).round() as i64, (p[1] * 1000.0).round() as i64);
    let mut degree: BTreeMap<(i64, i64), usize> = BTreeMap::new();
    for r in shown.roads.iter().filter(|r| r.class != "water") {
        *degree.entry(key(r.a)).or_default() += 1;
        *degree.entry(key(r.b)).or_default() += 1;
    }
    for r in shown.roads.iter().filter(|r| r.class == "minor") {
        assert!(degree[&key(r.a)] > 1 && degree[&key(r.b)] > 1, "a stub is drawn: {r:?}");
    }
    let tmp = tempfile::tempdir().unwrap();
    let req = GrowRequest {
        context: model("small-river.toml"),
        out: tmp.path().to_path_buf(),
        seed: None,
        steps: Some(4),
        every: Some(2),
        all_streets: false,
        gallery: Some(3),
        interrupt: None,
    };
    grow::run(&req, &mut |_, _| {}).unwrap();
    let text = |f: &str| std::fs::read_to_string(tmp.path().join(f)).unwrap();
    let cities = ctx.neighbour.len();
    assert_eq!(text("steps.svg").matches("class=\"city\"").count(), 3 * cities, "steps 0, 2 and 4");
    assert_eq!(text("gallery.svg").matches("class=\"city\"").count(), 3 * cities, "three seeds");
    assert!(tmp.path().join("gallery.png").exists() && tmp.path().join("steps.png").exists());
}

/// A grown directory is only windowed (refused without a window); a triggered interrupt ends
/// the steps at once and the network so far is still checked and written.
#[test]
fn the_source_of_a_request_and_an_interrupt() {
    let tmp = tempfile::tempdir().unwrap();
    let req = GrowRequest {
        context: model("small-lake.toml"),
        out: tmp.path().join("grown"),
        seed: None,
        steps: Some(5),
        every: None,
        all_streets: false,
        gallery: None,
        interrupt: None,
    };
    assert_eq!(req.source(None).unwrap(), grow::Source::Context);
    assert_eq!(req.window_name(), "grown");
    let dir = GrowRequest { context: tmp.path().to_path_buf(), ..req.clone() };
    assert_eq!(dir.source(Some([0.0, 0.0, 1.0, 1.0])).unwrap(), grow::Source::Grown(tmp.path().to_path_buf()));
    let e = dir.source(None).unwrap_err().to_string();
    assert!(e.ends_with("is a directory: give a context file to grow, or --window to window a grown network"), "{e}");

    let interrupt = netspec::solvers::Interrupt::new();
    interrupt.trigger();
    let mut heard = Vec::new();
    let s = grow::run(&GrowRequest { interrupt: Some(interrupt), ..req }, &mut |k, n| heard.push((k, n))).unwrap();
    assert_eq!((s.last.step, heard), (0, vec![(0, 5)]));
    let net: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("grown/network.json")).unwrap()).unwrap();
    assert_eq!(net["violations"], serde_json::json!([]));
}
