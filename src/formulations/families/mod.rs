//! The constraint families. Each function emits one family into the [`Ctx`] and cites the
//! equations it implements (FORMULATION.md numbering; §8 for the strengthened forms).

pub mod connectivity;
pub mod coverage;
pub mod cutset;
pub mod edges;
pub mod local;
pub mod paths;
pub mod rooms;
pub mod user;

use super::expr::{Emitter, Expr, Value};
use super::recipe::{Plan, Recipe};
use super::vars::VarMap;
use crate::mesh::{EdgeId, HalfEdgeId, Mesh, VertexId};
use crate::spec::{EdgeRole, Problem};

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
    /// The variable map.
    pub vars: VarMap,
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
}

/// `v3` — a vertex as a name fragment.
pub fn vname(v: VertexId) -> String {
    format!("v{}", v.0)
}

/// `v3_v7` — a half-edge as a name fragment.
pub fn he_name(mesh: &Mesh, h: HalfEdgeId) -> String {
    format!("v{}_v{}", mesh.he_tail(h).0, mesh.he_head(h).0)
}
