//! Edge variables, and the paper's distance labels: (4), (1)–(3), and the label bounds of §8.

use super::{he_name, Ctx};
use crate::design::{label_distances, Network};
use crate::formulations::expr::Expr;
use crate::mesh::EdgeId;
use crate::spec::{BigMForm, EdgeRole, Problem};

/// The constant of (2). `paper`: Δall, the sum of the lengths of all half-edges of the candidate
/// network. `tight`: the sum of the `|V_c| − 1` longest candidate edges (a label is the length
/// of a simple path, which has at most `|V_c| − 1` edges).
pub fn big_m(p: &Problem, form: BigMForm) -> f64 {
    let mesh = &p.mesh;
    let mut lens: Vec<f64> =
        mesh.edges().filter(|e| p.roles[e.index()] == EdgeRole::Candidate).map(|e| mesh.edge_length(e)).collect();
    match form {
        BigMForm::Paper => 2.0 * lens.iter().sum::<f64>(),
        BigMForm::Tight => {
            let mut touched = vec![false; mesh.num_vertices()];
            for e in mesh.edges().filter(|e| p.roles[e.index()] == EdgeRole::Candidate) {
                let (a, b) = mesh.edge_vertices(e);
                touched[a.index()] = true;
                touched[b.index()] = true;
            }
            let nv = touched.iter().filter(|&&t| t).count();
            lens.sort_by(|a, b| b.total_cmp(a));
            lens.iter().take(nv.saturating_sub(1)).sum()
        }
    }
}

/// Edges forced active: forced edges and the edges of through routes.
pub fn forced_edges(p: &Problem) -> Vec<EdgeId> {
    let mut out = p.forced_edges.clone();
    for r in &p.through_routes {
        for w in r.windows(2) {
            if let Some(h) = p.mesh.half_edge_between(w[0], w[1]) {
                out.push(p.mesh.he_edge(h));
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

/// `E_x` per candidate edge, with `λL·Δ(x)` in the objective (7) and forced edges fixed at 1.
/// With labels, per half-edge `E(i→j)` and `D(i→j) ∈ [0, M]` (λD on `D`), and (4):
/// `−1 ≤ E(i→j) + E(j→i) − 2·E_x ≤ 0` (`paper`), or `E(i→j) + E(j→i) = E_x` when the recipe
/// takes the label bounds (one direction per active edge: never worse, since a label is ≥ 0).
pub fn edges(c: &mut Ctx, m: f64) {
    let p = c.p;
    let mesh = &p.mesh;
    let forced = forced_edges(p);
    for e in mesh.edges() {
        if p.roles[e.index()] != EdgeRole::Candidate {
            continue;
        }
        let len = mesh.edge_length(e);
        let x = c.em.model.add_binary(format!("E_e{}", e.0), p.w_length * len);
        if forced.binary_search(&e).is_ok() {
            c.em.model.var_mut(x).lb = 1.0;
        }
        c.vars.edge[e.index()] = Some(x);
        if !c.plan.labels {
            continue;
        }
        let [h0, h1] = mesh.edge_half_edges(e);
        for h in [h0, h1] {
            let name = he_name(mesh, h);
            c.vars.half_edge[h.index()] = Some(c.em.model.add_binary(format!("H_{name}"), 0.0));
            c.vars.label[h.index()] = Some(c.em.model.add_continuous(format!("D_{name}"), 0.0, m, p.w_distance));
        }
        let mut ex = Expr::new();
        ex.add(c.vars.half_edge[h0.index()].unwrap(), 1.0).add(c.vars.half_edge[h1.index()].unwrap(), 1.0);
        if c.recipe.label_bounds {
            ex.add(x, -1.0);
            c.em.eq(format!("noisl4_e{}", e.0), &ex, 0.0);
        } else {
            ex.add(x, -2.0);
            c.em.row(format!("noisl4_e{}", e.0), -1.0, &ex, 0.0);
        }
    }
}

/// (1)–(3): for every candidate half-edge `i→j` whose head is not a sink, and every candidate
/// successor `j→k`, `k ≠ i`: (1) `L ≤ E(j→k)`; (2) `D(j→k) − D(i→j) + M·L ≤ M − Δ(i→j)`;
/// (3) `E(i→j) − Σ_k L ≤ 0`.
pub fn no_island_labels(c: &mut Ctx, m: f64) {
    let p = c.p;
    let mesh = &p.mesh;
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
                c.em.model.add_le(format!("noisl2_v{iv}_v{jv}_v{kv}"), [(djk, 1.0), (dij, -1.0), (l, m)], m - delta);
                three.add(l, -1.0);
                c.vars.successors.push(crate::formulations::vars::Successor { from: h, to: g, var: l });
            }
            c.em.le(format!("noisl3_{}", he_name(mesh, h)), &three, 0.0);
        }
    }
}

/// The label bounds of FORMULATION §8, tied to the direction binaries: for `i→j` with a
/// non-sink head, `D(i→j) ≥ (Δ(i→j) + h_M(j))·E(i→j)` where `h_M(j)` is the shortest path in
/// the candidate mesh from `v_j` to a sink minus its last edge (the label of the best network
/// through `v_j`: valid on every mesh, and `= d_M(j)` on meshes with one edge length), and
/// `D(i→j) ≤ M·E(i→j)` (an unused label can be 0); a label into a sink is fixed at 0.
pub fn label_bounds(c: &mut Ctx, m: f64) {
    let p = c.p;
    let mesh = &p.mesh;
    let h_mesh = label_distances(p, &Network::all_usable(p));
    for e in mesh.edges() {
        if !c.is_candidate(e) {
            continue;
        }
        for h in mesh.edge_half_edges(e) {
            let j = mesh.he_head(h);
            let (eij, dij) = (c.vars.half_edge[h.index()].unwrap(), c.vars.label[h.index()].unwrap());
            if p.is_sink[j.index()] {
                c.em.model.var_mut(dij).ub = 0.0;
                continue;
            }
            let name = he_name(mesh, h);
            let lb = mesh.edge_length(e) + h_mesh[j.index()];
            if !lb.is_finite() {
                // No sink can be reached through `v_j`: the half-edge is never used.
                c.em.model.var_mut(eij).ub = 0.0;
                c.em.model.var_mut(dij).ub = 0.0;
                continue;
            }
            if lb > 0.0 {
                c.em.model.add_ge(format!("dlb_{name}"), [(dij, 1.0), (eij, -lb)], 0.0);
            }
            c.em.model.add_le(format!("dub_{name}"), [(dij, 1.0), (eij, -m)], 0.0);
        }
    }
}
