//! The solver-neutral MILP: variables, linear rows, objective.
//!
//! Rows are stored row-wise in one compressed (CSR) buffer, so a model with 10^6 nonzeros costs
//! three flat vectors and a few allocations. Every ordering is insertion order.

use serde::{Deserialize, Serialize};

/// Index of a variable (column) in a [`Model`], in insertion order.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct VarId(pub u32);

/// Index of a linear row (constraint) in a [`Model`], in insertion order.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct RowId(pub u32);

impl VarId {
    /// The position of the variable in [`Model::vars`].
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl RowId {
    /// The position of the row in the model's row list.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The domain of a variable.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum VarKind {
    /// A real number between the bounds.
    Continuous,
    /// An integer between the bounds.
    Integer,
    /// An integer in `[0, 1]` (bounds may fix it to 0 or 1).
    Binary,
}

impl VarKind {
    /// Whether the variable must take an integral value.
    pub fn is_integral(self) -> bool {
        !matches!(self, VarKind::Continuous)
    }
}

/// Direction of optimisation.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    /// Minimise the objective.
    #[default]
    Minimize,
    /// Maximise the objective.
    Maximize,
}

impl Sense {
    /// Whether objective `a` is better than `reference` by more than `rel · max(|reference|, 1)`.
    pub fn improves(self, a: f64, reference: f64, rel: f64) -> bool {
        let tol = rel * reference.abs().max(1.0);
        match self {
            Sense::Minimize => a < reference - tol,
            Sense::Maximize => a > reference + tol,
        }
    }

    /// Whether objective `a` is worse than `reference` by more than `rel · max(|reference|, 1)`.
    pub fn falls_short(self, a: f64, reference: f64, rel: f64) -> bool {
        let tol = rel * reference.abs().max(1.0);
        match self {
            Sense::Minimize => a > reference + tol,
            Sense::Maximize => a < reference - tol,
        }
    }
}

/// The kind of a row, derived from its two sides.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RowKind {
    /// `a·x ≤ rhs` (lower side −∞).
    Le,
    /// `a·x ≥ lhs` (upper side +∞).
    Ge,
    /// `a·x = rhs` (both sides equal).
    Eq,
    /// `lhs ≤ a·x ≤ rhs`, both finite and different.
    Ranged,
    /// Both sides infinite: the row constrains nothing (an MPS `N` row other than the objective).
    Free,
}

/// A variable (column).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Variable {
    /// Name, unique within the model.
    pub name: String,
    /// Continuous, integer or binary.
    pub kind: VarKind,
    /// Lower bound (may be `-inf`).
    pub lb: f64,
    /// Upper bound (may be `+inf`).
    pub ub: f64,
    /// Objective coefficient.
    pub obj: f64,
}

/// A row's data, borrowed from the model.
#[derive(Clone, Copy, Debug)]
pub struct RowView<'a> {
    /// The row's id.
    pub id: RowId,
    /// Name, unique within the model.
    pub name: &'a str,
    /// Lower side (may be `-inf`).
    pub lhs: f64,
    /// Upper side (may be `+inf`).
    pub rhs: f64,
    /// Variables with a coefficient in this row, in insertion order.
    pub vars: &'a [VarId],
    /// The coefficients, parallel to `vars`.
    pub coefs: &'a [f64],
}

impl RowView<'_> {
    /// The kind of row.
    pub fn kind(&self) -> RowKind {
        row_kind(self.lhs, self.rhs)
    }

    /// `Σ a_j x_j` at a point.
    pub fn activity(&self, x: &[f64]) -> f64 {
        self.vars.iter().zip(self.coefs).map(|(v, a)| a * x[v.index()]).sum()
    }

    /// The (variable, coefficient) pairs of the row.
    pub fn terms(&self) -> impl Iterator<Item = (VarId, f64)> + '_ {
        self.vars.iter().copied().zip(self.coefs.iter().copied())
    }
}

/// Classifies a row by its sides.
pub fn row_kind(lhs: f64, rhs: f64) -> RowKind {
    match (lhs.is_finite(), rhs.is_finite()) {
        (false, false) => RowKind::Free,
        (false, true) => RowKind::Le,
        (true, false) => RowKind::Ge,
        (true, true) if lhs == rhs => RowKind::Eq,
        (true, true) => RowKind::Ranged,
    }
}

/// A mixed-integer linear program `min/max c·x + c0  s.t.  lhs ≤ A x ≤ rhs,  lb ≤ x ≤ ub`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Model {
    /// The model's name (written to files; may be empty).
    pub name: String,
    /// Direction of optimisation.
    pub sense: Sense,
    /// Name of the objective row in files (default `obj`).
    pub objective_name: String,
    /// Constant term of the objective.
    pub obj_constant: f64,
    vars: Vec<Variable>,
    row_names: Vec<String>,
    row_lhs: Vec<f64>,
    row_rhs: Vec<f64>,
    /// CSR: row `r` holds entries `row_start[r]..row_start[r+1]`.
    row_start: Vec<usize>,
    entry_var: Vec<VarId>,
    entry_coef: Vec<f64>,
}

impl Model {
    /// An empty minimisation model.
    pub fn new(name: impl Into<String>) -> Self {
        Model { name: name.into(), objective_name: "obj".into(), row_start: vec![0], ..Default::default() }
    }

    /// Reserves room for more variables, rows and nonzeros (avoids re-allocation when emitting
    /// large models).
    pub fn reserve(&mut self, vars: usize, rows: usize, nonzeros: usize) {
        self.vars.reserve(vars);
        self.row_names.reserve(rows);
        self.row_lhs.reserve(rows);
        self.row_rhs.reserve(rows);
        self.row_start.reserve(rows);
        self.entry_var.reserve(nonzeros);
        self.entry_coef.reserve(nonzeros);
    }

    /// Adds a variable and returns its id.
    pub fn add_var(&mut self, name: impl Into<String>, kind: VarKind, lb: f64, ub: f64, obj: f64) -> VarId {
        let id = VarId(self.vars.len() as u32);
        self.vars.push(Variable { name: name.into(), kind, lb, ub, obj });
        id
    }

    /// Adds a binary variable with objective coefficient `obj`.
    pub fn add_binary(&mut self, name: impl Into<String>, obj: f64) -> VarId {
        self.add_var(name, VarKind::Binary, 0.0, 1.0, obj)
    }

    /// Adds a continuous variable.
    pub fn add_continuous(&mut self, name: impl Into<String>, lb: f64, ub: f64, obj: f64) -> VarId {
        self.add_var(name, VarKind::Continuous, lb, ub, obj)
    }

    /// Adds a general integer variable.
    pub fn add_integer(&mut self, name: impl Into<String>, lb: f64, ub: f64, obj: f64) -> VarId {
        self.add_var(name, VarKind::Integer, lb, ub, obj)
    }

    /// Adds the row `lhs ≤ Σ a_j x_j ≤ rhs` (use infinities for one-sided rows).
    pub fn add_row<I>(&mut self, name: impl Into<String>, lhs: f64, rhs: f64, terms: I) -> RowId
    where
        I: IntoIterator<Item = (VarId, f64)>,
    {
        let id = RowId(self.row_names.len() as u32);
        for (v, a) in terms {
            self.entry_var.push(v);
            self.entry_coef.push(a);
        }
        self.row_start.push(self.entry_var.len());
        self.row_names.push(name.into());
        self.row_lhs.push(lhs);
        self.row_rhs.push(rhs);
        id
    }

    /// Adds `Σ a_j x_j ≤ rhs`.
    pub fn add_le<I: IntoIterator<Item = (VarId, f64)>>(
        &mut self,
        name: impl Into<String>,
        terms: I,
        rhs: f64,
    ) -> RowId {
        self.add_row(name, f64::NEG_INFINITY, rhs, terms)
    }

    /// Adds `Σ a_j x_j ≥ lhs`.
    pub fn add_ge<I: IntoIterator<Item = (VarId, f64)>>(
        &mut self,
        name: impl Into<String>,
        terms: I,
        lhs: f64,
    ) -> RowId {
        self.add_row(name, lhs, f64::INFINITY, terms)
    }

    /// Adds `Σ a_j x_j = rhs`.
    pub fn add_eq<I: IntoIterator<Item = (VarId, f64)>>(
        &mut self,
        name: impl Into<String>,
        terms: I,
        rhs: f64,
    ) -> RowId {
        self.add_row(name, rhs, rhs, terms)
    }

    /// Number of variables.
    pub fn num_vars(&self) -> usize {
        self.vars.len()
    }

    /// Number of rows.
    pub fn num_rows(&self) -> usize {
        self.row_names.len()
    }

    /// Number of stored coefficients in the rows (the objective is not counted).
    pub fn num_nonzeros(&self) -> usize {
        self.entry_var.len()
    }

    /// All variables, indexed by [`VarId::index`].
    pub fn vars(&self) -> &[Variable] {
        &self.vars
    }

    /// One variable. Panics on an id from another model; use [`Model::try_var`] for untrusted ids.
    pub fn var(&self, id: VarId) -> &Variable {
        &self.vars[id.index()]
    }

    /// One variable, or `None` for an unknown id.
    pub fn try_var(&self, id: VarId) -> Option<&Variable> {
        self.vars.get(id.index())
    }

    /// Mutable access to one variable (bounds, kind, objective coefficient, name).
    pub fn var_mut(&mut self, id: VarId) -> &mut Variable {
        &mut self.vars[id.index()]
    }

    /// One row. Panics on an id from another model.
    pub fn row(&self, id: RowId) -> RowView<'_> {
        let r = id.index();
        let (s, e) = (self.row_start[r], self.row_start[r + 1]);
        RowView {
            id,
            name: &self.row_names[r],
            lhs: self.row_lhs[r],
            rhs: self.row_rhs[r],
            vars: &self.entry_var[s..e],
            coefs: &self.entry_coef[s..e],
        }
    }

    /// All rows, in insertion order.
    pub fn rows(&self) -> impl ExactSizeIterator<Item = RowView<'_>> + '_ {
        (0..self.num_rows()).map(|r| self.row(RowId(r as u32)))
    }

    /// Changes the two sides of a row.
    pub fn set_row_sides(&mut self, id: RowId, lhs: f64, rhs: f64) {
        self.row_lhs[id.index()] = lhs;
        self.row_rhs[id.index()] = rhs;
    }

    /// Renames a row.
    pub fn set_row_name(&mut self, id: RowId, name: impl Into<String>) {
        self.row_names[id.index()] = name.into();
    }

    /// The objective value `c·x + c0` at a point (in the model's own sense).
    pub fn objective_value(&self, x: &[f64]) -> f64 {
        self.vars.iter().zip(x).map(|(v, xi)| v.obj * xi).sum::<f64>() + self.obj_constant
    }

    /// Whether any variable is integer or binary.
    pub fn is_mip(&self) -> bool {
        self.vars.iter().any(|v| v.kind.is_integral())
    }

    /// The column-wise (CSC) form of the constraint matrix: `(col_start, row_index, value)`,
    /// with entries of each column in row order. Solvers that load by column use this.
    pub fn to_csc(&self) -> (Vec<usize>, Vec<u32>, Vec<f64>) {
        let n = self.num_vars();
        let mut count = vec![0usize; n + 1];
        for v in &self.entry_var {
            count[v.index() + 1] += 1;
        }
        for j in 0..n {
            count[j + 1] += count[j];
        }
        let start = count.clone();
        let mut next = count;
        let nnz = self.num_nonzeros();
        let mut rows = vec![0u32; nnz];
        let mut vals = vec![0f64; nnz];
        for r in 0..self.num_rows() {
            for k in self.row_start[r]..self.row_start[r + 1] {
                let j = self.entry_var[k].index();
                rows[next[j]] = r as u32;
                vals[next[j]] = self.entry_coef[k];
                next[j] += 1;
            }
        }
        (start, rows, vals)
    }

    /// Raw CSR arrays `(row_start, var, coef)` for fast loading into solvers.
    pub fn csr(&self) -> (&[usize], &[VarId], &[f64]) {
        (&self.row_start, &self.entry_var, &self.entry_coef)
    }

    /// Lower and upper sides of all rows.
    pub fn row_sides(&self) -> (&[f64], &[f64]) {
        (&self.row_lhs, &self.row_rhs)
    }
}
