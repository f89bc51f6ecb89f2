//! The paper's no-island rows (1)–(3) on the labels: successors `L(i→j; j→k)`.

use crate::formulations::encode::{EncodeError, Encoding};
use crate::formulations::expr::Expr;
use crate::formulations::family::{he_name, Ctx, Family};
use crate::mesh::HalfEdgeId;
use crate::milp::VarId;

/// (1)–(3): for every candidate half-edge `i→j` whose head is not a sink, and every candidate
/// successor `j→k`, `k ≠ i`: (1) `L ≤ E(j→k)`; (2) `D(j→k) − D(i→j) + M·L ≤ M − Δ(i→j)`;
/// (3) `E(i→j) − Σ_k L ≤ 0`.
pub struct NoIsland {
    /// `(i→j, j→k, L)` per successor variable.
    successors: Vec<(HalfEdgeId, HalfEdgeId, VarId)>,
}

impl NoIsland {
    /// With the paper's labels.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        c.plan.labels.then(|| Box::new(NoIsland { successors: Vec::new() }) as Box<dyn Family>)
    }
}

impl Family for NoIsland {
    fn label(&self) -> String {
        "no-island (1)-(3)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let mesh = &p.mesh;
        let m = c.big_m.unwrap_or(0.0);
        for e in mesh.edges() {
            if !c.is_candidate(e) {
                continue;
            }
            for h in mesh.edge_half_edges(e) {
                let (i, j) = (mesh.he_tail(h), mesh.he_head(h));
                if p.is_sink[j.index()] {
                    continue;
                }
                let eij = c.vars.half_edge[h.index()].unwrap();
                let dij = c.vars.label[h.index()].unwrap();
                let delta = mesh.edge_length(e);
                let mut three = Expr::new();
                three.add(eij, 1.0);
                for &g in mesh.outgoing(j) {
                    let k = mesh.he_head(g);
                    let Some(ejk) = c.vars.half_edge[g.index()] else { continue };
                    if k == i {
                        continue;
                    }
                    let djk = c.vars.label[g.index()].unwrap();
                    let (iv, jv, kv) = (i.0, j.0, k.0);
                    let l = c.em.model.add_binary(format!("L_v{iv}_v{jv}_v{kv}"), 0.0);
                    c.em.model.add_le(format!("noisl1_v{iv}_v{jv}_v{kv}"), [(l, 1.0), (ejk, -1.0)], 0.0);
                    c.em.model.add_le(
                        format!("noisl2_v{iv}_v{jv}_v{kv}"),
                        [(djk, 1.0), (dij, -1.0), (l, m)],
                        m - delta,
                    );
                    three.add(l, -1.0);
                    self.successors.push((h, g, l));
                }
                c.em.le(format!("noisl3_{}", he_name(mesh, h)), &three, 0.0);
            }
        }
    }

    /// A successor is on when its first half-edge is an active direction and the second is the
    /// best next step from their common vertex.
    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        let next = e.next();
        for &(from, to, l) in &self.successors {
            let j = e.p.mesh.he_head(from);
            x[l.index()] = if e.direction_on(x, from) && next[j.index()] == Some(to) { 1.0 } else { 0.0 };
        }
        Ok(())
    }
}
