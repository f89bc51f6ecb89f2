//! Bridge to [`good_lp`], for users who already pick their solver through good_lp.
//!
//! The neutral model is translated to good_lp variables (bounds, integrality, names), an
//! objective expression (with the constant) and constraints (a ranged row becomes two, a free row
//! is left out), then solved with `good_lp::default_solver`, or with any good_lp solver through
//! [`solve_with`].
//!
//! # Which solver runs
//!
//! netspec enables good_lp's `microlp` feature only. Which solver `default_solver` is depends on
//! good_lp's own cargo features, which the final binary may enable (cargo unifies them): in
//! good_lp 1.15 it is `coin_cbc` if enabled, else `microlp`, else `lpsolve`, `highs`, `scip`,
//! `cplex-rs`, the command-line solvers of `lp-solvers`, and last `clarabel` (an LP/conic
//! solver without integer variables). To pick one, enable its good_lp feature in your own
//! `Cargo.toml`, or call [`solve_with`] with the solver you want. The result's
//! `solver_version` names the solver that ran.
//!
//! # What the bridge cannot do
//!
//! good_lp's common interface (`SolverModel`, `Solution`) has no options and reports only a
//! status (optimal, time limit, gap limit) and the variable values. Hence:
//!
//! * every [`SolveOptions`] field is **unsupported** (time limit, gaps, threads, seed, node limit,
//!   a log, a MIP start): the solve fails with
//!   [`SolverErrorKind::Unsupported`](super::SolverErrorKind::Unsupported) rather than
//!   ignore one. Options exist only on some of good_lp's solver types (`WithTimeLimit`,
//!   `WithMipGap`…), which a backend chosen by cargo features cannot rely on;
//! * the result has **no dual bound, no gap, no node count and no solver time**: only the
//!   termination, the primal point and its objective (evaluated from the point, with the
//!   constant), and netspec's `wall_time`;
//! * "infeasible" and "unbounded" are recognised when the solver reports them as good_lp's
//!   `ResolutionError`; any other failure is [`Termination::Error`] with the solver's message.

use super::{
    preflight, Capabilities, LimitKind, SolveOptions, SolveResult, Solver, SolverError, SolverKind, Termination,
};
use crate::milp::NumericLimits;
use crate::milp::{Model, RowKind, Sense};
use good_lp::{variable, Expression, ProblemVariables, ResolutionError, Solution, SolutionStatus, SolverModel};
use std::time::Instant;

/// The good_lp bridge, solving with `good_lp::default_solver`.
#[derive(Clone, Copy, Debug, Default)]
pub struct GoodLpSolver;

const KIND: SolverKind = SolverKind::GoodLp;

/// The bridge's capabilities: integer variables, nothing else (see the module documentation).
fn capabilities() -> Capabilities {
    Capabilities {
        integer_variables: true,
        time_limit: false,
        time_limit_whole_seconds: false,
        rel_gap: false,
        abs_gap: false,
        threads: false,
        seed: false,
        node_limit: false,
        log_stdout: false,
        log_file: false,
        mip_start: false,
        reports_dual_bound: false,
        reports_nodes: false,
        reports_solver_time: false,
        reports_progress: false,
        lazy_constraints: false,
        interrupt: false,
        raw_params: false,
        numeric: NumericLimits::uniform(1e20, None),
    }
}

/// `good_lp 1.15 / <solver name>` for the solver type `S`.
fn version_of<S: good_lp::Solver>() -> String {
    format!("good_lp 1.15 / {}", <S as good_lp::Solver>::name())
}

/// Solves `model` with any good_lp solver (e.g. `good_lp::microlp`, or `good_lp::highs` when
/// that good_lp feature is enabled). Same contract as [`Solver::solve`]: options are checked
/// against the bridge's capabilities first (all unsupported), infeasible and unbounded are
/// results, not errors.
pub fn solve_with<S>(solver: S, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError>
where
    S: good_lp::Solver,
    <S::Model as SolverModel>::Error: 'static,
{
    let t0 = Instant::now();
    preflight(KIND, &capabilities(), model, o)?;
    if let Some(why) = crate::milp::screen(model) {
        let mut r = SolveResult::empty(KIND, version_of::<S>(), Termination::Infeasible);
        r.infeasibility = Some(why);
        r.wall_time = t0.elapsed().as_secs_f64();
        return Ok(r);
    }
    let mut pv = ProblemVariables::new();
    let vars: Vec<good_lp::Variable> = model
        .vars()
        .iter()
        .map(|v| {
            let def = variable().min(v.lb).max(v.ub).name(v.name.clone());
            pv.add(if v.kind.is_integral() { def.integer() } else { def })
        })
        .collect();
    let mut objective = Expression::from(model.obj_constant);
    for (v, var) in model.vars().iter().zip(&vars) {
        if v.obj != 0.0 {
            objective.add_mul(v.obj, *var);
        }
    }
    let unsolved = match model.sense {
        Sense::Minimize => pv.minimise(objective.clone()),
        Sense::Maximize => pv.maximise(objective.clone()),
    };
    let mut problem = unsolved.using(solver);
    for row in model.rows() {
        let expr = || {
            let mut e = Expression::with_capacity(row.vars.len());
            for (v, a) in row.terms() {
                e.add_mul(a, vars[v.index()]);
            }
            e
        };
        match row.kind() {
            RowKind::Free => {}
            RowKind::Le => {
                problem.add_constraint(expr().leq(row.rhs));
            }
            RowKind::Ge => {
                problem.add_constraint(expr().geq(row.lhs));
            }
            RowKind::Eq => {
                problem.add_constraint(expr().eq(row.rhs));
            }
            RowKind::Ranged => {
                problem.add_constraint(expr().geq(row.lhs));
                problem.add_constraint(expr().leq(row.rhs));
            }
        }
    }
    let mut r = SolveResult::empty(KIND, version_of::<S>(), Termination::Optimal);
    match problem.solve() {
        Ok(sol) => {
            r.termination = match sol.status() {
                SolutionStatus::Optimal => Termination::Optimal,
                SolutionStatus::TimeLimit => Termination::Limit(LimitKind::Time),
                SolutionStatus::GapLimit => Termination::Limit(LimitKind::Gap),
            };
            let x: Vec<f64> = vars.iter().map(|&v| sol.value(v)).collect();
            r.objective = Some(sol.eval(&objective));
            r.primal = Some(x);
        }
        Err(e) => {
            r.termination = match (&e as &dyn std::any::Any).downcast_ref::<ResolutionError>() {
                Some(ResolutionError::Infeasible) => Termination::Infeasible,
                Some(ResolutionError::Unbounded) => Termination::Unbounded,
                _ => Termination::Error(e.to_string()),
            };
        }
    }
    r.finish(model.sense);
    r.wall_time = t0.elapsed().as_secs_f64();
    Ok(r)
}

impl Solver for GoodLpSolver {
    fn kind(&self) -> SolverKind {
        KIND
    }

    fn version(&self) -> String {
        version_of_default()
    }

    fn capabilities(&self) -> Capabilities {
        capabilities()
    }

    fn solve(&self, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError> {
        solve_with(good_lp::default_solver, model, o)
    }
}

fn version_of_default() -> String {
    fn of<S: good_lp::Solver>(_: &S) -> String {
        version_of::<S>()
    }
    of(&good_lp::default_solver)
}
