//! User specifications: forced vertices and through routes (docs/formulation.md §3.5); forced
//! edges are fixed on their variables' bounds by the edges family.

use crate::formulations::expr::{Expr, Value};
use crate::formulations::family::{vname, Ctx, Family};

/// Forced vertices without a vertex variable (`≥ 1` on an empty row, so a vertex no edge can
/// reach makes the model infeasible by name), and through routes: inner vertices of active
/// degree exactly 2 (the route's edges are forced active on their bounds). No variable of its own.
pub struct UserSpecs;

impl UserSpecs {
    /// When the spec forces vertices, edges or through routes.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        let p = c.p;
        (!p.forced_vertices.is_empty() || !p.through_routes.is_empty() || !p.forced_edges.is_empty())
            .then(|| Box::new(UserSpecs) as Box<dyn Family>)
    }
}

impl Family for UserSpecs {
    fn label(&self) -> String {
        "user specifications".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        for &v in &p.forced_vertices {
            if c.vars.vertex[v.index()] == Value::Const(0.0) {
                c.em.ge(format!("forced_{}", vname(v)), &Expr::new(), 1.0);
            }
        }
        for (r, route) in p.through_routes.iter().enumerate() {
            for &v in &route[1..route.len() - 1] {
                let d = c.degree(v);
                c.em.eq(format!("thru{r}_{}", vname(v)), &d, 2.0);
            }
        }
    }
}
