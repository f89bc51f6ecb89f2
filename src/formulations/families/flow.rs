//! What the flow families share (not a family): the candidate half-edges, flow conservation,
//! and a flow in which every active non-sink vertex supplies one unit. Every flow runs from
//! non-sink vertices to the sinks, which absorb it; arcs leave non-sinks only. Variables are
//! named `F_`, `G_`, `C_` + the half-edge (`F_v3_v7`).

use crate::formulations::encode::Encoding;
use crate::formulations::expr::Expr;
use crate::formulations::family::{he_name, vname, Ctx};
use crate::mesh::{HalfEdgeId, VertexId};
use crate::milp::VarId;

/// The candidate half-edges, in edge order.
pub fn candidate_half_edges(c: &Ctx) -> Vec<HalfEdgeId> {
    let mesh = &c.p.mesh;
    mesh.edges().filter(|&e| c.is_candidate(e)).flat_map(|e| mesh.edge_half_edges(e)).collect()
}

/// Flow conservation at every non-sink vertex with a candidate edge:
/// `Σ_out f − Σ_in f − supply(v) = 0`.
pub fn conservation(c: &mut Ctx, tag: &str, flow: &[Option<VarId>], supply: impl Fn(&Ctx, VertexId) -> Expr) {
    let p = c.p;
    let mesh = &p.mesh;
    for v in mesh.vertices() {
        if p.is_sink[v.index()] || !mesh.incident_edges(v).any(|e| c.is_candidate(e)) {
            continue;
        }
        let mut ex = supply(c, v);
        for t in ex.terms.iter_mut() {
            t.1 = -t.1;
        }
        ex.constant = -ex.constant;
        for &g in mesh.outgoing(v) {
            if let Some(f) = flow[g.index()] {
                ex.add(f, 1.0);
            }
            if let Some(f) = flow[mesh.he_twin(g).index()] {
                ex.add(f, -1.0);
            }
        }
        c.em.eq(format!("{tag}_{}", vname(v)), &ex, 0.0);
    }
}

/// A flow in which every active non-sink vertex supplies one unit (`V_v`), on active edges in
/// either direction (`f(u→v) ≤ U·E_x`, `U` = the number of non-sink vertices), at `cost(Δ)` per
/// unit and arc. Returns the flow variables per half-edge.
pub fn vertex_flow(c: &mut Ctx, prefix: &str, cost: impl Fn(f64) -> f64) -> Vec<Option<VarId>> {
    let p = c.p;
    let mesh = &p.mesh;
    let hes = candidate_half_edges(c);
    let cap =
        mesh.vertices().filter(|v| !p.is_sink[v.index()] && mesh.incident_edges(*v).any(|e| c.is_candidate(e))).count()
            as f64;
    let mut flow = vec![None; mesh.num_half_edges()];
    for &h in &hes {
        if p.is_sink[mesh.he_tail(h).index()] {
            continue;
        }
        let name = he_name(mesh, h);
        let f = c.em.model.add_continuous(format!("{prefix}_{name}"), 0.0, cap, cost(mesh.he_length(h)));
        flow[h.index()] = Some(f);
        let x = c.vars.edge[mesh.he_edge(h).index()].unwrap();
        c.em.model.add_le(format!("{}cap_{name}", prefix.to_lowercase()), [(f, 1.0), (x, -cap)], 0.0);
    }
    conservation(c, &format!("{}cons", prefix.to_lowercase()), &flow, |c, v| {
        let mut ex = Expr::new();
        ex.add_value(c.vars.vertex[v.index()], 1.0);
        ex
    });
    flow
}

/// Sets a [`vertex_flow`] at the design: every active non-sink vertex sends its unit along a
/// shortest-path tree (true distances).
pub fn encode_vertex_flow(
    e: &Encoding,
    x: &mut [f64],
    flow: &[Option<VarId>],
) -> Result<(), crate::formulations::EncodeError> {
    let tree = e.tree()?;
    let mut supply: Vec<f64> = e.p.mesh.vertices().map(|v| if e.active_non_sink(v) { 1.0 } else { 0.0 }).collect();
    e.route(x, flow, &mut supply, &tree, e.travel());
    Ok(())
}
