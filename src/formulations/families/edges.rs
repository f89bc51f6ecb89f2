//! Edge variables `E_x` with the length term of (7), and with labels the direction binaries
//! `E(i→j)`, the labels `D(i→j)` and (4).

use crate::design::Network;
use crate::formulations::encode::{set, EncodeError, Encoding};
use crate::formulations::expr::Expr;
use crate::formulations::family::{he_name, Ctx, Family};
use crate::mesh::{EdgeId, HalfEdgeId};
use crate::milp::VarId;
use crate::spec::{switch, BigMForm, EdgeRole, Problem};

/// `E_x` per candidate edge, with `λL·Δ(x)` in the objective (7) and forced edges fixed at 1.
/// With labels, per half-edge `E(i→j)` and `D(i→j) ∈ [0, M]` (λD on `D`), and (4):
/// `−1 ≤ E(i→j) + E(j→i) − 2·E_x ≤ 0` (`paper`), or `E(i→j) + E(j→i) = E_x` with the label
/// bounds switch (one direction per active edge: never worse, since a label is ≥ 0).
pub struct Edges {
    labels: bool,
    /// `(i→j, E(i→j), D(i→j))` for every label, in emission order.
    label_vars: Vec<(HalfEdgeId, VarId, VarId)>,
}

impl Edges {
    /// Always in the model.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        Some(Box::new(Edges { labels: c.plan.labels, label_vars: Vec::new() }))
    }
}

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

impl Family for Edges {
    fn label(&self) -> String {
        if self.labels { "edges (4)" } else { "edges" }.to_string()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let mesh = &p.mesh;
        let m = c.big_m.unwrap_or(0.0);
        let tied = c.recipe.on(&switch::LABEL_BOUNDS);
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
            if !self.labels {
                continue;
            }
            let [h0, h1] = mesh.edge_half_edges(e);
            for h in [h0, h1] {
                let name = he_name(mesh, h);
                let dir = c.em.model.add_binary(format!("H_{name}"), 0.0);
                let d = c.em.model.add_continuous(format!("D_{name}"), 0.0, m, p.w_distance);
                c.vars.half_edge[h.index()] = Some(dir);
                c.vars.label[h.index()] = Some(d);
                self.label_vars.push((h, dir, d));
            }
            let mut ex = Expr::new();
            ex.add(c.vars.half_edge[h0.index()].unwrap(), 1.0).add(c.vars.half_edge[h1.index()].unwrap(), 1.0);
            if tied {
                ex.add(x, -1.0);
                c.em.eq(format!("noisl4_e{}", e.0), &ex, 0.0);
            } else {
                ex.add(x, -2.0);
                c.em.row(format!("noisl4_e{}", e.0), -1.0, &ex, 0.0);
            }
        }
    }

    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        for edge in e.p.mesh.edges() {
            set(x, e.vars.edge[edge.index()], if e.on(edge) { 1.0 } else { 0.0 });
        }
        if self.labels {
            e.set_directions(x)?;
        }
        Ok(())
    }

    /// The labels of the active directions, in edge order.
    fn decode(&self, p: &Problem, x: &[f64], net: &mut Network) {
        let mesh = &p.mesh;
        for &(h, dir, d) in &self.label_vars {
            if x[dir.index()] > 0.5 {
                net.labels.push((mesh.he_tail(h), mesh.he_head(h), x[d.index()]));
            }
        }
    }
}
