//! Dead-ends forbidden at non-sinks (10)–(11).

use crate::formulations::encode::{EncodeError, Encoding};
use crate::formulations::expr::{Expr, Value};
use crate::formulations::family::{he_name, vname, Ctx, Family};
use crate::mesh::HalfEdgeId;
use crate::milp::VarId;
use crate::spec::{Allow, DeadEndForm};

/// `degree`: `Σ E_x ≥ 2·V_y`. `nu` (the paper's): the ν form (10)–(11), corrected to use `E_x`
/// for both half-edges of `x`: for every candidate half-edge `i→j` with a non-sink head,
/// `ν ≤ Σ_{x∈E_j∖{ij}} E_x ≤ |E_j∖{ij}|·ν` and `E_{ij} ≤ ν`.
pub struct DeadEnds {
    /// `(i→j, ν(i→j))`: the paper's indicators, 1 when the head of `i→j` has another active edge.
    indicators: Vec<(HalfEdgeId, VarId)>,
}

impl DeadEnds {
    /// When the spec forbids dead-ends.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        (c.p.dead_ends == Allow::Forbid).then(|| Box::new(DeadEnds { indicators: Vec::new() }) as Box<dyn Family>)
    }
}

impl Family for DeadEnds {
    fn label(&self) -> String {
        "dead-ends (10)-(11)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let mesh = &p.mesh;
        match c.recipe.dead_ends {
            DeadEndForm::Degree => {
                for v in mesh.vertices() {
                    if p.is_sink[v.index()] {
                        continue;
                    }
                    if let Value::Var(y) = c.vars.vertex[v.index()] {
                        let mut ex = c.degree(v);
                        ex.add(y, -2.0);
                        c.em.ge(format!("dead_{}", vname(v)), &ex, 0.0);
                    }
                }
            }
            DeadEndForm::Nu => {
                for e in mesh.edges() {
                    let Some(x) = c.vars.edge[e.index()] else { continue };
                    for h in mesh.edge_half_edges(e) {
                        let j = mesh.he_head(h);
                        if p.is_sink[j.index()] {
                            continue;
                        }
                        let name = he_name(mesh, h);
                        let mut others = Expr::new();
                        for f in mesh.incident_edges(j).filter(|&f| f != e) {
                            others.add_value(c.edge_value(f), 1.0);
                        }
                        let n = others.terms.len() as f64;
                        let nu = c.em.model.add_binary(format!("nu_{name}"), 0.0);
                        self.indicators.push((h, nu));
                        let mut a = others.clone();
                        a.add(nu, -1.0);
                        c.em.ge(format!("dead10a_{name}"), &a, 0.0);
                        let mut b = others;
                        b.add(nu, -n.max(1.0));
                        c.em.le(format!("dead10b_{name}"), &b, 0.0);
                        c.em.model.add_le(format!("dead11_{name}"), [(x, 1.0), (nu, -1.0)], 0.0);
                    }
                }
            }
        }
    }

    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        let mesh = &e.p.mesh;
        for &(h, nu) in &self.indicators {
            let edge = mesh.he_edge(h);
            let others = mesh.incident_edges(mesh.he_head(h)).filter(|&f| f != edge && e.on(f)).count();
            x[nu.index()] = if others > 0 { 1.0 } else { 0.0 };
        }
        Ok(())
    }
}
