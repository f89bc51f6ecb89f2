//! microlp backend (pure Rust, crate `microlp` 0.7: simplex plus branch and bound).
//!
//! # How the model is given to microlp
//!
//! * microlp's constraints are one-sided (`≤`, `≥`, `=`): a ranged row becomes two constraints,
//!   a free row is left out.
//! * The objective constant is carried by an extra variable fixed at 1, so that microlp's
//!   objective, best bound and relative gap all include it, as netspec's own
//!   [`gap`](super::gap) does. The variable is removed from the reported solution. A model
//!   without a constant gets no such variable.
//! * Integer bounds must be integers in `i32` range: netspec rounds a fractional bound inwards
//!   and gives an infinite one as `i32::MIN`/`i32::MAX` (so an "unbounded" integer variable is
//!   limited to ±2^31); a finite integer bound outside `i32` is refused
//!   ([`SolverErrorKind::ModelUnsupported`]).
//!
//! # Options
//!
//! | option | microlp |
//! |---|---|
//! | `time_limit` | `SolveOptions::time_limit` (wall clock, fractional seconds) |
//! | `rel_gap` | `SolveOptions::mip_gap` (`(incumbent − bound) / |incumbent|`) |
//! | `node_limit` | `SolveOptions::node_limit` (the root LP is not a node) |
//! | `mip_start` | `SolveOptions::warm_start` (a hint for a MIP: an infeasible one is ignored; an LP has no use for it) |
//! | `interrupt` | the search runs in slices of at most 0.1 s, resumed (microlp's `resume_with`) until done, out of budget, or interrupted |
//! | `abs_gap`, `threads` > 1, `seed`, any log, `params` | unsupported: microlp has no such option and logs only through the `log` crate |
//!
//! The result reports microlp's best bound, its node count and its own elapsed time.

use super::stop::StopControl;
use super::{
    guarded_solve, Capabilities, LimitKind, SolveOptions, SolveResult, Solver, SolverError, SolverErrorKind,
    SolverKind, Termination,
};
use crate::milp::NumericLimits;
use crate::milp::{Model, RowKind, Sense, VarKind};
use microlp::{ComparisonOp, OptimizationDirection, Problem, Variable};
use std::time::Duration;

/// The microlp backend.
#[derive(Clone, Copy, Debug, Default)]
pub struct MicrolpSolver;

const KIND: SolverKind = SolverKind::Microlp;

/// The version of the microlp crate netspec is built with.
pub const MICROLP_VERSION: &str = "0.7.0";

/// An integer bound for microlp: rounded inwards, infinite as the `i32` extreme, `None` when a
/// finite bound does not fit in `i32`.
fn int_bound(b: f64, lower: bool) -> Option<i32> {
    if b.is_infinite() {
        return Some(if lower { i32::MIN } else { i32::MAX });
    }
    let r = if lower { b.ceil() } else { b.floor() };
    (i32::MIN as f64..=i32::MAX as f64).contains(&r).then_some(r as i32)
}

/// The microlp problem, the model's variables in [`crate::milp::VarId`] order, and the variable
/// carrying the objective constant (if any).
struct Loaded {
    problem: Problem,
    vars: Vec<Variable>,
    constant: Option<Variable>,
}

fn load(model: &Model) -> Result<Loaded, SolverError> {
    let mut problem = Problem::new(match model.sense {
        Sense::Minimize => OptimizationDirection::Minimize,
        Sense::Maximize => OptimizationDirection::Maximize,
    });
    let mut vars = Vec::with_capacity(model.num_vars());
    for v in model.vars() {
        let var = match v.kind {
            VarKind::Continuous => problem.add_var(v.obj, (v.lb, v.ub)),
            VarKind::Integer | VarKind::Binary => {
                let (lo, hi) = match (int_bound(v.lb, true), int_bound(v.ub, false)) {
                    (Some(lo), Some(hi)) => (lo, hi),
                    _ => {
                        return Err(SolverError::new(
                            KIND,
                            SolverErrorKind::ModelUnsupported(format!(
                                "integer variable `{}` has a bound outside microlp's i32 range [{}, {}]",
                                v.name, v.lb, v.ub
                            )),
                        ))
                    }
                };
                // Bounds that round past each other (e.g. [0.2, 0.8]) leave no integer: keep them
                // crossed so that microlp reports the model infeasible.
                problem.add_integer_var(v.obj, (lo, hi))
            }
        };
        vars.push(var);
    }
    let constant = (model.obj_constant != 0.0).then(|| problem.add_var(model.obj_constant, (1.0, 1.0)));
    for row in model.rows() {
        let terms: Vec<(Variable, f64)> = row.terms().map(|(v, a)| (vars[v.index()], a)).collect();
        match row.kind() {
            RowKind::Free => {}
            RowKind::Le => problem.add_constraint(terms, ComparisonOp::Le, row.rhs),
            RowKind::Ge => problem.add_constraint(terms, ComparisonOp::Ge, row.lhs),
            RowKind::Eq => problem.add_constraint(terms, ComparisonOp::Eq, row.rhs),
            RowKind::Ranged => {
                problem.add_constraint(terms.clone(), ComparisonOp::Ge, row.lhs);
                problem.add_constraint(terms, ComparisonOp::Le, row.rhs);
            }
        }
    }
    Ok(Loaded { problem, vars, constant })
}

/// The longest stretch microlp runs without netspec checking for an interrupt.
const SLICE: Duration = Duration::from_millis(100);

/// The time budget for the next call: what is left of the limit, cut to a [`SLICE`] when an
/// interrupt may come.
fn budget(ctl: &StopControl, sliced: bool) -> Option<Duration> {
    // Durations beyond what `Duration` holds count as no limit, as microlp reads `Duration::MAX`.
    let left = ctl.remaining().map(|t| Duration::try_from_secs_f64(t).unwrap_or(Duration::MAX));
    match (left, sliced) {
        (Some(l), true) => Some(l.min(SLICE)),
        (None, true) => Some(SLICE),
        (l, false) => l,
    }
}

fn options(loaded: &Loaded, o: &SolveOptions, ctl: &StopControl, sliced: bool) -> microlp::SolveOptions {
    let mut opts = microlp::SolveOptions::default();
    opts.time_limit = budget(ctl, sliced);
    opts.node_limit = o.node_limit;
    if let Some(g) = o.rel_gap {
        opts.mip_gap = g;
    }
    if let Some(x) = &o.mip_start {
        // microlp refuses NaN or infinite hint values outright; leave those variables to it.
        let mut hint: Vec<(Variable, f64)> =
            loaded.vars.iter().zip(x).filter(|(_, v)| v.is_finite()).map(|(&var, &v)| (var, v)).collect();
        hint.extend(loaded.constant.map(|c| (c, 1.0)));
        opts.warm_start = Some(hint);
    }
    opts
}

impl Solver for MicrolpSolver {
    fn kind(&self) -> SolverKind {
        KIND
    }

    fn version(&self) -> String {
        MICROLP_VERSION.to_string()
    }

    fn capabilities(&self) -> Capabilities {
        Capabilities {
            integer_variables: true,
            time_limit: true,
            time_limit_whole_seconds: false,
            rel_gap: true,
            abs_gap: false,
            threads: false,
            seed: false,
            node_limit: true,
            log_stdout: false,
            log_file: false,
            mip_start: true,
            reports_dual_bound: true,
            reports_nodes: true,
            reports_solver_time: true,
            reports_progress: false,
            lazy_constraints: false,
            interrupt: true,
            raw_params: false,
            numeric: NumericLimits::uniform(1e20, None),
        }
    }

    fn solve(&self, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError> {
        guarded_solve(self, model, o, |o, ctl| native(model, o, ctl))
    }
}

/// Runs microlp; with an interrupt, in slices of [`SLICE`], resuming until the search ends, a
/// limit is reached or the interrupt comes. Returns the last solved and whether the interrupt
/// stopped it.
fn run_sliced(
    loaded: &Loaded,
    o: &SolveOptions,
    ctl: &StopControl,
) -> (Result<microlp::SolveOutcome, microlp::Error>, bool) {
    let sliced = o.interrupt.is_some();
    let mut solved = loaded.problem.solve_with(options(loaded, o, ctl, sliced));
    if !sliced {
        return (solved, false);
    }
    loop {
        let out = match solved {
            Ok(out) if out.termination_reason() == microlp::TerminationReason::TimeLimit => out,
            other => return (other, false),
        };
        if ctl.interrupted() {
            return (Ok(out), true);
        }
        if ctl.remaining() == Some(0.0) {
            return (Ok(out), false); // the limit itself: TimeLimit is the answer
        }
        let mut resume = out.last_resume_options();
        resume.time_limit = budget(ctl, true);
        resume.node_limit = o.node_limit.map(|n| n.saturating_sub(out.stats().nodes_solved));
        resume.mip_gap = o.rel_gap;
        if resume.node_limit == Some(0) {
            return (Ok(out), false); // reported as the node limit below
        }
        solved = out.resume_with(resume);
    }
}

/// The solve itself, after netspec's common checks (`guarded_solve`).
fn native(model: &Model, o: &SolveOptions, ctl: &StopControl) -> Result<SolveResult, SolverError> {
    let loaded = load(model)?;
    let (solved, interrupted) = run_sliced(&loaded, o, ctl);
    let mut r = SolveResult::empty(KIND, MICROLP_VERSION.to_string(), Termination::Optimal);
    match solved {
        Err(microlp::Error::Infeasible) => r.termination = Termination::Infeasible,
        Err(microlp::Error::Unbounded) => r.termination = Termination::Unbounded,
        Err(microlp::Error::InternalError(e)) => r.termination = Termination::Error(format!("microlp: {e}")),
        Err(microlp::Error::InvalidOptions(e) | microlp::Error::InvalidOperation(e)) => {
            return Err(SolverError::new(KIND, SolverErrorKind::Rejected(format!("microlp: {e}"))))
        }
        Err(e) => r.termination = Termination::Error(format!("microlp: {e}")),
        Ok(solved) => {
            let stats = solved.stats();
            r.termination = match solved.termination_reason() {
                _ if interrupted => Termination::Limit(LimitKind::Interrupt),
                microlp::TerminationReason::ProvenOptimal => Termination::Optimal,
                // microlp stopped on the user's gap: `finish` says Limit(Gap) unless the gap is
                // within the default tolerance anyway.
                microlp::TerminationReason::MipGap => Termination::Optimal,
                microlp::TerminationReason::TimeLimit
                    if o.node_limit.is_some_and(|n| stats.nodes_solved >= n) && ctl.remaining() != Some(0.0) =>
                {
                    Termination::Limit(LimitKind::Node)
                }
                microlp::TerminationReason::TimeLimit => Termination::Limit(LimitKind::Time),
                microlp::TerminationReason::NodeLimit => Termination::Limit(LimitKind::Node),
                _ => Termination::Limit(LimitKind::Other),
            };
            if let Some(sol) = solved.solution() {
                r.primal = Some(loaded.vars.iter().map(|&v| sol.var_value(v)).collect());
                r.objective = Some(sol.objective());
            }
            r.dual_bound = stats.best_bound.filter(|b| b.is_finite());
            r.nodes = Some(stats.nodes_solved);
            r.solver_time = Some(stats.elapsed.as_secs_f64());
        }
    }
    if model.num_vars() == 0 && r.termination == Termination::Optimal && r.primal.is_none() {
        r.primal = Some(Vec::new());
        r.objective = Some(model.obj_constant);
        r.dual_bound = Some(model.obj_constant);
    }
    r.finish(model.sense);
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_bounds_without_an_integer_are_infeasible() {
        let mut m = Model::new("crossed");
        m.add_integer("z", 0.2, 0.8, 1.0);
        let o = SolveOptions::default();
        // microlp itself (netspec's screen would answer before it).
        let r = native(&m, &o, &StopControl::new(&o, std::time::Instant::now())).unwrap();
        assert_eq!(r.termination, Termination::Infeasible);
    }

    #[test]
    fn out_of_range_integer_bound_is_refused() {
        let mut m = Model::new("big");
        m.add_integer("x", 0.0, 1e12, 1.0);
        let e = MicrolpSolver.solve(&m, &SolveOptions::default()).unwrap_err();
        assert!(matches!(e.kind, SolverErrorKind::ModelUnsupported(_)));
    }
}
