//! The everyday solve loop: trivially infeasible models, honest "optimal", time limits
//! CBC does not keep by itself, interrupts, option errors naming the field, `.gz` model files,
//! solution files, MIP starts checked before use, raw solver parameters.

use crate::conformance::models;
use crate::network::problem;
use netspec::milp::Model;
use netspec::pipeline;
use netspec::solvers::{Interrupt, LimitKind, RawParam, SolveOptions, SolverErrorKind, SolverKind, Termination};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

fn models_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("models")
}

/// An 8×6 case, made small: a 5×5 grid, all boundary sinks, coverage 3, dead-ends
/// forbidden, length 1 and the paper's `0*` distance weight (1e-4). The optimum is 5.0004
/// (SCIP and CBC agree); HiGHS's own default gap (1e-4 relative) stopped it at 5.0006 and called
/// that optimal.
const ZERO_STAR: &str = r#"
name = "zero_star"
boundary = "wall"
formulation = "tight"
[mesh]
grid = { width = 5, height = 5, spacing = 1.0 }
[sinks]
all_boundary = true
[coverage]
range = 3
[weights]
length = 1
distance = 1e-4
[features]
dead_ends = "forbid"
"#;

#[test]
fn optimal_is_true_for_the_papers_zero_star_weights() {
    let p = problem(ZERO_STAR);
    let nm = pipeline::build(&p);
    let r = pipeline::solve_built(&p, &nm, SolverKind::Highs, &SolveOptions::default()).unwrap();
    assert_eq!(r.solve.termination, Termination::Optimal);
    let obj = r.solve.objective.unwrap();
    assert!((obj - 5.0004).abs() < 1e-9, "HiGHS called {obj} optimal; the optimum is 5.0004");
    assert!(r.validity.valid);
}

/// The objective split (`solvers::split`) on the same weights with the strong recipe: every
/// backend that takes a start solves in two phases — phase 1 proves the length 5, phase 2 the
/// whole objective — and ends at the same proven optimum 5.0004 as the one-phase solve.
#[test]
fn objective_split_proves_the_zero_star_optimum_on_every_backend() {
    let p = problem(&ZERO_STAR.replace("formulation = \"tight\"", "formulation = \"strong\""));
    let f = pipeline::build(&p);
    assert!(pipeline::Strategy::for_problem(&p, &f).split_objective);
    let o = SolveOptions { time_limit: Some(60.0), threads: Some(1), ..Default::default() };
    for k in crate::network::backends(true) {
        let r = pipeline::solve_from(&p, &f, k, &o, &pipeline::default_start(o.time_limit)).unwrap();
        assert_eq!(r.solve.termination, Termination::Optimal, "{k}: {}", r.solve.status_line());
        assert!((r.solve.objective.unwrap() - 5.0004).abs() < 1e-9, "{k}: {:?}", r.solve.objective);
        assert!(r.validity.valid, "{k}: {:?}", r.validity);
        assert_eq!(r.solver_hints.is_empty(), k != SolverKind::Highs, "{k}: {:?}", r.solver_hints);
        if k.instance().unwrap().capabilities().mip_start {
            let split = r.split.as_ref().unwrap_or_else(|| panic!("{k}: no split"));
            assert_eq!(split.quantum, 1.0, "{k}");
            assert_eq!(split.phase1.termination, Termination::Optimal, "{k}");
            assert!((split.phase1.objective.unwrap() - 5.0).abs() < 1e-9, "{k}: phase 1 {:?}", split.phase1.objective);
            assert_eq!(split.phase2.as_ref().map(|p| p.termination.clone()), Some(Termination::Optimal), "{k}");
        }
    }
    // Switched off in the spec's [solver] section, the strong recipe solves in one phase to the
    // same optimum; the model is the same.
    let off = problem(&format!(
        "{}[solver]\nsplit_objective = false\n",
        ZERO_STAR.replace("formulation = \"tight\"", "formulation = \"strong\"")
    ));
    let f = pipeline::build(&off);
    assert_eq!(f.recipe.label, "strong");
    assert!(!pipeline::Strategy::for_problem(&off, &f).split_objective);
    let r = pipeline::solve_from(&off, &f, SolverKind::Highs, &o, &pipeline::default_start(o.time_limit)).unwrap();
    assert!(r.split.is_none());
    assert_eq!(r.solve.termination, Termination::Optimal);
    assert!((r.solve.objective.unwrap() - 5.0004).abs() < 1e-9, "{:?}", r.solve.objective);
}

/// The strong recipe without `symmetric_flow`, as a `[formulation]` table.
const SYMMETRY_OFF: &str = "[formulation]\nrecipe = \"strong\"\nsymmetric_flow = false";

/// Solves the zero-star grid with `formulation` (TOML in place of its `formulation = "tight"`
/// line) and `solver` (lines of its `[solver]` section) on HiGHS from the default start, asserts
/// the proven optimum 5.0004 and a valid design, and returns the result with the recipe's label.
fn solve_zero_star(formulation: &str, solver: &str, o: &SolveOptions, what: &str) -> (pipeline::DesignResult, String) {
    let p = problem(&format!("{}[solver]\n{solver}\n", ZERO_STAR.replace("formulation = \"tight\"", formulation)));
    let f = pipeline::build(&p);
    let r = pipeline::solve_from(&p, &f, SolverKind::Highs, o, &pipeline::default_start(o.time_limit)).unwrap();
    assert_eq!(r.solve.termination, Termination::Optimal, "{what}: {}", r.solve.status_line());
    assert!((r.solve.objective.unwrap() - 5.0004).abs() < 1e-9, "{what}: {:?}", r.solve.objective);
    assert!(r.validity.valid, "{what}");
    (r, f.recipe.label)
}

/// The solve strategy's backend hint for the strong recipe (`Solver::strategy_hints`): HiGHS gets
/// `mip_pscost_minreliable=0` and the result says so; the user's own value for it, or
/// `solver_tuning = false`, replaces it and the result lists none; every way ends at the same
/// proven optimum. (`symmetric_flow` is off: the zero-star grid is symmetric, and its own hint,
/// `presolve=off`, is tested with it in `network::symmetric_grids_…`.)
#[test]
fn the_strong_recipes_solver_hint_reaches_highs_and_yields_to_the_user() {
    let strong = SYMMETRY_OFF;
    let o = SolveOptions { time_limit: Some(60.0), threads: Some(1), ..Default::default() };
    let (r, _) = solve_zero_star(strong, "", &o, "hinted");
    assert_eq!(r.solver_hints, ["highs.mip_pscost_minreliable=0"]);
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["solver_hints"][0], "highs.mip_pscost_minreliable=0");

    let own = SolveOptions { params: vec!["highs.mip_pscost_minreliable=8".parse::<RawParam>().unwrap()], ..o.clone() };
    let (r, _) = solve_zero_star(strong, "", &own, "user's value");
    assert!(r.solver_hints.is_empty(), "{:?}", r.solver_hints);

    let (r, label) = solve_zero_star(SYMMETRY_OFF, "solver_tuning = false", &o, "tuning off");
    assert_eq!(label, "strong(symmetric_flow=false)");
    assert!(r.solver_hints.is_empty());
    assert!(serde_json::to_value(&r).unwrap().get("solver_hints").is_none());
    // Other backends get no hint: checked per backend in
    // `objective_split_proves_the_zero_star_optimum_on_every_backend`.
}

/// With two threads the strong recipe also hands HiGHS its parallel tree search
/// (`parallel=on`); it proves the same optimum, and `parallel_search = false` or the user's own
/// `highs.parallel` leaves it out (`symmetric_flow` off, as above).
#[test]
fn the_parallel_tree_search_reaches_highs_at_two_threads_and_yields_to_the_user() {
    let strong = SYMMETRY_OFF;
    let o = SolveOptions { time_limit: Some(60.0), threads: Some(2), ..Default::default() };
    let (r, _) = solve_zero_star(strong, "", &o, "parallel");
    assert_eq!(r.solver_hints, ["highs.mip_pscost_minreliable=0", "highs.parallel=on"]);

    let own = SolveOptions { params: vec!["highs.parallel=off".parse::<RawParam>().unwrap()], ..o.clone() };
    let (r, _) = solve_zero_star(strong, "", &own, "user's value");
    assert_eq!(r.solver_hints, ["highs.mip_pscost_minreliable=0"]);

    let (r, label) = solve_zero_star(SYMMETRY_OFF, "parallel_search = false", &o, "serial");
    assert_eq!(label, "strong(symmetric_flow=false)");
    assert_eq!(r.solver_hints, ["highs.mip_pscost_minreliable=0"]);
}

#[test]
fn one_by_one_walled_grid_is_infeasible_on_every_backend() {
    let p = problem("name = \"g1\"\nboundary = \"wall\"\n[mesh]\ngrid = { width = 1, height = 1, spacing = 1.0 }\n[sinks]\nall_boundary = true\n[coverage]\nrange = 1\n");
    let nm = pipeline::build(&p);
    for k in crate::network::backends(true) {
        let r = pipeline::solve_built(&p, &nm, k, &SolveOptions::default()).unwrap();
        assert_eq!(r.solve.termination, Termination::Infeasible, "{k}");
        assert!(!r.design_found, "{k}");
        let why = r.solve.infeasibility.as_ref().unwrap_or_else(|| panic!("{k}: no row named"));
        assert!(why.to_string().contains("row `cov"), "{k}: {why}");
    }
}

/// A third case: a mesh of two separate squares, the sink on one, coverage needing
/// the other. No design exists (the far square would be an island); every backend, under every
/// recipe, says infeasible, never "optimal".
#[test]
fn two_separate_squares_are_infeasible_on_every_backend() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("squares.json"),
        r#"{"vertices": [[0,0],[1,0],[1,1],[0,1],[3,0],[4,0],[4,1],[3,1]], "faces": [[0,1,2,3],[4,5,6,7]]}"#,
    )
    .unwrap();
    for recipe in ["paper", "tight", "strong"] {
        let spec = dir.path().join(format!("{recipe}.toml"));
        let text = format!("name = \"squares\"\nboundary = \"candidate\"\nformulation = \"{recipe}\"\n[mesh]\nfile = \"squares.json\"\n[sinks]\nvertices = [0]\n[coverage]\nrange = 1\n");
        std::fs::write(&spec, text).unwrap();
        let p = netspec::spec::Spec::load(&spec).unwrap().resolve(dir.path()).unwrap();
        let nm = pipeline::build(&p);
        for k in crate::network::backends(true) {
            let r = pipeline::solve_built(&p, &nm, k, &SolveOptions { time_limit: Some(60.0), ..Default::default() })
                .unwrap();
            assert_eq!(r.solve.termination, Termination::Infeasible, "{k} {recipe}: {}", r.solve.status_line());
            assert!(!r.design_found, "{k} {recipe}");
        }
    }
}

/// `solve`'s status line says apart why it stopped and whether a design exists: a time limit
/// with a design, a time limit without one (no start, no time), and infeasible.
#[test]
fn status_line_says_why_and_whether() {
    let dir = tempfile::tempdir().unwrap();
    let fig2b = models_dir().join("fig2b.toml");
    let run = |args: &[&str]| {
        let out = netspec().arg("solve").args(args).arg("--out").arg(dir.path().join("o")).output().unwrap();
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    // A start and one second: the solver stops at its limit with the start or better.
    let with = run(&[fig2b.to_str().unwrap(), "--time-limit", "1"]);
    assert!(with.lines().any(|l| l.starts_with("status     limit(time), design found (")), "{with}");
    // No start and no time: nothing to show.
    let without = run(&[fig2b.to_str().unwrap(), "--time-limit", "0", "--no-start"]);
    assert!(without.lines().any(|l| l.starts_with("status     limit(time), no design")), "{without}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("o/result.json")).unwrap()).unwrap();
    assert_eq!(v["design_found"], false);
}

/// fig9b1 makes CBC sit in its preprocessing (no clock checks) far past a short limit: netspec's
/// worker stops it and a result still comes back, marked as stopped by the time limit.
#[cfg(feature = "cbc")]
#[test]
fn cbc_stuck_in_its_root_still_returns_a_result() {
    let spec = netspec::spec::Spec::load(&models_dir().join("fig9b1.toml")).unwrap();
    let p = spec.resolve(&models_dir()).unwrap();
    let nm = pipeline::build(&p);
    let o = SolveOptions { time_limit: Some(1.0), ..Default::default() };
    let r = pipeline::solve_built(&p, &nm, SolverKind::Cbc, &o).expect("a result, not an error");
    assert_eq!(r.solve.termination, Termination::Limit(LimitKind::Time));
    assert_eq!(r.design_found, r.solve.objective.is_some());
    // The same, stopped by an interrupt instead.
    let stop = Interrupt::new();
    let trigger = stop.clone();
    let o = SolveOptions { interrupt: Some(stop), ..Default::default() };
    let t = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(300));
        trigger.trigger();
    });
    let r = pipeline::solve_built(&p, &nm, SolverKind::Cbc, &o).expect("a result, not an error");
    t.join().unwrap();
    assert_eq!(r.solve.termination, Termination::Limit(LimitKind::Interrupt));
}

/// An interrupt stops every backend on a model none of them finishes quickly, keeps the
/// incumbent (the all-slack point every solver finds at once), and is reported as such.
#[test]
fn interrupt_stops_every_backend_and_keeps_the_incumbent() {
    let (model, _) = models::market_split(4, 30, 7, false);
    for k in SolverKind::compiled().into_iter().filter(|k| *k != SolverKind::GoodLp) {
        let stop = Interrupt::new();
        let trigger = stop.clone();
        let t = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(700));
            trigger.trigger();
        });
        let o = SolveOptions { interrupt: Some(stop), ..Default::default() };
        let r = k.instance().unwrap().solve(&model, &o).unwrap();
        t.join().unwrap();
        assert_eq!(r.termination, Termination::Limit(LimitKind::Interrupt), "{k}");
        assert_eq!(r.termination.label(), "interrupted");
        crate::conformance::assert_checked(&model, &r);
        // An interrupt made before the solve returns at once, without a solution.
        let done = Interrupt::new();
        done.trigger();
        let r =
            k.instance().unwrap().solve(&model, &SolveOptions { interrupt: Some(done), ..Default::default() }).unwrap();
        assert_eq!(r.termination, Termination::Limit(LimitKind::Interrupt), "{k}");
    }
}

/// A MIP start that fails netspec's checker is reported and never handed over; one that passes
/// is handed over and reported as accepted.
#[test]
fn mip_starts_are_checked_before_use() {
    let model = models::knapsack();
    for k in SolverKind::compiled().into_iter().filter(|k| k.instance().unwrap().capabilities().mip_start) {
        let bad = vec![1.0; model.num_vars()]; // over capacity
        let r =
            k.instance().unwrap().solve(&model, &SolveOptions { mip_start: Some(bad), ..Default::default() }).unwrap();
        let st = r.mip_start.clone().unwrap();
        assert!(
            !st.accepted && st.violations == 1 && st.first_violation.as_deref().unwrap().contains("cap"),
            "{k}: {st:?}"
        );
        assert_eq!(r.termination, Termination::Optimal, "{k}");
        let mut good = vec![0.0; model.num_vars()];
        good[0] = 1.0;
        let r =
            k.instance().unwrap().solve(&model, &SolveOptions { mip_start: Some(good), ..Default::default() }).unwrap();
        assert!(r.mip_start.unwrap().accepted, "{k}");
    }
}

#[test]
fn raw_parameters_reach_the_backend_and_unknown_ones_are_refused() {
    let model = models::knapsack();
    let cases: Vec<(SolverKind, &str, &str)> = vec![
        (SolverKind::Highs, "mip_heuristic_effort", "0.3"),
        (SolverKind::Scip, "limits/nodes", "1000"),
        (SolverKind::Cbc, "cuts", "off"),
    ];
    for (k, name, value) in cases.into_iter().filter(|(k, ..)| k.is_compiled()) {
        let ok = RawParam { solver: k, name: name.into(), value: value.into() };
        // Parameters of another backend are not this one's: a list can serve several.
        let other = RawParam {
            solver: if k == SolverKind::Highs { SolverKind::Scip } else { SolverKind::Highs },
            name: "whatever".into(),
            value: "1".into(),
        };
        let r = k
            .instance()
            .unwrap()
            .solve(&model, &SolveOptions { params: vec![ok, other], ..Default::default() })
            .unwrap();
        assert_eq!(r.termination, Termination::Optimal, "{k}");
        let bad = RawParam { solver: k, name: "no_such_parameter".into(), value: "1".into() };
        let e =
            k.instance().unwrap().solve(&model, &SolveOptions { params: vec![bad], ..Default::default() }).unwrap_err();
        assert!(
            matches!(&e.kind, SolverErrorKind::Param { name, .. } if name == &format!("{k}.no_such_parameter")),
            "{k}: {e}"
        );
    }
    if SolverKind::Cbc.is_compiled() {
        let bad = RawParam { solver: SolverKind::Cbc, name: "cuts".into(), value: "maybe".into() };
        let e = SolverKind::Cbc
            .instance()
            .unwrap()
            .solve(&model, &SolveOptions { params: vec![bad], ..Default::default() })
            .unwrap_err();
        assert!(matches!(e.kind, SolverErrorKind::Param { .. }), "{e}");
    }
    let micro = RawParam { solver: SolverKind::Microlp, name: "x".into(), value: "1".into() };
    if SolverKind::Microlp.is_compiled() {
        let e = SolverKind::Microlp
            .instance()
            .unwrap()
            .solve(&model, &SolveOptions { params: vec![micro], ..Default::default() })
            .unwrap_err();
        assert!(matches!(e.kind, SolverErrorKind::Unsupported { option: "params", .. }), "{e}");
    }
}

#[test]
fn gz_models_read_and_write() {
    let dir = tempfile::tempdir().unwrap();
    let m: Model = models::knapsack();
    for name in ["k.mps.gz", "k.lp.gz"] {
        let p = dir.path().join(name);
        netspec::io::write_model_file(&m, &p).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        assert_eq!(&bytes[..2], &[0x1f, 0x8b], "{name} is not gzip");
        let back = netspec::io::read_model_file(&p).unwrap().model;
        assert_eq!(back.num_vars(), m.num_vars());
        assert_eq!(back.vars(), m.vars());
    }
    // And through the command line, with a solution file out and back in as a start.
    let p = dir.path().join("k.mps.gz");
    let sol = dir.path().join("k.sol");
    let out = netspec().arg("solve-file").arg(&p).arg("--sol").arg(&sol).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&sol).unwrap();
    assert!(text.lines().filter(|l| !l.starts_with('#')).count() == m.num_vars(), "{text}");
    let out = netspec().arg("solve-file").arg(&p).arg("--start").arg(&sol).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && stdout.contains("start      passed netspec's check"), "{stdout}");
    // A start that fails the check is reported and not used.
    let bad = dir.path().join("bad.sol");
    std::fs::write(&bad, (0..m.num_vars()).map(|j| format!("x{j} 1\n")).collect::<String>()).unwrap();
    let out = netspec().arg("solve-file").arg(&p).arg("--start").arg(&bad).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && stdout.contains("start      REJECTED"), "{stdout}");
    assert!(stdout.contains("status     optimal"), "{stdout}");
}

#[test]
fn option_errors_name_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("s.toml");
    std::fs::write(&spec, format!("{ZERO_STAR}\n[solver]\ngap = -1\n")).unwrap();
    let out = netspec().arg("solve").arg(&spec).arg("--out").arg(dir.path()).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("s.toml: solver.gap must be a finite number ≥ 0, got -1"), "{stderr}");
    let lp = dir.path().join("m.lp");
    std::fs::write(&lp, "Minimize\n obj: x\nSubject To\n c: x >= 1\nEnd\n").unwrap();
    let out = netspec().arg("solve-file").arg(&lp).arg("--time-limit=-2").output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("--time-limit must be a number of seconds ≥ 0"), "{stderr}");
    // An infinite limit is no limit, on every backend (SCIP used to fail in paramset.c).
    for k in ["highs", "cbc", "scip", "microlp"] {
        let out = netspec().arg("solve-file").arg(&lp).args(["--time-limit", "inf", "--solver", k]).output().unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success() && stdout.contains("status     optimal"),
            "{k}: {stdout}{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let out = netspec().arg("solve-file").arg(&lp).args(["--param", "highs.no_such=1"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("parameter `highs.no_such`: HiGHS has no such option"), "{stderr}");
}

/// The empty-row model, through the command line: infeasible, the row named.
#[test]
fn empty_row_lp_is_infeasible_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let lp = dir.path().join("m.lp");
    std::fs::write(&lp, "Minimize\n obj:\nSubject To\n c: >= 1\nEnd\n").unwrap();
    for k in ["highs", "cbc", "scip", "microlp"] {
        let out = netspec().arg("solve-file").arg(&lp).args(["--solver", k]).output().unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{k}: {stdout}");
        assert!(stdout.contains("status     infeasible (found by netspec before solving): row `c`"), "{k}: {stdout}");
    }
}

fn sigint(child: &Child) {
    // SAFETY: signalling our own child process.
    unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) };
}

/// Waits up to `secs` for the child; kills it and fails if it is still running.
fn wait(mut child: Child, secs: u64) -> std::process::Output {
    for _ in 0..secs * 20 {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    panic!("the command did not end {secs} s after the interrupt");
}

/// Ctrl-C (SIGINT sent from the test) on `netspec solve`: the solver stops, a valid
/// result.json with the incumbent is written, status `interrupted`, exit code 130.
#[test]
fn interrupted_solve_writes_the_incumbent() {
    let dir = tempfile::tempdir().unwrap();
    let child = netspec()
        .arg("solve")
        .arg(models_dir().join("fig2b.toml"))
        .args(["--solver", "highs", "--time-limit", "120", "--out"])
        .arg(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_secs(4));
    sigint(&child);
    let out = wait(child, 30);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(130), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("status     interrupted, design found ("), "{stdout}");
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("result.json")).unwrap()).unwrap();
    assert_eq!(r["solve"]["termination"]["reason"], "limit");
    assert_eq!(r["solve"]["termination"]["detail"], "interrupt");
    assert_eq!(r["design_found"], true);
    assert_eq!(r["validity"]["valid"], true);
}

/// The same for `solve-file` on CBC (stopped in its worker by CBC's own handler), which keeps
/// its incumbent.
#[cfg(feature = "cbc")]
#[test]
fn interrupted_solve_file_keeps_the_incumbent() {
    let dir = tempfile::tempdir().unwrap();
    let (model, _) = models::market_split(4, 30, 7, false);
    let lp = dir.path().join("ms.lp");
    netspec::io::write_model_file(&model, &lp).unwrap();
    let json = dir.path().join("r.json");
    let child = netspec()
        .arg("solve-file")
        .arg(&lp)
        .args(["--solver", "cbc", "--json"])
        .arg(&json)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_secs(2));
    sigint(&child);
    let out = wait(child, 20);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(130), "{stdout}");
    let r: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(r["result"]["termination"]["detail"], "interrupt");
    assert_eq!(r["solution_found"], true);
    assert_eq!(r["valid"], true);
}

/// `compare`: the running child is stopped, its record kept as `interrupted`, the tables
/// written, no further run started.
#[test]
fn interrupted_compare_keeps_its_records() {
    let dir = tempfile::tempdir().unwrap();
    let child = netspec()
        .arg("compare")
        .arg(models_dir().join("fig2b.toml"))
        .args(["--solvers", "highs,scip", "--time-limit", "120", "--out"])
        .arg(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_secs(5));
    sigint(&child);
    let out = wait(child, 30);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(130), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    let all: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("results.json")).unwrap()).unwrap();
    let records = all["records"].as_array().unwrap();
    assert_eq!(records.len(), 1, "no run after the interrupt: {records:?}");
    assert_eq!(records[0]["status"], "interrupted");
    assert_eq!(records[0]["valid"], true);
}

/// `city`: Ctrl-C once region 0 has finished: the command ends with 130, writes city.json with
/// region 0's levels kept, and any level it did not run is marked skipped for the interrupt.
#[test]
fn interrupted_city_keeps_finished_regions() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/city/two-regions.toml");
    let child = netspec()
        .args(["city", spec.to_str().unwrap(), "--threads", "1", "--out", out.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let first_done = out.join("regions/00-region-0/L3/state.json");
    let t0 = std::time::Instant::now();
    while !first_done.exists() {
        assert!(t0.elapsed() < Duration::from_secs(120), "region 0 never finished");
        std::thread::sleep(Duration::from_millis(10));
    }
    sigint(&child);
    let o = wait(child, 60);
    assert_eq!(o.status.code(), Some(130), "{}", String::from_utf8_lossy(&o.stderr));
    let r: netspec::urban::CityResult =
        serde_json::from_str(&std::fs::read_to_string(out.join("city.json")).unwrap()).unwrap();
    assert!(r.regions[0].levels.iter().all(|l| l.state == "solved"), "{:?}", r.regions[0].levels);
    for l in r.regions.iter().flat_map(|r| &r.levels) {
        assert!(l.state != "skipped" || l.message.as_deref() == Some("interrupted"), "{l:?}");
    }
}

/// The `lns` strategy switch (`--formulation strong:lns=on`): Fig. 2c's heuristic start (184) is
/// improved by windows solved from it before the full MILP, which starts from the best; the
/// search is reported in `result.json`, and the design is checked and valid. Unset, the switch
/// is on for `strong` models from `pipeline::strategy::LNS_FROM_NONZEROS` nonzeros.
#[test]
fn lns_improves_the_start_before_the_milp() {
    // `netspec solve SPEC` with HiGHS on one thread: its result.json, the run having succeeded.
    let solved = |spec: &str, formulation: &str, limit: &str| -> serde_json::Value {
        let out = tempfile::tempdir().unwrap();
        let run = netspec()
            .args(["solve", spec, "--solver", "highs", "--formulation", formulation])
            .args(["--time-limit", limit, "--threads", "1", "--out"])
            .arg(out.path())
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap();
        assert!(run.status.success(), "{spec}: {}", String::from_utf8_lossy(&run.stderr));
        serde_json::from_str(&std::fs::read_to_string(out.path().join("result.json")).unwrap()).unwrap()
    };
    let r = solved("models/fig2c.toml", "strong:lns=on", "4");
    let lns = &r["lns"];
    let (start, best) = (lns["start_objective"].as_f64().unwrap(), lns["objective"].as_f64().unwrap());
    assert_eq!(start, r["start"]["objective"].as_f64().unwrap());
    assert!(lns["windows"].as_u64().unwrap() >= 1 && lns["improvements"].as_u64().unwrap() >= 1, "{lns}");
    assert!(best < start, "{lns}");
    assert_eq!(lns["trace"].as_array().unwrap().len() as u64, lns["improvements"].as_u64().unwrap());
    assert!(r["objective"]["total"].as_f64().unwrap() <= best + 1e-6, "the MILP starts from the search's best");
    assert_eq!(r["validity"]["valid"], true);
    // By default only from `LNS_FROM_NONZEROS` (Fig. 2c: 33,957 nonzeros; Fig. 1b's level 4:
    // 63,896), and `lns=off` turns it off there.
    let searched = |spec: &str, formulation: &str| {
        let r = solved(spec, formulation, "1");
        assert_eq!(r["validity"]["valid"], true, "{spec}");
        r.get("lns").is_some()
    };
    assert!(!searched("models/fig2c.toml", "strong"));
    assert!(searched("models/streets/fig1b/L4/spec.json", "strong"));
    assert!(!searched("models/streets/fig1b/L4/spec.json", "strong:lns=off"));
}
