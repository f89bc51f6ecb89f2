//! Zig-zags and too-close pairs (13): sets of edges that must not all be active.

use super::penalty::penalty_row;
use crate::formulations::encode::{set, EncodeError, Encoding};
use crate::formulations::expr::Expr;
use crate::formulations::family::{Ctx, Family};
use crate::mesh::EdgeId;
use crate::milp::VarId;
use crate::rules::{designed, too_close_configs, zigzag_configs};
use crate::spec::{EdgeRole, Weight};

/// (13) for one kind `k` (`0` zig-zags, `1` too-close pairs): forbidden → `Σ E ≤ |S| − 1`;
/// penalised → an indicator with `λ·Z` in the objective ([`penalty_row`]).
pub struct LocalConfigs {
    k: u8,
    /// The configurations emitted: their edges and, when penalised, their indicator.
    configs: Vec<(Vec<EdgeId>, Option<VarId>)>,
}

impl LocalConfigs {
    /// Zig-zags (k = 0), when the spec forbids or penalises them.
    pub fn zigzags(c: &Ctx) -> Option<Box<dyn Family>> {
        (c.p.w_zigzag != Weight::Off).then(|| Box::new(LocalConfigs { k: 0, configs: Vec::new() }) as Box<dyn Family>)
    }

    /// Too-close pairs (k = 1), when the spec forbids or penalises them.
    pub fn too_close(c: &Ctx) -> Option<Box<dyn Family>> {
        (c.p.w_too_close != Weight::Off)
            .then(|| Box::new(LocalConfigs { k: 1, configs: Vec::new() }) as Box<dyn Family>)
    }

    /// Emits one configuration.
    fn config(&mut self, c: &mut Ctx, tag: String, edges: Vec<EdgeId>, w: Weight) {
        let p = c.p;
        if edges.iter().any(|e| p.roles[e.index()] == EdgeRole::Excluded) || !designed(p, &edges) {
            return;
        }
        let n = edges.len() as f64;
        let mut ex = Expr::new();
        for &e in &edges {
            ex.add_value(c.edge_value(e), 1.0);
        }
        let k = self.k;
        let row = format!("{}_{tag}", if k == 0 { "zz" } else { "close" });
        let indicator = match w {
            Weight::Forbid => {
                c.em.le(row, &ex, n - 1.0);
                None
            }
            Weight::Penalty(lambda) => Some(penalty_row(c, format!("Z{k}_{tag}"), row, ex, n, lambda)),
            Weight::Off => return,
        };
        self.configs.push((edges, indicator));
    }
}

impl Family for LocalConfigs {
    fn label(&self) -> String {
        if self.k == 0 { "zig-zag (13, k=0)" } else { "too-close (13, k=1)" }.to_string()
    }

    fn emit(&mut self, c: &mut Ctx) {
        if self.k == 0 {
            for z in zigzag_configs(&c.p.mesh) {
                self.config(c, z.name(), z.edges.to_vec(), c.p.w_zigzag);
            }
        } else {
            for t in too_close_configs(&c.p.mesh) {
                self.config(c, t.name(), t.edges.to_vec(), c.p.w_too_close);
            }
        }
    }

    /// An indicator is on when every edge of its configuration is active.
    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        for (edges, indicator) in &self.configs {
            set(x, *indicator, if edges.iter().all(|&f| e.on(f)) { 1.0 } else { 0.0 });
        }
        Ok(())
    }

    fn lattice_vars(&self) -> Vec<VarId> {
        self.configs.iter().filter_map(|(_, z)| *z).collect()
    }
}
