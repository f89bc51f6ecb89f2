//! Infeasibility explained: tiny infeasible specs, their minimal conflicting sets on every
//! backend, several contradictions in one spec, and the command line's console, JSON and picture.

use crate::network::{backends, problem};
use netspec::explain::{explain, ExplainOptions, ExplainStatus, Explanation, ForbiddenKind, Requirement};
use netspec::solvers::SolverKind;
use std::process::Command;

fn opts() -> ExplainOptions {
    ExplainOptions { check_time_limit: 20.0, time_budget: 120.0, ..ExplainOptions::default() }
}

/// The conflicts as lists of requirements.
fn sets(e: &Explanation) -> Vec<Vec<Requirement>> {
    e.conflicts.iter().map(|c| c.requirements.iter().map(|r| r.requirement).collect()).collect()
}

/// A 3×3 grid walled in, whose only sink is a corner: the two walls at the corner cut it off,
/// and coverage needs a network. The same minimal set on every backend (but microlp, a plain
/// branch and bound that needs minutes for these feasibility checks).
const CORNER: &str = r#"
name = "corner"
boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 3, height = 3 }
[sinks]
vertices = [0]
"#;

#[test]
fn corner_sink_behind_a_wall_on_every_backend() {
    let p = problem(CORNER);
    // Edges 0–1 and 0–4 (on the 4 × 4 vertex grid).
    let wall = |a: u32, b: u32| Requirement::Wall {
        edge: p
            .mesh
            .he_edge(p.mesh.half_edge_between(netspec::mesh::VertexId(a), netspec::mesh::VertexId(b)).unwrap())
            .0,
    };
    for kind in backends(false) {
        let e = explain(&p, kind, &opts());
        assert_eq!(e.status, ExplainStatus::Explained, "{kind}: {e:#?}");
        let mut want = vec![Requirement::Coverage, wall(0, 1), wall(0, 4)];
        want.sort();
        let mut got = sets(&e);
        got[0].sort();
        assert_eq!(got, vec![want], "{kind}");
        assert!(e.complete && e.conflicts[0].minimal && e.unknown_checks == 0, "{kind}: {e:#?}");
        // Dropping coverage, or opening the corner's walls (relaxed together), repairs the spec.
        assert_eq!(e.repairs, [vec!["coverage"], vec!["boundary[0–1]", "boundary[4–0]"]], "{kind}");
        let wall_info = &e.conflicts[0].requirements.iter().find(|r| r.field == "boundary").unwrap();
        assert_eq!(wall_info.edges.len(), 1);
        // 14 requirements: coverage, dead-ends and the 12 boundary walls.
        assert_eq!(e.requirements, 14);
        assert_eq!(e.solver, kind.name());
    }
}

/// A through route must not branch; a forced edge makes it branch at an inner vertex.
#[test]
fn through_route_with_a_forced_branch() {
    let p = problem(
        r#"
name = "route"
boundary = "road"
formulation = "tight"
[mesh]
grid = { width = 6, height = 6 }
[sinks]
all_boundary = true
[user]
through_routes = [{ from = [0, 3], to = [6, 3] }]
forced_edges = [[24, 31]]   # (3, 3)–(3, 4), up from the route's middle
"#,
    );
    let e = explain(&p, SolverKind::default_kind().unwrap(), &opts());
    assert_eq!(
        sets(&e),
        vec![vec![Requirement::ForcedEdge { index: 0 }, Requirement::ThroughRoute { index: 0 }]],
        "{e:#?}"
    );
    assert!(e.complete && e.conflicts[0].minimal);
    let route = &e.conflicts[0].requirements[1];
    assert_eq!(route.field, "user.through_routes[0]");
    assert_eq!(route.edges.len(), 6);
    assert_eq!(route.vertices, (21..=27).collect::<Vec<u32>>());
}

/// Four 2×2 offices exactly fill a 4×4 floor; a hall must fit too: the tiling and both counts
/// conflict (any one dropped, a plan exists).
#[test]
fn contradictory_room_counts() {
    let p = problem(
        r#"
name = "rooms"
boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = [2]
[features]
dead_ends = "allow"
[rooms]
mode = "floorplan"
templates = [{ name = "office", shape = "rect 2x2", exact = 4 }, { name = "hall", shape = "rect 2x4", min = 1 }]
"#,
    );
    let e = explain(&p, SolverKind::default_kind().unwrap(), &opts());
    assert_eq!(
        sets(&e),
        vec![vec![
            Requirement::RoomTiling,
            Requirement::RoomCount { template: 0 },
            Requirement::RoomCount { template: 1 }
        ]],
        "{e:#?}"
    );
    assert!(e.complete && e.conflicts[0].minimal);
    let texts: Vec<&str> = e.conflicts[0].requirements.iter().map(|r| r.text.as_str()).collect();
    assert_eq!(texts[1], r#"exactly 4 room(s) of type "office""#);
    assert_eq!(texts[2], r#"at least 1 room(s) of type "hall""#);
}

/// Two separate contradictions in one spec — a route forced to branch, and a forced vertex
/// fenced off by obstacle edges — are both reported; the command line prints them, writes them
/// to result.json and highlights their elements in the picture.
const TWO: &str = r#"
name = "two"
boundary = "road"
formulation = "tight"
[mesh]
grid = { width = 6, height = 6 }
[sinks]
all_boundary = true
[user]
through_routes = [{ from = [0, 4], to = [6, 4] }]
forced_edges = [[31, 38]]   # (3, 4)–(3, 5)
# Vertices (2, 2) = 16 and (3, 2) = 17 fenced in; 16 must be active.
obstacle_edges = [[16, 9], [16, 23], [16, 15], [17, 10], [17, 24], [17, 18]]
forced_vertices = [16]
"#;

#[test]
fn every_contradiction_is_reported() {
    let p = problem(TWO);
    let e = explain(&p, SolverKind::default_kind().unwrap(), &opts());
    let mut got = sets(&e);
    got.sort();
    let fence: Vec<Requirement> = (0..6)
        .map(|index| Requirement::ObstacleEdge { index })
        .chain([Requirement::ForcedVertex { index: 0 }])
        .collect();
    assert_eq!(
        got,
        vec![fence, vec![Requirement::ForcedEdge { index: 0 }, Requirement::ThroughRoute { index: 0 }]],
        "{e:#?}"
    );
    assert!(e.complete && e.conflicts.iter().all(|c| c.minimal), "{e:#?}");
    // One requirement (or fence) of each conflict relaxed together repairs it.
    assert_eq!(e.repairs.len(), 4, "{:?}", e.repairs);
    assert!(e
        .repairs
        .iter()
        .all(|r| r.iter().any(|f| f.starts_with("user.forced_edges") || f.starts_with("user.through_routes"))));

    // The command line: console, result.json, picture.
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("two.toml");
    std::fs::write(&spec, TWO).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .arg("solve")
        .arg(&spec)
        .arg("--out")
        .arg(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains("status     infeasible") && stdout.contains("explain    2 conflicting sets of requirements ("),
        "{stdout}"
    );
    assert!(
        stdout.contains("- user.forced_edges[0]: forced edge 31–38")
            && stdout.contains("- user.forced_vertices[0]: forced vertex 16"),
        "{stdout}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("result.json")).unwrap()).unwrap();
    let inf = &json["infeasibility"];
    assert_eq!(inf["status"], "explained");
    assert_eq!(inf["conflicts"].as_array().unwrap().len(), 2);
    assert_eq!(json["solve"]["termination"]["reason"], "infeasible", "{}", json["solve"]);
    let fields: Vec<&str> = inf["conflicts"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| c["requirements"].as_array().unwrap().iter().map(|r| r["field"].as_str().unwrap()))
        .collect();
    assert!(fields.contains(&"user.through_routes[0]") && fields.contains(&"user.obstacle_edges[5]"), "{fields:?}");
    // The result still reads as a design result.
    let _: netspec::pipeline::DesignResult = serde_json::from_value(json.clone()).unwrap();
    let svg = std::fs::read_to_string(dir.path().join("network.svg")).unwrap();
    // Conflict 1 or 2: the route's 6 edges + the forced edge, or the 6 fence edges; the route's 7
    // vertices + the forced vertex ringed.
    let count = |k: usize, tag: &str| svg.matches(&format!(r#"<{tag} class="conflict" data-conflict="{k}""#)).count();
    let mut lines = [count(1, "line"), count(2, "line")];
    lines.sort();
    assert_eq!(lines, [6, 7], "{svg}");
    let mut rings = [count(1, "circle"), count(2, "circle")];
    rings.sort();
    assert_eq!(rings, [1, 7], "{svg}");
    assert!(svg.contains(">conflict 1<") && svg.contains(">conflict 2<"));
    assert!(dir.path().join("network.png").exists());
    // --no-explain: the plain infeasible result.
    let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .arg("solve")
        .arg(&spec)
        .arg("--no-explain")
        .arg("--out")
        .arg(dir.path().join("plain"))
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&o.stdout).contains("explain"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("plain/result.json")).unwrap()).unwrap();
    assert!(json.get("infeasibility").is_none());
}

/// The requirements listed for a game level: the tiling, its counts, the level type, dead-ends
/// and forbidden kinds, walls; a feasible spec has nothing to explain.
#[test]
fn requirements_of_a_game_level_and_a_feasible_spec() {
    let p = problem(
        r#"
name = "game"
boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = [7]
[weights]
too_close = "forbid"
[rooms]
mode = "game"
level = "circular"
templates = [{ name = "room", shape = "rect 2x2", max = 4 }]
"#,
    );
    let reqs = netspec::explain::requirements(&p);
    assert_eq!(reqs[0], Requirement::DeadEnds, "no coverage with rooms: {reqs:?}");
    assert_eq!(reqs[1], Requirement::Forbidden { config: ForbiddenKind::TooClose });
    assert_eq!(reqs.iter().filter(|r| matches!(r, Requirement::Wall { .. })).count(), 16);
    assert_eq!(
        &reqs[reqs.len() - 3..],
        &[Requirement::RoomTiling, Requirement::RoomCount { template: 0 }, Requirement::LevelType]
    );
    // This level exists (a cycle through the four blocks).
    let e = explain(&p, SolverKind::default_kind().unwrap(), &opts());
    assert_eq!(e.status, ExplainStatus::Feasible, "{e:#?}");
    assert!(e.conflicts.is_empty() && e.checks == 1);
}

/// The measured instances of docs/benchmarks.md resolve and list their requirements (solving
/// them is for the benchmark, not the tests).
#[test]
fn benchmark_instances_resolve() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/specs");
    for (file, requirements) in [("infeasible_16x16.toml", 11), ("infeasible_16x16_hard.toml", 76)] {
        let spec = netspec::spec::Spec::load(&dir.join(file)).unwrap();
        let p = spec.resolve(&dir).unwrap();
        assert_eq!(p.mesh.num_edges(), 544);
        assert_eq!(netspec::explain::requirements(&p).len(), requirements, "{file}");
    }
}
