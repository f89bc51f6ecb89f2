//! Designs without a solver: the construction heuristic and its local search, the
//! repair of broken designs, the paper's stochastic search, heuristic designs as MIP starts,
//! and both searches as solver choices of `solve` and `compare`. Every design a search returns
//! is judged here again by the independent validator and the design objective; budgets are
//! generous upper bounds (the searches stop at their first design), never timing assertions.

use netspec::design::{self, Network, Objective};
use netspec::formulations::{build_with, Recipe};
use netspec::heuristics::{self, AnnealOptions, Inputs, Options, OwnedInputs, Stop};
use netspec::pipeline;
use netspec::pipeline::search::{run_search, SearchMethod};
use netspec::spec::{Problem, RecipeName, Spec};
use proptest::prelude::*;
use std::path::Path;
use std::process::Command;

use crate::network::problem;

fn load(path: &str) -> Problem {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    let spec = Spec::load(&path).unwrap_or_else(|e| panic!("{e}"));
    spec.resolve(path.parent().unwrap()).unwrap_or_else(|e| panic!("{e}"))
}

/// The independent verdict on a design: validator items 1–6 clean.
fn assert_valid(p: &Problem, inputs: &Inputs, net: &Network) {
    let mut violations = design::validate(p, net, inputs.paths);
    if let Some(pl) = inputs.placements {
        violations.extend(design::validate_rooms(p, net, pl, &net.rooms));
    }
    assert!(violations.is_empty(), "{}: {:?}", p.spec.name, violations.iter().take(5).collect::<Vec<_>>());
}

/// The first design of the heuristic (no local search), within a generous bound.
fn first_design(p: &Problem, inputs: &Inputs) -> heuristics::SearchOutput {
    heuristics::heuristic(
        p,
        inputs,
        &Options { time_limit: 60.0, max_designs: Some(1), local_search: false, ..Options::default() },
    )
}

/// The spec files under models/ small enough for the test suite (the paper-size floor plans,
/// game levels and level-3/4 street meshes are run by `benches/heuristics.rs`).
const SMALL_MODELS: &[&str] = &[
    "models/fig2a.toml",
    "models/fig2b.toml",
    "models/fig2c.toml",
    "models/fig2d.toml",
    "models/fig2e.toml",
    "models/fig2f.toml",
    "models/fig2g.toml",
    "models/fig9b4.toml",
    "models/fig11a.toml",
    "models/streets/fig1a/L2/spec.json",
    "models/streets/fig1b/L2/spec.json",
    "models/streets/fig1c/L2/spec.json",
    "models/streets/fig5/L3/spec.json",
    "models/streets/fig5/L4/spec.json",
    "models/streets/fig7a/L2/spec.json",
    "models/streets/fig7b/L2/spec.json",
    "models/streets/fig7d/L2/spec.json",
    "models/streets/fig7e/L2/spec.json",
    "models/streets/fig8/L2/spec.json",
    "fixtures/specs/tiny_network.toml",
    "fixtures/specs/tiny_floorplan.toml",
];

#[test]
fn small_models_get_a_valid_design() {
    for path in SMALL_MODELS {
        let p = load(path);
        let owned = OwnedInputs::enumerate(&p);
        let inputs = owned.inputs();
        let out = first_design(&p, &inputs);
        let net = out.network.as_ref().unwrap_or_else(|| panic!("{path}: no design ({:?})", out.stats));
        assert_valid(&p, &inputs, net);
        // The reported objective is the design's own.
        assert_eq!(out.objective, Some(Objective::of(&p, net).total), "{path}");
        assert_eq!(out.stop, Stop::Exhausted, "{path}");
    }
}

#[test]
fn local_search_only_improves() {
    let p = load("models/fig2a.toml");
    let inputs = Inputs::default();
    let first = first_design(&p, &inputs).objective.unwrap();
    let out =
        heuristics::heuristic(&p, &inputs, &Options { time_limit: 1.0, max_designs: Some(1), ..Options::default() });
    assert_valid(&p, &inputs, out.network.as_ref().unwrap());
    let best = out.objective.unwrap();
    assert!(best <= first + 1e-9, "{best} > {first}");
    assert!(
        out.trace.windows(2).all(|w| w[1].objective < w[0].objective && w[1].seconds >= w[0].seconds),
        "{:?}",
        out.trace
    );
    assert_eq!(out.trace.last().unwrap().objective, best);
}

#[test]
fn plain_infeasibility_is_proven_not_searched() {
    // The first Fig. 7c level-2 reconstruction froze its sink on a walled corner: its two edges
    // are walls, and coverage needs a network, so nothing could ever reach a sink.
    let p = load("fixtures/specs/walled_corner_sink/spec.json");
    for out in [
        heuristics::heuristic(&p, &Inputs::default(), &Options::default()),
        heuristics::anneal(&p, &Inputs::default(), &AnnealOptions::default()),
    ] {
        assert_eq!(out.stop, Stop::Infeasible);
        assert!(out.network.is_none());
        assert!(out.infeasible.as_deref().unwrap().contains("no sink (v140)"), "{:?}", out.infeasible);
    }
}

#[test]
fn repair_mends_islands_dead_ends_and_forbidden_pairs() {
    let p = load("models/fig2b.toml");
    let inputs = Inputs::default();
    let good = first_design(&p, &inputs).network.unwrap();
    let mesh = &p.mesh;
    // Break it three ways: an island far from the network, a dead-end, a too-close pair.
    let mut bad = good.clone();
    let off = good.active_edges()[3];
    bad.active[off.index()] = false;
    let island = mesh.edges().find(|&e| {
        let (a, b) = mesh.edge_vertices(e);
        p.roles[e.index()] == netspec::spec::EdgeRole::Candidate
            && mesh.incident_edges(a).chain(mesh.incident_edges(b)).all(|x| !good.active[x.index()])
    });
    if let Some(e) = island {
        bad.active[e.index()] = true;
    }
    assert!(!design::validate(&p, &bad, None).is_empty());
    let fixed = heuristics::repair(&p, &inputs, &bad).expect("repairable");
    assert_valid(&p, &inputs, &fixed);
    // A valid design comes back valid.
    assert_valid(&p, &inputs, &heuristics::repair(&p, &inputs, &good).unwrap());
    // A design of the wrong size cannot be repaired.
    let short = Network { active: vec![true; 3], ..good };
    assert!(heuristics::repair(&p, &inputs, &short).is_none());
}

#[test]
fn repair_keeps_a_floor_plan_tiling_and_refuses_a_broken_one() {
    let p = load("fixtures/specs/tiny_floorplan.toml");
    let owned = OwnedInputs::enumerate(&p);
    let inputs = owned.inputs();
    let good = first_design(&p, &inputs).network.unwrap();
    let mut no_corridors = good.clone();
    no_corridors.active.iter_mut().for_each(|a| *a = false);
    let fixed = heuristics::repair(&p, &inputs, &no_corridors).expect("corridors rebuilt");
    assert_eq!(fixed.rooms, good.rooms);
    assert_valid(&p, &inputs, &fixed);
    let mut holes = good;
    holes.rooms.pop();
    assert!(heuristics::repair(&p, &inputs, &holes).is_none(), "a tiling with a hole is not the repair's to fix");
}

/// A 4×4 grid with every local rule on, small enough for every backend (microlp included).
const START_SPEC: &str = r#"
name = "start4"
boundary = "wall"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
all_boundary = true
[weights]
length = 1
distance = 0.1
zigzag = 5
too_close = "forbid"
t_junction = 1
[features]
dead_ends = "forbid"
"#;

#[test]
fn heuristic_start_is_accepted_by_every_backend_that_takes_starts() {
    let mut p = problem(START_SPEC);
    let start = heuristics::start(&p, &Inputs::default(), 0.5, 0).expect("a design");
    let start_objective = Objective::of(&p, &start).total;
    for recipe in RecipeName::ALL {
        p.formulation = netspec::spec::FormulationSpec::Named(recipe);
        let f = build_with(&p, &Recipe::of(&p));
        let (x, report) = pipeline::prepare_start(&p, &f, &start, "heuristic");
        assert!(report.accepted, "{recipe}: {:?}", report.reason);
        assert_eq!(report.objective, Some(start_objective));
        let x = x.unwrap();
        for kind in netspec::solvers::SolverKind::compiled() {
            let solver = kind.instance().unwrap();
            if !solver.capabilities().mip_start || kind == netspec::solvers::SolverKind::GoodLp {
                continue;
            }
            let options = netspec::solvers::SolveOptions {
                time_limit: Some(60.0),
                mip_start: Some(x.clone()),
                ..Default::default()
            };
            let r = pipeline::solve_built(&p, &f, kind, &options).unwrap_or_else(|e| panic!("{kind} {recipe}: {e}"));
            assert!(r.validity.valid, "{kind} {recipe}: {:?}", r.validity.design_violations);
            let obj = r.objective.as_ref().unwrap().total;
            assert!(obj <= start_objective + 1e-6, "{kind} {recipe}: {obj} worse than the start {start_objective}");
        }
    }
}

#[test]
fn side_by_side_searches_keep_the_best_design_of_all_and_count_every_construction() {
    let p = problem(START_SPEC);
    // Construction only, a fixed number per search: no result depends on timing.
    let opts =
        Options { time_limit: 60.0, max_constructions: Some(3), local_search: false, seed: 5, ..Options::default() };
    let one = heuristics::heuristic(&p, &Inputs::default(), &opts);
    let two = heuristics::heuristic(&p, &Inputs::default(), &Options { threads: 2, ..opts });
    assert_eq!(one.stats.constructions, 3);
    assert_eq!(two.stats.constructions, 6);
    let (a, b) =
        (one.objective.expect("one search finds a design"), two.objective.expect("two searches find a design"));
    assert!(b <= a + 1e-9, "two searches ({b}) ended worse than the first alone ({a})");
    assert_valid(&p, &Inputs::default(), two.network.as_ref().unwrap());
    // The trace is the running best over both searches: strictly improving, ending at the best.
    assert!(two.trace.windows(2).all(|w| w[1].objective < w[0].objective && w[1].seconds >= w[0].seconds));
    assert!((two.trace.last().unwrap().objective - b).abs() < 1e-9);
}

#[test]
fn without_a_design_the_start_goes_on_to_its_first_design_budget_and_no_further() {
    let p = problem(START_SPEC);
    // No time at all: nothing is constructed.
    let none = heuristics::heuristic(&p, &Inputs::default(), &Options { time_limit: 0.0, ..Options::default() });
    assert!(none.network.is_none());
    assert_eq!(none.stats.constructions, 0);
    // No time but a first-design allowance: the search goes on until its first design, then
    // stops at once (its ordinary budget is long gone), without restarts or local search.
    let opts = Options { time_limit: 0.0, first_design_limit: Some(60.0), ..Options::default() };
    let first = heuristics::heuristic(&p, &Inputs::default(), &opts);
    let net = first.network.expect("a design within the first-design allowance");
    assert_valid(&p, &Inputs::default(), &net);
    assert_eq!(first.stats.constructions, 1);
    assert_eq!(first.stats.moves_tried, 0);
    assert_eq!(heuristics::start_within(&p, &Inputs::default(), 0.0, 60.0, 0, 1), Some(net));
    // The defaults: a tenth of the limit (≤ 2 s of work) to improve, a fifth (≤ 60 s of the
    // clock) to find one.
    for (limit, budget, first) in [
        (Some(300.0), 2.0, 60.0),
        (Some(100.0), 2.0, 20.0),
        (Some(4.0), 0.4, 0.8),
        (Some(1.0), 0.1, 0.2),
        (None, 2.0, 60.0),
    ] {
        assert!((pipeline::default_start_budget(limit) - budget).abs() < 1e-12, "{limit:?}");
        assert!((pipeline::default_first_design_budget(limit) - first).abs() < 1e-12, "{limit:?}");
    }
}

#[test]
fn a_solve_from_the_heuristic_start_never_ends_worse_than_it() {
    let p = problem(START_SPEC);
    let f = pipeline::build(&p);
    for kind in netspec::solvers::SolverKind::compiled() {
        if kind == netspec::solvers::SolverKind::GoodLp {
            continue;
        }
        // No time left after the start: whatever the solver manages, the design is at least the start.
        for limit in [0.0, 30.0] {
            let options = netspec::solvers::SolveOptions { time_limit: Some(limit), ..Default::default() };
            let r = pipeline::solve_from(
                &p,
                &f,
                kind,
                &options,
                &pipeline::StartFrom::Heuristic { budget: 0.3, first_design_budget: 0.3 },
            )
            .unwrap_or_else(|e| panic!("{kind}: {e}"));
            let start = r.start.as_ref().unwrap_or_else(|| panic!("{kind}: no start report"));
            if !kind.instance().unwrap().capabilities().mip_start {
                assert!(
                    !start.accepted && start.reason.as_ref().unwrap().contains("does not accept"),
                    "{kind}: {start:?}"
                );
                continue;
            }
            assert!(start.accepted, "{kind}: {start:?}");
            assert!(start.seconds.is_some());
            assert!(r.validity.valid, "{kind} at {limit} s: {:?}", r.validity.design_violations);
            let (obj, start_obj) = (r.objective.as_ref().unwrap().total, start.objective.unwrap());
            assert!(obj <= start_obj + 1e-6, "{kind} at {limit} s: {obj} worse than the start {start_obj}");
            if start.returned {
                assert!(
                    (obj - start_obj).abs() <= 1e-6,
                    "{kind}: returned the start but the objective is {obj}, not {start_obj}"
                );
            }
        }
    }
}

#[test]
fn solve_reads_a_start_from_a_result_file_and_refuses_one_of_another_spec() {
    let dir = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let spec = root.join("fixtures/specs/tiny_network.toml");
    let run = |args: &[&str]| Command::new(env!("CARGO_BIN_EXE_netspec")).arg("solve").args(args).output().unwrap();
    let first = dir.path().join("first");
    let out = run(&[
        spec.to_str().unwrap(),
        "--solver",
        "heuristic",
        "--time-limit",
        "0.3",
        "--out",
        first.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let result = first.join("result.json");
    let out = run(&[
        spec.to_str().unwrap(),
        "--start",
        result.to_str().unwrap(),
        "--time-limit",
        "20",
        "--out",
        dir.path().join("second").to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains(&format!("start      {}", result.display())) && stdout.contains("accepted"), "{stdout}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("second/result.json")).unwrap()).unwrap();
    assert_eq!(v["start"]["accepted"], true);
    assert!(v["objective"]["total"].as_f64().unwrap() <= v["start"]["objective"].as_f64().unwrap() + 1e-6);
    // By default the start is the heuristic's; --no-start solves without one.
    let out = run(&[spec.to_str().unwrap(), "--time-limit", "20", "--out", dir.path().join("third").to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("start      heuristic objective"));
    let out = run(&[
        spec.to_str().unwrap(),
        "--no-start",
        "--time-limit",
        "20",
        "--out",
        dir.path().join("fourth").to_str().unwrap(),
    ]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("start      "));
    // A result of another spec (another mesh) is refused with the file named.
    let other = root.join("models/fig2b.toml");
    let out = run(&[
        other.to_str().unwrap(),
        "--start",
        result.to_str().unwrap(),
        "--time-limit",
        "1",
        "--out",
        dir.path().join("fifth").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains(&result.display().to_string()) && stderr.contains("another spec"), "{stderr}");
    // A JSON file that is not a result says so.
    let not_a_result = dir.path().join("other.json");
    std::fs::write(&not_a_result, r#"{"x": 1}"#).unwrap();
    let out = run(&[
        spec.to_str().unwrap(),
        "--start",
        not_a_result.to_str().unwrap(),
        "--out",
        dir.path().join("sixth").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("not a netspec result.json"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_corrupted_start_is_refused_with_the_rows_it_breaks() {
    let p = problem(START_SPEC);
    let f = pipeline::build(&p);
    let mut start = heuristics::start(&p, &Inputs::default(), 0.5, 0).unwrap();
    // Switch off one edge of the design: its ends become dead-ends (or an island appears).
    let e =
        start.active_edges().into_iter().find(|e| p.roles[e.index()] == netspec::spec::EdgeRole::Candidate).unwrap();
    start.active[e.index()] = false;
    let (x, report) = pipeline::prepare_start(&p, &f, &start, "corrupted");
    assert!(x.is_none());
    assert!(!report.accepted);
    let reason = report.reason.unwrap();
    assert!(
        reason.contains("violations of the model")
            || reason.contains("connectivity")
            || reason.contains("cannot reach"),
        "{reason}"
    );
}

#[test]
fn search_results_carry_the_independent_checks() {
    let p = load("fixtures/specs/tiny_floorplan.toml");
    let f = pipeline::build(&p);
    for method in [SearchMethod::Heuristic, SearchMethod::Anneal] {
        let r = run_search(&p, &f, method, 0.5, 1, 1);
        assert!(r.network.is_some(), "{method:?}");
        assert!(
            r.validity.valid,
            "{method:?}: {:?} {:?}",
            r.validity.design_violations,
            r.validity.milp_check.as_ref().map(|c| &c.violations)
        );
        assert!(r.validity.milp_check.as_ref().unwrap().is_feasible());
        assert_eq!(r.validity.objective_agrees, Some(true));
        assert_eq!(r.solve.solver, method.name());
        assert_eq!(r.solve.termination.label(), "limit(time)");
        assert!(r.solve.dual_bound.is_none() && r.solve.gap.is_none());
        assert_eq!(r.rooms.as_ref().unwrap().chosen.len(), r.network.as_ref().unwrap().rooms.len());
    }
}

#[test]
fn solve_and_compare_take_the_searches_as_solvers() {
    let dir = tempfile::tempdir().unwrap();
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/specs/tiny_network.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .args(["solve"])
        .arg(&spec)
        .args(["--solver", "heuristic", "--time-limit", "0.5", "--out"])
        .arg(dir.path().join("h"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("validity   valid"), "{stdout}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("h/result.json")).unwrap()).unwrap();
    assert_eq!(v["solve"]["solver"], "heuristic");
    assert_eq!(v["validity"]["valid"], true);
    assert!(dir.path().join("h/network.png").exists());
    // The budget is work, not the clock (nor what the model's build left of it): the same seed
    // gives the same design, one search or two side by side.
    for threads in ["1", "2"] {
        let designs: Vec<serde_json::Value> = ["a", "b"]
            .iter()
            .map(|run| {
                let to = dir.path().join(format!("seed-{threads}-{run}"));
                let out = Command::new(env!("CARGO_BIN_EXE_netspec"))
                    .arg("solve")
                    .arg(&spec)
                    .args(["--solver", "heuristic", "--time-limit", "0.3", "--seed", "11", "--threads", threads])
                    .arg("--out")
                    .arg(&to)
                    .output()
                    .unwrap();
                assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
                let v: serde_json::Value =
                    serde_json::from_str(&std::fs::read_to_string(to.join("result.json")).unwrap()).unwrap();
                v["network"].clone()
            })
            .collect();
        assert_eq!(designs[0], designs[1], "--threads {threads}: the same seed gave two designs");
    }
    // An option a search cannot honour is refused.
    let out = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .arg("solve")
        .arg(&spec)
        .args(["--solver", "anneal", "--gap", "0.1"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("`--gap` is not supported by the anneal search"));
    // compare lists them beside a MILP backend.
    let cmp = dir.path().join("cmp");
    let out = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .arg("compare")
        .arg(&spec)
        .args(["--solvers", "highs,heuristic,anneal", "--time-limit", "1", "--out"])
        .arg(&cmp)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let records: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(cmp.join("results.json")).unwrap()).unwrap();
    let runs = records["records"].as_array().unwrap();
    assert_eq!(runs.len(), 3);
    for r in runs {
        assert_eq!(r["valid"], true, "{r}");
    }
    assert_eq!(runs[1]["solver"], "heuristic");
    assert_eq!(runs[1]["status"], "limit(time)");
    assert!(std::fs::read_to_string(cmp.join("bars.svg")).unwrap().contains(r#"data-solver="anneal""#));
}

/// A random small spec: grid size, sinks, boundary role, coverage, every switch.
fn random_spec() -> impl Strategy<Value = String> {
    let weight = prop_oneof![Just("0".to_string()), Just("2".to_string()), Just("\"forbid\"".to_string())];
    (
        (2usize..7, 2usize..7, prop_oneof![Just("wall"), Just("road"), Just("candidate")], 1u32..4),
        (weight.clone(), weight.clone(), weight, any::<bool>(), any::<bool>()),
        (proptest::collection::vec(0u32..64, 1..4), any::<bool>(), 0u32..3),
    )
        .prop_map(|((w, h, boundary, range), (zz, tc, tj, dead_ends, branches), (sinks, all_boundary, distance))| {
            let nv = ((w + 1) * (h + 1)) as u32;
            let sinks: Vec<String> = sinks.iter().map(|s| (s % nv).to_string()).collect();
            let all_boundary = all_boundary || boundary == "road";
            format!(
                "name = \"random\"\nboundary = \"{boundary}\"\n[mesh]\ngrid = {{ width = {w}, height = {h} }}\n[sinks]\nall_boundary = {all_boundary}\nvertices = [{}]\n[coverage]\nrange = {range}\n[weights]\nlength = 1\ndistance = {distance}\nzigzag = {zz}\ntoo_close = {tc}\nt_junction = {tj}\n[features]\ndead_ends = \"{}\"\nbranches = \"{}\"\n",
                sinks.join(", "),
                if dead_ends { "forbid" } else { "allow" },
                if branches { "forbid" } else { "allow" },
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Whatever a search returns is valid by the validator, or it returns nothing.
    #[test]
    fn searches_return_valid_designs_or_none(text in random_spec(), seed in 0u64..1000) {
        let p = Spec::from_toml(&text).unwrap().resolve(Path::new(".")).unwrap();
        let inputs = Inputs::default();
        let h = heuristics::heuristic(&p, &inputs, &Options { time_limit: 0.2, seed, max_designs: Some(1), ..Options::default() });
        let a = heuristics::anneal(&p, &inputs, &AnnealOptions { time_limit: 0.1, seed, passes: 2, ..AnnealOptions::default() });
        for out in [h, a] {
            if let Some(net) = &out.network {
                prop_assert!(design::validate(&p, net, None).is_empty(), "{text}\n{:?}", design::validate(&p, net, None));
                prop_assert_eq!(out.objective, Some(Objective::of(&p, net).total));
            }
            prop_assert_eq!(out.network.is_none() && out.stop == Stop::Infeasible, out.infeasible.is_some() && out.network.is_none());
        }
    }

    /// Repair returns a valid design or nothing, from any set of active edges.
    #[test]
    fn repair_returns_valid_designs_or_none(text in random_spec(), bits in proptest::collection::vec(any::<bool>(), 120)) {
        let p = Spec::from_toml(&text).unwrap().resolve(Path::new(".")).unwrap();
        let active: Vec<bool> = (0..p.mesh.num_edges()).map(|i| bits[i % bits.len()]).collect();
        let net = Network { active, directions: Vec::new(), labels: Vec::new(), rooms: Vec::new() };
        if let Some(fixed) = heuristics::repair(&p, &Inputs::default(), &net) {
            prop_assert!(design::validate(&p, &fixed, None).is_empty());
        }
    }
}

/// Burns one core until `stop` is set: a machine busy with something else.
fn busy(stop: &std::sync::atomic::AtomicBool) {
    let mut x = 0u64;
    while !stop.load(std::sync::atomic::Ordering::Relaxed) {
        x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
    }
}

#[test]
fn the_budget_is_work_so_a_seed_gives_the_same_design_on_an_idle_or_a_busy_machine() {
    // A street level and a game level (rooms: tiling, traversal); a budget a search spends
    // many times over (restarts, local search), far below the wall-clock net.
    for (path, limit) in [("models/fig2d.toml", 0.4), ("models/fig11a.toml", 0.4)] {
        let p = load(path);
        let owned = OwnedInputs::enumerate(&p);
        let inputs = owned.inputs();
        let opts = Options { time_limit: limit, seed: 7, ..Options::default() };
        let idle = heuristics::heuristic(&p, &inputs, &opts);
        let stop = std::sync::atomic::AtomicBool::new(false);
        let loaded = std::thread::scope(|scope| {
            scope.spawn(|| busy(&stop));
            let out = heuristics::heuristic(&p, &inputs, &opts);
            stop.store(true, std::sync::atomic::Ordering::Relaxed);
            out
        });
        // Both stopped by work, not by the clock's net.
        for out in [&idle, &loaded] {
            assert!(
                out.stats.work >= heuristics::budget::units(limit),
                "{path}: stopped by the clock: {:?}",
                out.stats
            );
        }
        assert!(idle.stats.constructions > 1, "{path}: one construction only: {:?}", idle.stats);
        assert_eq!(idle.network, loaded.network, "{path}: the same seed gave two designs");
        assert_eq!(idle.objective, loaded.objective, "{path}");
        assert_eq!(idle.stats, loaded.stats, "{path}: the same search did different work");
        assert_valid(&p, &inputs, idle.network.as_ref().expect("a design"));
    }
}

#[test]
fn side_by_side_searches_give_the_same_design_whatever_their_scheduling() {
    let p = load("models/fig11a.toml");
    let owned = OwnedInputs::enumerate(&p);
    let inputs = owned.inputs();
    // With a budget, and without one but a first-design allowance (the least work's design).
    for opts in [
        Options { time_limit: 0.1, seed: 3, threads: 2, ..Options::default() },
        Options { time_limit: 0.0, first_design_limit: Some(60.0), seed: 3, threads: 3, ..Options::default() },
    ] {
        let runs: Vec<_> = (0..3)
            .map(|k| {
                let stop = std::sync::atomic::AtomicBool::new(false);
                std::thread::scope(|scope| {
                    // Every other run shares the machine with a busy thread.
                    if k % 2 == 1 {
                        scope.spawn(|| busy(&stop));
                    }
                    let out = heuristics::heuristic(&p, &inputs, &opts);
                    stop.store(true, std::sync::atomic::Ordering::Relaxed);
                    out
                })
            })
            .collect();
        let net = runs[0].network.as_ref().expect("a design");
        assert_valid(&p, &inputs, net);
        for r in &runs[1..] {
            assert_eq!(r.network.as_ref(), Some(net), "{opts:?}: the same seed gave two designs");
            assert_eq!(r.objective, runs[0].objective);
        }
    }
}
