//! The conformance suite (in the spirit of MathOptInterface's `MOI.Test`): plain functions over
//! small models with known answers, instantiated for every compiled backend by one macro.
//! Every solution goes through the independent checker. A bug found in one backend becomes a
//! case here.

pub mod models;

use netspec::milp::{check_point, objectives_agree, Model, Tolerances};
use netspec::solvers::{LimitKind, SolveOptions, SolveResult, Solver, SolverErrorKind, SolverKind, Termination};
use std::time::Instant;

/// Solves and insists on an `Ok` result.
pub fn solve(kind: SolverKind, model: &Model, options: &SolveOptions) -> SolveResult {
    let solver = kind.instance().expect("compiled backend");
    match solver.solve(model, options) {
        Ok(r) => r,
        Err(e) => panic!("{kind} on {}: {e}", model.name),
    }
}

/// Asserts the result's primal point passes the independent checker and that the recomputed
/// objective matches the reported one.
pub fn assert_checked(model: &Model, r: &SolveResult) {
    let x = r.primal.as_ref().unwrap_or_else(|| panic!("{} on {}: no primal point ({})", r.solver, model.name, r.termination));
    let rep = check_point(model, x, &Tolerances::default());
    assert!(rep.is_feasible(), "{} on {}: checker found {:?}", r.solver, model.name, rep.violations);
    let obj = r.objective.expect("objective with a primal point");
    assert!(objectives_agree(rep.objective, obj, 1e-6), "{} on {}: solver objective {obj}, recomputed {}", r.solver, model.name, rep.objective);
}

/// Solves to optimality and checks the optimum against `expected`.
pub fn assert_optimal(kind: SolverKind, model: &Model, expected: f64) -> SolveResult {
    let r = solve(kind, model, &SolveOptions::default());
    assert_eq!(r.termination, Termination::Optimal, "{kind} on {}", model.name);
    assert_checked(model, &r);
    let obj = r.objective.unwrap();
    assert!(objectives_agree(obj, expected, 1e-6), "{kind} on {}: objective {obj}, expected {expected}", model.name);
    if let Some(b) = r.dual_bound {
        assert!(objectives_agree(b, expected, 1e-6), "{kind} on {}: bound {b}, expected {expected}", model.name);
    }
    if let Some(g) = r.gap {
        assert!(g <= 1e-6, "{kind}: gap {g} at optimality");
    }
    assert!(r.wall_time >= 0.0 && r.solver_version.chars().any(|c| c.is_ascii_digit()), "{kind}: version {:?}", r.solver_version);
    r
}

pub fn lp_max(kind: SolverKind) {
    assert_optimal(kind, &models::lp_max(), 11.0);
}

pub fn lp_free_vars(kind: SolverKind) {
    assert_optimal(kind, &models::lp_free_vars(), -2.0);
}

pub fn lp_ranged_eq(kind: SolverKind) {
    assert_optimal(kind, &models::lp_ranged_eq(), 6.0);
}

pub fn knapsack(kind: SolverKind) {
    let r = assert_optimal(kind, &models::knapsack(), models::knapsack_optimum());
    let x = r.primal.unwrap();
    assert!(x.iter().all(|v| *v == 0.0 || *v == 1.0 || (v.fract().abs() < 1e-9)), "{kind}: {x:?}");
}

pub fn general_integer(kind: SolverKind) {
    assert_optimal(kind, &models::general_integer(), models::general_integer_optimum());
}

pub fn max_with_constant(kind: SolverKind) {
    assert_optimal(kind, &models::max_with_constant(), 8.0);
}

pub fn empty_model(kind: SolverKind) {
    let r = assert_optimal(kind, &models::empty(), 7.0);
    assert_eq!(r.primal.as_deref(), Some(&[][..]));
}

fn assert_termination_in(kind: SolverKind, model: &Model, allowed: &[Termination]) {
    let r = solve(kind, model, &SolveOptions::default());
    assert!(allowed.contains(&r.termination), "{kind} on {}: got {}, expected one of {allowed:?}", model.name, r.termination);
    assert!(r.objective.is_none() || r.termination == Termination::Unbounded, "{kind}: objective on {}", r.termination);
}

pub fn infeasible_lp(kind: SolverKind) {
    assert_termination_in(kind, &models::infeasible_lp(), &[Termination::Infeasible]);
}

pub fn infeasible_mip(kind: SolverKind) {
    assert_termination_in(kind, &models::infeasible_mip(), &[Termination::Infeasible]);
}

pub fn unbounded_lp(kind: SolverKind) {
    assert_termination_in(kind, &models::unbounded_lp(), &[Termination::Unbounded, Termination::InfeasibleOrUnbounded]);
}

pub fn infeasible_or_unbounded(kind: SolverKind) {
    assert_termination_in(kind, &models::infeasible_or_unbounded(), &[Termination::Infeasible, Termination::InfeasibleOrUnbounded]);
}

/// Slack allowed beyond a time limit: process and model setup, the solver noticing the clock.
const TIME_MARGIN: f64 = 1.5;

pub fn time_limit_stops_hard_model(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let caps = solver.capabilities();
    let (model, _) = models::market_split(4, 30, 7, false);
    let o = SolveOptions { time_limit: Some(1.0), threads: caps.threads.then_some(1), ..Default::default() };
    if !caps.time_limit {
        let e = solver.solve(&model, &o).expect_err("unsupported option must be refused");
        assert!(matches!(e.kind, SolverErrorKind::Unsupported { option: "time_limit", .. }));
        return;
    }
    let t0 = Instant::now();
    let r = solve(kind, &model, &o);
    let wall = t0.elapsed().as_secs_f64();
    assert_eq!(r.termination, Termination::Limit(LimitKind::Time), "{kind}");
    // A solver that rounds the limit up to whole seconds gets one more second.
    let limit = if caps.time_limit_whole_seconds { 2.0 } else { 1.0 };
    assert!(wall <= limit + TIME_MARGIN, "{kind}: returned after {wall:.2} s for a 1 s limit");
    assert!(wall >= 0.5, "{kind}: returned after {wall:.2} s, before the limit could have mattered");
    // The trivial all-slack incumbent is found by every solver's heuristics; it must be kept.
    assert_checked(&model, &r);
}

pub fn mip_start_is_used(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let (model, planted) = models::market_split(4, 30, 11, true);
    let o = SolveOptions { time_limit: Some(0.5), mip_start: Some(planted), ..Default::default() };
    if !solver.capabilities().mip_start {
        let e = solver.solve(&model, &o).expect_err("unsupported option must be refused");
        assert!(matches!(e.kind, SolverErrorKind::Unsupported { option: "mip_start", .. }));
        return;
    }
    let r = solve(kind, &model, &o);
    assert_checked(&model, &r);
    // The planted point has objective 0; without the start no solver finds it in 0.5 s.
    assert_eq!(r.objective, Some(0.0), "{kind}: the MIP start was not used ({})", r.termination);
}

pub fn gap_limit_stops_early(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let model = models::multi_knapsack(60, 5, 3);
    let o = SolveOptions { rel_gap: Some(0.05), time_limit: Some(20.0), ..Default::default() };
    if !solver.capabilities().rel_gap {
        let e = solver.solve(&model, &o).expect_err("unsupported option must be refused");
        assert!(matches!(e.kind, SolverErrorKind::Unsupported { option: "rel_gap", .. }));
        return;
    }
    let r = solve(kind, &model, &o);
    assert_checked(&model, &r);
    assert!(
        matches!(r.termination, Termination::Optimal | Termination::Limit(LimitKind::Gap)),
        "{kind}: stopped by {} instead of the gap limit",
        r.termination
    );
    if let Some(g) = r.gap {
        assert!(g <= 0.05 + 1e-9, "{kind}: gap {g} above the 5% limit");
    }
}

pub fn node_limit(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let (model, _) = models::market_split(4, 30, 5, false);
    let o = SolveOptions { node_limit: Some(10), time_limit: Some(20.0), ..Default::default() };
    if !solver.capabilities().node_limit {
        let e = solver.solve(&model, &o).expect_err("unsupported option must be refused");
        assert!(matches!(e.kind, SolverErrorKind::Unsupported { option: "node_limit", .. }));
        return;
    }
    let r = solve(kind, &model, &o);
    assert_eq!(r.termination, Termination::Limit(LimitKind::Node), "{kind}");
    if let Some(n) = r.nodes {
        assert!(n <= 20, "{kind}: {n} nodes for a limit of 10");
    }
}

pub fn invalid_model_is_an_error(kind: SolverKind) {
    let mut m = models::lp_max();
    m.var_mut(netspec::milp::VarId(0)).lb = f64::NAN;
    let e = kind.instance().unwrap().solve(&m, &SolveOptions::default()).expect_err("NaN bound");
    assert!(matches!(e.kind, SolverErrorKind::InvalidModel(_)), "{kind}: {e}");
}

pub fn unsupported_options_are_refused(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let caps = solver.capabilities();
    let model = models::lp_max();
    let mut probes: Vec<(bool, SolveOptions)> = vec![
        (caps.seed, SolveOptions { seed: Some(1), ..Default::default() }),
        (caps.threads, SolveOptions { threads: Some(2), ..Default::default() }),
        (caps.abs_gap, SolveOptions { abs_gap: Some(1.0), ..Default::default() }),
    ];
    let log = std::env::temp_dir().join(format!("netspec-log-{kind}-{}.txt", std::process::id()));
    probes.push((caps.log_file, SolveOptions { log: netspec::solvers::LogTarget::File(log.clone()), ..Default::default() }));
    for (supported, o) in probes {
        let r = solver.solve(&model, &o);
        if supported {
            let r = r.unwrap_or_else(|e| panic!("{kind}: supported option refused: {e}"));
            assert_eq!(r.termination, Termination::Optimal);
        } else {
            assert!(matches!(r, Err(ref e) if matches!(e.kind, SolverErrorKind::Unsupported { .. })), "{kind}: {o:?} silently accepted");
        }
    }
    if caps.log_file {
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        assert!(!text.is_empty(), "{kind}: log file {} empty", log.display());
        let _ = std::fs::remove_file(&log);
    }
}

/// Instantiates every case above for one backend.
macro_rules! conformance_suite {
    ($($module:ident => $kind:expr, $feature:literal;)*) => {$(
        #[cfg(feature = $feature)]
        mod $module {
            conformance_suite!(@cases $kind;
                lp_max, lp_free_vars, lp_ranged_eq, knapsack, general_integer, max_with_constant,
                empty_model, infeasible_lp, infeasible_mip, unbounded_lp, infeasible_or_unbounded,
                time_limit_stops_hard_model, mip_start_is_used, gap_limit_stops_early, node_limit,
                invalid_model_is_an_error, unsupported_options_are_refused);
        }
    )*};
    (@cases $kind:expr; $($case:ident),*) => {$(
        #[test]
        fn $case() {
            super::$case($kind)
        }
    )*};
}

conformance_suite! {
    highs => netspec::solvers::SolverKind::Highs, "highs";
    cbc => netspec::solvers::SolverKind::Cbc, "cbc";
    scip => netspec::solvers::SolverKind::Scip, "scip";
    microlp => netspec::solvers::SolverKind::Microlp, "microlp";
}

/// Every compiled backend agrees on every optimum of the suite's models.
#[test]
fn backends_agree() {
    let cases: Vec<Model> = vec![
        models::lp_max(),
        models::lp_free_vars(),
        models::lp_ranged_eq(),
        models::knapsack(),
        models::general_integer(),
        models::max_with_constant(),
        models::multi_knapsack(20, 3, 1),
    ];
    let kinds: Vec<SolverKind> = SolverKind::compiled().into_iter().filter(|k| *k != SolverKind::GoodLp).collect();
    for m in &cases {
        let objs: Vec<(SolverKind, f64)> = kinds
            .iter()
            .map(|&k| {
                let r = solve(k, m, &SolveOptions::default());
                assert_eq!(r.termination, Termination::Optimal, "{k} on {}", m.name);
                assert_checked(m, &r);
                (k, r.objective.unwrap())
            })
            .collect();
        for w in objs.windows(2) {
            assert!(objectives_agree(w[0].1, w[1].1, 1e-6), "{}: {objs:?}", m.name);
        }
    }
}
