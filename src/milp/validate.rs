//! Structural validation of a [`Model`] and its size statistics.

use super::model::{Model, RowKind, VarId, VarKind};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};
use std::collections::HashSet;

/// Where in the model a problem was found.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "at", content = "name")]
pub enum Location {
    /// The objective (its constant or a coefficient of the named variable).
    Objective(String),
    /// A variable, by name (or `#index` if unnamed).
    Variable(String),
    /// A row, by name (or `#index` if unnamed).
    Row(String),
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Location::Objective(v) if v.is_empty() => write!(f, "objective"),
            Location::Objective(v) => write!(f, "objective coefficient of `{v}`"),
            Location::Variable(v) => write!(f, "variable `{v}`"),
            Location::Row(r) => write!(f, "row `{r}`"),
        }
    }
}

/// What is wrong with a model.
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum ModelErrorKind {
    /// A coefficient, side or bound is NaN.
    #[error("NaN value")]
    NaN,
    /// A coefficient (matrix or objective) is infinite.
    #[error("infinite coefficient")]
    InfiniteCoefficient,
    /// A lower bound or row side is `+inf`, or an upper one `-inf`.
    #[error("bound on the wrong side of infinity ({0})")]
    WrongInfinity(String),
    /// A row's lower side above its upper side (no file format can hold it). Crossed
    /// *variable* bounds are not an error: they make the model infeasible (see
    /// [`crate::milp::screen`]).
    #[error("lower side {lb} is greater than upper side {ub}")]
    CrossedBounds {
        /// The lower value.
        lb: f64,
        /// The upper value.
        ub: f64,
    },
    /// A binary variable with bounds outside `[0, 1]`.
    #[error("binary variable with bounds [{lb}, {ub}] outside [0, 1]")]
    BinaryBounds {
        /// The lower bound.
        lb: f64,
        /// The upper bound.
        ub: f64,
    },
    /// Two variables or two rows share a name.
    #[error("duplicate name")]
    DuplicateName,
    /// A name that cannot be written to a file (empty, or containing whitespace or control
    /// characters).
    #[error("unusable name {0:?}: names must be non-empty without whitespace or control characters")]
    UnusableName(String),
    /// A row refers to a variable id that does not exist.
    #[error("unknown variable id {0}")]
    UnknownVar(u32),
    /// A row mentions the same variable twice.
    #[error("variable `{0}` appears twice")]
    DuplicateEntry(String),
}

/// A validation error: where, and what.
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[error("{location}: {kind}")]
pub struct ModelError {
    /// Where it was found.
    pub location: Location,
    /// What is wrong.
    pub kind: ModelErrorKind,
}

fn usable_name(name: &str) -> bool {
    !name.is_empty() && !name.chars().any(|c| c.is_whitespace() || c.is_control())
}

impl Model {
    /// Checks the model and returns every problem found (empty when the model is sound).
    pub fn validation_errors(&self) -> Vec<ModelError> {
        let mut out = Vec::new();
        let mut push = |location: Location, kind| out.push(ModelError { location, kind });
        let mut var_names: HashSet<&str> = HashSet::with_capacity(self.num_vars());
        for v in self.vars() {
            let loc = || Location::Variable(v.name.clone());
            if !usable_name(&v.name) {
                push(loc(), ModelErrorKind::UnusableName(v.name.clone()));
            } else if !var_names.insert(&v.name) {
                push(loc(), ModelErrorKind::DuplicateName);
            }
            if v.lb.is_nan() || v.ub.is_nan() {
                push(loc(), ModelErrorKind::NaN);
            } else {
                if v.lb == f64::INFINITY {
                    push(loc(), ModelErrorKind::WrongInfinity("lower bound +inf".into()));
                }
                if v.ub == f64::NEG_INFINITY {
                    push(loc(), ModelErrorKind::WrongInfinity("upper bound -inf".into()));
                }
                // Crossed variable bounds are a well-formed infeasible model, not an error:
                // `milp::screen` reports them as the reason for `infeasible`.
                if v.kind == VarKind::Binary && (v.lb < 0.0 || v.ub > 1.0) {
                    push(loc(), ModelErrorKind::BinaryBounds { lb: v.lb, ub: v.ub });
                }
            }
            if v.obj.is_nan() {
                push(Location::Objective(v.name.clone()), ModelErrorKind::NaN);
            } else if v.obj.is_infinite() {
                push(Location::Objective(v.name.clone()), ModelErrorKind::InfiniteCoefficient);
            }
        }
        if !self.obj_constant.is_finite() {
            let kind =
                if self.obj_constant.is_nan() { ModelErrorKind::NaN } else { ModelErrorKind::InfiniteCoefficient };
            push(Location::Objective(String::new()), kind);
        }
        let mut row_names: HashSet<&str> = HashSet::with_capacity(self.num_rows());
        let mut seen = vec![u32::MAX; self.num_vars()];
        for row in self.rows() {
            let loc = || Location::Row(row.name.to_string());
            if !usable_name(row.name) {
                push(loc(), ModelErrorKind::UnusableName(row.name.to_string()));
            } else if !row_names.insert(row.name) {
                push(loc(), ModelErrorKind::DuplicateName);
            }
            if row.lhs.is_nan() || row.rhs.is_nan() {
                push(loc(), ModelErrorKind::NaN);
            } else {
                if row.lhs == f64::INFINITY {
                    push(loc(), ModelErrorKind::WrongInfinity("lhs +inf".into()));
                }
                if row.rhs == f64::NEG_INFINITY {
                    push(loc(), ModelErrorKind::WrongInfinity("rhs -inf".into()));
                }
                if row.lhs > row.rhs {
                    push(loc(), ModelErrorKind::CrossedBounds { lb: row.lhs, ub: row.rhs });
                }
            }
            for (v, a) in row.terms() {
                if a.is_nan() {
                    push(loc(), ModelErrorKind::NaN);
                } else if a.is_infinite() {
                    push(loc(), ModelErrorKind::InfiniteCoefficient);
                }
                match seen.get_mut(v.index()) {
                    None => push(loc(), ModelErrorKind::UnknownVar(v.0)),
                    Some(s) if *s == row.id.0 => push(loc(), ModelErrorKind::DuplicateEntry(self.var(v).name.clone())),
                    Some(s) => *s = row.id.0,
                }
            }
        }
        out
    }

    /// Checks the model; `Err` holds the first problem (see [`Model::validation_errors`] for all).
    pub fn validate(&self) -> Result<(), ModelError> {
        match self.validation_errors().into_iter().next() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Size statistics.
    pub fn stats(&self) -> ModelStats {
        let mut s = ModelStats { nonzeros: self.num_nonzeros(), ..Default::default() };
        for v in self.vars() {
            match v.kind {
                VarKind::Continuous => s.continuous += 1,
                VarKind::Integer => s.integer += 1,
                VarKind::Binary => s.binary += 1,
            }
        }
        for r in self.rows() {
            match r.kind() {
                RowKind::Le => s.rows_le += 1,
                RowKind::Ge => s.rows_ge += 1,
                RowKind::Eq => s.rows_eq += 1,
                RowKind::Ranged => s.rows_ranged += 1,
                RowKind::Free => s.rows_free += 1,
            }
        }
        s.vars = self.num_vars();
        s.rows = self.num_rows();
        s
    }

    /// A name → id index over the variables (first occurrence wins on duplicates).
    pub fn var_index(&self) -> IndexMap<&str, VarId> {
        let mut m = IndexMap::with_capacity(self.num_vars());
        for (i, v) in self.vars().iter().enumerate() {
            m.entry(v.name.as_str()).or_insert(VarId(i as u32));
        }
        m
    }
}

/// Counts of variables by kind, rows by kind, and nonzeros.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ModelStats {
    /// All variables.
    pub vars: usize,
    /// Continuous variables.
    pub continuous: usize,
    /// General integer variables.
    pub integer: usize,
    /// Binary variables.
    pub binary: usize,
    /// All rows.
    pub rows: usize,
    /// `≤` rows.
    pub rows_le: usize,
    /// `≥` rows.
    pub rows_ge: usize,
    /// `=` rows.
    pub rows_eq: usize,
    /// Ranged rows.
    pub rows_ranged: usize,
    /// Rows with no finite side.
    pub rows_free: usize,
    /// Matrix nonzeros (objective excluded).
    pub nonzeros: usize,
}

impl std::fmt::Display for ModelStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} vars ({} bin, {} int, {} cont), {} rows ({} ≤, {} ≥, {} =, {} ranged, {} free), {} nonzeros",
            self.vars,
            self.binary,
            self.integer,
            self.continuous,
            self.rows,
            self.rows_le,
            self.rows_ge,
            self.rows_eq,
            self.rows_ranged,
            self.rows_free,
            self.nonzeros
        )
    }
}
