//! Solving a built formulation: the backend (with the lazily separated rows through its
//! callback or the solve–cut–resolve loop), the solve strategy, and every answer checked.

use super::outcome::Outcome;
use super::result::StartReport;
use super::result::{
    active_edge_pairs, design_violations, rooms_result, DesignResult, Validity, DESIGN_SCHEMA_VERSION,
};
use super::start::{start_for, StartFrom};
use super::strategy::{tuned_options, Strategy};
use crate::design::{self, Metrics, Objective, Violation};
use crate::formulations::Formulation;
use crate::heuristics::{self, Inputs};
use crate::milp::{check_point, objectives_agree, Model, Tolerances};
use crate::solvers::lattice::LatticeReport;
use crate::solvers::split::{solve_split, ObjectiveSplit, PhaseSolve, SplitReport};
use crate::solvers::{LazyReport, LazyRow, SolveOptions, SolverError, SolverKind};
use crate::spec::Problem;

/// The formulation's point for a repaired version of a disconnected integral point: islands
/// (components without a sink) are dropped, and the rest encoded. `None` when the rest is not a
/// valid design (e.g. coverage needed an island).
fn repair_point(p: &Problem, f: &Formulation, x: &[f64]) -> Option<Vec<f64>> {
    let mut net = f.decode(p, x);
    for v in design::validate(p, &net, f.path_sets.as_ref()) {
        if let Violation::Island { edges } = v {
            for e in edges {
                net.active[e.index()] = false;
            }
        }
    }
    if f.placements.is_none() && design::validate(p, &net, f.path_sets.as_ref()).is_empty() {
        return f.encode(p, &net).ok();
    }
    // Dropping the islands broke a rule (coverage, rooms, …): the heuristic's rule steps mend it.
    let inputs =
        Inputs { paths: f.path_sets.as_ref(), placements: f.placements.as_ref().map(|r| r.placements.as_slice()) };
    let fixed = heuristics::repair_within(p, &inputs, &net, REPAIR_BUDGET)?;
    f.encode(p, &fixed).ok()
}

/// Seconds the solve–cut–resolve loop gives [`heuristics::repair_within`] per broken point.
const REPAIR_BUDGET: f64 = 0.2;

/// [`solve_built`] from a MIP start: the start is prepared ([`start_for`]) within the time
/// limit, handed to the backend when the checker accepts it and the backend takes starts, and
/// returned as the design when the solver ends with nothing better (so a solve never ends worse
/// than its start). The report is in [`DesignResult::start`].
pub fn solve_from(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    options: &SolveOptions,
    from: &StartFrom,
) -> Result<DesignResult, SolverError> {
    solve_from_with(p, f, kind, options, from, &Strategy::for_problem(p, f))
}

/// [`solve_from`] under a given solve strategy.
pub fn solve_from_with(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    options: &SolveOptions,
    from: &StartFrom,
    strategy: &Strategy,
) -> Result<DesignResult, SolverError> {
    let takes_starts = kind.instance()?.capabilities().mip_start;
    let prepared =
        if takes_starts { start_for(p, f, from, options.seed.unwrap_or(0), options.heuristic_threads()) } else { None };
    let Some((x, mut report)) = prepared else {
        let mut res = solve_built_with(p, f, kind, options, strategy)?;
        if !takes_starts && !matches!(from, StartFrom::Nothing) {
            res.start = Some(StartReport {
                source: "none".into(),
                objective: None,
                accepted: false,
                reason: Some(format!("{kind} does not accept a starting solution")),
                seconds: None,
                returned: false,
            });
        }
        return Ok(res);
    };
    let mut o = options.clone();
    if let (Some(limit), Some(spent)) = (o.finite_time_limit(), report.seconds) {
        o.time_limit = Some((limit - spent).max(0.0));
    }
    o.mip_start = x.clone();
    let mut res = solve_built_with(p, f, kind, &o, strategy)?;
    if let (Some(x), Some(start_obj)) = (x, report.objective) {
        let infeasible = res.solve.termination == crate::solvers::Termination::Infeasible;
        let worse = match res.objective.as_ref().filter(|_| res.validity.valid) {
            None => true,
            Some(o) => f.model.sense.falls_short(o.total, start_obj, 1e-9),
        };
        if worse && !infeasible {
            let mut solve = res.solve.clone();
            solve.objective = Some(f.model.objective_value(&x));
            solve.finish(f.model.sense);
            let reports = Reports {
                lazy: res.lazy.clone(),
                split: res.split.clone(),
                lns: res.lns.clone(),
                solver_hints: res.solver_hints.clone(),
                lattice: res.lattice.clone(),
            };
            let mut again = checked_result(p, f, (solve, Some(x)), reports, &[])?;
            again.solve.wall_time = res.solve.wall_time;
            report.returned = true;
            res = again;
        }
    }
    res.start = Some(report);
    Ok(res)
}

/// Solves a built formulation and checks the answer: lazily separated rows go through the
/// backend's `solve_lazy` (its callback, or the solve–cut–resolve loop), every row and bound of
/// the model and every separated row is checked at the returned point, the network is decoded,
/// validated and measured, and its objective recomputed from the design alone.
pub fn solve_built(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    options: &SolveOptions,
) -> Result<DesignResult, SolverError> {
    solve_built_with(p, f, kind, options, &Strategy::for_problem(p, f))
}

/// [`solve_built`] under a given solve strategy.
pub fn solve_built_with(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    options: &SolveOptions,
    strategy: &Strategy,
) -> Result<DesignResult, SolverError> {
    let solver = kind.instance()?;
    let (tuned, solver_hints) = tuned_options(solver.as_ref(), f, strategy, options);
    let options = &tuned;
    let mut sep = f.separator().map(|sep| sep.with_repair(Box::new(|x: &[f64]| repair_point(p, f, x))));
    // Root-round rows no phase's model kept: checked at the answer with the others.
    let mut left_out = Vec::new();
    let mut solve = |m: &Model, o: &SolveOptions| -> Result<PhaseSolve, SolverError> {
        Ok(match sep.as_mut() {
            Some(sep) => {
                let ls = solver.solve_lazy(m, sep, o)?;
                left_out.extend(ls.left_out);
                (ls.result, ls.rows, Some(ls.report))
            }
            None => (solver.solve(m, o)?, Vec::new(), None),
        })
    };
    // The large-neighbourhood search improves the start for the full MILP, under one time limit.
    let mut lns = None;
    let options: std::borrow::Cow<SolveOptions> = match (&options.mip_start, options.time_limit) {
        (Some(x0), Some(limit)) if strategy.lns && limit.is_finite() => {
            let t0 = std::time::Instant::now();
            let (x, report) =
                super::lns::improve(p, &f.model, &f.vars.edge, x0, options, super::lns::LNS_SHARE * limit, &mut solve);
            lns = Some(report);
            let mut rest = options.clone();
            rest.mip_start = Some(x);
            rest.time_limit = Some((limit - t0.elapsed().as_secs_f64()).max(0.0));
            std::borrow::Cow::Owned(rest)
        }
        _ => std::borrow::Cow::Borrowed(options),
    };
    let options = options.as_ref();
    let split = options
        .mip_start
        .as_ref()
        .filter(|_| strategy.split_objective)
        .and_then(|x| ObjectiveSplit::detect(&f.model).filter(|s| s.suits(&f.model, x)));
    let (mut result, mut lazy_rows, lazy, split) = match split {
        Some(split) => {
            let polish = |x: &[f64]| f.encode(p, &f.decode(p, x)).ok();
            let s = solve_split(&f.model, &split, options, &mut solve, polish)?;
            (s.result, s.rows, s.lazy, Some(s.report))
        }
        None => {
            let (r, rows, lazy) = solve(&f.model, options)?;
            (r, rows, lazy, None)
        }
    };
    lazy_rows.extend(left_out);
    // The search's windows were backend solves of this run: its times count.
    if let Some(l) = &lns {
        result.wall_time += l.seconds;
        result.solver_time = result.solver_time.map(|t| t + l.seconds);
    }
    let lattice = f
        .objective_lattice
        .filter(|_| strategy.objective_lattice)
        .map(|lattice| LatticeReport { lattice, solver_bound: lattice.settle(&mut result, f.model.sense) });
    let primal = result.primal.take();
    checked_result(
        p,
        f,
        (Outcome::of_solve(result), primal),
        Reports { lazy, split, lns, solver_hints, lattice },
        &lazy_rows,
    )
}

/// What a solve did besides its result, carried into the design result.
struct Reports {
    lazy: Option<LazyReport>,
    split: Option<SplitReport>,
    lns: Option<super::lns::LnsReport>,
    solver_hints: Vec<String>,
    lattice: Option<LatticeReport>,
}

/// Checks a solver's result and builds the design result: every row and bound of the model
/// and every separated row at the point, the decoded network validated and measured, its
/// objective recomputed from the design alone.
fn checked_result(
    p: &Problem,
    f: &Formulation,
    (outcome, primal): (Outcome, Option<Vec<f64>>),
    reports: Reports,
    lazy_rows: &[LazyRow],
) -> Result<DesignResult, SolverError> {
    let Reports { lazy, split, lns, solver_hints, lattice } = reports;
    let mut validity = Validity {
        valid: false,
        design_violations: Vec::new(),
        milp_check: None,
        objective_recomputed: None,
        objective_agrees: None,
    };
    let mut net = None;
    let mut metrics = None;
    let mut objective = None;
    if let Some(x) = &primal {
        let check = if lazy_rows.is_empty() {
            check_point(&f.model, x, &Tolerances::default())
        } else {
            let mut full: Model = f.model.clone();
            for r in lazy_rows {
                r.add_to(&mut full);
            }
            check_point(&full, x, &Tolerances::default())
        };
        let n = f.decode(p, x);
        validity.design_violations = design_violations(p, f, &n);
        // The solver's objective must be the model's objective at its point (the checker
        // recomputes it), and the design's own objective can only be lower: a formulation's
        // surrogate (labels, flows, indicators) overestimates off the optimum, never under.
        let design_objective = Objective::of(p, &n);
        let surrogate = check.objective;
        validity.objective_recomputed = Some(design_objective.total);
        validity.objective_agrees = outcome.objective.map(|o| {
            objectives_agree(o, surrogate, 1e-6)
                && design_objective.total <= surrogate + 1e-6 * surrogate.abs().max(1.0)
        });
        validity.valid =
            check.is_feasible() && validity.design_violations.is_empty() && validity.objective_agrees == Some(true);
        validity.milp_check = Some(check);
        metrics = Some(Metrics::of(p, &n));
        objective = Some(design_objective);
        net = Some(n);
    }
    let active_edges = active_edge_pairs(p, net.as_ref());
    let rooms = rooms_result(p, f, net.as_ref());
    Ok(DesignResult {
        schema: "netspec.design".into(),
        schema_version: DESIGN_SCHEMA_VERSION,
        netspec_version: env!("CARGO_PKG_VERSION").into(),
        spec: p.spec.clone(),
        mesh: p.mesh.clone(),
        sinks: p.mesh.vertices().filter(|v| p.is_sink[v.index()]).map(|v| v.0).collect(),
        active_edges,
        design_found: net.is_some(),
        network: net,
        metrics,
        objective,
        validity,
        solve: outcome,
        model_stats: f.model.stats(),
        families: f.families.clone(),
        formulation: f.recipe.label.clone(),
        big_m: f.big_m,
        lazy,
        split,
        lns,
        lattice,
        solver_hints,
        start: None,
        path_sets: f.path_sets.clone(),
        rooms,
        primal_point: primal,
    })
}
