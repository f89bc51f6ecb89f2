//! The label bounds of docs/formulation.md §8, tied to the direction binaries.

use crate::design::{label_distances, Network};
use crate::formulations::family::{he_name, Ctx, Family};
use crate::spec::switch;

/// For `i→j` with a non-sink head, `D(i→j) ≥ (Δ(i→j) + h_M(j))·E(i→j)` where `h_M(j)` is the
/// shortest path in the candidate mesh from `v_j` to a sink minus its last edge (the label of
/// the best network through `v_j`: valid on every mesh, and `= d_M(j)` on meshes with one edge
/// length), and `D(i→j) ≤ M·E(i→j)` (an unused label can be 0); a label into a sink is fixed at
/// 0. Sets no variable of its own: the labels' values come with the directions.
pub struct LabelBounds;

impl LabelBounds {
    /// With the paper's labels and the `label_bounds` switch.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        (c.plan.labels && c.recipe.on(&switch::LABEL_BOUNDS)).then(|| Box::new(LabelBounds) as Box<dyn Family>)
    }
}

impl Family for LabelBounds {
    fn label(&self) -> String {
        "label bounds (§8)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let mesh = &p.mesh;
        let m = c.big_m.unwrap_or(0.0);
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
}
