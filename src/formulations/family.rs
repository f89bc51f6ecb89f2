//! The constraint-family trait, what families share while a model is built, and the registry.
//!
//! A family is one file under `families/`: a type implementing [`Family`] that emits its
//! variables and rows (citing the equations of docs/formulation.md), sets its own variables at
//! the point that stands for a design (a MIP start), and reads its part of a design back from a
//! point. Whether a family is in a problem's model is decided by its entry in [`super::REGISTRY`] from
//! the problem, the recipe and its plan; the registry's order is the model's emission order, so
//! the same problem and recipe give the same model, byte for byte.

use super::encode::{EncodeError, Encoding};
use super::expr::{Emitter, Expr, Value};
use super::recipe::{Plan, Recipe};
pub use super::vars::VarMap;
use crate::design::Network;
use crate::mesh::{EdgeId, HalfEdgeId, Mesh, VertexId};
use crate::milp::VarId;
use crate::rules::paths::PathSets;
use crate::rules::placements::PlacementReport;
use crate::spec::{EdgeRole, Problem};

/// One constraint family of the network IP.
pub trait Family: std::any::Any + Send + Sync {
    /// The family's line in the model statistics, citing its equations (`dead-ends (10)-(11)`).
    fn label(&self) -> String;
    /// Emits the family's variables and rows.
    fn emit(&mut self, c: &mut Ctx);
    /// Sets the family's own variables in `x`, the point that stands for the design `e.net()` (a
    /// MIP start). Families run in emission order, so the variables of the families before this
    /// one are already set. The default: nothing to set.
    fn encode(&self, _e: &Encoding, _x: &mut [f64]) -> Result<(), EncodeError> {
        Ok(())
    }
    /// Adds the family's part of a design read from the point `x` (labels, rooms) to `net`,
    /// whose active edges and directions are already set. The default: nothing to add.
    fn decode(&self, _p: &Problem, _x: &[f64], _net: &mut Network) {}
    /// The family's continuous variables with a cost whose values stay on the objective's
    /// lattice at an optimum (flows on a network matrix with integral supplies, exact
    /// indicators), for [`crate::solvers::lattice`]. The default: none.
    fn lattice_vars(&self) -> Vec<VarId> {
        Vec::new()
    }
}

/// A family's entry in the registry: the family, ready to emit, when the problem's model has it.
pub type Entry = fn(&Ctx) -> Option<Box<dyn Family>>;

/// What the families share while a formulation is being built.
pub struct Ctx<'a> {
    /// The problem.
    pub p: &'a Problem,
    /// The recipe.
    pub recipe: &'a Recipe,
    /// The families it emits for this problem.
    pub plan: Plan,
    /// The model under construction.
    pub em: Emitter,
    /// The shared variables.
    pub vars: VarMap,
    /// The big-M of the label rows (2), when the plan has labels.
    pub big_m: Option<f64>,
    /// Point-to-point path sets, when the problem has point-to-point pairs.
    pub path_sets: Option<&'a PathSets>,
    /// Room placements, when the problem tiles rooms.
    pub placements: Option<&'a PlacementReport>,
}

impl Ctx<'_> {
    /// The activity of edge `e`: its variable, or 1 (existing) / 0 (excluded).
    pub fn edge_value(&self, e: EdgeId) -> Value {
        match (self.p.roles[e.index()], self.vars.edge[e.index()]) {
            (_, Some(v)) => Value::Var(v),
            (EdgeRole::Existing, None) => Value::Const(1.0),
            _ => Value::Const(0.0),
        }
    }

    /// Active-degree expression at `v`: `Σ_{x∈E_y} E_x` plus existing incident edges.
    pub fn degree(&self, v: VertexId) -> Expr {
        let mut ex = Expr::new();
        for e in self.p.mesh.incident_edges(v) {
            ex.add_value(self.edge_value(e), 1.0);
        }
        ex
    }

    /// Whether `e` is a candidate edge with a variable.
    pub fn is_candidate(&self, e: EdgeId) -> bool {
        self.vars.edge[e.index()].is_some()
    }

    /// Whether the cutsets are separated (lazily) and, without the distance flow's direction
    /// binaries, counted on the parent arcs of the out-arc rows (`directed_cutsets`).
    pub fn parent_cutsets(&self) -> bool {
        self.recipe.on(&crate::spec::switch::DIRECTED_CUTSETS) && !self.plan.distance_flow && self.plan.lazy_cutsets()
    }
}

/// `v3` — a vertex as a name fragment.
pub fn vname(v: VertexId) -> String {
    format!("v{}", v.0)
}

/// `v3_v7` — a half-edge as a name fragment.
pub fn he_name(mesh: &Mesh, h: HalfEdgeId) -> String {
    format!("v{}_v{}", mesh.he_tail(h).0, mesh.he_head(h).0)
}
