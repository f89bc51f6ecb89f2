//! The independent feasibility checker: given a model and a point, report every violated
//! bound, row and integrality requirement, and recompute the objective. It never asks a solver.
//!
//! Tolerances follow the MIPLIB 2017 solution checker: a row `lhs ≤ a·x ≤ rhs` holds when
//! `a·x ≥ lhs − tol·max(1, |lhs|, Σ|a_j x_j|)` and `a·x ≤ rhs + tol·max(1, |rhs|, Σ|a_j x_j|)`;
//! a bound `lb ≤ x_j ≤ ub` holds within `tol·max(1, |bound|)`; an integer variable holds when
//! `|x_j − round(x_j)| ≤ int_tol`.

use super::model::{Model, VarId};
use serde::{Deserialize, Serialize};

/// Checker tolerances.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Tolerances {
    /// Relative feasibility tolerance for rows and bounds (default 1e-6).
    pub feasibility: f64,
    /// Absolute integrality tolerance (default 1e-6).
    pub integrality: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances { feasibility: 1e-6, integrality: 1e-6 }
    }
}

/// One violated requirement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Violation {
    /// The point has the wrong length.
    Dimension {
        /// Number of values given.
        got: usize,
        /// Number of variables in the model.
        expected: usize,
    },
    /// A value is NaN or infinite.
    NotFinite {
        /// The variable's name.
        var: String,
    },
    /// `x_j` below its lower bound.
    LowerBound {
        /// The variable's name.
        var: String,
        /// Its value.
        value: f64,
        /// The bound.
        bound: f64,
    },
    /// `x_j` above its upper bound.
    UpperBound {
        /// The variable's name.
        var: String,
        /// Its value.
        value: f64,
        /// The bound.
        bound: f64,
    },
    /// An integer or binary variable with a fractional value.
    Integrality {
        /// The variable's name.
        var: String,
        /// Its value.
        value: f64,
    },
    /// A row's activity below its lower side.
    RowLower {
        /// The row's name.
        row: String,
        /// `a·x`.
        activity: f64,
        /// The side.
        lhs: f64,
    },
    /// A row's activity above its upper side.
    RowUpper {
        /// The row's name.
        row: String,
        /// `a·x`.
        activity: f64,
        /// The side.
        rhs: f64,
    },
}

impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Violation::Dimension { got, expected } => {
                write!(f, "point has {got} values, model has {expected} variables")
            }
            Violation::NotFinite { var } => write!(f, "{var} is not finite"),
            Violation::LowerBound { var, value, bound } => write!(f, "{var} = {value} < lower bound {bound}"),
            Violation::UpperBound { var, value, bound } => write!(f, "{var} = {value} > upper bound {bound}"),
            Violation::Integrality { var, value } => write!(f, "{var} = {value} is not integral"),
            Violation::RowLower { row, activity, lhs } => write!(f, "row {row}: activity {activity} < {lhs}"),
            Violation::RowUpper { row, activity, rhs } => write!(f, "row {row}: activity {activity} > {rhs}"),
        }
    }
}

/// The checker's verdict on a point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CheckReport {
    /// Every violated requirement (empty means feasible).
    pub violations: Vec<Violation>,
    /// The objective recomputed from the point, `c·x + c0`.
    pub objective: f64,
    /// Largest absolute bound violation.
    pub max_bound_violation: f64,
    /// Largest absolute row violation.
    pub max_row_violation: f64,
    /// Largest distance to the nearest integer over integer variables.
    pub max_integrality_violation: f64,
    /// The tolerances used.
    pub tolerances: Tolerances,
}

impl CheckReport {
    /// Whether the point satisfies every bound, row and integrality requirement.
    pub fn is_feasible(&self) -> bool {
        self.violations.is_empty()
    }
}

/// Checks a point against every bound, row and integrality requirement of `model`.
pub fn check_point(model: &Model, x: &[f64], tol: &Tolerances) -> CheckReport {
    let mut report = CheckReport {
        violations: Vec::new(),
        objective: f64::NAN,
        max_bound_violation: 0.0,
        max_row_violation: 0.0,
        max_integrality_violation: 0.0,
        tolerances: *tol,
    };
    if x.len() != model.num_vars() {
        report.violations.push(Violation::Dimension { got: x.len(), expected: model.num_vars() });
        return report;
    }
    let mut finite = true;
    for (v, &xj) in model.vars().iter().zip(x) {
        if !xj.is_finite() {
            report.violations.push(Violation::NotFinite { var: v.name.clone() });
            finite = false;
            continue;
        }
        if xj < v.lb {
            let d = v.lb - xj;
            report.max_bound_violation = report.max_bound_violation.max(d);
            if d > tol.feasibility * v.lb.abs().max(1.0) {
                report.violations.push(Violation::LowerBound { var: v.name.clone(), value: xj, bound: v.lb });
            }
        }
        if xj > v.ub {
            let d = xj - v.ub;
            report.max_bound_violation = report.max_bound_violation.max(d);
            if d > tol.feasibility * v.ub.abs().max(1.0) {
                report.violations.push(Violation::UpperBound { var: v.name.clone(), value: xj, bound: v.ub });
            }
        }
        if v.kind.is_integral() {
            let d = (xj - xj.round()).abs();
            report.max_integrality_violation = report.max_integrality_violation.max(d);
            if d > tol.integrality {
                report.violations.push(Violation::Integrality { var: v.name.clone(), value: xj });
            }
        }
    }
    if !finite {
        return report;
    }
    for row in model.rows() {
        let mut activity = 0.0;
        let mut abs_sum = 0.0;
        for (v, a) in row.terms() {
            let t = a * x[v.index()];
            activity += t;
            abs_sum += t.abs();
        }
        if activity < row.lhs {
            let d = row.lhs - activity;
            report.max_row_violation = report.max_row_violation.max(d);
            if d > tol.feasibility * row.lhs.abs().max(abs_sum).max(1.0) {
                report.violations.push(Violation::RowLower { row: row.name.to_string(), activity, lhs: row.lhs });
            }
        }
        if activity > row.rhs {
            let d = activity - row.rhs;
            report.max_row_violation = report.max_row_violation.max(d);
            if d > tol.feasibility * row.rhs.abs().max(abs_sum).max(1.0) {
                report.violations.push(Violation::RowUpper { row: row.name.to_string(), activity, rhs: row.rhs });
            }
        }
    }
    report.objective = model.objective_value(x);
    report
}

/// Whether `a` and `b` agree to a relative tolerance `rel` (absolute near zero).
pub fn objectives_agree(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(1.0)
}

/// Looks a variable up in a point by id (convenience for callers decoding solutions).
pub fn value(x: &[f64], v: VarId) -> f64 {
    x[v.index()]
}
