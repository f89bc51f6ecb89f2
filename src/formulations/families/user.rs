//! User specifications: forced vertices and through routes (FORMULATION §3.5); forced edges
//! are fixed on their variables' bounds by [`super::edges::edges`].

use super::{vname, Ctx};
use crate::formulations::expr::{Expr, Value};

/// Forced vertices (`V_y ≥ 1`, set on the variable's bound), forced edges (bound), and through
/// routes: route edges forced active (bound), inner vertices of active degree exactly 2.
pub fn user_specs(c: &mut Ctx) {
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
