//! Game levels from a connectivity graph (Ma et al. 2014): configuration spaces, the exact
//! placement model on every backend, the validator, spec errors, the command.

use netspec::geometry::{self, convex};
use netspec::levels::anneal::{self, AnnealOptions};
use netspec::levels::cspace::{contact_segments, CSpaces};
use netspec::levels::exact::{self, ExactOptions, ExactStatus};
use netspec::levels::spec::{Block, Level};
use netspec::levels::validate::validate;
use netspec::levels::{Layout, Placement};
use netspec::solvers::SolverKind;
use std::process::Command;

const SQUARE: &str = "[[block]]\nname = \"square\"\npolygon = [[0, 0], [1, 0], [1, 1], [0, 1]]\n";

fn block(poly: &[[f64; 2]]) -> Block {
    Block { name: "b".into(), polygon: poly.to_vec(), parts: convex::convex_parts(poly), rotation_of: None }
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
    let o = ExactOptions { solver: kind, time_limit: 60.0, count, threads: Some(1), explain, interrupt: None };
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
    // The default method runs both side by side; the first answer stops the other, whose
    // report (cut short by the clock) goes to run.json with the measured seconds.
    assert_eq!(json["method"], "both");
    let run_json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run.json")).unwrap()).unwrap();
    assert!(run_json["cspace_time"].as_f64().is_some(), "{run_json}");
    assert!(json.get("cspace_time").is_none(), "no clock values in level.json");
    let answered = json["anneal"]["stopped"] == "count" || json["milp"]["status"] == "feasible";
    assert!(answered, "{json}");
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
    AnnealOptions { seed, count, time_limit: 1e6, cycles: 10, trials: 200, restarts: 0, ..AnnealOptions::default() }
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
            let o = ExactOptions {
                solver: kind,
                time_limit: 60.0,
                count: 1,
                threads: Some(1),
                explain: false,
                interrupt: None,
            };
            let r = exact::solve(&level, &cs, &o, &a.layouts).unwrap();
            assert_eq!(r.status, ExactStatus::Feasible, "{kind}");
            assert_eq!(r.start_accepted, Some(true), "{kind}");
        }
    }
}

/// Two unit squares, `a` fixed at the origin, `b` free, one edge, door width 0.6, and the
/// given extra TOML (obstacles, rotations…).
fn pair_with(extra: &str) -> Level {
    Level::from_toml(&format!(
        "door_width = 0.6\n{SQUARE}[[node]]\nname = \"a\"\nposition = [0, 0]\n[[node]]\nname = \"b\"\n\
         [[edge]]\nnodes = [\"a\", \"b\"]\n{extra}"
    ))
    .unwrap()
}

/// Walls to the right of and above the square at the origin.
const RIGHT_AND_TOP: &str = "[[obstacle]]\npolygon = [[1, -1], [3, -1], [3, 3], [1, 3]]\n\
                             [[obstacle]]\npolygon = [[-1, 1], [1, 1], [1, 3], [-1, 3]]\n";

/// A U around the square at the origin (its well `[0,1] × [0,2]`), and optionally a lid over
/// the well's upper half.
fn walled_in(lid: bool) -> Level {
    let mut t =
        String::from("[[obstacle]]\npolygon = [[-1, -1], [2, -1], [2, 2], [1, 2], [1, 0], [0, 0], [0, 2], [-1, 2]]\n");
    if lid {
        t += "[[obstacle]]\npolygon = [[0, 1.5], [1, 1.5], [1, 2], [0, 2]]\n";
    }
    pair_with(&t)
}

#[test]
fn obstacles_leave_two_sides_and_every_layout_avoids_them_on_every_backend() {
    let level = pair_with(RIGHT_AND_TOP);
    // Right and top contacts are walled off; left and bottom are cut to their lower and left
    // halves (y ≤ 0 on the left, x ≤ 0 below): two contact segments, so two layouts and a proof.
    for kind in backends() {
        let r = solve(&level, kind, 10, false);
        assert_eq!(r.status, ExactStatus::Feasible, "{kind}");
        assert_eq!(r.layouts.len(), 2, "{kind}");
        assert!(r.time_to_proof.is_some(), "{kind}: no proof that a third layout is missing");
        for l in &r.layouts {
            let v = validate(&level, l);
            assert!(v.is_valid(), "{kind}: {:?}", v.problems());
            let [x, y] = l.nodes[1].position;
            let left = (x + 1.0).abs() < 1e-6 && (-0.4 - 1e-6..=1e-6).contains(&y);
            let below = (y + 1.0).abs() < 1e-6 && (-0.4 - 1e-6..=1e-6).contains(&x);
            assert!(left || below, "{kind}: b at {x}, {y}");
        }
        // Without the obstacles: all four sides.
        assert_eq!(solve(&pair_with(""), kind, 10, false).layouts.len(), 4, "{kind}");
    }
}

#[test]
fn an_obstacle_walling_in_a_fixed_node_is_proven_infeasible_on_every_backend() {
    for kind in backends() {
        // The well's open top is the only place b fits: exactly one layout, b at (0, 1).
        let open = solve(&walled_in(false), kind, 10, false);
        assert_eq!(open.layouts.len(), 1, "{kind}");
        let p = open.layouts[0].nodes[1].position;
        assert!(p[0].abs() < 1e-6 && (p[1] - 1.0).abs() < 1e-6, "{kind}: {p:?}");
        assert!(validate(&walled_in(false), &open.layouts[0]).is_valid());
        // A lid closes it.
        let shut = solve(&walled_in(true), kind, 1, false);
        assert_eq!(shut.status, ExactStatus::Infeasible, "{kind}");
    }
    let shut = walled_in(true);
    let o = AnnealOptions { partial_variations: 2, ..quick(1, 1) };
    assert!(anneal::anneal(&shut, &CSpaces::new(&shut), &o).layouts.is_empty());
}

#[test]
fn validator_finds_blocks_on_obstacles() {
    let level = pair_with(RIGHT_AND_TOP);
    let at = |x: f64, y: f64| Layout {
        nodes: vec![
            Placement::new(&level, level_node(0), level.nodes[0].blocks[0], [0.0, 0.0]),
            Placement::new(&level, level_node(1), level.nodes[1].blocks[0], [x, y]),
        ],
    };
    assert!(validate(&level, &at(-1.0, -0.2)).is_valid());
    let v = validate(&level, &at(1.0, 0.0)); // a door, but inside the right wall
    assert!(v.missing_doors.is_empty() && v.overlaps.is_empty());
    assert_eq!(v.obstacle_overlaps.len(), 1, "{:?}", v.problems());
    assert_eq!(v.obstacle_overlaps[0].1, 0);
    assert!((v.obstacle_overlaps[0].2 - 1.0).abs() < 1e-9);
    let v = validate(&level, &at(-1.0, 0.25)); // pokes a quarter into the top wall
    assert_eq!(v.obstacle_overlaps.len(), 1);
    assert_eq!(v.obstacle_overlaps[0].1, 1);
    assert!((v.obstacle_overlaps[0].2 - 0.25).abs() < 1e-9);
}

#[test]
fn annealed_layouts_avoid_obstacles_and_are_accepted_starts() {
    for level in [pair_with(RIGHT_AND_TOP), walled_in(false)] {
        let cs = CSpaces::new(&level);
        let a = anneal::anneal(&level, &cs, &quick(3, 1));
        assert_eq!(a.layouts.len(), 1);
        assert!(validate(&level, &a.layouts[0]).is_valid());
        for kind in backends() {
            let o = ExactOptions {
                solver: kind,
                time_limit: 60.0,
                count: 1,
                threads: Some(1),
                explain: false,
                interrupt: None,
            };
            let r = exact::solve(&level, &cs, &o, &a.layouts).unwrap();
            assert_eq!(r.start_accepted, Some(true), "{kind}");
        }
    }
    // No fixed node: the obstacles cannot bar a layout, which is moved clear of them.
    let free = Level::from_toml(&format!(
        "door_width = 0.6\n{SQUARE}[[node]]\nname = \"a\"\n[[node]]\nname = \"b\"\n[[edge]]\nnodes = [\"a\", \"b\"]\n\
         [[obstacle]]\npolygon = [[-3, -3], [3, -3], [3, 3], [-3, 3]]\n"
    ))
    .unwrap();
    let r = solve(&free, SolverKind::default_kind().unwrap(), 1, false);
    assert!(validate(&free, &r.layouts[0]).is_valid());
    let a = anneal::anneal(&free, &CSpaces::new(&free), &quick(2, 1));
    assert!(validate(&free, &a.layouts[0]).is_valid());
}

#[test]
fn bad_obstacles_name_the_field() {
    let bow = "[[obstacle]]\npolygon = [[5, 5], [6, 6], [6, 5], [5, 6]]\n";
    let e = spec_error(&format!("door_width = 0.5\n{SQUARE}[[node]]\nname = \"a\"\n{bow}"));
    assert!(e.contains("obstacle[0].polygon") && e.contains("self-intersecting"), "{e}");
    let on_a =
        "[[obstacle]]\npolygon = [[9, 9], [10, 9], [10, 10]]\n[[obstacle]]\npolygon = [[0.5, 0.5], [2, 0.5], [2, 2]]\n";
    let e = spec_error(&format!("door_width = 0.5\n{SQUARE}[[node]]\nname = \"a\"\nposition = [0, 0]\n{on_a}"));
    assert!(e.contains("obstacle[1].polygon") && e.contains("\"a\"") && e.contains("fixed position"), "{e}");
    // Touching the fixed block is allowed.
    let beside = "[[obstacle]]\npolygon = [[1, 0], [2, 0], [2, 1], [1, 1]]\n";
    assert!(Level::from_toml(&format!(
        "door_width = 0.5\n{SQUARE}[[node]]\nname = \"a\"\nposition = [0, 0]\n{beside}"
    ))
    .is_ok());
    let e = spec_error(&format!(
        "door_width = 0.5\n{SQUARE}[[node]]\nname = \"a\"\n[[obstacle]]\npolygon = [[0, 0], [1, 0]]\n"
    ));
    assert!(e.contains("obstacle[0].polygon"), "{e}");
}

const ELL: &str = "[[block]]\nname = \"ell\"\npolygon = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]\n";

/// An L fixed at the origin and a unit square fixed in the inner corner of the L turned by
/// 180° (touching both its arms): only that variant gives them a wall in common.
fn ell_and_square(rotations: &str) -> Level {
    Level::from_toml(&format!(
        "door_width = 0.5\n{ELL}{rotations}{SQUARE}[[node]]\nname = \"l\"\nblocks = [\"ell\"]\nposition = [0, 0]\n\
         [[node]]\nname = \"s\"\nblocks = [\"square\"]\nposition = [-2, -2]\n[[edge]]\nnodes = [\"l\", \"s\"]\n"
    ))
    .unwrap()
}

#[test]
fn only_a_rotated_l_fits_its_fixed_neighbour_on_every_backend() {
    let turned = ell_and_square("rotations = [90, 180, 270]\n");
    let names: Vec<&str> = turned.blocks.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["ell", "ell@90", "ell@180", "ell@270", "square"]);
    assert_eq!(turned.nodes[0].blocks.len(), 4, "a node allowing the block allows its rotations");
    for kind in backends() {
        // Both fixed: one placement, reached through either wall of the inner corner (two
        // contact segments meeting there), so two contact choices and then a proof.
        let r = solve(&turned, kind, 10, false);
        assert_eq!(r.layouts.len(), 2, "{kind}");
        assert!(r.time_to_proof.is_some(), "{kind}");
        for l in &r.layouts {
            assert_eq!(l.nodes[0].block_name, "ell@180", "{kind}");
            assert!(validate(&turned, l).is_valid(), "{kind}");
        }
        let plain = solve(&ell_and_square(""), kind, 1, false);
        assert_eq!(plain.status, ExactStatus::Infeasible, "{kind}");
    }
    let a = anneal::anneal(&turned, &CSpaces::new(&turned), &quick(4, 1));
    assert_eq!(a.layouts[0].nodes[0].block_name, "ell@180");
}

#[test]
fn rotations_turn_the_polygon_and_bad_angles_name_the_field() {
    let level = ell_and_square("rotations = [-90, 450]\n");
    let names: Vec<&str> = level.blocks.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["ell", "ell@270", "ell@90", "square"]);
    // (2, 0) turned by 90° is (0, 2); the polygon stays counter-clockwise.
    assert_eq!(level.blocks[2].polygon[1], [0.0, 2.0]);
    assert!(geometry::signed_area(&level.blocks[2].polygon) > 0.0);
    for (bad, why) in [("[45]", "multiple of 90"), ("[360]", "the block itself"), ("[90, -270]", "twice")] {
        let e = spec_error(&format!("door_width = 0.5\n{ELL}rotations = {bad}\n[[node]]\nname = \"a\"\n"));
        assert!(e.contains("block[0] (\"ell\").rotations") && e.contains(why), "{e}");
    }
}

fn complete(n: usize) -> Vec<(usize, usize)> {
    (0..n).flat_map(|a| (a + 1..n).map(move |b| (a, b))).collect()
}

#[test]
fn the_annealer_refuses_k5_and_k33_and_takes_planar_graphs() {
    let k33: Vec<(usize, usize)> = (0..3).flat_map(|a| (3..6).map(move |b| (a, b))).collect();
    // K3,3 has 9 edges on 6 nodes: within Euler's bound, yet not planar.
    for (name, edges, nodes) in [("K5", complete(5), 5), ("K3,3", k33, 6)] {
        assert!(!squares(0.3, nodes, &edges).is_planar(), "{name}");
        let dir = tempfile::tempdir().unwrap();
        let spec = dir.path().join("g.toml");
        let mut t = format!("door_width = 0.3\n{SQUARE}");
        for i in 0..nodes {
            t += &format!("[[node]]\nname = \"n{i}\"\n");
        }
        for (a, b) in &edges {
            t += &format!("[[edge]]\nnodes = [\"n{a}\", \"n{b}\"]\n");
        }
        std::fs::write(&spec, t).unwrap();
        let run = netspec().arg("level").arg(&spec).args(["--method", "anneal"]).output().unwrap();
        assert_eq!(run.status.code(), Some(1), "{name}");
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(err.contains("edge:") && err.contains("not planar"), "{name}: {err}");
    }
    // Planar: K4, K5 less an edge, the octahedron (3V − 6 edges), a 3 × 3 grid.
    let mut k5e = complete(5);
    k5e.pop();
    let octahedron: Vec<(usize, usize)> = complete(6).into_iter().filter(|&(a, b)| b != a + 3).collect();
    let grid: Vec<(usize, usize)> =
        (0..9).flat_map(|i| [(i % 3 < 2).then_some((i, i + 1)), (i < 6).then_some((i, i + 3))]).flatten().collect();
    for (nodes, edges) in [(4, complete(4)), (5, k5e), (6, octahedron), (9, grid)] {
        assert!(squares(0.3, nodes, &edges).is_planar(), "{edges:?}");
    }
}

#[test]
fn command_reports_the_variant_and_draws_obstacles() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("ell.toml");
    let text = format!(
        "door_width = 0.5\n{ELL}rotations = [90, 180, 270]\n{SQUARE}[[node]]\nname = \"l\"\nblocks = [\"ell\"]\n\
         position = [0, 0]\n[[node]]\nname = \"s\"\nblocks = [\"square\"]\nposition = [-2, -2]\n\
         [[edge]]\nnodes = [\"l\", \"s\"]\n[[obstacle]]\npolygon = [[1, 1], [3, 1], [3, 3], [1, 3]]\n"
    );
    std::fs::write(&spec, text).unwrap();
    let out = dir.path().join("out");
    let run = netspec().arg("level").arg(&spec).arg("--out").arg(&out).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("level.json")).unwrap()).unwrap();
    assert_eq!(json["status"], "feasible");
    assert_eq!(json["layouts"][0]["nodes"][0]["block_name"], "ell@180");
    let svg = std::fs::read_to_string(out.join("layout-1.svg")).unwrap();
    assert_eq!(svg.matches("<polygon").count(), 3, "two blocks and the obstacle");
    assert_eq!(svg.matches("class=\"obstacle\"").count(), 1);
    assert!(svg.contains("l (ell@180)"), "the label names the variant");
}

#[test]
fn seeds_give_a_summary_over_the_annealer_runs() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("star.toml");
    let mut text = format!("door_width = 0.6\n{SQUARE}[[node]]\nname = \"hub\"\n");
    for i in 0..4 {
        text += &format!("[[node]]\nname = \"leaf{i}\"\n[[edge]]\nnodes = [\"hub\", \"leaf{i}\"]\n");
    }
    std::fs::write(&spec, &text).unwrap();
    let out = dir.path().join("out");
    let args = ["--method", "anneal", "--seed", "5", "--seeds", "3", "--count", "2", "--out"];
    let run = netspec().arg("level").arg(&spec).args(args).arg(&out).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["method"], "anneal");
    assert_eq!(s["seeds"], 3);
    let seeds: Vec<u64> = s["runs"].as_array().unwrap().iter().map(|r| r["seed"].as_u64().unwrap()).collect();
    assert_eq!(seeds, [5, 6, 7]);
    // The 4-leaf star has layouts: every seed finds two.
    assert_eq!(s["success_count"], 1.0);
    assert_eq!(s["time_to_count"]["runs"], 3);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("| anneal | 3 | 1/1 | 2 |"), "{stdout}");
    // level.json and the pictures are the first seed's.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("level.json")).unwrap()).unwrap();
    assert_eq!(json["layouts"].as_array().unwrap().len(), 2);
    // The exact model has no seeds.
    let run = netspec().arg("level").arg(&spec).args(["--method", "milp", "--seeds", "2"]).output().unwrap();
    assert_eq!(run.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&run.stderr).contains("--seeds"));
}

#[test]
fn the_obstacles_example_reads() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/levels/obstacles.toml");
    let level = Level::read(&path).unwrap();
    let names: Vec<&str> = level.blocks.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["ell", "ell@90", "ell@180", "ell@270", "square", "bar", "bar@90"]);
    assert_eq!(level.obstacles.len(), 2);
    assert!(level.is_planar());
}

#[test]
fn chains_start_with_the_fixed_nodes_and_then_touch_what_is_laid_out() {
    // A path 0-1-2 with node 2 fixed, then a triangle 2-3-4 and a cycle 0-5-6-7 away from it.
    let mut t = format!("door_width = 0.3\n{SQUARE}");
    for i in 0..8 {
        t += &format!("[[node]]\nname = \"n{i}\"\n{}", if i == 2 { "position = [5, 5]\n" } else { "" });
    }
    for (a, b) in [(0, 1), (1, 2), (2, 3), (3, 4), (4, 2), (0, 5), (5, 6), (6, 7), (7, 0)] {
        t += &format!("[[edge]]\nnodes = [\"n{a}\", \"n{b}\"]\n");
    }
    let level = Level::from_toml(&t).unwrap();
    let c: Vec<Vec<u32>> = anneal::chains(&level).iter().map(|c| c.iter().map(|n| n.0).collect()).collect();
    assert_eq!(c[0], [2]);
    assert_eq!(c[1], [3, 4], "the triangle through the fixed node");
    let mut placed = vec![2, 3, 4];
    for chain in &c[2..] {
        let touches = chain.iter().any(|&n| {
            level.edges.iter().any(|&(a, b)| (a.0 == n && placed.contains(&b.0)) || (b.0 == n && placed.contains(&a.0)))
        });
        assert!(touches, "{chain:?} in {c:?}");
        placed.extend(chain);
    }
    assert_eq!(placed.len(), 8);
    let r = anneal::anneal(&level, &CSpaces::new(&level), &quick(2, 1));
    assert!(validate(&level, &r.layouts[0]).is_valid());
    assert_eq!(r.layouts[0].nodes[2].position, [5.0, 5.0]);
}

fn generated(family: &str, w: f64) -> Level {
    netspec::levels::generate::Generated::parse(family).unwrap().level(w).unwrap()
}

fn options(kind: SolverKind, time_limit: f64) -> ExactOptions {
    ExactOptions { solver: kind, time_limit, count: 1, threads: Some(1), explain: true, interrupt: None }
}

#[test]
fn a_grid_with_a_triangle_is_proven_infeasible_by_the_triangle_on_every_backend() {
    let level = generated("grid:4x4+triangle", 0.55);
    for kind in backends() {
        let r = exact::solve(&level, &CSpaces::new(&level), &options(kind, 60.0), &[]).unwrap();
        assert_eq!(r.status, ExactStatus::Infeasible, "{kind}");
        assert_eq!(r.route, exact::Route::Subgraph, "{kind}");
        let proof = r.screen.as_ref().and_then(|s| s.proof.as_ref()).expect("the subgraph");
        assert_eq!(proof.nodes, ["r0c0", "r0c1", "r1c1"], "{kind}");
        let c = r.conflict.expect("explained");
        let mut edges = c.edges.clone();
        edges.sort();
        assert_eq!(edges, [["r0c0", "r0c1"], ["r0c0", "r1c1"], ["r0c1", "r1c1"]].map(|e| e.map(String::from)));
        assert!(c.minimal, "{kind}");
    }
}

#[test]
fn a_ladder_and_a_grid_are_laid_out_incrementally_and_validated_on_every_backend() {
    for (family, kinds) in [("ladder:12", backends()), ("grid:5x5", vec![SolverKind::default_kind().unwrap()])] {
        let level = generated(family, 0.5);
        assert!(level.nodes.len() > exact::WHOLE_MAX_NODES || family.starts_with("grid"));
        for kind in kinds {
            let r = exact::solve(&level, &CSpaces::new(&level), &options(kind, 60.0), &[]).unwrap();
            assert_eq!(r.status, ExactStatus::Feasible, "{family} {kind}: {:?}", r.note);
            assert_eq!(r.route, exact::Route::Incremental, "{family} {kind}");
            let v = validate(&level, &r.layouts[0]);
            assert!(v.is_valid(), "{family} {kind}: {:?}", v.problems());
            let st = r.incremental.as_ref().unwrap();
            assert!(st.steps >= 2 && st.largest_step <= level.nodes.len(), "{st:?}");
        }
    }
}

#[test]
fn incremental_layouts_keep_fixed_nodes_and_give_more_layouts_by_the_last_step() {
    // A path of 30 with its first node fixed away from the origin: the route is incremental,
    // the fixed node stays where it is, and the last step gives two more layouts.
    let mut t = String::from("door_width = 0.5\n") + SQUARE;
    for i in 0..30 {
        t += &format!("[[node]]\nname = \"n{i}\"\n{}", if i == 0 { "position = [3, 4]\n" } else { "" });
    }
    for i in 1..30 {
        t += &format!("[[edge]]\nnodes = [\"n{}\", \"n{i}\"]\n", i - 1);
    }
    let level = Level::from_toml(&t).unwrap();
    let o = ExactOptions { count: 3, ..options(SolverKind::default_kind().unwrap(), 60.0) };
    let r = exact::solve(&level, &CSpaces::new(&level), &o, &[]).unwrap();
    assert_eq!(r.route, exact::Route::Incremental);
    assert_eq!(r.layouts.len(), 3, "{:?}", r.note);
    for l in &r.layouts {
        assert!(validate(&level, l).is_valid());
        assert_eq!(l.nodes[0].position, [3.0, 4.0]);
    }
    assert_ne!(r.layouts[0], r.layouts[1]);
    // A ladder's last step closes a square: fewer layouts than asked, and the note says why.
    let ladder = generated("ladder:12", 0.5);
    let r = exact::solve(&ladder, &CSpaces::new(&ladder), &o, &[]).unwrap();
    assert!(!r.layouts.is_empty());
    if r.layouts.len() < 3 {
        assert!(r.note.as_deref().is_some_and(|n| n.contains("last step")), "{:?}", r.note);
    }
}

#[test]
fn an_interrupt_returns_at_once_and_the_deadline_holds() {
    let level = generated("path:60", 0.5);
    let cs = CSpaces::new(&level);
    let kind = SolverKind::default_kind().unwrap();
    let stop = netspec::solvers::Interrupt::new();
    stop.trigger();
    let o = ExactOptions { interrupt: Some(stop), ..options(kind, 60.0) };
    let t = std::time::Instant::now();
    let r = exact::solve(&level, &cs, &o, &[]).unwrap();
    assert!(t.elapsed().as_secs_f64() < 10.0);
    assert_eq!(r.status, ExactStatus::Unknown);
    assert_eq!(r.note.as_deref(), Some("stopped"));
    // A tiny limit: no answer, the time limit named, back well within a few limits.
    let t = std::time::Instant::now();
    let r = exact::solve(&level, &cs, &options(kind, 0.05), &[]).unwrap();
    assert!(t.elapsed().as_secs_f64() < 5.0);
    assert!(r.note.as_deref().is_some_and(|n| n.contains("time limit")), "{:?}", r.note);
}
