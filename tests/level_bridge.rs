//! A laid-out level exported as a mesh and a network spec (`levels::bridge`), solved by the
//! network IP, and checked with plain geometry: the network stays inside the rooms, passes
//! between two rooms only through the door of a graph edge, and visits every room.

use netspec::levels::anneal::{self, AnnealOptions};
use netspec::levels::bridge::{self, Bridge, BridgeOptions};
use netspec::levels::cspace::CSpaces;
use netspec::levels::spec::{BlockId, Level, NodeId};
use netspec::levels::validate::{door, validate};
use netspec::levels::{Layout, Placement};
use netspec::pipeline::{self, DesignResult};
use netspec::solvers::{SolveOptions, SolverKind, Termination};
use netspec::spec::Spec;
use std::path::Path;
use std::process::Command;

type Pt = [f64; 2];

const BLOCKS: &str = "[[block]]\nname = \"square\"\npolygon = [[0, 0], [1, 0], [1, 1], [0, 1]]\n\
[[block]]\nname = \"wide\"\npolygon = [[0, 0], [2, 0], [2, 1], [0, 1]]\n";

/// A level whose nodes are `(name, block, position)`, joined by `edges`, and its one layout.
fn fixed(w: f64, nodes: &[(&str, &str, Pt)], edges: &[(&str, &str)]) -> (Level, Layout) {
    let mut t = format!("door_width = {w}\n{BLOCKS}");
    for (n, b, _) in nodes {
        t += &format!("[[node]]\nname = \"{n}\"\nblocks = [\"{b}\"]\n");
    }
    for (a, b) in edges {
        t += &format!("[[edge]]\nnodes = [\"{a}\", \"{b}\"]\n");
    }
    let level = Level::from_toml(&t).unwrap();
    let placements = nodes
        .iter()
        .enumerate()
        .map(|(i, (_, b, p))| {
            let k = level.blocks.iter().position(|x| x.name == *b).unwrap();
            Placement::new(&level, NodeId(i as u32), BlockId(k as u32), *p)
        })
        .collect();
    let layout = Layout { nodes: placements };
    assert!(validate(&level, &layout).is_valid());
    (level, layout)
}

fn opts(spacing: f64) -> BridgeOptions {
    BridgeOptions { spacing: Some(spacing), entrance: None, coverage: None }
}

/// Writes the export, reads the spec back as `netspec solve` does, solves it on HiGHS (the
/// default backend), and asserts a proven optimum that netspec's validator accepts.
fn solve(b: &Bridge, spec: Option<Spec>) -> DesignResult {
    let dir = tempfile::tempdir().unwrap();
    bridge::write(dir.path(), b).unwrap();
    let path = dir.path().join(bridge::SPEC_FILE);
    let mut read = Spec::load(&path).unwrap();
    assert_eq!(read, b.spec, "network.toml reads back as the spec");
    if let Some(s) = spec {
        read = s;
    }
    let p = read.resolve(dir.path()).unwrap_or_else(|e| panic!("{e}"));
    let kind = SolverKind::default_kind().unwrap();
    let o = SolveOptions { time_limit: Some(120.0), ..Default::default() };
    let r = pipeline::solve_built(&p, &pipeline::build(&p), kind, &o).unwrap();
    assert_eq!(r.solve.termination, Termination::Optimal);
    assert!(r.validity.valid, "{:?}", r.validity.design_violations);
    r
}

/// Even-odd point in polygon.
fn inside(p: Pt, poly: &[Pt]) -> bool {
    let mut c = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            c = !c;
        }
    }
    c
}

fn close(a: [Pt; 2], b: [Pt; 2]) -> bool {
    (0..2).all(|i| (0..2).all(|k| (a[i][k] - b[i][k]).abs() < 1e-12))
}

/// Distance from `p` to segment `s`.
fn dist(p: Pt, s: [Pt; 2]) -> f64 {
    let d = [s[1][0] - s[0][0], s[1][1] - s[0][1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    let t = if l2 == 0.0 { 0.0 } else { (((p[0] - s[0][0]) * d[0] + (p[1] - s[0][1]) * d[1]) / l2).clamp(0.0, 1.0) };
    let q = [s[0][0] + t * d[0], s[0][1] + t * d[1]];
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
}

/// The independent check, plain geometry on the placed blocks and the given doors
/// (`(block a, block b, span)`): every active edge lies inside exactly one block, off its walls;
/// where the network passes from one block to another (a vertex with active edges in both),
/// the two are joined by a door and the vertex lies on it; every block holds an active edge.
fn check(blocks: &[Vec<Pt>], doors: &[(usize, usize, [Pt; 2])], r: &DesignResult) -> Result<(), String> {
    let pos = |v: u32| r.mesh.positions()[v as usize];
    let mut at: std::collections::BTreeMap<u32, std::collections::BTreeSet<usize>> = Default::default();
    let mut visited = vec![false; blocks.len()];
    for &[a, b] in &r.active_edges {
        let (pa, pb) = (pos(a), pos(b));
        let mid = [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0];
        let on_wall =
            blocks.iter().any(|poly| (0..poly.len()).any(|i| dist(mid, [poly[i], poly[(i + 1) % poly.len()]]) < 1e-9));
        let holders: Vec<usize> = (0..blocks.len()).filter(|&k| inside(mid, &blocks[k])).collect();
        if on_wall || holders.len() != 1 {
            return Err(format!("edge {pa:?}–{pb:?} runs along a wall or outside the blocks"));
        }
        visited[holders[0]] = true;
        at.entry(a).or_default().insert(holders[0]);
        at.entry(b).or_default().insert(holders[0]);
    }
    for (v, bs) in &at {
        if bs.len() < 2 {
            continue;
        }
        let p = pos(*v);
        let through_door = bs.len() == 2
            && doors.iter().any(|&(a, b, span)| bs.contains(&a) && bs.contains(&b) && dist(p, span) < 1e-9);
        if !through_door {
            return Err(format!("the network passes between blocks {bs:?} at {p:?}, not through a door"));
        }
    }
    match visited.iter().position(|v| !v) {
        Some(k) => Err(format!("block {k} is not visited")),
        None => Ok(()),
    }
}

#[test]
fn two_squares_meet_through_their_door() {
    let (level, layout) = fixed(0.6, &[("a", "square", [0.0, 0.0]), ("b", "square", [1.0, 0.0])], &[("a", "b")]);
    let b = bridge::bridge(&level, &layout, "two", &opts(0.25)).unwrap();
    // A 8 × 4 grid of quarter cells; the door x = 1, y ∈ [0.2, 0.8].
    assert_eq!((b.mesh.num_vertices(), b.mesh.num_faces()), (45, 32));
    assert!(close(b.doors[0].span, [[1.0, 0.2], [1.0, 0.8]]), "{:?}", b.doors[0].span);
    let pos = |v: &u32| b.mesh.positions()[*v as usize];
    let blocked: Vec<Pt> = b.spec.user.obstacle_vertices.iter().map(pos).collect();
    assert_eq!(blocked, vec![[1.0, 0.0], [1.0, 1.0]], "wall vertices off the door");
    assert_eq!(b.spec.user.obstacle_edges.len(), 4, "the wall x = 1, four edges");
    assert_eq!(b.mesh.positions()[b.rooms[0].index()], [0.5, 0.5]);
    assert_eq!(b.mesh.positions()[b.rooms[1].index()], [1.5, 0.5]);
    assert_eq!(b.spec.sinks.vertices, vec![b.rooms[0].0]);
    // Coverage: the far corners of b are sqrt(0.5) from its room vertex; the spec's minimum is 1.
    assert_eq!(b.spec.coverage.range, 1.0);
    let r = solve(&b, None);
    // The straight corridor from room to room through the door's middle.
    assert!((r.solve.objective.unwrap() - 1.0).abs() < 1e-6, "{:?}", r.solve.objective);
    check(&b.blocks, &[(0, 1, [[1.0, 0.2], [1.0, 0.8]])], &r).unwrap();
}

/// A chain a – b – c where a and c also share a wall with no door: the network must go round
/// through b. Without the walls the optimum (2) crosses from a to c; with them it is 2.25.
#[test]
fn a_three_room_chain_goes_round_through_the_middle_room() {
    let (level, layout) = fixed(
        0.6,
        &[("a", "square", [0.0, 0.0]), ("b", "square", [1.0, 0.0]), ("c", "wide", [0.0, 1.0])],
        &[("a", "b"), ("b", "c")],
    );
    let b = bridge::bridge(&level, &layout, "chain", &opts(0.25)).unwrap();
    let doors = [(0, 1, [[1.0, 0.2], [1.0, 0.8]]), (1, 2, [[1.8, 1.0], [1.2, 1.0]])];
    assert!(close(b.doors[0].span, doors[0].2) && close(b.doors[1].span, doors[1].2), "{:?}", b.doors);
    let r = solve(&b, None);
    assert!((r.solve.objective.unwrap() - 2.25).abs() < 1e-6, "{:?}", r.solve.objective);
    check(&b.blocks, &doors, &r).unwrap();
    // The same mesh with crossable walls: a shorter network, which the check rejects.
    let mut open = b.spec.clone();
    open.user.obstacle_vertices.clear();
    open.user.obstacle_edges.clear();
    let r = solve(&b, Some(open));
    assert!((r.solve.objective.unwrap() - 2.0).abs() < 1e-6, "{:?}", r.solve.objective);
    let e = check(&b.blocks, &doors, &r).unwrap_err();
    assert!(e.contains("not through a door") || e.contains("along a wall"), "{e}");
    // The entrance moves the sink; every other room keeps its forced vertex.
    let o = BridgeOptions { entrance: Some("c".into()), ..opts(0.25) };
    let moved = bridge::bridge(&level, &layout, "chain", &o).unwrap();
    assert_eq!(moved.spec.sinks.vertices, vec![moved.rooms[2].0]);
    assert_eq!(moved.spec.user.forced_vertices.len(), 2);
}

/// Without the forced room vertices, and with a coverage range the entrance's room alone meets,
/// the network stays at home; the check notices the unvisited room.
#[test]
fn a_skipped_room_is_caught() {
    let (level, layout) = fixed(0.6, &[("a", "square", [0.0, 0.0]), ("b", "square", [1.0, 0.0])], &[("a", "b")]);
    let b = bridge::bridge(&level, &layout, "two", &opts(0.25)).unwrap();
    let mut lax = b.spec.clone();
    lax.user.forced_vertices.clear();
    lax.coverage.range = 100.0;
    let r = solve(&b, Some(lax));
    let e = check(&b.blocks, &[(0, 1, [[1.0, 0.2], [1.0, 0.8]])], &r).unwrap_err();
    assert!(e.contains("is not visited"), "{e}");
}

#[test]
fn blocks_touching_at_a_corner_keep_the_mesh_manifold() {
    // c touches a only at (1, 1); b joins them.
    let (level, layout) = fixed(
        0.5,
        &[("a", "square", [0.0, 0.0]), ("b", "square", [1.0, 0.0]), ("c", "square", [1.0, 1.0])],
        &[("a", "b"), ("b", "c")],
    );
    // Moving b away leaves a and c diagonal neighbours only: a is placed next to nothing but c.
    let diag = Layout {
        nodes: vec![
            layout.nodes[0].clone(),
            Placement { position: [2.0, 1.0], ..layout.nodes[1].clone() },
            layout.nodes[2].clone(),
        ],
    };
    let lone = Level { edges: vec![(NodeId(1), NodeId(2))], ..level.clone() };
    let b = bridge::bridge(&lone, &diag, "corner", &opts(0.25)).unwrap();
    // One cell lost its corner at (1, 1): one triangle among the quads.
    let tri = b.mesh.faces().filter(|&f| b.mesh.face_size(f) == 3).count();
    assert_eq!(tri, 1);
    let at = b.mesh.positions().iter().filter(|p| **p == [1.0, 1.0]).count();
    assert_eq!(at, 1);
    // The chain itself exports and solves.
    let b = bridge::bridge(&level, &layout, "corner", &opts(0.25)).unwrap();
    let r = solve(&b, None);
    let doors: Vec<(usize, usize, [Pt; 2])> =
        level.edges.iter().zip(&b.doors).map(|(&(x, y), d)| (x.0 as usize, y.0 as usize, d.span)).collect();
    check(&b.blocks, &doors, &r).unwrap();
}

#[test]
fn bad_exports_name_the_field() {
    let (level, layout) = fixed(0.6, &[("a", "square", [0.0, 0.0]), ("b", "square", [1.0, 0.0])], &[("a", "b")]);
    let err = |o: BridgeOptions| bridge::bridge(&level, &layout, "x", &o).unwrap_err().to_string();
    let e = err(BridgeOptions { entrance: Some("hall".into()), ..opts(0.25) });
    assert!(e.starts_with("entrance:") && e.contains("hall"), "{e}");
    let e = err(opts(-1.0));
    assert!(e.starts_with("spacing:"), "{e}");
    let e = err(opts(2.0));
    assert!(e.starts_with("spacing:") && e.contains("no grid vertex inside"), "{e}");
    let e = err(BridgeOptions { coverage: Some(0.5), ..opts(0.25) });
    assert!(e.starts_with("coverage:"), "{e}");
    // A slanted wall.
    let t = "door_width = 0.3\n[[block]]\nname = \"tri\"\npolygon = [[0, 0], [1, 0], [0, 1]]\n\
             [[node]]\nname = \"a\"\n";
    let tri = Level::from_toml(t).unwrap();
    let one = Layout { nodes: vec![Placement::new(&tri, NodeId(0), BlockId(0), [0.0, 0.0])] };
    let e = bridge::bridge(&tri, &one, "x", &opts(0.1)).unwrap_err().to_string();
    assert!(e.contains("block[0] (\"tri\").polygon") && e.contains("axis-parallel"), "{e}");
}

/// The worked example of docs/levels.md: Fig. 1's reconstruction, annealed, exported, solved.
#[test]
fn fig1_laid_out_exported_and_solved() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let level = Level::read(&dir.join("models/levels/fig1.toml")).unwrap();
    let cs = CSpaces::new(&level);
    let a = anneal::anneal(&level, &cs, &AnnealOptions { seed: 1, count: 1, time_limit: 60.0, ..Default::default() });
    let layout = &a.layouts[0];
    let b = bridge::bridge(&level, layout, "fig1", &opts(0.5)).unwrap();
    let r = solve(&b, None);
    let v = validate(&level, layout);
    let doors: Vec<(usize, usize, [Pt; 2])> = level
        .all_edges()
        .into_iter()
        .map(|e| {
            let (x, y) = level.edges[e.0 as usize];
            (x.0 as usize, y.0 as usize, door(&level, &v, e).unwrap())
        })
        .collect();
    check(&b.blocks, &doors, &r).unwrap();
}

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

#[test]
fn command_exports_a_spec_that_solve_takes() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("two.toml");
    let text = format!(
        "door_width = 0.6\n{BLOCKS}[[node]]\nname = \"a\"\nblocks = [\"square\"]\nposition = [0, 0]\n\
         [[node]]\nname = \"b\"\nblocks = [\"square\"]\n[[edge]]\nnodes = [\"a\", \"b\"]\n"
    );
    std::fs::write(&spec, &text).unwrap();
    let out = dir.path().join("out");
    let run = netspec()
        .arg("level")
        .arg(&spec)
        .args(["--method", "milp", "--export-spec", "--spacing", "0.25", "--entrance", "b", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("mesh.json") && stdout.contains("network.toml"), "{stdout}");
    let solved = dir.path().join("solved");
    let run = netspec().arg("solve").arg(out.join("network.toml")).arg("--out").arg(&solved).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(solved.join("result.json")).unwrap()).unwrap();
    assert_eq!(json["validity"]["valid"], true, "{json}");
    assert!(json["solve"]["objective"].as_f64().unwrap() >= 1.0, "room centres are at least 1 apart");
}

#[test]
fn exporting_a_level_without_a_layout_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("star.toml");
    let mut text = format!("door_width = 0.6\n{BLOCKS}[[node]]\nname = \"hub\"\nblocks = [\"square\"]\n");
    for i in 0..5 {
        text +=
            &format!("[[node]]\nname = \"leaf{i}\"\nblocks = [\"square\"]\n[[edge]]\nnodes = [\"hub\", \"leaf{i}\"]\n");
    }
    std::fs::write(&spec, &text).unwrap();
    let out = dir.path().join("out");
    let run = netspec()
        .arg("level")
        .arg(&spec)
        .args(["--method", "milp", "--no-explain", "--export-spec", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(4), "{stderr}");
    assert!(stderr.contains("star.toml") && stderr.contains("no layout to export (status infeasible)"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!out.join("network.toml").exists());
}
