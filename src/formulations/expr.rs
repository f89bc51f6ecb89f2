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

    /// The terms with every variable once: repeated variables merged at their first place,
    /// coefficients summed (a game level's crossing count holds an inner edge twice when both its
    /// ends are on the block's boundary). Terms that cancel to zero stay, with coefficient 0.
    pub fn merged_terms(&self) -> Vec<(VarId, f64)> {
        let n = self.terms.len();
        let repeated = if n <= 16 {
            (0..n).any(|i| self.terms[..i].iter().any(|t| t.0 == self.terms[i].0))
        } else {
            let mut seen = std::collections::HashSet::with_capacity(n);
            !self.terms.iter().all(|t| seen.insert(t.0))
        };
        if !repeated {
            return self.terms.clone();
        }
        let mut out: Vec<(VarId, f64)> = Vec::with_capacity(n);
        let mut at: std::collections::HashMap<VarId, usize> = std::collections::HashMap::with_capacity(n);
        for &(v, a) in &self.terms {
            match at.get(&v) {
                Some(&k) => out[k].1 += a,
                None => {
                    at.insert(v, out.len());
                    out.push((v, a));
                }
            }
        }
        out
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
        self.model.add_row(name, lo - e.constant, hi - e.constant, e.merged_terms())
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
