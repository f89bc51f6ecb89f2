//! Flow families (FORMULATION §8): the distance flow (the λD term with a real bound, and
//! connectivity), the travel flow (the per-vertex travel term) and the connectivity flow (the
//! compact form of the cutsets).
//!
//! Every flow runs from non-sink vertices to the sinks, which absorb it; arcs leave non-sinks
//! only. Variables are named `F_`, `G_`, `C_` + the half-edge (`F_v3_v7`).

use super::{he_name, vname, Ctx};
use crate::formulations::expr::{Expr, Value};
use crate::mesh::HalfEdgeId;
use crate::milp::VarId;

/// The candidate half-edges, in edge order.
fn candidate_half_edges(c: &Ctx) -> Vec<HalfEdgeId> {
    let mesh = &c.p.mesh;
    mesh.edges().filter(|&e| c.is_candidate(e)).flat_map(|e| mesh.edge_half_edges(e)).collect()
}

/// Flow conservation at every non-sink vertex with a candidate edge:
/// `Σ_out f − Σ_in f − supply(v) = 0`.
fn conservation(c: &mut Ctx, tag: &str, flow: &[Option<VarId>], supply: impl Fn(&Ctx, crate::mesh::VertexId) -> Expr) {
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
pub fn distance_flow(c: &mut Ctx) {
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
                c.em.model.add_binary(format!("H_{}", he_name(mesh, h)), if head_is_sink { 0.0 } else { lambda * len });
            c.vars.half_edge[h.index()] = Some(d);
            ex.add(d, 1.0);
        }
        ex.add(c.vars.edge[e.index()].unwrap(), -1.0);
        c.em.eq(format!("dir_e{}", e.0), &ex, 0.0);
    }
    for &h in &hes {
        let (u, v) = (mesh.he_tail(h), mesh.he_head(h));
        if p.is_sink[u.index()] {
            continue;
        }
        let cost = if p.is_sink[v.index()] { 0.0 } else { lambda * mesh.he_length(h) };
        let f = c.em.model.add_continuous(format!("F_{}", he_name(mesh, h)), 0.0, cap, cost);
        c.vars.distance_flow[h.index()] = Some(f);
        let dir = c.vars.half_edge[h.index()].unwrap();
        c.em.model.add_le(format!("fcap_{}", he_name(mesh, h)), [(f, 1.0), (dir, -cap)], 0.0);
    }
    let flow = c.vars.distance_flow.clone();
    conservation(c, "fcons", &flow, |c, v| {
        let mut ex = Expr::new();
        for &g in c.p.mesh.outgoing(v) {
            if let Some(d) = c.vars.half_edge[c.p.mesh.he_twin(g).index()] {
                ex.add(d, 1.0);
            }
        }
        ex
    });
}

/// A flow in which every active non-sink vertex supplies one unit (`V_v`), on active edges in
/// either direction (`f(u→v) ≤ U·E_x`, `U` = the number of non-sink vertices), at `cost(Δ)` per
/// unit and arc. Returns the flow variables per half-edge.
fn vertex_flow(c: &mut Ctx, prefix: &str, cost: impl Fn(f64) -> f64) -> Vec<Option<VarId>> {
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

/// The travel flow: its cost is `λtravel·Σ_{active non-sink v} d(v)`, `d` the network distance
/// to the nearest sink (an uncapacitated min-cost flow in which every active vertex supplies one
/// unit). Rows `gcap_…`, `gcons_…`.
pub fn travel_flow(c: &mut Ctx) {
    let lambda = c.p.w_travel;
    c.vars.travel_flow = vertex_flow(c, "G", |len| lambda * len);
}

/// The connectivity flow, the compact form of the cutsets: every active non-sink vertex sends
/// one unit to the sinks over active edges. Rows `ccap_…`, `ccons_…`.
pub fn connectivity_flow(c: &mut Ctx) {
    c.vars.connect_flow = vertex_flow(c, "C", |_| 0.0);
}

/// Out-arc rows (FORMULATION §8, a strengthening of the no-island rows): every active
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
pub fn out_arcs(c: &mut Ctx) {
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
    let exactly_one = !directions && c.recipe.directed_cutsets;
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
