//! Small helpers for emitting rows whose terms mix variables and constants (existing edges are
//! constant 1, excluded edges constant 0), and for counting what each constraint family adds.

use crate::milp::{Model, RowId, VarId};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

/// A linear expression `Σ a_j x_j + c`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Expr {
    /// Variable terms.
    pub terms: Vec<(VarId, f64)>,
    /// Constant part.
    pub constant: f64,
}

impl Expr {
    /// The empty expression.
    pub fn new() -> Self {
        Expr::default()
    }

    /// Adds `a · x`.
    pub fn add(&mut self, x: VarId, a: f64) -> &mut Self {
        self.terms.push((x, a));
        self
    }

    /// Adds `a · value`, where `value` is a variable or a constant.
    pub fn add_value(&mut self, v: Value, a: f64) -> &mut Self {
        match v {
            Value::Var(x) => self.terms.push((x, a)),
            Value::Const(c) => self.constant += a * c,
        }
        self
    }

    /// Adds a constant.
    pub fn add_const(&mut self, c: f64) -> &mut Self {
        self.constant += c;
        self
    }

    /// Whether the expression has no variable.
    pub fn is_constant(&self) -> bool {
        self.terms.is_empty()
    }
}

/// A quantity that is a variable or a constant.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Value {
    /// A decision variable.
    Var(VarId),
    /// A fixed number.
    Const(f64),
}

impl Value {
    /// Its value at a point.
    pub fn at(self, x: &[f64]) -> f64 {
        match self {
            Value::Var(v) => x[v.index()],
            Value::Const(c) => c,
        }
    }
}

/// Variables and rows added by one constraint family.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct FamilyStats {
    /// Variables added.
    pub vars: usize,
    /// Rows added.
    pub rows: usize,
    /// Nonzeros added.
    pub nonzeros: usize,
}

/// A model under construction, with per-family accounting.
pub struct Emitter {
    /// The model.
    pub model: Model,
    /// Per-family counts, in emission order.
    pub families: IndexMap<String, FamilyStats>,
}

impl Emitter {
    /// A new emitter over an empty model.
    pub fn new(name: &str) -> Self {
        Emitter { model: Model::new(name), families: IndexMap::new() }
    }

    /// Adds `lo ≤ expr ≤ hi`, moving the constant to the sides.
    pub fn row(&mut self, name: String, lo: f64, e: &Expr, hi: f64) -> RowId {
        self.model.add_row(name, lo - e.constant, hi - e.constant, e.terms.iter().copied())
    }

    /// Adds `expr ≤ hi`.
    pub fn le(&mut self, name: String, e: &Expr, hi: f64) -> RowId {
        self.row(name, f64::NEG_INFINITY, e, hi)
    }

    /// Adds `expr ≥ lo`.
    pub fn ge(&mut self, name: String, e: &Expr, lo: f64) -> RowId {
        self.row(name, lo, e, f64::INFINITY)
    }

    /// Adds `expr = rhs`.
    pub fn eq(&mut self, name: String, e: &Expr, rhs: f64) -> RowId {
        self.row(name, rhs, e, rhs)
    }
}
