//! Point-to-point path sets (8)–(9).

use super::Ctx;
use crate::formulations::expr::Expr;
use crate::milp::VarId;
use crate::rules::paths::{enumerate_path_sets, PathSets};
use crate::spec::PathForm;

/// (8)–(9) over the enumerated path sets (returned). `paper` form: `−N + 1 ≤ N·P − Σ_n E_n ≤ 0`; `tight` form:
/// `P ≤ E_n` for each candidate edge of the path. Then `Σ_paths P ≥ 1` per pair of parts.
pub fn point_to_point(c: &mut Ctx) -> PathSets {
    let p = c.p;
    let sets = enumerate_path_sets(p);
    for (pi, pair) in sets.pairs.iter().enumerate() {
        let mut nine = Expr::new();
        let mut always = false;
        let mut vars = vec![None; pair.paths.len()];
        for (k, path) in pair.paths.iter().enumerate() {
            let cand: Vec<VarId> = path.edges.iter().filter_map(|e| c.vars.edge[e.index()]).collect();
            if cand.is_empty() {
                always = true; // every edge existing: the pair is connected already
                continue;
            }
            let pv = c.em.model.add_binary(format!("P_p{pi}_{k}"), 0.0);
            vars[k] = Some(pv);
            let n = cand.len() as f64;
            match c.recipe.paths {
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
            }
            nine.add(pv, 1.0);
        }
        if !always {
            c.em.ge(format!("p2p9_p{pi}"), &nine, 1.0);
        }
        c.vars.paths.push(vars);
    }
    sets
}

