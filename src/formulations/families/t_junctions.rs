//! T-junctions (14).

use super::penalty::penalty_row;
use crate::formulations::encode::{set, EncodeError, Encoding};
use crate::formulations::expr::Expr;
use crate::formulations::family::{he_name, Ctx, Family};
use crate::mesh::EdgeId;
use crate::milp::VarId;
use crate::rules::{designed, t_configs};
use crate::spec::Weight;

/// At an interior valence-4 vertex, `e0` inactive while the other three edges are active:
/// forbidden → `E1 + E2 + E3 + (1 − E0) ≤ 3`; penalised → `0 ≤ E1 + E2 + E3 + (1 − E0) − 4·T ≤ 3`
/// with `λT·T` in the objective ([`penalty_row`]).
pub struct TJunctions {
    /// `(e0, the other three edges, the indicator when penalised)` per configuration emitted.
    configs: Vec<(EdgeId, [EdgeId; 3], Option<VarId>)>,
}

impl TJunctions {
    /// When the spec forbids or penalises T-junctions.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        (c.p.w_t_junction != Weight::Off).then(|| Box::new(TJunctions { configs: Vec::new() }) as Box<dyn Family>)
    }
}

impl Family for TJunctions {
    fn label(&self) -> String {
        "T-junctions (14)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let p = c.p;
        let mesh = &p.mesh;
        for (h, _v, e0, others) in t_configs(mesh) {
            if !designed(p, &[e0, others[0], others[1], others[2]]) {
                continue;
            }
            let mut ex = Expr::new();
            for &e in &others {
                ex.add_value(c.edge_value(e), 1.0);
            }
            ex.add_const(1.0).add_value(c.edge_value(e0), -1.0);
            let name = he_name(mesh, h);
            let indicator = match p.w_t_junction {
                Weight::Forbid => {
                    c.em.le(format!("tj_{name}"), &ex, 3.0);
                    None
                }
                Weight::Penalty(lambda) => {
                    Some(penalty_row(c, format!("T_{name}"), format!("tj_{name}"), ex, 4.0, lambda))
                }
                Weight::Off => continue,
            };
            self.configs.push((e0, others, indicator));
        }
    }

    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        for &(e0, others, indicator) in &self.configs {
            set(x, indicator, if !e.on(e0) && others.iter().all(|&f| e.on(f)) { 1.0 } else { 0.0 });
        }
        Ok(())
    }

    fn lattice_vars(&self) -> Vec<VarId> {
        self.configs.iter().filter_map(|c| c.2).collect()
    }
}
