//! Trivial infeasibility, found by netspec before any solver sees the model: a variable whose
//! bounds are crossed (or, for an integer variable, hold no integer), an empty row whose sides
//! exclude 0, and a row whose activity range — from the bounds of its variables alone — cannot
//! meet one of its sides. Each is a proof of infeasibility that names the variable or row;
//! [`screen`] returns the first one, in variable then row order.
//!
//! The comparisons use the independent checker's tolerance (`1e-6 · max(1, |side|)`), so a row
//! is called infeasible only when no point within the checker's tolerance could satisfy it.

use super::model::Model;
use super::validate::Location;
use serde::{Deserialize, Serialize};

/// Why the model has no feasible point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum InfeasibilityKind {
    /// A variable's lower bound is above its upper bound.
    CrossedBounds {
        /// The lower bound.
        lb: f64,
        /// The upper bound.
        ub: f64,
    },
    /// An integer variable whose bounds hold no integer (e.g. `[0.2, 0.8]`).
    NoIntegerInBounds {
        /// The lower bound.
        lb: f64,
        /// The upper bound.
        ub: f64,
    },
    /// A row without coefficients whose sides exclude 0.
    EmptyRow {
        /// The lower side.
        #[serde(with = "super::ext_f64")]
        lhs: f64,
        /// The upper side.
        #[serde(with = "super::ext_f64")]
        rhs: f64,
    },
    /// The row's activity cannot reach a side: its range `[min, max]` over the variables'
    /// bounds lies entirely outside `[lhs, rhs]`.
    ActivityOutOfReach {
        /// The smallest activity the bounds allow.
        #[serde(with = "super::ext_f64")]
        min: f64,
        /// The largest activity the bounds allow.
        #[serde(with = "super::ext_f64")]
        max: f64,
        /// The lower side.
        #[serde(with = "super::ext_f64")]
        lhs: f64,
        /// The upper side.
        #[serde(with = "super::ext_f64")]
        rhs: f64,
    },
}

/// A proof that a model is infeasible: where, and why.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Infeasibility {
    /// The variable or row.
    pub location: Location,
    /// Why.
    pub kind: InfeasibilityKind,
}

impl std::fmt::Display for Infeasibility {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let side = |lhs: f64, rhs: f64| match (lhs.is_finite(), rhs.is_finite()) {
            (true, true) if lhs == rhs => format!("= {rhs}"),
            (true, true) => format!("in [{lhs}, {rhs}]"),
            (true, false) => format!("≥ {lhs}"),
            (false, true) => format!("≤ {rhs}"),
            (false, false) => "free".to_string(),
        };
        match &self.kind {
            InfeasibilityKind::CrossedBounds { lb, ub } => {
                write!(f, "{}: lower bound {lb} is above upper bound {ub}", self.location)
            }
            InfeasibilityKind::NoIntegerInBounds { lb, ub } => {
                write!(f, "{}: integer variable with no integer in [{lb}, {ub}]", self.location)
            }
            InfeasibilityKind::EmptyRow { lhs, rhs } => {
                write!(
                    f,
                    "{}: the row has no coefficients, so its activity is 0, which is not {}",
                    self.location,
                    side(*lhs, *rhs)
                )
            }
            InfeasibilityKind::ActivityOutOfReach { min, max, lhs, rhs } => write!(
                f,
                "{}: the variables' bounds keep the activity in [{min}, {max}], which never meets {}",
                self.location,
                side(*lhs, *rhs)
            ),
        }
    }
}

/// The checker's tolerance at a side (see [`crate::milp::check`]).
fn tol(side: f64) -> f64 {
    1e-6 * side.abs().max(1.0)
}

/// Returns the first trivial reason why `model` has no feasible point, or `None`. Linear in the
/// model's size; assumes a valid model (see [`Model::validate`]).
pub fn screen(model: &Model) -> Option<Infeasibility> {
    for v in model.vars() {
        let at = || Location::Variable(v.name.clone());
        if v.lb > v.ub {
            return Some(Infeasibility {
                location: at(),
                kind: InfeasibilityKind::CrossedBounds { lb: v.lb, ub: v.ub },
            });
        }
        if v.kind.is_integral() && v.lb.is_finite() && v.ub.is_finite() && (v.lb - 1e-6).ceil() > (v.ub + 1e-6).floor()
        {
            return Some(Infeasibility {
                location: at(),
                kind: InfeasibilityKind::NoIntegerInBounds { lb: v.lb, ub: v.ub },
            });
        }
    }
    for row in model.rows() {
        let (mut min, mut max) = (0.0f64, 0.0f64);
        let mut nonzero = false;
        for (v, a) in row.terms() {
            if a == 0.0 {
                continue;
            }
            nonzero = true;
            let var = model.var(v);
            let (lo, hi) = if a > 0.0 { (a * var.lb, a * var.ub) } else { (a * var.ub, a * var.lb) };
            min += lo;
            max += hi;
        }
        let at = || Location::Row(row.name.to_string());
        let unreachable =
            min.is_finite() && min > row.rhs + tol(row.rhs) || max.is_finite() && max < row.lhs - tol(row.lhs);
        if !unreachable {
            continue;
        }
        let kind = if nonzero {
            InfeasibilityKind::ActivityOutOfReach { min, max, lhs: row.lhs, rhs: row.rhs }
        } else {
            InfeasibilityKind::EmptyRow { lhs: row.lhs, rhs: row.rhs }
        };
        return Some(Infeasibility { location: at(), kind });
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::milp::Model;

    fn kind_at(m: &Model) -> Option<(String, InfeasibilityKind)> {
        screen(m).map(|i| (i.location.to_string(), i.kind))
    }

    #[test]
    fn empty_row_excluding_zero() {
        let mut m = Model::new("e");
        m.add_ge("c", [], 1.0);
        let (at, kind) = kind_at(&m).unwrap();
        assert_eq!(at, "row `c`");
        assert_eq!(kind, InfeasibilityKind::EmptyRow { lhs: 1.0, rhs: f64::INFINITY });
        assert!(screen(&m).unwrap().to_string().contains("activity is 0, which is not ≥ 1"));
    }

    #[test]
    fn empty_rows_admitting_zero_and_free_rows_pass() {
        let mut m = Model::new("ok");
        m.add_ge("c", [], -1.0);
        m.add_eq("d", [], 0.0);
        m.add_row("free", f64::NEG_INFINITY, f64::INFINITY, []);
        let x = m.add_binary("x", 0.0);
        m.add_row("zero_coef", 1.0, 2.0, [(x, 0.0)]);
        // A zero coefficient is no coefficient: the row is empty and excludes 0.
        assert_eq!(kind_at(&m).unwrap().0, "row `zero_coef`");
        m.set_row_sides(crate::milp::RowId(3), -1.0, 2.0);
        assert_eq!(screen(&m), None);
    }

    #[test]
    fn activity_out_of_reach() {
        let mut m = Model::new("a");
        let x = m.add_binary("x", 0.0);
        let y = m.add_continuous("y", -1.0, 2.0, 0.0);
        m.add_ge("fine", [(x, 1.0), (y, 1.0)], 3.0);
        assert_eq!(screen(&m), None);
        m.add_ge("far", [(x, 1.0), (y, -1.0)], 2.5);
        let (at, kind) = kind_at(&m).unwrap();
        assert_eq!(at, "row `far`");
        assert_eq!(kind, InfeasibilityKind::ActivityOutOfReach { min: -2.0, max: 2.0, lhs: 2.5, rhs: f64::INFINITY });
        // Within the checker's tolerance it is not called infeasible.
        m.set_row_sides(crate::milp::RowId(1), 2.0 + 1e-7, f64::INFINITY);
        assert_eq!(screen(&m), None);
    }

    #[test]
    fn infinite_bounds_never_prove_anything() {
        let mut m = Model::new("inf");
        let x = m.add_continuous("x", 0.0, f64::INFINITY, 0.0);
        m.add_le("c", [(x, -1.0)], -1e9);
        assert_eq!(screen(&m), None);
    }

    #[test]
    fn contradictory_bounds() {
        let mut m = Model::new("b");
        m.add_continuous("x", 2.0, 1.0, 0.0);
        assert_eq!(
            kind_at(&m).unwrap(),
            ("variable `x`".into(), InfeasibilityKind::CrossedBounds { lb: 2.0, ub: 1.0 })
        );
        let mut m = Model::new("i");
        m.add_integer("z", 0.2, 0.8, 0.0);
        assert!(matches!(kind_at(&m).unwrap().1, InfeasibilityKind::NoIntegerInBounds { .. }));
        let mut m = Model::new("i2");
        m.add_integer("z", 0.9999999, 1.0, 0.0);
        assert_eq!(screen(&m), None);
    }
}
