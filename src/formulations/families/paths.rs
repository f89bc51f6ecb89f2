//! Point-to-point path sets (8)–(9).

use crate::formulations::encode::{set, EncodeError, Encoding};
use crate::formulations::expr::{Expr, Value};
use crate::formulations::family::{vname, Ctx, Family};
use crate::mesh::{EdgeId, VertexId};
use crate::milp::VarId;
use crate::spec::PathForm;
use std::collections::BTreeMap;

/// (8)–(9) over the enumerated path sets. `paper` form: `−N + 1 ≤ N·P − Σ_n E_n ≤ 0`; `tight` form:
/// `P ≤ E_n` for each candidate edge of the path. Then `Σ_paths P ≥ 1` per pair of parts.
///
/// `select` form (docs/formulation.md §3.4, aggregated over the paths of a pair): one path is chosen per
/// pair, `Σ_paths P = 1`, and each candidate edge `e` of the pair's paths carries every chosen
/// path through it, `Σ_{paths through e} P ≤ E_e` (rows `p2p8_p{pair}_e{edge}`), as does each
/// vertex `y` of them where no single edge at `y` carries every path through it,
/// `Σ_{paths through y} P ≤ V_y` (`p2p8_p{pair}_v{vertex}`; elsewhere the edge's row and
/// `E_x ≤ V_y` imply it). A feasible network has a whole path per pair, and choosing just that
/// one satisfies the rows, so the networks allowed are the same; the relaxation is tighter,
/// because paths sharing an edge or a vertex can no longer each lean on the same fraction of it
/// (Fig. 2c's LP bound as written 37.2 → 97.4; docs/spec.md *Point-to-point*).
pub struct PointToPoint {
    form: PathForm,
    /// `P` per enumerated path, per pair (`None` when every edge of the path is existing).
    vars: Vec<Vec<Option<VarId>>>,
}

impl PointToPoint {
    /// When the spec has point-to-point pairs.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        c.path_sets
            .is_some()
            .then(|| Box::new(PointToPoint { form: c.recipe.paths, vars: Vec::new() }) as Box<dyn Family>)
    }

    /// The path variables, per pair and path, parallel to the formulation's path sets.
    pub fn vars(&self) -> &[Vec<Option<VarId>>] {
        &self.vars
    }
}

impl Family for PointToPoint {
    fn label(&self) -> String {
        "point-to-point (8)-(9)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let form = self.form;
        let p = c.p;
        let sets = c.path_sets.expect("the entry checked");
        for (pi, pair) in sets.pairs.iter().enumerate() {
            let mut nine = Expr::new();
            let mut always = false;
            let mut vars = vec![None; pair.paths.len()];
            // Select form: the path variables through each candidate edge and each vertex.
            let mut through: BTreeMap<EdgeId, (VarId, Vec<VarId>)> = BTreeMap::new();
            let mut at: BTreeMap<VertexId, (VarId, Vec<VarId>)> = BTreeMap::new();
            for (k, path) in pair.paths.iter().enumerate() {
                let cand: Vec<VarId> = path.edges.iter().filter_map(|e| c.vars.edge[e.index()]).collect();
                if cand.is_empty() {
                    always = true; // every edge existing: the pair is connected already
                    continue;
                }
                let pv = c.em.model.add_binary(format!("P_p{pi}_{k}"), 0.0);
                vars[k] = Some(pv);
                let n = cand.len() as f64;
                match form {
                    PathForm::Paper => {
                        let mut ex = Expr::new();
                        ex.add(pv, n);
                        for &x in &cand {
                            ex.add(x, -1.0);
                        }
                        c.em.row(format!("p2p8_p{pi}_{k}"), 1.0 - n, &ex, 0.0);
                    }
                    PathForm::Tight => {
                        for (t, &x) in cand.iter().enumerate() {
                            c.em.model.add_le(format!("p2p8_p{pi}_{k}_{t}"), [(pv, 1.0), (x, -1.0)], 0.0);
                        }
                    }
                    PathForm::Select => {
                        for &e in &path.edges {
                            if let Some(x) = c.vars.edge[e.index()] {
                                through.entry(e).or_insert((x, Vec::new())).1.push(pv);
                            }
                        }
                        for &v in &path.vertices {
                            if let Value::Var(y) = c.vars.vertex[v.index()] {
                                at.entry(v).or_insert((y, Vec::new())).1.push(pv);
                            }
                        }
                    }
                }
                nine.add(pv, 1.0);
            }
            // `Σ ps − carrier ≤ 0`: the carrier (an edge's or a vertex's variable) holds the paths.
            let carry = |ps: &[VarId], carrier: VarId| {
                ps.iter().map(|&pv| (pv, 1.0)).chain([(carrier, -1.0)]).collect::<Vec<_>>()
            };
            for (e, (x, ps)) in &through {
                c.em.model.add_le(format!("p2p8_p{pi}_e{}", e.0), carry(ps, *x), 0.0);
            }
            // Through one vertex, unless one edge at it carries every path through it (the row is
            // then implied by the edge's row and `E_x ≤ V_y`).
            let implied = |v: VertexId, ps: &[VarId]| {
                p.mesh
                    .incident_edges(v)
                    .any(|e| through.get(&e).is_some_and(|(_, on_e)| ps.iter().all(|pv| on_e.contains(pv))))
            };
            for (&v, (y, ps)) in at.iter().filter(|(&v, (_, ps))| !implied(v, ps)) {
                c.em.model.add_le(format!("p2p8_p{pi}_{}", vname(v)), carry(ps, *y), 0.0);
            }
            // A path of existing edges connects the pair whatever the design: no (9) then.
            if !always {
                if form == PathForm::Select {
                    c.em.eq(format!("p2p9_p{pi}"), &nine, 1.0);
                } else {
                    c.em.ge(format!("p2p9_p{pi}"), &nine, 1.0);
                }
            }
            self.vars.push(vars);
        }
    }

    /// The `select` form chooses one path per pair (the first whole one); the others mark every
    /// whole path.
    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        let Some(sets) = e.path_sets else { return Ok(()) };
        let one_per_pair = self.form == PathForm::Select;
        for (pair, vars) in sets.pairs.iter().zip(&self.vars) {
            let mut chosen = false;
            for (path, v) in pair.paths.iter().zip(vars) {
                let whole = path.edges.iter().all(|&f| e.on(f)) && !(one_per_pair && chosen);
                chosen |= whole && v.is_some();
                set(x, *v, if whole { 1.0 } else { 0.0 });
            }
        }
        Ok(())
    }
}
