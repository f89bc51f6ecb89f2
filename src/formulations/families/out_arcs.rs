//! Out-arc rows (docs/formulation.md §8): every active non-sink vertex has an arc out toward
//! the sinks.

use crate::formulations::encode::{set, EncodeError, Encoding};
use crate::formulations::expr::{Expr, Value};
use crate::formulations::family::{he_name, vname, Ctx, Family};
use crate::spec::{switch, Allow};

/// Out-arc rows (docs/formulation.md §8, a strengthening of the no-island rows): every active
/// non-sink vertex has an arc out of it toward the sinks, and an edge gives an arc to at most
/// one of its ends. Valid because a network whose every active vertex reaches a sink has a
/// shortest-path forest into the sinks, in which each active non-sink vertex owns its parent
/// edge. Summed over a sink-free vertex set `S`, the rows say `Σ_{v∈S} V_v ≤ Σ E_x` over the
/// edges with an end in `S` (each component inside `S` has a spanning tree and an edge out);
/// a relaxation without them may switch on every vertex of a path whose edges are at ½.
/// - With the distance flow's direction binaries (every active edge points toward its end with
///   the smaller label in the optimum, and the step of each vertex to its successor points out
///   of it): `Σ_{(v→w)} E(v→w) ≥ V_v` (`out_v…`), no new variable.
/// - Without them, continuous parent arcs `P(v→w) ∈ [0, 1]` on the candidate half-edges out of
///   non-sinks: `P(v→w) + P(w→v) ≤ E_x` (`par_e…`) and `Σ_{(v→w)} P(v→w) ≥ V_v` (`out_v…`);
///   with the directed cutsets on them (`directed_cutsets`) `Σ_{(v→w)} P(v→w) = V_v`, since the
///   forest gives each active non-sink vertex exactly one parent and an inactive one none (root
///   LP of 1c-L2 25.83 → 26.22, of 5L3 22.01 → 22.41, in fewer rounds).
///
/// The formulation writes it where dead-ends are allowed: forbidden, the degree rows
/// `2·V_v ≤ Σ_{x∈E_v} E_x` already imply the sums over `S` (with half the edges out of `S`), and
/// the rows moved the root bound of 7b-L2, 1b-L3 and 7d-L3 by less than 0.2
/// (docs/benchmarks.md, *Out-arc rows*). It also writes them, whatever the dead-end rule, when
/// the cutsets are directed on the parent arcs (`directed_cutsets`, no distance flow).
pub struct OutArcs;

impl OutArcs {
    /// With the `out_arcs` switch where dead-ends are allowed, and whenever the cutsets count
    /// parent arcs.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        ((c.recipe.on(&switch::OUT_ARCS) && c.p.dead_ends == Allow::Allow) || c.parent_cutsets())
            .then(|| Box::new(OutArcs) as Box<dyn Family>)
    }
}

impl Family for OutArcs {
    fn label(&self) -> String {
        "out-arcs (§8)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let mesh = &p.mesh;
        let directions = c.plan.distance_flow;
        if !directions {
            for e in mesh.edges() {
                let Some(x) = c.vars.edge[e.index()] else { continue };
                let mut ex = Expr::new();
                for h in mesh.edge_half_edges(e) {
                    if p.is_sink[mesh.he_tail(h).index()] {
                        continue;
                    }
                    let a = c.em.model.add_continuous(format!("P_{}", he_name(mesh, h)), 0.0, 1.0, 0.0);
                    c.vars.parent[h.index()] = Some(a);
                    ex.add(a, 1.0);
                }
                if !ex.terms.is_empty() {
                    ex.add(x, -1.0);
                    c.em.le(format!("par_e{}", e.0), &ex, 0.0);
                }
            }
        }
        let arcs = if directions { &c.vars.half_edge } else { &c.vars.parent };
        // With the directed cutsets on parent arcs, the arcs are a forest's: exactly one out of each
        // active non-sink vertex, none out of an inactive one (the direction binaries of the
        // distance flow may leave a vertex twice, so their rows stay `≥`).
        let exactly_one = !directions && c.recipe.on(&switch::DIRECTED_CUTSETS);
        for v in mesh.vertices() {
            let Value::Var(y) = c.vars.vertex[v.index()] else { continue };
            if p.is_sink[v.index()] {
                continue;
            }
            let mut ex = Expr::new();
            for &g in mesh.outgoing(v) {
                if let Some(a) = arcs[g.index()] {
                    ex.add(a, 1.0);
                }
            }
            ex.add(y, -1.0);
            if exactly_one {
                c.em.eq(format!("out_{}", vname(v)), &ex, 0.0);
            } else {
                c.em.ge(format!("out_{}", vname(v)), &ex, 0.0);
            }
        }
    }

    /// Each active non-sink vertex owns the edge to its parent in a shortest-path tree.
    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        if e.vars.parent.iter().any(Option::is_some) {
            for g in e.tree()?.iter().flatten() {
                set(x, e.vars.parent[g.index()], 1.0);
            }
        }
        Ok(())
    }
}
