//! What a solve returns: why it stopped, and what it found.

use super::SolverKind;
use crate::milp::{check_point, CheckReport, Infeasibility, Model, Sense, Tolerances};
use serde::{Deserialize, Serialize};

/// Which limit stopped the solve.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LimitKind {
    /// The time limit.
    Time,
    /// The node limit.
    Node,
    /// The relative or absolute gap limit (the solution is not proven optimal to the default
    /// tolerance).
    Gap,
    /// A solution-count limit.
    Solution,
    /// An interrupt (signal or callback).
    Interrupt,
    /// Another limit the solver reported (iterations, memory).
    Other,
}

/// Why the solver stopped. Says nothing about whether a solution exists: see
/// [`SolveResult::primal`].
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "reason", content = "detail")]
pub enum Termination {
    /// Proven optimal (to the solver's default tolerances).
    Optimal,
    /// Proven infeasible.
    Infeasible,
    /// Proven unbounded.
    Unbounded,
    /// Infeasible or unbounded, the solver cannot tell which.
    InfeasibleOrUnbounded,
    /// A limit was reached.
    Limit(LimitKind),
    /// The solver gave up for numerical reasons.
    NumericalError,
    /// The solver failed; the text is its own message.
    Error(String),
}

impl Termination {
    /// Short text for tables: `optimal`, `infeasible`, `limit(time)` …
    pub fn label(&self) -> String {
        match self {
            Termination::Optimal => "optimal".into(),
            Termination::Infeasible => "infeasible".into(),
            Termination::Unbounded => "unbounded".into(),
            Termination::InfeasibleOrUnbounded => "infeasible_or_unbounded".into(),
            Termination::Limit(LimitKind::Interrupt) => "interrupted".into(),
            Termination::Limit(k) => format!("limit({})", format!("{k:?}").to_lowercase()),
            Termination::NumericalError => "numerical_error".into(),
            Termination::Error(_) => "error".into(),
        }
    }
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Termination::Error(e) => write!(f, "error: {e}"),
            t => f.write_str(&t.label()),
        }
    }
}

/// The result of one solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveResult {
    /// Why the solver stopped.
    pub termination: Termination,
    /// The best primal point found, one value per variable, if any.
    pub primal: Option<Vec<f64>>,
    /// The objective of `primal` as the solver reported it (in the model's sense, with the
    /// constant).
    pub objective: Option<f64>,
    /// The best proven bound on the optimum (lower for min, upper for max), if known.
    pub dual_bound: Option<f64>,
    /// The relative gap by netspec's one formula [`gap`], from `objective` and `dual_bound`.
    pub gap: Option<f64>,
    /// Branch-and-bound nodes, if the solver reports them.
    pub nodes: Option<u64>,
    /// The solver's own run time in seconds, if it reports one (for CBC, which does not,
    /// netspec's measurement of the native solve call, excluding any queueing).
    pub solver_time: Option<f64>,
    /// Wall-clock time of the whole `solve` call, measured by netspec.
    pub wall_time: f64,
    /// The backend.
    pub solver: SolverKind,
    /// The solver's version.
    pub solver_version: String,
    /// When netspec proved the model infeasible without a solver (see
    /// [`crate::milp::screen`]): the variable or row, and why.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub infeasibility: Option<Infeasibility>,
    /// The MIP start's check by netspec's checker, when one was given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mip_start: Option<StartCheck>,
    /// What netspec noticed about the input before the solve (finite bounds the backend treats
    /// as infinite, [`crate::milp::numeric`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// What netspec's independent checker said of a MIP start before the solve: a start that fails
/// is reported here and never handed to the solver.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StartCheck {
    /// Whether the start passed and was handed over.
    pub accepted: bool,
    /// The start's objective (recomputed by the checker).
    pub objective: f64,
    /// How many bounds, rows and integralities it violates.
    pub violations: usize,
    /// The first violation, as text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_violation: Option<String>,
}

/// The largest difference between a solution's objective and the dual bound that netspec still
/// calls optimal: `1e-6` absolute, or `1e-9` relative for objectives above 1000. Solvers whose
/// own default gap is looser (HiGHS stops at 1e-4 relative) are given a zero relative gap when
/// none is set, so that "optimal" holds for objectives with small weights such as the paper's
/// `0*` (1e-4).
pub const OPTIMALITY_TOLERANCE: (f64, f64) = (1e-6, 1e-9);

/// Whether a primal value and a dual bound are close enough to call the primal optimal (see
/// [`OPTIMALITY_TOLERANCE`]).
pub fn within_optimality_tolerance(primal: f64, dual: f64, sense: Sense) -> bool {
    let behind = match sense {
        Sense::Minimize => primal - dual,
        Sense::Maximize => dual - primal,
    };
    behind <= OPTIMALITY_TOLERANCE.0 || behind <= OPTIMALITY_TOLERANCE.1 * primal.abs().max(dual.abs())
}

impl SolveResult {
    /// A result with no solution, for the given termination.
    pub fn empty(solver: SolverKind, version: String, termination: Termination) -> Self {
        SolveResult {
            termination,
            primal: None,
            objective: None,
            dual_bound: None,
            gap: None,
            nodes: None,
            solver_time: None,
            wall_time: 0.0,
            solver,
            solver_version: version,
            infeasibility: None,
            mip_start: None,
            warnings: Vec::new(),
        }
    }

    /// Fills in `gap` from the bounds, and turns a solver's "optimal" into [`LimitKind::Gap`]
    /// when its dual bound is not within [`OPTIMALITY_TOLERANCE`] of the objective (the solver
    /// stopped on a gap limit, the user's or its own default).
    pub fn finish(&mut self, sense: Sense) {
        (self.gap, self.termination) = finished(&self.termination, self.objective, self.dual_bound, sense);
    }

    /// One line that says apart why the solver stopped and whether it has a solution:
    /// `limit(time), solution found (objective 12.5, gap 3.10 %)`, `limit(time), no solution`,
    /// `infeasible: row `c`: …`.
    pub fn status_line(&self) -> String {
        status_line(&self.termination, self.infeasibility.as_ref(), self.objective, self.gap, self.primal.is_some())
    }

    /// Runs the independent checker on the primal point, if any.
    pub fn check(&self, model: &Model, tol: &Tolerances) -> Option<CheckReport> {
        self.primal.as_ref().map(|x| check_point(model, x, tol))
    }

    /// Whether a primal point is present.
    pub fn has_solution(&self) -> bool {
        self.primal.is_some()
    }
}

/// The gap from an objective and a bound, and the termination with a solver's "optimal" turned
/// into [`LimitKind::Gap`] when the bound is not within [`OPTIMALITY_TOLERANCE`] of the objective
/// (the solver stopped on a gap limit, the user's or its own default).
pub fn finished(
    termination: &Termination,
    objective: Option<f64>,
    dual_bound: Option<f64>,
    sense: Sense,
) -> (Option<f64>, Termination) {
    let (gap, close) = match (objective, dual_bound) {
        (Some(p), Some(d)) => (Some(gap(p, d, sense)), within_optimality_tolerance(p, d, sense)),
        _ => (None, true),
    };
    let termination = match termination {
        Termination::Optimal if !close => Termination::Limit(LimitKind::Gap),
        t => t.clone(),
    };
    (gap, termination)
}

/// One line that says apart why a solve stopped and whether it has a solution (`has_point`: a
/// point without an objective): `limit(time), solution found (objective 12.5, gap 3.10 %)`,
/// `limit(time), no solution`, `infeasible: row `c`: …`.
pub fn status_line(
    termination: &Termination,
    infeasibility: Option<&Infeasibility>,
    objective: Option<f64>,
    gap: Option<f64>,
    has_point: bool,
) -> String {
    let found = match (has_point, objective) {
        (_, Some(obj)) => {
            format!(
                "solution found (objective {obj}{})",
                gap.map_or(String::new(), |g| format!(", gap {}", percent(g)))
            )
        }
        (true, None) => "solution found".to_string(),
        (false, None) => "no solution".to_string(),
    };
    match (termination, infeasibility) {
        (Termination::Infeasible, Some(why)) => format!("infeasible (found by netspec before solving): {why}"),
        (Termination::Infeasible, None) => "infeasible".into(),
        (Termination::Optimal, _) => format!("optimal, {found}"),
        (t, _) => format!("{t}, {found}"),
    }
}

/// netspec's one gap formula, the *primal gap* of Berthold (2006) as used by MIPLIB:
/// `0` when primal and dual are equal; `1` when they have opposite signs (or one is zero and the
/// other is not); else `|primal − dual| / max(|primal|, |dual|)`. Always in `[0, 1]`, for
/// either sense. A dual bound on the wrong side of the primal (within round-off) counts as 0.
pub fn gap(primal: f64, dual: f64, sense: Sense) -> f64 {
    if !primal.is_finite() || !dual.is_finite() {
        return 1.0;
    }
    let behind = match sense {
        Sense::Minimize => primal - dual,
        Sense::Maximize => dual - primal,
    };
    if behind <= 0.0 {
        return 0.0;
    }
    if primal * dual < 0.0 || primal == 0.0 || dual == 0.0 {
        return 1.0;
    }
    (behind / primal.abs().max(dual.abs())).min(1.0)
}

/// A gap as a percentage for status lines: `12.0 %`, `0.013 %`, `100 %`.
pub fn percent(g: f64) -> String {
    let p = 100.0 * g;
    if p == 0.0 || p >= 10.0 {
        format!("{p:.0} %")
    } else if p >= 0.1 {
        format!("{p:.1} %")
    } else {
        format!("{p:.2e} %")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result(t: Termination, p: f64, d: f64) -> SolveResult {
        let mut r = SolveResult::empty(SolverKind::Highs, "test".into(), t);
        r.primal = Some(vec![]);
        r.objective = Some(p);
        r.dual_bound = Some(d);
        r
    }

    /// The case of the paper's 0* weight (1e-4) hidden in a solver's default gap.
    #[test]
    fn optimal_only_within_the_tolerance() {
        let mut r = result(Termination::Optimal, 8.0003, 8.0002);
        r.finish(Sense::Minimize);
        assert_eq!(r.termination, Termination::Limit(LimitKind::Gap));
        let mut r = result(Termination::Optimal, 8.0002, 8.0002 - 5e-7);
        r.finish(Sense::Minimize);
        assert_eq!(r.termination, Termination::Optimal);
        let mut r = result(Termination::Optimal, 1e7, 1e7 - 5e-3);
        r.finish(Sense::Minimize);
        assert_eq!(r.termination, Termination::Optimal);
        let mut r = result(Termination::Optimal, 3.0, 3.5);
        r.finish(Sense::Maximize);
        assert_eq!(r.termination, Termination::Limit(LimitKind::Gap));
    }

    #[test]
    fn status_line_says_why_and_whether() {
        let mut r = result(Termination::Limit(LimitKind::Time), 47.0, 41.36);
        r.finish(Sense::Minimize);
        assert_eq!(r.status_line(), "limit(time), solution found (objective 47, gap 12 %)");
        let r = SolveResult::empty(SolverKind::Highs, "test".into(), Termination::Limit(LimitKind::Time));
        assert_eq!(r.status_line(), "limit(time), no solution");
        let r = SolveResult::empty(SolverKind::Highs, "test".into(), Termination::Limit(LimitKind::Interrupt));
        assert_eq!(r.status_line(), "interrupted, no solution");
    }
}
