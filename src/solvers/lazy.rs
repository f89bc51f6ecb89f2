//! Lazy constraints: rows too many to write down, produced on demand by a [`Separator`].
//!
//! A backend with the `lazy_constraints` capability runs the separator inside its own branch
//! and cut (SCIP: a constraint handler that checks and enforces integral points and separates
//! fractional LP points). Every other backend gets [`solve_loop`]: solve, separate the
//! incumbent, add the violated rows, solve again from a repaired start, under one shared time
//! limit — each round is a full solve of a relaxation, so its bound is valid for the whole
//! problem, and the loop ends when an incumbent violates no lazy row.
//!
//! Either way the rows that were added come back with the result, so the MILP checker can check
//! the returned point against the emitted rows **and** every separated row.

use super::{LimitKind, SolveOptions, SolveResult, Solver, SolverError, Termination};
use crate::milp::{check_point, Model, Sense, Tolerances, VarId};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// A row produced by a separator: `lhs ≤ Σ a_j x_j ≤ rhs`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LazyRow {
    /// A name for files and reports.
    pub name: String,
    /// Lower side (may be −∞).
    pub lhs: f64,
    /// Upper side (may be +∞).
    pub rhs: f64,
    /// The terms.
    pub terms: Vec<(VarId, f64)>,
}

impl LazyRow {
    /// The row's activity `Σ a_j x_j` at `x`.
    pub fn activity(&self, x: &[f64]) -> f64 {
        self.terms.iter().map(|&(v, c)| c * x[v.index()]).sum()
    }

    /// How far `x` is outside the row's sides (0 when it holds).
    pub fn violation(&self, x: &[f64]) -> f64 {
        let a = self.activity(x);
        (self.lhs - a).max(a - self.rhs).max(0.0)
    }

    /// Adds the row to a model.
    pub fn add_to(&self, m: &mut Model) {
        m.add_row(self.name.clone(), self.lhs, self.rhs, self.terms.iter().copied());
    }
}

/// Which way a lazy row can be hurt by moving a variable, so that a solver's presolve does not
/// round it the wrong way ("variable locks").
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Lock {
    /// Decreasing the variable can violate a lazy row.
    Down,
    /// Increasing the variable can violate a lazy row.
    Up,
    /// Both.
    Both,
}

/// Produces violated rows of a family that is not written into the model.
pub trait Separator {
    /// A short name (`cutset`).
    fn name(&self) -> &str;
    /// The rows violated by `x`, a point whose integer variables are integral. Empty means
    /// `x` satisfies every lazy row: this must be exact.
    fn separate_integral(&mut self, x: &[f64]) -> Vec<LazyRow>;
    /// Rows violated by a fractional point (an LP solution); may find only some, or none.
    fn separate_fractional(&mut self, _x: &[f64]) -> Vec<LazyRow> {
        Vec::new()
    }
    /// A point that satisfies every lazy row, made from an integral point that does not (for
    /// the next round's start), if the separator knows how.
    fn repair(&mut self, _x: &[f64]) -> Option<Vec<f64>> {
        None
    }
    /// The variables the lazy rows involve, and which way each can be hurt.
    fn locks(&self) -> Vec<(VarId, Lock)>;
}

/// How the lazy rows were handled.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LazyMode {
    /// Inside the solver's branch and cut (a callback).
    Callback,
    /// Solve, separate, add, solve again ([`solve_loop`]).
    Loop,
}

/// What the lazy rows cost and did.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LazyReport {
    /// The separator's name.
    pub separator: String,
    /// Callback or loop.
    pub mode: LazyMode,
    /// Loop: solves run. Callback: separation calls.
    pub rounds: u64,
    /// Rows added in all.
    pub rows_added: usize,
    /// Seconds spent in the separator.
    pub separation_seconds: f64,
    /// Loop: whether a start was handed to a round after the first.
    #[serde(default)]
    pub repaired_starts: u64,
    /// Loop: cutting-plane rounds on the LP relaxation before the first solve, and the rows
    /// they added (part of `rows_added`).
    #[serde(default)]
    pub root_rounds: u64,
    /// The LP relaxation's bound after the root rounds (before: the first round's value).
    #[serde(default)]
    pub root_bounds: Option<(f64, f64)>,
    /// Loop: root-round rows left out of the model handed to the solver because they were slack
    /// at the last LP point (still valid, and still checked; part of `rows_added`).
    #[serde(default)]
    pub root_rows_dropped: usize,
    /// Loop: whether the root rounds kept the LP loaded in the backend, each round starting
    /// from the last basis ([`Solver::lp_session`]); `false` when each was solved from scratch.
    #[serde(default)]
    pub warm_root_rounds: bool,
}

impl LazyReport {
    /// A report with nothing done yet.
    pub fn new(separator: String, mode: LazyMode) -> LazyReport {
        LazyReport {
            separator,
            mode,
            rounds: 0,
            rows_added: 0,
            separation_seconds: 0.0,
            repaired_starts: 0,
            root_rounds: 0,
            root_bounds: None,
            root_rows_dropped: 0,
            warm_root_rounds: false,
        }
    }
}

impl std::ops::AddAssign<&LazyReport> for LazyReport {
    /// Adds the counts and seconds of a later solve with the same separator (the two phases of
    /// [`crate::solvers::split`]); the root bounds stay this report's.
    fn add_assign(&mut self, later: &LazyReport) {
        self.rounds += later.rounds;
        self.rows_added += later.rows_added;
        self.separation_seconds += later.separation_seconds;
        self.repaired_starts += later.repaired_starts;
        self.root_rounds += later.root_rounds;
        self.root_rows_dropped += later.root_rows_dropped;
        self.warm_root_rounds |= later.warm_root_rounds;
    }
}

/// A solve with lazy rows: the result, the rows added, and the report.
#[derive(Clone, Debug)]
pub struct LazySolve {
    /// The result, for the whole problem (emitted and lazy rows).
    pub result: SolveResult,
    /// Every row the separator produced that is in the solver's last model.
    pub rows: Vec<LazyRow>,
    /// The root rounds' rows left out of the solver's model (slack at the last LP point): valid
    /// like the others and checked at the answer with them, but not handed to a solver — nor
    /// to the next phase of a split solve ([`super::split`]), which on Fig. 2e they had slowed
    /// from 61 s to 77 s.
    pub left_out: Vec<LazyRow>,
    /// What it cost.
    pub report: LazyReport,
}

/// The generic lazy-constraint solve: solve, separate the incumbent, add the rows, solve again
/// from a repaired start, until an incumbent violates no lazy row or the time limit is spent.
///
/// The dual bound of every round is valid for the whole problem (a round solves a relaxation).
/// A round that stops with an incumbent that violates lazy rows does not give a solution of the
/// whole problem: the result then carries the best repaired point found (if any), with
/// termination `Limit(Time)` when the time is spent.
pub fn solve_loop<S: Solver + ?Sized>(
    solver: &S,
    model: &Model,
    sep: &mut dyn Separator,
    o: &SolveOptions,
) -> Result<LazySolve, SolverError> {
    let t0 = Instant::now();
    let tol = Tolerances::default();
    let mut work = model.clone();
    let mut rows: Vec<LazyRow> = Vec::new();
    let mut left_out: Vec<LazyRow> = Vec::new();
    let mut report = LazyReport::new(sep.name().to_string(), LazyMode::Loop);
    let budget = RoundBudget {
        base: o.time_limit.map(|l| ROOT_SHARE * l),
        productive: o.time_limit.map(|l| ROOT_SHARE_PRODUCTIVE * l),
        incumbent: o.mip_start.as_ref().map(|x| model.objective_value(x)),
    };
    root_rounds(solver, &mut work, &mut rows, &mut left_out, sep, o, t0, budget, &mut report)?;
    // The best point known to satisfy every row (emitted and lazy), with its objective.
    let mut best: Option<(Vec<f64>, f64)> = None;
    let better = |a: f64, b: f64| match model.sense {
        Sense::Minimize => a < b,
        Sense::Maximize => a > b,
    };
    let mut start = o.mip_start.clone();
    if let Some(x) = &start {
        if sep.separate_integral(x).is_empty() && check_point(&work, x, &tol).is_feasible() {
            best = Some((x.clone(), model.objective_value(x)));
        }
    }
    let mut bound: Option<f64> = None;
    let mut nodes = 0u64;
    let mut solver_time = 0.0;
    loop {
        report.rounds += 1;
        let mut oi = o.clone();
        if let Some(limit) = o.time_limit {
            oi.time_limit = Some((limit - t0.elapsed().as_secs_f64()).max(0.0));
        }
        // A start is handed over only if it satisfies the current rows.
        oi.mip_start = start.take().filter(|x| check_point(&work, x, &tol).is_feasible());
        if report.rounds > 1 && oi.mip_start.is_some() {
            report.repaired_starts += 1;
        }
        let mut r = solver.solve(&work, &oi)?;
        nodes += r.nodes.unwrap_or(0);
        solver_time += r.solver_time.unwrap_or(0.0);
        if let Some(b) = r.dual_bound {
            // Later rounds solve tighter relaxations; keep the strongest bound seen.
            bound = Some(match (bound, model.sense) {
                (None, _) => b,
                (Some(a), Sense::Minimize) => a.max(b),
                (Some(a), Sense::Maximize) => a.min(b),
            });
        }
        let finish = |mut r: SolveResult, best: Option<(Vec<f64>, f64)>, bound: Option<f64>| {
            if let Some((x, obj)) = best {
                r.primal = Some(x);
                r.objective = Some(obj);
            } else {
                r.primal = None;
                r.objective = None;
            }
            r.dual_bound = bound;
            r.nodes = Some(nodes);
            r.solver_time = Some(solver_time);
            r.finish(model.sense);
            r.wall_time = t0.elapsed().as_secs_f64();
            r
        };
        let Some(x) = r.primal.clone() else {
            // No incumbent: infeasible relaxation means an infeasible problem; a limit leaves
            // the best repaired point, if any.
            if r.termination == Termination::Infeasible {
                best = None;
            }
            return Ok(LazySolve { result: finish(r, best, bound), rows, left_out, report });
        };
        let ts = Instant::now();
        let cuts = sep.separate_integral(&x);
        report.separation_seconds += ts.elapsed().as_secs_f64();
        if cuts.is_empty() {
            // Feasible for the whole problem.
            let obj = r.objective.unwrap_or_else(|| model.objective_value(&x));
            if best.as_ref().is_none_or(|(_, b)| better(obj, *b) || (obj - *b).abs() <= 1e-9 * b.abs().max(1.0)) {
                best = Some((x, obj));
            }
            return Ok(LazySolve { result: finish(r, best, bound), rows, left_out, report });
        }
        for c in &cuts {
            c.add_to(&mut work);
        }
        report.rows_added += cuts.len();
        rows.extend(cuts);
        let ts = Instant::now();
        let repaired = sep.repair(&x);
        report.separation_seconds += ts.elapsed().as_secs_f64();
        if let Some(y) = repaired {
            if sep.separate_integral(&y).is_empty() && check_point(&work, &y, &tol).is_feasible() {
                let obj = model.objective_value(&y);
                if best.as_ref().is_none_or(|(_, b)| better(obj, *b)) {
                    best = Some((y, obj));
                }
            }
        }
        start = best.as_ref().map(|(x, _)| x.clone());
        let out_of_time = o.time_limit.is_some_and(|l| t0.elapsed().as_secs_f64() >= l);
        let interrupted = o.interrupt.as_ref().is_some_and(|i| i.is_triggered());
        // A round that stopped on its gap stopped on an incumbent that is no design (it breaks
        // a lazy row), so that gap says nothing: the next round goes on like after an optimum.
        let stopped = !matches!(r.termination, Termination::Optimal | Termination::Limit(LimitKind::Gap));
        if out_of_time || interrupted || stopped {
            if matches!(r.termination, Termination::Optimal | Termination::Limit(LimitKind::Gap)) {
                r.termination = Termination::Limit(if interrupted { LimitKind::Interrupt } else { LimitKind::Time });
            }
            return Ok(LazySolve { result: finish(r, best, bound), rows, left_out, report });
        }
    }
}

/// The root rounds' share of the time limit.
const ROOT_SHARE: f64 = 0.2;
/// The share the root rounds may go on to while they still close the gap fast
/// ([`RoundBudget::productive`]).
const ROOT_SHARE_PRODUCTIVE: f64 = 0.4;
/// The share of the gap between the start and the LP bound that the last three rounds must
/// have closed for the rounds to go on past [`ROOT_SHARE`].
const ROOT_MIN_CLOSED: f64 = 0.05;

/// How long the root rounds may run (seconds from the solve's start).
#[derive(Clone, Copy, Debug, Default)]
struct RoundBudget {
    /// Until here in any case.
    base: Option<f64>,
    /// Until here while the last three rounds closed at least [`ROOT_MIN_CLOSED`] of the gap
    /// between `incumbent` and the bound (on Fig. 7c-L2 the rounds lift the bound from 326 to
    /// 563 over 25 s, and are still closing a fifth of the gap every three rounds when a fifth
    /// of its 70-s limit is spent).
    productive: Option<f64>,
    /// The objective of the start, if any.
    incumbent: Option<f64>,
}

impl RoundBudget {
    /// Whether rounds may go on at `elapsed`, after the LP bounds `bounds` of the rounds so far.
    fn allows(&self, elapsed: f64, bounds: &[f64], sense: Sense) -> bool {
        if self.base.is_none_or(|b| elapsed < b) {
            return true;
        }
        let (Some(limit), Some(incumbent), [.., before, _, _, last]) = (self.productive, self.incumbent, bounds) else {
            return false;
        };
        let toward = |a: f64, b: f64| match sense {
            Sense::Minimize => b - a,
            Sense::Maximize => a - b,
        };
        let gap = toward(*last, incumbent);
        elapsed < limit && gap > 0.0 && toward(*before, *last) >= ROOT_MIN_CLOSED * gap
    }

    /// The time a round allowed to start at `elapsed`, after `rounds` rounds, may take: up to
    /// the productive share when the rounds may go on to it (a round's LP that runs out of time
    /// ends the rounds, so one begun just before the base share ends gets the time its
    /// successors might get) — not before three rounds have shown their pace, so that at a
    /// tiny limit a slow first LP does not eat the solver's time (Fig. 8-L4 at 1 s).
    fn left(&self, elapsed: f64, rounds: usize) -> Option<f64> {
        let until = match (self.base, self.productive, self.incumbent) {
            (Some(_), Some(p), Some(_)) if rounds >= 3 => p,
            (b, _, _) => b?,
        };
        Some((until - elapsed).max(0.0))
    }
}

/// Cutting-plane rounds at the root: solve the LP relaxation, add the separator's rows for the
/// fractional point, repeat while they move the bound (at most [`MAX_ROOT_ROUNDS`] rounds, and
/// [`RoundBudget`]'s time: a fifth of the time limit, two fifths while they close the gap
/// fast). The rows are valid everywhere, so they join the model: a backend without callbacks
/// then branches on the strengthened relaxation. Only the rows tight at the
/// last LP point (and those added after it) stay in `work` and `rows`; the others go to
/// `left_out`: slack ones only slow the solver's LPs (on Fig. 2e the rounds added 1,898 rows and
/// HiGHS no longer proved the row in the paper's time). Returns the last LP point.
#[allow(clippy::too_many_arguments)]
fn root_rounds<S: Solver + ?Sized>(
    solver: &S,
    work: &mut Model,
    rows: &mut Vec<LazyRow>,
    left_out: &mut Vec<LazyRow>,
    sep: &mut dyn Separator,
    o: &SolveOptions,
    t0: Instant,
    budget: RoundBudget,
    report: &mut LazyReport,
) -> Result<Option<Vec<f64>>, SolverError> {
    let mut stalled = 0;
    let base = work.clone();
    let start = rows.len();
    let mut last_point: Option<(Vec<f64>, usize)> = None;
    // The LP bound of every round so far.
    let mut bounds: Vec<f64> = Vec::new();
    let relax = |m: &Model| {
        let mut relaxed = m.clone();
        for j in 0..relaxed.num_vars() {
            relaxed.var_mut(VarId(j as u32)).kind = crate::milp::VarKind::Continuous;
        }
        relaxed
    };
    let lp_options = SolveOptions {
        log: super::LogTarget::Quiet,
        threads: o.threads,
        interrupt: o.interrupt.clone(),
        ..SolveOptions::default()
    };
    // The LP kept loaded between rounds, when the backend can (each round then starts from the
    // last basis); a session that fails is dropped and the rounds go on from scratch.
    let mut session = solver.lp_session(&relax(work), &lp_options).ok().flatten();
    for _ in 0..MAX_ROOT_ROUNDS {
        let elapsed = t0.elapsed().as_secs_f64();
        if !budget.allows(elapsed, &bounds, work.sense) || o.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
            break;
        }
        let time_left = budget.left(elapsed, bounds.len());
        let r = match session.as_mut().map(|s| s.solve(time_left)) {
            Some(Ok(r)) => r,
            failed => {
                if failed.is_some() {
                    session = None;
                }
                solver.solve(&relax(work), &SolveOptions { time_limit: time_left, ..lp_options.clone() })?
            }
        };
        let (Some(x), Some(obj)) = (r.primal, r.objective) else { break };
        if r.termination != Termination::Optimal {
            break;
        }
        bounds.push(obj);
        let ts = Instant::now();
        let cuts = sep.separate_fractional(&x);
        last_point = Some((x, rows.len()));
        report.separation_seconds += ts.elapsed().as_secs_f64();
        if cuts.is_empty() {
            break;
        }
        let previous = bounds.len().checked_sub(2).map(|i| bounds[i]);
        if previous.is_some_and(|p| (obj - p).abs() <= 1e-4 * obj.abs().max(1.0)) {
            stalled += 1;
            if stalled >= 3 {
                break;
            }
        } else {
            stalled = 0;
        }
        report.root_rounds += 1;
        report.rows_added += cuts.len();
        for c in &cuts {
            c.add_to(work);
        }
        if session.as_mut().is_some_and(|s| s.add_rows(&cuts).is_err()) {
            session = None;
        }
        rows.extend(cuts);
    }
    // A session that failed was dropped, and the rounds after it ran from scratch.
    report.warm_root_rounds = session.is_some();
    if let (Some(&first), Some(&last)) = (bounds.first(), bounds.last()) {
        report.root_bounds = Some((first, last));
    }
    if let Some((x, solved_with)) = &last_point {
        let tight = |r: &LazyRow| {
            let a = r.activity(x);
            let tol = |side: f64| 1e-6 * side.abs().max(1.0);
            (r.lhs.is_finite() && a - r.lhs <= tol(r.lhs)) || (r.rhs.is_finite() && r.rhs - a <= tol(r.rhs))
        };
        // The rows added after the last LP point stay; of the earlier ones, the tight.
        let added_after = rows.split_off(*solved_with);
        let (kept, slack): (Vec<LazyRow>, Vec<LazyRow>) = rows.drain(start..).partition(|r| tight(r));
        rows.extend(kept);
        rows.extend(added_after);
        report.root_rows_dropped = slack.len();
        if !slack.is_empty() {
            *work = base;
            for r in &rows[start..] {
                r.add_to(work);
            }
        }
        left_out.extend(slack);
    }
    Ok(last_point.map(|(x, _)| x))
}

/// Cap on the cutting-plane rounds at the root.
const MAX_ROOT_ROUNDS: usize = 200;

/// The LP relaxation's bound: of the model as written, and after cutting-plane rounds with the
/// separator's fractional rows (when one is given).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LpBound {
    /// The relaxation's optimum as written (`None` when it has none: infeasible, a limit).
    pub plain: Option<f64>,
    /// After the cutting-plane rounds.
    pub with_cuts: Option<f64>,
    /// Rounds run and rows added.
    pub rounds: u64,
    /// Rows added.
    pub rows: usize,
    /// Seconds in all.
    pub seconds: f64,
    /// The last LP point (the relaxation's optimum after the rounds), one value per variable.
    pub point: Option<Vec<f64>>,
}

/// Solves the LP relaxation of `model` (and runs the separator's cutting-plane rounds on it, if
/// given) within `o.time_limit`.
pub fn lp_bound<S: Solver + ?Sized>(
    solver: &S,
    model: &Model,
    sep: Option<&mut dyn Separator>,
    o: &SolveOptions,
) -> Result<LpBound, SolverError> {
    let t0 = Instant::now();
    let mut report = LazyReport::new(String::new(), LazyMode::Loop);
    let mut work = model.clone();
    let (mut rows, mut left_out) = (Vec::new(), Vec::new());
    struct NoRows;
    impl Separator for NoRows {
        fn name(&self) -> &str {
            "none"
        }
        fn separate_integral(&mut self, _: &[f64]) -> Vec<LazyRow> {
            Vec::new()
        }
        fn locks(&self) -> Vec<(VarId, Lock)> {
            Vec::new()
        }
    }
    let mut none = NoRows;
    let sep: &mut dyn Separator = match sep {
        Some(s) => s,
        None => &mut none,
    };
    let point = root_rounds(
        solver,
        &mut work,
        &mut rows,
        &mut left_out,
        sep,
        o,
        t0,
        RoundBudget { base: o.time_limit, ..RoundBudget::default() },
        &mut report,
    )?;
    let (plain, with_cuts) = report.root_bounds.map_or((None, None), |(a, b)| (Some(a), Some(b)));
    Ok(LpBound {
        plain,
        with_cuts,
        rounds: report.root_rounds,
        rows: rows.len() + left_out.len(),
        seconds: t0.elapsed().as_secs_f64(),
        point,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::{Capabilities, SolverKind};
    use std::cell::Cell;

    #[test]
    fn root_rounds_go_on_past_their_share_only_while_they_close_the_gap_fast() {
        let b = RoundBudget { base: Some(10.0), productive: Some(20.0), incumbent: Some(100.0) };
        let min = Sense::Minimize;
        // Within the base share: always, with its own time left.
        assert!(b.allows(5.0, &[], min));
        assert_eq!(b.left(5.0, 3), Some(15.0), "up to the productive share, which its successors might reach");
        assert_eq!(b.left(5.0, 2), Some(5.0), "before three rounds, only the base share");
        assert_eq!(
            RoundBudget { incumbent: None, ..b }.left(5.0, 3),
            Some(5.0),
            "without a start, only the base share"
        );
        // Past it: the last three rounds (50 → 60) closed 10 of the 40 left (25 % ≥ 5 %).
        assert!(b.allows(12.0, &[40.0, 50.0, 55.0, 58.0, 60.0], min));
        assert_eq!(b.left(12.0, 5), Some(8.0));
        // 59.9 → 60 closes 0.25 % of the gap: stop; so too past the productive share, with
        // fewer than four rounds, or without a start.
        assert!(!b.allows(12.0, &[59.9, 59.95, 59.98, 60.0], min));
        assert!(!b.allows(20.0, &[40.0, 50.0, 55.0, 58.0, 60.0], min));
        assert!(!b.allows(12.0, &[50.0, 55.0, 60.0], min));
        assert!(!RoundBudget { incumbent: None, ..b }.allows(12.0, &[40.0, 50.0, 55.0, 60.0], min));
        // A maximisation's bound falls toward its start.
        let max = RoundBudget { incumbent: Some(10.0), ..b };
        assert!(max.allows(12.0, &[60.0, 50.0, 45.0, 40.0], Sense::Maximize));
        assert!(!max.allows(12.0, &[60.0, 50.0, 45.0, 40.0], min), "a bound moving away from the start");
        // No limit: no budget.
        assert!(RoundBudget::default().allows(1e9, &[], min));
        assert_eq!(RoundBudget::default().left(3.0, 5), None);
    }

    /// A backend that answers from a script: the relaxations at the root get nothing; the first
    /// MIP round stops on its gap (objective 1, bound 0.5) at a point that breaks the lazy row,
    /// the second is optimal at one that keeps it.
    struct Scripted {
        rounds: Cell<u32>,
    }

    impl Solver for Scripted {
        fn kind(&self) -> SolverKind {
            SolverKind::Microlp
        }
        fn version(&self) -> String {
            "scripted".into()
        }
        fn capabilities(&self) -> Capabilities {
            SolverKind::Microlp.instance().expect("microlp is always compiled").capabilities()
        }
        fn solve(&self, model: &Model, _: &SolveOptions) -> Result<SolveResult, SolverError> {
            let mut r = SolveResult::empty(SolverKind::Microlp, self.version(), Termination::Optimal);
            if model.var(VarId(0)).kind == crate::milp::VarKind::Continuous {
                return Ok(r);
            }
            self.rounds.set(self.rounds.get() + 1);
            let (x, obj, bound) =
                if self.rounds.get() == 1 { (vec![1.0, 0.0], 1.0, 0.5) } else { (vec![1.0, 1.0], 2.0, 2.0) };
            r.primal = Some(x);
            r.objective = Some(obj);
            r.dual_bound = Some(bound);
            r.finish(model.sense);
            Ok(r)
        }
    }

    /// The lazy row `x1 ≥ x0`.
    struct Follows;

    impl Separator for Follows {
        fn name(&self) -> &str {
            "follows"
        }
        fn separate_integral(&mut self, x: &[f64]) -> Vec<LazyRow> {
            if x[1] + 1e-9 < x[0] {
                vec![LazyRow {
                    name: "follows".into(),
                    lhs: f64::NEG_INFINITY,
                    rhs: 0.0,
                    terms: vec![(VarId(0), 1.0), (VarId(1), -1.0)],
                }]
            } else {
                Vec::new()
            }
        }
        fn locks(&self) -> Vec<(VarId, Lock)> {
            Vec::new()
        }
    }

    /// At the first fractional point: `a ≥ 0.5` (tight at the next LP point) and `a + b ≥ 0.2`
    /// (slack there); nothing after.
    struct TwoRoots {
        calls: u32,
    }

    impl Separator for TwoRoots {
        fn name(&self) -> &str {
            "two roots"
        }
        fn separate_integral(&mut self, _: &[f64]) -> Vec<LazyRow> {
            Vec::new()
        }
        fn separate_fractional(&mut self, _: &[f64]) -> Vec<LazyRow> {
            self.calls += 1;
            if self.calls > 1 {
                return Vec::new();
            }
            let row = |name: &str, lhs: f64, terms: Vec<(VarId, f64)>| LazyRow {
                name: name.into(),
                lhs,
                rhs: f64::INFINITY,
                terms,
            };
            vec![row("tight", 0.5, vec![(VarId(0), 1.0)]), row("slack", 0.2, vec![(VarId(0), 1.0), (VarId(1), 1.0)])]
        }
        fn locks(&self) -> Vec<(VarId, Lock)> {
            Vec::new()
        }
    }

    #[test]
    fn root_rows_slack_at_the_last_lp_point_are_left_out_of_the_model_and_of_the_rows_passed_on() {
        let mut m = Model::new("roots");
        let a = m.add_binary("a", 1.0);
        let b = m.add_binary("b", 1.0);
        let _ = (a, b);
        let solver = SolverKind::Microlp.instance().expect("microlp is always compiled");
        let out = solve_loop(solver.as_ref(), &m, &mut TwoRoots { calls: 0 }, &SolveOptions::default()).unwrap();
        assert_eq!(out.report.root_rounds, 1);
        assert_eq!(out.report.root_rows_dropped, 1);
        let names = |rows: &[LazyRow]| rows.iter().map(|r| r.name.clone()).collect::<Vec<_>>();
        assert_eq!(
            names(&out.rows),
            ["tight"],
            "only the tight row stays in the model (a split's next phase gets these)"
        );
        assert_eq!(names(&out.left_out), ["slack"], "the slack one is kept aside, to be checked");
        assert_eq!(out.result.termination, Termination::Optimal);
        assert_eq!(out.result.objective, Some(1.0));
    }

    #[test]
    fn a_round_that_stops_on_its_gap_at_a_point_that_breaks_a_lazy_row_is_not_the_end() {
        let mut m = Model::new("gap_round");
        let a = m.add_binary("a", 1.0);
        let b = m.add_binary("b", 1.0);
        m.add_ge("one", [(a, 1.0)], 1.0);
        let _ = b;
        let solver = Scripted { rounds: Cell::new(0) };
        let out =
            solve_loop(&solver, &m, &mut Follows, &SolveOptions { rel_gap: Some(0.99), ..SolveOptions::default() })
                .unwrap();
        assert_eq!(solver.rounds.get(), 2, "the loop stopped after the gap-limited round");
        assert_eq!(out.result.termination, Termination::Optimal);
        assert_eq!(out.result.primal.as_deref(), Some(&[1.0, 1.0][..]));
        assert_eq!(out.result.objective, Some(2.0));
        assert_eq!(out.report.rows_added, 1);
    }
}
