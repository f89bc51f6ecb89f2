//! Game levels from a connectivity graph (Ma et al. 2014): configuration spaces, the exact
//! placement model on every backend, the validator, spec errors, the command.

use netspec::levels::anneal::{self, AnnealOptions};
use netspec::levels::cspace::{contact_segments, CSpaces};
use netspec::levels::exact::{self, ExactOptions, ExactStatus};
use netspec::levels::spec::{Block, Level};
use netspec::levels::validate::validate;
use netspec::levels::{geometry, Layout, Placement};
use netspec::solvers::SolverKind;
use std::process::Command;

const SQUARE: &str = "[[block]]\nname = \"square\"\npolygon = [[0, 0], [1, 0], [1, 1], [0, 1]]\n";

fn block(poly: &[[f64; 2]]) -> Block {
    Block { name: "b".into(), polygon: poly.to_vec(), parts: geometry::convex_parts(poly) }
}

/// A level of unit squares: `nodes`, `edges` by index, door width `w`.
fn squares(w: f64, nodes: usize, edges: &[(usize, usize)]) -> Level {
    let mut t = format!("door_width = {w}\n{SQUARE}");
    for i in 0..nodes {
        t += &format!("[[node]]\nname = \"n{i}\"\n");
    }
    for (a, b) in edges {
        t += &format!("[[edge]]\nnodes = [\"n{a}\", \"n{b}\"]\n");
    }
    Level::from_toml(&t).unwrap()
}

fn star(leaves: usize) -> Level {
    let edges: Vec<(usize, usize)> = (1..=leaves).map(|i| (0, i)).collect();
    squares(0.6, leaves + 1, &edges)
}

fn backends() -> Vec<SolverKind> {
    SolverKind::compiled().into_iter().filter(|k| *k != SolverKind::GoodLp).collect()
}

fn solve(level: &Level, kind: SolverKind, count: usize, explain: bool) -> exact::ExactReport {
    let o = ExactOptions { solver: kind, time_limit: 60.0, count, threads: Some(1), explain };
    exact::solve(level, &CSpaces::new(level), &o, &[]).unwrap()
}

#[test]
fn two_unit_squares_touch_along_four_segments_of_two_minus_two_w() {
    let sq = block(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    for w in [0.1, 0.5, 0.6, 0.9] {
        let segs = contact_segments(&sq, &sq, w);
        assert_eq!(segs.len(), 4, "w = {w}");
        for s in &segs {
            assert!((s.len() - (2.0 - 2.0 * w)).abs() < 1e-12, "w = {w}: {s:?}");
        }
    }
    // The segment right of the square: x = 1, y from w − 1 to 1 − w.
    let segs = contact_segments(&sq, &sq, 0.6);
    let right = segs.iter().find(|s| (s.a[0] - 1.0).abs() < 1e-12 && (s.b[0] - 1.0).abs() < 1e-12).unwrap();
    let (lo, hi) = (right.a[1].min(right.b[1]), right.a[1].max(right.b[1]));
    assert!((lo + 0.4).abs() < 1e-12 && (hi - 0.4).abs() < 1e-12);
}

#[test]
fn l_block_against_a_square_gives_the_inner_corner_segments() {
    let ell = block(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]);
    let sq = block(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    let w = 0.25;
    let segs = contact_segments(&ell, &sq, w);
    let has = |a: [f64; 2], b: [f64; 2]| {
        let close = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9;
        segs.iter().any(|s| (close(s.a, a) && close(s.b, b)) || (close(s.a, b) && close(s.b, a)))
    };
    // On the lower arm's top: from the inner corner (touching the upper arm too) out to a door's
    // overlap; the part where the square would enter the upper arm is cut away.
    assert!(has([1.0, 1.0], [2.0 - w, 1.0]), "{segs:?}");
    // On the upper arm's right side, symmetric.
    assert!(has([1.0, 1.0], [1.0, 2.0 - w]), "{segs:?}");
    // Outer sides: full sliding ranges (bottom: y = −1, x from w − 1 to 2 − w).
    assert!(has([w - 1.0, -1.0], [2.0 - w, -1.0]) || has([2.0 - w, -1.0], [w - 1.0, -1.0]), "{segs:?}");
    // Every segment point is a contact without overlap, by the validator.
    let level = Level::from_toml(&format!(
        "door_width = {w}\n[[block]]\nname = \"ell\"\npolygon = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]\n{SQUARE}\
         [[node]]\nname = \"l\"\nblocks = [\"ell\"]\n[[node]]\nname = \"s\"\nblocks = [\"square\"]\n[[edge]]\nnodes = [\"l\", \"s\"]\n"
    ))
    .unwrap();
    let cs = CSpaces::new(&level);
    for s in cs.segments(level.nodes[0].blocks[0], level.nodes[1].blocks[0]) {
        for t in [0.0, 0.3, 0.5, 1.0] {
            let layout = Layout {
                nodes: vec![
                    Placement::new(&level, level_node(0), level.nodes[0].blocks[0], [0.0, 0.0]),
                    Placement::new(&level, level_node(1), level.nodes[1].blocks[0], s.at(t)),
                ],
            };
            let v = validate(&level, &layout);
            assert!(v.is_valid(), "{s:?} at {t}: {:?}", v.problems());
        }
    }
}

fn level_node(i: u32) -> netspec::levels::spec::NodeId {
    netspec::levels::spec::NodeId(i)
}

#[test]
fn triangle_of_squares_is_feasible_exactly_when_w_at_most_half_on_every_backend() {
    for kind in backends() {
        let ok = solve(&squares(0.5, 3, &[(0, 1), (1, 2), (0, 2)]), kind, 1, false);
        assert_eq!(ok.status, ExactStatus::Feasible, "{kind}");
        let level = squares(0.5, 3, &[(0, 1), (1, 2), (0, 2)]);
        assert!(validate(&level, &ok.layouts[0]).is_valid(), "{kind}");
        let no = solve(&squares(0.55, 3, &[(0, 1), (1, 2), (0, 2)]), kind, 1, false);
        assert_eq!(no.status, ExactStatus::Infeasible, "{kind}");
    }
}

#[test]
fn star_of_squares_has_four_leaves_at_most_on_every_backend() {
    for kind in backends() {
        let four = solve(&star(4), kind, 1, false);
        assert_eq!(four.status, ExactStatus::Feasible, "{kind}");
        assert!(validate(&star(4), &four.layouts[0]).is_valid(), "{kind}");
        let five = solve(&star(5), kind, 1, false);
        assert_eq!(five.status, ExactStatus::Infeasible, "{kind}");
    }
}

#[test]
fn five_leaf_star_conflict_is_all_five_edges() {
    let r = solve(&star(5), SolverKind::default_kind().unwrap(), 1, true);
    let c = r.conflict.expect("an infeasible level is explained");
    assert_eq!(c.edges.len(), 5, "{:?}", c.edges);
    assert!(c.minimal);
    // A star with a sixth, harmless edge elsewhere: the conflict leaves it out.
    let mut edges: Vec<(usize, usize)> = (1..=5).map(|i| (0, i)).collect();
    edges.push((5, 6));
    let r = solve(&squares(0.6, 7, &edges), SolverKind::default_kind().unwrap(), 1, true);
    let c = r.conflict.unwrap();
    assert_eq!(c.edges.len(), 5);
    assert!(c.edges.iter().all(|[a, _]| a == "n0"), "{:?}", c.edges);
}

#[test]
fn no_good_cuts_give_distinct_layouts_and_stop_when_none_is_left() {
    // Two squares: exactly four contact segments, so four layouts and then a proof of no more.
    let level = squares(0.6, 2, &[(0, 1)]);
    for kind in backends() {
        let r = solve(&level, kind, 10, false);
        assert_eq!(r.layouts.len(), 4, "{kind}");
        assert!(r.time_to_proof.is_some(), "{kind}");
        for l in &r.layouts {
            assert!(validate(&level, l).is_valid());
        }
        let mut seen: Vec<[i64; 2]> =
            r.layouts.iter().map(|l| l.nodes[1].position.map(|v| v.signum() as i64)).collect();
        seen.sort();
        seen.dedup();
        assert!(seen.len() >= 2, "{kind}: {seen:?}");
    }
}

#[test]
fn validator_finds_overlaps_and_missing_doors() {
    let level = squares(0.6, 2, &[(0, 1)]);
    let at = |x: f64, y: f64| Layout {
        nodes: vec![
            Placement::new(&level, level_node(0), level.nodes[0].blocks[0], [0.0, 0.0]),
            Placement::new(&level, level_node(1), level.nodes[1].blocks[0], [x, y]),
        ],
    };
    assert!(validate(&level, &at(1.0, 0.4)).is_valid());
    let v = validate(&level, &at(1.0, 0.5)); // a wall of 0.5 < 0.6
    assert_eq!(v.missing_doors.len(), 1);
    assert!(v.overlaps.is_empty());
    let v = validate(&level, &at(0.9, 0.0));
    assert_eq!(v.overlaps.len(), 1);
    assert!((v.overlaps[0].2 - 0.1).abs() < 1e-9);
}

fn spec_error(text: &str) -> String {
    Level::from_toml(text).unwrap_err().to_string()
}

#[test]
fn bad_specs_name_the_field() {
    let e = spec_error("door_width = 0.5\n[[block]]\nname = \"bow\"\npolygon = [[0, 0], [1, 1], [1, 0], [0, 1]]\n[[node]]\nname = \"a\"\n");
    assert!(e.contains("block[0] (\"bow\").polygon") && e.contains("self-intersecting"), "{e}");
    let e = spec_error("door_width = 0.5\n[[block]]\nname = \"cw\"\npolygon = [[0, 0], [0, 1], [1, 1], [1, 0]]\n[[node]]\nname = \"a\"\n");
    assert!(e.contains("counter-clockwise"), "{e}");
    let e = spec_error(&format!("door_width = 1.5\n{SQUARE}[[node]]\nname = \"a\"\n"));
    assert!(e.contains("door_width") && e.contains("wider than every wall"), "{e}");
    let e =
        spec_error(&format!("door_width = 0.5\n{SQUARE}[[node]]\nname = \"a\"\n[[edge]]\nnodes = [\"a\", \"b\"]\n"));
    assert!(e.contains("edge[0].nodes") && e.contains("\"b\""), "{e}");
    let e = spec_error(&format!("door_width = 0.5\n{SQUARE}[[node]]\nname = \"a\"\nblocks = [\"round\"]\n"));
    assert!(e.contains("node[0] (\"a\").blocks"), "{e}");
    let e = spec_error(&format!("door_width = 0.5\n{SQUARE}[[node]]\nname = \"a\"\n[[node]]\nname = \"b\"\n"));
    assert!(e.contains("connected") && e.contains("\"b\""), "{e}");
    let e = spec_error("door_width = 0.5\n[[block]]\nname = 3\n");
    assert!(e.contains("line 3"), "{e}");
    let e = spec_error(&format!("door_width = -1\n{SQUARE}[[node]]\nname = \"a\"\n"));
    assert!(e.contains("door_width"), "{e}");
}

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

#[test]
fn command_writes_level_json_with_the_status() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("star.toml");
    let mut text = format!("door_width = 0.6\n{SQUARE}[[node]]\nname = \"hub\"\nblocks = [\"square\"]\n");
    for i in 0..5 {
        text += &format!("[[node]]\nname = \"leaf{i}\"\n[[edge]]\nnodes = [\"hub\", \"leaf{i}\"]\n");
    }
    std::fs::write(&spec, &text).unwrap();
    let out = dir.path().join("out");
    let run = netspec().arg("level").arg(&spec).args(["--method", "milp", "--out"]).arg(&out).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("level.json")).unwrap()).unwrap();
    assert_eq!(json["status"], "infeasible");
    assert_eq!(json["milp"]["conflict"]["edges"].as_array().unwrap().len(), 5);
    // Four leaves: a layout, each node's block and position.
    let four = text.replace("[[node]]\nname = \"leaf4\"\n[[edge]]\nnodes = [\"hub\", \"leaf4\"]\n", "");
    std::fs::write(&spec, four).unwrap();
    let run = netspec().arg("level").arg(&spec).arg("--out").arg(&out).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("level.json")).unwrap()).unwrap();
    assert_eq!(json["status"], "feasible");
    // The default method anneals first and hands the layout to the MILP as a checked start.
    assert_eq!(json["method"], "both");
    assert_eq!(json["milp"]["start_accepted"], true);
    let svg = std::fs::read_to_string(out.join("layout-1.svg")).unwrap();
    assert_eq!(svg.matches("<polygon").count(), 5);
    assert_eq!(svg.matches("<polyline").count(), 4, "one door and graph edge per edge");
    assert!(std::fs::metadata(out.join("layout-1.png")).unwrap().len() > 0);
    let nodes = json["layouts"][0]["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 5);
    assert_eq!(nodes[0]["block_name"], "square");
    assert_eq!(nodes[0]["position"].as_array().unwrap().len(), 2);
    // A bad file: an error naming the file and the field, no panic.
    std::fs::write(
        &spec,
        "door_width = 0.6\n[[block]]\nname = \"x\"\npolygon = [[0, 0], [1, 0]]\n[[node]]\nname = \"a\"\n",
    )
    .unwrap();
    let run = netspec().arg("level").arg(&spec).output().unwrap();
    assert_eq!(run.status.code(), Some(1));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("star.toml") && err.contains("block[0] (\"x\").polygon"), "{err}");
}

fn quick(seed: u64, count: usize) -> AnnealOptions {
    // A short schedule: the tests check what is found, never how fast.
    AnnealOptions { seed, count, time_limit: 1e6, cycles: 10, trials: 200, ..AnnealOptions::default() }
}

#[test]
fn chains_start_with_the_smallest_cycle_and_end_with_trees() {
    // A square 0-1-2-3 with a triangle 3-4-0 on one side and a tail 1-5-6.
    let level = squares(0.3, 7, &[(0, 1), (1, 2), (2, 3), (3, 0), (3, 4), (4, 0), (1, 5), (5, 6)]);
    let c = anneal::chains(&level);
    let names = |i: usize| c[i].iter().map(|n| n.0).collect::<Vec<_>>();
    assert_eq!(names(0), vec![0, 3, 4]);
    assert_eq!(names(1), vec![1, 2]);
    assert_eq!(names(2), vec![5, 6]);
    assert_eq!(c.len(), 3);
}

#[test]
fn annealer_finds_distinct_valid_layouts_and_nothing_where_none_exists() {
    let level = star(4);
    let cs = CSpaces::new(&level);
    let r = anneal::anneal(&level, &cs, &quick(7, 3));
    assert_eq!(r.layouts.len(), 3, "{r:?}");
    assert_eq!(r.stopped, "count");
    for l in &r.layouts {
        assert!(validate(&level, l).is_valid());
    }
    assert_ne!(r.layouts[0], r.layouts[1]);
    let triangle = squares(0.4, 3, &[(0, 1), (1, 2), (0, 2)]);
    let r = anneal::anneal(&triangle, &CSpaces::new(&triangle), &quick(3, 1));
    assert_eq!(r.layouts.len(), 1);
    assert!(validate(&triangle, &r.layouts[0]).is_valid());
    // No layout exists: the stack runs empty, nothing is returned.
    let five = star(5);
    let o = AnnealOptions { partial_variations: 2, ..quick(1, 1) };
    let r = anneal::anneal(&five, &CSpaces::new(&five), &o);
    assert!(r.layouts.is_empty());
    assert_eq!(r.stopped, "exhausted");
}

#[test]
fn annealed_layouts_are_mip_starts_the_checker_accepts_on_every_backend() {
    for level in [star(4), squares(0.4, 3, &[(0, 1), (1, 2), (0, 2)])] {
        let cs = CSpaces::new(&level);
        let a = anneal::anneal(&level, &cs, &quick(5, 1));
        assert_eq!(a.layouts.len(), 1);
        for kind in backends() {
            let o = ExactOptions { solver: kind, time_limit: 60.0, count: 1, threads: Some(1), explain: false };
            let r = exact::solve(&level, &cs, &o, &a.layouts).unwrap();
            assert_eq!(r.status, ExactStatus::Feasible, "{kind}");
            assert_eq!(r.start_accepted, Some(true), "{kind}");
        }
    }
}
