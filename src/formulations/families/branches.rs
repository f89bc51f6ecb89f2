//! Branches forbidden (12).

use crate::formulations::expr::Value;
use crate::formulations::family::{vname, Ctx, Family};
use crate::spec::{Allow, CoverageForm};

/// `Σ_{x∈E_y} E_x ≤ 2` at every vertex with more than two usable edges; with a vertex variable
/// and a non-aggregated coverage form, `Σ E_x ≤ 2·V_y` (an inactive vertex has no edge: the same
/// integer points, a tighter relaxation). No variable of its own.
pub struct Branches;

impl Branches {
    /// When the spec forbids branches.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        (c.p.branches == Allow::Forbid).then(|| Box::new(Branches) as Box<dyn Family>)
    }
}

impl Family for Branches {
    fn label(&self) -> String {
        "branches (12)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        for v in p.mesh.vertices() {
            let mut ex = c.degree(v);
            if ex.terms.len() as f64 + ex.constant > 2.0 {
                match c.vars.vertex[v.index()] {
                    Value::Var(y) if c.recipe.coverage != CoverageForm::Aggregated => {
                        ex.add(y, -2.0);
                        c.em.le(format!("branch_{}", vname(v)), &ex, 0.0);
                    }
                    _ => {
                        c.em.le(format!("branch_{}", vname(v)), &ex, 2.0);
                    }
                }
            }
        }
    }
}
