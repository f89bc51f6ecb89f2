//! The distance flow (docs/formulation.md §8): the λD term with a real bound, and connectivity.

use super::flow::{candidate_half_edges, conservation};
use crate::formulations::encode::{EncodeError, Encoding};
use crate::formulations::expr::Expr;
use crate::formulations::family::{he_name, Ctx, Family};
use crate::milp::VarId;

/// The distance flow, whose cost is the paper's `Σ D(i→j)` exactly (on every mesh):
/// - direction binaries `E(i→j)` with `E(i→j) + E(j→i) = E_x` (`dir_e…`);
/// - every active half-edge `i→j` whose head is not a sink supplies one unit at `v_j` and costs
///   `λD·Δ(i→j)` itself; the unit then flows to a sink along active half-edges at `λD·Δ` per arc,
///   except that an arc into a sink is free (`fcap_…`: `f(u→v) ≤ U·E(u→v)`, `fcons_…`).
///
/// A unit supplied at `v_j` costs at least `h(j)`, the shortest path to a sink minus its last
/// edge, so an active half-edge costs at least `Δ(i→j) + h(j)` — the paper's label — and the
/// minimum is reached by orienting every edge toward its end with the smaller label. With
/// `U` = the number of candidate edges.
pub struct DistanceFlow {
    /// `F` per half-edge.
    flow: Vec<Option<VarId>>,
}

impl DistanceFlow {
    /// When the recipe writes the λD term as a flow.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        c.plan.distance_flow.then(|| Box::new(DistanceFlow { flow: Vec::new() }) as Box<dyn Family>)
    }
}

impl Family for DistanceFlow {
    fn label(&self) -> String {
        "distance flow (§8)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let mesh = &p.mesh;
        let lambda = p.w_distance;
        let hes = candidate_half_edges(c);
        let cap = (hes.len() / 2) as f64;
        let edges: Vec<_> = mesh.edges().filter(|&e| c.is_candidate(e)).collect();
        for e in edges {
            let len = mesh.edge_length(e);
            let mut ex = Expr::new();
            for h in mesh.edge_half_edges(e) {
                let head_is_sink = p.is_sink[mesh.he_head(h).index()];
                let d =
                    c.em.model
                        .add_binary(format!("H_{}", he_name(mesh, h)), if head_is_sink { 0.0 } else { lambda * len });
                c.vars.half_edge[h.index()] = Some(d);
                ex.add(d, 1.0);
            }
            ex.add(c.vars.edge[e.index()].unwrap(), -1.0);
            c.em.eq(format!("dir_e{}", e.0), &ex, 0.0);
        }
        self.flow = vec![None; mesh.num_half_edges()];
        for &h in &hes {
            let (u, v) = (mesh.he_tail(h), mesh.he_head(h));
            if p.is_sink[u.index()] {
                continue;
            }
            let cost = if p.is_sink[v.index()] { 0.0 } else { lambda * mesh.he_length(h) };
            let f = c.em.model.add_continuous(format!("F_{}", he_name(mesh, h)), 0.0, cap, cost);
            self.flow[h.index()] = Some(f);
            let dir = c.vars.half_edge[h.index()].unwrap();
            c.em.model.add_le(format!("fcap_{}", he_name(mesh, h)), [(f, 1.0), (dir, -cap)], 0.0);
        }
        conservation(c, "fcons", &self.flow, |c, v| {
            let mut ex = Expr::new();
            for &g in c.p.mesh.outgoing(v) {
                if let Some(d) = c.vars.half_edge[c.p.mesh.he_twin(g).index()] {
                    ex.add(d, 1.0);
                }
            }
            ex
        });
    }

    /// Directions toward the smaller label; each active half-edge into a non-sink supplies a
    /// unit at its head, which follows the best next steps to a sink.
    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        e.set_directions(x)?;
        let mesh = &e.p.mesh;
        let mut supply = vec![0.0f64; mesh.num_vertices()];
        for edge in mesh.edges() {
            for g in mesh.edge_half_edges(edge) {
                if e.direction_on(x, g) && !e.p.is_sink[mesh.he_head(g).index()] {
                    supply[mesh.he_head(g).index()] += 1.0;
                }
            }
        }
        e.route(x, &self.flow, &mut supply, e.next(), e.labels());
        Ok(())
    }

    fn lattice_vars(&self) -> Vec<VarId> {
        self.flow.iter().flatten().copied().collect()
    }
}
