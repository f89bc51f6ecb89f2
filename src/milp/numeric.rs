//! The magnitudes a backend can take, checked before it sees a model.
//!
//! One rule for every backend, with each backend's own numbers ([`NumericLimits`], listed by
//! `netspec solvers`): a matrix or objective coefficient at or above the backend's limit is
//! refused, naming the row and column (a backend would otherwise reject the model without a
//! reason, abort, or answer nonsense); a finite bound or right-hand side at or above the
//! backend's infinity is passed with a warning, since the backend treats it as no bound.

use super::model::Model;
use serde::{Deserialize, Serialize};

/// What magnitudes a backend loads.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct NumericLimits {
    /// A matrix coefficient's magnitude must be below this.
    pub max_matrix: f64,
    /// An objective coefficient's magnitude must be below this.
    pub max_objective: f64,
    /// Finite bounds and sides at or above this magnitude are infinite to the backend; `None`
    /// when it takes every finite value as given.
    pub infinity: Option<f64>,
}

impl NumericLimits {
    /// Limits for a backend that takes any finite value below `1e20` in the matrix and objective
    /// and treats finite bounds at or above `infinity` as infinite.
    pub const fn uniform(max: f64, infinity: Option<f64>) -> NumericLimits {
        NumericLimits { max_matrix: max, max_objective: max, infinity }
    }
}

/// A model's values against a backend's limits.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NumericReport {
    /// The first coefficient the backend cannot take, if any (the model is refused).
    pub refused: Option<String>,
    /// Finite bounds and sides the backend will treat as infinite: how many, and the first few.
    pub infinite: Vec<String>,
    /// How many values are in `infinite` before it was cut to its first few.
    pub infinite_count: usize,
}

/// How many of the values treated as infinite are named in a warning.
const NAMED: usize = 3;

/// Checks every coefficient, bound and side of `model` against `limits`; `backend` names the
/// backend in the messages.
pub fn numeric_screen(model: &Model, limits: &NumericLimits, backend: &str) -> NumericReport {
    let mut report = NumericReport::default();
    let vars = model.vars();
    for (j, v) in vars.iter().enumerate() {
        if v.obj.abs() >= limits.max_objective {
            report.refused = Some(format!(
                "objective coefficient of `{}` is {}: {backend} takes objective coefficients below {:e} in magnitude (rescale the model)",
                name(&v.name, j),
                num(v.obj),
                limits.max_objective
            ));
            return report;
        }
    }
    for (i, row) in model.rows().enumerate() {
        for (var, a) in row.terms() {
            if a.abs() >= limits.max_matrix {
                report.refused = Some(format!(
                    "row `{}`, column `{}`: coefficient {} — {backend} takes matrix coefficients below {:e} in magnitude (rescale the row)",
                    name(row.name, i),
                    name(&vars[var.index()].name, var.index()),
                    num(a),
                    limits.max_matrix
                ));
                return report;
            }
        }
    }
    let Some(inf) = limits.infinity else { return report };
    let mut note = |what: String| {
        report.infinite_count += 1;
        if report.infinite.len() < NAMED {
            report.infinite.push(what);
        }
    };
    let big = |x: f64| x.is_finite() && x.abs() >= inf;
    for (j, v) in vars.iter().enumerate() {
        for (side, x) in [("lower bound", v.lb), ("upper bound", v.ub)] {
            if big(x) {
                note(format!("{side} {} of `{}`", num(x), name(&v.name, j)));
            }
        }
    }
    for (i, row) in model.rows().enumerate() {
        for (side, x) in [("lower side", row.lhs), ("upper side", row.rhs)] {
            if big(x) {
                note(format!("{side} {x} of row `{}`", name(row.name, i)));
            }
        }
    }
    report
}

impl NumericReport {
    /// The warning for the values treated as infinite, if any.
    pub fn warning(&self, backend: &str, limits: &NumericLimits) -> Option<String> {
        let inf = limits.infinity?;
        (self.infinite_count > 0).then(|| {
            let more = self.infinite_count - self.infinite.len();
            format!(
                "{} finite bound(s) or side(s) at or above {backend}'s infinity {inf:e} are treated as no bound: {}{}",
                self.infinite_count,
                self.infinite.join(", "),
                if more > 0 { format!(" and {more} more") } else { String::new() }
            )
        })
    }
}

/// A value as a message shows it: large and small magnitudes in exponent form.
fn num(x: f64) -> String {
    if x != 0.0 && (x.abs() >= 1e6 || x.abs() < 1e-4) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

fn name(n: &str, index: usize) -> String {
    if n.is_empty() {
        format!("#{index}")
    } else {
        n.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_coefficients_and_warns_on_infinite_bounds() {
        let limits = NumericLimits { max_matrix: 1e15, max_objective: 1e20, infinity: Some(1e20) };
        let mut m = Model::new("big");
        let x = m.add_continuous("X", 0.0, 1e25, -1.0);
        m.add_le("R1", [(x, 1e16)], 1.0);
        let r = numeric_screen(&m, &limits, "highs");
        let why = r.refused.unwrap();
        assert!(why.contains("row `R1`, column `X`: coefficient 1e16") && why.contains("highs"), "{why}");

        let mut m = Model::new("ok");
        let x = m.add_continuous("X", 0.0, 1e25, -1.0);
        m.add_le("R1", [(x, 2.0)], 1e21);
        let r = numeric_screen(&m, &limits, "highs");
        assert_eq!(r.refused, None);
        assert_eq!(r.infinite_count, 2);
        let w = r.warning("highs", &limits).unwrap();
        assert!(w.contains("upper bound 1e25 of `X`") && w.contains("row `R1`"), "{w}");

        let mut m = Model::new("obj");
        m.add_continuous("Y", 0.0, 1.0, 1e20);
        assert!(numeric_screen(&m, &limits, "scip").refused.unwrap().contains("objective coefficient of `Y`"));
    }
}
