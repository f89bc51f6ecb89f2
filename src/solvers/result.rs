//! What a solve returns: why it stopped, and what it found.

use super::SolverKind;
use crate::milp::{check_point, CheckReport, Model, Sense, Tolerances};
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

/// The outcome of one solve.
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
        }
    }

    /// Fills in `gap` from the bounds, and turns a solver's "optimal" into
    /// [`LimitKind::Gap`] when the user's gap limit stopped it short of the default tolerance
    /// (1e-6 relative, as netspec's gap formula measures it).
    pub fn finish(&mut self, sense: Sense, gap_limit_set: bool) {
        self.gap = match (self.objective, self.dual_bound) {
            (Some(p), Some(d)) => Some(gap(p, d, sense)),
            _ => None,
        };
        if self.termination == Termination::Optimal && gap_limit_set {
            if let Some(g) = self.gap {
                if g > 1e-6 {
                    self.termination = Termination::Limit(LimitKind::Gap);
                }
            }
        }
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
