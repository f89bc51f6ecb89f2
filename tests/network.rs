//! The network IP on small grids: every feature, every backend that proves optimality, exact
//! objectives in snapshots, the independent validator on hand-built bad networks, and clear
//! errors for bad or infeasible specs.

use netspec::design::{self, Network, Violation};
use netspec::formulations;
use netspec::mesh::{EdgeId, VertexId};
use netspec::milp::objectives_agree;
use netspec::pipeline;
use netspec::solvers::{SolveOptions, Solver, SolverKind, Termination};
use netspec::spec::{switch, EdgeRole, PathForm, Problem, RecipeName, Spec, SpecErrorKind};
use serde::Serialize;
use std::path::Path;

/// Parses and resolves an inline TOML spec (shared by the room tests).
pub fn problem(toml: &str) -> Problem {
    Spec::from_toml(toml).unwrap_or_else(|e| panic!("{e}")).resolve(Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// Backends for small network models. microlp is a plain branch and bound: it is given only the
/// specs marked `small` (it takes minutes on the others).
pub fn backends(small: bool) -> Vec<SolverKind> {
    SolverKind::compiled()
        .into_iter()
        .filter(|k| *k != SolverKind::GoodLp && (small || *k != SolverKind::Microlp))
        .collect()
}

#[derive(Serialize)]
struct Snapshot {
    objective: f64,
    solved_by: Vec<String>,
    valid: bool,
    design_violations: Vec<String>,
    edges: usize,
    length: f64,
    families: indexmap::IndexMap<String, netspec::formulations::expr::FamilyStats>,
}

/// Solves with every backend, asserts each proves optimality with a valid design, that all
/// agree, and returns the snapshot record.
fn solve_all(p: &Problem, small: bool) -> Snapshot {
    let nm = pipeline::build(p);
    let mut objs: Vec<(SolverKind, f64)> = Vec::new();
    let mut first = None;
    for k in backends(small) {
        let o = SolveOptions { time_limit: Some(60.0), ..Default::default() };
        let r = pipeline::solve_built(p, &nm, k, &o).unwrap_or_else(|e| panic!("{}: {e}", p.spec.name));
        assert_eq!(r.solve.termination, Termination::Optimal, "{k} on {}", p.spec.name);
        assert!(
            r.validity.valid,
            "{k} on {}: {:?} {:?}",
            p.spec.name,
            r.validity.design_violations,
            r.validity.milp_check.as_ref().map(|c| &c.violations)
        );
        objs.push((k, r.solve.objective.unwrap()));
        first.get_or_insert(r);
    }
    for w in objs.windows(2) {
        assert!(objectives_agree(w[0].1, w[1].1, 1e-6), "{}: backends disagree {objs:?}", p.spec.name);
    }
    // Every recipe has the same optimum (the distance term means the same in all of them), and
    // the design's own objective equals it at the optimum. `strong` is also solved by SCIP
    // (cutsets in its branch and cut) and by HiGHS (the solve–cut–resolve loop).
    let expected = objs[0].1;
    for recipe in RecipeName::ALL {
        let f = formulations::build_with(p, &formulations::Recipe::named(recipe));
        let kinds: &[SolverKind] =
            if recipe == RecipeName::Strong { &[SolverKind::Highs, SolverKind::Scip] } else { &[SolverKind::Highs] };
        for &k in kinds.iter().filter(|k| k.is_compiled()) {
            let o = SolveOptions { time_limit: Some(60.0), ..Default::default() };
            let r = pipeline::solve_built(p, &f, k, &o).unwrap_or_else(|e| panic!("{recipe} {k}: {e}"));
            assert_eq!(r.solve.termination, Termination::Optimal, "{recipe} {k} on {}", p.spec.name);
            assert!(r.validity.valid, "{recipe} {k} on {}: {:?}", p.spec.name, r.validity);
            let got = r.solve.objective.unwrap();
            assert!(
                objectives_agree(got, expected, 1e-6),
                "{}: {recipe} on {k} gives {got}, expected {expected}",
                p.spec.name
            );
            let design = r.objective.as_ref().unwrap().total;
            assert!(
                objectives_agree(design, expected, 1e-6),
                "{}: {recipe} on {k}: design objective {design}, solver {expected}",
                p.spec.name
            );
        }
    }
    let r = first.unwrap();
    let m = r.metrics.unwrap();
    Snapshot {
        objective: (objs[0].1 * 1e4).round() / 1e4,
        solved_by: objs.iter().map(|(k, _)| k.name().to_string()).collect(),
        valid: r.validity.valid,
        design_violations: r.validity.design_violations.iter().map(|v| v.to_string()).collect(),
        edges: m.edges,
        length: (m.length * 1e4).round() / 1e4,
        families: r.families,
    }
}

const BASE: &str = r#"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
all_boundary = true
"#;

fn spec(name: &str, body: &str) -> String {
    format!("name = \"{name}\"\n{body}")
}

macro_rules! network_case {
    ($name:ident, $small:expr, $toml:expr) => {
        #[test]
        fn $name() {
            let p = problem(&spec(stringify!($name), $toml));
            insta::assert_yaml_snapshot!(stringify!($name), solve_all(&p, $small));
        }
    };
}

network_case!(grid4_wall_length_paper, true, &format!("boundary = \"wall\"\nformulation = \"paper\"\n{BASE}"));
network_case!(grid4_wall_length_tight, true, &format!("boundary = \"wall\"\nformulation = \"tight\"\n{BASE}"));
network_case!(
    grid4_road_distance,
    true,
    r#"boundary = "road"
formulation = "tight"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
all_boundary = true
[coverage]
range = 1
[weights]
length = 0
distance = 1
"#
);
network_case!(
    grid5_two_sinks_no_branches,
    false,
    r#"boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 5, height = 5 }
[sinks]
vertices = [2, 32]
[features]
branches = "forbid"
"#
);
network_case!(
    grid5_local_features_forbidden,
    false,
    r#"boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 5, height = 5 }
[sinks]
all_boundary = true
[weights]
length = 1
zigzag = "forbid"
too_close = "forbid"
t_junction = "forbid"
"#
);
network_case!(
    grid4_local_features_penalised,
    true,
    r#"boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
all_boundary = true
[weights]
length = 1
zigzag = 5
too_close = 2
t_junction = 3
"#
);
network_case!(
    grid4_point_to_point,
    false,
    r#"boundary = "wall"
formulation = "paper"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
all_boundary = true
[weights]
length = 1
[point_to_point]
blocks = 2
seed = 3
"#
);
network_case!(
    grid6_user_specs,
    false,
    r#"boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 6, height = 6 }
[sinks]
all_boundary = true
[user]
obstacle_faces = [14, 15]
obstacle_vertices = [33]
forced_edges = [[12, 19]]
forced_vertices = [40]
through_routes = [{ from = [3, 0], to = [3, 6] }]
"#
);
network_case!(
    grid3_euclidean_dead_ends_allowed,
    true,
    r#"boundary = "candidate"
formulation = "tight"
[mesh]
grid = { width = 3, height = 3 }
jitter = { amount = 0.2, seed = 4 }
[sinks]
points = [[0, 0], [3, 3]]
[coverage]
range = 1.5
model = "euclidean"
[features]
dead_ends = "allow"
"#
);
network_case!(
    clipped_l_shape,
    false,
    r#"boundary = "wall"
formulation = "tight"
[mesh]
clipped = { outer = [[0, 0], [6, 0], [6, 3], [3, 3], [3, 6], [0, 6]], spacing = 1 }
[sinks]
all_boundary = true
[weights]
length = 1
distance = 0.1
"#
);

#[test]
fn exported_lp_of_a_tiny_instance() {
    let p = problem(&spec(
        "tiny",
        r#"boundary = "wall"
formulation = "paper"
[mesh]
grid = { width = 2, height = 2 }
[sinks]
all_boundary = true
[weights]
zigzag = 5
too_close = "forbid"
t_junction = 1
"#,
    ));
    let nm = pipeline::build(&p);
    let mut text = Vec::new();
    netspec::io::lp::write(&nm.model, &mut text, &Default::default()).unwrap();
    insta::assert_snapshot!("tiny_lp", String::from_utf8(text).unwrap());
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    enc.write_all(bytes).unwrap();
    enc.finish().unwrap()
}

fn gunzip(bytes: &[u8]) -> Vec<u8> {
    use std::io::Read;
    let mut out = Vec::new();
    flate2::read::GzDecoder::new(bytes).read_to_end(&mut out).unwrap();
    out
}

#[test]
fn fig2_models_export_and_read_back() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    for f in ["a", "b", "c", "d", "e", "f", "g"] {
        let spec_path = dir.join(format!("models/fig2{f}.toml"));
        let spec = Spec::load(&spec_path).unwrap();
        let p = spec.resolve(spec_path.parent().unwrap()).unwrap();
        assert_eq!(p.mesh.num_edges(), 312, "Fig. 2 meshes have the paper's 312 edges");
        // The paper's own recipe: these fixtures pin its rows, names and order byte for byte.
        let nm = formulations::build_with(&p, &formulations::Recipe::named(RecipeName::Paper));
        let fixture = dir.join(format!("fixtures/fig2/fig2{f}.mps.gz"));
        // The committed fixture, unpacked, must equal what we emit now (byte for byte), and read
        // back through the gzip reader.
        let mut now = Vec::new();
        netspec::io::mps::write(&nm.model, &mut now, &Default::default()).unwrap();
        let committed = std::fs::read(&fixture).map(|b| gunzip(&b)).unwrap_or_default();
        if committed != now {
            if std::env::var_os("NETSPEC_BLESS").is_some() {
                std::fs::create_dir_all(fixture.parent().unwrap()).unwrap();
                std::fs::write(&fixture, gzip(&now)).unwrap();
            } else {
                panic!("{} is stale: rerun with NETSPEC_BLESS=1", fixture.display());
            }
        }
        let back = netspec::io::read_model_file(&fixture).unwrap().model;
        assert_eq!(back.stats(), nm.model.stats(), "fig2{f}");
    }
}

#[test]
fn infeasible_spec_is_a_result() {
    // One sink in a corner, a wall boundary, no branches, coverage 1 on a 6×6 grid: a single
    // path cannot come within one edge of every vertex.
    let p = problem(&spec(
        "infeasible",
        r#"boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 6, height = 6 }
[sinks]
vertices = [0]
[coverage]
range = 1
[features]
branches = "forbid"
"#,
    ));
    let nm = pipeline::build(&p);
    for k in backends(false) {
        let r = pipeline::solve_built(&p, &nm, k, &SolveOptions::default()).unwrap();
        assert_eq!(r.solve.termination, Termination::Infeasible, "{k}");
        assert!(r.network.is_none() && !r.validity.valid);
    }
}

fn spec_error(toml: &str) -> String {
    match Spec::from_toml(toml).and_then(|s| s.resolve(Path::new("."))) {
        Ok(_) => panic!("accepted: {toml}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_specs_name_the_field() {
    let cases: &[(&str, &str)] = &[
        ("name = \"x\"\nbogus = 1\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nall_boundary = true", "bogus"),
        ("name = \"x\"\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nvertices = [99]", "sinks.vertices[0]"),
        ("name = \"x\"\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nall_boundary = true\n[coverage]\nrange = 0.5", "coverage.range"),
        (
            "name = \"x\"\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nall_boundary = true\n[user]\nforced_edges = [[0, 1]]\nobstacle_edges = [[0, 1]]",
            "user.forced_edges[0]",
        ),
        ("name = \"x\"\nboundary = \"road\"\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nvertices = [4]", "sinks"),
        ("name = \"x\"\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nall_boundary = true\n[weights]\nlength = \"forbid\"", "weights.length"),
        ("name = \"x\"\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nall_boundary = true\n[user]\nforced_edges = [[0, 4]]", "not joined"),
        ("name = \"x\"\n[mesh]\n[sinks]\nall_boundary = true", "mesh"),
        // Found by the fuzzing campaign: positions beyond f64, and cells too small to tell apart.
        ("name = \"x\"\n[mesh]\ngrid = { width = 3, height = 3, spacing = 1e308 }\n[sinks]\nall_boundary = true", "mesh.grid"),
        ("name = \"x\"\n[mesh]\ngrid = { width = 3, height = 3, spacing = 4.9e-324 }\n[sinks]\nall_boundary = true", "mesh.grid"),
    ];
    for (toml, needle) in cases {
        let msg = spec_error(toml);
        assert!(msg.contains(needle), "error for {toml:?} should mention {needle:?}: {msg}");
    }
    // TOML syntax errors carry the line.
    let e = Spec::from_toml("name = \"x\"\n[mesh\n").unwrap_err();
    assert!(matches!(e, SpecErrorKind::Toml(ref m) if m.contains("line 2")), "{e}");
}

fn edges_between(p: &Problem, pairs: &[(u32, u32)]) -> Vec<EdgeId> {
    pairs.iter().map(|&(a, b)| p.mesh.he_edge(p.mesh.half_edge_between(VertexId(a), VertexId(b)).unwrap())).collect()
}

/// A 4×4 grid (vertex id = 5·row + col) with a wall boundary and all boundary vertices sinks.
fn grid4() -> Problem {
    problem(&spec(
        "hand",
        &format!("boundary = \"wall\"\n{BASE}\n[coverage]\nrange = 1\n[features]\nbranches = \"forbid\""),
    ))
}

#[test]
fn validator_finds_an_island() {
    let p = grid4();
    // A path 1-6-7-8-3 (boundary to boundary) and a separate segment 11-12 with no sink.
    let net = Network::from_edges(&p, &edges_between(&p, &[(1, 6), (6, 7), (7, 8), (8, 3), (16, 17)]));
    let v = design::validate(&p, &net, None);
    assert!(v.iter().any(|v| matches!(v, Violation::Island { edges } if edges.len() == 1)), "{v:?}");
}

#[test]
fn validator_finds_a_loop_island() {
    let p = grid4();
    let net = Network::from_edges(&p, &edges_between(&p, &[(6, 7), (7, 12), (12, 11), (11, 6)]));
    let v = design::validate(&p, &net, None);
    assert!(v.iter().any(|v| matches!(v, Violation::Island { edges } if edges.len() == 4)), "{v:?}");
}

#[test]
fn validator_finds_a_dead_end_at_the_tail_of_a_half_edge() {
    // 6→7→2: vertex 6 is the tail of the first half-edge and has one active edge. The paper's
    // (11) constrains only heads, so this is the case its form lets through.
    let p = grid4();
    let net = Network::from_edges(&p, &edges_between(&p, &[(6, 7), (7, 2)]));
    let v = design::validate(&p, &net, None);
    assert!(v.contains(&Violation::DeadEnd { vertex: VertexId(6) }), "{v:?}");
    assert!(!v.iter().any(|v| matches!(v, Violation::Island { .. })), "{v:?}");
}

#[test]
fn validator_finds_an_uncovered_vertex_and_a_branch() {
    let p = grid4();
    // Only the left column path: the right part is farther than one edge.
    let net = Network::from_edges(&p, &edges_between(&p, &[(5, 6), (6, 11), (11, 10), (6, 7), (7, 2)]));
    let v = design::validate(&p, &net, None);
    assert!(v.contains(&Violation::Uncovered { vertex: VertexId(18) }), "{v:?}");
    assert!(v.contains(&Violation::Branch { vertex: VertexId(6), degree: 3 }), "{v:?}");
}

#[test]
fn validator_accepts_a_good_network_and_objective_recomputes() {
    let p = problem(&spec("good", &format!("boundary = \"wall\"\nformulation = \"tight\"\n{BASE}")));
    let nm = formulations::build(&p);
    let r = pipeline::solve_built(&p, &nm, SolverKind::default_kind().unwrap(), &SolveOptions::default()).unwrap();
    assert!(r.validity.valid);
    assert!(design::validate(&p, r.network.as_ref().unwrap(), None).is_empty());
    assert!(objectives_agree(r.validity.objective_recomputed.unwrap(), r.solve.objective.unwrap(), 1e-9));
}

/// A strong-recipe model written to a file is complete: its lazily separated cutsets are
/// written as the equivalent flow, and the file read back and solved without any separator has
/// the lazy solve's optimum (with and without the distance term). `symmetric_flow` is off: the
/// grid is symmetric, and with the distance term `strong` would write no cutsets on it.
#[test]
fn strong_export_is_complete() {
    for (name, weights) in [("len", "length = 1\nzigzag = 2"), ("dist", "length = 1\ndistance = 0.5")] {
        let p = problem(&spec(name, &format!("boundary = \"wall\"\n{BASE}\n[weights]\n{weights}\n[formulation]\nrecipe = \"strong\"\nsymmetric_flow = false\n")));
        let f = pipeline::build(&p);
        assert!(!f.is_complete(), "{name}: strong has lazy cutsets");
        let lazy = pipeline::solve_built(&p, &f, SolverKind::Highs, &SolveOptions::default()).unwrap();
        assert_eq!(lazy.solve.termination, Termination::Optimal);
        let compact = formulations::build_compact(&p);
        // Without the distance term the cutsets become the connectivity flow; with it, the
        // distance flow already ties every edge to a sink.
        let flow = if name == "len" { "connectivity flow (§8)" } else { "distance flow (§8)" };
        assert!(compact.is_complete() && compact.families.contains_key(flow), "{name}: {:?}", compact.families.keys());
        let dir = tempfile::tempdir().unwrap();
        for ext in ["lp", "mps"] {
            let path = dir.path().join(format!("m.{ext}"));
            netspec::io::write_model_file_with_comments(&compact.model, &path, &["cutsets written as a flow".into()])
                .unwrap();
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(text.contains("cutsets written as a flow"), "{ext}: header comment");
            let back = netspec::io::read_model_file(&path).unwrap().model;
            let r = SolverKind::Highs.instance().unwrap().solve(&back, &SolveOptions::default()).unwrap();
            assert_eq!(r.termination, Termination::Optimal);
            assert!(
                objectives_agree(r.objective.unwrap(), lazy.solve.objective.unwrap(), 1e-6),
                "{name} {ext}: {:?} vs {:?}",
                r.objective,
                lazy.solve.objective
            );
        }
    }
}

/// A backend as it is but without an LP session ([`Solver::lp_session`]): every LP from scratch.
struct FromScratch<'a>(&'a (dyn Solver + Send + Sync));

impl Solver for FromScratch<'_> {
    fn kind(&self) -> SolverKind {
        self.0.kind()
    }
    fn version(&self) -> String {
        self.0.version()
    }
    fn capabilities(&self) -> netspec::solvers::Capabilities {
        self.0.capabilities()
    }
    fn solve(
        &self,
        model: &netspec::milp::Model,
        options: &SolveOptions,
    ) -> Result<netspec::solvers::SolveResult, netspec::solvers::SolverError> {
        self.0.solve(model, options)
    }
}

/// The cover cutsets of the strong recipe: every group is a sink-free, inclusion-minimal ball;
/// they raise the root LP bound over the cutsets alone — on a length-only spec like the paper's
/// level-4 streets (dead-ends allowed), and with the distance term, where counting only the
/// half-edges that leave a set closes the root gap of this small spec entirely — and the strong
/// recipe with them still proves the paper recipe's optimum.
#[test]
fn cover_cutsets_raise_the_root_bound_and_keep_the_optimum() {
    for (weights, range) in [("length = 1", 2), ("length = 1\ndistance = 1", 1)] {
        let toml = format!("name = \"cover\"\nformulation = \"strong\"\nboundary = \"wall\"\n[mesh]\ngrid = {{ width = 4, height = 4 }}\n[sinks]\nvertices = [2]\n[coverage]\nrange = {range}\n[weights]\n{weights}\n[features]\ndead_ends = \"allow\"\n");
        let p = problem(&toml);
        let f = pipeline::build(&p);
        let g = f.cutsets.clone().expect("strong separates cutsets on streets");
        assert!(g.groups.len() > 1, "{weights}: {} groups", g.groups.len());
        for (i, a) in g.groups.iter().enumerate() {
            assert!(a.nodes.iter().all(|&k| k > 0 && (k as usize) < g.nodes), "group {i} holds the root");
            for (j, b) in g.groups.iter().enumerate() {
                assert!(
                    i == j || !a.nodes.iter().all(|k| b.nodes.contains(k)),
                    "group {i} ⊆ group {j}: {j} is not minimal"
                );
            }
        }
        let directed = p.w_distance > 0.0;
        // Direction binaries with the distance flow, else the parent arcs (`directed_cutsets`).
        let arcs = g.arcs.as_ref().expect("the strong recipe's cutsets are directed");
        let kinds: Vec<&[Option<netspec::milp::VarId>]> = vec![&f.vars.half_edge, &f.vars.parent];
        let owner = if directed { kinds[0] } else { kinds[1] };
        assert!(
            arcs.iter().flat_map(|&(a, b)| [a, b]).flatten().all(|a| owner.contains(&Some(a))),
            "{weights}: arcs of the wrong kind"
        );
        let highs = SolverKind::Highs.instance().unwrap();
        let o = SolveOptions { threads: Some(1), ..SolveOptions::default() };
        let bound = |graph: formulations::CutsetGraph| {
            let mut sep = formulations::CutsetSeparator::new(graph);
            netspec::solvers::lazy::lp_bound(highs.as_ref(), &f.model, Some(&mut sep), &o).unwrap().with_cuts.unwrap()
        };
        let with_groups = bound(g.clone());
        // The rounds on HiGHS keep the LP loaded (each from the last basis); solved from scratch
        // each time they reach the same bound here (both run until no row is violated).
        let scratch = {
            let mut sep = formulations::CutsetSeparator::new(g.clone());
            netspec::solvers::lazy::lp_bound(&FromScratch(highs.as_ref()), &f.model, Some(&mut sep), &o)
                .unwrap()
                .with_cuts
                .unwrap()
        };
        assert!(
            objectives_agree(with_groups, scratch, 1e-6),
            "{weights}: root bound {with_groups} kept loaded, {scratch} from scratch"
        );
        let undirected = bound(formulations::CutsetGraph { arcs: None, ..g.clone() });
        let cutsets_only = bound(formulations::CutsetGraph { groups: Vec::new(), arcs: None, ..g.clone() });
        assert!(
            undirected > cutsets_only + 0.1,
            "{weights}: root bound {undirected} with cover cutsets, {cutsets_only} without"
        );
        let strong = pipeline::solve_built(&p, &f, SolverKind::Highs, &SolveOptions::default()).unwrap();
        let paper = pipeline::solve_built(
            &p,
            &formulations::build_with(&p, &formulations::Recipe::named(RecipeName::Paper)),
            SolverKind::Highs,
            &SolveOptions::default(),
        )
        .unwrap();
        for r in [&strong, &paper] {
            assert_eq!(r.solve.termination, Termination::Optimal, "{weights}");
            assert!(r.validity.valid, "{weights}: {:?}", r.validity);
        }
        let optimum = paper.solve.objective.unwrap();
        assert!(
            objectives_agree(strong.solve.objective.unwrap(), optimum, 1e-6),
            "{weights}: strong {:?}, paper {optimum}",
            strong.solve.objective
        );
        if directed {
            assert!(with_groups > undirected + 0.1, "{weights}: directed {with_groups}, undirected {undirected}");
            assert!(
                objectives_agree(with_groups, optimum, 1e-6),
                "{weights}: the directed cover cutsets close the root gap: {with_groups} against {optimum}"
            );
        } else {
            assert!(
                with_groups >= undirected - 1e-6,
                "{weights}: parent-arc cutsets {with_groups}, undirected {undirected}"
            );
            assert!(with_groups <= optimum + 1e-6, "{weights}: bound {with_groups} above the optimum {optimum}");
        }
    }
}

/// The directed cutsets on parent arcs (`strong` without the distance flow): on a length-only
/// 5×5 grid with one corner sink they raise the root LP bound after the cut rounds over the
/// undirected rows (`directed_cutsets = false`) — to the optimum where dead-ends are allowed —
/// and every variant proves the same optimum, with a valid design, on HiGHS and microlp.
#[test]
fn directed_cutsets_on_parent_arcs_raise_the_root_bound_and_keep_the_optimum() {
    let highs = SolverKind::Highs.instance().unwrap();
    let one_thread = SolveOptions { threads: Some(1), ..SolveOptions::default() };
    for (dead_ends, optimum, undirected_root, directed_root) in
        [("allow", 10.0, 8.0, 10.0), ("forbid", 12.0, 10.542373, 11.235294)]
    {
        let p = problem(&spec("directed", &format!("boundary = \"candidate\"\nformulation = \"strong\"\n[mesh]\ngrid = {{ width = 5, height = 5 }}\n[sinks]\nvertices = [0]\n[coverage]\nrange = 2\n[weights]\nlength = 1\n[features]\ndead_ends = \"{dead_ends}\"\n")));
        let directed = pipeline::build(&p);
        assert!(directed.recipe.on(&switch::DIRECTED_CUTSETS));
        let undirected = formulations::build_with(&p, &directed.recipe.with(&switch::DIRECTED_CUTSETS, false));
        let arcs = directed.cutsets.as_ref().and_then(|g| g.arcs.as_ref()).expect("parent arcs in the cutset graph");
        assert!(arcs.iter().flat_map(|&(a, b)| [a, b]).flatten().all(|a| directed.vars.parent.contains(&Some(a))));
        assert!(undirected.cutsets.as_ref().is_some_and(|g| g.arcs.is_none()));
        let root = |f: &formulations::Formulation| {
            let mut sep = formulations::CutsetSeparator::new(f.cutsets.clone().unwrap());
            netspec::solvers::lazy::lp_bound(highs.as_ref(), &f.model, Some(&mut sep), &one_thread)
                .unwrap()
                .with_cuts
                .unwrap()
        };
        let (b_directed, b_undirected) = (root(&directed), root(&undirected));
        assert!(
            objectives_agree(b_directed, directed_root, 1e-5) && objectives_agree(b_undirected, undirected_root, 1e-5),
            "{dead_ends}: root {b_directed} directed, {b_undirected} undirected"
        );
        for (f, kind) in [
            (&directed, SolverKind::Highs),
            (&undirected, SolverKind::Highs),
            (&directed, SolverKind::Microlp),
            (&undirected, SolverKind::Microlp),
        ] {
            let r = pipeline::solve_built(&p, f, kind, &one_thread).unwrap();
            assert_eq!(r.solve.termination, Termination::Optimal, "{kind}, {}, dead-ends {dead_ends}", f.recipe.label);
            assert!(r.validity.valid, "{:?}", r.validity);
            assert!(
                objectives_agree(r.solve.objective.unwrap(), optimum, 1e-9),
                "{kind}, {}, dead-ends {dead_ends}: {:?}",
                f.recipe.label,
                r.solve.objective
            );
        }
    }
}

/// `symmetric_flow`: on a grid whose problem has the square's eight symmetries (every boundary
/// vertex a sink, a distance term) `strong` leaves connectivity to the distance flow (no
/// cutsets) and hands HiGHS `presolve=off`; with `symmetric_flow = false`, or with one corner
/// sink (one reflection), it separates cutsets. Both models prove the same optimum with a valid
/// design on HiGHS and microlp, and the image of the design under each symmetry is a valid
/// design with the same objective, recomputed from the network alone.
#[test]
fn symmetric_grids_leave_connectivity_to_the_distance_flow_and_keep_the_optimum() {
    let text = |sinks: &str| {
        spec("sym", &format!("boundary = \"wall\"\nformulation = \"strong\"\n[mesh]\ngrid = {{ width = 6, height = 6 }}\n[sinks]\n{sinks}\n[coverage]\nrange = 1\n[weights]\nlength = 0\ndistance = 1\nzigzag = 5\ntoo_close = \"forbid\"\n[features]\ndead_ends = \"forbid\"\n"))
    };
    let corner = pipeline::build(&problem(&text("vertices = [0]")));
    assert_eq!(corner.symmetry_order, None);
    assert!(corner.cutsets.is_some());
    let p = problem(&text("all_boundary = true"));
    let symmetric = pipeline::build(&p);
    assert_eq!(symmetric.symmetry_order, Some(8));
    assert!(
        symmetric.cutsets.is_none()
            && !symmetric.families.contains_key("connectivity flow (§8)")
            && symmetric.is_complete()
    );
    let presolve_off = |f: &formulations::Formulation, kind: SolverKind| {
        let hints = pipeline::Strategy::for_problem(&p, f).hints(f, Some(1));
        kind.instance().unwrap().strategy_hints(&hints).iter().any(|h| h.name == "presolve" && h.value == "off")
    };
    assert!(presolve_off(&symmetric, SolverKind::Highs) && !presolve_off(&symmetric, SolverKind::Microlp));
    let cutsets = formulations::build_with(&p, &symmetric.recipe.with(&switch::SYMMETRIC_FLOW, false));
    assert!(
        cutsets.symmetry_order.is_none() && cutsets.cutsets.is_some() && !presolve_off(&cutsets, SolverKind::Highs)
    );
    let one_thread = SolveOptions { threads: Some(1), ..SolveOptions::default() };
    for (f, kind) in [
        (&symmetric, SolverKind::Highs),
        (&cutsets, SolverKind::Highs),
        (&symmetric, SolverKind::Microlp),
        (&cutsets, SolverKind::Microlp),
    ] {
        let r = pipeline::solve_built(&p, f, kind, &one_thread).unwrap();
        assert_eq!(r.solve.termination, Termination::Optimal, "{kind}, {}", f.recipe.label);
        assert!(r.validity.valid, "{:?}", r.validity);
        assert!(
            objectives_agree(r.solve.objective.unwrap(), 8.0, 1e-9),
            "{kind}, {}: {:?}",
            f.recipe.label,
            r.solve.objective
        );
        if kind == SolverKind::Highs && f.symmetry_order.is_some() {
            assert!(r.solver_hints.iter().any(|h| h == "highs.presolve=off"), "{:?}", r.solver_hints);
        }
        let net = r.network.unwrap();
        let symmetries = netspec::spec::symmetries(&p);
        assert_eq!(symmetries.len(), 7);
        for s in &symmetries {
            let image =
                Network::from_edges(&p, &net.active_edges().iter().map(|e| s.edge[e.index()]).collect::<Vec<_>>());
            assert!(
                design::validate(&p, &image, None).is_empty(),
                "{:?}: {:?}",
                s.matrix,
                design::validate(&p, &image, None)
            );
            assert!(objectives_agree(design::Objective::of(&p, &image).total, 8.0, 1e-9), "{:?}", s.matrix);
        }
    }
}

/// The strong recipe chooses one point-to-point path per pair (`paths = "select"`): its LP bound
/// is above the per-path rows' (`paths = "tight"`) on a spec whose paths share edges and vertices, both prove
/// the same optimum with a valid design, and a network holding several whole paths of a pair
/// still encodes as a start that passes the checker (one path chosen, the others 0).
#[test]
fn selected_paths_tighten_the_relaxation_and_keep_the_optimum() {
    let p = problem(&spec("select", "boundary = \"wall\"\nformulation = \"strong\"\n[mesh]\ngrid = { width = 6, height = 6 }\n[sinks]\nall_boundary = true\n[weights]\nlength = 0\ndistance = 1\n[point_to_point]\nblocks = 3\ntolerance = 2\nseed = 1\n"));
    let select = pipeline::build(&p);
    assert_eq!(select.recipe.paths, PathForm::Select);
    let through_a_vertex = select.model.rows().filter(|r| r.name.starts_with("p2p8_") && r.name.contains("_v")).count();
    assert!(through_a_vertex > 0, "no row for paths sharing a vertex");
    let tight = formulations::build_with(&p, &formulations::Recipe { paths: PathForm::Tight, ..select.recipe.clone() });
    let highs = SolverKind::Highs.instance().unwrap();
    let o = SolveOptions { threads: Some(1), ..SolveOptions::default() };
    let plain = |f: &formulations::Formulation| {
        netspec::solvers::lazy::lp_bound(highs.as_ref(), &f.model, None, &o).unwrap().plain.unwrap()
    };
    let (b_select, b_tight) = (plain(&select), plain(&tight));
    assert!(b_select > b_tight + 0.5, "LP bound: select {b_select}, tight {b_tight}");
    let solve = |f: &formulations::Formulation| {
        pipeline::solve_built(&p, f, SolverKind::Highs, &SolveOptions::default()).unwrap()
    };
    let (rs, rt) = (solve(&select), solve(&tight));
    for r in [&rs, &rt] {
        assert_eq!(r.solve.termination, Termination::Optimal);
        assert!(r.validity.valid, "{:?}", r.validity);
    }
    let optimum = rt.solve.objective.unwrap();
    assert!(
        objectives_agree(rs.solve.objective.unwrap(), optimum, 1e-6),
        "select {:?}, tight {optimum}",
        rs.solve.objective
    );
    assert!(b_select <= optimum + 1e-6, "bound {b_select} above the optimum {optimum}");
    // Every usable edge on: every enumerated path is whole.
    let all = Network {
        active: p.roles.iter().map(|r| *r != EdgeRole::Excluded).collect(),
        directions: Vec::new(),
        labels: Vec::new(),
        rooms: Vec::new(),
    };
    for f in [&select, &tight] {
        let (x, report) = pipeline::prepare_start(&p, f, &all, "every edge");
        assert!(report.accepted, "{}: {:?}", f.recipe.label, report.reason);
        let x = x.unwrap();
        let sets = f.path_sets.as_ref().expect("path sets");
        for (pi, pair) in sets.pairs.iter().enumerate() {
            let prefix = format!("P_p{pi}_");
            let on = f.model.vars().iter().zip(&x).filter(|(v, &xv)| v.name.starts_with(&prefix) && xv > 0.5).count();
            let want = if f.recipe.paths == PathForm::Select { 1 } else { pair.paths.len() };
            assert_eq!(on, want, "{}: paths chosen of a pair", f.recipe.label);
        }
    }
}

/// The out-arc rows (`strong`, dead-ends allowed): without direction binaries they bring
/// parent arcs, and the LP as written rises above the recipe's without them (which may switch
/// on every vertex of a path whose edges are at ½); with the distance flow they are rows on its
/// direction binaries alone; with dead-ends forbidden they are written only for the directed
/// cutsets on parent arcs (`directed_cutsets`, no distance flow). Every variant proves the same
/// optimum, with a valid design, on HiGHS and microlp.
#[test]
fn out_arcs_tighten_the_relaxation_and_keep_the_optimum() {
    let text = |distance: f64, dead_ends: &str| {
        format!("boundary = \"candidate\"\nformulation = \"strong\"\n[mesh]\ngrid = {{ width = 7, height = 2 }}\n[sinks]\nvertices = [0]\n[coverage]\nrange = 1\n[weights]\nlength = 1\ndistance = {distance}\nzigzag = 0\n[features]\ndead_ends = \"{dead_ends}\"\n")
    };
    let highs = SolverKind::Highs.instance().unwrap();
    let one_thread = SolveOptions { threads: Some(1), ..SolveOptions::default() };
    let plain = |f: &formulations::Formulation| {
        netspec::solvers::lazy::lp_bound(highs.as_ref(), &f.model, None, &one_thread).unwrap().plain.unwrap()
    };
    for (distance, dead_ends) in [(0.0, "allow"), (1.0, "allow"), (0.0, "forbid")] {
        let p = problem(&spec("out-arcs", &text(distance, dead_ends)));
        let with = pipeline::build(&p);
        assert!(with.recipe.on(&switch::OUT_ARCS));
        let without = formulations::build_with(
            &p,
            &with.recipe.with(&switch::OUT_ARCS, false).with(&switch::DIRECTED_CUTSETS, false),
        );
        let undirected = formulations::build_with(&p, &with.recipe.with(&switch::DIRECTED_CUTSETS, false));
        let family = with.families.get("out-arcs (§8)");
        let parents = with.vars.parent.iter().flatten().count();
        // Parent arcs with the directed cutsets are a forest's: one out of each active vertex.
        let out_rows: Vec<(f64, f64)> =
            with.model.rows().filter(|r| r.name.starts_with("out_")).map(|r| (r.lhs, r.rhs)).collect();
        assert!(
            !out_rows.is_empty() && out_rows.iter().all(|&(lo, hi)| lo == 0.0 && (hi == 0.0) == (distance == 0.0)),
            "{out_rows:?}"
        );
        match (distance > 0.0, dead_ends) {
            (false, "allow") => {
                assert!(family.is_some_and(|f| f.vars == parents && parents > 0 && f.rows > 0), "{family:?}");
                let (b_with, b_without) = (plain(&with), plain(&without));
                assert!(b_with > b_without + 1.0, "LP bound: with {b_with}, without {b_without}");
            }
            (true, _) => assert!(family.is_some_and(|f| f.vars == 0 && f.rows > 0) && parents == 0, "{family:?}"),
            _ => {
                assert!(family.is_some_and(|f| f.vars == parents && parents > 0 && f.rows > 0), "{family:?}");
                assert!(
                    undirected.families.get("out-arcs (§8)").is_none()
                        && undirected.vars.parent.iter().all(Option::is_none)
                );
            }
        }
        assert!(without.families.get("out-arcs (§8)").is_none());
        let mut optima = Vec::new();
        for (f, kind) in [(&with, SolverKind::Highs), (&without, SolverKind::Highs), (&with, SolverKind::Microlp)] {
            let r = pipeline::solve_built(&p, f, kind, &one_thread).unwrap();
            assert_eq!(r.solve.termination, Termination::Optimal, "{kind}, distance {distance}, dead-ends {dead_ends}");
            assert!(r.validity.valid, "{:?}", r.validity);
            optima.push(r.solve.objective.unwrap());
        }
        assert!(
            optima.iter().all(|&o| objectives_agree(o, optima[0], 1e-9)),
            "distance {distance}, dead-ends {dead_ends}: {optima:?}"
        );
        if distance == 0.0 && dead_ends == "allow" {
            assert!(objectives_agree(optima[0], 8.0, 1e-9), "{optima:?}");
        }
    }
}

/// A design becomes a MIP start for every recipe: the optimal design of one recipe, encoded for
/// each recipe, passes the MILP checker with that recipe's objective; a corrupted design is
/// refused with a reason.
#[test]
fn designs_encode_as_checked_starts() {
    let p = problem(&spec(
        "start",
        &format!("boundary = \"wall\"\n{BASE}\n[weights]\nlength = 1\ndistance = 0.25\nzigzag = 1\n"),
    ));
    let r = pipeline::solve_built(&p, &pipeline::build(&p), SolverKind::Highs, &SolveOptions::default()).unwrap();
    let net = r.network.clone().unwrap();
    for recipe in RecipeName::ALL {
        let f = formulations::build_with(&p, &formulations::Recipe::named(recipe));
        let (x, report) = pipeline::prepare_start(&p, &f, &net, "test");
        assert!(report.accepted, "{recipe}: {:?}", report.reason);
        let x = x.unwrap();
        assert!(
            objectives_agree(f.model.objective_value(&x), r.solve.objective.unwrap(), 1e-9),
            "{recipe}: start objective"
        );
        // Handed to a solver with a limit of zero nodes' work, the start comes back as the
        // incumbent at worst.
        let o = SolveOptions { mip_start: Some(x), ..Default::default() };
        let again = pipeline::solve_built(&p, &f, SolverKind::Highs, &o).unwrap();
        assert!(again.solve.objective.unwrap() <= r.solve.objective.unwrap() + 1e-9);
    }
    // Drop one edge of the optimum: a dead-end (or an uncovered vertex) appears, and the start
    // is refused with a reason that names a row.
    let mut broken = net.clone();
    let e = broken.active_edges()[0];
    broken.active[e.index()] = false;
    let f = pipeline::build(&p);
    let (x, report) = pipeline::prepare_start(&p, &f, &broken, "broken");
    assert!(x.is_none() && !report.accepted);
    assert!(
        report
            .reason
            .as_deref()
            .is_some_and(|r| r.contains("violations") || r.contains("connectivity") || r.contains("reach")),
        "{:?}",
        report.reason
    );
}

/// A quick infeasibility case: one corner sink behind a wall on a 4×4 grid. The
/// strong recipe's flows and coverage rows make the LP itself infeasible, so every backend
/// proves it (the timing is in docs/benchmarks.md, not asserted here).
#[test]
fn corner_sink_behind_a_wall_is_infeasible() {
    let p = problem(&spec("corner", "boundary = \"wall\"\nformulation = \"strong\"\n[mesh]\ngrid = { width = 4, height = 4 }\n[sinks]\nvertices = [0]\n"));
    let f = pipeline::build(&p);
    for k in backends(true) {
        let r = pipeline::solve_built(&p, &f, k, &SolveOptions::default()).unwrap();
        assert_eq!(r.solve.termination, Termination::Infeasible, "{k}");
        assert!(r.network.is_none());
    }
}

/// The name of a validator check (an exhaustive match: a new check must be added to
/// [`validator_guard`]'s list).
fn check_name(v: &Violation) -> &'static str {
    match v {
        Violation::Island { .. } => "island",
        Violation::Uncovered { .. } => "uncovered",
        Violation::DeadEnd { .. } => "dead_end",
        Violation::Branch { .. } => "branch",
        Violation::ZigZag { .. } => "zigzag",
        Violation::TooClose { .. } => "too_close",
        Violation::TJunction { .. } => "t_junction",
        Violation::ExcludedActive { .. } => "excluded_active",
        Violation::ForcedInactive { .. } => "forced_inactive",
        Violation::ForcedVertexInactive { .. } => "forced_vertex_inactive",
        Violation::ThroughRoute { .. } => "through_route",
        Violation::PointToPoint { .. } => "point_to_point",
        Violation::Cover { .. } => "cover",
        Violation::Room { .. } => "room",
        Violation::LevelShape { .. } => "level_shape",
        Violation::RoomCount { .. } => "room_count",
    }
}

/// The validator guard: for every check the validator makes, a spec that drives the solver to the
/// edge of it, solved under the `paper` and `strong` recipes by HiGHS and SCIP — a design that
/// passes the MILP check but fails the validator would be a bug in the model.
#[test]
fn validator_guard() {
    let g = |w: u32, h: u32| format!("[mesh]\ngrid = {{ width = {w}, height = {h} }}\n");
    let cases: Vec<(&[&str], String)> = vec![
        (&["island", "uncovered", "dead_end"], format!("boundary = \"wall\"\n{}[sinks]\npoints = [[2, 2]]\n[coverage]\nrange = 2\n", g(5, 5))),
        (&["branch"], format!("boundary = \"wall\"\n{}[sinks]\nall_boundary = true\n[coverage]\nrange = 1\n[features]\nbranches = \"forbid\"\n", g(5, 5))),
        (&["zigzag", "too_close", "t_junction"], format!("boundary = \"wall\"\n{}[sinks]\nall_boundary = true\n[coverage]\nrange = 1\n[weights]\nzigzag = \"forbid\"\ntoo_close = \"forbid\"\nt_junction = \"forbid\"\n", g(5, 5))),
        (&["excluded_active", "forced_inactive", "forced_vertex_inactive"], format!("boundary = \"wall\"\n{}[sinks]\nall_boundary = true\n[user]\nobstacle_faces = [6, 7]\nforced_edges = [[1, 6]]\nforced_vertices = [18]\n", g(4, 4))),
        (&["through_route"], format!("boundary = \"road\"\n{}[sinks]\nall_boundary = true\n[coverage]\nrange = 1\n[user]\nthrough_routes = [{{ from = [2, 0], to = [2, 4] }}]\n", g(4, 4))),
        (&["point_to_point"], format!("boundary = \"road\"\n{}[sinks]\nall_boundary = true\n[point_to_point]\nblocks = 2\n", g(4, 4))),
        (&["cover", "room", "room_count"], format!("boundary = \"wall\"\n{}[sinks]\nvertices = [2]\n[features]\ndead_ends = \"allow\"\n[rooms]\nmode = \"floorplan\"\ntemplates = [{{ name = \"office\", shape = \"rect 2x2\" }}, {{ name = \"lab\", shape = \"rect 2x1\", exact = 2 }}]\n", g(4, 4))),
        (&["level_shape"], format!("boundary = \"wall\"\n{}[sinks]\nvertices = [1, 3]\n[rooms]\nmode = \"game\"\nlevel = \"linear\"\ntemplates = [{{ name = \"block\", shape = \"rect 2x2\" }}]\n", g(4, 4))),
    ];
    let samples = [
        Violation::Island { edges: vec![] },
        Violation::Uncovered { vertex: VertexId(0) },
        Violation::DeadEnd { vertex: VertexId(0) },
        Violation::Branch { vertex: VertexId(0), degree: 3 },
        Violation::ZigZag { edges: vec![] },
        Violation::TooClose { edges: vec![] },
        Violation::TJunction { vertex: VertexId(0) },
        Violation::ExcludedActive { edge: EdgeId(0) },
        Violation::ForcedInactive { edge: EdgeId(0) },
        Violation::ForcedVertexInactive { vertex: VertexId(0) },
        Violation::ThroughRoute { route: 0, detail: String::new() },
        Violation::PointToPoint { parts: (0, 1) },
        Violation::Cover { face: netspec::mesh::FaceId(0), rooms: 0 },
        Violation::Room { placement: 0, detail: String::new() },
        Violation::LevelShape { level: netspec::spec::LevelType::Linear, shape: design::GraphShape::Tree },
        Violation::RoomCount { template: 0, count: 0 },
    ];
    let mut covered: Vec<&str> = cases.iter().flat_map(|(names, _)| names.iter().copied()).collect();
    covered.sort();
    let mut all: Vec<&str> = samples.iter().map(check_name).collect();
    all.sort();
    assert_eq!(covered, all, "every validator check has a guard spec");
    for (i, (names, body)) in cases.iter().enumerate() {
        let p = problem(&spec(&format!("guard{i}"), body));
        for recipe in [RecipeName::Paper, RecipeName::Strong] {
            let f = formulations::build_with(&p, &formulations::Recipe::named(recipe));
            for k in [SolverKind::Highs, SolverKind::Scip].into_iter().filter(|k| k.is_compiled()) {
                let r =
                    pipeline::solve_built(&p, &f, k, &SolveOptions { time_limit: Some(60.0), ..Default::default() })
                        .unwrap();
                assert_eq!(r.solve.termination, Termination::Optimal, "{names:?} {recipe} {k}");
                assert!(r.validity.valid, "{names:?} {recipe} {k}: {:?}", r.validity);
            }
        }
    }
}

/// `strong`'s penalised zig-zags, too-close pairs and T-junctions have continuous indicators with
/// one row each, `Σ E − Z ≤ n − 1`; with `continuous_indicators = false` they are the paper's
/// binaries with `0 ≤ Σ E − n·Z ≤ n − 1`. Both give the same optimum, with every indicator at 0
/// or 1 in the solver's answer, and the design's objective counts the penalised configurations.
#[test]
fn continuous_indicators_are_exact_and_write_one_row_each() {
    let text = |continuous: bool| {
        format!("boundary = \"candidate\"\n[formulation]\nrecipe = \"strong\"\ncontinuous_indicators = {continuous}\n[mesh]\ngrid = {{ width = 3, height = 3 }}\n[sinks]\nvertices = [0]\n[coverage]\nrange = 1\n[weights]\nlength = 1\nzigzag = 0.5\ntoo_close = 0.25\nt_junction = 0.125\n")
    };
    let mut optima = Vec::new();
    for continuous in [true, false] {
        let p = problem(&spec("indicators", &text(continuous)));
        let f = pipeline::build(&p);
        assert_eq!(f.recipe.on(&switch::CONTINUOUS_INDICATORS), continuous);
        let indicators: Vec<_> = f
            .model
            .vars()
            .iter()
            .enumerate()
            .filter(|(_, v)| v.name.starts_with("Z0_") || v.name.starts_with("Z1_") || v.name.starts_with("T_"))
            .collect();
        assert!(
            indicators.iter().any(|(_, v)| v.name.starts_with("Z0_"))
                && indicators.iter().any(|(_, v)| v.name.starts_with("Z1_"))
                && indicators.iter().any(|(_, v)| v.name.starts_with("T_")),
            "every kind of indicator"
        );
        for (_, v) in &indicators {
            assert_eq!(v.kind == netspec::milp::VarKind::Continuous, continuous, "{}", v.name);
        }
        let ranged = f
            .model
            .rows()
            .filter(|r| {
                (r.name.starts_with("zz_") || r.name.starts_with("close_") || r.name.starts_with("tj_"))
                    && r.lhs.is_finite()
                    && r.rhs.is_finite()
            })
            .count();
        assert_eq!(ranged == 0, continuous, "two-sided rows only for binary indicators");
        let r = pipeline::solve_built(
            &p,
            &f,
            SolverKind::Highs,
            &SolveOptions { threads: Some(1), ..SolveOptions::default() },
        )
        .unwrap();
        assert_eq!(r.solve.termination, Termination::Optimal);
        assert!(r.validity.valid, "{:?}", r.validity);
        let x = r.primal_point.as_ref().expect("a point");
        for (j, v) in &indicators {
            assert!(x[*j].abs() < 1e-6 || (x[*j] - 1.0).abs() < 1e-6, "{} = {}", v.name, x[*j]);
        }
        let o = r.objective.as_ref().expect("the design's objective");
        assert!(o.zigzags + o.too_close + o.t_junctions > 0, "the optimum pays for some configuration: {o:?}");
        optima.push(r.solve.objective.unwrap());
    }
    // 8 edges, a zig-zag, two too-close pairs and a T-junction: 8 + 0.5 + 2·0.25 + 0.125.
    for o in optima {
        assert!(objectives_agree(o, 9.125, 1e-9), "{o}");
    }
}

/// The objective lattice (a formulation property the solve strategy uses): a distance spec on a unit grid (lengths, zig-zag
/// penalty and distance flow all integral) has the lattice ℤ; the backend's bound is rounded up
/// to it, and the optimum is the one without it, on HiGHS and microlp. The paper's labels carry
/// the distance term on big-M rows: no lattice; without a distance term its objective is
/// integral.
#[test]
fn objective_lattice_rounds_the_bound_and_keeps_the_optimum() {
    let text = |recipe: &str, lattice: bool, distance: f64| {
        format!("boundary = \"candidate\"\nformulation = \"{recipe}\"\n[mesh]\ngrid = {{ width = 4, height = 3 }}\n[sinks]\nvertices = [0]\n[coverage]\nrange = 1\n[weights]\nlength = 1\ndistance = {distance}\nzigzag = 5\n[features]\ndead_ends = \"forbid\"\n[solver]\nobjective_lattice = {lattice}\n")
    };
    let one_thread = SolveOptions { threads: Some(1), ..SolveOptions::default() };
    let mut optima = Vec::new();
    for (kind, lattice) in [(SolverKind::Highs, true), (SolverKind::Highs, false), (SolverKind::Microlp, true)] {
        let p = problem(&spec("lattice", &text("strong", lattice, 1.0)));
        let f = pipeline::build(&p);
        assert_eq!(
            f.objective_lattice.map(|l| (l.step, l.offset)),
            Some((1.0, 0.0)),
            "a formulation property, used or not"
        );
        let r = pipeline::solve_built(&p, &f, kind, &one_thread).unwrap();
        assert_eq!(r.solve.termination, Termination::Optimal, "{kind}");
        assert!(r.validity.valid, "{:?}", r.validity);
        assert_eq!(r.solve.dual_bound, r.solve.objective, "{kind}: the bound meets the objective");
        match (&r.lattice, lattice) {
            (None, false) => {}
            (Some(l), true) => {
                assert_eq!(l.lattice.step, 1.0);
                assert!(l.solver_bound.is_some_and(|b| b <= r.solve.dual_bound.unwrap() + 1e-9), "{kind}: {l:?}");
            }
            (l, _) => panic!("{kind}, lattice {lattice}: report {l:?}"),
        }
        optima.push(r.solve.objective.unwrap());
    }
    assert!(optima.iter().all(|&o| objectives_agree(o, 41.0, 1e-9)), "{optima:?}");

    let paper =
        |distance| pipeline::build(&problem(&spec("lattice", &text("paper", false, distance)))).objective_lattice;
    assert_eq!(paper(1.0), None, "labels hold the distance term");
    assert_eq!(paper(0.0).map(|l| l.step), Some(1.0));
}
