//! The conformance suite (in the spirit of MathOptInterface's `MOI.Test`): plain functions over
//! small models with known answers, instantiated for every compiled backend by one macro.
//! Every solution goes through the independent checker. A bug found in one backend becomes a
//! case here.

pub mod models;

use netspec::milp::{check_point, objectives_agree, Model, Tolerances};
use netspec::solvers::{LimitKind, SolveOptions, SolveResult, SolverError, SolverErrorKind, SolverKind, Termination};
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
    let x = r
        .primal
        .as_ref()
        .unwrap_or_else(|| panic!("{} on {}: no primal point ({})", r.solver, model.name, r.termination));
    let rep = check_point(model, x, &Tolerances::default());
    assert!(rep.is_feasible(), "{} on {}: checker found {:?}", r.solver, model.name, rep.violations);
    let obj = r.objective.expect("objective with a primal point");
    assert!(
        objectives_agree(rep.objective, obj, 1e-6),
        "{} on {}: solver objective {obj}, recomputed {}",
        r.solver,
        model.name,
        rep.objective
    );
}

/// Solves to optimality and checks the optimum against `expected`.
pub fn assert_optimal(kind: SolverKind, model: &Model, expected: f64) -> SolveResult {
    assert_optimal_with(kind, model, &SolveOptions::default(), expected)
}

/// [`assert_optimal`] with options that must not change the optimum.
pub fn assert_optimal_with(kind: SolverKind, model: &Model, options: &SolveOptions, expected: f64) -> SolveResult {
    let r = solve(kind, model, options);
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
    assert!(
        r.wall_time >= 0.0 && r.solver_version.chars().any(|c| c.is_ascii_digit()),
        "{kind}: version {:?}",
        r.solver_version
    );
    assert_reports_match_capabilities(kind, model, &r);
    r
}

/// At optimality a result carries a dual bound (and so a gap), a node count and the solver's
/// own time exactly when the backend's capabilities say it reports them.
fn assert_reports_match_capabilities(kind: SolverKind, model: &Model, r: &SolveResult) {
    let caps = kind.instance().unwrap().capabilities();
    let name = &model.name;
    assert_eq!(r.dual_bound.is_some(), caps.reports_dual_bound, "{kind} on {name}: dual bound {:?}", r.dual_bound);
    assert_eq!(r.gap.is_some(), caps.reports_dual_bound, "{kind} on {name}: gap {:?}", r.gap);
    assert_eq!(r.nodes.is_some(), caps.reports_nodes, "{kind} on {name}: nodes {:?}", r.nodes);
    assert_eq!(r.solver_time.is_some(), caps.reports_solver_time, "{kind} on {name}: solver time {:?}", r.solver_time);
}

/// Where the backend lacks `option` (`supported` is false), asserts that a solve of `model` with
/// `o` is refused with the typed error naming it, and returns `true`: the case is done.
fn refused_unless(supported: bool, kind: SolverKind, model: &Model, o: &SolveOptions, option: &str) -> bool {
    if !supported {
        assert_refused(kind, kind.instance().unwrap().solve(model, o), option);
    }
    !supported
}

/// Asserts that `r` is the typed refusal of `option`.
fn assert_refused(kind: SolverKind, r: Result<SolveResult, SolverError>, option: &str) {
    match r {
        Err(e) => assert!(
            matches!(e.kind, SolverErrorKind::Unsupported { option: o, .. } if o == option),
            "{kind}: expected `{option}` to be refused as unsupported, got: {e}"
        ),
        Ok(r) => panic!("{kind}: unsupported option `{option}` silently accepted ({})", r.termination),
    }
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

pub fn lp_with_constant(kind: SolverKind) {
    assert_optimal(kind, &models::lp_with_constant(), 4.2);
}

pub fn ranged_and_free_rows(kind: SolverKind) {
    let r = assert_optimal(kind, &models::ranged_and_free_rows(), 19.0);
    let x = r.primal.unwrap();
    assert!((x[0] - 10.0).abs() < 1e-6 && (x[1] - 9.0).abs() < 1e-6, "{kind}: {x:?}");
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
    // And without a constant: objective 0 (not missing).
    let r = assert_optimal(kind, &Model::new("empty0"), 0.0);
    assert_eq!(r.primal.as_deref(), Some(&[][..]));
    // With a MIP start (of no values), the same answer: netspec answers a model without columns
    // itself, the same for every backend.
    let o = SolveOptions { mip_start: Some(Vec::new()), ..Default::default() };
    let r = assert_optimal_with(kind, &models::empty(), &o, 7.0);
    assert_eq!(r.primal.as_deref(), Some(&[][..]));
}

/// A coefficient beyond what the backend loads is refused by netspec before the backend sees
/// the model (no panic, no abort, no unexplained rejection), naming the row and column; a finite
/// bound at or above the backend's infinity is solved with a warning saying it is no bound.
pub fn numeric_limits_are_screened(kind: SolverKind) {
    let limits = kind.instance().unwrap().capabilities().numeric;
    let mut m = Model::new("big");
    let x = m.add_continuous("X", 0.0, 10.0, -1.0);
    m.add_le("R1", [(x, limits.max_matrix)], 1.0);
    let e = kind.instance().unwrap().solve(&m, &SolveOptions::default()).unwrap_err().to_string();
    assert!(e.contains("row `R1`, column `X`") && e.contains(kind.name()), "{kind}: {e}");
    let mut m = Model::new("bigobj");
    let x = m.add_continuous("X", 0.0, 10.0, -limits.max_objective);
    m.add_le("R1", [(x, 1.0)], 1.0);
    let e = kind.instance().unwrap().solve(&m, &SolveOptions::default()).unwrap_err().to_string();
    assert!(e.contains("objective coefficient of `X`"), "{kind}: {e}");
    if let Some(inf) = limits.infinity {
        let mut m = Model::new("wide");
        let x = m.add_continuous("X", 0.0, inf * 10.0, -1.0);
        m.add_le("R1", [(x, 1.0)], 2.0);
        let r = assert_optimal(kind, &m, -2.0);
        assert!(
            r.warnings.iter().any(|w| w.contains("treated as no bound") && w.contains("`X`")),
            "{kind}: {:?}",
            r.warnings
        );
    }
}

fn assert_termination_in(kind: SolverKind, model: &Model, allowed: &[Termination]) {
    let r = solve(kind, model, &SolveOptions::default());
    assert!(
        allowed.contains(&r.termination),
        "{kind} on {}: got {}, expected one of {allowed:?}",
        model.name,
        r.termination
    );
    assert!(r.objective.is_none() || r.termination == Termination::Unbounded, "{kind}: objective on {}", r.termination);
    if r.termination == Termination::Infeasible {
        assert!(r.primal.is_none(), "{kind} on {}: a primal point for an infeasible model", model.name);
    }
    if matches!(r.termination, Termination::Unbounded | Termination::InfeasibleOrUnbounded) {
        assert!(r.dual_bound.is_none(), "{kind} on {}: dual bound {:?} on {}", model.name, r.dual_bound, r.termination);
    }
}

/// An empty row whose side excludes 0 is infeasible on every backend, and the result names the
/// row (netspec proves it before the backend is called).
pub fn empty_row_is_infeasible(kind: SolverKind) {
    for model in [models::empty_row_no_columns(), models::empty_row_with_columns()] {
        assert_termination_in(kind, &model, &[Termination::Infeasible]);
        let r = solve(kind, &model, &SolveOptions::default());
        let why = r.infeasibility.unwrap_or_else(|| panic!("{kind} on {}: no reason given", model.name));
        assert!(why.to_string().starts_with("row `"), "{kind}: {why}");
    }
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

pub fn unbounded_mip(kind: SolverKind) {
    assert_termination_in(
        kind,
        &models::unbounded_mip(),
        &[Termination::Unbounded, Termination::InfeasibleOrUnbounded],
    );
}

pub fn infeasible_or_unbounded(kind: SolverKind) {
    assert_termination_in(
        kind,
        &models::infeasible_or_unbounded(),
        &[Termination::Infeasible, Termination::InfeasibleOrUnbounded],
    );
}

/// Seconds the solve itself took: the solver's own time where it reports one, else the wall
/// time since `t0`. Tests run in parallel, and a solve may first queue behind a process-wide
/// lock (CBC's global lock, a HiGHS scheduler reset); that queueing is not the solver's.
fn solving_seconds(r: &SolveResult, t0: Instant) -> f64 {
    r.solver_time.unwrap_or_else(|| t0.elapsed().as_secs_f64())
}

/// Slack allowed beyond a time limit: process and model setup, the solver noticing the clock.
const TIME_MARGIN: f64 = 1.5;

pub fn time_limit_stops_hard_model(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let caps = solver.capabilities();
    let (model, _) = models::market_split(4, 30, 7, false);
    let o = SolveOptions { time_limit: Some(1.0), ..Default::default() };
    if refused_unless(caps.time_limit, kind, &model, &o, "time_limit") {
        return;
    }
    let t0 = Instant::now();
    let r = solve(kind, &model, &o);
    let wall = solving_seconds(&r, t0);
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
    let caps = solver.capabilities();
    let (model, planted) = models::market_split(4, 30, 11, true);
    let alone = SolveOptions { mip_start: Some(planted.clone()), ..Default::default() };
    if refused_unless(caps.mip_start, kind, &model, &alone, "mip_start") {
        return;
    }
    if !caps.time_limit {
        return; // Without a time limit the hard model would run for hours.
    }
    let o = SolveOptions { time_limit: Some(0.5), mip_start: Some(planted), ..Default::default() };
    let r = solve(kind, &model, &o);
    assert_checked(&model, &r);
    // The planted point has objective 0; without the start no solver finds it in 0.5 s.
    assert_eq!(r.objective, Some(0.0), "{kind}: the MIP start was not used ({})", r.termination);
}

pub fn gap_limit_stops_early(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let caps = solver.capabilities();
    let model = models::multi_knapsack(60, 5, 3);
    let alone = SolveOptions { rel_gap: Some(0.05), ..Default::default() };
    if refused_unless(caps.rel_gap, kind, &model, &alone, "rel_gap") {
        return;
    }
    let o = SolveOptions { rel_gap: Some(0.05), time_limit: caps.time_limit.then_some(20.0), ..Default::default() };
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
    let caps = solver.capabilities();
    let (model, _) = models::market_split(4, 30, 5, false);
    let alone = SolveOptions { node_limit: Some(10), ..Default::default() };
    if refused_unless(caps.node_limit, kind, &model, &alone, "node_limit") {
        return;
    }
    let o = SolveOptions { node_limit: Some(10), time_limit: caps.time_limit.then_some(20.0), ..Default::default() };
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
    let mut probes: Vec<(bool, &str, SolveOptions)> = vec![
        (caps.seed, "seed", SolveOptions { seed: Some(1), ..Default::default() }),
        (caps.threads, "threads", SolveOptions { threads: Some(2), ..Default::default() }),
        (caps.abs_gap, "abs_gap", SolveOptions { abs_gap: Some(1.0), ..Default::default() }),
    ];
    let log = std::env::temp_dir().join(format!("netspec-log-{kind}-{}.txt", std::process::id()));
    probes.push((
        caps.log_file,
        "log",
        SolveOptions { log: netspec::solvers::LogTarget::File(log.clone()), ..Default::default() },
    ));
    // A log on standard output is probed only where it must be refused (it would litter the
    // test output where it is honoured).
    if !caps.log_stdout {
        probes.push((false, "log", SolveOptions { log: netspec::solvers::LogTarget::Stdout, ..Default::default() }));
    }
    for (supported, option, o) in probes {
        let r = solver.solve(&model, &o);
        if supported {
            let r = r.unwrap_or_else(|e| panic!("{kind}: supported option `{option}` refused: {e}"));
            assert_eq!(r.termination, Termination::Optimal);
        } else {
            assert_refused(kind, r, option);
        }
    }
    if caps.log_file {
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        assert!(!text.is_empty(), "{kind}: log file {} empty", log.display());
        let _ = std::fs::remove_file(&log);
    }
}

/// More than one thread, where supported, gives the same optimum; elsewhere it is refused.
pub fn two_threads(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let model = models::knapsack();
    let o = SolveOptions { threads: Some(2), ..Default::default() };
    if refused_unless(solver.capabilities().threads, kind, &model, &o, "threads") {
        return;
    }
    assert_optimal_with(kind, &model, &o, models::knapsack_optimum());
}

/// A zero time limit is legal: the solver stops at once (or has already solved the model), and
/// whatever point it returns is feasible.
pub fn time_limit_zero(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let o = SolveOptions { time_limit: Some(0.0), ..Default::default() };
    let (hard, _) = models::market_split(4, 30, 7, false);
    for model in [models::knapsack(), hard] {
        if refused_unless(solver.capabilities().time_limit, kind, &model, &o, "time_limit") {
            continue;
        }
        let t0 = Instant::now();
        let r = solve(kind, &model, &o);
        let wall = solving_seconds(&r, t0);
        assert!(
            matches!(r.termination, Termination::Optimal | Termination::Limit(LimitKind::Time)),
            "{kind} on {}: {} with a zero time limit",
            model.name,
            r.termination
        );
        assert!(wall <= TIME_MARGIN, "{kind} on {}: returned after {wall:.2} s for a zero time limit", model.name);
        if r.primal.is_some() {
            assert_checked(&model, &r);
        }
    }
}

/// A MIP start with a non-finite value, or of the wrong length, is refused before the solve;
/// a backend without MIP starts refuses the option itself.
pub fn nan_mip_start_is_refused(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let model = models::knapsack();
    let n = model.num_vars();
    let mut nan = vec![0.0; n];
    nan[1] = f64::NAN;
    let mut inf = vec![0.0; n];
    inf[0] = f64::INFINITY;
    for start in [nan, inf, vec![0.0; n - 1]] {
        let o = SolveOptions { mip_start: Some(start.clone()), ..Default::default() };
        let r = solver.solve(&model, &o);
        if !solver.capabilities().mip_start {
            assert_refused(kind, r, "mip_start");
            continue;
        }
        let e = r.err().unwrap_or_else(|| panic!("{kind}: MIP start {start:?} accepted"));
        assert!(matches!(e.kind, SolverErrorKind::Rejected(_)), "{kind}: MIP start {start:?}: {e}");
    }
}

/// A feasible but suboptimal MIP start is a starting point, not a constraint: the solve still
/// reaches the optimum. With a node limit of 0 the start itself (or better) is returned.
pub fn mip_start_is_only_a_start(kind: SolverKind) {
    let caps = kind.instance().unwrap().capabilities();
    let model = models::knapsack();
    // Items 0 and 1: weight 11 of 12, value 23, below the optimum.
    let mut start = vec![0.0; model.num_vars()];
    start[0] = 1.0;
    start[1] = 1.0;
    let o = SolveOptions { mip_start: Some(start.clone()), ..Default::default() };
    if refused_unless(caps.mip_start, kind, &model, &o, "mip_start") {
        return;
    }
    assert_optimal_with(kind, &model, &o, models::knapsack_optimum());
    if caps.node_limit {
        let o = SolveOptions { mip_start: Some(start), node_limit: Some(0), ..Default::default() };
        let r = solve(kind, &model, &o);
        assert!(
            matches!(r.termination, Termination::Optimal | Termination::Limit(LimitKind::Node)),
            "{kind}: {} with a node limit of 0",
            r.termination
        );
        assert_checked(&model, &r);
        assert!(r.objective.unwrap() >= 23.0 - 1e-9, "{kind}: objective {:?} below the MIP start's 23", r.objective);
    }
}

/// An optimal MIP start leaves nothing to find: the solve is still optimal, with the start's
/// objective (CBC ends such a search as "relaxation worse than the cutoff", which once read as
/// infeasible).
pub fn optimal_mip_start_is_proven_optimal(kind: SolverKind) {
    let caps = kind.instance().unwrap().capabilities();
    let model = models::general_integer();
    let best = models::general_integer_optimum();
    // The optimum by enumeration, as a point.
    let mut start = None;
    for a in -5..=5 {
        for b in -5..=5 {
            let x = vec![a as f64, b as f64];
            if netspec::milp::check_point(&model, &x, &netspec::milp::Tolerances::default()).is_feasible()
                && model.objective_value(&x) == best
            {
                start = Some(x);
            }
        }
    }
    let o = SolveOptions { mip_start: start, ..Default::default() };
    if refused_unless(caps.mip_start, kind, &model, &o, "mip_start") {
        return;
    }
    assert_optimal_with(kind, &model, &o, best);
    let model = models::knapsack();
    let n = model.num_vars();
    let best = models::knapsack_optimum();
    let start = (0u32..1 << n)
        .map(|s| (0..n).map(|i| (s >> i & 1) as f64).collect::<Vec<f64>>())
        .find(|x| {
            netspec::milp::check_point(&model, x, &netspec::milp::Tolerances::default()).is_feasible()
                && model.objective_value(x) == best
        })
        .unwrap();
    assert_optimal_with(kind, &model, &SolveOptions { mip_start: Some(start), ..Default::default() }, best);
}

/// A 6-city tour whose degree-2 relaxation is two triangles: subtour elimination rows are
/// needed, and come only from a separator (the backend's callback, or the solve–cut–resolve
/// loop). The optimum is found by brute force over every tour.
pub fn lazy_subtour_elimination(kind: SolverKind) {
    let (model, edges, cities) = models::two_cluster_tour();
    let mut sep = models::SubtourSeparator { edges: edges.clone(), n: cities.len(), calls: 0 };
    let solver = kind.instance().unwrap();
    let out = solver.solve_lazy(&model, &mut sep, &SolveOptions::default()).unwrap_or_else(|e| panic!("{kind}: {e}"));
    let r = &out.result;
    assert_eq!(r.termination, Termination::Optimal, "{kind}");
    assert!(out.report.rows_added >= 1 && out.rows.len() == out.report.rows_added, "{kind}: {:?}", out.report);
    let caps = solver.capabilities();
    assert_eq!(
        out.report.mode == netspec::solvers::LazyMode::Callback,
        caps.lazy_constraints,
        "{kind}: {:?}",
        out.report.mode
    );
    // The point satisfies the model and every separated row, and is one tour.
    let mut full = model.clone();
    for row in &out.rows {
        row.add_to(&mut full);
    }
    assert_checked(&full, r);
    let x = r.primal.as_ref().unwrap();
    assert!(models::SubtourSeparator { edges, n: cities.len(), calls: 0 }.components(x) == 1, "{kind}: not one tour");
    let best = models::brute_force_tour(&cities);
    assert!(
        objectives_agree(r.objective.unwrap(), best, 1e-6),
        "{kind}: {} vs brute force {best}",
        r.objective.unwrap()
    );
}

/// A lazy solve from a MIP start that satisfies every lazy row (a poor but complete tour):
/// the backend checks the start against the separator before the solve begins (SCIP's handler
/// is asked in the problem stage, where only the original variables exist), keeps it as a
/// starting point only, and still reaches the brute-force optimum.
pub fn lazy_solve_from_a_start(kind: SolverKind) {
    let (model, edges, cities) = models::two_cluster_tour();
    let solver = kind.instance().unwrap();
    if !solver.capabilities().mip_start {
        return;
    }
    // The tour 0-3-1-4-2-5-0 crosses between the clusters six times.
    let tour = [0, 3, 1, 4, 2, 5];
    let mut start = vec![0.0; model.num_vars()];
    for k in 0..tour.len() {
        let (a, b) = (tour[k].min(tour[(k + 1) % 6]), tour[k].max(tour[(k + 1) % 6]));
        let &(_, _, x) = edges.iter().find(|&&(i, j, _)| (i, j) == (a, b)).unwrap();
        start[x.index()] = 1.0;
    }
    let mut sep = models::SubtourSeparator { edges: edges.clone(), n: cities.len(), calls: 0 };
    let o = SolveOptions { mip_start: Some(start), ..Default::default() };
    let out = solver.solve_lazy(&model, &mut sep, &o).unwrap_or_else(|e| panic!("{kind}: {e}"));
    let r = &out.result;
    assert_eq!(r.termination, Termination::Optimal, "{kind}");
    let mut full = model.clone();
    for row in &out.rows {
        row.add_to(&mut full);
    }
    assert_checked(&full, r);
    let best = models::brute_force_tour(&cities);
    assert!(
        objectives_agree(r.objective.unwrap(), best, 1e-6),
        "{kind}: {} vs brute force {best}",
        r.objective.unwrap()
    );
}

/// An LP kept loaded between solves ([`netspec::solvers::Solver::lp_session`]), for backends
/// that offer one: rows added between solves are honoured (each optimum agrees with a fresh
/// solve of the model with the rows written in, and its point passes the checker on it), for
/// both senses and with an objective constant; a row that empties the LP makes it infeasible.
pub fn lp_session_adds_rows(kind: SolverKind) {
    let solver = kind.instance().unwrap();
    let o = SolveOptions { threads: Some(1), ..Default::default() };
    // (model, its optimum, a row to add as (lhs, rhs, terms by column), an infeasible row)
    type Side = (f64, f64, Vec<(usize, f64)>);
    let cases: Vec<(Model, f64, Side, Side)> = vec![
        (
            models::lp_with_constant(),
            4.2,
            (f64::NEG_INFINITY, 2.0, vec![(0, 1.0), (1, 1.0)]),
            (3.0, f64::INFINITY, vec![(0, 1.0), (1, 1.0)]),
        ),
        (models::lp_max(), 11.0, (1.5, f64::INFINITY, vec![(1, 1.0)]), (f64::NEG_INFINITY, 1.0, vec![(1, 1.0)])),
    ];
    for (model, optimum, row, empties) in cases {
        let Some(mut lp) = solver.lp_session(&model, &o).unwrap_or_else(|e| panic!("{kind} on {}: {e}", model.name))
        else {
            return;
        };
        let lazy = |name: &str, (lhs, rhs, terms): &Side| netspec::solvers::LazyRow {
            name: name.into(),
            lhs: *lhs,
            rhs: *rhs,
            terms: terms.iter().map(|&(j, c)| (netspec::milp::VarId(j as u32), c)).collect(),
        };
        let r = lp.solve(None).unwrap();
        assert_eq!(r.termination, Termination::Optimal, "{kind} on {}", model.name);
        assert_checked(&model, &r);
        assert!(objectives_agree(r.objective.unwrap(), optimum, 1e-6), "{kind} on {}: {:?}", model.name, r.objective);
        let added = lazy("added", &row);
        lp.add_rows(std::slice::from_ref(&added)).unwrap();
        let mut with_row = model.clone();
        added.add_to(&mut with_row);
        let fresh = solve(kind, &with_row, &o);
        let r = lp.solve(Some(10.0)).unwrap();
        assert_eq!(r.termination, Termination::Optimal, "{kind} on {} with the row", model.name);
        assert_checked(&with_row, &r);
        assert!(
            objectives_agree(r.objective.unwrap(), fresh.objective.unwrap(), 1e-6),
            "{kind} on {}: {:?} kept, {:?} fresh",
            model.name,
            r.objective,
            fresh.objective
        );
        assert!(
            !objectives_agree(r.objective.unwrap(), optimum, 1e-6),
            "{kind} on {}: the added row must cut the optimum off",
            model.name
        );
        lp.add_rows(&[lazy("empties", &empties)]).unwrap();
        let r = lp.solve(None).unwrap();
        assert!(
            matches!(r.termination, Termination::Infeasible | Termination::InfeasibleOrUnbounded),
            "{kind} on {}: {}",
            model.name,
            r.termination
        );
    }
}

/// A backend that reports progress hands over every improving point while it solves (one
/// thread): each passes the checker, objectives improve, and the last is the final optimum.
/// Elsewhere the option is refused with the typed error naming it.
pub fn live_incumbents_are_checked_points_ending_at_the_optimum(kind: SolverKind) {
    use std::sync::{Arc, Mutex};
    let model = models::knapsack();
    type Seen = Vec<(f64, Vec<f64>)>;
    let seen: Arc<Mutex<Seen>> = Arc::default();
    let sink = seen.clone();
    let o = SolveOptions {
        threads: Some(1),
        incumbents: Some(netspec::solvers::PointSink(Arc::new(move |obj, x| {
            sink.lock().unwrap().push((obj, x.to_vec()));
        }))),
        ..SolveOptions::default()
    };
    let caps = kind.instance().unwrap().capabilities();
    if refused_unless(caps.reports_progress, kind, &model, &o, "incumbents") {
        return;
    }
    let r = assert_optimal_with(kind, &model, &o, models::knapsack_optimum());
    let seen = seen.lock().unwrap();
    assert!(!seen.is_empty(), "{kind}: no incumbent reported");
    for (obj, x) in seen.iter() {
        let c = check_point(&model, x, &Tolerances::default());
        assert!(c.is_feasible(), "{kind}: a reported point fails the checker: {:?}", c.violations.first());
        assert!(objectives_agree(*obj, model.objective_value(x), 1e-6), "{kind}: objective {obj} of its point");
    }
    assert!(seen.windows(2).all(|w| w[1].0 >= w[0].0 - 1e-9), "{kind}: a maximisation's incumbents improve");
    let last = seen.last().unwrap().0;
    assert!(objectives_agree(last, r.objective.unwrap(), 1e-6), "{kind}: last incumbent {last}");
}

/// Instantiates every case above for one backend.
macro_rules! conformance_suite {
    ($($module:ident => $kind:expr, $feature:literal;)*) => {$(
        #[cfg(feature = $feature)]
        mod $module {
            conformance_suite!(@cases $kind;
                lp_max, lp_free_vars, lp_ranged_eq, lp_with_constant, ranged_and_free_rows, knapsack,
                general_integer, max_with_constant, empty_model, empty_row_is_infeasible, infeasible_lp, infeasible_mip,
                unbounded_lp, unbounded_mip, infeasible_or_unbounded, time_limit_stops_hard_model,
                time_limit_zero, mip_start_is_used, mip_start_is_only_a_start, nan_mip_start_is_refused,
                gap_limit_stops_early, node_limit, two_threads, invalid_model_is_an_error,
                unsupported_options_are_refused, lazy_subtour_elimination, lazy_solve_from_a_start, optimal_mip_start_is_proven_optimal,
                lp_session_adds_rows, numeric_limits_are_screened,
                live_incumbents_are_checked_points_ending_at_the_optimum);
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
    good_lp => netspec::solvers::SolverKind::GoodLp, "good_lp";
}

/// Every compiled backend agrees on every optimum of the suite's models.
#[test]
fn backends_agree() {
    let cases: Vec<Model> = vec![
        models::lp_max(),
        models::lp_free_vars(),
        models::lp_ranged_eq(),
        models::lp_with_constant(),
        models::ranged_and_free_rows(),
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
