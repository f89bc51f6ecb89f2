//! Room tiling (docs/formulation.md §4–§5): floor plans and game levels on small footprints, every
//! backend, the validator's item 6 on hand-built violations, infeasible tilings, bad specs.

use netspec::design::{self, GraphShape, Network, Violation};
use netspec::mesh::FaceId;
use netspec::milp::objectives_agree;
use netspec::pipeline;
use netspec::solvers::{SolveOptions, SolverKind, Termination};
use netspec::spec::{Problem, Spec};
use std::path::Path;

use crate::network::{backends as network_backends, problem};

/// Every compiled backend but the good_lp bridge (these room models are small enough for microlp).
fn backends() -> Vec<SolverKind> {
    network_backends(true)
}

/// Solves with every backend; each must prove optimality with a valid design, and all agree
/// on `expected`.
fn assert_all_optimal(p: &Problem, expected: f64) -> netspec::pipeline::DesignResult {
    let nm = pipeline::build(p);
    let mut last = None;
    for k in backends() {
        let r =
            pipeline::solve_built(p, &nm, k, &SolveOptions { time_limit: Some(60.0), ..Default::default() }).unwrap();
        assert_eq!(r.solve.termination, Termination::Optimal, "{k} on {}", p.spec.name);
        assert!(r.validity.valid, "{k} on {}: {:?}", p.spec.name, r.validity.design_violations);
        let obj = r.solve.objective.unwrap();
        assert!(objectives_agree(obj, expected, 1e-6), "{k} on {}: {obj}, expected {expected}", p.spec.name);
        last = Some(r);
    }
    last.unwrap()
}

const FLOORPLAN_4X4: &str = r#"
name = "floorplan4"
boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = [2]          # the entrance, bottom middle
[features]
dead_ends = "allow"
[rooms]
mode = "floorplan"
templates = [{ name = "office", shape = "rect 2x2" }]
"#;

#[test]
fn floorplan_four_offices_and_a_corridor() {
    // Four 2×2 offices; the shortest corridor touching all four runs up the middle from the
    // entrance: 3 edges.
    let r = assert_all_optimal(&problem(FLOORPLAN_4X4), 3.0);
    assert_eq!(r.network.unwrap().rooms.len(), 4);
}

#[test]
fn floorplan_with_room_type_counts() {
    let p = problem(&FLOORPLAN_4X4.replace(
        r#"templates = [{ name = "office", shape = "rect 2x2" }]"#,
        r#"templates = [{ name = "office", shape = "rect 2x2" }, { name = "lab", shape = "rect 2x1", exact = 2 }]"#,
    ));
    let r = assert_all_optimal(&p, 3.0);
    let net = r.network.unwrap();
    assert_eq!(net.rooms.len(), 5, "three offices and two labs tile 16 faces");
}

#[test]
fn game_level_circular() {
    // Four 2×2 blocks, one sink, no branches: the cycle through the four block centres and the
    // four shared boundary midpoints, 8 edges.
    let p = problem(
        r#"
name = "circular4"
boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = [7]
[rooms]
mode = "game"
level = "circular"
templates = [{ name = "block", shape = "rect 2x2" }]
"#,
    );
    let r = assert_all_optimal(&p, 8.0);
    let m = r.metrics.unwrap();
    assert_eq!((m.edges, m.junctions_3way, m.dead_ends), (8, 0, 0));
    let g = r.rooms.unwrap().block_graph.unwrap();
    assert_eq!((g.nodes.len(), g.edges.len(), g.shape), (4, 4, GraphShape::Cycle));
    assert!(g.to_dot("circular4").contains("b0 -- "));
}

#[test]
fn game_level_linear() {
    // Two boundary sinks under the two bottom blocks: the path must traverse all four blocks,
    // 8 edges, and the block graph is a path.
    let p = problem(
        r#"
name = "linear4"
boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = [1, 3]
[rooms]
mode = "game"
level = "linear"
templates = [{ name = "block", shape = "rect 2x2" }]
"#,
    );
    let r = assert_all_optimal(&p, 8.0);
    let g = r.rooms.unwrap().block_graph.unwrap();
    assert_eq!((g.nodes.len(), g.edges.len(), g.shape), (4, 3, GraphShape::Path));
}

#[test]
fn level_types_check_their_sinks() {
    let base = r#"
name = "x"
boundary = "wall"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = SINKS
[rooms]
mode = "MODE"
level = "LEVEL"
templates = [{ name = "block", shape = "rect 2x2" }]
"#;
    for (sinks, mode, level, needle) in [
        ("[1, 3]", "game", "circular", "exactly one sink"),
        ("[7]", "game", "linear", "two sinks"),
        ("[1, 7]", "game", "linear", "two sinks"),
        ("[1]", "floorplan", "circular", "rooms.level"),
    ] {
        let toml = base.replace("SINKS", sinks).replace("MODE", mode).replace("LEVEL", level);
        let e = Spec::from_toml(&toml).and_then(|s| s.resolve(Path::new("."))).unwrap_err().to_string();
        assert!(e.contains(needle), "{sinks} {mode} {level}: {e}");
    }
}

#[test]
fn infeasible_tiling_is_a_result() {
    // 25 faces cannot be tiled by 4-face rooms.
    let p = problem(&FLOORPLAN_4X4.replace("width = 4, height = 4", "width = 5, height = 5"));
    let nm = pipeline::build(&p);
    for k in backends() {
        let r = pipeline::solve_built(&p, &nm, k, &SolveOptions::default()).unwrap();
        assert_eq!(r.solve.termination, Termination::Infeasible, "{k}");
        assert!(r.network.is_none());
    }
}

#[test]
fn validator_item_6_on_hand_built_violations() {
    let p = problem(FLOORPLAN_4X4);
    let nm = pipeline::build(&p);
    let pls = &nm.placements.as_ref().unwrap().placements;
    let find =
        |faces: &[u32]| pls.iter().position(|pl| pl.faces.iter().map(|f| f.0).collect::<Vec<_>>() == faces).unwrap();
    // Faces are numbered row by row (4 per row).
    let (a, b, c, d) = (find(&[0, 1, 4, 5]), find(&[2, 3, 6, 7]), find(&[8, 9, 12, 13]), find(&[10, 11, 14, 15]));
    let overlap = find(&[1, 2, 5, 6]);
    let edge = |u: u32, v: u32| {
        p.mesh.he_edge(p.mesh.half_edge_between(netspec::mesh::VertexId(u), netspec::mesh::VertexId(v)).unwrap())
    };
    // A corridor up the middle (vertices 2-7-12-17, grid vertex id = 5·row + col).
    let corridor = [edge(2, 7), edge(7, 12), edge(12, 17)];
    let mut net = Network::from_edges(&p, &corridor);
    net.rooms = vec![a, b, c, d];
    assert!(design::validate_rooms(&p, &net, pls, &net.rooms).is_empty());
    // Overlap and a gap.
    net.rooms = vec![a, overlap, c, d];
    let v = design::validate_rooms(&p, &net, pls, &net.rooms);
    assert!(v.contains(&Violation::Cover { face: FaceId(1), rooms: 2 }), "{v:?}");
    assert!(v.contains(&Violation::Cover { face: FaceId(3), rooms: 0 }), "{v:?}");
    // A corridor inside a room (edge 6-7 lies inside room a).
    net.rooms = vec![a, b, c, d];
    let net2 = Network {
        rooms: net.rooms.clone(),
        ..Network::from_edges(&p, &[edge(2, 7), edge(7, 12), edge(12, 17), edge(6, 7)])
    };
    let v = design::validate_rooms(&p, &net2, pls, &net2.rooms);
    assert!(v.iter().any(|v| matches!(v, Violation::Room { placement, .. } if *placement == a)), "{v:?}");
    // A room with no corridor along it.
    let net3 = Network { rooms: net.rooms.clone(), ..Network::from_edges(&p, &[edge(2, 7)]) };
    let v = design::validate_rooms(&p, &net3, pls, &net3.rooms);
    assert!(
        v.iter().any(
            |v| matches!(v, Violation::Room { placement, detail } if *placement == c && detail.contains("no corridor"))
        ),
        "{v:?}"
    );
}

#[test]
fn named_shapes() {
    let p = problem(&FLOORPLAN_4X4.replace(
        r#"templates = [{ name = "office", shape = "rect 2x2" }]"#,
        r#"templates = [{ name = "t", shape = "T 3x2" }, { name = "l", shape = "L 3x2" }, { name = "r", shape = "rect 3x1" }]"#,
    ));
    let t = &p.rooms.as_ref().unwrap().templates;
    assert_eq!(t[0].cells, vec![(0, 1), (1, 0), (1, 1), (2, 1)]);
    assert_eq!((t[0].cells.len(), t[1].cells.len(), t[2].cells.len()), (4, 4, 3));
    assert_eq!(t[0].images().len(), 4, "a T has four rotations and is its own mirror image");
}

#[test]
fn bad_room_specs_name_the_field() {
    for (bad, needle) in [
        (r#"templates = [{ name = "x", shape = "hexagon 2x2" }]"#, "rooms.templates[0].shape"),
        (r#"templates = [{ name = "x", shape = "rect 2x2", exact = 1, min = 1 }]"#, "rooms.templates[0]"),
        (r#"templates = [{ name = "x", cells = [[0, 0], [0, 0]] }]"#, "rooms.templates[0].cells"),
        (r#"templates = []"#, "rooms.templates"),
        (r#"templates = [{ name = "x", shape = "T 2x2" }]"#, "rooms.templates[0].shape"),
    ] {
        let toml = FLOORPLAN_4X4.replace(r#"templates = [{ name = "office", shape = "rect 2x2" }]"#, bad);
        let e = Spec::from_toml(&toml).and_then(|s| s.resolve(Path::new("."))).unwrap_err().to_string();
        assert!(e.contains(needle), "{bad}: {e}");
    }
}

#[test]
fn paper_examples_resolve_and_build() {
    // The reconstructions of Fig. 9b1–b4, 1d, 1e, 11a, 11b: sizes near the paper's, models build
    // (solving them is benchmark work, not test work).
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    for (name, lo, hi) in [
        ("fig9b1", 500, 540),
        ("fig9b2", 500, 540),
        ("fig9b3", 500, 540),
        ("fig9b4", 500, 540),
        ("fig1d", 980, 1040),
        ("fig1e", 650, 790),
        ("fig11a", 650, 790),
        ("fig11b", 650, 790),
    ] {
        let path = dir.join(format!("{name}.toml"));
        let p = Spec::load(&path).unwrap().resolve(&dir).unwrap_or_else(|e| panic!("{name}: {e}"));
        let edges = p.mesh.num_edges();
        assert!((lo..=hi).contains(&edges), "{name}: {edges} edges");
        let nm = pipeline::build(&p);
        let rm = nm.placements.as_ref().unwrap();
        assert!(!rm.truncated && rm.per_template.iter().all(|&n| n > 0), "{name}: {:?}", rm.per_template);
        nm.model.validate().unwrap();
    }
}

#[derive(serde::Serialize)]
struct RoomSnapshot {
    objective: f64,
    valid: bool,
    rooms: usize,
    block_graph: Option<GraphShape>,
    families: indexmap::IndexMap<String, netspec::formulations::expr::FamilyStats>,
}

/// 6×6 footprints with 2×2 and 3×2 templates: a floor plan, a circular and a linear level. Every
/// backend but microlp (minutes on these) must prove the same optimum.
fn six_by_six(name: &str, sinks: &str, dead_ends: &str, mode: &str, level: &str) -> RoomSnapshot {
    let p = problem(&format!(
        r#"
name = "{name}"
boundary = "wall"
formulation = "tight"
[mesh]
grid = {{ width = 6, height = 6 }}
[sinks]
vertices = {sinks}
[features]
dead_ends = "{dead_ends}"
[rooms]
mode = "{mode}"
{level}
templates = [{{ name = "room", shape = "rect 2x2" }}, {{ name = "hall", shape = "rect 3x2" }}]
"#
    ));
    let nm = pipeline::build(&p);
    let mut objs = Vec::new();
    let mut first = None;
    for k in backends().into_iter().filter(|k| *k != SolverKind::Microlp) {
        let r =
            pipeline::solve_built(&p, &nm, k, &SolveOptions { time_limit: Some(60.0), ..Default::default() }).unwrap();
        assert_eq!(r.solve.termination, Termination::Optimal, "{k} on {name}");
        assert!(r.validity.valid, "{k} on {name}: {:?}", r.validity.design_violations);
        objs.push(r.solve.objective.unwrap());
        first.get_or_insert(r);
    }
    assert!(objs.windows(2).all(|w| objectives_agree(w[0], w[1], 1e-6)), "{name}: {objs:?}");
    let r = first.unwrap();
    let rooms = r.rooms.unwrap();
    RoomSnapshot {
        objective: (objs[0] * 1e4).round() / 1e4,
        valid: r.validity.valid,
        rooms: rooms.chosen.len(),
        block_graph: rooms.block_graph.map(|g| g.shape),
        families: r.families,
    }
}

#[test]
fn snapshot_floorplan_6x6() {
    insta::assert_yaml_snapshot!("floorplan_6x6", six_by_six("floorplan6", "[3]", "allow", "floorplan", ""));
}

#[test]
fn snapshot_circular_6x6() {
    insta::assert_yaml_snapshot!(
        "circular_6x6",
        six_by_six("circular6", "[10]", "forbid", "game", "level = \"circular\"")
    );
}

#[test]
fn snapshot_linear_6x6() {
    insta::assert_yaml_snapshot!(
        "linear_6x6",
        six_by_six("linear6", "[1, 47]", "forbid", "game", "level = \"linear\"")
    );
}

#[test]
fn snapshot_branching_6x6() {
    insta::assert_yaml_snapshot!(
        "branching_6x6",
        six_by_six("branching6", "[3]", "forbid", "game", "level = \"branching\"")
    );
}

/// A strip, made small: a linear level between two boundary sinks with two block
/// shapes and zig-zags penalised.
const STRIP: &str = r#"
name = "strip"
boundary = "wall"
[mesh]
grid = { width = 8, height = 6, spacing = 1.0 }
[sinks]
points = [[0, 2], [8, 2]]
[weights]
length = 1
zigzag = 5
too_close = "forbid"
[rooms]
mode = "game"
level = "linear"
templates = [
  { name = "room", shape = "rect 2x2" },
  { name = "hall", shape = "rect 3x2" },
]
"#;

/// Solves with every backend: each proves optimality, the design is valid (so the block graph
/// has the level's shape), and all agree on the optimum.
fn assert_level(p: &Problem, shape: GraphShape) {
    let nm = pipeline::build(p);
    let mut objs = Vec::new();
    for k in backends() {
        let r =
            pipeline::solve_built(p, &nm, k, &SolveOptions { time_limit: Some(60.0), ..Default::default() }).unwrap();
        assert_eq!(r.solve.termination, Termination::Optimal, "{k} on {}", p.spec.name);
        assert!(r.validity.valid, "{k} on {}: {:?}", p.spec.name, r.validity.design_violations);
        let g = r.rooms.as_ref().unwrap().block_graph.as_ref().unwrap();
        assert_eq!(g.shape, shape, "{k} on {}", p.spec.name);
        objs.push(r.solve.objective.unwrap());
    }
    assert!(objs.windows(2).all(|w| objectives_agree(w[0], w[1], 1e-6)), "{}: {objs:?}", p.spec.name);
}

#[test]
fn linear_level_with_dead_ends_allowed_is_refused() {
    let spec = Spec::from_toml(&STRIP.replace("[rooms]", "[features]\ndead_ends = \"allow\"\n[rooms]")).unwrap();
    let e = spec.resolve(Path::new(".")).unwrap_err().to_string();
    assert!(e.contains("features.dead_ends") && e.contains("rooms.level") && e.contains("linear"), "{e}");
}

#[test]
fn linear_level_is_one_path_through_every_block() {
    assert_level(&problem(STRIP), GraphShape::Path);
}

#[test]
fn circular_level_with_dead_ends_allowed_is_refused_and_otherwise_a_cycle() {
    let circular = STRIP
        .replace("level = \"linear\"", "level = \"circular\"")
        .replace("points = [[0, 2], [8, 2]]", "points = [[4, 3]]");
    let spec = Spec::from_toml(&circular.replace("[rooms]", "[features]\ndead_ends = \"allow\"\n[rooms]")).unwrap();
    let e = spec.resolve(Path::new(".")).unwrap_err().to_string();
    assert!(e.contains("features.dead_ends") && e.contains("circular"), "{e}");
    assert_level(&problem(&circular), GraphShape::Cycle);
}

/// The strong recipe's level rows (two inner edges per traversed block where implied, two
/// crossings per block without a sink) cut off no design: on the linear and the circular strip
/// it proves the paper recipe's optimum, and the rows are in its model.
#[test]
fn strong_level_rows_keep_the_paper_optimum() {
    let circular = STRIP
        .replace("level = \"linear\"", "level = \"circular\"")
        .replace("points = [[0, 2], [8, 2]]", "points = [[4, 3]]");
    for spec in [STRIP.to_string(), circular] {
        let mut objs = Vec::new();
        for recipe in ["paper", "strong"] {
            let p = problem(&spec.replace("[mesh]", &format!("formulation = \"{recipe}\"\n[mesh]")));
            let nm = pipeline::build(&p);
            let enter_rows = nm.model.rows().filter(|r| r.name.starts_with("levelenter_")).count();
            assert_eq!(enter_rows > 0, recipe == "strong", "{recipe}: {enter_rows} levelenter rows");
            let r = pipeline::solve_built(
                &p,
                &nm,
                SolverKind::Highs,
                &SolveOptions { time_limit: Some(60.0), ..Default::default() },
            )
            .unwrap();
            assert_eq!(r.solve.termination, Termination::Optimal, "{recipe} on {}", p.spec.name);
            assert!(r.validity.valid, "{recipe} on {}: {:?}", p.spec.name, r.validity.design_violations);
            objs.push(r.solve.objective.unwrap());
        }
        assert!(objectives_agree(objs[0], objs[1], 1e-6), "paper and strong optima differ: {objs:?}");
    }
}

/// The picture tells room types apart (each room marked with its type's letter, A, B, …) and its
/// legend lists only what is drawn: the types used, the sink, no p2p sample, obstacle or route.
#[test]
fn picture_marks_room_types_and_lists_what_is_drawn() {
    let p = problem(&FLOORPLAN_4X4.replace(
        r#"templates = [{ name = "office", shape = "rect 2x2" }]"#,
        r#"templates = [{ name = "office", shape = "rect 2x2" }, { name = "lab", shape = "rect 2x1", exact = 2 }, { name = "hall", shape = "rect 3x3", max = 0 }]"#,
    ));
    let nm = pipeline::build(&p);
    let r = pipeline::solve_built(
        &p,
        &nm,
        SolverKind::default_kind().unwrap(),
        &SolveOptions { time_limit: Some(60.0), ..Default::default() },
    )
    .unwrap();
    let net = r.network.unwrap();
    let placements = &nm.placements.as_ref().unwrap().placements;
    let svg = netspec::design::picture::network_svg(
        &p,
        &net,
        None,
        Some(placements),
        &netspec::render::Caption { name: "a \"quoted\" <plan>".into(), ..Default::default() },
    );
    assert_eq!(svg.matches(r#"class="room-type""#).count(), 5, "{svg}");
    let letter = |l: &str| svg.matches(&format!(">{l}</text>")).count();
    // Three offices (A) and two labs (B), each letter once more in the legend; no hall (C).
    assert_eq!((letter("A"), letter("B"), letter("C")), (4, 3, 0), "{svg}");
    assert!(svg.contains(">office</text>") && svg.contains(">lab</text>") && !svg.contains(">hall</text>"), "{svg}");
    assert!(
        svg.contains(">sink</text>")
            && !svg.contains("p2p sample")
            && !svg.contains(">obstacle<")
            && !svg.contains("forced / route"),
        "{svg}"
    );
    assert!(svg.contains("a &quot;quoted&quot; &lt;plan&gt;"), "{svg}");
    netspec::render::png(&svg).unwrap();
}

/// Every floor plan and game level a spec can ask for builds a valid model: generated grids,
/// modes, level types, template shapes and counts, and sinks (on the boundary, as many as the
/// level type takes, or any), under every recipe — each emitted model passes the MILP validator
/// (no repeated variable in a row, finite coefficients, bounds in order). A spec resolution may
/// refuse a contradiction, with an error; most generated specs resolve.
#[test]
fn every_generated_tiling_builds_a_valid_model() {
    use netspec::formulations::{build_with, Recipe};
    use netspec::spec::RecipeName;
    const SHAPES: &[&str] = &["rect 1x1", "rect 2x1", "rect 2x2", "rect 3x2", "L 2x2", "L 3x2", "L 3x3", "rect 3x3"];
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = |n: u64| {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 33) % n
    };
    let (mut built, cases) = (0, 160);
    for _ in 0..cases {
        let (w, h) = (2 + next(5), 2 + next(5));
        let game = next(2) == 0;
        let level = next(4) as usize;
        let templates: Vec<String> = (0..1 + next(3))
            .map(|i| format!("{{ name = \"t{i}\", shape = \"{}\", max = {} }}", SHAPES[next(8) as usize], 1 + next(5)))
            .collect();
        // Bottom-row vertices are on the boundary; a linear level takes two sinks, a circular one.
        let want = match (game, level) {
            (true, 2) => 2,
            (true, 3) => 1,
            _ => 1 + next(2),
        };
        let mut sinks: Vec<u64> = (0..want).map(|_| next(w + 1)).collect();
        sinks.dedup();
        let level = if game {
            ["", "level = \"branching\"\n", "level = \"linear\"\n", "level = \"circular\"\n"][level]
        } else {
            ""
        };
        let text = format!(
            "name = \"gen\"\nboundary = \"wall\"\n[mesh]\ngrid = {{ width = {w}, height = {h} }}\n[sinks]\nvertices = {sinks:?}\n[rooms]\nmode = \"{}\"\n{level}max_placements = 2000\ntemplates = [{}]\n",
            if game { "game" } else { "floorplan" },
            templates.join(", ")
        );
        let spec = Spec::from_toml(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        let Ok(p) = spec.resolve(Path::new(".")) else { continue };
        built += 1;
        for name in RecipeName::ALL {
            let f = build_with(&p, &Recipe::named(name));
            assert!(f.model.validate().is_ok(), "{name}: {:?}\n{text}", f.model.validate());
        }
    }
    assert!(built >= cases / 2, "only {built} of {cases} generated specs resolved");
}

/// A circular game level with L-shaped blocks: an inner edge with both ends on a block's
/// boundary is counted twice in the block's crossing row, as one term with coefficient 2; the
/// model is valid and every backend that proves it agrees.
#[test]
fn circular_level_with_l_blocks_builds_and_solves() {
    let p = problem(
        r#"
name = "game"
boundary = "wall"
[mesh]
grid = { width = 6, height = 6 }
[sinks]
vertices = [3]
[rooms]
mode = "game"
level = "circular"
max_placements = 1000
templates = [ { name = "b", shape = "L 3x2", max = 2 } ]
"#,
    );
    let f = pipeline::build(&p);
    f.model.validate().unwrap();
    let r = pipeline::solve_built(
        &p,
        &f,
        SolverKind::Highs,
        &SolveOptions { time_limit: Some(30.0), ..Default::default() },
    )
    .unwrap();
    assert!(matches!(r.solve.termination, Termination::Optimal | Termination::Infeasible), "{}", r.solve.status_line());
    assert!(r.network.is_none() || r.validity.valid, "{:?}", r.validity);
}

/// The tilings' rows of docs/formulation.md §8.11, `roomlen` (`room_length`, on in `strong`) and
/// `roomreach_f…` (`room_reach`, on in no recipe): on a game level and a floor plan the strong
/// recipe's root LP with both rises above its value with neither, and both prove the same
/// optimum with a valid design; `paper` and `tight` write neither.
#[test]
fn room_rows_lift_the_relaxation_and_keep_the_optimum() {
    use netspec::formulations::{build_with, Formulation, Recipe};
    use netspec::spec::{switch, RecipeName};
    let highs = SolverKind::Highs.instance().unwrap();
    let one_thread = SolveOptions { threads: Some(1), ..SolveOptions::default() };
    let lp = |f: &Formulation| {
        netspec::solvers::lazy::lp_bound(highs.as_ref(), &f.model, None, &one_thread).unwrap().plain.unwrap()
    };
    for (mode, dead_ends) in [("mode = \"game\"\nlevel = \"branching\"", "allow"), ("mode = \"floorplan\"", "forbid")] {
        let p = problem(&format!(
            "name = \"length\"\nboundary = \"wall\"\nformulation = \"strong\"\n[mesh]\ngrid = {{ width = 6, height = 6 }}\n[sinks]\nvertices = [3]\n[features]\ndead_ends = \"{dead_ends}\"\n[rooms]\n{mode}\ntemplates = [{{ name = \"room\", shape = \"rect 2x2\" }}, {{ name = \"hall\", shape = \"rect 3x2\" }}]\n"
        ));
        let strong = pipeline::build(&p);
        assert!(strong.recipe.on(&switch::ROOM_LENGTH) && !strong.recipe.on(&switch::ROOM_REACH));
        let with = build_with(&p, &strong.recipe.with(&switch::ROOM_REACH, true));
        let without = build_with(&p, &strong.recipe.with(&switch::ROOM_LENGTH, false));
        let rows = |f: &Formulation| {
            let named = |prefix: &str| f.model.rows().filter(|r| r.name.starts_with(prefix)).count();
            (named("roomlen"), named("roomreach_f"))
        };
        // One length row; on the floor plan a reach row per face (36).
        let reach = if mode.contains("floorplan") { 36 } else { 0 };
        assert_eq!((rows(&with), rows(&without)), ((1, reach), (0, 0)), "{mode}");
        for name in [RecipeName::Paper, RecipeName::Tight] {
            assert_eq!(rows(&build_with(&p, &Recipe::named(name))), (0, 0), "{mode}: {name}");
        }
        let (b_with, b_without) = (lp(&with), lp(&without));
        assert!(b_with > 1.1 * b_without, "{mode}: LP bound with {b_with}, without {b_without}");
        let mut optima = Vec::new();
        for f in [&with, &without] {
            let r = pipeline::solve_built(
                &p,
                f,
                SolverKind::Highs,
                &SolveOptions { time_limit: Some(60.0), ..Default::default() },
            )
            .unwrap();
            assert_eq!(r.solve.termination, Termination::Optimal, "{mode}: {}", f.recipe.label);
            assert!(r.validity.valid, "{mode}: {:?}", r.validity.design_violations);
            optima.push(r.solve.objective.unwrap());
        }
        assert!(objectives_agree(optima[0], optima[1], 1e-6), "{mode}: {optima:?}");
        assert!(b_with <= optima[0] + 1e-6, "{mode}: bound {b_with} above the optimum {}", optima[0]);
    }
}
